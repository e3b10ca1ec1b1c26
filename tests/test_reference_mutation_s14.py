"""Reference details that session 14's fresh sample found unchecked (issue 16, docs/mutation.md,
reference, "Session 14: a fresh seed 33").

Expected values are worked out by hand, or by an independent NumPy computation, from docs/mathematics.md
and the docstrings' contracts; never by running the code under test on the same input.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from stgen.config import SolverConfig, load_config
from stgen.reference.crank import crank_inverse_kinematics
from stgen.reference.cycloidal import cycloidal_fraction
from stgen.reference.playback import evaluate, make_table, read_playback_csv
from stgen.reference.variant_fk import variant_forward_kinematics

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
P = np.array([6.0, -3.0, 1.5, 0.0, 12.0, 2.0])


def test_a_cycloidal_fraction_takes_float32_fractions_at_their_value():
    # σ(τ) = τ − sin(2πτ)/(2π) in double precision (the ST's LREAL) for a float32 τ: the fraction's exact
    # value, not float32 arithmetic on it (as cycloidal_velocity, session 13).  NumPy in float64.
    tau = np.array([0.1, 0.3, 0.7, 0.95], dtype=np.float32)
    exact = tau.astype(np.float64)
    expected = exact - np.sin(2.0 * np.pi * exact) / (2.0 * np.pi)
    found = cycloidal_fraction(tau)
    assert found.dtype == np.float64
    assert found == pytest.approx(expected, rel=1e-14, abs=1e-15)


def test_a_table_is_evaluated_at_times_rounded_to_doubles():
    # Times are LREAL: a time given wider (np.longdouble) is the double nearest it, and the results are
    # doubles.  The two-row table of 0 -> P over 3 s passes its inserted knots P/6 at 1 s and 5P/6 at 2 s
    # (session 13's hand derivation).
    table = make_table([0.0, 3.0], [np.zeros(6), P])
    poses, rates, accelerations = evaluate(table, np.array([1.0, 2.0], dtype=np.longdouble))
    assert (poses.dtype, rates.dtype, accelerations.dtype) == (np.float64,) * 3
    assert poses == pytest.approx(np.stack((P / 6, 5 * P / 6)), rel=1e-13, abs=1e-13)
    wide = np.longdouble(1) / np.longdouble(3)         # not a double: rounded to 1/3 as a double first
    assert [a.tolist() for a in evaluate(table, wide)] == [a.tolist() for a in evaluate(table, 1.0 / 3.0)]


@pytest.mark.parametrize("start", [10.0, -7.5, 1000.0])
def test_a_two_row_table_does_not_depend_on_where_its_time_starts(start):
    # Only differences of times enter the spline: rows at `start` and `start` + 3 s get the knots
    # start + 1 s and start + 2 s with the values P/6 and 5P/6, as rows at 0 and 3 s do (session 13's
    # derivation: rest in velocity and acceleration at both ends, for every T).
    table = make_table([start, start + 3.0], [np.zeros(6), P])
    assert table.t.tolist() == [start, start + 1.0, start + 2.0, start + 3.0]
    assert table.poses[1] == pytest.approx(P / 6, rel=1e-12, abs=1e-12)
    assert table.poses[2] == pytest.approx(5 * P / 6, rel=1e-12, abs=1e-12)


def test_a_blank_line_between_rows_of_a_playback_csv_is_skipped(tmp_path):
    # Blank rows are skipped wherever they are, and the rows after them are read: three rows at 0, 1 and
    # 2 s give the knots 0, 0.5, 1, 1.5, 2 (one inserted in the middle of each end segment).
    path = tmp_path / "gap.csv"
    path.write_text("t,x,y,z,alpha,beta,gamma\n0,0,0,0,0,0,0\n1,5,0,0,0,0,0\n\n , ,\n2,10,0,0,0,0,0\n")
    table = read_playback_csv(path)
    assert table.t.tolist() == [0.0, 0.5, 1.0, 1.5, 2.0]
    assert table.poses[[0, 2, 4], 0].tolist() == [0.0, 5.0, 10.0]


def test_crank_forward_kinematics_on_a_moving_base_recovers_the_pose():
    # The crank tips follow the base (Ai in the world frame: RB·Ai + pB): crank angles solved for an upper
    # pose over a raised and turned base give that pose back when the same base is given.
    crank = load_config(EXAMPLES / "crank_platform.toml")
    base = np.array([4.0, -3.0, 20.0, 2.0, -1.5, 3.0])
    pose = np.array([10.0, -5.0, 23.0, 1.0, 2.0, -2.0])
    solution = crank_inverse_kinematics(crank, pose, base)
    assert solution.reachable.all()
    tight = SolverConfig(tolerance=1e-9, max_iterations=50)
    result = variant_forward_kinematics(crank, solution.angles_deg, base, base, solver=tight)
    assert result.converged
    assert np.abs(result.pose - pose).max() < 1e-9


def test_a_leibniz_determinant_is_computed_in_double_precision_whatever_the_input_type():
    from stgen.reference.linalg import leibniz_det

    # The ST computes det A in LREAL (det := 0.0, then + a00·a11, − a01·a10 for n = 2): a float32 matrix
    # is taken at its exact values, a batch of integer matrices gives doubles.  By hand, in Python floats.
    a = np.array([[0.1, 0.2], [0.3, 0.4]], dtype=np.float32)
    a00, a01, a10, a11 = (float(v) for v in a.ravel())
    assert leibniz_det(a) == 0.0 + a00 * a11 - a01 * a10
    batch = leibniz_det(np.array([[[2, 1], [1, 3]], [[1, 2], [3, 4]]]))
    assert batch.dtype == np.float64 and batch.tolist() == [5.0, -2.0]
