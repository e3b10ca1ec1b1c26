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

With `--until`, the JSON also says whether the output became TRUE:
"reached" (true/false, last; to stderr instead when the POU declares a
variable of that name).

Exit 0 on success, 1 on diagnostics, runtime faults or an `--until` output
still FALSE after `--max-cycles` scans (the outputs are printed all the same,
with "reached": false, and stderr says so), 2 on usage errors.
"""

from __future__ import annotations

import json
import math
import sys

from st_runtime.api import CallError, LoadError, load
from st_runtime.values import JsonValueError, json_text

from .run import DIALECT_HELP, MAX_FAULT_LINES, kind_hint, period_option, source_problem


def add_arguments(parser) -> None:
    parser.add_argument("paths", nargs="+", metavar="FILE_OR_DIR",
                        help="ST files, PLCopen TC6 or IEC 61131-10 .xml files, or directories whose .st files form one program")
    parser.add_argument("--pou", required=True, metavar="NAME", help="the FUNCTION or FUNCTION_BLOCK")
    parser.add_argument("--set", action="append", default=[], metavar="NAME=JSON",
                        help="an input value as JSON, e.g. 'Pose=[0,0,150,0,0,0]'")
    parser.add_argument("--until", metavar="OUTPUT", help="BOOL output that ends the calls when TRUE")
    parser.add_argument("--max-cycles", type=int, default=1000, metavar="N",
                        help="most scans for an FB with --until (default 1000)")
    parser.add_argument("--period", default="1ms", metavar="TIME",
                        help="scan period for FB calls: a duration with its unit, 1ms, 250us or"
                             " T#2ms (default 1ms)")
    parser.add_argument("--json", action="store_true",
                        help="print the outputs as one strict JSON object (the default; a"
                             ' non-finite REAL/LREAL is the string "NaN", "Infinity" or'
                             ' "-Infinity", which --set also accepts)')
    parser.add_argument("--dialect", choices=("iec", "nj", "codesys"), default="iec", help=DIALECT_HELP)


def usage(message: str) -> int:
    print(f"stgen call: error: {message}", file=sys.stderr)
    return 2


def _finite_float(text: str) -> float:
    """A JSON number; one beyond the double range (1e999) is refused, not infinity."""
    value = float(text)
    if math.isinf(value):
        raise ValueError(f"{text} is too large for any ST number; infinity is written \"Infinity\"")
    return value


#: Digits of the longest JSON integer a --set may hold: LREAL's largest value
#: written out has 309; Python refuses 4,300 in its own words.
MAX_INT_DIGITS = 1000
#: Nesting of a --set JSON value (an ST value nests arrays and structs, never this deep).
MAX_JSON_DEPTH = 64


def _bounded_int(text: str) -> int:
    """A JSON integer of at most MAX_INT_DIGITS digits (100,000 digits took
    Python's own wording to the user)."""
    if len(text.lstrip("-")) > MAX_INT_DIGITS:
        raise ValueError(f"a number of {len(text.lstrip('-')):,} digits is beyond any ST number")
    return int(text)


def _check_json(value) -> None:
    """Refuse what JSON allows and no ST value holds: nesting beyond
    MAX_JSON_DEPTH, and strings with a lone UTF-16 surrogate ("\\ud800")."""
    work = [(value, 1)]
    while work:
        item, depth = work.pop()
        if depth > MAX_JSON_DEPTH:
            raise ValueError(f"nested more than {MAX_JSON_DEPTH} levels deep")
        if isinstance(item, str):
            try:
                item.encode("utf-8")
            except UnicodeEncodeError as exc:
                raise ValueError(f"the string holds a lone UTF-16 surrogate (\\u{ord(item[exc.start]):04x}),"
                                 " which is no character") from None
        elif isinstance(item, list):
            work.extend((x, depth + 1) for x in item)
        elif isinstance(item, dict):
            work.extend((x, depth + 1) for pair in item.items() for x in pair)


def _shown(text: str, width: int = 40) -> str:
    return repr(text if len(text) <= width else text[:width] + "...")


def parse_sets(items: list[str]) -> dict:
    inputs = {}
    for item in items:
        name, sep, text = item.partition("=")
        if not sep or not name.strip():
            raise ValueError(f"--set {_shown(item)}: expected NAME=JSON")
        name = name.strip()
        shown_name = name if len(name) <= 60 else name[:60] + "..."
        if name.upper() in (key.upper() for key in inputs):
            raise ValueError(f"--set {shown_name}: given twice")
        try:
            value = json.loads(text, parse_float=_finite_float, parse_int=_bounded_int)
            _check_json(value)
        except json.JSONDecodeError as exc:
            raise ValueError(f"--set {shown_name}: not JSON ({exc.msg}): {_shown(text)}; "
                             "strings need quotes, e.g. 'PT=\"T#1s\"'") from None
        except RecursionError:
            raise ValueError(f"--set {shown_name}: nested more than {MAX_JSON_DEPTH} levels deep") from None
        except ValueError as exc:
            raise ValueError(f"--set {shown_name}: {exc}") from None
        inputs[name] = value
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
    outputs = dict(result["outputs"])
    declared = project.program.pous[args.pou.upper()].variables
    if args.until and "REACHED" not in declared:
        outputs["reached"] = result["reached"]
    print(json_text(outputs))
    if "CYCLES" in declared:
        print(f"stgen call: {result['cycles']} cycle(s); the \"cycles\" above is {args.pou}'s own",
              file=sys.stderr)
    faults = result["faults"]
    for record in faults[:MAX_FAULT_LINES]:
        print(record.render(), file=sys.stderr)
    missed = bool(args.until) and not result["reached"]
    if missed:
        print(f"stgen call: {args.until} did not become TRUE within {args.max_cycles} cycles",
              file=sys.stderr)
    return 1 if faults or missed else 0
