"""The study's motions as scenarios for SP_Controller (issue 5, SPEC 4).

* ``point_to_point``: from (0, 0, 150, 0, 0, 0), +100 mm in X, Y and Z at
  20 mm/s and +6°, +6°, +10° in α, β, γ at 2 °/s. Read as ONE synchronised
  move to (100, 100, 250, 6, 6, 10): the study's numbers give the same
  duration for both groups (2·100/20 = 10 s and 2·10/2 = 10 s), which only
  matters if the coordinates move together. Acceleration and jerk keep the
  configured defaults (they do not bind: 1.1 s and 0.7 s for 100 mm).
* ``airy_wave``: the study's regular wave (A = 3 mm, Tw = 10 s, L = 100 m,
  φ = 10°) around the centre pose (0, 0, 150, 0, 0, 0), 60 s.
* ``random_wave``: the five-component random wave of SPEC 4 around the same
  centre, 60 s.

A wave scenario starts with the controller's lead-in (a cycloidal move with
the configured limits from the start pose to the wave's pose at t = 0); its
duration is the lead-in plus ``wave_seconds`` of wave.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

from stgen.config import TrajectoryConfig
from stgen.reference.wave import AIRY, RANDOM_5, OceanWave

#: The study's start pose: 150 mm above home, level (mm, degrees).
STUDY_START_POSE = (0.0, 0.0, 150.0, 0.0, 0.0, 0.0)


@dataclass(frozen=True)
class PointToPointMotion:
    """A cycloidal move to ``target_pose`` (mm, degrees)."""

    target_pose: tuple[float, ...]


@dataclass(frozen=True)
class WaveMotion:
    """Lead-in to the wave's first pose, then ``wave_seconds`` of ``wave`` around ``centre_pose``."""

    wave: OceanWave
    centre_pose: tuple[float, ...]
    wave_seconds: float


@dataclass(frozen=True)
class Scenario:
    """One run of SP_Controller: power on at ``start_pose``, then one command.

    ``limits``: the motion limits written to SpLinearxxx / SpAngularxxx (None:
    the configuration's). ``settle_seconds``: scans run after a move ends.
    """

    name: str
    title: str
    start_pose: tuple[float, ...]
    motion: PointToPointMotion | WaveMotion
    limits: TrajectoryConfig | None = None
    settle_seconds: float = 0.5

    def with_wave_seconds(self, seconds: float) -> "Scenario":
        """The same scenario with a shorter (or longer) wave; unchanged for a move."""
        if not isinstance(self.motion, WaveMotion):
            return self
        return dataclasses.replace(self, motion=dataclasses.replace(self.motion, wave_seconds=seconds))


POINT_TO_POINT = Scenario(
    name="point_to_point",
    title="Point to point: +100 mm in X, Y, Z at 20 mm/s; +6, +6, +10 deg at 2 deg/s",
    start_pose=STUDY_START_POSE,
    motion=PointToPointMotion(target_pose=(100.0, 100.0, 250.0, 6.0, 6.0, 10.0)),
    limits=TrajectoryConfig(linear_velocity=20.0, angular_velocity=2.0),
)

AIRY_WAVE = Scenario(
    name="airy_wave",
    title="Airy wave: A = 3 mm, Tw = 10 s, L = 100 m, phase 10 deg",
    start_pose=STUDY_START_POSE,
    motion=WaveMotion(wave=AIRY, centre_pose=STUDY_START_POSE, wave_seconds=60.0),
)

RANDOM_WAVE = Scenario(
    name="random_wave",
    title="Random wave of five components (SPEC 4)",
    start_pose=STUDY_START_POSE,
    motion=WaveMotion(wave=RANDOM_5, centre_pose=STUDY_START_POSE, wave_seconds=60.0),
)

#: The study's three scenarios, in the order ``stgen demo`` runs them.
SCENARIOS = (POINT_TO_POINT, AIRY_WAVE, RANDOM_WAVE)


def scenario_by_name(name: str) -> Scenario:
    for scenario in SCENARIOS:
        if scenario.name == name:
            return scenario
    raise KeyError(f"no scenario {name!r}; known: {', '.join(s.name for s in SCENARIOS)}")
