"""Compiler behaviours that mutants left open by sessions 8 and 9, and survivors of the mutation
sample of seed 25, pinned down (issue 16, session 10; docs/mutation.md, "st_runtime/compiler/",
"Session 10").

Each test loads ST through the public entry point and takes its expected values from
IEC 61131-3, the CODESYS rules the codesys dialect follows, OMRON's manuals as docs/nj501.md
cites them, or a hand calculation stated beside it.
"""

from __future__ import annotations

import pytest

from test_compiler_mutants import run


# ------------------------------------- a METHOD whose whole body reads its FB's array

METHOD_OVER_FB_ARRAY = """
FUNCTION_BLOCK Acc
VAR a : ARRAY[1..8] OF REAL := [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0]; END_VAR
METHOD Sum : REAL
VAR s : REAL; t : REAL; END_VAR
s := a[1] + a[2] + a[3] + a[4];
t := a[5] + a[6] + a[7] + a[8];
s := s + t + a[1] * a[2];
Sum := s;
END_METHOD
END_FUNCTION_BLOCK
PROGRAM Main
VAR f : Acc; r : REAL; END_VAR
r := f.Sum();
END_PROGRAM"""


@pytest.mark.parametrize("dialect", ["iec", "codesys"])
def test_a_method_reading_its_blocks_array_at_literal_indices(dialect: str):
    # A METHOD reads its FB's variables through the instance (IEC 61131-3 6.6.5); a body of
    # eight element reads at literal indices that stores only the METHOD's own locals is
    # compiled as one region whose reads are looked up by name afterwards.
    # 1 + 2 + ... + 8 = 36, and 1 * 2 = 2: Sum = 38.
    main, plc = run(METHOD_OVER_FB_ARRAY, dialect=dialect)
    assert (main["r"], plc.faults) == (38.0, [])
