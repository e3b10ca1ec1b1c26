"""``stgen workspace [--config FILE] [--centre POSE] [--slice A,B ...] [--at POSE] [--resolution N]
[--png DIR] [--json]``.

Computes offline with NumPy (:mod:`stgen.workspace`) the range of each pose
coordinate alone from the home pose (or ``--centre``), with the limit and leg
that stop it, and slices of the reachable set at a fixed orientation
(``--at``: the rest of the pose, default the centre). Prints a table, or with
``--json`` one JSON object (values in mm and degrees, upper pose in the world
frame with z from the home height h0, angles in the order of
``platform.platform_rotation``); ``--png DIR`` draws each slice with the
binding limit coloured. Exit status 0, 1 for a bad configuration or an
infeasible centre, 2 for usage errors.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from stgen.commands.config_option import add_config_argument, config_from_args
from stgen.workspace import COORDINATES, coordinate_ranges, slice_map

DEFAULT_SLICES = ("x,y", "x,z")


def _pose(text: str) -> list[float]:
    try:
        values = [float(part) for part in text.replace("[", "").replace("]", "").split(",")]
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected six numbers x,y,z,a1,a2,a3, got {text!r}") from None
    if len(values) != 6 or not all(abs(v) < float("inf") for v in values):
        raise argparse.ArgumentTypeError(f"expected six finite numbers x,y,z,a1,a2,a3, got {text!r}")
    return values


def _axes(text: str) -> tuple[str, str]:
    parts = tuple(part.strip() for part in text.split(","))
    if len(parts) != 2 or any(p not in COORDINATES for p in parts) or parts[0] == parts[1]:
        raise argparse.ArgumentTypeError(
            f"expected two different coordinates of {', '.join(COORDINATES)} as A,B, got {text!r}")
    return parts


def _resolution(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected an integer 2..2000, got {text!r}") from None
    if not 2 <= value <= 2000:
        raise argparse.ArgumentTypeError(f"expected an integer 2..2000, got {value}")
    return value


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_config_argument(parser)
    parser.add_argument("--centre", type=_pose, metavar="POSE",
                        help="pose the coordinate ranges start from, x,y,z,a1,a2,a3 (default: home 0,0,0,0,0,0)")
    parser.add_argument("--base", type=_pose, metavar="POSE",
                        help="base pose for a moving base, x,y,z,b1,b2,b3 (default: zero)")
    parser.add_argument("--slice", dest="slices", type=_axes, action="append", metavar="A,B",
                        help=f"a slice over two coordinates (repeatable; default: {' and '.join(DEFAULT_SLICES)})")
    parser.add_argument("--at", type=_pose, metavar="POSE",
                        help="the fixed rest of the pose of every slice (default: the centre)")
    parser.add_argument("--resolution", type=_resolution, default=200, metavar="N",
                        help="grid points per slice axis (default: 200)")
    parser.add_argument("--png", metavar="DIR", help="write one PNG per slice into DIR")
    parser.add_argument("--json", action="store_true", help="print one JSON object instead of the table")


def run(args: argparse.Namespace) -> int:
    config = config_from_args(args, "workspace")
    if config is None:
        return 1
    centre = args.centre or [0.0] * 6
    slices = args.slices or [_axes(text) for text in DEFAULT_SLICES]
    try:
        ranges = coordinate_ranges(config, args.base, centre)
        maps = [slice_map(config, axes, resolution=args.resolution, fixed_pose=args.at or centre,
                          base_pose_deg=args.base) for axes in slices]
    except ValueError as error:
        print(f"stgen workspace: error: {error}", file=sys.stderr)
        return 1
    written = []
    if args.png:
        from stgen.workspace_figures import draw_slice

        folder = Path(args.png)
        try:
            folder.mkdir(parents=True, exist_ok=True)
            for item in maps:
                path = folder / f"workspace_{item.axes[0]}_{item.axes[1]}.png"
                draw_slice(item, path)
                written.append(str(path))
        except OSError as error:
            print(f"stgen workspace: error: cannot write {error.filename or folder}: {error.strerror}", file=sys.stderr)
            return 1
    if args.json:
        print(json.dumps({
            "frame": "upper pose in the world frame: x, y, z in mm (z from the home height h0), "
                     f"angles in degrees in the order {config.platform.platform_rotation}",
            "centre": centre, "base": args.base or [0.0] * 6,
            "ranges": [r.to_json() for r in ranges],
            "slices": [m.to_json() for m in maps],
            "figures": written,
        }))
    else:
        print(format_report(ranges, maps, centre))
        for path in written:
            print(f"wrote {path}")
    return 0


def format_report(ranges, maps, centre) -> str:
    lines = [f"coordinate ranges from {centre} (others held), mm and degrees:",
             f"  {'coord':<5} {'min':>12}  {'stopped by':<24} {'max':>12}  {'stopped by':<24}"]
    for item in ranges:
        lines.append(f"  {item.coordinate:<5} {item.low.value:>12.3f}  {_stop(item.low):<24} "
                     f"{item.high.value:>12.3f}  {_stop(item.high):<24}")
    for item in maps:
        extent = item.feasible_extent()
        lines.append(f"slice {item.axes[0]},{item.axes[1]} at {list(item.fixed_pose)}: "
                     f"{len(item.xs)}x{len(item.ys)} points, {100 * item.feasible.mean():.1f} % feasible; "
                     f"feasible {item.axes[0]} {_span(extent[item.axes[0]])}, {item.axes[1]} {_span(extent[item.axes[1]])}; "
                     + ", ".join(f"{name} {count}" for name, count in item.limit_counts().items()))
    return "\n".join(lines)


def _stop(end) -> str:
    return f"{end.limit.label}, leg {end.leg}" if end.leg else "nothing within the search"


def _span(pair) -> str:
    return "none" if pair is None else f"{pair[0]:.1f}..{pair[1]:.1f}"
