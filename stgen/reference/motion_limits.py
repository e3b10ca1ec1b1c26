"""A sampled motion's actuator positions, rates and accelerations against the platform's limits.

Shared by the path planner (:mod:`stgen.reference.paths`) and playback
(:mod:`stgen.reference.playback`): give the pose samples with their analytic
rates and accelerations; the legs come from :func:`actuator_rates` (docs/mathematics.md section 6.3).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from stgen.config import PlatformConfig
from stgen.reference.actuator_rates import ActuatorRates, actuator_rates


@dataclass(frozen=True)
class MotionCheck:
    """Samples ``t[n]``, poses/rates/accelerations ``[n, 6]`` and their legs; positions qi = li − l0."""

    t: np.ndarray
    poses: np.ndarray = field(repr=False)
    rates: np.ndarray = field(repr=False)
    accelerations: np.ndarray = field(repr=False)
    legs: ActuatorRates = field(repr=False)
    positions: np.ndarray = field(repr=False)

    def extremes(self) -> dict[str, np.ndarray]:
        """Per actuator: min/max position (mm), max |velocity| (mm/s), max |acceleration| (mm/s²)."""
        return {
            "position_min": self.positions.min(axis=0),
            "position_max": self.positions.max(axis=0),
            "velocity_max": np.abs(self.legs.velocities).max(axis=0),
            "acceleration_max": np.abs(self.legs.accelerations).max(axis=0),
        }

    def breaches(self, config: PlatformConfig) -> list[tuple[int, str, float, float]]:
        """(leg 1..6, what, worst value, its limit) of every actuator limit broken, in leg order.

        ``what`` is ``stroke min``, ``stroke max``, ``velocity`` or ``acceleration``.
        """
        ext = self.extremes()
        found = []
        for leg in range(6):
            checks = (
                ("stroke min", ext["position_min"][leg], config.stroke.min, ext["position_min"][leg] < config.stroke.min),
                ("stroke max", ext["position_max"][leg], config.stroke.max, ext["position_max"][leg] > config.stroke.max),
                ("velocity", ext["velocity_max"][leg], config.actuator.max_velocity,
                 ext["velocity_max"][leg] > config.actuator.max_velocity),
                ("acceleration", ext["acceleration_max"][leg], config.actuator.max_acceleration,
                 ext["acceleration_max"][leg] > config.actuator.max_acceleration),
            )
            found += [(leg + 1, what, float(value), float(limit)) for what, value, limit, broken in checks if broken]
        return found


def check_motion(config: PlatformConfig, t, poses, rates, accelerations) -> MotionCheck:
    """The legs of a sampled motion (mm, degrees and their rates) as a :class:`MotionCheck`."""
    legs = actuator_rates(config.geometry, poses, rates, accelerations)
    return MotionCheck(np.asarray(t, dtype=float), np.asarray(poses), np.asarray(rates),
                       np.asarray(accelerations), legs, legs.lengths - config.geometry.l0)
