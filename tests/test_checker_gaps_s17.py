"""Two checker gaps seen during issue 16's mutation work (docs/mutation.md, "Session 17, checker
gaps"), each refused with file, line and column, through the API and `stgen check`.

1. IEC 61131-3 3rd ed. 7.3.3.4.2 (FOR): the control variable "shall not be altered by any of the
   repeated statements". A FOR nested in a FOR over the same variable assigns it at every
   iteration of the inner loop: E-ASSIGN-003 at the inner FOR, as `i := i` in the body is. The
   other ways a body may write it (an output `=>` target, a VAR_IN_OUT argument, REF and ADR)
   were already refused; their rows pin that the new check changed none of them.
2. IEC 61131-3 3rd ed. Annex A: `Struct_Decl : 'STRUCT' 'OVERLAP'? ( Struct_Elem_Decl ';' )+
   'END_STRUCT'`, one member at least. CODESYS's help on STRUCT and UNION (content.helpme-codesys.com,
   _cds_datatype_structure.html, _cds_datatype_union.html) asks for member declarations too;
   no OMRON source says what Sysmac Studio does with an empty one (docs/nj501.md): E-DECL-018
   under every dialect, at the STRUCT (UNION) keyword.

Each row's expected diagnostics are the rule's words and the place counted by hand in its text.
"""

from __future__ import annotations

import pytest

from checker_helpers import diagnostics
from st_runtime.api import LoadError, load_text
from stgen.cli import main

DIALECTS = ("iec", "codesys", "nj")


def program(body: str, decls: str = "i : INT; j : INT; s : INT;") -> str:
    """PROGRAM Main with `decls` on line 3 and `body` from line 5."""
    return f"PROGRAM Main\nVAR\n  {decls}\nEND_VAR\n{body}\nEND_PROGRAM\n"


NESTED = "FOR i := 1 TO 3 DO\n  FOR i := 1 TO 2 DO\n    s := s + 1;\n  END_FOR;\nEND_FOR;"
INNER = "FOR control variable 'i' is already the control variable of an enclosing FOR loop"

# ====================================================================== 1. nested FOR

NESTED_ROWS = [
    pytest.param(NESTED, [("E-ASSIGN-003", 6, 3, INNER)], id="nested_directly"),
    # Any depth of statements between the two loops: the enclosing FOR is still running.
    pytest.param("FOR i := 1 TO 3 DO\n  WHILE s < 3 DO\n    IF s >= 0 THEN\n      FOR i := 0 TO 1 DO\n"
                 "        s := s + 1;\n      END_FOR;\n    END_IF;\n  END_WHILE;\nEND_FOR;",
                 [("E-ASSIGN-003", 8, 7, INNER)], id="nested_under_while_and_if"),
    # Three deep, the outer two over other variables: only the innermost alters its enclosing loop's.
    pytest.param("FOR i := 1 TO 2 DO\n  FOR j := 1 TO 2 DO\n    FOR i := 1 TO 2 DO\n    END_FOR;\n"
                 "  END_FOR;\nEND_FOR;", [("E-ASSIGN-003", 7, 5, INNER)], id="two_levels_down"),
    # The inner loop's refusal does not free the outer's variable in the inner body.
    pytest.param("FOR i := 1 TO 3 DO\n  FOR i := 1 TO 2 DO\n    i := 5;\n  END_FOR;\nEND_FOR;",
                 [("E-ASSIGN-003", 6, 3, INNER),
                  ("E-ASSIGN-003", 7, 5, "assignment: 'i' is the control variable of an enclosing FOR loop")],
                 id="and_assigned_inside"),
    # The near misses: another variable inside, the same variable after the loop has ended.
    pytest.param("FOR i := 1 TO 3 DO\n  FOR j := 1 TO 2 DO\n    s := s + 1;\n  END_FOR;\nEND_FOR;", [],
                 id="near_miss_another_variable"),
    pytest.param("FOR i := 1 TO 3 DO\n  s := s + 1;\nEND_FOR;\nFOR i := 1 TO 2 DO\n  s := s + i;\nEND_FOR;", [],
                 id="near_miss_one_after_the_other"),
]


@pytest.mark.parametrize("dialect", DIALECTS)
@pytest.mark.parametrize("body, expected", NESTED_ROWS)
def test_a_for_nested_in_a_for_over_the_same_variable(body, expected, dialect):
    assert diagnostics(program(body), dialect) == expected


FB = ("FUNCTION_BLOCK Fb\nVAR_INPUT a : INT; END_VAR\nVAR_OUTPUT q : INT; END_VAR\n"
      "VAR_IN_OUT io : INT; END_VAR\nq := a;\nio := io + 1;\nEND_FUNCTION_BLOCK\n")   # 7 lines

# The other writes of the control variable by the body (the program after FB: line 8 on, its
# declarations on line 10 and its body from line 12).
OTHER_WRITES = [
    pytest.param("iec", "FOR i := 1 TO 3 DO\n  f(a := 1, io := s, q => i);\nEND_FOR;",
                 [("E-ASSIGN-003", 13, 27, "output 'q' of Fb: 'i' is the control variable of an "
                                           "enclosing FOR loop")], id="output_target"),
    pytest.param("iec", "FOR i := 1 TO 3 DO\n  f(a := 1, io := i);\nEND_FOR;",
                 [("E-CALL-007", 13, 19, "VAR_IN_OUT 'io' of Fb: expected a writable variable, found "
                                         "'i', the control variable of an enclosing FOR loop")], id="in_out"),
    pytest.param("iec", "FOR i := 1 TO 3 DO\n  r := REF(i);\nEND_FOR;",
                 [("E-ASSIGN-003", 13, 12, "REF(...): 'i' is the control variable of an enclosing "
                                           "FOR loop")], id="ref"),
    pytest.param("codesys", "FOR i := 1 TO 3 DO\n  p := ADR(i);\nEND_FOR;",
                 [("E-ASSIGN-003", 13, 12, "ADR(...): 'i' is the control variable of an enclosing "
                                           "FOR loop")], id="adr"),
    # Reading it is no write: into an input, an FB's output read into another variable.
    pytest.param("iec", "FOR i := 1 TO 3 DO\n  f(a := i, io := s);\n  j := f.q + i;\nEND_FOR;", [],
                 id="near_miss_read_only"),
]


@pytest.mark.parametrize("dialect, body, expected", OTHER_WRITES)
def test_the_other_writes_of_a_control_variable_stay_refused(dialect, body, expected):
    decls = "i, j, s : INT; f : Fb; " + ("p : POINTER TO INT;" if dialect == "codesys" else "r : REF_TO INT;")
    assert diagnostics(FB + program(body, decls), dialect) == expected


# ====================================================================== 2. STRUCT without members

EMPTY_ROWS = [
    pytest.param(("iec", "codesys", "nj"), "TYPE Empty : STRUCT END_STRUCT; END_TYPE\n",
                 [("E-DECL-018", 1, 14, "STRUCT Empty: expected at least one member")], id="struct_one_line"),
    pytest.param(("iec", "codesys", "nj"), "TYPE\n  Empty :\n    STRUCT\n    END_STRUCT\nEND_TYPE\n",
                 [("E-DECL-018", 3, 5, "STRUCT Empty: expected at least one member")], id="struct_lines"),
    # UNION is CODESYS's and the NJ's (iec refuses it as a construct, E-DIALECT-001).
    pytest.param(("codesys", "nj"), "TYPE U : UNION END_UNION END_TYPE\n",
                 [("E-DECL-018", 1, 10, "UNION U: expected at least one member")], id="union"),
    # The near misses: one member is enough (not CODESYS's documented "at least 2": see the module).
    pytest.param(("iec", "codesys", "nj"), "TYPE One : STRUCT a : INT; END_STRUCT; END_TYPE\n", [],
                 id="near_miss_one_member"),
    pytest.param(("codesys", "nj"), "TYPE U : UNION a : INT; END_UNION END_TYPE\n", [],
                 id="near_miss_union_of_one"),
]


@pytest.mark.parametrize("dialects, text, expected", EMPTY_ROWS)
def test_a_struct_without_members(dialects, text, expected):
    for dialect in dialects:
        assert diagnostics(text, dialect) == expected, dialect


def test_a_variable_of_an_empty_struct_gives_the_one_diagnostic_at_the_type():
    """The type is refused once, where it is declared; the variables of it and their assignment
    add nothing (the structure's member table is still made, empty)."""
    text = "TYPE E : STRUCT END_STRUCT; END_TYPE\n" + program("e1 := e2;", "e1, e2 : E;")
    assert diagnostics(text) == [("E-DECL-018", 1, 10, "STRUCT E: expected at least one member")]


# ====================================================================== through the API and the CLI

@pytest.mark.parametrize("text, code, line, col", [
    (program(NESTED), "E-ASSIGN-003", 6, 3),
    ("TYPE Empty : STRUCT END_STRUCT; END_TYPE\n" + program("s := 1;"), "E-DECL-018", 1, 14),
])
def test_load_text_refuses_with_the_place(text, code, line, col):
    with pytest.raises(LoadError) as refused:
        load_text(text, path="gap.st")
    assert [(d.code, d.pos.file, d.pos.line, d.pos.col) for d in refused.value.diagnostics
            if d.is_error] == [(code, "gap.st", line, col)]


@pytest.mark.parametrize("text, header", [
    (program(NESTED), ":6:3: error[E-ASSIGN-003]: " + INNER),
    ("TYPE Empty : STRUCT END_STRUCT; END_TYPE\n" + program("s := 1;"),
     ":1:14: error[E-DECL-018]: STRUCT Empty: expected at least one member"),
])
def test_stgen_check_exits_1_naming_file_line_and_column(text, header, tmp_path, capsys):
    path = tmp_path / "gap.st"
    path.write_text(text)
    code = main(["check", str(path)])
    out = capsys.readouterr()
    assert code == 1
    assert f"{path}{header}" in (out.out + out.err).splitlines()


@pytest.mark.parametrize("text", [
    program("FOR i := 1 TO 3 DO\n  FOR j := 1 TO 2 DO\n    s := s + 1;\n  END_FOR;\nEND_FOR;"),
    "TYPE One : STRUCT a : INT; END_STRUCT; END_TYPE\n" + program("s := 1;"),
])
def test_stgen_check_accepts_the_near_misses(text, tmp_path, capsys):
    path = tmp_path / "ok.st"
    path.write_text(text)
    assert main(["check", str(path)]) == 0
    assert "1 file(s), 0 error(s), 0 warning(s)" in capsys.readouterr().err
