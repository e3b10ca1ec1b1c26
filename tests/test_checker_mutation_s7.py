"""Checker rules that mutation testing found unchecked: survivors of the fresh
seed-21 sample (issue 16, docs/mutation.md, checker, session 7).

Each test states a rule of IEC 61131-3 (2nd ed. 2003 or 3rd ed. 2013) or of
the checker's own contract (its module docstrings: every diagnostic has its
registered code, its words and the position of what it is about), with line
and column counted by hand in the snippet, and values worked out by hand.
"""

from __future__ import annotations

import importlib

from checker_helpers import checked, diagnostics, only, program, walk
from test_checker_mutants_third import after_one_scan


# ------------------------------------------------------------ constant folding

def test_integer_or_and_less_or_equal_of_constants():
    """Constant operands are folded by the checker (constfold.apply_binary):
    16#0F OR 16#30 = 16#3F = 63; 1 <= 2 is TRUE, 2 <= 1 FALSE, 2 <= 2 TRUE."""
    main = after_one_scan(program("    w : WORD; a, b, c : BOOL;",
                                  "w := WORD#16#0F OR WORD#16#30;\na := 1 <= 2;\nb := 2 <= 1;\nc := 2 <= 2;"))
    assert (main["w"], main["a"], main["b"], main["c"]) == (63, True, False, True)


def test_not_constant_shows_its_name():
    from st_runtime.checker.constfold import NOT_CONSTANT

    assert repr(NOT_CONSTANT) == "NOT_CONSTANT"


# ------------------------------------------------------------ diagnostics: words and positions

def test_a_bcd_function_of_one_named_type_names_it():
    """WORD_BCD_TO_UINT takes a WORD (OMRON's BCD functions): the message names
    the type itself, not a category."""
    assert only(program("    i : UINT; r : REAL;", "i := WORD_BCD_TO_UINT(r);")) == \
        ("E-TYPE-004", 5, 23, "WORD_BCD_TO_UINT: argument IN: expected WORD, found REAL")


def test_a_read_write_access_path_to_a_constant_names_the_path():
    text = ("PROGRAM Tank\nVAR CONSTANT Capacity : INT := 100; END_VAR\n"
            "VAR_ACCESS Cap : Capacity : INT READ_WRITE; END_VAR\nEND_PROGRAM\n")
    assert only(text) == ("E-ASSIGN-001", 3, 18, "VAR_ACCESS Cap: 'Capacity' is CONSTANT and cannot be written")


def test_an_unknown_enumeration_value_lists_the_values():
    text = "TYPE Color : (Red, Green); END_TYPE\n" + program("    c : Color;", "c := Color#Blue;")
    assert only(text) == ("E-TYPE-015", 6, 6, "'Blue' is not a value of Color (values: Red, Green)")


def test_an_index_out_of_bounds_names_its_dimension():
    """Dimensions count from 1 (the first index is dimension 1)."""
    text = program("    a : ARRAY[1..3, 1..2] OF INT;", "a[1, 5] := 0;\na[4, 1] := 0;")
    assert diagnostics(text) == [
        ("E-TYPE-008", 5, 6, "index 5 is out of bounds 1..2 of dimension 2"),
        ("E-TYPE-008", 6, 3, "index 4 is out of bounds 1..3 of dimension 1"),
    ]


def test_ref_of_a_literal_names_ref():
    assert only(program("    r : REF_TO INT;", "r := REF(5);")) == \
        ("E-TYPE-014", 5, 10, "REF(...): expected a variable, found a literal")


def test_an_output_of_the_wrong_type_is_reported_at_its_variable():
    """`f(Q => s)`: the diagnostic points at s (line 8, column 8)."""
    text = ("FUNCTION_BLOCK F\nVAR_OUTPUT Q : BOOL; END_VAR\nEND_FUNCTION_BLOCK\n"
            + program("    f : F; s : STRING;", "f(Q => s);"))
    code, line, col, message = only(text)
    assert (code, line, col) == ("E-TYPE-004", 8, 8)
    assert message.startswith("output 'Q' of F: expected STRING[80], found BOOL")


# ------------------------------------------------------------ rules

def test_exit_and_continue_after_a_loop_are_outside_it():
    """IEC 61131-3 3rd ed. 7.3.3.4 (EXIT) and 7.3.3.5 (CONTINUE): only inside
    FOR, WHILE or REPEAT; after the loop's END the statement is outside."""
    assert only(program("    i : INT;", "WHILE FALSE DO i := 1; END_WHILE;\nEXIT;")) == \
        ("E-FLOW-001", 6, 1, "EXIT outside a loop: expected inside FOR, WHILE or REPEAT")
    assert only(program("    i : INT;", "REPEAT i := 1; UNTIL TRUE END_REPEAT;\nCONTINUE;"))[:3] == \
        ("E-FLOW-002", 6, 1)
    assert only(program("    i : INT;", "FOR i := 1 TO 2 DO END_FOR;\nEXIT;"))[:3] == ("E-FLOW-001", 6, 1)


def test_a_repetition_count_of_zero_adds_no_element():
    """An array initializer's repetition count is a non-negative integer
    (the checker's E-DECL-006 rule): 0(7) repeats 7 no times."""
    main = after_one_scan(program("    a : ARRAY[1..3] OF INT := [0(7), 1, 2, 3];\n    s : INT;",
                                  "s := a[1] * 100 + a[2] * 10 + a[3];"))
    assert main["s"] == 123


def test_this_reads_the_instances_own_variables():
    """THIS is the instance itself (3rd ed. 6.6.5.8): a method reads and writes
    the FB's internal VAR through it, which an outside reader may not."""
    text = ("FUNCTION_BLOCK F\nVAR n : INT; END_VAR\nMETHOD Bump\nTHIS.n := THIS.n + 1;\nEND_METHOD\n"
            "END_FUNCTION_BLOCK\n" + program("    f : F; k : INT;", "f.Bump();\nf.Bump();"))
    assert diagnostics(text) == []
    outside = ("FUNCTION_BLOCK F\nVAR n : INT; END_VAR\nEND_FUNCTION_BLOCK\n"
               + program("    f : F; k : INT;", "k := f.n;"))
    assert only(outside)[:3] == ("E-TYPE-009", 8, 6)      # at `f.n`, where the path starts


def test_limits_worked_out_afresh(monkeypatch):
    """The limits walk keeps each node class's shape in a memo filled on first
    use (`PerClass(_shape)`); with an empty memo the same limits hold (MAX_LOOP_DEPTH = 12)."""
    limits = importlib.import_module("st_runtime.checker.limits")
    from st_runtime.per_class import PerClass

    def nested(depth: int) -> str:
        return program("    i : INT;", "WHILE FALSE DO " * depth + "i := 1;" + " END_WHILE;" * depth)

    monkeypatch.setattr(limits, "_SHAPES", PerClass(limits._shape))
    assert diagnostics(nested(limits.MAX_LOOP_DEPTH)) == []
    monkeypatch.setattr(limits, "_SHAPES", PerClass(limits._shape))
    assert [d[:2] for d in diagnostics(nested(limits.MAX_LOOP_DEPTH + 1))] == [("E-LIMIT-004", 5)]


def test_the_native_prelude_built_afresh_is_shared(monkeypatch):
    """The native prelude checks alone, so a load builds a shared base of it
    (prelude_base's contract), also when none is cached yet."""
    prelude_base = importlib.import_module("st_runtime.checker.prelude_base")
    from st_runtime.loader import parse_texts

    for dialect in ("iec", "nj"):
        monkeypatch.setattr(prelude_base, "_BASES", {})
        _, parsed, _ = parse_texts({}, dialect)
        base = prelude_base.prelude_base([f for _, f in parsed], dialect, False)
        assert base is not None and base.dialect == dialect


# ------------------------------------------------------------ SFC (IEC 61131-3 3rd ed. 6.7)

L_CHART = """PROGRAM Main
VAR Go : BOOL; Count : INT; END_VAR
INITIAL_STEP S1:
    Inc(L, T#1s);
END_STEP
STEP S2:
END_STEP
TRANSITION FROM S1 TO S2 := Go;
END_TRANSITION
TRANSITION FROM S2 TO S1 := FALSE;
END_TRANSITION
ACTION Inc:
    Count := Count + 1;
END_ACTION
END_PROGRAM
"""


def test_a_time_limited_action_stops_when_its_step_is_left():
    """Qualifier L (3rd ed. table 56): the action is active while its step is
    active and the time has not elapsed. Scans 1-2 in S1: Count 1, 2; scan 3
    leaves S1 (Go), Q falls, the body runs its final time: 3; then no more."""
    from st_runtime.api import load_text

    plc = load_text(L_CHART).controller(period="1ms")
    main = plc.add_program("Main")
    plc.run(2)
    assert main["Count"] == 2
    main["Go"] = True
    plc.run(3)
    assert (main["S2.X"], main["Count"]) == (True, 3)


def test_every_node_of_a_lowered_chart_has_a_position():
    """The lowering gives every statement and expression it makes (the steps'
    initial values, the hidden flags, the body) the position of the chart
    element it comes from, so a diagnostic or fault points into the file. (The
    type names of the variables it adds are built-in types, which no
    diagnostic can point at, and carry none.)"""
    from st_runtime import ast

    main = checked(L_CHART).pous["MAIN"].node
    nodes = [n for n in walk(main) if not isinstance(n, ast.NamedType)]
    assert len(nodes) > 100
    assert [type(n).__name__ for n in nodes if n.pos.file != "t.st" or n.pos.line < 1] == []


# ------------------------------------------------------------ later survivors of the sample

def test_ampersand_is_reported_as_and():
    """`&` is IEC's other spelling of AND (3rd ed. table 71): the message names AND."""
    assert only(program("    b : BOOL; i : INT;", "b := i & TRUE;")) == \
        ("E-TYPE-001", 5, 8, "AND: expected BOOL or bit-string operands, found INT")


def test_an_integer_literal_added_to_a_real_is_a_real():
    """A literal takes the type its context needs (3rd ed. 6.3.2): in `r + 16777217`
    with r REAL it is the REAL 16777216 (2^24 + 1 is a tie between 2^24 and
    2^24 + 2, rounded to even), and 1.0 + 16777216 = 2^24 + 1 rounds to 2^24
    again: 16777216, where an LREAL literal would give 16777218."""
    main = after_one_scan(program("    r, r2 : REAL;", "r := 1.0;\nr2 := r + 16777217;"))
    assert main["r2"] == 16777216.0


def test_an_enumeration_takes_four_bytes_aligned_to_four():
    """OMRON's table (memory.py, W501 appendix / W506 A-47): an enumeration is
    4 bytes at a multiple of 4, so after a BYTE it starts at 4: 8 bytes."""
    from st_runtime.checker.memory import MemoryModel

    types = checked("TYPE Color : (Red, Green); END_TYPE\n"
                    "TYPE S : STRUCT b : BYTE; c : Color; END_STRUCT; END_TYPE\n" + program("    s : S;", "")).types
    assert MemoryModel().layout(types["COLOR"]) == (4, 4)
    assert MemoryModel().layout(types["S"]) == (8, 4)


def test_a_reference_input_writes_what_it_refers_to():
    """`p^.a := 5` inside an FB whose VAR_INPUT p is a REF_TO writes the
    variable p refers to, not the (read-only) input itself."""
    text = ("TYPE Pair : STRUCT a, b : INT; END_STRUCT; END_TYPE\nFUNCTION_BLOCK Setter\n"
            "VAR_INPUT p : REF_TO Pair; END_VAR\np^.a := 5;\nEND_FUNCTION_BLOCK\n"
            + program("    x : Pair; s : Setter;", "s(p := REF(x));"))
    assert after_one_scan(text)["x.a"] == 5


def test_a_constant_external_is_a_constant():
    """A VAR_EXTERNAL CONSTANT has its global's value (3rd ed. 6.5.2.2):
    N = 3 bounds an array and indexes it."""
    text = ("VAR_GLOBAL CONSTANT N : INT := 3; END_VAR\nPROGRAM Main\nVAR_EXTERNAL CONSTANT N : INT; END_VAR\n"
            "VAR a : ARRAY[1..N] OF INT; s : INT; END_VAR\na[3] := 7;\ns := a[N];\nEND_PROGRAM\n")
    assert after_one_scan(text)["s"] == 7


def test_statements_nested_too_deep_name_the_statement():
    """E-LIMIT-003 at the 41st nested IF (MAX_BLOCK_DEPTH = 40): column
    40 x len('IF TRUE THEN ') + 1 = 521 of line 5, naming IF."""
    text = program("    i : INT;", "IF TRUE THEN " * 41 + "i := 1;" + " END_IF;" * 41)
    assert only(text) == ("E-LIMIT-003", 5, 521, "statements nested more than 40 levels deep (IF here) in Main")


def test_open_instances_reach_inside_an_fb():
    """`stgen test` checks with open_instances: every variable of an FB
    instance is visible from outside (checker.check's contract)."""
    from st_runtime.checker import check
    from st_runtime.loader import parse_texts

    text = ("FUNCTION_BLOCK F\nVAR n : INT; END_VAR\nEND_FUNCTION_BLOCK\n"
            + program("    f : F; k : INT;", "k := f.n;"))
    codes = {}
    for open_instances in (False, True):
        _, parsed, _ = parse_texts({"t.st": text}, "iec")
        _, found = check([f for _, f in parsed], "iec", open_instances=open_instances)
        codes[open_instances] = [d.code for d in found]
    assert codes == {False: ["E-TYPE-009"], True: []}
