"""Reference details that mutation testing found unchecked: seed 27's last survivor and the fresh
seed-28 sample (issue 16, docs/mutation.md, session 11).

Written after seed 28's "before" run. Expected values are worked out by hand, or by an independent
NumPy computation, from docs/mathematics.md, the docstrings' contracts and the ST template that the
reference twins (TRJ_Path's time law).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from stgen.config import GeometryConfig, TrajectoryConfig, load_config
from stgen.error_codes import ErrorCode

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


# --- seed 27's last survivor --------------------------------------------------------------------


def test_the_blend_law_at_half_time_takes_the_start_branch_as_trj_path_does():
    from stgen.reference.paths import PathSpec, time_law

    # TRJ_Path (st_templates/trajectory/TRJ_Path.st.j2) mirrors only for u > 1/2 (`Mirror := u > HALF`), and
    # the reference is its twin: at u = 1/2 both evaluate the start formula F0 = Rate·(u − b/2), Rate = 1/(1 − b),
    # and leave F2 = +0.0 unsigned. In float64 with b = 0.05 that is 1/2 − 2⁻⁵⁴ (exactly 1/2 in real numbers,
    # the mirrored 1 − F0 rounds to 1/2): the test pins the branch, bit for bit.
    blend = 0.05
    rate = np.float64(1.0) / (np.float64(1.0) - np.float64(blend))
    expected = rate * (np.float64(0.5) - np.float64(blend) / 2.0)
    assert expected == 0.5 - 2.0**-54
    f, f1, f2, f3 = time_law(PathSpec("epitrochoid", blend=blend), 0.5)
    assert float(f) == expected and float(f1) == rate
    assert float(f2) == 0.0 and not np.signbit(f2) and float(f3) == 0.0


# --- seed 28 (a fresh sample, session 11) ---------------------------------------------------------


def test_feasibility_of_a_crank_platform_on_a_moving_base_reads_the_base_pose():
    from stgen.reference.feasibility import feasibility

    # examples/crank_platform.toml puts every crank at 140.66° at home (its comment). Base and upper pose lifted
    # by the same 25 mm leave every joint where it was relative to the base: the cranks stay at 140.66°.
    crank = load_config(EXAMPLES / "crank_platform.toml")
    lifted = np.array([0.0, 0.0, 25.0, 0.0, 0.0, 0.0])
    angles = feasibility(crank, lifted, base_pose_deg=lifted).values["crank_angle_deg"]
    assert angles == pytest.approx([140.66] * 6, abs=0.005)


def test_a_new_forward_kinematics_solver_shows_the_fb_at_rest():
    from stgen.reference.forward import NewtonRaphsonSolver

    # Before any start (the FB before its first Execute): done, status OK, no iteration, no scan, pose 0.
    solver = NewtonRaphsonSolver(GeometryConfig())
    assert solver.done and solver.status == ErrorCode.OK
    assert solver.iterations == 0 and solver.scans == 0
    assert solver.pose_deg.tolist() == [0.0] * 6
    assert solver.scan() is True and solver.scans == 0


def test_lu_solve_works_in_float64_whatever_the_dtype_of_its_factors():
    from stgen.reference.linalg import lu_solve

    # SP_LuSolve computes in LREAL (float64): a single-precision LU = [[3]] is read as 3.0, so x = 1/3 in
    # float64, not float32's 0.33333334.
    x = lu_solve(np.array([[3.0]], dtype=np.float32), [0], [1.0])
    assert x.dtype == np.float64 and x.tolist() == [1.0 / 3.0]


def test_a_path_with_no_blend_is_refused():
    from stgen.reference.paths import PathError, PathSpec

    # PathSpec: blend is a fraction of T per blend, 0 < b <= 0.5 (b = 0 would divide by zero in the law).
    with pytest.raises(PathError, match="blend"):
        PathSpec("epitrochoid", blend=0.0)
    assert PathSpec("epitrochoid", blend=0.5).blend == 0.5


def test_a_hypocycloid_whose_rolling_circle_equals_the_fixed_one_is_refused():
    from stgen.reference.paths import PathError, PathSpec

    # PathSpec: r must be less than R for a hypocycloid (r = R rolls on the spot: m = (R − r)/r = 0).
    with pytest.raises(PathError, match="less than R"):
        PathSpec("hypocycloid", R=60.0, r=60.0)
    assert PathSpec("hypocycloid", R=60.0, r=59.0).r == 59.0


def _one_component_wave(amplitude_mm: float, omega: float):
    from stgen.reference.wave import OceanWave, WaveComponent

    # Heading 0: x and z have D0..D3 = A·ωⁿ (wave_derivative_bounds), y none; L = 100 m keeps the tilts'
    # bounds small (slope A·2π/100 m), so their rates are far above the linear ones below.
    return OceanWave((WaveComponent(amplitude_mm, 2.0 * math.pi / omega, 100.0, 0.0),))


def test_a_wave_that_leaves_less_than_one_unit_of_a_limit_still_fades_in():
    from stgen.reference.wave import fade_in_duration

    # A = 5 mm, ω = 1 rad/s: D = (5, 5, 5, 5). Velocity limit 5.5 mm/s leaves 0.5 mm/s: r = 0.5/(2·5) = 0.05;
    # defaults 500 mm/s², 5000 mm/s³ give r = 2.8, 2.0, 12.4, 4.2, 55.5 (docstring's terms). T_F = 1/0.05 = 20 s.
    limits = TrajectoryConfig(linear_velocity=5.5)
    assert fade_in_duration(_one_component_wave(5.0, 1.0), limits) == pytest.approx(20.0, rel=1e-12)


def test_a_fade_in_set_by_the_jerk_term_of_the_first_derivative():
    from stgen.reference.wave import fade_in_duration

    # A = 1 mm, ω = 10 rad/s: D = (1, 10, 100, 1000). Limits 1000 mm/s, 1100 mm/s², 10000 mm/s³ leave 990,
    # 1000, 9000: r = 495, sqrt(1000/2/2π) = 8.92, cbrt(9000/3/4π²) = 4.24, 1000/2/40 = 12.5,
    # sqrt(9000/3/(6π·10)) = 3.99, 9000/3/600 = 5. The least (jerk, D1 term): T_F = sqrt(6π·10·3/9000) = sqrt(π/50) s.
    limits = TrajectoryConfig(linear_velocity=1000.0, linear_acceleration=1100.0, linear_jerk=10000.0)
    expected = math.sqrt(math.pi / 50.0)
    assert fade_in_duration(_one_component_wave(1.0, 10.0), limits) == pytest.approx(expected, rel=1e-12)


def test_a_fade_in_set_by_the_jerk_term_of_a_small_second_derivative():
    from stgen.reference.wave import fade_in_duration

    # A = 1 mm, ω = 1 rad/s: D = (1, 1, 1, 1), so D2 = 1 (a term for every D2 > 0). Jerk limit 5.5 mm/s³ leaves
    # 4.5: r = cbrt(4.5/3/4π²) = 0.336, sqrt(4.5/3/6π) = 0.282, 4.5/3/6 = 0.25; the defaults' velocity and
    # acceleration terms are 49.5, 6.3 and 62. The least (jerk, D2 term): T_F = 1/0.25 = 4 s.
    limits = TrajectoryConfig(linear_jerk=5.5)
    assert fade_in_duration(_one_component_wave(1.0, 1.0), limits) == pytest.approx(4.0, rel=1e-12)


# --- seed 29 (a fresh sample after the tests above, session 11) --------------------------------------


def test_the_time_law_before_the_start_is_the_law_at_the_start():
    from stgen.reference.paths import PathSpec, time_law

    # time_law: u = t/T is clipped to [0, 1]; at u = 0 the blend law has τ = 0, sin 0 = 0, cos 0 = 1, so
    # f = Ω·b·(0 + 0) = 0 and f' = f'' = f''' = 0: the path is at rest at its start before it.
    law = time_law(PathSpec("epitrochoid", blend=0.1), np.array([-0.5, 0.0]))
    assert [values.tolist() for values in law] == [[0.0, 0.0]] * 4


def test_a_wave_whose_velocity_alone_reaches_the_limit_has_no_fade_in():
    from stgen.reference.wave import fade_in_duration

    # A = 5 mm, ω = 1 rad/s: D1 = 5 mm/s on x, the velocity limit 5 mm/s: nothing is left for the fade
    # (docstring: ValueError when the wave alone reaches a limit), here in coordinate 1 (x).
    with pytest.raises(ValueError, match="pose coordinate 1"):
        fade_in_duration(_one_component_wave(5.0, 1.0), TrajectoryConfig(linear_velocity=5.0))


def test_a_motion_report_samples_every_period_to_the_period_nearest_its_duration():
    from stgen.reference.study_motions import motion_report

    # Samples at k·period for k·period < duration + period/2: the last one is the period nearest the
    # duration. 0.026 s at 10 ms is 2.6 periods, so 0, 10, 20, 30 ms: 4 samples (a platform at home).
    def home(t):
        value = np.zeros(t.shape + (6,))
        return value, value, value

    moving = load_config(EXAMPLES / "moving_base_platform.toml")
    assert motion_report(moving, "home", home, duration=0.026, period=0.01).samples == 4
    assert motion_report(moving, "home", home, duration=0.024, period=0.01).samples == 3
