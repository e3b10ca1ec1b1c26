"""Compiler behaviours that survivors of the mutation samples of seeds 21, 22 and 23 pinned
down (issue 16, session 8; docs/mutation.md, "st_runtime/compiler/").

Each test loads ST through the public entry point (or calls a pass on its own lines) and
takes its expected values from IEC 61131-3, OMRON's W501 manual as docs/nj501.md quotes
it, the passes' own documented contracts, or a hand calculation stated beside it.
"""

from __future__ import annotations

import math
import re
import warnings

from st_runtime.api import load_text
from st_runtime.compiler import compile_program
from st_runtime.compiler.optimise import vector
from test_compiler_mutants import run
from test_compiler_mutation_s7 import faults
from test_optimiser_equivalence import _Context


# ----------------------------------------------- `ranges`: a store that may fault

def test_a_store_that_may_fault_keeps_the_union_of_both_ranges():
    # i := 1, then i := i + 1 in a branch: after the IF, i is 1 or 2, both inside a[1..3],
    # so a[i] is read unchecked.  k = 1: i = 2, a[2] + k = 20 + 1 = 21.
    main, plc = run("""
FUNCTION Step : INT
VAR_INPUT k : INT; END_VAR
VAR i : INT; a : ARRAY[1..3] OF INT := [10, 20, 30]; END_VAR
i := 1;
IF k > 0 THEN i := i + 1; END_IF;
i := a[i] + k;
Step := i;
END_FUNCTION
PROGRAM Main
VAR r : INT; s : INT; END_VAR
r := Step(k := 1);
s := Step(k := 0);       (* i stays 1: a[1] + 0 = 10 *)
END_PROGRAM""")
    assert (main["r"], main["s"], plc.faults) == (21, 10, [])


# ----------------------------------- an FB's in-out array read from outside the FB

def test_an_in_out_array_of_an_instance_is_read_from_outside():
    # IEC 61131-3 6.5.2.2: a VAR_IN_OUT is the variable connected by the last call; the FB
    # added 1 to A[2] of arr = [1, 2, 3], so f.A[2] is arr[2] = 3.
    main, plc = run("""
FUNCTION_BLOCK Fb
VAR_IN_OUT A : ARRAY[1..3] OF INT; END_VAR
A[2] := A[2] + 1;
END_FUNCTION_BLOCK
PROGRAM Main
VAR f : Fb; arr : ARRAY[1..3] OF INT := [1, 2, 3]; x : INT; END_VAR
f(A := arr);
x := f.A[2];
END_PROGRAM""")
    assert (main["x"], main["arr"], plc.faults) == (3, [1, 3, 3], [])


# -------------------------- `unroll`: the size of a loop whose CASE has an ELSE loop

def test_a_loop_in_the_else_of_a_case_inside_an_unrolled_loop():
    # i = 1: x = 1; i = 2 and 3: the ELSE adds j = 1 and 2 each time: y = 2 * (1 + 2) = 6.
    main, plc = run("""
FUNCTION Count : INT
VAR i : INT; j : INT; x : INT; y : INT; END_VAR
FOR i := 1 TO 3 DO
    CASE i OF
        1: x := x + 1;
    ELSE
        FOR j := 1 TO 2 DO y := y + j; END_FOR;
    END_CASE;
END_FOR;
Count := 10 * x + y;
END_FUNCTION
PROGRAM Main
VAR r : INT; END_VAR
r := Count();
END_PROGRAM""")
    assert (main["r"], plc.faults) == (16, [])


# ------------------------------------------------- `vector`: two chains in one run

def _vectorised(lines: list[str], floats: set[str]):
    """vector.vectorise on a copy of `lines`, which must become one call: (the helper it
    registered, its output names, its input names)."""
    done, bound = list(lines), {}

    def register(helper) -> str:
        bound["_k0"] = helper
        return "_k0"

    vector.vectorise(done, 0, len(done), floats.__contains__, register)
    call = re.fullmatch(r"    (.*), = _k0\(None, \((.*), \)\)", done[0])
    assert call is not None and len(done) == 1
    return bound["_k0"], call.group(1).split(", "), call.group(2).split(", ")


def test_a_run_of_two_sums_becomes_one_call_with_python_results():
    # Two accumulations, D and E, of 100 products each (400 operations, above
    # MIN_OPERATIONS): one NumPy call, whose results are the lines' own, evaluated here
    # by Python operation by operation (the pass's contract, module docstring).
    lines = []
    for i in range(100):
        lines.append(f"    _t9 = (_t{i % 3 + 1} * _t{(i + 1) % 3 + 1})")
        lines.append(f"    v_D = (v_D + (_t9 * _t4))")
        lines.append(f"    _t8 = (_t{(i + 2) % 3 + 1} * _t5)")
        lines.append(f"    v_E = (v_E - (_t8 * _t4))")
    helper, outputs, names = _vectorised(lines, {"_t1", "_t2", "_t3", "_t4", "_t5", "v_D", "v_E"})
    assert {"v_D", "v_E"} <= set(outputs)
    env = {"_t1": 1.25, "_t2": -0.75, "_t3": 3.0, "_t4": 1e-3, "_t5": 7.0, "v_D": 0.1, "v_E": -2.5}
    got = helper(None, tuple(env[name] for name in names))
    exec("\n".join(line[4:] for line in lines), {}, env)
    assert dict(zip(outputs, got)) == {name: env[name] for name in outputs}


# ------------------------------------ NJ: a narrower signed sum stored into a wider unsigned

NJ_WIDER_UNSIGNED = """
PROGRAM Main
VAR
    s1 : SINT := 127; s2 : SINT := 127; u : UINT; cu : UINT;
    i1 : INT := 32767; w : UDINT; cw : UDINT;
END_VAR
u := s1 + s2;
cu := SINT_TO_UINT(s1 + s2);
w := i1 + i1;
cw := INT_TO_UDINT(i1 + i1);
END_PROGRAM
"""


def test_nj_a_signed_sum_that_overflows_is_sign_extended_into_a_wider_unsigned():
    # docs/nj501.md: under nj an integer + - * result outside the range of its type overflows
    # where it is used, stored into a wider type included (W501 6-5-3); a signed integer
    # assigned to an unsigned one of a larger size keeps its bits, sign-extended as
    # SINT_TO_ULINT does.  SINT 127 + 127 = 254 overflows to -2 = 16#FE; in a UINT that is
    # 16#FFFE = 65534.  INT 32767 + 32767 = 65534 overflows to -2; in a UDINT 16#FFFF_FFFE.
    main, plc = run(NJ_WIDER_UNSIGNED, dialect="nj")
    assert plc.faults == []
    assert (main["u"], main["cu"]) == (65534, 65534)
    assert (main["w"], main["cw"]) == (4294967294, 4294967294)


# ---------------------------------------------------------------- seed 23's survivors

FOLDED_REGION = """
FUNCTION F : INT
VAR CONSTANT Off : BOOL := FALSE; END_VAR
VAR a : ARRAY[1..8] OF INT := [1, 2, 3, 4, 5, 6, 7, 8]; x : INT; END_VAR
IF Off THEN x := a[1] + a[2] + a[3] + a[4] + a[5] + a[6] + a[7] + a[8]; END_IF;
END_FUNCTION
PROGRAM Main
VAR r : INT; END_VAR
r := F() + 1;
END_PROGRAM
"""


def test_a_whole_body_region_that_folds_to_nothing_compiles_without_charges():
    # Eight element reads make F's body one CSE region (cse.worth_a_region); the IF on a
    # FALSE constant folds away, and without charges nothing is left inside the region:
    # the function still compiles and returns its result's initial value, 0.
    program = load_text(FOLDED_REGION, "m.st").program
    compiled = compile_program(program, charge_costs=False)
    assert compiled.namespace["_fn_F"](_Context()) == 0
    main, plc = run(FOLDED_REGION)         # with charges: F() + 1 = 1
    assert (main["r"], plc.faults) == (1, [])


def test_inputs_whose_products_could_overflow_take_the_python_run_without_a_warning():
    # vector.py: inputs so large that some value could overflow run in Python, so NumPy
    # never sees an inf (and never warns).  Products of two inputs of 1e160 reach 1e320:
    # beyond the largest double, inf in Python as in NumPy; the results are Python's.
    lines = []
    for i in range(100):
        lines.append(f"    _t9 = (_t{i % 3 + 1} * _t{(i + 1) % 3 + 1})")
        lines.append(f"    v_D = (v_D + (_t9 * _t4))")
    helper, outputs, names = _vectorised(lines, {"_t1", "_t2", "_t3", "_t4", "v_D"})
    env = {"_t1": 1e160, "_t2": -1e160, "_t3": 2.0, "_t4": 0.5, "v_D": 1.0}
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        got = helper(None, tuple(env[name] for name in names))
    exec("\n".join(line[4:] for line in lines), {}, env)
    assert env["v_D"] == -math.inf                  # 1e160 * -1e160 = -inf, then -inf * 0.5
    assert dict(zip(outputs, got)) == {name: env[name] for name in outputs}


def test_the_else_of_an_elsif_chain_starts_from_the_ranges_before_the_if():
    # The first condition can fault (10 / d), so the chain is compiled through an index of
    # the branch taken.  d = 3: 10 / 3 = 3 is not > 5, d is not > 100, so the ELSE runs with
    # i = 0 (the ELSIF's i := 2 did not run): a[0] is outside 1..3, a fault (F-INDEX) at
    # line 8, and G keeps its initial value 0.
    main, plc = run("""
FUNCTION G : INT
VAR_INPUT d : INT; END_VAR
VAR i : INT; a : ARRAY[1..3] OF INT := [10, 20, 30]; END_VAR
i := 0;
IF 10 / d > 5 THEN G := 1;
ELSIF d > 100 THEN i := 2;
ELSE G := a[i];
END_IF;
END_FUNCTION
PROGRAM Main
VAR r : INT; END_VAR
r := G(d := 3);
END_PROGRAM""")
    assert main["r"] == 0
    assert faults(plc) == [("F-INDEX", 8)]


def test_an_operator_in_call_form_used_as_a_statement():
    # IEC 61131-3 Table 24: ADD and GT are the functions of + and >; called as statements
    # their results are dropped and nothing changes: x stays 4, and y := x + 1 is 5.
    main, plc = run("""PROGRAM Main
VAR x : INT := 4; y : INT; END_VAR
ADD(x, 1);
GT(x, 1);
y := x + 1;
END_PROGRAM""")
    assert (main["x"], main["y"], plc.faults) == (4, 5, [])
