"""The parser's fast LALR loop (st_runtime/lalr_fast.py) builds exactly the AST, and
leads to exactly the diagnostics, of Lark's own parser loop, on every ST file of the
repository (corpus, rejected syntax, dialect files, generated code, examples)."""

from __future__ import annotations

from pathlib import Path

import pytest

from st_runtime import parser as st_parser

ROOT = Path(__file__).resolve().parent.parent
FILES = sorted({p for folder in ("tests", "generated", "examples", "stgen", "st_runtime")
                for p in (ROOT / folder).rglob("*.st")})


def _both(text: str, path: str, parse=st_parser.parse):
    grammar = st_parser.grammar()
    usable = grammar.fast.usable
    fast = parse(text, path)
    grammar.fast.usable = False           # Lark's own loop, as before the fast path
    try:
        plain = parse(text, path)
    finally:
        grammar.fast.usable = usable
    return fast, plain


def test_there_are_files_of_every_kind():
    assert st_parser.grammar().fast.usable      # (the installed Lark has what the loop reads)
    assert len(FILES) > 400
    assert any("reject_syntax" in str(p) for p in FILES) and any("generated" in str(p) for p in FILES)


@pytest.mark.parametrize("path", FILES, ids=lambda p: str(p.relative_to(ROOT)))
def test_fast_loop_builds_the_same_ast(path: Path):
    text = path.read_text(encoding="utf-8", errors="replace")
    fast, plain = _both(text, path.name)
    assert fast == plain


@pytest.mark.parametrize("text", [
    "", "PROGRAM", "PROGRAM P x := ; END_PROGRAM", "PROGRAM P VAR x : INT END_VAR END_PROGRAM",
    "PROGRAM P VAR x : INT; END_VAR x := 16#FFFFFFFFFFFFFFFFFF; END_PROGRAM",     # a literal error
    "PROGRAM P VAR x : TIME := T#1x; END_VAR END_PROGRAM", "FUNCTION_BLOCK F (* open",
    "x := 1; y := x * (2 + 3);",
])
def test_fast_loop_gives_the_same_diagnostics(text: str):
    fast, plain = _both(text, "t.st")
    assert fast == plain
    fast, plain = _both(text, "t.st", st_parser.parse_body)
    assert fast == plain
