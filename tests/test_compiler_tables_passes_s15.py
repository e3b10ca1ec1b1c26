"""The optimiser passes' table, session 15 (issue 16; docs/mutation.md, compiler, "Session 15,
optimise"): rows for session 14's leftovers and the fresh sample's survivors.  The rows are
`Row`s of test_compiler_tables_passes (the values after the scans worked out by hand, held
with the pass alone, with none and with every pass, the NJ time charged the same).
"""

from __future__ import annotations

import pytest

from test_compiler_tables_passes import Row, check, main

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


@pytest.mark.parametrize("r", ROWS, ids=lambda r: r.id)
def test_row(r: Row):
    check(r)
