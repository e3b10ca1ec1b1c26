"""The study's motions as scenarios for SP_Controller (issue 5, docs/mathematics.md section 4).

* ``point_to_point``: the study's point-to-point moves, each a single
  coordinate from the start pose (0, 0, 150, 0, 0, 0): +100 mm in X, in Y and
  in Z at 20 mm/s, +6° in α, +6° in β and +10° in γ at 2 °/s. Every move goes
  out and back to the start pose before the next, all in one controller run
  (twelve ``SpMoveStart`` commands, ``settle_seconds`` of standstill after
  each move). Velocity governs the cycloidal duration T = 2h/v: 10 s for
  100 mm at 20 mm/s and for 10° at 2 °/s, 6 s for 6°; the configured
  acceleration and jerk do not bind (√(2π·100/500) = 1.1 s and
  ∛(4π²·100/5000) = 0.7 s for 100 mm, likewise for 10° at 50 °/s², 500 °/s³).
* ``airy_wave``: the study's regular wave (A = 3 mm, Tw = 10 s, L = 100 m,
  φ = 10°) around the centre pose (0, 0, 150, 0, 0, 0), 60 s.
* ``random_wave``: the five-component random wave of docs/mathematics.md section 4 around the same
  centre, 60 s.

A wave scenario starts with the controller's lead-in (a cycloidal move with
the configured limits from the start pose to the wave's pose at t = 0); its
duration is the lead-in plus ``wave_seconds`` of wave.

:data:`SYNCHRONISED_MOVE` (all six coordinates in one move to
(100, 100, 250, 6, 6, 10)) is not one of the study's scenarios; the tests run
it to check a move of every coordinate at once.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

from stgen.config import TrajectoryConfig
from stgen.reference.wave import AIRY, RANDOM_5, OceanWave

#: The study's start pose: 150 mm above home, level (mm, degrees).
STUDY_START_POSE = (0.0, 0.0, 150.0, 0.0, 0.0, 0.0)


#: The study's point-to-point moves: (pose coordinate index, displacement), mm or degrees.
STUDY_MOVES = ((0, 100.0), (1, 100.0), (2, 100.0), (3, 6.0), (4, 6.0), (5, 10.0))

#: Pose coordinate names, in pose order (x, y, z in mm; α, β, γ in degrees).
COORDINATE_NAMES = ("x", "y", "z", "α", "β", "γ")


@dataclass(frozen=True)
class PointToPointMotion:
    """Cycloidal moves to ``targets`` (mm, degrees) in order, each from where the previous ended."""

    targets: tuple[tuple[float, ...], ...]


def out_and_back(start_pose, moves) -> tuple[tuple[float, ...], ...]:
    """The targets of single-coordinate moves from ``start_pose`` and back to it.

    ``moves``: (coordinate index, displacement) pairs; returns
    (start + h1, start, start + h2, start, ...).
    """
    start = tuple(float(v) for v in start_pose)
    targets = []
    for coordinate, displacement in moves:
        out = list(start)
        out[coordinate] += displacement
        targets += [tuple(out), start]
    return tuple(targets)


def describe_move(start, target) -> str:
    """A short label of a move: the coordinates that change and by how much ("z +100 mm", "α -6°")."""
    parts = []
    for index, (a, b) in enumerate(zip(start, target)):
        if b != a:
            unit = " mm" if index < 3 else "°"
            parts.append(f"{COORDINATE_NAMES[index]} {b - a:+g}{unit}")
    return ", ".join(parts) if parts else "no move"


@dataclass(frozen=True)
class WaveMotion:
    """Lead-in to the wave's first pose, then ``wave_seconds`` of ``wave`` around ``centre_pose``."""

    wave: OceanWave
    centre_pose: tuple[float, ...]
    wave_seconds: float


@dataclass(frozen=True)
class Scenario:
    """One run of SP_Controller: power on at ``start_pose``, then the motion's commands.

    ``limits``: the motion limits written to SpLinearxxx / SpAngularxxx (None:
    the configuration's). ``settle_seconds``: standstill after each move of a
    point-to-point motion (before the next command, and at the end).
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

    def shortened(self, wave_seconds: float, move_fraction: float, settle_seconds: float) -> "Scenario":
        """A quick version: a wave of ``wave_seconds``; point-to-point moves of
        ``move_fraction`` of each displacement (same limits, so shorter moves)
        with ``settle_seconds`` of standstill after each."""
        if isinstance(self.motion, WaveMotion):
            return self.with_wave_seconds(wave_seconds)
        start = self.start_pose
        targets = tuple(tuple(a + move_fraction * (b - a) for a, b in zip(start, target))
                        for target in self.motion.targets)
        return dataclasses.replace(self, motion=PointToPointMotion(targets=targets),
                                   settle_seconds=settle_seconds,
                                   title=f"{self.title} (quick: {move_fraction:g} of each move)")


#: The study's limits of the point-to-point moves: 20 mm/s and 2 °/s (acceleration and jerk: the defaults).
STUDY_MOVE_LIMITS = TrajectoryConfig(linear_velocity=20.0, angular_velocity=2.0)

POINT_TO_POINT = Scenario(
    name="point_to_point",
    title="Point to point from (0, 0, 150, 0, 0, 0), out and back: +100 mm in x, y, z at 20 mm/s; "
          "+6°, +6°, +10° in α, β, γ at 2°/s",
    start_pose=STUDY_START_POSE,
    motion=PointToPointMotion(targets=out_and_back(STUDY_START_POSE, STUDY_MOVES)),
    limits=STUDY_MOVE_LIMITS,
)

SYNCHRONISED_MOVE = Scenario(
    name="synchronised_move",
    title="One synchronised move to (100, 100, 250, 6, 6, 10) at 20 mm/s and 2°/s",
    start_pose=STUDY_START_POSE,
    motion=PointToPointMotion(targets=((100.0, 100.0, 250.0, 6.0, 6.0, 10.0),)),
    limits=STUDY_MOVE_LIMITS,
)

AIRY_WAVE = Scenario(
    name="airy_wave",
    title="Airy wave: A = 3 mm, Tw = 10 s, L = 100 m, phase 10 deg",
    start_pose=STUDY_START_POSE,
    motion=WaveMotion(wave=AIRY, centre_pose=STUDY_START_POSE, wave_seconds=60.0),
)

RANDOM_WAVE = Scenario(
    name="random_wave",
    title="Random wave of five components (docs/mathematics.md section 4)",
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
