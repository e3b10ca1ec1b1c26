"""Machine instructions of one round of the accept corpus's loads (issue 15's second measure).

    python tools/load_callgrind.py [TREE ...]

For each tree (default: this one), runs callgrind on a child that loads every file of
tests/corpus/accept as `benchmarks/bench_load_vs_blark.py` does (`loader.load_texts`, then
`compile_program`; the compiler's code cache emptied before each load), twice unmeasured
and once measured, and prints the instructions of the measured round.  Only that round is
counted: instrumentation starts off (`--instr-atstart=no`), the child switches it on
(`callgrind_control -i on`) just before the round, and collection is on only inside
`itertools.starmap`, which runs the round (`--toggle-collect=starmap_next`).
`PYTHONHASHSEED=0`; the count is the same from run to run of one tree, and moves by a
million or two (0.1-0.2%) between trees that differ in nothing the round runs (dicts keyed
by `id()` probe by address).  Needs valgrind (Debian's package).  Slow: about half a
minute a tree on an idle machine.
"""

from __future__ import annotations

import glob
import os
import re
import subprocess
import sys
import tempfile
from itertools import starmap
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def child() -> None:
    from st_runtime import compiler as compiler_module
    from st_runtime import loader

    loads = [{path: Path(path).read_text(encoding="utf-8")}
             for path in sorted(glob.glob("tests/corpus/accept/*.st"))]

    def load(texts: dict[str, str]) -> None:
        compiler_module._CODE.clear()
        result = loader.load_texts(dict(texts))
        if result.program is not None:
            compiler_module.compile_program(result.program)

    for _ in range(2):
        for texts in loads:
            load(texts)
    subprocess.run(["callgrind_control", "-i", "on", str(os.getpid())], check=True, stdout=subprocess.DEVNULL)
    for _ in starmap(load, [(texts,) for texts in loads]):
        pass


def instructions(tree: Path) -> int:
    with tempfile.TemporaryDirectory() as scratch:
        out = Path(scratch) / "callgrind.out"
        env = dict(os.environ, PYTHONHASHSEED="0", PYTHONPATH=str(tree))
        subprocess.run(["valgrind", "--tool=callgrind", "--instr-atstart=no", "--toggle-collect=starmap_next",
                        f"--callgrind-out-file={out}", sys.executable, __file__, "--child"],
                       cwd=tree, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
        return int(re.search(r"^summary:\s+(\d+)", out.read_text(), re.M).group(1))


def main() -> None:
    if sys.argv[1:] == ["--child"]:
        child()
        return
    for tree in [Path(t).resolve() for t in sys.argv[1:]] or [ROOT]:
        print(f"{tree}: {instructions(tree):,} instructions, one accept corpus round")


if __name__ == "__main__":
    main()
