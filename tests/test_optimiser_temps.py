"""The `temps` pass (st_runtime/compiler/statements.py `_statement_with_values`): the
temporaries of a statement are its own, so once it is compiled the next statement takes the
same numbers again, and a body has fewer local slots (each call creates and clears every one).
A loop's hoisted and per-iteration temps, which the statements after read, stay taken.  The
same Python runs with other names: results, faults (code, line, scan), instance states and
the NJ time are equal bit for bit with the pass on and off, also when F-PERIOD cuts a scan.
"""

from __future__ import annotations

import math
from dataclasses import replace

import pytest

from st_runtime import api
from st_runtime.compiler import Optimisations, compile_program
from st_runtime.controller import Controller
from test_optimiser_equivalence import run_both, stopped_runs

ON = Optimisations()
WITHOUT = replace(ON, temps=False)

SIBLINGS = """
PROGRAM Main
VAR
    N, I, J, K, Z, Count, Q : INT; X, Y, Angle, Sum, Grid : LREAL; Flag : BOOL;
    A : ARRAY[1..8] OF LREAL := [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0];
    M : ARRAY[1..3, 1..4] OF LREAL := [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0, 11.0, 12.0];
END_VAR
N := N + 1;
Count := N MOD 10;                              (* 9: A[9] faults in the checked copy *)
Angle := 0.5 * N;
X := SIN(Angle * 2.0) + COS(Angle * 3.0);       (* walrus temps of inline SIN/COS *)
IF 10 / (N - 3) > 1 THEN Flag := TRUE; ELSE Flag := FALSE; END_IF;  (* a guarded IF: N = 3 faults *)
Sum := 0.0;
FOR I := 1 TO Count DO                          (* the range and its end in temps *)
    Sum := Sum + A[I] * A[I];                   (* I - 1 once an iteration: a temp that stays *)
END_FOR;
Grid := 0.0;
K := 1 + N MOD 3;
FOR J := 1 TO 4 DO
    Grid := Grid + M[K, J];                     (* K's row hoisted before the loop *)
END_FOR;
Y := SIN(Sum * 0.001) - COS(Grid * 0.01);
CASE N MOD 4 OF
    0: Q := 10 / Z;                             (* F-DIV-ZERO every fourth scan *)
    1: Q := N;
    2, 3: Q := -N;
END_CASE;
END_PROGRAM
"""


def _program():
    return api.load_text(SIBLINGS).program


def _slots(optimise) -> int:
    return compile_program(_program(), optimise=optimise).namespace["_body_MAIN"].__code__.co_nlocals


def test_siblings_share_their_temps():
    source = compile_program(_program(), optimise=ON).python_sources["MAIN"]
    plain = compile_program(_program(), optimise=WITHOUT).python_sources["MAIN"]
    # (one slot each since session 19: `A[I] * A[I]` reads A[I] once, into a temp: reads.py)
    assert (_slots(ON), _slots(WITHOUT)) == (22, 26)
    # _t1: the walrus of SIN, the guarded IF's condition, then the FOR's range (from a table)
    assert [line.strip()[:12] for line in source.splitlines() if line.strip().startswith(("_t1 =", "self.v_X ="))] \
        == ["self.v_X = (", "_t1 = (_idiv", "_t1 = None", "_t1 = (_FROM", "_t1 = None"]
    assert "_t3 = (_idiv" in plain
    assert "_t6 = v_K * 4 - 5" in source and "_t7 := (v_SUM" in source   # hoisted: stays taken


def test_the_values_are_those_worked_by_hand():
    controller = Controller(compile_program(_program(), optimise=ON))
    main = controller.add_program("Main")
    for n in range(1, 13):
        controller.run(1)
        count = n % 10
        angle = 0.5 * n
        x = math.sin(angle * 2.0) + math.cos(angle * 3.0)
        total = sum(a * a for a in [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0][:min(count, 8)])
        row = 1 + n % 3
        grid = 0.0
        for j in range(4):
            grid += (row - 1) * 4.0 + j + 1.0
        assert main.v_X == x and main.v_GRID == grid, n
        if count <= 8:
            assert main.v_SUM == total and main.v_Y == math.sin(total * 0.001) - math.cos(grid * 0.01), n
    codes = [(f.code, f.scan) for f in controller.faults]
    assert ("F-DIV-ZERO", 3) in codes and ("F-INDEX", 9) in codes and ("F-DIV-ZERO", 4) in codes


def test_the_scans_see_the_same_with_and_without_the_pass():
    off, alone = run_both(_program(), 12, optimise=Optimisations.only("temps"))
    assert alone == off
    off, every = run_both(_program(), 12, optimise=ON)
    assert every == off


@pytest.mark.parametrize("budget_ns", [100, 300, 600, 1_000, 2_000])
def test_f_period_lands_on_the_same_statement_with_the_pass(budget_ns):
    off, on = run_both(_program(), 8, budget_ns, optimise=ON)
    assert on == off


def test_the_time_charged_and_a_stopping_fault_are_the_same():
    outcomes = stopped_runs(_program(), 4, WITHOUT, ON)
    assert outcomes[0] == outcomes[1]
    assert [(code, scan) for code, _, scan in outcomes[1][0]] == [("F-DIV-ZERO", 3)]


def test_a_per_iteration_temp_is_set_above_every_sibling_s_temps():
    """A loop body whose second statement checks an index with a walrus temp and whose third
    needs `I * 3` once an iteration: that value is set at the top of the body, before the
    second statement runs, so it takes a number no statement had (`lasting_temp`)."""
    from test_optimiser_ranges import VERSIONED

    source = compile_program(api.load_text(VERSIONED).program, optimise=ON).python_sources["MAIN"]
    top = [line.strip() for line in source.splitlines() if line.strip().endswith("= v_I * 3")]
    assert top and all(f"({name} := " not in source for name in (line.split(" = ")[0] for line in top))
    for only in (Optimisations.only("temps", "offsets", "ranges"), ON):
        off, on = run_both(api.load_text(VERSIONED).program, 13, optimise=only)
        assert on == off
