"""Reference details that mutation testing found unchecked (issue 16).

Expected values are worked out by hand (hand-made limit maps and extremes,
ErrorIDs from the table in stgen/error_codes.py, docs/mathematics.md sections
4-6), or come from an independent computation (central differences of the leg
extensions for the rates).
"""

from __future__ import annotations

from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from stgen.config import PlatformConfig, load_config
from stgen.reference.brake import brake_pose
from stgen.reference.cycloidal import cycloidal_velocity
from stgen.reference.feasibility import FeasibilityMap, Limit, check_pose, error_ids, feasibility
from stgen.reference.geometry import pose_to_radians
from stgen.reference.linalg import lu_doolittle, lu_solve
from stgen.reference.motion_limits import MotionCheck
from stgen.reference.paths import PathError, PathSpec, describe, plan_path
from stgen.reference.playback import clamped_spline_slopes
from stgen.reference.study_motions import (fixed_base_upper, motion_report, moving_base_base, moving_base_upper,
                                           study_reports)

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
MOVING = load_config(EXAMPLES / "moving_base_platform.toml")
CRANK = load_config(EXAMPLES / "crank_platform.toml")


# --- ErrorIDs of the variants' IK (stgen/error_codes.py: base + leg; 16#1003 non-finite) ----

def _map(*broken_per_pose):
    """A FeasibilityMap whose excess is 1 where (leg 1..6, limit) is listed, -inf elsewhere."""
    excess = np.full((len(broken_per_pose), 6, len(Limit)), -np.inf)
    for pose, broken in enumerate(broken_per_pose):
        for leg, limit in broken:
            excess[pose, leg - 1, limit] = 1.0
    return FeasibilityMap(excess, {})


def test_error_ids_name_the_lowest_leg_and_its_first_limit():
    result = _map(
        [],                                                                   # feasible
        [(5, Limit.SPHERICAL_TILT), (3, Limit.STROKE_MAX)],                  # lowest leg: 3, stroke
        [(2, Limit.SPHERICAL_TILT), (2, Limit.UNIVERSAL_GAMMA)],            # first limit: universal
        [(6, Limit.CRANK_ANGLE_MAX)],
        [(1, Limit.STROKE_MIN), (4, Limit.NON_FINITE)],                      # non-finite wins
    )
    ids, legs = error_ids(result)
    assert ids.tolist() == [0, 0x1043, 0x1072, 0x1066, 0x1003]
    assert legs.tolist() == [0, 3, 2, 6, 0]
    assert ids.dtype.kind == "i" and legs.dtype.kind == "i"


# --- which limit binds ------------------------------------------------------------------------

def test_binding_of_a_non_finite_pose_is_non_finite():
    result = feasibility(MOVING, np.full(6, np.nan))
    limit, leg = result.binding
    assert (int(limit), int(leg)) == (Limit.NON_FINITE, 1)
    assert not result.feasible


def test_binding_of_a_pose_far_above_the_stroke_is_stroke_max():
    # z = 1000 mm above home: every leg far beyond its 150 mm stroke, nothing else matters as much.
    result = feasibility(PlatformConfig(), np.array([0.0, 0.0, 1000.0, 0.0, 0.0, 0.0]))
    limit, _ = result.binding
    assert int(limit) == Limit.STROKE_MAX
    check = check_pose(PlatformConfig(), [0, 0, 1000, 0, 0, 0], [0, 0, 0, 0, 0, 0])
    assert not check.feasible
    assert {v.limit for v in check.violations} == {Limit.STROKE_MAX}
    assert [v.leg for v in check.violations] == [1, 2, 3, 4, 5, 6]


# --- actuator limits of a sampled motion --------------------------------------------------------

def test_motion_check_extremes_and_breaches_by_hand():
    positions = np.array([[10.0, 20, 30, 40, 50, 60],
                          [-5.0, 25, 35, 45, 160, 65]])
    velocities = np.array([[100.0, -300, 0, 0, 0, 0],
                           [-250.0, 50, 0, 0, 0, 0]])
    accelerations = np.array([[0.0, 0, 0, 0, 0, 2500],
                              [0.0, 0, 0, 0, 0, -3500]])
    check = MotionCheck(np.array([0.0, 0.1]), np.zeros((2, 6)), np.zeros((2, 6)), np.zeros((2, 6)),
                        SimpleNamespace(velocities=velocities, accelerations=accelerations), positions)
    ext = check.extremes()
    assert ext["position_min"].tolist() == [-5, 20, 30, 40, 50, 60]
    assert ext["position_max"].tolist() == [10, 25, 35, 45, 160, 65]
    assert ext["velocity_max"].tolist() == [250, 300, 0, 0, 0, 0]
    assert ext["acceleration_max"].tolist() == [0, 0, 0, 0, 0, 3500]
    config = SimpleNamespace(stroke=SimpleNamespace(min=0.0, max=150.0),
                             actuator=SimpleNamespace(max_velocity=280.0, max_acceleration=3000.0))
    assert check.breaches(config) == [
        (1, "stroke min", -5.0, 0.0),
        (2, "velocity", 300.0, 280.0),
        (5, "stroke max", 160.0, 150.0),
        (6, "acceleration", 3500.0, 3000.0),
    ]


# --- time laws after their end -------------------------------------------------------------------

def test_cycloidal_velocity_is_zero_after_the_move():
    # tau = 1.5: (1 - cos 3pi)/T would be 2/T; outside the move the velocity is 0 (docs/mathematics.md section 4).
    v = cycloidal_velocity(np.zeros(6), np.ones(6), 2.0, np.array([-1.0, 1.0, 3.0]))
    assert v[0].tolist() == [0.0] * 6 and v[2].tolist() == [0.0] * 6
    assert v[1] == pytest.approx([1.0] * 6)         # peak 2h/T = 2 * 1 / 2


def test_brake_of_zero_duration_holds_the_start():
    start = np.arange(6.0)
    poses = brake_pose(start, np.ones(6), np.ones(6), 0.0, np.array([0.0, 0.5, 1.0]))
    assert poses.shape == (3, 6)
    assert (poses == start).all()


# --- paths: description, checks, sample count ------------------------------------------------------

def test_describe_names_the_time_law():
    assert describe(PathSpec("epicycloid", R=60.0, r=20.0, law="cycloidal")).endswith("law cycloidal")
    assert describe(PathSpec("epicycloid", R=60.0, r=20.0, law="blend", blend=0.25)).endswith("law blend 0.25")


@pytest.mark.parametrize("kwargs, message", [
    (dict(R=0.0, r=20.0), "R and r: must be > 0, got R=0.0, r=20.0"),
    (dict(R=60.0, r=20.0, phi_end=0.0), "phi_end: must be a finite number > 0, got 0.0"),
    (dict(R=60.0, r=20.0, phi_end=float("inf")), "phi_end: must be a finite number > 0, got inf"),
])
def test_path_spec_errors_word_for_word(kwargs, message):
    with pytest.raises(PathError) as err:
        PathSpec("epicycloid", **kwargs)
    assert str(err.value) == message


def test_plan_samples_every_task_period_or_as_asked():
    config = PlatformConfig()
    period = config.task.period_s
    spec = PathSpec("epicycloid", R=60.0, r=20.0, duration=2.0)
    plan = plan_path(spec, config, plan_samples=200)
    assert len(plan.samples.t) == round(2.0 / period) + 1          # 0, T/n, ..., 2 s
    assert plan.samples.t[-1] == pytest.approx(2.0)
    assert len(plan_path(spec, config, samples=50, plan_samples=200).samples.t) == 50


# --- the study's motions (docs/mathematics.md section 6.2) ------------------------------------------

def test_study_report_names_and_both_readings_of_theta_b():
    reports = study_reports(MOVING)
    assert [r.name for r in reports] == [
        "moving base (thetaB about z, y, x)", "moving base (thetaB about x, y, z)", "fixed base"]
    # The (x, y, z) reading takes thetaB = (0.3, 0.3, 0.2) t unreversed: a different base motion.
    xyz = motion_report(MOVING, "xyz", moving_base_upper, lambda t: moving_base_base(t, False))
    assert reports[1].max_tilt == xyz.max_tilt and reports[1].extension_range == xyz.extension_range
    assert reports[0].extension_range != reports[1].extension_range


def test_motion_report_rates_match_central_differences_of_the_extensions():
    report = motion_report(MOVING, "fixed base", fixed_base_upper, duration=2.0, period=0.01)
    t, h = np.arange(0.0, 2.0 + 0.005, 0.01), 1e-5
    ahead = feasibility(MOVING, fixed_base_upper(t + h)[0]).values["extension_mm"]
    behind = feasibility(MOVING, fixed_base_upper(t - h)[0]).values["extension_mm"]
    assert report.max_velocity == pytest.approx(np.abs((ahead - behind) / (2 * h)).max(), rel=1e-6)
    assert report.samples == 201


def test_motion_report_names_the_first_broken_limit():
    def far_up(t):
        value = np.zeros(t.shape + (6,))
        value[..., 2] = np.where(t > 0.0, 1000.0, 0.0)   # home, then 1 m above: beyond the 150 mm stroke
        return value, np.zeros_like(value), np.zeros_like(value)

    report = motion_report(MOVING, "far up", far_up, duration=0.01, period=0.005)
    assert not report.feasible
    time, limit, leg = report.first_violation
    assert (time, limit) == (0.005, "stroke_max") and 1 <= leg <= 6
    assert report.max_velocity == 0.0


# --- integer inputs give the float results ------------------------------------------------------------

def test_integer_inputs_are_read_as_floats():
    assert pose_to_radians([0, 0, 0, 90, 180, 45]).tolist() == pytest.approx(
        [0, 0, 0, np.pi / 2, np.pi, np.pi / 4])
    lu, perm = lu_doolittle(np.array([[4.0, 3.0], [6.0, 3.0]]))
    assert lu_solve(lu, perm, [10, 12]) == pytest.approx([1.0, 2.0])     # 4+6 = 10, 6+6 = 12
    # Knots 0..3 at y = 0..3, m0 = m3 = 0: 4 m1 + m2 = 3 (1 + 1) = 6 = m1 + 4 m2, so m1 = m2 = 6/5.
    assert clamped_spline_slopes([0, 1, 2, 3], [[0], [1], [2], [3]])[:, 0] == pytest.approx([0, 1.2, 1.2, 0])


# --- crank legs (docs/mathematics.md section 6.1) ---------------------------------------------------

def test_crank_out_of_reach_excess_is_how_far_the_cosine_is_out():
    # |H / (2 a rho)| - 1 (feasibility's docstring): dimensionless distance out of reach.
    far = check_pose(CRANK, [0, 0, 600, 0, 0, 0])
    cosine = feasibility(CRANK, np.array([0.0, 0.0, 600.0, 0.0, 0.0, 0.0])).values["crank_cosine"]
    assert [v.excess for v in far.violations] == pytest.approx(list(np.abs(cosine) - 1.0), rel=1e-12)
    assert all(abs(c) > 1.0 for c in cosine)


def test_crank_angle_above_its_maximum_is_reported():
    from stgen.reference.crank import crank_inverse_kinematics

    z = np.linspace(-400.0, 400.0, 81)
    poses = np.zeros((len(z), 6))
    poses[:, 2] = z
    solution = crank_inverse_kinematics(CRANK, poses)
    over = solution.solvable & (solution.angles_deg > CRANK.crank.angle_max_deg)
    assert over.any()                                  # the grid reaches above 230 degrees somewhere
    pose, leg = np.argwhere(over)[0]
    found = {(v.leg, v.limit): v.excess for v in check_pose(CRANK, poses[pose]).violations}
    assert found[(leg + 1, Limit.CRANK_ANGLE_MAX)] == pytest.approx(
        solution.angles_deg[pose, leg] - CRANK.crank.angle_max_deg)


# --- the wave's derivative bounds and fade-in (docstrings of wave_derivative_bounds, fade_in_duration) ---

def test_wave_derivative_bounds_of_one_component_by_hand():
    from stgen.reference.wave import OceanWave, WaveComponent, wave_derivative_bounds

    a, w, k = 3.0, 2 * np.pi / 10.0, 2 * np.pi / 100_000.0       # 3 mm, 10 s, 100 m
    bounds = wave_derivative_bounds(OceanWave((WaveComponent(a, 10.0, 100.0, 0.0),), heading_deg=30.0))
    orbit = a * w ** np.arange(4)
    assert bounds[:, 0] == pytest.approx(orbit * np.cos(np.radians(30.0)), rel=1e-12)
    assert bounds[:, 1] == pytest.approx(orbit * 0.5, rel=1e-12)
    assert bounds[:, 2] == pytest.approx(orbit, rel=1e-12)
    assert bounds[:, 3].tolist() == [0.0] * 4
    k0, k1, k2, k3 = a * k * w ** np.arange(4) * 0.5                # the sin(30 deg) column
    c2 = 3 * np.sqrt(3) / 8
    assert bounds[:, 5] == pytest.approx(np.degrees(
        [np.arctan(k0), k1, k2 + c2 * k1**2, k3 + 3 * c2 * k1 * k2 + 2 * k1**3]), rel=1e-12)


def test_fade_in_set_by_the_acceleration_term():
    from stgen.config import TrajectoryConfig
    from stgen.reference.wave import OceanWave, WaveComponent, fade_in_duration

    # A = 100 mm, Tw = 100 s, L = 1000 m: D0 = 100, D2 = 100 w^2. With a velocity limit of 1e4 mm/s the
    # acceleration term 2 pi D0 r^2 <= (500 - D2) / 2 binds (jerk: r = 0.75, velocity: r = 50; the rest larger).
    w = 2 * np.pi / 100.0
    rate = np.sqrt((500.0 - 100.0 * w**2) / 2.0 / (2 * np.pi * 100.0))
    wave = OceanWave((WaveComponent(100.0, 100.0, 1000.0, 0.0),))
    assert fade_in_duration(wave, TrajectoryConfig(linear_velocity=10_000.0)) == pytest.approx(1 / rate, rel=1e-12)


def test_a_wave_whose_jerk_alone_breaks_the_limit_is_refused():
    from stgen.config import TrajectoryConfig
    from stgen.reference.wave import OceanWave, WaveComponent, fade_in_duration

    # A = 1 mm, w = 20 rad/s: D1 = 20 < 100 mm/s, D2 = 400 < 500 mm/s^2, D3 = 8000 > 5000 mm/s^3.
    wave = OceanWave((WaveComponent(1.0, 2 * np.pi / 20.0, 1_000_000.0, 0.0),))
    with pytest.raises(ValueError) as err:
        fade_in_duration(wave, TrajectoryConfig())
    assert str(err.value) == "the wave alone reaches the limits in pose coordinate 1"


# --- more from the second sample (seed 17) -------------------------------------------------------------

@pytest.mark.parametrize("kwargs, message", [
    (dict(family="circle"), "family: must be one of epitrochoid, epicycloid, hypocycloid, spiral, got 'circle'"),
    (dict(family="spiral", law="linear"), "law: must be one of blend, cycloidal, got 'linear'"),
])
def test_path_family_and_law_errors(kwargs, message):
    with pytest.raises(PathError) as err:
        PathSpec(**kwargs)
    assert str(err.value) == message


def test_describe_names_each_family_with_its_parameters():
    assert describe(PathSpec("epitrochoid", R=60.0, r=20.0, d=30.0)).startswith("epitrochoid R=60 r=20 d=30 mm, ")
    assert describe(PathSpec("hypocycloid", R=100.0, r=25.0)).startswith("hypocycloid R=100 r=25 mm, ")
    assert describe(PathSpec("spiral", a=10.0, b=5.0)).startswith("spiral a=10 mm b=5 mm/rad, ")


def test_cycloidal_time_law_and_the_angle_it_drives():
    from stgen.reference.paths import sample, time_law

    spec = PathSpec("epicycloid", R=60.0, r=20.0, law="cycloidal")
    f, f1, f2, f3 = time_law(spec, np.array([0.25]))
    # sigma(u) = u - sin(2 pi u) / (2 pi) (docs/mathematics.md section 4): at u = 1/4, sin = 1, cos = 0.
    assert f[0] == pytest.approx(0.25 - 1 / (2 * np.pi), rel=1e-12)
    assert (f1[0], f2[0]) == pytest.approx((1.0, 2 * np.pi))
    assert abs(f3[0]) < 1e-9
    path = sample(spec, 2.0, np.array([0.0, 2.0]))
    assert path.phi.tolist() == pytest.approx([0.0, spec.end])


def test_a_wave_component_of_zero_wavelength_is_refused():
    from stgen.reference.wave import OceanWave, WaveComponent

    with pytest.raises(ValueError) as err:
        OceanWave((WaveComponent(3.0, 10.0, 0.0, 0.0),))
    assert str(err.value).startswith("period and wavelength must be > 0: WaveComponent(")


def test_brake_refuses_an_angular_acceleration_at_its_limit():
    from stgen.config import TrajectoryConfig
    from stgen.reference.brake import brake_duration

    limits = TrajectoryConfig()                       # angular acceleration limit 50 deg/s^2, linear 500 mm/s^2
    with pytest.raises(ValueError) as err:
        brake_duration(np.zeros(6), [0, 0, 0, 50.0, 0, 0], limits, 0.001)
    assert str(err.value) == "the set-point already accelerates at the limit in pose coordinate 4"


def test_solve_passes_its_pivot_tolerance_on():
    from stgen.reference.linalg import SingularMatrixError, solve

    nearly = np.array([[1.0, 1.0], [1.0, 1.0 + 1e-9]])
    assert solve(nearly, [2.0, 2.0]) == pytest.approx([2.0, 0.0])
    with pytest.raises(SingularMatrixError):
        solve(nearly, [2.0, 2.0], pivot_tolerance=1e-6)


def test_positions_are_leg_lengths_less_l0():
    from stgen.reference.kinematics import inverse_kinematics
    from stgen.reference.motion_limits import check_motion

    config = PlatformConfig()
    pose = np.array([[0.0, 0.0, 20.0, 0.0, 0.0, 0.0]])
    check = check_motion(config, [0.0], pose, np.zeros((1, 6)), np.zeros((1, 6)))
    lengths = inverse_kinematics(config.geometry, pose[0]).leg_lengths
    assert check.positions[0] == pytest.approx(lengths - config.geometry.l0)


def test_spline_through_three_knots():
    # One unknown: 2 (h0 + h1) m1 = 3 (h1 d0 + h0 d1) with h = 1, d = (1, 2): m1 = 9 / 4.
    assert clamped_spline_slopes([0.0, 1.0, 2.0], [[0.0], [1.0], [3.0]])[:, 0].tolist() == [0.0, 2.25, 0.0]


def test_crank_angle_below_its_minimum_is_reported():
    import dataclasses

    from stgen.reference.crank import crank_inverse_kinematics

    # With the minimum raised to 120 degrees, z = +150 mm (cranks near 101 degrees) lies below it.
    config = dataclasses.replace(CRANK, crank=dataclasses.replace(CRANK.crank, angle_min_deg=120.0))
    pose = np.array([0.0, 0.0, 150.0, 0.0, 0.0, 0.0])
    angles = crank_inverse_kinematics(config, pose).angles_deg
    under = [leg for leg in range(6) if angles[leg] < 120.0]
    assert under
    found = {(v.leg, v.limit): v.excess for v in check_pose(config, pose).violations}
    for leg in under:
        assert found[(leg + 1, Limit.CRANK_ANGLE_MIN)] == pytest.approx(120.0 - angles[leg])


def test_lu_needs_a_square_matrix_and_the_leibniz_table_starts_at_one():
    from stgen.reference.linalg import permutation_table

    with pytest.raises(ValueError) as err:
        lu_doolittle(np.zeros((2, 3)))
    assert str(err.value) == "expected a square matrix, got shape (2, 3)"
    perms, signs = permutation_table(1)
    assert perms.tolist() == [[0]] and signs.tolist() == [1]
    with pytest.raises(ValueError) as err:
        permutation_table(0)
    assert str(err.value) == "n must be >= 1, got 0"


def test_a_finished_solver_stays_done():
    from stgen.config import GeometryConfig, SolverConfig
    from stgen.reference import NewtonRaphsonSolver
    from stgen.reference.kinematics import inverse_kinematics

    geometry = GeometryConfig()
    pose = np.array([1.0, 2.0, 20.0, 1.0, 2.0, 3.0])
    machine = NewtonRaphsonSolver(geometry, SolverConfig(tolerance=1e-9, iterations_per_scan=1))
    machine.start(inverse_kinematics(geometry, pose).positions, np.zeros(6))
    while not machine.step():
        pass
    iterations = machine.iterations
    assert machine.step() is True and machine.iterations == iterations


def test_one_upper_pose_against_several_base_poses():
    from stgen.reference.moving_base import legs

    upper = np.array([0.0, 0.0, 20.0, 1.0, 2.0, 3.0])
    bases = np.array([[5.0, -3, 2, 0, 0, 0], [0.0, 0, 0, 0, 0, 0], [1.0, 1, 1, 1, 1, 1]])
    state = legs(MOVING, upper, bases)
    assert state.lengths.shape == (3, 6)
    for k, base in enumerate(bases):
        assert state.lengths[k] == pytest.approx(legs(MOVING, upper, base).lengths, rel=1e-15)
    # li = |vector i|, direction = vector / li
    assert np.linalg.norm(state.vectors, axis=-1) == pytest.approx(state.lengths, rel=1e-12)
    assert state.directions * state.lengths[..., None] == pytest.approx(state.vectors, rel=1e-12)


def test_cranks_rest_when_platform_and_base_move_together():
    from stgen.reference.rates import crank_rates

    # Pure translation shared by base and platform (same velocity and acceleration): nothing moves
    # relative to the base, so the cranks stand still (docs/mathematics.md section 6.1).
    base = np.array([5.0, -3.0, 2.0, 0.0, 0.0, 0.0])
    velocity = np.array([10.0, -20.0, 30.0, 0.0, 0.0, 0.0])
    acceleration = np.array([100.0, 50.0, -200.0, 0.0, 0.0, 0.0])
    upper = base + [0.0, 0.0, 20.0, 0.0, 0.0, 0.0]
    moving = crank_rates(CRANK, upper, velocity, acceleration, base, velocity, acceleration)
    assert np.abs(moving.rates).max() < 1e-9 and np.abs(moving.accelerations).max() < 1e-6
    # No base given: the base at rest at the origin.
    alone = crank_rates(CRANK, [0.0, 0.0, 20.0, 0.0, 0.0, 0.0], velocity, acceleration)
    fixed = crank_rates(CRANK, [0.0, 0.0, 20.0, 0.0, 0.0, 0.0], velocity, acceleration, np.zeros(6))
    assert alone.rates == pytest.approx(fixed.rates) and alone.accelerations == pytest.approx(fixed.accelerations)


@pytest.mark.filterwarnings("ignore::RuntimeWarning")
def test_a_jacobian_too_large_for_its_determinant_is_non_finite():
    from stgen.config import GeometryConfig
    from stgen.error_codes import ErrorCode
    from stgen.reference import forward_kinematics
    from stgen.reference.kinematics import inverse_kinematics

    # From (1e60, 1e60, 1e60) mm the residual (~1e120) and the Jacobian (~1e60) are finite, but a
    # product of six Jacobian entries (~1e360) is not: the determinant step reports NON_FINITE.
    geometry = GeometryConfig()
    positions = inverse_kinematics(geometry, np.array([0.0, 0.0, 20.0, 0.0, 0.0, 0.0])).positions
    result = forward_kinematics(geometry, positions, [1e60, 1e60, 1e60, 0.0, 0.0, 0.0])
    assert result.status == ErrorCode.NON_FINITE and result.iterations == 0


# --- the two survivors left after seed 17's second round (docs/mutation.md, reference) ----------------------

def test_fade_in_set_by_the_jerk_term_of_the_second_derivative():
    from stgen.config import TrajectoryConfig
    from stgen.reference.wave import OceanWave, WaveComponent, fade_in_duration

    # A = 1 mm, w = 20 rad/s, L = 1e6 m (tilts negligible): D0..D3 = 1, 20, 400, 8000. With the velocity and
    # acceleration limits far away and a jerk limit of 9800 (spare 1800), the jerk rates are
    # cbrt(1800 / 3 / (4 pi^2)) = 2.48, sqrt(1800 / 3 / (6 pi 20)) = 1.26 and 1800 / 3 / (6 * 400) = 0.25:
    # the last one, the D2 term of the Leibniz rule, binds.
    period = 2 * np.pi / 20.0
    w = 2 * np.pi / period
    wave = OceanWave((WaveComponent(1.0, period, 1_000_000.0, 0.0),))
    limits = TrajectoryConfig(linear_velocity=1e4, linear_acceleration=1e6, linear_jerk=9800.0)
    rate = (9800.0 - w**3) / 3.0 / (6.0 * w**2)
    assert fade_in_duration(wave, limits) == pytest.approx(1.0 / rate, rel=1e-12)
    assert fade_in_duration(wave, limits) == pytest.approx(4.0, rel=1e-9)


@pytest.mark.filterwarnings("ignore::RuntimeWarning")
def test_a_newton_step_that_overflows_is_non_finite_after_one_iteration():
    from stgen.config import GeometryConfig, SolverConfig
    from stgen.error_codes import ErrorCode
    from stgen.reference import NewtonRaphsonSolver

    # Residual 1.7e308 and Jacobian 0.5 I (finite, det 1/64 > Ktol 0): the Newton step J^-1 r = 3.4e308
    # overflows to infinity, so the estimate after the update is not finite.
    class Model:
        def residual(self, pose):
            return np.full(6, 1.7e308)

        def jacobian(self, pose):
            return 0.5 * np.eye(6)

    machine = NewtonRaphsonSolver(GeometryConfig(), SolverConfig(singularity_threshold=0.0),
                                  model_factory=lambda positions: Model())
    machine.start(np.zeros(6), np.zeros(6))
    assert machine.step() is True
    assert machine.status == ErrorCode.NON_FINITE and machine.iterations == 1
