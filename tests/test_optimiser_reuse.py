"""The `reuse` pass (st_runtime/compiler/optimise/reuse.py): a float value computed again over
unchanged operands is set once and read by name, and nothing a program can see changes:
results, faults (code, file, line, column, scan) and instance states are equal bit for bit with
the pass on and off, also when F-PERIOD cuts the scan, a store changes an operand between two
uses, a loop would run a use after a store, or a call of ST code could change an operand.
"""

from __future__ import annotations

from dataclasses import replace

import pytest

from st_runtime import api
from st_runtime.compiler import Optimisations, compile_program
from st_runtime.controller import Controller
from test_optimiser_equivalence import compiled_lines, run_both, same_alone_and_with_all

ON = Optimisations()
WITHOUT = replace(ON, reuse=False)

LEGS = """
VAR_GLOBAL Offset : LREAL := 0.5; END_VAR
FUNCTION Bump : LREAL
VAR_INPUT X : LREAL; END_VAR
Offset := Offset + 1.0;
Bump := X;
END_FUNCTION
FUNCTION_BLOCK Legs
VAR_INPUT Pose : ARRAY[1..3] OF LREAL; END_VAR
VAR_OUTPUT Length : ARRAY[1..4] OF LREAL; Sums : ARRAY[1..3] OF LREAL; END_VAR
VAR
    Leg : INT; Z : LREAL; A, B, S, T : LREAL; K : INT; Arr : ARRAY[1..2] OF LREAL := [1.0, 2.0];
    W : ARRAY[1..3] OF LREAL;
END_VAR
W := Pose;
FOR Leg := 1 TO 4 DO                                     (* unrolled: Pose[3] + 10.0 - 2.0 once *)
    Z := Pose[3] + 10.0 - 2.0;
    Length[Leg] := SQRT(Pose[1] * Pose[1] + Z * Z) + INT_TO_LREAL(Leg);
END_FOR;
S := SIN(Pose[2]) * 2.0 + SIN(Pose[2]);                  (* one SIN *)
A := W[1] * 3.0;
W[1] := W[1] + 1.0;                                      (* a store between two uses *)
B := W[1] * 3.0;
T := 0.0;
FOR K := 1 TO 3 DO                                       (* Arr[1] * 2.0 before and in the loop *)
    T := T + Arr[1] * 2.0;
    Arr[1] := Arr[1] + 0.25;
END_FOR;
Sums[1] := A + B + T + Arr[1] * 2.0;
Sums[2] := Offset * 2.0 + Bump(Arr[2]) + Offset * 2.0;   (* a call changes Offset in between *)
IF Pose[2] > 0.5 THEN
    Sums[3] := Pose[2] * Pose[2];
ELSE
    Sums[3] := Pose[2] * Pose[2] + 1.0;
END_IF;
Sums[3] := Sums[3] + Pose[2] * Pose[2];
END_FUNCTION_BLOCK
PROGRAM Main
VAR L : Legs; N : INT; P : ARRAY[1..3] OF LREAL; END_VAR
N := N + 1;
P[1] := INT_TO_LREAL(N) * 0.1; P[2] := INT_TO_LREAL(N MOD 3) * 0.4; P[3] := 1.0 / INT_TO_LREAL(N MOD 2);
L(Pose := P);
END_PROGRAM
"""


def _program():
    return api.load_text(LEGS).program


def _lines(optimise):
    return compiled_lines(_program(), "LEGS", optimise)


def test_a_value_is_set_once_and_read_by_name():
    lines, plain = _lines(ON), _lines(WITHOUT)
    text = "\n".join(lines)
    z = [line for line in lines if line.startswith("v_Z = ") and line != "v_Z = self.v_Z"]
    assert len(z) == 4 and len(set(z)) == 1 and "+ 10.0" not in z[0]       # one name in each copy
    assert "= ((v_POSE[2] + 10.0) - 2.0)" in text                           # (not its parts)
    assert sum("(v_Z * v_Z)" in line for line in plain) == 4
    assert text.count("_m_sin(") == 1 and "\n".join(plain).count("_m_sin(") == 2
    # the store of W[1] ends its value: computed again after it
    a = next(line for line in lines if line.startswith("self.v_A = "))
    b = next(line for line in lines if line.startswith("self.v_B = "))
    assert a.endswith(" * 3.0)") and b == "self.v_B = (v_W[0] * 3.0)"
    # a call of ST code ends every value: Offset * 2.0 is computed on both sides of Bump
    sums2 = next(line for line in lines if line.startswith("v_SUMS[1] = "))
    assert sums2.count("(_G.v_OFFSET * 2.0)") == 2


def test_the_scans_see_the_same_with_and_without_the_pass():
    same_alone_and_with_all(_program, 9, "reuse")


def test_the_values_are_the_ones_worked_out_by_hand():
    """N = 1: Pose (0.1, 0.4, 1.0); a loop over Arr[1] = 1.0, 1.25, 1.5 (T = 7.5), then 1.75."""
    import math

    controller = Controller(compile_program(_program(), optimise=ON))
    main = controller.add_program("Main")
    controller.run(1)
    legs = main.v_L
    z = 1.0 + 10.0 - 2.0
    assert legs.v_LENGTH == [math.sqrt(0.1 * 0.1 + z * z) + k for k in (1.0, 2.0, 3.0, 4.0)]
    assert legs.v_S == math.sin(0.4) * 2.0 + math.sin(0.4)
    a, b, t = 0.1 * 3.0, (0.1 + 1.0) * 3.0, 1.0 * 2.0 + 1.25 * 2.0 + 1.5 * 2.0
    assert legs.v_SUMS[0] == a + b + t + 1.75 * 2.0
    assert legs.v_SUMS[1] == 0.5 * 2.0 + 2.0 + 1.5 * 2.0        # Offset 0.5, then 1.5 after Bump
    assert legs.v_SUMS[2] == (0.4 * 0.4 + 1.0) + 0.4 * 0.4     # Pose[2] 0.4: the ELSE branch


@pytest.mark.parametrize("budget_ns", [400, 1_000, 3_000, 8_000])
def test_f_period_lands_on_the_same_statement_with_the_pass(budget_ns):
    off, on = run_both(_program(), 4, budget_ns, optimise=Optimisations.only("reuse"))
    assert on == off


WHILE_LOOP = """
FUNCTION_BLOCK Climb
VAR_OUTPUT Steps : INT; Seen : LREAL; END_VAR
VAR X : LREAL; Y : LREAL; END_VAR
X := 0.0; Steps := 0;
WHILE X * 2.0 < 10.0 DO             (* the condition runs again after X changes *)
    Y := X * 2.0;
    Seen := Seen + Y;
    X := X + 1.0;
    Steps := Steps + 1;
END_WHILE;
Y := X * 2.0 + X * 2.0;
END_FUNCTION_BLOCK
PROGRAM Main
VAR C : Climb; END_VAR
C();
END_PROGRAM
"""


def test_a_while_condition_is_computed_each_time():
    """By hand: X = 0..4 pass X * 2.0 < 10.0, so 5 steps and Seen = 0 + 2 + 4 + 6 + 8 a call."""
    program = api.load_text(WHILE_LOOP).program
    controller = Controller(compile_program(program, optimise=ON))
    main = controller.add_program("Main")
    controller.run(2)
    assert (main.v_C.v_STEPS, main.v_C.v_SEEN, main.v_C.v_Y) == (5, 40.0, 20.0)
    same_alone_and_with_all(lambda: api.load_text(WHILE_LOOP).program, 3, "reuse")
