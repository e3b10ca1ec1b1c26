"""NumPy reference of the platform variants (docs/mathematics.md sections 6.1, 6.2): rotations, legs, joint angles,
crank IK, feasibility, rates (against central differences) and the variants' FK."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from stgen.config import PlatformConfig, SolverConfig, load_config
from stgen.reference import inverse_kinematics, jacobian, residual
from stgen.reference.crank import crank_inverse_kinematics, crank_tips_world
from stgen.reference.feasibility import Limit, check_pose, feasibility
from stgen.reference.geometry import rotation_matrix
from stgen.reference.moving_base import legs, spherical_tilt, universal_joint_angles
from stgen.reference.orientation import (
    axis_rotation,
    angular_acceleration,
    angular_velocity,
    rotation,
    rotation_partials,
)
from stgen.reference.rates import crank_rates, leg_rates
from stgen.reference.variant_fk import VariantModel, variant_forward_kinematics

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
CRANK = load_config(EXAMPLES / "crank_platform.toml")
MOVING = load_config(EXAMPLES / "moving_base_platform.toml")
ORDERS = ("ZYX", "XYZ", "XZY", "YXZ", "YZX", "ZXY")


def _skew_to_vector(matrix):
    return np.stack((matrix[..., 2, 1], matrix[..., 0, 2], matrix[..., 1, 0]), axis=-1)


# ------------------------------------------------------------------ rotations


def test_zyx_is_spec_1s_rotation():
    angles = np.random.default_rng(1).uniform(-1.5, 1.5, (50, 3))
    assert np.abs(rotation("ZYX", angles) - rotation_matrix(*angles.T)).max() < 1e-15


def test_xyz_is_the_product_of_the_elementary_rotations():
    a, b, c = 0.3, -0.7, 1.1
    expected = axis_rotation("X", a) @ axis_rotation("Y", b) @ axis_rotation("Z", c)
    assert np.abs(rotation("XYZ", [a, b, c]) - expected).max() < 1e-15
    # Hand check of Rx(90°): y goes to z.
    assert axis_rotation("X", np.pi / 2) @ np.array([0, 1.0, 0]) == pytest.approx([0, 0, 1.0])


@pytest.mark.parametrize("order", ORDERS)
def test_angular_velocity_and_acceleration_against_central_differences(order):
    rng = np.random.default_rng(7)
    a0, rate, accel = rng.uniform(-1, 1, (3, 20, 3))
    h = 1e-5

    def angles(t):
        return a0 + rate * t + 0.5 * accel * t * t

    def omega_fd(t):
        r_dot = (rotation(order, angles(t + h)) - rotation(order, angles(t - h))) / (2 * h)
        return _skew_to_vector(r_dot @ np.swapaxes(rotation(order, angles(t)), -1, -2))

    omega = angular_velocity(order, a0, rate)
    assert np.abs(omega - omega_fd(0.0)).max() < 1e-8
    omega_dot_fd = (angular_velocity(order, angles(h), rate + accel * h)
                    - angular_velocity(order, angles(-h), rate - accel * h)) / (2 * h)
    assert np.abs(angular_acceleration(order, a0, rate, accel) - omega_dot_fd).max() < 1e-7
    partials = rotation_partials(order, a0)
    for k in range(3):
        step = np.zeros(3)
        step[k] = h
        numeric = (rotation(order, a0 + step) - rotation(order, a0 - step)) / (2 * h)
        assert np.abs(partials[..., k, :, :] - numeric).max() < 1e-9


# ------------------------------------------------------------------ linear legs, joint angles


def test_fixed_base_zyx_legs_are_spec_2s_ik():
    config = PlatformConfig.default()
    poses = np.random.default_rng(3).uniform(-1, 1, (200, 6)) * [100, 100, 100, 10, 10, 10]
    expected = inverse_kinematics(config.geometry, poses).positions
    assert np.abs(legs(config, poses).extensions - expected).max() < 1e-9


def test_moving_the_base_with_the_platform_leaves_the_legs_unchanged():
    # Same translation of both platforms (no rotation): the legs do not change.
    shift = np.array([12.0, -30.0, 7.0, 0, 0, 0])
    upper = np.array([5.0, 3.0, 20.0, 2.0, -3.0, 4.0])
    moved = legs(MOVING, upper + shift, shift).lengths
    assert moved == pytest.approx(legs(MOVING, upper).lengths, abs=1e-10)


def test_home_tilt_and_universal_angles_by_hand():
    # Both joint planes flat, legs from Oi to Pi: tilt = acos(h0 / l) at home.
    state = legs(MOVING, np.zeros(6))
    o = 184.0 * np.array([np.cos(np.radians(45)), np.sin(np.radians(45)), 0])
    p = 184.0 * np.array([np.cos(np.radians(15)), np.sin(np.radians(15)), 415.706 / 184.0])
    leg = p - o
    assert state.lengths[0] == pytest.approx(np.linalg.norm(leg), abs=1e-12)
    assert np.degrees(spherical_tilt(state))[0] == pytest.approx(np.degrees(np.arccos(415.706 / np.linalg.norm(leg))))
    gamma, psi = universal_joint_angles(MOVING, state)
    e = leg / np.linalg.norm(leg)
    c, s = np.cos(np.radians(45)), np.sin(np.radians(45))
    assert gamma[0] == pytest.approx(np.arcsin(c * e[0] + s * e[1]))
    assert psi[0] == pytest.approx(np.arctan2(s * e[0] - c * e[1], e[2]))


def test_universal_angles_rebuild_the_leg_direction():
    # The leg frame Rz(aB)·Rx(ψ)·Ry(γ) carries the base z axis onto the leg (base frame).
    rng = np.random.default_rng(4)
    upper = rng.uniform(-1, 1, (30, 6)) * [20, 20, 60, 8, 8, 8] + [0, 0, 40, 0, 0, 0]
    base = rng.uniform(-1, 1, (30, 6)) * [10, 10, 5, 6, 6, 6]
    state = legs(MOVING, upper, base)
    gamma, psi = universal_joint_angles(MOVING, state)
    polar = np.radians([45, 75, 165, 195, 285, 315])
    frame = axis_rotation("Z", polar) @ axis_rotation("X", psi) @ axis_rotation("Y", gamma)
    rebuilt = np.einsum("...kj,...ik->...ij", state.joints.base_rotation, state.directions)
    assert np.abs(frame[..., :, 2] - rebuilt).max() < 1e-12


# ------------------------------------------------------------------ crank IK


def _crank_poses(count, seed):
    rng = np.random.default_rng(seed)
    return rng.uniform(-1, 1, (count, 6)) * [120, 120, 80, 8, 8, 10]


def test_crank_ik_meets_the_rod_constraint_to_1e_9_mm():
    poses = _crank_poses(1000, 11)
    solution = crank_inverse_kinematics(CRANK, poses)
    assert solution.solvable.mean() > 0.9
    tips = crank_tips_world(CRANK, solution.angles_deg)
    upper = legs(CRANK, poses).joints.upper
    gap = np.linalg.norm(upper - tips, axis=-1) - CRANK.crank.rod_length
    assert np.nanmax(np.abs(gap[solution.solvable])) < 1e-9


def test_crank_ik_on_a_moving_base_meets_the_rod_constraint():
    rng = np.random.default_rng(12)
    poses, bases = _crank_poses(300, 13), rng.uniform(-1, 1, (300, 6)) * [50, 50, 30, 6, 6, 6]
    solution = crank_inverse_kinematics(CRANK, poses, bases)
    tips = crank_tips_world(CRANK, solution.angles_deg, bases)
    gap = np.linalg.norm(legs(CRANK, poses, bases).joints.upper - tips, axis=-1) - CRANK.crank.rod_length
    assert np.nanmax(np.abs(gap[solution.solvable])) < 1e-9


def test_the_other_branch_is_the_second_solution():
    from dataclasses import replace

    poses = _crank_poses(200, 14)
    first = crank_inverse_kinematics(CRANK, poses)
    config = replace(CRANK, crank=replace(CRANK.crank, branch=(-1,) * 6, angle_min_deg=-180.0, angle_max_deg=180.0))
    second = crank_inverse_kinematics(config, poses)
    both = first.solvable & second.solvable
    tips = crank_tips_world(config, second.angles_deg)
    gap = np.linalg.norm(legs(config, poses).joints.upper - tips, axis=-1) - CRANK.crank.rod_length
    assert np.nanmax(np.abs(gap[both])) < 1e-9
    difference = np.mod(first.angles_deg - second.angles_deg, 360.0)
    assert np.all((difference[both] > 1e-6) | (np.abs(first.cosine[both]) > 1 - 1e-12))


def test_crank_out_of_reach_and_out_of_limits_are_reported():
    far = check_pose(CRANK, [0, 0, 600, 0, 0, 0])  # rods too short: no solution on every leg
    assert not far.feasible
    assert {v.limit for v in far.violations} == {Limit.CRANK_NO_SOLUTION}
    assert sorted(v.leg for v in far.violations) == [1, 2, 3, 4, 5, 6]
    home = crank_inverse_kinematics(CRANK, np.zeros(6)).angles_deg
    assert home == pytest.approx([140.65540422] * 6, abs=1e-6)


# ------------------------------------------------------------------ feasibility


def test_feasibility_names_leg_and_limit():
    report = check_pose(MOVING, [0, 0, 160, 0, 0, 0])  # every leg beyond 150 mm of stroke
    assert not report.feasible
    assert {(v.leg, v.limit) for v in report.violations} >= {(leg, Limit.STROKE_MAX) for leg in range(1, 7)}
    assert "leg 1: stroke_max exceeded by" in str(report.violations[0])
    low = check_pose(MOVING, [0, 0, -5, 0, 0, 0])
    assert {v.limit for v in low.violations} == {Limit.STROKE_MIN}


def test_the_studys_test_poses_are_feasible():
    # docs/mathematics.md section 6.2: (0, 0, 415.706 + 25, 0, 0, 30) and (-15, 15, 415.706 + 100, -5, 7, -15).
    assert check_pose(MOVING, [0, 0, 25, 0, 0, 30]).feasible
    assert check_pose(MOVING, [-15, 15, 100, -5, 7, -15]).feasible


def test_vectorised_feasibility_equals_the_per_pose_check():
    rng = np.random.default_rng(21)
    poses = rng.uniform(-1, 1, (300, 6)) * [40, 40, 80, 15, 15, 25] + [0, 0, 60, 0, 0, 0]
    vectorised = feasibility(MOVING, poses).feasible
    assert 0.1 < vectorised.mean() < 0.9
    assert list(vectorised) == [check_pose(MOVING, pose).feasible for pose in poses]


# ------------------------------------------------------------------ rates


def _motion(t):
    """An arbitrary smooth motion of both platforms (mm and degrees)."""
    upper = np.stack([5 * np.sin(t), 3 * np.cos(2 * t), 20 + 20 * t, 4 * np.sin(t), 3 * t, -2 * np.cos(t)], -1)
    base = np.stack([0.4 * t, -0.2 * t, -3 * np.cos(np.pi * t), 3 * t, 3 * np.sin(t), 2 * t], -1)
    return upper, base


def _differences(t, h=1e-4):
    (u, b), (up, bp), (um, bm) = _motion(t), _motion(t + h), _motion(t - h)
    return u, b, (up - um) / (2 * h), (bp - bm) / (2 * h), (up - 2 * u + um) / h**2, (bp - 2 * b + bm) / h**2


@pytest.mark.parametrize("order", ["XYZ", "ZYX", "YZX"])
def test_leg_rates_against_central_differences(order):
    from dataclasses import replace

    config = replace(MOVING, platform=replace(MOVING.platform, platform_rotation=order, base_rotation=order[::-1]))
    t, h = np.linspace(0.0, 2.0, 41), 1e-4
    u, b, ud, bd, udd, bdd = _differences(t, h)
    rates = leg_rates(config, u, ud, udd, b, bd, bdd)
    lengths = [leg_rates(config, *_motion(t + k * h)[:1], base_pose_deg=_motion(t + k * h)[1]).lengths for k in (-1, 1)]
    assert np.abs(rates.velocities - (lengths[1] - lengths[0]) / (2 * h)).max() < 1e-6
    second = (lengths[1] - 2 * rates.lengths + lengths[0]) / h**2
    assert np.abs(rates.accelerations - second).max() < 1e-3


def test_fixed_base_leg_velocity_is_the_path_jacobian():
    # docs/mathematics.md section 6.3: l̇ = J·(v, ω), row i = [eiᵀ, ((R·Pi) × ei)ᵀ].
    config = PlatformConfig.default()
    pose, rate = np.array([10, -20, 30, 4, -3, 6.0]), np.array([5, 7, -3, 2, -1, 3.0])
    state = legs(config, pose)
    from stgen.reference.orientation import angular_velocity as omega_of

    omega = omega_of("ZYX", np.radians(pose[3:]), np.radians(rate[3:]))
    rows = np.concatenate((state.directions, np.cross(state.joints.upper_arms, state.directions)), axis=-1)
    assert leg_rates(config, pose, rate).velocities == pytest.approx(rows @ np.concatenate((rate[:3], omega)))


def test_crank_rates_against_central_differences():
    from dataclasses import replace

    config = replace(CRANK, platform=replace(CRANK.platform, base="moving"))
    t, h = np.linspace(0.0, 1.0, 21), 1e-4
    u, b, ud, bd, udd, bdd = _differences(t, h)
    u = u - [0, 0, 20, 0, 0, 0]
    rates = crank_rates(config, u, ud, udd, b, bd, bdd)
    assert np.all(np.isfinite(rates.angles_deg))
    angles = [crank_rates(config, _motion(t + k * h)[0] - [0, 0, 20, 0, 0, 0],
                          base_pose_deg=_motion(t + k * h)[1]).angles_deg for k in (-1, 1)]
    assert np.abs(rates.rates - (angles[1] - angles[0]) / (2 * h)).max() < 1e-6
    second = (angles[1] - 2 * rates.angles_deg + angles[0]) / h**2
    assert np.abs(rates.accelerations - second).max() < 1e-3


# ------------------------------------------------------------------ FK


def test_variant_model_of_the_default_platform_is_spec_3():
    config = PlatformConfig.default()
    poses = np.random.default_rng(5).uniform(-1, 1, (20, 6)) * [100, 100, 100, 0.2, 0.2, 0.2]
    positions = np.full(6, 120.0)
    model = VariantModel(config, positions)
    assert np.abs(model.residual(poses) - residual(config.geometry, poses, positions)).max() < 1e-6
    assert np.abs(model.jacobian(poses) - jacobian(config.geometry, poses)).max() < 1e-6


@pytest.mark.parametrize("config", [CRANK, MOVING], ids=["crank", "moving_base"])
def test_variant_jacobian_against_central_differences(config):
    rng = np.random.default_rng(8)
    poses = rng.uniform(-1, 1, (20, 6)) * [30, 30, 30, 0.1, 0.1, 0.1] + [0, 0, 30, 0, 0, 0]
    model = VariantModel(config, np.full(6, 140.0) if config.is_crank else np.full(6, 40.0),
                         None if config.is_crank else [5, -3, 2, 3, -2, 4])
    analytic = model.jacobian(poses)
    for column, step in enumerate([1e-3] * 3 + [1e-6] * 3):
        offset = np.zeros(6)
        offset[column] = step
        numeric = (model.residual(poses + offset) - model.residual(poses - offset)) / (2 * step)
        assert np.abs(analytic[..., column] - numeric).max() <= 1e-6 * np.abs(analytic[..., column]).max()


def test_crank_fk_recovers_the_pose_from_measured_crank_angles():
    tight = SolverConfig(tolerance=1e-9, max_iterations=50)
    poses = _crank_poses(50, 31) * 0.5
    solution = crank_inverse_kinematics(CRANK, poses)
    assert solution.reachable.all()
    for pose, angles in zip(poses, solution.angles_deg):
        result = variant_forward_kinematics(CRANK, angles, np.zeros(6), solver=tight)
        assert result.converged
        assert np.abs(result.pose - pose).max() < 1e-9


def test_moving_base_fk_recovers_the_world_pose():
    tight = SolverConfig(tolerance=1e-9, max_iterations=50, singularity_threshold=1e18)
    rng = np.random.default_rng(32)
    poses = rng.uniform(-1, 1, (50, 6)) * [20, 20, 40, 8, 8, 8] + [0, 0, 60, 0, 0, 0]
    bases = rng.uniform(-1, 1, (50, 6)) * [20, 20, 10, 5, 5, 5]
    extensions = legs(MOVING, poses, bases).extensions
    for pose, base, measured in zip(poses, bases, extensions):
        result = variant_forward_kinematics(MOVING, measured, base + [0, 0, 60, 0, 0, 0], base, solver=tight)
        assert result.converged
        assert np.abs(result.pose - pose).max() < 1e-9
