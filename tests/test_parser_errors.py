"""Syntax errors: codes, positions, readable messages, one fault -> one error.

Reject corpus: every `tests/corpus/reject_syntax/*.st` starts with
`(* expect: CODE line N [col C] *)` (the convention of `tests/corpus/reject/`,
plus an optional column).  Parsing it must give exactly that one diagnostic.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from st_runtime import parser as parser_module
from st_runtime.diagnostics import CODES
from st_runtime.parser import parse

CORPUS = Path(__file__).parent / "corpus" / "reject_syntax"
REJECT = sorted(CORPUS.glob("*.st"))
HEADER = re.compile(r"\(\* expect: (?P<code>E-PARSE-\d{3}) line (?P<line>\d+)"
                    r"(?: col (?P<col>\d+))? \*\)")


def expectation(path: Path):
    m = HEADER.match(path.read_text(encoding="utf-8").splitlines()[0])
    assert m, f"{path.name}: first line must be (* expect: E-PARSE-NNN line N *)"
    return m["code"], int(m["line"]), int(m["col"]) if m["col"] else None


def diagnostics_of(text: str, path: str = "e.st"):
    tree, diagnostics = parse(text, path)
    assert tree is None
    return diagnostics


@pytest.mark.parametrize("path", REJECT, ids=lambda p: p.stem)
def test_reject_syntax_corpus(path: Path):
    code, line, col = expectation(path)
    text = path.read_text(encoding="utf-8")
    diagnostics = diagnostics_of(text, path.name)
    got = [d.header() for d in diagnostics]
    assert len(diagnostics) == 1, f"one fault must give one diagnostic, got {got}"
    (diag,) = diagnostics
    assert (diag.code, diag.pos.line) == (code, line), got
    if col is not None:
        assert diag.pos.col == col, got
    assert diag.pos.file == path.name


def test_every_parse_code_is_registered_and_tested():
    parse_codes = {c for c in CODES if c.startswith("E-PARSE-")}
    assert set(parser_module.CODES) == parse_codes
    tested = {expectation(p)[0] for p in REJECT}
    # 013 (too many errors) and 099 (internal error) have their own tests below.
    assert parse_codes - tested == {"E-PARSE-013", "E-PARSE-099"}


PROGRAM = "PROGRAM P\nVAR\n    x, y : INT;\nEND_VAR\n{}\nEND_PROGRAM\n"


def test_message_says_what_was_expected_and_found():
    (diag,) = diagnostics_of(PROGRAM.format("    x := 1\n    y := 2;"))
    assert diag.message == "expected ';' after statement, found 'y'"
    (diag,) = diagnostics_of(PROGRAM.format("    x := y + ;"))
    assert diag.message == "expected expression, found ';'"
    (diag,) = diagnostics_of(PROGRAM.format("    x := 1 +"))
    assert diag.message.startswith("expected expression, found keyword 'END_PROGRAM'")


def test_missing_end_if_names_the_opening_line():
    (diag,) = diagnostics_of(PROGRAM.format("    IF x > 0 THEN\n        y := 1;"))
    assert diag.code == "E-PARSE-003"
    assert "to close the IF at line 5" in diag.message
    assert diag.message.endswith("found keyword 'END_PROGRAM'")


def test_end_of_file_is_named():
    (diag,) = diagnostics_of("PROGRAM P\n    x := 1;\n")
    assert diag.code == "E-PARSE-003"
    assert diag.message.endswith("found end of file")


def test_render_shows_line_and_caret():
    text = PROGRAM.format("    x := y @ 1;")
    (diag,) = diagnostics_of(text, "r.st")
    assert diag.render(text).splitlines() == [
        "r.st:5:12: error[E-PARSE-007]: unexpected character '@'",
        "        x := y @ 1;",
        "               ^",
    ]


def test_separate_faults_are_each_reported_once():
    text = PROGRAM.format("    x := 1\n    y := 2;\n    x := y + * 2;\n    y = 3;\n"
                          "    IF x > THEN\n        y := 1;\n    END_IF;")
    diagnostics = diagnostics_of(text)
    assert [(d.code, d.pos.line) for d in diagnostics] == [
        ("E-PARSE-002", 5), ("E-PARSE-004", 7), ("E-PARSE-001", 8), ("E-PARSE-004", 9)]


def test_faults_in_declarations_and_body_are_both_reported():
    text = "PROGRAM P\nVAR\n    x : INT\n    y : ;\nEND_VAR\n    x := (1 + 2;\nEND_PROGRAM\n"
    assert [(d.code, d.pos.line) for d in diagnostics_of(text)] == [
        ("E-PARSE-002", 3), ("E-PARSE-001", 4), ("E-PARSE-001", 6)]


def test_fault_in_one_pou_does_not_hide_the_next_pou():
    text = ("FUNCTION_BLOCK A\n    x := ;\nEND_FUNCTION_BLOCK\n"
            "PROGRAM B\n    IF THEN END_IF;\nEND_PROGRAM\n")
    assert [(d.code, d.pos.line) for d in diagnostics_of(text)] == [
        ("E-PARSE-004", 2), ("E-PARSE-004", 5)]


def test_invalid_literal_next_to_syntax_error_reports_both():
    text = PROGRAM.format("    x := 2#102;\n    y := ;")
    assert [(d.code, d.pos.line) for d in diagnostics_of(text)] == [
        ("E-PARSE-009", 5), ("E-PARSE-004", 6)]


def test_too_many_errors_stops_with_its_own_code():
    body = "\n".join("    x := ;" for _ in range(40))
    diagnostics = diagnostics_of(PROGRAM.format(body))
    assert diagnostics[-1].code == "E-PARSE-013"
    assert len(diagnostics) <= 26


def test_internal_error_becomes_a_diagnostic(monkeypatch):
    def explode(text, path):
        raise RuntimeError("boom")

    monkeypatch.setattr(parser_module, "_parse", explode)
    tree, diagnostics = parse("PROGRAM P END_PROGRAM", "i.st")
    assert tree is None
    assert [d.code for d in diagnostics] == ["E-PARSE-099"]
    assert "boom" in diagnostics[0].message


def test_non_text_input_is_a_diagnostic_not_an_exception():
    tree, diagnostics = parse(b"PROGRAM P END_PROGRAM", "b.st")  # type: ignore[arg-type]
    assert tree is None and diagnostics[0].code == "E-PARSE-099"


# ----------------------------------------------- one typo, one error: rates

def _mutations(action: str, count: int, seed: int):
    """Seeded single-token typos in the accept corpus (layout and comments kept)."""
    import random

    from st_runtime.parser import grammar

    rng = random.Random(seed)
    paths = sorted((Path(__file__).parent / "corpus" / "accept").glob("*.st"))
    texts = [p.read_text(encoding="utf-8") for p in paths]
    lexer = grammar().lark
    made = 0
    while made < count:
        text = rng.choice(texts)
        tokens = list(lexer.lex(text))
        k = rng.randrange(len(tokens) - 1)
        t, u = tokens[k], tokens[k + 1]
        if action == "delete":
            yield text[:t.start_pos] + " " + text[t.end_pos:]
        elif action == "duplicate":
            yield text[:t.end_pos] + " " + t.value + text[t.end_pos:]
        else:
            yield (text[:t.start_pos] + u.value + text[t.end_pos:u.start_pos] + t.value
                   + text[u.end_pos:])
        made += 1


@pytest.mark.parametrize("action,minimum", [("delete", 0.93), ("duplicate", 0.97),
                                            ("swap", 0.88)])
def test_single_token_typos_mostly_give_exactly_one_error(action, minimum):
    """Measured on 3 x 1,500 typos: 98.5 % (delete), 99.9 % (duplicate), 94 % (swap)."""
    counts = []
    for text in _mutations(action, 150, seed=2026):
        tree, diagnostics = parse(text, "typo.st")
        if tree is None:
            counts.append(len(diagnostics))
    share = sum(1 for c in counts if c == 1) / len(counts)
    assert share >= minimum, f"{action}: one error in {share:.1%} of faulty texts"
    assert min(counts) >= 1
