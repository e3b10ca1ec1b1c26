"""Playback (issue 12): clamped cubic spline through a pose table, CSV reading and its errors."""

from __future__ import annotations

import numpy as np
import pytest

from stgen.reference.playback import (ADDED_KNOTS, PlaybackError, PlaybackTable, clamped_spline_slopes, evaluate,
                                     make_table, read_playback_csv)


def _table(n=41, seed=3):
    rng = np.random.default_rng(seed)
    t = np.cumsum(rng.uniform(0.05, 0.15, n))
    t -= t[0]
    poses = np.column_stack([20 * np.sin(1.3 * t + k) for k in range(6)]) + rng.normal(0, 0.5, (n, 6))
    return make_table(t, poses)


def test_spline_passes_through_the_knots_and_is_c2_at_every_knot():
    table = _table()
    pose, _, _ = evaluate(table, table.t)
    assert np.abs(pose - table.poses).max() < 1e-12
    eps = 1e-9
    inner = table.t[1:-1]
    for which in (1, 2):                     # velocity, acceleration from both sides
        left = evaluate(table, inner - eps)[which]
        right = evaluate(table, inner + eps)[which]
        assert np.abs(left - right).max() < 1e-5 * (1 + np.abs(left).max())


def test_table_keeps_every_row_and_rests_in_velocity_and_acceleration_at_both_ends():
    for rows in (2, 3, 41):
        t = np.linspace(0.0, 4.0, rows)
        poses = np.column_stack([20 * np.sin(1.3 * t + k) + 3 * k for k in range(6)])
        table = make_table(t, poses)
        assert len(table.t) == rows + ADDED_KNOTS
        assert np.abs(evaluate(table, t)[0] - poses).max() < 1e-12
        _, rate, acc = evaluate(table, np.array([0.0, 1e-12, table.duration - 1e-12, table.duration]))
        assert np.abs(rate).max() < 1e-9
        assert np.abs(acc).max() < 1e-6 * (1 + np.abs(poses).max())


def test_spline_starts_and_ends_at_rest_and_rates_match_differences():
    table = _table()
    _, rate, _ = evaluate(table, np.array([0.0, table.duration]))
    assert np.abs(rate).max() == 0.0
    t = np.linspace(0.01, table.duration - 0.01, 333)
    h = 1e-6
    pose, rate, acc = evaluate(table, t)
    assert np.abs((evaluate(table, t + h)[0] - evaluate(table, t - h)[0]) / (2 * h) - rate).max() < 1e-4
    assert np.abs((evaluate(table, t + h)[1] - evaluate(table, t - h)[1]) / (2 * h) - acc).max() < 1e-2


def test_clamped_slopes_reproduce_a_cubic_with_zero_end_slopes():
    # y = 3t² − 2t³ on [0, 1] has zero slope at both ends: the clamped spline is that cubic exactly
    t = np.linspace(0.0, 1.0, 7)
    y = np.repeat((3 * t**2 - 2 * t**3)[:, None], 6, axis=1)
    table = PlaybackTable(t, y, clamped_spline_slopes(t, y))
    s = np.linspace(0, 1, 101)
    pose, rate, acc = evaluate(table, s)
    assert np.abs(pose[:, 0] - (3 * s**2 - 2 * s**3)).max() < 1e-12
    assert np.abs(acc[:, 0] - (6 - 12 * s)).max() < 1e-9


def test_csv_is_read_and_shifted_to_zero(tmp_path):
    path = tmp_path / "m.csv"
    path.write_text("t,x,y,z,alpha,beta,gamma\n5,0,0,200,0,0,0\n5.1,1,0,200,0,0,0\n5.2,2,0,200,0,0,0\n")
    table = read_playback_csv(path)
    assert table.t == pytest.approx([0.0, 0.05, 0.1, 0.15, 0.2])     # rows at 0, 0.1, 0.2 s; knots added between
    assert table.poses[[0, 2, 4], 0] == pytest.approx([0.0, 1.0, 2.0])


@pytest.mark.parametrize("text, where", [
    ("t,x,y\n0,0,0\n", ":1:1: the header"),
    ("t,x,y,z,alpha,beta,gamma\n0,0,0,0,0,0,0\n0.1,0,zz,0,0,0,0\n", ":3:7: expected a finite number"),
    ("t,x,y,z,alpha,beta,gamma\n0,0,0,0,0,0,0\n0,0,0,0,0,0,0\n", ":3:1: times must increase"),
    ("t,x,y,z,alpha,beta,gamma\n0,0,0,0,0,0\n", ":2:1: expected 7 columns"),
    ("t,x,y,z,alpha,beta,gamma\n0,0,0,0,0,0,0\n", "at least two rows"),
])
def test_bad_csv_names_file_line_and_column(tmp_path, text, where):
    path = tmp_path / "bad.csv"
    path.write_text(text)
    with pytest.raises(PlaybackError, match=str(path).replace("\\", "\\\\") + ".*" if "rows" in where else None) as info:
        read_playback_csv(path)
    assert str(info.value).startswith(str(path)) and where in str(info.value)
