"""The reference takes numbers at their value and gives doubles (issue 16, docs/mutation.md,
reference, "Session 15, gaps (h-gaps-s15)").

The registry listed 56 mutants `np.asarray(x, dtype=float)` -> `np.asarray(x)` as equivalent
"for integer inputs".  The public functions below are called by users with whatever arrays they
hold: a float32 array (as from a file or a sensor), np.longdouble (wider than the ST's LREAL) or
integers.  The ST computes in LREAL, so the reference must take each input at its value, round
it to the nearest double once, and return doubles; without the conversion a float32 input is
computed in float32 arithmetic (NumPy keeps float32 against Python floats), a long double one in
long double, and an input stored as given comes back in its own type.

Expected values are worked out by hand or by an independent NumPy computation in float64 from
the docstrings' formulas (docs/mathematics.md), on the inputs' values converted to doubles first;
never by running the code under test on the same input.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from stgen.config import PlatformConfig, load_config
from stgen.reference.geometry import base_joints, platform_joints

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
TWO_PI = 2.0 * math.pi


def f32(*values):
    return np.array(values, dtype=np.float32)


def wide(*fractions):
    """Long doubles p/q that are not doubles (1/3 in 64 bits of mantissa)."""
    return np.array([np.longdouble(p) / np.longdouble(q) for p, q in fractions])


def doubles(a) -> np.ndarray:
    """The doubles nearest the given numbers: what the ST's LREAL holds."""
    return np.asarray(a).astype(np.float64)


def same(found, expected) -> None:
    found = np.asarray(found)
    assert found.dtype == np.float64
    assert found == pytest.approx(np.asarray(expected, dtype=np.float64), rel=1e-15, abs=1e-15)


def rz(alpha: float) -> np.ndarray:
    c, s = math.cos(alpha), math.sin(alpha)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


# ------------------------------------------------------------------------- actuator_rates

def test_an_angular_acceleration_takes_float32_rates_and_wide_accelerations_at_their_value():
    from stgen.reference.actuator_rates import angular_acceleration

    # At α = β = 0 the formula of angular_acceleration reads x = γ̈ − β̇·α̇, y = β̈ + γ̇·α̇,
    # z = α̈ − γ̇·β̇ (cos 0 = 1, sin 0 = 0).  A product of two float32 rates is exact in double
    # precision and not in float32.
    rates = f32(0.1, 0.3, 0.7)
    acc = wide((1, 3), (1, 7), (1, 9))
    da, db, dg = doubles(rates)
    dda, ddb, ddg = doubles(acc)
    same(angular_acceleration(np.zeros(3), rates, acc), [ddg - db * da, ddb + dg * da, dda - dg * db])


def test_a_rate_jacobian_turns_a_float32_pose_at_its_value():
    from stgen.reference.actuator_rates import rate_jacobian

    # Row i = [eiᵀ, (ri × ei)ᵀ] (docs/mathematics.md section 6.3): ri = Rz(α)·Pi, Li = ri + p + h0·z
    # − Bi, ei = Li/|Li|, α the float32 angle's value in radians (in double precision).
    geometry = PlatformConfig().geometry
    pose = f32(1.5, -2.25, 3.0, 10.1, 0.0, 0.0)
    p = doubles(pose)
    r = platform_joints(geometry) @ rz(math.radians(p[3])).T
    legs = r + p[:3] + np.array([0.0, 0.0, geometry.h0]) - base_joints(geometry)
    e = legs / np.sqrt(np.sum(legs * legs, axis=-1))[:, None]
    same(rate_jacobian(geometry, pose), np.concatenate((e, np.cross(r, e)), axis=-1))


# ---------------------------------------------------------------------------------- brake

def test_a_brake_pose_takes_float32_rates_and_times_and_a_wide_start_at_their_value():
    from stgen.reference.brake import brake_pose

    # p(t) = p0 + v0·T·h00(τ) + a0·T²·h10(τ), τ = t/T, h00 = τ − τ³ + τ⁴/2,
    # h10 = τ²/2 − 2τ³/3 + τ⁴/4 (brake.py's docstring), in double precision.
    start = wide((1, 3), (2, 3), (1, 7), (5, 7), (1, 9), (4, 9))
    velocity = f32(0.1, -0.3, 0.7, 1.1, -1.3, 0.17)
    acceleration = f32(2.1, 0.3, -0.7, 0.11, 1.9, -2.3)
    t = f32(0.1, 0.2, 0.33)
    T = 0.37
    tau = (doubles(t) / T)[:, None]
    h00 = tau - tau ** 3 + tau ** 4 / 2.0
    h10 = tau ** 2 / 2.0 - (2.0 / 3.0) * tau ** 3 + 0.25 * tau ** 4
    expected = doubles(start) + doubles(velocity) * T * h00 + doubles(acceleration) * (T * T) * h10
    same(brake_pose(start, velocity, acceleration, T, t), expected)


def test_set_point_motion_takes_float32_set_points_at_their_value():
    from stgen.reference.brake import setpoint_motion

    # a0 = (p0 − 2·p1 + p2)/dt², v0 = (p0 − p1)/dt + a0·dt/2 (setpoint_motion's docstring).
    p2, p1, p0 = f32(0.1, 0.2, 0.3), f32(0.13, 0.19, 0.37), f32(0.17, 0.23, 0.41)
    dt = 0.001
    a0 = (doubles(p0) - 2.0 * doubles(p1) + doubles(p2)) / (dt * dt)
    v0 = (doubles(p0) - doubles(p1)) / dt + a0 * (dt / 2.0)
    velocity, acceleration = setpoint_motion(p2, p1, p0, dt)
    same(velocity, v0)
    same(acceleration, a0)


# ---------------------------------------------------------------------- crank, cycloidal

def test_wrapped_crank_angles_take_float32_angles_at_their_value():
    from stgen.reference.crank import wrap_crank_angle

    # [c − 180, c + 180) with c the middle of the limits: mod(θ − low, 360) + low.
    config = load_config(EXAMPLES / "crank_platform.toml")
    low = 0.5 * (config.crank.angle_min_deg + config.crank.angle_max_deg) - 180.0
    angles = f32(10.1, 370.3, -200.7, 1000.9)
    same(wrap_crank_angle(config, angles), np.mod(doubles(angles) - low, 360.0) + low)


def test_a_cycloidal_pose_takes_float32_times_at_their_value():
    from stgen.reference.cycloidal import cycloidal_pose

    # p0 + (pf − p0)·σ(τ), σ(τ) = τ − sin(2πτ)/(2π), τ = (t − t0)/T in double precision.
    p0, pf = np.zeros(6), np.array([10.0, -20.0, 5.0, 1.0, -2.0, 3.0])
    t = f32(0.1, 0.3, 0.5)
    tau = (doubles(t) - 0.05) / 0.7
    sigma = tau - np.sin(TWO_PI * tau) / TWO_PI
    same(cycloidal_pose(p0, pf, 0.7, t, 0.05), p0 + (pf - p0) * sigma[:, None])


# ---------------------------------------------------------------------------------- paths

def test_a_path_takes_float32_times_and_fractions_at_their_value():
    from stgen.reference.paths import PathSpec, sample, time_law

    # The cycloidal time law: f = u − sin(2πu)/(2π), f' = 1 − cos 2πu, f'' = 2π·sin 2πu,
    # f''' = 4π²·cos 2πu; φ = φ_end·f(t/T).
    spec = PathSpec("epitrochoid", phi_end=6.0, law="cycloidal")
    u = doubles(f32(0.1, 0.33, 0.77))
    found = time_law(spec, f32(0.1, 0.33, 0.77))
    expected = (u - np.sin(TWO_PI * u) / TWO_PI, 1.0 - np.cos(TWO_PI * u), TWO_PI * np.sin(TWO_PI * u),
                TWO_PI ** 2 * np.cos(TWO_PI * u))
    for f, e in zip(found, expected):
        same(f, e)
    t = f32(0.1, 3.3, 7.7)
    samples = sample(spec, 10.0, t)
    same(samples.t, doubles(t))
    u = doubles(t) / 10.0
    same(samples.phi, 6.0 * (u - np.sin(TWO_PI * u) / TWO_PI))


# ---------------------------------------------------------------------------------- rates

def test_joint_motion_takes_float32_poses_and_rates_at_their_value():
    from stgen.reference.rates import joint_motion

    # Only α, α̇ and α̈ (with a linear velocity and acceleration): ω = (0, 0, α̇), ω̇ = (0, 0, α̈) in
    # rad; arms ri = Rz(α)·Pi; a joint moves with v + ω × ri and a + ω̇ × ri + ω × (ω × ri)
    # (rates.py, _rigid).  Values of the float32 numbers, converted to radians in double precision.
    geometry = PlatformConfig().geometry
    pose = f32(1.5, -2.25, 3.0, 10.1, 0.0, 0.0)
    rate = f32(0.3, -0.7, 0.11, 7.3, 0.0, 0.0)
    acceleration = f32(1.3, 0.9, -0.6, 2.9, 0.0, 0.0)
    p, v, a = doubles(pose), doubles(rate), doubles(acceleration)
    r = platform_joints(geometry) @ rz(math.radians(p[3])).T
    w = np.array([0.0, 0.0, math.radians(v[3])])
    wd = np.array([0.0, 0.0, math.radians(a[3])])
    joints, motion = joint_motion(PlatformConfig(), pose, rate, acceleration)
    same(joints.upper_arms, r)
    same(motion.upper_velocity, v[:3] + np.cross(w, r))
    same(motion.upper_acceleration, a[:3] + np.cross(wd, r) + np.cross(w, np.cross(w, r)))


# ---------------------------------------------------------------------------- orientation

def test_an_angular_acceleration_by_order_takes_wide_rates_at_their_value():
    from stgen.reference.orientation import angular_acceleration

    # ω̇ = E·ä + Σk ωk−1 × (E[:, k]·ȧk); at zero angles E's columns for "ZYX" are z, y, x.  With
    # ȧ = (r, r, 0) and ä = (q, 0, 0): E·ä = (0, 0, q) and (z·r) × (y·r) = −r²·x: ω̇ = (−r², 0, q),
    # r and q the doubles nearest 1/3 and 1/7.
    rates, accelerations = wide((1, 3), (1, 3), (0, 1)), wide((1, 7), (0, 1), (0, 1))
    r, q = doubles(rates)[0], doubles(accelerations)[0]
    same(angular_acceleration("ZYX", np.zeros(3), rates, accelerations), [-r * r, 0.0, q])


# ----------------------------------------------------------------------------------- wave

def test_a_wave_pose_takes_wide_times_and_centre_at_their_value():
    from stgen.reference.wave import OceanWave, WaveComponent, wave_pose

    # One component, heading 0, at x̃ = 0: φ' = −ω·t + φ; pose = (−A sin φ', 0, A cos φ', 0,
    # −deg(atan(−A·k·sin φ')), 0) + centre, ω = 2π/Tw, k = 2π/(L·1000 mm) (wave.py's docstring).
    wave = OceanWave((WaveComponent(3.0, 10.0, 100.0, 10.0),))
    t = wide((1, 3), (7, 3))
    centre = wide((1, 3), (1, 7), (240, 1), (1, 9), (1, 11), (1, 13))
    A, omega, k = 3.0, TWO_PI / 10.0, TWO_PI / 100_000.0
    phase = -omega * doubles(t) + math.radians(10.0)
    pose = np.stack((-A * np.sin(phase), np.zeros(2), A * np.cos(phase), np.zeros(2),
                     -np.degrees(np.arctan(-A * k * np.sin(phase))), np.zeros(2)), axis=-1)
    same(wave_pose(wave, t, centre), pose + doubles(centre))


# ----------------------------------------------------------------- moving_base, motion_limits

@pytest.mark.parametrize("base", [f32(0.5, 0.25, 0.1), np.array([1, -2, 3])], ids=["float32", "int"])
def test_world_joints_are_doubles_whatever_the_positions_given(base):
    from stgen.reference.moving_base import world_joints_rad

    # The upper origin is p + h0·z (p the double nearest the given long double); the base position
    # (base_origin) is given back as doubles of its values (it was the caller's float32 or int array).
    config = PlatformConfig()
    position = wide((1, 3), (2, 3), (1, 7))
    joints = world_joints_rad(config, position, np.zeros(3), base, np.zeros(3))
    same(joints.upper_origin, doubles(position) + np.array([0.0, 0.0, config.geometry.h0]))
    same(joints.base_origin, doubles(base))


@pytest.mark.parametrize("t", [f32(0.1, 0.2), np.array([0, 1])], ids=["float32", "int"])
def test_a_motion_check_holds_its_times_as_doubles(t):
    from stgen.reference.motion_limits import check_motion

    # MotionCheck.t: the sample times (s) as doubles of the given values.
    poses = np.array([[0.0, 0.0, 0.0, 0.0, 0.0, 0.0]] * 2)
    check = check_motion(PlatformConfig(), t, poses, np.zeros((2, 6)), np.zeros((2, 6)))
    same(check.t, doubles(t))
