"""Cycloidal point-to-point motion (docs/mathematics.md section 4, [19–28]) against hand calculation."""

from __future__ import annotations

import math

import numpy as np
import pytest

from stgen.config import TrajectoryConfig
from stgen.reference import cycloidal_duration, cycloidal_fraction, cycloidal_pose, cycloidal_velocity

LOOSE = 1e12  # a limit that never binds


def _limits(**binding) -> TrajectoryConfig:
    values = {
        "linear_velocity": LOOSE,
        "linear_acceleration": LOOSE,
        "linear_jerk": LOOSE,
        "angular_velocity": LOOSE,
        "angular_acceleration": LOOSE,
        "angular_jerk": LOOSE,
    }
    values.update(binding)
    return TrajectoryConfig(**values)


def test_spec_example_30_mm_at_20_mm_per_s_takes_3_s():
    duration = cycloidal_duration([30.0, 0, 0, 0, 0, 0], _limits(linear_velocity=20.0))
    assert duration == pytest.approx(3.0, rel=1e-12)


def test_acceleration_limited_duration():
    # T = √(2π·10/a); a = 5π mm/s² gives √4 = 2 s.
    duration = cycloidal_duration([0, 10.0, 0, 0, 0, 0], _limits(linear_acceleration=5 * math.pi))
    assert duration == pytest.approx(2.0, rel=1e-12)


def test_jerk_limited_duration():
    # T = ∛(4π²·10/j); j = 5π² mm/s³ gives ∛8 = 2 s; the sign of h does not matter.
    duration = cycloidal_duration([0, 0, -10.0, 0, 0, 0], _limits(linear_jerk=5 * math.pi**2))
    assert duration == pytest.approx(2.0, rel=1e-12)


def test_angles_obey_the_angular_limits_only():
    displacement = [0, 0, 0, 0, 0, 30.0]  # 30° of γ
    assert cycloidal_duration(displacement, _limits(angular_velocity=20.0, linear_velocity=1e-3)) == pytest.approx(3.0)
    assert cycloidal_duration([0, 0, 0, 15.0, 0, 0], _limits(angular_velocity=10.0)) == pytest.approx(3.0)


def test_slowest_coordinate_sets_the_shared_duration():
    limits = _limits(linear_velocity=20.0, angular_velocity=5.0)
    # x alone needs 2·30/20 = 3 s, β alone needs 2·10/5 = 4 s.
    assert cycloidal_duration([30.0, 0, 0, 0, 10.0, 0], limits) == pytest.approx(4.0)


def test_default_limits_combine_all_three_bounds():
    limits = TrajectoryConfig()  # 100 mm/s, 500 mm/s², 5000 mm/s³
    expected = max(2 * 300 / 100, math.sqrt(2 * math.pi * 300 / 500), (4 * math.pi**2 * 300 / 5000) ** (1 / 3))
    assert cycloidal_duration([300.0, 0, 0, 0, 0, 0], limits) == pytest.approx(expected)


def test_no_displacement_needs_no_time():
    assert cycloidal_duration(np.zeros(6), TrajectoryConfig()) == 0.0


def test_duration_vectorises_over_moves():
    moves = np.array([[30.0, 0, 0, 0, 0, 0], [60.0, 0, 0, 0, 0, 0]])
    assert cycloidal_duration(moves, _limits(linear_velocity=20.0)) == pytest.approx([3.0, 6.0])


def test_fraction_by_hand():
    assert cycloidal_fraction([0.0, 0.25, 0.5, 0.75, 1.0]) == pytest.approx(
        [0.0, 0.25 - 1 / (2 * math.pi), 0.5, 0.75 + 1 / (2 * math.pi), 1.0]
    )
    assert cycloidal_fraction([-1.0, 2.0]).tolist() == [0.0, 1.0]


def test_pose_at_hand_computed_times():
    p0 = np.array([0.0, 10.0, 200.0, 0.0, 1.0, -2.0])
    pf = np.array([30.0, 10.0, 180.0, 5.0, 1.0, 2.0])
    times = np.array([-1.0, 0.0, 0.75, 1.5, 3.0, 4.0])
    poses = cycloidal_pose(p0, pf, 3.0, times)
    assert poses.shape == (6, 6)
    quarter = 0.25 - 1 / (2 * math.pi)
    assert poses[0] == pytest.approx(p0) and poses[1] == pytest.approx(p0)
    assert poses[2] == pytest.approx(p0 + (pf - p0) * quarter)
    assert poses[3] == pytest.approx((p0 + pf) / 2)
    assert poses[4] == pytest.approx(pf) and poses[5] == pytest.approx(pf)


def test_start_time_shifts_the_move():
    p0, pf = np.zeros(6), np.full(6, 6.0)
    assert cycloidal_pose(p0, pf, 2.0, 11.0, t0=10.0) == pytest.approx(np.full(6, 3.0))


def test_peaks_equal_the_spec_formulas():
    p0, pf, duration = np.zeros(6), np.array([30.0, 0, 0, 0, 0, 0]), 3.0
    step = 1e-4
    times = np.arange(0.0, duration + step / 2, step)
    velocity = cycloidal_velocity(p0, pf, duration, times)[:, 0]
    assert velocity.max() == pytest.approx(2 * 30 / duration, rel=1e-9)  # 20 mm/s at T/2
    assert velocity[0] == 0.0 and velocity[-1] == pytest.approx(0.0, abs=1e-12)
    positions = cycloidal_pose(p0, pf, duration, times)[:, 0]
    assert np.gradient(positions, step)[1:-1] == pytest.approx(velocity[1:-1], abs=1e-6)
    acceleration = np.diff(positions, 2) / step**2
    assert np.abs(acceleration).max() == pytest.approx(2 * math.pi * 30 / duration**2, rel=1e-4)


def test_zero_duration_is_a_step_at_t0():
    poses = cycloidal_pose(np.zeros(6), np.ones(6), 0.0, [-0.1, 0.0, 0.1])
    assert poses[:, 0].tolist() == [0.0, 1.0, 1.0]
