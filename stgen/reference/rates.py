"""Actuator rates from pose rates through the Jacobians (docs/mathematics.md section 6.2; also the paths issue, docs/mathematics.md section 6.3).

Public entry points: :func:`leg_rates` (linear legs: length, velocity and
acceleration) and :func:`crank_rates` (crank angle, rate and acceleration).
Poses and their rates are given as at every interface: x, y, z in mm, mm/s,
mm/s²; the three angles in degrees, deg/s, deg/s² in the order of the
configured rotation (Euler rates, converted to the angular velocity ω by
:mod:`stgen.reference.orientation`: the rates are not ω themselves).

Linear legs (docs/mathematics.md section 6.2): V_Pi = vU + ωU × (RU·Pi_U), V_Oi = vB + ωB × (RB·Oi_B),
ṙi = V_Pi − V_Oi, vi = l̇i = ei·ṙi;
a_Pi = aU + ω̇U × (RU·Pi_U) + ωU × (ωU × RU·Pi_U) (likewise a_Oi),
ai = l̈i = ei·(a_Pi − a_Oi) + (|ṙi|² − vi²)/li.

Crank legs (docs/mathematics.md section 6.1), from d/dt |Pi − Ai|² = 0 in the base frame with
g = Pi − Ai, Ȧi = a·θ̇i·ti (ti = ∂ui/∂θ, ui the crank direction):
θ̇i = (g·Ṗi)/(a·g·ti);
θ̈i = (|Ṗi − Ȧi|² + g·P̈i + a·θ̇i²·(g·ui))/(a·g·ti).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from stgen.config import PlatformConfig
from stgen.reference.crank import crank_directions, crank_inverse_kinematics, crank_tips
from stgen.reference.moving_base import legs_of, world_joints_rad
from stgen.reference.orientation import angular_acceleration, angular_velocity


def _pose_rates(order: str, pose_deg, rate, acceleration):
    """(angles rad, v mm/s, ω rad/s, a mm/s², ω̇ rad/s²) of one platform's pose and rates in degrees."""
    pose = np.asarray(pose_deg, dtype=float)
    rate = np.zeros_like(pose) if rate is None else np.asarray(rate, dtype=float)
    acceleration = np.zeros_like(pose) if acceleration is None else np.asarray(acceleration, dtype=float)
    angles = np.radians(pose[..., 3:])
    omega = angular_velocity(order, angles, np.radians(rate[..., 3:]))
    omega_dot = angular_acceleration(order, angles, np.radians(rate[..., 3:]), np.radians(acceleration[..., 3:]))
    return angles, rate[..., :3], omega, acceleration[..., :3], omega_dot


@dataclass(frozen=True)
class PointMotion:
    """World-frame velocity and acceleration of the upper joints Pi and base joints Oi, ``[..., 6, 3]``."""

    upper_velocity: np.ndarray
    upper_acceleration: np.ndarray
    base_velocity: np.ndarray
    base_acceleration: np.ndarray


def _rigid(arms, velocity, omega, acceleration, omega_dot):
    """Velocity and acceleration of points at ``arms`` from the origin of a rigid body."""
    w = omega[..., None, :]
    point_velocity = velocity[..., None, :] + np.cross(w, arms)
    point_acceleration = (acceleration[..., None, :] + np.cross(omega_dot[..., None, :], arms)
                          + np.cross(w, np.cross(w, arms)))
    return point_velocity, point_acceleration


def joint_motion(config: PlatformConfig, upper_pose_deg, upper_rate=None, upper_acceleration=None,
                 base_pose_deg=None, base_rate=None, base_acceleration=None):
    """(:class:`~stgen.reference.moving_base.WorldJoints`, :class:`PointMotion`) of poses and rates."""
    order_u, order_b = config.platform.platform_rotation, config.platform.base_rotation
    base_pose = np.zeros(6) if base_pose_deg is None else base_pose_deg
    upper_angles, vu, wu, au, wdu = _pose_rates(order_u, upper_pose_deg, upper_rate, upper_acceleration)
    base_angles, vb, wb, ab, wdb = _pose_rates(order_b, base_pose, base_rate, base_acceleration)
    joints = world_joints_rad(config, np.asarray(upper_pose_deg, dtype=float)[..., :3], upper_angles,
                              np.asarray(base_pose, dtype=float)[..., :3], base_angles)
    up_v, up_a = _rigid(joints.upper_arms, vu, wu, au, wdu)
    base_v, base_a = _rigid(joints.base_arms, vb, wb, ab, wdb)
    return joints, PointMotion(up_v, up_a, base_v, base_a)


@dataclass(frozen=True)
class LegRates:
    """Leg lengths li (mm), velocities l̇i (mm/s) and accelerations l̈i (mm/s²), ``[..., 6]``."""

    lengths: np.ndarray
    velocities: np.ndarray
    accelerations: np.ndarray


def leg_rates(config: PlatformConfig, upper_pose_deg, upper_rate=None, upper_acceleration=None,
              base_pose_deg=None, base_rate=None, base_acceleration=None) -> LegRates:
    """Length, velocity and acceleration of the six linear legs (docs/mathematics.md section 6.2), vectorised over ``[...]``.

    Rates default to zero; the base defaults to the fixed zero pose.
    """
    joints, motion = joint_motion(config, upper_pose_deg, upper_rate, upper_acceleration,
                                  base_pose_deg, base_rate, base_acceleration)
    state = legs_of(config, joints)
    e = state.directions
    relative_velocity = motion.upper_velocity - motion.base_velocity
    velocity = np.sum(e * relative_velocity, axis=-1)
    acceleration = (np.sum(e * (motion.upper_acceleration - motion.base_acceleration), axis=-1)
                    + (np.sum(relative_velocity**2, axis=-1) - velocity**2) / state.lengths)
    return LegRates(state.lengths, velocity, acceleration)


@dataclass(frozen=True)
class CrankRates:
    """Crank angles θi (degrees), rates θ̇i (deg/s) and accelerations θ̈i (deg/s²), ``[..., 6]``."""

    angles_deg: np.ndarray
    rates: np.ndarray
    accelerations: np.ndarray


def crank_rates(config: PlatformConfig, upper_pose_deg, upper_rate=None, upper_acceleration=None,
                base_pose_deg=None, base_rate=None, base_acceleration=None) -> CrankRates:
    """Crank angle, rate and acceleration of the six cranks (docs/mathematics.md section 6.1), vectorised over ``[...]``.

    NaN where the IK has no solution.
    """
    joints, motion = joint_motion(config, upper_pose_deg, upper_rate, upper_acceleration,
                                  base_pose_deg, base_rate, base_acceleration)
    angles = crank_inverse_kinematics(config, upper_pose_deg, base_pose_deg).angles_deg
    # Everything in the base frame: relative motion of Pi seen from the (moving) base.
    rb = joints.base_rotation
    _, vb, wb, ab, wdb = _pose_rates(config.platform.base_rotation,
                                     np.zeros(6) if base_pose_deg is None else base_pose_deg,
                                     base_rate, base_acceleration)
    relative = joints.upper - joints.base_origin[..., None, :]
    w = wb[..., None, :]
    # Velocity and acceleration of Pi relative to the base frame, expressed in the world frame.
    rel_v = motion.upper_velocity - vb[..., None, :] - np.cross(w, relative)
    rel_a = (motion.upper_acceleration - ab[..., None, :] - np.cross(wdb[..., None, :], relative)
             - np.cross(w, np.cross(w, relative)) - 2.0 * np.cross(w, rel_v))
    to_base = lambda vectors: np.einsum("...kj,...ik->...ij", rb, vectors)  # noqa: E731
    p_dot, p_ddot = to_base(rel_v), to_base(rel_a)
    p_base = to_base(relative)
    a = config.crank.crank_length
    direction, tangent = crank_directions(config, angles)
    g = p_base - crank_tips(config, angles)
    denominator = a * np.sum(g * tangent, axis=-1)
    rate = np.sum(g * p_dot, axis=-1) / denominator
    relative_velocity = p_dot - a * rate[..., None] * tangent
    accel = (np.sum(relative_velocity**2, axis=-1) + np.sum(g * p_ddot, axis=-1)
             + a * rate**2 * np.sum(g * direction, axis=-1)) / denominator
    return CrankRates(angles, np.degrees(rate), np.degrees(accel))
