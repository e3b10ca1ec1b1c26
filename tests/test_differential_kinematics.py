"""The rendered IK and FK, executed in st_runtime, against the NumPy reference (issue 4 item 5).

Harness PROGRAMs (stgen.verify) run thousands of cases in one scan; the
scan-by-scan behaviour of SP_ForwardKinematics is tested through real
controller scans at the end.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from st_runtime import api
from stgen.config import PlatformConfig, SolverConfig
from stgen.error_codes import ErrorCode
from stgen.reference import forward_kinematics, inverse_kinematics
from stgen.render import RenderOptions
from stgen.verify import (
    WARM_START_OFFSET,
    check_forward_kinematics,
    check_inverse_kinematics,
    fk_solver,
    kinematics_sources,
    load_kinematics,
    random_poses,
)

CONFIG = PlatformConfig.default()
IK_POSES = 10_000
FK_POSES = 500
SEED = 4242


@pytest.fixture(scope="module")
def runtime():
    return load_kinematics(CONFIG, RenderOptions("table"), capacity=2000)


@pytest.fixture(scope="module")
def reachable_poses():
    return random_poses(CONFIG, IK_POSES, SEED)


def _solver(**changes) -> SolverConfig:
    """The default solver settings with Tolerance 1e-9 (and ``changes``)."""
    return fk_solver(CONFIG, **changes)


# --------------------------------------------------------------------------- inverse kinematics


def test_random_poses_are_reachable_and_spread(reachable_poses):
    assert reachable_poses.shape == (IK_POSES, 6)
    assert inverse_kinematics(CONFIG.geometry, reachable_poses, CONFIG.stroke).reachable.all()
    spread = reachable_poses.max(axis=0) - reachable_poses.min(axis=0)
    assert (spread[:3] > 200.0).all() and (spread[3:] > 20.0).all()


def test_ik_matches_the_reference_on_10000_reachable_and_1000_mixed_poses(runtime, reachable_poses):
    mixed = random_poses(CONFIG, 1000, SEED + 1, reachable=False)
    reference_status = inverse_kinematics(CONFIG.geometry, mixed, CONFIG.stroke).status
    assert 50 < np.sum(reference_status == ErrorCode.UNREACHABLE) < 950  # both outcomes exercised
    check = check_inverse_kinematics(runtime, CONFIG, np.concatenate([reachable_poses, mixed]))
    assert check.problems == ()
    assert check.max_error <= 1e-9


def test_ik_home_pose_gives_the_documented_home_cylinder_position(runtime):
    """docs/mathematics.md section 2: the home pose puts every cylinder at about 9.9994 mm."""
    run = runtime.inverse_kinematics(np.zeros((1, 6)))
    assert run.positions[0] == pytest.approx([9.9994] * 6, abs=1e-4)
    assert run.reachable[0] and run.error_ids[0] == 0


def test_ik_reports_an_unreachable_pose_with_the_positions_it_would_need(runtime):
    pose = np.array([[0.0, 0.0, 900.0, 0.0, 0.0, 0.0]])  # far above the stroke
    run = runtime.inverse_kinematics(pose)
    expected = inverse_kinematics(CONFIG.geometry, pose, CONFIG.stroke).positions[0]
    assert not run.reachable[0]
    assert run.error_ids[0] == ErrorCode.UNREACHABLE.error_id == 0x1004
    assert np.all(run.positions[0] > CONFIG.stroke.max)
    assert np.max(np.abs(run.positions[0] - expected)) <= 1e-9


def test_ik_never_outputs_nan(runtime):
    good = np.array([10.0, -20.0, 200.0, 1.0, 2.0, 3.0])
    run = runtime.inverse_kinematics(np.array([good, [np.nan, 0.0, 200.0, 0.0, 0.0, 0.0], good * [1, 1, 1, 1, 1, np.inf]]))
    assert list(run.error_ids) == [0, 0x1003, 0x1003]
    assert list(run.reachable) == [True, False, False]
    # CylinderPos keeps the last finite result.
    assert np.array_equal(run.positions[1], run.positions[0]) and np.array_equal(run.positions[2], run.positions[0])


# --------------------------------------------------------------------------- forward kinematics


def test_fk_from_p_nr_on_500_poses(runtime, reachable_poses):
    check = check_forward_kinematics(runtime, CONFIG, reachable_poses[:FK_POSES], "p_NR", CONFIG.solver.start_pose)
    assert check.problems == ()
    assert check.max_error <= 1e-6


def test_fk_from_warm_starts_on_500_poses(runtime, reachable_poses):
    poses = reachable_poses[FK_POSES : 2 * FK_POSES]
    rng = np.random.default_rng(SEED + 2)
    warm = poses + rng.uniform(-1.0, 1.0, size=poses.shape) * WARM_START_OFFSET
    check = check_forward_kinematics(runtime, CONFIG, poses, "warm starts", warm)
    assert check.problems == ()
    assert check.max_error <= 1e-6
    # a warm start needs fewer iterations than p_NR
    assert int(check.iterations.split("..")[1]) <= 5


def test_fk_with_the_det_from_the_lu_diagonal_takes_the_same_iterations(reachable_poses):
    runtime_lu = load_kinematics(CONFIG, RenderOptions("lu"), capacity=200)
    check = check_forward_kinematics(runtime_lu, CONFIG, reachable_poses[:100], "p_NR", CONFIG.solver.start_pose)
    assert check.problems == ()
    assert check.max_error <= 1e-6


def test_fk_with_the_unrolled_determinant_takes_the_same_iterations(reachable_poses):
    runtime_unrolled = load_kinematics(CONFIG, RenderOptions("unrolled"), capacity=100)
    check = check_forward_kinematics(runtime_unrolled, CONFIG, reachable_poses[:50], "p_NR", CONFIG.solver.start_pose)
    assert check.problems == ()


def _fk_case(runtime, positions, start, solver):
    run = runtime.forward_kinematics(np.array([positions]), np.array([start]), solver)
    ref = forward_kinematics(CONFIG.geometry, positions, start, solver)
    return run, ref


def test_fk_unreachable_cylinder_positions_end_in_an_error_without_nan(runtime):
    # Legs alternately fully retracted and fully extended: no pose has these lengths.
    positions = np.array([0.0, 600.0, 0.0, 600.0, 0.0, 600.0])
    run, ref = _fk_case(runtime, positions, CONFIG.solver.start_pose, _solver())
    assert not ref.converged
    assert not run.done[0] and run.error_ids[0] == ref.status.error_id != 0
    assert run.iterations[0] == ref.iterations
    assert np.all(np.isfinite(run.poses[0]))


def test_fk_too_few_iterations_is_not_converged(runtime, reachable_poses):
    positions = inverse_kinematics(CONFIG.geometry, reachable_poses[0], CONFIG.stroke).positions
    run, ref = _fk_case(runtime, positions, CONFIG.solver.start_pose, _solver(max_iterations=2))
    assert ref.status == ErrorCode.NOT_CONVERGED
    assert run.error_ids[0] == 0x1002 and run.iterations[0] == 2 and not run.done[0]


def test_fk_singular_jacobian_is_reported_before_any_step(runtime):
    """With R = I and the platform joints in the plane of the base joints
    (z + h0 + hp = hb), every leg is horizontal: the z column of J is zero, det J = 0."""
    g = CONFIG.geometry
    start = np.array([0.0, 0.0, g.hb - g.h0 - g.hp, 0.0, 0.0, 0.0])
    positions = inverse_kinematics(g, np.array([0.0, 0.0, 100.0, 0.0, 0.0, 0.0]), CONFIG.stroke).positions
    run, ref = _fk_case(runtime, positions, start, _solver())
    assert ref.status == ErrorCode.SINGULAR_JACOBIAN and ref.iterations == 0
    assert run.error_ids[0] == 0x1001 and run.iterations[0] == 0 and not run.done[0]


def test_fk_nan_input_is_non_finite(runtime):
    positions = np.array([10.0, 10.0, math.nan, 10.0, 10.0, 10.0])
    run, ref = _fk_case(runtime, positions, CONFIG.solver.start_pose, _solver())
    assert ref.status == ErrorCode.NON_FINITE
    assert run.error_ids[0] == 0x1003 and run.iterations[0] == 0
    assert np.all(np.isfinite(run.poses[0]))


# --------------------------------------------------------------------------- scan by scan


_SCAN_PROGRAM = """
PROGRAM FkScans
VAR
    Execute : BOOL;
    CylinderPos : ARRAY[1..6] OF LREAL;
    StartPose : ARRAY[1..6] OF LREAL;
    IterationsPerScan : INT := 1;
    Fk : SP_ForwardKinematics;
END_VAR
Fk(Execute := Execute, CylinderPos := CylinderPos, StartPose := StartPose, Tolerance := 1.0E-9,
   IterationsPerScan := IterationsPerScan, MaxIterations := 50);
END_PROGRAM
"""


@pytest.fixture(scope="module")
def scan_program():
    sources = kinematics_sources(CONFIG, RenderOptions("table"), capacity=1)
    sources["FkScans.st"] = _SCAN_PROGRAM
    plc = api.load_sources(sources).controller(period="1ms", stop_on_fault=True)
    return plc, plc.add_program("FkScans")


def test_one_iteration_per_scan_spreads_the_solve_over_many_scans(scan_program):
    plc, program = scan_program
    pose = np.array([40.0, -30.0, 180.0, 4.0, -3.0, 2.0])
    positions = inverse_kinematics(CONFIG.geometry, pose, CONFIG.stroke).positions
    ref = forward_kinematics(CONFIG.geometry, positions, CONFIG.solver.start_pose, _solver(iterations_per_scan=1))
    assert ref.converged and ref.scans == ref.iterations >= 4

    program["CylinderPos"] = positions.tolist()
    program["StartPose"] = list(CONFIG.solver.start_pose)
    program["IterationsPerScan"] = 1
    program["Execute"] = True
    history = []
    for _ in range(ref.scans + 2):
        plc.scan()
        history.append((program["Fk.Busy"], program["Fk.Done"], program["Fk.Iterations"]))
    expected = [(True, False, k) for k in range(1, ref.scans)] + [(False, True, ref.scans)] * 3
    assert history == expected
    assert np.max(np.abs(np.array(program["Fk.Pose"]) - pose)) <= 1e-6
    assert plc.faults == []

    # Done stays while Execute is held, and is cleared by the first call with Execute FALSE.
    program["Execute"] = False
    plc.scan()
    assert (program["Fk.Done"], program["Fk.Busy"], program["Fk.Error"]) == (False, False, False)
    assert np.max(np.abs(np.array(program["Fk.Pose"]) - pose)) <= 1e-6  # the pose stays readable


def test_execute_dropped_while_busy_shows_done_for_one_scan(scan_program):
    plc, program = scan_program
    pose = np.array([-50.0, 20.0, 300.0, -5.0, 6.0, -2.0])
    positions = inverse_kinematics(CONFIG.geometry, pose, CONFIG.stroke).positions
    ref = forward_kinematics(CONFIG.geometry, positions, CONFIG.solver.start_pose, _solver(iterations_per_scan=1))
    program["CylinderPos"] = positions.tolist()
    program["IterationsPerScan"] = 1
    program["Execute"] = True
    plc.scan()  # rising edge: started, first iteration
    program["Execute"] = False
    done_scans = []
    for scan in range(ref.scans + 3):
        plc.scan()
        if program["Fk.Done"]:
            done_scans.append(scan)
    assert done_scans == [ref.scans - 2]  # exactly one scan, the one that finished the solve
    assert program["Fk.Iterations"] == ref.iterations


def test_another_platform_renders_and_matches_its_reference():
    from stgen.config import GeometryConfig, StrokeConfig

    config = PlatformConfig(geometry=GeometryConfig(rb=520.0, rp=350.0, h0=1300.0, l0=1150.0, hb=80.0, hp=-90.0,
                                                    phi_b_deg=30.0, phi_p_deg=90.0),
                            stroke=StrokeConfig(min=-20.0, max=650.0))
    other = load_kinematics(config, RenderOptions("table"), capacity=1000)
    poses = random_poses(config, 1000, 77)
    ik = check_inverse_kinematics(other, config, poses)
    assert ik.problems == () and ik.max_error <= 1e-9
    fk = check_forward_kinematics(other, config, poses[:50], "p_NR", config.solver.start_pose)
    assert fk.problems == () and fk.max_error <= 1e-6


def test_fk_on_a_singular_geometry_reports_a_singular_jacobian():
    """Joint pairs that coincide (phi_b = phi_p = 0) make legs 2k-1 and 2k one leg: J has two
    equal rows everywhere. The configuration refuses such a geometry, so it is forced past
    the validation here, as a hand-edited SP_Constants could be; the FB must still end
    in ERR_SINGULAR_JACOBIAN, never in a division by a zero pivot or a NaN."""
    geometry = CONFIG.geometry.__class__()
    object.__setattr__(geometry, "phi_b_deg", 0.0)
    object.__setattr__(geometry, "phi_p_deg", 0.0)
    config = PlatformConfig()
    object.__setattr__(config, "geometry", geometry)
    singular = load_kinematics(config, RenderOptions("table"), capacity=1)
    positions = inverse_kinematics(geometry, np.array([0.0, 0.0, 150.0, 0.0, 0.0, 0.0]), CONFIG.stroke).positions
    run = singular.forward_kinematics(positions[None, :], np.array([CONFIG.solver.start_pose]), _solver())
    ref = forward_kinematics(geometry, positions, CONFIG.solver.start_pose, _solver())
    assert ref.status == ErrorCode.SINGULAR_JACOBIAN and ref.iterations == 0
    assert run.error_ids[0] == 0x1001 and run.iterations[0] == 0 and not run.done[0]
    assert np.all(np.isfinite(run.poses[0]))
