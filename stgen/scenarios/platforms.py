"""The platform variants' scenarios (issue 11): the moving-base study's motions and test poses
(docs/mathematics.md section 6.2) and the crank study's test signals (docs/mathematics.md section 6.1),
each on its example platform, through SP_Controller with simulated axes.

* ``moving_base_motion``: 10 s of pU = (4.5 cos πt, 4.5 sin πt, 11.5 t), θU = (0.5 t, t, 1.5 t)
  on a deck with pB = (0.4 t, −0.2 t, −3 cos πt), θB = (0.3 t, 0.3 t, 0.2 t)
  (:mod:`stgen.reference.study_motions`; θB read as about z, y, x, in RB's order);
  streamed (SpTrackPose, SpBasePose every scan);
* ``fixed_base_motion``: 10 s of pU = (5 t, 0.5 sin πt, 8 t), θU = (0.5 t, 1.25 t, 2 t), streamed;
* ``test_pose_1``, ``test_pose_2``: the study's test poses (0, 0, 25, 0, 0, 30) and
  (−15, 15, 100, −5, 7, −15) (z from h0), each a cycloidal move from home and back
  (SpMoveStart, the configured limits);
* ``crank_surge``: ±300 mm surge at 4 s period, x = −300 cos(2πt/4) (starts at rest), two periods;
* ``crank_roll``: ±26° roll with a largest rate of 12°/s, γ = −26 cos(ωt), ω = 12/26 rad/s
  (period 13.6 s, starts at rest), one period. The crank study names the signals only as
  "±300 mm at 4 s" and "±26° at ±12°/s"; the sine and the roll axis are our reading (pitch ±26°
  is outside the assumed layout's range, −25.5..40.0°, ``stgen workspace``).

The study's motions start with a velocity step (their rates at t = 0 are not zero): the
set-point acceleration check reports it; :class:`PlatformReport` also gives the extremes
from the second streamed scan on (``motion_only``).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from stgen.config import PlatformConfig, load_config
from stgen.reference.study_motions import fixed_base_upper, moving_base_base, moving_base_upper
from stgen.scenarios.definitions import PointToPointMotion, Scenario
from stgen.scenarios.track import TrackScenario

#: The example platforms (``examples/`` of the source tree).
EXAMPLES = Path(__file__).resolve().parent.parent.parent / "examples"
MOVING_BASE_CONFIG = "moving_base_platform.toml"
CRANK_CONFIG = "crank_platform.toml"

SURGE_AMPLITUDE_MM, SURGE_PERIOD_S = 300.0, 4.0
ROLL_AMPLITUDE_DEG, ROLL_RATE_DEG_S = 26.0, 12.0


def _starting_at_rest(coordinate: int, amplitude: float, omega: float):
    """Coordinate ``coordinate`` = −amplitude·cos(ωt) (at rest at t = 0), the others zero: a
    :data:`~stgen.scenarios.track.Trajectory` (value, rate, acceleration)."""
    def trajectory(t):
        value, rate, acceleration = (np.zeros((len(t), 6)) for _ in range(3))
        value[:, coordinate] = -amplitude * np.cos(omega * t)
        rate[:, coordinate] = amplitude * omega * np.sin(omega * t)
        acceleration[:, coordinate] = amplitude * omega * omega * np.cos(omega * t)
        return value, rate, acceleration

    return trajectory


_surge = _starting_at_rest(0, SURGE_AMPLITUDE_MM, 2.0 * np.pi / SURGE_PERIOD_S)
_roll = _starting_at_rest(5, ROLL_AMPLITUDE_DEG, ROLL_RATE_DEG_S / ROLL_AMPLITUDE_DEG)  # peak rate = amplitude·ω


@dataclass(frozen=True)
class PlatformScenario:
    """A scenario on one example platform: a streamed motion or point-to-point moves."""

    config_file: str
    scenario: TrackScenario | Scenario

    @property
    def name(self) -> str:
        return self.scenario.name

    def config(self) -> PlatformConfig:
        return load_config(EXAMPLES / self.config_file)

    def shortened(self, seconds: float, move_fraction: float) -> "PlatformScenario":
        if isinstance(self.scenario, TrackScenario):
            return PlatformScenario(self.config_file, self.scenario.shortened(seconds))
        return PlatformScenario(self.config_file, self.scenario.shortened(0.0, move_fraction, 0.1))


HOME = (0.0,) * 6
TEST_POSES = ((0.0, 0.0, 25.0, 0.0, 0.0, 30.0), (-15.0, 15.0, 100.0, -5.0, 7.0, -15.0))

PLATFORM_SCENARIOS = (
    PlatformScenario(MOVING_BASE_CONFIG, TrackScenario(
        "moving_base_motion", "Moving-base study: upper and deck both moving, 10 s (docs/mathematics.md section 6.2)",
        moving_base_upper, 10.0, base=lambda t: moving_base_base(t, True))),
    PlatformScenario(MOVING_BASE_CONFIG, TrackScenario(
        "fixed_base_motion", "Moving-base study, fixed base: upper moving, 10 s (docs/mathematics.md section 6.2)",
        fixed_base_upper, 10.0)),
    *(PlatformScenario(MOVING_BASE_CONFIG, Scenario(
        f"test_pose_{index}", f"Moving-base study, test pose {index} {pose}: from home and back",
        HOME, PointToPointMotion(targets=(pose, HOME)), settle_seconds=0.2))
      for index, pose in enumerate(TEST_POSES, start=1)),
    PlatformScenario(CRANK_CONFIG, TrackScenario(
        "crank_surge", "Crank platform: surge x = -300 cos(2 pi t / 4) mm, two periods (docs/mathematics.md section 6.1)",
        _surge, 2.0 * SURGE_PERIOD_S)),
    PlatformScenario(CRANK_CONFIG, TrackScenario(
        "crank_roll", "Crank platform: roll = -26 cos(w t) deg, peak rate 12 deg/s, one period (docs/mathematics.md section 6.1)",
        _roll, 2.0 * np.pi * ROLL_AMPLITUDE_DEG / ROLL_RATE_DEG_S)),
)


def platform_scenario(name: str) -> PlatformScenario:
    for item in PLATFORM_SCENARIOS:
        if item.name == name:
            return item
    raise KeyError(f"no platform scenario {name!r}; known: {', '.join(s.name for s in PLATFORM_SCENARIOS)}")
