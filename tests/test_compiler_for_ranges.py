"""A FOR of step 1 from 0 or 1 whose end is known only at run time takes its range from a
table made once (support.FROM_0 and FROM_1, ends below SMALL_END), else from `range()`.

Expected values by hand (IEC 61131-3: FOR runs while the variable is at most the end, and
after a normal end the variable holds the first value past it; no iteration leaves it at the
start): the sum of 1..N is N (N + 1) / 2, of 0..N the same, and the loop runs N or N + 1
times."""

from __future__ import annotations

import re

import pytest

from optimiser_helpers import run_main
from st_runtime import api
from st_runtime.compiler import Optimisations, compile_program, support

LOOPS = """
PROGRAM Main
VAR N : DINT; I, J : DINT; Sum1, Sum0, Runs1, Runs0 : DINT; END_VAR
Sum1 := 0; Sum0 := 0; Runs1 := 0; Runs0 := 0;
FOR I := 1 TO N DO Sum1 := Sum1 + I; Runs1 := Runs1 + 1; END_FOR;
FOR J := 0 TO N DO Sum0 := Sum0 + J; Runs0 := Runs0 + 1; END_FOR;
END_PROGRAM
"""
OUTPUTS = ("Sum1", "Runs1", "I", "Sum0", "Runs0", "J")


def by_hand(n: int) -> tuple:
    runs1, runs0 = max(n, 0), max(n + 1, 0)
    return (n * (n + 1) // 2 if n > 0 else 0, runs1, n + 1 if n >= 1 else 1,
            n * (n + 1) // 2 if n >= 0 else 0, runs0, n + 1 if n >= 0 else 0)


@pytest.mark.parametrize("n", [-3, -1, 0, 1, 2, 9, support.SMALL_END - 1, support.SMALL_END, 100])
@pytest.mark.parametrize("optimise", [Optimisations.none(), Optimisations()], ids=["none", "all"])
def test_a_loop_to_a_run_time_end_runs_from_its_start_to_its_end(n, optimise):
    values, faults, _ = run_main(LOOPS, optimise, {"N": n}, OUTPUTS)
    assert faults == []
    assert values == by_hand(n)


def test_the_tables_hold_the_ranges_from_0_and_1_to_each_small_end():
    assert len(support.FROM_0) == len(support.FROM_1) == support.SMALL_END
    for end in range(support.SMALL_END):
        assert support.FROM_0[end] == range(0, end + 1) and support.FROM_1[end] == range(1, end + 1)


def test_the_loops_take_their_ranges_from_the_tables():
    source = compile_program(api.load_text(LOOPS).program, optimise=Optimisations()).python_sources["MAIN"]
    assert re.search(rf"_FROM_1\[(_t\d+)\] if 0 <= \1 < {support.SMALL_END} else range\(1, \1 \+ 1\)", source)
    assert "_FROM_0[" in source and source.count("range(") == 2


# Session 21 (h-mut-s21): the loops the tables do not serve (statements._for_range's test of
# a step of 1 from a literal 0 or 1; kills _for_range_66 and _67, which took `_FROM_2`,
# `_FROM_None` or the table of step 1 for them).
OTHERS = """
PROGRAM Main
VAR N, S : DINT; I, J, K : DINT; Sum2, SumS, SumE : DINT; END_VAR
Sum2 := 0; SumS := 0; SumE := 0;
FOR I := 2 TO N DO Sum2 := Sum2 + I; END_FOR;
FOR J := S TO N DO SumS := SumS + J; END_FOR;
FOR K := 0 TO N BY 2 DO SumE := SumE + K; END_FOR;
END_PROGRAM
"""
OTHER_OUTPUTS = ("Sum2", "I", "SumS", "J", "SumE", "K")


@pytest.mark.parametrize("n, s, want", [
    (5, 1, (2 + 3 + 4 + 5, 6, 1 + 2 + 3 + 4 + 5, 6, 0 + 2 + 4, 6)),
    (6, 3, (2 + 3 + 4 + 5 + 6, 7, 3 + 4 + 5 + 6, 7, 0 + 2 + 4 + 6, 8)),
    (1, 0, (0, 2, 0 + 1, 2, 0, 2))])
@pytest.mark.parametrize("optimise", [Optimisations.none(), Optimisations()], ids=["none", "all"])
def test_a_loop_from_another_start_or_by_another_step_runs_its_own_range(n, s, want, optimise):
    """From the literal 2, from a variable, and from 0 BY 2, each to a run-time end: the
    values by hand (IEC 61131-3: the variable runs start, start + step, ... while at most the
    end, and holds the first value past it afterwards)."""
    values, faults, _ = run_main(OTHERS, optimise, {"N": n, "S": s}, OTHER_OUTPUTS)
    assert faults == []
    assert values == want
    source = compile_program(api.load_text(OTHERS).program, optimise=optimise).python_sources["MAIN"]
    assert "_FROM_" not in source
