"""Checker rules that mutation testing found unchecked: survivors of the fresh
seed-24 sample (issue 16, docs/mutation.md, checker, session 9).

Each test states a rule of IEC 61131-3 (3rd ed. 2013) or of the checker's own
contract (every diagnostic has its registered code, its words and the position
of what it is about), with line and column counted by hand in the snippet and
values worked out by hand.
"""

from __future__ import annotations

from checker_helpers import diagnostics, only, program
from test_checker_mutants_third import after_one_scan


# ------------------------------------------------------------ constant folding

def test_xor_and_greater_or_equal_of_constants_are_constant_initial_values():
    """3rd ed. 6.5.1.5: an initial value is a constant expression.  16#06 XOR 16#03 = 16#05;
    TRUE XOR FALSE is TRUE; 3 >= 2 TRUE, 2 >= 3 FALSE, 2 >= 2 TRUE."""
    text = program("    x : WORD := WORD#16#06 XOR WORD#16#03; c : BOOL := TRUE XOR FALSE;\n"
                   "    b : BOOL := 3 >= 2; d : BOOL := 2 >= 3; e : BOOL := 2 >= 2;", "")
    main = after_one_scan(text)
    assert (main["x"], main["c"], main["b"], main["d"], main["e"]) == (5, True, True, False, True)


def test_not_of_a_bool_constant_folds():
    from st_runtime.checker.constfold import NOT_CONSTANT, apply_unary

    assert apply_unary("NOT", True) is False and apply_unary("NOT", False) is True
    assert apply_unary("NOT", 5) is NOT_CONSTANT      # bit strings: the caller masks ~value


def test_time_times_and_divided_by_a_number_fold_to_the_run_time_value():
    """TIME * ANY_NUM and TIME / ANY_NUM (3rd ed. table 30): T#10s * 2 = T#20s,
    T#10s / 5 = T#2s, T#10ns * 0.25 = 2.5 ns, rounded to even: T#2ns."""
    main = after_one_scan(program("    t, u, v : TIME;", "t := T#10s * 2;\nu := T#10s / 5;\nv := T#10ns * 0.25;"))
    assert (main["t"], main["u"], main["v"]) == ("T#20s", "T#2s", "T#2ns")


def test_mul_of_three_inputs_is_their_product():
    """MUL is extensible (3rd ed. table 29): MUL(2, 3, 4) = 24."""
    assert after_one_scan(program("    x : DINT;", "x := MUL(2, 3, 4);"))["x"] == 24


def test_the_time_operator_functions_name_their_operand_types():
    # The table of ADD_TIME & co. is built at import: its builder is called here afresh.
    from st_runtime.checker.operator_calls import OperatorFunction, _time

    assert _time("+", "TIME", "TIME", "TIME") == OperatorFunction("+", False, ("TIME", "TIME"), "TIME")


# ------------------------------------------------------------ diagnostics: words and positions

def test_a_conversion_with_the_wrong_number_of_arguments():
    assert only(program("    r : REAL;", "r := INT_TO_REAL(1, 2);")) == \
        ("E-CALL-006", 5, 6, "INT_TO_REAL: expected 1 argument, found 2")
    assert only(program("    r : REAL;", "r := INT_TO_REAL();")) == \
        ("E-CALL-009", 5, 6, "INT_TO_REAL: expected 1 argument, found 0")


def test_a_duplicate_declaration_names_where_the_first_one_is():
    """Even when the first one was an in-out given an initial value (E-DECL-012 first)."""
    text = "FUNCTION_BLOCK F\nVAR_IN_OUT\n  x : INT := 1;\nEND_VAR\nVAR\n  x : INT;\nEND_VAR\nEND_FUNCTION_BLOCK\n"
    assert diagnostics(text) == [
        ("E-DECL-012", 3, 14, "VAR_IN_OUT 'x' refers to a variable declared elsewhere: expected no "
                              "initial value, found one"),
        ("E-DECL-002", 6, 3, "duplicate declaration of 'x' in POU F (first declared at t.st:3:3)"),
    ]


def test_a_non_constant_subrange_limit_names_the_limit():
    assert only("PROGRAM Main\nVAR x : INT; s : INT (0..x); END_VAR\nEND_PROGRAM\n") == \
        ("E-DECL-006", 2, 26, "subrange upper limit: expected a constant integer, found a "
                              "non-constant expression")


def test_an_index_out_of_bounds_of_a_one_dimensional_array_names_no_dimension():
    assert only(program("    a : ARRAY[1..3] OF INT;", "a[4] := 0;")) == \
        ("E-TYPE-008", 5, 3, "index 4 is out of bounds 1..3")


def test_an_integer_literal_of_a_date_type_is_refused():
    assert only(program("    x : DINT;", "x := TOD#5;")) == \
        ("E-TYPE-004", 5, 6, "integer literal with prefix TIME_OF_DAY#: expected a numeric or "
                             "bit-string type, found TIME_OF_DAY")


def test_a_real_for_variable_is_reported_once():
    """The loop with a refused control variable is still checked, but that variable is no
    control variable: assigning it in the body is not E-ASSIGN-003 on top."""
    text = "PROGRAM Main\nVAR r : REAL; END_VAR\nFOR r := 1 TO 3 DO\n  r := 2.0;\nEND_FOR\nEND_PROGRAM\n"
    assert only(text) == ("E-TYPE-010", 3, 1, "FOR control variable 'r': expected an integer "
                                              "variable, found REAL")


def test_an_ambiguous_enumeration_value_lists_both_spellings():
    text = ("TYPE Color : (Red, Green); Light : (Red, Off); END_TYPE\n"
            + program("    x : INT;", "IF Red = Red THEN x := 1; END_IF;"))
    assert diagnostics(text)[0] == ("E-TYPE-015", 6, 4, "enumeration value 'Red' is ambiguous: "
                                                        "write Color#Red or Light#Red")


# ------------------------------------------------------------ object orientation

def test_a_function_block_that_extends_itself():
    assert only("FUNCTION_BLOCK A EXTENDS A\nEND_FUNCTION_BLOCK\n") == \
        ("E-DECL-016", 1, 1, "FUNCTION_BLOCK A extends itself (through A)")


def test_two_function_blocks_that_extend_each_other():
    """A EXTENDS B, B EXTENDS A: a cycle (3rd ed. 6.6.5: a base is another FB).  The checker
    looped for ever on it (the cycle closed while the base was being declared)."""
    text = "FUNCTION_BLOCK A EXTENDS B\nEND_FUNCTION_BLOCK\nFUNCTION_BLOCK B EXTENDS A\nEND_FUNCTION_BLOCK\n"
    assert only(text) == ("E-DECL-016", 1, 1, "FUNCTION_BLOCK A extends itself (through B)")


# ------------------------------------------------------------ configurations and charts

TANK = ("TYPE Pair : STRUCT A : INT; B : REAL; END_STRUCT; END_TYPE\n"
        "CONFIGURATION Plant\nRESOURCE Cpu ON PLC\nPROGRAM Tank1 : Tank;\nVAR_ACCESS\n"
        "  L : Cpu.Tank1.P.B : {type} READ_ONLY;\nEND_VAR\nEND_RESOURCE\nEND_CONFIGURATION\n"
        "PROGRAM Tank\nVAR\n  P : Pair;\nEND_VAR\nEND_PROGRAM\n")


def test_an_access_path_may_name_a_member_of_a_structure():
    assert diagnostics(TANK.format(type="REAL")) == []
    assert only(TANK.format(type="INT")) == ("E-TYPE-004", 6, 3, "VAR_ACCESS L: declared INT, "
                                                                 "the variable is REAL")


def test_an_action_no_step_uses_is_accepted():
    text = ("PROGRAM Filler\nVAR Count : INT; END_VAR\nINITIAL_STEP Idle:\nEND_STEP\n"
            "ACTION Unused:\n    Count := Count + 1;\nEND_ACTION\nEND_PROGRAM\n")
    assert diagnostics(text) == []


def test_a_file_has_at_most_100000_lines():
    from st_runtime.checker.limits import MAX_FILE_LINES, file_too_large

    assert MAX_FILE_LINES == 100_000
    assert file_too_large("\n" * 99_999) is None          # 100,000 lines
    assert file_too_large("\n" * 100_000) == \
        "100,001 lines: a source file has at most 100,000 (split it into several files)"
