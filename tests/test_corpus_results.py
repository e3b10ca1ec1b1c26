"""The accept corpus checks meaning, not only acceptance (issue 16).

Each `tests/corpus/accept/*.st` snippet may carry, in comments,

    (* expect: x = 3; a[2] = TRUE after 1 scan *)
    (* no-result: why the snippet has nothing to observe *)
    (* faults: F-INDEX, ... *)

A run must end without faults, unless a `faults` comment names the codes the
snippet raises by design: then its faults must have exactly those codes.

An `expect` comment runs every PROGRAM of the snippet for N scans (cumulative
across the comments of one snippet, in ascending N) and compares the values
(through the instance API: `name`, `a[i, j]`, `s.member`; a PROGRAM name as
the first step when there are several; else a global).  Values are written
in ST: TRUE/FALSE, integers (16#FF too), reals, 'strings', enum names and
TIME literals as the API shows them (`T#1s`).  The expected values were
worked out by hand from the IEC 61131-3 rules, next to nothing but the
snippet.  Every snippet carries one comment or the other.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from st_runtime.api import load_text
from test_checker_corpus import accept_dialect

ACCEPT = sorted((Path(__file__).parent / "corpus" / "accept").glob("*.st"))

EXPECT = re.compile(r"\(\*\s*expect:\s*(?P<body>.+?)\s+after\s+(?P<scans>\d+)\s+scans?\s*\*\)", re.S)
FAULTS = re.compile(r"\(\*\s*faults:\s*(?P<codes>F-[A-Z0-9-]+(?:\s*,\s*F-[A-Z0-9-]+)*)\s*\*\)")
NO_RESULT = re.compile(r"\(\*\s*no-result:\s*(?P<why>.+?)\s*\*\)", re.S)

ESCAPES = {"$": "$", "'": "'", "L": "\n", "N": "\n", "R": "\r", "T": "\t", "P": "\f"}


def st_string(body: str) -> str:
    """A STRING literal's characters: $$ $' $L $N $R $T $P and $hh (IEC 61131-3 6.3.3).

    Expectations write '(' as $28 and ')' as $29 where the text would
    otherwise close the comment."""
    out, i = [], 0
    while i < len(body):
        if body[i] != "$":
            out.append(body[i])
            i += 1
        elif body[i + 1].upper() in ESCAPES:
            out.append(ESCAPES[body[i + 1].upper()])
            i += 2
        else:
            out.append(chr(int(body[i + 1:i + 3], 16)))
            i += 3
    return "".join(out)


def parse_value(text: str):
    """An ST literal of an expectation as the API shows it."""
    text = text.strip()
    upper = text.upper()
    if upper in ("TRUE", "FALSE"):
        return upper == "TRUE"
    if len(text) >= 2 and text[0] == text[-1] == "'":
        return st_string(text[1:-1])
    m = re.fullmatch(r"([+-]?)(\d+)#([0-9A-Fa-f_]+)", text)
    if m:
        value = int(m[3].replace("_", ""), int(m[2]))
        return -value if m[1] == "-" else value
    if re.fullmatch(r"[+-]?\d[\d_]*", text):
        return int(text.replace("_", ""))
    if re.fullmatch(r"[+-]?\d[\d_]*(\.\d+)?([eE][+-]?\d+)?", text):
        return float(text.replace("_", ""))
    return text        # an enum value name or a TIME/DATE literal


def expectations(text: str) -> list[tuple[int, list[tuple[str, object]]]]:
    """(scans, [(path, value), ...]) of every expect comment, ascending scans."""
    found = []
    for m in EXPECT.finditer(text):
        checks = []
        for item in m["body"].split(";"):
            path, sep, value = item.partition("=")
            assert sep, f"expect: '{item.strip()}' is not 'path = value'"
            checks.append((path.strip(), parse_value(value)))
        found.append((int(m["scans"]), checks))
    return sorted(found, key=lambda e: e[0])


def read(plc, programs: dict, path: str):
    head, dot, rest = path.partition(".")
    if dot and head.upper() in programs and len(programs) > 1:
        return programs[head.upper()][rest]
    for instance in programs.values():
        try:
            return instance[path]
        except KeyError:
            continue
    return plc.globals[path]


def check_snippet(text: str, name: str = "snippet.st") -> int:
    """Run the snippet and assert its expectations; the number of values checked."""
    expected = expectations(text)
    project = load_text(text, name, accept_dialect(text))
    plc = project.controller()
    programs = {pou.name.upper(): plc.add_program(pou.name)
                for pou in project.program.pous.values() if pou.kind == "PROGRAM"}
    done, checked = 0, 0
    for scans, checks in expected:
        plc.run(scans - done)
        done = scans
        for path, value in checks:
            actual = read(plc, programs, path)
            assert actual == value and type(actual) is type(value), \
                f"{name}: {path} = {actual!r} after {scans} scans, expected {value!r}"
            checked += 1
    declared = FAULTS.search(text)
    expected_codes = {code.strip() for code in declared["codes"].split(",")} if declared else set()
    assert {fault.code for fault in plc.faults} == expected_codes, f"{name}: faults {plc.faults}"
    return checked


ANNOTATED = [p for p in ACCEPT if EXPECT.search(p.read_text(encoding="utf-8"))]


@pytest.mark.parametrize("path", ANNOTATED, ids=lambda p: p.stem)
def test_accept_snippet_result(path: Path):
    assert check_snippet(path.read_text(encoding="utf-8"), path.name) > 0


def test_every_snippet_says_its_result_or_why_not():
    missing = [p.name for p in ACCEPT
               if not EXPECT.search(p.read_text(encoding="utf-8"))
               and not NO_RESULT.search(p.read_text(encoding="utf-8"))]
    assert missing == [], "snippets without (* expect: ... *) or (* no-result: ... *)"


def test_a_wrong_expectation_fails():
    snippet = "(* expect: x = 4 after 1 scan *)\nPROGRAM Main\nVAR x : INT; END_VAR\nx := 1 + 2;\nEND_PROGRAM\n"
    with pytest.raises(AssertionError, match="x = 3 after 1 scans, expected 4"):
        check_snippet(snippet)
    assert check_snippet(snippet.replace("x = 4", "x = 3")) == 1


def test_a_fault_must_be_declared_and_a_declared_fault_must_happen():
    snippet = ("(* expect: x = 0 after 1 scan *)\nPROGRAM Main\nVAR x : INT; a : ARRAY[1..2] OF INT; i : INT := 3; END_VAR\n"
               "x := a[i];\nEND_PROGRAM\n")
    with pytest.raises(AssertionError, match="F-INDEX"):
        check_snippet(snippet)
    assert check_snippet(snippet.replace("END_PROGRAM", "END_PROGRAM\n(* faults: F-INDEX *)")) == 1
    with pytest.raises(AssertionError, match="faults"):
        check_snippet(snippet.replace("i : INT := 3", "i : INT := 2") + "(* faults: F-INDEX *)")


def test_types_must_match_too():
    # 3.0 is not 3: a REAL result must be written as a real.
    snippet = "(* expect: x = 3 after 1 scan *)\nPROGRAM Main\nVAR x : LREAL; END_VAR\nx := 3.0;\nEND_PROGRAM\n"
    with pytest.raises(AssertionError):
        check_snippet(snippet)


def test_values_parse_as_st_literals():
    assert parse_value("TRUE") is True and parse_value("false") is False
    assert parse_value("16#FF") == 255 and parse_value("-2#101") == -5
    assert parse_value("1_000") == 1000 and parse_value("-3") == -3
    assert parse_value("2.5") == 2.5 and parse_value("1.0E-3") == 0.001
    assert parse_value("'leg'") == "leg" and parse_value("Green") == "Green"
    assert parse_value("'It$'s $28a$29$N$t'") == "It's (a)\n\t"
