"""The optimiser passes' table, session 15 (issue 16; docs/mutation.md, compiler, "Session 15,
optimise"): rows for session 14's leftovers and the fresh sample's survivors.  The rows are
`Row`s of test_compiler_tables_passes (the values after the scans worked out by hand, held
with the pass alone, with none and with every pass, the NJ time charged the same).
"""

from __future__ import annotations

import math
import random

import numpy as np
import pytest

from st_runtime import api
from st_runtime.compiler import Optimisations, compile_program
from st_runtime.compiler.optimise import chains
from st_runtime.controller import Controller

from test_compiler_tables_passes import EVERY, NONE, Row, _landings, check, fast_src, main, modes_fb
from test_compiler_tables_passes_vector import _check, _inputs, _run, _same, _vectorised

ROWS: list[Row] = []


def row(*args, **kwargs) -> None:
    ROWS.append(Row(*args, **kwargs))


# ---------------------------------------------------------------------------------- ranges
# A variable stored through an output (`q => i`) is not followed past the call: the call may
# store any value of its type.  It must be a plain Python local for `ranges` to follow it at
# all: a FUNCTION's VAR, or a PROGRAM's variable used often enough to be cached (a read in a
# loop counts 10).  i := 1, then the call gives i = -1: arr[i] is out of ARRAY[1..3] (F-INDEX
# at the read's line, the statement abandoned: y keeps 0); unchecked, arr[-1] would read the
# list's element -2 (20).
NEG_FN = """
FUNCTION Neg : INT
VAR_OUTPUT q : INT; END_VAR
q := -1;
Neg := 0;
END_FUNCTION
FUNCTION Outer : INT
VAR i, y, z : INT; arr : ARRAY[1..3] OF INT := [10, 20, 30]; END_VAR
i := 1;
z := Neg(q => i);
y := arr[i];
Outer := y;
END_FUNCTION"""
row("ranges", "a FUNCTION's local stored through an output is not followed past the call",
    main("r : INT;", "r := Outer();", before=NEG_FN), {"r": 0}, faults=[("F-INDEX", 11, 1)])

NEG_FB = """FUNCTION_BLOCK NegFb
VAR_OUTPUT q : INT; END_VAR
q := -1;
END_FUNCTION_BLOCK"""
# (lines: 7 i := 1, 8 the call, 9 the read; then y := 0 + i + i = -2 by the loop)
row("ranges", "a cached variable stored through an FB's output is not followed past the call",
    main("arr : ARRAY[1..3] OF INT := [10, 20, 30]; i, y, k : INT; g : NegFb;",
         "i := 1;\ng(q => i);\ny := arr[i];\nFOR k := 1 TO 2 DO y := y + i; END_FOR;", before=NEG_FB),
    {"i": -1, "y": -2}, faults=[("F-INDEX", 9, 1)])

# An argument with no variable at its root (a bit of a directly represented variable) leaves
# nothing to exclude.  %MW1 = 8 = 2#1000: bit 3 TRUE, bit 2 FALSE; Inv gives their negation.
INV = """FUNCTION Inv : BOOL
VAR_INPUT b : BOOL; END_VAR
Inv := NOT b;
END_FUNCTION"""
row("ranges", "an argument that is a bit of a directly represented variable", main(
    "y, z : BOOL;", "%MW1 := 8;\ny := Inv(%MW1.%X3);\nz := Inv(b := %MW1.%X2);", before=INV),
    {"y": False, "z": True})

# ---------------------------------------------------------------------------------- spread
# A cached variable stored in one branch and only read in the other branch of the same IF is
# loaded in each and stored back in the branch that stores it, and only there (stores.py:
# "stored back around each that stores it").  Mode 0, 1, 2, 3 by scan: ELSE gives
# Cnt + 0.5 = 0.5; THEN Cnt = (0 + 1) * 2 = 2, Out = 2.0; ELSE 2.5 twice.
row("spread", "a branch that only reads a cached variable does not store it back", modes_fb(
    "IF Mode = 1 THEN Cnt := Cnt + 1; Cnt := Cnt * 2; Out := INT_TO_LREAL(Cnt); "
    "ELSE Out := INT_TO_LREAL(Cnt) + 0.5; END_IF;"),
    {"outs": [0.5, 2.0, 2.5, 2.5], "f.Cnt": 2}, scans=4,
    shape=("FB", r"\n {12,}finally:\n {16,}self\.v_CNT = v_CNT"),
    never=("FB", r"(?s)self\.v_CNT = v_CNT.*self\.v_CNT = v_CNT"))

# ---------------------------------------------------------------------------------- finite
# A located REAL may change through another variable at its address (b here): SIN and COS of
# it test its finiteness each time, no value is shared.  REAL SIN / COS: the float32 nearest
# the exact result for the float32 input (0.5, then 1.0 stored through b).
F32 = np.float32
row("finite", "SIN and COS of a located REAL are no values of the pass", main(
    "a AT %MD10 : REAL; b AT %MD10 : REAL; x, y, z : REAL;",
    "a := 0.5;\nx := SIN(a);\nz := COS(a);\nb := 1.0;\ny := SIN(a);"),
    {"x": float(F32(math.sin(0.5))), "z": float(F32(math.cos(0.5))), "y": float(F32(math.sin(1.0)))},
    never=("MAIN", r"_c\d+ = "))


# ======================================================================= the fresh seed 350
# Rows for the survivors of the fresh sample (docs/mutation.md, compiler, "Session 15").

# ----------------------------------------------------------------------------------- reuse
# SIN of a global before and after a FUNCTION that stores the global, in one statement: the
# statement calls ST code, so no value is kept across it; each SIN reads g as it is then
# (left to right): sin(0.5) + 0.0 + sin(1.0) in Python's floats (LREAL: binary64).
SETG = """VAR_GLOBAL g : LREAL := 0.5; END_VAR
FUNCTION SetG : LREAL
VAR_EXTERNAL g : LREAL; END_VAR
g := 1.0;
SetG := 0.0;
END_FUNCTION"""
row("reuse", "SIN of a global on both sides of a call that stores it", main(
    "y : LREAL; END_VAR VAR_EXTERNAL g : LREAL;", "y := SIN(g) + SetG() + SIN(g);", before=SETG),
    {"y": (math.sin(0.5) + 0.0) + math.sin(1.0)})

# A loop whose body calls ST code ends every value at its start, also one computed before
# it (ga * b, y's): ga = 1.5, b = 2.0; x = 0 + 1.5 * 2.0 = 3.0, BumpA makes ga 2.5, then
# x = 3.0 + 2.5 * 2.0 = 8.0 (a value kept from before the loop would give 6.0).
BUMP = """VAR_GLOBAL ga : LREAL := 1.5; END_VAR
FUNCTION BumpA : LREAL
VAR_EXTERNAL ga : LREAL; END_VAR
ga := ga + 1.0;
BumpA := 0.0;
END_FUNCTION"""
row("reuse", "a value read in a loop whose body calls ST code that stores its operand", main(
    "x, y, z : LREAL; b : LREAL := 2.0; i : INT; END_VAR VAR_EXTERNAL ga : LREAL;",
    "y := ga * b;\nFOR i := 1 TO 2 DO x := x + ga * b; z := BumpA(); END_FOR;", before=BUMP),
    {"x": 8.0, "y": 3.0})

# ---------------------------------------------------------------------------------- spread
# Uses in branches of two IFs, both inside one outer branch: not spread (both IFs may run),
# loaded once in the outer branch (their common branch).  Mode 0..3: Out keeps its value
# where no assignment runs; Mode 1 reads Arr[1] = 1.0, Mode 2 Arr[2] = 2.0.
row("spread", "branches of two IFs inside one branch: loaded in that branch", modes_fb(
    "IF Mode > 0 THEN IF Mode = 1 THEN Out := Arr[1]; END_IF; IF Mode = 2 THEN Out := Arr[2]; END_IF; END_IF;"),
    {"outs": [0.0, 1.0, 2.0, 2.0]}, scans=4, shape=("FB", r"\n {12,}v_ARR = self\.v_ARR"))


# A cached REF only dereferenced into an in-out (`SetI(io := p^)`) is stored nowhere in the
# body (the walk of branches finds no store of it; Usage counts it assigned): under spread it
# is loaded in both branches, stored back in neither.  p is NULL: the call faults
# (F-NULL-REF, line 10, scan 2, Mode 1); the ELSE counts Out up: 1, 1, 2, 3.
INOUT_REF = """FUNCTION SetI : BOOL
VAR_IN_OUT io : INT; END_VAR
io := 5;
SetI := TRUE;
END_FUNCTION
FUNCTION_BLOCK Fb
VAR_INPUT Mode : INT; END_VAR
VAR_OUTPUT Out : INT; END_VAR
VAR r : BOOL; p : REF_TO INT; END_VAR
IF Mode = 1 THEN r := SetI(io := p^); ELSE r := p = NULL; r := r AND p = NULL AND p = NULL; IF r THEN Out := Out + 1; END_IF; END_IF;
END_FUNCTION_BLOCK
PROGRAM Main
VAR f : Fb; n : INT; outs : ARRAY[0..3] OF INT; END_VAR
f(Mode := n); outs[n] := f.Out; n := n + 1;
END_PROGRAM
"""
row("spread", "a cached REF only dereferenced into an in-out", INOUT_REF, {"outs": [1, 1, 2, 3]}, scans=4,
    faults=[("F-NULL-REF", 10, 2)])


@pytest.mark.parametrize("r", ROWS, ids=lambda r: r.id)
def test_row(r: Row):
    check(r)


# -------------------------------------------------------------------------------- fastpath
# A FOR counting down (BY -1) over a constant range: its values 6, 5, ..., 1 bound the inner
# loop's count (FOR k := 1 TO j: 21 iterations in all).  F-PERIOD lands the same with
# fastpath alone and every pass as with none at every budget 2 ns apart up to the scan's
# whole time (a bound counting fewer values would take the fast copy where it does not fit).
DOWN = fast_src("FOR j := 6 TO 1 BY -1 DO FOR k := 1 TO j DO s := s + 1; END_FOR; END_FOR;")


def test_a_for_counting_down_bounds_its_fast_copy_by_all_its_values():
    controller = Controller(compile_program(api.load_text(DOWN, "m.st").program, optimise=NONE),
                            time_limit_ns=10_000_000)
    main_ = controller.add_program("Main")
    controller.run(1)
    assert (main_.v_R, controller.faults) == (164 + 21, [])
    spent_ns = 10_000_000 - controller.ctx.budget // 1000
    budgets = list(range(1, spent_ns + 20, 2))
    expected = _landings(DOWN, NONE, budgets, scans=1, stop=True)
    for optimise in (Optimisations.only("fastpath"), EVERY):
        assert _landings(DOWN, optimise, budgets, scans=1, stop=True) == expected


# ---------------------------------------------------------------------------------- vector
# 260 products of two inputs each (c = 1, d = 2): the bound under which no value reaches
# 1e300 is B = 10**150.  Inputs of 1e151 and more take the Python run (1e155 * 1e155
# overflows to inf there, as in Python); those below NumPy's, which never overflows
# (the harness makes NumPy raise where it would warn).  Every store bit for bit Python's.
def test_products_of_two_inputs_take_numpy_below_1e150_only():
    lines = [f"v_P{k} = (_t{1 + k % 8} * _t{1 + (k + 1) % 8})" for k in range(260)]
    after, bound = _vectorised(lines)
    assert len(bound) == 1
    for big in (1e140, 1e149, 1e151, 1e155, 1e160):
        env = _inputs(random.Random(1))
        env["_t1"] = env["_t2"] = big
        want, got = _run(lines, env, {}), _run(after, env, bound)
        assert all(_same(got[f"v_P{k}"], want[f"v_P{k}"]) for k in range(260)), big


# A run whose last line stores a temporary no later line reads: its operations are dead, not
# computed (the run's other values as Python's, the temporary not stored).
def test_a_run_ending_in_a_dead_nested_product():
    lines = [f"v_P{k} = (_t{1 + k % 8} * _t{1 + (k + 1) % 8})" for k in range(260)]
    lines.append("_t99 = (((_t1 * _t2) * _t3) * _t4)")
    after, bound = _vectorised(lines)
    assert len(bound) == 1
    _check(lines, after, bound)


# ---------------------------------------------------------------------------------- chains
# chains.merge leaves the lines of a `try:` body as they are (`free`: a merge keeps the
# first line's indentation, which must not be a try's body); the same three stores outside
# a try merge into one line, left to right.
STORES = ["v_A[1] = (v_A[1] + 1.0)", "v_A[1] = (v_A[1] * 2.0)", "v_A[1] = (v_A[1] + 3.0)"]


def test_chains_merge_keeps_a_try_body_and_merges_plain_lines():
    lines = ["    try:"] + ["        " + s for s in STORES] + ["    except _FAULTS as _e:", "        pass"]
    got = list(lines)
    chains.merge(got, 0)
    assert got == lines
    got = ["    " + s for s in STORES]
    chains.merge(got, 0)
    assert got == ["    v_A[1] = (((v_A[1] + 1.0) * 2.0) + 3.0)"]
