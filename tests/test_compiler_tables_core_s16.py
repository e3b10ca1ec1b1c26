"""More rows of the core files' tables (issue 16, session 16): the survivors of the fresh
seed-460 sample in st_runtime/compiler/ outside optimise/ (docs/mutation.md, "Session 16, the
core files").

As in tests/test_compiler_tables_core.py: one row per behaviour, checked in full with `==`;
expected values from IEC 61131-3, OMRON's manuals as docs/nj501.md cites them and hand
calculation, never from running the code under test; every row with every optimisation pass
and with none.
"""

from __future__ import annotations

import pytest

from test_compiler_tables_core import PS_PER_UNIT, line_of, program, scan_times
from test_compiler_tables_core_s14 import PASSES, run      # (Main after its scans, and its faults)


# ============================ cost.py: a structure of no members (no row since session 17)
# `elements`' floor for a structure (`sum(...) or 1`) had a row here, an assignment of a STRUCT
# without members charged as one elementary assignment (2 units). IEC 61131-3's grammar (Annex
# A, Struct_Decl) asks for one member at least, and the checker refuses one without members
# under every dialect since session 17 (E-DECL-018, tests/test_checker_gaps_s17.py); every
# member type counts one element at least, so the floor is never reached and its mutant
# `cost.elements_8` is registered equivalent (tools/mutation_equivalent.toml, docs/mutation.md).


# ============================ cost.py: a structure holding a function block instance
# The checker accepts an FB instance as a STRUCT member (under every dialect), and assigning
# the structure copies the instance: `elements` counts its variables (docs/nj501.md "What a
# scan costs": 2 units per element moved), an FB without variables as one value. These rows
# kill `cost.elements_9` and `_12`, registered equivalent since seeds 16 and 21 on the ground
# that an FB instance is never copied by value (session 17: that ground does not hold here).

FB_OF_TWO = "FUNCTION_BLOCK Two\nVAR a, b : INT; END_VAR\nEND_FUNCTION_BLOCK\n"
FB_OF_NONE = "FUNCTION_BLOCK Nothing\nEND_FUNCTION_BLOCK\n"


@pytest.mark.parametrize("fb, name, moved", [(FB_OF_TWO, "Two", 2), (FB_OF_NONE, "Nothing", 1)],
                         ids=["two_variables", "no_variables"])
def test_an_assignment_of_a_structure_holding_an_fb_instance_moves_its_variables(fb, name, moved):
    src = (fb + f"TYPE Holder : STRUCT f : {name}; END_STRUCT; END_TYPE\n"
           + program("h1, h2 : Holder;", "h1 := h2;"))
    expected = ([], [2 * moved * PS_PER_UNIT])
    assert scan_times(src, {}) == {"every pass": expected, "no pass": expected}


# ============================ statements.py: a CASE reached by halves keeps what its clauses assign

CASE_OF_SIX = """FUNCTION Pick : INT
VAR_INPUT sel : INT; END_VAR
VAR x : INT; a : ARRAY[1..10] OF INT := [11, 12, 13, 14, 15, 16, 17, 18, 19, 20]; END_VAR
x := 1;
CASE sel OF
1: x := 2;
2: x := 3;
3: x := 4;
4: x := 5;
5: x := 6;
6: x := 20;
END_CASE;
Pick := a[x];
END_FUNCTION
PROGRAM Main
VAR sel : INT; r : INT := -1; END_VAR
r := Pick(sel);
END_PROGRAM
"""


@PASSES
@pytest.mark.parametrize("sel, r, faults", [(3, 14, []), (9, 11, []), (5, 16, []),
                                            (6, 0, [("F-INDEX", line_of(CASE_OF_SIX, "Pick := a[x]"), 1)])])
def test_a_case_of_many_clauses_leaves_each_clauses_assignment_after_it(sel: int, r: int, faults: list, optimise):
    # Six clauses and no ELSE: the halves pass reaches the clause by `sel < pivot` tests; the
    # clause taken assigns x and the read after the CASE sees it (IEC 61131-3 7.3.3.3.3): sel 3
    # gives x 4 and a[4] = 14, sel 9 no clause (x stays 1, a[1] = 11), sel 5 a[6] = 16; sel 6
    # gives x 20, outside a's 1..10: F-INDEX, the statement abandoned (README, "a runtime fault
    # abandons the faulting statement"), so Pick keeps INT's initial 0, which Main stores.
    _, main, got = run(CASE_OF_SIX, optimise, inputs={"sel": sel})
    assert (main.v_R, got) == (r, faults)


# ============================ __init__.py: a VAR_TEMP is no variable of its instance

TEMPS = """FUNCTION_BLOCK Acc
VAR_INPUT x : INT; END_VAR
VAR_OUTPUT total : INT; END_VAR
VAR_TEMP twice : INT; END_VAR
twice := x * 2;
total := total + twice;
END_FUNCTION_BLOCK
PROGRAM Main
VAR acc : Acc; n : INT; END_VAR
VAR_TEMP t : INT; END_VAR
t := 3;
acc(x := t);
n := acc.total;
END_PROGRAM
"""


def test_a_var_temp_is_not_a_variable_of_its_program_or_fb_instance():
    # IEC 61131-3 VAR_TEMP: storage for one execution of the POU's body, not part of its
    # instance: the instance's layout (`Instance.layout`, what paths are read through) holds
    # the other variables only, and a path to the temp names no variable. Two scans: acc.total
    # 6, then 12; n as acc.total.
    from st_runtime import api

    plc = api.load_text(TEMPS).controller()
    main = plc.add_program("Main")
    plc.run(2)
    assert (sorted(main.layout), sorted(type(main.raw("acc"))._st_vars), main["n"]) == \
        (["ACC", "N"], ["TOTAL", "X"], 12)
    with pytest.raises(KeyError, match="no variable 't'"):
        main["t"]
