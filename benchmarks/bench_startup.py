"""Benchmark: start-up of `stgen check` on a small file, against `python -c pass`.

    python benchmarks/bench_startup.py [--runs N]

Runs, alternately and N times each (default 15), in fresh processes of this
interpreter:

1. `python -c pass` (the floor: the interpreter's own start-up);
2. `python -c "import st_runtime.loader"` (what checking needs imported);
3. `python -m stgen check SMALL.st` (a one-POU file, four lines);
4. `python -m stgen check examples/plc` (the README's example program).

Each process is measured by its CPU time (user + system, from
`resource.getrusage(RUSAGE_CHILDREN)`), which does not depend on what else
the shared machine runs, and by wall time. The medians and the ratio of each
to `python -c pass` are printed. It also says which heavy modules `stgen
check` imported (NumPy, Jinja2, stgen.render must not be among them).

Target (issue 15): `stgen check` of a small file within 8x `python -c pass`.
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

SMALL = "PROGRAM Main\nVAR x : INT; END_VAR\nx := x + 1;\nEND_PROGRAM\n"

#: Modules `stgen check` has no use for.
HEAVY = ("numpy", "jinja2", "matplotlib", "rich", "stgen.render", "stgen.reference", "st_runtime.compiler")


#: The children may write their bytecode (`__pycache__`), as an installed
#: package has it: with PYTHONDONTWRITEBYTECODE set (as on some CI machines)
#: every start would compile every module again, which is not start-up as a
#: user meets it.
CHILD_ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}


def measure(argv: list[str]) -> tuple[float, float]:
    """(CPU seconds, wall seconds) of one run of `argv`; it must exit 0."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    result = subprocess.run(argv, cwd=ROOT, capture_output=True, text=True, env=CHILD_ENV)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if result.returncode != 0:
        raise SystemExit(f"{' '.join(argv)} failed ({result.returncode}): {result.stderr}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return cpu, wall


def heavy_imports(small: Path) -> list[str]:
    """The HEAVY modules loaded by `stgen check SMALL.st`."""
    probe = ("import sys, runpy; sys.argv = ['stgen', 'check', %r]\n"
             "try:\n    runpy.run_module('stgen', run_name='__main__')\n"
             "except SystemExit:\n    pass\n"
             "print('HEAVY:' + ','.join(m for m in %r if m in sys.modules), file=sys.stderr)") % (str(small), HEAVY)
    result = subprocess.run([sys.executable, "-c", probe], cwd=ROOT, capture_output=True, text=True, env=CHILD_ENV)
    line = [text for text in result.stderr.splitlines() if text.startswith("HEAVY:")][-1]
    return [m for m in line.removeprefix("HEAVY:").split(",") if m]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=15)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        small = Path(tmp) / "small.st"
        small.write_text(SMALL)
        cases = {
            "python -c pass": [sys.executable, "-c", "pass"],
            "import st_runtime.loader": [sys.executable, "-c", "import st_runtime.loader"],
            "stgen check small.st": [sys.executable, "-m", "stgen", "check", str(small)],
            "stgen check examples/plc": [sys.executable, "-m", "stgen", "check", "examples/plc"],
        }
        for argv in cases.values():      # warm the file cache, the bytecode and the user cache
            measure(argv)
        samples: dict[str, list[tuple[float, float]]] = {name: [] for name in cases}
        for _ in range(args.runs):
            for name, argv in cases.items():
                samples[name].append(measure(argv))
        heavy = heavy_imports(small)
    cpu = {name: statistics.median(c for c, _ in runs) for name, runs in samples.items()}
    wall = {name: statistics.median(w for _, w in runs) for name, runs in samples.items()}
    floor_cpu, floor_wall = cpu["python -c pass"], wall["python -c pass"]
    print(f"Start-up, median of {args.runs} runs each (Python {sys.version.split()[0]}, {os.cpu_count()} CPUs)")
    print(f"{'process':<28}{'CPU ms':>9}{'x pass':>9}{'wall ms':>10}{'x pass':>9}")
    for name in cases:
        print(f"{name:<28}{cpu[name] * 1e3:>9.1f}{cpu[name] / floor_cpu:>9.1f}"
              f"{wall[name] * 1e3:>10.1f}{wall[name] / floor_wall:>9.1f}")
    ratio = cpu["stgen check small.st"] / floor_cpu
    print(f"stgen check of a small file: {ratio:.1f}x python -c pass in CPU time (target <= 8x): "
          f"{'met' if ratio <= 8 else 'NOT met'}")
    print(f"heavy modules imported by stgen check: {', '.join(heavy) if heavy else 'none'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
