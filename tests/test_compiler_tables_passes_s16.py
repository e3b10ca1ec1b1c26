"""The optimiser passes' table, session 16 (issue 16; docs/mutation.md, compiler, "Session 16,
optimise"): rows for the survivors of the fresh sample, seed 450.  The rows are `Row`s of
test_compiler_tables_passes (the values after the scans worked out by hand, held with the
pass alone, with none and with every pass, the NJ time charged the same).
"""

from __future__ import annotations

import pytest

from test_compiler_tables_passes import Row, check, main

ROWS: list[Row] = []


def row(*args, **kwargs) -> None:
    ROWS.append(Row(*args, **kwargs))


# ---------------------------------------------------------------------------------- ranges
# A store into a bit of an integer local (`w.%X0 := FALSE`) changes the local: its root is
# not followed (ranges.py: "never ... the root of an element/member/bit store").  w := 1,
# then bit 0 cleared: w = 0, outside ARRAY[1..4]: F-INDEX at the read (line 5), the
# statement abandoned (F keeps 0).  Unchecked, arr[w] would read the list's element -1 (40).
BIT_STORE = """FUNCTION F : INT
VAR w : INT; arr : ARRAY[1..4] OF INT := [10, 20, 30, 40]; END_VAR
w := 1;
w.%X0 := FALSE;
F := arr[w];
END_FUNCTION"""
row("ranges", "a local whose bit is stored is not followed", main("y : INT;", "y := F();", before=BIT_STORE),
    {"y": 0}, faults=[("F-INDEX", 5, 1)])


@pytest.mark.parametrize("r", ROWS, ids=lambda r: r.id)
def test_row(r: Row):
    check(r)
