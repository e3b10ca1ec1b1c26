"""Checker results found unchecked in session 14 (issue 16, docs/mutation.md, checker, "Session
14: a fresh seed 29"), and the PROPERTY accessors (session 13's "Reported (checker)").

A PROPERTY (CODESYS; not in IEC 61131-3, whose 3rd edition has METHODs but no PROPERTY) has a
GET accessor for reading and a SET accessor for writing, and may have only one of them. CODESYS
refuses a read of a property without GET (compiler error C0143, "The property 'Prop' cannot be
used in this context because it lacks the get accessor"); the checker said nothing and the load
then failed in the compiler (E-COMPILE-001 "nested too deeply (invalid syntax)"). Every
diagnostic below is given in full: code, line and column counted by hand, message.
"""

from __future__ import annotations

import pytest

from checker_helpers import diagnostics, program
from st_runtime import api
from stgen.cli import main
from test_checker_mutants_third import after_one_scan

TANK = """FUNCTION_BLOCK Tank
VAR lvl : INT; END_VAR
PROPERTY ReadOnly : INT
GET
ReadOnly := lvl;
END_GET
END_PROPERTY
PROPERTY WriteOnly : INT
SET
lvl := WriteOnly;
END_SET
END_PROPERTY
PROPERTY Both : INT
GET
Both := lvl;
END_GET
SET
lvl := Both;
END_SET
END_PROPERTY
METHOD Peek : INT
Peek := THIS.WriteOnly;
END_METHOD
END_FUNCTION_BLOCK
FUNCTION_BLOCK Src
VAR_INPUT i : INT; END_VAR
VAR_OUTPUT q : INT; END_VAR
q := i;
END_FUNCTION_BLOCK
FUNCTION_BLOCK Setter
VAR_IN_OUT b : INT; END_VAR
b := 1;
END_FUNCTION_BLOCK
PROGRAM Main
VAR t : Tank; s : Src; io : Setter; x : INT; END_VAR
"""
BODY = TANK.count("\n") + 1          # the line of the first statement of Main (36)
NO_GET = "property Tank.WriteOnly has no GET and cannot be read"
PEEK = ("E-TYPE-018", 22, 9, NO_GET)        # THIS.WriteOnly in Tank's own METHOD


def _main(*statements: str) -> str:
    return TANK + "\n".join(statements) + "\nEND_PROGRAM\n"


@pytest.mark.parametrize("statement, column", [
    ("x := t.WriteOnly;", 6),                            # an assignment's value
    ("x := 1 + t.WriteOnly;", 10),                       # an operand
    ("IF t.WriteOnly > 0 THEN x := 1; END_IF;", 4),      # a condition
    ("s(i := t.WriteOnly);", 8),                         # an input of a call
    ("t.WriteOnly := t.WriteOnly + 1;", 16),             # written (accepted), then read
])
def test_reading_a_property_without_get_is_refused_where_it_is_read(statement, column):
    assert diagnostics(_main(statement), "codesys") == [PEEK, ("E-TYPE-018", BODY, column, NO_GET)]


def test_a_property_without_get_to_an_in_out_is_read_and_has_no_address():
    # A VAR_IN_OUT is read and written through a reference: both reasons are reported.
    assert diagnostics(_main("io(b := t.WriteOnly);"), "codesys") == [
        PEEK, ("E-TYPE-018", BODY, 9, NO_GET),
        ("E-CALL-007", BODY, 9, "VAR_IN_OUT 'b' of Setter: expected a variable, found property 'WriteOnly'")]


def test_what_each_accessor_allows_is_accepted():
    # The other side of each rule: a property is written through SET, read through GET.
    accepted = _main("t.WriteOnly := 1;", "s(q => t.WriteOnly);", "x := t.ReadOnly;", "t.Both := t.Both + 1;",
                     "s(i := t.Both, q => t.Both);")
    assert diagnostics(accepted, "codesys") == [PEEK]


def test_writing_a_property_without_set_is_refused_where_it_is_written():
    found = diagnostics(_main("t.ReadOnly := 1;", "s(q => t.ReadOnly);"), "codesys")
    assert found == [PEEK,
                     ("E-ASSIGN-004", BODY, 1, "assignment: property 'ReadOnly' has no SET"),
                     ("E-ASSIGN-004", BODY + 1, 8, "output 'q' of Src: property 'ReadOnly' has no SET")]


def test_the_api_refuses_the_load_with_the_checkers_diagnostic():
    with pytest.raises(api.LoadError) as raised:
        api.load_text(_main("x := t.WriteOnly;"), "m.st", "codesys")
    assert [(d.code, d.pos.file, d.pos.line, d.pos.col, d.message) for d in raised.value.diagnostics] == [
        ("E-TYPE-018", "m.st", 22, 9, NO_GET), ("E-TYPE-018", "m.st", BODY, 6, NO_GET)]


def test_stgen_check_prints_both_with_file_line_column_and_caret(tmp_path, capsys):
    path = tmp_path / "tank.st"
    path.write_text(_main("x := t.WriteOnly;", "t.ReadOnly := 2;"))
    code = main(["check", str(path), "--dialect", "codesys"])
    out = capsys.readouterr()
    lines = (out.out + out.err).splitlines()
    assert code == 1
    read = lines.index(f"{path}:{BODY}:6: error[E-TYPE-018]: {NO_GET}")
    assert lines[read + 1:read + 3] == ["    x := t.WriteOnly;", "         ^"]
    write = lines.index(f"{path}:{BODY + 1}:1: error[E-ASSIGN-004]: assignment: property 'ReadOnly' has no SET")
    assert lines[write + 1:write + 3] == ["    t.ReadOnly := 2;", "    ^"]


def test_a_store_inside_a_written_propertys_path_leaves_it_written():
    # The index of `ts[...]` calls a function whose output is stored (k) before the property
    # itself is typed: the property is still the assignment's target, written, not read.
    pick = "FUNCTION Pick : INT\nVAR_INPUT i : INT; END_VAR\nVAR_OUTPUT o : INT; END_VAR\nPick := i;\no := i + 1;\nEND_FUNCTION\n"
    text = pick + _main("ts[Pick(i := 1, o => k)].WriteOnly := 5;").replace(
        "VAR t : Tank;", "VAR t : Tank; ts : ARRAY[0..2] OF Tank; k : INT;")
    assert diagnostics(text, "codesys") == [("E-TYPE-018", 28, 9, NO_GET)]       # PEEK, 6 lines down


# ------------------------------------------------------------------ the seed-29 sample

CHART = """PROGRAM Main
VAR Go : BOOL := TRUE; Lamp : BOOL; {mine} : BOOL; END_VAR
INITIAL_STEP Wait:
END_STEP
TRANSITION FROM Wait TO A := Go;
END_TRANSITION
STEP A:
    Lamp({qualifier}, T#1s);
END_STEP
TRANSITION FROM A TO Wait := FALSE;
END_TRANSITION
END_PROGRAM
"""


@pytest.mark.parametrize("qualifier", ["SD", "DS", "SL"])
def test_a_variable_named_like_a_charts_flip_flop_is_declared_twice_at_the_association(qualifier):
    """A timed stored action (the IEC 61131-3 action qualifiers SD, DS, SL) keeps a flip-flop, a BOOL the chart
    declares as __<qualifier>F<n>_<action> (n: the association's index in its step, from 0).  A variable
    of that name is a duplicate, reported where the association makes the flip-flop (line 8, column 5),
    after the warnings of the name itself (2:37); a name of another index is no clash."""
    mine = f"__{qualifier}F0_Lamp"
    twice = diagnostics(CHART.format(mine=mine, qualifier=qualifier))
    assert twice == [
        ("W-NJ-002", 2, 37, f"identifier '{mine}' starts or ends with '_': not allowed on an OMRON NJ"),
        ("W-NJ-003", 2, 37, f"identifier '{mine}' contains '__': not allowed on an OMRON NJ"),
        ("E-DECL-002", 8, 5, f"duplicate declaration of '{mine}' in POU Main (first declared at t.st:2:37)")]
    other = f"__{qualifier}F1_Lamp"
    assert [code for code, *_ in diagnostics(CHART.format(mine=other, qualifier=qualifier))] == ["W-NJ-002", "W-NJ-003"]


def test_a_constant_mod_of_udint_by_dint_takes_the_njs_ranking_as_division_does():
    """W501's ranking makes UDINT op DINT a UDINT operation (test_folding_follows_the_dialect: UDINT#10
    / DINT#-1 is 0): a constant DINT#-3 is 4294967293 there, so UDINT#10 MOD DINT#-3 is 10 and
    UDINT#7 MOD DINT#-2 is 7.  Between signed values MOD truncates (IEC 61131-3): DINT#10 MOD DINT#-3
    is 10 - (-3)·(-3) = 1, DINT#7 MOD DINT#-2 is 7 - (-2)·(-3) = 1."""
    decls, body = "    u, v : UDINT; w, z : DINT;", "u := UDINT#10 MOD DINT#-3; v := UDINT#7 MOD DINT#-2;"
    nj = after_one_scan(program(decls, body), "nj")
    assert (nj["u"], nj["v"]) == (10, 7)
    iec = after_one_scan(program(decls, "w := DINT#10 MOD DINT#-3; z := DINT#7 MOD DINT#-2;"))
    assert (iec["w"], iec["z"]) == (1, 1)
