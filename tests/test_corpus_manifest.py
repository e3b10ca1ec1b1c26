"""The third-party corpus manifest (benchmarks/corpus/manifest.tsv) is a frozen, complete record."""

from __future__ import annotations

import csv
import re
from pathlib import Path

MANIFEST = Path(__file__).parent.parent / "benchmarks" / "corpus" / "manifest.tsv"


def rows() -> list[dict[str, str]]:
    with open(MANIFEST, encoding="utf-8", newline="") as handle:
        return list(csv.DictReader(handle, delimiter="\t"))


def test_every_row_records_where_the_file_is_and_what_it_is():
    seen = set()
    for row in rows():
        assert row["dialect"] in ("iec", "nj", "codesys"), row
        assert row["kind"] in ("project", "fragment", "erratum"), row
        assert re.fullmatch(r"[0-9a-f]{40}", row["commit"]), row
        assert "/" in row["repository"] and row["path"] and row["licence"], row
        assert (row["origin"], row["path"]) not in seen, row
        seen.add((row["origin"], row["path"]))


def test_an_origin_has_one_dialect():
    dialects: dict[str, set] = {}
    for row in rows():
        dialects.setdefault(row["origin"], set()).add(row["dialect"])
    assert all(len(d) == 1 for d in dialects.values()), dialects
