"""The `rowswap` pass (st_runtime/compiler/optimise/rowswap.py): the unrolled loop that
exchanges two rows through a buffer becomes two slice assignments where that is exact,
and every program runs, faults and ends in the same state with the pass on and off."""

from __future__ import annotations

from dataclasses import replace

from st_runtime import api
from st_runtime.compiler import Optimisations, compile_program
from test_optimiser_equivalence import run_both

ON = Optimisations()
NO_ROWSWAP = replace(ON, rowswap=False)

SWAP = """
FUNCTION SwapRows : LREAL
VAR_IN_OUT M : ARRAY[1..4, 1..3] OF LREAL; END_VAR
VAR_INPUT K : INT; P : INT; END_VAR
VAR Col : INT; Held : LREAL; END_VAR
FOR Col := 1 TO 3 DO
    Held := M[K, Col]; M[K, Col] := M[P, Col]; M[P, Col] := Held;
END_FOR;
SwapRows := Held + INT_TO_LREAL(Col);
END_FUNCTION
FUNCTION SwapFirst : INT
VAR_IN_OUT M : ARRAY[0..2, 0..1] OF INT; END_VAR
VAR_INPUT P : INT; END_VAR
VAR Col : INT; Held : INT; END_VAR
FOR Col := 0 TO 1 DO
    Held := M[0, Col]; M[0, Col] := M[P, Col]; M[P, Col] := Held;
END_FOR;
SwapFirst := Held;
END_FUNCTION
FUNCTION PartRow : LREAL
VAR_IN_OUT M : ARRAY[1..2, 1..2] OF LREAL; END_VAR
VAR Col : INT; Held : LREAL; END_VAR
FOR Col := 2 TO 2 DO
    Held := M[1, Col]; M[1, Col] := M[2, Col]; M[2, Col] := Held;
END_FOR;
PartRow := Held;
END_FUNCTION
PROGRAM Main
VAR M : ARRAY[1..4, 1..3] OF LREAL := [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0, 11.0, 12.0];
    I : ARRAY[0..2, 0..1] OF INT := [1, 2, 3, 4, 5, 6];
    N : ARRAY[1..2, 1..2] OF LREAL := [0.1, 0.2, 0.3, 0.4];
    Scan : INT; R : LREAL; Q : INT; S : LREAL; K : INT := 1; P : INT; END_VAR
Scan := Scan + 1;
CASE Scan OF
    1: P := 2;              (* rows 1 and 2 exchanged *)
    2: P := 1;              (* a row with itself: nothing changes *)
    3: P := 5;              (* past the last row: every statement faults *)
    4: P := 0; K := 4;      (* before the first row *)
    5: P := 4; K := 3;
END_CASE;
R := SwapRows(M := M, K := K, P := P);
Q := SwapFirst(M := I, P := Scan MOD 4);
S := PartRow(M := N);
END_PROGRAM
"""


def _program():
    return api.load_text(SWAP).program


def test_the_pass_fires_only_on_an_exact_row_exchange():
    program = _program()
    on = compile_program(program, optimise=ON).python_sources
    off = compile_program(program, optimise=NO_ROWSWAP).python_sources
    assert "], v_M[" in on["SWAPROWS"] and "], v_M[" not in off["SWAPROWS"]
    assert "v_M[0:2], v_M[" in on["SWAPFIRST"]
    # a loop over part of a row: the statements stay
    assert "], v_M[" not in on["PARTROW"]


def test_rows_exchanged_as_by_hand():
    """Scan 1: rows 1 and 2 of 1..12 exchanged, Held = the old M[1, 3] = 3.0, Col = 4."""
    program = _program()
    compiled = compile_program(program, optimise=ON)
    from st_runtime.controller import Controller

    controller = Controller(compiled)
    main = controller.add_program("Main")
    controller.run(1)
    assert main.v_M == [4.0, 5.0, 6.0, 1.0, 2.0, 3.0, 7.0, 8.0, 9.0, 10.0, 11.0, 12.0]
    assert main.v_R == 3.0 + 4.0
    assert main.v_I == [3, 4, 1, 2, 5, 6] and main.v_Q == 2      # SwapFirst with P = 1
    controller.run(1)                                           # P = 1 = K: unchanged
    assert main.v_M[:6] == [4.0, 5.0, 6.0, 1.0, 2.0, 3.0] and main.v_R == 6.0 + 4.0
    assert controller.faults == []


def test_runs_faults_and_states_are_the_same_with_and_without():
    """Scans 3 and 4 take rows out of range (F-INDEX at each statement, as without the pass);
    the states, the faults (code, line, column, scan) and the time charged are equal."""
    program = _program()
    for optimise in (ON, NO_ROWSWAP):
        off_run, on_run = run_both(program, 6, optimise=optimise)
        assert on_run == off_run
    faults = run_both(program, 6)[1][0]
    assert {(code, scan) for code, _, _, _, scan in faults} == {("F-INDEX", 3), ("F-INDEX", 4)}


def test_f_period_lands_on_the_same_statement():
    program = _program()
    for budget_ns in (300, 1_000, 3_000):
        off_run, on_run = run_both(program, 5, budget_ns)
        assert on_run == off_run
