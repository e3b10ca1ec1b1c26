"""Paths (docs/mathematics.md section 6.3): curves, time law, actuator rates against central differences, planning."""

from __future__ import annotations

import math

import numpy as np
import pytest

from stgen.config import PlatformConfig
from stgen.reference.actuator_rates import actuator_rates, rate_jacobian, angular_velocity
from stgen.reference.kinematics import inverse_kinematics
from stgen.reference.paths import (FAMILIES, PathError, PathSpec, curve_derivatives, plan_path, sample,
                                   time_law)

CONFIG = PlatformConfig()
SPECS = [PathSpec("epitrochoid"), PathSpec("epicycloid"), PathSpec("hypocycloid", R=100.0, r=25.0),
         PathSpec("spiral", a=10.0, b=5.0)]


@pytest.mark.parametrize("spec", SPECS, ids=FAMILIES)
def test_curve_derivatives_match_central_differences(spec):
    phi = np.linspace(0.1, spec.end - 0.1, 57)
    h = 1e-5
    for order in (1, 2, 3):
        numeric = (curve_derivatives(spec, phi + h, order - 1) - curve_derivatives(spec, phi - h, order - 1)) / (2 * h)
        scale = np.abs(curve_derivatives(spec, phi, order)).max()
        assert np.abs(numeric - curve_derivatives(spec, phi, order)).max() < 1e-7 * max(scale, 1.0) * 10


def test_curves_by_hand():
    # φ = 0: epitrochoid (R + r − d, 0); hypocycloid (R, 0); spiral (a, 0)
    assert curve_derivatives(PathSpec("epitrochoid", R=60, r=20, d=30), 0.0, 0) == pytest.approx(50.0)
    assert curve_derivatives(PathSpec("hypocycloid", R=100, r=25), 0.0, 0) == pytest.approx(100.0)
    assert curve_derivatives(PathSpec("spiral", a=7, b=5), 0.0, 0) == pytest.approx(7.0)
    # epicycloid cusp at φ = 0: d = r, speed zero; closes after 2π for R/r = 3, after 4π for R/r = 3/2
    assert abs(curve_derivatives(PathSpec("epicycloid"), 0.0, 1)) < 1e-12
    assert PathSpec("epicycloid", R=30, r=20).end == pytest.approx(4 * math.pi)
    spec = PathSpec("epitrochoid", R=30, r=20)
    assert curve_derivatives(spec, spec.end, 0) == pytest.approx(curve_derivatives(spec, 0.0, 0))


@pytest.mark.parametrize("law", ["blend", "cycloidal"])
def test_time_law_derivatives_and_rest_at_both_ends(law):
    spec = PathSpec("spiral", law=law, blend=0.2)
    u = np.linspace(0.0, 1.0, 2001)[1:-1]
    h = 1e-6
    values = time_law(spec, u)
    for order in (1, 2, 3):
        numeric = (time_law(spec, u + h)[order - 1] - time_law(spec, u - h)[order - 1]) / (2 * h)
        assert np.abs(numeric - values[order]).max() < 1e-4 * (1 + np.abs(values[order]).max())
    f0, f1, f2, _ = time_law(spec, np.array([0.0, 1.0]))
    assert f0 == pytest.approx([0.0, 1.0], abs=1e-15)
    assert f1 == pytest.approx([0.0, 0.0], abs=1e-15)
    assert f2 == pytest.approx([0.0, 0.0], abs=1e-12)


def test_blend_law_is_uniform_between_blends_and_continuous_at_their_ends():
    spec = PathSpec("spiral", blend=0.1)
    f0, f1, f2, _ = time_law(spec, np.array([0.1 - 1e-12, 0.1 + 1e-12, 0.5, 0.9 - 1e-12, 0.9 + 1e-12]))
    assert f1 == pytest.approx([1 / 0.9] * 5)
    assert f2 == pytest.approx([0.0] * 5, abs=1e-9)
    assert f0[2] == pytest.approx(0.5)
    assert f0[0] == pytest.approx(0.1 / 0.9 / 2)            # the blend covers Ω·b/2


def _smooth_pose(t):
    """A pose moving in all six coordinates, and its analytic first and second derivatives."""
    w = np.array([0.7, 1.1, 0.5, 0.9, 1.3, 0.6])
    amp = np.array([80.0, -60.0, 50.0, 20.0, -15.0, 25.0])
    base = np.array([10.0, -5.0, 250.0, 5.0, 3.0, -4.0])
    t = np.asarray(t)[..., None]
    return base + amp * np.sin(w * t), amp * w * np.cos(w * t), -amp * w * w * np.sin(w * t)


def test_actuator_rates_match_central_differences_with_rotation():
    t = np.linspace(0.0, 8.0, 101)
    h = 1e-5
    pose, rate, acc = _smooth_pose(t)
    legs = actuator_rates(CONFIG.geometry, pose, rate, acc)
    length = lambda tt: inverse_kinematics(CONFIG.geometry, _smooth_pose(tt)[0]).leg_lengths
    v_num = (length(t + h) - length(t - h)) / (2 * h)
    a_num = (length(t + h) - 2 * legs.lengths + length(t - h)) / h**2
    assert np.abs(legs.velocities - v_num).max() < 1e-6
    assert np.abs(legs.accelerations - a_num).max() < 1e-2     # second difference: rounding ~ 1e-13/h²
    assert np.abs(legs.lengths - length(t)).max() < 1e-9


def test_rate_jacobian_times_twist_is_the_leg_rate():
    pose, rate, acc = _smooth_pose(np.linspace(0.0, 5.0, 11))
    omega = angular_velocity(np.radians(pose[:, 3:]), np.radians(rate[:, 3:]))
    twist = np.concatenate((rate[:, :3], omega), axis=-1)
    jac = rate_jacobian(CONFIG.geometry, pose)
    expected = actuator_rates(CONFIG.geometry, pose, rate, acc).velocities
    assert np.abs(np.einsum("nij,nj->ni", jac, twist) - expected).max() < 1e-9


@pytest.mark.parametrize("spec", SPECS + [PathSpec("epitrochoid", orientation=(0.0, 35.0, 35.0), law="cycloidal")])
def test_path_leg_rates_match_central_differences_of_the_ik(spec):
    duration = 20.0
    t = np.linspace(0.01, duration - 0.01, 301)
    h = 1e-5
    path = sample(spec, duration, t)
    legs = actuator_rates(CONFIG.geometry, path.poses, path.rates, path.accelerations)
    length = lambda tt: inverse_kinematics(CONFIG.geometry, sample(spec, duration, tt).poses).leg_lengths
    assert np.abs(legs.velocities - (length(t + h) - length(t - h)) / (2 * h)).max() < 1e-6
    assert np.abs(legs.accelerations - (length(t + h) - 2 * legs.lengths + length(t - h)) / h**2).max() < 1e-2
    # pose jerk against differences of the analytic acceleration
    jerk = (sample(spec, duration, t + h).accelerations - sample(spec, duration, t - h).accelerations) / (2 * h)
    assert np.abs(path.jerks - jerk).max() < 1e-5


def test_shortest_duration_of_the_epicycloid_by_hand():
    # R/r = 3: φ_end = 2π, max |y'| = 2(R + r) at φ = π; blend 0.1 → φ̇ peak = φ_end/(0.9 T);
    # x/y velocity limit 100 mm/s binds: T = 2·80·2π/(0.9·100), rounded up to the 1 ms period.
    plan = plan_path(PathSpec("epicycloid"), CONFIG)
    assert plan.binding == "x/y velocity"
    assert plan.duration == pytest.approx(math.ceil(2 * 80 * 2 * math.pi / 0.9 / 100 * 1000) / 1000)


@pytest.mark.parametrize("spec", SPECS, ids=FAMILIES)
def test_plan_keeps_every_limit_and_starts_and_ends_at_rest(spec):
    plan = plan_path(spec, CONFIG)
    ext = plan.extremes()
    assert ext["velocity_max"].max() <= CONFIG.actuator.max_velocity
    assert ext["acceleration_max"].max() <= CONFIG.actuator.max_acceleration
    assert np.abs(plan.samples.rates[:, :2]).max() <= CONFIG.trajectory.linear_velocity * (1 + 1e-9)
    assert np.abs(plan.samples.accelerations[:, :2]).max() <= CONFIG.trajectory.linear_acceleration * (1 + 1e-9)
    for row in (0, -1):
        assert np.abs(plan.legs.velocities[row]).max() < 1e-9
        assert np.abs(plan.legs.accelerations[row]).max() < 1e-9


def test_actuator_limit_binds_when_tight():
    slow = PlatformConfig(actuator=type(CONFIG.actuator)(max_velocity=5.0, max_acceleration=2500.0))
    plan = plan_path(PathSpec("epitrochoid", orientation=(0.0, 20.0, 20.0)), slow)
    assert plan.binding == "actuator velocity"
    assert plan.extremes()["velocity_max"].max() == pytest.approx(5.0, rel=1e-3)


def test_bad_specs_are_refused_with_the_parameter():
    with pytest.raises(PathError, match="family"):
        PathSpec("circle")
    with pytest.raises(PathError, match="r: must be less than R"):
        PathSpec("hypocycloid", R=10.0, r=20.0)
    assert plan_path(PathSpec("epicycloid", duration=1.0), CONFIG, samples=11).too_short
