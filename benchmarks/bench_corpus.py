"""Corpus acceptance: which third-party ST files st_runtime loads, per origin.

    python benchmarks/bench_corpus.py CORPUS_DIR [--manifest FILE]

CORPUS_DIR/<origin>/<path> holds the files of benchmarks/corpus/manifest.tsv
(see corpus_export.py; this script fetches nothing).  Each origin is checked
with the dialect the manifest gives it.  A file counts as accepted when it
loads alone, or when the origin's files loaded together (project context: a
file may use another's types and POUs) report no error in it.  A crash is an
internal error (a code ending in -099) or a Python exception.  Prints, per
origin, files accepted, files that at least parse (some test suites hold
syntax-only files with undeclared names), and the refusal reasons (first
error code and message, counted); exit 0.
"""

from __future__ import annotations

import argparse
import collections
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))

from benchmarks.corpus_export import MANIFEST, rows  # noqa: E402
from st_runtime.loader import load_texts  # noqa: E402
from st_runtime.parser import parse  # noqa: E402


def _errors(texts: dict[str, str], dialect: str):
    try:
        result = load_texts(texts, dialect)
    except Exception as exc:  # a crash is what this benchmark must find
        return None, f"crash: {type(exc).__name__}: {exc}"
    return [d for d in result.diagnostics if d.is_error], None


def _reason(diagnostic) -> str:
    message = diagnostic.message if len(diagnostic.message) < 90 else diagnostic.message[:87] + "..."
    return f"{diagnostic.code}: {message}"


def measure(corpus: str, manifest: str = MANIFEST) -> dict[str, dict]:
    by_origin: dict[str, list[dict[str, str]]] = collections.defaultdict(list)
    for row in rows(manifest):
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
        together, crash = _errors(texts, dialect)
        accepted, crashes, parsed, reasons = 0, 0, 0, collections.Counter()
        for path, text in texts.items():
            parsed += parse(text, path)[0] is not None
            alone, crash_alone = _errors({path: text}, dialect)
            crash_alone = crash_alone or next((d.message for d in alone or ()
                                               if d.code.endswith("-099")), None)
            if crash_alone:
                crashes += 1
                reasons[f"crash: {crash_alone}"] += 1
            elif not alone or (together is not None
                               and not any(d.pos.file == path for d in together)):
                accepted += 1
            else:
                reasons[_reason(alone[0])] += 1
        report[origin] = {"dialect": dialect, "files": len(files), "present": len(texts),
                          "accepted": accepted, "parsed": parsed, "crashes": crashes,
                          "reasons": reasons}
    return report


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(description="corpus acceptance per origin")
    parser.add_argument("corpus")
    parser.add_argument("--manifest", default=MANIFEST)
    parser.add_argument("--reasons", type=int, default=12, help="reasons shown per origin")
    args = parser.parse_args(argv)
    report = measure(args.corpus, args.manifest)
    total = [0, 0]
    for origin, r in report.items():
        share = 100.0 * r["accepted"] / r["present"] if r["present"] else 0.0
        print(f"{origin} (--dialect {r['dialect']}): {r['accepted']}/{r['present']} accepted "
              f"({share:.0f} %), {r['parsed']} parse, {r['crashes']} crashes"
              + (f", {r['files'] - r['present']} missing" if r["files"] != r["present"] else ""))
        for reason, count in r["reasons"].most_common(args.reasons):
            print(f"    {count:3d}  {reason}")
        total[0] += r["accepted"]
        total[1] += r["present"]
    print(f"all: {total[0]}/{total[1]} accepted")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
