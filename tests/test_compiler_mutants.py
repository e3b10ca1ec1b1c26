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
