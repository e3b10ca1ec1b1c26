"""Copy the corpus files named in corpus/manifest.tsv out of local git mirrors.

    python benchmarks/corpus_export.py MIRRORS OUT

MIRRORS holds one bare or normal git clone per repository, named
`owner+name` (e.g. `/work/.mirror/ironplc+ironplc/repo` or
`MIRRORS/ironplc+ironplc`).  Nothing is downloaded: the files are read with
`git show COMMIT:PATH` and written to OUT/<origin>/<path>.  Third-party code
stays out of this repository; only the manifest (repository, commit, path,
licence) is committed.
"""

from __future__ import annotations

import csv
import os
import subprocess
import sys

MANIFEST = os.path.join(os.path.dirname(__file__), "corpus", "manifest.tsv")


def rows(manifest: str = MANIFEST) -> list[dict[str, str]]:
    with open(manifest, encoding="utf-8", newline="") as handle:
        return list(csv.DictReader(handle, delimiter="\t"))


def _git_dir(mirrors: str, repository: str) -> str:
    base = os.path.join(mirrors, repository.replace("/", "+"))
    nested = os.path.join(base, "repo")
    return nested if os.path.isdir(nested) else base


def main(argv: list[str]) -> int:
    if len(argv) != 2:
        print(__doc__.strip().splitlines()[2].strip(), file=sys.stderr)
        return 2
    mirrors, out = argv
    missing = 0
    for row in rows():
        blob = subprocess.run(["git", "-C", _git_dir(mirrors, row["repository"]), "show",
                               f"{row['commit']}:{row['path']}"], capture_output=True)
        if blob.returncode != 0:
            print(f"missing: {row['repository']} {row['path']}", file=sys.stderr)
            missing += 1
            continue
        target = os.path.join(out, row["origin"], row["path"])
        os.makedirs(os.path.dirname(target), exist_ok=True)
        with open(target, "wb") as handle:
            handle.write(blob.stdout)
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
