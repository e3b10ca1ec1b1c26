"""Linear-actuator rates from pose rates: l̇ = J·(v, ω) (docs/mathematics.md section 6.3), l̈ likewise (docs/mathematics.md section 6.2).

Fixed base, the platform of docs/mathematics.md section 1: pose (x, y, z, α, β, γ) in mm and
degrees with R = Rz(α)·Ry(β)·Rx(γ). Pose rates are the time derivatives of
those six numbers (mm/s and deg/s, Euler-angle rates); they become the angular
velocity through

    ω = α̇·ẑ + β̇·Rz(α)·ŷ + γ̇·Rz(α)·Ry(β)·x̂
      = α̇·(0, 0, 1) + β̇·(−sα, cα, 0) + γ̇·(cα cβ, sα cβ, −sβ).

With ri = R·Pi, Li the leg vector of docs/mathematics.md section 2, li = |Li| and ei = Li/li:
    l̇i = ei·(v + ω × ri) = [eiᵀ, (ri × ei)ᵀ]·(v, ω)          (docs/mathematics.md section 6.3)
    l̈i = ei·(a + ω̇ × ri + ω × (ω × ri)) + (|L̇i|² − l̇i²)/li   (docs/mathematics.md section 6.2)
The cylinder position is qi = li − l0, so q̇ = l̇ and q̈ = l̈.

This is the fixed-base linear case the paths need; the platforms issue
(branch i11-platforms, ``stgen.reference.rates``) covers the moving base and
crank actuators with configurable rotation orders.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from stgen.config import GeometryConfig
from stgen.reference.kinematics import leg_vectors


def angular_velocity(angles_rad, rates_rad) -> np.ndarray:
    """ω (rad/s, ``[..., 3]``) of R = Rz(α)·Ry(β)·Rx(γ) from (α, β, γ) and their rates, radians."""
    angles = np.asarray(angles_rad, dtype=float)
    rates = np.asarray(rates_rad, dtype=float)
    a, b = angles[..., 0], angles[..., 1]
    da, db, dg = rates[..., 0], rates[..., 1], rates[..., 2]
    ca, sa, cb, sb = np.cos(a), np.sin(a), np.cos(b), np.sin(b)
    return np.stack((-db * sa + dg * ca * cb, db * ca + dg * sa * cb, da - dg * sb), axis=-1)


def angular_acceleration(angles_rad, rates_rad, accelerations_rad) -> np.ndarray:
    """ω̇ (rad/s², ``[..., 3]``): the time derivative of :func:`angular_velocity`."""
    angles = np.asarray(angles_rad, dtype=float)
    rates = np.asarray(rates_rad, dtype=float)
    acc = np.asarray(accelerations_rad, dtype=float)
    a, b = angles[..., 0], angles[..., 1]
    da, db, dg = rates[..., 0], rates[..., 1], rates[..., 2]
    dda, ddb, ddg = acc[..., 0], acc[..., 1], acc[..., 2]
    ca, sa, cb, sb = np.cos(a), np.sin(a), np.cos(b), np.sin(b)
    x = -ddb * sa - db * da * ca + ddg * ca * cb - dg * (da * sa * cb + db * ca * sb)
    y = ddb * ca - db * da * sa + ddg * sa * cb + dg * (da * ca * cb - db * sa * sb)
    z = dda - ddg * sb - dg * db * cb
    return np.stack((x, y, z), axis=-1)


def _cross(u, v) -> np.ndarray:
    """u × v over the last axis (np.cross is several times slower on [..., 3] arrays)."""
    u, v = np.broadcast_arrays(u, v)
    return np.stack((u[..., 1] * v[..., 2] - u[..., 2] * v[..., 1],
                     u[..., 2] * v[..., 0] - u[..., 0] * v[..., 2],
                     u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]), axis=-1)


@dataclass(frozen=True)
class ActuatorRates:
    """Leg lengths li (mm), rates l̇i (mm/s) and accelerations l̈i (mm/s²), each ``[..., 6]``."""

    lengths: np.ndarray
    velocities: np.ndarray
    accelerations: np.ndarray


def rate_jacobian(geometry: GeometryConfig, poses_deg) -> np.ndarray:
    """J with l̇ = J·(v, ω): row i = [eiᵀ, (ri × ei)ᵀ] (docs/mathematics.md section 6.3), shape ``[..., 6, 6]``."""
    poses = np.asarray(poses_deg, dtype=float)
    legs = leg_vectors(geometry, np.concatenate((poses[..., :3], np.radians(poses[..., 3:])), axis=-1))
    e = legs.legs / legs.lengths[..., None]
    return np.concatenate((e, _cross(legs.rotated_joints, e)), axis=-1)


def actuator_rates(geometry: GeometryConfig, poses_deg, pose_rates, pose_accelerations) -> ActuatorRates:
    """Lengths, rates and accelerations of the six linear legs for poses and their rates ``[..., 6]``.

    Units: mm, degrees; rates mm/s and deg/s; accelerations mm/s² and deg/s².
    """
    poses = np.asarray(poses_deg, dtype=float)
    rates = np.asarray(pose_rates, dtype=float)
    accs = np.asarray(pose_accelerations, dtype=float)
    angles = np.radians(poses[..., 3:])
    omega = angular_velocity(angles, np.radians(rates[..., 3:]))
    omega_dot = angular_acceleration(angles, np.radians(rates[..., 3:]), np.radians(accs[..., 3:]))
    legs = leg_vectors(geometry, np.concatenate((poses[..., :3], angles), axis=-1))
    e = legs.legs / legs.lengths[..., None]
    arms = legs.rotated_joints
    w = omega[..., None, :]
    leg_rate = rates[..., None, :3] + _cross(w, arms)                      # L̇i
    joint_acc = accs[..., None, :3] + _cross(omega_dot[..., None, :], arms) + _cross(w, _cross(w, arms))
    velocity = np.sum(e * leg_rate, axis=-1)
    acceleration = np.sum(e * joint_acc, axis=-1) + (np.sum(leg_rate**2, axis=-1) - velocity**2) / legs.lengths
    return ActuatorRates(legs.lengths, velocity, acceleration)
