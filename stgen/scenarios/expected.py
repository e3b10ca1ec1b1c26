"""What SP_Controller must command in every scan of a scenario, from the NumPy reference.

The timeline is fixed by the controller's specification, not read from the
run. The first command's rising edge is seen in scan ``command_scan``
(1-based); every move is planned by :func:`planned_moves`:

* before the first edge the platform holds the start pose;
* a move is ``cycloidal_pose(start, target, T, j·dt)`` in the scan j calls
  after its edge (j = 0 on the edge: the start pose, never a jump), T from
  ``cycloidal_duration`` with the scenario's limits, for j = 0..n, where n is
  the first call with j·dt/T >= 1 (the pose is then exactly the target, as
  the reference computes it, and the controller is back in STANDBY);
* a point-to-point motion holds that pose for ``settle_seconds``; the next
  move's edge is the scan after, and it starts from the pose held;
* a wave's only move is the lead-in to ``wave_pose(wave, 0, centre, fade_s=T_F)``
  (the centre pose: the wave fades in from rest); the wave clock starts in the
  scan after the lead-in's last call: scan ``command_scan + n + 1 + m`` commands
  ``wave_pose(wave, m·dt, centre, fade_s=T_F)``, T_F from ``fade_in_duration``
  with the scenario's limits.

A path or a playback (:mod:`stgen.scenarios.path_scenarios`): the planning
pass, then its lead-in, then the motion, then its end pose held.

Cylinder positions come from the reference IK of those poses.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from stgen.config import PlatformConfig
from stgen.reference.cycloidal import cycloidal_duration, cycloidal_pose, executed_duration
from stgen.reference.kinematics import inverse_kinematics
from stgen.reference.wave import fade_in_duration, wave_pose
from stgen.scenarios import path_scenarios
from stgen.scenarios.actuators import actuator_positions
from stgen.scenarios.definitions import PointToPointMotion, Scenario, WaveMotion


@dataclass(frozen=True)
class PlannedMove:
    """One cycloidal move of a scenario as the reference plans it (poses in mm and degrees)."""

    start: np.ndarray   # where it starts: the scenario's start pose or the previous move's end
    target: np.ndarray
    end: np.ndarray     # the set-point of its last call (tau = 1): the target, to rounding
    duration: float     # T, s
    calls: int          # n: the call that outputs ``end`` (Done); the move spans calls 0..n
    edge: int           # scans from the first command's edge to this move's edge


def calls_until_done(duration: float, period: float) -> int:
    """n: the first call count with n·period/T >= 1, as TRJ_Cycloidal decides Done (0 for T = 0)."""
    if duration <= 0.0:
        return 0
    calls = max(int(np.floor(duration / period)) - 1, 0)
    while (calls * period) / duration < 1.0:
        calls += 1
    return calls


def move_targets(scenario: Scenario, config: PlatformConfig | None = None) -> list[np.ndarray]:
    """The targets of the scenario's cycloidal moves: the moves, or the wave's pose at t = 0 (the lead-in)."""
    motion = scenario.motion
    if isinstance(motion, PointToPointMotion):
        return [np.asarray(target, dtype=float) for target in motion.targets]
    if path_scenarios.is_planned(motion):
        return [path_scenarios.first_pose(motion, config)]
    return [wave_pose(motion.wave, 0.0, motion.centre_pose, fade_s=wave_fade_duration(scenario, config))]


def scenario_limits(scenario: Scenario, config: PlatformConfig | None):
    """The trajectory limits SP_Controller runs the scenario with: the scenario's, else the configuration's."""
    if scenario.limits is not None:
        return scenario.limits
    return config.trajectory if config is not None else PlatformConfig.default().trajectory


def commanded_config(scenario: Scenario, config: PlatformConfig) -> PlatformConfig:
    """``config`` with the trajectory limits SP_Controller runs the scenario with."""
    return dataclasses.replace(config, trajectory=scenario_limits(scenario, config))


def wave_fade_duration(scenario: Scenario, config: PlatformConfig | None) -> float:
    """T_F of a wave scenario (0 for a point-to-point motion)."""
    motion = scenario.motion
    if not isinstance(motion, WaveMotion):
        return 0.0
    return fade_in_duration(motion.wave, scenario_limits(scenario, config))


def settle_scans(scenario: Scenario, config: PlatformConfig) -> int:
    """Standstill after each move of a point-to-point motion, scans (none after a wave's lead-in)."""
    if isinstance(scenario.motion, WaveMotion):
        return 0
    return int(round(scenario.settle_seconds / config.task.period_s))


def planned_moves(scenario: Scenario, config: PlatformConfig) -> list[PlannedMove]:
    """Every cycloidal move of the scenario, in order, each from where the previous ended."""
    period = config.task.period_s
    limits = scenario_limits(scenario, config)
    hold = settle_scans(scenario, config)
    start = np.asarray(scenario.start_pose, dtype=float)
    edge = lead_in_delay(scenario, config)
    moves = []
    for target in move_targets(scenario, config):
        duration = executed_duration(float(cycloidal_duration(target - start, limits)), period)
        calls = calls_until_done(duration, period)
        # SP_Controller starts the next move from the set-point this last call output.
        end = cycloidal_pose(start, target, duration, calls * period)
        moves.append(PlannedMove(start, target, end, duration, calls, edge))
        start = end
        edge += calls + 1 + hold
    return moves


def lead_in_delay(scenario: Scenario, config: PlatformConfig) -> int:
    """Scans from the command's edge to the first move's edge: K - 1 after a planning pass, else 0."""
    if path_scenarios.is_planned(scenario.motion):
        return path_scenarios.planning_calls(scenario.motion, config) - 1
    return 0


def command_edges(scenario: Scenario, config: PlatformConfig) -> list[int]:
    """Scans from the first command's edge to each command's edge (a path or playback: one command)."""
    if path_scenarios.is_planned(scenario.motion):
        return [0]
    return [move.edge for move in planned_moves(scenario, config)]


def motion_scans(scenario: Scenario, config: PlatformConfig) -> int:
    """Scans from the first command's edge to the end of the scenario (edge included)."""
    moves = planned_moves(scenario, config)
    last = moves[-1]
    after_last = last.edge + last.calls + 1
    motion = scenario.motion
    if isinstance(motion, WaveMotion):
        return after_last + int(round(motion.wave_seconds / config.task.period_s))
    if path_scenarios.is_planned(motion):
        after_last += path_scenarios.run_calls(motion, commanded_config(scenario, config)) + 1
    return after_last + settle_scans(scenario, config)


def expected_poses(scenario: Scenario, config: PlatformConfig, command_scan: int, scans: int) -> np.ndarray:
    """Pose set-point of scans 1..``scans`` (row k-1 is scan k), mm and degrees."""
    period = config.task.period_s
    poses = np.tile(np.asarray(scenario.start_pose, dtype=float), (scans, 1))
    since_first = np.arange(1, scans + 1) - command_scan  # scans since the first command's edge
    moves = planned_moves(scenario, config)
    for move in moves:  # in order: a later move overwrites the hold of the one before
        calls = since_first - move.edge  # j: calls since this move's edge
        moving = (calls >= 0) & (calls <= move.calls)
        poses[moving] = cycloidal_pose(move.start, move.target, move.duration, calls[moving].astype(float) * period)
        poses[calls > move.calls] = move.end
    motion = scenario.motion
    if isinstance(motion, WaveMotion):
        wave_calls = since_first - moves[0].calls - 1  # m: the wave clock runs from the scan after the lead-in
        riding = wave_calls >= 0
        poses[riding] = wave_pose(motion.wave, wave_calls[riding].astype(float) * period, motion.centre_pose,
                                  fade_s=wave_fade_duration(scenario, config))
    if path_scenarios.is_planned(motion):
        # m: the motion's clock runs from the scan after the lead-in; past its last call the end pose is held.
        run_calls = since_first - moves[0].edge - moves[0].calls - 1
        running = run_calls >= 0
        planned = commanded_config(scenario, config)  # TRJ_Path plans with the limits written to SpLinear...
        last = path_scenarios.run_calls(motion, planned)
        poses[running] = path_scenarios.motion_poses(motion, planned, np.minimum(run_calls[running], last))
    return poses


def expected_cylinders(poses: np.ndarray, config: PlatformConfig) -> np.ndarray:
    """Reference IK of every pose: cylinder positions q_i, mm (a platform variant: its actuator
    coordinates, the base at rest at the world origin, :mod:`stgen.scenarios.actuators`)."""
    if not config.is_default_kind:
        return actuator_positions(config, poses)
    return np.asarray(inverse_kinematics(config.geometry, poses, config.stroke).positions, dtype=float)
