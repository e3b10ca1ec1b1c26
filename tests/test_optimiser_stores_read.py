"""The `stores_read` pass (st_runtime/compiler/optimise/reuse.py `stored`, with `reuse`): after
`X[k] := v`, v a value of `reuse` stored as it is into an own array at a literal index, a read
of `X[k]` is that value while neither X nor what v reads changes (SP_InverseKinematics'
`Position[Leg]`, stored, then read by the finite and stroke tests).  The element holds that
very float, so results, faults, instance states and the NJ time are equal bit for bit with
the pass on and off; a store into the array, a value that read the array, a REAL store
(rounded) and a call that may change the array end it.
"""

from __future__ import annotations

import math
from dataclasses import replace

import pytest

from st_runtime import api
from st_runtime.compiler import Optimisations, compile_program
from st_runtime.controller import Controller
from test_optimiser_equivalence import compiled_lines, run_both, stopped_runs

ON = Optimisations()
WITHOUT = replace(ON, stores_read=False)

PROBE = """FUNCTION Bump : BOOL
VAR_IN_OUT A : ARRAY[0..3] OF LREAL; END_VAR
A[0] := A[0] + 100.0;
Bump := TRUE;
END_FUNCTION
FUNCTION_BLOCK Probe
VAR_INPUT X : LREAL; END_VAR
VAR_OUTPUT Finite, InRange : BOOL; Copy, Again, Shifted, After : LREAL; Narrow : REAL; END_VAR
VAR P : ARRAY[0..3] OF LREAL; R : ARRAY[0..1] OF REAL; Done : BOOL; END_VAR
P[0] := X * 2.0 - 1.0;                      (* stored as it is: read back by name *)
Finite := P[0] - P[0] = 0.0;
InRange := P[0] >= 0.0 AND P[0] <= 600.0;
P[1] := P[0] + 1.0;
P[0] := P[1] * 3.0;                         (* stored again: the reads see the new value *)
Copy := P[0] + P[0];
P[2] := P[2] + X;                           (* reads the array it stores into *)
Again := P[2] * 2.0 + P[2];
R[0] := LREAL_TO_REAL(X * 0.5);             (* REAL: stored rounded *)
Narrow := R[0] + R[0];
Shifted := P[1] + P[1];
Done := Bump(A := P);                       (* P[0] changed by the call *)
After := P[0] + P[0];
END_FUNCTION_BLOCK
PROGRAM Main
VAR Pr : Probe; N : INT; Zero : LREAL; Inputs : ARRAY[0..4] OF LREAL; Q : INT; K : INT; END_VAR
Inputs[0] := 0.75; Inputs[1] := 1.0E308; Inputs[2] := 1.0 / Zero; Inputs[3] := Zero / Zero; Inputs[4] := -3.5;
Pr(X := Inputs[N MOD 5]);
Q := 7 / K;
N := N + 1;
END_PROGRAM
"""


def _program():
    return api.load_text(PROBE).program


def test_a_stored_value_is_read_back_by_name():
    lines = compiled_lines(_program(), "PROBE", ON)
    plain = compiled_lines(_program(), "PROBE", WITHOUT)
    at = lines.index("v_P[0] = _c1")
    assert lines[at - 1] == "_c1 = ((self.v_X * 2.0) - 1.0)"
    assert lines[at + 1:at + 3] == ["self.v_FINITE = (True if ((_c1 - _c1) == 0.0) else False)",
                                    "self.v_INRANGE = (True if ((_c1 >= 0.0) and (_c1 <= 600.0)) else False)"]
    assert "self.v_COPY = (_c4 + _c4)" in lines             # the second store's value
    for element in ("v_P[2]", "v_R[0]", "v_P[1]", "v_P[0]"):   # ended: read again
        assert f" = {element}" in "\n".join(lines[at + 3:])
    assert "v_P[0] = ((self.v_X * 2.0) - 1.0)" in plain and "v_P[0] = _c" not in "\n".join(plain)


def _bits(x: float) -> str:
    return "nan" if math.isnan(x) else x.hex()


def test_the_values_are_those_worked_by_hand():
    controller = Controller(compile_program(_program(), optimise=ON))
    main = controller.add_program("Main")
    for n, x in enumerate([0.75, 1.0e308, math.inf, math.nan, -3.5] * 2):
        controller.run(1)
        p0 = x * 2.0 - 1.0
        p1 = p0 + 1.0
        probe = main.v_PR
        assert (probe.v_FINITE, probe.v_INRANGE) == (p0 - p0 == 0.0, 0.0 <= p0 <= 600.0), x
        got = [probe.v_COPY, probe.v_SHIFTED, probe.v_AFTER]
        want = [p1 * 3.0 + p1 * 3.0, p1 + p1, (p1 * 3.0 + 100.0) * 2.0]
        assert list(map(_bits, got)) == list(map(_bits, want)), x


def test_the_scans_see_the_same_with_and_without_the_pass():
    off, alone = run_both(_program(), 10, optimise=Optimisations.only("reuse", "stores_read"))
    assert alone == off
    off, every = run_both(_program(), 10, optimise=ON)
    assert every == off
    assert {code for code, *_ in every[0]} >= {"F-DIV-ZERO"}


@pytest.mark.parametrize("budget_ns", [50, 100, 200, 1_000])
def test_f_period_lands_on_the_same_statement_with_the_pass(budget_ns):
    off, on = run_both(_program(), 6, budget_ns, optimise=ON)
    assert on == off


def test_the_time_charged_and_a_stopping_fault_are_the_same():
    outcomes = stopped_runs(_program(), 3, WITHOUT, ON)
    assert outcomes[0] == outcomes[1]
    assert outcomes[1][0][0][0] in ("F-DIV-ZERO", "F-CONVERT")
