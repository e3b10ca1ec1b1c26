"""Reference details that mutation testing found unchecked, seeds 25 and 27 (issue 16, docs/mutation.md).

Written from the survivors of the fresh seed-25 sample of stgen/reference/ (session 10), after its
"before" run, and at the end from those of the fresh seed-27 sample. Expected values are worked out by hand or by an independent NumPy computation from
docs/mathematics.md and the docstrings' contracts (the Jacobian's rows, the crank's wrap range, the
ErrorID table, the fade-in's rate terms, the table at rest at both ends).
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from stgen.config import GeometryConfig, PlatformConfig, SolverConfig, TrajectoryConfig, load_config
from stgen.error_codes import ErrorCode

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
CRANK = load_config(EXAMPLES / "crank_platform.toml")


def _study_joints(geometry: GeometryConfig) -> tuple[np.ndarray, np.ndarray]:
    """(Bi, Pi) of docs/mathematics.md section 1 [2-4], by hand: θi = (2iπ − 3φb)/6 for odd i, θ(i−1) + φb
    for even i (the platform's ϕi likewise with φp)."""
    def polar(pair_deg: float) -> np.ndarray:
        odd = np.array([(2.0 * i * math.pi - 3.0 * math.radians(pair_deg)) / 6.0 for i in (1, 3, 5)])
        return np.stack((odd, odd + math.radians(pair_deg)), axis=-1).reshape(6)

    theta, phi = polar(geometry.phi_b_deg), polar(geometry.phi_p_deg)
    base = np.column_stack((geometry.rb * np.cos(theta), geometry.rb * np.sin(theta), np.full(6, geometry.hb)))
    upper = np.column_stack((geometry.rp * np.cos(phi), geometry.rp * np.sin(phi), np.full(6, geometry.hp)))
    return base, upper


def test_the_rate_jacobian_of_one_pose_has_the_rows_of_section_6_3():
    from stgen.reference.actuator_rates import rate_jacobian

    # At home (R = I): ri = Pi, Li = Pi + (0, 0, h0) − Bi, ei = Li/|Li|, row i = [eiᵀ, (ri × ei)ᵀ].
    geometry = GeometryConfig()
    base, upper = _study_joints(geometry)
    legs = upper + np.array([0.0, 0.0, geometry.h0]) - base
    e = legs / np.linalg.norm(legs, axis=-1)[:, None]
    expected = np.concatenate((e, np.cross(upper, e)), axis=-1)
    assert rate_jacobian(geometry, np.zeros(6)) == pytest.approx(expected, rel=1e-12, abs=1e-12)


def test_a_pose_out_of_the_cranks_reach_is_in_no_leg_limit():
    from stgen.reference.crank import crank_inverse_kinematics

    # z = 1500 mm: Δz = 1500 + h0 + hp − hb = 2470 mm > a + s = 1190 mm on every leg, no solution.
    solution = crank_inverse_kinematics(CRANK, np.array([0.0, 0.0, 1500.0, 0.0, 0.0, 0.0]))
    assert solution.finite.all() and not solution.solvable.any()
    assert not solution.in_limits.any() and not bool(solution.reachable)


@pytest.mark.parametrize("angle, wrapped", [(319.5, 319.5), (-40.5, 319.5), (-40.0, -40.0), (320.0, -40.0)])
def test_crank_angles_wrap_into_the_half_open_turn_around_the_middle_of_the_limits(angle, wrapped):
    from stgen.reference.crank import wrap_crank_angle

    # Limits 50..230°: the middle is 140°, so angles land in [−40°, 320°).
    assert wrap_crank_angle(CRANK, angle) == wrapped


def _broken_on(*legs: int):
    from stgen.reference.feasibility import FeasibilityMap, Limit

    excess = np.full((6, len(Limit)), -np.inf)
    for leg in legs:
        excess[leg - 1, Limit.STROKE_MAX] = 1.0
    return FeasibilityMap(excess, {})


@pytest.mark.parametrize("legs", [(1,), (1, 3), (3, 1, 6)])
def test_leg_one_outside_its_stroke_is_reported_as_leg_one(legs):
    from stgen.reference.feasibility import error_ids

    # ErrorID 16#1040 + leg, the lowest leg named (stgen.error_codes.LegLimitError).
    ids, leg = error_ids(_broken_on(*legs))
    assert (int(ids), int(leg)) == (0x1041, 1)


def test_a_leg_length_that_overflows_is_non_finite_with_joint_limits():
    from stgen.reference.feasibility import Limit, error_ids, feasibility

    # z = 1e200 mm: |ri|² overflows, li = inf, so Di is not finite, while ei = ri/inf = 0 gives γ = asin 0
    # and ψ = atan2(0, 0), both finite. The pose is non-finite (16#1003) all the same.
    moving = load_config(EXAMPLES / "moving_base_platform.toml")
    with np.errstate(over="ignore"):
        result = feasibility(moving, np.array([0.0, 0.0, 1e200, 0.0, 0.0, 0.0]))
    assert result.excess[:, Limit.NON_FINITE].tolist() == [math.inf] * 6
    assert int(error_ids(result)[0]) == ErrorCode.NON_FINITE.error_id


def test_a_newton_step_exactly_at_the_tolerance_has_not_converged():
    from stgen.reference import NewtonRaphsonSolver

    # Residual 0.5 and Jacobian I: the step Δ = 0.5 exactly, equal to the tolerance Klim = 0.5; converged
    # needs every |Δk| < Klim (SolverConfig), so the solve goes on until max_iterations = 2.
    class Model:
        def residual(self, pose):
            return np.full(6, 0.5)

        def jacobian(self, pose):
            return np.eye(6)

    settings = SolverConfig(tolerance=0.5, singularity_threshold=0.0, max_iterations=2)
    machine = NewtonRaphsonSolver(GeometryConfig(), settings, model_factory=lambda positions: Model())
    machine.start(np.zeros(6), np.zeros(6))
    assert machine.step() is False
    assert machine.step() is True
    assert machine.status == ErrorCode.NOT_CONVERGED and machine.iterations == 2


def test_a_non_finite_pose_does_not_spoil_the_others_of_a_batch():
    from stgen.reference.kinematics import inverse_kinematics

    # The home pose is inside the stroke (PlatformConfig's home check); the NaN pose is NON_FINITE alone.
    result = inverse_kinematics(GeometryConfig(), np.array([[0.0] * 6, [math.nan] * 6]))
    assert result.status.tolist() == [int(ErrorCode.OK), int(ErrorCode.NON_FINITE)]


def test_universal_joint_gamma_of_a_direction_rounded_past_minus_one_is_minus_a_right_angle():
    from stgen.reference.geometry import joint_angles
    from stgen.reference.moving_base import universal_joint_angles

    # Each leg pointing straight in, against its base joint's polar direction: γ = asin(−(c² + s²)) = −90°,
    # also for a unit vector that rounding left a hair longer than 1 (not asin(< −1) = NaN).
    config = PlatformConfig()
    polar, _ = joint_angles(config.geometry)
    directions = -np.stack((np.cos(polar), np.sin(polar), np.zeros(6)), axis=-1) * (1.0 + 1e-12)
    state = SimpleNamespace(joints=SimpleNamespace(base_rotation=np.eye(3)), directions=directions)
    gamma, _ = universal_joint_angles(config, state)
    assert gamma.tolist() == [-math.pi / 2] * 6


def test_a_table_is_at_rest_outside_its_times():
    from stgen.reference.playback import evaluate, make_table

    table = make_table([0.0, 2.0], [[0.0] * 6, [6.0, 0.0, 0.0, 0.0, 0.0, 0.0]])
    poses, rates, accelerations = evaluate(table, np.array([-1.0, 3.0]))
    assert poses[:, 0].tolist() == pytest.approx([0.0, 6.0], abs=1e-12)
    assert not rates.any() and not accelerations.any()


def test_a_table_with_uneven_rows_starts_and_ends_at_rest():
    from stgen.reference.playback import evaluate, make_table

    # Rows 1 s then 2 s apart: the inserted knots (0.5 s, 2 s) are not symmetric, so the two end conditions
    # (start and end acceleration 0) are not interchangeable; both must hold (make_table's docstring).
    table = make_table([0.0, 1.0, 3.0], [[0.0] * 6, [6.0, -3.0, 1.0, 0.0, 0.0, 2.0], [1.0, 2.0, 0.0, 0.0, 4.0, 0.0]])
    _, rates, accelerations = evaluate(table, np.array([0.0, 3.0]))
    assert np.abs(rates).max() < 1e-12
    assert np.abs(accelerations).max() < 1e-9


def test_variant_fk_without_a_solver_uses_the_configs_solver():
    from stgen.reference.variant_fk import variant_forward_kinematics

    # max_iterations = 1 in the platform's [solver]: one Newton step from p_NR cannot land within Klim of a
    # pose 100 mm up, so the result is "not converged" after that one iteration.
    base = PlatformConfig()
    config = dataclasses.replace(base, solver=dataclasses.replace(base.solver, max_iterations=1))
    result = variant_forward_kinematics(config, np.full(6, 100.0))
    assert result.status == ErrorCode.NOT_CONVERGED and result.iterations == 1


def test_fade_in_set_by_the_acceleration_term_of_the_first_derivative():
    from stgen.reference.wave import OceanWave, WaveComponent, fade_in_duration

    # A = 1 mm, w = 10 rad/s (Tw = 2π/10 s), L = 100 m, heading 0: x and z have D0..D3 = 1, 10, 100, 1000.
    # Limits 1000 mm/s, 200 mm/s², 1e6 mm/s³: the rates r of fade_in_duration's docstring are
    # 990/2 = 495, sqrt(100/2/2π) = 2.82, cbrt(999000/3/4π²) = 20.4, 100/2/(4·10) = 1.25,
    # sqrt(999000/3/(6π·10)) = 42, 999000/3/(6·100) = 555; the tilt's are far larger (D1 = 0.036 °/s).
    # The least, r = 1.25 (acceleration, D1 term), gives T_F = 0.8 s.
    wave = OceanWave((WaveComponent(1.0, 2.0 * math.pi / 10.0, 100.0, 0.0),))
    limits = TrajectoryConfig(linear_velocity=1000.0, linear_acceleration=200.0, linear_jerk=1e6)
    assert fade_in_duration(wave, limits) == pytest.approx(0.8, rel=1e-12)


# --- seed 27 (a fresh sample, session 10) ---------------------------------------------------------------


def test_a_zero_duration_move_is_a_step_to_the_end_pose():
    from stgen.reference.cycloidal import cycloidal_pose

    # T <= 0: τ is 0 before t0 and 1 from t0 on (_progress), so the pose jumps from p0 to pf.
    poses = cycloidal_pose(np.zeros(6), np.full(6, 4.0), 0.0, np.array([-1.0, 0.0, 1.0]))
    assert poses.tolist() == [[0.0] * 6, [4.0] * 6, [4.0] * 6]


def test_the_universal_joint_psi_excess_at_home():
    from stgen.reference.feasibility import Limit, feasibility

    # ψi = atan2(s·ex − c·ey, ez) (stgen.reference.moving_base), e the home leg direction by hand; excess
    # |ψi| − universal_max_deg (negative at home, which is feasible).
    moving = load_config(EXAMPLES / "moving_base_platform.toml")
    geometry = moving.geometry
    base, upper = _study_joints(geometry)
    legs = upper + np.array([0.0, 0.0, geometry.h0]) - base
    e = legs / np.linalg.norm(legs, axis=-1)[:, None]
    polar = np.arctan2(base[:, 1], base[:, 0])
    psi = np.degrees(np.arctan2(np.sin(polar) * e[:, 0] - np.cos(polar) * e[:, 1], e[:, 2]))
    result = feasibility(moving, np.zeros(6))
    assert result.excess[:, Limit.UNIVERSAL_PSI] == pytest.approx(np.abs(psi) - 24.25, rel=1e-9, abs=1e-9)


def test_the_progress_of_a_zero_duration_move_is_zero_then_one():
    from stgen.reference.cycloidal import _progress

    # Its docstring: τ clipped to [0, 1], a step at t0 when T <= 0 (cycloidal_fraction clips again after it).
    assert _progress(0.0, np.array([-1.0, 0.0, 1.0]), 0.0).tolist() == [0.0, 1.0, 1.0]


def test_feasibility_names_the_crank_angles():
    from stgen.reference.feasibility import feasibility

    # examples/crank_platform.toml: h0 = 1180 mm puts every crank at 140.66° at home (its comment).
    angles = feasibility(CRANK, np.zeros(6)).values["crank_angle_deg"]
    assert angles == pytest.approx([140.66] * 6, abs=0.005)


def test_lu_of_an_integer_matrix_keeps_its_fractions():
    from stgen.reference.linalg import solve

    # 2x + y = 3, x + 3y = 5: x = 4/5, y = 7/5. The pivot 2 gives l21 = 1/2, which an integer array would lose.
    assert solve(np.array([[2, 1], [1, 3]]), [3.0, 5.0]).tolist() == pytest.approx([0.8, 1.4], rel=1e-15)


def test_check_motion_keeps_the_sample_accelerations():
    from stgen.reference.motion_limits import check_motion

    poses = np.array([[0.0, 0.0, 20.0, 0.0, 0.0, 0.0]] * 2)
    accelerations = np.array([[0.0, 0.0, 3.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0, 0.0, 0.0]])
    check = check_motion(PlatformConfig(), [0.0, 0.25], poses, np.zeros((2, 6)), accelerations)
    assert check.accelerations.tolist() == accelerations.tolist()


def test_a_two_row_table_that_starts_later_gets_knots_at_its_thirds():
    from stgen.reference.playback import make_table

    # Rows at 1 s and 4 s: the inserted knots at 1 + 3/3 = 2 s and 1 + 2·3/3 = 3 s.
    table = make_table([1.0, 4.0], [[0.0] * 6, [6.0, 0.0, 0.0, 0.0, 0.0, 0.0]])
    assert table.t.tolist() == [1.0, 2.0, 3.0, 4.0]


def test_the_moving_base_reads_its_angles_reversed_by_default():
    from stgen.reference.study_motions import moving_base_base

    # reversed_angles defaults to True: θB given to Rz·Ry·Rx as (about z, about y, about x) = (0.2, 0.3, 0.3) t.
    value, _, _ = moving_base_base(np.array([1.0]))
    assert value[0, 3:].tolist() == pytest.approx([0.2, 0.3, 0.3], rel=1e-15)
