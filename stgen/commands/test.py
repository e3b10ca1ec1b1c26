"""`stgen test FILE_OR_DIR... [--junit FILE] [--dialect iec|nj] [-k PATTERN] [--period 1ms]`.

Runs the TEST blocks of ST test files (STruC++'s form: `TEST 'name' ...
END_TEST` with ASSERT_EQ/NEQ/GT/LT/GE/LE/TRUE/FALSE/NEAR, ADVANCE_TIME,
optional SETUP/TEARDOWN; see st_runtime/testing) against the code in the
other files given.  Prints PASS/FAIL per test, the file:line:column of a
failed assert with both values, a total; `--junit` writes JUnit XML for CI.
Exit 0 when every test passes, 1 on a failed test or a load error, 2 on
usage errors.
"""

from __future__ import annotations

import sys

from st_runtime.testing import junit_xml, run_tests

from .run import output_problem, period_option, source_problem


def add_arguments(parser) -> None:
    parser.add_argument("paths", nargs="+", metavar="FILE_OR_DIR",
                        help="test files (lines `TEST 'name'`) and the ST files they test")
    parser.add_argument("--junit", metavar="FILE", help="write a JUnit XML report to FILE")
    parser.add_argument("--dialect", choices=("iec", "nj"), default="iec",
                        help="nj: OMRON NJ rules are errors (default iec)")
    parser.add_argument("-k", dest="pattern", metavar="PATTERN",
                        help="run only tests whose name contains PATTERN (or matches it as a "
                             "glob with * ? [])")
    parser.add_argument("--period", default="1ms",
                        help="the task period FBs see (ctx period, default 1ms); the clock "
                             "itself moves only by ADVANCE_TIME")


def run(args) -> int:
    problem = source_problem(args.paths)
    if problem is None and args.junit:
        problem = output_problem(args.junit)
    try:
        period = period_option(args.period)
    except ValueError as exc:
        problem = problem or str(exc)
    if problem:
        print(f"stgen test: error: {problem}", file=sys.stderr)
        return 2
    result = run_tests(args.paths, args.dialect, args.pattern, period)
    if not result.loaded:
        print(result.render_diagnostics(), file=sys.stderr)
        print("stgen test: the files do not load; no test was run", file=sys.stderr)
        return 1
    print(result.render())
    if args.junit:
        with open(args.junit, "w", encoding="utf-8") as handle:
            handle.write(junit_xml(result))
    if not result.results:
        print(f"stgen test: no test matches -k '{args.pattern}'", file=sys.stderr)
        return 1
    return 0 if result.ok else 1
