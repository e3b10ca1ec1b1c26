"""`stgen check FILE_OR_DIR... [--dialect nj|iec]`: parse and check ST.

Diagnostics go to stderr, gcc-style with the source line and a caret; a
one-line summary follows.  Exit 0 when there is no error (warnings allowed),
1 on errors, 2 on usage errors (a path that does not exist, nothing to
check: no .st file in the paths given).
"""

from __future__ import annotations

import os
import sys

from st_runtime.loader import load

from .run import source_problem


def add_arguments(parser) -> None:
    parser.add_argument("paths", nargs="+", metavar="FILE_OR_DIR",
                        help="ST files, or directories whose .st files are checked together")
    parser.add_argument("--dialect", choices=("iec", "nj", "codesys"), default="iec",
                        help="nj: OMRON NJ identifier rules are errors (default iec: warnings)")


def run(args) -> int:
    missing = [p for p in args.paths if not os.path.exists(p)]
    if missing:
        for path in missing:
            print(f"stgen check: error: no such file or directory: '{path}'", file=sys.stderr)
        return 2
    problem = source_problem(args.paths)
    if problem:
        print(f"stgen check: error: {problem}", file=sys.stderr)
        return 2
    result = load(args.paths, dialect=args.dialect)
    if result.diagnostics:
        print(result.render(), file=sys.stderr)
    n_errors = sum(1 for d in result.diagnostics if d.is_error)
    n_warnings = len(result.diagnostics) - n_errors
    n_files = len([p for p in result.sources if p != "<builtin>"])
    print(f"stgen check: {n_files} file(s), {n_errors} error(s), {n_warnings} warning(s)",
          file=sys.stderr)
    if n_errors and any(_is_sysmac_body(path) for path in result.sources):
        print("stgen check: note: these .st files are Sysmac Studio bodies (stgen generate --target"
              " nj: statements only, variables in <POU>.variables.tsv); to check the POUs, generate"
              " whole ones with --target iec and run stgen check --dialect nj on that folder",
              file=sys.stderr)
    return 1 if n_errors else 0


def _is_sysmac_body(path: str) -> bool:
    """An .st file with a `<POU>.variables.tsv` beside it, as `--target nj` writes."""
    stem, ext = os.path.splitext(path)
    return ext.lower() == ".st" and os.path.isfile(stem + ".variables.tsv")
