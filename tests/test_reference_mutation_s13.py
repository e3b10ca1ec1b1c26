"""Reference details that session 13's mutation work found unchecked (issue 16, docs/mutation.md,
reference, "Session 13: a fresh seed 32").

Expected values are worked out by hand, or by an independent NumPy computation, from docs/mathematics.md
and the docstrings' contracts; never by running the code under test.
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from pathlib import Path

import numpy as np
import pytest

from stgen.config import GeometryConfig, PlatformConfig, SolverConfig, TrajectoryConfig, load_config
from stgen.error_codes import ErrorCode
from stgen.reference.playback import PlaybackError, evaluate, make_table, read_playback_csv

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


@pytest.mark.parametrize("duration", [1e-120, 1e-3, 1.0, 3.0, 1e9, 1e120])
def test_a_two_row_table_inserts_a_sixth_and_five_sixths_whatever_the_time_unit(duration):
    """make_table's two-row case by hand.  Knots 0, T/3, 2T/3, T with values 0, a, b, P; the clamped
    spline's slopes m1, m2 (m0 = m3 = 0) on the even spacing h = T/3 solve
        4·m1 + m2 = 3(δ0 + δ1),  m1 + 4·m2 = 3(δ1 + δ2),  δk = (y_{k+1} − y_k)/h,
    and rest in acceleration at both ends (the module's s''(t0) = (6(y1 − y0) − 2h·m1)/h² = 0, and its
    mirror at the end) gives m1 = 3a/h, m2 = 3(P − b)/h.  Substituted: 4a + P = 2b and 2a + 3P = 4b,
    so a = P/6 and b = 5P/6, for every T: the time unit only scales the slopes.  The durations span
    the range where the segments' squares are normal floats (a table in seconds, milliseconds, or
    far beyond), where the end condition must not be scaled by one power of h more than the start's."""
    P = np.array([6.0, -3.0, 1.5, 0.0, 12.0, 2.0])
    table = make_table([0.0, duration], [np.zeros(6), P])
    assert table.t.tolist() == pytest.approx([0.0, duration / 3, 2 * duration / 3, duration], rel=1e-15)
    assert table.poses[0].tolist() == [0.0] * 6 and table.poses[3].tolist() == P.tolist()
    assert table.poses[1] == pytest.approx(P / 6, rel=1e-13, abs=1e-13)
    assert table.poses[2] == pytest.approx(5 * P / 6, rel=1e-13, abs=1e-13)
    # the slopes by hand: m1 = 3a/h = 1.5·P/T, m2 = 3(P − b)/h = 1.5·P/T (the S-curve is symmetric)
    assert table.slopes[1] == pytest.approx(1.5 * P / duration, rel=1e-12, abs=1e-300)
    assert table.slopes[2] == pytest.approx(1.5 * P / duration, rel=1e-12, abs=1e-300)
    assert table.slopes[0].tolist() == [0.0] * 6 and table.slopes[3].tolist() == [0.0] * 6


def test_a_two_row_table_rests_in_acceleration_at_its_end_by_finite_differences():
    """The same table in seconds (T = 3 s, P as above): the acceleration a step inside each end, by
    central differences of the played position (NumPy, h = 1e-4 s), tends to zero as the end is
    approached.  By hand: on the first segment (h = 1 s, y0 = m0 = 0, y1 = P/6, m1 = 1.5·P/T = P/2)
    y'' = (−12s + 6)·P/6 + (6s − 2)·P/2 = s·P, zero at the start and P/2 at T/6; the middle segment's
    y'' at its centre is m1 − m0 = 0; the table is odd about T/2 (y(T − t) = P − y(t)), so the end
    mirrors the start.  A cubic's second central difference is its y'' exactly (up to rounding)."""
    P = np.array([6.0, -3.0, 1.5, 0.0, 12.0, 2.0])
    table = make_table([0.0, 3.0], [np.zeros(6), P])

    def second_difference(t, step=1e-4):
        pose = evaluate(table, np.array([t - step, t, t + step]))[0]
        return (pose[0] - 2 * pose[1] + pose[2]) / step**2

    assert second_difference(0.5) == pytest.approx(0.5 * P, abs=1e-5)
    assert second_difference(2.5) == pytest.approx(-0.5 * P, abs=1e-5)
    assert second_difference(1.5) == pytest.approx(np.zeros(6), abs=1e-5)
    assert second_difference(1e-3) == pytest.approx(1e-3 * P, abs=1e-5)
    assert second_difference(3.0 - 1e-3) == pytest.approx(-1e-3 * P, abs=1e-5)


# ------------------------------------------------------------------ seed 32's survivors

def test_a_crank_solution_holds_the_platform_joints_in_the_base_frame():
    from stgen.reference.crank import crank_inverse_kinematics

    # CrankSolution's last field: Pi in the base frame, RBᵀ·(Pi − pB).  examples/crank_platform.toml:
    # rp = 388.95 mm, φp = 103.66°, hp = −115 mm, h0 = 1180 mm; by [4] ϕi = (i·360° − 3φp)/6 for i = 1, 3, 5
    # (ϕ1 = 8.17°) and ϕ(i+1) = ϕi + φp.  The upper
    # platform moved by (10, −5, 3) mm and the base raised by 20 mm, neither turned:
    # Pi = (rp cos ϕi + 10, rp sin ϕi − 5, hp + h0 + 3 − 20).
    config = load_config(EXAMPLES / "crank_platform.toml")
    solution = crank_inverse_kinematics(config, [10.0, -5.0, 3.0, 0.0, 0.0, 0.0], [0.0, 0.0, 20.0, 0.0, 0.0, 0.0])
    odd = [(360.0 * i - 3 * 103.66) / 6 for i in (1, 3, 5)]
    phi = np.radians([odd[0], odd[0] + 103.66, odd[1], odd[1] + 103.66, odd[2], odd[2] + 103.66])
    expected = np.column_stack((388.95 * np.cos(phi) + 10.0, 388.95 * np.sin(phi) - 5.0,
                                np.full(6, -115.0 + 1180.0 + 3.0 - 20.0)))
    assert solution.platform_joints_base.shape == (6, 3)
    assert solution.platform_joints_base == pytest.approx(expected, abs=1e-9)


def test_one_moves_duration_is_a_python_float():
    from stgen.reference.cycloidal import cycloidal_duration

    # docs/mathematics.md section 4 with the default limits (100 mm/s, 500 mm/s², 5000 mm/s³): 100 mm in x
    # takes max(2·100/100, √(2π·100/500), ∛(4π²·100/5000)) = max(2, 1.12, 0.92) = 2 s.  One move gives a
    # float (the annotation's), which a message quotes as 2.0, not as np.float64(2.0).
    duration = cycloidal_duration([100.0, 0.0, 0.0, 0.0, 0.0, 0.0], TrajectoryConfig())
    assert type(duration) is float and repr(duration) == "2.0"


def test_a_cycloidal_velocity_takes_float32_times_at_their_value():
    from stgen.reference.cycloidal import cycloidal_velocity

    # dp/dt = (h/T)(1 − cos 2πτ), τ = (t − t0)/T in double precision (the ST's LREAL) for a float32 t:
    # the time's exact value, not float32 arithmetic on it.  NumPy in float64 by the docstring's formula.
    t = np.array([0.3, 1.7, 2.9], dtype=np.float32)
    h = np.array([6.0, -3.0, 1.5, 0.0, 12.0, 2.0])
    tau = (t.astype(np.float64) - 0.1) / 3.0
    expected = h * ((1.0 - np.cos(2.0 * np.pi * tau)) / 3.0)[:, None]
    assert cycloidal_velocity(np.zeros(6), h, 3.0, t, 0.1) == pytest.approx(expected, rel=1e-13, abs=1e-13)


def test_a_newton_step_that_overflows_reports_without_a_warning():
    from stgen.reference import NewtonRaphsonSolver
    from stgen.reference.kinematics import inverse_kinematics

    # forward.py: "non-finite values are reported, not warned".  From x = 1e200 mm the squared leg lengths of
    # the residual overflow (1e400): the step ends NON_FINITE before any iteration, and no RuntimeWarning is
    # given (warnings are errors here).
    geometry = GeometryConfig()
    positions = inverse_kinematics(geometry, np.array([0.0, 0.0, 20.0, 0.0, 0.0, 0.0])).positions
    machine = NewtonRaphsonSolver(geometry, SolverConfig())
    machine.start(positions, np.array([1e200, 0.0, 0.0, 0.0, 0.0, 0.0]))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert machine.step() is True
    assert machine.status == ErrorCode.NON_FINITE and machine.iterations == 0


def _check_with_leg_velocity(velocity: float):
    from stgen.reference.actuator_rates import ActuatorRates
    from stgen.reference.motion_limits import MotionCheck

    rest = np.zeros((1, 6))
    legs = ActuatorRates(np.zeros((1, 6)), np.full((1, 6), velocity), np.zeros((1, 6)))
    return MotionCheck(np.zeros(1), rest, rest, rest, legs, np.full((1, 6), 300.0))


def test_a_leg_exactly_at_its_velocity_limit_breaks_nothing():
    # MotionCheck.breaches: "velocity" only above the limit (the default 250 mm/s); the stroke (0 .. 600 mm)
    # holds 300 mm and nothing accelerates.
    config = PlatformConfig()
    assert config.actuator.max_velocity == 250.0
    assert _check_with_leg_velocity(250.0).breaches(config) == []
    assert _check_with_leg_velocity(-250.0).breaches(config) == []
    above = math.nextafter(250.0, math.inf)
    assert _check_with_leg_velocity(above).breaches(config) == [(leg, "velocity", above, 250.0) for leg in range(1, 7)]


def test_poses_given_in_float32_are_turned_at_their_value():
    from stgen.reference.moving_base import world_joints

    # RU = Rz(α)·Ry(β)·Rx(γ) ("ZYX", the default) with only α: [[c, −s, 0], [s, c, 0], [0, 0, 1]], α the
    # float32 number's exact value in radians (converted in double precision, as the ST's LREAL).
    pose = np.array([1.5, -2.25, 3.0, 10.1, 0.0, 0.0], dtype=np.float32)
    alpha = math.radians(float(pose[3]))
    c, s = math.cos(alpha), math.sin(alpha)
    joints = world_joints(PlatformConfig(), pose)
    assert joints.upper_rotation == pytest.approx(np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]),
                                                   rel=0, abs=1e-15)
    assert joints.upper_origin.tolist() == [1.5, -2.25, 3.0 + PlatformConfig().geometry.h0]


def test_a_path_keeps_its_centre_height_and_orientation():
    from stgen.reference.paths import PathSpec, sample

    # (xc + x(φ), yc + y(φ), z0) at a fixed orientation (paths.py): z0 and (α, β, γ) at every sample.
    spec = PathSpec("epitrochoid", centre=(5.0, -7.0, 250.5), orientation=(1.0, -2.0, 3.0))
    poses = sample(spec, 10.0, np.linspace(0.0, 10.0, 7)).poses
    assert poses[:, 2].tolist() == [250.5] * 7
    assert poses[:, 3:].tolist() == [[1.0, -2.0, 3.0]] * 7
    # at φ = 0 the epitrochoid (R + r)·cos φ − d·cos((R + r)φ/r) is at R + r − d = 50 mm, y = 0
    assert poses[0, :2].tolist() == [5.0 + 50.0, -7.0]


def test_a_playback_file_that_cannot_be_read_is_named_with_the_reason(tmp_path):
    missing = tmp_path / "missing.csv"
    with pytest.raises(PlaybackError) as error:
        read_playback_csv(missing)
    assert str(error.value) == f"{missing}: cannot read: [Errno 2] No such file or directory: '{missing}'"
    latin = tmp_path / "latin.csv"
    latin.write_bytes(b"t,x,y,z,alpha,beta,gamma\n0,1,2,3,4,5,6\xff\n")
    with pytest.raises(PlaybackError) as error:
        read_playback_csv(latin)
    assert str(error.value) == (f"{latin}: cannot read: 'utf-8' codec can't decode byte 0xff in position 38: "
                                "invalid start byte")


def test_a_steep_waves_fade_in_is_set_by_the_angular_limits():
    from stgen.reference.wave import OceanWave, WaveComponent, fade_in_duration

    # A = 100 mm, Tw = 100 s, L = 1 m, heading 0: the slope A·k = 0.2π gives the tilt about y bounds (the
    # docstring of wave_derivative_bounds) D0 = atan(0.2π) = 32.1°, D1 = A·k·ω = 2.26°/s.  Under the default
    # angular limits (10 °/s, 50 °/s², 500 °/s³) its velocity term binds: r = (10 − D1)/(2·D0) = 0.120/s,
    # T_F = 8.31 s; its other terms allow r >= 0.35, and z and x (D0 = 100 mm, D1 = 6.28 mm/s under
    # 100 mm/s) r = 0.47.  Taken with the linear limits, the tilt would allow r = 1.09 and z would set
    # T_F = 2.13 s.
    k, w = 2 * math.pi / 1000.0, 2 * math.pi / 100.0
    d0, d1 = math.degrees(math.atan(100.0 * k)), math.degrees(100.0 * k * w)
    wave = OceanWave((WaveComponent(100.0, 100.0, 1.0, 0.0),))
    assert fade_in_duration(wave, TrajectoryConfig()) == pytest.approx(2.0 * d0 / (10.0 - d1), rel=1e-12)
    assert 2.0 * d0 / (10.0 - d1) == pytest.approx(8.31, abs=0.005)


@pytest.mark.parametrize("limit, refused", [(16.0, True), (17.0, False)])
def test_a_wave_whose_acceleration_alone_reaches_the_limit_is_refused(limit, refused):
    from stgen.reference.wave import OceanWave, WaveComponent, fade_in_duration

    # A = 1 mm, ω = 4 rad/s (Tw = π/2 s), L = 1e6 m (tilts negligible): D1 = 4 mm/s, D2 = 16 mm/s², D3 = 64 mm/s³.
    # An acceleration limit of 16 mm/s² leaves nothing to fade in with ("reaches": spare <= 0); 17 leaves 1,
    # shared by its two terms in r: 4·D1·r <= 1/2 binds, r = 1/32, T_F = 32 s (2π·D0·r² <= 1/2 allows
    # r = 0.28; velocity 48, jerk 3.5).
    wave = OceanWave((WaveComponent(1.0, math.pi / 2, 1_000_000.0, 0.0),))
    limits = TrajectoryConfig(linear_acceleration=limit)
    if refused:
        with pytest.raises(ValueError) as error:
            fade_in_duration(wave, limits)
        assert str(error.value) == "the wave alone reaches the limits in pose coordinate 1"
    else:
        assert fade_in_duration(wave, limits) == pytest.approx(32.0, rel=1e-12)


def test_an_angular_acceleration_takes_float32_angles_at_their_value():
    from stgen.reference.actuator_rates import angular_acceleration

    # ω = E(a)·ȧ with E's columns the turned axes; with β = γ = 0, no rates and only γ̈ = 1 rad/s²,
    # ω̇ = γ̈ times the x axis turned by Rz(α): (cos α, sin α, 0), α the float32 number's exact value
    # (the registry had judged the dtype mutant equivalent for integer angles; float32 ones tell).
    angles = np.array([0.7, 0.0, 0.0], dtype=np.float32)
    alpha = float(angles[0])
    result = angular_acceleration(angles, np.zeros(3), np.array([0.0, 0.0, 1.0]))
    assert result == pytest.approx([math.cos(alpha), math.sin(alpha), 0.0], rel=0, abs=1e-16)
