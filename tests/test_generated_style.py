"""The generated ST reads like careful hand-written code (DESIGN: "named
constants, comments that cite the equation, no magic numbers")."""

from __future__ import annotations

import re

import pytest

from stgen.exports import iec, sysmac
from stgen.render import RenderOptions, render_program

VARIANTS = {name: render_program(options=RenderOptions(name)) for name in ("table", "unrolled", "lu")}

#: Literals that are no magic numbers: zero, one, and the factor 2 of d|L|^2/da (docs/mathematics.md section 3 [36]).
PLAIN_LITERALS = {"0", "1", "0.0", "1.0", "2.0"}

_COMMENT = re.compile(r"\(\*.*?\*\)", re.S)
_NUMBER = re.compile(r"(?<![\w#.])(16#[0-9A-Fa-f_]+|\d+\.\d+(?:E[-+]?\d+)?|\d+)(?![\w.])")
# Integers that index an unrolled array element or name the axis of an unrolled block.
_INDEX = re.compile(r"\[\s*\d+\s*(?:,\s*\d+\s*)?\]|\[\s*\d+\s*,|,\s*\d+\s*\]|NewFaultAxis := \d+;")
# A CASE label as Sysmac Studio takes it (NJ rule 007): the literal, named by the comment after it.
_NAMED_LABEL = re.compile(r"^\s*\d+(?:, \d+)*: \(\* [A-Z][A-Z0-9_]*(?:, [A-Z][A-Z0-9_]*)* \*\)", re.M)


def _code(body: str) -> str:
    return _INDEX.sub(" ", _COMMENT.sub(" ", _NAMED_LABEL.sub(" ", body)))


@pytest.mark.parametrize("variant", sorted(VARIANTS))
def test_bodies_use_named_constants_not_magic_numbers(variant):
    found = []
    for pou in VARIANTS[variant].pous:
        for number in _NUMBER.findall(_code(pou.body)):
            if number not in PLAIN_LITERALS:
                found.append(f"{pou.name}: {number}")
    assert found == []


def test_the_magic_number_scan_sees_what_it_must():
    assert _NUMBER.findall(_code("ErrorID := 16#0000; FOR Leg := 1 TO 6 DO X := Y * 0.25; END_FOR;")) == [
        "16#0000", "1", "6", "0.25"]
    assert _NUMBER.findall(_code("A[3, 4] := M[Term, 2] * 2.0; (* 42 *) NewFaultAxis := 5;")) == ["2.0"]
    assert _NUMBER.findall(_code("CASE S OF\n    4, 5: (* SP_STATE_MOVING, SP_STATE_WAVE *)\n    7:\n")) == ["7"]


def test_every_pou_header_cites_the_mathematics():
    for pou in VARIANTS["table"].pous:
        if pou.kind != "VAR_GLOBAL":
            assert re.search(r"docs/mathematics\.md section \d", pou.header), pou.name


def test_no_generated_line_ends_in_whitespace():
    # ST and Markdown; in a .tsv table a trailing tab is an empty last cell.
    program = VARIANTS["table"]
    texts = {**iec.files(program), **{f"nj/{name}": text for name, text in sysmac.files(program).items()}}
    for name, text in texts.items():
        if name.endswith(".tsv"):
            continue
        for number, line in enumerate(text.splitlines(), 1):
            assert line == line.rstrip(), f"{name}:{number}: trailing whitespace"


def _stem(variable) -> str:
    """R11 -> R, LegY -> Leg: the name without its index or axis letter."""
    return re.sub(r"(\d+|[XYZ])$", "", variable.name)


def test_every_own_variable_is_commented_or_continues_a_commented_group():
    # Externals are documented in their global lists. A group such as R11 .. R33 or
    # LegX, LegY, LegZ carries its comment on its first member.
    for variant, program in VARIANTS.items():
        for pou in program.pous:
            previous = None
            for variable in pou.variables:
                if variable.usage != "External" and not variable.comment:
                    grouped = previous is not None and previous.usage == variable.usage and _stem(previous) == _stem(variable)
                    assert grouped, f"{variant} {pou.name}.{variable.name} has no comment"
                previous = variable
