"""Reference details that the fresh seed-30 mutation sample found unchecked (issue 16, docs/mutation.md,
session 12).

Written after seed 30's "before" run. Expected values are worked out by hand, or by an independent NumPy
computation, from docs/mathematics.md, the docstrings' contracts and the ST templates the reference
twins; inputs are chosen exact in binary where a boundary is tested.
"""

from __future__ import annotations

import dataclasses
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import stgen
from stgen.config import GeometryConfig, SolverConfig, load_config
from stgen.error_codes import ErrorCode

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def test_a_crank_exactly_at_its_lower_angle_limit_is_in_limits():
    from stgen.reference.crank import crank_inverse_kinematics

    # SP_InverseKinematics (crank): LegInRange := Angle >= SP_CRANK_ANGLE_MIN AND Angle <= SP_CRANK_ANGLE_MAX,
    # limits included. The lower limit is put on the smallest home angle (leg 6 of examples/crank_platform.toml).
    config = load_config(EXAMPLES / "crank_platform.toml")
    home = crank_inverse_kinematics(config, np.zeros(6)).angles_deg
    lowest = float(home.min())
    at_limit = dataclasses.replace(config, crank=dataclasses.replace(config.crank, angle_min_deg=lowest))
    solution = crank_inverse_kinematics(at_limit, np.zeros(6))
    assert solution.angles_deg[5] == lowest          # the wrap about the new middle keeps it
    assert solution.in_limits.tolist() == [True] * 6


def test_a_cycloidal_move_shorter_than_a_second_is_not_a_step():
    from stgen.reference.cycloidal import cycloidal_pose

    # p(t) = p0 + h·σ(t/T), σ(τ) = τ − sin(2πτ)/2π: half-way through a 0.5 s move, σ(1/2) = 1/2.
    pose = cycloidal_pose(np.zeros(6), np.full(6, 4.0), 0.5, 0.25)
    np.testing.assert_allclose(pose, np.full(6, 2.0), rtol=0, atol=1e-12)


def test_the_cycloidal_velocity_is_that_of_the_displacement_not_of_the_end_point():
    from stgen.reference.cycloidal import cycloidal_velocity

    # dp/dt = (h/T)(1 − cos 2πτ), h = pf − p0: from 1 to 3 mm in 1 s the peak at τ = 1/2 is 2h/T = 4 mm/s.
    velocity = cycloidal_velocity(np.ones(6), np.full(6, 3.0), 1.0, 0.5)
    np.testing.assert_allclose(velocity, np.full(6, 4.0), rtol=1e-15)


def test_a_solver_started_again_after_an_error_shows_ok_until_its_first_step():
    from stgen.reference.forward import NewtonRaphsonSolver

    class Singular:                                 # J = 0: |det J| = 0 <= Ktol
        def residual(self, pose):
            return np.ones(6)

        def jacobian(self, pose):
            return np.zeros((6, 6))

    solver = NewtonRaphsonSolver(GeometryConfig(), model_factory=lambda positions: Singular())
    solver.start(np.zeros(6))
    assert solver.scan() and solver.status == ErrorCode.SINGULAR_JACOBIAN
    # A new start is a new Execute: no error, not done, no iteration until the next call.
    solver.start(np.zeros(6))
    assert solver.status == ErrorCode.OK and not solver.done and solver.iterations == 0


def test_a_determinant_equal_to_the_singularity_threshold_is_singular():
    from stgen.reference.forward import NewtonRaphsonSolver

    # forward.py step 2 (and SolverConfig): |det J| <= Ktol is singular. J = diag(2, 1, 1, 1, 1, 1) has
    # det 2 exactly (every other Leibniz product has a zero factor); Ktol = 2.
    class Diagonal:
        def residual(self, pose):
            return np.ones(6)

        def jacobian(self, pose):
            return np.diag([2.0, 1.0, 1.0, 1.0, 1.0, 1.0])

    settings = dataclasses.replace(SolverConfig(), singularity_threshold=2.0)
    solver = NewtonRaphsonSolver(GeometryConfig(), settings, lambda positions: Diagonal())
    solver.start(np.zeros(6))
    assert solver.step() and solver.status == ErrorCode.SINGULAR_JACOBIAN and solver.iterations == 0


def test_the_time_law_after_its_end_is_the_law_at_the_end():
    from stgen.reference.paths import PathSpec, time_law

    # u = t/T is clipped to [0, 1]: at u = 1.5 the cycloidal law is f(1) = 1 − sin(2π)/2π = 1 (to rounding),
    # f'(1) = 1 − cos 2π = 0.
    f, f1, _, _ = time_law(PathSpec("epitrochoid", law="cycloidal"), 1.5)
    assert float(f) == pytest.approx(1.0, abs=1e-15) and float(f1) == pytest.approx(0.0, abs=1e-15)


def test_path_parameter_errors_word_for_word():
    from stgen.reference.paths import PathError, PathSpec

    with pytest.raises(PathError) as raised:
        PathSpec("epitrochoid", d=math.nan)
    assert str(raised.value) == "every parameter must be a finite number"
    # r must be > 0 (a trochoid's rolling circle): r = 0 is refused.
    with pytest.raises(PathError) as raised:
        PathSpec("epitrochoid", r=0.0)
    assert str(raised.value) == "R and r: must be > 0, got R=60.0, r=0.0"


HEADER = "t,x,y,z,alpha,beta,gamma\n"


def test_playback_times_are_compared_with_times_only(tmp_path):
    from stgen.reference.playback import read_playback_csv

    # Times 0, 1, 2 increase strictly; x = 5 in the first row is larger than the next time (the check compares
    # a row's time with the time of the row before, not with its x).
    path = tmp_path / "moves.csv"
    path.write_text(HEADER + "0,5,0,0,0,0,0\n1,0,0,0,0,0,0\n2,0,0,0,0,0,0\n", encoding="utf-8")
    read_playback_csv(path)                          # no PlaybackError


def test_a_playback_csv_is_read_as_utf8_whatever_the_locale(tmp_path):
    # A cell "1.0" followed by a no-break space (U+00A0, two bytes in UTF-8) is a number to float(). Read in a
    # Python whose locale encoding is ASCII (C locale, no UTF-8 mode), the file must still be UTF-8.
    path = tmp_path / "moves.csv"
    path.write_text(HEADER + "0,0,0,0,0,0,0\n1.0\u00a0,1,0,0,0,0,0\n", encoding="utf-8")
    from stgen.reference.playback import read_playback_csv

    # Here first (a mutation tool runs a test only for the functions it saw the test call in its own process).
    assert read_playback_csv(path).t[-1] > 0.0
    env = {**os.environ, "LC_ALL": "C", "LANG": "C", "PYTHONUTF8": "0", "PYTHONCOERCECLOCALE": "0",
           "PYTHONPATH": os.pathsep.join([str(Path(stgen.__file__).resolve().parent.parent),
                                          os.environ.get("PYTHONPATH", "")])}
    code = ("import locale, sys; from stgen.reference.playback import read_playback_csv; "
            "print(locale.getpreferredencoding(False)); read_playback_csv(sys.argv[1]); print('read')")
    run = subprocess.run([sys.executable, "-c", code, str(path)], env=env, capture_output=True, text=True,
                         encoding="utf-8", errors="replace")
    encoding, *rest = run.stdout.split()
    assert encoding.lower() in ("ansi_x3.4-1968", "ascii", "us-ascii")    # the case being tested
    assert run.returncode == 0 and rest == ["read"], run.stderr


def test_the_wave_bounds_are_four_derivatives_of_six_coordinates():
    from stgen.reference.wave import OceanWave, WaveComponent, wave_derivative_bounds

    # One component, A = 1 mm, period 2π s (ω = 1), L = 100 m, heading 0 (docstring of wave_derivative_bounds):
    # x and z have A·ωⁿ = 1; y none; the tilt about y (column 4) has K = A·k·ωⁿ = k = 2π/1e5 per mm, through
    # atan's bounds (3√3/8, 2); α (column 3) and the tilt about x (column 5) stay 0.
    wave = OceanWave((WaveComponent(1.0, 2.0 * math.pi, 100.0, 0.0),))
    k = 2.0 * math.pi / 1e5
    c2, c3 = 3.0 * math.sqrt(3.0) / 8.0, 2.0
    tilt = np.degrees([math.atan(k), k, k + c2 * k**2, k + 3.0 * c2 * k * k + c3 * k**3])
    expected = np.zeros((4, 6))
    expected[:, 0] = expected[:, 2] = 1.0
    expected[:, 4] = tilt
    bounds = wave_derivative_bounds(wave)
    assert bounds.shape == (4, 6)
    np.testing.assert_allclose(bounds, expected, rtol=1e-12, atol=1e-15)


def test_spline_slopes_of_float32_knots_are_computed_in_float64():
    from stgen.reference.playback import clamped_spline_slopes

    # The knot spacing h of float32 times is taken in float64, as the ST's LREAL does: float32(0.3) −
    # float32(0.1) needs 25 bits, so a float32 subtraction would round it. Expected: the clamped C2 spline's
    # equations (m_0 = m_N = 0; h_k m_{k-1} + 2(h_{k-1} + h_k) m_k + h_{k-1} m_{k+1} = 3(h_k δ_{k-1} + h_{k-1} δ_k))
    # solved densely by NumPy on the float64 values of the same knots.
    knots = np.array([0.0, 0.1, 0.3, 0.7, 1.5], dtype=np.float32)
    y = np.array([[0.0], [1.0], [0.0], [2.0], [1.0]])
    t = knots.astype(np.float64)
    h = np.diff(t)
    delta = np.diff(y[:, 0]) / h
    system, rhs = np.zeros((3, 3)), np.zeros(3)
    for row, k in enumerate(range(1, 4)):
        system[row, row] = 2.0 * (h[k - 1] + h[k])
        if k > 1:
            system[row, row - 1] = h[k]
        if k < 3:
            system[row, row + 1] = h[k - 1]
        rhs[row] = 3.0 * (h[k] * delta[k - 1] + h[k - 1] * delta[k])
    expected = np.concatenate(([0.0], np.linalg.solve(system, rhs), [0.0]))
    np.testing.assert_allclose(clamped_spline_slopes(knots, y)[:, 0], expected, rtol=1e-13, atol=0)


# --- seed 31 (a fresh sample after the tests above) ------------------------------------------------------


def test_a_cycloidal_move_shorter_than_a_period_is_output_at_once():
    from stgen.reference.cycloidal import executed_duration

    # TRJ_Cycloidal: T < one task period runs as T = 0; T of a period or more runs as it is.
    assert executed_duration(0.0005, 0.001) == 0.0
    assert executed_duration(0.001, 0.001) == 0.001 and executed_duration(0.25, 0.001) == 0.25


def test_inverse_kinematics_reports_the_stroke_it_is_given():
    from stgen.config import StrokeConfig
    from stgen.reference.kinematics import inverse_kinematics

    # qi = |Li| − l0 >= −l0 > −99999 mm: no leg can be inside a stroke of −100000 .. −99999 mm (the default
    # stroke, 0 .. 600 mm, holds the home pose).
    geometry = GeometryConfig()
    assert geometry.l0 < 99999.0
    result = inverse_kinematics(geometry, np.zeros(6), StrokeConfig(min=-100000.0, max=-99999.0))
    assert not np.any(result.in_stroke)


def test_path_phi_end_below_one_radian_and_a_zero_duration():
    from stgen.reference.paths import PathError, PathSpec

    # phi_end: a finite number > 0 (half a radian is a valid end); duration: > 0 when given.
    assert PathSpec("epitrochoid", phi_end=0.5).phi_end == 0.5
    with pytest.raises(PathError) as raised:
        PathSpec("epitrochoid", duration=0.0)
    assert str(raised.value) == "duration: must be a finite number > 0 s, got 0.0"


@pytest.mark.parametrize("limit, value, binding", [("linear_acceleration", 5.0, "x/y acceleration"),
                                                   ("linear_jerk", 5.0, "x/y jerk")])
def test_a_path_plan_names_the_limit_that_sets_its_duration(limit, value, binding):
    from stgen.config import PlatformConfig
    from stgen.reference.paths import PathSpec, plan_path

    # The lowest x/y acceleration (or jerk) limit the configuration allows, 5 mm/s² (mm/s³), stretches the
    # default epitrochoid far beyond what the velocity limits need: that limit sets T, and the plan says so.
    config = PlatformConfig()
    config = dataclasses.replace(config, trajectory=dataclasses.replace(config.trajectory, **{limit: value}))
    assert plan_path(PathSpec("epitrochoid"), config, samples=16).binding == binding


def test_a_leg_exactly_at_its_stroke_maximum_is_no_breach():
    from stgen.config import PlatformConfig
    from stgen.reference.motion_limits import check_motion

    # MotionCheck.breaches: "stroke max" only for a position above the maximum. The maximum is put on the
    # longest leg at home; resting there, nothing is broken.
    config = PlatformConfig()
    rest = np.zeros((1, 6))
    longest = float(check_motion(config, [0.0], rest, rest, rest).positions.max())
    at_limit = dataclasses.replace(config, stroke=dataclasses.replace(config.stroke, max=longest))
    check = check_motion(at_limit, [0.0], rest, rest, rest)
    assert check.positions.max() == at_limit.stroke.max
    assert check.breaches(at_limit) == []


def test_a_path_plan_checks_its_samples_at_their_times():
    from stgen.config import PlatformConfig
    from stgen.reference.paths import PathSpec, plan_path

    # The plan's MotionCheck holds the samples' times (16 points from 0 to T), not a placeholder.
    plan = plan_path(PathSpec("epitrochoid"), PlatformConfig(), samples=16)
    assert plan.check.t.shape == (16,) and plan.check.t[0] == 0.0
    assert np.array_equal(plan.check.t, plan.samples.t)
