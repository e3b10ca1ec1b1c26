"""Reference details that session 13's mutation work found unchecked (issue 16, docs/mutation.md,
reference, "Session 13: a fresh seed 32").

Expected values are worked out by hand, or by an independent NumPy computation, from docs/mathematics.md
and the docstrings' contracts; never by running the code under test.
"""

from __future__ import annotations

import numpy as np
import pytest

from stgen.reference.playback import evaluate, make_table


@pytest.mark.parametrize("duration", [1e-120, 1e-3, 1.0, 3.0, 1e9, 1e120])
def test_a_two_row_table_inserts_a_sixth_and_five_sixths_whatever_the_time_unit(duration):
    """make_table's two-row case by hand.  Knots 0, T/3, 2T/3, T with values 0, a, b, P; the clamped
    spline's slopes m1, m2 (m0 = m3 = 0) on the even spacing h = T/3 solve
        4·m1 + m2 = 3(δ0 + δ1),  m1 + 4·m2 = 3(δ1 + δ2),  δk = (y_{k+1} − y_k)/h,
    and rest in acceleration at both ends (the module's s''(t0) = (6(y1 − y0) − 2h·m1)/h² = 0, and its
    mirror at the end) gives m1 = 3a/h, m2 = 3(P − b)/h.  Substituted: 4a + P = 2b and 2a + 3P = 4b,
    so a = P/6 and b = 5P/6, for every T: the time unit only scales the slopes.  The durations span
    the range where the segments' squares are normal floats (a table in seconds, milliseconds, or
    far beyond), where the end condition must not be scaled by one power of h more than the start's."""
    P = np.array([6.0, -3.0, 1.5, 0.0, 12.0, 2.0])
    table = make_table([0.0, duration], [np.zeros(6), P])
    assert table.t.tolist() == pytest.approx([0.0, duration / 3, 2 * duration / 3, duration], rel=1e-15)
    assert table.poses[0].tolist() == [0.0] * 6 and table.poses[3].tolist() == P.tolist()
    assert table.poses[1] == pytest.approx(P / 6, rel=1e-13, abs=1e-13)
    assert table.poses[2] == pytest.approx(5 * P / 6, rel=1e-13, abs=1e-13)
    # the slopes by hand: m1 = 3a/h = 1.5·P/T, m2 = 3(P − b)/h = 1.5·P/T (the S-curve is symmetric)
    assert table.slopes[1] == pytest.approx(1.5 * P / duration, rel=1e-12, abs=1e-300)
    assert table.slopes[2] == pytest.approx(1.5 * P / duration, rel=1e-12, abs=1e-300)
    assert table.slopes[0].tolist() == [0.0] * 6 and table.slopes[3].tolist() == [0.0] * 6


def test_a_two_row_table_rests_in_acceleration_at_its_end_by_finite_differences():
    """The same table in seconds (T = 3 s, P as above): the acceleration a step inside each end, by
    central differences of the played position (NumPy, h = 1e-4 s), tends to zero as the end is
    approached.  By hand: on the first segment (h = 1 s, y0 = m0 = 0, y1 = P/6, m1 = 1.5·P/T = P/2)
    y'' = (−12s + 6)·P/6 + (6s − 2)·P/2 = s·P, zero at the start and P/2 at T/6; the middle segment's
    y'' at its centre is m1 − m0 = 0; the table is odd about T/2 (y(T − t) = P − y(t)), so the end
    mirrors the start.  A cubic's second central difference is its y'' exactly (up to rounding)."""
    P = np.array([6.0, -3.0, 1.5, 0.0, 12.0, 2.0])
    table = make_table([0.0, 3.0], [np.zeros(6), P])

    def second_difference(t, step=1e-4):
        pose = evaluate(table, np.array([t - step, t, t + step]))[0]
        return (pose[0] - 2 * pose[1] + pose[2]) / step**2

    assert second_difference(0.5) == pytest.approx(0.5 * P, abs=1e-5)
    assert second_difference(2.5) == pytest.approx(-0.5 * P, abs=1e-5)
    assert second_difference(1.5) == pytest.approx(np.zeros(6), abs=1e-5)
    assert second_difference(1e-3) == pytest.approx(1e-3 * P, abs=1e-5)
    assert second_difference(3.0 - 1e-3) == pytest.approx(-1e-3 * P, abs=1e-5)
