"""Corpus acceptance: which third-party ST files st_runtime loads, per origin, before and after.

    python benchmarks/bench_corpus.py CORPUS_DIR [--manifest FILE] [--before COMMIT]

CORPUS_DIR/<origin>/<path> holds the files of benchmarks/corpus/manifest.tsv
(see corpus_export.py; this script fetches nothing).  Each origin is checked
with the dialect the manifest gives it.  A file counts as accepted when it
loads alone, or when the origin's files loaded together (project context: a
file may use another's types and POUs) report no error in it.  A crash is an
internal error (a code ending in -099) or a Python exception.

The manifest's `kind` says what a file is: `project` (a file of a complete
project or library, the issue's target), `fragment` (a compiler's test input:
syntax snippets, often deliberately invalid or with undeclared names) or
`erratum` (a file whose text is not valid ST as published, e.g. a typo in the
standard's draft example; refusing it is right).  The targets count only
`project` files.

`--before COMMIT` (default 06e0508, main before the corpus work) measures the
same files with that commit's st_runtime, extracted with `git archive` into a
temporary folder and run in a child process, side by side.  Prints, per
origin: files accepted before and after, files that parse, crashes, and the
refusal reasons of the rest (first error code and message, counted); then
the share of project files accepted, standard ST (`--dialect iec`) and
vendor dialects apart.  Exit 0.
"""

from __future__ import annotations

import argparse
import collections
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
MANIFEST = os.path.join(HERE, "corpus", "manifest.tsv")
BEFORE = "06e0508"


def _rows(manifest: str) -> list[dict[str, str]]:
    import csv
    with open(manifest, encoding="utf-8", newline="") as handle:
        return list(csv.DictReader(handle, delimiter="\t"))


def _errors(load_texts, texts: dict[str, str], dialect: str):
    try:
        result = load_texts(texts, dialect)
    except Exception as exc:  # a crash is what this benchmark must find
        return None, f"crash: {type(exc).__name__}: {exc}"
    return [d for d in result.diagnostics if d.is_error], None


def _reason(diagnostic) -> str:
    message = diagnostic.message if len(diagnostic.message) < 90 else diagnostic.message[:87] + "..."
    return f"{diagnostic.code}: {message}"


def measure(corpus: str, manifest: str = MANIFEST) -> dict[str, dict]:
    """Per origin: dialect, files, accepted paths, parsed, crashes, reasons."""
    from st_runtime.loader import load_texts
    from st_runtime.parser import parse

    by_origin: dict[str, list[dict[str, str]]] = collections.defaultdict(list)
    for row in _rows(manifest):
        by_origin[row["origin"]].append(row)
    report = {}
    for origin, files in by_origin.items():
        dialect = files[0]["dialect"]
        texts = {}
        for row in files:
            path = os.path.join(corpus, origin, row["path"])
            if os.path.exists(path):
                with open(path, encoding="utf-8-sig", errors="replace") as handle:
                    texts[row["path"]] = handle.read()
        together, crash = _errors(load_texts, texts, dialect)
        accepted, crashes, parsed, reasons = [], 0, 0, collections.Counter()
        for path, text in texts.items():
            parsed += parse(text, path)[0] is not None
            alone, crash_alone = _errors(load_texts, {path: text}, dialect)
            crash_alone = crash_alone or next((d.message for d in alone or ()
                                               if d.code.endswith("-099")), None)
            if crash_alone:
                crashes += 1
                reasons[f"crash: {crash_alone}"] += 1
            elif not alone or (together is not None
                               and not any(d.pos.file == path for d in together)):
                accepted.append(path)
            else:
                reasons[_reason(alone[0])] += 1
        report[origin] = {"dialect": dialect, "files": len(files), "present": len(texts),
                          "accepted": accepted, "parsed": parsed, "crashes": crashes,
                          "reasons": dict(reasons)}
    return report


def measure_at(commit: str, corpus: str, manifest: str) -> dict[str, dict] | str:
    """`measure` with st_runtime as it was at `commit` (a child process), or why not."""
    with tempfile.TemporaryDirectory() as tree:
        archive = subprocess.run(["git", "-C", os.path.dirname(HERE), "archive", commit, "st_runtime"],
                                 capture_output=True)
        if archive.returncode != 0:
            return archive.stderr.decode(errors="replace").strip()
        subprocess.run(["tar", "-x", "-C", tree], input=archive.stdout, check=True)
        child = subprocess.run([sys.executable, os.path.abspath(__file__), corpus,
                                "--manifest", manifest, "--runtime", tree, "--json"],
                               capture_output=True, text=True)
        if child.returncode != 0:
            return child.stderr.strip().splitlines()[-1:] or "failed"
        return json.loads(child.stdout)


def _share(accepted: int, present: int) -> str:
    return f"{accepted}/{present} ({100.0 * accepted / present:.0f} %)" if present else "0/0"


def _print(after: dict, before: dict | str, kinds: dict[str, str], commit: str, shown: int) -> None:
    if isinstance(before, str):
        print(f"before ({commit}): not measured: {before}")
        before = {}
    totals = collections.defaultdict(lambda: [0, 0, 0])   # class -> before, after, present
    for origin, r in after.items():
        old = before.get(origin, {}).get("accepted", [])
        print(f"{origin} (--dialect {r['dialect']}): before {_share(len(old), r['present'])}, "
              f"after {_share(len(r['accepted']), r['present'])}, {r['parsed']} parse, "
              f"{r['crashes']} crashes"
              + (f", {r['files'] - r['present']} missing" if r["files"] != r["present"] else ""))
        for reason, count in sorted(r["reasons"].items(), key=lambda kv: -kv[1])[:shown]:
            print(f"    {count:3d}  {reason}")
        for path in {p for p in kinds if p[0] == origin}:
            kind = kinds[path]
            group = ("standard ST" if r["dialect"] == "iec" else "vendor dialect") + f" {kind}"
            totals[group][0] += path[1] in old
            totals[group][1] += path[1] in r["accepted"]
            totals[group][2] += 1
    crashes = sum(r["crashes"] for r in after.values())
    for group in sorted(totals):
        b, a, n = totals[group]
        print(f"{group} files: before {_share(b, n)}, after {_share(a, n)}")
    print(f"crashes: {crashes}")


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(description="corpus acceptance per origin")
    parser.add_argument("corpus")
    parser.add_argument("--manifest", default=MANIFEST)
    parser.add_argument("--reasons", type=int, default=12, help="reasons shown per origin")
    parser.add_argument("--before", default=BEFORE, help="commit measured side by side")
    parser.add_argument("--runtime", help=argparse.SUPPRESS)   # child: import st_runtime from here
    parser.add_argument("--json", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    sys.path.insert(0, args.runtime or os.path.join(HERE, ".."))
    after = measure(args.corpus, args.manifest)
    if args.json:
        print(json.dumps(after))
        return 0
    kinds = {(row["origin"], row["path"]): row["kind"] for row in _rows(args.manifest)}
    before = measure_at(args.before, os.path.abspath(args.corpus), os.path.abspath(args.manifest))
    _print(after, before, kinds, args.before, args.reasons)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
