"""Checker rules that mutation testing found unchecked: seed 24's last survivors
and the survivors of the fresh seed-25 sample (issue 16, docs/mutation.md,
checker, session 10).

Each test states a rule of IEC 61131-3 (3rd ed. 2013) or of the checker's own
contract (one root cause, one diagnostic), with line and column counted by hand
in the snippet and values worked out by hand.
"""

from __future__ import annotations

import importlib

from checker_helpers import diagnostics, only, program
from test_checker_mutants_third import after_one_scan


# ------------------------------------------------------------ seed 24's last survivors

def test_the_bounds_of_a_refused_for_variable_add_no_diagnostic():
    """A REAL control variable is the one error (E-TYPE-010); `SQRT(4)` as the end
    value is a REAL function of an untyped literal (4 is then LREAL) and must not
    be reported as well: typed against the refused variable's ERROR, the literal
    would become SINT and SQRT would be refused for it."""
    assert diagnostics(program("    r : REAL;", "FOR r := 1 TO SQRT(4) DO\nEND_FOR;")) == \
        [("E-TYPE-010", 5, 1, "FOR control variable 'r': expected an integer variable, found REAL")]


def test_not_of_a_typed_bit_string_constant_is_a_constant():
    """3rd ed. 6.5.1.5: an initial value is a constant expression, and so is a CASE
    label.  NOT WORD#16#00FF = 16#FF00 = 65280; NOT BYTE#16#FE = 1."""
    main = after_one_scan(program("    w : WORD := NOT WORD#16#00FF; b : BYTE := 1; hit : BOOL;",
                                  "CASE b OF\n  NOT BYTE#16#FE: hit := TRUE;\nEND_CASE;"))
    assert (main["w"], main["hit"]) == (65280, True)


def test_a_method_that_never_assigns_its_result_returns_the_default_value():
    """A METHOD's result is a variable like a FUNCTION's: not assigned, it keeps its
    type's default initial value (0 for INT, 3rd ed. table 10); `Next` assigns
    n * 10 after the two increments: 20."""
    text = ("FUNCTION_BLOCK Counter\nVAR n : INT; END_VAR\n"
            "METHOD Untouched : INT\nn := n + 1;\nEND_METHOD\n"
            "METHOD Next : INT\nn := n + 1;\nNext := n * 10;\nEND_METHOD\n"
            "END_FUNCTION_BLOCK\n" + program("    c : Counter; a, b : INT := -1;", "a := c.Untouched();\nb := c.Next();"))
    main = after_one_scan(text)
    assert (main["a"], main["b"]) == (0, 20)


def test_a_real_constant_beyond_real_is_refused_only_where_it_is_stored():
    """The literal typing rule (checker/expressions.py): a constant that does not fit is
    an error in an assignment, initial value or input argument (E-TYPE-005), not as an
    operand.  `r < 1.0E40` compares, stores nothing: accepted, and TRUE for r = 3.0E38."""
    text = program("    r : REAL := 3.0E38; b : BOOL;", "b := r < 1.0E40;")
    assert diagnostics(text) == []
    assert after_one_scan(text)["b"] is True


def test_a_global_of_a_prelude_structure_orders_the_types_as_a_full_check():
    """checker/prelude_base.py: a load that shares the checked prelude gives exactly the
    program of a full check, its tables in the same order.  A global AXIS_REF resolves
    that prelude TYPE before the others; its member types enter first, as resolving it
    does in the full check."""
    from test_prelude_sharing import _both_ways, _layout

    bases = importlib.import_module("st_runtime.checker.prelude_base")   # (the package exports its function)
    texts = {"g.st": "VAR_GLOBAL gax : AXIS_REF; END_VAR\n"
                     + program("    p : LREAL;", "p := gax.Cmd.Pos;")}
    kept = dict(bases._BASES)    # a base built afresh here, not one of an earlier load
    bases._BASES.clear()
    try:
        (shared, program_shared), (full, program_full) = _both_ways(texts, "iec")
    finally:
        bases._BASES.clear()
        bases._BASES.update(kept)
    assert shared == full == []
    assert _layout(program_shared) == _layout(program_full)


# ------------------------------------------------------------ seed 25: diagnostics, their words and places

def test_the_until_condition_is_named_in_its_diagnostic():
    text = program("    i : INT;", "REPEAT\n  i := i + 1;\nUNTIL i\nEND_REPEAT;")
    assert only(text) == ("E-TYPE-003", 7, 7, "UNTIL condition: expected BOOL, found INT")


def test_a_zero_step_is_reported_at_the_step():
    text = program("    i : INT;", "FOR i := 1 TO 5 BY 0 DO\nEND_FOR;")
    assert only(text) == ("E-TYPE-010", 5, 20, "FOR ... BY 0: the step must not be zero")


def test_a_case_label_of_a_wider_type_is_refused():
    """A DINT label cannot select an INT (DINT does not convert implicitly to INT)."""
    text = program("    i : INT;", "CASE i OF\n  DINT#5: i := 1;\nEND_CASE;")
    assert only(text) == ("E-TYPE-012", 6, 3, "CASE label: expected a constant of type INT, found DINT")


def test_nj_rule_007_gives_no_hint_for_a_label_without_a_value():
    text = program("    i, j : INT;", "CASE i OF\n  j: i := 1;\nEND_CASE;")
    assert diagnostics(text, "nj") == [
        ("E-TYPE-012", 6, 3, "CASE label: expected a constant of type INT, found a non-constant expression"),
        ("E-NJ-007", 6, 3, "CASE label 'j' is not an integer literal or an enumerator; "
                           "OMRON documents CASE labels as integer constants")]


def test_nj_rule_008_writes_a_false_initial_value_as_false():
    """NOT TRUE is FALSE, written as the ST literal FALSE."""
    assert only(program("    b : BOOL := NOT TRUE;", ""), "nj") == \
        ("E-NJ-008", 3, 17, "initial value of 'b': 'NOT TRUE' is not a literal; a variable table in "
                            "Sysmac Studio takes literals: write FALSE (* NOT TRUE *)")


def test_an_operator_function_has_no_output_to_read():
    assert only(program("    x, y : INT;", "x := ADD(1, 2, OUT => y);")) == \
        ("E-CALL-005", 5, 6, "ADD has no outputs: 'OUT' cannot be read with =>")


def test_lower_bound_with_one_argument_lacks_one():
    text = program("    a : ARRAY[1..3] OF INT; x : DINT;", "x := LOWER_BOUND(a);")
    assert only(text) == \
        ("E-CALL-009", 5, 6, "LOWER_BOUND: expected an array and a dimension number, found 1 argument(s)")


def test_ref_of_a_bit_is_refused_at_the_bit():
    text = program("    w : WORD; r : REF_TO BOOL;", "r := REF(w.%X3);")
    assert only(text) == ("E-TYPE-014", 5, 10, "REF(...): expected a variable, found a bit access")


def test_an_unknown_parameter_of_a_fixed_function_lists_its_parameters():
    """ABS is not extensible: its one parameter, no ', ...'."""
    assert only(program("    x : INT;", "x := ABS(Y := 1);")) == \
        ("E-CALL-002", 5, 10, "ABS has no parameter 'Y' (parameters: IN)")


def test_arguments_without_a_common_type_are_reported_at_the_second():
    assert only(program("    i : INT; t : TIME; x : INT;", "x := MAX(i, t);")) == \
        ("E-TYPE-002", 5, 13, "MAX: arguments of types INT and TIME have no common type")


def test_a_wildcard_address_read_in_code():
    """%I* (3rd ed. 6.5.5: a located variable to be placed later) has no place to read."""
    assert only(program("    x : BOOL;", "x := %I*;")) == \
        ("E-DECL-015", 5, 6, "%I*: %I* has no place in the process image to read")


def test_arrays_are_not_compared():
    text = program("    a, c : ARRAY[1..2] OF INT; b : BOOL;", "b := a < c;")
    assert only(text) == \
        ("E-TYPE-001", 5, 8, "<: expected elementary, string or enumeration operands, found ARRAY[1..2] OF INT")


def test_an_unknown_type_of_a_known_namespace():
    """NS exists: only the type is unknown (no "(no NAMESPACE NS)")."""
    text = "NAMESPACE NS\nTYPE T1 : INT; END_TYPE\nEND_NAMESPACE\n" + program("    x : NS.Unknown;", "")
    assert only(text) == ("E-DECL-004", 6, 9, "unknown type 'NS.Unknown'")


def test_a_variable_subrange_limit_is_named():
    assert only(program("    j : INT; s : INT(j..10);", "")) == \
        ("E-DECL-006", 3, 22, "subrange lower limit: expected a constant integer, found a non-constant expression")


def test_a_subrange_of_one_value():
    """3rd ed. 6.4.4.4: lower <= upper; INT(5..5) holds 5 alone."""
    text = program("    s : INT(5..5) := 5;", "")
    assert diagnostics(text) == []
    assert after_one_scan(text)["s"] == 5


# ------------------------------------------------------------ seed 25: enumeration values typed by the context

ENUMS = "TYPE Color : (Red, Blue); Light : (Red, Off); END_TYPE\n"


def test_an_ambiguous_enumeration_value_takes_the_type_of_the_assignment():
    """Red is a Color and a Light; assigned to a Color through SEL, it is Color's Red."""
    text = ENUMS + program("    c : Color := Blue; g : BOOL;", "c := SEL(g, Red, Blue);")
    assert diagnostics(text) == []
    assert after_one_scan(text)["c"] == "Red"


def test_an_undeclared_argument_is_the_one_error_of_a_call():
    """After an undeclared first argument, Red is still typed by the assignment's Color."""
    text = ENUMS + program("    c : Color;", "c := MAX(nothere, Red);")
    assert only(text) == ("E-DECL-001", 6, 10, "undeclared name 'nothere'")


def test_a_p_underscore_name_is_reserved_on_the_nj():
    """Names starting with P_ are the NJ's system-defined variables (P_On; W501 6-3-12)."""
    from st_runtime.checker.nj_rules import identifier_problems

    message = "identifier 'P_count' starts with 'P_', which the NJ reserves for system-defined variables"
    assert only(program("    P_count : INT;", ""), "nj") == ("E-NJ-005", 3, 5, message)
    # the rule itself, called afresh: a load asks it through an lru_cache, which mutmut's
    # forked test runs inherit filled from its first (unmutated) run
    assert identifier_problems("P_count") == [("005", message)]


def test_date_and_time_minus_time_is_a_date_and_time():
    """3rd ed. table 30, SUB_DT_TIME: DT - TIME is DT; 00:00:10 - 10 s = 00:00:00."""
    main = after_one_scan(program("    d : DT := DT#2024-01-01-00:00:10; e : DT;", "e := d - T#10s;"))
    assert main["e"] == "DT#2024-01-01-00:00:00"


# ------------------------------------------------------------ seed 25: a bug (references and subranges)

def test_a_reference_and_its_target_agree_on_a_subrange():
    """3rd ed. 6.4.4.10: a reference refers to a variable of its declared type, and a
    subrange's limits are part of that type (6.4.4.4: a value outside them is an
    error).  A REF_TO INT to an INT(1..5) would let `R^ := 100` write 100 into it; a
    REF_TO INT(1..5) to an INT would read 100 as a value of INT(1..5)."""
    into_subrange = program("    s : INT(1..5) := 1; r : REF_TO INT;", "r := REF(s);")
    assert only(into_subrange) == ("E-TYPE-004", 5, 6, "assignment: expected REF_TO INT, found REF_TO INT (1..5)")
    from_int = program("    i : INT; r : REF_TO INT(1..5);", "r := REF(i);")
    assert only(from_int) == ("E-TYPE-004", 5, 6, "assignment: expected REF_TO INT (1..5), found REF_TO INT")
    same = program("    s : INT(1..5) := 1; r : REF_TO INT(1..5); k : INT;", "r := REF(s);\nk := r^;")
    assert diagnostics(same) == []
    assert after_one_scan(same)["k"] == 1


# ------------------------------------------------------------ seed 25: calls

def test_a_function_block_type_is_not_called():
    text = "FUNCTION_BLOCK B\nEND_FUNCTION_BLOCK\n" + program("    x : INT;", "B();")
    assert only(text) == \
        ("E-CALL-001", 7, 1, "'B' is a FUNCTION_BLOCK type: declare an instance (inst : B;) and call the instance")


def test_a_namespaced_call_has_its_function_s_type():
    """checker/__init__.py: every expression node has a type in expr_types (the callee
    Name and an FB call statement excepted); NS.F(2) is F's INT, and 2 * 3 + 1 = 7."""
    from checker_helpers import body, checked, nodes
    from st_runtime import ast, types as T

    text = ("NAMESPACE NS\nFUNCTION F : INT\nVAR_INPUT a : INT; END_VAR\nF := a * 3;\nEND_FUNCTION\n"
            "END_NAMESPACE\n" + program("    x : INT;", "x := NS.F(2) + 1;"))
    checked_program = checked(text)
    (call,) = nodes(body(checked_program), ast.Call)
    assert checked_program.expr_types[id(call)] is T.INT
    assert after_one_scan(text)["x"] == 7


def test_a_type_is_not_called():
    text = "TYPE Speed : INT; END_TYPE\n" + program("    x : INT;", "x := Speed(5);")
    assert only(text) == ("E-CALL-001", 6, 6, "'Speed' is a type, not a function")


def test_greater_than_of_equal_constants_is_false():
    """3rd ed. 6.5.1.5: constant initial values; 2 > 2 is FALSE, 3 > 2 TRUE."""
    main = after_one_scan(program("    b : BOOL := 2 > 2; c : BOOL := 3 > 2;", ""))
    assert (main["b"], main["c"]) == (False, True)


# ------------------------------------------------------------ seed 25: declared types

def test_a_namespaced_function_is_not_a_type():
    text = "NAMESPACE NS\nFUNCTION Fn : INT\nFn := 1;\nEND_FUNCTION\nEND_NAMESPACE\n" + program("    x : NS.Fn;", "")
    assert only(text) == ("E-DECL-004", 8, 9, "'Fn' is a FUNCTION, not a type")


def test_a_pointer_is_named_a_pointer():
    """CODESYS's POINTER TO INT is shown as written, not as a REF_TO."""
    text = program("    i : INT; p : POINTER TO INT;", "p := i;")
    assert only(text, "codesys") == \
        ("E-TYPE-004", 5, 6, "assignment: expected POINTER TO INT, found INT; take a reference with REF(...)")


def test_a_function_block_that_holds_itself_has_no_size():
    """An FB that declares an instance of itself would be infinitely large (E-REC-001): its
    size, and so the memory limits, are not computed (checker/__init__.py: sizes need
    acyclic types), whatever else it holds (here 200,000,000 LREALs, 1.6 GB)."""
    text = ("FUNCTION_BLOCK A\nVAR inner : A; big : ARRAY[1..200000000] OF LREAL; END_VAR\nEND_FUNCTION_BLOCK\n"
            + program("    a : A;", ""))
    assert only(text) == \
        ("E-REC-001", 2, 5, "recursion: A declares an instance of A; IEC 61131-3 and OMRON NJ forbid recursion")
