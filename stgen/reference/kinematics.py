"""Inverse kinematics, the FK residual and its analytic Jacobian (docs/mathematics.md sections 2 and 3).

Poses are arrays ``[..., 6]`` = (x, y, z, α, β, γ). The public IK takes
degrees (the interface unit); :func:`residual` and :func:`jacobian` take
radians because Newton–Raphson iterates in radians (docs/mathematics.md section 3).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from stgen.config import GeometryConfig, StrokeConfig
from stgen.error_codes import ErrorCode
from stgen.reference.geometry import base_joints, platform_joints, pose_to_radians, rotation_matrix


@dataclass(frozen=True)
class LegVectors:
    """The quantities of [5–12] for every leg of every pose (shapes ``[..., 6]`` or ``[..., 6, 3]``).

    ``rotated_joints`` holds (ui, vi, wi) = R·Pi, ``offsets`` holds
    di = (x̄i, ȳi, z̄i) = (x − Bix, y − Biy, z + h0 − Biz), ``legs`` holds
    Li = R·Pi + di and ``lengths`` holds li = |Li|.
    """

    rotation: np.ndarray
    rotated_joints: np.ndarray
    offsets: np.ndarray
    legs: np.ndarray
    lengths: np.ndarray


def leg_vectors(geometry: GeometryConfig, poses_rad) -> LegVectors:
    """Leg vectors Li = R·Pi + di for poses in radians [5–11]; broadcasts over leading axes."""
    poses = np.asarray(poses_rad, dtype=float)
    rotation = rotation_matrix(poses[..., 3], poses[..., 4], poses[..., 5])
    rotated = np.einsum("...jk,ik->...ij", rotation, platform_joints(geometry))
    centre = poses[..., None, :3] + np.array([0.0, 0.0, geometry.h0])
    offsets = centre - base_joints(geometry)
    legs = rotated + offsets
    return LegVectors(rotation, rotated, offsets, legs, np.sqrt(np.sum(legs * legs, axis=-1)))


@dataclass(frozen=True)
class InverseKinematicsResult:
    """Cylinder positions of many poses.

    ``positions[..., 6]``: qi = li − l0 in mm [12]; ``leg_lengths[..., 6]``: li;
    ``in_stroke[..., 6]``: True where stroke.min <= qi <= stroke.max (docs/mathematics.md section 2);
    ``status[...]``: :class:`ErrorCode` values per pose (OK, UNREACHABLE, NON_FINITE).
    """

    positions: np.ndarray
    leg_lengths: np.ndarray
    in_stroke: np.ndarray
    status: np.ndarray

    @property
    def reachable(self) -> np.ndarray:
        """True for poses whose six legs are all inside the stroke."""
        return self.status == ErrorCode.OK


def inverse_kinematics(
    geometry: GeometryConfig, poses_deg, stroke: StrokeConfig | None = None
) -> InverseKinematicsResult:
    """Cylinder positions qi = |R·Pi + di| − l0 [5–12] for poses ``[..., 6]`` in mm and degrees.

    ``stroke`` defaults to :class:`StrokeConfig` defaults (docs/mathematics.md section 1, table). A leg
    outside the stroke is reported in ``in_stroke``, never clipped.
    """
    stroke = stroke if stroke is not None else StrokeConfig()
    lengths = leg_vectors(geometry, pose_to_radians(poses_deg)).lengths
    positions = lengths - geometry.l0
    with np.errstate(invalid="ignore"):
        in_stroke = (positions >= stroke.min) & (positions <= stroke.max)
    finite = np.all(np.isfinite(positions), axis=-1)
    status = np.where(
        ~finite,
        int(ErrorCode.NON_FINITE),
        np.where(np.all(in_stroke, axis=-1), int(ErrorCode.OK), int(ErrorCode.UNREACHABLE)),
    )
    return InverseKinematicsResult(positions, lengths, in_stroke, status)


def residual(geometry: GeometryConfig, poses_rad, positions) -> np.ndarray:
    """FK residual fi(a) = |Li(a)|² − (qi + l0)² [13–18], pose angles in radians, shape ``[..., 6]``."""
    legs = leg_vectors(geometry, poses_rad).legs
    target = np.asarray(positions, dtype=float) + geometry.l0
    return np.sum(legs * legs, axis=-1) - target * target


def jacobian(geometry: GeometryConfig, poses_rad) -> np.ndarray:
    """Analytic Jacobian ∂fi/∂a of :func:`residual`, rows [36], shape ``[..., 6, 6]``.

    Columns are (x, y, z, α, β, γ) with angles in radians::

        ∂fi/∂x = 2(x̄i + ui)   ∂fi/∂y = 2(ȳi + vi)   ∂fi/∂z = 2(z̄i + wi)
        ∂fi/∂α = 2(ȳi·ui − x̄i·vi)
        ∂fi/∂β = 2[(x̄i cα + ȳi sα)·wi − (cβ Pix + sβ sγ Piy + sβ cγ Piz)·z̄i]
        ∂fi/∂γ = 2[(x̄i r13 + ȳi r23 + z̄i r33)·Piy − (x̄i r12 + ȳi r22 + z̄i r32)·Piz]
    """
    poses = np.asarray(poses_rad, dtype=float)
    vectors = leg_vectors(geometry, poses)
    joints = platform_joints(geometry)
    px, py, pz = joints[:, 0], joints[:, 1], joints[:, 2]
    u, v, w = (vectors.rotated_joints[..., k] for k in range(3))
    xb, yb, zb = (vectors.offsets[..., k] for k in range(3))
    r = vectors.rotation[..., None, :, :]  # broadcast over the six legs
    ca, sa = np.cos(poses[..., 3])[..., None], np.sin(poses[..., 3])[..., None]
    cb, sb = np.cos(poses[..., 4])[..., None], np.sin(poses[..., 4])[..., None]
    cg, sg = np.cos(poses[..., 5])[..., None], np.sin(poses[..., 5])[..., None]
    columns = (
        2.0 * (xb + u),
        2.0 * (yb + v),
        2.0 * (zb + w),
        2.0 * (yb * u - xb * v),
        2.0 * ((xb * ca + yb * sa) * w - (cb * px + sb * sg * py + sb * cg * pz) * zb),
        2.0
        * (
            (xb * r[..., 0, 2] + yb * r[..., 1, 2] + zb * r[..., 2, 2]) * py
            - (xb * r[..., 0, 1] + yb * r[..., 1, 1] + zb * r[..., 2, 1]) * pz
        ),
    )
    return np.stack(columns, axis=-1)
