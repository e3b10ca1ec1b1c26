"""Velocity and acceleration of the set-points a program hands to MC_SyncMoveAbsolute,
checked against the actuator's limits (issue 8, docs/mathematics.md sections 4 and 5).

MC_SyncMoveAbsolute takes one position per task period and does not limit
acceleration (OMRON: "maximum acceleration/deceleration are not used"), so
whatever the program commands reaches the drive: the program itself must keep
every cylinder inside ``actuator.max_velocity`` and ``actuator.max_acceleration``.
The check differentiates the commanded positions at the task period,
v_k = (q_k - q_k-1)/dt and a_k = (v_k - v_k-1)/dt, over the scans in which
the program drove the synchronous move (``active``); a difference that spans
a scan outside those is not taken. Any |v| or |a| above its limit is a breach.

Reused by every scenario runner (the study's scenarios, platform and path
scenarios): give it the set-points, the period and the limits.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: Relative slack on a limit: finite differences of positions near 600 mm carry rounding of about 1e-13 mm / 1e-6 s^2.
LIMIT_SLACK = 1e-9


@dataclass(frozen=True)
class SetpointLimitCheck:
    """Largest |v| and |a| per cylinder of a run, against the limits."""

    max_velocity: np.ndarray       # per cylinder, mm/s
    max_acceleration: np.ndarray   # per cylinder, mm/s^2
    velocity_limit: float          # mm/s
    acceleration_limit: float      # mm/s^2
    period_s: float
    velocity_breaches: int         # (scan, cylinder) pairs above the velocity limit
    acceleration_breaches: int     # (scan, cylinder) pairs above the acceleration limit
    first_breach_scan: int | None  # 1-based row of the first breach, None when none

    @property
    def max_velocity_step(self) -> np.ndarray:
        """Largest change of velocity in one scan per cylinder, mm/s (= max |a| * dt)."""
        return self.max_acceleration * self.period_s

    @property
    def passed(self) -> bool:
        return self.velocity_breaches == 0 and self.acceleration_breaches == 0

    def describe(self) -> str:
        """One line: the largest |v| and |a| over all cylinders against their limits."""
        return (f"max |v| {self.max_velocity.max():.1f} of {self.velocity_limit:g} mm/s, "
                f"max |a| {self.max_acceleration.max():.1f} of {self.acceleration_limit:g} mm/s^2"
                + ("" if self.passed else f", breach from row {self.first_breach_scan}"))


def _differences(q: np.ndarray, period_s: float, active):
    on = np.ones(len(q), dtype=bool) if active is None else np.asarray(active, dtype=bool)
    velocity = np.diff(q, axis=0) / period_s                       # row k-1 holds v of row k
    acceleration = np.diff(velocity, axis=0) / period_s            # row k-2 holds a of row k
    velocity_valid = on[1:] & on[:-1]
    acceleration_valid = velocity_valid[1:] & velocity_valid[:-1]
    return velocity, acceleration, velocity_valid, acceleration_valid


def setpoint_rates(positions, period_s: float, active=None) -> tuple[np.ndarray, np.ndarray]:
    """(v, a) per row and cylinder as :func:`check_setpoint_limits` takes them, same shape as
    ``positions``; NaN where a difference is not taken (first rows, scans outside ``active``)."""
    q = np.asarray(positions, dtype=float)
    velocity, acceleration, velocity_valid, acceleration_valid = _differences(q, period_s, active)
    v = np.full(q.shape, np.nan)
    a = np.full(q.shape, np.nan)
    v[1:] = np.where(velocity_valid[:, None], velocity, np.nan)
    a[2:] = np.where(acceleration_valid[:, None], acceleration, np.nan)
    return v, a


def _masked_max(values: np.ndarray, valid: np.ndarray) -> np.ndarray:
    magnitude = np.where(valid[:, None], np.abs(values), 0.0)
    return magnitude.max(axis=0) if len(magnitude) else np.zeros(values.shape[1])


def check_setpoint_limits(
    positions,
    period_s: float,
    velocity_limit: float,
    acceleration_limit: float,
    active=None,
) -> SetpointLimitCheck:
    """Check ``positions[scan, cylinder]`` (mm, one row per scan) against the limits.

    ``active[scan]``: True where the program drove the synchronous move in that
    scan (default: every scan). Velocity of row k needs rows k-1, k active;
    acceleration of row k needs rows k-2..k active.
    """
    q = np.asarray(positions, dtype=float)
    if q.ndim != 2:
        raise ValueError(f"positions must be [scans, cylinders], got shape {q.shape}")
    scans, cylinders = q.shape
    velocity, acceleration, velocity_valid, acceleration_valid = _differences(q, period_s, active)
    v_over = (np.abs(velocity) > velocity_limit * (1.0 + LIMIT_SLACK)) & velocity_valid[:, None]
    a_over = (np.abs(acceleration) > acceleration_limit * (1.0 + LIMIT_SLACK)) & acceleration_valid[:, None]
    first = []
    if v_over.any():
        first.append(int(np.argmax(v_over.any(axis=1))) + 2)
    if a_over.any():
        first.append(int(np.argmax(a_over.any(axis=1))) + 3)
    return SetpointLimitCheck(
        max_velocity=_masked_max(velocity, velocity_valid) if scans > 1 else np.zeros(cylinders),
        max_acceleration=_masked_max(acceleration, acceleration_valid) if scans > 2 else np.zeros(cylinders),
        velocity_limit=float(velocity_limit),
        acceleration_limit=float(acceleration_limit),
        period_s=float(period_s),
        velocity_breaches=int(np.count_nonzero(v_over)),
        acceleration_breaches=int(np.count_nonzero(a_over)),
        first_breach_scan=min(first) if first else None,
    )
