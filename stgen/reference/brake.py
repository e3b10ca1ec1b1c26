"""A controlled stop of a moving pose set-point (issue 8, docs/mathematics.md section 5): the program
ramps the set-point to rest before MC_Stop, because MC_Stop on an axis under
MC_SyncMoveAbsolute is an immediate stop (OMRON, docs/nj501.md).

From the set-point's velocity v0 and acceleration a0 at the start of the stop,
each coordinate's velocity follows the cubic Hermite curve from (v0, a0) to
(0, 0) over the stop duration T_S (τ = t/T_S):
  v(τ) = v0·h00(τ) + a0·T_S·h10(τ),  h00 = 2τ³ − 3τ² + 1,  h10 = τ³ − 2τ² + τ,
so the position
  p(τ) = p0 + v0·T_S·H00(τ) + a0·T_S²·H10(τ),  H00 = τ − τ³ + τ⁴/2,  H10 = τ²/2 − 2τ³/3 + τ⁴/4,
is continuous in position, velocity and acceleration at the start, and at rest
with zero acceleration at the end (stop distance v0·T_S/2 + a0·T_S²/12).

T_S: with |h00'| <= 3/2, |h10'| <= 1, |h00''| <= 6, |h10''| <= 4,
  |a| <= 3|v0|/(2T_S) + |a0| <= a_max  →  T_S >= 3|v0| / (2(a_max − |a0|)),
  |j| <= 6|v0|/T_S² + 4|a0|/T_S <= j_max, each term half  →  T_S >= √(12|v0|/j_max), T_S >= 8|a0|/j_max,
over the six coordinates (linear limits for x, y, z; angular for α, β, γ),
rounded up to whole task periods so the last set-point is exactly at rest.
The velocity may exceed |v0| by at most |a0|·T_S·4/27 (h10 peaks at τ = 1/3).
"""

from __future__ import annotations

import math

import numpy as np

from stgen.config import TrajectoryConfig


def brake_duration(velocity, acceleration, limits: TrajectoryConfig, period: float) -> float:
    """T_S (s), a whole number of periods; ValueError when |a0| already reaches a limit."""
    duration = 0.0
    for coordinate in range(6):
        v0 = abs(float(velocity[coordinate]))
        a0 = abs(float(acceleration[coordinate]))
        if coordinate < 3:
            a_max, j_max = limits.linear_acceleration, limits.linear_jerk
        else:
            a_max, j_max = limits.angular_acceleration, limits.angular_jerk
        if a0 >= a_max:
            raise ValueError(f"the set-point already accelerates at the limit in pose coordinate {coordinate + 1}")
        duration = max(duration, 1.5 * v0 / (a_max - a0), math.sqrt(12.0 * v0 / j_max), 8.0 * a0 / j_max)
    return math.ceil(duration / period - 1e-9) * period


def brake_pose(start, velocity, acceleration, duration: float, t) -> np.ndarray:
    """Pose ``[..., 6]`` of the stop at times ``t[...]`` (s) after its start; the end pose from ``duration`` on."""
    start = np.asarray(start, dtype=float)
    v0 = np.asarray(velocity, dtype=float)
    a0 = np.asarray(acceleration, dtype=float)
    t = np.asarray(t, dtype=float)
    if duration <= 0.0:
        return np.broadcast_to(start, t.shape + (6,)).copy()
    tau = np.clip(t / duration, 0.0, 1.0)[..., None]
    h00 = tau - tau * tau * tau + (tau * tau * tau * tau) / 2.0
    h10 = tau * tau / 2.0 - (2.0 / 3.0) * (tau * tau * tau) + 0.25 * (tau * tau * tau * tau)
    return start + v0 * duration * h00 + a0 * (duration * duration) * h10


def setpoint_motion(previous2, previous, current, period: float) -> tuple[np.ndarray, np.ndarray]:
    """(v0, a0) of a set-point sequence at its last sample: a0 = second difference / dt²,
    v0 = backward difference / dt + a0·dt/2 (so the stop's first step keeps the second difference a0)."""
    p2, p1, p0 = (np.asarray(p, dtype=float) for p in (previous2, previous, current))
    acceleration = (p0 - 2.0 * p1 + p2) / (period * period)
    velocity = (p0 - p1) / period + acceleration * (period / 2.0)
    return velocity, acceleration
