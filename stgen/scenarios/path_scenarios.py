"""Paths and playback as scenarios for SP_Controller (issue 12, docs/mathematics.md section 6.3).

A path scenario writes the curve into SpPath... and gives SpPathStart; a
playback scenario gives SpPlaybackStart to a controller rendered with the
table of a CSV (``stgen generate --playback``). The timeline SP_Controller
follows, and the reference poses of every scan:

* the edge scan is the first call of the planning pass; the pass takes
  K = ceil(N / SpPlanSamplesPerScan) calls (N: PlanSamples of a path, the
  task-period samples of the table of a playback), the pose held;
* the call that ends the pass starts the cycloidal lead-in (TRJ_Cycloidal with
  the scenario's limits) from the start pose to the motion's first pose: the
  lead-in's edge is K - 1 scans after the command's edge;
* the motion's clock starts in the scan after the lead-in's last call: its call
  m outputs the pose at t = m·dt (the path: ``stgen.reference.paths.sample`` at
  the duration ``plan_path`` plans with the same PlanSamples; the playback:
  ``stgen.reference.playback.evaluate``) up to the first m with m·dt >= T, then
  that end pose is held for ``settle_seconds``.

The four path scenarios use the curves of ``stgen plan``'s figures
(:data:`stgen.reference.paths.STUDY_PATHS`) at roll = pitch = 35°
(:data:`~stgen.reference.paths.STUDY_TILT`), centre (0, 0, 240) mm, blend law
b = 0.1, the shortest duration (limits :data:`PATH_LIMITS`): epitrochoid R = 60, r = 20, d = 30 mm;
epicycloid R = 60, r = 20 mm; hypocycloid R = 100, r = 25 mm (each closed,
φ_end = 2π); Archimedean spiral a = 10 mm, b = 5 mm/rad, three turns.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from stgen.config import PlatformConfig, TrajectoryConfig
from stgen.reference.paths import PLAN_SAMPLES, STUDY_PATHS, STUDY_TILT, PathSpec, describe, plan_path, sample
from stgen.reference.playback import PlaybackTable, evaluate, read_playback_csv
from stgen.scenarios.definitions import STUDY_START_POSE, Scenario
from stgen.scenarios.path_inputs import trj_path_inputs

#: SpPlanSamplesPerScan's default (SP_ControllerGlobals).
SAMPLES_PER_SCAN = 200
#: Standstill at the end pose recorded after a path or playback, s.
END_HOLD_SECONDS = 0.5


@dataclass(frozen=True)
class PathMotion:
    """The path ``spec`` through SpPathStart, planned on ``plan_samples`` points."""

    spec: PathSpec
    plan_samples: int = PLAN_SAMPLES
    samples_per_scan: int = SAMPLES_PER_SCAN


@dataclass(frozen=True)
class PlaybackMotion:
    """The recorded motion of the CSV file ``csv_path`` (t,x,y,z,alpha,beta,gamma) through SpPlaybackStart."""

    csv_path: str
    samples_per_scan: int = SAMPLES_PER_SCAN

    @property
    def table(self) -> PlaybackTable:
        return _read_table(self.csv_path)


@lru_cache(maxsize=8)
def _read_table(path: str) -> PlaybackTable:
    return read_playback_csv(path)


PlannedMotion = (PathMotion, PlaybackMotion)


def is_planned(motion) -> bool:
    """A motion SP_Controller plans before it moves (a path or a playback)."""
    return isinstance(motion, PlannedMotion)


#: Limits of the path scenarios: the defaults, but 9 deg/s for alpha, beta, gamma (they only bind in the
#: lead-in; TRJ_Path keeps the orientation fixed). 35 deg at the default 10 deg/s is 7,000 task periods
#: exactly, a tie on Done that the last bit of the located pose decides; 70/9 s is off the grid.
PATH_LIMITS = TrajectoryConfig(angular_velocity=9.0)


def path_scenario(spec: PathSpec, name: str, plan_samples: int = PLAN_SAMPLES) -> Scenario:
    return Scenario(name=name, title=f"Path: {describe(spec)}", start_pose=STUDY_START_POSE,
                    motion=PathMotion(spec, plan_samples), limits=PATH_LIMITS, settle_seconds=END_HOLD_SECONDS)


#: Start pose of the playback scenario: the study's, 0.37 mm higher. A lead-in of a whole number of task
#: periods (90 mm at 100 mm/s is 1,800 periods exactly) is a tie that the last bit of the located pose
#: decides; 89.63 mm (1,792.6 periods) is not.
PLAYBACK_START_POSE = (0.0, 0.0, 150.37, 0.0, 0.0, 0.0)


def playback_scenario(csv_path: str, name: str = "playback", title: str | None = None) -> Scenario:
    return Scenario(name=name, title=title or f"Playback of {csv_path}", start_pose=PLAYBACK_START_POSE,
                    motion=PlaybackMotion(str(csv_path)), settle_seconds=END_HOLD_SECONDS)


#: One scenario per curve family, at the study's tilt (see the module).
PATH_SCENARIOS = tuple(
    path_scenario(dataclasses.replace(spec, orientation=STUDY_TILT), f"path_{spec.family}")
    for spec in STUDY_PATHS
)


def shortened_path(scenario: Scenario, fraction: float) -> Scenario:
    """The same curve over ``fraction`` of its parameter range (a path scenario; others unchanged)."""
    motion = scenario.motion
    if not isinstance(motion, PathMotion):
        return scenario
    spec = dataclasses.replace(motion.spec, phi_end=fraction * motion.spec.end)
    return dataclasses.replace(scenario, motion=dataclasses.replace(motion, spec=spec),
                               title=f"{scenario.title} (quick: {fraction:g} of the curve)")


#: PlanSamples of the quick paths (the planning pass is the costliest part of a short run).
QUICK_PLAN_SAMPLES = 2001


def quick_path(scenario: Scenario, fraction: float) -> Scenario:
    """``fraction`` of the curve, starting at the path's first pose (no lead-in), planned on
    :data:`QUICK_PLAN_SAMPLES` points: for ``stgen demo --quick``."""
    short = shortened_path(scenario, fraction)
    if not isinstance(short.motion, PathMotion):
        return short
    start = tuple(float(v) for v in first_pose(short.motion, None))
    return dataclasses.replace(short, start_pose=start,
                               motion=dataclasses.replace(short.motion, plan_samples=QUICK_PLAN_SAMPLES))


#: The recorded motion of the playback scenario: a JONSWAP sea state (stgen.scenarios.sea_state) at 10 Hz.
SEA_STATE_RATE_HZ = 10.0


def write_sea_state_csv(path, seconds: float) -> None:
    """``seconds`` of the JONSWAP sea state sampled at 10 Hz, as a playback CSV (t,x,y,z,alpha,beta,gamma)."""
    from pathlib import Path

    from stgen.scenarios.sea_state import jonswap_motion, write_csv

    t, poses = jonswap_motion(duration_s=seconds, rate_hz=SEA_STATE_RATE_HZ)
    write_csv(Path(path), t, poses)


def sea_state_scenario(csv_path, seconds: float) -> Scenario:
    return playback_scenario(str(csv_path), title=f"Playback of a recorded JONSWAP sea state: {seconds:g} s sampled "
                                                  f"at {SEA_STATE_RATE_HZ:g} Hz (Tp = 8 s, gamma = 3.3)")


# --- the timeline (see the module) -------------------------------------------------------------


def path_duration(motion: PathMotion, config: PlatformConfig) -> float:
    """T of the path as TRJ_Path plans it (the shortest, rounded up to whole periods, or the spec's)."""
    return plan_path(motion.spec, config, samples=2, plan_samples=motion.plan_samples).duration


def playback_sample_count(table: PlaybackTable, period: float) -> int:
    """Task-period samples t_n = n·dt <= the table's end, as TRJ_Playback counts them."""
    count = int(round(table.duration / period))
    if count * period > table.duration:
        count -= 1
    return count + 1


def planning_calls(motion, config: PlatformConfig) -> int:
    """K: calls of the planning pass, the edge's call included."""
    if isinstance(motion, PathMotion):
        samples = motion.plan_samples
    else:
        samples = playback_sample_count(motion.table, config.task.period_s)
    return -(-samples // motion.samples_per_scan)


def motion_duration(motion, config: PlatformConfig) -> float:
    """T: the path's planned duration or the table's last knot time, s."""
    if isinstance(motion, PathMotion):
        return path_duration(motion, config)
    return motion.table.duration


def run_calls(motion, config: PlatformConfig) -> int:
    """M: the first call m with m·dt >= T (it outputs the end pose and sets Done)."""
    period = config.task.period_s
    duration = motion_duration(motion, config)
    calls = max(int(math.floor(duration / period)) - 1, 0)
    while calls * period < duration:
        calls += 1
    return calls


def motion_poses(motion, config: PlatformConfig, calls) -> np.ndarray:
    """Poses (mm, deg) of the motion's calls m = ``calls`` (t = m·dt, the end pose past T)."""
    t = np.asarray(calls, dtype=float) * config.task.period_s
    if isinstance(motion, PathMotion):
        return sample(motion.spec, path_duration(motion, config), t).poses
    return evaluate(motion.table, np.minimum(t, motion.table.duration))[0]


def first_pose(motion, config: PlatformConfig) -> np.ndarray:
    """The target of the lead-in: the path at φ = 0, or the table's first knot."""
    if isinstance(motion, PathMotion):
        return sample(motion.spec, 1.0, np.zeros(1)).poses[0]
    return np.array(motion.table.poses[0], dtype=float)


# --- commands -------------------------------------------------------------------------------


def command_planned(sim, motion) -> None:
    """Write the path's parameters and SpPathStart := TRUE (or SpPlaybackStart): the edge is seen in the next scan."""
    g = sim.globals
    g["SpPlanSamplesPerScan"] = motion.samples_per_scan
    if isinstance(motion, PlaybackMotion):
        g["SpPlaybackStart"] = True
        return
    inputs = trj_path_inputs(motion.spec, motion.plan_samples, motion.samples_per_scan)
    for name in ("Family", "FixedRadius", "RollingRadius", "PenDistance", "SpiralStart", "SpiralPitch",
                 "ParameterEnd", "Centre", "Orientation", "Law", "BlendFraction", "Duration", "PlanSamples"):
        g[f"SpPath{name}"] = inputs[name]
    g["SpPathStart"] = True


def release_planned(sim) -> None:
    sim.globals["SpPathStart"] = False
    sim.globals["SpPlaybackStart"] = False


def playback_table(scenario: Scenario) -> PlaybackTable | None:
    """The table the controller must be rendered with (None unless a playback scenario)."""
    motion = scenario.motion
    return motion.table if isinstance(motion, PlaybackMotion) else None
