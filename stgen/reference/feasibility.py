"""Is a pose feasible, and which limit on which leg stops it (docs/mathematics.md sections 6.1, 6.2 workspace).

A pose is feasible when every leg is inside its limits:

* linear legs: stroke.min <= Di <= stroke.max (Di = li − l0, docs/mathematics.md section 2 / 6.2);
  with ``[joints]``: |γi|, |ψi| <= universal_max_deg, tilt <= spherical_tilt_max_deg;
* crank legs: a solution exists (ρ > 0, |H| <= 2aρ) and
  angle_min_deg <= θi <= angle_max_deg (docs/mathematics.md section 6.1).

:func:`feasibility` is vectorised over poses ``[..., 6]``; :func:`check_pose`
reports one pose as a list of violations naming leg (1-based) and limit.
When several limits are broken, :attr:`FeasibilityMap.binding` names the one
broken by the largest excess (mm for lengths, degrees for angles, taken as
comparable), leg and limit.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import IntEnum

import numpy as np

from stgen.config import PlatformConfig
from stgen.error_codes import ErrorCode, LegLimitError
from stgen.reference.crank import crank_inverse_kinematics
from stgen.reference.moving_base import legs, spherical_tilt, universal_joint_angles


class Limit(IntEnum):
    """The limits of a leg; 0 means none broken."""

    NONE = 0
    STROKE_MIN = 1
    STROKE_MAX = 2
    UNIVERSAL_GAMMA = 3
    UNIVERSAL_PSI = 4
    SPHERICAL_TILT = 5
    CRANK_NO_SOLUTION = 6
    CRANK_ANGLE_MIN = 7
    CRANK_ANGLE_MAX = 8
    NON_FINITE = 9

    @property
    def label(self) -> str:
        return self.name.lower()


@dataclass(frozen=True)
class FeasibilityMap:
    """Per pose and leg: ``excess[..., 6, len(Limit)]`` (> 0 where broken, in mm or degrees),
    ``values`` (the leg quantities by name, mm and degrees), and the verdicts."""

    excess: np.ndarray
    values: dict

    @property
    def broken(self) -> np.ndarray:
        return self.excess > 0.0

    @property
    def feasible(self) -> np.ndarray:
        return ~np.any(self.broken, axis=(-1, -2))

    @property
    def binding(self) -> tuple[np.ndarray, np.ndarray]:
        """(limit code, leg 1..6) of the largest excess per pose; (0, 0) where feasible."""
        flat = self.excess.reshape(self.excess.shape[:-2] + (-1,))
        index = np.argmax(flat, axis=-1)
        limit = np.where(self.feasible, 0, index % len(Limit))
        leg = np.where(self.feasible, 0, index // len(Limit) + 1)
        return limit, leg


def feasibility(config: PlatformConfig, upper_pose_deg, base_pose_deg=None) -> FeasibilityMap:
    """Evaluate every limit of every leg for poses ``[..., 6]`` (mm, degrees), vectorised."""
    upper = np.asarray(upper_pose_deg, dtype=float)
    shape = upper.shape[:-1] + (6, len(Limit))
    excess = np.full(shape, -np.inf)
    values: dict[str, np.ndarray] = {}
    with np.errstate(invalid="ignore"):
        if config.is_crank:
            solution = crank_inverse_kinematics(config, upper, base_pose_deg)
            angles = solution.angles_deg
            values["crank_angle_deg"] = angles
            values["crank_cosine"] = solution.cosine
            # |H/(2aρ)| − 1 says how far out (dimensionless); ρ = 0 gives inf or NaN: out.
            out = np.nan_to_num(np.maximum(np.abs(solution.cosine) - 1.0, 1e-12), nan=np.inf)
            excess[..., Limit.CRANK_NO_SOLUTION] = np.where(solution.solvable | ~solution.finite, -np.inf, out)
            excess[..., Limit.CRANK_ANGLE_MIN] = np.where(solution.solvable, config.crank.angle_min_deg - angles, -np.inf)
            excess[..., Limit.CRANK_ANGLE_MAX] = np.where(solution.solvable, angles - config.crank.angle_max_deg, -np.inf)
            finite = solution.finite
        else:
            state = legs(config, upper, base_pose_deg)
            extension = state.extensions
            values["extension_mm"] = extension
            excess[..., Limit.STROKE_MIN] = config.stroke.min - extension
            excess[..., Limit.STROKE_MAX] = extension - config.stroke.max
            finite = np.isfinite(extension)
            joints = config.joints
            if joints.any:
                gamma, psi = (np.degrees(angle) for angle in universal_joint_angles(config, state))
                tilt = np.degrees(spherical_tilt(state))
                values.update(universal_gamma_deg=gamma, universal_psi_deg=psi, spherical_tilt_deg=tilt)
                if joints.universal_max_deg is not None:
                    excess[..., Limit.UNIVERSAL_GAMMA] = np.abs(gamma) - joints.universal_max_deg
                    excess[..., Limit.UNIVERSAL_PSI] = np.abs(psi) - joints.universal_max_deg
                if joints.spherical_tilt_max_deg is not None:
                    excess[..., Limit.SPHERICAL_TILT] = tilt - joints.spherical_tilt_max_deg
                finite = finite & np.isfinite(gamma) & np.isfinite(psi)
    excess = np.where(np.isnan(excess), -np.inf, excess)
    excess[..., Limit.NON_FINITE] = np.where(finite, -np.inf, np.inf)
    excess[..., Limit.NONE] = -np.inf
    return FeasibilityMap(excess, values)


@dataclass(frozen=True)
class Violation:
    leg: int
    limit: Limit
    excess: float

    def __str__(self) -> str:
        return f"leg {self.leg}: {self.limit.label} exceeded by {self.excess:.6g}"


@dataclass(frozen=True)
class PoseCheck:
    feasible: bool
    violations: tuple[Violation, ...]


def check_pose(config: PlatformConfig, upper_pose_deg, base_pose_deg=None) -> PoseCheck:
    """One pose: feasible, and every broken limit naming its leg (1-based) and limit."""
    result = feasibility(config, np.asarray(upper_pose_deg, dtype=float).reshape(6),
                         None if base_pose_deg is None else np.asarray(base_pose_deg, dtype=float).reshape(6))
    violations = tuple(
        Violation(leg + 1, Limit(limit), float(result.excess[leg, limit]))
        for leg in range(6)
        for limit in range(len(Limit))
        if result.excess[leg, limit] > 0.0
    )
    return PoseCheck(not violations, violations)


#: Which ErrorID each limit reports, in the order a leg's limits are tested (docs/mathematics.md sections 6.1, 6.2).
LIMIT_ERRORS = (
    (Limit.STROKE_MIN, LegLimitError.STROKE),
    (Limit.STROKE_MAX, LegLimitError.STROKE),
    (Limit.UNIVERSAL_GAMMA, LegLimitError.UNIVERSAL_JOINT),
    (Limit.UNIVERSAL_PSI, LegLimitError.UNIVERSAL_JOINT),
    (Limit.SPHERICAL_TILT, LegLimitError.SPHERICAL_TILT),
    (Limit.CRANK_NO_SOLUTION, LegLimitError.CRANK_NO_SOLUTION),
    (Limit.CRANK_ANGLE_MIN, LegLimitError.CRANK_ANGLE),
    (Limit.CRANK_ANGLE_MAX, LegLimitError.CRANK_ANGLE),
)


def error_ids(result: FeasibilityMap) -> tuple[np.ndarray, np.ndarray]:
    """(ErrorID WORD, leg 1..6 or 0) per pose, as the variants' SP_InverseKinematics reports them:
    0 when feasible; 16#1003 when non-finite; else the lowest leg with a broken limit and its
    first limit in :data:`LIMIT_ERRORS` order (:class:`~stgen.error_codes.LegLimitError`)."""
    broken = result.broken
    ids = np.zeros(broken.shape[:-2], dtype=int)
    legs_out = np.zeros(broken.shape[:-2], dtype=int)
    for leg in range(6, 0, -1):  # lowest leg last, so it wins
        leg_id = np.zeros(broken.shape[:-2], dtype=int)
        for limit, error in reversed(LIMIT_ERRORS):  # first limit last, so it wins
            leg_id = np.where(broken[..., leg - 1, limit], error.error_id(leg), leg_id)
        ids = np.where(leg_id > 0, leg_id, ids)
        legs_out = np.where(leg_id > 0, leg, legs_out)
    non_finite = np.any(broken[..., Limit.NON_FINITE], axis=-1)
    ids = np.where(non_finite, ErrorCode.NON_FINITE.error_id, ids)
    legs_out = np.where(non_finite, 0, legs_out)
    return ids, legs_out
