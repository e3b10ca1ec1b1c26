"""The optimiser passes' table, session 15 (issue 16; docs/mutation.md, compiler, "Session 15,
optimise"): rows for session 14's leftovers and the fresh sample's survivors.  The rows are
`Row`s of test_compiler_tables_passes (the values after the scans worked out by hand, held
with the pass alone, with none and with every pass, the NJ time charged the same).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from test_compiler_tables_passes import Row, check, main, modes_fb

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


@pytest.mark.parametrize("r", ROWS, ids=lambda r: r.id)
def test_row(r: Row):
    check(r)
