"""Reuse of an array element read again within one iteration of a FOR loop
(st_runtime/compiler/optimise/reads.py, with the `cse` switch): the first read keeps the
element, the later ones of the iteration read the name, where nothing in the body can change
an array (assignments to Python names only, no call but the numeric library) and the first
read is always evaluated.  Results, faults and the time charged are the same with and without.
"""

from __future__ import annotations

import pytest

from st_runtime import api
from st_runtime.compiler import Optimisations
from st_runtime.compiler.optimise.reads import share_in_loops, shared_reads
from test_optimiser_equivalence import compiled_lines, run_both, same_alone_and_with_all, stopped_runs


def _temps():
    names = iter(range(50, 100))
    return lambda: f"_t{next(names)}"


# By hand: A[k] is read three times (the first keeps it), W[k] twice, B[k] once (no name);
# the first read of C[k] is on a line with a conditional expression (it may be skipped), so
# it keeps nothing and its later read reads the list again.
_BODY = ["    _t4 = v_K - 1",
         "    v_P = ((v_W[_t4] * 2.0) - v_A[_t4])",
         "    v_S = (v_S + (v_A[_t4] * (_m_sin(v_P) if _c3 else _sf_SIN(v_P))))",
         "    v_Q = (v_C[_t4] if v_P > 0.0 else 1.0)",
         "    v_C2 = ((v_C2 + (v_A[_t4] * v_B[_t4])) + v_W[_t4]) + v_C[_t4]"]
_SHARED = ["    _t4 = v_K - 1",
           "    v_P = (((_t50 := v_W[_t4]) * 2.0) - (_t51 := v_A[_t4]))",
           "    v_S = (v_S + (_t51 * (_m_sin(v_P) if _c3 else _sf_SIN(v_P))))",
           "    v_Q = (v_C[_t4] if v_P > 0.0 else 1.0)",
           "    v_C2 = ((v_C2 + (_t51 * v_B[_t4])) + _t50) + v_C[_t4]"]


def test_an_element_read_again_in_the_iteration_is_read_once_by_hand():
    assert shared_reads(_BODY, _temps()) == _SHARED


# Nothing is kept where something between may change the element: an element store, an
# attribute store, a call of anything but the numeric library, a line that is not an
# assignment (an IF, a charge check), a chained assignment (it stores twice), an index set by
# `:=` inside a line; nor past a store of the index or of the array's name.
@pytest.mark.parametrize("between", [
    "    v_A[_t4] = 1.0", "    self.v_X = 1.0", "    v_X = _fn_F(_ctx, v_A)", "    v_X = v_FB.execute(_ctx)",
    "    v_X = _m_0_GET(self)", "    if v_P:", "    if _ctx.budget < _spent: _overrun(1)",
    "    v_X = _t4 = 1", "    v_X = ((_t4 := 2) * 1.0)"])
def test_nothing_is_kept_across_what_may_change_an_array(between):
    body = ["    _t4 = v_K - 1", "    v_P = (v_A[_t4] * 2.0)", between, "    v_S = (v_S + v_A[_t4])"]
    assert shared_reads(body, _temps()) == body


@pytest.mark.parametrize("store", ["    _t4 = (_t4 + 1)", "    v_A = v_B", "    _t4 += 1"])
def test_a_store_of_the_index_or_the_array_ends_the_reuse(store):
    body = ["    _t4 = v_K - 1", "    v_P = (v_A[_t4] * 2.0)", store, "    v_S = (v_S + v_A[_t4])"]
    assert shared_reads(body, _temps()) == body
    kept = ["    _t4 = v_K - 1", "    v_P = (v_A[_t4] * 2.0)", "    v_Q = v_A[_t4]", store, "    v_S = (v_S + v_A[_t4])"]
    assert shared_reads(kept, _temps()) == ["    _t4 = v_K - 1", "    v_P = ((_t50 := v_A[_t4]) * 2.0)",
                                             "    v_Q = _t50", store, "    v_S = (v_S + v_A[_t4])"]


# A line that reads an element and then stores its index (or its array): the line's own read
# comes first, the store ends the element's life, so the read keeps nothing (no name made for
# a value no later line may use).
@pytest.mark.parametrize("store", ["    _t4 = (v_A[_t4] + 1)", "    _t4 += v_A[_t4]"])
def test_a_line_storing_the_index_it_reads_keeps_nothing(store):
    body = ["    _t4 = v_K - 1", store, "    v_S = (v_S + v_A[_t4])"]
    assert shared_reads(body, _temps()) == body



# Session 21 (h-mut-s21): only a `for` line's body is rewritten; another block's (an `if`,
# a `while`, ending with ":" as well) keeps its lines, the element read twice (kills
# share_in_loops_4, which took any line ending with ":").
def test_only_the_body_of_a_for_loop_is_rewritten():
    body = ["    _t4 = v_K - 1", "    v_P = (v_A[_t4] * 2.0)", "    v_S = (v_S + v_A[_t4])"]
    for head in ("if v_Z:", "while v_Z:"):
        lines = [head, *body]
        share_in_loops(lines, 0, _temps())
        assert lines == [head, *body]
    lines = ["for v_K in _r1:", *body]
    share_in_loops(lines, 0, _temps())
    assert lines == ["for v_K in _r1:", "    _t4 = v_K - 1", "    v_P = ((_t50 := v_A[_t4]) * 2.0)", "    v_S = (v_S + _t50)"]

# A program: the loop's end is known only at run time (N MOD 10), so the loop runs in two
# versions, one for an end inside the arrays (its reads kept) and the checked one, which
# faults at N = 9 (K = 9 is out of A's and W's bounds).
READS = """
PROGRAM Main
VAR N, K : INT; A, W : ARRAY[1..8] OF LREAL; S, C, P : LREAL; END_VAR
N := N + 1;
IF N = 1 THEN
    FOR K := 1 TO 8 DO A[K] := INT_TO_LREAL(K) * 0.5; W[K] := 1.0 / INT_TO_LREAL(K); END_FOR;
END_IF;
S := 0.0;
C := 0.0;
FOR K := 1 TO N MOD 10 DO
    P := W[K] * 2.0 - A[K];
    S := S + A[K] * SIN(P);
    C := C + A[K] * COS(P) + W[K];
END_FOR;
END_PROGRAM
"""


def _reads():
    return api.load_text(READS).program


def test_the_loop_reads_each_element_once_an_iteration():
    lines = compiled_lines(_reads(), "MAIN", Optimisations())
    body = lines[lines.index("if _t1.stop <= 9:") + 2:lines.index("if _t1.stop <= 9:") + 7]
    assert sum(line.count("v_A[") for line in body) == 1 and sum(line.count("v_W[") for line in body) == 1
    plain = compiled_lines(_reads(), "MAIN", Optimisations(cse=False))
    assert sum(line.count("v_A[_t") for line in plain) > sum(line.count("v_A[_t") for line in lines)


def test_the_scans_see_the_same_with_and_without_the_reuse():
    alone = same_alone_and_with_all(_reads, 12, "cse")
    assert [(fault[0], fault[4]) for fault in alone[0]][:1] == [("F-INDEX", 9)]
    outcomes = stopped_runs(_reads(), 12, Optimisations(cse=False), Optimisations(), Optimisations.none())
    assert outcomes[0] == outcomes[1] == outcomes[2]


@pytest.mark.parametrize("budget_ns", [300, 1_500, 5_000])
def test_f_period_lands_on_the_same_statement_with_the_reuse(budget_ns):
    off, on = run_both(_reads(), 12, budget_ns, optimise=Optimisations())
    assert on == off
