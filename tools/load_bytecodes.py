"""Bytecode instructions of a load, per stage and per function (issue 15's measure).

    python tools/load_bytecodes.py [--top N] [--set accept|plc|iec] [--rounds N]

Loads a file set as `benchmarks/bench_load_vs_blark.py` does (`loader.parse_texts`,
`checker.check`, `compiler.compile_program`; the compiler's code cache emptied
before each load), first twice untraced (so the prelude, the grammar and every
per-process memo are made), then `--rounds` times under `sys.settrace` with opcode
events, and prints the bytecode instructions executed per round: the whole load,
each stage, the Python calls, and the `--top` functions by inclusive count
(a recursive function counted once per outermost call) with their exclusive count.

A count, not a time: the same on a busy machine as on an idle one, and the same
from run to run (`PYTHONHASHSEED` aside: set it for the last digit).  Compare two
trees by running this file from each (`PYTHONPATH=/path/to/tree`), each from a
snapshot.  What it does not see: C code (the regex engine, `compile()`, dict and
set operations), which callgrind counts (docs/load.md, the eighth round).
"""

from __future__ import annotations

import argparse
import sys
from collections import Counter
from pathlib import Path


def file_set(name: str, root: Path) -> list[dict[str, str]]:
    def read(path: Path) -> str:
        return path.read_text(encoding="utf-8")
    if name == "accept":
        return [{str(p): read(p)} for p in sorted((root / "tests/corpus/accept").glob("*.st"))]
    folder = {"plc": "examples/plc", "iec": "generated/iec"}[name]
    return [{str(p): read(p) for p in sorted((root / folder).rglob("*.st"))}]


class Tally:
    """Opcode events per code object (exclusive) and per outermost call (inclusive)."""

    def __init__(self) -> None:
        self.total = 0
        self.calls = 0
        self.own: Counter = Counter()
        self.inclusive: Counter = Counter()
        self._stack: list[tuple[object, int]] = []
        self._open: Counter = Counter()

    def trace(self, frame, event, arg):
        if event == "call":
            frame.f_trace_opcodes = True
            code = frame.f_code
            self.calls += 1
            self._stack.append((code, self.total))
            self._open[code] += 1
            return self.trace
        if event == "opcode":
            self.total += 1
            self.own[frame.f_code] += 1
        elif event == "return" and self._stack:
            code, start = self._stack.pop()
            self._open[code] -= 1
            if not self._open[code]:
                self.inclusive[code] += self.total - start
        return self.trace

    def run(self, function, *args):
        sys.settrace(self.trace)
        try:
            return function(*args)
        finally:
            sys.settrace(None)


def name_of(code) -> str:
    path = code.co_filename
    short = path.split("st_runtime/", 1)[-1] if "st_runtime/" in path else Path(path).name
    return f"{short}:{code.co_firstlineno} {code.co_qualname if hasattr(code, 'co_qualname') else code.co_name}"


def main() -> None:
    options = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    options.add_argument("--set", default="accept", choices=("accept", "plc", "iec"))
    options.add_argument("--rounds", type=int, default=1)
    options.add_argument("--top", type=int, default=40)
    arguments = options.parse_args()

    from st_runtime import loader
    from st_runtime import compiler as compiler_module
    from st_runtime.checker import check
    from st_runtime.compiler import compile_program

    root = Path(loader.__file__).resolve().parent.parent
    loads = file_set(arguments.set, root)
    stages = {"parse": Tally(), "check": Tally(), "compile": Tally()}

    def one_round(tallies=None) -> int:
        loaded = 0
        for texts in loads:
            compiler_module._CODE.clear()
            run = (lambda stage, f, *a: tallies[stage].run(f, *a)) if tallies else (lambda stage, f, *a: f(*a))
            _, parsed, diagnostics = run("parse", loader.parse_texts, dict(texts))
            program, found = run("check", check, [file for _, file in parsed], "iec", None)
            if program is None or any(d.is_error for d in diagnostics + found):
                continue
            run("compile", compile_program, program)
            loaded += 1
        return loaded

    one_round()
    one_round()
    for _ in range(arguments.rounds):
        loaded = one_round(stages)
    rounds = arguments.rounds
    whole = sum(t.total for t in stages.values())
    print(f"{arguments.set}: {len(loads)} sets of files, {loaded} compiled; per round:")
    print(f"  whole load {whole // rounds:,} bytecodes, {sum(t.calls for t in stages.values()) // rounds:,} calls")
    for stage, tally in stages.items():
        print(f"  {stage:8s} {tally.total // rounds:,} bytecodes, {tally.calls // rounds:,} calls")
    if not arguments.top:
        return
    inclusive: Counter = Counter()
    own: Counter = Counter()
    for tally in stages.values():
        for code, count in tally.inclusive.items():
            inclusive[name_of(code)] += count
        for code, count in tally.own.items():
            own[name_of(code)] += count
    print(f"top {arguments.top} by inclusive count (inclusive / own):")
    for name, count in inclusive.most_common(arguments.top):
        print(f"  {count // rounds:>10,} {own[name] // rounds:>10,}  {name}")
    print(f"top {arguments.top} by own count:")
    for name, count in own.most_common(arguments.top):
        print(f"  {count // rounds:>10,}  {name}")


if __name__ == "__main__":
    main()
