"""Streamed set-points through SP_Controller on a platform variant (docs/mathematics.md sections 6.1, 6.2).

A :class:`TrackScenario` is a motion given as functions of time (the upper
platform's world pose, and on a moving base the deck's pose, with analytic
rates). The controller is powered on at the motion's first pose (the axes
start where the reference IK puts them, the base at its first pose), holds it
for ``hold_seconds`` in STANDBY, then follows the stream: the scan that sees
the rising edge of ``SpTrackStart`` commands ``upper(0)``, scan m after it
``upper(m·dt)``, with ``SpBasePose = base(m·dt)`` written before the same
scan (the IMU), ``base(0)`` before the edge. That timeline is the reference:
every commanded axis position is compared with the reference IK of it.
"""

from __future__ import annotations

import dataclasses
import time
from dataclasses import dataclass
from typing import Callable

import numpy as np

from stgen.config import PlatformConfig
from stgen.scenarios.actuators import actuator_positions
from stgen.scenarios.runner import CHUNK_SCANS, POWER_ON_SCANS, Progress, ScenarioResult, _Recorder, recorded_result
from stgen.scenarios.simulation import ControllerSimulation

#: t [n] -> (value, rate, acceleration), each [n, 6] (mm, degrees, s), as :mod:`stgen.reference.study_motions`.
Trajectory = Callable[[np.ndarray], tuple[np.ndarray, np.ndarray, np.ndarray]]


@dataclass(frozen=True)
class TrackScenario:
    """``upper`` (world frame, z from h0) for ``duration_s``, on a base that follows ``base`` (None: fixed)."""

    name: str
    title: str
    upper: Trajectory
    duration_s: float
    base: Trajectory | None = None
    hold_seconds: float = 0.05

    @property
    def start_pose(self) -> tuple[float, ...]:
        return tuple(float(v) for v in self.upper(np.zeros(1))[0][0])

    @property
    def start_base_pose(self) -> tuple[float, ...] | None:
        return None if self.base is None else tuple(float(v) for v in self.base(np.zeros(1))[0][0])

    def shortened(self, seconds: float) -> "TrackScenario":
        """The first ``seconds`` of the motion."""
        return dataclasses.replace(self, duration_s=min(seconds, self.duration_s),
                                   title=f"{self.title} (first {min(seconds, self.duration_s):g} s)")


@dataclass
class TrackRun:
    """A track scenario's :class:`ScenarioResult` with the base pose of every scan (zeros on a fixed base)."""

    result: ScenarioResult
    base_pose: np.ndarray          # the base pose SpBasePose held in every scan, mm and deg
    stream_scan: int               # scan of SpTrackStart's rising edge (1-based)


def stream_times(scenario: TrackScenario, period_s: float) -> np.ndarray:
    """m·dt of every streamed set-point, m = 0 .. duration / dt."""
    return np.arange(int(round(scenario.duration_s / period_s)) + 1) * period_s


def run_track_scenario(scenario: TrackScenario, config: PlatformConfig, progress: Progress | None = None,
                       servo_lag_s: float = 0.0) -> TrackRun:
    """Power on at the first pose, hold, stream the motion, compare every scan with the reference."""
    period = config.task.period_s
    times = stream_times(scenario, period)
    upper = scenario.upper(times)[0]
    base = scenario.base(times)[0] if scenario.base is not None else np.zeros_like(upper)
    hold = int(round(scenario.hold_seconds / period))
    sim = ControllerSimulation(config, scenario.start_pose, servo_lag_s,
                               base[0] if scenario.base is not None else None)
    recorder = _Recorder(sim, POWER_ON_SCANS + hold + len(times))
    sim.plc.controller.add_observer(recorder, reads_only=True)
    started = time.perf_counter()
    sim.power_on(POWER_ON_SCANS)
    sim.run(hold)
    edge = sim.scan_count + 1
    total = edge - 1 + len(times)
    sim.globals["SpTrackStart"] = True
    stream_base = config.moving_base
    for index in range(len(times)):
        sim.set_pose("SpTrackPose", upper[index])
        if stream_base:
            sim.set_pose("SpBasePose", base[index])
        sim.run(1)
        if progress is not None and (sim.scan_count % CHUNK_SCANS == 0 or sim.scan_count == total):
            progress(sim.scan_count, total)
    wall = time.perf_counter() - started

    count = recorder.count
    expected_pose = np.tile(upper[0], (count, 1))
    base_pose = np.tile(base[0], (count, 1))
    expected_pose[edge - 1:] = upper[: count - edge + 1]
    base_pose[edge - 1:] = base[: count - edge + 1]
    expected = actuator_positions(config, expected_pose, base_pose if stream_base else None)
    result = recorded_result(sim, recorder, scenario, (edge,), expected_pose, expected, wall, servo_lag_s)
    return TrackRun(result, base_pose, edge)
