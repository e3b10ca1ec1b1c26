"""The `deferred` pass (st_runtime/compiler/optimise/aliases.py `drop_unread`, with `unused`):
the load of a cached variable that the body sets before it reads it is left out also when
budget checks come before the set, and made in each such check's branch, before `_overrun`.
Nothing a program can see changes: an overrun at the check stores back the value the
instance held (the load at entry would have read the same), and results, faults (code,
line, scan), instance states and the NJ time charged are equal bit for bit with the pass on
and off, F-PERIOD landing at the check or not.
"""

from __future__ import annotations

from dataclasses import replace

import pytest

from st_runtime import api
from st_runtime.compiler import Optimisations, compile_program
from st_runtime.controller import Controller
from test_optimiser_equivalence import compiled_lines, run_both, stopped_runs

ON = Optimisations()
WITHOUT = replace(ON, deferred=False)

LEGS = """
FUNCTION_BLOCK Legs
VAR_INPUT X : LREAL; END_VAR
VAR_OUTPUT Total : LREAL; END_VAR
VAR U, V, W : LREAL; Leg : INT; Scale : LREAL; Lengths : ARRAY[1..4] OF LREAL; END_VAR
Scale := X * 0.5;
FOR Leg := 1 TO 4 DO                            (* charged and checked before the copies *)
    U := Scale * 3.0 - X;
    V := U + Scale;
    W := V * U;
    Lengths[Leg] := W + U + V;
END_FOR;
Total := Lengths[1] + Lengths[4] + U + V + W;
END_FUNCTION_BLOCK
PROGRAM Main
VAR L, Other : Legs; N : INT; Q : INT; K : INT; END_VAR
N := N + 1;
IF N MOD 2 = 0 THEN
    Other(X := 1.0);                            (* spends what L's check then misses *)
END_IF;
L(X := 0.25 * N);
Q := 7 / K;                                     (* F-DIV-ZERO every scan it runs *)
END_PROGRAM
"""


def _program():
    return api.load_text(LEGS).program


def test_the_loads_move_into_the_check():
    """(`early` off: it leaves out Leg's load for its own reason, a store of its one set, which
    the last line checks; test_optimiser_early.py.)"""
    lines = compiled_lines(_program(), "LEGS", replace(ON, early=False))
    plain = compiled_lines(_program(), "LEGS", replace(WITHOUT, early=False))
    check = next(line for line in lines if line.startswith("if _ctx.budget < _spent:"))
    assert check.startswith("if _ctx.budget < _spent: v_U = self.v_U; v_V = self.v_V; v_W = self.v_W; _overrun(")
    assert not {"v_U = self.v_U", "v_V = self.v_V", "v_W = self.v_W"} & set(lines)
    assert {"v_U = self.v_U", "v_V = self.v_V", "v_W = self.v_W", "v_LEG = self.v_LEG"} <= set(plain)
    assert "v_LEG = self.v_LEG" in lines        # (set after a store into an array: stays)
    assert "v_SCALE = self.v_SCALE" not in plain + lines     # (set before the check: never loaded)
    assert "self.v_LEG = v_LEG = 5" in compiled_lines(_program(), "LEGS", ON)


def test_an_overrun_at_the_check_keeps_what_the_instance_held():
    """By hand: at 150 ns, L's check fails on even scans (Other spent the time), so L keeps
    the U, V and W of the odd scan before: U = 0.25 N (0.5 * 3 - 1), V = U + 0.125 N."""
    controller = Controller(compile_program(_program(), optimise=ON), time_limit_ns=150)
    main = controller.add_program("Main")
    for n in range(1, 9):
        controller.run(1)
        held = n if n % 2 else n - 1
        u = 0.25 * held * 0.5 * 3.0 - 0.25 * held
        v = u + 0.25 * held * 0.5
        assert (main.v_L.v_U, main.v_L.v_V, main.v_L.v_W) == (u, v, v * u), n
    periods = [(f.line, f.scan) for f in controller.faults if f.code == "F-PERIOD"]
    assert periods == [(7, scan) for scan in (2, 4, 6, 8)]      # the FOR's check, in Legs


@pytest.mark.parametrize("budget_ns", [60, 100, 150, 175, 1_000])
def test_f_period_lands_on_the_same_statement_with_the_pass(budget_ns):
    off, on = run_both(_program(), 8, budget_ns, optimise=Optimisations.only("unused", "deferred"))
    assert on == off
    off, every = run_both(_program(), 8, budget_ns, optimise=ON)
    assert every == off


def test_the_time_charged_and_a_stopping_fault_are_the_same():
    outcomes = stopped_runs(_program(), 3, WITHOUT, ON)
    assert outcomes[0] == outcomes[1]
    assert [(code, scan) for code, _, scan in outcomes[1][0]] == [("F-DIV-ZERO", 1)]


TRIG = """
FUNCTION_BLOCK Turn
VAR_INPUT A : LREAL; END_VAR
VAR_OUTPUT X : LREAL; END_VAR
VAR C, S : LREAL; END_VAR
C := COS(A * 0.5);                              (* inline COS with its finite test *)
S := SIN(A * 0.5);
X := C * S + C * C + S * S + C - S + C * 2.0 + S * 3.0;      (* read often: cached in locals *)
X := X + C * S + C + S;
END_FUNCTION_BLOCK
PROGRAM Main
VAR T : Turn; N : INT; END_VAR
N := N + 1;
T(A := INT_TO_LREAL(N));
END_PROGRAM
"""


def test_a_body_that_opens_with_inline_trig_leaves_the_loads_out():
    """`drop_unread` reads an inline SIN/COS with its finite test (pysrc.finite_test) as the
    argument it tests: S is set before anything reads it, so it is not loaded (when the
    pattern missed the test's text, SP_Jacobian loaded 24 such variables again)."""
    lines = compiled_lines(api.load_text(TRIG).program, "TURN", ON)
    assert "v_S = self.v_S" not in lines
    assert any("< 1e309 and" in line and "_m_cos(" in line for line in lines)
    off, on = run_both(api.load_text(TRIG).program, 5)
    assert on == off
