"""Every diagnostic of the checker's declaration, statement, object, configuration,
memory, limit, chart, recursion, dialect and NJ-rule passes, each stated in full
(issue 16, docs/mutation.md, checker, session 12).

Fresh mutation samples of the checker stayed near 80 % for six sessions: what
survives is code that runs but whose result no test looks at in full, mostly the
words, code or place of a diagnostic that a test matched only in part, and a rule's
boundary tested on one side.  So this file is a table with one row per diagnostic
site of st_runtime/checker/{declarations, statements, stores, oo, configuration,
memory, limits, sfc, recursion, dialects, nj_rules, nj_build, context}.py (each
branch giving another code or message its own row): an ST snippet and the whole
list of what it gives, (code, line, column, message), compared with ==.  Lines and
columns are counted by hand in the snippet; the messages are each site's wording,
read for being right.  Each rule's boundary has a row on both sides (the value just
inside accepted, just outside refused), the ranges from IEC 61131-3 3rd ed. table 10
and the limits from docs/limits.md and OMRON's manuals (docs/nj501.md).

A positional note: the AST builder places an array or struct initializer
(`[1, 2]`, `(a := 1)`) at its first item, a binary operation at its operator
(`a + 1` at `+`); a diagnostic about the whole expression says start_pos where the
site asks for it (conditions, FOR parts, CASE labels, W-NJ-00x).
"""

from __future__ import annotations

import pytest

from checker_helpers import diagnostics, program as P

#: `program(...)` puts the declarations at line 3 and the body at line 5.


def rows(*items):
    """pytest params from (id, dialect, source, expected diagnostics)."""
    return [pytest.param(dialect, source, expected, id=name) for name, dialect, source, expected in items]


def check(dialect: str, source: str, expected: list) -> None:
    assert diagnostics(source, dialect) == expected


# ================================================================ declarations.py

CFG_POUS = "PROGRAM Ctrl\nEND_PROGRAM\nFUNCTION_BLOCK Fb\nEND_FUNCTION_BLOCK\n"


def config(*lines: str) -> str:
    """A CONFIGURATION C with RESOURCE R: `lines` at lines 3, 4, ..."""
    return ("CONFIGURATION C\n  RESOURCE R ON NJ501\n" + "".join(f"    {line}\n" for line in lines)
            + "  END_RESOURCE\nEND_CONFIGURATION\n" + CFG_POUS)


TASK = "TASK T1(INTERVAL := T#1ms, PRIORITY := 4);"

DECLARATIONS = rows(
    ("program_instance_of_a_function_block", "iec", config(TASK, "PROGRAM I1 WITH T1 : Fb;"),
     [("E-DECL-004", 4, 5, "program instance I1: expected a PROGRAM 'Fb', found a FUNCTION_BLOCK")]),
    ("program_instance_of_nothing", "iec", config(TASK, "PROGRAM I1 WITH T1 : Nope;"),
     [("E-DECL-004", 4, 5, "program instance I1: expected a PROGRAM 'Nope', found nothing of that name")]),
    ("program_instance_of_an_interface", "iec",
     "INTERFACE IRun\nEND_INTERFACE\n" + config(TASK, "PROGRAM I1 WITH T1 : IRun;"),
     [("E-DECL-004", 6, 5, "program instance I1: expected a PROGRAM 'IRun', found an INTERFACE")]),
    ("program_instance_undeclared_task", "iec",
     config(TASK, "TASK T2(INTERVAL := T#2ms, PRIORITY := 5);", "PROGRAM I1 WITH Fast : Ctrl;"),
     [("E-DECL-001", 5, 5, "program instance I1: undeclared task 'Fast' (tasks: T1, T2)")]),
    ("program_instance_task_and_no_tasks", "iec", config("PROGRAM I1 WITH Fast : Ctrl;"),
     [("E-DECL-001", 3, 5, "program instance I1: undeclared task 'Fast' (tasks: none)")]),
    ("program_instance_accepted", "iec", config(TASK, "PROGRAM I1 WITH t1 : ctrl;"), []),
    ("task_interval_not_a_time", "iec", config("TASK T1(INTERVAL := 5, PRIORITY := 4);"),
     [("E-TYPE-004", 3, 25,
       "INTERVAL of task T1: expected TIME, found SINT; convert explicitly with SINT_TO_TIME")]),
    ("task_priority_not_a_number", "iec", config("TASK T1(INTERVAL := T#1ms, PRIORITY := T#1s);"),
     [("E-TYPE-004", 3, 44,
       "PRIORITY of task T1: expected UINT, found TIME; convert explicitly with TIME_TO_UINT")]),
    ("a_standard_function_block_replaced", "iec",
     "FUNCTION_BLOCK TON\nVAR_INPUT IN : BOOL; PT : TIME; END_VAR\nVAR_OUTPUT Q : BOOL; ET : TIME; END_VAR\n"
     "END_FUNCTION_BLOCK\n",
     [("W-DECL-001", 1, 1, "'TON' replaces the built-in standard function block of that name in this project"),
      ("W-NJ-004", 1, 1, "identifier 'TON' is the name of an NJ instruction: choose another name")]),
    ("an_elementary_type_declared_again", "iec", "TYPE INT : DINT; END_TYPE\n",
     [("E-DECL-003", 1, 6, "'INT' is an elementary type name and cannot be declared again")]),
    ("a_standard_function_redefined", "iec", "FUNCTION Sqrt : REAL\nVAR_INPUT x : REAL; END_VAR\nSqrt := x;\nEND_FUNCTION\n",
     [("E-DECL-003", 1, 1, "'Sqrt' would redefine the standard function SQRT"),
      ("W-NJ-004", 1, 1, "identifier 'Sqrt' is the name of an NJ instruction: choose another name")]),
    ("a_type_and_a_pou_of_one_name", "iec", "TYPE Speed : INT; END_TYPE\nFUNCTION_BLOCK speed\nEND_FUNCTION_BLOCK\n",
     [("E-DECL-003", 2, 1, "duplicate declaration of 'speed': already declared at t.st:1:6")]),
    ("a_type_defined_in_terms_of_itself", "iec", "TYPE A : B; END_TYPE\nTYPE B : A; END_TYPE\n",
     [("E-DECL-005", 1, 6, "type A is defined in terms of itself")]),
    ("a_struct_member_twice", "iec", "TYPE S :\nSTRUCT\n    a : INT;\n    A : REAL;\nEND_STRUCT;\nEND_TYPE\n",
     [("E-DECL-002", 4, 5, "duplicate member 'A' in struct S")]),
    ("a_union_member_that_shares_no_bytes", "codesys",
     "TYPE U :\nUNION\n    a : INT;\n    s : STRING[4];\nEND_UNION;\nEND_TYPE\n",
     [("E-DECL-017", 4, 5, "UNION U: member 's' is STRING[4]; expected BOOL, an integer, a bit string or "
                           "a real (they share bytes)")]),
    ("a_union_of_each_kind_it_takes", "codesys",
     "TYPE U :\nUNION\n    b : BOOL;\n    i : LINT;\n    w : LWORD;\n    r : LREAL;\nEND_UNION;\nEND_TYPE\n", []),
    ("an_enumeration_value_not_an_integer", "iec", "TYPE E : (A := 1.5, B); END_TYPE\n",
     [("E-DECL-008", 1, 16, "value of 'A': expected a constant integer")]),
    ("an_enumeration_value_twice", "iec", "TYPE E : (Red, Green, red); END_TYPE\n",
     [("E-DECL-002", 1, 23, "duplicate value 'red' in enumeration E")]),
    ("a_function_as_a_type", "iec", "FUNCTION F : INT\nF := 1;\nEND_FUNCTION\n" + P("    x : F;", ""),
     [("E-DECL-004", 6, 9, "'F' is a FUNCTION, not a type")]),
    ("an_unknown_type_close_to_a_known_one", "iec", P("    x : DINTT;", ""),
     [("E-DECL-004", 3, 9, "unknown type 'DINTT' (did you mean DINT?)")]),
    ("an_unknown_type", "iec", P("    x : Motor;", ""),
     [("E-DECL-004", 3, 9, "unknown type 'Motor'")]),
    ("a_string_of_length_0_and_1", "iec", P("    s : STRING[0];\n    t : STRING[1];", ""),
     [("E-DECL-006", 3, 16, "string length: expected a positive integer, found 0")]),
    ("array_bounds_reversed_and_equal", "iec", P("    a : ARRAY[2..1] OF INT;\n    b : ARRAY[1..1] OF INT;", ""),
     [("E-DECL-006", 3, 15, "array bounds 2..1: expected the lower bound not above the upper bound")]),
    ("an_array_bound_not_constant", "iec", P("    n : INT;\n    a : ARRAY[0..n] OF INT;", ""),
     [("E-DECL-006", 4, 18, "array upper bound: expected a constant integer, found a non-constant expression")]),
    ("an_array_bound_not_an_integer", "iec", P("    a : ARRAY[1.5..2] OF INT;", ""),
     [("E-DECL-006", 3, 15, "array lower bound: expected a constant integer, found LREAL")]),
    ("a_type_of_an_unknown_namespace", "iec", P("    x : NoSpace.T;", ""),
     [("E-DECL-004", 3, 9, "unknown type 'NoSpace.T' (no NAMESPACE NoSpace)")]),
    ("a_type_its_namespace_lacks", "iec",
     "NAMESPACE Lib\nTYPE T : INT; END_TYPE\nEND_NAMESPACE\n" + P("    x : Lib.U;\n    y : Lib.T;", ""),
     [("E-DECL-004", 6, 9, "unknown type 'Lib.U'")]),
    ("a_subrange_of_a_real", "iec", P("    x : REAL(0..10);", ""),
     [("E-DECL-014", 3, 9, "subrange of 'REAL': expected an integer type (SINT ... ULINT) before the range")]),
    # IEC 61131-3 table 10: SINT -128..127, USINT 0..255, INT -32768..32767.
    ("subranges_at_their_bases_ends", "iec", P("    x : SINT(-128..127);\n    y : USINT(0..255);\n    z : INT(5..5);", ""),
     []),
    ("a_subrange_below_sint", "iec", P("    x : SINT(-129..0);", ""),
     [("E-DECL-014", 3, 14, "subrange -129..0 of SINT: expected -128 <= lower <= upper <= 127")]),
    ("a_subrange_above_sint", "iec", P("    x : SINT(0..128);", ""),
     [("E-DECL-014", 3, 14, "subrange 0..128 of SINT: expected -128 <= lower <= upper <= 127")]),
    ("a_subrange_below_usint", "iec", P("    x : USINT(-1..0);", ""),
     [("E-DECL-014", 3, 15, "subrange -1..0 of USINT: expected 0 <= lower <= upper <= 255")]),
    ("a_subrange_reversed", "iec", P("    x : INT(5..4);", ""),
     [("E-DECL-014", 3, 13, "subrange 5..4 of INT: expected -32768 <= lower <= upper <= 32767")]),
    ("a_variable_twice_in_a_pou", "iec", P("    x : INT;\n    X : REAL;", ""),
     [("E-DECL-002", 4, 5, "duplicate declaration of 'X' in POU Main (first declared at t.st:3:5)")]),
    ("a_global_twice", "iec", "VAR_GLOBAL\n    g : INT;\n    g : INT;\nEND_VAR\n",
     [("E-DECL-002", 3, 5, "duplicate declaration of 'g' in the global variables (first declared at t.st:2:5)")]),
    ("a_function_block_instance_in_a_function", "iec",
     "FUNCTION F : INT\nVAR t : TON; END_VAR\nF := 1;\nEND_FUNCTION\n",
     [("E-DECL-009", 2, 5, "FUNCTION F declares 't' of function block type TON: functions keep no state; "
                           "use a FUNCTION_BLOCK")]),
    ("a_function_returning_a_function_block", "iec", "FUNCTION F : TON\nEND_FUNCTION\n",
     [("E-DECL-009", 1, 14, "FUNCTION F returns function block type TON: expected a data type")]),
    ("an_open_array_outside_in_out", "iec",
     "FUNCTION F : INT\nVAR_INPUT a : ARRAY[*] OF INT; END_VAR\nF := 1;\nEND_FUNCTION\n",
     [("E-DECL-006", 2, 11, "'a' : ARRAY[*] OF INT: ARRAY[*] is only for a VAR_IN_OUT (the bounds come with "
                            "the argument)")]),
    ("an_abstract_function_block_instantiated", "iec",
     "FUNCTION_BLOCK ABSTRACT Shape\nEND_FUNCTION_BLOCK\n" + P("    s : Shape;", ""),
     [("E-DECL-016", 5, 5, "'s': Shape is ABSTRACT and cannot be instantiated (declare an FB that extends it)")]),
    ("an_edge_on_a_var", "iec", "FUNCTION_BLOCK Fb\nVAR x : BOOL R_EDGE; END_VAR\nEND_FUNCTION_BLOCK\n",
     [("E-DECL-013", 2, 5, "'x' is declared R_EDGE: expected a BOOL VAR_INPUT of a FUNCTION_BLOCK or PROGRAM, "
                           "found a BOOL VAR")]),
    ("an_edge_on_a_function_input", "iec",
     "FUNCTION F : INT\nVAR_INPUT x : BOOL F_EDGE; END_VAR\nF := 1;\nEND_FUNCTION\n",
     [("E-DECL-013", 2, 11, "'x' is declared F_EDGE: expected a BOOL VAR_INPUT of a FUNCTION_BLOCK or "
                            "PROGRAM, found a BOOL VAR_INPUT of FUNCTION F")]),
    ("an_edge_on_an_int_input", "iec", "FUNCTION_BLOCK Fb\nVAR_INPUT x : INT R_EDGE; END_VAR\nEND_FUNCTION_BLOCK\n",
     [("E-DECL-013", 2, 11, "'x' is declared R_EDGE: expected a BOOL VAR_INPUT of a FUNCTION_BLOCK or "
                            "PROGRAM, found an INT VAR_INPUT")]),
    ("edges_where_they_belong", "iec",
     "FUNCTION_BLOCK Fb\nVAR_INPUT x : BOOL R_EDGE; END_VAR\nEND_FUNCTION_BLOCK\n"
     "PROGRAM Main\nVAR_INPUT y : BOOL F_EDGE; END_VAR\nEND_PROGRAM\n", []),
    ("an_external_without_its_global", "iec", "PROGRAM Main\nVAR_EXTERNAL g : INT; END_VAR\nEND_PROGRAM\n",
     [("E-DECL-010", 2, 14, "VAR_EXTERNAL 'g': expected a VAR_GLOBAL of that name, found none")]),
    ("an_external_of_another_type", "iec",
     "VAR_GLOBAL g : INT; END_VAR\nPROGRAM Main\nVAR_EXTERNAL g : DINT; END_VAR\nEND_PROGRAM\n",
     [("E-DECL-010", 3, 14, "VAR_EXTERNAL 'g': declared DINT here, but the VAR_GLOBAL is INT")]),
    ("an_external_with_an_initial_value", "iec",
     "VAR_GLOBAL g : INT; END_VAR\nPROGRAM Main\nVAR_EXTERNAL g : INT := 3; END_VAR\nEND_PROGRAM\n",
     [("E-DECL-012", 3, 25, "VAR_EXTERNAL 'g' refers to a variable declared elsewhere: expected no initial "
                            "value, found one")]),
    ("an_in_out_with_an_initial_value", "iec",
     "FUNCTION_BLOCK Fb\nVAR_IN_OUT x : INT := 3; END_VAR\nEND_FUNCTION_BLOCK\n",
     [("E-DECL-012", 2, 23, "VAR_IN_OUT 'x' refers to a variable declared elsewhere: expected no initial "
                            "value, found one")]),
    # An FB instance in VAR CONSTANT needs no initial value (its own variables have theirs).
    ("a_constant_without_a_value", "iec", "PROGRAM Main\nVAR CONSTANT\n    k : INT;\n    t : TON;\nEND_VAR\nEND_PROGRAM\n",
     [("E-DECL-011", 3, 5, "CONSTANT 'k': expected an initial value, found none")]),
    ("a_bit_address_beyond_bit_7", "iec", P("    x AT %IX0.8 : BOOL;\n    y AT %IX0.7 : BOOL;", ""),
     [("E-DECL-015", 3, 5, "'x' AT %IX0.8: '%IX0.8': a bit address is <byte>.<bit> with bit 0..7")]),
    ("a_located_var_temp", "iec", "PROGRAM Main\nVAR_TEMP x AT %IW1 : INT; END_VAR\nEND_PROGRAM\n",
     [("E-DECL-015", 2, 10, "'x' AT %IW1: a VAR_TEMP cannot be located (VAR, VAR_GLOBAL, VAR_INPUT or "
                            "VAR_OUTPUT can)")]),
    ("a_located_variable_in_a_function", "iec", "FUNCTION F : INT\nVAR x AT %IW1 : INT; END_VAR\nF := 1;\nEND_FUNCTION\n",
     [("E-DECL-015", 2, 5, "'x' AT %IW1: a FUNCTION keeps no variables between calls and cannot have "
                           "located ones")]),
    ("a_full_address_in_a_function_block", "iec",
     "FUNCTION_BLOCK Fb\nVAR x AT %IW1 : INT; END_VAR\nEND_FUNCTION_BLOCK\n",
     [("E-DECL-015", 2, 5, "'x' AT %IW1: in a FUNCTION_BLOCK only %I*, %Q* or %M* (a place chosen by the "
                           "configuration), found a full address")]),
    ("a_star_address_in_a_function_block", "iec",
     "FUNCTION_BLOCK Fb\nVAR x AT %I* : INT; END_VAR\nEND_FUNCTION_BLOCK\n", []),
    ("a_word_address_of_a_dint", "iec", P("    x AT %IW1 : DINT;\n    y AT %IW2 : INT;", ""),
     [("E-DECL-015", 3, 5, "'x' AT %IW1: an address of size W holds 16 bit(s); expected a type of that "
                           "width, found DINT")]),
    ("an_unnamed_bit_address_of_an_int", "iec", P("    AT %IX1.1 : INT;", ""),
     [("E-DECL-015", 3, 8, "%IX1.1: an address of size X holds 1 bit(s); expected a type of that width, "
                           "found INT")]),
    ("an_unnamed_address_initialised", "iec", P("    AT %IW2 : INT := TRUE;", ""),
     [("E-TYPE-004", 3, 22, "initial value of %IW2: expected INT, found BOOL; convert explicitly with "
                            "BOOL_TO_INT")]),
    ("an_array_initializer_for_a_scalar", "iec", P("    x : INT := [1, 2];", ""),
     [("E-DECL-007", 3, 17, "initial value of 'x': expected a value of type INT, found an array initializer")]),
    ("one_element_too_many_and_just_enough", "iec",
     P("    a : ARRAY[0..2] OF INT := [1, 2, 3, 4];\n    b : ARRAY[0..2] OF INT := [1, 2, 3];", ""),
     [("E-DECL-007", 3, 32, "initial value of 'a': expected at most 3 element(s) for ARRAY[0..2] OF INT, "
                            "found 4")]),
    ("repeated_elements_one_too_many_and_just_enough", "iec",
     P("    a : ARRAY[0..2] OF INT := [2(7), 2(8)];\n    b : ARRAY[0..3] OF INT := [2(7), 2(8)];", ""),
     [("E-DECL-007", 3, 32, "initial value of 'a': expected at most 3 element(s) for ARRAY[0..2] OF INT, "
                            "found 4")]),
    ("a_struct_initializer_for_a_scalar", "iec", P("    x : INT := (a := 1);", ""),
     [("E-DECL-007", 3, 17, "initial value of 'x': expected a value of type INT, found a struct initializer")]),
    ("a_struct_initializer_of_an_unknown_member", "iec",
     "TYPE S : STRUCT a : INT; END_STRUCT; END_TYPE\n" + P("    s : S := (b := 1);", ""),
     [("E-DECL-007", 4, 15, "initial value of 's': S has no member 'b'")]),
    ("a_member_initialised_twice", "iec",
     "TYPE S : STRUCT a : INT; END_STRUCT; END_TYPE\n" + P("    s : S := (a := 1, A := 2);", ""),
     [("E-DECL-007", 4, 23, "initial value of 's': member 'A' is initialised twice")]),
    ("a_function_block_output_initialised", "iec", P("    t : TON := (Q := TRUE);\n    u : TON := (PT := T#1s);", ""),
     [("E-DECL-007", 3, 17, "initial value of 't': TON has no input 'Q'")]),
    ("an_initial_value_of_variables", "iec", P("    a : INT;\n    b : INT := a + 1;", ""),
     [("W-NJ-008", 4, 16, "initial value of 'b': 'a + 1' is not a literal; a variable table in Sysmac Studio "
                          "takes literals"),
      ("E-DECL-008", 4, 18, "initial value of 'b': expected a constant expression, found an expression that "
                            "depends on variables")]),
    ("a_type_initial_value", "iec", "TYPE T : INT := 2.5; END_TYPE\n",
     [("E-TYPE-004", 1, 17, "initial value of type T: expected INT, found LREAL; convert explicitly with "
                            "LREAL_TO_INT")]),
    ("a_member_initial_value", "iec", "TYPE S : STRUCT a : INT := TRUE; END_STRUCT; END_TYPE\n",
     [("E-TYPE-004", 1, 28, "initial value of member 'a': expected INT, found BOOL; convert explicitly with "
                            "BOOL_TO_INT")]),
)


@pytest.mark.parametrize("dialect, source, expected", DECLARATIONS)
def test_declarations(dialect, source, expected):
    check(dialect, source, expected)


# ================================================================ statements.py

STATEMENTS = rows(
    ("exit_outside_a_loop", "iec", P("    x : INT;", "EXIT;"),
     [("E-FLOW-001", 5, 1, "EXIT outside a loop: expected inside FOR, WHILE or REPEAT")]),
    ("continue_outside_a_loop", "iec", P("    x : INT;", "IF TRUE THEN\n    CONTINUE;\nEND_IF;"),
     [("E-FLOW-002", 6, 5, "CONTINUE outside a loop: expected inside FOR, WHILE or REPEAT")]),
    ("exit_and_continue_in_each_loop", "iec",
     P("    i : INT;", "FOR i := 1 TO 2 DO\n    EXIT;\nEND_FOR;\nWHILE TRUE DO\n    CONTINUE;\nEND_WHILE;\n"
                      "REPEAT\n    EXIT;\nUNTIL TRUE\nEND_REPEAT;"), []),
    ("exit_after_a_loop", "iec", P("    i : INT;", "FOR i := 1 TO 2 DO\nEND_FOR;\nEXIT;"),
     [("E-FLOW-001", 7, 1, "EXIT outside a loop: expected inside FOR, WHILE or REPEAT")]),
    ("an_if_condition", "iec", P("    x : INT;", "IF x THEN\n    x := 1;\nEND_IF;"),
     [("E-TYPE-003", 5, 4, "IF condition: expected BOOL, found INT")]),
    ("an_elsif_condition", "iec", P("    x : INT;", "IF FALSE THEN\n    x := 1;\nELSIF x + 1 THEN\n    x := 2;\nEND_IF;"),
     [("E-TYPE-003", 7, 7, "ELSIF condition: expected BOOL, found INT")]),
    ("a_while_condition", "iec", P("    x : INT;", "WHILE x DO\n    x := 1;\nEND_WHILE;"),
     [("E-TYPE-003", 5, 7, "WHILE condition: expected BOOL, found INT")]),
    ("an_until_condition", "iec", P("    x : INT;", "REPEAT\n    x := 1;\nUNTIL x\nEND_REPEAT;"),
     [("E-TYPE-003", 7, 7, "UNTIL condition: expected BOOL, found INT")]),
    ("a_for_variable_undeclared", "iec", P("    x : INT;", "FOR k := 1 TO 2 DO\n    x := 1;\nEND_FOR;"),
     [("E-DECL-001", 5, 1, "undeclared FOR control variable 'k'")]),
    ("a_for_variable_of_real", "iec", P("    r : REAL;", "FOR r := 1 TO 2 DO\nEND_FOR;"),
     [("E-TYPE-010", 5, 1, "FOR control variable 'r': expected an integer variable, found REAL")]),
    ("a_for_variable_constant", "iec", "PROGRAM Main\nVAR CONSTANT\n    k : INT := 1;\nEND_VAR\nFOR k := 1 TO 2 DO\nEND_FOR;\nEND_PROGRAM\n",
     [("E-ASSIGN-001", 5, 1, "FOR control variable 'k' is CONSTANT")]),
    ("a_for_variable_an_input", "iec", "FUNCTION_BLOCK Fb\nVAR_INPUT i : INT; END_VAR\nFOR i := 1 TO 2 DO\nEND_FOR;\nEND_FUNCTION_BLOCK\n",
     [("E-ASSIGN-002", 3, 1, "FOR control variable 'i' is a VAR_INPUT and read-only")]),
    ("a_for_variable_an_input_under_codesys", "codesys",
     "FUNCTION_BLOCK Fb\nVAR_INPUT i : INT; END_VAR\nFOR i := 1 TO 2 DO\nEND_FOR;\nEND_FUNCTION_BLOCK\n", []),
    ("a_for_start_real", "iec", P("    i : INT;", "FOR i := 1.5 TO 2 DO\nEND_FOR;"),
     [("E-TYPE-010", 5, 10, "FOR start value: expected an integer, found LREAL")]),
    ("a_for_end_real", "iec", P("    i : INT;", "FOR i := 1 TO 2.5 DO\nEND_FOR;"),
     [("E-TYPE-010", 5, 15, "FOR end value: expected an integer, found LREAL")]),
    ("a_for_step_real", "iec", P("    i : INT;", "FOR i := 1 TO 2 BY 0.5 DO\nEND_FOR;"),
     [("E-TYPE-010", 5, 20, "FOR BY value: expected an integer, found LREAL")]),
    ("a_for_start_wider", "iec", P("    i : INT;\n    d : DINT;", "FOR i := d TO 2 DO\nEND_FOR;"),
     [("E-TYPE-004", 6, 10, "FOR start value: expected INT, found DINT; convert explicitly with DINT_TO_INT")]),
    ("a_for_end_wider", "iec", P("    i : INT;\n    d : DINT;", "FOR i := 1 TO d DO\nEND_FOR;"),
     [("E-TYPE-004", 6, 15, "FOR end value: expected INT, found DINT; convert explicitly with DINT_TO_INT")]),
    ("a_for_step_wider", "iec", P("    i : INT;\n    d : DINT;", "FOR i := 1 TO 2 BY d DO\nEND_FOR;"),
     [("E-TYPE-004", 6, 20, "FOR BY value: expected INT, found DINT; convert explicitly with DINT_TO_INT")]),
    ("a_for_step_zero", "iec", P("    i : INT;", "FOR i := 1 TO 2 BY 0 DO\nEND_FOR;"),
     [("E-TYPE-010", 5, 20, "FOR ... BY 0: the step must not be zero")]),
    ("for_steps_next_to_zero", "iec", P("    i : INT;", "FOR i := 2 TO 1 BY -1 DO\nEND_FOR;\nFOR i := 1 TO 2 BY 1 DO\nEND_FOR;"), []),
    ("a_case_selector_real", "iec", P("    r : REAL;", "CASE r OF\n1: r := 1.0;\nEND_CASE;"),
     [("E-TYPE-011", 5, 6, "CASE selector: expected an integer, bit string or enumeration, found REAL")]),
    ("a_case_selector_of_each_kind_it_takes", "iec",
     "TYPE Color : (Red, Green); END_TYPE\n"
     + P("    i : INT;\n    w : WORD;\n    c : Color;",
         "CASE i OF\n1: i := 0;\nEND_CASE;\nCASE w OF\n16#01: i := 0;\nEND_CASE;\nCASE c OF\nRed: i := 0;\nEND_CASE;"), []),
    ("a_case_range_reversed", "iec", P("    x : INT;", "CASE x OF\n5..4: x := 1;\nEND_CASE;"),
     [("E-TYPE-012", 6, 1, "CASE range 5..4: expected the lower bound first")]),
    ("a_case_range_of_one_value", "iec", P("    x : INT;", "CASE x OF\n5..5: x := 1;\n6: x := 2;\n4: x := 3;\nEND_CASE;"), []),
    ("a_case_label_of_a_variable", "iec", P("    x : INT;\n    y : INT;", "CASE x OF\ny: x := 1;\nEND_CASE;"),
     [("E-TYPE-012", 7, 1, "CASE label: expected a constant of type INT, found a non-constant expression"),
      ("W-NJ-007", 7, 1, "CASE label 'y' is not an integer literal or an enumerator; OMRON documents CASE "
                         "labels as integer constants")]),
    ("a_case_label_bool", "iec", P("    x : INT;", "CASE x OF\nTRUE: x := 1;\nEND_CASE;"),
     [("E-TYPE-012", 6, 1, "CASE label: expected a constant of type INT, found BOOL"),
      ("W-NJ-007", 6, 1, "CASE label 'TRUE' is not an integer literal or an enumerator; OMRON documents "
                         "CASE labels as integer constants")]),
    ("a_case_label_real", "iec", P("    x : INT;", "CASE x OF\n1.5: x := 1;\nEND_CASE;"),
     [("E-TYPE-012", 6, 1, "CASE label: expected a constant of type INT, found LREAL"),
      ("W-NJ-007", 6, 1, "CASE label '1.5' is not an integer literal or an enumerator; OMRON documents "
                         "CASE labels as integer constants")]),
    ("a_case_label_of_another_enumeration", "iec",
     "TYPE Color : (Red, Green); END_TYPE\nTYPE Size : (Small, Large); END_TYPE\n"
     + P("    c : Color;", "CASE c OF\nSize#Small: c := Red;\nEND_CASE;"),
     [("E-TYPE-012", 8, 1, "CASE label: expected a value of Color, found Size")]),
    ("a_case_label_wider_than_the_selector", "iec", P("    x : SINT;\n    y : INT;", "CASE x OF\nINT#300: y := 1;\nEND_CASE;"),
     [("E-TYPE-012", 7, 1, "CASE label: expected a constant of type SINT, found INT")]),
    ("a_case_label_twice", "iec", P("    x : INT;", "CASE x OF\n1: x := 1;\n2, 1: x := 2;\nEND_CASE;"),
     [("E-TYPE-013", 7, 4, "CASE label 1 overlaps a label at line 6")]),
    ("case_ranges_sharing_an_end", "iec", P("    x : INT;", "CASE x OF\n1..5: x := 1;\n5..9: x := 2;\nEND_CASE;"),
     [("E-TYPE-013", 7, 1, "CASE label 5..9 overlaps a label at line 6")]),
    ("a_case_range_over_an_earlier_value", "iec", P("    x : INT;", "CASE x OF\n3: x := 1;\n1..5: x := 2;\nEND_CASE;"),
     [("E-TYPE-013", 7, 1, "CASE label 1..5 overlaps a label at line 6")]),
    # Fewer values in the range than single labels seen: the range's values are looked up one by one.
    ("a_short_case_range_over_earlier_values", "iec",
     P("    x : INT;", "CASE x OF\n1, 2, 7: x := 1;\n8..9: x := 2;\n6..7: x := 3;\nEND_CASE;"),
     [("E-TYPE-013", 8, 1, "CASE label 6..7 overlaps a label at line 6")]),
    ("a_case_value_inside_an_earlier_range", "iec", P("    x : INT;", "CASE x OF\n1..5: x := 1;\n0, 6, 5: x := 2;\nEND_CASE;"),
     [("E-TYPE-013", 7, 7, "CASE label 5 overlaps a label at line 6")]),
    ("case_labels_next_to_each_other", "iec",
     P("    x : INT;", "CASE x OF\n1..4: x := 1;\n5..9: x := 2;\n0: x := 3;\n10: x := 4;\nEND_CASE;"), []),
)


@pytest.mark.parametrize("dialect, source, expected", STATEMENTS)
def test_statements(dialect, source, expected):
    check(dialect, source, expected)
