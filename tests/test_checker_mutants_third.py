"""Checker rules that mutation testing found unchecked, third round (issue 16):
survivors of the fresh seed-19 sample and the last ones of seed 18.

Each test states a rule of IEC 61131-3 (2nd ed. 2003 or 3rd ed. 2013), of
OMRON's manuals (docs/nj501.md) or of the checker's own contract (its module
docstrings: every diagnostic has its registered code, its words and the
position of what it is about), with line and column counted by hand in the
snippet.
"""

from __future__ import annotations

from st_runtime.api import load_text
from checker_helpers import diagnostics, only, program
from test_prelude_sharing import _both_ways, _layout     # (shared and full check side by side)


def after_one_scan(text: str, dialect: str = "iec"):
    """The program Main of `text` after one scan (the text must check clean)."""
    plc = load_text(text, dialect=dialect).controller(period="1ms")
    main = plc.add_program("Main")
    plc.run(1)
    return main


# ------------------------------------------------------------ conditions and literals

def test_boolean_zero_and_one_are_conditions():
    """IEC 61131-3 2nd ed. table 4 (3rd ed. table 5), feature "Boolean zero
    and one": the literals 0 and 1 are BOOL literals, so `IF 1 THEN` is a
    BOOL condition (the checker reads a condition with the BOOL hint); 2 is
    no BOOL literal and is refused (E-TYPE-003 at the condition)."""
    main = after_one_scan(program("    x, y : INT;", "IF 1 THEN x := 5; END_IF;\nIF 0 THEN y := 7; END_IF;"))
    assert (main["x"], main["y"]) == (5, 0)
    code, line, col, message = only(program("    x : INT;", "IF 2 THEN x := 5; END_IF;"))
    assert (code, line, col) == ("E-TYPE-003", 5, 4) and "IF condition: expected BOOL" in message


def test_sqrt_of_an_untyped_literal_is_an_lreal():
    """An untyped literal given to an ANY_REAL input takes LREAL when nothing
    else fixes the type (3rd ed. 6.6.2.5.4, the literal is typed by its use)."""
    main = after_one_scan(program("    b : BOOL;\n    r : LREAL;", "b := SQRT(16) > 3.5;\nr := SQRT(2) * SQRT(2);"))
    assert main["b"] is True
    assert main["r"] == 2.0000000000000004        # sqrt(2)**2 in binary64, by hand: 2 + 2**-51


def test_max_takes_a_third_input_by_its_formal_name():
    """MAX is extensible (3rd ed. table 28): IN3 is its third input."""
    main = after_one_scan(program("    i : INT;", "i := MAX(IN1 := 1, IN2 := 5, IN3 := 9);"))
    assert main["i"] == 9


def test_enumeration_values_are_dint_constants():
    """An enumeration value given explicitly is a DINT constant (the
    checker's rule, after OMRON's enumerated types: values -2147483648 to
    2147483647): 3000000000 does not fit, 2.5 is no integer."""
    code, line, col, message = only("TYPE E : (A := 3000000000, B); END_TYPE\n")
    assert (code, line, col) == ("E-TYPE-005", 1, 16) and "does not fit DINT" in message
    code, line, col, message = only("TYPE E : (A := 2.5, B); END_TYPE\n")
    assert (code, line, col) == ("E-DECL-008", 1, 16)
    assert message == "value of 'A': expected a constant integer"


def test_division_by_zero_in_a_constant_expression():
    code, line, col, message = only(program("    x : DINT;", "x := 10 / 0;"))
    assert (code, line, col) == ("E-TYPE-017", 5, 9)      # at the operator
    assert message == "division by zero in a constant expression"


# ------------------------------------------------------------ configurations

TANK = ("CONFIGURATION Plant\nRESOURCE Cpu ON PLC\nPROGRAM Tank1 : Tank;\nVAR_ACCESS\n"
        "  L : {path} : {type} READ_ONLY;\nEND_VAR\nEND_RESOURCE\nEND_CONFIGURATION\n"
        "PROGRAM Tank\nVAR\n  Level : INT; Arr : ARRAY[1..2] OF INT;\nEND_VAR\nEND_PROGRAM\n")


def test_access_path_is_resource_program_variable():
    """3rd ed. 6.8.2 (table 62): an access path names Resource.Program.Variable;
    an indexed element is no such path (E-TYPE-014 at the path)."""
    code, line, col, message = only(TANK.format(path="Cpu.Tank1.Arr[1]", type="INT"))
    assert (code, line, col) == ("E-TYPE-014", 5, 7)
    assert message == "VAR_ACCESS L: expected a path Resource.Program.Variable"


def test_access_path_type_may_use_a_global_constant():
    """The declared type of an access path is resolved like any declared
    type: a bound that is a global constant (N = 2) gives ARRAY[1..2]."""
    text = "VAR_GLOBAL CONSTANT N : INT := 2; END_VAR\n" + TANK
    assert diagnostics(text.format(path="Cpu.Tank1.Arr", type="ARRAY[1..N] OF INT")) == []
    code, line, col, message = only(text.format(path="Cpu.Tank1.Arr", type="ARRAY[1..N+1] OF INT"))
    assert (code, line, col) == ("E-TYPE-004", 6, 3) and "ARRAY[1..3] OF INT" in message


def test_program_instance_of_something_that_is_no_program():
    text = ("CONFIGURATION C\nRESOURCE R ON PLC\nPROGRAM P1 : F;\nEND_RESOURCE\nEND_CONFIGURATION\n"
            "FUNCTION F : INT\nF := 1;\nEND_FUNCTION\n")
    code, line, col, message = only(text)
    assert (code, line, col) == ("E-DECL-004", 3, 1)
    assert message == "program instance P1: expected a PROGRAM 'F', found a FUNCTION"


# ------------------------------------------------------------ declarations

def test_unknown_type_suggests_the_closest_name():
    code, line, col, message = only(program("    x : INTT;", ""))
    assert (code, line, col) == ("E-DECL-004", 3, 9)
    assert message == "unknown type 'INTT' (did you mean INT?)"


def test_a_var_temp_cannot_be_located():
    """3rd ed. 6.5.5: AT is for VAR, VAR_GLOBAL, VAR_INPUT, VAR_OUTPUT."""
    code, line, col, message = only("PROGRAM Main\nVAR_TEMP x AT %IX0.0 : BOOL; END_VAR\nEND_PROGRAM\n")
    assert (code, line, col) == ("E-DECL-015", 2, 10) and "a VAR_TEMP cannot be located" in message


def test_for_variable_may_not_be_an_input():
    """3rd ed. 6.5.2.2: a VAR_INPUT is read-only inside its POU, so it cannot
    be a FOR control variable (E-ASSIGN-002 at the FOR)."""
    text = "FUNCTION_BLOCK F\nVAR_INPUT i : INT; END_VAR\nFOR i := 1 TO 3 DO\nEND_FOR;\nEND_FUNCTION_BLOCK\n"
    assert only(text) == ("E-ASSIGN-002", 3, 1, "FOR control variable 'i' is a VAR_INPUT and read-only")


def test_case_beyond_its_clause_limit_points_at_the_case():
    clauses = "".join(f"{i}: x := 1;\n" for i in range(1501))
    code, line, col, message = only(program("    x : INT;", f"CASE x OF\n{clauses}END_CASE;"))
    assert (code, line, col) == ("E-LIMIT-006", 5, 1) and "1501 clauses (at most 1500)" in message


def test_recursion_found_after_a_pou_that_is_in_no_cycle():
    """F1 calls F2 (no cycle) and comes first; A and B call each other
    (3rd ed. 6.6.1.2: no recursion): one E-REC-001 at A's call of B."""
    text = ("FUNCTION F2 : INT\nF2 := 1;\nEND_FUNCTION\nFUNCTION F1 : INT\nF1 := F2();\nEND_FUNCTION\n"
            "FUNCTION A : INT\nA := B();\nEND_FUNCTION\nFUNCTION B : INT\nB := A();\nEND_FUNCTION\n")
    code, line, col, message = only(text)
    assert (code, line, col) == ("E-REC-001", 8, 6) and "A calls B, B calls A" in message


# ------------------------------------------------------------ object orientation

def test_private_and_protected_methods_name_who_may_call_them():
    """3rd ed. 6.6.5.4: PRIVATE only inside the FB, PROTECTED also in FBs
    extending it."""
    fb = "FUNCTION_BLOCK A\nMETHOD {access} M\nEND_METHOD\nEND_FUNCTION_BLOCK\n"
    code, line, col, message = only(fb.format(access="PRIVATE") + program("    a : A;", "a.M();"))
    assert (code, line, col) == ("E-CALL-012", 9, 1)
    assert message == "method A.M is PRIVATE: it may be called only inside A"
    assert only(fb.format(access="PROTECTED") + program("    a : A;", "a.M();"))[3] == \
        "method A.M is PROTECTED: it may be called only inside A and the FBs extending it"


def test_final_and_abstract_rules():
    """3rd ed. 6.6.5.5-6: a FINAL FB is not extended; an FB extending an
    ABSTRACT one implements its ABSTRACT methods; an ABSTRACT method only in
    an ABSTRACT FB; EXTENDS names a FUNCTION_BLOCK."""
    assert only("FUNCTION_BLOCK FINAL A\nEND_FUNCTION_BLOCK\nFUNCTION_BLOCK B EXTENDS A\nEND_FUNCTION_BLOCK\n") \
        == ("E-DECL-016", 3, 1, "B EXTENDS A, which is FINAL")
    code, line, col, message = only("FUNCTION_BLOCK ABSTRACT A\nMETHOD ABSTRACT M\nEND_METHOD\n"
                                    "END_FUNCTION_BLOCK\nFUNCTION_BLOCK B EXTENDS A\nEND_FUNCTION_BLOCK\n")
    assert (code, line, col) == ("E-DECL-016", 5, 1) and "must implement the ABSTRACT method M of A" in message
    found = diagnostics("FUNCTION_BLOCK A\nMETHOD ABSTRACT M\nEND_METHOD\nEND_FUNCTION_BLOCK\n")
    assert ("E-DECL-016", 2, 17, "ABSTRACT method M in A, which is not ABSTRACT") in found
    assert {d[0] for d in found} == {"E-DECL-016"}
    assert only("FUNCTION F : INT\nF := 1;\nEND_FUNCTION\nFUNCTION_BLOCK B EXTENDS F\nEND_FUNCTION_BLOCK\n") \
        == ("E-DECL-016", 4, 1, "EXTENDS 'F': expected a FUNCTION_BLOCK, found a FUNCTION")


def test_an_interface_extends_an_interface():
    """3rd ed. 6.6.6.3: an INTERFACE may EXTEND others; an FB implementing it
    implements the methods of both (it is called through either)."""
    text = ("INTERFACE I\nMETHOD Size : INT\nEND_METHOD\nEND_INTERFACE\nINTERFACE J EXTENDS I\nEND_INTERFACE\n"
            "FUNCTION_BLOCK B IMPLEMENTS J\nMETHOD PUBLIC Size : INT\nSize := 42;\nEND_METHOD\nEND_FUNCTION_BLOCK\n"
            + program("    b : B;\n    j : J;\n    v : INT;", "j := b;\nv := j.Size();"))
    assert after_one_scan(text)["v"] == 42


# ------------------------------------------------------------ standard functions

def test_standard_function_output_message():
    code, line, col, message = only(program("    a, b, c : INT;", "c := MAX(IN1 := a, IN2 := b, OUT => c);"))
    assert (code, line, col) == ("E-CALL-005", 5, 30)
    assert message == "MAX has no outputs: 'OUT' cannot be read with =>"


def test_sel_selector_must_be_bool():
    """SEL's G is BOOL (3rd ed. table 28): 1 is a BOOL literal, 2 is not."""
    assert after_one_scan(program("    i : INT;", "i := SEL(1, 2, 3);"))["i"] == 3
    code, line, col, message = only(program("    i : INT;", "i := SEL(2, 2, 3);"))
    assert (code, line, col) == ("E-TYPE-004", 5, 10) and "argument G: expected BOOL" in message


def test_sel_selector_beyond_the_real_range_is_named_as_such():
    """A real literal beyond LREAL's range (IEC 60559 binary64) is refused as
    not fitting LREAL, wherever it stands, even where BOOL is expected."""
    code, line, col, message = only(program("    i : INT;", "i := SEL(1.0E400, 1, 2);"))
    assert (code, line, col) == ("E-TYPE-005", 5, 10) and "does not fit LREAL" in message


def test_division_by_a_typed_zero_constant():
    """Integer division by a constant 0 (3rd ed. 7.3.2: an error) is found by
    the checker, at the operator when both sides are constants, at the zero
    when only the divisor is."""
    found = only(program("    x : DINT;", "x := DINT#10 / DINT#0;"))
    assert found == ("E-TYPE-017", 5, 14, "division by zero in a constant expression")
    found = only(program("    x : DINT;", "x := x / DINT#0;"))
    assert found == ("E-TYPE-017", 5, 10, "division by zero in a constant expression")


def test_super_outside_a_function_block():
    """SUPER (3rd ed. 6.6.5.8) names the base of the FB it is used in."""
    found = diagnostics(program("    i : INT;", "SUPER.M();"))
    assert ("E-DECL-016", 5, 1, "SUPER.M: SUPER is only valid inside a FUNCTION_BLOCK or its methods") in found
    assert all(code.startswith("E-DECL-") for code, *_ in found)


def test_a_method_an_interface_does_not_have():
    code, line, col, _ = only("INTERFACE I\nEND_INTERFACE\n" + program("    j : I;", "j.Nope();"))
    assert (code, line, col) == ("E-TYPE-009", 7, 1)


def test_untyped_real_literal_takes_the_type_of_the_other_operand():
    """3rd ed. 6.6.2.5.4 (and the checker's module docstring): an untyped
    literal takes its type from the typed operand, so `1.5 * r` with r a
    REAL is a REAL and may be stored in a REAL without conversion."""
    main = after_one_scan(program("    x : REAL;\n    r : REAL := 2.0;", "x := 1.5 * r;"))
    assert main["x"] == 3.0


def test_namespaced_function_without_result_called_as_a_statement():
    """A function without a result type is called as a statement (3rd ed.
    6.6.1.2.2), also through its namespace (6.9: NS.F)."""
    text = ("NAMESPACE NS\nFUNCTION F\nVAR_INPUT i : INT; END_VAR\nEND_FUNCTION\nEND_NAMESPACE\n"
            + program("    x : INT;", "NS.F(1);"))
    assert diagnostics(text) == []


def test_expression_given_to_an_in_out_is_still_checked():
    """An expression given to a VAR_IN_OUT is refused (it is no variable,
    3rd ed. 6.6.1.2.2), and what is wrong inside it is reported as well."""
    text = ("FUNCTION_BLOCK B\nVAR_IN_OUT v : INT; END_VAR\nEND_FUNCTION_BLOCK\n"
            + program("    b : B; x : INT;", "b(v := x + TRUE);"))
    assert [d[:3] for d in diagnostics(text)] == [("E-CALL-007", 8, 8), ("E-TYPE-001", 8, 10)]


def test_an_enumerator_written_type_dot_value_is_a_literal_initial_value():
    """Sysmac Studio's variable table takes literals (docs/nj501.md, NJ rule
    008); CODESYS's `Light.Green` is an enumerator, a literal: no warning."""
    text = "TYPE Light : (Red, Green); END_TYPE\n" + program("    c : Light := Light.Green;", "")
    assert diagnostics(text, "codesys") == []


def test_struct_initializer_reports_every_wrong_member():
    """3rd ed. 6.4.4.5 (structure initialization): each member named once,
    each one a member, each value of its type; all three faults reported."""
    text = ("TYPE S : STRUCT x : INT; y : INT; END_STRUCT; END_TYPE\n"
            + program("    s : S := (q := 1, x := 1, x := 2, y := TRUE);", ""))
    assert [d[:3] for d in diagnostics(text)] == [("E-DECL-007", 4, 15), ("E-DECL-007", 4, 31),
                                                  ("E-TYPE-004", 4, 44)]


# ------------------------------------------------------------ seed-18 survivors left by round two

def test_multime_names_the_number_it_expects():
    """MULTIME (3rd ed. table 30: TIME * ANY_NUM) names the category wanted."""
    code, line, col, message = only(program("    t : TIME; b : BOOL;", "t := MULTIME(t, b);"))
    assert (code, line, col) == ("E-TYPE-004", 5, 17)
    assert message == "MULTIME: argument IN2: expected a number (ANY_NUM), found BOOL"


def test_upper_bound_takes_no_output():
    """UPPER_BOUND (3rd ed. 6.5.3) has the inputs ARR and DIM only: an
    output argument is no second input (E-CALL-006 at the call, 2 counted)."""
    code, line, col, message = only(program("    a : ARRAY[1..3] OF INT; i : DINT;", "i := UPPER_BOUND(a, X => i);"))
    assert (code, line, col) == ("E-CALL-006", 5, 6) and "found 2 argument(s)" in message


def test_enumeration_value_given_to_an_in_out_points_at_the_value():
    text = ("TYPE Light : (Red, Green); END_TYPE\nFUNCTION_BLOCK B\nVAR_IN_OUT v : Light; END_VAR\n"
            "END_FUNCTION_BLOCK\n" + program("    b : B;", "b(v := Red);"))
    code, line, col, message = only(text)
    assert (code, line, col) == ("E-CALL-007", 9, 8) and message.endswith("found an enumeration value")


CONNECT = ("CONFIGURATION Plant\nRESOURCE Cpu ON PLC\nTASK T(INTERVAL := T#1ms, PRIORITY := 1);\n"
           "PROGRAM P1 WITH T : Tank({args});\nEND_RESOURCE\nEND_CONFIGURATION\nVAR_GLOBAL G : INT; END_VAR\n"
           "PROGRAM Tank\nVAR_INPUT Level : INT; END_VAR\nVAR_OUTPUT Out : INT; END_VAR\nEND_PROGRAM\n")


def test_program_configuration_connects_inputs_with_values_and_outputs_with_variables():
    """3rd ed. 6.8.2 (table 62, PROGRAM ... WITH task : type (connections)):
    an input takes a value (:=), an output goes to a variable (=>)."""
    assert diagnostics(CONNECT.format(args="Level := 5, Out => G")) == []
    code, line, col, message = only(CONNECT.format(args="Level => G"))
    assert (code, line, col) == ("E-CALL-005", 4, 26) and "'Level' is a VAR_INPUT" in message


def test_access_path_in_a_configuration_without_programs():
    text = ("CONFIGURATION Plant\nRESOURCE Cpu ON PLC\nVAR_ACCESS\n  L : Cpu.Tank1.Level : INT READ_ONLY;\n"
            "END_VAR\nEND_RESOURCE\nEND_CONFIGURATION\n")
    assert only(text) == ("E-DECL-001", 4, 3, "VAR_ACCESS L: the path names no program instance of Plant "
                                              "(instances: none)")


def test_initial_value_of_a_type_names_the_type():
    code, line, col, message = only("TYPE T : INT := TRUE; END_TYPE\n")
    assert (code, line, col) == ("E-TYPE-004", 1, 17) and message.startswith("initial value of type T: expected INT")


def test_union_reports_every_wrong_member():
    """A UNION's members share bytes (OMRON NJ union: BOOL, integers, bit
    strings, reals: docs/nj501.md): a STRING member is refused, and the
    members after it are still checked."""
    found = diagnostics("TYPE U : UNION a : STRING; b : INT := TRUE; END_UNION; END_TYPE\n", "nj")
    assert [d[:3] for d in found] == [("E-DECL-017", 1, 16), ("E-TYPE-004", 1, 39)]


def test_nj_initial_value_hint_spells_true_in_upper_case():
    code, line, col, message = only(program("    b : BOOL := NOT FALSE;", ""))
    assert (code, line, col) == ("W-NJ-008", 3, 17) and message.endswith("write TRUE (* NOT FALSE *)")


def test_memory_limit_of_a_variable_is_inclusive():
    """checker/memory.py: a variable may need as many bytes as the limit,
    not one more (100000 BYTEs against limits 100000 and 99999)."""
    from st_runtime.loader import load_texts
    text = program("    a : ARRAY[1..100000] OF BYTE;", "")
    assert [d for d in load_texts({"t.st": text}, "iec", 100_000).diagnostics if d.code.startswith("E")] == []
    refused = [(d.code, d.pos.line, d.pos.col) for d in load_texts({"t.st": text}, "iec", 99_999).diagnostics
               if d.code.startswith("E") and d.pos.file == "t.st"]
    assert ("E-LIMIT-008", 3, 5) in refused
    # An instance of 100001 bytes whose variables are each within the limit is
    # itself above it: E-LIMIT-009 at the POU.
    text = program("    a : ARRAY[1..100000] OF BYTE;\n    b : BYTE;", "")
    found = [(d.code, d.pos.line, d.pos.col, d.message) for d in load_texts({"t.st": text}, "iec", 100_000).diagnostics
             if d.code.startswith("E") and d.pos.file == "t.st"]
    assert found == [("E-LIMIT-009", 1, 1, "an instance of Main needs 100,001 bytes, above the memory limit "
                                           "of 100,000 bytes")]


CHART = """PROGRAM Main
VAR Go : BOOL := TRUE; Lamp : BOOL; END_VAR
INITIAL_STEP Wait:
END_STEP
TRANSITION FROM Wait TO (A, B) := Go;
END_TRANSITION
STEP A:
    Lamp(N);
END_STEP
STEP B:
    {b}
END_STEP
TRANSITION FROM (A, B) TO Wait := FALSE;
END_TRANSITION
END_PROGRAM
"""


def test_reset_qualifier_overrides_a_non_stored_association():
    """IEC 61131-3 3rd ed. 6.7.4 (action control, figure 15): Q = (N OR S
    ...) AND NOT R: an action reset (R) by one active step is off even while
    another active step associates it with N.  A and B run side by side
    after the divergence; without B's R, A's N turns the lamp on."""
    for b, lamp in (("Lamp(R);", False), ("", True)):
        plc = load_text(CHART.format(b=b)).controller(period="1ms")
        main = plc.add_program("Main")
        plc.run(3)
        assert (main["A.X"], main["B.X"], main["Lamp"]) == (True, True, lamp), b


# ------------------------------------------------------------ the shared prelude, built afresh

SHARED_CASES = [
    ("TYPE Light : (Red, Green); END_TYPE\nTYPE Pair : STRUCT a : Light; t : TON; END_STRUCT; END_TYPE\n"
     + program("    p : Pair; c : Light := Green; t : TON;", "t(IN := c = Red, PT := T#1ms);"), None),
    ("PROGRAM MAIN VAR t : TON; p : MC_Power; a : AXIS_REF; s : STRING[10]; END_VAR END_PROGRAM", 16),
    ("PROGRAM MAIN VAR t : TON; p : MC_Power; a : AXIS_REF; s : STRING[10]; END_VAR END_PROGRAM", 40),
]


def test_a_prelude_built_afresh_checks_like_a_full_check(monkeypatch):
    """The shared prelude is built once per process; here it is built again
    for each case (an empty cache), so a changed builder is seen."""
    import importlib
    prelude_base = importlib.import_module("st_runtime.checker.prelude_base")   # (the package exports a function of that name)
    for text, limit in SHARED_CASES:
        for dialect in ("iec", "nj"):
            monkeypatch.setattr(prelude_base, "_BASES", {})
            (shared, program), (full, again) = _both_ways({"m.st": text}, dialect, limit)
            assert shared == full, (text, dialect, limit)
            if program is not None:
                assert _layout(program) == _layout(again)


def test_a_property_named_like_a_variable_of_its_fb_is_refused():
    # `fb.x` would name both; the same rule as for a METHOD (seed-19 survivor `_Member`).
    text = ("FUNCTION_BLOCK FB\nVAR x : INT; END_VAR\n"
            "PROPERTY x : INT\nGET\nx := 2;\nEND_GET\nEND_PROPERTY\nEND_FUNCTION_BLOCK\n")
    code, line, col, message = only(text, "codesys")
    assert (code, line, col) == ("E-DECL-002", 3, 10)
    assert message == "property x has the name of a variable of FB"


def test_a_property_of_another_name_is_no_duplicate():
    text = ("FUNCTION_BLOCK FB\nVAR v : INT; END_VAR\n"
            "PROPERTY x : INT\nGET\nx := v;\nEND_GET\nEND_PROPERTY\nEND_FUNCTION_BLOCK\n")
    assert diagnostics(text, "codesys") == []
