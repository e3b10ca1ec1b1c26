"""The conformance corpus through the checker.

Reject corpus: every `tests/corpus/reject/*.st` starts with
`(* expect: CODE line N [dialect nj] *)`; loading it must fail with that code
on that line, and with no other error (one root cause, one diagnostic).
Accept corpus: every `tests/corpus/accept/*.st` loads with no error.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from st_runtime.loader import load_texts

CORPUS = Path(__file__).parent / "corpus"
HEADER = re.compile(r"\(\* expect: (?P<code>[EW]-[A-Z]+-\d{3}) line (?P<line>\d+)"
                    r"(?: dialect (?P<dialect>iec|nj|codesys))? \*\)")

REJECT = sorted((CORPUS / "reject").glob("*.st"))
ACCEPT = sorted((CORPUS / "accept").glob("*.st"))


def expectation(path: Path) -> tuple[str, int, str]:
    first = path.read_text(encoding="utf-8").splitlines()[0]
    m = HEADER.match(first)
    assert m, f"{path.name}: first line must be (* expect: CODE line N *)"
    return m["code"], int(m["line"]), m["dialect"] or "iec"


def test_reject_corpus_is_large_enough():
    assert len(REJECT) >= 60


@pytest.mark.parametrize("path", REJECT, ids=lambda p: p.stem)
def test_reject(path: Path):
    code, line, dialect = expectation(path)
    result = load_texts({path.name: path.read_text(encoding="utf-8")}, dialect)
    errors = [d for d in result.errors]
    assert result.program is None
    assert any(d.code == code and d.pos.line == line for d in errors), \
        f"expected {code} on line {line}, got: " + "; ".join(d.header() for d in errors)
    others = [d.header() for d in errors if not (d.code == code and d.pos.line == line)]
    assert not others, f"cascade or unrelated errors: {others}"


def accept_dialect(text: str) -> str:
    """An accept file opening with `(* dialect codesys ...` is checked in that dialect."""
    m = re.match(r"\(\* dialect (iec|nj|codesys)\b", text)
    return m[1] if m else "iec"


@pytest.mark.parametrize("path", ACCEPT, ids=lambda p: p.stem)
def test_accept_passes_checker(path: Path):
    text = path.read_text(encoding="utf-8")
    result = load_texts({path.name: text}, accept_dialect(text))
    assert not result.errors, "; ".join(d.header() for d in result.errors)
    assert result.program is not None
