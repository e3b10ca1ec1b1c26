"""The `sets` pass (st_runtime/compiler/optimise/sets.py): a run of `X = c` in an OR chain is
`X in {...}`, a run of `X <> c` in an AND chain `X not in {...}`, and nothing a program can see
changes: results, faults (code, file, line, column, scan) and instance states are equal bit for
bit with the pass on and off, also when F-PERIOD cuts the scan.
"""

from __future__ import annotations

from dataclasses import replace

import pytest

from st_runtime import api
from st_runtime.compiler import Optimisations, compile_program
from st_runtime.controller import Controller
from test_optimiser_equivalence import run_both, same_alone_and_with_all

ON = Optimisations()
WITHOUT = replace(ON, sets=False)

STATES = """
TYPE Mode : (IDLE, RUN, HOLD, DONE); END_TYPE
VAR_GLOBAL Shared : DINT; END_VAR
PROGRAM Main
VAR
    N : INT; State : INT; M : Mode; W : WORD; R : LREAL; Flag : BOOL;
    Moving, Stopped, Other, Either, Named, Bits, Mixed, Real, Few : BOOL;
    Count : ARRAY[1..6] OF INT;
END_VAR
N := N + 1;
State := N MOD 7;
M := Mode#IDLE;
IF N MOD 4 = 1 THEN M := Mode#RUN; ELSIF N MOD 4 = 2 THEN M := Mode#DONE; END_IF;
Shared := Shared + 3;
W := INT_TO_WORD(3 + N MOD 3);
R := INT_TO_LREAL(N MOD 3);
Flag := N MOD 2 = 0;
Moving := State = 1 OR State = 2 OR State = 5;
Stopped := State <> 0 AND State <> 3 AND State <> 6;
Other := Flag OR State = 4 OR State = 6 OR Shared = 9;          (* a run between other operands *)
Either := Shared = 3 OR Shared = 12 OR Shared = 21;              (* a global *)
Named := M = Mode#RUN OR M = Mode#HOLD;                          (* an enumeration *)
Bits := W = WORD#16#0004 OR W = WORD#16#0005;
Mixed := State = 1 OR N = 3 OR State = 2;                        (* no run of one variable *)
Real := R = 1.0 OR R = 2.0;                                      (* LREAL: left as it was *)
Few := State = 2 OR State = 2;
IF State = 2 OR State = 3 THEN Count[1] := Count[1] + 1; END_IF;
IF Moving AND Stopped THEN Count[2] := Count[2] + 1; END_IF;
IF Other THEN Count[3] := Count[3] + 1; END_IF;
IF Either THEN Count[4] := Count[4] + 1; END_IF;
IF Named THEN Count[5] := Count[5] + 1; END_IF;
IF Bits OR Mixed OR Real OR Few THEN Count[6] := Count[6] + 1; END_IF;
END_PROGRAM
"""


def _program():
    return api.load_text(STATES).program


def test_runs_of_one_variable_become_membership_tests():
    source = compile_program(_program(), optimise=ON).python_sources["MAIN"]
    plain = compile_program(_program(), optimise=WITHOUT).python_sources["MAIN"]
    assert "(v_STATE in {1, 2, 5})" in source
    assert "(v_STATE not in {0, 3, 6})" in source
    assert "(v_STATE in {4, 6})" in source
    assert "(_G.v_SHARED in {3, 12, 21})" in source
    assert "(v_M in {1, 2})" in source                   # RUN and HOLD: 1 and 2
    assert "(self.v_W in {4, 5})" in source                 # a slot of the instance
    assert "(v_STATE in {2, 3})" in source
    assert "(v_STATE in {2, 2})" in source
    assert " in {" not in plain and " in (" not in plain.replace("_t", "")      # without the pass: the comparisons
    # (two comparisons of different variables: `or` by shortcut, not a membership test)
    assert "(self.v_R == 1.0)" in source and "(v_STATE == 1) or (v_N == 3)" in source


def test_a_scan_sees_the_same_values_with_and_without_the_pass():
    same_alone_and_with_all(_program, 14, "sets")


def test_the_tests_give_the_values_the_comparisons_give():
    """Scan by scan against the comparisons worked out by hand (N = 1..14)."""
    controller = Controller(compile_program(_program(), optimise=ON))
    main = controller.add_program("Main")
    for n in range(1, 15):
        controller.run(1)
        state, shared = n % 7, 3 * n
        assert main.v_MOVING == (state in (1, 2, 5))
        assert main.v_STOPPED == (state not in (0, 3, 6))
        assert main.v_OTHER == (n % 2 == 0 or state in (4, 6) or shared == 9)
        assert main.v_EITHER == (shared in (3, 12, 21))
        assert main.v_NAMED == (n % 4 == 1)
        assert main.v_BITS == (3 + n % 3 in (4, 5))
        assert main.v_FEW == (state == 2)


@pytest.mark.parametrize("budget_ns", [300, 1_000, 2_000, 4_000])
def test_f_period_lands_on_the_same_statement_with_the_pass(budget_ns):
    off, on = run_both(_program(), 4, budget_ns, optimise=Optimisations.only("sets"))
    assert on == off
