"""Cycloidal point-to-point motion (docs/mathematics.md section 4, [19–28]).

h = pf − p0, τ = (t − t0)/T, σ(τ) = τ − sin(2πτ)/(2π), p = p0 + h·σ(τ).
Peaks per coordinate: velocity 2h/T, acceleration 2πh/T², jerk 4π²h/T³.
Poses are (x, y, z, α, β, γ) in mm and degrees; x, y, z obey the linear
limits, α, β, γ the angular ones.
"""

from __future__ import annotations

import numpy as np

from stgen.config import TrajectoryConfig

TWO_PI = 2.0 * np.pi


def cycloidal_fraction(tau) -> np.ndarray:
    """σ(τ) = τ − sin(2πτ)/(2π) for τ clipped to [0, 1]: 0 → 0, 1 → 1, zero slope at both ends."""
    tau = np.clip(np.asarray(tau, dtype=float), 0.0, 1.0)
    return tau - np.sin(TWO_PI * tau) / TWO_PI


def _limits_per_coordinate(limits: TrajectoryConfig) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    linear, angular = np.ones(3), np.ones(3)
    velocity = np.concatenate((linear * limits.linear_velocity, angular * limits.angular_velocity))
    acceleration = np.concatenate((linear * limits.linear_acceleration, angular * limits.angular_acceleration))
    jerk = np.concatenate((linear * limits.linear_jerk, angular * limits.angular_jerk))
    return velocity, acceleration, jerk


def cycloidal_duration(displacement, limits: TrajectoryConfig) -> float | np.ndarray:
    """Smallest T keeping every coordinate of ``h[..., 6]`` inside its limits (docs/mathematics.md section 4).

    T = max over the six coordinates of 2|h|/v_max, √(2π|h|/a_max) and
    ∛(4π²|h|/j_max), so all coordinates share T and start and stop together.
    Zero displacement gives T = 0.
    """
    magnitude = np.abs(np.asarray(displacement, dtype=float))
    velocity, acceleration, jerk = _limits_per_coordinate(limits)
    durations = np.stack(
        (
            2.0 * magnitude / velocity,
            np.sqrt(TWO_PI * magnitude / acceleration),
            np.cbrt(TWO_PI**2 * magnitude / jerk),
        )
    )
    longest = durations.max(axis=(0, -1))
    return float(longest) if longest.ndim == 0 else longest


def executed_duration(duration: float, period: float) -> float:
    """T as TRJ_Cycloidal runs it: a move shorter than one task period is output at once (T = 0).

    Such a move is tiny: the jerk limit keeps |h| <= j_max·T³/(4π²), 1.3e-7 mm at
    5000 mm/s³ and T < 1 ms.
    """
    return 0.0 if duration < period else duration


def _progress(duration: float, t, t0: float) -> np.ndarray:
    """τ = (t − t0)/T clipped to [0, 1]; with T <= 0 the move is a step at t0."""
    t = np.asarray(t, dtype=float)
    if duration <= 0.0:
        return np.where(t >= t0, 1.0, 0.0)
    return np.clip((t - t0) / duration, 0.0, 1.0)


def cycloidal_pose(p0, pf, duration: float, t, t0: float = 0.0) -> np.ndarray:
    """p(t) = p0 + (pf − p0)·σ((t − t0)/T) [19–28], for times ``t[...]`` → poses ``[..., 6]``.

    Before t0 the pose is p0, after t0 + T it is pf.
    """
    p0 = np.asarray(p0, dtype=float)
    displacement = np.asarray(pf, dtype=float) - p0
    sigma = cycloidal_fraction(_progress(duration, t, t0))
    return p0 + displacement * sigma[..., None]


def cycloidal_velocity(p0, pf, duration: float, t, t0: float = 0.0) -> np.ndarray:
    """dp/dt = (h/T)·(1 − cos 2πτ) inside the move, 0 outside; peak 2h/T at τ = 1/2."""
    displacement = np.asarray(pf, dtype=float) - np.asarray(p0, dtype=float)
    t = np.asarray(t, dtype=float)
    if duration <= 0.0:
        return np.zeros(t.shape + (6,))
    tau = (t - t0) / duration
    inside = (tau >= 0.0) & (tau <= 1.0)
    rate = np.where(inside, (1.0 - np.cos(TWO_PI * tau)) / duration, 0.0)
    return displacement * rate[..., None]
