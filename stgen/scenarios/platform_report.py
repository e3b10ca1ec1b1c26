"""Run a platform scenario (:mod:`stgen.scenarios.platforms`) and say whether every limit holds on
every scan (docs/mathematics.md sections 6.1, 6.2).

Per scan, from what SP_Controller commanded: the set-point pose (world frame) over the
base pose of that scan through the NumPy feasibility test (stroke or crank angle,
universal-joint angles, spherical tilt, per leg), and the velocity and acceleration of the
axis set-points against the actuator's limits (:mod:`stgen.scenarios.setpoint_limits`; on a
crank platform in degrees/s and degrees/s²). A streamed motion that starts at speed steps
its set-point velocity in the scan after the edge; that step is reported apart
(``start_step``), the limits of the motion itself from the edge on (``motion_limits``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from stgen.config import PlatformConfig
from stgen.reference.feasibility import Limit, feasibility
from stgen.scenarios.platforms import PlatformScenario
from stgen.scenarios.runner import Progress, ScenarioResult, run_scenario
from stgen.scenarios.setpoint_limits import SetpointLimitCheck, check_setpoint_limits
from stgen.scenarios.track import TrackScenario, run_track_scenario

#: Largest allowed |commanded - reference| axis position of a platform scenario (mm, or degrees on a crank).
PLATFORM_MAX_ERROR = 1e-9


@dataclass(frozen=True)
class PlatformLimits:
    """The pose limits over every scan: feasible throughout, the first broken (row, limit, leg), extremes."""

    feasible: bool
    first_violation: tuple[int, str, int] | None   # (1-based scan, limit, leg)
    actuator_range: tuple[float, float]            # commanded axis positions, mm or degrees
    max_universal_gamma: float | None              # |γi|, degrees (linear legs with joint limits)
    max_universal_psi: float | None
    max_tilt: float | None
    joint_angles: dict                             # per scan [n, 6]: gamma, psi, tilt (degrees), empty for a crank


@dataclass
class PlatformRun:
    """One platform scenario: the controller run, the base pose of every scan and the limit verdicts."""

    item: PlatformScenario
    config: PlatformConfig
    result: ScenarioResult
    base_pose: np.ndarray
    pose_limits: PlatformLimits
    motion_limits: SetpointLimitCheck   # v and a of the set-points from the first command's scan on (a
    #                                     stream's first acceleration, its start step, needs the scan before)
    start_step: SetpointLimitCheck      # v and a of the whole run, the start of a stream included

    @property
    def name(self) -> str:
        return self.item.name

    @property
    def unit(self) -> str:
        return "deg" if self.config.is_crank else "mm"

    @property
    def limits_hold(self) -> bool:
        return self.pose_limits.feasible and self.motion_limits.passed

    @property
    def passed(self) -> bool:
        r = self.result
        return (r.max_error_mm <= PLATFORM_MAX_ERROR and r.fault_count == 0 and r.refused_commands == 0
                and self.limits_hold)


def pose_limits(config: PlatformConfig, poses: np.ndarray, base_poses: np.ndarray | None,
                commanded: np.ndarray) -> PlatformLimits:
    result = feasibility(config, poses, base_poses if config.moving_base else None)
    feasible = result.feasible
    first = None
    if not feasible.all():
        row = int(np.argmin(feasible))
        limit, leg = result.binding
        first = (row + 1, Limit(int(limit[row])).label, int(leg[row]))
    values = result.values
    angles = {}
    if "universal_gamma_deg" in values:
        angles = {"gamma": values["universal_gamma_deg"], "psi": values["universal_psi_deg"],
                  "tilt": values["spherical_tilt_deg"]}

    def largest(key):
        return float(np.abs(angles[key]).max()) if key in angles else None

    return PlatformLimits(bool(feasible.all()), first, (float(commanded.min()), float(commanded.max())),
                          largest("gamma"), largest("psi"), largest("tilt"), angles)


def run_platform_scenario(item: PlatformScenario, progress: Progress | None = None,
                          servo_lag_s: float = 0.0) -> PlatformRun:
    """Run ``item`` on its example platform and check every limit on every scan."""
    config = item.config()
    if isinstance(item.scenario, TrackScenario):
        track = run_track_scenario(item.scenario, config, progress, servo_lag_s)
        result, base, first_command = track.result, track.base_pose, track.stream_scan
    else:
        result = run_scenario(item.scenario, config, progress, servo_lag_s)
        base, first_command = np.zeros_like(result.setpoint_pose), result.command_scan
    actuator, period = config.actuator, config.task.period_s
    from_command = result.sync & (np.arange(result.scans) >= first_command - 1)
    return PlatformRun(
        item, config, result, base,
        pose_limits(config, result.setpoint_pose, base, result.commanded),
        check_setpoint_limits(result.setpoint, period, actuator.max_velocity, actuator.max_acceleration,
                              from_command),
        check_setpoint_limits(result.setpoint, period, actuator.max_velocity, actuator.max_acceleration,
                              result.sync),
    )
