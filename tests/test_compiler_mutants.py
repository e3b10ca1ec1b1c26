"""Behaviours of the compiled code that no other compiler test pinned down (issue 16).

Each test holds one promise of the compiler (st_runtime/compiler/) that a
mutant of a seeded sample (`python tools/mutation.py compiler --sample 200
--seed 16`) broke without a selected test failing.  Expected values come
from IEC 61131-3 or a hand calculation (stated beside each), never from a
run of the code under test; docs/mutation.md lists the mutants.
"""

from __future__ import annotations

import pytest

from st_runtime.api import load_text


def run(src: str, cycles: int = 1, dialect: str = "iec"):
    """Load `src`, run PROGRAM Main `cycles` scans; (instance, plc)."""
    plc = load_text(src, "m.st", dialect).controller()
    main = plc.add_program("Main")
    plc.run(cycles)
    return main, plc


def faults(plc):
    return [(f.code, f.line, f.message) for f in plc.faults]


# ------------------------------------------------------------------ loops

def test_for_with_a_variable_step_over_a_global_control_variable():
    # A global control variable makes FOR a loop that tests the variable each time (a callee
    # could change it); BY s with s = 3 known only at run time: g = 1, 4, 7, 10, then 13.
    main, plc = run("""VAR_GLOBAL g : INT; END_VAR
    PROGRAM Main
    VAR s : INT := 3; n : INT; last : INT; END_VAR
    FOR g := 1 TO 10 BY s DO n := n + 1; last := g; END_FOR;
    END_PROGRAM""")
    assert (main["n"], main["last"], plc.globals["g"]) == (4, 10, 13)
    assert plc.faults == []


def test_an_endless_while_ends_in_f_period_at_the_while():
    # WHILE TRUE never ends on a PLC: the task period (1 ms) is exceeded; the fault names the
    # WHILE statement (line 3, column 1 of the program text).
    main, plc = run("PROGRAM Main\nVAR n : DINT; END_VAR\nWHILE TRUE DO n := n + 1; END_WHILE;\nEND_PROGRAM\n")
    assert [(f.code, f.line, f.col) for f in plc.faults] == [("F-PERIOD", 3, 1)]
    assert main["n"] > 0


# ------------------------------------------------------------------ references and bits

def test_dereferencing_null_is_f_null_ref_with_its_message():
    _, plc = run("PROGRAM Main\nVAR r : REF_TO INT; x : INT; END_VAR\nx := r^;\nEND_PROGRAM\n")
    assert faults(plc) == [("F-NULL-REF", 3, "dereference of NULL (the reference refers to nothing)")]


def test_setting_the_sign_bit_of_a_signed_integer_makes_it_negative():
    # Two's complement: bit 7 of a SINT is -2^7, bit 15 of an INT -2^15 (5 - 32768 = -32763),
    # bit 31 of a DINT -2^31; bit 7 of a USINT is +128.
    main, _ = run("""PROGRAM Main
    VAR a : SINT; b : INT := 5; c : DINT; w : USINT; END_VAR
    a.7 := TRUE; b.15 := TRUE; c.31 := TRUE; w.7 := TRUE;
    END_PROGRAM""", dialect="codesys")
    assert (main["a"], main["b"], main["c"], main["w"]) == (-128, -32763, -(2**31), 128)


# ------------------------------------------------------------------ open arrays

def test_an_open_array_index_out_of_range_names_its_dimension():
    # ARRAY[*, *] bound to ARRAY[1..2, 1..3]: j = 4 is outside dimension 2 (1..3); the
    # statement is abandoned (IEC: the fault ends the statement), the next call stores.
    main, plc = run("""FUNCTION_BLOCK G
    VAR_IN_OUT grid : ARRAY[*, *] OF INT; END_VAR
    VAR_INPUT i, j : INT; END_VAR
    grid[i, j] := 7;
    END_FUNCTION_BLOCK
    PROGRAM Main
    VAR a : ARRAY[1..2, 1..3] OF INT; g : G; END_VAR
    g(grid := a, i := 2, j := 4);
    g(grid := a, i := 2, j := 3);
    END_PROGRAM""")
    assert faults(plc) == [("F-INDEX", 4, "index 4 (dimension 2) of 'grid' out of bounds 1..3")]
    assert main["a"] == [[0, 0, 0], [0, 0, 7]]


class _Context:
    """What a compiled body needs of the controller: a budget and a fault log."""

    def __init__(self):
        self.budget = 10**12
        self.faults = []

    def fault(self, exc, where):
        self.faults.append((getattr(exc, "code", None), str(exc), where[2]))


def test_an_unconnected_in_out_names_itself_in_its_fault():
    # The checker requires io at every call, so only a direct run of the body leaves it
    # unconnected: the read is F-NULL-REF naming the VAR_IN_OUT as declared (line 4).
    project = load_text("""FUNCTION_BLOCK F
VAR_IN_OUT io : INT; END_VAR
VAR_OUTPUT x : INT; END_VAR
x := io;
END_FUNCTION_BLOCK
PROGRAM Main VAR f : F; a : INT; END_VAR f(io := a); END_PROGRAM""", "m.st")
    fb, context = project.compiled.new("F"), _Context()
    type(fb).execute(fb, context)
    assert context.faults == [("F-NULL-REF", "VAR_IN_OUT 'io' was not passed a variable", 4)]


# ------------------------------------------------------------------ functions

def test_a_function_result_passed_by_reference_and_an_input_left_out():
    # IEC 61131-3 (3rd ed., function calls): an input left out of a call takes its declared initial
    # value (b = 10); the result variable is a variable of the function, so it can be passed to
    # a VAR_IN_OUT (Inc adds 1) or referenced with REF (G triples it through the reference).
    main, plc = run("""FUNCTION Inc : BOOL
    VAR_IN_OUT v : INT; END_VAR
    v := v + 1; Inc := TRUE;
    END_FUNCTION
    FUNCTION F : INT
    VAR_INPUT a : INT; b : INT := 10; END_VAR
    F := a + b;
    Inc(F);
    END_FUNCTION
    FUNCTION G : INT
    VAR r : REF_TO INT; END_VAR
    G := 5;
    r := REF(G);
    r^ := r^ * 3;
    END_FUNCTION
    PROGRAM Main
    VAR x, y, z : INT; END_VAR
    x := F(a := 1); y := F(2, 3); z := G();
    END_PROGRAM""")
    assert (main["x"], main["y"], main["z"]) == (1 + 10 + 1, 2 + 3 + 1, 5 * 3)
    assert plc.faults == []


def test_positional_arguments_go_to_the_inputs_in_declaration_order():
    # IEC 61131-3: a non-formal call lists the inputs in the order they are declared.
    main, _ = run("""FUNCTION H : DINT
    VAR_INPUT a, b, c : DINT; END_VAR
    H := a * 100 + b * 10 + c;
    END_FUNCTION
    PROGRAM Main
    VAR hh : DINT; END_VAR
    hh := H(1, 2, 3);
    END_PROGRAM""")
    assert main["hh"] == 123


def test_en_and_eno_of_a_function_called_inside_an_expression():
    # IEC 61131-3 EN/ENO: ENO alone is TRUE after a normal call; EN = FALSE calls nothing: the
    # value is the type's initial value (FALSE), outputs keep their values (t2 stays 5), ENO FALSE.
    main, _ = run("""FUNCTION Pair : BOOL
    VAR_INPUT x : INT; END_VAR
    VAR_OUTPUT twice : INT; END_VAR
    twice := 2 * x; Pair := x > 0;
    END_FUNCTION
    PROGRAM Main
    VAR r1, r2, ok : BOOL; ok2 : BOOL := TRUE; t : INT; t2 : INT := 5; END_VAR
    r1 := Pair(5, twice => t, ENO => ok);
    r2 := Pair(EN := FALSE, x := 5, twice => t2, ENO => ok2);
    END_PROGRAM""")
    assert (main["r1"], main["t"], main["ok"]) == (True, 10, True)
    assert (main["r2"], main["t2"], main["ok2"]) == (False, 5, False)


# ------------------------------------------------------------------ declarations

def test_initial_values_declared_with_a_derived_type():
    # IEC 61131-3 derived types carry an initial value that their variables take.
    main, _ = run("""TYPE Speed : INT := 42; END_TYPE
    TYPE Mode : (Off, Slow, Fast) := Slow; END_TYPE
    PROGRAM Main
    VAR s : Speed; md : Mode; END_VAR
    END_PROGRAM""")
    assert (main["s"], main["md"]) == (42, "Slow")


def test_members_and_elements_of_an_enumerated_type_take_its_initial_value():
    # IEC 61131-3: an enumerated type declared `:= Slow` starts every variable of the type at
    # Slow, members of a structure and elements of an array as well (c has its own value).
    # (Bug found by the mutation run: the compiler looked the type's initial value up by the
    # type's spelling, its table is upper case, so members and elements started at Off.)
    main, _ = run("""TYPE Mode : (Off, Slow, Fast) := Slow; END_TYPE
    TYPE Pair : STRUCT b : Mode; c : Mode := Fast; END_STRUCT; END_TYPE
    PROGRAM Main
    VAR p : Pair; arr : ARRAY[1..2] OF Mode; END_VAR
    END_PROGRAM""")
    assert main["p"] == {"b": "Slow", "c": "Fast"} and main["arr"] == ["Slow", "Slow"]


def test_members_and_elements_of_an_elementary_derived_type_take_its_initial_value():
    # IEC 61131-3 (table 11): `TYPE Speed : INT := 42` starts every variable of type Speed at
    # 42: a member of a structure (c has its own value), an element of an array, also of an
    # array partly initialised, and a FB's variable. (Found beside the enumerated case: the
    # alias resolves to INT, so members and elements started at 0.)
    main, _ = run("""TYPE Speed : INT := 42; END_TYPE
    TYPE Pair : STRUCT b : Speed; c : Speed := 7; END_STRUCT; END_TYPE
    FUNCTION_BLOCK Holder
    VAR_OUTPUT s : Speed; END_VAR
    END_FUNCTION_BLOCK
    PROGRAM Main
    VAR p : Pair; arr : ARRAY[1..2] OF Speed; part : ARRAY[1..3] OF Speed := [1];
        h : Holder; fromfb : INT; END_VAR
    fromfb := h.s;
    END_PROGRAM""")
    assert main["p"] == {"b": 42, "c": 7} and main["arr"] == [42, 42]
    assert main["part"] == [1, 42, 42] and main["fromfb"] == 42


def test_a_write_through_this_is_read_back_by_the_body():
    # THIS is the instance itself: n written through it is the n the body reads next
    # (read four times, so a body that kept n in a local would show 0).
    main, _ = run("""FUNCTION_BLOCK Self
    VAR n, m : INT; END_VAR
    THIS.n := 7; m := n + n + n + n;
    END_FUNCTION_BLOCK
    PROGRAM Main
    VAR fb : Self; END_VAR
    fb();
    END_PROGRAM""")
    assert main["fb"] == {"n": 7, "m": 28}


# ------------------------------------------------------------------ loops and conditions

def test_for_with_a_variable_step_over_a_local_control_variable():
    # BY step (3, known at run time): i = 1, 4, 7, 10, then 13 after the loop.
    main, _ = run("""PROGRAM Main
    VAR i, n : INT; step : INT := 3; END_VAR
    FOR i := 1 TO 10 BY step DO n := n + 1; END_FOR;
    END_PROGRAM""")
    assert (main["n"], main["i"]) == (4, 13)


def test_not_of_a_constant_table_condition_takes_the_other_branch():
    # sg[2] = -1, so sg[2] > 0 is FALSE and NOT of it TRUE: the THEN branch.
    main, _ = run("""PROGRAM Main
    VAR k : INT; END_VAR
    VAR CONSTANT sg : ARRAY[1..2] OF INT := [1, -1]; END_VAR
    IF NOT (sg[2] > 0) THEN k := 1; ELSE k := 2; END_IF;
    END_PROGRAM""")
    assert main["k"] == 1


def test_a_one_dimensional_open_array_index_out_of_range():
    main, plc = run("""FUNCTION_BLOCK G
    VAR_IN_OUT v : ARRAY[*] OF INT; END_VAR
    VAR_INPUT i : INT; END_VAR
    v[i] := 7;
    END_FUNCTION_BLOCK
    PROGRAM Main
    VAR a : ARRAY[1..3] OF INT; g : G; END_VAR
    g(v := a, i := 4);
    g(v := a, i := 3);
    END_PROGRAM""")
    assert faults(plc) == [("F-INDEX", 4, "index 4 of 'v' out of bounds 1..3")]
    assert main["a"] == [0, 0, 7]


def test_the_instance_of_an_fb_call_is_evaluated_once():
    # t[Next()](a := 1, b := 10): one call statement evaluates its instance once (Next runs
    # once, returns 1): t[1] gets both inputs and runs (s = 11); t[2] is untouched.
    main, plc = run("""VAR_GLOBAL calls : INT; END_VAR
    FUNCTION Next : INT
    Next := 1 + calls MOD 2; calls := calls + 1;
    END_FUNCTION
    FUNCTION_BLOCK Acc
    VAR_INPUT a, b : INT; END_VAR
    VAR_OUTPUT s : INT; END_VAR
    s := s + a + b;
    END_FUNCTION_BLOCK
    PROGRAM Main
    VAR t : ARRAY[1..2] OF Acc; END_VAR
    t[Next()](a := 1, b := 10);
    END_PROGRAM""")
    assert main["t"] == [{"a": 1, "b": 10, "s": 11}, {"a": 0, "b": 0, "s": 0}]
    assert plc.globals["calls"] == 1


# ------------------------------------------------------------------ the estimated NJ501 time (cost.py's weights, by hand)

def _scan_ps(src: str, dialect: str = "iec") -> int:
    plc = load_text(src, "m.st", dialect).controller()
    plc.add_program("Main")
    plc.run(1)
    return plc.controller.task_times["Primary"][0]


def _ps(units) -> int:
    from st_runtime.compiler.cost import PICOSECONDS_PER_UNIT

    return int(round(units * PICOSECONDS_PER_UNIT))


@pytest.mark.parametrize("decls, body, dialect, units", [
    # x := a[i]: load a, load i + subscript, store x
    ("a : ARRAY[1..3] OF INT; i : INT := 2; x : INT;", "x := a[i];", "iec", lambda w: w["load"] + w["load"] + w["index"] + w["store"]),
    # FOR setup (start, end, store i), then 3 iterations of (loop + n := n + 1) charged up front
    ("i, n : INT;", "FOR i := 1 TO 3 DO n := n + 1; END_FOR;", "iec",
     lambda w: 2 * w["load"] + w["store"] + 3 * (w["loop"] + 2 * w["load"] + w["int_op"] + w["store"])),
    # a PLCopen motion FB: its instruction, Axis by reference, Enable by value (a load)
    ("ax : AXIS_REF; p : MC_Power;", "p(Axis := ax, Enable := TRUE);", "nj",
     lambda w: w["motion_fb"] + w["argument"] + w["argument"] + w["load"]),
    # REAL negation costs an add
    ("r, s : LREAL := 2.0;", "r := -s;", "iec", lambda w: w["load"] + w["real_add"] + w["store"]),
])
def test_the_estimated_time_of_one_statement(decls, body, dialect, units):
    from st_runtime.compiler.cost import WEIGHTS

    assert _scan_ps(f"PROGRAM Main\nVAR {decls} END_VAR\n{body}\nEND_PROGRAM\n", dialect) == _ps(units(WEIGHTS))


def test_an_lint_output_read_into_an_lreal_inside_an_expression_is_rounded():
    # 2^53 + 1 has no LREAL: the implicit LINT -> LREAL conversion rounds it to nearest, 2^53
    # (ties to even), so lr = 2^53 and LREAL_TO_LINT gives 2^53 back.
    main, _ = run("""FUNCTION F : BOOL
    VAR_OUTPUT big : LINT; END_VAR
    big := 9007199254740993; F := TRUE;
    END_FUNCTION
    PROGRAM Main VAR ok, same : BOOL; lr : LREAL; back : LINT; END_VAR
    ok := F(big => lr); same := lr = 9007199254740992.0; back := LREAL_TO_LINT(lr);
    END_PROGRAM""")
    assert (main["ok"], main["same"], main["back"]) == (True, True, 2**53)


def test_a_constant_string_is_cut_to_the_bytes_an_nj_string_holds():
    # docs/nj501.md: under --dialect nj STRING[n] holds n bytes (UTF-8), never half a character:
    # 'ÄÄ' is 4 bytes, STRING[3] keeps the first 'Ä' (2 bytes); under iec it counts 2 characters.
    nj, _ = run("PROGRAM Main\nVAR s : STRING[3]; END_VAR\ns := 'ÄÄ';\nEND_PROGRAM\n", dialect="nj")
    iec, _ = run("PROGRAM Main\nVAR s : STRING[3]; END_VAR\ns := 'ÄÄ';\nEND_PROGRAM\n")
    assert (nj["s"], iec["s"]) == ("Ä", "ÄÄ")


def test_a_wider_value_stored_in_a_subrange_is_checked():
    # USINT 200 fits INT but not INT(0..10): IEC 61131-3 subrange, a fault (the store is abandoned).
    main, plc = run("""PROGRAM Main VAR s : INT(0..10); u : USINT := 200; END_VAR
    s := u;
    END_PROGRAM""")
    assert faults(plc) == [("F-SUBRANGE", 2, "200 is outside the subrange 0..10")] and main["s"] == 0


def test_a_long_for_left_by_exit_is_charged_only_for_the_iterations_it_ran():
    # FOR to 10,000,000 left by EXIT at i = 2: two iterations of a few units each (ns), far
    # inside the 1 ms period; charging the whole count up front would be about 50 ms: F-PERIOD.
    main, plc = run("""PROGRAM Main VAR i : DINT; n : DINT; END_VAR
    FOR i := 1 TO 10000000 DO IF i = 2 THEN EXIT; END_IF; n := n + 1; END_FOR;
    END_PROGRAM""")
    assert plc.faults == [] and (main["n"], main["i"]) == (1, 2)


def test_a_variable_passed_positionally_to_a_third_in_out_is_written_back():
    # Add3(1, 2, x): the third positional argument goes to the VAR_IN_OUT io, which the call
    # changes (10 + 1 + 2 = 13); the program reads x often (4 times before), and must see 13.
    main, _ = run("""FUNCTION Add3 : BOOL
    VAR_INPUT a, b : INT; END_VAR
    VAR_IN_OUT io : INT; END_VAR
    io := io + a + b; Add3 := TRUE;
    END_FUNCTION
    PROGRAM Main VAR x : INT := 10; y : INT; ok : BOOL; END_VAR
    y := x + x + x + x;
    ok := Add3(1, 2, x);
    y := y + x;
    END_PROGRAM""")
    assert (main["x"], main["y"]) == (13, 4 * 10 + 13)


def test_a_body_that_writes_an_array_reads_the_value_it_wrote():
    # Eight element reads at literal indices after a store to a[1]: the sum reads the new
    # a[1] = 8, so s = 8 + 2 + 3 + 4 + 5 + 6 + 7 + 8 = 43 (reads taken before the store: 36).
    main, _ = run("""PROGRAM Main
    VAR a : ARRAY[1..8] OF INT := [1, 2, 3, 4, 5, 6, 7, 8]; s : INT; END_VAR
    a[1] := a[8];
    s := a[1] + a[2] + a[3] + a[4] + a[5] + a[6] + a[7] + a[8];
    END_PROGRAM""")
    assert (main["a"][0], main["s"]) == (8, 43)


def test_time_multiplied_and_divided_by_a_real_variable():
    # TIME * REAL and TIME / REAL (IEC 61131-3 MUL/DIV of TIME by ANY_NUM): 2 s * 1.5 = 3 s,
    # 1.5 * 2 s = 3 s, 2 s / 0.5 = 4 s (variables, so the checker folds nothing).
    main, _ = run("""PROGRAM Main
    VAR t : TIME := T#2s; k : LREAL := 1.5; h : LREAL := 0.5; a, b, c : TIME; END_VAR
    a := t * k; b := k * t; c := t / h;
    END_PROGRAM""")
    assert (main["a"], main["b"], main["c"]) == ("T#3s", "T#3s", "T#4s")


def test_a_long_time_times_one_is_exact():
    # MULTIME rounds the exact product (values.time_mul): 200 days + 1 ns (above 2^53 ns, no
    # LREAL holds it) times 1.0 is itself, to the nanosecond.
    main, _ = run("""PROGRAM Main
    VAR big, a : TIME; one : LREAL := 1.0; n : LINT; END_VAR
    big := LINT_TO_TIME(17280000000000001); a := big * one; n := TIME_TO_LINT(a);
    END_PROGRAM""")
    assert main["n"] == 200 * 86_400 * 10**9 + 1


def test_a_global_control_variable_read_without_var_external_is_tested_each_time():
    # Main uses the global g directly; Bump adds 4 to it inside the loop. A PLC tests g at
    # each end: g = 1 -> 5 -> 6, -> 10 -> 11 > 10: two iterations, g = 11 after the loop.
    main, plc = run("""VAR_GLOBAL g : INT; END_VAR
    FUNCTION Bump : BOOL
    g := g + 4; Bump := TRUE;
    END_FUNCTION
    PROGRAM Main VAR n : INT; ok : BOOL; END_VAR
    FOR g := 1 TO 10 DO ok := Bump(); n := n + 1; END_FOR;
    END_PROGRAM""")
    assert (main["n"], plc.globals["g"]) == (2, 11)
