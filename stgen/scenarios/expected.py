"""What SP_Controller must command in every scan of a scenario, from the NumPy reference.

The timeline is fixed by the controller's specification, not read from the
run: the command's rising edge is seen in scan ``command_scan`` (1-based), and

* before it the platform holds the start pose;
* a move is ``cycloidal_pose(start, target, T, j·dt)`` in the scan j calls
  after the edge (j = 0 on the edge: the start pose, never a jump), T from
  ``cycloidal_duration`` with the scenario's limits; after it the target;
* a wave first runs the lead-in, the same cycloid from the start pose to
  ``wave_pose(wave, 0, centre)``, for j = 0..n, where n is the first call with
  j·dt/T >= 1 (the pose is then exactly the wave's first pose); the wave clock
  starts in the next scan: scan ``command_scan + n + 1 + m`` commands
  ``wave_pose(wave, m·dt, centre)``.

Cylinder positions come from the reference IK of those poses.
"""

from __future__ import annotations

import numpy as np

from stgen.config import PlatformConfig
from stgen.reference.cycloidal import cycloidal_duration, cycloidal_pose
from stgen.reference.kinematics import inverse_kinematics
from stgen.reference.wave import wave_pose
from stgen.scenarios.definitions import PointToPointMotion, Scenario, WaveMotion


def calls_until_done(duration: float, period: float) -> int:
    """n: the first call count with n·period/T >= 1, as TRJ_Cycloidal decides Done (0 for T = 0)."""
    if duration <= 0.0:
        return 0
    calls = max(int(np.floor(duration / period)) - 1, 0)
    while (calls * period) / duration < 1.0:
        calls += 1
    return calls


def move_duration(scenario: Scenario, config: PlatformConfig) -> float:
    """T of the scenario's cycloidal move (the lead-in for a wave), s."""
    limits = scenario.limits if scenario.limits is not None else config.trajectory
    return float(cycloidal_duration(np.subtract(first_target(scenario), scenario.start_pose), limits))


def first_target(scenario: Scenario) -> np.ndarray:
    """The target of the cycloidal move: the move's target, or the wave's pose at t = 0."""
    motion = scenario.motion
    if isinstance(motion, PointToPointMotion):
        return np.asarray(motion.target_pose, dtype=float)
    return wave_pose(motion.wave, 0.0, motion.centre_pose)


def motion_scans(scenario: Scenario, config: PlatformConfig) -> int:
    """Scans from the command's edge to the end of the scenario (edge included)."""
    period = config.task.period_s
    lead = calls_until_done(move_duration(scenario, config), period) + 1
    motion = scenario.motion
    if isinstance(motion, WaveMotion):
        return lead + int(round(motion.wave_seconds / period))
    return lead + int(round(scenario.settle_seconds / period))


def expected_poses(scenario: Scenario, config: PlatformConfig, command_scan: int, scans: int) -> np.ndarray:
    """Pose set-point of scans 1..``scans`` (row k-1 is scan k), mm and degrees."""
    period = config.task.period_s
    start = np.asarray(scenario.start_pose, dtype=float)
    target = first_target(scenario)
    duration = move_duration(scenario, config)
    poses = np.tile(start, (scans, 1))
    calls = np.arange(1, scans + 1) - command_scan  # j: calls since the edge
    moving = calls >= 0
    if isinstance(scenario.motion, WaveMotion):
        lead_end = calls_until_done(duration, period)
        moving = moving & (calls <= lead_end)
        riding = calls > lead_end
        wave_calls = (calls[riding] - lead_end - 1).astype(float)
        motion = scenario.motion
        poses[riding] = wave_pose(motion.wave, wave_calls * period, motion.centre_pose)
    poses[moving] = cycloidal_pose(start, target, duration, calls[moving].astype(float) * period)
    return poses


def expected_cylinders(poses: np.ndarray, config: PlatformConfig) -> np.ndarray:
    """Reference IK of every pose: cylinder positions q_i, mm."""
    return np.asarray(inverse_kinematics(config.geometry, poses, config.stroke).positions, dtype=float)
