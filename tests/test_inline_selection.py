"""MIN and MAX compiled as Python's min/max of the arguments (Optimisations.inline), and
ATAN without a wrapper: the same values, bit for bit, as the library functions.

IEC 61131-3 (2013) table 33: MIN/MAX of two or more inputs of one type; with the
`inline` pass the call of the library's MIN(*values) (min of the tuple) goes, the
comparisons stay the same and in the same order (ties: the first input; a NaN
compares false, so where it stands decides, as in the library)."""

from __future__ import annotations

import math

from st_runtime import api
from st_runtime.compiler import Optimisations, compile_program
from st_runtime.controller import Controller

from test_optimiser_equivalence import run_both

PROGRAM = """
PROGRAM Main
VAR
    Nan : LREAL; Inf : LREAL := 1.0E308;
    A : LREAL; B : LREAL; C : LREAL; D : LREAL; E : LREAL; F : LREAL; G : LREAL; H : LREAL;
    I : DINT; J : DINT; T : TIME; U : LREAL; V : LREAL;
END_VAR
Inf := Inf * 10.0;
Nan := Inf - Inf;
A := MIN(0.0, -0.0);          (* a tie: the first input *)
B := MAX(-0.0, 0.0);
C := MIN(Nan, 1.0);            (* 1.0 < NaN is false: the first stays *)
D := MIN(1.0, Nan);
E := MAX(2.5, 7.0, -3.0);
F := MIN(2.5, 7.0, -3.0);
G := MIN(IN1 := 4.0, IN2 := 3.0);
H := MAX(Inf, 1.0);
I := MIN(3, -7);
J := MAX(3, -7, 12);
T := MIN(T#5s, T#2s);
U := ATAN(Inf);
V := ATAN(-2.0);
END_PROGRAM
"""


def _values(optimise):
    project = api.load_text(PROGRAM)
    compiled = compile_program(project.program, optimise=optimise)
    controller = Controller(compiled)
    main = controller.add_program("Main")
    controller.run(1)
    assert controller.faults == []
    return compiled, main


def test_min_and_max_are_python_builtins_with_the_pass():
    compiled, _ = _values(Optimisations())
    source = compiled.python_sources["MAIN"]
    assert "min(" in source and "max(" in source and "_sf_MIN" not in source
    plain, _ = _values(Optimisations.none())
    assert "_sf_MIN" in plain.python_sources["MAIN"]


def test_hand_values():
    _, main = _values(Optimisations())
    assert math.copysign(1.0, main.v_A) == 1.0 and math.copysign(1.0, main.v_B) == -1.0
    assert math.isnan(main.v_C) and main.v_D == 1.0
    assert (main.v_E, main.v_F, main.v_G, main.v_H) == (7.0, -3.0, 3.0, math.inf)
    assert (main.v_I, main.v_J, main.v_T) == (-7, 12, 2_000_000_000)
    assert main.v_U == math.pi / 2 and main.v_V == math.atan(-2.0)


def test_the_same_bits_with_and_without_the_pass():
    off, on = run_both(api.load_text(PROGRAM).program, 2)
    assert on == off
