"""The simulated controller: tasks, clock, faults, NJ501 time per scan, I/O hooks, trace."""

from __future__ import annotations

import numpy as np
import pytest

from st_runtime.api import load_text
from st_runtime.compiler.cost import PICOSECONDS_PER_UNIT, WEIGHTS
from st_runtime.controller import Controller

PROGRAMS = """
VAR_GLOBAL log : DINT; END_VAR
PROGRAM Fast
VAR n : INT; END_VAR
VAR_EXTERNAL log : DINT; END_VAR
n := n + 1; log := log * 10 + 1;
END_PROGRAM
PROGRAM Slow
VAR n : INT; END_VAR
VAR_EXTERNAL log : DINT; END_VAR
n := n + 1; log := log * 10 + 2;
END_PROGRAM
PROGRAM Clock
VAR t : TON; fired : INT; END_VAR
t(IN := TRUE, PT := T#10ms);
IF t.Q AND fired = 0 THEN fired := 1; END_IF;
END_PROGRAM
"""


def test_programs_run_in_order_and_tasks_at_multiples_of_the_primary_period():
    plc = load_text(PROGRAMS).controller(period="2ms")
    plc.add_task("Background", "6ms")
    fast = plc.add_program("Fast")
    slow = plc.add_program("Slow", task="Background")
    plc.run(6)
    assert fast["n"] == 6
    assert slow["n"] == 2                     # scans 1 and 4
    # Scan 1: fast then slow; scans 2, 3: fast; scan 4: fast, slow; 5, 6: fast.
    assert plc.globals["log"] == 12_111_211
    assert plc.now_ns == 12_000_000


def test_task_period_must_be_a_multiple():
    plc = load_text(PROGRAMS).controller(period="1ms")
    with pytest.raises(ValueError):
        plc.add_task("Odd", "2500us")


def test_clock_advances_only_by_the_period():
    plc = load_text(PROGRAMS).controller(period="1ms")
    clock = plc.add_program("Clock")
    seen = []
    plc.add_io_hook(before=lambda ctx: seen.append((ctx.scan, ctx.now_ns, ctx.period_ns)))
    plc.run(3)
    assert seen == [(1, 0, 1_000_000), (2, 1_000_000, 1_000_000), (3, 2_000_000, 1_000_000)]
    plc.run(8)
    # TON with PT = 10 ms started at 0 ms: Q in scan 11 (t = 10 ms).
    assert clock["fired"] == 1 and clock["t.ET"] == "T#10ms"


FAULTY = """
PROGRAM Main
VAR a : ARRAY[1..3] OF INT; i : INT := 4; after : INT; scans : INT; END_VAR
scans := scans + 1;
a[i] := 1;
after := after + 1;
END_PROGRAM
"""


def test_fault_is_recorded_and_scanning_continues():
    plc = load_text(FAULTY, "faulty.st").controller()
    main = plc.add_program("Main")
    assert plc.run(3) == 3
    assert main["scans"] == 3 and main["after"] == 3
    assert [(f.code, f.pou, f.file, f.line, f.scan) for f in plc.faults] == [
        ("F-INDEX", "Main", "faulty.st", 5, s) for s in (1, 2, 3)]
    assert plc.faults[0].render().startswith("faulty.st:5:")
    assert "fault[F-INDEX]" in plc.faults[0].render() and plc.faults[0].render().endswith("(scan 1)")


def test_stop_on_fault_stops_at_the_first_fault():
    plc = load_text(FAULTY, "faulty.st").controller(stop_on_fault=True)
    main = plc.add_program("Main")
    assert plc.run(5) == 1
    assert main["scans"] == 1 and main["after"] == 0
    assert len(plc.faults) == 1 and plc.controller.stopped is plc.faults[0]
    assert plc.run(5) == 0


RUNAWAY = """
PROGRAM Main
VAR k : DINT; scans : INT; after : INT; END_VAR
scans := scans + 1;
WHILE TRUE DO k := k + 1; END_WHILE;
after := 1;
END_PROGRAM
PROGRAM Other
VAR n : INT; END_VAR
n := n + 1;
END_PROGRAM
"""


def _ps(units: int) -> int:
    """Units of the cost model's weights table as the picoseconds a block charges."""
    return units * PICOSECONDS_PER_UNIT


def test_runaway_loop_ends_the_scan_with_task_period_exceeded():
    plc = load_text(RUNAWAY, "loop.st").controller()
    main = plc.add_program("Main")
    other = plc.add_program("Other")
    assert plc.run(2) == 2
    assert [(f.code, f.line, f.scan) for f in plc.faults] == [("F-PERIOD", 5, 1), ("F-PERIOD", 5, 2)]
    # By hand from the weights: `scans := scans + 1` is load, load, int_op,
    # store; each WHILE TRUE iteration charges loop + (load TRUE + branch) and
    # the body `k := k + 1` (load, load, int_op, store) before it runs.
    w = WEIGHTS
    first = _ps(2 * w["load"] + w["int_op"] + w["store"])
    per_iteration = _ps(w["loop"] + w["load"] + w["branch"] + 2 * w["load"] + w["int_op"] + w["store"])
    period_ps = 1_000_000_000
    bodies_run = (period_ps - first) // per_iteration      # the next charge goes below zero
    assert main["k"] == 2 * bodies_run
    assert main["scans"] == 2 and main["after"] == 0
    assert other["n"] == 0              # the rest of the task is abandoned
    assert list(plc.controller.task_times["Primary"]) == [first + (bodies_run + 1) * per_iteration] * 2
    # held as unsigned 64-bit integers (an append without PyArg_Parse); a run's time is never
    # below zero, and an overrun's, above the limit, fits
    record = plc.controller.task_times["Primary"]
    assert (record.typecode, record.itemsize) == ("Q", 8) and record[0] > period_ps


def test_for_loops_are_charged_by_their_blocks():
    src = """PROGRAM Main
    VAR i, j : DINT; n : DINT; END_VAR
    FOR i := 1 TO 100 DO FOR j := 1 TO 100 DO n := n + 1; END_FOR; END_FOR;
    END_PROGRAM"""
    # By hand: the outer FOR's setup (start, end, store); per outer iteration
    # its loop overhead and the inner FOR's setup; the inner FOR's body is one
    # block, charged up front: 100 * (loop + load, load, int_op, store).
    w = WEIGHTS
    setup = w["load"] + w["load"] + w["store"]
    inner = 100 * (w["loop"] + 2 * w["load"] + w["int_op"] + w["store"])
    total_ps = _ps(setup + 100 * (w["loop"] + setup + inner))
    plc = load_text(src).controller(time_limit=total_ps // 1000 - 1)
    plc.add_program("Main")
    plc.run(1)
    assert [f.code for f in plc.faults] == ["F-PERIOD"]
    plc = load_text(src).controller(time_limit=total_ps // 1000 + 1)
    main = plc.add_program("Main")
    plc.run(1)
    assert plc.faults == [] and main["n"] == 10_000
    assert list(plc.controller.task_times["Primary"]) == [total_ps]


def test_io_hooks_run_before_and_after_the_programs():
    src = """VAR_GLOBAL cmd, fb : LREAL; END_VAR
    PROGRAM Main
    VAR_EXTERNAL cmd, fb : LREAL; END_VAR
    cmd := fb + 1.0;
    END_PROGRAM"""
    plc = load_text(src).controller()
    plc.add_program("Main")
    order = []
    g = plc.controller.globals

    def feedback(ctx):
        order.append(("in", ctx.scan))
        g.v_FB = 10.0 * ctx.scan

    def motion(ctx):
        order.append(("out", ctx.scan, g.v_CMD))

    plc.add_io_hook(before=feedback, after=motion)
    plc.run(2)
    assert order == [("in", 1), ("out", 1, 11.0), ("in", 2), ("out", 2, 21.0)]


def test_trace_records_paths_every_scan(tmp_path):
    src = """PROGRAM Main
    VAR n : INT; a : ARRAY[1..2] OF LREAL; t : TON; END_VAR
    n := n + 1; a[2] := a[2] + 0.5; t(IN := TRUE, PT := T#2ms);
    END_PROGRAM"""
    plc = load_text(src).controller()
    plc.add_program("Main")
    trace = plc.trace(["n", "a[2]", "t.Q"], program="Main")
    plc.run(4)
    data = trace.to_numpy()
    assert list(data["n"]) == [1, 2, 3, 4]
    assert np.allclose(data["a[2]"], [0.5, 1.0, 1.5, 2.0])
    assert list(data["t.Q"]) == [False, False, True, True]
    out = tmp_path / "trace.csv"
    trace.write_csv(out)
    assert out.read_text().splitlines()[0].startswith("time_s,scan,n")


def test_empty_controller_and_run_zero_cycles():
    project = load_text(PROGRAMS)
    controller = Controller(project.compiled)
    assert controller.run(0) == 0 and controller.scan_count == 0
    assert controller.run(2) == 2 and controller.now_ns == 2_000_000


def test_unconnected_var_in_out_is_a_fault_not_a_crash():
    src = """FUNCTION_BLOCK UsesRef
    VAR_IN_OUT x : INT; a : ARRAY[1..2] OF INT; END_VAR
    VAR_OUTPUT done : BOOL; END_VAR
    x := x + 1;
    a[1] := 5;
    done := TRUE;
    END_FUNCTION_BLOCK
    PROGRAM Main
    VAR n : INT; END_VAR
    n := 1;
    END_PROGRAM"""
    project = load_text(src)
    plc = project.controller()
    fb = project.compiled.new("UsesRef")
    plc.controller.tasks[0].programs.append(("UsesRef", fb))
    plc.run(1)
    assert [f.code for f in plc.faults] == ["F-NULL-REF", "F-NULL-REF"]
    assert fb.v_DONE is True


def test_a_fault_raised_by_an_io_hook_is_recorded():
    from st_runtime.faults import STFault

    plc = load_text(PROGRAMS).controller()
    fast = plc.add_program("Fast")

    def failing(ctx):
        raise STFault("F-MATH", "axis feedback lost")

    plc.add_io_hook(before=failing)
    assert plc.run(2) == 2
    assert fast["n"] == 2
    assert [(f.code, f.file, f.scan) for f in plc.faults] == [("F-MATH", "<io>", 1), ("F-MATH", "<io>", 2)]


def test_one_ms_primary_task_and_a_four_ms_task_in_program_order():
    # Primary 1 ms: Fast; 4 ms task: Slow, then Clock (assignment order).  The
    # 4 ms task runs in scans 1, 5, 9 (t = 0, 4, 8 ms), after the primary's
    # programs of the same scan, so `log` reads 1, 2 (Slow) for scans 1, 5, 9
    # and 1 alone otherwise (log := log * 10 + digit).  Clock's TON (PT 10 ms) sees the clock of its own
    # calls only: 0, 4, 8 ms -> ET 8 ms, not yet Q, after 12 scans.
    plc = load_text(PROGRAMS).controller(period="1ms")
    plc.add_task("Slow4", "4ms")
    fast = plc.add_program("Fast")
    slow = plc.add_program("Slow", task="Slow4")
    clock = plc.add_program("Clock", task="Slow4")
    plc.run(5)
    assert plc.globals["log"] == 1_211_112    # scans 1..5: 12, 1, 1, 1, 12
    plc.run(4)
    assert (fast["n"], slow["n"]) == (9, 3)
    plc.run(3)
    assert plc.now_ns == 12_000_000
    assert (clock["t.ET"], clock["t.Q"], clock["fired"]) == ("T#8ms", False, 0)


def test_task_period_exceeded_is_named_and_located():
    plc = load_text(RUNAWAY, "loop.st").controller(time_limit="10us")
    plc.add_program("Main")
    plc.run(1)
    record = plc.faults[0]
    assert (record.code, record.pou, record.file, record.line, record.scan) == \
        ("F-PERIOD", "Main", "loop.st", 5, 1)
    assert "task period exceeded" in record.render()
