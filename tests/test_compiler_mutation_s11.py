"""Compiler behaviours that survivors of the mutation sample of seed 26 left open, pinned down
(issue 16, session 11; docs/mutation.md, "st_runtime/compiler/", "Session 11").

Each test loads ST through the public entry point and takes its expected values from
IEC 61131-3, the CODESYS rules the codesys dialect follows, OMRON's manuals as docs/nj501.md
cites them, NumPy, or a hand calculation stated beside it.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from st_runtime.api import load_text
from test_compiler_mutants import _Context, run


# ------------------------------------------- a bit written into a negative signed integer

@pytest.mark.parametrize("dialect", ["codesys", "nj"])   # (bit access is not IEC: E-DIALECT-001)
def test_a_bit_written_into_a_negative_signed_integer_keeps_its_range(dialect: str):
    # Two's complement, by hand: -1 is all ones; clearing bit 0 gives -2, clearing the sign bit
    # gives the type's maximum (INT 32767, DINT 2**31 - 1, LINT 2**63 - 1); SINT -128 is
    # 16#80, and setting bit 0 gives 16#81 = -127. The result stays in the type's range.
    main, plc = run("""PROGRAM Main
VAR s : SINT := -128; i : INT := -1; j : INT := -1; d : DINT := -1; l : LINT := -1; END_VAR
s.0 := TRUE;
i.0 := FALSE;
j.15 := FALSE;
d.31 := FALSE;
l.0 := FALSE;
END_PROGRAM""", dialect=dialect)
    assert [main[n] for n in "sijdl"] == [-127, -2, 32767, 2**31 - 1, -2]
    assert plc.faults == []


# ------------------------------------- an INT sum passed to a wider input, under each dialect

ARGUMENT = """FUNCTION Wide : DINT
VAR_INPUT d : DINT; END_VAR
Wide := d;
END_FUNCTION
FUNCTION Real64 : LREAL
VAR_INPUT x : LREAL; END_VAR
Real64 := x;
END_FUNCTION
FUNCTION_BLOCK Keep
VAR_INPUT d : DINT; END_VAR
VAR_OUTPUT q : DINT; END_VAR
q := d;
END_FUNCTION_BLOCK
PROGRAM Main
VAR i1 : INT := 32767; i2 : INT := 1; a : DINT; b : LREAL; c : DINT; k : Keep; END_VAR
a := Wide(i1 + i2);
b := Real64(i1 + i2);
k(d := i1 + i2);
c := k.q;
END_PROGRAM"""


@pytest.mark.parametrize("dialect, total", [("iec", 32768), ("codesys", 32768), ("nj", -32768)])
def test_an_int_sum_passed_to_a_wider_input_overflows_first_under_nj(dialect: str, total: int):
    # W501 6-5-3 "Implicit Casts" (docs/nj501.md, "Integer overflow inside an expression"):
    # under nj the INT sum 32767 + 1 overflows to -32768 before it is cast to the wider
    # DINT or LREAL input; under iec and codesys it stays exact, 32768.
    main, plc = run(ARGUMENT, dialect=dialect)
    assert (main["a"], main["b"], main["c"], plc.faults) == (total, float(total), total, [])


# --------------------------------- a standard function's REAL result, under each dialect

@pytest.mark.parametrize("dialect", ["iec", "codesys", "nj"])
def test_a_standard_function_of_real_is_rounded_where_computed_under_nj(dialect: str):
    # docs/nj501.md, "REAL arithmetic in single precision": under nj a standard function with
    # a REAL result (SQRT, ...) is rounded to float32 where it is computed, so an LREAL
    # receives the single-precision root; elsewhere the double result is stored as it is.
    main, plc = run("""PROGRAM Main
VAR r : REAL := 2.0; l : LREAL; END_VAR
l := SQRT(r);
END_PROGRAM""", dialect=dialect)
    single = float(np.sqrt(np.float32(2.0)))          # 1.4142135381698608
    assert main["l"] == (single if dialect == "nj" else math.sqrt(2.0))
    assert plc.faults == []


# -------------------------------------------- a TIME sum in a FUNCTION's own local variable

def test_a_time_sum_in_a_function_local_wraps_past_64_bits():
    # TIME is signed 64-bit nanoseconds and wraps to its width when stored (README,
    # "Semantics"). A FUNCTION's locals are Python locals whose ranges the compiler follows
    # from the constants stored into them: T#106751D is 9223286400000000000 ns, twice that is past 2**63 - 1 and wraps to
    # 18446572800000000000 - 2**64 = -171273709551616 ns, a negative duration.
    main, plc = run("""FUNCTION Twice : BOOL
VAR t : TIME; END_VAR
t := T#106751D;
t := t + t;
Twice := t < T#0S;
END_FUNCTION
PROGRAM Main
VAR neg : BOOL; END_VAR
neg := Twice();
END_PROGRAM""")
    assert (main["neg"], plc.faults) == (True, [])


# ------------------------------------------------------- the estimated cost of unary operators

@pytest.mark.parametrize("decls, body, units", [
    # docs/nj501.md's weights: a negation or NOT of an integer, bit string or BOOL is one
    # int_op; a REAL/LREAL negation costs as a REAL addition (real_add); load a, store x
    ("a : INT := 3; x : INT;", "x := -a;", lambda w: w["load"] + w["int_op"] + w["store"]),
    ("a : WORD := 3; x : WORD;", "x := NOT a;", lambda w: w["load"] + w["int_op"] + w["store"]),
    ("a : BOOL; x : BOOL;", "x := NOT a;", lambda w: w["load"] + w["int_op"] + w["store"]),
    ("a : REAL := 3.0; x : REAL;", "x := -a;", lambda w: w["load"] + w["real_add"] + w["store"]),
    ("a : LREAL := 3.0; x : LREAL;", "x := -a;", lambda w: w["load"] + w["real_add"] + w["store"]),
], ids=["neg-int", "not-word", "not-bool", "neg-real", "neg-lreal"])
def test_a_unary_operator_costs_its_operand_and_its_operation(decls: str, body: str, units):
    from st_runtime.compiler.cost import WEIGHTS
    from test_compiler_mutants import _ps, _scan_ps

    assert _scan_ps(f"PROGRAM Main\nVAR {decls} END_VAR\n{body}\nEND_PROGRAM\n") == _ps(units(WEIGHTS))


def test_an_aggregate_argument_at_a_subscript_costs_its_subscript():
    # A structure passed by value costs one `argument` per element (three here) and locating
    # it: a plain variable is located for free, an array element costs its subscript (load i,
    # one `index`). The two calls differ by exactly that.
    from st_runtime.compiler.cost import WEIGHTS
    from test_compiler_mutants import _ps, _scan_ps

    def scan(argument: str) -> int:
        return _scan_ps(f"""TYPE P : STRUCT a : INT; b : INT; c : INT; END_STRUCT END_TYPE
FUNCTION F : INT
VAR_INPUT p : P; END_VAR
F := p.a;
END_FUNCTION
PROGRAM Main
VAR ps : ARRAY[1..2] OF P; q : P; i : INT := 2; x : INT; END_VAR
x := F({argument});
END_PROGRAM
""")

    assert scan("ps[i]") - scan("q") == _ps(WEIGHTS["load"] + WEIGHTS["index"])


# ---------------------------------------------- a store through a reference ends reused values

@pytest.mark.parametrize("dialect", ["iec", "codesys"])
def test_a_store_through_a_reference_ends_a_reused_float_value(dialect: str):
    # r points at x; `r^ := 5.0` changes x, so the second `x + 1.0` is 6.0, not the 2.0 the
    # first computed (IEC 61131-3 references: a dereference designates the variable itself).
    main, plc = run("""PROGRAM Main
VAR x : LREAL := 1.0; r : REF_TO LREAL; a : LREAL; b : LREAL; END_VAR
r := REF(x);
a := x + 1.0;
r^ := 5.0;
b := x + 1.0;
END_PROGRAM""", dialect=dialect)
    assert (main["a"], main["b"], plc.faults) == (2.0, 6.0, [])


# -------------------------------------------- a REAL divided by a constant zero, not folded

@pytest.mark.parametrize("t", ["REAL", "LREAL"])
def test_a_real_divided_by_a_constant_zero_follows_ieee_754(t: str):
    # The runtime divides REAL/LREAL as IEEE 754 does (values.real_div; the checker folds
    # 1.0 / 0.0 to +inf "as at run time"): a finite non-zero dividend over zero gives an
    # infinity of the dividend's sign, 0.0 / 0.0 a NaN (which is not equal to itself); no fault.
    main, plc = run(f"""PROGRAM Main
VAR p : {t} := 1.0; n : {t} := -1.0; z : {t}; up : BOOL; down : BOOL; nan : BOOL; END_VAR
up := p / 0.0 > 1.0E38;
down := n / 0.0 < -1.0E38;
nan := z / 0.0 <> z / 0.0;
END_PROGRAM""")
    assert (main["up"], main["down"], main["nan"], plc.faults) == (True, True, True, [])


# ------------------------------------------- a value written to a PROPERTY takes its type

def test_a_value_written_to_a_property_is_converted_to_the_propertys_type():
    # CODESYS dialect: `B.Value := r * 3.0` calls the SET accessor with the product converted
    # to the PROPERTY's type, as an assignment to a variable of that type would. CODESYS
    # computes REAL intermediate results in double precision and rounds them when stored
    # (docs/nj501.md, "REAL arithmetic in single precision"): float32(float32(0.1) * 3.0) by
    # NumPy; an INT 32767 + 1 wraps to -32768 (two's complement, INT's 16 bits).
    main, plc = run("""FUNCTION_BLOCK Box
VAR Raw : REAL; Count : INT; END_VAR
PROPERTY Value : REAL
GET
    Value := Raw;
END_GET
SET
    Raw := Value;
END_SET
END_PROPERTY
PROPERTY Items : INT
GET
    Items := Count;
END_GET
SET
    Count := Items;
END_SET
END_PROPERTY
END_FUNCTION_BLOCK
PROGRAM Main
VAR B : Box; r : REAL := 0.1; back : LREAL; i : INT := 32767; n : DINT; END_VAR
B.Value := r * 3.0;
back := B.Value;
B.Items := i + 1;
n := B.Items;
END_PROGRAM""", dialect="codesys")
    assert (main["back"], main["n"], plc.faults) == (float(np.float32(np.float64(np.float32(0.1)) * 3.0)), -32768, [])



# --------------------------- a FOR variable that is an in-out aliasing an element the body reads

@pytest.mark.parametrize("dialect", ["iec", "codesys", "nj"])
def test_a_for_variable_passed_as_an_element_of_the_array_the_loop_reads(dialect: str):
    # k is an in-out bound to a[1] and arr to a itself (IEC 61131-3: an in-out is the caller's
    # variable), so each `k := ...` of the FOR changes arr[1]: iteration 1 reads
    # 1 + 7 * 1 = 8, iteration 2 reads 2 + 7 = 9, r = 17; k ends one step past its end
    # value, 3 (FOR increments before its end test), which a[1] holds afterwards.
    main, plc = run("""FUNCTION F : INT
VAR_IN_OUT k : INT; arr : ARRAY[1..8] OF INT; END_VAR
VAR s : INT; END_VAR
FOR k := 1 TO 2 DO
    s := s + arr[1] + arr[2] + arr[3] + arr[4] + arr[5] + arr[6] + arr[7] + arr[8];
END_FOR;
F := s;
END_FUNCTION
PROGRAM Main
VAR a : ARRAY[1..8] OF INT := [0, 1, 1, 1, 1, 1, 1, 1]; r : INT; last : INT; END_VAR
r := F(k := a[1], arr := a);
last := a[1];
END_PROGRAM""", dialect=dialect)
    assert (main["r"], main["last"], plc.faults) == (17, 3, [])


# --------------------------------------------- a variable of a named type takes its default

def test_a_variable_of_a_named_type_takes_the_types_initial_value():
    # IEC 61131-3 (derived data types): a variable, a structure member or an array element
    # declared with a derived type and no initial value of its own starts with the type's;
    # one with its own keeps its own.
    main, plc = run("""TYPE Level : INT := 42; END_TYPE
TYPE Gain : LREAL := 2.5; END_TYPE
TYPE Pair : STRUCT m : Level; n : Gain; END_STRUCT END_TYPE
PROGRAM Main
VAR a : Level; b : Level := 7; g : Gain; p : Pair; arr : ARRAY[1..2] OF Level;
    x : INT; y : INT; z : LREAL; pm : INT; pn : LREAL; e : INT; END_VAR
x := a; y := b; z := g; pm := p.m; pn := p.n; e := arr[2];
END_PROGRAM""")
    assert (main["x"], main["y"], main["z"], plc.faults) == (42, 7, 2.5, [])
    assert (main["pm"], main["pn"], main["e"]) == (42, 2.5, 42)


# ------------------------- the exact path of a CSE region, taken when an in-out is unconnected

def test_the_exact_path_of_a_region_checks_indices_from_the_bodys_start():
    # A body with eight reads of io at literal indices is compiled twice: with the reads made
    # once, and as written, which runs when a read faults. The checker requires io at every
    # call, so only a direct run of the body leaves it unconnected (as in
    # test_compiler_mutants). Then the body runs as written from its start: x is still -1,
    # outside b's bounds 0..1, so `y := b[x]` is F-INDEX (line 4) before the read of io is
    # F-NULL-REF (line 6); `x := 1` later in the body does not make b[x] safe.
    project = load_text("""FUNCTION_BLOCK F
VAR_IN_OUT io : ARRAY[1..8] OF INT; END_VAR
VAR x : INT := -1; y : INT; s : INT; b : ARRAY[0..1] OF INT := [5, 7]; END_VAR
y := b[x];
x := 1;
s := io[1] + io[2] + io[3] + io[4] + io[5] + io[6] + io[7] + io[8] + x + x + y + y + y;
s := s + s + s;
END_FUNCTION_BLOCK
PROGRAM Main VAR f : F; a : ARRAY[1..8] OF INT; END_VAR f(io := a); END_PROGRAM""", "m.st")
    fb, context = project.compiled.new("F"), _Context()
    type(fb).execute(fb, context)
    assert [(code, line) for code, _, line in context.faults] == [("F-INDEX", 4), ("F-NULL-REF", 6)]
