"""Run a scenario: SP_Controller and six axes in the simulator, every scan
recorded and held against the NumPy reference (:mod:`stgen.scenarios.expected`).

The commands are given at the scans the reference timeline plans (a command
refused because the controller was not ready shows as SpRefusalID and as an
error against the reference); ``SpMoveStart`` and ``SpWaveStart`` are written
TRUE before their edge scan and FALSE after it.

The comparison takes the command position of every axis after every scan
(what motion processing applied, i.e. what ``MC_SyncMoveAbsolute`` commanded)
and the reference IK of the reference trajectory for that scan.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from stgen.config import PlatformConfig
from stgen.scenarios.definitions import PointToPointMotion, Scenario, WaveMotion
from stgen.scenarios import path_scenarios
from stgen.scenarios.expected import command_edges, expected_cylinders, expected_poses, motion_scans
from stgen.scenarios.setpoint_limits import SetpointLimitCheck, check_setpoint_limits
from stgen.scenarios.simulation import ControllerSimulation

#: Largest allowed |commanded - reference| cylinder position, mm (issue 5).
MAX_ERROR_MM = 1e-6

#: Scans allowed for power-on and locating the pose.
POWER_ON_SCANS = 200

#: Scans run between two progress reports.
CHUNK_SCANS = 1000

Progress = Callable[[int, int], None]


@dataclass
class ScenarioResult:
    """One scenario run, scan by scan (row k-1 is scan k)."""

    scenario: Scenario
    period_s: float
    command_scans: tuple[int, ...]  # scan of every command's rising edge (1-based)
    commanded: np.ndarray          # axis command positions (Cmd.Pos, after any saturation by the axis), mm
    expected: np.ndarray           # reference IK of the reference trajectory, mm
    setpoint_pose: np.ndarray      # SpSetpointPose, mm and deg
    expected_pose: np.ndarray      # reference trajectory, mm and deg
    state: np.ndarray              # SpState
    fault_id: np.ndarray           # SpFaultID
    refusal_id: np.ndarray         # SpRefusalID
    axis_fault: np.ndarray         # True where some axis is in ErrorStop
    following_error: np.ndarray    # command - actual position of every axis, mm
    setpoint: np.ndarray = None    # SpCylinderSetpoint: the Position handed to MC_SyncMoveAbsolute, mm
    sync: np.ndarray = None        # True where SP_Controller executed MC_SyncMoveAbsolute in that scan
    limits: SetpointLimitCheck = None  # velocity and acceleration of ``setpoint`` against the actuator
    commanded_limits: SetpointLimitCheck = None  # the same of ``commanded`` (Cmd.Pos), reported apart
    runtime_faults: list = field(default_factory=list)
    wall_seconds: float = 0.0
    servo_lag_s: float = 0.0      # first-order lag of Act.Pos behind Cmd.Pos of the simulated axes
    move_durations_s: tuple[float, ...] = ()  # SpMoveDuration after each move's edge (a wave: the lead-in)
    nj_time: object = None         # estimated NJ501 time per scan (st_runtime.controller.TaskTime)
    state_names: dict[int, str] = field(default_factory=dict)  # SpState value -> SP_STATE_xxx name

    @property
    def command_scan(self) -> int:
        """Scan of the first command's rising edge."""
        return self.command_scans[0]

    @property
    def scans(self) -> int:
        return len(self.state)

    @property
    def duration_s(self) -> float:
        """Simulated time, s."""
        return self.scans * self.period_s

    @property
    def time_s(self) -> np.ndarray:
        """The simulated clock during every scan, s: (k - 1) * period for scan k,
        the time the program's timers see and `stgen run --trace` writes."""
        return np.arange(self.scans) * self.period_s

    @property
    def error(self) -> np.ndarray:
        return np.abs(self.commanded - self.expected)

    @property
    def max_error_mm(self) -> float:
        return float(self.error.max())

    @property
    def controller_faults(self) -> int:
        """Scans in which SpFaultID was set."""
        return int(np.count_nonzero(self.fault_id))

    @property
    def fault_count(self) -> int:
        """Controller faults, axis errors and runtime faults, counted by scans."""
        return self.controller_faults + int(np.count_nonzero(self.axis_fault)) + len(self.runtime_faults)

    @property
    def realtime_factor(self) -> float:
        return self.duration_s / self.wall_seconds if self.wall_seconds > 0 else float("inf")

    @property
    def refused_commands(self) -> int:
        """Scans in which SpRefusalID reported a refused command."""
        return int(np.count_nonzero(self.refusal_id))

    @property
    def passed(self) -> bool:
        return (self.max_error_mm <= MAX_ERROR_MM and self.fault_count == 0 and self.refused_commands == 0
                and (self.limits is None or self.limits.passed))


class _Recorder:
    """Copies what is compared into preallocated arrays at the end of every scan."""

    def __init__(self, sim: ControllerSimulation, capacity: int):
        from st_runtime.native import mangle

        self.sim = sim
        self.globals_obj = sim.globals.obj
        self.attrs = {name: mangle(name) for name in
                      ("SpSetpointPose", "SpCylinderSetpoint", "SpState", "SpFaultID", "SpRefusalID")}
        self.program_obj = sim.program.obj
        self.sync_attr = mangle("SyncExecute")
        self.commanded = np.empty((capacity, 6))
        self.setpoint = np.empty((capacity, 6))
        self.sync = np.empty(capacity, dtype=bool)
        self.pose = np.empty((capacity, 6))
        self.state = np.empty(capacity, dtype=np.int64)
        self.fault_id = np.empty(capacity, dtype=np.int64)
        self.refusal_id = np.empty(capacity, dtype=np.int64)
        self.axis_fault = np.empty(capacity, dtype=bool)
        self.following_error = np.empty((capacity, 6))
        self.count = 0

    def __call__(self, controller) -> None:
        row = self.count
        axes = self.sim.axes
        self.commanded[row] = [axis.cmd_pos for axis in axes]
        g = self.globals_obj
        self.pose[row] = getattr(g, self.attrs["SpSetpointPose"])
        self.setpoint[row] = getattr(g, self.attrs["SpCylinderSetpoint"])
        self.sync[row] = getattr(self.program_obj, self.sync_attr)
        self.state[row] = getattr(g, self.attrs["SpState"])
        self.fault_id[row] = getattr(g, self.attrs["SpFaultID"])
        self.refusal_id[row] = getattr(g, self.attrs["SpRefusalID"])
        self.axis_fault[row] = any(axis.fault_active for axis in axes)
        self.following_error[row] = [axis.following_error for axis in axes]
        self.count = row + 1


def command_move(sim: ControllerSimulation, target) -> None:
    """SpTargetPose := ``target``, SpMoveStart := TRUE: the edge is seen in the next scan."""
    sim.set_pose("SpTargetPose", target)
    sim.globals["SpMoveStart"] = True


def command_wave(sim: ControllerSimulation, motion: WaveMotion) -> None:
    """The wave's parameters and SpWaveStart := TRUE: the edge is seen in the next scan."""
    g = sim.globals
    components = motion.wave.components
    # The component arrays are as long as the generated code declares them (TRJ_WAVE_COMPONENTS_MAX).
    padding = [0.0] * (len(g["SpWaveAmplitude"]) - len(components))
    g["SpWaveComponentCount"] = len(components)
    g["SpWaveAmplitude"] = [c.amplitude_mm for c in components] + padding
    g["SpWavePeriod"] = [c.period_s for c in components] + padding
    g["SpWaveLength"] = [c.wavelength for c in components] + padding
    g["SpWavePhase"] = [c.phase_deg for c in components] + padding
    g["SpWaveLengthUnit"] = motion.wave.wavelength_unit_mm
    g["SpWaveHeading"] = motion.wave.heading_deg
    sim.set_pose("SpWaveCentrePose", motion.centre_pose)
    g["SpWaveStart"] = True


def command_scenario(sim: ControllerSimulation, scenario: Scenario, move: int = 0) -> None:
    """Write the scenario's command number ``move`` (a wave has one) into the globals."""
    motion = scenario.motion
    if isinstance(motion, PointToPointMotion):
        command_move(sim, motion.targets[move])
    elif isinstance(motion, WaveMotion):
        command_wave(sim, motion)
    elif path_scenarios.is_planned(motion):
        path_scenarios.command_planned(sim, motion)
    else:  # pragma: no cover - a new motion kind without a command
        raise TypeError(f"unknown motion {motion!r}")


def release_commands(sim: ControllerSimulation) -> None:
    """SpMoveStart and SpWaveStart back to FALSE, so the next command is a new edge."""
    sim.globals["SpMoveStart"] = False
    sim.globals["SpWaveStart"] = False
    path_scenarios.release_planned(sim)


def apply_limits(sim: ControllerSimulation, scenario: Scenario) -> None:
    if scenario.limits is None:
        return
    limits = scenario.limits
    for name, value in (
        ("SpLinearVelocity", limits.linear_velocity),
        ("SpLinearAcceleration", limits.linear_acceleration),
        ("SpLinearJerk", limits.linear_jerk),
        ("SpAngularVelocity", limits.angular_velocity),
        ("SpAngularAcceleration", limits.angular_acceleration),
        ("SpAngularJerk", limits.angular_jerk),
    ):
        sim.globals[name] = value


def _run_to(sim: ControllerSimulation, scan: int, total: int, progress: Progress | None) -> None:
    """Scan until ``scan`` scans have run, reporting progress every CHUNK_SCANS."""
    while sim.scan_count < scan:
        sim.run(min(CHUNK_SCANS - sim.scan_count % CHUNK_SCANS, scan - sim.scan_count))
        if progress is not None and (sim.scan_count % CHUNK_SCANS == 0 or sim.scan_count == total):
            progress(sim.scan_count, total)


def run_scenario(
    scenario: Scenario,
    config: PlatformConfig | None = None,
    progress: Progress | None = None,
    servo_lag_s: float = 0.0,
) -> ScenarioResult:
    """Power on at the start pose, give the commands at their planned scans, run to the end,
    compare with the reference.

    ``servo_lag_s``: the axes' servo lag (0: ideal axes, the actual position is the command).
    """
    config = config if config is not None else PlatformConfig.default()
    sim = ControllerSimulation(config, scenario.start_pose, servo_lag_s, playback=path_scenarios.playback_table(scenario))
    after_command = motion_scans(scenario, config)
    recorder = _Recorder(sim, POWER_ON_SCANS + after_command)
    sim.plc.controller.add_observer(recorder, reads_only=True)
    apply_limits(sim, scenario)

    started = time.perf_counter()
    sim.power_on(POWER_ON_SCANS)
    first = sim.scan_count + 1
    total = first - 1 + after_command
    command_scans, durations = [], []
    for index, offset in enumerate(command_edges(scenario, config)):
        edge = first + offset
        _run_to(sim, edge - 1, total, progress)
        command_scenario(sim, scenario, index)
        sim.run(1)
        release_commands(sim)
        command_scans.append(edge)
        durations.append(float(sim.globals["SpMoveDuration"]))
    _run_to(sim, total, total, progress)
    wall = time.perf_counter() - started

    count = recorder.count
    poses = expected_poses(scenario, config, first, count)
    return recorded_result(sim, recorder, scenario, tuple(command_scans), poses, expected_cylinders(poses, config),
                           wall, servo_lag_s, tuple(durations))


def recorded_result(sim: ControllerSimulation, recorder: _Recorder, scenario, command_scans: tuple[int, ...],
                    expected_pose: np.ndarray, expected: np.ndarray, wall: float, servo_lag_s: float,
                    move_durations: tuple[float, ...] = ()) -> ScenarioResult:
    """The :class:`ScenarioResult` of a finished run: what ``recorder`` took, the reference
    (``expected_pose`` and its axis positions ``expected``, one row per recorded scan) and the
    set-points' velocity and acceleration against the actuator's limits."""
    count = recorder.count
    config = sim.config
    sync = recorder.sync[:count]
    actuator = config.actuator
    period = config.task.period_s
    return ScenarioResult(
        scenario=scenario,
        period_s=period,
        command_scans=command_scans,
        commanded=recorder.commanded[:count],
        expected=expected,
        setpoint_pose=recorder.pose[:count],
        expected_pose=expected_pose,
        state=recorder.state[:count],
        fault_id=recorder.fault_id[:count],
        refusal_id=recorder.refusal_id[:count],
        axis_fault=recorder.axis_fault[:count],
        following_error=recorder.following_error[:count],
        setpoint=recorder.setpoint[:count],
        sync=sync,
        limits=check_setpoint_limits(recorder.setpoint[:count], period, actuator.max_velocity,
                                     actuator.max_acceleration, sync),
        commanded_limits=check_setpoint_limits(recorder.commanded[:count], period, actuator.max_velocity,
                                               actuator.max_acceleration, sync),
        runtime_faults=list(sim.runtime_faults),
        wall_seconds=wall,
        servo_lag_s=servo_lag_s,
        move_durations_s=move_durations,
        nj_time=sim.plc.controller.time_report()[0],
        state_names={value: name for name, value in sim.codes.items() if name.startswith("SP_STATE_")},
    )
