"""The `halves` pass (st_runtime/compiler/optimise/halves.py): a CASE of many clauses with no
ELSE tests `selector < P` first and reaches its clause by halves.  Nothing a program can see
changes: the clause each selector runs, results, faults (code, file, line, column, scan),
instance states and the NJ time charged are equal bit for bit with the pass on and off, also
when F-PERIOD cuts the scan or a fault stops the run in a clause.
"""

from __future__ import annotations

import re
from dataclasses import replace

import pytest

from st_runtime import api
from st_runtime.compiler import Optimisations, compile_program
from st_runtime.compiler.optimise import halves
from st_runtime.controller import Controller
from test_optimiser_equivalence import run_both, same_alone_and_with_all, stopped_runs

ON = Optimisations()
WITHOUT = replace(ON, halves=False)

# S = (7 N) MOD 23 - 2 runs through -2..20 as N counts 1..23 (7 is invertible mod 23).
DISPATCH = """
TYPE Mode : (IDLE, RUN, HOLD, DONE, FAULTED, RESET); END_TYPE
PROGRAM Main
VAR
    N : INT; S : INT; Zero : INT; Q : INT; Last : INT := -1; After : INT;
    Hits : ARRAY[0..7] OF INT;
    M : Mode; Named : INT; W : WORD; Bits : INT;
END_VAR
N := N + 1;
S := (7 * N) MOD 23 - 2;
Last := -1;
CASE S OF
0:      Hits[0] := Hits[0] + 1; Last := 0;
1, 2:   Hits[1] := Hits[1] + 1; Last := 1;
3..5:   Hits[2] := Hits[2] + 1; Last := 2;
14, 9:  Hits[3] := Hits[3] + 1; Last := 3;      (* labels around the next clauses' *)
6:      Hits[4] := Hits[4] + 1; Last := 4;
10..12: Hits[5] := Hits[5] + 1; Last := 5;
7, 8:   Hits[6] := Hits[6] + 1; Last := 6;
20:     Last := 7; Q := 100 / Zero;              (* F-DIV-ZERO *)
15:     Last := 8; RETURN;
13:     Hits[7] := Hits[7] + 1; Last := 9;
END_CASE;
After := After + 1;
CASE N MOD 6 OF
0: M := Mode#IDLE;
1: M := Mode#RUN;
2: M := Mode#HOLD;
3: M := Mode#DONE;
4: M := Mode#FAULTED;
5: M := Mode#RESET;
END_CASE;
CASE M OF
Mode#IDLE: Named := 10;
Mode#RUN: Named := 11;
Mode#HOLD: Named := 12;
Mode#DONE: Named := 13;
Mode#FAULTED: Named := 14;
Mode#RESET: Named := 15;
END_CASE;
W := INT_TO_WORD(N MOD 8);
CASE W OF
0: Bits := 0;
1: Bits := 1;
2: Bits := 2;
3: Bits := 3;
4, 5: Bits := 4;
6: Bits := 6;
ELSE Bits := 7;                                  (* an ELSE: tested in a row *)
END_CASE;
END_PROGRAM
"""

DIVISION = DISPATCH.split("\n").index("20:     Last := 7; Q := 100 / Zero;              (* F-DIV-ZERO *)") + 1


def _program():
    return api.load_text(DISPATCH).program


def _source(optimise):
    return compile_program(_program(), optimise=optimise).python_sources["MAIN"]


def test_the_pivots_split_only_between_clauses():
    """The 10 clauses' label extents: (0,0) (1,2) (3,5) (9,14) (6,6) (10,12) (7,8) (20,20)
    (15,15) (13,13).  No pivot may fall in 10..14 (clause 14, 9 lies on both sides)."""
    extent = [(0, 0), (1, 2), (3, 5), (9, 14), (6, 6), (10, 12), (7, 8), (20, 20), (15, 15), (13, 13)]
    # 9: five clauses below (0, 1-2, 3-5, 6, 7-8), five at or above; 10, 13 cannot split
    # the upper five (9..14 on both sides), 15 can: 9..14, 10..12 and 13 below it.
    assert halves.tree(extent) == halves.Split(9, halves.Split(3, [0, 1], [2, 4, 6]),
                                               halves.Split(15, [3, 5, 9], [7, 8]))
    assert halves.tree([(0, 9), (1, 1), (2, 2), (3, 3), (4, 4), (5, 5)]) == [0, 1, 2, 3, 4, 5]
    assert halves.tree(extent[:5]) == [0, 1, 2, 3, 4]                 # fewer than MIN_CLAUSES


def test_a_case_of_many_clauses_is_dispatched_by_halves():
    source, plain = _source(ON), _source(WITHOUT)
    pivots = re.findall(r"if (?:\(True if )?_t\d+ < (\d+)(?: else False\))?:", source)     # (jump_far)
    assert re.findall(r"if _t\d+ < (\d+):", plain) == []
    # S's CASE: 9, 3, 15; N MOD 6's and the enumeration's (IDLE..RESET: 0..5): 3 each;
    # W's CASE has an ELSE: tested in a row
    assert pivots == ["9", "3", "15", "3", "3"]


def test_each_selector_runs_the_clause_its_labels_name():
    """By hand, N = 1..23: S = 7N mod 23 - 2 takes every value of -2..20 once."""
    controller = Controller(compile_program(_program(), optimise=ON))
    main = controller.add_program("Main")
    expected_last = {0: 0, 1: 1, 2: 1, 3: 2, 4: 2, 5: 2, 6: 4, 7: 6, 8: 6, 9: 3, 10: 5, 11: 5, 12: 5,
                     13: 9, 14: 3, 15: 8, 20: 7}
    after = named = bits = 0
    for n in range(1, 24):
        controller.run(1)
        s = (7 * n) % 23 - 2
        assert main.v_S == s
        assert main.v_LAST == expected_last.get(s, -1), s
        if s != 15:                             # RETURN leaves before the rest (a fault does not)
            after, named, bits = after + 1, 10 + n % 6, {5: 4, 7: 7}.get(n % 8, n % 8)
        assert (main.v_AFTER, main.v_NAMED, main.v_BITS) == (after, named, bits)
    assert [main.v_HITS[i] for i in range(8)] == [1, 2, 3, 2, 1, 3, 2, 1]
    assert [(f.code, f.line) for f in controller.faults] == [("F-DIV-ZERO", DIVISION)]


def test_the_scans_see_the_same_with_and_without_the_pass():
    faults = same_alone_and_with_all(_program, 30, "halves")[0]
    assert {(code, line) for code, _, line, _, _ in faults} == {("F-DIV-ZERO", DIVISION)}


@pytest.mark.parametrize("budget_ns", [300, 700, 1_200, 2_000, 4_000])
def test_f_period_lands_on_the_same_statement_with_the_pass(budget_ns):
    off, on = run_both(_program(), 25, budget_ns, optimise=Optimisations.only("halves"))
    assert on == off


def test_the_time_charged_and_a_stopping_fault_are_the_same():
    """stop_on_fault: S = 20 at N = 13 (7 * 13 = 91 = 3 * 23 + 22), in the eighth clause."""
    outcomes = stopped_runs(_program(), 15, WITHOUT, ON)
    assert outcomes[0] == outcomes[1]
    assert outcomes[1][0] == [("F-DIV-ZERO", DIVISION, 13)]


def _long_clauses() -> str:
    """A CASE of eight clauses, each of 30 statements: every test's branch is long."""
    clauses = "\n".join(f"{k}: " + " ".join(f"X[{j}] := X[{j}] + {k};" for j in range(1, 31)) + f" Last := {k};"
                        for k in range(8))
    return f"""
PROGRAM Main
VAR N, S, Last : INT; X : ARRAY[1..30] OF INT; END_VAR
N := N + 1;
S := N MOD 9;                                     (* 8: no clause *)
Last := -1;
CASE S OF
{clauses}
END_CASE;
END_PROGRAM
"""


def test_a_test_before_a_long_branch_keeps_its_jump_short():
    """`jump_far`: the tests of the selector whose branches are long are `True if ... else
    False` (their comparison then specialised by CPython 3.11); the clause each value runs,
    by hand: S = N mod 9, clause S for S < 8, none for 8."""
    program = api.load_text(_long_clauses()).program
    source = compile_program(program, optimise=ON).python_sources["MAIN"]
    assert re.findall(r"if \(True if _t\d+ < (\d+) else False\):", source)
    assert re.findall(r"if \(True if _t\d+ == (\d+) else False\):", source)
    assert not re.findall(r"if \(True if", compile_program(program, optimise=WITHOUT).python_sources["MAIN"])
    controller = Controller(compile_program(program, optimise=ON))
    main = controller.add_program("Main")
    for n in range(1, 20):
        controller.run(1)
        assert main.v_LAST == (n % 9 if n % 9 < 8 else -1), n
    off, on = run_both(program, 20)
    assert on == off


def test_jump_far_rewrites_only_a_single_comparison_before_a_long_branch():
    lines = ["        if _t1 < 8:"] + ["            x = 1"] * (halves.FAR + 1)
    halves.jump_far(lines, 0)
    assert lines[0] == "        if (True if _t1 < 8 else False):"
    short = ["        elif _t2 == 3:"] + ["            x = 1"] * halves.FAR
    halves.jump_far(short, 0)
    assert short[0] == "        elif _t2 == 3:"
    membership = ["        if _t1 in (1, 2,):"] + ["            x = 1"] * (halves.FAR + 1)
    halves.jump_far(membership, 0)
    assert membership[0] == "        if _t1 in (1, 2,):"
