"""Reference details that mutation testing found unchecked, seeds 24, 26 and 27 (issue 16, docs/mutation.md).

Written from the survivors of the fresh seed-24 sample of stgen/reference/ (session 9's run,
judged in session 10), and, at the end, of the fresh seed-26 and seed-27 samples (session 10, after their runs). Expected values are worked out by hand from docs/mathematics.md and
the docstrings (the crank's closed form, the study's motions, the time law's zero rate) or
are the documented contracts (messages, defaults, no warning for a zero-length leg).
"""

from __future__ import annotations

import math
import warnings
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from stgen.config import PlatformConfig, load_config

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
CRANK = load_config(EXAMPLES / "crank_platform.toml")


def _leg_one_offset(geometry) -> np.ndarray:
    """B1 − P1 (platform frame) − (0, 0, h0): leg 1's Δ = P1 − B1 is pU + that offset's negative, by hand
    from docs/mathematics.md section 1 [2-4] (θ1 = (2π − 3φb)/6, ϕ1 = (2π − 3φp)/6)."""
    theta = (2.0 * math.pi - 3.0 * math.radians(geometry.phi_b_deg)) / 6.0
    phi = (2.0 * math.pi - 3.0 * math.radians(geometry.phi_p_deg)) / 6.0
    base = np.array([geometry.rb * math.cos(theta), geometry.rb * math.sin(theta), geometry.hb])
    upper = np.array([geometry.rp * math.cos(phi), geometry.rp * math.sin(phi), geometry.hp + geometry.h0])
    return base - upper


def _leg_one_at(m: float, dz: float, w: float | None = None) -> np.ndarray:
    """The pose (a translation) that puts leg 1's joint at M = m, Δz = dz in its crank plane and off the
    plane (horizontally) by w, by default w² = s² − a² − m² − dz², so that H = |Δ|² + a² − s² = 0 (section 6.1)."""
    plane = math.radians(CRANK.crank.plane_angle_deg[0])
    a, s = CRANK.crank.crank_length, CRANK.crank.rod_length
    w = math.sqrt(s * s - a * a - m * m - dz * dz) if w is None else w
    delta = np.array([math.cos(plane) * m - math.sin(plane) * w, math.sin(plane) * m + math.cos(plane) * w, dz])
    return np.concatenate((delta + _leg_one_offset(CRANK.geometry), np.zeros(3)))


def test_a_crank_whose_joint_lies_half_a_millimetre_from_its_plane_axis_is_solvable():
    from stgen.reference.crank import crank_inverse_kinematics

    # Leg 1's joint placed off the crank plane by w (perpendicular, horizontal) and 0.5 mm above the shaft:
    # M = 0, Δz = 0.5, ρ = 0.5 mm; |Δ|² = w² + 0.25 = s² − a² makes H = 0, so cos = 0 and
    # θ = atan2(0.5, 0) + acos(0) = 90° + 90° = 180° (section 6.1), inside 50..230°. Any ρ > 0 is solvable.
    solution = crank_inverse_kinematics(CRANK, _leg_one_at(0.0, 0.5))
    assert bool(solution.solvable[0]) and bool(solution.in_limits[0])
    assert solution.cosine[0] == pytest.approx(0.0, abs=1e-9)
    assert solution.angles_deg[0] == pytest.approx(180.0, abs=1e-6)


def test_a_crank_whose_h_overflows_is_not_finite():
    from stgen.reference.crank import crank_inverse_kinematics

    # z = 1e200 mm: |Δ|² overflows to inf (H infinite) while ρ = hypot(M, Δz) stays finite. "finite" is
    # H and ρ both finite, so every leg is not finite.
    with np.errstate(over="ignore"):
        solution = crank_inverse_kinematics(CRANK, np.array([0.0, 0.0, 1e200, 0.0, 0.0, 0.0]))
    assert not solution.finite.any()
    assert not solution.solvable.any()


def test_a_zero_duration_move_has_zero_velocity_of_six_coordinates():
    from stgen.reference.cycloidal import cycloidal_velocity

    rates = cycloidal_velocity(np.zeros(6), np.ones(6), 0.0, np.array([0.0, 1.0]))
    assert rates.shape == (2, 6) and not rates.any()


def test_the_solver_refuses_other_than_six_positions():
    from stgen.reference.forward import NewtonRaphsonSolver

    with pytest.raises(ValueError):
        NewtonRaphsonSolver(PlatformConfig().geometry).start(np.zeros(7))


def test_a_leg_whose_length_underflows_to_zero_divides_without_a_warning():
    from stgen.reference.moving_base import legs_of

    # (1e-200)² underflows to 0, so the length is 0 and 1e-200 / 0 = inf: a division by zero, which legs_of
    # does silently (its errstate), as it does 0 / 0.
    upper = np.array([[1e-200, 0.0, 0.0]] * 6)
    joints = SimpleNamespace(upper=upper, base=np.zeros((6, 3)))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        state = legs_of(PlatformConfig(), joints)
    assert state.lengths.tolist() == [0.0] * 6
    assert state.directions[:, 0].tolist() == [math.inf] * 6


def test_the_spherical_tilt_of_a_leg_rounded_past_minus_one_is_a_half_turn():
    from stgen.reference.moving_base import spherical_tilt

    # Each leg along −(normal) with a length rounding left a hair over 1: the tilt is π, not acos(< −1) = NaN.
    directions = np.array([[0.0, 0.0, -(1.0 + 1e-12)]] * 6)
    state = SimpleNamespace(joints=SimpleNamespace(upper_rotation=np.eye(3)), directions=directions)
    assert spherical_tilt(state).tolist() == [math.pi] * 6


def test_a_rotation_order_of_three_letters_that_repeats_an_axis_is_refused():
    from stgen.reference.orientation import rotation

    with pytest.raises(ValueError, match="permutation of XYZ, got 'XXY'"):
        rotation("XXY", np.zeros(3))


def test_an_unknown_axis_is_named_in_the_error():
    from stgen.reference.orientation import axis_rotation

    with pytest.raises(ValueError, match="unknown rotation axis 'W'"):
        axis_rotation("W", 0.0)


def test_trochoid_circles_below_one_millimetre_are_valid():
    from stgen.reference.paths import PathSpec

    # R/r = 2 = 2/1: the curve closes after 2π·1.
    spec = PathSpec("epitrochoid", R=0.5, r=0.25, d=0.1)
    assert spec.end == pytest.approx(2.0 * math.pi, rel=1e-15)


def test_a_negative_duration_is_named_in_the_error():
    from stgen.reference.paths import PathError, PathSpec

    with pytest.raises(PathError, match=r"duration: must be a finite number > 0 s, got -1\.0"):
        PathSpec("epitrochoid", duration=-1.0)


def test_a_table_made_without_a_source_is_named_table():
    from stgen.reference.playback import make_table

    table = make_table([0.0, 2.0], [[0.0] * 6, [6.0, 0.0, 0.0, 0.0, 0.0, 0.0]])
    assert table.source == "<table>"


def test_a_feasible_study_motion_reports_no_first_violation():
    from stgen.reference.study_motions import motion_report, moving_base_base, moving_base_upper

    moving = load_config(EXAMPLES / "moving_base_platform.toml")
    report = motion_report(moving, "first 10 ms", moving_base_upper, lambda t: moving_base_base(t, True),
                           duration=0.01)
    assert report.feasible and report.first_violation is None


@pytest.mark.parametrize("reversed_angles, angles", [(True, [0.2, 0.3, 0.3]), (False, [0.3, 0.3, 0.2])])
def test_the_moving_base_angles_at_one_second(reversed_angles, angles):
    from stgen.reference.study_motions import moving_base_base

    # docs/mathematics.md section 6.2: θB = (0.3 t, 0.3 t, 0.2 t) about (x, y, z), given to Rz·Ry·Rx as
    # (about z, about y, about x) when reversed; pB = (0.4 t, −0.2 t, −3 cos πt): at t = 1, (0.4, −0.2, 3).
    value, rate, _ = moving_base_base(np.array([1.0]), reversed_angles)
    assert value[0].tolist() == pytest.approx([0.4, -0.2, 3.0, *angles], rel=1e-15)
    assert rate[0, 3:].tolist() == angles


# --- seed 26 (a fresh sample, session 10) ---------------------------------------------------------------


def test_a_crank_angle_below_its_minimum_is_out_of_limits():
    from stgen.reference.crank import crank_inverse_kinematics

    # Leg 1 at ρ = 600 mm, 60° below the horizontal in its plane, H = 0: θ = −60° + acos 0 = 30° < 50°.
    rho = 600.0
    solution = crank_inverse_kinematics(CRANK, _leg_one_at(rho * math.cos(math.radians(-60.0)),
                                                           rho * math.sin(math.radians(-60.0))))
    assert bool(solution.solvable[0]) and solution.angles_deg[0] == pytest.approx(30.0, abs=1e-9)
    assert not bool(solution.in_limits[0]) and not bool(solution.reachable)


def test_a_newton_step_of_a_model_with_invalid_operations_reports_without_a_warning():
    from stgen.config import GeometryConfig, SolverConfig
    from stgen.error_codes import ErrorCode
    from stgen.reference import NewtonRaphsonSolver

    # inf − inf is an invalid operation (NaN): the solver reports it as NON_FINITE and does not warn.
    class Model:
        def residual(self, pose):
            return np.full(6, np.inf) - np.inf

        def jacobian(self, pose):
            return np.eye(6)

    machine = NewtonRaphsonSolver(GeometryConfig(), SolverConfig(singularity_threshold=0.0),
                                  model_factory=lambda positions: Model())
    machine.start(np.zeros(6), np.zeros(6))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert machine.step() is True
    assert machine.status == ErrorCode.NON_FINITE and machine.iterations == 0


def test_check_motion_keeps_the_sample_rates():
    from stgen.reference.motion_limits import check_motion

    poses = np.array([[0.0, 0.0, 20.0, 0.0, 0.0, 0.0]] * 2)
    rates = np.array([[1.0, 0.0, 0.0, 0.0, 0.0, 0.0], [0.0, 2.0, 0.0, 0.0, 0.0, 0.0]])
    check = check_motion(PlatformConfig(), [0.0, 0.25], poses, rates, np.zeros((2, 6)))
    assert check.rates.tolist() == rates.tolist()


def test_a_leg_at_exactly_the_stroke_minimum_breaks_no_limit():
    from stgen.reference.motion_limits import MotionCheck

    # stroke.min <= qi is inside (docs/mathematics.md section 2): leg 1 at 0 mm, the default stroke.min.
    config = PlatformConfig()
    positions = np.array([[config.stroke.min, 100.0, 100.0, 100.0, 100.0, 100.0]])
    still = SimpleNamespace(velocities=np.zeros((1, 6)), accelerations=np.zeros((1, 6)))
    check = MotionCheck(np.zeros(1), np.zeros((1, 6)), np.zeros((1, 6)), np.zeros((1, 6)), still, positions)
    assert check.breaches(config) == []


def test_a_wave_without_fade_is_the_study_wave_before_time_zero():
    from stgen.reference.wave import AIRY, wave_pose

    # A = 3 mm, Tw = 10 s, L = 100 m, φ = 10°, heading 0, x̃ = 0: at t = −2.5 s the phase is
    # −ω t + φ = π/2 + 10°, so x = −A sin(phase) = −3 cos 10°, z = A cos(phase) = −3 sin 10° and
    # β = −atan(∂η/∂x̃) with ∂η/∂x̃ = −A k sin(phase) = −3 (2π/1e5) cos 10°. fade_s = 0 is no fade.
    c, s = math.cos(math.radians(10.0)), math.sin(math.radians(10.0))
    expected = [-3.0 * c, 0.0, -3.0 * s, 0.0, math.degrees(math.atan(3.0 * 2.0 * math.pi / 1e5 * c)), 0.0]
    assert wave_pose(AIRY, np.array(-2.5), fade_s=0.0).tolist() == pytest.approx(expected, rel=1e-12, abs=1e-12)


def test_the_shortest_duration_samples_the_time_law_over_its_unit_interval():
    from stgen.reference.paths import PathSpec, _scale_duration

    # A circle of a = 10 mm (a spiral with b = 0) once round, cycloidal law, 3 plan samples: u = 0, 1/2, 1.
    # At u = 1/2 (T = 1) dφ/dt = 2π·(1 − cos π) = 4π and d²φ/dt² = 0, so |acceleration| = a·(4π)² = 160π²
    # mm/s²; the shortest T is at least that limit's sqrt(160π² / 500) (docs: largest of the candidates).
    spec = PathSpec("spiral", a=10.0, b=0.0, phi_end=2.0 * math.pi, law="cycloidal")
    shortest, _ = _scale_duration(spec, PlatformConfig(), 3)
    assert shortest >= math.sqrt(160.0 * math.pi**2 / 500.0) * (1.0 - 1e-12)


# --- seed 27 (a fresh sample, session 10) ---------------------------------------------------------------


def test_a_crank_joint_on_the_shafts_perpendicular_divides_by_zero_without_a_warning():
    from stgen.reference.crank import crank_inverse_kinematics

    # Leg 1's joint 500 mm off its plane at shaft height: M = Δz = 0, so ρ = 0 and H = 500² + a² − s² < 0;
    # H/(2aρ) = −inf, a division by zero done silently: no solution (ρ > 0 fails).
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        solution = crank_inverse_kinematics(CRANK, _leg_one_at(0.0, 0.0, 500.0))
    assert solution.cosine[0] == -math.inf and not bool(solution.solvable[0])
