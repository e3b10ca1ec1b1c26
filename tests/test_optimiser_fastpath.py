"""The per-POU fast path (st_runtime/compiler/optimise/fastpath.py): equivalence with it on and off.

A body (or an iteration of a FOR that may leave early) whose worst-case NJ time is bounded at
compile time runs without budget checks, its charges merged, when the time left covers that
worst case; otherwise it runs as before.  With the pass on and off, every run must give the same
results, faults (code, line, column, scan) and NJ time per scan, whatever the time limit (so
F-PERIOD lands on the same statement when the budget does not cover the worst case), and with
stop_on_fault (a fault mid-body ends the scan with the time charged so far).  The worst case is
checked against a sum of the weights table by hand.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from st_runtime.api import Instance, Plc, load, load_text
from st_runtime.compiler import Optimisations, compile_program
from st_runtime.compiler.cost import PICOSECONDS_PER_UNIT, WEIGHTS
from st_runtime.compiler.optimise import fastpath
from st_runtime.compiler.statements import BodyCompiler
from st_runtime.controller import Controller

ON = Optimisations()
OFF = replace(ON, fastpath=False)

# A bounded FUNCTION (constant loops, a pivot-like search, an early RETURN, a fault: M[J]
# with J = 0 when the caller asks) and a FOR with a data count that may EXIT, whose
# iterations call it: the per-POU and the per-iteration fast path.
PROGRAM = """
FUNCTION Sweep : LREAL
VAR_INPUT Bad : BOOL; END_VAR
VAR_IN_OUT M : ARRAY[1..4] OF LREAL; END_VAR
VAR I, J, Best : INT; Acc : LREAL; END_VAR
J := 2;
IF Bad THEN
    J := 0;
END_IF;
Acc := M[J];
Best := 1;
FOR I := 1 TO 4 DO
    FOR J := I TO 4 DO
        Acc := Acc + M[J] * M[I];
    END_FOR;
    IF ABS(M[I]) > ABS(M[Best]) THEN
        Best := I;
    END_IF;
END_FOR;
IF Acc > 150.0 THEN
    Sweep := -1.0;
    RETURN;
END_IF;
FOR I := 1 TO 4 DO
    M[I] := M[I] * 0.5 + INT_TO_LREAL(Best);
END_FOR;
Sweep := Acc;
END_FUNCTION

PROGRAM Main
VAR
    M : ARRAY[1..4] OF LREAL := [1.5, -2.0, 3.25, 0.5];
    Steps : INT := 3;
    K, I, Calls : INT;
    Total : LREAL;
    Bad : BOOL;
END_VAR
FOR K := 1 TO Steps DO
    Total := Total + Sweep(Bad := Bad AND K = 2, M := M);
    Calls := Calls + 1;
    IF Total > 500.0 THEN
        EXIT;
    END_IF;
    FOR I := 1 TO 2 DO
        M[I] := M[I] + 1.0;
        IF M[I] > 4.0 THEN
            M[I] := M[I] - 3.0;
        END_IF;
    END_FOR;
END_FOR;
Bad := NOT Bad;
END_PROGRAM
"""


@pytest.fixture(scope="module")
def program():
    return load_text(PROGRAM, "fast.st").program


@pytest.fixture(autouse=True)
def every_bounded_body(monkeypatch):
    """The fast path for any body with a budget check (the default asks for more: load time)."""
    monkeypatch.setattr(fastpath, "WORTH", 1)


def _run(program, optimise, scans: int, time_limit_ns: int | None = None, stop_on_fault: bool = False):
    compiled = compile_program(program, optimise=optimise)
    plc = Plc(Controller(compiled, 1_000_000, None, stop_on_fault, time_limit_ns))
    main = plc.add_program("Main")
    plc.run(scans)
    state = {name: main[name] for name in ("M", "K", "Calls", "Total", "Bad", "Steps")}
    faults = [(f.code, f.pou, f.line, f.col, f.scan) for f in plc.faults]
    return state, faults, list(plc.controller.task_times["Primary"]), compiled


def _same(program, **run):
    on, off = _run(program, ON, **run), _run(program, OFF, **run)
    assert on[:3] == off[:3]
    return on


def test_the_fast_path_fires(program):
    source = compile_program(program, optimise=ON).python_sources
    plain = compile_program(program, optimise=OFF).python_sources
    assert "if _ctx.budget >= " in source["SWEEP"] and "_ctx.budget >=" not in plain["SWEEP"]
    assert "if _ctx.budget - _spent >= " in source["MAIN"]          # per iteration of the data FOR
    fast = source["SWEEP"].split("else:\n")[0]
    assert "_overrun" not in fast and fast.count("_spent += ") < plain["SWEEP"].count("_spent += ")


def test_results_faults_and_time_are_the_same(program):
    state, faults, times, _ = _same(program, scans=4)
    # Bad is TRUE in scans 2 and 4, where the call of K = 2 reads M[0] (line 10, column 8).
    # Scan 1 by hand: Best = 3 in each call, M[I] := M[I] * 0.5 + 3, then M[1], M[2] + 1 (- 3
    # past 4).  From scan 2 on Acc passes 150: Sweep RETURNs -1 before scaling M, and the three
    # steps of +1 (- 3) bring M[1] and M[2] back; Total stays below 500: no EXIT
    assert faults == [("F-INDEX", "Sweep", 10, 8, 2), ("F-INDEX", "Sweep", 10, 8, 4)]
    assert (state["Calls"], state["K"]) == (12, 4) and len(times) == 4
    assert state["M"] == [1.9375, 2.25, 5.65625, 5.3125]


def test_f_period_lands_on_the_same_statement_at_every_budget(program):
    """Limits from below the first call's worst case to above a whole scan: where the
    budget does not cover the worst case the exact path runs and its check fires."""
    _, _, times, compiled = _run(program, OFF, scans=1)
    whole = times[0]
    landed = set()
    for limit in range(whole // 1000 - 40, 0, -max(1, whole // 1000 // 60)):
        _, faults, _, _ = _same(program, scans=2, time_limit_ns=limit)
        landed.update((f[1], f[2]) for f in faults if f[0] == "F-PERIOD")
    assert {pou for pou, _ in landed} == {"Sweep", "Main"}      # inside the callee and the caller
    assert len(landed) >= 4


def test_stop_on_fault_ends_the_scan_with_the_time_charged_so_far(program):
    """The fast body charges a straight run of blocks at its start; the fault handler takes
    back what it charged ahead, so a fault that stops the run sees the exact time."""
    state, faults, times, _ = _same(program, scans=2, stop_on_fault=True)
    assert faults == [("F-INDEX", "Sweep", 10, 8, 2)] and len(times) == 2     # stopped


def test_the_worst_case_by_hand():
    text = """
    FUNCTION Count : INT
    VAR I, N : INT; END_VAR
    FOR I := 1 TO 3 DO
        IF I > 1 THEN
            N := N + I;
        END_IF;
    END_FOR;
    Count := N;
    END_FUNCTION
    PROGRAM Main
    VAR c : INT; END_VAR
    c := Count();
    END_PROGRAM"""
    program = load_text(text).program
    unit = type("Unit", (), {})()
    from st_runtime.compiler import CompileUnit

    unit = CompileUnit(program)
    unit.optimise = ON
    w = WEIGHTS
    setup = 2 * w["load"] + w["store"]                                  # bounds 1 and 3, I set
    test = 2 * w["load"] + w["compare"] + w["branch"]                   # I > 1 and its jump
    add = 2 * w["load"] + w["int_op"] + w["store"]                      # N := N + I
    count = setup + 3 * (w["loop"] + test + add) + w["load"] + w["store"]
    callee = BodyCompiler(program, program.pous["COUNT"], unit, method=False)
    assert fastpath.worst_case(callee, callee.body) == count
    main = BodyCompiler(program, program.pous["MAIN"], unit, method=True)
    call = w["call"] + w["store"]                                       # no argument
    assert fastpath.worst_case(main, main.body) == call + count         # the callee's included
    assert count * PICOSECONDS_PER_UNIT > 0


def test_no_fast_path_where_the_cost_is_not_bounded():
    text = """
    PROGRAM Main
    VAR i, n, s : INT; END_VAR
    FOR i := 1 TO n DO s := s + i; END_FOR;
    WHILE s > 10 DO s := s - 1; END_WHILE;
    END_PROGRAM"""
    program = load_text(text).program
    from st_runtime.compiler import CompileUnit

    unit = CompileUnit(program)
    unit.optimise = ON
    main = BodyCompiler(program, program.pous["MAIN"], unit, method=True)
    assert fastpath.worst_case(main, main.body) is None
    assert fastpath.worst_case(main, main.body[:1]) is None          # a data count
    assert fastpath.worst_case(main, main.body[1:]) is None          # a WHILE


GENERATED = Path(__file__).resolve().parents[1] / "generated" / "iec"
STUDY_START = [60.25, 85.0, 230.7, 0.0, 0.0, 3.75]     # docs/mathematics.md section 3


def _fk_scan(compiled, cylinders, time_limit_ns: int):
    """Two scans of SP_ForwardKinematics (3 iterations per scan): its state, faults and times."""
    controller = Controller(compiled, 1_000_000, None, False, time_limit_ns)
    fk = compiled.new("SP_ForwardKinematics")
    view = Instance(fk)
    view["Execute"] = True
    view["CylinderPos"] = list(cylinders)
    view["StartPose"] = STUDY_START
    view["IterationsPerScan"] = 3
    view["MaxIterations"] = 20
    view["Tolerance"] = 1e-9
    controller.tasks[0].programs.append(("SP_ForwardKinematics", fk))
    controller.run(2)
    state = [value.hex() for value in view["Estimate"]] + [view["Iterations"], view["Busy"]]
    faults = [(f.code, f.pou, f.line, f.col, f.scan) for f in controller.faults]
    return state, faults, list(controller.task_times["Primary"])


def test_fk_cut_by_f_period_at_many_budgets_lands_the_same():
    """The generated FK (its LU and its iterations take the fast path when the time left covers
    them), cut at budgets 1.1 us apart from inside its first iteration to past its second
    (an iteration is about 49.5 us: docs/nj501.md)."""
    project = load([str(GENERATED)])
    pose = list(np.array(STUDY_START) - [10, 0, 0, 0, 0, 0])
    cylinders = project.call("SP_InverseKinematics", {"Pose": pose})["outputs"]["CylinderPos"]
    builds = [compile_program(project.program, optimise=o) for o in (ON, OFF)]
    assert "if _ctx.budget >= " in builds[0].python_sources["SP_LUSOLVE"]
    landed = set()
    for limit_ns in range(20_000, 120_000, 1_100):
        on, off = (_fk_scan(compiled, cylinders, limit_ns) for compiled in builds)
        assert on == off
        landed.update((f[1], f[2]) for f in on[1])
    assert {"SP_ForwardKinematics", "SP_LuSolve", "SP_LeibnizDeterminant"} <= {pou for pou, _ in landed}



# A FUNCTION whose in-out M the fast copy reads and stores at indices in range (Best is
# within 1..4 by ranges.py), called with a list, and from an FB that passes on its own
# in-out: run directly, that one is the NullRef of an unconnected in-out.
IN_OUTS = """
FUNCTION Scale : BOOL
VAR_IN_OUT M : ARRAY[1..4] OF LREAL; END_VAR
VAR I, Best : INT; END_VAR
Best := 1;
FOR I := 2 TO 4 DO
    IF ABS(M[I]) > ABS(M[Best]) THEN
        Best := I;
    END_IF;
END_FOR;
FOR I := 1 TO 4 DO
    M[I] := M[I] - M[Best] * 0.5;
END_FOR;
Scale := TRUE;
END_FUNCTION

FUNCTION_BLOCK Relay
VAR_IN_OUT M : ARRAY[1..4] OF LREAL; END_VAR
VAR Done : BOOL; END_VAR
Done := Scale(M := M);
END_FUNCTION_BLOCK

PROGRAM Main
VAR
    M : ARRAY[1..4] OF LREAL := [1.5, -6.0, 3.25, 0.5];
    Done : BOOL;
END_VAR
Done := Scale(M := M);
END_PROGRAM
"""


def test_the_fast_path_runs_with_the_in_out_arrays_as_lists_only():
    """In Scale's fast copy, run only when M is a Python list, reads and stores of M at
    indices in range cannot fault: the IF is tested in place and the stores have no
    `try`; the exact copy keeps both guarded (M may be a NullRef there)."""
    program = load_text(IN_OUTS, "inouts.st").program
    source = compile_program(program, optimise=ON).python_sources["SCALE"]
    fast, exact = source.split("\n        else:\n", 1)
    assert "if _ctx.budget >= " in fast and " and _type(v_M) is _list:" in fast
    # (the candidate's test as `pivots` keeps the best abs: session 19)
    assert "if ((_cand := abs(v_M[1])) > _best):" in fast and "if (abs(v_M[" not in exact
    lines = fast.splitlines()
    store = next(i for i, line in enumerate(lines) if line.strip().startswith("v_M[0] = "))
    assert lines[store - 1].strip() != "try:"
    lines = exact.splitlines()
    store = next(i for i, line in enumerate(lines) if line.strip().startswith("v_M[0] = "))
    assert lines[store - 1].strip() == "try:"
    assert "_type(v_M)" not in compile_program(program, optimise=OFF).python_sources["SCALE"]
    # by hand: Best = 2 (|-6.0| the largest); M[I] - M[2] * 0.5 with M[2] already -3.0 from I = 2
    state = {}
    for optimise in (OFF, ON):
        plc = Plc(Controller(compile_program(program, optimise=optimise), 1_000_000))
        main = plc.add_program("Main")
        plc.run(1)
        state[optimise] = (main["M"], main["Done"], list(plc.controller.task_times["Primary"]))
    assert state[ON] == state[OFF]
    assert state[ON][:2] == ([4.5, -3.0, 4.75, 2.0], True)


def test_an_unconnected_in_out_passed_on_takes_the_exact_path():
    """M is not a list: the exact path runs, and every read of M faults F-NULL-REF at its
    own line, as with the pass off (the same faults in the same order, the same time)."""
    from test_optimiser_equivalence import _Context

    program = load_text(IN_OUTS, "inouts.st").program
    outcomes = []
    for optimise in (OFF, ON):
        compiled = compile_program(program, optimise=optimise)
        fb, context = compiled.new("Relay"), _Context()
        type(fb).execute(fb, context)
        outcomes.append((context.faults, context.budget, fb.v_DONE))
    assert outcomes[0] == outcomes[1]
    assert {f[1] for f in outcomes[0][0]} == {"F-NULL-REF"} and len(outcomes[0][0]) > 4
