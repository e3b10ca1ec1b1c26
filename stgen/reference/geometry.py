"""Joint positions and the platform rotation (docs/mathematics.md section 1, equations [2-4], [6,7]).

Angles inside this module are radians; the configuration stores the pair
angles in degrees (``phi_b_deg``, ``phi_p_deg``).
"""

from __future__ import annotations

import numpy as np

from stgen.config import GeometryConfig

LEG_COUNT = 6


def joint_angles(geometry: GeometryConfig) -> tuple[np.ndarray, np.ndarray]:
    """Polar angles of the base joints θi and platform joints ϕi, radians [4].

    For i = 1, 3, 5: θi = (2iπ − 3φb)/6 and ϕi = (2iπ − 3φp)/6;
    for i = 2, 4, 6: θi = θ(i−1) + φb and ϕi = ϕ(i−1) + φp.
    Array index k = i − 1 (leg 1 is index 0).
    """
    phi_b = np.radians(geometry.phi_b_deg)
    phi_p = np.radians(geometry.phi_p_deg)
    theta = np.empty(LEG_COUNT)
    phi = np.empty(LEG_COUNT)
    for i in (1, 3, 5):
        theta[i - 1] = (2.0 * i * np.pi - 3.0 * phi_b) / 6.0
        phi[i - 1] = (2.0 * i * np.pi - 3.0 * phi_p) / 6.0
        theta[i] = theta[i - 1] + phi_b
        phi[i] = phi[i - 1] + phi_p
    return theta, phi


def base_joints(geometry: GeometryConfig) -> np.ndarray:
    """Universal-joint centres Bi = (rb cos θi, rb sin θi, hb) in the base frame [2], shape [6,3]."""
    theta, _ = joint_angles(geometry)
    return np.column_stack(
        (geometry.rb * np.cos(theta), geometry.rb * np.sin(theta), np.full(LEG_COUNT, geometry.hb))
    )


def platform_joints(geometry: GeometryConfig) -> np.ndarray:
    """Spherical-joint centres Pi = (rp cos ϕi, rp sin ϕi, hp) in the platform frame [3], shape [6,3]."""
    _, phi = joint_angles(geometry)
    return np.column_stack(
        (geometry.rp * np.cos(phi), geometry.rp * np.sin(phi), np.full(LEG_COUNT, geometry.hp))
    )


def rotation_matrix(alpha, beta, gamma) -> np.ndarray:
    """R = Rz(α)·Ry(β)·Rx(γ) [6,7], angles in radians, broadcast over any shape.

    Returns an array of shape ``shape + (3, 3)`` with the entries of [7]::

        r11 = cα cβ   r12 = cα sβ sγ − sα cγ   r13 = cα sβ cγ + sα sγ
        r21 = sα cβ   r22 = sα sβ sγ + cα cγ   r23 = sα sβ cγ − cα sγ
        r31 = −sβ     r32 = cβ sγ              r33 = cβ cγ
    """
    alpha, beta, gamma = np.broadcast_arrays(
        np.asarray(alpha, dtype=float), np.asarray(beta, dtype=float), np.asarray(gamma, dtype=float)
    )
    ca, sa = np.cos(alpha), np.sin(alpha)
    cb, sb = np.cos(beta), np.sin(beta)
    cg, sg = np.cos(gamma), np.sin(gamma)
    rows = (
        (ca * cb, ca * sb * sg - sa * cg, ca * sb * cg + sa * sg),
        (sa * cb, sa * sb * sg + ca * cg, sa * sb * cg - ca * sg),
        (-sb, cb * sg, cb * cg),
    )
    return np.stack([np.stack(row, axis=-1) for row in rows], axis=-2)


def pose_to_radians(poses_deg) -> np.ndarray:
    """Copy of ``poses[..., 6]`` with α, β, γ converted from degrees to radians."""
    poses = np.array(poses_deg, dtype=float)
    poses[..., 3:] = np.radians(poses[..., 3:])
    return poses


def pose_to_degrees(poses_rad) -> np.ndarray:
    """Copy of ``poses[..., 6]`` with α, β, γ converted from radians to degrees."""
    poses = np.array(poses_rad, dtype=float)
    poses[..., 3:] = np.degrees(poses[..., 3:])
    return poses
