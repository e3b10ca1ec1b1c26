"""Property: no input, however broken, makes `parse` raise or fail internally.

Random text, random bytes, token soups drawn from the grammar's vocabulary and
small mutations of the accept corpus must only ever give (AST, []) or
(None, diagnostics) — never an exception, never the internal-error code.
Bounded: 200 examples per property, a few seconds each; a long sweep sets
ST_FUZZ_EXAMPLES (e.g. `ST_FUZZ_EXAMPLES=5000 pytest tests/test_fuzz_parser.py`).
"""

from __future__ import annotations

import os
import re
from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from st_runtime import ast
from st_runtime.diagnostics import Diagnostic
from st_runtime.parser import parse

ACCEPT = sorted((Path(__file__).parent / "corpus" / "accept").glob("*.st"))
CORPUS_TEXTS = [p.read_text(encoding="utf-8") for p in ACCEPT]

KEYWORDS = """PROGRAM END_PROGRAM FUNCTION END_FUNCTION FUNCTION_BLOCK END_FUNCTION_BLOCK
TYPE END_TYPE STRUCT END_STRUCT VAR VAR_INPUT VAR_OUTPUT VAR_IN_OUT VAR_TEMP VAR_GLOBAL
VAR_EXTERNAL END_VAR CONSTANT RETAIN ARRAY OF STRING WSTRING IF THEN ELSIF ELSE END_IF
CASE END_CASE FOR TO BY DO END_FOR WHILE END_WHILE REPEAT UNTIL END_REPEAT EXIT CONTINUE
RETURN NOT AND OR XOR MOD TRUE FALSE R_EDGE F_EDGE METHOD END_METHOD INTERFACE END_INTERFACE EXTENDS IMPLEMENTS PUBLIC PRIVATE ABSTRACT FINAL THIS SUPER REF_TO NULL POINTER ACTION END_ACTION PROPERTY END_PROPERTY GET END_GET SET END_SET UNION END_UNION NAMESPACE END_NAMESPACE USING CONFIGURATION RESOURCE ON TASK WITH
END_RESOURCE END_CONFIGURATION INITIAL_STEP STEP END_STEP TRANSITION FROM END_TRANSITION VAR_CONFIG VAR_ACCESS READ_ONLY READ_WRITE""".split()
PUNCTUATION = [";", ":", ":=", "=>", ",", ".", "..", "(", ")", "[", "]", "**", "*", "/",
               "+", "-", "<=", ">=", "<>", "<", ">", "=", "&", "#", "(*", "*)", "/*", "*/",
               "//", "'", '"', "$", "\n", "{", "}"]
ATOMS = ["x", "Speed", "INT", "LREAL", "TON", "0", "1", "16#FF", "2#102", "1.5E-3",
         "T#1s", "T#5x", "INT#-5", "Color#Red", "'it$'s'", "'$Q'", "D#2024-02-30",
         "TOD#25:00:00", "\"w\"", "{attribute 'hide'}", "AT", "%IX0.0", "%QW3", "%I*", "%IX0.9", "^", "REF(x)", "S=", ".%X3", ",)",
         "STRING#'a'", 'WSTRING#"w"', "STRING#\"x\"", "SUPER^()", "Color.Red", "Act(N);", "Act(L, T#1s);",
         "FROM (A, B) TO C"]

SETTINGS = settings(max_examples=int(os.environ.get("ST_FUZZ_EXAMPLES", "200")), deadline=None,
                    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])


def assert_well_behaved(text: str) -> None:
    tree, diagnostics = parse(text, "fuzz.st")
    assert isinstance(diagnostics, list)
    assert all(isinstance(d, Diagnostic) for d in diagnostics)
    if tree is None:
        assert diagnostics, "a rejected text must say why"
    else:
        assert isinstance(tree, ast.SourceFile) and not diagnostics
    internal = [d.header() for d in diagnostics if d.code == "E-PARSE-099"]
    assert not internal, internal
    for d in diagnostics:
        assert d.pos.line >= 1 and d.pos.col >= 1
        d.render(text)


@SETTINGS
@given(st.text(max_size=300))
def test_random_text(text):
    assert_well_behaved(text)


@SETTINGS
@given(st.binary(max_size=300))
def test_random_bytes_decoded(data):
    assert_well_behaved(data.decode("latin-1"))
    assert_well_behaved(data.decode("utf-8", errors="replace"))


_token = st.one_of(st.sampled_from(KEYWORDS), st.sampled_from(PUNCTUATION),
                   st.sampled_from(ATOMS))


@SETTINGS
@given(st.lists(_token, max_size=80), st.sampled_from([" ", "", "\n"]))
def test_token_soup(tokens, separator):
    assert_well_behaved(separator.join(tokens))


@SETTINGS
@given(st.lists(_token, max_size=40))
def test_token_soup_inside_a_program_body(tokens):
    assert_well_behaved("PROGRAM P\nVAR\n x : INT;\nEND_VAR\n" + " ".join(tokens)
                        + "\nEND_PROGRAM\n")


_TOKEN_RE = re.compile(r"\(\*.*?\*\)|'(?:[^'$]|\$.)*'|[A-Za-z_][A-Za-z0-9_]*(?:#[\w.+-]+)?"
                       r"|\d[\w.#:-]*|:=|=>|\.\.|\*\*|<=|>=|<>|\S", re.S)


@SETTINGS
@given(st.sampled_from(range(len(CORPUS_TEXTS))), st.data())
def test_mutated_corpus(index, data):
    tokens = _TOKEN_RE.findall(CORPUS_TEXTS[index])
    for _ in range(data.draw(st.integers(1, 3))):
        if not tokens:
            break
        i = data.draw(st.integers(0, len(tokens) - 1))
        action = data.draw(st.sampled_from(["delete", "duplicate", "swap", "replace"]))
        if action == "delete":
            del tokens[i]
        elif action == "duplicate":
            tokens.insert(i, tokens[i])
        elif action == "swap" and i + 1 < len(tokens):
            tokens[i], tokens[i + 1] = tokens[i + 1], tokens[i]
        elif action == "replace":
            tokens[i] = data.draw(_token)
    assert_well_behaved(" ".join(tokens))


def test_pathological_nesting_is_reported_not_crashed():
    deep = "PROGRAM P\n x := " + "(" * 3000 + "1" + ")" * 3000 + ";\nEND_PROGRAM\n"
    tree, diagnostics = parse(deep, "deep.st")
    assert (tree is None) == bool(diagnostics)
    assert not [d for d in diagnostics if d.code == "E-PARSE-099"]
    unclosed = "PROGRAM P\n" + "IF a THEN\n" * 500 + "END_PROGRAM\n"
    assert_well_behaved(unclosed)
