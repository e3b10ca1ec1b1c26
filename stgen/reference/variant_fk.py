"""FK residual and Jacobian of the platform variants, for the same Newton–Raphson (docs/mathematics.md sections 3, 6.1, 6.2).

Unknown: the upper pose a = (x, y, z, a1, a2, a3) (mm and radians, angles in
the order of ``platform.platform_rotation``); known: the base pose and, per
leg, a centre Ci and a length ρi:

* linear legs: Ci = Oi = RB·Oi_B + pB and ρi = qi + l0 (measured cylinder positions);
* crank legs: Ci = Ai (the crank tips from the measured crank angles, world frame)
  and ρi = s (docs/mathematics.md section 6.1: "fi with Ai in place of Bi").

fi(a) = |Pi(a) − Ci|² − ρi², Pi(a) = RU(a)·Pi_U + (x, y, h0 + z);
∂fi/∂(x, y, z) = 2·ri and ∂fi/∂ak = 2·ri·(∂RU/∂ak·Pi_U), ri = Pi − Ci.
For the default platform (ZYX, fixed base) these are docs/mathematics.md section 3's fi and rows [36].

:class:`VariantModel` plugs into :class:`stgen.reference.forward.NewtonRaphsonSolver`.
"""

from __future__ import annotations

import numpy as np

from stgen.config import PlatformConfig, SolverConfig
from stgen.reference.crank import crank_tips_world
from stgen.reference.geometry import platform_joints
from stgen.reference.moving_base import world_joints
from stgen.reference.orientation import rotation, rotation_partials


class VariantModel:
    """fi and ∂fi/∂a for measured actuator values ``measured[6]`` (mm of stroke, or crank degrees)."""

    def __init__(self, config: PlatformConfig, measured, base_pose_deg=None) -> None:
        self.config = config
        measured = np.asarray(measured, dtype=float).reshape(6)
        if config.is_crank:
            self.centres = crank_tips_world(config, measured, base_pose_deg)
            self.radii = np.full(6, config.crank.rod_length)
        else:
            self.centres = world_joints(config, np.zeros(6), base_pose_deg).base
            self.radii = measured + config.geometry.l0

    def _legs(self, poses_rad) -> np.ndarray:
        poses = np.asarray(poses_rad, dtype=float)
        turned = rotation(self.config.platform.platform_rotation, poses[..., 3:])
        upper = np.einsum("...jk,ik->...ij", turned, platform_joints(self.config.geometry))
        origin = poses[..., :3] + np.array([0.0, 0.0, self.config.geometry.h0])
        return upper + origin[..., None, :] - self.centres

    def residual(self, poses_rad) -> np.ndarray:
        legs = self._legs(poses_rad)
        return np.sum(legs * legs, axis=-1) - self.radii**2

    def jacobian(self, poses_rad) -> np.ndarray:
        poses = np.asarray(poses_rad, dtype=float)
        legs = self._legs(poses)
        partials = rotation_partials(self.config.platform.platform_rotation, poses[..., 3:])
        moved = np.einsum("...kab,ib->...kia", partials, platform_joints(self.config.geometry))
        angular = 2.0 * np.einsum("...ia,...kia->...ik", legs, moved)
        return np.concatenate((2.0 * legs, angular), axis=-1)


def variant_forward_kinematics(config: PlatformConfig, measured, start_pose_deg=None, base_pose_deg=None,
                               solver: SolverConfig | None = None):
    """Upper pose (mm, degrees) from measured cylinder positions (mm) or crank angles (degrees),
    by docs/mathematics.md section 3's Newton–Raphson with :class:`VariantModel`; a
    :class:`~stgen.reference.forward.ForwardKinematicsResult`."""
    from stgen.reference.forward import NewtonRaphsonSolver

    machine = NewtonRaphsonSolver(config.geometry, solver if solver is not None else config.solver,
                                  lambda values: VariantModel(config, values, base_pose_deg))
    machine.start(measured, start_pose_deg)
    while not machine.scan():
        pass
    return machine.result()
