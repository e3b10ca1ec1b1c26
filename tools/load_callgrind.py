"""Machine instructions of one round of the accept corpus's loads (issue 15's second measure),
or of one `api.load` of a folder (issue 17's load criterion).

    python tools/load_callgrind.py [TREE ...]
    python tools/load_callgrind.py --folder generated/iec [--mode fresh|repeat|first] [TREE ...]

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

`--folder`: one `api.load` of the folder (relative to each tree, or one absolute path for
every tree: e.g. the issue's start and main loading the same files).  `--mode` says which load
is measured: `fresh` (the default) the third load of the process after `compiler._CODE`, the
cache of compiled Python by source, is emptied (a tree without that cache, such as issue 17's
start 0814391, compiles its code at every load: fresh compares the same work); `repeat` the
third load with every cache as the first two left it; `first` the first load in the process
(the lazy imports, the prelude and the grammar read from the user cache included).  The child
uses only `st_runtime.api.load`, which every tree since the issue's start has.
"""

from __future__ import annotations

import argparse
import glob
import os
import re
import subprocess
import sys
import tempfile
from itertools import starmap
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def folder_child(folder: str, mode: str) -> None:
    import st_runtime.compiler
    from st_runtime import api

    if mode in ("fresh", "repeat"):
        for _ in range(2):
            api.load([folder])
    if mode == "fresh":
        getattr(st_runtime.compiler, "_CODE", {}).clear()
    measured(api.load, [([folder],)])


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
    measured(load, [(texts,) for texts in loads])


def measured(function, calls: list[tuple]) -> None:
    """Each call of `function` with the arguments of `calls`, the only code counted: the
    instrumentation switched on here, the collection on only inside `starmap`."""
    subprocess.run(["callgrind_control", "-i", "on", str(os.getpid())], check=True, stdout=subprocess.DEVNULL)
    for _ in starmap(function, calls):
        pass


def instructions(tree: Path, child_args: list[str]) -> int:
    with tempfile.TemporaryDirectory() as scratch:
        out = Path(scratch) / "callgrind.out"
        env = dict(os.environ, PYTHONHASHSEED="0", PYTHONPATH=str(tree))
        subprocess.run(["valgrind", "--tool=callgrind", "--instr-atstart=no", "--toggle-collect=starmap_next",
                        f"--callgrind-out-file={out}", sys.executable, __file__, "--child", *child_args],
                       cwd=tree, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
        return int(re.search(r"^summary:\s+(\d+)", out.read_text(), re.M).group(1))


def main() -> None:
    if sys.argv[1:2] == ["--child"]:
        child() if len(sys.argv) == 2 else folder_child(*sys.argv[2:4])
        return
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("trees", nargs="*", metavar="TREE", help="source trees (default: this one)")
    parser.add_argument("--folder", help="measure one api.load of this folder instead of the accept corpus")
    parser.add_argument("--mode", choices=("fresh", "repeat", "first"), default="fresh",
                        help="which load of the folder is measured (default fresh; see above)")
    args = parser.parse_args()
    for tree in [Path(t).resolve() for t in args.trees] or [ROOT]:
        if args.folder is None:
            print(f"{tree}: {instructions(tree, []):,} instructions, one accept corpus round")
            continue
        folder = (tree / args.folder).resolve()
        print(f"{tree}: {instructions(tree, [str(folder), args.mode]):,} instructions, "
              f"one {args.mode} load of {folder}")


if __name__ == "__main__":
    main()
