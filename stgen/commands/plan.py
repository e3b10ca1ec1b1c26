"""``stgen plan [--config FILE] (--path CURVE | --playback FILE.csv | --study) [--figures DIR] [--json]``.

Plans a motion without a controller (issue 12, docs/mathematics.md section 6.3): a parametric path
gets its shortest duration within the pose limits of docs/mathematics.md section 4 and the actuator
limits (or the ``duration=`` asked for); a playback table is interpolated at
the task period. Prints the duration and, per actuator, the extreme
positions against the stroke and the largest |velocity| and |acceleration|
against the actuator limits, on the samples at the task period; a broken
limit is named with its leg. ``--study`` plans the four curves of the
figures (stgen.reference.paths.STUDY_PATHS) at roll = pitch = 0 and 35 deg.
``--figures DIR`` draws the six actuator velocities of each.
Exit 0 when every limit holds, 1 when one breaks or on bad input (file:line:col).
A crank or moving-base platform is refused (exit 1), as the controller refuses paths there.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import sys
import time
from pathlib import Path

import numpy as np

from stgen.commands.config_option import add_config_argument, config_from_args
from stgen.reference.motion_limits import MotionCheck, check_motion
from stgen.reference.paths import STUDY_PATHS, STUDY_TILT, PathError, describe, plan_path
from stgen.reference.playback import ADDED_KNOTS, PlaybackError, evaluate, read_playback_csv


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_config_argument(parser)
    what = parser.add_mutually_exclusive_group(required=True)
    what.add_argument("--path", metavar="CURVE",
                      help="FAMILY[:KEY=VALUE,...], e.g. epitrochoid:R=60,r=20,d=30,z=240,roll=35,pitch=35"
                           " (keys: R r d a b phi_end turns x y z roll pitch yaw law blend duration)")
    what.add_argument("--playback", metavar="FILE.csv", help="table t,x,y,z,alpha,beta,gamma (s, mm, deg)")
    what.add_argument("--study", action="store_true",
                      help="the four curves of the figures at roll = pitch = 0 and 35 deg")
    parser.add_argument("--figures", metavar="DIR", help="write PNG figures of the actuator velocities here")
    parser.add_argument("--json", action="store_true", help="print the plan as JSON")


@dataclasses.dataclass(frozen=True)
class PlannedMotion:
    label: str
    duration: float
    note: str
    check: MotionCheck
    refusal: str = ""   # a reason to refuse besides the legs' breaches


def _plan_paths(args, config) -> list[PlannedMotion]:
    from stgen.path_spec import parse_path_spec

    specs = ([parse_path_spec(args.path)] if args.path else
             [dataclasses.replace(s, orientation=o) for s in STUDY_PATHS for o in ((0.0, 0.0, 0.0), STUDY_TILT)])
    motions = []
    for spec in specs:
        plan = plan_path(spec, config)
        note = f"shortest {plan.shortest:.3f} s, set by {plan.binding}"
        refusal = (f"duration {plan.duration:g} s is shorter than the shortest {plan.shortest:.3f} s"
                   f" ({plan.binding})" if plan.too_short else "")
        motions.append(PlannedMotion(describe(spec), plan.duration, note, plan.check, refusal))
    return motions


def _plan_playback(path: str, config) -> list[PlannedMotion]:
    table = read_playback_csv(path)
    period = config.task.period_s
    t = np.arange(int(np.floor(table.duration / period + 1e-9)) + 1) * period
    pose, rate, acc = evaluate(table, t)
    note = (f"{len(table.t) - ADDED_KNOTS} rows, {len(table.t)} knots with the two added for rest at the ends, "
            f"cubic spline at {period * 1000:g} ms")
    return [PlannedMotion(f"playback {path}", table.duration, note, check_motion(config, t, pose, rate, acc))]


def format_plan(motion: PlannedMotion, config) -> str:
    ext = motion.check.extremes()
    lines = [motion.label, f"duration {motion.duration:.3f} s ({motion.note}); {len(motion.check.t)} samples",
             "leg  q min mm  q max mm  stroke      |v| max mm/s  limit  |a| max mm/s^2  limit"]
    for leg in range(6):
        lines.append(f"{leg + 1:<4} {ext['position_min'][leg]:8.3f}  {ext['position_max'][leg]:8.3f}  "
                     f"{config.stroke.min:g}..{config.stroke.max:<6g}  {ext['velocity_max'][leg]:12.3f}  "
                     f"{config.actuator.max_velocity:<5g}  {ext['acceleration_max'][leg]:14.3f}  "
                     f"{config.actuator.max_acceleration:g}")
    breaches = motion.check.breaches(config)
    for leg, what, value, limit in breaches:
        lines.append(f"REFUSED: leg {leg} {what}: {value:.3f} beyond {limit:g}")
    if motion.refusal:
        lines.append(f"REFUSED: {motion.refusal}")
    lines.append("within every limit" if not (breaches or motion.refusal)
                 else f"{len(breaches) + bool(motion.refusal)} limit(s) broken")
    return "\n".join(lines)


def _as_json(motion: PlannedMotion, config) -> dict:
    ext = motion.check.extremes()
    return {"motion": motion.label, "duration_s": motion.duration, "note": motion.note,
            **{key: [float(v) for v in values] for key, values in ext.items()},
            "breaches": [{"leg": leg, "limit": what, "value": value, "bound": bound}
                         for leg, what, value, bound in motion.check.breaches(config)],
            "refusal": motion.refusal}


def _figures(motions: list[PlannedMotion], config, out: Path, study: bool) -> list[Path]:
    from stgen.path_figures import draw_actuator_velocities

    rows = [(m.label + f", T = {m.duration:.3f} s", m.check) for m in motions]
    if not study:
        return [draw_actuator_velocities(rows, config, "Actuator velocities (parameters in the panel title)",
                                         out / "plan.png")]
    paths = []
    for index, spec in enumerate(STUDY_PATHS):
        pair = rows[2 * index: 2 * index + 2]
        title = (f"{spec.family}: six actuator velocities at roll = pitch = 0 (top) and 35 deg (bottom); "
                 "curve parameters are ours (the study gives none)")
        paths.append(draw_actuator_velocities(pair, config, title, out / f"path_{spec.family}.png"))
    return paths


def run(args: argparse.Namespace) -> int:
    config = config_from_args(args, "plan")
    if config is None:
        return 1
    if not config.is_default_kind:
        # The legs planned here are linear on a fixed base; SP_Controller refuses paths and
        # playback on the other platforms (SP_REFUSED_PLATFORM): plan nothing rather than wrong legs.
        kind = config.platform
        print(f"stgen plan: error: {args.config}: paths and playback are planned for linear legs on a "
              f"fixed base (docs/mathematics.md section 6.3); this platform (actuator {kind.actuator!r}, "
              f"base {kind.base!r}) is not planned, as SP_Controller refuses them there", file=sys.stderr)
        return 1
    started = time.perf_counter()
    try:
        motions = _plan_playback(args.playback, config) if args.playback else _plan_paths(args, config)
    except PlaybackError as error:
        print(f"stgen plan: error: {error}", file=sys.stderr)
        return 1
    except PathError as error:
        print(f"stgen plan: error: --path: {error}", file=sys.stderr)
        return 1
    elapsed = time.perf_counter() - started
    broken = any(m.check.breaches(config) or m.refusal for m in motions)
    if args.json:
        print(json.dumps({"motions": [_as_json(m, config) for m in motions], "planning_time_s": elapsed}, indent=1))
    else:
        print("\n\n".join(format_plan(m, config) for m in motions))
        print(f"\nplanned in {elapsed:.2f} s")
    if args.figures:
        for path in _figures(motions, config, Path(args.figures), bool(args.study)):
            print(f"figure {path}", file=sys.stderr if args.json else sys.stdout)
    return 1 if broken else 0
