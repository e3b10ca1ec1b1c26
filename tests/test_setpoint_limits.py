"""check_setpoint_limits: finite differences at the task period against the actuator limits, values by hand."""

from __future__ import annotations

import numpy as np
import pytest

from stgen.scenarios.setpoint_limits import check_setpoint_limits

DT = 0.001


def test_constant_acceleration_by_hand():
    # q = 1000 * t^2 / 2 (a = 1000 mm/s^2) on cylinder 1, rest on cylinder 2; 101 scans:
    # v of the last scan = (q(0.1) - q(0.099)) / dt = 1000 * (0.1 + 0.099) / 2 = 99.5 mm/s.
    t = np.arange(101) * DT
    q = np.stack((500.0 * t**2, np.full_like(t, 300.0)), axis=1)
    check = check_setpoint_limits(q, DT, velocity_limit=250.0, acceleration_limit=2500.0)
    assert check.max_velocity == pytest.approx([99.5, 0.0], abs=1e-9)
    assert check.max_acceleration == pytest.approx([1000.0, 0.0], rel=1e-6)
    assert check.max_velocity_step == pytest.approx([1.0, 0.0], rel=1e-6)
    assert check.passed and check.first_breach_scan is None


def test_velocity_step_is_an_acceleration_breach():
    # At rest, then 7.4 mm/s from row 4 on: one scan changes v by 7.4 mm/s, a = 7400 mm/s^2 > 2500.
    q = np.zeros((8, 1))
    q[3:, 0] = 7.4e-3 * np.arange(1, 6)
    check = check_setpoint_limits(q, DT, 250.0, 2500.0)
    assert check.max_acceleration[0] == pytest.approx(7400.0, rel=1e-9)
    assert check.acceleration_breaches == 1 and check.velocity_breaches == 0
    assert check.first_breach_scan == 4 and not check.passed


def test_velocity_breach_and_inactive_scans_are_skipped():
    # 0.3 mm in one scan = 300 mm/s > 250 mm/s; with that scan marked inactive the jump is not taken.
    q = np.array([[0.0], [0.0], [0.3], [0.3]])
    check = check_setpoint_limits(q, DT, 250.0, 1e9)
    assert check.velocity_breaches == 1 and check.first_breach_scan == 3
    skipped = check_setpoint_limits(q, DT, 250.0, 1e9, active=[True, True, False, True])
    assert skipped.passed and skipped.max_velocity[0] == 0.0
