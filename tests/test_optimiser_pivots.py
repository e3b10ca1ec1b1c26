"""`pivots` (st_runtime/compiler/optimise/pivots.py): a pivot search's best `abs` kept in a local.

Each program runs with the pass on and off: the same results, faults, arrays and NJ time per
scan, and the values by hand.  The cases a wrong rewrite gets wrong: a candidate larger than
the best (the row moves, the kept `abs` must follow), equal (it stays), a NaN, a zero pivot,
and columns whose elements were changed (held in `scalars`' locals, written back before the
search) between the searches.
"""

from __future__ import annotations

import math
from dataclasses import replace

import pytest

from st_runtime.api import load_text
from st_runtime.compiler import Optimisations, compile_program
from st_runtime.compiler.optimise import pivots

from optimiser_helpers import run_main

ON = Optimisations()
OFF = replace(ON, pivots=False)

# The LU's search for each column K, then every column from K on mapped x -> 2x - 3 (so the
# next search reads elements stored since the last); Pick holds the pivot rows as digits,
# Zeros counts the zero pivots.
SEARCH = """
FUNCTION Pick : INT
VAR_IN_OUT M : ARRAY[1..4, 1..4] OF LREAL; END_VAR
VAR_OUTPUT Zeros : INT; END_VAR
VAR K, Row, C, PivotRow : INT; END_VAR
FOR K := 1 TO 4 DO
    PivotRow := K;
    FOR Row := K + 1 TO 4 DO
        IF ABS(M[Row, K]) > ABS(M[PivotRow, K]) THEN
            PivotRow := Row;
        END_IF;
    END_FOR;
    IF ABS(M[PivotRow, K]) <= 0.0 THEN
        Zeros := Zeros + 1;
    END_IF;
    Pick := Pick * 10 + PivotRow;
    FOR Row := 1 TO 4 DO
        FOR C := K TO 4 DO
            M[Row, C] := M[Row, C] * 2.0 - 3.0;
        END_FOR;
    END_FOR;
END_FOR;
END_FUNCTION

PROGRAM Main
VAR
    X : ARRAY[1..4, 1..4] OF LREAL;
    R, Zeros : INT;
END_VAR
R := Pick(M := X, Zeros => Zeros);
END_PROGRAM
"""

# Columns by hand.  1: [1, -5, 3, 2], row 2 (abs 5).  2: [2, 0, -7, 4] -> 2x - 3 = [1, -3,
# -17, 5]; from row 2 (3): row 3 (17), row 4 (5 < 17): row 3.  3: [0, 1, 2, 6] -> 4x - 9 =
# [-9, -5, -1, 15]; from row 3 (1): row 4.  4: M[4, 4] = 2.625 -> 8x - 21 = 0: row 4, a zero.
COLUMNS = [[1.0, 2.0, 0.0, 1.0], [-5.0, 0.0, 1.0, 1.0], [3.0, -7.0, 2.0, 1.0], [2.0, 4.0, 6.0, 2.625]]


def _run(optimise: Optimisations, x):
    (r, zeros, matrix), faults, times = run_main(SEARCH, optimise, {"X": x}, ("R", "Zeros", "X"))
    return r, zeros, repr(matrix), faults, times


def _same(x):
    on = _run(ON, x)
    assert on == _run(OFF, x)
    return on


def _with(row: int, column: int, value: float):
    x = [list(r) for r in COLUMNS]
    x[row][column] = value
    return x


def test_the_fast_copy_keeps_the_best_abs():
    """The pass applies (what the other tests run is the rewritten code); off, no `_best`."""
    program = load_text(SEARCH, "t.st").program
    code = compile_program(program, optimise=ON).python_sources["PICK"]
    fast = code.split("\n        else:\n", 1)[0]
    assert "_ctx.budget >= " in fast and "_best = abs(v_M[v_PIVOTROW * 4 - " in fast
    assert "(_cand := abs(v_M_e" in fast and "if (_best <= 0.0):" in fast
    assert "_best" not in compile_program(program, optimise=OFF).python_sources["PICK"]


def test_the_pivot_rows_by_hand():
    r, zeros, _, faults, _ = _same(COLUMNS)
    assert (r, zeros, faults) == (2344, 1, [])


@pytest.mark.parametrize("value, rows", [
    (5.0, 1344),        # column 1 [5, -5, 3, 2]: -5 is not larger: row 1 stays
    (-6.0, 1344),       # [-6, -5, 3, 2]: row 1
    (math.nan, 1344),   # abs(NaN) > nothing and nothing > it: row 1
    (0.0, 2344),        # [0, -5, 3, 2]: row 2
])
def test_the_first_column(value, rows):
    r, zeros, _, faults, _ = _same(_with(0, 0, value))
    assert (r, zeros, faults) == (rows, 1, [])


def test_a_zero_pivot_in_a_searched_column():
    # column 2 all zeros after 2x - 3 (x = 1.5): the search keeps row 2, whose abs is 0
    x = [list(r) for r in COLUMNS]
    for row in x:
        row[1] = 1.5
    r, zeros, _, faults, _ = _same(x)
    assert (r, zeros, faults) == (2244, 2, [])


# The rewrite on lines written by hand (the compiler's shapes): what it must and must not do.

def _candidate(element: str, row: int, charge: str = "_spent += 5") -> list[str]:
    return [f"if (abs({element}) > abs(v_X[v_P * 3 - 3])):", f"    {charge}", f"    v_P = {row}"]


def _keep(lines: list[str]) -> list[str]:
    lines = list(lines)
    pivots.keep(lines, 0)
    return lines


def test_a_chain_with_its_zero_test():
    lines = [*_candidate("v_X[3]", 2), "v_R = 7", *_candidate("v_X_e6", 3), "if (-0.0 <= v_X[v_P * 3 - 3] <= 0.0):",
             "    v_Z = True"]
    assert _keep(lines) == [
        "_best = abs(v_X[v_P * 3 - 3])",
        "if ((_cand := abs(v_X[3])) > _best):", "    _spent += 5", "    v_P = 2", "    _best = _cand",
        "v_R = 7",
        "if ((_cand := abs(v_X_e6)) > _best):", "    _spent += 5", "    v_P = 3", "    _best = _cand",
        "if (_best <= 0.0):", "    v_Z = True"]


@pytest.mark.parametrize("lines", [
    _candidate("v_X[6]", 2),                        # the candidate is not the row moved to (3)
    _candidate("v_Y[3]", 2),                        # another list's element
    _candidate("v_X[3]", 2, "v_Q = 1"),             # a branch doing more than move the row
    [*_candidate("v_X[3]", 2), "elif v_Q:", "    v_P = 3"],
])
def test_a_test_that_is_no_pivot_move_stays(lines):
    assert _keep(lines) == lines


@pytest.mark.parametrize("between", ["v_X[0] = 1.0", "v_Y[0] = 1.0", "v_P = 1", "v_X = v_Y", "v_R = _f(v_Q)",
                                     "v_X_e6 = 2.0"])
def test_a_line_that_may_change_the_best_ends_the_chain(between):
    """After it the next test starts a chain of its own: the best element read again."""
    lines = [*_candidate("v_X[3]", 2), between, *_candidate("v_X[6]", 3), "if (-0.0 <= v_X[v_P * 3 - 3] <= 0.0):",
             "    v_Z = True"]
    kept = _keep(lines)
    assert kept.index(between) == 5 and kept[6] == "_best = abs(v_X[v_P * 3 - 3])"


def test_a_zero_test_of_another_element_or_bound_stays():
    for test in ("if (-0.0 <= v_X[v_P * 3 - 2] <= 0.0):", "if (-1.0 <= v_X[v_P * 3 - 3] <= 2.0):",
                 "if (-v_T <= v_X[v_P * 3 - 3] <= v_T):"):
        assert _keep([*_candidate("v_X[3]", 2), test])[-1] == test


# Session 20's rows (docs/mutation.md, "Session 20, session 19's new passes"): each expected
# list written from the module docstring's rewrite, by hand.

_BEST_LINE = "_best = abs(v_X[v_P * 3 - 3])"


def _kept_test(element: str, row: int, body=("    _spent += 5",)) -> list[str]:
    """A candidate test as the pass rewrites it (module docstring)."""
    return [f"if ((_cand := abs({element})) > _best):", *body, f"    v_P = {row}", "    _best = _cand"]


def test_a_chain_that_ends_the_lines():
    """The last test's body is the last line: the chain ends with the lines."""
    assert _keep(_candidate("v_X[3]", 2)) == [_BEST_LINE, *_kept_test("v_X[3]", 2)]


def test_a_branch_that_only_moves_the_row():
    lines = ["if (abs(v_X[3]) > abs(v_X[v_P * 3 - 3])):", "    v_P = 2", "v_R = 1"]
    assert _keep(lines) == [_BEST_LINE, *_kept_test("v_X[3]", 2, ()), "v_R = 1"]


def test_a_test_that_is_no_move_ends_the_chain_kept_so_far():
    """The second test's candidate (element 7) is not row 3's (3 * 3 - 3 = 6): the first test
    is rewritten, the second stays as written, reading the list."""
    second = _candidate("v_X[7]", 3)
    assert _keep([*_candidate("v_X[3]", 2), *second]) == [_BEST_LINE, *_kept_test("v_X[3]", 2), *second]


def test_a_test_that_is_no_move_after_other_lines_stays():
    """No chain, no `_best` line: the lines as they were, wherever the test stands."""
    lines = ["v_R = 7", *_candidate("v_X[6]", 2)]
    assert _keep(lines) == lines


def test_a_scale_other_than_the_offset():
    """`X[P * 4 - 2]`: row 2's element is 2 * 4 - 2 = 6 (a 4-column matrix's column 3)."""
    lines = ["if (abs(v_X[6]) > abs(v_X[v_P * 4 - 2])):", "    _spent += 5", "    v_P = 2"]
    assert _keep(lines) == ["_best = abs(v_X[v_P * 4 - 2])", *_kept_test("v_X[6]", 2)]


@pytest.mark.parametrize("line", ["    v_Q = _f(v_Y)", "    v_Q = v_Y"])
def test_a_branch_that_moves_the_row_and_does_more_stays(line):
    lines = [*_candidate("v_X[3]", 2), line]
    assert _keep(lines) == lines


def test_a_branch_that_does_not_move_the_row_stays():
    lines = ["if (abs(v_X[3]) > abs(v_X[v_P * 3 - 3])):", "    _spent += 5", "v_R = 1"]
    assert _keep(lines) == lines


def test_an_else_that_only_charges_is_kept_with_the_test():
    lines = [*_candidate("v_X[3]", 2), "else:", "    _spent += 3", "v_R = 1"]
    assert _keep(lines) == [_BEST_LINE, *_kept_test("v_X[3]", 2), "else:", "    _spent += 3", "v_R = 1"]


@pytest.mark.parametrize("body", [("    _spent += 3", "    v_Q = 1"), ("    v_Q = 1", "    _spent += 3")])
def test_an_else_that_does_more_than_charge_keeps_the_test(body):
    lines = [*_candidate("v_X[3]", 2), "else:", *body]
    assert _keep(lines) == lines


# Session 21's rows (docs/mutation.md, "Session 21, the compiler's unrun mutants"): where
# `_candidate_lines` finds the hint `) > abs(` in the joined text, and the line it names.

def test_a_blank_first_line_does_not_shift_the_candidates():
    """The line number counts every newline before the hint, the first one too (an empty
    `lines[start]`): the test on the next line is found and rewritten (kills _candidate_lines_5)."""
    assert _keep(["", *_candidate("v_X[3]", 2)]) == ["", _BEST_LINE, *_kept_test("v_X[3]", 2)]


def test_the_hint_at_the_very_start_of_the_lines_is_searched_on_from():
    """A first line that begins with the hint (not a test: no rewrite) does not end the
    search: the test after it is still found (kills _candidate_lines_9 and _10)."""
    first = ") > abs(v_Q)"
    assert _keep([first, *_candidate("v_X[3]", 2)]) == [first, _BEST_LINE, *_kept_test("v_X[3]", 2)]


def test_a_last_line_holding_the_hint_ends_the_search():
    """`ABS(Q) > ABS(R)` on the last line: the hint found there is the last (no newline after
    it), and the chain before it is still rewritten (kills _candidate_lines_30, which returned
    nothing for the lines found)."""
    last = "v_B = (abs(v_Q) > abs(v_R))"
    assert _keep([*_candidate("v_X[3]", 2), last]) == [_BEST_LINE, *_kept_test("v_X[3]", 2), last]


def test_every_chain_of_three_is_kept():
    """Three tests, each chain ended by a call before the next: each hint is a chain's start,
    the middle one too (kills _candidate_lines_36, whose `rfind` jumped to the last hint)."""
    call = "v_R = _f(v_Q)"
    lines = [*_candidate("v_X[3]", 2), call, *_candidate("v_X[6]", 3), call, *_candidate("v_X[9]", 4)]
    assert _keep(lines) == [_BEST_LINE, *_kept_test("v_X[3]", 2), call, _BEST_LINE, *_kept_test("v_X[6]", 3),
                            call, _BEST_LINE, *_kept_test("v_X[9]", 4)]
