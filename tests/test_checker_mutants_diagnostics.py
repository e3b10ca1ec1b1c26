"""Every diagnostic the checker gives is well formed (issue 16, mutation testing).

The reject corpus's own test (test_checker_corpus) asserts the code and line
of the one expected diagnostic; mutation testing found that a message, a
column or the position itself could be lost (None) or a code misspelt
without any test noticing.  README and docs/diagnostics: a diagnostic has a
registered code (E-... an error, W-... a warning), a message that says what
was expected and what was found, and a position (file, 1-based line and
column) inside the file it is about.  This holds for every diagnostic of
every reject file, whatever its code.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from st_runtime.ast import Pos
from st_runtime.checker import typesys as ts
from st_runtime.diagnostics import CODES, ERROR, WARNING
from st_runtime.loader import load_texts
from checker_helpers import walk

CORPUS = Path(__file__).parent / "corpus"
HEADER = re.compile(r"\(\* expect: [EW]-[A-Z]+-\d{3} line \d+(?: dialect (?P<dialect>iec|nj|codesys))? \*\)")
REJECT = sorted((CORPUS / "reject").glob("*.st"))
CODE = re.compile(r"[EW]-[A-Z]+-\d{3}")


def assert_well_formed(diagnostics, texts: dict[str, str]) -> None:
    for d in diagnostics:
        assert CODE.fullmatch(d.code), d
        assert d.code in CODES, f"{d.code} is not registered"
        assert d.severity == (ERROR if d.code.startswith("E") else WARNING), d
        assert isinstance(d.message, str) and d.message.strip(), d
        assert isinstance(d.pos, Pos), d
        lines = texts[d.pos.file].splitlines()
        assert 1 <= d.pos.line <= len(lines), d
        assert 1 <= d.pos.col <= len(lines[d.pos.line - 1]) + 1, d
        # The header names the place as file:line:col and the code in brackets.
        assert d.header().startswith(f"{d.pos.file}:{d.pos.line}:{d.pos.col}: ")
        assert f"[{d.code}]" in d.header()


@pytest.mark.parametrize("path", REJECT, ids=lambda p: p.stem)
def test_every_diagnostic_of_a_reject_file_is_well_formed(path: Path):
    text = path.read_text(encoding="utf-8")
    dialect = HEADER.match(text)["dialect"] or "iec"
    result = load_texts({path.name: text}, dialect)
    assert result.diagnostics
    assert_well_formed(result.diagnostics, {path.name: text})


# ------------------------------------------------ accepted programs

ACCEPT = sorted((CORPUS / "accept").glob("*.st"))


def accept_dialect(text: str) -> str:
    m = re.match(r"\(\* dialect (iec|nj|codesys)\b", text)
    return m[1] if m else "iec"


@pytest.mark.parametrize("path", ACCEPT, ids=lambda p: p.stem)
def test_an_accepted_program_is_placed_and_typed(path: Path):
    """What the checker hands the compiler (st_runtime/checker/__init__.py): every
    statement and expression of a body, including those a chart (SFC) or an
    operator in call form is lowered to, keeps a position in its file (a run-time
    fault names file, line and column), and no expression of an accepted program
    has the ERROR type (ERROR only follows a diagnostic)."""
    text = path.read_text(encoding="utf-8")
    program = load_texts({path.name: text}, accept_dialect(text)).program
    assert program is not None
    bodies = [info.node.body for info in program.pous.values()
              if info.node is not None and info.node.pos.file == path.name]
    lowered = list(program.lowered.values())
    for node in walk([bodies, lowered]):
        assert isinstance(node.pos, Pos), node
        assert node.pos.file == path.name and node.pos.line >= 1, node
    assert not [t for t in program.expr_types.values() if t is ts.ERROR]
