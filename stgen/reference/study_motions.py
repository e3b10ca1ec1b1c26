"""The moving-base study's motions (docs/mathematics.md section 6.2) and whether they keep every limit.

Each motion is given as functions of time with analytic first and second
derivatives (mm, degrees, seconds), in this project's frame: the upper z is
measured from the home height h0 (the study's 415.706 + ... becomes ...), the
base at the world origin at rest. The study's θ vectors are taken as angles
about (x, y, z); the upper rotation RU = Rx·Ry·Rz takes them in that order, the
base's RB = Rz·Ry·Rx takes them reversed (about z first). docs/mathematics.md section 6.2 does not say
which component of the study's θB is about which axis; :func:`motion_report`
evaluates both readings where it matters (``base_angles_reversed``).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from stgen.config import PlatformConfig
from stgen.reference.feasibility import Limit, feasibility
from stgen.reference.rates import leg_rates

PI = np.pi
#: One kinematic quantity: t [n] -> (value, rate, acceleration), each [n, 6].
Trajectory = Callable[[np.ndarray], tuple[np.ndarray, np.ndarray, np.ndarray]]


def _stack(*columns):
    return np.stack(columns, axis=-1)


def moving_base_upper(t):
    """pU = (4.5 cos πt, 4.5 sin πt, 11.5 t) (z from h0), θU = (0.5 t, t, 1.5 t) about (x, y, z)."""
    zero, one = np.zeros_like(t), np.ones_like(t)
    value = _stack(4.5 * np.cos(PI * t), 4.5 * np.sin(PI * t), 11.5 * t, 0.5 * t, t, 1.5 * t)
    rate = _stack(-4.5 * PI * np.sin(PI * t), 4.5 * PI * np.cos(PI * t), 11.5 * one, 0.5 * one, one, 1.5 * one)
    acceleration = _stack(-4.5 * PI**2 * np.cos(PI * t), -4.5 * PI**2 * np.sin(PI * t), zero, zero, zero, zero)
    return value, rate, acceleration


def moving_base_base(t, reversed_angles: bool = True):
    """pB = (0.4 t, −0.2 t, −3 cos πt), θB = (0.3 t, 0.3 t, 0.2 t) about (x, y, z); with
    ``reversed_angles`` given to RB = Rz·Ry·Rx as (about z, about y, about x)."""
    zero, one = np.zeros_like(t), np.ones_like(t)
    angles = (0.2, 0.3, 0.3) if reversed_angles else (0.3, 0.3, 0.2)
    value = _stack(0.4 * t, -0.2 * t, -3.0 * np.cos(PI * t), *(k * t for k in angles))
    rate = _stack(0.4 * one, -0.2 * one, 3.0 * PI * np.sin(PI * t), *(k * one for k in angles))
    acceleration = _stack(zero, zero, 3.0 * PI**2 * np.cos(PI * t), zero, zero, zero)
    return value, rate, acceleration


def fixed_base_upper(t):
    """pU = (5 t, 0.5 sin πt, 8 t) (z from h0), θU = (0.5 t, 1.25 t, 2 t) about (x, y, z)."""
    zero, one = np.zeros_like(t), np.ones_like(t)
    value = _stack(5.0 * t, 0.5 * np.sin(PI * t), 8.0 * t, 0.5 * t, 1.25 * t, 2.0 * t)
    rate = _stack(5.0 * one, 0.5 * PI * np.cos(PI * t), 8.0 * one, 0.5 * one, 1.25 * one, 2.0 * one)
    acceleration = _stack(zero, -0.5 * PI**2 * np.sin(PI * t), zero, zero, zero, zero)
    return value, rate, acceleration


@dataclass(frozen=True)
class MotionReport:
    """Extremes of one motion sampled every ``period`` s: ``feasible`` on every sample, the first
    broken (time, limit, leg) if any, and the extremes of D_i, |γ|, |ψ|, tilt (mm, degrees),
    |l̇i| (mm/s) and |l̈i| (mm/s²)."""

    name: str
    samples: int
    feasible: bool
    first_violation: tuple[float, str, int] | None
    extension_range: tuple[float, float]
    max_universal_gamma: float
    max_universal_psi: float
    max_tilt: float
    max_velocity: float
    max_acceleration: float


def motion_report(config: PlatformConfig, name: str, upper: Trajectory, base: Trajectory | None = None,
                  duration: float = 10.0, period: float = 0.001) -> MotionReport:
    t = np.arange(0.0, duration + period / 2, period)
    u, ud, udd = upper(t)
    b, bd, bdd = base(t) if base is not None else (None, None, None)
    result = feasibility(config, u, b)
    rates = leg_rates(config, u, ud, udd, b, bd, bdd)
    values = result.values
    first = None
    if not result.feasible.all():
        index = int(np.argmin(result.feasible))
        limit, leg = result.binding
        first = (float(t[index]), Limit(int(limit[index])).label, int(leg[index]))
    extension = values["extension_mm"]
    return MotionReport(
        name, len(t), bool(result.feasible.all()), first,
        (float(extension.min()), float(extension.max())),
        float(np.abs(values["universal_gamma_deg"]).max()), float(np.abs(values["universal_psi_deg"]).max()),
        float(values["spherical_tilt_deg"].max()),
        float(np.abs(rates.velocities).max()), float(np.abs(rates.accelerations).max()),
    )


def study_reports(config: PlatformConfig) -> list[MotionReport]:
    """The two 10 s motions of docs/mathematics.md section 6.2 (both readings of θB for the moving base)."""
    return [
        motion_report(config, "moving base (thetaB about z, y, x)", moving_base_upper,
                      lambda t: moving_base_base(t, True)),
        motion_report(config, "moving base (thetaB about x, y, z)", moving_base_upper,
                      lambda t: moving_base_base(t, False)),
        motion_report(config, "fixed base", fixed_base_upper),
    ]
