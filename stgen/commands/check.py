"""`stgen check FILE_OR_DIR... [--dialect nj|iec]`: parse and check ST.

Test files (lines `TEST 'name'`, see `stgen test`) are checked as `stgen
test` reads them.  Diagnostics go to stderr, gcc-style with the source line and a caret; a
one-line summary follows.  Exit 0 when there is no error (warnings allowed),
1 on errors, 2 on usage errors (a path that does not exist, nothing to
check: no .st file in the paths given).
"""

from __future__ import annotations

import os
import sys

from st_runtime.loader import LoadResult, expand, load, read_source
from st_runtime.testing.detect import is_test_source

from .sources import DIALECT_HELP, source_problem


def add_arguments(parser) -> None:
    parser.add_argument("paths", nargs="+", metavar="FILE_OR_DIR",
                        help="ST files, PLCopen TC6 or IEC 61131-10 .xml files, or directories whose .st files are checked together")
    parser.add_argument("--dialect", choices=("iec", "nj", "codesys"), default="iec", help=DIALECT_HELP)
    parser.add_argument("--memory-limit", type=_bytes, default=None, metavar="BYTES",
                        help="most bytes a variable, a POU instance or the project may need"
                             " (default 64 MiB; suffixes k, M, G: 512k, 16M)")


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
    files, _ = expand(list(args.paths))
    bodies = [f for f in files if _is_sysmac_body(f)]
    if bodies:
        # Said first and in one line: what these files are and how to check them.
        print(f"stgen check: {_where(bodies)}: {len(bodies)} Sysmac Studio statement bod"
              f"{'y' if len(bodies) == 1 else 'ies'} (stgen generate --target nj; variables in"
              " <POU>.variables.tsv), not ST POUs, so not checked: check the POUs with"
              " 'stgen generate --target iec --out DIR' then 'stgen check --dialect nj DIR'",
              file=sys.stderr)
        if len(bodies) == len(files):
            return 1
    result = _load([f for f in files if f not in bodies] if bodies else args.paths, args.dialect,
                   args.memory_limit)
    if result.diagnostics:
        print(result.render(), file=sys.stderr)
    n_errors = sum(1 for d in result.diagnostics if d.is_error)
    n_warnings = len(result.diagnostics) - n_errors
    n_files = len([p for p in result.sources if p != "<builtin>"])
    print(f"stgen check: {n_files} file(s), {n_errors} error(s), {n_warnings} warning(s)",
          file=sys.stderr)
    return 1 if n_errors or bodies else 0


def _bytes(text: str) -> int:
    """`--memory-limit`: a positive number of bytes, with an optional k, M or G (powers of 1024)."""
    import argparse

    scale = {"k": 2**10, "m": 2**20, "g": 2**30}.get(text[-1:].lower(), 1)
    digits = text[:-1] if scale != 1 else text
    if not digits.isdigit() or int(digits) <= 0 or len(digits) > 15:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number of bytes (e.g. 65536, 512k, 16M)")
    return int(digits) * scale


def _where(bodies: list[str]) -> str:
    """The folder of the bodies (or the one file)."""
    folders = sorted({os.path.dirname(b) or "." for b in bodies})
    return bodies[0] if len(bodies) == 1 else ", ".join(folders)


def _load(paths: list[str], dialect: str, memory_limit: int | None):
    """The files loaded as one program; test files (`TEST 'name'` lines) are checked
    as `stgen test` reads them, with the code they test."""
    files, _ = expand(list(paths))
    if not any(_is_test_file(path) for path in files):
        return load(paths, dialect=dialect, memory_limit=memory_limit)
    from st_runtime.testing import run_tests  # the test runner only for test files

    run = run_tests(paths, dialect, execute=False)
    return LoadResult(None, run.diagnostics, run.sources)


def _is_test_file(path: str) -> bool:
    text, _ = read_source(path)
    return text is not None and is_test_source(text)


def _is_sysmac_body(path: str) -> bool:
    """An .st file with a `<POU>.variables.tsv` beside it, as `--target nj` writes."""
    stem, ext = os.path.splitext(path)
    return ext.lower() == ".st" and os.path.isfile(stem + ".variables.tsv")
