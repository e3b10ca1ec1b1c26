"""Compiler behaviours that survivors of a fresh mutation sample pinned down (issue 16).

The sample: `python tools/mutation.py compiler --sample 100 --seed 19` (docs/mutation.md,
"st_runtime/compiler/").  Each test goes through the public entry points (load ST, run
scans, the optimiser switches) and takes its expected values from IEC 61131-3 or a hand
calculation stated beside it, never from a run of the code under test.
"""

from __future__ import annotations

import itertools

import pytest

from st_runtime.api import load_text

N = 5
PERMUTATIONS = list(itertools.permutations(range(1, N + 1)))       # lexicographic


def _sign(p) -> int:
    inversions = sum(1 for i in range(N) for j in range(i + 1, N) if p[i] > p[j])
    return -1 if inversions % 2 else 1


def run(src: str, cycles: int = 1):
    """Load `src`, run PROGRAM Main `cycles` scans; (instance, plc)."""
    plc = load_text(src, "m.st", "iec").controller()
    main = plc.add_program("Main")
    plc.run(cycles)
    return main, plc


# A Leibniz 5x5 determinant written as a FOR over a constant permutation table: with
# every optimiser pass on (the default) its unrolled body is one long straight run of
# LREAL `*` and `+`/`-` (the `vector` pass computes such a run with NumPy).  The INT
# sum in the loop is not a float: it must stay an INT computed as an integer.
DET_WITH_AN_INT = f"""
FUNCTION_BLOCK Det5
VAR_INPUT M : ARRAY[1..{N}, 1..{N}] OF LREAL; END_VAR
VAR_OUTPUT D : LREAL; K2 : INT; END_VAR
VAR CONSTANT
    P : ARRAY[1..{len(PERMUTATIONS)}, 1..{N}] OF USINT := [{", ".join(str(x) for p in PERMUTATIONS for x in p)}];
    S : ARRAY[1..{len(PERMUTATIONS)}] OF SINT := [{", ".join(str(_sign(p)) for p in PERMUTATIONS)}];
END_VAR
VAR T : INT; X : LREAL; K0 : INT; K1 : INT; END_VAR
D := 0.0; K0 := 1; K1 := 2;
FOR T := 1 TO {len(PERMUTATIONS)} DO
    X := M[1, P[T, 1]] * M[2, P[T, 2]] * M[3, P[T, 3]] * M[4, P[T, 4]] * M[5, P[T, 5]];
    K2 := K0 + K1;
    IF S[T] > 0 THEN D := D + X; ELSE D := D - X; END_IF;
END_FOR;
END_FUNCTION_BLOCK

PROGRAM Main
VAR A : ARRAY[1..5, 1..5] OF LREAL := [1.0, 0.0, 0.0, 0.0, 1.0,
                                       0.0, 2.0, 0.0, 0.0, 0.0,
                                       0.0, 0.0, 3.0, 0.0, 0.0,
                                       0.0, 0.0, 0.0, 4.0, 0.0,
                                       0.0, 0.0, 0.0, 0.0, 5.0];
    Tab : ARRAY[1..4] OF INT := [10, 20, 30, 40];
    F : Det5; Det : LREAL; K : INT; Picked : INT; Text : STRING; END_VAR
F(M := A);
Det := F.D;
K := F.K2;
Picked := Tab[K];
Text := INT_TO_STRING(K * 7);
END_PROGRAM
"""


def test_an_int_sum_inside_a_long_float_run_stays_an_integer():
    # diag(1, 2, 3, 4, 5) with a 1 in the top right corner (upper triangular): det = 120.
    # K0 + K1 = 1 + 2 = 3 (an INT); Tab[3] = 30; 3 * 7 = 21 as text '21' (IEC: INT_TO_STRING
    # of an integer is its decimal digits).
    main, plc = run(DET_WITH_AN_INT)
    assert plc.faults == []
    assert main["Det"] == 120.0
    assert main["K"] == 3 and isinstance(main["K"], int)
    assert main["Picked"] == 30
    assert main["Text"] == "21"


# ------------------------------------------------------------------ the estimated NJ501 time (cost.py's weights, by hand)

def _scan_ps(src: str) -> int:
    plc = load_text(src, "m.st", "iec").controller()
    plc.add_program("Main")
    plc.run(1)
    return plc.controller.task_times["Primary"][0]


def test_the_estimated_time_of_a_call_of_an_fb_written_in_st():
    # The call of an FB written in ST costs its call and return plus each argument passed
    # (by value: one `argument` and the load of its value); the FB's empty body charges
    # nothing of its own.  10 + (1 + 1) + (1 + 1) = 14 units of 598 ps (cost.py's table).
    from st_runtime.compiler.cost import PICOSECONDS_PER_UNIT, WEIGHTS

    w = WEIGHTS
    units = w["call"] + 2 * (w["argument"] + w["load"])
    assert units == 14
    src = """FUNCTION_BLOCK F
VAR_INPUT a : INT; b : INT; END_VAR
END_FUNCTION_BLOCK
PROGRAM Main
VAR f : F; x : INT := 5; END_VAR
f(a := 1, b := x);
END_PROGRAM
"""
    assert _scan_ps(src) == units * PICOSECONDS_PER_UNIT


# ------------------------------------------------------------------ the optimiser switch

def test_st_runtime_optimise_takes_a_comma_separated_list_of_passes(monkeypatch):
    # optimise/__init__.py: ST_RUNTIME_OPTIMISE is `none`, `all` or a comma-separated list
    # of pass names (case and spaces around names do not matter): the passes named are on,
    # every other pass off.
    from dataclasses import fields

    from st_runtime.compiler import Optimisations

    monkeypatch.setenv("ST_RUNTIME_OPTIMISE", " Fold, CSE ,unroll ")
    chosen = Optimisations.from_environment()
    assert {f.name for f in fields(chosen) if getattr(chosen, f.name)} == {"fold", "cse", "unroll"}
    monkeypatch.setenv("ST_RUNTIME_OPTIMISE", "ranges,nosuchpass")
    with pytest.raises(ValueError, match="nosuchpass"):
        Optimisations.from_environment()


@pytest.mark.parametrize("statement", ["p := tab[i];", "tab[i] := p;"])
def test_the_estimated_time_of_a_structure_copied_from_or_to_an_array_element(statement):
    # A structure assignment moves its 3 INT members one by one (3 x `element`), and
    # locating tab[i] costs the load of i and one subscript: 3 * 2 + (1 + 2) = 9 units,
    # whichever side the element is on (cost.py's table).
    from st_runtime.compiler.cost import PICOSECONDS_PER_UNIT, WEIGHTS

    w = WEIGHTS
    units = 3 * w["element"] + w["load"] + w["index"]
    assert units == 9
    src = f"""TYPE P3 : STRUCT a : INT; b : INT; c : INT; END_STRUCT; END_TYPE
PROGRAM Main
VAR tab : ARRAY[1..2] OF P3; p : P3; i : INT := 2; END_VAR
{statement}
END_PROGRAM
"""
    assert _scan_ps(src) == units * PICOSECONDS_PER_UNIT


def test_the_estimated_time_of_a_for_whose_body_has_two_blocks():
    # FOR i := 1 TO 3: setup (load 1, load 3, store i) = 3 units.  Its body is two blocks:
    # the IF's test, charged up front with the loop for all 3 iterations
    # (3 x (loop 2 + load n, load 100, compare, branch = 4) = 18), and `n := n + 1` after
    # the IF, charged when it runs (3 x (load, load, int_op, store) = 12); the IF's branch
    # never runs (n stays below 100).  3 + 18 + 12 = 33 units (cost.py's table).
    from st_runtime.compiler.cost import PICOSECONDS_PER_UNIT, WEIGHTS

    w = WEIGHTS
    setup = 2 * w["load"] + w["store"]
    head = w["loop"] + 2 * w["load"] + w["compare"] + w["branch"]
    increment = 2 * w["load"] + w["int_op"] + w["store"]
    units = setup + 3 * head + 3 * increment
    assert units == 33
    src = """PROGRAM Main
VAR i : INT; n : INT; END_VAR
FOR i := 1 TO 3 DO
    IF n > 100 THEN n := 0; END_IF;
    n := n + 1;
END_FOR;
END_PROGRAM
"""
    assert _scan_ps(src) == units * PICOSECONDS_PER_UNIT


# ------------------------------------------------------------------ seed 20's survivors

def faults(plc):
    return [(f.code, f.line, f.message) for f in plc.faults]


def test_mod_and_integer_division_by_a_zero_variable_fault_with_their_messages():
    # IEC 61131-3: an integer division or MOD by zero is an error; here F-DIV-ZERO with the
    # same messages as the library's int_div / int_mod (values.py), at the statement's line.
    main, plc = run("""PROGRAM Main
VAR a : DINT := 7; b : DINT; q : DINT := 5; r : DINT := 6; END_VAR
q := a / b;
r := a MOD b;
END_PROGRAM
""")
    assert faults(plc) == [("F-DIV-ZERO", 3, "integer division by zero"), ("F-DIV-ZERO", 4, "MOD by zero")]
    assert (main["q"], main["r"]) == (5, 6)      # a faulting statement stores nothing


def test_an_index_summed_from_two_loop_variables_is_checked_at_its_low_end(monkeypatch):
    # i runs 1..3 and j -2..0, so i + j runs -1..3: below the array's 0..3 when i = 1 and
    # j = -2 (and j = -1 gives 0, in bounds).  The loops are kept as loops (no unrolling),
    # so the index is checked at run time: F-INDEX for (1, -2), the only pair below 0.
    monkeypatch.setenv("ST_RUNTIME_OPTIMISE", "none")
    main, plc = run("""PROGRAM Main
VAR arr : ARRAY[0..3] OF INT := [10, 20, 30, 40]; i : INT; j : INT; s : INT; END_VAR
FOR i := 1 TO 3 DO
    FOR j := -2 TO 0 DO
        s := s + arr[i + j];
    END_FOR;
END_FOR;
END_PROGRAM
""")
    assert [(f.code, f.line) for f in plc.faults] == [("F-INDEX", 5)]
    # the other 8 pairs: i + j = 0, 1 (i = 1); 0, 1, 2 (i = 2); 1, 2, 3 (i = 3)
    assert main["s"] == (10 + 20) + (10 + 20 + 30) + (20 + 30 + 40)


def test_the_estimated_time_of_an_array_passed_by_value():
    # An input of ARRAY[1..4] OF INT is passed by value, element by element: 4 x `argument`
    # (no load of a whole array); with the call of an FB written in ST (empty body):
    # 10 + 4 = 14 units (cost.py's table).
    from st_runtime.compiler.cost import PICOSECONDS_PER_UNIT, WEIGHTS

    units = WEIGHTS["call"] + 4 * WEIGHTS["argument"]
    assert units == 14
    src = """FUNCTION_BLOCK F
VAR_INPUT v : ARRAY[1..4] OF INT; END_VAR
END_FUNCTION_BLOCK
PROGRAM Main
VAR f : F; a : ARRAY[1..4] OF INT; END_VAR
f(v := a);
END_PROGRAM
"""
    assert _scan_ps(src) == units * PICOSECONDS_PER_UNIT


def test_continue_in_a_for_over_a_global_still_steps_the_variable():
    # A global control variable makes FOR a loop that tests the variable each time; CONTINUE
    # must still add the step (IEC 61131-3 ed. 3, CONTINUE: on to the next iteration).
    # g = 1, 3, 5, 7, 9: CONTINUE at g = 3 skips one count, so n = 4; g ends at 11.
    main, plc = run("""VAR_GLOBAL g : INT; END_VAR
PROGRAM Main
VAR n : INT; END_VAR
FOR g := 1 TO 10 BY 2 DO
    IF g = 3 THEN CONTINUE; END_IF;
    n := n + 1;
END_FOR;
END_PROGRAM
""")
    assert plc.faults == []
    assert (main["n"], plc.globals["g"]) == (4, 11)


def test_a_while_loop_forgets_what_it_knew_of_a_variable_its_body_changes():
    # i := 4 before the loop, but the body counts i down to 0: the read arr[i] must be
    # checked each time, so i = 0 (below arr's 1..4) is F-INDEX at line 5 and that
    # statement stores nothing; s = 40 + 30 + 20 + 10 = 100, and the loop ends at i = -1.
    main, plc = run("""PROGRAM Main
VAR arr : ARRAY[1..4] OF INT := [10, 20, 30, 40]; i : INT; s : INT; END_VAR
i := 4;
WHILE i >= 0 DO
    s := s + arr[i];
    i := i - 1;
END_WHILE;
END_PROGRAM
""")
    assert [(f.code, f.line) for f in plc.faults] == [("F-INDEX", 5)]
    assert (main["s"], main["i"]) == (100, -1)
