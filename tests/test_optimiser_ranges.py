"""The `ranges` pass (st_runtime/compiler/optimise/ranges.py): a bounds check is left out
only where the integer local's value is proven in range at that point of the code, and
every program runs, faults and ends in the same state with the pass on and off."""

from __future__ import annotations

from dataclasses import replace

import pytest

from st_runtime import api
from st_runtime.compiler import Optimisations, compile_program
from test_optimiser_equivalence import _Context, run_both

ON = Optimisations()
NO_RANGES = replace(ON, ranges=False)

PIVOT = """
FUNCTION Pivot : INT
VAR_IN_OUT M : ARRAY[1..4, 1..4] OF LREAL; END_VAR
VAR K : INT; Row : INT; P : INT; Col : INT; Held : LREAL; END_VAR
FOR K := 1 TO 3 DO
    P := K;
    FOR Row := K + 1 TO 4 DO
        IF ABS(M[Row, K]) > ABS(M[P, K]) THEN P := Row; END_IF;
    END_FOR;
    FOR Col := 1 TO 4 DO
        Held := M[K, Col]; M[K, Col] := M[P, Col]; M[P, Col] := Held;
    END_FOR;
END_FOR;
Pivot := P;
END_FUNCTION
PROGRAM Main
VAR A : ARRAY[1..4, 1..4] OF LREAL := [1.0, 2.0, 3.0, 4.0, -9.0, 1.0, 0.5, 2.0,
                                       3.0, 8.0, -1.0, 0.0, 2.0, -2.0, 7.0, 1.0];
    Last : INT; END_VAR
Last := Pivot(M := A);
A[1, 1] := A[1, 1] + 0.25;
END_PROGRAM
"""


def _sources(text: str, pou: str):
    program = api.load_text(text).program
    on = compile_program(program, optimise=ON).python_sources[pou]
    off = compile_program(program, optimise=NO_RANGES).python_sources[pou]
    return program, on, off


def test_a_pivot_row_proven_in_range_needs_no_check():
    program, on, off = _sources(PIVOT, "PIVOT")
    assert "v_P * 4" in on and "_index_fault" in off
    assert "_index_fault" not in on          # every M[P, .] after P := K / P := Row (both in 1..4)
    off_run, on_run = run_both(program, 3)
    assert on_run == off_run
    assert off_run[0] == []                  # no faults


UNPROVEN = """
FUNCTION Count : INT
VAR_IN_OUT A : ARRAY[1..5] OF INT; END_VAR
VAR_INPUT Z : INT; END_VAR
VAR I : INT; J : INT; N : INT; C : INT; END_VAR
(* a WHILE: I changes in the body, so the condition's A[I] keeps its check *)
I := 1;
WHILE A[I] > 0 DO I := I + 1; END_WHILE;
(* a division that faults leaves J as it was (3): J is 3 or unknown *)
J := 3;
J := 12 / Z;
N := A[J];
(* a branch that may store 9 *)
C := 2;
IF Z > 0 THEN C := 9; END_IF;
N := N + A[C];
(* a CASE whose clause stores 0 *)
CASE Z OF 1: C := 0; ELSE C := 5; END_CASE;
N := N + A[C];
(* a loop that is not unrolled (its bound is data) changes C each time *)
C := 1;
FOR I := 1 TO Z DO C := C + 2; END_FOR;
Count := N + A[C];
END_FUNCTION
PROGRAM Main
VAR A : ARRAY[1..5] OF INT := [4, 3, 2, 1, 7]; Z : INT; R : INT; S : INT; END_VAR
R := Count(A := A, Z := Z);
Z := Z + 1;
IF Z = 3 THEN A[3] := 0; END_IF;
END_PROGRAM
"""


def test_values_not_proven_keep_their_checks_and_fault_the_same():
    program, on, off = _sources(UNPROVEN, "COUNT")
    assert on.count("_index_fault") == off.count("_index_fault") == on.count("v_A[(") == 5   # every read checked
    off_run, on_run = run_both(program, 6)
    assert on_run == off_run
    # By hand: scan 1 (Z = 0) runs off A's end in the WHILE (line 8) and divides by zero
    # (11); scan 2 (Z = 1): J = 12 (12), C = 9 (16), C = 0 (19); scan 4 on: C = 1 + 2 * Z
    # is past 5 (23).
    assert {(f[0], f[2]) for f in off_run[0]} == {("F-INDEX", 8), ("F-DIV-ZERO", 11), ("F-INDEX", 12),
                                                  ("F-INDEX", 16), ("F-INDEX", 19), ("F-INDEX", 23)}


REFERENCED = """
FUNCTION Bump : BOOL
VAR_IN_OUT X : INT; END_VAR
X := X + 10;
Bump := TRUE;
END_FUNCTION
FUNCTION UseRef : LREAL
VAR_IN_OUT A : ARRAY[1..3] OF LREAL; END_VAR
VAR I : INT; Ok : BOOL; END_VAR
I := 2;
Ok := Bump(X := I);
UseRef := A[I];
END_FUNCTION
PROGRAM Main
VAR A : ARRAY[1..3] OF LREAL := [1.0, 2.0, 3.0]; R : LREAL; END_VAR
R := UseRef(A := A);
END_PROGRAM
"""


def test_a_variable_passed_by_reference_is_not_followed():
    program, on, off = _sources(REFERENCED, "USEREF")
    assert "_index_fault" in on              # I may be anything after Bump(X := I)
    off_run, on_run = run_both(program, 2)
    assert on_run == off_run and off_run[0] and all(f[2] == 12 for f in off_run[0])   # A[12]: out of range


@pytest.mark.parametrize("budget_ns", [500, 2_000, 5_000, 500_000])
def test_f_period_lands_on_the_same_statement(budget_ns):
    program = api.load_text(PIVOT).program
    off_run, on_run = run_both(program, 2, budget_ns)
    assert on_run == off_run


def test_the_time_charged_is_the_same():
    """The NJ estimate comes from the ST: a check left out charges what it charged."""
    program = api.load_text(PIVOT).program
    spent = []
    for optimise in (Optimisations.none(), NO_RANGES, ON):
        pivot = compile_program(program, optimise=optimise).functions["PIVOT"]
        context = _Context()
        matrix = [1.0, 2.0, 3.0, 4.0, -9.0, 1.0, 0.5, 2.0, 3.0, 8.0, -1.0, 0.0, 2.0, -2.0, 7.0, 1.0]
        result = pivot(context, matrix)
        spent.append((10**12 - context.budget, result, matrix, context.faults))
    assert spent[0] == spent[1] == spent[2] and spent[0][0] > 0


# A FOR whose end is data (the wave's `FOR Component := 1 TO Count`): a version without
# the checks on its variable runs when the range lies inside every array it indexes.
VERSIONED = """
PROGRAM Main
VAR
    Count : INT; Scan : INT; First : INT := 1; I : INT; J : INT;
    A : ARRAY[1..8] OF LREAL := [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0];
    B : ARRAY[0..6] OF LREAL; M : ARRAY[1..8, 1..3] OF INT; Sum : LREAL; Hits : INT;
END_VAR
Scan := Scan + 1;
Count := (Scan * 3) MOD 11 - 1;         (* -1, 2, 5, 8, 0, 3, 6, 9, 1, 4, 7, -1, ... *)
Sum := 0.0;
FOR I := 1 TO Count DO
    Sum := Sum + A[I] * 0.5;
    B[I - 1] := Sum;                    (* I - 1 is not the variable: checked in both *)
    M[I, 2] := M[I, 2] + 1;
    IF A[I] > 2.5 THEN Hits := Hits + 1; EXIT; END_IF;
END_FOR;
FOR J := First TO Count DO              (* the start is data too: no version *)
    Sum := Sum + A[J];
END_FOR;
END_PROGRAM
"""


def test_a_loop_with_a_data_end_has_a_version_without_checks():
    source = compile_program(api.load_text(VERSIONED).program, optimise=ON).python_sources["MAIN"]
    fast, checked = source.split("for v_I in", 2)[1:]
    assert ".stop <= 9:" in source                          # A and M: 1..8
    assert "'A'" not in fast and "_index_fault_n(" not in fast and "'B'" in fast
    assert "'A'" in checked and "_index_fault_n(" in checked
    assert source.count("for v_J in") == 1
    plain = compile_program(api.load_text(VERSIONED).program, optimise=NO_RANGES).python_sources["MAIN"]
    assert ".stop <=" not in plain and plain.count("for v_I in") == 1


def test_the_versions_run_and_fault_the_same():
    off, on = run_both(api.load_text(VERSIONED).program, 13, optimise=Optimisations.only("ranges"))
    assert on == off
    assert any(code == "F-INDEX" for code, *_ in on[0])     # Count = 9: A[9] in the checked copy
    off, on = run_both(api.load_text(VERSIONED).program, 13, optimise=ON)
    assert on == off


@pytest.mark.parametrize("budget_ns", [300, 1_000, 2_500, 6_000])
def test_f_period_lands_on_the_same_statement_in_a_version(budget_ns):
    off, on = run_both(api.load_text(VERSIONED).program, 13, budget_ns, optimise=Optimisations.only("ranges"))
    assert on == off


# The version without checks runs only when the end is at most the arrays' bound, so the
# FOR variable's final value (the end + 1, or the start when the loop does not run) lies
# in [1, 9]: stored without the wrap into INT the checked copy keeps.
FINAL = """
PROGRAM Main
VAR
    Count : INT; Scan : INT; I : INT; After : INT; Sum : LREAL;
    A : ARRAY[1..8] OF LREAL := [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0];
END_VAR
Scan := Scan + 1;
Count := (Scan * 3) MOD 11 - 1;         (* -1, 2, 5, 8, 0, 3, 6, 9, 1, 4, 7, -1, ... *)
Sum := 0.0;
FOR I := 1 TO Count DO
    Sum := Sum + A[I];
END_FOR;
After := I;
END_PROGRAM
"""


def test_the_version_stores_the_final_value_without_a_wrap():
    source = compile_program(api.load_text(FINAL).program, optimise=ON).python_sources["MAIN"]
    fast, checked = source.split("for v_I in", 2)[1:]
    assert "32768" not in fast.split("else:", 2)[1].splitlines()[1]
    assert "32768 & 65535" in checked.split("else:", 1)[1].splitlines()[1]


def test_the_final_value_is_the_end_plus_one_or_the_start():
    """By hand: I after the loop is Count + 1 when Count >= 1, else 1; F-INDEX at Count 9 (scan 7)."""
    from st_runtime.controller import Controller

    controller = Controller(compile_program(api.load_text(FINAL).program, optimise=ON))
    main = controller.add_program("Main")
    for scan in range(1, 14):
        controller.run(1)
        count = (scan * 3) % 11 - 1
        if count <= 8:
            assert (main.v_I, main.v_AFTER) == ((count + 1 if count >= 1 else 1),) * 2, count
    assert [(f.code, f.scan) for f in controller.faults] == [("F-INDEX", 7)]
    off, on = run_both(api.load_text(FINAL).program, 13, optimise=Optimisations.only("ranges"))
    assert on == off
