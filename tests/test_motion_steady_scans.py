"""The steady scans of a run (st_runtime/motion/steady_scans.py): the scan loop fused with the
motion task's hooks, which runs every scan of a `Controller.run` after the first while the
controller keeps the motion task's shape.  Held, scan by scan, to the same run through the
general loop (`Controller._scans`, the hooks called as hooks): the program of
test_motion_stream_epoch (direction changes, VelLimit, a soft limit and its reset, 16#543B,
MC_Stop, power off and on) and the ways a scan leaves the loop: F-PERIOD, a fault that
stops the run, a fault raised by the motion processing, an observer that adds a hook, a
writing observer, another exception.
"""

from __future__ import annotations

import math
import sys

import pytest

from st_runtime.api import load_sources
from st_runtime.faults import STFault
from st_runtime.motion import MotionTask
from st_runtime.motion.axis import Axis
from st_runtime.motion.error_ids import ErrorID

from test_motion_stream_epoch import make_plc, state


def observed_run(chunks, steady: bool, setup=None, between=None, observed: bool = True):
    """States after every scan of `chunks` runs (a read-only observer), and the scans the
    steady loop ran; `between(plc, task)` after each run.  Not `observed`: no observer at
    all (the loop reads no shape again at a scan's end), the state after each run."""
    plc, main, task = make_plc()
    controller = plc.controller
    if setup is not None:
        setup(plc, main, task)
    fused = []
    if steady:
        loop = task._steady_scans

        def counted(controller, cycles):
            fused.append(loop(controller, cycles))
            return fused[-1]

        task._steady_scans = counted
    else:
        controller.steady_scans = None           # every scan through Controller._scans
    states = []
    if observed:
        controller.add_observer(lambda c: states.append(state(plc, task)), reads_only=True)
    for scans in chunks:
        plc.run(scans)
        if not observed:
            states.append(state(plc, task))
        if between is not None:
            between(plc, task)
    return states, sum(fused), controller


def assert_same_runs(chunks, setup=None, steady_at_least=1, between=None):
    got, fused, controller = observed_run(chunks, True, setup, between)
    expected, none, reference = observed_run(chunks, False, setup, between)
    assert len(got) == len(expected) and got
    for scan, (one, other) in enumerate(zip(got, expected), start=1):
        assert one == other, scan
    assert [(f.code, f.pou, f.line, f.scan) for f in controller.faults] == \
        [(f.code, f.pou, f.line, f.scan) for f in reference.faults]
    assert list(controller.task_times["Primary"]) == list(reference.task_times["Primary"])
    assert (controller.stopped is None) == (reference.stopped is None)
    assert fused >= steady_at_least and none == 0
    return controller


def test_a_run_of_the_stream_program_ends_every_scan_as_the_general_loop():
    assert_same_runs([400], steady_at_least=399)


def test_runs_of_several_lengths_start_each_through_the_general_loop():
    assert_same_runs([1, 2, 57, 140, 200], steady_at_least=390)


def test_a_new_period_between_runs_is_stepped_with_its_own_slack():
    """The steady loop keeps each axis's step slack in a local: a new period (a new slack,
    set by the axis's general step) between two runs is seen as in the general loop."""
    periods = {100: 2_000_000, 160: 500_000, 300: 1_000_000}

    def new_period(plc, task):
        controller = plc.controller
        controller.period_ns = controller.tasks[0].period_ns = periods.get(controller.scan_count, controller.period_ns)

    assert_same_runs([100, 60, 140, 100], steady_at_least=390, between=new_period)


def test_f_period_in_steady_scans():
    """A time limit that the program's costlier scans pass: F-PERIOD after the program."""
    def tight(plc, main, task):
        plc.controller.time_limit_ns = 539

    controller = assert_same_runs([400], tight, steady_at_least=300)
    assert any(f.code == "F-PERIOD" for f in controller.faults)


class _Wrapped:
    """The task's program, and `after(ctx)` run after it in every scan."""

    def __init__(self, program, after):
        self.program, self.after = program, after

    def execute(self, ctx):
        self.program.execute(ctx)
        self.after(ctx)


def _wrap_program(plc, after) -> None:
    programs = plc.controller.tasks[0].programs
    name, program = programs[0]
    programs[0] = (name, _Wrapped(program, after))


def _faulting_program_at(scan: int):
    """A setup whose program records a fault in `scan` (as compiled ST records one)."""
    def after(ctx):
        if ctx.scan == scan:
            ctx.fault(STFault("F-TEST", "recorded by the program"), ("Main", "main.st", 3, 1))
    return lambda plc, main, task: _wrap_program(plc, after)


def test_a_fault_that_stops_the_run_in_a_steady_scan():
    def stopping(plc, main, task):
        plc.controller.stop_on_fault = True
        _faulting_program_at(120)(plc, main, task)

    controller = assert_same_runs([400], stopping, steady_at_least=118)
    assert controller.stopped is not None and controller.stopped.scan == 120
    assert controller.scan_count == 120


def test_a_fault_in_the_motion_processing_that_stops_the_run():
    def stopping(plc, main, task):
        plc.controller.stop_on_fault = True
        _raising_at(95, STFault("F-TEST", "raised by the motion processing"))(plc, main, task)

    controller = assert_same_runs([400], stopping, steady_at_least=93)
    assert controller.stopped is not None and controller.stopped.scan == 95


def _raising_at(scan: int, exception: Exception):
    """A setup whose Cyl1 raises `exception` from its general step in `scan` (the scans of
    the jump to VelLimit take the general step)."""
    def setup(plc, main, task):
        cyl1 = task.axes[0]

        def step(dt, axis=cyl1, controller=plc.controller):
            if controller.ctx.scan == scan:
                raise exception
            Axis.step(axis, dt)

        cyl1.step = step
    return setup


def test_a_fault_in_the_motion_processing_leaves_the_steady_loop():
    controller = assert_same_runs([100, 300], _raising_at(95, STFault("F-TEST", "raised by the motion processing")),
                                  steady_at_least=390)
    assert [(f.code, f.pou, f.scan) for f in controller.faults if f.code == "F-TEST"] == \
        [("F-TEST", "MotionTask._after_programs", 95)]


def _escaping(setup) -> list:
    """(the hooks' flags, scans run, state) after a run of 400 scans that an exception other
    than a fault leaves, with the steady loop and without."""
    outcomes = []
    for steady in (True, False):
        plc, main, task = make_plc()
        setup(plc, main, task)
        if not steady:
            plc.controller.steady_scans = None
        with pytest.raises(KeyError):
            plc.run(400)
        outcomes.append((task._published, task._continuing, plc.controller.scan_count, state(plc, task)))
    return outcomes


def test_an_exception_from_the_motion_processing_leaves_the_hooks_flags_as_the_hook_does():
    outcomes = _escaping(_raising_at(95, KeyError("not a fault")))
    assert outcomes[0] == outcomes[1]
    assert outcomes[0][:3] == (False, False, 94)


def test_an_exception_from_the_programs_leaves_the_hooks_flags_as_the_hook_does():
    def raising(ctx):
        if ctx.scan == 120:
            raise KeyError("not a fault")

    outcomes = _escaping(lambda plc, main, task: _wrap_program(plc, raising))
    assert outcomes[0] == outcomes[1]
    assert outcomes[0][:3] == (False, True, 119)


def test_an_observer_that_adds_a_hook_ends_the_steady_loop():
    """An observer that breaks its word and adds a hook: the next scan runs the hook, as in
    the general loop (the shape is checked at the end of every scan)."""
    calls = []

    def setup(plc, main, task):
        controller = plc.controller

        def adding(controller):
            if controller.scan_count == 150:
                controller.add_io_hook(after=lambda ctx: calls.append(ctx.scan))
        controller.add_observer(adding, reads_only=True)

    assert_same_runs([400], setup, steady_at_least=140)
    assert calls[:1] == [151] and len(calls) == 2 * 250


class _Counting:
    """A program of Python that notes the scans it runs in."""

    def __init__(self):
        self.scans = []

    def execute(self, ctx):
        self.scans.append(ctx.scan)


def _counted_runs(add_counter) -> list:
    """The scans a counting program ran in, in the runs of `assert_same_runs([400])` (the steady
    loop's, the general loop's); `add_counter(plc, program)` gives it to the controller."""
    counters = []

    def setup(plc, main, task):
        counters.append(_Counting())
        add_counter(plc, counters[-1])

    assert_same_runs([400], setup, steady_at_least=140)
    return [counter.scans for counter in counters]


def test_a_task_of_two_programs_runs_both_in_every_steady_scan():
    """The steady loop of a task of one program keeps it in locals; a task of two runs both."""
    def second(plc, program):
        plc.controller.tasks[0].programs.append(("Counter", program))

    assert _counted_runs(second) == [list(range(1, 401))] * 2


def test_an_observer_that_adds_a_program_ends_the_one_program_loop():
    """An observer that breaks its word and adds a program to the task: the next scan runs it,
    as in the general loop (the end of a scan with observers compares the programs)."""
    def adding(plc, program):
        def observer(controller):
            if controller.scan_count == 150:
                controller.tasks[0].programs.append(("Counter", program))
        plc.controller.add_observer(observer, reads_only=True)

    assert _counted_runs(adding) == [list(range(151, 401))] * 2


def test_a_writing_observer_ends_the_steady_loop_at_once():
    def setup(plc, main, task):
        def writing(controller):
            if controller.scan_count == 120:
                controller.add_observer(lambda c: None)
        plc.controller.add_observer(writing, reads_only=True)

    assert_same_runs([400], setup, steady_at_least=110)


@pytest.mark.parametrize("chunks, setup, fused, last_scan", [
    # the stream program's runs: each run's first scan through the general loop
    ([1, 2, 57, 140, 200], None, 0 + 1 + 56 + 139 + 199, 400),
    # a fault in the motion processing at scan 95 leaves the loop (scans 2-95 fused)
    ([100, 300], _raising_at(95, STFault("F-TEST", "raised by the motion processing")), 94 + 299, 400),
    # a fault of the program that stops the run at scan 120
    ([400], "stopping", 119, 120),
], ids=["stream", "motion-fault", "stop"])
def test_a_run_without_observers_ends_as_the_general_loop(chunks, setup, fused, last_scan):
    """No observer: the end of a steady scan tests only the stop and the hooks' flag; a
    fault in the motion processing and a stop still leave the loop at that scan."""
    if setup == "stopping":
        def setup(plc, main, task):
            plc.controller.stop_on_fault = True
            _faulting_program_at(120)(plc, main, task)
    got, steady_scans, controller = observed_run(chunks, True, setup, observed=False)
    expected, none, reference = observed_run(chunks, False, setup, observed=False)
    assert got == expected and none == 0
    assert steady_scans == fused
    assert controller.scan_count == reference.scan_count == last_scan
    assert [(f.code, f.pou, f.line, f.scan) for f in controller.faults] == \
        [(f.code, f.pou, f.line, f.scan) for f in reference.faults]
    assert list(controller.task_times["Primary"]) == list(reference.task_times["Primary"])


# A stream whose every step is one period's reach of an axis as fast as a float allows: the
# velocity overflows to +inf from the first step on (validated: max_velocity is finite).
_FASTEST = sys.float_info.max
_DT = 1_000_000 * 1e-9                           # the period of "1ms", as the controller makes dt
_SLACK = _FASTEST * _DT * (1 + 1e-9)             # Axis._set_period's step slack
_OVERFLOWING_STEP = 1.797693135e305              # within the slack, over the largest velocity


def _stream(axis: dict, step: str, steady: bool, general: bool = False, scans: int = 8) -> tuple[list, int]:
    """(Cmd.Pos, Cmd.Vel, Cmd.AccDec, MFaultLvl.Code, Details.VelLimit) after each scan of a
    sync stream on the axis of table `axis` whose target moves by `step` (an LREAL expression
    that may read the scan's number `Scan`) a scan from 0 (powered in scan 1, the stream from
    scan 2), and the scans the steady loop ran; `general`: the motion processing as Axis.step
    and the writer."""
    task = MotionTask.from_tables([{"name": "Ax", **axis}])
    program = f"""
    PROGRAM Main
    VAR Power : MC_Power; Sync : MC_SyncMoveAbsolute; Target : LREAL; Scan : DINT; END_VAR
    Scan := Scan + 1;
    Power(Axis := Ax, Enable := TRUE);
    IF Power.Status THEN Target := Target + {step}; END_IF;
    Sync(Axis := Ax, Execute := Power.Status AND NOT Ax.Status.ErrorStop, Position := Target,
         BufferMode := _mcAborting);
    END_PROGRAM
    """
    project = load_sources({"axes.st": task.globals_source(), "main.st": program}, dialect="nj")
    assert not [d for d in project.diagnostics if d.is_error]
    plc = project.controller(period="1ms")
    task.install(plc.controller)
    plc.add_program("Main")
    controller = plc.controller
    if general:
        def after_programs(ctx):
            for writer in task._writers:
                Axis.step(writer.axis, ctx.period_ns * 1e-9)
                writer.write()
            task._published = False
        controller.after_hooks[:] = [after_programs]
    fused = []
    if steady:
        loop = task._steady_scans
        task._steady_scans = lambda controller, cycles: fused.append(loop(controller, cycles)) or fused[-1]
    else:
        controller.steady_scans = None
    ref = controller.compiled.globals.v_AX
    shown = []
    controller.add_observer(lambda c: shown.append((ref.v_CMD.v_POS, ref.v_CMD.v_VEL, ref.v_CMD.v_ACCDEC,
                                                    ref.v_MFAULTLVL.v_CODE, ref.v_DETAILS.v_VELLIMIT)),
                           reads_only=True)
    plc.run(scans)
    return shown, sum(fused)


def _same_in_all_three_loops(axis: dict, step: str, scans: int = 8) -> list:
    """The stream's scans in the steady loop, held to the general loop and to Axis.step."""
    got, fused = _stream(axis, step, True, scans=scans)
    assert fused == scans - 1
    assert got == _stream(axis, step, False, scans=scans)[0] == _stream(axis, step, False, True, scans)[0]
    return got


def test_a_stream_of_infinite_velocity_keeps_accdec_zero_while_the_velocity_holds():
    """Axis.step's AccDec is 0.0 for equal velocities, +inf == +inf included (OMRON's AccDec
    is 0 at a constant velocity, W507 p.6-28).  The stream step tests the signs first and
    takes (new - old) / dt for two positive velocities, NaN for two infinite ones: an axis
    whose step's velocity can overflow never takes it (Axis._set_period)."""
    assert _OVERFLOWING_STEP <= _SLACK and _OVERFLOWING_STEP / _DT == math.inf
    got = _same_in_all_three_loops({"max_velocity": _FASTEST}, repr(_OVERFLOWING_STEP))
    # by hand: scan 1 powers the axis, scan 2 starts the stream from rest (+inf, +inf), every
    # later scan repeats the velocity +inf
    assert [shown[1:3] for shown in got[1:]] == [(math.inf, math.inf)] + [(math.inf, 0.0)] * 6


def test_a_stream_that_passes_the_lower_soft_limit_in_a_steady_scan():
    """The steady loop's stream test holds the target to both soft limits: a target 0.25 mm
    below the lower one (16#6441, W507's software limit error) stops the axis at the last
    command within it, as Axis.step does."""
    got = _same_in_all_three_loops({"max_velocity": 1000.0, "soft_limit_min": -5.0, "soft_limit_max": 50.0},
                                   "-0.25", scans=24)
    # by hand: the command is -0.25 * (k - 1) after scan k (exact in binary) until -5.0 in
    # scan 21; scan 22's -5.25 is refused and the axis holds -5.0 in ErrorStop
    assert [shown[0] for shown in got[:21]] == [-0.25 * k for k in range(21)]
    assert [shown[3] for shown in got] == [0] * 21 + [int(ErrorID.TARGET_NEGATIVE_SOFT_LIMIT)] * 3
    assert [shown[0] for shown in got[21:]] == [-5.0] * 3


def test_an_axis_keeps_every_attribute_in_its_slots():
    """Axis declares its attributes as slots (the lanes and the FBs' hot paths load and store
    them every scan); an attribute left out would fall into the instance's `__dict__`, where
    every access takes the slower path.  After the stream program (powers, streams, VelLimit,
    ErrorStop, resets, MC_Stop, power off) none is there."""
    _, _, controller = observed_run([400], True)
    assert [vars(axis) for axis in controller.motion.axes] == [{}, {}]


def test_a_stream_that_leaves_the_short_step_and_comes_back_in_steady_scans():
    """A jump of 5 mm out of one period's reach (1 mm) in scan 10: the steps in VelLimit are
    the axis's general step, which ends its epoch and the task's stamp, so the scan that is
    within reach again takes the whole test and shows VelLimit FALSE (VelLimit TRUE only while
    the command moves at the maximum velocity: W507 9-2, docs/nj501.md's evidence table)."""
    got = _same_in_all_three_loops({"max_velocity": 1000.0}, "SEL(Scan = 10, 0.25, 5.25)", scans=20)
    # by hand: the command is the target 0.25 * (k - 1) until scan 9 (2.0); the target is 7.25
    # in scan 10 and 0.25 more a scan after it, the command 1 mm a scan more: 3, 4, ..., 8 in
    # scans 10-15 (VelLimit), the target 8.75 in scan 16, within reach
    assert [shown[4] for shown in got] == [False] * 9 + [True] * 6 + [False] * 5
    assert [shown[0] for shown in got[:9]] == [0.25 * k for k in range(9)]
    assert got[15][0] == 8.75
