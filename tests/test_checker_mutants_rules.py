"""Checker rules that mutation testing found unchecked (issue 16, seed-16 sample).

Each test states a rule of IEC 61131-3 (3rd edition unless said), of OMRON's
manuals (docs/nj501.md) or of the checker's own contract (its module
docstrings), and the diagnostic it gives: code, line and column counted by
hand in the snippet, and the words of the message that name what was
expected and what was found.
"""

from __future__ import annotations

import pytest

from st_runtime import ast
from st_runtime import types as T
from st_runtime.checker import check, constfold, limits, typesys
from st_runtime.checker.constfold import NOT_CONSTANT
from st_runtime.checker.memory import MemoryModel
from st_runtime.parser import parse
from checker_helpers import checked, diagnostics, nodes, only, program, statement


# ------------------------------------------------------------ references

def test_a_reference_refers_to_its_declared_string_length():
    """3rd ed. 6.4.4.10: a REF_TO T refers to a variable of type T.  A REF_TO
    STRING[20] set to REF(s), s a STRING[4], would let 20 characters be written
    into s (it did before this rule: 12 characters stayed in the STRING[4])."""
    text = program("    s : STRING[4];\n    r : REF_TO STRING[20];", "r := REF(s);")
    code, line, col, message = only(text)
    assert (code, line, col) == ("E-TYPE-004", 6, 6)
    assert "REF_TO STRING[20]" in message and "REF_TO STRING[4]" in message
    # The same length (and the same array of strings) is accepted.
    checked(program("    s : STRING[20];\n    r : REF_TO STRING[20];", "r := REF(s);"))
    checked(program("    a : ARRAY[1..2] OF STRING[5];\n    r : REF_TO ARRAY[1..2] OF STRING[5];",
                    "r := REF(a);"))
    assert only(program("    a : ARRAY[1..2] OF STRING[5];\n    r : REF_TO ARRAY[1..2] OF STRING[6];",
                        "r := REF(a);"))[:3] == ("E-TYPE-004", 6, 6)


def test_a_value_is_not_a_reference():
    code, line, col, message = only(program("    x : INT;\n    r : REF_TO INT;", "r := x;"))
    assert (code, line, col) == ("E-TYPE-004", 6, 6)
    assert "REF_TO INT" in message and "REF(" in message     # the hint: take a reference


def test_ref_takes_exactly_one_variable():
    """REF (3rd ed. 6.6.1.7) has one input: two arguments are too many
    (E-CALL-006), none too few (E-CALL-009)."""
    code, line, col, message = only(program("    x, y : INT;\n    r : REF_TO INT;", "r := REF(x, y);"))
    assert (code, line, col) == ("E-CALL-006", 6, 6) and "2 argument" in message
    code, line, col, _ = only(program("    r : REF_TO INT;", "r := REF();"))
    assert (code, line, col) == ("E-CALL-009", 5, 6)


def test_function_block_instances_are_not_values():
    """An FB instance is not copied by assignment (the checker's rule,
    E-TYPE-016, in both directions)."""
    code, line, col, message = only(program("    t : TON;\n    i : INT;", "i := t;"))
    assert (code, line, col) == ("E-TYPE-016", 6, 6) and "TON" in message
    assert only(program("    t : TON;\n    i : INT;", "t := i;"))[:3] == ("E-TYPE-016", 6, 6)


# ------------------------------------------------------------ standard functions

def test_extensible_max_takes_the_common_type_of_every_input():
    """MAX is extensible (3rd ed. table 28): IN3, IN4, ... are of the same
    generic type as IN1 and IN2, so MAX(INT, INT, LREAL) is an LREAL."""
    p = checked(program("    a, b : INT;\n    c, m : LREAL;", "m := MAX(a, b, c);"))
    call = statement(p, 0).value
    assert p.expr_types[id(call)] is T.LREAL
    code, line, col, _ = only(program("    a, b : INT;\n    c : LREAL;\n    i : INT;", "i := MAX(a, b, c);"))
    assert (code, line, col) == ("E-TYPE-004", 7, 6)       # an LREAL into an INT


def test_a_standard_input_given_twice():
    code, line, col, message = only(program("    a, b, m : INT;", "m := MAX(IN1 := a, IN1 := b);"))
    assert (code, line, col) == ("E-CALL-003", 5, 20) and "IN1" in message


def test_shift_of_an_untyped_literal_takes_the_smallest_bit_string():
    """SHL's IN is ANY_BITS (3rd ed. table 29).  16#FF without a type and
    without a context takes the smallest bit string holding it, BYTE, so
    SHL(16#FF, 4) is a BYTE (16#F0: the high bits leave the byte)."""
    p = checked(program("    ok : BOOL;", "ok := SHL(16#FF, 4) = 16#F0;"))
    shl = statement(p, 0).value.left
    assert p.expr_types[id(shl)] is T.BYTE


def test_operator_in_call_form_is_folded_like_the_operator():
    """ADD(2, 3) is 2 + 3 (3rd ed. table 29): a constant 5."""
    p = checked(program("    x : INT;", "x := ADD(2, 3);"))
    assert p.constants[id(statement(p, 0).value)] == 5


def test_upper_and_lower_bound():
    """LOWER_BOUND / UPPER_BOUND (3rd ed. 6.5.3) of a dimension: DINT."""
    p = checked(program("    a : ARRAY[2..7, 0..1] OF INT;\n    n : DINT;",
                        "n := UPPER_BOUND(a, 1) - LOWER_BOUND(a, 2);"))
    calls = nodes(statement(p, 0), ast.Call)
    assert [p.expr_types[id(c)] for c in calls] == [T.DINT, T.DINT]
    code, line, col, message = only(program("    x : INT;\n    n : DINT;", "n := UPPER_BOUND(x, 1);"))
    assert (code, line, col) == ("E-TYPE-006", 6, 18)
    assert "UPPER_BOUND" in message and "INT" in message


def test_mod_is_not_folded_on_reals():
    """MOD is defined on ANY_INT (3rd ed. table 30): on reals there is nothing to fold."""
    assert constfold.apply_binary("MOD", 7, 3) == 1
    assert constfold.apply_binary("MOD", 7.5, 2.0) is NOT_CONSTANT
    assert constfold.apply_binary("MOD", 7, 2.0) is NOT_CONSTANT


def test_power_with_a_literal_base_takes_the_real_of_its_context():
    """The base of ** is ANY_REAL; an untyped literal takes the type of the
    context (`r := 2.0 ** n` with r REAL is a REAL), whether the exponent is a
    variable or a literal too."""
    p = checked(program("    r : REAL;\n    n : INT;", "r := 2.0 ** n;\nr := 2.0 ** 3;"))
    for i in (0, 1):
        power = statement(p, i).value
        assert p.expr_types[id(power)] is T.REAL
        assert p.expr_types[id(power.left)] is T.REAL


# ------------------------------------------------------------ literals and members

def test_enumeration_literal_of_a_type_that_is_no_enumeration():
    text = ("TYPE S : STRUCT a : INT; END_STRUCT; END_TYPE\n"
            + program("    x : INT;", "x := S#a;"))
    code, line, col, message = only(text)
    assert (code, line, col) == ("E-TYPE-015", 6, 6) and "S" in message
    # The checker's contract: an expression that gave a diagnostic has the type ERROR.
    files = [parse(text, "t.st")[0]]
    checked_program, _ = check(files)
    literal = next(n for n in nodes(checked_program.pous["MAIN"].node.body, ast.EnumLiteral))
    assert checked_program.expr_types[id(literal)] is typesys.ERROR


def test_unknown_type_prefix_on_a_literal():
    text = program("    x : INT;", "x := FOO#5;")
    code, line, col, message = only(text)
    assert (code, line, col) == ("E-DECL-004", 5, 6) and "FOO" in message
    checked_program, _ = check([parse(text, "t.st")[0]])
    literal = next(n for n in nodes(checked_program.pous["MAIN"].node.body, ast.IntLiteral))
    assert checked_program.expr_types[id(literal)] is typesys.ERROR


def test_member_a_function_block_does_not_have():
    code, line, col, message = only(program("    t : TON;\n    b : BOOL;", "b := t.Foo;"))
    assert (code, line, col) == ("E-TYPE-009", 6, 6)
    assert "TON" in message and "Foo" in message


def test_iec_pin_name_read_under_nj():
    """OMRON's CTU names its reset input Reset (docs/nj501.md, pins): `c.R` is
    another dialect's name, E-PIN-001 at the member."""
    code, line, col, message = only(program("    c : CTU;\n    b : BOOL;", "b := c.R;"), "nj")
    assert (code, line, col) == ("E-PIN-001", 6, 6)
    assert "Reset" in message


def test_nj_rule_006_names_the_element_or_the_member():
    """OMRON (docs/nj501.md, rule 006): "Cannot use an element of array or a
    member of structure for the reference of function block instance
    variables"; the message says which of the two it is."""
    fb = ("TYPE P : STRUCT v : INT; END_STRUCT; END_TYPE\n"
          "FUNCTION_BLOCK F\nVAR_OUTPUT\n    A : ARRAY[1..2] OF INT;\n    S : P;\nEND_VAR\nEND_FUNCTION_BLOCK\n")
    text = fb + program("    f : F;\n    x : INT;", "x := f.A[1];\nx := f.S.v;")
    found = diagnostics(text, "nj")
    assert [(c, line, col) for c, line, col, _ in found] == [("E-NJ-006", 13, 6), ("E-NJ-006", 14, 6)]
    assert found[0][3].startswith("an element of 'f.A'")
    assert found[1][3].startswith("a member of 'f.S'")


# ------------------------------------------------------------ declarations

def test_array_initializer_repeating_a_nested_row_counts_every_element():
    """`[3([1, 2, 3])]` gives 3 x 3 = 9 elements, more than ARRAY[1..2, 1..3]'s 6."""
    code, line, col, message = only(program("    a : ARRAY[1..2, 1..3] OF INT := [3([1, 2, 3])];", ""))
    assert (code, line) == ("E-DECL-007", 3) and "6" in message and "9" in message
    checked(program("    a : ARRAY[1..2, 1..3] OF INT := [2([1, 2, 3])];", ""))


def test_function_returning_a_function_block_type():
    """A FUNCTION's result is a data type; an FB type is refused at the type."""
    code, line, col, message = only("FUNCTION F : TON\nEND_FUNCTION\n")
    assert (code, line, col) == ("E-DECL-009", 1, 14) and "TON" in message


def test_a_function_block_may_not_locate_a_full_address():
    """6.5.5: inside a FUNCTION_BLOCK only %I*, %Q*, %M* (the configuration
    places them), not a full address."""
    code, line, col, message = only("FUNCTION_BLOCK F\nVAR\n    x AT %IW3 : INT;\nEND_VAR\n"
                                    "END_FUNCTION_BLOCK\n")
    assert (code, line, col) == ("E-DECL-015", 3, 5) and "%IW3" in message


def test_edge_is_only_for_a_bool_input():
    """R_EDGE / F_EDGE (3rd ed. 6.5.3, table 13) qualify BOOL inputs of an FB
    or PROGRAM; a plain VAR may not be an edge."""
    code, line, col, message = only(program("    x : BOOL R_EDGE;", ""))
    assert (code, line, col) == ("E-DECL-013", 3, 5)
    assert message.endswith("found a BOOL VAR")


def test_external_of_a_constant_global_is_constant():
    """A VAR_EXTERNAL refers to the VAR_GLOBAL: a CONSTANT global stays
    unwritable through it (3rd ed. 6.5.6)."""
    text = ("VAR_GLOBAL CONSTANT\n    Most : INT := 5;\nEND_VAR\n"
            "PROGRAM Main\nVAR_EXTERNAL\n    Most : INT;\nEND_VAR\nMost := 6;\nEND_PROGRAM\n")
    code, line, col, message = only(text)
    assert (code, line, col) == ("E-ASSIGN-001", 8, 1) and "CONSTANT" in message


def test_a_parent_namespace_that_declares_no_such_pou():
    """NAMESPACE Units.Length declares Units as well (3rd ed. 6.9): Units.MmToM
    is looked up in Units, which has no MmToM."""
    text = ("NAMESPACE Units.Length\nFUNCTION MmToM : LREAL\nVAR_INPUT\n    Mm : LREAL;\nEND_VAR\n"
            "MmToM := Mm / 1000.0;\nEND_FUNCTION\nEND_NAMESPACE\n"
            + program("    m : LREAL;", "m := Units.MmToM(5.0);"))
    code, line, col, message = only(text)
    assert (code, line, col) == ("E-DECL-001", 13, 6)
    assert "NAMESPACE Units " in message and "MmToM" in message


def test_function_block_extends_one_function_block():
    """3rd ed. 6.6.5.2: an FB EXTENDS at most one FB."""
    text = ("FUNCTION_BLOCK A\nEND_FUNCTION_BLOCK\nFUNCTION_BLOCK B\nEND_FUNCTION_BLOCK\n"
            "FUNCTION_BLOCK C EXTENDS A, B\nEND_FUNCTION_BLOCK\n")
    found = diagnostics(text)
    assert ("E-DECL-016", 5, 1) in [(c, line, col) for c, line, col, _ in found]
    assert any("EXTENDS 2" in m for _, _, _, m in found)


def test_a_method_belongs_to_its_file():
    p = checked("FUNCTION_BLOCK F\nMETHOD M : INT\nM := 1;\nEND_METHOD\nEND_FUNCTION_BLOCK\n")
    assert p.pous["F"].methods["M"].file == "t.st"


def test_super_body_rules_under_codesys():
    """CODESYS's SUPER^() runs the base FB's body: only in an FB that EXTENDS
    another, and with no arguments."""
    plain = "FUNCTION_BLOCK A\nSUPER^();\nEND_FUNCTION_BLOCK\n"
    code, line, col, message = only(plain, "codesys")
    assert (code, line, col) == ("E-DECL-016", 2, 1)
    assert "FUNCTION_BLOCK" in message and "EXTENDS" in message
    with_args = ("FUNCTION_BLOCK A\nVAR_INPUT\n    x : INT;\nEND_VAR\nEND_FUNCTION_BLOCK\n"
                 "FUNCTION_BLOCK B EXTENDS A\nSUPER^(x := 1);\nEND_FUNCTION_BLOCK\n")
    code, line, col, _ = only(with_args, "codesys")
    assert (code, line, col) == ("E-CALL-006", 7, 8)


# ------------------------------------------------------------ statements, recursion, limits

def test_case_ranges_that_share_their_end_overlap():
    """3rd ed. 7.3.3.3.3: no value may appear in two CASE labels; 1..5 and 5..8 share 5."""
    code, line, col, message = only(program("    x, y : INT;",
                                            "CASE x OF\n1..5: y := 1;\n5..8: y := 2;\nEND_CASE;"))
    assert (code, line) == ("E-TYPE-013", 7) and "line 6" in message
    checked(program("    x, y : INT;", "CASE x OF\n1..5: y := 1;\n6..8: y := 2;\nEND_CASE;"))


def test_recursion_is_found_after_a_callee_already_visited():
    """IEC 61131-3 and OMRON NJ forbid recursion: C and D call each other, after
    A's call of B (the search must go on past B, already seen from A)."""
    text = ("FUNCTION A : INT\nA := B();\nEND_FUNCTION\n"
            "FUNCTION B : INT\nB := 1;\nEND_FUNCTION\n"
            "FUNCTION C : INT\nC := D();\nEND_FUNCTION\n"
            "FUNCTION D : INT\nD := C();\nEND_FUNCTION\n")
    code, line, col, message = only(text)
    assert (code, line, col) == ("E-REC-001", 8, 6) and "C calls D" in message


def test_file_size_limit_is_inclusive():
    """E-LIMIT-012: at most MAX_FILE_BYTES characters; exactly that many pass."""
    assert limits.file_too_large("x" * limits.MAX_FILE_BYTES) is None
    assert limits.file_too_large("x" * (limits.MAX_FILE_BYTES + 1)) is not None



def test_project_without_a_pou_is_checked_without_an_internal_error():
    """Globals alone beyond the project limit (no POU to point at): the checker
    never raises (st_runtime/checker/__init__.py)."""
    text = "VAR_GLOBAL\n    a : ARRAY[1..40] OF LREAL;\n    b : ARRAY[1..40] OF LREAL;\nEND_VAR\n"
    _, found = check([parse(text, "g.st")[0]], memory_limit=400)
    assert not [d for d in found if d.code == "E-CHECK-999"]


# ------------------------------------------------------------ tables built at import time

def test_implicit_widening_closure_built_afresh():
    """typesys.WIDENS_TO is built at import time; built again here and compared
    with the chains of IEC 61131-3 3rd ed. figure 11 (implicit conversions)."""
    widens = typesys._closure()
    assert widens["SINT"] == {"INT", "DINT", "LINT", "REAL", "LREAL"}
    assert widens["USINT"] == {"UINT", "UDINT", "ULINT", "INT", "DINT", "LINT", "REAL", "LREAL"}
    assert widens["REAL"] == {"LREAL"}
    assert widens["BOOL"] == {"BYTE", "WORD", "DWORD", "LWORD"}
    assert widens == typesys.WIDENS_TO


# ------------------------------------------------------------ memory

def test_a_reference_takes_eight_bytes():
    """A REF_TO (or INTERFACE) variable holds a reference, counted as the 8
    bytes of a VAR_IN_OUT's (memory.py's assumption): 10^8 of them are 800 MB,
    beyond the 64 MiB limit (they counted 0 bytes before)."""
    assert MemoryModel().layout(T.RefType(T.INT, False)) == (8, 8)
    code, line, col, message = only(program("    a : ARRAY[0..99999999] OF REF_TO INT;", ""))
    assert (code, line) == ("E-LIMIT-008", 3) and "800,000,000 bytes" in message



def test_a_variable_of_an_unknown_type_needs_no_memory():
    """One root cause, one diagnostic: a variable whose type is unknown was
    refused at its type (E-DECL-004) and counts no bytes, so even a limit of 0
    bytes adds no E-LIMIT diagnostic for it."""
    text = "PROGRAM Main\nVAR\n    x : Nowhere;\nEND_VAR\nEND_PROGRAM\n"
    _, found = check([parse(text, "t.st")[0]], memory_limit=0)
    assert [(d.code, d.pos.line, d.pos.col) for d in found] == [("E-DECL-004", 3, 9)]


# ------------------------------------------------------------ second round (seed-18 survivors)

def test_subrange_may_reach_the_limits_of_its_base():
    """3rd ed. 6.4.4.4: a subrange's limits lie within its base type's range, ends included."""
    checked(program("    a : INT(-32768..32767);\n    b : USINT(0..255);", ""))
    code, line, col, message = only(program("    b : USINT(0..256);", ""))
    assert (code, line, col) == ("E-DECL-014", 3, 15) and "255" in message


def test_strings_of_different_lengths_compare():
    """Comparison of STRINGs (3rd ed. table 31): lengths need not agree."""
    p = checked(program("    s : STRING[10];\n    t : STRING[20];\n    b : BOOL;", "b := s = t;"))
    assert p.expr_types[id(statement(p, 0).value)] is T.BOOL
    # STRING and WSTRING have no implicit conversion (3rd ed. figure 11): not comparable.
    code, line, col, _ = only(program("    s : STRING;\n    w : WSTRING;\n    b : BOOL;", "b := s = w;"))
    assert (code, line) == ("E-TYPE-002", 7)


def test_time_of_day_minus_time_of_day_is_a_time():
    """3rd ed. table 35: TOD - TOD is a TIME."""
    p = checked(program("    a, b : TOD;\n    d : TIME;", "d := a - b;"))
    assert p.expr_types[id(statement(p, 0).value)] is T.TIME


def test_protected_method_is_called_from_a_derived_block():
    """3rd ed. 6.6.5.5: PROTECTED is visible in the FB and the FBs extending it."""
    checked("FUNCTION_BLOCK A\nMETHOD PROTECTED M : INT\nM := 1;\nEND_METHOD\nEND_FUNCTION_BLOCK\n"
            "FUNCTION_BLOCK B EXTENDS A\nVAR\n    x : INT;\nEND_VAR\nx := M();\nEND_FUNCTION_BLOCK\n")


def test_chained_comparison_in_call_form_holds_for_every_pair():
    """GT(IN1, IN2, IN3) is IN1 > IN2 AND IN2 > IN3 (3rd ed. table 31): GT(1, 7, 3) is FALSE."""
    p = checked(program("    b : BOOL;", "b := GT(1, 7, 3);"))
    assert p.constants[id(statement(p, 0).value)] is False


def test_operator_in_call_form_input_given_twice():
    code, line, col, _ = only(program("    a, b, c : INT;", "c := ADD(IN1 := a, IN1 := b);"))
    assert (code, line, col) == ("E-CALL-003", 5, 6)


def test_chart_without_initial_step_is_one_diagnostic():
    """An SFC needs an INITIAL_STEP (3rd ed. 6.7.2): one E-SFC-002, nothing after it."""
    text = ("PROGRAM Main\nVAR\n    n : INT;\nEND_VAR\nSTEP S1 : A(N); END_STEP\n"
            "ACTION A:\nn := n + 1;\nEND_ACTION\nEND_PROGRAM\n")
    assert [(c, line, col) for c, line, col, _ in diagnostics(text)] == [("E-SFC-002", 5, 1)]


def test_step_declared_twice_points_at_the_second():
    text = ("PROGRAM Main\nVAR\n    n : INT;\nEND_VAR\nINITIAL_STEP S1 : END_STEP\nSTEP S1 : END_STEP\n"
            "END_PROGRAM\n")
    found = diagnostics(text)
    assert [(c, line, col) for c, line, col, _ in found] == [("E-SFC-002", 6, 1)]
    assert "S1" in found[0][3]


def test_constant_for_variable_and_non_bool_condition_messages():
    code, line, col, message = only("PROGRAM Main\nVAR CONSTANT\n    i : INT := 1;\nEND_VAR\n"
                                    "FOR i := 1 TO 3 DO\nEND_FOR;\nEND_PROGRAM\n")
    assert (code, line, col) == ("E-ASSIGN-001", 5, 1) and "FOR" in message and "i" in message
    code, line, col, message = only(program("    x : INT;", "IF x THEN\nx := 1;\nEND_IF;"))
    assert (code, line, col) == ("E-TYPE-003", 5, 4) and message.startswith("IF condition")


def test_bool_literal_with_prefix_is_true():
    p = checked(program("    b : BOOL;", "b := BOOL#1;"))
    assert p.constants[id(statement(p, 0).value)] is True


def test_comparisons_fold():
    assert constfold.apply_binary("=", 3, 3) is True
    assert constfold.apply_binary("<>", 3, 3) is False


def test_unknown_method_of_a_user_block_is_a_diagnostic_not_an_internal_error():
    text = ("FUNCTION_BLOCK F\nEND_FUNCTION_BLOCK\n" + program("    f : F;", "f.Nope();"))
    found = diagnostics(text)
    assert found and not [c for c, _, _, _ in found if c == "E-CHECK-999"]
    assert [(c, line, col) for c, line, col, _ in found] == [("E-TYPE-009", 7, 1)]
    assert "Nope" in found[0][3]


def test_reference_to_a_literal_is_one_diagnostic():
    found = diagnostics(program("    r : REF_TO INT;", "r := REF(5);"))
    assert len(found) == 1 and found[0][1] == 5


def test_conversion_hints_name_the_conversion():
    """A real function of an INT suggests INT_TO_LREAL; a shift of an INT, INT_TO_WORD."""
    _, _, _, message = only(program("    i : INT;\n    r : LREAL;", "r := SQRT(i);"))
    assert "INT_TO_LREAL" in message
    _, _, _, message = only(program("    i : INT;\n    w : WORD;", "w := SHL(i, 1);"))
    assert "INT_TO_WORD" in message


def test_standard_function_has_no_outputs():
    code, line, col, _ = only(program("    a, b, c : INT;", "c := MAX(IN1 := a, IN2 := b, OUT => c);"))
    assert (code, line, col) == ("E-CALL-005", 5, 30)


def test_function_without_result_used_as_a_value():
    code, line, col, message = only("FUNCTION F\nVAR_INPUT\n    a : INT;\nEND_VAR\nEND_FUNCTION\n"
                                    + program("    x : INT;", "x := F(1);"))
    assert (code, line, col) == ("E-TYPE-016", 10, 6) and message.startswith("function F")


def test_eno_must_be_bool():
    code, _, _, message = only("FUNCTION F : INT\nF := 1;\nEND_FUNCTION\n"
                               + program("    x, i : INT;", "x := F(EN := TRUE, ENO => i);"))
    assert code == "E-TYPE-004" and message.startswith("ENO")


def test_duplicate_variable_names_its_pou():
    code, line, col, message = only(program("    x : INT;\n    x : INT;", ""))
    assert (code, line, col) == ("E-DECL-002", 4, 5) and "POU Main" in message


def test_a_refused_construct_is_reported_once_per_file_with_the_count():
    """One root cause, one diagnostic (dialects.py): POINTER TO, CODESYS's, is
    refused under iec at its first use, the message counting the 2 others."""
    code, line, _, message = only(program("    p : POINTER TO INT;\n    q : POINTER TO INT;\n"
                                          "    r : POINTER TO INT;", ""))
    assert (code, line) == ("E-DIALECT-001", 3) and message.endswith("(2 more use(s) in this file)")


def test_string_length_must_be_positive():
    code, line, col, _ = only(program("    s : STRING[0];", ""))
    assert (code, line, col) == ("E-DECL-006", 3, 16)


def test_interface_variable_takes_an_instance():
    code, line, col, message = only("INTERFACE I\nEND_INTERFACE\n"
                                    + program("    i : I;\n    x : INT;", "i := x;"))
    assert (code, line, col) == ("E-TYPE-004", 8, 6) and "implements I" in message



def test_every_positional_argument_after_a_formal_one_is_refused():
    """6.6.1.4.2: positional inputs come before formal ones; each one after is reported."""
    found = diagnostics(program("    a, b, c, m : INT;", "m := MAX(IN1 := a, b, c);"))
    assert [(code, line, col) for code, line, col, _ in found] == [("E-CALL-008", 5, 20),
                                                                     ("E-CALL-008", 5, 23)]


def test_f_edge_is_reserved_under_iec():
    """IEC 61131-3 reserves R_EDGE and F_EDGE (CODESYS takes them as names)."""
    code, line, _, message = only("PROGRAM Main\nVAR F_EDGE : BOOL; END_VAR\nF_EDGE := TRUE;\nEND_PROGRAM\n")
    assert (code, line) == ("E-DIALECT-001", 2) and "F_EDGE" in message


def test_statements_nested_beyond_the_limit():
    """E-LIMIT-003: at most MAX_BLOCK_DEPTH (40) statements nested; 41 IFs are one too many."""
    depth = limits.MAX_BLOCK_DEPTH + 1
    body = "IF TRUE THEN\n" * depth + "x := 1;\n" + "END_IF;\n" * depth
    found = diagnostics(program("    x : INT;", body))
    assert [code for code, _, _, _ in found] == ["E-LIMIT-003"]


@pytest.mark.parametrize("error, code, words", [
    (RecursionError(), "E-LIMIT-001", ["nested too deeply"]),
    (ValueError("boom"), "E-CHECK-999", ["ValueError", "boom"]),
])
def test_an_exception_in_a_pass_is_one_diagnostic(monkeypatch, error, code, words):
    """The promise of check(): diagnostics, never a traceback.  A RecursionError
    anywhere in the passes is E-LIMIT-001, any other exception E-CHECK-999 naming
    it, both at the first user file."""
    import st_runtime.checker as checker

    def failing(ctx):
        raise error

    monkeypatch.setattr(checker, "check_recursion", failing)
    _, found = check([parse("PROGRAM Main\nEND_PROGRAM\n", "t.st")[0]])
    assert [(d.code, str(d.pos)) for d in found] == [(code, "t.st:1:1")]
    assert all(w in found[0].message for w in words)
