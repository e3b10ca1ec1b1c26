"""The estimated NJ501 execution time (st_runtime/compiler/cost.py): its
calibration against the study, how blocks are charged, and F-PERIOD from it.

Expected values: the study's figures (docs/mathematics.md section 3: one Newton-Raphson iteration
49.5 us on an NJ501-1300; 3 iterations 0.149 ms, 13 iterations 0.644 ms) and
sums of the weights table by hand.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest

from st_runtime.api import Instance, load, load_text
from st_runtime.compiler import compile_program
from st_runtime.compiler.cost import PICOSECONDS_PER_UNIT, WEIGHTS
from st_runtime.controller import Controller, Task, TaskTime

GENERATED = Path(__file__).resolve().parents[1] / "generated" / "iec"
STUDY_START = [60.25, 85.0, 230.7, 0.0, 0.0, 3.75]     # docs/mathematics.md section 3: the study's start p_NR


@pytest.fixture(scope="module")
def kinematics():
    return load([str(GENERATED)])


def fk_solve_us(project, cylinders, per_scan: int, max_iterations: int, tolerance: float):
    """One scan of SP_ForwardKinematics from the study's start: (iterations, estimated us)."""
    plc = project.controller(time_limit="1s")
    fk = project.compiled.new("SP_ForwardKinematics")
    view = Instance(fk)
    view["Execute"] = True
    view["CylinderPos"] = list(cylinders)
    view["StartPose"] = STUDY_START
    view["IterationsPerScan"] = per_scan
    view["MaxIterations"] = max_iterations
    view["Tolerance"] = tolerance
    plc.controller.tasks[0].programs.append(("SP_ForwardKinematics", fk))
    plc.controller.run(1)
    return view["Iterations"], plc.controller.task_times["Primary"][0] / 1e6


@pytest.fixture(scope="module")
def target(kinematics):
    """Cylinder positions of a pose 10 mm from the study's start (x - 10)."""
    pose = list(np.array(STUDY_START) - [10, 0, 0, 0, 0, 0])
    return kinematics.call("SP_InverseKinematics", {"Pose": pose})["outputs"]["CylinderPos"]


def test_one_newton_raphson_iteration_costs_the_studys_49_5_us(kinematics, target):
    # The slope between one and three iterations in one scan is one iteration.
    _, one = fk_solve_us(kinematics, target, 50, 1, 0.0)
    _, three = fk_solve_us(kinematics, target, 50, 3, 0.0)
    assert (three - one) / 2 == pytest.approx(49.5, rel=0.005)


@pytest.mark.parametrize("iterations, study_ms", [(3, 0.149), (13, 0.644)])
def test_the_study_end_points(kinematics, target, iterations, study_ms):
    # Tolerance 0 never converges: exactly `iterations` Newton steps, then ERR_NOT_CONVERGED.
    done, us = fk_solve_us(kinematics, target, 50, iterations, 0.0)
    assert done == iterations
    assert us / 1000 == pytest.approx(study_ms, rel=0.01)


def test_a_converging_solve_costs_as_many_iterations(kinematics, target):
    iterations, us = fk_solve_us(kinematics, target, 50, 50, 0.01)
    assert iterations == 3                # 10 mm from the start: 3 steps (the study's fastest)
    assert us / 1000 == pytest.approx(0.149, rel=0.01)


def _ps(units) -> int:
    return int(round(units * PICOSECONDS_PER_UNIT))


HOSTILE = """
PROGRAM Main
VAR a, b : ARRAY[1..1000000] OF LREAL; copies : DINT; END_VAR
WHILE TRUE DO
    a := b;
    copies := copies + 1;
END_WHILE;
END_PROGRAM
"""


def test_a_loop_assigning_huge_arrays_ends_in_f_period_before_any_copy():
    # Issue 9: the old budget counted iterations, so this scan ran about 27
    # minutes.  The estimate charges the assignment by its 1,000,000 elements
    # before the iteration runs: far over 1 ms, so the scan ends at once and
    # the body never runs (no copy, wall time bounded by loading the arrays).
    plc = load_text(HOSTILE, "hostile.st").controller()
    main = plc.add_program("Main")
    plc.run(2)
    assert [(f.code, f.line, f.scan) for f in plc.faults] == [("F-PERIOD", 4, 1), ("F-PERIOD", 4, 2)]
    assert main["copies"] == 0
    w = WEIGHTS
    per_iteration = w["loop"] + w["load"] + w["branch"] + 1_000_000 * w["element"] \
        + 2 * w["load"] + w["int_op"] + w["store"]
    assert list(plc.controller.task_times["Primary"]) == [_ps(per_iteration)] * 2


def test_structure_and_array_assignments_cost_by_their_elements():
    src = """
    TYPE Pair : STRUCT x : LREAL; y : ARRAY[1..3] OF INT; END_STRUCT; END_TYPE
    PROGRAM Main
    VAR p, q : Pair; m, n : ARRAY[1..4, 1..5] OF LREAL; END_VAR
    p := q;
    m := n;
    END_PROGRAM"""
    plc = load_text(src).controller()
    plc.add_program("Main")
    plc.run(1)
    assert list(plc.controller.task_times["Primary"]) == [_ps((4 + 20) * WEIGHTS["element"])]


def test_elsif_and_case_branches_charge_the_tests_that_led_to_them():
    src = """
    PROGRAM Main
    VAR x : LREAL := 3.0; k : INT := 2; y : LREAL; END_VAR
    IF x > 5.0 THEN y := 1.0; ELSIF x > 2.0 THEN y := x * x; ELSE y := 0.0; END_IF;
    CASE k OF 1: y := 1.0; 2, 3: y := y + 1.0; END_CASE;
    END_PROGRAM"""
    w = WEIGHTS
    test = 2 * w["load"] + w["compare"] + w["branch"]              # `x > 5.0` and its jump
    first_block = test                                              # the IF's first test
    elsif_branch = test + 2 * w["load"] + w["real_mul"] + w["store"]  # second test, `y := x * x`
    case_block = w["load"]                                          # the selector
    clause_two = 3 * w["branch"] + 2 * w["load"] + w["real_add"] + w["store"]   # labels 1, 2, 3
    plc = load_text(src).controller()
    plc.add_program("Main")
    plc.run(1)
    expected = sum(_ps(u) for u in (first_block, elsif_branch, case_block, clause_two))
    assert list(plc.controller.task_times["Primary"]) == [expected]


def test_calls_charge_the_call_and_the_callees_own_blocks():
    src = """
    FUNCTION Hyp : LREAL
    VAR_INPUT a, b : LREAL; END_VAR
    Hyp := SQRT(a * a + b * b);
    END_FUNCTION
    PROGRAM Main
    VAR h : LREAL; t : TON; END_VAR
    h := Hyp(3.0, 4.0);
    t(IN := TRUE, PT := T#1s);
    END_PROGRAM"""
    w = WEIGHTS
    caller = (w["call"] + 2 * (w["argument"] + w["load"]) + w["store"]) \
        + (w["standard_fb"] + 2 * (w["argument"] + w["load"]))
    callee = 4 * w["load"] + 2 * w["real_mul"] + w["real_add"] + w["sqrt"] + w["argument"] + w["store"]
    plc = load_text(src).controller()
    main = plc.add_program("Main")
    plc.run(1)
    assert main["h"] == 5.0
    assert list(plc.controller.task_times["Primary"]) == [_ps(caller) + _ps(callee)]


def test_the_estimate_belongs_to_the_st_not_to_the_python(kinematics, target):
    # A different translation (no fault handlers) runs other Python; the
    # charges come from the ST blocks, so the estimate is the same.
    times = []
    for guard in (True, False):
        compiled = compile_program(kinematics.program, guard_statements=guard)
        controller = Controller(compiled)
        fk = compiled.new("SP_ForwardKinematics")
        view = Instance(fk)
        view["Execute"] = True
        view["CylinderPos"] = list(target)
        view["StartPose"] = STUDY_START
        controller.tasks[0].programs.append(("SP_ForwardKinematics", fk))
        controller.run(3)
        times.append(list(controller.task_times["Primary"]))
    assert times[0] == times[1] and times[0][0] > 0


def test_without_charges_nothing_is_estimated():
    project = load_text("PROGRAM Main VAR i : INT; END_VAR i := i + 1; END_PROGRAM")
    compiled = compile_program(project.program, charge_costs=False)
    assert "_spent" not in compiled.python_sources["MAIN"] and "budget" not in compiled.python_sources["MAIN"]


def test_straight_line_overrun_is_reported_after_its_program():
    src = """PROGRAM Main
    VAR a, b : ARRAY[1..100000] OF LREAL; END_VAR
    a := b;
    END_PROGRAM
    PROGRAM Other VAR n : INT; END_VAR n := n + 1; END_PROGRAM"""
    plc = load_text(src, "big.st").controller(period="10us")
    plc.add_program("Main")
    other = plc.add_program("Other")
    plc.run(1)
    record = plc.faults[0]
    assert (record.code, record.pou, record.line) == ("F-PERIOD", "Main", 1)
    assert other["n"] == 0


def test_task_time_statistics_by_hand():
    task = Task("Primary", 1_000_000, 1)
    times_ps = [100_000_000 * k for k in range(1, 101)]     # 0.1 ms .. 10 ms
    report = TaskTime.of(task, times_ps)
    assert report.max_ns == 10_000_000 and report.p99_ns == 9_900_000
    assert report.mean_ns == pytest.approx(5_050_000)
    assert not report.fits and not report.load_ok
    light = TaskTime.of(task, [700_000_000, 900_000_000])  # mean 0.8 ms: not below 80 %
    assert light.fits and not light.load_ok
    assert TaskTime.of(task, [700_000_000, 880_000_000]).load_ok


def test_the_loop_iteration_budget_is_deprecated():
    project = load_text("PROGRAM Main VAR i : INT; END_VAR i := i + 1; END_PROGRAM")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        project.controller(budget=1000)
    assert any(issubclass(w.category, DeprecationWarning) and "budget" in str(w.message) for w in caught)


def test_stgen_run_reports_the_estimate(tmp_path, capsys):
    import json

    from stgen.cli import main

    (tmp_path / "main.st").write_text("PROGRAM Main VAR i : INT; END_VAR i := i + 1; END_PROGRAM")
    assert main(["run", str(tmp_path / "main.st"), "--program", "Main", "--cycles", "3"]) == 0
    err = capsys.readouterr().err
    assert "estimated NJ501 time of task Primary (1000 us period, 3 runs)" in err
    assert "meets OMRON's 80 % rule" in err
    assert main(["run", str(tmp_path / "main.st"), "--program", "Main", "--json", "--time-report"]) == 0
    data = json.loads(capsys.readouterr().out)
    units = 2 * WEIGHTS["load"] + WEIGHTS["int_op"] + WEIGHTS["store"]
    assert data["i"] == 1
    assert data["$nj501_time"] == [{
        "task": "Primary", "period_ns": 1_000_000, "runs": 1,
        "max_ns": _ps(units) / 1000, "p99_ns": _ps(units) / 1000, "mean_ns": _ps(units) / 1000,
        "max_percent": round(100 * _ps(units) / 1e9, 4), "mean_percent": round(100 * _ps(units) / 1e9, 4),
        "within_period": True, "within_80_percent_rule": True}]


def test_stgen_run_time_limit_and_the_deprecated_budget(tmp_path, capsys):
    from stgen.cli import main

    (tmp_path / "loop.st").write_text(RUNAWAY_ONE)
    assert main(["run", str(tmp_path / "loop.st"), "--program", "Main", "--time-limit", "5us",
                 "--budget", "10"]) == 1
    err = capsys.readouterr().err
    assert "--budget is deprecated and ignored" in err
    assert "fault[F-PERIOD]" in err and "passed 0.005 ms" in err


RUNAWAY_ONE = "PROGRAM Main VAR k : DINT; END_VAR WHILE TRUE DO k := k + 1; END_WHILE; END_PROGRAM"


def test_a_scenario_result_carries_the_controller_time_per_scan():
    from stgen.scenarios.definitions import scenario_by_name
    from stgen.scenarios.runner import run_scenario

    result = run_scenario(scenario_by_name("airy_wave").with_wave_seconds(0.5))
    times = result.nj_time
    assert times.runs == result.scans and times.period_ns == 1_000_000
    # The power-on FK solve (IterationsPerScan 4) is the longest scan: about 4 x 49.5 us.
    assert 4 * 49_500 * 0.99 < times.max_ns < 4 * 49_500 * 1.03
    assert times.fits and times.load_ok and times.p99_ns < times.max_ns
