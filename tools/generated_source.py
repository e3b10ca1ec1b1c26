"""The generated Python and the diagnostics of every load of the repository's ST files: proof
that a change to the parser, checker or compiler left both exactly as they were.

    # record with the code before the change (any checkout: PYTHONPATH picks the tree)
    PYTHONPATH=/path/to/main .venv/bin/python tools/generated_source.py record before.json
    # check the working tree against it
    .venv/bin/python tools/generated_source.py check before.json

The loads, each under the dialects iec, nj and codesys, as `st_runtime.api.load_sources` does
(`loader.load_texts`, then `compile_program`): every `.st` and `.xml` file of tests/corpus/*
(accept, reject, reject_syntax), examples/plc and generated/* alone, and each of those folders
as one project (the benchmark's sets: `benchmarks/bench_load_vs_blark.py`).  The files are read
from this script's tree, by paths relative to it, so two checkouts load the same texts.

Recorded per load, as SHA-256 hashes:

* `diagnostics`: the load's list (code, message, file, line, column, severity), in its order;
* `raw`: the same diagnostics in the order the parser and checker gave them, before the
  loader sorts them by position (a change of order inside one position shows here);
* `compiled`: every (file name, source) the compiler hands to `compile()` (its `_code_of`),
  in order, one hash each, and `sources`: `python_sources` per POU, the text kept for reading;
* `error`: a `CompileError`'s message, when the compile refuses the program.

`check` names each load and each part that differs.  Not a test: it takes a minute or two and
compares two versions of the code.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
DIALECTS = ("iec", "nj", "codesys")
FOLDERS = ("tests/corpus", "examples/plc", "generated")


def digest(text: str) -> str:
    return hashlib.sha256(text.encode("utf-8", "surrogatepass")).hexdigest()[:20]


def diagnostics_text(diagnostics) -> str:
    return "\n".join(f"{d.code}|{d.message}|{d.pos.file}|{d.pos.line}|{d.pos.col}|{d.severity}"
                     for d in diagnostics)


def loads() -> list[tuple[str, list[Path]]]:
    """(name, files): each file alone, then each folder of files as one project."""
    single, projects = [], []
    for top in FOLDERS:
        for folder in sorted({p.parent for p in (ROOT / top).rglob("*") if p.suffix in (".st", ".xml")}):
            files = sorted(p for p in folder.iterdir() if p.suffix in (".st", ".xml"))
            single += [(str(p.relative_to(ROOT)), [p]) for p in files]
            projects.append((str(folder.relative_to(ROOT)) + "/", files))
    return single + projects


class Recorder:
    """Hooks the loader's ordering and the compiler's `compile()` to see what they are given."""

    def __init__(self):
        from st_runtime import loader
        from st_runtime import compiler
        self.loader, self.compiler = loader, compiler
        self.raw, self.compiled = [], []
        ordered, code_of = loader._ordered, compiler._code_of

        def seen_ordered(diagnostics, paths):
            self.raw = list(diagnostics)
            return ordered(diagnostics, paths)

        def seen_code_of(source, filename):
            self.compiled.append(digest(filename + "\0" + source))
            return code_of(source, filename)

        loader._ordered, compiler._code_of = seen_ordered, seen_code_of

    def load(self, files: list[Path], dialect: str) -> dict:
        texts = {str(p.relative_to(ROOT)): p.read_text(encoding="utf-8") for p in files}
        self.raw, self.compiled = [], []
        result = self.loader.load_texts(texts, dialect)
        record = {"diagnostics": digest(diagnostics_text(result.diagnostics)),
                  "raw": digest(diagnostics_text(self.raw))}
        if result.program is not None:
            try:
                compiled = self.compiler.compile_program(result.program)
            except self.compiler.CompileError as exc:
                record["error"] = str(exc)
            else:
                record["sources"] = {k: digest(v) for k, v in compiled.python_sources.items()}
            record["compiled"] = list(self.compiled)
        return record


def record_all() -> dict:
    recorder = Recorder()
    return {f"{dialect}:{name}": recorder.load(files, dialect)
            for name, files in loads() for dialect in DIALECTS}


def differences(before: dict, after: dict) -> list[str]:
    found = []
    for key in sorted(before.keys() | after.keys()):
        if key not in before or key not in after:
            found.append(f"{key}: only {'after' if key in after else 'before'}")
            continue
        a, b = before[key], after[key]
        for part in sorted(a.keys() | b.keys()):
            if a.get(part) == b.get(part):
                continue
            if part == "sources" and isinstance(a.get(part), dict) and isinstance(b.get(part), dict):
                pous = sorted(p for p in a[part].keys() | b[part].keys() if a[part].get(p) != b[part].get(p))
                found.append(f"{key}: python_sources differ for {', '.join(pous)}")
            else:
                found.append(f"{key}: {part} differ")
    return found


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("mode", choices=("record", "check"))
    parser.add_argument("file")
    args = parser.parse_args(argv)
    now = record_all()
    if args.mode == "record":
        Path(args.file).write_text(json.dumps(now, indent=0, sort_keys=True))
        print(f"recorded {len(now)} loads to {args.file}")
        return 0
    found = differences(json.loads(Path(args.file).read_text()), now)
    for line in found:
        print(line)
    print(f"{len(now)} loads: " + ("the same" if not found else f"{len(found)} differences"))
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
