"""More rows of the core files' tables (issue 16, session 16): the survivors of the fresh
seed-460 sample in st_runtime/compiler/ outside optimise/ (docs/mutation.md, "Session 16, the
core files").

As in tests/test_compiler_tables_core.py: one row per behaviour, checked in full with `==`;
expected values from IEC 61131-3, OMRON's manuals as docs/nj501.md cites them and hand
calculation, never from running the code under test; every row with every optimisation pass
and with none.
"""

from __future__ import annotations

from test_compiler_tables_core import PS_PER_UNIT, program, scan_times


# ============================ cost.py: a structure of no members is assigned as one value

def test_an_assignment_of_a_structure_without_members_costs_one_load_and_one_store():
    # docs/nj501.md "What a scan costs": an array or structure moves element by element (2 per
    # element), anything else is its value's load (1) and a store (1). A STRUCT without
    # members (IEC 61131-3's grammar, Annex A Struct_Decl, asks for one at least; the checker
    # accepts none) has no element to move: the assignment is charged as one elementary
    # assignment, 2 units, not 2 * 2.
    src = "TYPE Empty : STRUCT END_STRUCT; END_TYPE\n" + program("e1, e2 : Empty;", "e1 := e2;")
    expected = ([], [2 * PS_PER_UNIT])
    assert scan_times(src, {}) == {"every pass": expected, "no pass": expected}
