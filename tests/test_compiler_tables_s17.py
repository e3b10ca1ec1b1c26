"""More rows of the compiler's tables (issue 16, session 17): the survivors of seeds 450 and 460
(st_runtime/compiler/, drawn at 62bbc63 in session 16) that its runs had not reached, run to
their end here (docs/mutation.md, "Session 17, seeds 450 and 460 completed").

As in tests/test_compiler_tables_core.py: one row per behaviour, checked in full with `==`;
expected values from IEC 61131-3, OMRON's manuals as docs/nj501.md cites them and hand
calculation, never from running the code under test; every row with every optimisation pass
and with none.
"""

from __future__ import annotations

import pytest

from test_compiler_tables_core_s14 import PASSES, run      # (Main after its scans, and its faults)


# ============================ exprs.py: a narrower sum on the left of a wider one

NARROWER_ON_THE_LEFT = """PROGRAM Main
VAR d0 : DINT := 0; i1 : INT := 32767; i2 : INT := 1; d : DINT; END_VAR
d := (i1 + i2) + d0;
END_PROGRAM
"""


@PASSES
@pytest.mark.parametrize("dialect, d", [("nj", -32768), ("iec", 32768)])
def test_a_narrower_sum_on_the_left_of_a_wider_one_overflows_in_its_own_type(dialect: str, d: int, optimise):
    # W501 6-5-3 "Implicit Casts" (docs/nj501.md, "Integer overflow inside an expression"):
    # under nj an addition is evaluated in the type of its highest-ranked operand; i1 + i2 is
    # INT + INT, and 32767 + 1 overflows there to -32768 before the DINT addition takes it
    # (-32768 + 0). Under iec the intermediate stays exact: 32768. The same sum on the right
    # is test_compiler_mutation_s9.py's row; the left operand is settled on its own.
    _, main, faults = run(NARROWER_ON_THE_LEFT, optimise, dialect=dialect)
    assert (main.v_D, faults) == (d, [])
