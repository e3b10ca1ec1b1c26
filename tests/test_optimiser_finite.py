"""The `finite` pass (st_runtime/compiler/optimise/reuse.py `finite`): the finite test of
inline SIN, COS and TAN of a float local is a value of `reuse`, so SIN(X) and COS(X) of one
unchanged X test it once.  Nothing a program can see changes: results (NaN for an infinite
or NaN argument, IEC's SIN of the library), faults, instance states and the NJ time charged
are equal bit for bit with the pass on and off, also when F-PERIOD cuts the scan.
"""

from __future__ import annotations

import math
import re
from dataclasses import replace

import pytest

from st_runtime import api
from st_runtime.compiler import Optimisations, compile_program
from st_runtime.controller import Controller
from test_optimiser_equivalence import run_both, same_alone_and_with_all, stopped_runs

ON = Optimisations()
WITHOUT = replace(ON, finite=False)

ANGLES = """
PROGRAM Main
VAR
    N : INT; Zero : LREAL; Inputs : ARRAY[0..5] OF LREAL;
    S, C, T, S2, C2 : LREAL; Q : INT; K : INT;
END_VAR
VAR_TEMP X : LREAL; END_VAR
Inputs[0] := 0.5; Inputs[1] := -2.0; Inputs[2] := 1.0E300;
Inputs[3] := 1.0 / Zero; Inputs[4] := -1.0 / Zero; Inputs[5] := Zero / Zero;
X := Inputs[N MOD 6];
S := SIN(X);
C := COS(X);
T := TAN(X);
X := X * 0.5;                                   (* X changed: tested again *)
S2 := SIN(X);
C2 := COS(X);
Q := 7 / K;                                     (* F-DIV-ZERO every scan *)
N := N + 1;
END_PROGRAM
"""


def _program():
    return api.load_text(ANGLES).program


def _expected(x: float, f) -> float:
    return f(x) if math.isfinite(x) else math.nan


def _bits(x: float) -> str:
    return "nan" if math.isnan(x) else x.hex()


def test_sin_and_cos_of_one_local_test_it_once():
    source = compile_program(_program(), optimise=ON).python_sources["MAIN"]
    plain = compile_program(_program(), optimise=WITHOUT).python_sources["MAIN"]
    assert len(re.findall(r"_c\d+ = \(True if \(v_X < 1e309 and v_X > -1e309\) else False\)", source)) == 2     # X, then X * 0.5
    assert "_m_sin(v_X) if _c" in source and "_m_cos(v_X) if _c" in source and "_m_tan(v_X) if _c" in source
    assert "v_X < 1e309" not in plain and plain.count(":= v_X) < 1e309 and ") == 5


def test_the_values_are_the_library_s():
    """By hand: math's SIN/COS/TAN of a finite X, NaN of an infinite or NaN X."""
    controller = Controller(compile_program(_program(), optimise=ON))
    main = controller.add_program("Main")
    inputs = [0.5, -2.0, 1.0e300, math.inf, -math.inf, math.nan]
    for n in range(12):
        controller.run(1)
        x = inputs[n % 6]
        got = [main.v_S, main.v_C, main.v_T, main.v_S2, main.v_C2]
        want = [_expected(x, math.sin), _expected(x, math.cos), _expected(x, math.tan),
                _expected(x * 0.5, math.sin), _expected(x * 0.5, math.cos)]
        assert list(map(_bits, got)) == list(map(_bits, want)), x


def test_the_scans_see_the_same_with_and_without_the_pass():
    faults = same_alone_and_with_all(_program, 12, "finite")[0]
    assert {code for code, *_ in faults} == {"F-DIV-ZERO"}


@pytest.mark.parametrize("budget_ns", [200, 500, 900, 1_500])
def test_f_period_lands_on_the_same_statement_with_the_pass(budget_ns):
    off, on = run_both(_program(), 8, budget_ns, optimise=Optimisations.only("reuse", "finite"))
    assert on == off


def test_the_time_charged_and_a_stopping_fault_are_the_same():
    outcomes = stopped_runs(_program(), 3, WITHOUT, ON)
    assert outcomes[0] == outcomes[1]
    assert [(code, scan) for code, _, scan in outcomes[1][0]] == [("F-DIV-ZERO", 1)]


SLOTS = """
FUNCTION_BLOCK Tilt
VAR_INPUT Degrees : LREAL; END_VAR
VAR_OUTPUT CosA, SinA, Rotated : LREAL; END_VAR
VAR Alpha : LREAL; END_VAR
Alpha := Degrees * 0.5;                         (* three occurrences: a slot, not cached *)
CosA := COS(Alpha);
SinA := SIN(Alpha);
Rotated := CosA * 2.0 - SinA;
END_FUNCTION_BLOCK
PROGRAM Main
VAR T : Tilt; N : INT; Zero : LREAL; Inputs : ARRAY[0..5] OF LREAL; Q : INT; K : INT; END_VAR
Inputs[0] := 0.5; Inputs[1] := -2.0; Inputs[2] := 1.0E300;
Inputs[3] := 1.0 / Zero; Inputs[4] := -1.0 / Zero; Inputs[5] := Zero / Zero;
T(Degrees := Inputs[N MOD 6]);
Q := 7 / K;
N := N + 1;
END_PROGRAM
"""


def _slots():
    return api.load_text(SLOTS).program


def test_an_own_slot_is_tested_once_for_sin_and_cos():
    source = compile_program(_slots(), optimise=ON).python_sources["TILT"]
    plain = compile_program(_slots(), optimise=WITHOUT).python_sources["TILT"]
    assert len(re.findall(r"_c\d+ = \(True if \(self\.v_ALPHA < 1e309 and self\.v_ALPHA > -1e309\) else False\)", source)) == 1
    assert "_m_cos(self.v_ALPHA) if _c" in source and "_m_sin(self.v_ALPHA) if _c" in source
    assert "self.v_ALPHA < 1e309" not in plain and plain.count(":= self.v_ALPHA) < 1e309 and ") == 2


def test_the_slot_s_values_are_the_library_s():
    """By hand: COS and SIN of half the input when finite, NaN otherwise."""
    controller = Controller(compile_program(_slots(), optimise=ON))
    main = controller.add_program("Main")
    inputs = [0.5, -2.0, 1.0e300, math.inf, -math.inf, math.nan]
    for n in range(12):
        controller.run(1)
        x = inputs[n % 6] * 0.5
        c, s = _expected(x, math.cos), _expected(x, math.sin)
        assert list(map(_bits, (main.v_T.v_COSA, main.v_T.v_SINA, main.v_T.v_ROTATED))) == \
            list(map(_bits, (c, s, c * 2.0 - s))), x


def test_the_slot_scans_see_the_same_with_and_without_the_pass():
    off, on = run_both(_slots(), 12, optimise=Optimisations.only("reuse", "finite"))
    assert on == off
    assert {code for code, *_ in on[0]} == {"F-DIV-ZERO"}


@pytest.mark.parametrize("budget_ns", [50, 100, 150, 1_200])
def test_f_period_lands_on_the_same_statement_with_a_slot(budget_ns):
    off, on = run_both(_slots(), 8, budget_ns, optimise=ON)
    assert on == off


def test_the_finite_test_is_false_for_infinities_and_nan_only():
    """pysrc.finite_test, evaluated: False for +inf, -inf and NaN, True for every other float
    (the largest, the smallest subnormal, both zeros) and for ints, even one beyond the
    largest double (an int compares exactly with the infinity): what `x - x == 0.0` gave."""
    from st_runtime.compiler.pysrc import finite_test

    test = eval(f"lambda x: {finite_test('x', 'x')}")
    cases = [(math.inf, False), (-math.inf, False), (math.nan, False), (-math.nan, False),
             (0.0, True), (-0.0, True), (1.7976931348623157e308, True), (-1.7976931348623157e308, True),
             (5e-324, True), (-5e-324, True), (0, True), (-7, True), (10 ** 400, True), (-10 ** 400, True)]
    for x, finite in cases:
        assert test(x) is finite, x
