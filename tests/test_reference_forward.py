"""Newton–Raphson forward kinematics (docs/mathematics.md section 3): accuracy, iteration accounting, every failure."""

from __future__ import annotations

import math

import numpy as np
import pytest

from stgen.config import GeometryConfig, SolverConfig
from stgen.error_codes import ErrorCode
from stgen.reference import NewtonRaphsonSolver, forward_kinematics, inverse_kinematics, jacobian, residual

GEOMETRY = GeometryConfig()
P_NR = (60.25, 85.0, 230.7, 0.0, 0.0, 3.75)


def _reachable_poses(count: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(seed)
    poses = rng.uniform(-1.0, 1.0, (2 * count, 6)) * [120.0, 120.0, 120.0, 10.0, 10.0, 10.0]
    poses[:, 2] += 250.0
    ik = inverse_kinematics(GEOMETRY, poses)
    keep = np.flatnonzero(ik.reachable)[:count]
    assert len(keep) == count
    return poses[keep], ik.positions[keep]


def test_fk_recovers_random_reachable_poses_from_p_nr():
    poses, positions = _reachable_poses(300, seed=7)
    solver = SolverConfig(tolerance=1e-9)
    for pose, legs in zip(poses, positions):
        result = forward_kinematics(GEOMETRY, legs, P_NR, solver)
        assert result.status == ErrorCode.OK
        assert np.abs(result.pose[:3] - pose[:3]).max() < 1e-6  # mm
        assert np.abs(result.pose[3:] - pose[3:]).max() < 1e-6  # degrees


def test_default_solver_starts_at_p_nr_and_lands_within_klim():
    poses, positions = _reachable_poses(20, seed=8)
    for pose, legs in zip(poses, positions):
        result = forward_kinematics(GEOMETRY, legs)
        assert result.converged
        # The last step was below Klim = 0.01 and Newton converges quadratically, so the error is far smaller.
        assert np.abs(result.pose[:3] - pose[:3]).max() < 0.01
        assert np.abs(np.radians(result.pose[3:] - pose[3:])).max() < 0.01


def _independent_iteration_count(legs, start_deg, tolerance, limit=100) -> int:
    """Plain Newton with numpy.linalg.solve; counts the step that falls below the tolerance."""
    estimate = np.array(start_deg, dtype=float)
    estimate[3:] = np.radians(estimate[3:])
    for count in range(1, limit + 1):
        delta = np.linalg.solve(jacobian(GEOMETRY, estimate), residual(GEOMETRY, estimate, legs))
        estimate = estimate - delta
        if np.all(np.abs(delta) < tolerance):
            return count
    raise AssertionError("independent Newton did not converge")


@pytest.mark.parametrize("tolerance", [0.01, 1e-6])
def test_iteration_count_follows_the_step_rule(tolerance):
    poses, positions = _reachable_poses(30, seed=9)
    solver = SolverConfig(tolerance=tolerance)
    for legs in positions:
        result = forward_kinematics(GEOMETRY, legs, P_NR, solver)
        assert result.iterations == _independent_iteration_count(legs, P_NR, tolerance)


def test_home_pose_from_itself_takes_one_iteration():
    legs = inverse_kinematics(GEOMETRY, np.zeros(6)).positions
    result = forward_kinematics(GEOMETRY, legs, np.zeros(6))
    assert result.status == ErrorCode.OK and result.iterations == 1
    assert result.pose == pytest.approx(np.zeros(6), abs=1e-9)


@pytest.mark.parametrize("per_scan", [1, 2, 4, 7])
def test_iterations_per_scan_splits_the_work_across_scans(per_scan):
    _, positions = _reachable_poses(1, seed=10)
    reference = forward_kinematics(GEOMETRY, positions[0], P_NR, SolverConfig(tolerance=1e-9, iterations_per_scan=1))
    result = forward_kinematics(
        GEOMETRY, positions[0], P_NR, SolverConfig(tolerance=1e-9, iterations_per_scan=per_scan)
    )
    assert result.iterations == reference.iterations == reference.scans
    assert result.scans == math.ceil(reference.iterations / per_scan)
    assert np.array_equal(result.pose, reference.pose)


def test_solver_state_carries_over_between_scans():
    _, positions = _reachable_poses(1, seed=12)
    machine = NewtonRaphsonSolver(GEOMETRY, SolverConfig(tolerance=1e-9, iterations_per_scan=1))
    machine.start(positions[0], P_NR)
    assert not machine.done and machine.iterations == 0
    assert machine.scan() is False
    assert machine.iterations == 1 and machine.scans == 1
    while not machine.scan():
        pass
    assert machine.status == ErrorCode.OK
    finished = machine.result()
    assert machine.scan() is True  # a finished solver stays put
    again = machine.result()
    assert (again.iterations, again.scans, again.status) == (finished.iterations, finished.scans, finished.status)
    assert np.array_equal(again.pose, finished.pose)


def test_singular_jacobian_is_reported_before_any_step():
    _, positions = _reachable_poses(1, seed=13)
    result = forward_kinematics(GEOMETRY, positions[0], P_NR, SolverConfig(singularity_threshold=1e40))
    assert result.status == ErrorCode.SINGULAR_JACOBIAN
    assert result.iterations == 0
    assert result.pose == pytest.approx(P_NR)


def test_architecture_singular_platform_is_reported():
    # Similar base and platform hexagons (φb = φp): det J vanishes at every pose.
    similar = GeometryConfig(phi_p_deg=24.07)
    result = forward_kinematics(similar, np.full(6, 50.0))
    assert result.status == ErrorCode.SINGULAR_JACOBIAN


def test_not_converged_after_the_total_limit():
    _, positions = _reachable_poses(1, seed=14)
    solver = SolverConfig(tolerance=1e-12, max_iterations=2, iterations_per_scan=1)
    result = forward_kinematics(GEOMETRY, positions[0], P_NR, solver)
    assert result.status == ErrorCode.NOT_CONVERGED
    assert result.iterations == 2 and result.scans == 2


@pytest.mark.parametrize(
    ("positions", "start"),
    [
        ([10.0, np.nan, 10.0, 10.0, 10.0, 10.0], P_NR),
        ([10.0] * 6, (0.0, 0.0, np.inf, 0.0, 0.0, 0.0)),
    ],
)
def test_non_finite_input_is_reported(positions, start):
    result = forward_kinematics(GEOMETRY, positions, start)
    assert result.status == ErrorCode.NON_FINITE
    assert result.iterations == 0
