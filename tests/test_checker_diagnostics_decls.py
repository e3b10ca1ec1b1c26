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
and the limits from docs/limits.md and OMRON's manuals (docs/nj501.md).  Where the
checker's result is no diagnostic (an SFC lowering, a method's scope, OMRON's type
ranking, a prelude type's values), a program is run and its values are traced by hand.

A positional note: the AST builder places an array or struct initializer
(`[1, 2]`, `(a := 1)`) at its first item, a binary operation at its operator
(`a + 1` at `+`); a diagnostic about the whole expression says start_pos where the
site asks for it (conditions, FOR parts, CASE labels, W-NJ-00x).
"""

from __future__ import annotations

import pytest

from checker_helpers import diagnostics, program as P
from test_checker_mutants_third import after_one_scan

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
    # A variable of such a type: its initial value's look-up down the chain stops at the cycle;
    # the type is already reported, so the variable adds nothing.
    ("a_variable_of_a_type_defined_in_terms_of_itself", "iec",
     "TYPE A : B; END_TYPE\nTYPE B : A; END_TYPE\nPROGRAM Main\nVAR\n    x : A;\nEND_VAR\nEND_PROGRAM\n",
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
    ("limits_not_constant_integers", "iec", P("    n : INT;\n    x : INT(0..n);\n    y : INT(1.5..3);\n    s : STRING[n];", ""),
     [("E-DECL-006", 4, 16, "subrange upper limit: expected a constant integer, found a non-constant expression"),
      ("E-DECL-006", 5, 13, "subrange lower limit: expected a constant integer, found LREAL"),
      ("E-DECL-006", 6, 16, "string length: expected a constant integer, found a non-constant expression")]),
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
    ("an_edge_on_a_uint_input", "iec", "FUNCTION_BLOCK Fb\nVAR_INPUT x : UINT R_EDGE; END_VAR\nEND_FUNCTION_BLOCK\n",
     [("E-DECL-013", 2, 11, "'x' is declared R_EDGE: expected a BOOL VAR_INPUT of a FUNCTION_BLOCK or "
                            "PROGRAM, found a UINT VAR_INPUT")]),       # "a UINT": the U said as "you"
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
    # Unnamed, the star's place is a place only: no type recorded for an address it does not have yet.
    ("an_unnamed_star_address_in_a_function_block", "iec",
     "FUNCTION_BLOCK Fb\nVAR AT %I* : INT; END_VAR\nEND_FUNCTION_BLOCK\n", []),
    # Unnamed places follow the same rules as named ones (session 14, seed 29: `declare_14`).
    ("an_unnamed_located_place_in_a_function", "iec", "FUNCTION F : INT\nVAR AT %IW1 : INT; END_VAR\nF := 1;\nEND_FUNCTION\n",
     [("E-DECL-015", 2, 8, "%IW1: a FUNCTION keeps no variables between calls and cannot have located ones")]),
    ("an_unnamed_full_address_in_a_function_block", "iec",
     "FUNCTION_BLOCK Fb\nVAR AT %IW1 : INT; END_VAR\nEND_FUNCTION_BLOCK\n",
     [("E-DECL-015", 2, 8, "%IW1: in a FUNCTION_BLOCK only %I*, %Q* or %M* (a place chosen by the "
                           "configuration), found a full address")]),
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
      ("E-DECL-008", 4, 18, "initial value of 'b': expected a constant expression, found one that reads "
                            "variables or calls a function")]),
    # A call is not folded (SHL of constants included): it was said to 'depend on variables'.
    ("an_initial_value_of_a_call", "iec", P("    w : WORD := SHL(WORD#1, 2);", ""),
     [("E-DECL-008", 3, 17, "initial value of 'w': expected a constant expression, found one that reads "
                            "variables or calls a function"),
      ("W-NJ-008", 3, 17, "initial value of 'w': 'SHL(WORD#1, 2)' is not a literal; a variable table in Sysmac "
                          "Studio takes literals")]),
    ("a_type_initial_value", "iec", "TYPE T : INT := 2.5; END_TYPE\n",
     [("E-TYPE-004", 1, 17, "initial value of type T: expected INT, found LREAL; convert explicitly with "
                            "LREAL_TO_INT")]),
    ("a_member_initial_value", "iec", "TYPE S : STRUCT a : INT := TRUE; END_STRUCT; END_TYPE\n",
     [("E-TYPE-004", 1, 28, "initial value of member 'a': expected INT, found BOOL; convert explicitly with "
                            "BOOL_TO_INT")]),
)



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



# ================================================================ stores.py (what may be written)

FB_IO = "FUNCTION_BLOCK Fb\nVAR_INPUT i : INT; END_VAR\nVAR_OUTPUT o : INT; END_VAR\nVAR v : INT; END_VAR\nEND_FUNCTION_BLOCK\n"
IN_OUT_F = "FUNCTION F : INT\nVAR_IN_OUT x : INT; END_VAR\nF := x;\nEND_FUNCTION\n"

NJ_006 = ("{what} '{path}', a variable of a function block instance: Sysmac Studio refuses it at Build "
          "(\"Cannot use an element of array or a member of structure for the reference of function block "
          "instance variables\"); copy '{path}' whole into a local variable first")

STORES = rows(
    ("an_enumeration_value_written", "iec",
     "TYPE Color : (Red, Green); END_TYPE\n" + P("    c : Color;", "Red := c;"),
     [("E-TYPE-014", 6, 1, "assignment: 'Red' is an enumeration value, not a variable")]),
    ("a_constant_written", "iec", "PROGRAM Main\nVAR CONSTANT\n    k : INT := 1;\nEND_VAR\nk := 2;\nEND_PROGRAM\n",
     [("E-ASSIGN-001", 5, 1, "assignment: 'k' is CONSTANT and cannot be written")]),
    ("an_own_input_written", "iec", "FUNCTION_BLOCK Fb\nVAR_INPUT i : INT; END_VAR\ni := 2;\nEND_FUNCTION_BLOCK\n",
     [("E-ASSIGN-002", 3, 1, "assignment: 'i' is a VAR_INPUT of Fb and is read-only inside it "
                             "(--dialect codesys accepts writing it)")]),
    ("an_own_input_written_under_codesys", "codesys",
     "FUNCTION_BLOCK Fb\nVAR_INPUT i : INT; END_VAR\ni := 2;\nEND_FUNCTION_BLOCK\n", []),
    ("a_for_variable_written_in_its_loop", "iec", P("    i : INT;", "FOR i := 1 TO 2 DO\n    i := 3;\nEND_FOR;\ni := 4;"),
     [("E-ASSIGN-003", 6, 5, "assignment: 'i' is the control variable of an enclosing FOR loop")]),
    ("an_instances_output_written", "iec", FB_IO + P("    f : Fb;", "f.o := 1;\nf.i := 3;"),
     [("E-ASSIGN-004", 10, 1, "assignment: 'o' is a VAR_OUTPUT of function block Fb; only its inputs may be "
                              "written from outside")]),
    # Through an element or a member the written variable is still the instance's output;
    # an input's member may be written (W-NJ-006: the NJ refuses parts of instance variables).
    ("parts_of_an_instances_outputs_written", "iec",
     "TYPE S : STRUCT x : INT; END_STRUCT; END_TYPE\nFUNCTION_BLOCK Fb\n"
     "VAR_OUTPUT a : ARRAY[0..2] OF INT; s : S; END_VAR\nVAR_INPUT i : S; END_VAR\nEND_FUNCTION_BLOCK\n"
     + P("    m : Fb;", "m.a[1] := 5;\nm.s.x := 6;\nm.i.x := 7;"),
     [("E-ASSIGN-004", 10, 1, "assignment: 'a' is a VAR_OUTPUT of function block Fb; only its inputs may be "
                              "written from outside"),
      ("W-NJ-006", 10, 1, NJ_006.format(what="an element of", path="m.a")),
      ("E-ASSIGN-004", 11, 1, "assignment: 's' is a VAR_OUTPUT of function block Fb; only its inputs may be "
                              "written from outside"),
      ("W-NJ-006", 11, 1, NJ_006.format(what="a member of", path="m.s")),
      ("W-NJ-006", 12, 1, NJ_006.format(what="a member of", path="m.i"))]),
    ("a_set_of_an_int", "codesys", P("    x : INT;\n    b : BOOL;", "x S= b;"),
     [("E-TYPE-004", 6, 1, "S=: expected INT, found BOOL; convert explicitly with BOOL_TO_INT")]),
    ("a_property_without_set_written", "codesys",
     "FUNCTION_BLOCK Fb\nVAR n : INT; END_VAR\nPROPERTY P : INT\nGET\nP := n;\nEND_GET\nEND_PROPERTY\nEND_FUNCTION_BLOCK\n"
     + P("    f : Fb;\n    k : INT;", "f.P := 1;\nk := f.P;"),
     [("E-ASSIGN-004", 14, 1, "assignment: property 'P' has no SET")]),
    # REF takes a variable (3rd ed. 6.6.1.7); each kind of literal, a call, an expression (at its operator).
    ("ref_of_what_is_no_variable", "iec",
     "TYPE Color : (Red, Green); END_TYPE\n"
     + P("    x : INT;\n    r : REF_TO INT;",
         "r := REF(1);\nr := REF(1.5);\nr := REF(TRUE);\nr := REF('s');\nr := REF(T#1s);\nr := REF(DT#2020-01-01-00:00:00);\n"
         "r := REF(Color#Red);\nr := REF(ABS(x));\nr := REF(x + 1);"),
     [("E-TYPE-014", 7, 10, "REF(...): expected a variable, found a literal"),
      ("E-TYPE-014", 8, 10, "REF(...): expected a variable, found a literal"),
      ("E-TYPE-014", 9, 10, "REF(...): expected a variable, found a literal"),
      ("E-TYPE-014", 10, 10, "REF(...): expected a variable, found a literal"),
      ("E-TYPE-014", 11, 10, "REF(...): expected a variable, found a literal"),
      ("E-TYPE-014", 12, 10, "REF(...): expected a variable, found a literal"),
      ("E-TYPE-014", 13, 10, "REF(...): expected a variable, found a literal"),
      ("E-TYPE-014", 14, 10, "REF(...): expected a variable, found a call"),
      ("E-TYPE-014", 15, 12, "REF(...): expected a variable, found an expression")]),
    ("a_read_write_access_path_of_a_constant", "iec",
     "PROGRAM Tank\nVAR CONSTANT Level : INT := 1; END_VAR\nVAR_ACCESS Fill : Level : INT READ_WRITE; END_VAR\nEND_PROGRAM\n",
     [("E-ASSIGN-001", 3, 19, "VAR_ACCESS Fill: 'Level' is CONSTANT and cannot be written")]),
    ("a_read_only_access_path_of_a_constant", "iec",
     "PROGRAM Tank\nVAR CONSTANT Level : INT := 1; END_VAR\nVAR_ACCESS Fill : Level : INT READ_ONLY; END_VAR\nEND_PROGRAM\n", []),
    ("a_constant_to_an_in_out", "iec",
     IN_OUT_F + "PROGRAM Main\nVAR CONSTANT\n    k : INT := 1;\nEND_VAR\nVAR\n    r : INT;\nEND_VAR\nr := F(x := k);\nEND_PROGRAM\n",
     [("E-CALL-007", 12, 13, "VAR_IN_OUT 'x' of F: expected a writable variable, found CONSTANT 'k'")]),
    ("an_own_input_to_an_in_out", "iec",
     IN_OUT_F + "FUNCTION_BLOCK Fb\nVAR_INPUT i : INT; END_VAR\nVAR r : INT; END_VAR\nr := F(x := i);\nEND_FUNCTION_BLOCK\n",
     [("E-CALL-007", 8, 13, "VAR_IN_OUT 'x' of F: expected a writable variable, found VAR_INPUT 'i' of Fb "
                            "(inputs are read-only inside their POU)")]),
    ("a_for_variable_to_an_in_out", "iec",
     IN_OUT_F + P("    i : INT;\n    r : INT;", "FOR i := 1 TO 2 DO\n    r := F(x := i);\nEND_FOR;\nr := F(x := i);"),
     [("E-CALL-007", 11, 17, "VAR_IN_OUT 'x' of F: expected a writable variable, found 'i', the control "
                             "variable of an enclosing FOR loop")]),
    ("an_instances_output_to_an_in_out", "iec",
     IN_OUT_F + FB_IO + P("    m : Fb;\n    r : INT;", "r := F(x := m.o);\nr := F(x := m.i);"),
     [("E-CALL-007", 15, 13, "VAR_IN_OUT 'x' of F: expected a writable variable, found 'o', a VAR_OUTPUT of "
                             "function block Fb (only its inputs may be written from outside)")]),
    ("a_bit_to_an_in_out", "nj",
     "FUNCTION F : INT\nVAR_IN_OUT x : BOOL; END_VAR\nF := 1;\nEND_FUNCTION\n" + P("    w : WORD;\n    r : INT;", "r := F(x := w.3);"),
     [("E-CALL-007", 10, 13, "VAR_IN_OUT 'x' of F: expected a variable, found a bit access")]),
)



# ================================================================ oo.py

I_RUN = "INTERFACE IRun\nMETHOD Run : BOOL\nEND_METHOD\nEND_INTERFACE\n"
RUN = "METHOD Run : BOOL\nRun := TRUE;\nEND_METHOD\n"

OBJECTS = rows(
    ("extends_nothing", "iec", "FUNCTION_BLOCK B EXTENDS Nope\nEND_FUNCTION_BLOCK\n",
     [("E-DECL-016", 1, 1, "EXTENDS 'Nope': expected a FUNCTION_BLOCK, found nothing of that name")]),
    ("extends_a_function", "iec", "FUNCTION F : INT\nF := 1;\nEND_FUNCTION\nFUNCTION_BLOCK B EXTENDS F\nEND_FUNCTION_BLOCK\n",
     [("E-DECL-016", 4, 1, "EXTENDS 'F': expected a FUNCTION_BLOCK, found a FUNCTION")]),
    ("extends_an_interface", "iec", "INTERFACE I\nEND_INTERFACE\nFUNCTION_BLOCK B EXTENDS I\nEND_FUNCTION_BLOCK\n",
     [("E-DECL-016", 3, 1, "EXTENDS 'I': expected a FUNCTION_BLOCK, found an INTERFACE")]),
    ("extends_two", "iec",
     "FUNCTION_BLOCK A\nEND_FUNCTION_BLOCK\nFUNCTION_BLOCK C\nEND_FUNCTION_BLOCK\nFUNCTION_BLOCK B EXTENDS A, C\nEND_FUNCTION_BLOCK\n",
     [("E-DECL-016", 5, 1, "FUNCTION_BLOCK B EXTENDS 2 function blocks: expected one (interfaces are IMPLEMENTed)")]),
    ("extends_itself_through_another", "iec",
     "FUNCTION_BLOCK A EXTENDS B\nEND_FUNCTION_BLOCK\nFUNCTION_BLOCK B EXTENDS A\nEND_FUNCTION_BLOCK\n",
     [("E-DECL-016", 1, 1, "FUNCTION_BLOCK A extends itself (through B)")]),
    ("extends_a_final_one", "iec", "FUNCTION_BLOCK FINAL A\nEND_FUNCTION_BLOCK\nFUNCTION_BLOCK B EXTENDS A\nEND_FUNCTION_BLOCK\n",
     [("E-DECL-016", 3, 1, "B EXTENDS A, which is FINAL")]),
    ("implements_a_function_block", "iec", "FUNCTION_BLOCK A\nEND_FUNCTION_BLOCK\nFUNCTION_BLOCK B IMPLEMENTS A\nEND_FUNCTION_BLOCK\n",
     [("E-DECL-016", 3, 1, "IMPLEMENTS 'A': expected an INTERFACE, found a FUNCTION_BLOCK")]),
    ("an_interface_extends_a_function_block", "iec", "FUNCTION_BLOCK A\nEND_FUNCTION_BLOCK\nINTERFACE I EXTENDS A\nEND_INTERFACE\n",
     [("E-DECL-016", 3, 1, "EXTENDS 'A': expected an INTERFACE, found a FUNCTION_BLOCK")]),
    ("a_method_named_like_a_variable", "iec", "FUNCTION_BLOCK A\nVAR Run : INT; END_VAR\n" + RUN + "END_FUNCTION_BLOCK\n",
     [("E-DECL-002", 3, 8, "method Run has the name of a variable of A")]),
    ("a_property_named_like_a_variable", "codesys",
     "FUNCTION_BLOCK A\nVAR Speed : INT; END_VAR\nPROPERTY Speed : INT\nGET\nSpeed := 1;\nEND_GET\nEND_PROPERTY\nEND_FUNCTION_BLOCK\n",
     [("E-DECL-002", 3, 10, "property Speed has the name of a variable of A")]),
    ("a_method_twice", "iec", "FUNCTION_BLOCK A\n" + RUN + "METHOD run : BOOL\nrun := FALSE;\nEND_METHOD\nEND_FUNCTION_BLOCK\n",
     [("E-DECL-002", 5, 8, "method run is declared twice in A")]),
    # After each refused method the FB's other methods are still declared: a.Stop() is found.
    ("methods_after_refused_ones", "iec",
     "FUNCTION_BLOCK A\nVAR n : INT; END_VAR\nMETHOD Run : INT\nRun := 1;\nEND_METHOD\nMETHOD run : INT\nrun := 2;\n"
     "END_METHOD\nMETHOD n : INT\nn := 3;\nEND_METHOD\nMETHOD Stop : INT\nStop := 4;\nEND_METHOD\nEND_FUNCTION_BLOCK\n"
     + P("    a : A;\n    k : INT;", "k := a.Stop();"),
     [("E-DECL-002", 6, 8, "method run is declared twice in A"),
      ("E-DECL-002", 9, 8, "method n has the name of a variable of A")]),
    ("a_final_method_overridden", "iec",
     "FUNCTION_BLOCK A\nMETHOD FINAL Run : BOOL\nRun := TRUE;\nEND_METHOD\nEND_FUNCTION_BLOCK\n"
     "FUNCTION_BLOCK B EXTENDS A\n" + RUN + "END_FUNCTION_BLOCK\n",
     [("E-DECL-016", 7, 8, "method Run overrides the FINAL method of A")]),
    ("a_method_overridden", "iec",
     "FUNCTION_BLOCK A\n" + RUN + "END_FUNCTION_BLOCK\nFUNCTION_BLOCK B EXTENDS A\n" + RUN + "END_FUNCTION_BLOCK\n", []),
    ("an_abstract_method_left_unimplemented", "iec",
     "FUNCTION_BLOCK ABSTRACT A\nMETHOD ABSTRACT Run : BOOL\nEND_METHOD\nEND_FUNCTION_BLOCK\n"
     "FUNCTION_BLOCK B EXTENDS A\nEND_FUNCTION_BLOCK\n",
     [("E-DECL-016", 5, 1, "B must implement the ABSTRACT method Run of A (or be ABSTRACT itself)")]),
    ("an_abstract_method_implemented", "iec",
     "FUNCTION_BLOCK ABSTRACT A\nMETHOD ABSTRACT Run : BOOL\nEND_METHOD\nEND_FUNCTION_BLOCK\n"
     "FUNCTION_BLOCK B EXTENDS A\n" + RUN + "END_FUNCTION_BLOCK\n", []),
    ("an_interface_method_missing", "iec", I_RUN + "FUNCTION_BLOCK B IMPLEMENTS IRun\nEND_FUNCTION_BLOCK\n",
     [("E-DECL-016", 5, 1, "B IMPLEMENTS IRun but has no method Run")]),
    ("an_interface_method_inherited", "iec",
     I_RUN + "FUNCTION_BLOCK A\n" + RUN + "END_FUNCTION_BLOCK\nFUNCTION_BLOCK B EXTENDS A IMPLEMENTS IRun\nEND_FUNCTION_BLOCK\n", []),
    ("a_base_interfaces_method_missing", "iec",
     I_RUN + "INTERFACE IStop EXTENDS IRun\nMETHOD Halt : BOOL\nEND_METHOD\nEND_INTERFACE\n"
     "FUNCTION_BLOCK B IMPLEMENTS IStop\nMETHOD Halt : BOOL\nHalt := TRUE;\nEND_METHOD\nEND_FUNCTION_BLOCK\n",
     [("E-DECL-016", 9, 1, "B IMPLEMENTS IStop but has no method Run")]),
    ("an_interface_implemented_by_the_base", "iec",
     I_RUN + "FUNCTION_BLOCK A IMPLEMENTS IRun\n" + RUN + "END_FUNCTION_BLOCK\nFUNCTION_BLOCK B EXTENDS A\nEND_FUNCTION_BLOCK\n", []),
    ("an_interface_of_an_abstract_base_left_to_the_derived", "iec",
     I_RUN + "FUNCTION_BLOCK ABSTRACT A IMPLEMENTS IRun\nEND_FUNCTION_BLOCK\nFUNCTION_BLOCK B EXTENDS A\nEND_FUNCTION_BLOCK\n",
     [("E-DECL-016", 7, 1, "B IMPLEMENTS IRun but has no method Run")]),
)



def test_an_abstract_method_of_a_concrete_function_block_is_one_diagnostic():
    """One root cause, one diagnostic: the method is refused where it is declared; the
    function block is not told as well to implement its own ABSTRACT method."""
    check("iec", "FUNCTION_BLOCK A\nMETHOD ABSTRACT Run : BOOL\nEND_METHOD\nEND_FUNCTION_BLOCK\n",
          [("E-DECL-016", 2, 17, "ABSTRACT method Run in A, which is not ABSTRACT")])


def test_a_base_interfaces_method_called_through_a_derived_interface():
    """3rd ed. 6.6.6: an interface that EXTENDS another has its methods; s.Run() through an
    IStop variable runs the instance's Run (7 and 8 by hand from the bodies)."""
    text = (I_RUN.replace("BOOL", "INT") + "INTERFACE IStop EXTENDS IRun\nMETHOD Halt : INT\nEND_METHOD\nEND_INTERFACE\n"
            "FUNCTION_BLOCK B IMPLEMENTS IStop\nMETHOD Run : INT\nRun := 7;\nEND_METHOD\n"
            "METHOD Halt : INT\nHalt := 8;\nEND_METHOD\nEND_FUNCTION_BLOCK\n"
            + P("    b : B;\n    s : IStop;\n    r : INT;\n    h : INT;", "s := b;\nr := s.Run();\nh := s.Halt();"))
    assert diagnostics(text) == []
    main = after_one_scan(text)
    assert (main["r"], main["h"]) == (7, 8)


def test_omron_ranks_signed_and_unsigned_of_one_size_as_the_unsigned():
    """W501 6-5-3 (data type ranking): of a signed and an unsigned integer of one size the
    unsigned one is the type of `a + b`, whichever side it is on; the NJ computes there.
    By hand: SINT -2 + USINT 1 = -1, as a USINT 255; INT -2 + UINT 1 = -1, as a UINT 65535."""
    text = P("    s : SINT := -2;\n    u : USINT := 1;\n    i : INT := -2;\n    w : UINT := 1;\n"
             "    x : INT;\n    y : INT;\n    z : DINT;", "x := s + u;\ny := u + s;\nz := i + w;")
    assert diagnostics(text, "nj") == []
    main = after_one_scan(text, "nj")
    assert (main["x"], main["y"], main["z"]) == (255, 255, 65535)


def test_a_methods_variables_see_their_function_blocks_constants():
    """A METHOD's declarations are checked in its FB's scope (3rd ed. 6.6.5.8): its initial
    values and array bounds may name the FB's constants.  By hand: y = K = 5 and
    UPPER_BOUND(a, 1) = K = 5, so M() = 10."""
    text = ("FUNCTION_BLOCK Fb\nVAR CONSTANT\n    K : INT := 5;\nEND_VAR\nMETHOD M : DINT\nVAR\n    y : DINT := K;\n"
            "    a : ARRAY[0..K] OF INT;\nEND_VAR\nM := y + UPPER_BOUND(a, 1);\nEND_METHOD\nEND_FUNCTION_BLOCK\n"
            + P("    f : Fb;\n    r : DINT;", "r := f.M();"))
    assert diagnostics(text) == []
    assert after_one_scan(text)["r"] == 10


def test_a_global_of_a_prelude_enumeration_takes_its_bare_values():
    """A global declared with a prelude TYPE enters that type (and its values) before the
    other prelude types; its values are then usable bare (motion's _eMC_DIRECTION).
    By hand: g starts as _mcNegativeDirection, so n = 1."""
    text = ("VAR_GLOBAL\n    g : _eMC_DIRECTION := _mcNegativeDirection;\nEND_VAR\n"
            + P("    n : INT;", "IF g = _mcNegativeDirection THEN\n    n := 1;\nEND_IF;\ng := _mcShortestWay;"))
    assert diagnostics(text) == []
    assert after_one_scan(text)["n"] == 1


# ================================================================ configuration.py

MAIN_IO = ("PROGRAM Main\nVAR_INPUT Start : BOOL; END_VAR\nVAR_OUTPUT Done : INT; END_VAR\n"
           "VAR Level : INT; END_VAR\nEND_PROGRAM\n")


def cell(*lines: str) -> str:
    """CONFIGURATION C with `lines` at lines 2, 3, ..., then PROGRAM Main."""
    return "CONFIGURATION C\n" + "".join(f"    {line}\n" for line in lines) + "END_CONFIGURATION\n" + MAIN_IO


CONFIGURATIONS = rows(
    ("a_positional_connection", "iec", cell("VAR_GLOBAL g : BOOL; END_VAR", "PROGRAM P1 : Main (g);"),
     [("E-CALL-002", 3, 24, "program instance P1: a connection names an input or output of Main "
                            "(In := %IX0.0, Out => %QX0.0)")]),
    ("a_connection_to_no_pin", "iec", cell("PROGRAM P1 : Main (Stop := TRUE);"),
     [("E-CALL-002", 2, 24, "connection P1.Stop: PROGRAM Main has no input or output 'Stop'")]),
    ("a_connection_to_a_local", "iec", cell("PROGRAM P1 : Main (Level := 1);"),
     [("E-CALL-002", 2, 24, "connection P1.Level: PROGRAM Main has no input or output 'Level'")]),
    ("an_output_connected_with_assign", "iec", cell("PROGRAM P1 : Main (Done := 1);"),
     [("E-CALL-005", 2, 24, "connection P1.Done: 'Done' is a VAR_OUTPUT: connect an input with :=, an "
                            "output with =>")]),
    ("an_input_connected_with_arrow", "iec", cell("VAR_GLOBAL g : BOOL; END_VAR", "PROGRAM P1 : Main (Start => g);"),
     [("E-CALL-005", 3, 24, "connection P1.Start: 'Start' is a VAR_INPUT: connect an input with :=, an "
                            "output with =>")]),
    ("an_input_connection_of_another_type", "iec", cell("PROGRAM P1 : Main (Start := 5);"),
     [("E-TYPE-004", 2, 33, "connection P1.Start: expected BOOL, found SINT; convert explicitly with SINT_TO_BOOL")]),
    ("an_output_connection_of_another_type", "iec", cell("VAR_GLOBAL g : BOOL; END_VAR", "PROGRAM P1 : Main (Done => g);"),
     [("E-TYPE-004", 3, 32, "connection P1.Done: expected BOOL, found INT; convert explicitly with INT_TO_BOOL")]),
    ("connections_accepted", "iec",
     cell("VAR_GLOBAL g : INT; b : BOOL; END_VAR", "PROGRAM P1 : Main (Start := b, Done => g);"), []),
    ("an_access_path_with_an_index", "iec",
     "CONFIGURATION C\n    PROGRAM P1 : Main;\n    VAR_ACCESS A1 : P1.Arr[1] : INT READ_ONLY; END_VAR\n"
     "END_CONFIGURATION\nPROGRAM Main\nVAR Arr : ARRAY[0..1] OF INT; END_VAR\nEND_PROGRAM\n",
     [("E-TYPE-014", 3, 21, "VAR_ACCESS A1: expected a path Resource.Program.Variable")]),
    ("an_access_path_of_another_type", "iec", cell("PROGRAM P1 : Main;", "VAR_ACCESS A1 : P1.Level : REAL READ_ONLY; END_VAR"),
     [("E-TYPE-004", 3, 16, "VAR_ACCESS A1: declared REAL, the variable is INT")]),
    ("an_access_path_of_no_instance", "iec", cell("PROGRAM P1 : Main;", "VAR_ACCESS A1 : P2.Level : INT READ_ONLY; END_VAR"),
     [("E-DECL-001", 3, 16, "VAR_ACCESS A1: the path names no program instance of C (instances: P1)")]),
    ("an_access_path_and_no_instances", "iec", cell("VAR_ACCESS A1 : P2.Level : INT READ_ONLY; END_VAR"),
     [("E-DECL-001", 2, 16, "VAR_ACCESS A1: the path names no program instance of C (instances: none)")]),
    ("an_access_path_of_no_variable", "iec", cell("PROGRAM P1 : Main;", "VAR_ACCESS A1 : P1.Nope : INT READ_ONLY; END_VAR"),
     [("E-DECL-001", 3, 16, "VAR_ACCESS A1: Main has no variable 'Nope'")]),
    ("access_paths_through_a_resource_and_a_struct", "iec",
     "TYPE S : STRUCT a : INT; END_STRUCT; END_TYPE\nCONFIGURATION C\n    PROGRAM P1 : Main;\n    VAR_ACCESS\n"
     "        A1 : P1.s.a : INT READ_ONLY;\n        A2 : P1.s.b : INT READ_ONLY;\n        A3 : R.P1.s.a : REAL READ_ONLY;\n"
     "    END_VAR\nEND_CONFIGURATION\nPROGRAM Main\nVAR s : S; END_VAR\nEND_PROGRAM\n",
     [("E-DECL-001", 6, 9, "VAR_ACCESS A2: s has no variable 'b'"),
      ("E-TYPE-004", 7, 9, "VAR_ACCESS A3: declared REAL, the variable is INT")]),
    ("an_access_path_accepted", "iec", cell("PROGRAM P1 : Main;", "VAR_ACCESS A1 : P1.Level : INT READ_ONLY; END_VAR"), []),
    ("a_var_config_of_another_type", "iec", cell("PROGRAM P1 : Main;", "VAR_CONFIG P1.Level : REAL := 1.0; END_VAR"),
     [("E-TYPE-004", 3, 16, "VAR_CONFIG P1.Level: declared REAL, the variable is INT")]),
    ("a_var_config_value_of_another_type", "iec", cell("PROGRAM P1 : Main;", "VAR_CONFIG P1.Level : INT := TRUE; END_VAR"),
     [("E-TYPE-004", 3, 34, "VAR_CONFIG P1.Level: expected INT, found BOOL; convert explicitly with BOOL_TO_INT")]),
    ("a_programs_access_path_of_another_type", "iec",
     "PROGRAM Tank\nVAR Level : INT; END_VAR\nVAR_ACCESS Fill : Level : REAL READ_ONLY; END_VAR\nEND_PROGRAM\n",
     [("E-TYPE-004", 3, 12, "VAR_ACCESS Fill: declared REAL, the variable is INT")]),
)



# ================================================================ memory.py
# docs/limits.md: 64 MiB = 67,108,864 bytes by default; an LREAL is 8 bytes, a BYTE 1.

HALF = "ARRAY[0..4194303] OF LREAL"     # 4,194,304 LREALs: 33,554,432 bytes, half the limit
# An FB whose one variable is a VAR_IN_OUT of 80,000,000 bytes, above the limit.
REF_FB = "FUNCTION_BLOCK Ref\nVAR_IN_OUT\n    big : ARRAY[0..9999999] OF LREAL;\nEND_VAR\nEND_FUNCTION_BLOCK\n"

MEMORY = rows(
    ("a_variable_at_the_limit", "iec", P("    a : ARRAY[0..8388607] OF LREAL;", ""), []),
    ("a_variable_8_bytes_over", "iec", P("    a : ARRAY[0..8388608] OF LREAL;", ""),
     [("E-LIMIT-008", 3, 5, "Main.a needs 67,108,872 bytes (ARRAY[0..8388608] OF LREAL), above the memory "
                           "limit of 67,108,864 bytes")]),
    ("a_global_8_bytes_over", "iec", "VAR_GLOBAL\n    g : ARRAY[0..8388608] OF LREAL;\nEND_VAR\n",
     [("E-LIMIT-008", 2, 5, "global g needs 67,108,872 bytes (ARRAY[0..8388608] OF LREAL), above the memory "
                           "limit of 67,108,864 bytes")]),
    ("an_instance_at_the_limit", "iec", f"FUNCTION_BLOCK Big\nVAR\n    a : {HALF};\n    b : {HALF};\nEND_VAR\nEND_FUNCTION_BLOCK\n", []),
    ("an_instance_a_byte_over", "iec",
     f"FUNCTION_BLOCK Big\nVAR\n    a : {HALF};\n    b : {HALF};\n    c : BYTE;\nEND_VAR\nEND_FUNCTION_BLOCK\n",
     [("E-LIMIT-009", 1, 1, "an instance of Big needs 67,108,865 bytes, above the memory limit of 67,108,864 bytes")]),
    ("the_project_at_the_limit", "iec",
     f"VAR_GLOBAL\n    g : {HALF};\nEND_VAR\nPROGRAM Main\nVAR\n    a : {HALF};\nEND_VAR\nEND_PROGRAM\n", []),
    # At the project's first POU, in its own file (it was the built-in TON's line 91).
    ("the_project_a_byte_over", "iec",
     f"VAR_GLOBAL\n    g : {HALF};\nEND_VAR\nPROGRAM Main\nVAR\n    a : {HALF};\n    c : BYTE;\nEND_VAR\nEND_PROGRAM\n",
     [("E-LIMIT-010", 4, 1, "the project's variables need 67,108,865 bytes (globals and one instance of each "
                           "PROGRAM), above the memory limit of 67,108,864 bytes")]),
    ("globals_alone_a_byte_over", "iec", f"VAR_GLOBAL\n    g : {HALF};\n    h : {HALF};\n    c : BYTE;\nEND_VAR\n",
     [("E-LIMIT-010", 2, 5, "the project's variables need 67,108,865 bytes (globals and one instance of each "
                           "PROGRAM), above the memory limit of 67,108,864 bytes")]),
    # A variable of an unknown type (refused) takes no room and no alignment: Big is a BYTE and
    # 67,108,863 BYTEs, the limit exactly, and an instance of it is within the limit.
    ("a_variable_of_an_unknown_type_takes_no_room", "iec",
     "FUNCTION_BLOCK Big\nVAR\n    b : BYTE;\n    u : Nope;\n    a : ARRAY[0..67108862] OF BYTE;\nEND_VAR\n"
     "END_FUNCTION_BLOCK\n" + P("    f : Big;", ""),
     [("E-DECL-004", 4, 9, "unknown type 'Nope'")]),
    # An FB's VAR_IN_OUT is a reference, 8 bytes (as a program's own in-out), whatever it refers to:
    # an instance of Ref is 8 bytes, with 67,108,856 BYTEs beside it the limit exactly (session 13).
    ("an_fb_instance_holds_its_in_out_as_a_reference", "iec",
     REF_FB + P("    f : Ref;\n    pad : ARRAY[0..67108855] OF BYTE;", ""), []),
    ("an_fb_instance_with_its_in_out_a_byte_over", "iec",
     REF_FB + P("    f : Ref;\n    pad : ARRAY[0..67108856] OF BYTE;", ""),
     [("E-LIMIT-009", 6, 1, "an instance of Main needs 67,108,865 bytes, above the memory limit of 67,108,864 bytes")]),
    # OMRON W501: STRING[n] reserves n bytes, the NULL included; 1986 the largest.
    ("the_nj_largest_string", "nj", P("    s : STRING[1986];", ""), []),
    ("an_nj_string_a_byte_over", "nj", P("    s : STRING[1987];\n    t : ARRAY[0..1] OF STRING[1987];", ""),
     [("E-LIMIT-011", 3, 5, "s: STRING[1987] is longer than the NJ's largest STRING, STRING[1986] (1,986 "
                           "bytes with the NULL)"),
      ("E-LIMIT-011", 4, 5, "t: STRING[1987] is longer than the NJ's largest STRING, STRING[1986] (1,986 "
                           "bytes with the NULL)")]),
    ("a_long_string_under_iec", "iec", P("    s : STRING[1987];", ""), []),
)



# ================================================================ limits.py (docs/limits.md)

def nested(opening: str, closing: str, n: int) -> str:
    return opening * n + "b := FALSE;\n" + closing * n


def elsifs(n: int) -> str:
    return "IF b THEN\nb := FALSE;\n" + "ELSIF b THEN\nb := FALSE;\n" * n + "END_IF;"


def clauses(n: int) -> str:
    return "CASE x OF\n" + "".join(f"{i}: x := 0;\n" for i in range(n)) + "END_CASE;"


def parenthesised(n: int) -> str:
    """`x := (((1 + 1) + 1) ...)`: n additions nested, the innermost's right operand at depth n + 1."""
    return "x := " + "(" * n + "1" + " + 1)" * n + ";"


LIMITS = rows(
    ("loops_12_deep", "iec", P("    b : BOOL;", nested("WHILE b DO\n", "END_WHILE;\n", 12)), []),
    ("loops_13_deep", "iec", P("    b : BOOL;", nested("WHILE b DO\n", "END_WHILE;\n", 13)),
     [("E-LIMIT-004", 17, 1, "loops nested more than 12 levels deep in Main")]),
    ("statements_40_deep", "iec", P("    b : BOOL;", nested("IF b THEN\n", "END_IF;\n", 40)), []),
    ("statements_41_deep", "iec", P("    b : BOOL;", nested("IF b THEN\n", "END_IF;\n", 41)),
     [("E-LIMIT-003", 45, 1, "statements nested more than 40 levels deep (IF here) in Main")]),
    # Each limit is reported once per POU, and the walk goes on past the first: both, in either order.
    ("loops_too_deep_then_statements_too_deep", "iec",
     P("    b : BOOL;", nested("WHILE b DO\n", "END_WHILE;\n", 13) + nested("IF b THEN\n", "END_IF;\n", 41)),
     [("E-LIMIT-004", 17, 1, "loops nested more than 12 levels deep in Main"),
      ("E-LIMIT-003", 72, 1, "statements nested more than 40 levels deep (IF here) in Main")]),
    ("statements_too_deep_then_loops_too_deep", "iec",
     P("    b : BOOL;", nested("IF b THEN\n", "END_IF;\n", 41) + nested("WHILE b DO\n", "END_WHILE;\n", 13)),
     [("E-LIMIT-003", 45, 1, "statements nested more than 40 levels deep (IF here) in Main"),
      ("E-LIMIT-004", 100, 1, "loops nested more than 12 levels deep in Main")]),
    ("elsif_150", "iec", P("    b : BOOL;", elsifs(150)), []),
    ("elsif_151", "iec", P("    b : BOOL;", elsifs(151)),
     [("E-LIMIT-005", 5, 1, "IF with 151 ELSIF branches (at most 150; a CASE takes many more) in Main")]),
    ("case_clauses_1500", "iec", P("    x : INT;", clauses(1500)), []),
    ("case_clauses_1501", "iec", P("    x : INT;", clauses(1501)),
     [("E-LIMIT-006", 5, 1, "CASE with 1501 clauses (at most 1500) in Main")]),
    ("an_expression_64_deep", "iec", P("    x : INT;", parenthesised(63)), []),
    # The innermost `1 + 1` is at column 70: 5 for `x := `, 64 for the brackets; its right operand at 74.
    ("an_expression_65_deep", "iec", P("    x : INT;", parenthesised(64)),
     [("E-LIMIT-002", 5, 74, "expression nested more than 64 levels deep (split it with intermediate "
                             "variables or types) in Main")]),
)



def test_too_many_statements_in_full(monkeypatch):
    """E-LIMIT-007 at the POU, with the count and the limit in its words; 100,000 statements
    take seconds to parse, so the limit is lowered to 3 here: 3 accepted, 4 refused."""
    from st_runtime.checker import limits
    monkeypatch.setattr(limits, "MAX_STATEMENTS", 3)
    assert diagnostics(P("    x : INT;", "x := 1;\nx := 2;\nx := 3;")) == []
    assert diagnostics(P("    x : INT;", "x := 1;\nx := 2;\nx := 3;\nx := 4;")) == \
        [("E-LIMIT-007", 1, 1, "4 statements (at most 3; split the POU) in Main")]


# ================================================================ sfc.py, recursion.py, dialects.py

CHARTS = rows(
    ("a_step_twice", "iec",
     "PROGRAM P\nVAR Go : BOOL; END_VAR\nINITIAL_STEP Idle:\nEND_STEP\nSTEP Run:\nEND_STEP\nSTEP run:\nEND_STEP\n"
     "TRANSITION FROM Idle TO Run := Go;\nEND_TRANSITION\nEND_PROGRAM\n",
     [("E-SFC-002", 7, 1, "step 'run' is declared twice in P")]),
    ("no_initial_step", "iec",
     "PROGRAM P\nVAR Go : BOOL; END_VAR\nSTEP Idle:\nEND_STEP\nSTEP Run:\nEND_STEP\n"
     "TRANSITION FROM Idle TO Run := Go;\nEND_TRANSITION\nEND_PROGRAM\n",
     [("E-SFC-002", 3, 1, "the chart of P has no INITIAL_STEP")]),
    ("a_transition_to_no_step", "iec",
     "PROGRAM P\nVAR Go : BOOL; END_VAR\nINITIAL_STEP Idle:\nEND_STEP\nTRANSITION FROM Idle TO Running := Go;\n"
     "END_TRANSITION\nEND_PROGRAM\n",
     [("E-SFC-002", 5, 1, "transition from Idle to Running: no step 'Running' in P")]),
    ("a_transition_between_steps_of_which_two_are_missing", "iec",
     "PROGRAM P\nVAR Go : BOOL; END_VAR\nINITIAL_STEP Idle:\nEND_STEP\nTRANSITION FROM (Idle, A) TO (B, Idle) := Go;\n"
     "END_TRANSITION\nEND_PROGRAM\n",
     [("E-SFC-002", 5, 1, "transition from Idle, A to B, Idle: no step 'A' in P"),
      ("E-SFC-002", 5, 1, "transition from Idle, A to B, Idle: no step 'B' in P")]),
    # The step type (__SFC_STEP) joins a program only with a chart: without one the name is free.
    ("the_step_types_name_in_a_program_without_a_chart", "iec", "TYPE __SFC_STEP : INT; END_TYPE\n",
     [("W-NJ-002", 1, 6, "identifier '__SFC_STEP' starts or ends with '_': not allowed on an OMRON NJ"),
      ("W-NJ-003", 1, 6, "identifier '__SFC_STEP' contains '__': not allowed on an OMRON NJ")]),
    ("a_function_calling_itself", "iec", "FUNCTION F : INT\nVAR_INPUT n : INT; END_VAR\nF := F(n - 1);\nEND_FUNCTION\n",
     [("E-REC-001", 3, 6, "recursion: F calls F; IEC 61131-3 and OMRON NJ forbid recursion")]),
    ("two_functions_calling_each_other", "iec", "FUNCTION F : INT\nF := G();\nEND_FUNCTION\nFUNCTION G : INT\nG := F();\nEND_FUNCTION\n",
     [("E-REC-001", 2, 6, "recursion: F calls G, G calls F; IEC 61131-3 and OMRON NJ forbid recursion")]),
    # Two paths to one function (a diamond, each caller calling on) are no cycle; a caller of two callers
    # is searched edge by edge (session 14, seed 29: `_components_27` looped forever on the second edge).
    ("a_diamond_of_calls", "iec",
     "FUNCTION Leaf : INT\nLeaf := 1;\nEND_FUNCTION\nFUNCTION B : INT\nB := Leaf();\nEND_FUNCTION\n"
     "FUNCTION C : INT\nC := Leaf();\nEND_FUNCTION\n" + P("    x : INT;", "x := B() + C();"), []),
    ("a_cycle_behind_a_diamond", "iec",
     "FUNCTION F : INT\nF := G();\nEND_FUNCTION\nFUNCTION G : INT\nG := F();\nEND_FUNCTION\n"
     "FUNCTION B : INT\nB := F();\nEND_FUNCTION\nFUNCTION C : INT\nC := F();\nEND_FUNCTION\n"
     + P("    x : INT;", "x := B() + C();"),
     [("E-REC-001", 2, 6, "recursion: F calls G, G calls F; IEC 61131-3 and OMRON NJ forbid recursion")]),
    ("two_function_blocks_holding_each_other", "iec",
     "FUNCTION_BLOCK A\nVAR b : B; END_VAR\nEND_FUNCTION_BLOCK\nFUNCTION_BLOCK B\nVAR a : A; END_VAR\nEND_FUNCTION_BLOCK\n",
     [("E-REC-001", 2, 5, "recursion: A declares an instance of B, B declares an instance of A; IEC 61131-3 "
                          "and OMRON NJ forbid recursion")]),
    # An FB held in a STRUCT, or in an array of them, is an instance as surely as a variable.
    ("a_function_block_holding_itself_in_an_array_of_structs", "iec",
     "TYPE Axis : STRUCT f : F; END_STRUCT; END_TYPE\nFUNCTION_BLOCK F\nVAR a : ARRAY[0..1] OF Axis; END_VAR\n"
     "END_FUNCTION_BLOCK\n",
     [("E-REC-001", 3, 5, "recursion: F declares an Axis holding an instance of F; IEC 61131-3 and OMRON NJ "
                          "forbid recursion")]),
    ("a_function_block_holding_itself_in_a_lower_case_struct", "iec",
     "TYPE engine : STRUCT f : F; END_STRUCT; END_TYPE\nFUNCTION_BLOCK F\nVAR e : engine; END_VAR\nEND_FUNCTION_BLOCK\n",
     [("E-REC-001", 3, 5, "recursion: F declares an engine holding an instance of F; IEC 61131-3 and OMRON NJ "
                          "forbid recursion")]),
    ("a_function_block_holding_itself_in_a_struct", "iec",
     "TYPE S : STRUCT f : F; END_STRUCT; END_TYPE\nFUNCTION_BLOCK F\nVAR s : S; END_VAR\nEND_FUNCTION_BLOCK\n",
     [("E-REC-001", 3, 5, "recursion: F declares a S holding an instance of F; IEC 61131-3 and OMRON NJ "
                          "forbid recursion")]),
    ("a_function_block_holding_an_array_of_itself", "iec",
     "FUNCTION_BLOCK F\nVAR a : ARRAY[0..1] OF F; END_VAR\nEND_FUNCTION_BLOCK\n",
     [("E-REC-001", 2, 5, "recursion: F declares an instance of F; IEC 61131-3 and OMRON NJ forbid recursion")]),
    ("a_construct_of_another_dialect_three_times", "iec", P("    w : WORD;\n    b : BOOL;", "b := w.1;\nb := w.2;\nb := w.3;"),
     [("E-DIALECT-001", 6, 6, "bit access x.3 is not accepted by --dialect iec; --dialect codesys or --dialect nj "
                              "accepts it (2 more use(s) in this file)")]),
    ("a_construct_of_another_dialect_once", "iec", P("    w : WORD;\n    b : BOOL;", "b := w.1;"),
     [("E-DIALECT-001", 6, 6, "bit access x.3 is not accepted by --dialect iec; --dialect codesys or --dialect nj "
                              "accepts it")]),
    # In two POUs of a file: reported at the first in the file (session 14, seed 29: `check_dialect_24`).
    ("a_construct_of_another_dialect_in_two_pous", "iec",
     "FUNCTION_BLOCK A\nVAR w : WORD; b : BOOL; END_VAR\nb := w.1;\nEND_FUNCTION_BLOCK\n"
     + P("    w : WORD;\n    b : BOOL;", "b := w.2;"),
     [("E-DIALECT-001", 3, 6, "bit access x.3 is not accepted by --dialect iec; --dialect codesys or --dialect nj "
                              "accepts it (1 more use(s) in this file)")]),
)



def reset_chart(association: str, scans_in_s1: int) -> list:
    """(step flag, Lamp) after each scan of S1 (`association` of Lamp, Go FALSE), then of S2
    (Lamp(R), listed after S1's association in the text) and S3 (nothing), Go TRUE."""
    from st_runtime.api import load_text
    text = ("PROGRAM Main\nVAR Go : BOOL; Lamp : BOOL; END_VAR\n"
            f"INITIAL_STEP S1:\n    Lamp({association});\nEND_STEP\nTRANSITION FROM S1 TO S2 := Go; END_TRANSITION\n"
            "STEP S2:\n    Lamp(R);\nEND_STEP\nTRANSITION FROM S2 TO S3 := Go; END_TRANSITION\n"
            "STEP S3:\nEND_STEP\nEND_PROGRAM\n")
    plc = load_text(text).controller(period="1ms")
    main = plc.add_program("Main")
    seen = []
    for step in ["S1"] * scans_in_s1 + ["S2", "S3"]:
        main["Go"] = step != "S1"
        plc.run(1)
        seen.append((main[f"{step}.X"], main["Lamp"]))
    assert plc.faults == []
    return seen


def test_a_reset_listed_after_a_stored_action_still_dominates():
    """IEC 61131-3 6.7.4.5: an action's control is reset-dominant whatever the order of its
    associations.  S2's R comes after S1's association in the text; on the scan S2 is active
    the stored flip-flop is cleared, so when S3 follows Lamp stays off.  By hand (1 ms scans):
    SL for 10 s sets Lamp at once; DS for 2 ms sets it when its timer is done, on scan 3
    (ET 0, 1, 2 ms); the reset clears either on S2's scan, and S3 leaves it FALSE."""
    assert reset_chart("SL, T#10s", 1) == [(True, True), (True, False), (True, False)]
    assert reset_chart("DS, T#2ms", 4) == [(True, False), (True, False), (True, True), (True, True),
                                           (True, False), (True, False)]


# ---------------------------------------------------------------- each construct in each dialect
# st_runtime/dialects.py CONSTRUCTS: who accepts what.  Each snippet uses one construct (two
# where one needs the other: a dereference needs a reference) at a place counted by hand; in
# the dialects that accept it, it checks clean.

def refused(line: int, col: int, what: str, dialect: str, accepted_by: str) -> tuple:
    return ("E-DIALECT-001", line, col, f"{what} is not accepted by --dialect {dialect}; {accepted_by} accepts it")


IEC_CODESYS = "--dialect codesys or --dialect iec"
CODESYS = "--dialect codesys"
IEC = "--dialect iec"
CODESYS_NJ = "--dialect codesys or --dialect nj"

# name: (source, {dialect: expected}); a dialect not named accepts the snippet.
CONSTRUCT_SNIPPETS = {
    "METHOD": ("FUNCTION_BLOCK A\nMETHOD Run : BOOL\nRun := TRUE;\nEND_METHOD\nEND_FUNCTION_BLOCK\n",
               {"nj": [refused(2, 8, "METHOD", "nj", IEC_CODESYS)]}),
    "INTERFACE": ("INTERFACE I\nEND_INTERFACE\n", {"nj": [refused(1, 1, "INTERFACE", "nj", IEC_CODESYS)]}),
    "EXTENDS": ("FUNCTION_BLOCK A\nEND_FUNCTION_BLOCK\nFUNCTION_BLOCK B EXTENDS A\nEND_FUNCTION_BLOCK\n",
                {"nj": [refused(3, 1, "EXTENDS", "nj", IEC_CODESYS)]}),
    "IMPLEMENTS": ("INTERFACE I\nEND_INTERFACE\nFUNCTION_BLOCK B IMPLEMENTS I\nEND_FUNCTION_BLOCK\n",
                   {"nj": [refused(1, 1, "INTERFACE", "nj", IEC_CODESYS),
                           refused(3, 1, "IMPLEMENTS", "nj", IEC_CODESYS)]}),
    "REF_TO": (P("    r : REF_TO INT;", ""), {"nj": [refused(3, 9, "REF_TO", "nj", IEC_CODESYS)]}),
    "DEREF_AND_NULL": ("FUNCTION F : INT\nVAR_INPUT r : REF_TO INT; END_VAR\nIF r <> NULL THEN\n    F := r^;\nEND_IF;\nEND_FUNCTION\n",
                       {"nj": [refused(2, 15, "REF_TO", "nj", IEC_CODESYS),
                               refused(3, 9, "NULL", "nj", IEC_CODESYS),
                               refused(4, 10, "the dereference ^", "nj", IEC_CODESYS)]}),   # at r: where r^ starts
    "POINTER": (P("    p : POINTER TO INT;", ""),
                {d: [refused(3, 9, "POINTER TO", d, CODESYS)] for d in ("iec", "nj")}),
    "ADR": (P("    x : INT;\n    p : POINTER TO INT;", "p := ADR(x);"),
            {d: [refused(4, 9, "POINTER TO", d, CODESYS), refused(6, 6, "ADR()", d, CODESYS)] for d in ("iec", "nj")}),
    "TRAILING_COMMA": (P("    x : INT;", "x := MAX(1, 2,);"),
                       {d: [refused(5, 6, "a comma after the last argument", d, CODESYS)] for d in ("iec", "nj")}),
    "UNION": ("TYPE U :\nUNION\n    a : INT;\n    b : WORD;\nEND_UNION;\nEND_TYPE\n",
              {"iec": [refused(2, 1, "UNION", "iec", CODESYS_NJ)]}),
    "PROPERTY": ("FUNCTION_BLOCK A\nVAR n : INT; END_VAR\nPROPERTY P : INT\nGET\nP := n;\nEND_GET\nEND_PROPERTY\nEND_FUNCTION_BLOCK\n",
                 {d: [refused(3, 10, "PROPERTY", d, CODESYS)] for d in ("iec", "nj")}),
    "ACTION": ("FUNCTION_BLOCK F\nACTION Reset:\nEND_ACTION\nEND_FUNCTION_BLOCK\n",
               {d: [refused(2, 8, "ACTION", d, CODESYS)] for d in ("iec", "nj")}),
    "NAMESPACE": ("NAMESPACE Lib\nTYPE T : INT; END_TYPE\nEND_NAMESPACE\n",
                  {d: [refused(2, 6, "NAMESPACE", d, IEC)] for d in ("nj", "codesys")}),
    "SET_RESET": (P("    b : BOOL;", "b S= TRUE;\nb R= FALSE;"),
                  {d: [("E-DIALECT-001", 5, 1, f"S= / R= is not accepted by --dialect {d}; --dialect codesys "
                                               "accepts it (1 more use(s) in this file)")] for d in ("iec", "nj")}),
    "SUPER_BODY": ("FUNCTION_BLOCK A\nEND_FUNCTION_BLOCK\nFUNCTION_BLOCK B EXTENDS A\nSUPER^();\nEND_FUNCTION_BLOCK\n",
                   {"iec": [refused(4, 1, "SUPER^() (the base FB's body)", "iec", CODESYS)],
                    # SUPER^() is no dereference the user wrote: refused as what it is, once.
                    "nj": [refused(3, 1, "EXTENDS", "nj", IEC_CODESYS),
                           refused(4, 1, "SUPER^() (the base FB's body)", "nj", CODESYS)]}),
    "SFC": ("PROGRAM P\nINITIAL_STEP S:\nEND_STEP\nEND_PROGRAM\n",
            {d: [refused(2, 1, "a Sequential Function Chart body (INITIAL_STEP, TRANSITION)", d, IEC)]
             for d in ("nj", "codesys")}),
    "EDGE_NAME": (P("    R_EDGE : BOOL;", ""),
                  {d: [refused(3, 5, "a variable named R_EDGE or F_EDGE (IEC 61131-3 keywords)", d, CODESYS)]
                   for d in ("iec", "nj")}),
    "ENUM_DOT": ("TYPE Color : (Red, Green); END_TYPE\n" + P("    c : Color;", "c := Color.Green;"),
                 {d: [refused(6, 6, "an enumeration value written Type.Value", d, CODESYS)] for d in ("iec", "nj")}),
    "BIT_ACCESS": (P("    w : WORD;\n    b : BOOL;", "b := w.3;\nb := w.%X3;"),
                   {"iec": [refused(6, 6, "bit access x.3", "iec", CODESYS_NJ)]}),
}

CONSTRUCTS = rows(*((f"{name}_under_{dialect}", dialect, source, refusals.get(dialect, []))
                    for name, (source, refusals) in CONSTRUCT_SNIPPETS.items()
                    for dialect in ("iec", "nj", "codesys")))


# ================================================================ nj_rules.py, nj_build.py
# OMRON NJ identifier rules (W501 6-3-12): warnings under iec, errors under nj.

NAMES = "    _x : INT;\n    y_ : INT;\n    a__b : INT;\n    p_on : INT;\n    Round : INT;\n    INT_TO_DINT : INT;"
FB_ARRAY = "FUNCTION_BLOCK Fb\nVAR_OUTPUT a : ARRAY[0..2] OF INT; END_VAR\nEND_FUNCTION_BLOCK\n"

NJ = rows(
    ("an_identifier_of_128_bytes_and_of_127", "iec", P(f"    {'a' * 128} : INT;\n    {'b' * 127} : INT;", ""),
     [("W-NJ-001", 3, 5, f"identifier '{'a' * 32}...' is 128 bytes long: expected at most 127 bytes (UTF-8) "
                         "on an OMRON NJ")]),
    ("identifiers_the_nj_refuses_warned", "iec", P(NAMES, ""),
     [("W-NJ-002", 3, 5, "identifier '_x' starts or ends with '_': not allowed on an OMRON NJ"),
      ("W-NJ-002", 4, 5, "identifier 'y_' starts or ends with '_': not allowed on an OMRON NJ"),
      ("W-NJ-003", 5, 5, "identifier 'a__b' contains '__': not allowed on an OMRON NJ"),
      ("W-NJ-005", 6, 5, "identifier 'p_on' starts with 'P_', which the NJ reserves for system-defined variables"),
      ("W-NJ-004", 7, 5, "identifier 'Round' is the name of an NJ instruction: choose another name"),
      ("W-NJ-004", 8, 5, "identifier 'INT_TO_DINT' is the name of an NJ instruction: choose another name")]),
    ("identifiers_the_nj_refuses", "nj", P("    _x : INT;\n    a__b : INT;\n    P_On : INT;\n    Round : INT;", ""),
     [("E-NJ-002", 3, 5, "identifier '_x' starts or ends with '_': not allowed on an OMRON NJ"),
      ("E-NJ-003", 4, 5, "identifier 'a__b' contains '__': not allowed on an OMRON NJ"),
      ("E-NJ-005", 5, 5, "identifier 'P_On' starts with 'P_', which the NJ reserves for system-defined variables"),
      ("E-NJ-004", 6, 5, "identifier 'Round' is the name of an NJ instruction: choose another name")]),
    ("identifiers_the_nj_takes", "nj", P("    x_y : INT;\n    Rounded : INT;\n    Pump : INT;", ""), []),
    ("an_element_of_an_instances_array", "iec", FB_ARRAY + P("    f : Fb;\n    x : INT;", "x := f.a[1];"),
     [("W-NJ-006", 9, 6, NJ_006.format(what="an element of", path="f.a"))]),
    ("a_case_label_of_a_constant_expression", "iec",
     "PROGRAM Main\nVAR CONSTANT\n    K : INT := 3;\nEND_VAR\nVAR\n    x : INT;\nEND_VAR\nCASE x OF\nK + 1: x := 0;\nEND_CASE;\nEND_PROGRAM\n",
     [("W-NJ-007", 9, 1, "CASE label 'K + 1' is not an integer literal or an enumerator; OMRON documents CASE "
                         "labels as integer constants: write 4 (* K + 1 *)")]),
    ("case_labels_of_enumerators", "iec",
     "TYPE Color : (Red, Green); END_TYPE\n" + P("    c : Color;", "CASE c OF\nRed: c := Green;\nColor#Green: c := Red;\nEND_CASE;"), []),
    ("initial_values_of_constant_expressions", "iec",
     P("    x : INT := 2 * 3;\n    r : REAL := 1.0 / 4.0;\n    a : ARRAY[0..1] OF INT := [1 + 1, 2];", ""),
     [("W-NJ-008", 3, 16, "initial value of 'x': '2 * 3' is not a literal; a variable table in Sysmac Studio "
                          "takes literals: write 6 (* 2 * 3 *)"),
      ("W-NJ-008", 4, 17, "initial value of 'r': '1.0 / 4.0' is not a literal; a variable table in Sysmac "
                          "Studio takes literals: write 0.25 (* 1.0 / 4.0 *)"),
      ("W-NJ-008", 5, 32, "initial value of 'a': '1 + 1' is not a literal; a variable table in Sysmac Studio "
                          "takes literals: write 2 (* 1 + 1 *)")]),
    # A signed literal is a literal (+5, -5); a signed constant's name is not (-K: write -3).
    ("signed_literals_and_a_signed_constant", "iec",
     "PROGRAM Main\nVAR CONSTANT\n    K : INT := 3;\nEND_VAR\nVAR\n    x : INT := +5;\n    y : INT := -5;\n"
     "    z : INT := -K;\nEND_VAR\nCASE x OF\n-1, +2: x := 0;\n-K: x := 1;\nEND_CASE;\nEND_PROGRAM\n",
     [("W-NJ-008", 8, 16, "initial value of 'z': '-K' is not a literal; a variable table in Sysmac Studio "
                          "takes literals: write -3 (* -K *)"),
      ("W-NJ-007", 12, 1, "CASE label '-K' is not an integer literal or an enumerator; OMRON documents CASE "
                          "labels as integer constants: write -3 (* -K *)")]),
    ("an_initial_value_of_a_constant_expression_under_nj", "nj", P("    x : INT := 2 * 3;", ""),
     [("E-NJ-008", 3, 16, "initial value of 'x': '2 * 3' is not a literal; a variable table in Sysmac Studio "
                          "takes literals: write 6 (* 2 * 3 *)")]),
)


# ================================================================ __init__.py: an exception in a pass

@pytest.mark.parametrize("error, expected", [
    (RecursionError(), ("E-LIMIT-001", "t.st", 1, 1, "the program is nested too deeply to be checked "
                                                      "(expressions or statements nested hundreds of levels)")),
    (ValueError("boom"), ("E-CHECK-999", "t.st", 1, 1, "internal checker error: ValueError: boom")),
])
def test_an_exception_in_a_pass_is_one_diagnostic_at_the_first_user_file(monkeypatch, error, expected):
    """Loaded as a user loads (the built-in prelude file first): the diagnostic is at the
    user's file, line 1, column 1, not in <builtin>."""
    import st_runtime.checker as checker
    from checker_helpers import load

    def failing(ctx):
        raise error

    monkeypatch.setattr(checker, "check_recursion", failing)
    result, _ = load("PROGRAM Main\nEND_PROGRAM\n")
    assert [(d.code, d.pos.file, d.pos.line, d.pos.col, d.message) for d in result.diagnostics] == [expected]


# ================================================================ the test

@pytest.mark.parametrize("dialect, source, expected",
                         DECLARATIONS + STATEMENTS + STORES + OBJECTS + CONFIGURATIONS + MEMORY + LIMITS + CHARTS + CONSTRUCTS + NJ)
def test_every_diagnostic_in_full(dialect, source, expected):
    check(dialect, source, expected)
