"""The `chains` pass (st_runtime/compiler/optimise/chains.py): adjacent updates of one array
element in a fast copy written as one store, and the same results with the pass on and off,
also when one list is passed as two in-outs."""

from __future__ import annotations

from dataclasses import replace

import pytest

from st_runtime.api import Plc, load_text
from st_runtime.compiler import Optimisations, compile_program
from st_runtime.compiler.optimise import chains, fastpath
from st_runtime.controller import Controller

ON = Optimisations()
OFF = replace(ON, chains=False)


def _merge(lines):
    lines = list(lines)
    chains.merge(lines, 0)
    return lines


def test_adjacent_updates_of_one_element_become_one_store():
    assert _merge(["    v_S[3] = (v_S[3] - (v_M[18] * v_S[0]))",
                   "    v_S[3] = (v_S[3] - (v_M[19] * v_S[1]))",
                   "    v_S[3] = (v_S[3] + 2.0)"]) == [
        "    v_S[3] = (((v_S[3] - (v_M[18] * v_S[0])) - (v_M[19] * v_S[1])) + 2.0)"]
    # the first value is not one parenthesised whole: it is put in parentheses
    assert _merge(["v_S[1] = v_R[2]", "v_S[1] = (v_S[1] * 0.5)"]) == ["v_S[1] = ((v_R[2]) * 0.5)"]


@pytest.mark.parametrize("lines", [
    ["v_S[3] = (v_S[3] - 1.0)", "v_S[3] = (v_S[3] - (v_M[3] * 2.0))"],        # another list at k
    ["v_S[3] = (v_S[3] - 1.0)", "v_S[3] = (v_S[3] - v_M[v_I - 1])"],          # an index that is data
    ["v_S[3] = (v_S[3] - 1.0)", "v_S[3] = (v_S[3] - v_M[v_P[1]])"],           # nested
    ["v_S[3] = (v_S[3] - 1.0)", "v_S[3] = (2.0 - v_S[3])"],                   # not the left operand
    ["v_S[3] = (v_S[3] - 1.0)", "v_S[2] = (v_S[2] - 1.0)"],                   # another element
    ["v_S[3] = (v_S[3] - 1.0)", "v_T[3] = (v_T[3] - 1.0)"],                   # another list
    ["v_S[3] = (v_S[3] - 1.0)", "    v_S[3] = (v_S[3] - 1.0)"],               # another block
    ["v_S[3] = (v_S[3] - 1.0)", "_spent += 1196", "v_S[3] = (v_S[3] - 1.0)"],  # something between
    ["try:", "    v_S[3] = (v_S[3] / v_D)", "except _FAULTS as _e:", "    pass",
     "v_S[3] = (v_S[3] - 1.0)"],
])
def test_what_is_left_as_it_is(lines):
    assert _merge(lines) == lines


def test_a_guarded_store_is_not_merged():
    """The first store in a `try` body may raise: not merged (the second would be)."""
    lines = ["if v_X:", "    try:", "        v_S[3] = (v_S[3] - 1.0)", "    v_S[3] = (v_S[3] - 1.0)"]
    assert _merge(lines) == lines


# Forward substitution on two in-outs (the LU's shape); Main passes one list as both.
PROGRAM = """
FUNCTION Forward : BOOL
VAR_IN_OUT L : ARRAY[1..3, 1..3] OF LREAL; Y : ARRAY[1..3] OF LREAL; END_VAR
VAR R, C : INT; END_VAR
FOR R := 1 TO 3 DO
    FOR C := 1 TO R - 1 DO
        Y[R] := Y[R] - L[R, C] * Y[C];
    END_FOR;
END_FOR;
Forward := TRUE;
END_FUNCTION

FUNCTION Twice : BOOL
VAR_IN_OUT A : ARRAY[1..3] OF LREAL; B : ARRAY[1..3] OF LREAL; END_VAR
VAR I : INT; END_VAR
FOR I := 1 TO 3 DO
    B[2] := B[2] - A[I] * 2.0;
END_FOR;
B[3] := B[3] + A[1];
B[3] := B[3] + A[3];
Twice := TRUE;
END_FUNCTION

PROGRAM Main
VAR
    L : ARRAY[1..3, 1..3] OF LREAL := [1.0, 0.0, 0.0, 0.5, 1.0, 0.0, -0.25, 0.75, 1.0];
    Y : ARRAY[1..3] OF LREAL := [2.0, 3.0, 5.0];
    X : ARRAY[1..3] OF LREAL := [1.0, 10.0, 100.0];
    Ok : BOOL;
END_VAR
Ok := Forward(L := L, Y := Y);
Ok := Twice(A := X, B := X);
END_PROGRAM
"""


@pytest.fixture(autouse=True)
def every_bounded_body(monkeypatch):
    monkeypatch.setattr(fastpath, "WORTH", 1)


def test_the_pass_fires_and_the_results_are_the_same():
    program = load_text(PROGRAM, "chains.st").program
    on = compile_program(program, optimise=ON).python_sources
    assert "v_Y[2] = ((v_Y[2] - (v_L[6] * v_Y[0])) - (v_L[7] * v_Y[1]))" in on["FORWARD"]
    # B[2] is v_B[1]: A[2] (v_A[1]) may be it, A[3] may not; B[3] is v_B[2], and so may A[3] be
    assert "v_B[1] = ((v_B[1] - (v_A[0] * 2.0)) - (v_A[1] * 2.0))" not in on["TWICE"]
    assert "v_B[1] = ((v_B[1] - (v_A[1] * 2.0)) - (v_A[2] * 2.0))" in on["TWICE"]
    assert "v_B[2] = ((v_B[2] + v_A[0]) + v_A[2])" not in on["TWICE"]
    off = compile_program(program, optimise=OFF).python_sources
    assert "((v_Y[2] - (v_L[6] * v_Y[0])) - " not in off["FORWARD"]
    results = {}
    for optimise in (ON, OFF):
        plc = Plc(Controller(compile_program(program, optimise=optimise), 1_000_000))
        main = plc.add_program("Main")
        plc.run(2)
        results[optimise] = (main["Y"], main["X"], list(plc.controller.task_times["Primary"]), plc.faults)
    assert results[ON] == results[OFF]
    # by hand, scan 1: Y2 = 3 - 0.5 * 2 = 2, Y3 = 5 + 0.25 * 2 - 0.75 * 2 = 4; scan 2: Y2 = 2 - 1
    # = 1, Y3 = 4 + 0.5 - 0.75 = 3.75.  X as A and B: X2 = 10 - 1 * 2 = 8, 8 - 8 * 2 = -8,
    # -8 - 100 * 2 = -208; X3 = 100 + 1 = 101, 101 + 101 = 202; scan 2: X2 = -208 - 2 = -210,
    # -210 + 420 = 210, 210 - 404 = -194; X3 = 202 + 1 = 203, 406
    assert results[ON][:2] == ([2.0, 1.0, 3.75], [1.0, -194.0, 406.0])
