"""``stgen verify [--config FILE] [--poses N] [--fk-poses N] [--seed S]``.

Renders the kinematics for the configuration, runs them in st_runtime and
holds every result against the NumPy reference (see :mod:`stgen.verify`).
Prints one row per check: POU, what was compared, cases, max error and its
limit, the FK iteration counts, PASS or FAIL (with the first problems); then
the estimated NJ501 time of SP_ForwardKinematics per scan and which
IterationsPerScan fits the configured period.
Exit status 0 when every check passes, 1 otherwise or for a bad
configuration.
"""

from __future__ import annotations

import argparse
import sys
import time

from stgen.commands.config_option import add_config_argument, config_from_args
from stgen.verify import Check, SamplingError, run_verification

_MAX_PROBLEMS_SHOWN = 5


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_config_argument(parser)
    parser.add_argument("--poses", type=_positive, default=10_000, metavar="N",
                        help="random reachable poses for the IK comparison (default: 10000), plus N/10"
                             " drawn anywhere in the box, reachable or not (the table counts both)")
    parser.add_argument("--fk-poses", type=_positive, default=500, metavar="N",
                        help="poses for the FK comparisons, from p_NR and from warm starts (default: 500)")
    parser.add_argument("--seed", type=_non_negative, default=2024,
                        help="random seed, 0 or more (default: 2024)")


def _integer_at_least(minimum: int, expected: str):
    """An argparse type: an integer >= minimum, else a usage error saying `expected`."""

    def convert(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected {expected}, got {text!r}") from None
        if value < minimum:
            raise argparse.ArgumentTypeError(f"expected {expected}, got {value}")
        return value

    return convert


_positive = _integer_at_least(1, "a positive integer")
_non_negative = _integer_at_least(0, "an integer 0 or more")  # a NumPy seed


def format_table(checks: list[Check]) -> str:
    header = ("POU", "check", "cases", "max error", "limit", "iterations", "result")
    rows = [
        (c.pou, c.what, str(c.cases), "-" if c.max_error is None else f"{c.max_error:.3g} {c.unit}".strip(),
         "-" if c.max_error is None else f"{c.limit:g}", c.iterations or "-",
         "PASS" if c.passed else "FAIL")
        for c in checks
    ]
    widths = [max(len(r[i]) for r in [header, *rows]) for i in range(len(header))]
    lines = ["  ".join(cell.ljust(width) for cell, width in zip(row, widths)).rstrip() for row in [header, *rows]]
    lines.insert(1, "  ".join("-" * width for width in widths))
    for check in checks:
        for problem in check.problems[:_MAX_PROBLEMS_SHOWN]:
            lines.append(f"  {check.pou}: {problem}")
        if len(check.problems) > _MAX_PROBLEMS_SHOWN:
            lines.append(f"  {check.pou}: ... {len(check.problems) - _MAX_PROBLEMS_SHOWN} more")
    return "\n".join(lines)


def run(args: argparse.Namespace) -> int:
    config = config_from_args(args, "verify")
    if config is None:
        return 1
    from st_runtime.api import LoadError

    started = time.perf_counter()
    try:
        timing: list = []
        checks = run_verification(config, poses=args.poses, seed=args.seed, fk_poses=min(args.fk_poses, args.poses),
                                  timing=timing)
    except LoadError as error:
        print(f"stgen verify: error: the rendered kinematics do not load:\n{error.render()}", file=sys.stderr)
        return 1
    except (RuntimeError, SamplingError) as error:
        print(f"stgen verify: error: {error}", file=sys.stderr)
        return 1
    print(format_table(checks))
    for estimate in timing:
        print("\n" + estimate.render())
    failed = [c for c in checks if not c.passed]
    verdict = "all checks passed" if not failed else f"{len(failed)} of {len(checks)} checks FAILED"
    print(f"\n{verdict} ({time.perf_counter() - started:.1f} s)")
    return 1 if failed else 0
