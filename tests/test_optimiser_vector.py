"""The `vector` pass (st_runtime/compiler/optimise/vector.py): long runs of float `+ - *`
computed with NumPy give Python's floats bit for bit, and fall back to Python where NumPy
could differ (inf, NaN, values that may overflow).

The reference is the same program compiled without the pass (every other pass on), and
for the determinant the Leibniz formula written out in Python in this file (the same
products left to right, added in the table's order)."""

from __future__ import annotations

import itertools
import math
import random
import re
import struct
from dataclasses import replace

import pytest

from st_runtime import api
from st_runtime.compiler import Optimisations, compile_program
from st_runtime.compiler.optimise import vector
from test_optimiser_equivalence import _Context

ON = replace(Optimisations(), native=False, kernels=False)   # NumPy's kernel (the native one: test_optimiser_native.py;
#                                                            kernels.py's runs: test_optimiser_kernels.py)
NO_VECTOR = replace(ON, vector=False)
N = 5
PERMUTATIONS = list(itertools.permutations(range(1, N + 1)))       # lexicographic


def _sign(p) -> int:
    inversions = sum(1 for i in range(N) for j in range(i + 1, N) if p[i] > p[j])
    return -1 if inversions % 2 else 1


LEIBNIZ5 = f"""
FUNCTION_BLOCK Det5
VAR_OUTPUT D : LREAL; END_VAR
VAR_IN_OUT M : ARRAY[1..{N}, 1..{N}] OF LREAL; END_VAR
VAR CONSTANT
    P : ARRAY[1..{len(PERMUTATIONS)}, 1..{N}] OF USINT := [{", ".join(str(x) for p in PERMUTATIONS for x in p)}];
    S : ARRAY[1..{len(PERMUTATIONS)}] OF SINT := [{", ".join(str(_sign(p)) for p in PERMUTATIONS)}];
END_VAR
VAR T : INT; X : LREAL; END_VAR
D := 0.0;
FOR T := 1 TO {len(PERMUTATIONS)} DO
    X := M[1, P[T, 1]] * M[2, P[T, 2]] * M[3, P[T, 3]] * M[4, P[T, 4]] * M[5, P[T, 5]];
    IF S[T] > 0 THEN D := D + X; ELSE D := D - X; END_IF;
END_FOR;
END_FUNCTION_BLOCK
"""


def _leibniz(m: list[float]) -> float:
    d = 0.0
    for p in PERMUTATIONS:
        x = m[p[0] - 1] * m[N + p[1] - 1] * m[2 * N + p[2] - 1] * m[3 * N + p[3] - 1] * m[4 * N + p[4] - 1]
        d = d + x if _sign(p) > 0 else d - x
    return d


def _bits(x) -> bytes:
    return struct.pack("<d", x)


@pytest.fixture(scope="module")
def builds():
    program = api.load_text(LEIBNIZ5).program
    return {name: compile_program(program, optimise=o) for name, o in (("on", ON), ("off", NO_VECTOR))}


def helpers_in(compiled) -> list:
    """The Vectorised helpers a build calls (the namespace binds each one's `run`)."""
    return [v.__self__ for v in compiled.namespace.values() if isinstance(getattr(v, "__self__", None), vector.Vectorised)]


def _run(compiled, matrix):
    fb, context = compiled.new("Det5"), _Context()
    fb.v_M = list(matrix)
    type(fb).execute(fb, context)
    return fb, context


def test_the_pass_fires_on_a_5x5_leibniz_table(builds):
    on, off = builds["on"].python_sources["DET5"], builds["off"].python_sources["DET5"]
    assert re.search(r"v_D, v_X, = _k\d+\(v_M, \(v_D, \)\)", on) and "v_D, v_X, = " not in off
    # M is passed whole: of its reads before the region only the highest stays, the probe
    # that faults exactly when one of them would (an unconnected M)
    assert re.findall(r"= v_M\[(\d+)\]$", on, re.M) == [str(N * N - 1)]
    assert "((v_D + " in off and "((v_D + " not in on      # the fused sums: gone with the pass
    helpers = helpers_in(builds["on"])
    assert len(helpers) == 1
    assert [stop - start for _, _, start, stop in helpers[0].levels] == [20, 60, 120, 120]   # partial products
    assert not helpers_in(builds["off"])



def test_the_last_level_reads_its_left_operands_in_place(builds):
    """The last factor's level multiplies each product of four factors (the level before,
    each used once, in turn) by its one remaining column: it reads them where they are and
    gathers only the 120 right operands; the levels before gather both operands (2 x 20,
    2 x 60, 2 x 120).  The determinants are the Leibniz formula's bit for bit (the tests
    around)."""
    helper = helpers_in(builds["on"])[0]
    assert [len(gathered) for gathered, _, _, _ in helper.levels] == [40, 120, 240, 120]
    *before, last = helper.firsts
    assert before == [None, None, None]
    assert last == helper.levels[2][2]         # where the level before starts
    m = [float((3 * k) % 11) - 5.0 for k in range(N * N)]
    fb, _ = _run(builds["on"], m)
    assert _bits(fb.v_D) == _bits(_leibniz(m))


def test_the_sum_starts_in_the_slot_of_its_head(builds):
    """D, the chain's head, is the input placed last (after M's 25 elements): the chain's
    first slot is D's own, so no call copies it there; the sign 1.0 and the accumulate
    leave it as it is (the determinants are checked bit for bit in the tests around)."""
    helper = helpers_in(builds["on"])[0]
    (head, terms, _, start, stop), = helper.chains
    assert head == start == N * N and terms is None and stop - start == 1 + len(PERMUTATIONS)
    m = [float(k % 7) - 3.0 for k in range(N * N)]
    fb, _ = _run(builds["on"], m)
    assert _bits(fb.v_D) == _bits(_leibniz(m))
    assert _bits(helper.buffer[head]) == _bits(0.0)       # D := 0.0, as passed, after the sum


@pytest.mark.parametrize("lefts, expected", [
    ([5, 6, 7], 5),                     # in turn, each once
    ([7], 7),
    ([3, 3, 4, 4], None),               # twice each
    ([2, 1, 0], None),                  # not in turn
    ([3, 5], None),                     # 4 is not a left operand
])
def test_in_place_reads_left_operands_that_are_consecutive_values_in_turn(lefts, expected):
    assert vector._in_place(lefts) == expected


SPECIALS = [0.0, -0.0, math.inf, -math.inf, math.nan, 1e308, -1e200, 5e-324, -2.5e-310, 1e60]


def test_determinants_and_state_are_bit_identical(builds):
    rng = random.Random(2026)
    for trial in range(400):
        m = [rng.uniform(-10, 10) * 10.0 ** rng.randint(-40, 40) for _ in range(N * N)]
        if trial % 4 == 0:
            for _ in range(rng.randint(1, 3)):
                m[rng.randrange(N * N)] = rng.choice(SPECIALS)
        if trial % 4 == 1:
            m = [rng.choice([0.0, -0.0, 1.0, -1.0, 0.5]) for _ in range(N * N)]    # exact zeros
        got = {name: _run(c, m) for name, c in builds.items()}
        (fb_on, ctx_on), (fb_off, ctx_off) = got["on"], got["off"]
        for slot in ("v_D", "v_X"):
            a, b = getattr(fb_on, slot), getattr(fb_off, slot)
            assert (math.isnan(a) and math.isnan(b)) or _bits(a) == _bits(b), (trial, slot, a, b)
        assert fb_on.v_T == fb_off.v_T == len(PERMUTATIONS) + 1
        assert ctx_on.budget == ctx_off.budget and ctx_on.faults == ctx_off.faults == []
        expected = _leibniz(m)
        assert (math.isnan(expected) and math.isnan(fb_on.v_D)) or _bits(expected) == _bits(fb_on.v_D)


def test_a_hand_worked_determinant(builds):
    """diag(1, 2, 3, 4, 5) with a 1 in the corner above it: the determinant is 1*2*3*4*5 = 120."""
    m = [0.0] * (N * N)
    for i in range(N):
        m[i * N + i] = float(i + 1)
    m[N - 1] = 1.0
    fb, _ = _run(builds["on"], m)
    assert fb.v_D == 120.0


def test_an_unconnected_matrix_faults_as_without_the_pass(builds):
    outcomes = []
    for compiled in builds.values():
        fb, context = compiled.new("Det5"), _Context()
        type(fb).execute(fb, context)
        outcomes.append((context.faults, context.budget))
    assert outcomes[0] == outcomes[1] and len(outcomes[0][0]) == len(PERMUTATIONS)


def _register(bound):
    def register(value):
        bound[f"_k{len(bound)}"] = value
        return f"_k{len(bound) - 1}"
    return register


def _chain_lines(count: int, head: str = "v_D") -> list[str]:
    lines = []
    for i in range(count):
        lines.append(f"    _t9 = (_t{i % 3 + 1} * _t{(i + 1) % 3 + 1})")
        lines.append(f"    {head} = (({head} + (_t9 * _t4)) - ((_t9 * _t5) * {'-0.5' if i % 2 else '0.5'}))")
    return lines


def test_runs_that_do_not_qualify_stay_as_they_are():
    floats = {"_t1", "_t2", "_t3", "_t4", "_t5", "v_D"}
    short = _chain_lines(5)
    lines = list(short)
    vector.vectorise(lines, 0, len(lines), floats.__contains__, _register({}))
    assert lines == short                               # too few operations to repay NumPy
    long = _chain_lines(200)
    lines = list(long)
    vector.vectorise(lines, 0, len(lines), (floats - {"v_D"}).__contains__, _register({}))
    assert lines == long                                # v_D not known to be a float (an INT?)
    lines = list(long)
    lines.insert(100, "    v_D = _f32(v_D)")            # a call ends a run
    vector.vectorise(lines, 0, len(lines), floats.__contains__, _register({}))
    assert "    v_D = _f32(v_D)" in lines and len(lines) < len(long)


def test_a_run_becomes_one_call_with_python_results():
    floats = {"_t1", "_t2", "_t3", "_t4", "_t5", "v_D"}
    long = _chain_lines(200)
    bound = {}
    check = "    if _ctx.budget < _spent: _overrun(('X', 'x.st', 3, 1))"
    lines = long + ["    v_N = 7", check]
    vector.vectorise(lines, 0, len(lines), floats.__contains__, _register(bound))
    call = re.fullmatch(r"    v_D, = _k0\(None, \((.*), \)\)", lines[0])
    assert call is not None and lines[1:] == ["    v_N = 7", check]     # the literal store kept; the check ends the run
    names = call.group(1).split(", ")
    assert sorted(names) == sorted(floats)
    values = {"_t1": 1.25, "_t2": -0.75, "_t3": 3.0, "_t4": 1e-3, "_t5": 7.0, "v_D": 0.1}
    for changed in ({}, {"_t1": 1e200}, {"_t4": math.inf}, {"_t2": -0.0, "_t3": 0.0}):
        env = dict(values, **changed)
        got = bound["_k0"](None, tuple(env[name] for name in names))
        exec("\n".join(line[4:] for line in long), {}, env)           # the lines as Python runs them
        assert (math.isnan(got[0]) and math.isnan(env["v_D"])) or _bits(got[0]) == _bits(env["v_D"]), changed


MAIN5 = LEIBNIZ5 + """
PROGRAM Main
VAR A : ARRAY[1..5, 1..5] OF LREAL := [2.5, -1.0, 0.1, 3.0, 7.0, -2.0, 0.3, 1.0E10, 4.0, 1.5,
                                       0.25, 6.0, -3.5, 2.0, 1.0, 9.0, 0.5, -0.75, 8.0, 2.5,
                                       1.0, 1.0, 2.0, 3.0, 5.0];
    F : Det5; K : INT; Out : LREAL; END_VAR
FOR K := 1 TO 5 DO A[K, K] := A[K, K] * 1.0000001; END_FOR;
F(M := A);
Out := F.D;
END_PROGRAM
"""


@pytest.mark.parametrize("budget_ns", [1_000, 5_000, 20_000, 60_000, 500_000])
def test_f_period_lands_on_the_same_statement_and_state(budget_ns):
    """Every pass off against every pass on (vector included): faults (code, line, scan),
    instance states and globals equal bit for bit, also when the period is exceeded."""
    from test_optimiser_equivalence import run_both

    off, on = run_both(api.load_text(MAIN5).program, 3, budget_ns)
    assert on == off


def test_inputs_that_struct_cannot_pack_take_the_python_run(builds):
    """The inputs are written into NumPy's buffer by one struct.pack_into; an input it
    cannot pack as a double (an int beyond the double range, a string) makes the call
    compute the run in Python (`exact`), as an input NumPy must not see does."""
    helper, = helpers_in(builds["on"])
    m = [float(i % 7) - 3.0 for i in range(N * N)]
    assert helper(m, (0.0,)) == helper.exact(m, (0.0,))
    assert helper(m, (0,)) == helper.exact(m, (0,))                    # an int packs exactly
    huge = list(m)
    huge[0] = 10 ** 400                    # OverflowError in pack; Python's `*` raises it too
    for run in (helper, helper.exact):
        with pytest.raises(OverflowError):
            run(huge, (0.0,))
    assert helper(m, (0.0, 0.0)) == helper.exact(m, (0.0, 0.0))         # struct.error: count
