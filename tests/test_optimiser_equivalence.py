"""The optimisation passes (st_runtime/compiler/optimise) change nothing a program can see.

Every snippet of the accept corpus and the example PLC are compiled twice,
with every pass off and with every pass on, and run scan by scan: the faults
(code, file, line, column, scan), the time charged per scan and the state of
every instance and of the globals must be equal bit for bit.  The same for a
seeded differential of 1,000 FK solves (the Leibniz-table kinematics:
poses, iteration counts, flags), and for F-PERIOD cut at many budgets inside
the unrolled determinant (the fault lands on the same statement, the state
left behind is the same).  `ST_RUNTIME_OPTIMISE=none` runs the rest of the
suite without the passes.
"""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from st_runtime import loader
from st_runtime.compiler import Optimisations, compile_program
from st_runtime.compiler.optimise import unguard
from st_runtime.controller import Controller
from st_runtime.objects import STObject

ROOT = Path(__file__).resolve().parent.parent
CORPUS = sorted((ROOT / "tests" / "corpus" / "accept").glob("*.st"))
OFF, ON = Optimisations.none(), Optimisations()


def snapshot(value, seen=None):
    """Instance state as nested tuples; floats by their bits (-0.0 and NaN payloads count)."""
    seen = set() if seen is None else seen
    if isinstance(value, float):
        return ("f", value.hex() if not math.isnan(value) else "nan")
    if isinstance(value, (bool, int, str, bytes)) or value is None:
        return value
    if isinstance(value, (list, tuple)):
        return tuple(snapshot(v, seen) for v in value)
    if isinstance(value, STObject):
        if id(value) in seen:
            return ("cycle",)
        seen.add(id(value))
        return (type(value).__name__,) + tuple(
            (slot, snapshot(getattr(value, slot, None), seen)) for slot in type(value).__slots__)
    return type(value).__name__          # references, native helpers: identity only


def run_both(program, scans: int, budget_ns: int = 500_000, optimise: Optimisations = ON):
    """(faults, states, times) of `scans` scans with the passes off and on (`optimise`)."""
    outcomes = []
    for optimise in (OFF, optimise):
        compiled = compile_program(program, optimise=optimise)
        controller = Controller(compiled, time_limit_ns=budget_ns)
        for pou in program.pous.values():
            if pou.kind == "PROGRAM":
                controller.add_program(pou.name)
        states = []
        for _ in range(scans):
            controller.run(1)
            states.append((snapshot(compiled.globals),
                           tuple((k, snapshot(v)) for k, v in sorted(controller.instances.items()))))
        faults = [(f.code, f.file, f.line, f.col, f.scan) for f in controller.faults]
        outcomes.append((faults, states))
    return outcomes


def compiled_lines(program, pou: str, optimise: Optimisations) -> list[str]:
    """The lines of `pou`'s generated Python, stripped: what the pass tests read."""
    return [line.strip() for line in compile_program(program, optimise=optimise).python_sources[pou].splitlines()]


def stopped_runs(program, scans: int, *optimisations: Optimisations) -> list:
    """With stop_on_fault, for each of `optimisations`: (faults (code, line, scan), Main's
    state, the budget left after each of `scans` scans: the time charged)."""
    outcomes = []
    for optimise in optimisations:
        controller = Controller(compile_program(program, optimise=optimise), stop_on_fault=True)
        main = controller.add_program("Main")
        charged = []
        for _ in range(scans):
            controller.run(1)
            charged.append(controller.ctx.budget)
        outcomes.append(([(f.code, f.line, f.scan) for f in controller.faults], snapshot(main), charged))
    return outcomes


def same_alone_and_with_all(make_program, scans: int, name: str):
    """Run `scans` scans with pass `name` alone and with every pass, each the same as with
    none; the outcome with the pass alone."""
    off, alone = run_both(make_program(), scans, optimise=Optimisations.only(name))
    assert alone == off
    off, every = run_both(make_program(), scans, optimise=ON)
    assert every == off
    return alone


@pytest.mark.parametrize("path", CORPUS, ids=[p.stem for p in CORPUS])
def test_corpus_snippet_runs_the_same_with_and_without_the_passes(path):
    result = loader.load([str(path)])
    if result.program is None:
        pytest.skip("not accepted by the checker in this build")
    off, on = run_both(result.program, 3)
    assert on == off


def test_example_plc_runs_the_same_with_and_without_the_passes():
    result = loader.load([str(p) for p in sorted((ROOT / "examples" / "plc").glob("*.st"))])
    off, on = run_both(result.program, 50)
    assert on == off


LEIBNIZ = """
FUNCTION_BLOCK Det3
VAR_OUTPUT D : LREAL; END_VAR
VAR_IN_OUT M : ARRAY[1..3, 1..3] OF LREAL; END_VAR
VAR CONSTANT
    P : ARRAY[1..6, 1..3] OF USINT := [1,2,3, 1,3,2, 2,1,3, 2,3,1, 3,1,2, 3,2,1];
    S : ARRAY[1..6] OF SINT := [1, -1, -1, 1, 1, -1];
END_VAR
VAR T : INT; X : LREAL; END_VAR
D := 0.0;
FOR T := 1 TO 6 DO
    X := M[1, P[T, 1]] * M[2, P[T, 2]] * M[3, P[T, 3]];
    IF S[T] > 0 THEN D := D + X; ELSE D := D - X; END_IF;
END_FOR;
END_FUNCTION_BLOCK
PROGRAM Main
VAR A : ARRAY[1..3, 1..3] OF LREAL := [2.5, -1.0, 0.1, 3.0, 7.0, -2.0, 0.3, 1.0e10, 4.0];
    F : Det3; G : Det3; K : INT; Out : LREAL; END_VAR
FOR K := 1 TO 3 DO A[K, K] := A[K, K] * 1.0000001; END_FOR;
F(M := A);
Out := F.D;
END_PROGRAM
"""


def _text_program(text: str):
    from st_runtime import api

    return api.load_text(text).program


def test_the_passes_fire_on_a_leibniz_table():
    """The table reads become literals, the loop unrolled, the products shared, no try left."""
    program = _text_program(LEIBNIZ)
    source = compile_program(program, optimise=replace(ON, fuse=False, fastpath=False)).python_sources["DET3"]
    unrolled, fallback = source.split("for v_T")      # the copies, then the loop as before
    assert "v_P[" not in unrolled and "v_S[" not in unrolled and "v_P[" in fallback
    lines = source.splitlines()
    adds = [i for i, line in enumerate(lines) if line.strip() == "v_D = (v_D + v_X)"]
    assert len(adds) == 4                   # 3 unrolled copies (S = +1) and the loop as before
    assert not any(lines[i - 1].strip() == "try:" for i in adds)   # + of locals cannot raise: no handler
    plain = compile_program(program, optimise=OFF).python_sources["DET3"]
    assert "for v_T" in plain and "v_P[" in plain
    assert source.count("_t") > plain.count("_t")


class _Context:
    """What a compiled body needs of the controller: a budget and a fault log."""

    def __init__(self):
        self.budget = 10**12
        self.faults = []

    def fault(self, exc, where):
        self.faults.append((type(exc).__name__, getattr(exc, "code", None), where))


def test_an_unconnected_in_out_faults_the_same_in_the_unrolled_loop():
    """The checker requires M at every call, so only a direct run of the body can leave it
    unconnected: the unrolled copy's reads fault, and the loop as before runs and faults."""
    program = _text_program(LEIBNIZ)
    outcomes = []
    for optimise in (OFF, ON):
        compiled = compile_program(program, optimise=optimise)
        instance, context = compiled.new("Det3"), _Context()
        type(instance).execute(instance, context)
        outcomes.append((context.faults, context.budget, snapshot(instance)))
    assert outcomes[0] == outcomes[1]
    # Each of the 6 iterations: the product's read of M faults (line 12); the rest runs.
    assert [(code, where[2]) for _, code, where in outcomes[1][0]] == [("F-NULL-REF", 12)] * 6


@pytest.mark.parametrize("budget_ns", [200, 1_000, 2_000, 3_000, 4_000, 6_000, 10_000, 50_000])
def test_f_period_lands_on_the_same_statement(budget_ns):
    program = _text_program(LEIBNIZ)
    off, on = run_both(program, 2, budget_ns)
    assert on == off


def test_unguard_keeps_the_handler_where_python_can_raise():
    assert unguard.cannot_fault(["    v_A = (v_B + (v_C * 2.5))", "v_D = -v_A"])
    assert not unguard.cannot_fault(["v_A = (v_B / v_C)"])          # ZeroDivisionError
    assert not unguard.cannot_fault(["v_A = (v_B ** v_C)"])         # 0.0 ** -1
    assert not unguard.cannot_fault(["v_A = self.v_B"])
    assert not unguard.cannot_fault(["v_A = _f32(v_B)"])
    assert not unguard.cannot_fault(["v_A[3] = v_B"])
    assert not unguard.cannot_fault([])


def test_switches_parse():
    assert Optimisations.only("fold") == replace(Optimisations.none(), fold=True)
    assert Optimisations.only("fold").unroll is False and Optimisations().inline is True
    with pytest.raises(ValueError):
        Optimisations.only("fast")


@pytest.mark.parametrize("variant, count", [("table", 1000), ("unrolled", 200), ("lu", 200)])
def test_fk_solves_are_bit_identical_with_and_without_the_passes(monkeypatch, variant, count):
    from stgen.config import PlatformConfig
    from stgen.reference import inverse_kinematics
    from stgen.render import RenderOptions
    from stgen.verify import fk_solver, load_kinematics, random_poses

    config = PlatformConfig.default()
    poses = random_poses(config, count, seed=17)
    positions = inverse_kinematics(config.geometry, poses, config.stroke).positions
    start = np.asarray(config.solver.start_pose)
    runs = []
    for setting in ("none", "all"):
        monkeypatch.setenv("ST_RUNTIME_OPTIMISE", setting)
        runtime = load_kinematics(config, RenderOptions(variant), capacity=count)
        runs.append(runtime.forward_kinematics(positions, start, fk_solver(config)))
    off, on = runs
    assert off.done.all()
    assert np.array_equal(off.poses.view(np.uint64), on.poses.view(np.uint64))
    assert np.array_equal(off.iterations, on.iterations)
    assert np.array_equal(off.calls, on.calls)
    assert np.array_equal(off.error_ids, on.error_ids)


# A FOR whose body leaves only by RETURN (the LU elimination's shape): unrolled,
# its inner loops get constant bounds; a zero pivot returns from inside a copy.
ELIMINATE = """
FUNCTION Eliminate : BOOL
VAR_IN_OUT M : ARRAY[1..4, 1..4] OF LREAL; END_VAR
VAR_OUTPUT Product : LREAL; END_VAR
VAR K : INT; Row : INT; Col : INT; END_VAR
Product := 1.0;
FOR K := 1 TO 4 DO
    IF M[K, K] = 0.0 THEN
        Eliminate := FALSE;
        RETURN;
    END_IF;
    FOR Row := K + 1 TO 4 DO
        M[Row, K] := M[Row, K] / M[K, K];
        FOR Col := K + 1 TO 4 DO
            M[Row, Col] := M[Row, Col] - M[Row, K] * M[K, Col];
        END_FOR;
    END_FOR;
    Product := Product * M[K, K];
END_FOR;
Eliminate := TRUE;
END_FUNCTION
PROGRAM Main
VAR A : ARRAY[1..4, 1..4] OF LREAL := [4.0, 1.5, -2.0, 0.1, 2.0, 3.0, 1.0, 7.0,
                                       2.0, 0.75, 5.0, 1.0, -1.0, 2.5, 3.5, 9.0];
    S : ARRAY[1..4, 1..4] OF LREAL := [1.0, 2.0, 3.0, 4.0, 2.0, 4.0, 6.0, 8.0,
                                       0.5, 1.0, 2.0, 3.0, 1.0, 1.0, 1.0, 1.0];
    Ok : BOOL; Singular : BOOL; P : LREAL; Q : LREAL; Calls : INT; END_VAR
Calls := Calls + 1;
A[1, 1] := A[1, 1] + 0.125;
Ok := Eliminate(M := A, Product => P);
Singular := Eliminate(M := S, Product => Q);
END_PROGRAM
"""


def test_a_loop_left_by_return_is_unrolled():
    program = _text_program(ELIMINATE)
    source = compile_program(program, optimise=ON).python_sources["ELIMINATE"]
    assert "for v_K" not in source and "for v_ROW" not in source and "for v_COL" not in source
    assert source.count("return ") >= 5          # one per unrolled copy, and the end
    assert "for v_K" in compile_program(program, optimise=OFF).python_sources["ELIMINATE"]


@pytest.mark.parametrize("budget_ns", [300, 1_000, 2_000, 3_000, 5_000, 8_000, 500_000])
def test_a_loop_left_by_return_runs_and_faults_the_same(budget_ns):
    off, on = run_both(_text_program(ELIMINATE), 3, budget_ns)
    assert on == off


def test_the_singular_matrix_returns_from_the_unrolled_copy():
    """Hand-worked: S's second row is twice the first, so after K = 1 its pivot M[2, 2] is 0."""
    program = _text_program(ELIMINATE)
    compiled = compile_program(program, optimise=ON)
    controller = Controller(compiled, time_limit_ns=500_000)
    controller.add_program("Main")
    controller.run(1)
    main = controller.instances["Main"]
    assert main.v_OK is True and main.v_SINGULAR is False
    assert main.v_Q == 1.0                      # Product after K = 1 (M[1, 1] = 1.0), then RETURN
    assert main.v_S[1 * 4 + 1] == 0.0           # M[2, 2] - 2 * M[1, 2] = 4 - 4


def test_fuse_skips_only_stores_no_one_can_see():
    from st_runtime.compiler.optimise import fuse

    lines = ["if _t1:", "    v_P = ((_t2 * _t3) * _t4)", "    v_D = (v_D + v_P)",
             "    v_P = ((_t2 * _t5) * _t6)", "    v_D = (v_D - v_P)"]
    fuse.substitute(lines, 1)
    assert lines[1:] == ["    v_D = (v_D + ((_t2 * _t3) * _t4))",      # set again below: skipped
                         "    v_P = ((_t2 * _t5) * _t6)", "    v_D = (v_D - v_P)"]   # the last one stays
    fuse.merge(lines, 1)
    assert lines[1] == "    v_D = (v_D + ((_t2 * _t3) * _t4))"       # a store of v_P between: no merge
    checked = ["    v_P = (_t2 * _t3)", "    v_D = (v_D + v_P)",
               "    if _ctx.budget < _spent: _overrun(('X', 'x.st', 3, 1))", "    v_P = (_t4 * _t5)"]
    before = list(checked)
    fuse.substitute(checked, 0)
    assert checked == before            # an overrun check sees v_P: the store stays
    reading = ["    v_P = (_t2 * _t3)", "    v_D = (v_D + v_P)", "    v_Q = (v_P * 2.0)", "    v_P = _t4"]
    fuse.substitute(reading, 0)
    assert reading[0] == "    v_P = (_t2 * _t3)"          # read again before it is set
    division = ["    v_P = (_t2 / _t3)", "    v_D = (v_D + v_P)", "    v_P = _t4"]
    fuse.substitute(division, 0)
    assert division[0] == "    v_P = (_t2 / _t3)"         # may raise: not pure


def test_fuse_merges_in_order_and_renames_only_inside_straight_code():
    from st_runtime.compiler.optimise import fuse

    lines = ["    v_D = (v_D + _t1)", "    v_D = (v_D - (_t2 * _t3))", "    v_D = (v_D * v_D)"]
    fuse.merge(lines, 0)
    assert lines == ["    v_D = ((v_D + _t1) - (_t2 * _t3))", "    v_D = (v_D * v_D)"]   # reads D: stays
    names = iter(["_t90", "_t91", "_t92"])
    body = ["    _t5 = (_t1 * _t2)", "    v_A = (_t5 * _t3)", "    _t6 = (_t1 * _t4)", "    v_B = (_t6 * _t6)"]
    fuse.rename(body, 0, lambda: next(names))
    assert body == ["    _t90 = (_t1 * _t2)", "    v_A = (_t90 * _t3)", "    _t90 = (_t1 * _t4)",
                    "    v_B = (_t90 * _t90)"]        # _t1.._t4 are read before they are set: kept
    looped = ["    for v_I in _k1:", "        _t5 = (_t1 * v_I)", "        v_A = _t5"]
    fuse.rename(looped, 0, lambda: "_t99")
    assert looped[1] == "        _t5 = (_t1 * v_I)"


def test_gather_reads_the_same_attributes_in_the_same_order():
    from operator import attrgetter

    from st_runtime.compiler.optimise import gather

    bound = {}

    def register(value):
        bound[f"_k{len(bound)}"] = value
        return f"_k{len(bound) - 1}"

    lines = ["v_A = self.v_A", "v_B = self.v_B", "v_C = self.v_C", "v_D = self.v_D",
             "v_G1 = _G.v_G1", "v_G2 = _G.v_G2",              # a short run: as it was
             "v_T = [0]", "v_E = self.v_E"]
    out = gather.prologue(lines, register)
    assert out == ["v_A, v_B, v_C, v_D = _k0(self)", "v_G1 = _G.v_G1", "v_G2 = _G.v_G2",
                   "v_T = [0]", "v_E = self.v_E"]
    assert isinstance(bound["_k0"], attrgetter)

    class Owner:
        v_A, v_B, v_C, v_D = 1, 2.5, [3], "x"

    assert bound["_k0"](Owner()) == (1, 2.5, [3], "x")
    program = _text_program(GATHERED)
    source = compile_program(program, optimise=replace(ON, gather=True)).python_sources["MAIN"]
    assert source.splitlines()[1].startswith("    v_A, v_B, v_C, v_D, v_I = _k")    # the prologue: one call
    off, on = run_both(program, 3, optimise=replace(ON, gather=True))
    assert on == off


GATHERED = """
PROGRAM Main
VAR A, B, C, D : ARRAY[1..3] OF LREAL := [1.5, 2.5, 3.5]; I : INT; END_VAR
FOR I := 1 TO 3 DO A[I] := A[I] + B[I] * C[I] - D[I]; B[I] := A[I]; END_FOR;
END_PROGRAM
"""


SPECIAL_ARGUMENTS = """
PROGRAM Main
VAR X : ARRAY[1..7] OF LREAL; R : ARRAY[1..28] OF LREAL; I : INT; Z : LREAL; END_VAR
X[1] := 0.5; X[2] := -3.0; X[3] := 1.0 / Z; X[4] := -1.0 / Z; X[5] := Z / Z; X[6] := -0.0; X[7] := 1.0E300;
FOR I := 1 TO 7 DO
    R[I] := SIN(X[I]); R[I + 7] := COS(X[I]); R[I + 14] := TAN(X[I]); R[I + 21] := SQRT(X[I]);
END_FOR;
END_PROGRAM
"""


def test_inlined_math_functions_match_the_library_on_special_arguments():
    program = _text_program(SPECIAL_ARGUMENTS)
    assert "_m_sin(" in compile_program(program, optimise=ON).python_sources["MAIN"]
    off, on = run_both(program, 1)
    assert on == off
    compiled = compile_program(program, optimise=ON)
    controller = Controller(compiled, time_limit_ns=500_000)
    controller.add_program("Main")
    controller.run(1)
    r = controller.instances["Main"].v_R
    # IEEE 754 / OMRON: SIN, COS, TAN of +-inf and NaN are NaN; SQRT below zero is NaN;
    # SQRT(-0.0) = -0.0, SQRT(+inf) = +inf.
    assert all(math.isnan(r[i]) for i in (2, 3, 4, 9, 10, 11, 16, 17, 18, 22, 24, 25))
    assert r[21] == math.sqrt(0.5) and r[0] == math.sin(0.5) and r[7 + 6] == math.cos(1.0e300)
    assert math.copysign(1.0, r[26]) == -1.0 and r[26] == 0.0 and r[23] == math.inf


SQUARES = """
PROGRAM Main
VAR X : ARRAY[1..9] OF LREAL; R : ARRAY[1..9] OF LREAL; S : ARRAY[1..9] OF LREAL; I : INT;
    A, B, Z : LREAL; F : REAL; G : REAL; END_VAR
X[1] := 3.0; X[2] := -0.0; X[3] := 1.0 / Z; X[4] := -1.0 / Z; X[5] := Z / Z; X[6] := 1.0E300;
X[7] := -1.0E-200; X[8] := 0.0; X[9] := -5.0E-324;
FOR I := 1 TO 9 DO
    A := X[I]; B := X[10 - I];
    R[I] := SQRT(A * A + B * B);         (* a sum of squares: math.sqrt without the test *)
    S[I] := SQRT(A * B);                 (* not one: the test stays *)
END_FOR;
F := -2.0; G := SQRT(F * F);
END_PROGRAM
"""


def test_the_root_of_a_sum_of_squares_needs_no_test():
    """IEEE 754: a square is +0.0 or more, +inf or NaN, so is a sum of them; SQRT of it equals
    the library's on every special value (NaN, +-inf, -0.0, overflow to inf, underflow to 0)."""
    program = _text_program(SQUARES)
    source = compile_program(program, optimise=ON).python_sources["MAIN"]
    assert "_m_sqrt(((v_A * v_A) + (v_B * v_B)))" in source
    assert source.count("_sf_SQRT(") == 9            # S's nine (the loop unrolled), none for R nor G
    off, on = run_both(program, 1)
    assert on == off
    controller = Controller(compile_program(program, optimise=ON), time_limit_ns=500_000)
    controller.add_program("Main")
    controller.run(1)
    main = controller.instances["Main"]
    x = [3.0, -0.0, math.inf, -math.inf, math.nan, 1.0e300, -1.0e-200, 0.0, -5.0e-324]
    for i in range(9):      # the library's SQRT: NaN below zero, math.sqrt otherwise
        for got, value in ((main.v_R[i], x[i] * x[i] + x[8 - i] * x[8 - i]), (main.v_S[i], x[i] * x[8 - i])):
            expected = math.nan if value < 0 else math.sqrt(value)
            assert got == expected or (math.isnan(expected) and math.isnan(got)), (i, got, expected)
    assert main.v_R[0] == 3.0 and main.v_R[5] == math.inf and math.isnan(main.v_R[2]) is False
    assert math.isnan(main.v_S[0]) and main.v_G == 2.0      # 3.0 * -5e-324 < 0; SQRT(-2.0 * -2.0)
