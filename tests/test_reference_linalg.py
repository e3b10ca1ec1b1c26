"""Leibniz determinant and Doolittle LU against numpy.linalg and hand values."""

from __future__ import annotations

import numpy as np
import pytest

from stgen.reference import SingularMatrixError, leibniz_det, lu_doolittle, lu_solve, permutation_table, solve

RNG_SEED = 20240611


def test_permutation_table_for_three_by_hand():
    perms, signs = permutation_table(3)
    assert perms.tolist() == [[0, 1, 2], [0, 2, 1], [1, 0, 2], [1, 2, 0], [2, 0, 1], [2, 1, 0]]
    assert signs.tolist() == [1, -1, -1, 1, 1, -1]


def test_permutation_table_for_six_is_lexicographic_with_permutation_matrix_signs():
    perms, signs = permutation_table(6)
    assert perms.shape == (720, 6) and signs.shape == (720,)
    assert perms[0].tolist() == [0, 1, 2, 3, 4, 5] and signs[0] == 1
    assert perms[1].tolist() == [0, 1, 2, 3, 5, 4] and signs[1] == -1
    assert perms[-1].tolist() == [5, 4, 3, 2, 1, 0] and signs[-1] == -1  # 15 inversions
    rows = [tuple(row) for row in perms.tolist()]
    assert rows == sorted(rows) and len(set(rows)) == 720
    assert all(sorted(row) == list(range(6)) for row in rows)
    for row, sign in zip(perms[::37], signs[::37]):
        assert round(np.linalg.det(np.eye(6)[row])) == sign


def test_permutation_table_is_read_only():
    perms, signs = permutation_table(6)
    with pytest.raises(ValueError):
        perms[0, 0] = 1
    with pytest.raises(ValueError):
        signs[0] = 1


def test_leibniz_det_small_cases_by_hand():
    assert leibniz_det([[1.0, 2.0], [3.0, 4.0]]) == -2.0
    assert leibniz_det(np.diag([1.0, 2.0, 3.0, 4.0, 5.0, 6.0])) == 720.0
    upper = np.triu(np.full((6, 6), 7.0)) + np.diag([-6.0, -5.0, -4.0, -3.0, -2.0, -1.0])
    assert leibniz_det(upper) == 1.0 * 2.0 * 3.0 * 4.0 * 5.0 * 6.0
    swapped = np.eye(6)[[1, 0, 2, 3, 4, 5]]
    assert leibniz_det(swapped) == -1.0


def test_leibniz_det_matches_numpy_on_random_and_scaled_matrices():
    rng = np.random.default_rng(RNG_SEED)
    matrices = rng.normal(size=(200, 6, 6))
    expected = np.linalg.det(matrices)
    assert leibniz_det(matrices) == pytest.approx(expected, rel=1e-9, abs=1e-12)
    # Columns scaled like the FK Jacobian: mm (≈ 1e3) for x, y, z and mm² (≈ 1e6) for angles.
    scaled = matrices * np.array([1e3, 1e3, 1e3, 1e6, 1e6, 1e6])
    assert leibniz_det(scaled) == pytest.approx(np.linalg.det(scaled), rel=1e-9)


def test_leibniz_det_of_nearly_singular_matrices():
    rng = np.random.default_rng(RNG_SEED + 1)
    for _ in range(20):
        matrix = rng.normal(size=(6, 6))
        matrix[5] = matrix[:5].T @ rng.normal(size=5) + 1e-9 * rng.normal(size=6)
        exact_zero_rounding = np.prod(np.linalg.norm(matrix, axis=1)) * 1e-13
        assert abs(leibniz_det(matrix) - np.linalg.det(matrix)) <= exact_zero_rounding
        assert abs(leibniz_det(matrix)) < 1e-6


def test_leibniz_det_of_exactly_singular_matrix_is_zero():
    matrix = np.arange(36.0).reshape(6, 6)  # rank 2, small integers: every product is exact
    assert leibniz_det(matrix) == 0.0


def test_leibniz_det_rejects_non_square():
    with pytest.raises(ValueError):
        leibniz_det(np.ones((2, 3)))


def _split(lu):
    lower = np.tril(lu, -1) + np.eye(len(lu))
    return lower, np.triu(lu)


def test_lu_reconstructs_the_permuted_matrix():
    rng = np.random.default_rng(RNG_SEED + 2)
    for _ in range(50):
        matrix = rng.normal(size=(6, 6)) * rng.choice([1.0, 1e3, 1e6], size=6)
        lu, perm = lu_doolittle(matrix)
        lower, upper = _split(lu)
        assert sorted(perm.tolist()) == list(range(6))
        assert lower @ upper == pytest.approx(matrix[perm], rel=1e-12, abs=1e-9 * np.abs(matrix).max())
        assert np.all(np.abs(np.tril(lu, -1)) <= 1.0)  # partial pivoting bounds the multipliers


def test_lu_pivots_past_a_zero_pivot_by_hand():
    # Doolittle without row exchange would divide by zero at the first pivot.
    lu, perm = lu_doolittle([[0.0, 1.0], [2.0, 3.0]])
    assert perm.tolist() == [1, 0]
    assert lu.tolist() == [[2.0, 3.0], [0.0, 1.0]]
    assert lu_solve(lu, perm, [4.0, 13.0]).tolist() == [0.5, 4.0]  # y = 4, 2x + 3y = 13


def test_lu_takes_the_first_largest_pivot():
    lu, perm = lu_doolittle([[1.0, 0.0], [-3.0, 1.0]])
    assert perm.tolist() == [1, 0]  # |−3| > |1|
    lu, perm = lu_doolittle([[2.0, 1.0, 0.0], [-2.0, 0.0, 1.0], [1.0, 1.0, 1.0]])
    assert perm[0] == 0  # |−2| is not larger than |2|: keep the first


def test_solve_matches_numpy_on_random_and_scaled_systems():
    rng = np.random.default_rng(RNG_SEED + 3)
    for _ in range(100):
        matrix = rng.normal(size=(6, 6)) * np.array([1e3, 1e3, 1e3, 1e6, 1e6, 1e6])
        rhs = rng.normal(size=6) * 1e4
        assert solve(matrix, rhs) == pytest.approx(np.linalg.solve(matrix, rhs), rel=1e-8, abs=1e-12)


def test_solve_is_backward_stable_on_nearly_singular_systems():
    rng = np.random.default_rng(RNG_SEED + 4)
    for _ in range(20):
        matrix = rng.normal(size=(6, 6))
        matrix[5] = matrix[:5].T @ rng.normal(size=5) + 1e-10 * rng.normal(size=6)
        rhs = rng.normal(size=6)
        x = solve(matrix, rhs)
        residual = np.linalg.norm(matrix @ x - rhs)
        assert residual <= 1e-12 * np.linalg.norm(matrix) * np.linalg.norm(x) + 1e-12


@pytest.mark.parametrize(
    "matrix",
    [
        np.zeros((6, 6)),
        [[1.0, 2.0], [2.0, 4.0]],
        np.arange(36.0).reshape(6, 6),
        np.array([[1.0, 0.0, 2.0], [0.0, 0.0, 5.0], [3.0, 0.0, 1.0]]),  # zero column
    ],
)
def test_singular_matrix_raises_without_dividing_by_zero(matrix):
    with np.errstate(all="raise"):  # a division by zero would surface as FloatingPointError
        with pytest.raises(SingularMatrixError):
            lu_doolittle(matrix)


def test_pivot_tolerance_reports_tiny_pivots():
    matrix = np.diag([1.0, 1e-14, 1.0])
    lu_doolittle(matrix)  # exact arithmetic: fine with the default tolerance 0
    with pytest.raises(SingularMatrixError, match="pivot 1"):
        lu_doolittle(matrix, pivot_tolerance=1e-12)
