"""The stop ramp's reference (stgen.reference.brake), values by hand."""

from __future__ import annotations

import numpy as np
import pytest

from stgen.config import TrajectoryConfig
from stgen.reference.brake import brake_duration, brake_pose, setpoint_motion


def test_stop_distance_by_hand():
    # p(1) = p0 + v0*T*H00(1) + a0*T^2*H10(1), H00(1) = 1 - 1 + 1/2, H10(1) = 1/2 - 2/3 + 1/4 = 1/12.
    end = brake_pose(np.zeros(6), [10, 0, 0, 0, 0, 0], [0, 6, 0, 0, 0, 0], 2.0, 2.0)
    assert end == pytest.approx([10.0, 6 * 4 / 12, 0, 0, 0, 0], abs=1e-12)


def test_duration_by_hand():
    limits = TrajectoryConfig()  # 500 mm/s^2, 5000 mm/s^3; 50 deg/s^2, 500 deg/s^3
    # x: 1.5*100/(500-100) = 0.375 s, SQRT(12*100/5000) = 0.49 s, 8*100/5000 = 0.16 s -> 0.49 s.
    assert brake_duration([100, 0, 0, 0, 0, 0], [100, 0, 0, 0, 0, 0], limits, 0.001) == pytest.approx(0.49)
    # gamma: 1.5*10/50 = 0.3 s, SQRT(12*10/500) = 0.49 s; rounded up to whole periods of 3 ms: 164 * 3 ms = 0.492 s.
    assert brake_duration([0, 0, 0, 0, 0, 10], [0] * 6, limits, 0.003) == pytest.approx(0.492)
    assert brake_duration([0] * 6, [0] * 6, limits, 0.001) == 0.0
    with pytest.raises(ValueError):
        brake_duration([0] * 6, [500, 0, 0, 0, 0, 0], limits, 0.001)


def test_continuous_at_both_ends_and_inside_the_limits():
    limits = TrajectoryConfig()
    v0 = np.array([80.0, -40.0, 20.0, 5.0, -3.0, 2.0])
    a0 = np.array([-150.0, 100.0, 0.0, 10.0, -20.0, 0.0])
    duration = brake_duration(v0, a0, limits, 0.001)
    dt = 1e-4
    t = np.arange(0, int(round(duration / dt)) + 20) * dt
    pose = brake_pose(np.zeros(6), v0, a0, duration, t)
    velocity = np.diff(pose, axis=0) / dt
    acceleration = np.diff(velocity, axis=0) / dt
    assert velocity[0] == pytest.approx(v0 + a0 * dt / 2, abs=1e-5)  # jerk terms: O(j dt^2)
    assert acceleration[0] == pytest.approx(a0, abs=0.5)  # the first difference spans dt at a jerk below 5000
    assert np.abs(velocity[-5:]).max() == 0.0 and np.abs(acceleration[-5:]).max() == 0.0
    assert np.abs(acceleration[:, :3]).max() <= limits.linear_acceleration
    assert np.abs(acceleration[:, 3:]).max() <= limits.angular_acceleration


def test_setpoint_motion_of_a_parabola():
    # p = t^2 (a = 2) sampled at t = -2dt, -dt, 0: a0 = 2, v0 = (0 - dt^2)/dt + 2*dt/2 = 0 (the velocity at t = 0).
    dt = 0.001
    samples = [np.full(6, t * t) for t in (-2 * dt, -dt, 0.0)]
    velocity, acceleration = setpoint_motion(*samples, dt)
    assert acceleration == pytest.approx(np.full(6, 2.0), rel=1e-6)
    assert velocity == pytest.approx(np.zeros(6), abs=1e-9)
