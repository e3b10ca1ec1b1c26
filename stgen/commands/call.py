"""`stgen call FILE_OR_DIR... --pou NAME [--set NAME=JSON ...] [--until OUTPUT]
[--max-cycles N] --json`: call a FUNCTION once, or an FB until an output.

A FUNCTION is called once.  An FB instance is called once per scan (1 ms
simulated clock by default) until its BOOL output named by `--until` is TRUE
or `--max-cycles` (default 1000) scans have run; without `--until` it is
called once.  Inputs are JSON: `--set 'Pose=[0,0,150,0,0,0]'`, `--set
'PT="T#1s"'`.  stdout gets one JSON object: the outputs (and VAR_IN_OUTs) by
declared name, for a FUNCTION also "return", plus "cycles" (unless the POU
declares a variable of that name: then the count goes to stderr).  The JSON is
strict: a non-finite REAL/LREAL is the string "NaN", "Infinity" or
"-Infinity" (and `--set X='"Infinity"'` gives one).

Exit 0 on success, 1 on diagnostics or runtime faults, 2 on usage errors.
An `--until` output still FALSE after `--max-cycles` scans is no fault: the
outputs are printed, stderr says so, and the exit status stays 0.
"""

from __future__ import annotations

import json
import math
import sys

from st_runtime.api import CallError, LoadError, load
from st_runtime.values import JsonValueError, json_text

from .run import MAX_FAULT_LINES, kind_hint, period_option, source_problem


def add_arguments(parser) -> None:
    parser.add_argument("paths", nargs="+", metavar="FILE_OR_DIR",
                        help="ST files, or directories whose .st files form one program")
    parser.add_argument("--pou", required=True, metavar="NAME", help="the FUNCTION or FUNCTION_BLOCK")
    parser.add_argument("--set", action="append", default=[], metavar="NAME=JSON",
                        help="an input value as JSON, e.g. 'Pose=[0,0,150,0,0,0]'")
    parser.add_argument("--until", metavar="OUTPUT", help="BOOL output that ends the calls when TRUE")
    parser.add_argument("--max-cycles", type=int, default=1000, metavar="N",
                        help="most scans for an FB with --until (default 1000)")
    parser.add_argument("--period", default="1ms", help="scan period for FB calls (default 1ms)")
    parser.add_argument("--json", action="store_true",
                        help="print the outputs as one strict JSON object (the default; a"
                             ' non-finite REAL/LREAL is the string "NaN", "Infinity" or'
                             ' "-Infinity", which --set also accepts)')
    parser.add_argument("--dialect", choices=("iec", "nj", "codesys"), default="iec")


def usage(message: str) -> int:
    print(f"stgen call: error: {message}", file=sys.stderr)
    return 2


def _finite_float(text: str) -> float:
    """A JSON number; one beyond the double range (1e999) is refused, not infinity."""
    value = float(text)
    if math.isinf(value):
        raise ValueError(f"{text} is too large for any ST number; infinity is written \"Infinity\"")
    return value


def parse_sets(items: list[str]) -> dict:
    inputs = {}
    for item in items:
        name, sep, text = item.partition("=")
        if not sep or not name.strip():
            raise ValueError(f"--set {item!r}: expected NAME=JSON")
        if name.strip().upper() in (key.upper() for key in inputs):
            raise ValueError(f"--set {name.strip()}: given twice")
        try:
            inputs[name.strip()] = json.loads(text, parse_float=_finite_float)
        except json.JSONDecodeError as exc:
            raise ValueError(f"--set {name.strip()}: not JSON ({exc.msg}): {text!r}; "
                             "strings need quotes, e.g. 'PT=\"T#1s\"'") from None
        except ValueError as exc:
            raise ValueError(f"--set {name.strip()}: {exc}") from None
    return inputs


def run(args) -> int:
    problem = source_problem(args.paths)
    if problem:
        return usage(problem)
    if args.max_cycles <= 0:
        return usage("--max-cycles must be positive")
    try:
        inputs = parse_sets(args.set)
    except ValueError as exc:
        return usage(str(exc))
    try:
        period = period_option(args.period)
    except ValueError as exc:
        return usage(str(exc))
    try:
        project = load(args.paths, dialect=args.dialect)
    except LoadError as exc:
        print(exc.render(), file=sys.stderr)
        return 1
    try:
        result = project.call(args.pou, inputs, until=args.until, max_cycles=args.max_cycles,
                              period=period)
    except JsonValueError as exc:
        return usage(f"--set {exc}")
    except CallError as exc:
        hint = kind_hint(project, args.pou, "stgen run --program runs it")
        return usage(f"{exc}{hint}" if str(exc).startswith("no FUNCTION") else str(exc))
    print(json_text(result["outputs"]))
    if "CYCLES" in project.program.pous[args.pou.upper()].variables:
        print(f"stgen call: {result['cycles']} cycle(s); the \"cycles\" above is {args.pou}'s own",
              file=sys.stderr)
    faults = result["faults"]
    for record in faults[:MAX_FAULT_LINES]:
        print(record.render(), file=sys.stderr)
    if args.until and not result.get("reached", True):
        print(f"stgen call: {args.until} did not become TRUE within {args.max_cycles} cycles",
              file=sys.stderr)
    return 1 if faults else 0
