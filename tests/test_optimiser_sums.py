"""`sums` (st_runtime/compiler/optimise/sums.py): a run of finite tests folded into a test of their sum.

Each program runs with the pass on and off: the same results, faults (code, POU, line, column,
scan), arrays and NJ time per scan, and the values by hand.  The cases a wrong fold gets
wrong: a non-finite element at each position (the flag and the charge of the one test that
fires), two of them (two charges), finite elements whose sum overflows (no test fires), an
element stored after its test, the same list reached through two in-outs, a call between the
tests, the flag read between them.
"""

from __future__ import annotations

import math
from dataclasses import replace

import pytest

from st_runtime.api import load_text
from st_runtime.compiler import Optimisations, compile_program
from st_runtime.compiler.optimise import sums

from optimiser_helpers import run_main

ON = Optimisations()
OFF = replace(ON, sums=False)
BIG = "1.7976931348623157E308"

# SP_ForwardKinematics' shape: each row's residual F[Row] computed and tested, then the row's
# three elements of J tested, all setting one flag; then an integer division (F-DIV-ZERO on
# line 20 when Den = 0).
CHECK = f"""
PROGRAM Main
VAR
    J : ARRAY[1..3, 1..3] OF LREAL := [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0];
    Q : ARRAY[1..3] OF LREAL := [1.0, 2.0, 3.0];
    F : ARRAY[1..3] OF LREAL;
    AllFinite : BOOL;
    Row, Column : INT;
    Den : DINT := 4;
    N : DINT;
END_VAR
AllFinite := TRUE;
FOR Row := 1 TO 3 DO
    F[Row] := Q[Row] * 2.0 - 1.0;
    IF NOT (ABS(F[Row]) <= {BIG}) THEN AllFinite := FALSE; END_IF;
    FOR Column := 1 TO 3 DO
        IF NOT (ABS(J[Row, Column]) <= {BIG}) THEN AllFinite := FALSE; END_IF;
    END_FOR;
END_FOR;
N := 100 / Den;
END_PROGRAM
"""

# A 4x4 V tested element by element, with `{between}` after each test: a statement the tests
# may not move past (a store into the element tested, a call that stores into it, a read of
# the flag) or none.  Both tests its in-out A and stores into its in-out B, which Main passes
# W for both; Only tests A alone (3x4: fewer accesses than `scalars` takes into locals).
BETWEEN = f"""
FUNCTION Zero : BOOL
VAR_IN_OUT A : ARRAY[1..4, 1..4] OF LREAL; END_VAR
VAR_INPUT R, C : INT; END_VAR
A[R, C] := 0.0;
Zero := TRUE;
END_FUNCTION

FUNCTION Both : BOOL
VAR_IN_OUT A : ARRAY[1..3, 1..4] OF LREAL; B : ARRAY[1..3, 1..4] OF LREAL; END_VAR
VAR R, C : INT; Ok : BOOL; END_VAR
Ok := TRUE;
FOR R := 1 TO 3 DO
    FOR C := 1 TO 4 DO
        IF NOT (ABS(A[R, C]) <= {BIG}) THEN Ok := FALSE; END_IF;
        B[R, C] := 0.0;
    END_FOR;
END_FOR;
Both := Ok;
END_FUNCTION

FUNCTION Only : BOOL
VAR_IN_OUT A : ARRAY[1..3, 1..4] OF LREAL; END_VAR
VAR R, C : INT; Ok : BOOL; END_VAR
Ok := TRUE;
FOR R := 1 TO 3 DO
    FOR C := 1 TO 4 DO
        IF NOT (ABS(A[R, C]) <= {BIG}) THEN Ok := FALSE; END_IF;
    END_FOR;
END_FOR;
Only := Ok;
END_FUNCTION

PROGRAM Main
VAR
    V : ARRAY[1..4, 1..4] OF LREAL := [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0,
                                       9.0, 10.0, 11.0, 12.0, 13.0, 14.0, 15.0, 16.0];
    W : ARRAY[1..3, 1..4] OF LREAL;
    Seen : ARRAY[1..4, 1..4] OF BOOL;
    Ok, Called, Fine, Aliased : BOOL;
    R, C : INT;
END_VAR
Ok := TRUE;
FOR R := 1 TO 4 DO
    FOR C := 1 TO 4 DO
        IF NOT (ABS(V[R, C]) <= {BIG}) THEN Ok := FALSE; END_IF;
        {{between}}
    END_FOR;
END_FOR;
Fine := Only(A := W);
Aliased := Both(A := W, B := W);
END_PROGRAM
"""


def _run(source: str, optimise: Optimisations, inputs: dict, outputs: tuple[str, ...], stop: bool = False):
    return run_main(source, optimise, inputs, outputs, stop)


def _same(source: str, inputs: dict, outputs: tuple[str, ...], stop: bool = False):
    on, off = (_run(source, o, inputs, outputs, stop) for o in (ON, OFF))
    assert _bits(on) == _bits(off)
    return on


def _bits(result):
    """`result` with each float as its repr (a NaN equal to a NaN, -0.0 apart from 0.0)."""
    if isinstance(result, float):
        return repr(result)
    if isinstance(result, (list, tuple)):
        return [_bits(item) for item in result]
    return result


def _matrix(bad: dict[int, float]) -> list[list[float]]:
    """J's initial values with the flat positions (0..8) of `bad` replaced."""
    flat = [bad.get(k, float(k + 1)) for k in range(9)]
    return [flat[0:3], flat[3:6], flat[6:9]]


def _check(inputs: dict, stop: bool = False):
    return _same(CHECK, inputs, ("AllFinite", "F", "N"), stop)


def test_the_fast_copy_folds_the_twelve_tests():
    """The pass applies (what the other tests of CHECK run is the folded code); off, no fold."""
    program = load_text(CHECK, "t.st").program
    fast = compile_program(program, optimise=ON).python_sources["MAIN"]
    assert "_sum(v_J, _sum(v_F, 0.0))" in fast
    assert "_sum(" not in compile_program(program, optimise=OFF).python_sources["MAIN"]


def test_every_element_finite():
    # by hand: F = 2Q - 1 = [1, 3, 5]; no test fires; N = 100 / 4
    (ok, f, n), faults, times = _check({})
    assert (ok, f, n, faults) == (True, [1.0, 3.0, 5.0], 25, [])


@pytest.mark.parametrize("value", [math.inf, -math.inf, math.nan])
@pytest.mark.parametrize("position", range(9))
def test_a_non_finite_element_of_j_at_each_position(position, value):
    # by hand: the one test of that element fires: AllFinite FALSE, one block charged more
    (ok, f, n), faults, times = _check({"J": _matrix({position: value})})
    assert (ok, f, n, faults) == (False, [1.0, 3.0, 5.0], 25, [])
    assert times[0] > _check({})[2][0]


@pytest.mark.parametrize("row", range(3))
def test_a_non_finite_residual_in_each_row(row):
    q = [1.0, 2.0, 3.0]
    q[row] = math.inf               # F[row] = 2 inf - 1 = inf
    (ok, f, n), faults, times = _check({"Q": q})
    assert ok is False and f[row] == math.inf and n == 25 and faults == []


def test_each_test_that_fires_charges_its_block():
    # one, two and three elements not finite: each fired test adds the same block's time
    none = _check({})[2][0]
    one = _check({"J": _matrix({4: math.nan})})[2][0]
    two = _check({"J": _matrix({4: math.nan, 8: math.inf})})[2][0]
    three = _check({"J": _matrix({0: -math.inf, 4: math.nan, 8: math.inf})})[2][0]
    assert one - none == two - one == three - two > 0


def test_finite_elements_whose_sum_overflows():
    # by hand: 9 x 1e308 overflows the sum to inf, so the tests run, and none fires
    (ok, f, n), faults, times = _check({"J": [[1e308] * 3] * 3})
    assert (ok, f, n, faults) == (True, [1.0, 3.0, 5.0], 25, [])
    assert times == _check({})[2]


@pytest.mark.parametrize("stop", [False, True])
def test_a_fault_after_the_tests_lands_on_its_line(stop):
    # Den = 0: F-DIV-ZERO on line 20 (`N := 100 / Den`), after the tests set AllFinite FALSE
    (ok, f, n), faults, _ = _check({"J": _matrix({2: math.inf}), "Den": 0}, stop)
    assert (ok, f, n) == (False, [1.0, 3.0, 5.0], 0)
    assert [(code, line) for code, _, line, _, _ in faults] == [("F-DIV-ZERO", 20)]


def _fast(source: str, pou: str) -> str:
    """The fast copy of `pou`'s body (fastpath.py): the code before the exact copy's `else:`."""
    code = compile_program(load_text(source, "t.st").program, optimise=ON).python_sources[pou]
    assert "_ctx.budget >= " in code
    return code.split("\n        else:\n", 1)[0]


def _matrix4(value: float, rows: int = 4) -> list[list[float]]:
    """V's initial values (W's: three rows) with the element [1, 3] set to `value`."""
    matrix = [[float(4 * r + c + 1) for c in range(4)] for r in range(rows)]
    matrix[0][2] = value
    return matrix


def test_the_tests_fold_with_nothing_between():
    source = BETWEEN.format(between="")
    assert "_sum(v_V, 0.0)" in _fast(source, "MAIN") and "_sum(v_A, 0.0)" in _fast(source, "ONLY")
    (ok, v, fine), faults, _ = _same(source, {"V": _matrix4(math.inf), "W": _matrix4(math.inf, 3)},
                                     ("Ok", "V", "Fine"))
    assert (ok, v, fine, faults) == (False, _matrix4(math.inf), False, [])


@pytest.mark.parametrize("between, seen", [
    ("V[R, C] := 0.0;", [[False] * 4] * 4),                    # the element tested is set after
    ("Called := Zero(A := V, R := R, C := C);", [[False] * 4] * 4),   # a call sets it
    ("Seen[R, C] := Ok;", [[True, True, False, False]] + [[False] * 4] * 3),  # the flag read
])
def test_the_tests_stay_where_a_statement_between_changes_what_they_see(between, seen):
    """No fold where a statement between the tests stores the element, calls code or reads the
    flag: the tests run as written.  By hand: V[1, 3] is infinite when its test reads it."""
    source = BETWEEN.format(between=between)
    assert "_sum(" not in _fast(source, "MAIN")
    (ok, v, flags), faults, _ = _same(source, {"V": _matrix4(math.inf)}, ("Ok", "V", "Seen"))
    assert ok is False and faults == [] and flags == seen
    assert v == ([[0.0] * 4] * 4 if "Seen" not in between else _matrix4(math.inf))


def test_an_in_out_that_may_be_the_stored_one_keeps_its_tests():
    # Both(A := W, B := W): B[R, C] := 0.0 after A[R, C]'s test sets the element tested; by
    # hand, A[1, 3] is infinite when its test reads it, so Both is FALSE and W ends all zero
    source = BETWEEN.format(between="")
    assert "_sum(" not in _fast(source, "BOTH")
    (aliased, w), faults, _ = _same(source, {"W": _matrix4(math.inf, 3)}, ("Aliased", "W"))
    assert (aliased, w, faults) == (False, [[0.0] * 4] * 3, [])


# The fold on lines written by hand (the compiler's shapes): what it must and must not do.

_LISTS = {"v_A": (3, True, True), "v_B": (2, True, True), "v_C": (3, True, False), "v_I": (3, False, True)}


def _finite(name: str, k: int, body=("_spent += 5", "v_OK = False"), pad: str = "") -> list[str]:
    return [f"{pad}if (not (-1.7976931348623157e+308 <= {name}[{k}] <= 1.7976931348623157e+308)):",
            *(f"{pad}    {line}" for line in body)]


def _fold(lines: list[str], lists=None) -> list[str]:
    lines = list(lines)
    sums.fold(lines, 0, _LISTS if lists is None else lists)
    return lines


def test_a_run_moves_past_stores_to_where_its_last_test_stood():
    lines = [*_finite("v_A", 0), "v_X = (v_Y + 1.5)", "v_B[1] = (v_A[2] * v_X)", *_finite("v_A", 1),
             *_finite("v_B", 1), *_finite("v_A", 2), "v_Z = 7", *_finite("v_B", 0)]
    folded = _fold(lines)
    assert folded[:3] == ["v_X = (v_Y + 1.5)", "v_B[1] = (v_A[2] * v_X)", "v_Z = 7"]
    assert folded[3] == "if not (-1.7976931348623157e+308 <= (_sum(v_B, _sum(v_A, 0.0))) <= 1.7976931348623157e+308):"
    assert folded[4:] == ["    " + line for line in lines if line not in folded[:3]]


def test_a_list_not_tested_whole_is_summed_by_element():
    lines = [*_finite("v_A", 0), *_finite("v_A", 2), *_finite("v_C", 1), *_finite("v_C", 0)]
    assert "(v_A[0] + v_A[2] + v_C[1] + v_C[0])" in _fold(lines)[0]
    lines = [*_finite("v_C", 0), *_finite("v_A", 0), *_finite("v_A", 2), *_finite("v_A", 1)]
    assert "(_sum(v_A, v_C[0]))" in _fold(lines)[0]


@pytest.mark.parametrize("between", [
    "v_A[1] = 0.0",                 # the element tested
    "v_A = v_B",                    # the list rebound
    "v_C[0] = 0.0",                 # a list that may be v_A (not the POU's own)
    "v_OK = True",                  # the flag the bodies store
    "v_X = v_OK",                   # the flag read
    "_spent += 3",                  # a charge outside the tests
    "v_X = _f(v_Y)",                # a call
    "v_X = v_A[v_I]",               # a read at a data index
    "v_X = (v_Y / 2.0)",            # a division
    "v_X = self.v_Y",               # an attribute
    "_spent = 12",                  # a charge settled into a store (charges.settle)
    "v_X = (_spent + 1)",           # the charge read
])
def test_a_line_the_tests_may_not_pass_splits_the_run(between):
    lines = [*_finite("v_A", 0), *_finite("v_A", 1), between, *_finite("v_A", 2), *_finite("v_B", 0)]
    assert _fold(lines) == lines


def test_different_bodies_split_the_run():
    lines = [*_finite("v_A", 0), *_finite("v_A", 1), *_finite("v_A", 2, ("_spent += 6", "v_OK = False")),
             *_finite("v_B", 0), *_finite("v_B", 1)]
    assert _fold(lines) == lines


@pytest.mark.parametrize("body", [("_spent = 5",), ("v_OK = v_X",), ("_spent += 5", "v_A = 0")])
def test_a_body_that_does_not_commute_is_no_test(body):
    lines = [*_finite("v_A", 0, body), *_finite("v_A", 1, body), *_finite("v_A", 2, body),
             *_finite("v_B", 0, body)]
    assert _fold(lines) == lines


def test_a_test_with_an_else_ends_the_run():
    lines = [*_finite("v_A", 0), *_finite("v_A", 1), *_finite("v_A", 2), *_finite("v_B", 0),
             "else:", "    _spent += 2"]
    assert _fold(lines) == lines                # three tests before it: too few to fold


def test_integer_elements_are_not_summed():
    lines = [*_finite("v_I", 0), *_finite("v_I", 1), *_finite("v_I", 2), *_finite("v_I", 0)]
    assert _fold(lines) == lines


def test_runs_in_a_nested_block_fold_there():
    inner = [line for k in range(3) for line in _finite("v_A", k, pad="    ")] + _finite("v_B", 0, pad="    ")
    lines = ["if v_GO:", *inner, "v_X = 1"]
    folded = _fold(lines)
    assert folded[0] == "if v_GO:" and folded[-1] == "v_X = 1"
    assert folded[1].startswith("    if not (-1.7976931348623157e+308 <= (_sum(v_A, v_B[0]))")
    assert folded[2:-1] == ["    " + line for line in inner]


def test_a_list_of_one_element_is_added_as_its_element():
    """A one-element list tested whole is read as its element, not summed by a call."""
    lists = {**_LISTS, "v_D": (1, True, True)}
    lines = [*_finite("v_D", 0), *_finite("v_A", 0), *_finite("v_A", 1), *_finite("v_A", 2)]
    assert _fold(lines, lists)[0] == \
        "if not (-1.7976931348623157e+308 <= (_sum(v_A, v_D[0])) <= 1.7976931348623157e+308):"


def test_arrays_declared_after_scalars_are_still_found():
    """The arrays' table is read past every variable that is no array of REAL or LREAL: with
    scalars, a FB instance and an array of STRING (each used, so the body holds it) declared
    before J, Q and F the twelve tests still fold (and run as before)."""
    source = CHECK.replace("VAR\n    J :", "VAR\n    Before : LREAL := 2.0;\n    Flag : BOOL;\n"
                           "    Clock : TON;\n    Names : ARRAY[1..2] OF STRING;\n    J :", 1).replace(
        "AllFinite := TRUE;\n", "AllFinite := TRUE;\nClock(IN := Flag);\nNames[1] := 'a';\n", 1)
    fast = compile_program(load_text(source, "t.st").program, optimise=ON).python_sources["MAIN"]
    assert "_sum(v_J, _sum(v_F, 0.0))" in fast
    # by hand: J[2, 2] = inf fires its one test; F = 2Q - 1; N = 100 / 4
    (ok, f, n), faults, _ = _same(source, {"J": _matrix({4: math.inf})}, ("AllFinite", "F", "N"))
    assert (ok, f, n, faults) == (False, [1.0, 3.0, 5.0], 25, [])


def test_a_finite_test_of_a_product_beside_the_element_tests():
    """A finite test of an expression (`ABS(F[Row] * X)`) has the tests' form but no element of
    its own: it is left as written, and the element tests around it still run."""
    source = CHECK.replace(
        "        IF NOT (ABS(J[Row, Column]) <= {BIG}) THEN AllFinite := FALSE; END_IF;".format(BIG=BIG),
        "        IF NOT (ABS(J[Row, Column]) <= {BIG}) THEN AllFinite := FALSE; END_IF;\n"
        "        IF NOT (ABS(F[Row] * X) <= {BIG}) THEN AllFinite := FALSE; END_IF;".format(BIG=BIG))
    source = source.replace("    N : DINT;\n", "    N : DINT;\n    X : LREAL := 1.0E308;\n", 1)
    # by hand: F = [1, 3, 5]; F[1] * 1e308 = 1e308 is finite, F[2] * 1e308 = 3e308 overflows
    (ok, f, n), faults, _ = _same(source, {}, ("AllFinite", "F", "N"))
    assert (ok, f, n, faults) == (False, [1.0, 3.0, 5.0], 25, [])
    (ok, f, n), faults, _ = _same(source, {"X": 1.0}, ("AllFinite", "F", "N"))
    assert (ok, f, n, faults) == (True, [1.0, 3.0, 5.0], 25, [])
