"""One dialect table (st_runtime/dialects.py) that the checker, compiler and runtime consult."""

from __future__ import annotations

from st_runtime.dialects import CONSTRUCTS, DIALECTS, refusal
from st_runtime.loader import load_texts

OVERLONG = """PROGRAM Main
VAR s : STRING[3]; END_VAR
s := 'abcdef';
END_PROGRAM
"""

ADR_CALL = """PROGRAM Main
VAR i : INT; p : POINTER TO INT; END_VAR
p := ADR(i);
END_PROGRAM
"""


def codes(text: str, dialect: str) -> list[tuple[str, int, str]]:
    result = load_texts({"t.st": text}, dialect)
    return [(d.code, d.pos.line, d.message) for d in result.diagnostics]


def test_every_construct_names_known_dialects_and_a_source():
    for name, row in CONSTRUCTS.items():
        assert row.accepted_by and row.accepted_by <= set(DIALECTS), name
        assert row.source, name


def test_every_dialect_says_what_string_n_counts():
    # Each dialect answers every question the checker and runtime ask of it.
    for dialect in DIALECTS.values():
        assert dialect.string_unit in ("character", "byte")
        assert dialect.time_unit_ns >= 1


def test_overlong_string_literal_warns_in_every_dialect():
    # Was an internal checker error under --dialect codesys (its STRING unit
    # was missing from a second table).  6 characters into STRING[3].
    for name in DIALECTS:
        found = codes(OVERLONG, name)
        assert [(c, line) for c, line, _ in found] == [("W-TYPE-001", 3)], (name, found)


def test_adr_under_iec_names_the_dialect_that_accepts_it():
    found = [f for f in codes(ADR_CALL, "iec") if f[1] == 3]
    assert found == [("E-DIALECT-001", 3, refusal("ADR", "iec"))]
    assert "--dialect codesys" in found[0][2]
    assert codes(ADR_CALL, "codesys") == []


CODESYS_ONLY = {
    "enum_dot": ("TYPE Light : (Red, Green); END_TYPE\nPROGRAM Main\nVAR L : Light; END_VAR\n"
                 "L := Light.Red;\nEND_PROGRAM\n", "E-DIALECT-001"),
    "super_body": ("FUNCTION_BLOCK B\nVAR_OUTPUT N : INT; END_VAR\nN := N + 1;\nEND_FUNCTION_BLOCK\n"
                   "FUNCTION_BLOCK D EXTENDS B\nSUPER^();\nEND_FUNCTION_BLOCK\n", "E-DIALECT-001"),
    "input_write": ("FUNCTION F : INT\nVAR_INPUT X : INT; END_VAR\nX := 1;\nF := X;\nEND_FUNCTION\n",
                    "E-ASSIGN-002"),
}


def test_codesys_constructs_are_refused_under_nj_naming_codesys():
    for name, (text, code) in CODESYS_ONLY.items():
        errors = [(c, m) for c, _, m in codes(text, "nj") if c.startswith("E-")]
        # (under nj the EXTENDS and the ^ of SUPER^() are refused as well)
        assert any(c == code and "--dialect codesys" in m for c, m in errors), (name, errors)
        assert not [c for c, _, _ in codes(text, "codesys") if c.startswith("E-")], name
