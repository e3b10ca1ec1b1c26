"""Benchmark: our whole load (parse + check + compile) against blark's parse alone.

    python benchmarks/bench_load_vs_blark.py [--rounds N] [--sets NAME...]

For each file set, side by side in one run and one process:

* ours: `st_runtime` loads the files as `st_runtime.api.load` does:
  `loader.load_texts` (parse with the native prelude, check) and then
  `compiler.compile_program` (Python classes and functions, ready to run);
* blark: `blark.parse.get_parser()` parses the same texts (its raw Lark
  parse tree, blark's fastest path, no summary or transform).

File sets:

* `accept corpus`: `tests/corpus/accept/*.st`, small real programs each
  loaded on its own (one load per file, as a user checks one file);
* `generated/iec`, `generated/crank_iec`, `generated/moving_base_iec`: the
  rendered POUs of each platform, one load per folder (they are one project);
* `examples/plc`: the README's example program, one load.

Files blark's grammar (TwinCAT's) rejects are left out on both sides; their
number is printed.  Times are CPU seconds of this process
(`time.process_time`): for ours the median of `--rounds` rounds after a
warm-up round, for blark one pass (its Earley parser takes minutes on the
generated sets), after its grammar is built; neither side pays for building
its grammar.  The ratio is blark's time over ours: how many times faster
our full load is than blark only parsing.

Target (issue 15): at least 100x on every file set.
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from st_runtime import loader  # noqa: E402
from st_runtime.compiler import compile_program  # noqa: E402

clock = time.process_time


def file_sets() -> list[tuple[str, list[dict[str, str]]]]:
    """(name, loads): each load is one program, path -> text."""
    def read(path: Path) -> str:
        return path.read_text(encoding="utf-8")

    accept = sorted((ROOT / "tests" / "corpus" / "accept").glob("*.st"))
    sets = [("accept corpus", [{str(p): read(p)} for p in accept])]
    for folder in ("generated/iec", "generated/crank_iec", "generated/moving_base_iec", "examples/plc"):
        files = sorted((ROOT / folder).rglob("*.st"))
        sets.append((folder, [{str(p): read(p) for p in files}]))
    return sets


def load_once(texts: dict[str, str]) -> bool:
    result = loader.load_texts(dict(texts))
    if result.program is None:
        return False
    compile_program(result.program)
    return True


def blark_parser():
    try:
        from blark.parse import get_parser
    except ImportError:
        return None
    return get_parser()


def blark_parse_time(parser, text: str) -> float | None:
    """CPU seconds blark takes to parse `text`, or None when its grammar rejects it."""
    start = clock()
    try:
        parser.parse(text, start="iec_source")
    except Exception:  # blark's grammar is TwinCAT's: some IEC corners differ
        return None
    return clock() - start


def median_time(work, rounds: int) -> float:
    work()   # warm-up: grammars, caches
    times = []
    for _ in range(rounds):
        start = clock()
        work()
        times.append(clock() - start)
    return statistics.median(times)


def main() -> int:
    options = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    options.add_argument("--rounds", type=int, default=5)
    options.add_argument("--sets", nargs="*", metavar="NAME",
                         help="only these file sets (names as printed, e.g. 'accept corpus' examples/plc)")
    args = options.parse_args()
    parser = blark_parser()
    if parser is None:
        print("blark is not installed (pip install -e '.[test]'): nothing to compare against")
        return 0
    print(f"Load (parse + check + compile) against blark's parse; CPU seconds, Python "
          f"{sys.version.split()[0]}, load average {os.getloadavg()[0]:.1f}")
    print(f"{'file set':<28}{'files':>6}{'lines':>7}{'left out':>9}{'ours s':>10}{'blark s':>10}"
          f"{'ratio':>8}")
    worst = None
    for name, loads in file_sets():
        if args.sets and name not in args.sets:
            continue
        kept, left_out, theirs = [], 0, 0.0
        for texts in loads:
            accepted, blark_seconds = {}, 0.0
            for path, text in texts.items():
                seconds = blark_parse_time(parser, text)
                if seconds is None:
                    left_out += 1
                else:
                    accepted[path], blark_seconds = text, blark_seconds + seconds
            if accepted and load_once(accepted):
                kept.append(accepted)
                theirs += blark_seconds
            else:   # our loader refuses it (or nothing left): not comparable
                left_out += len(accepted)
        if not kept:
            print(f"{name:<28}  nothing both accept")
            continue
        texts = [t for load in kept for t in load.values()]
        lines = sum(t.count("\n") for t in texts)
        ours = median_time(lambda: [load_once(load) for load in kept], args.rounds)
        ratio = theirs / ours
        worst = ratio if worst is None else min(worst, ratio)
        print(f"{name:<28}{len(texts):>6}{lines:>7}{left_out:>9}{ours:>10.3f}{theirs:>10.3f}"
              f"{ratio:>7.0f}x", flush=True)
    if worst is not None:
        print(f"lowest ratio {worst:.0f}x (target >= 100x): {'met' if worst >= 100 else 'NOT met'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
