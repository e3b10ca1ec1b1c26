"""Legs of a platform whose base may move, and its joint angles (docs/mathematics.md section 6.2).

Both platforms have a pose in a fixed world frame. The upper pose
(x, y, z, a1, a2, a3) keeps docs/mathematics.md section 1's convention: x, y, z in mm from the home
position (the upper frame sits at (x, y, h0 + z)), angles in degrees in the
order of ``platform.platform_rotation``. The base pose (x, y, z, b1, b2, b3) is
in mm and degrees from the world origin, angles in the order of
``platform.base_rotation``; a fixed base is the zero base pose.

With Oi_B = Bi of ``[geometry]`` and Pi_U = Pi of ``[geometry]``:
Oi = RB·Oi_B + pB, Pi = RU·Pi_U + pU, ri = Pi − Oi, li = |ri|, ei = ri/li,
Di = li − l0. For the default platform (ZYX, fixed base) this is docs/mathematics.md section 2's IK.

Universal-joint angles (at the base joint): e = RBᵀ·ei, c = cos aBi,
s = sin aBi (aBi the base joint's polar angle θi of [4]):
γi = asin(c·ex + s·ey), ψi = atan2(s·ex − c·ey, ez), so the leg frame is
Rz(aBi)·Rx(ψi)·Ry(γi). Spherical tilt: the angle between ei and the upper
platform's normal RU·(0, 0, 1).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from stgen.config import PlatformConfig
from stgen.reference.geometry import base_joints, joint_angles, platform_joints
from stgen.reference.orientation import rotation


def split_pose_rad(pose_deg) -> tuple[np.ndarray, np.ndarray]:
    """(position mm, angles rad) of poses ``[..., 6]`` in mm and degrees."""
    pose = np.asarray(pose_deg, dtype=float)
    return pose[..., :3], np.radians(pose[..., 3:])


@dataclass(frozen=True)
class WorldJoints:
    """Joint centres and rotations in the world frame (shapes ``[..., 6, 3]`` and ``[..., 3, 3]``).

    ``base_arms`` = RB·Oi_B and ``upper_arms`` = RU·Pi_U are the joints
    relative to each platform's origin (the lever arms of the rates).
    """

    base_rotation: np.ndarray
    upper_rotation: np.ndarray
    base_origin: np.ndarray
    upper_origin: np.ndarray
    base_arms: np.ndarray
    upper_arms: np.ndarray

    @property
    def base(self) -> np.ndarray:
        """Oi = RB·Oi_B + pB."""
        return self.base_arms + self.base_origin[..., None, :]

    @property
    def upper(self) -> np.ndarray:
        """Pi = RU·Pi_U + pU."""
        return self.upper_arms + self.upper_origin[..., None, :]


def world_joints_rad(config: PlatformConfig, upper_position, upper_angles_rad,
                     base_position=None, base_angles_rad=None) -> WorldJoints:
    """:class:`WorldJoints` from positions in mm and angles in radians (base default: zero pose)."""
    upper_position = np.asarray(upper_position, dtype=float)
    upper_angles_rad = np.asarray(upper_angles_rad, dtype=float)
    base_position = np.zeros(3) if base_position is None else np.asarray(base_position, dtype=float)
    base_angles_rad = np.zeros(3) if base_angles_rad is None else np.asarray(base_angles_rad, dtype=float)
    upper_rotation = rotation(config.platform.platform_rotation, upper_angles_rad)
    base_rotation = rotation(config.platform.base_rotation, base_angles_rad)
    upper_arms = np.einsum("...jk,ik->...ij", upper_rotation, platform_joints(config.geometry))
    base_arms = np.einsum("...jk,ik->...ij", base_rotation, base_joints(config.geometry))
    upper_origin = upper_position + np.array([0.0, 0.0, config.geometry.h0])
    shape = np.broadcast_shapes(upper_origin.shape, base_position.shape)
    return WorldJoints(base_rotation, upper_rotation, np.broadcast_to(base_position, shape),
                       np.broadcast_to(upper_origin, shape), base_arms, upper_arms)


def world_joints(config: PlatformConfig, upper_pose_deg, base_pose_deg=None) -> WorldJoints:
    """:class:`WorldJoints` of upper (and base) poses in mm and degrees."""
    upper_position, upper_angles = split_pose_rad(upper_pose_deg)
    if base_pose_deg is None:
        return world_joints_rad(config, upper_position, upper_angles)
    base_position, base_angles = split_pose_rad(base_pose_deg)
    return world_joints_rad(config, upper_position, upper_angles, base_position, base_angles)


@dataclass(frozen=True)
class Legs:
    """ri = Pi − Oi, li = |ri|, ei = ri/li and the extension Di = li − l0 (mm)."""

    joints: WorldJoints
    vectors: np.ndarray
    lengths: np.ndarray
    directions: np.ndarray
    extensions: np.ndarray


def legs(config: PlatformConfig, upper_pose_deg, base_pose_deg=None) -> Legs:
    """The six legs of poses ``[..., 6]`` (mm, degrees), base at ``base_pose_deg`` (default zero)."""
    return legs_of(config, world_joints(config, upper_pose_deg, base_pose_deg))


def legs_of(config: PlatformConfig, joints: WorldJoints) -> Legs:
    vectors = joints.upper - joints.base
    lengths = np.sqrt(np.sum(vectors * vectors, axis=-1))
    with np.errstate(invalid="ignore", divide="ignore"):
        directions = vectors / lengths[..., None]
    return Legs(joints, vectors, lengths, directions, lengths - config.geometry.l0)


def universal_joint_angles(config: PlatformConfig, leg_state: Legs) -> tuple[np.ndarray, np.ndarray]:
    """(γi, ψi) in radians, shape ``[..., 6]`` each: the leg direction in the base frame through
    γ = asin(c·ex + s·ey), ψ = atan2(s·ex − c·ey, ez) with c, s of the base joint's polar angle."""
    local = np.einsum("...kj,...ik->...ij", leg_state.joints.base_rotation, leg_state.directions)  # RBᵀ·e
    polar, _ = joint_angles(config.geometry)
    c, s = np.cos(polar), np.sin(polar)
    ex, ey, ez = local[..., 0], local[..., 1], local[..., 2]
    gamma = np.arcsin(np.clip(c * ex + s * ey, -1.0, 1.0))
    psi = np.arctan2(s * ex - c * ey, ez)
    return gamma, psi


def spherical_tilt(leg_state: Legs) -> np.ndarray:
    """Angle (radians) between each leg and the upper platform's normal RU·(0,0,1), shape ``[..., 6]``."""
    normal = leg_state.joints.upper_rotation[..., :, 2]
    cosine = np.einsum("...ij,...j->...i", leg_state.directions, normal)
    return np.arccos(np.clip(cosine, -1.0, 1.0))
