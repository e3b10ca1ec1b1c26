"""The actuator coordinate of every leg, by platform kind: what SP_Controller commands on axis i.

* the study's kind: cylinder position q_i, mm (docs/mathematics.md section 2);
* a crank platform: crank angle theta_i, DEGREES (docs/mathematics.md section 6.1);
* a moving base: stroke D_i = l_i - l0, mm, of the upper pose in the world frame
  over the base pose (docs/mathematics.md section 6.2).

Each from the NumPy reference; the axes' software limits are the same
coordinate's limits (stroke, or crank angles).
"""

from __future__ import annotations

import numpy as np

from stgen.config import PlatformConfig


def actuator_positions(config: PlatformConfig, poses, base_poses=None) -> np.ndarray:
    """Reference actuator coordinates of ``poses`` [..., 6] (mm, degrees), [..., 6]."""
    poses = np.asarray(poses, dtype=float)
    if config.is_crank:
        from stgen.reference.crank import crank_inverse_kinematics

        return np.asarray(crank_inverse_kinematics(config, poses, base_poses).angles_deg, dtype=float)
    if not config.is_default_kind:
        from stgen.reference.moving_base import legs

        return np.asarray(legs(config, poses, base_poses).extensions, dtype=float)
    from stgen.reference.kinematics import inverse_kinematics

    return np.asarray(inverse_kinematics(config.geometry, poses, config.stroke).positions, dtype=float)


def actuator_limits(config: PlatformConfig) -> tuple[float, float]:
    """The axes' software limits: crank angles in degrees, else the stroke in mm."""
    if config.is_crank:
        return config.crank.angle_min_deg, config.crank.angle_max_deg
    return config.stroke.min, config.stroke.max


def actuator_unit(config: PlatformConfig) -> str:
    """``deg`` for crank angles, ``mm`` for cylinders."""
    return "deg" if config.is_crank else "mm"
