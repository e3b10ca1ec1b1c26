"""Rotary crank actuators, a 6-RSS platform (docs/mathematics.md section 6.1).

Leg i: the motor shaft at Bi (base frame) turns a crank of length a in the
vertical plane through Bi with horizontal direction (cos φi, sin φi, 0); the
tip is Ai = Bi + a·(cos θi cos φi, cos θi sin φi, sin θi); a rod of length s
joins Ai to the platform joint Pi: |Pi − Ai| = s.

IK, closed form (not the study's eqs 13-19, which carry sign errors):
Δ = Pi − Bi (base frame), M = cos φi·Δx + sin φi·Δy, H = |Δ|² + a² − s²,
ρ = √(M² + Δz²); M cos θ + Δz sin θ = H/(2a), so
θi = atan2(Δz, M) + σi·acos(H/(2aρ)), σi the configured branch.
Unreachable when ρ = 0 or |H| > 2aρ; the crank-angle limits are checked too.
Angles at the interface in degrees, wrapped into [c − 180, c + 180) with c the
middle of [angle_min, angle_max], so that one range holds for every leg and
an angle outside it reads as near the limit it is nearer to.

FK: docs/mathematics.md section 3 with fi(a) = |Pi(a) − Ai|² − s², Ai from the measured crank
angles (see :mod:`stgen.reference.variant_fk`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from stgen.config import PlatformConfig
from stgen.reference.geometry import base_joints
from stgen.reference.moving_base import WorldJoints, split_pose_rad, world_joints


def crank_planes(config: PlatformConfig) -> np.ndarray:
    """φi in radians, shape [6]."""
    return np.radians(np.asarray(config.crank.plane_angle_deg, dtype=float))


def wrap_crank_angle(config: PlatformConfig, angles_deg) -> np.ndarray:
    """Angles (degrees) brought into [c − 180, c + 180) by whole turns, c the middle of the limits."""
    low = 0.5 * (config.crank.angle_min_deg + config.crank.angle_max_deg) - 180.0
    return np.mod(np.asarray(angles_deg, dtype=float) - low, 360.0) + low


@dataclass(frozen=True)
class CrankSolution:
    """IK of a crank platform: ``angles_deg[..., 6]`` (NaN where no solution), ``solvable[..., 6]``
    (ρ > 0 and |H| <= 2aρ), ``in_limits[..., 6]`` (solvable and inside the crank-angle limits),
    ``cosine[..., 6]`` = H/(2aρ) (beyond ±1 says how far out), ``finite[..., 6]`` (H and ρ finite:
    no NaN or infinity came in), and the platform joints in the base frame."""

    angles_deg: np.ndarray
    solvable: np.ndarray
    in_limits: np.ndarray
    cosine: np.ndarray
    finite: np.ndarray
    platform_joints_base: np.ndarray

    @property
    def reachable(self) -> np.ndarray:
        return np.all(self.in_limits, axis=-1)


def platform_joints_in_base(joints: WorldJoints) -> np.ndarray:
    """Pi in the base frame: RBᵀ·(Pi − pB), shape ``[..., 6, 3]``."""
    relative = joints.upper - joints.base_origin[..., None, :]
    return np.einsum("...kj,...ik->...ij", joints.base_rotation, relative)


def crank_inverse_kinematics(config: PlatformConfig, upper_pose_deg, base_pose_deg=None) -> CrankSolution:
    """Crank angles θi (degrees) for poses ``[..., 6]``, closed form of docs/mathematics.md section 6.1 with branch σi."""
    joints = platform_joints_in_base(world_joints(config, upper_pose_deg, base_pose_deg))
    crank = config.crank
    a, s = crank.crank_length, crank.rod_length
    plane = crank_planes(config)
    delta = joints - base_joints(config.geometry)
    m = np.cos(plane) * delta[..., 0] + np.sin(plane) * delta[..., 1]
    dz = delta[..., 2]
    h = np.sum(delta * delta, axis=-1) + a * a - s * s
    rho = np.hypot(m, dz)
    with np.errstate(invalid="ignore", divide="ignore"):
        cosine = h / (2.0 * a * rho)
        solvable = (rho > 0.0) & (np.abs(cosine) <= 1.0)
        theta = np.arctan2(dz, m) + np.asarray(crank.branch) * np.arccos(np.where(solvable, cosine, np.nan))
    angles = wrap_crank_angle(config, np.degrees(theta))
    with np.errstate(invalid="ignore"):
        in_limits = solvable & (angles >= crank.angle_min_deg) & (angles <= crank.angle_max_deg)
    finite = np.isfinite(h) & np.isfinite(rho)
    return CrankSolution(angles, solvable & finite, in_limits & finite, cosine, finite, joints)


def crank_directions(config: PlatformConfig, angles_deg) -> tuple[np.ndarray, np.ndarray]:
    """(ui, ti): unit crank direction (cos θ cos φ, cos θ sin φ, sin θ) and its θ-derivative, base frame."""
    theta = np.radians(np.asarray(angles_deg, dtype=float))
    plane = crank_planes(config)
    c, s = np.cos(theta), np.sin(theta)
    direction = np.stack((c * np.cos(plane), c * np.sin(plane), s), axis=-1)
    tangent = np.stack((-s * np.cos(plane), -s * np.sin(plane), c), axis=-1)
    return direction, tangent


def crank_tips(config: PlatformConfig, angles_deg) -> np.ndarray:
    """Ai = Bi + a·(cos θi cos φi, cos θi sin φi, sin θi) in the base frame, shape ``[..., 6, 3]``."""
    direction, _ = crank_directions(config, angles_deg)
    return base_joints(config.geometry) + config.crank.crank_length * direction


def crank_tips_world(config: PlatformConfig, angles_deg, base_pose_deg=None) -> np.ndarray:
    """Ai in the world frame: RB·Ai + pB (the base pose default zero)."""
    tips = crank_tips(config, angles_deg)
    if base_pose_deg is None:
        return tips
    from stgen.reference.orientation import rotation

    position, angles = split_pose_rad(base_pose_deg)
    turned = np.einsum("...jk,...ik->...ij", rotation(config.platform.base_rotation, angles), tips)
    return turned + position[..., None, :]
