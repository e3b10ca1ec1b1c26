"""Determinant and linear solve exactly as the ST function blocks compute them (docs/mathematics.md section 3).

* :func:`leibniz_det`: the Leibniz formula over a constant permutation/sign
  table (docs/mathematics.md section 3, step 1), no recursion.
* :func:`lu_doolittle` and :func:`lu_solve`: Doolittle LU (L unit lower
  triangular) with partial pivoting, then forward and back substitution
  (docs/mathematics.md section 3, step 2).

The operation order is part of the contract, so that the ST (LREAL = IEEE
double) can reproduce these numbers bit for bit; it is spelled out in each
docstring and the templates follow it.
"""

from __future__ import annotations

from functools import lru_cache
from itertools import permutations

import numpy as np


class SingularMatrixError(ArithmeticError):
    """LU met a pivot whose magnitude is not above the pivot tolerance (zero by default)."""


@lru_cache(maxsize=None)
def _table(n: int) -> tuple[np.ndarray, np.ndarray]:
    perms = np.array(list(permutations(range(n))), dtype=np.int64).reshape(-1, n)
    inversions = np.array(
        [sum(1 for a in range(n) for b in range(a + 1, n) if perm[a] > perm[b]) for perm in perms],
        dtype=np.int64,
    )
    signs = np.where(inversions % 2 == 0, 1, -1).astype(np.int64)
    perms.setflags(write=False)
    signs.setflags(write=False)
    return perms, signs


def permutation_table(n: int = 6) -> tuple[np.ndarray, np.ndarray]:
    """The Leibniz table: ``perms[n!, n]`` (zero-based column indices) and ``signs[n!]`` (±1).

    Row ``k`` is the k-th permutation of ``itertools.permutations(range(n))``,
    i.e. lexicographic order: ``(0,1,2,3,4,5)``, ``(0,1,2,3,5,4)``,
    ``(0,1,2,4,3,5)``, ... ``(5,4,3,2,1,0)``. ``signs[k]`` is +1 for an
    even number of inversions, −1 for odd. The ST templates render the same
    rows in the same order (adding 1 where their arrays are 1-based).
    The arrays are read-only and shared.
    """
    if n < 1:
        raise ValueError(f"n must be >= 1, got {n}")
    return _table(n)


def leibniz_det(matrix) -> np.ndarray | float:
    """det A = Σk sign[k] · Πi A[i, perm[k][i]] (Leibniz formula), for ``A[..., n, n]``.

    Operation order (the ST does the same): for each table row k in order,
    ``term := A[0,p0] * A[1,p1] * ... * A[n-1,p(n-1)]`` multiplied left to
    right, then ``det := det + term`` (sign +1) or ``det := det - term``
    (sign −1), starting from ``det := 0.0``.
    """
    matrix = np.asarray(matrix, dtype=float)
    n = matrix.shape[-1]
    if matrix.ndim < 2 or matrix.shape[-2] != n:
        raise ValueError(f"expected square matrices [..., n, n], got shape {matrix.shape}")
    perms, signs = permutation_table(n)
    terms = matrix[..., 0, perms[:, 0]]
    for row in range(1, n):
        terms = terms * matrix[..., row, perms[:, row]]
    signed = np.where(signs > 0, terms, -terms)
    det = np.add.accumulate(signed, axis=-1)[..., -1]  # sequential, not pairwise, summation
    return float(det) if det.ndim == 0 else det


def lu_doolittle(matrix, pivot_tolerance: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """Doolittle LU with partial pivoting: ``A[perm] = L·U``; returns ``(lu, perm)``.

    ``lu`` holds U on and above the diagonal and L (unit diagonal, not stored)
    below it; ``perm[r]`` is the row of A that ended up in row r.

    Algorithm (in place, right-looking), for k = 0 .. n−1:

    1. pivot row p: the first row i >= k with the largest |lu[i, k]|
       (scan i = k+1 .. n−1, take row i only when strictly larger);
    2. |lu[p, k]| <= ``pivot_tolerance`` → :class:`SingularMatrixError`
       (never a division by zero);
    3. swap rows k and p of ``lu`` (whole rows) and of ``perm``;
    4. for i = k+1 .. n−1: ``lu[i,k] := lu[i,k] / lu[k,k]``, then for
       j = k+1 .. n−1: ``lu[i,j] := lu[i,j] - lu[i,k] * lu[k,j]``.
    """
    lu = np.array(matrix, dtype=float)
    n = lu.shape[0]
    if lu.shape != (n, n):
        raise ValueError(f"expected a square matrix, got shape {lu.shape}")
    perm = np.arange(n)
    for k in range(n):
        pivot_row = k
        for i in range(k + 1, n):
            if abs(lu[i, k]) > abs(lu[pivot_row, k]):
                pivot_row = i
        if abs(lu[pivot_row, k]) <= pivot_tolerance:
            raise SingularMatrixError(
                f"pivot {k} is {lu[pivot_row, k]!r} (|pivot| <= {pivot_tolerance}): matrix is singular"
            )
        if pivot_row != k:
            lu[[k, pivot_row]] = lu[[pivot_row, k]]
            perm[[k, pivot_row]] = perm[[pivot_row, k]]
        lu[k + 1 :, k] = lu[k + 1 :, k] / lu[k, k]
        lu[k + 1 :, k + 1 :] = lu[k + 1 :, k + 1 :] - np.outer(lu[k + 1 :, k], lu[k, k + 1 :])
    return lu, perm


def lu_solve(lu, perm, rhs) -> np.ndarray:
    """Solve A·x = b from :func:`lu_doolittle`'s ``(lu, perm)``.

    Forward substitution (L unit diagonal): ``y[i] := b[perm[i]]``, then for
    j = 0 .. i−1 ``y[i] := y[i] - lu[i,j] * y[j]``. Back substitution, i from
    n−1 down to 0: ``x[i] := y[i]``, for j = i+1 .. n−1
    ``x[i] := x[i] - lu[i,j] * x[j]``, then ``x[i] := x[i] / lu[i,i]``.
    """
    lu = np.asarray(lu, dtype=float)
    rhs = np.asarray(rhs, dtype=float)
    n = lu.shape[0]
    x = [float(rhs[perm[i]]) for i in range(n)]
    for i in range(n):
        for j in range(i):
            x[i] = x[i] - lu[i, j] * x[j]
    for i in range(n - 1, -1, -1):
        for j in range(i + 1, n):
            x[i] = x[i] - lu[i, j] * x[j]
        x[i] = x[i] / lu[i, i]
    return np.array(x)


def solve(matrix, rhs, pivot_tolerance: float = 0.0) -> np.ndarray:
    """A·x = b by :func:`lu_doolittle` then :func:`lu_solve`."""
    lu, perm = lu_doolittle(matrix, pivot_tolerance)
    return lu_solve(lu, perm, rhs)
