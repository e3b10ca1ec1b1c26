"""Run STruC++'s own ST test suite (tests/st-validation) under `stgen test`.

The suite is GPL-3.0 and is not kept here: benchmarks/third_party/strucpp.md
names the repository, commit and path.  Check it out and point this script
at the folder:

    git clone https://github.com/Autonomy-Logic/STruCpp /tmp/strucpp
    python benchmarks/bench_strucpp_suite.py /tmp/strucpp/tests/st-validation [--dialect iec]

The suite's convention (its README): in each category folder, `<name>.st`
holds the code and `test_<name>.st` its TEST blocks.  Each test file runs
with its source file (if there is one) as one `stgen test` run.  Printed: per
test file the outcome (passed/failed/error counts, or the first diagnostic
when the files do not load), then the pass rate over test blocks and over
files, and the reasons for the files that did not load, grouped by
diagnostic code.
"""

from __future__ import annotations

import argparse
import collections
import os
import sys
import time

from st_runtime.parser import parse_tests
from st_runtime.testing import run_tests
from st_runtime.parser import grammar


def pairs(root: str) -> list[tuple[str, list[str]]]:
    """(test file, [test file, source file if any]) for every test_*.st under root."""
    found = []
    for folder, _dirs, names in sorted(os.walk(root)):
        for name in sorted(names):
            if name.startswith("test_") and name.endswith(".st"):
                test = os.path.join(folder, name)
                source = os.path.join(folder, name[len("test_"):])
                found.append((test, [source, test] if os.path.exists(source) else [test]))
    return found


def count_blocks(path: str) -> int:
    """TEST blocks of a file, by the parser (0 when the file does not parse)."""
    with open(path, encoding="utf-8") as handle:
        parsed, _ = parse_tests(handle.read(), path)
    from st_runtime import ast

    return 0 if parsed is None else sum(isinstance(i, ast.TestCase) for i in parsed.items)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("root", help="a checkout's tests/st-validation folder")
    parser.add_argument("--dialect", default="iec", choices=("iec", "nj"))
    args = parser.parse_args()
    grammar()
    totals = collections.Counter()
    reasons = collections.Counter()
    examples = {}
    started = time.perf_counter()
    for test, files in pairs(args.root):
        blocks = count_blocks(test)
        run = run_tests(files, args.dialect)
        rel = os.path.relpath(test, args.root)
        totals["files"] += 1
        totals["blocks"] += blocks
        if not run.loaded:
            first = next(d for d in run.diagnostics if d.is_error)
            totals["files not loaded"] += 1
            totals["blocks not run"] += blocks
            reasons[first.code] += 1
            examples.setdefault(first.code, f"{os.path.relpath(first.pos.file, args.root)}:"
                                            f"{first.pos.line}: {first.message}")
            print(f"{rel}: NOT LOADED ({blocks} tests): {first.code} "
                  f"{os.path.relpath(first.pos.file, args.root)}:{first.pos.line}: {first.message}")
            continue
        counts = {s: run.count(s) for s in ("passed", "failed", "error")}
        totals.update(counts)
        totals["files all passed"] += run.ok
        print(f"{rel}: {counts['passed']} passed, {counts['failed']} failed, {counts['error']} error(s)")
        for r in run.results:
            if r.status != "passed":
                print(f"    {r.status.upper()}: {r.name}: {r.message}")
    seconds = time.perf_counter() - started
    blocks = totals["blocks"]
    print()
    print(f"test files: {totals['files']}, loaded: {totals['files'] - totals['files not loaded']}, "
          f"all passed: {totals['files all passed']}")
    print(f"TEST blocks: {blocks}; passed {totals['passed']} ({100.0 * totals['passed'] / max(blocks, 1):.1f} %), "
          f"failed {totals['failed']}, error {totals['error']}, not run (file not loaded) "
          f"{totals['blocks not run']}")
    print("files not loaded, by first diagnostic:")
    for code, n in reasons.most_common():
        print(f"  {code}: {n}  e.g. {examples[code]}")
    print(f"({seconds:.1f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
