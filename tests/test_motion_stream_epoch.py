"""The motion task's short stream step: inside one run, an axis that took a sync stream's step
and has not been changed since but by that step (its epoch, `MotionTask._epoch`) is stepped
testing only the new target and the direction of its velocity.  Held, scan by scan, to the
same program run one scan per call, where every scan starts a new epoch and so takes the
whole test, and to a run whose motion processing is `Axis.step` and the writer: through direction changes, a held target (velocity 0), a target out of reach
(VelLimit), a soft limit (ErrorStop) and its reset, a re-execution error (16#543B), MC_Stop,
power off and on, and changes made to an axis from Python between runs.
"""

from __future__ import annotations

import math

import pytest

from st_runtime.api import load_sources
from st_runtime.motion import MotionTask
from st_runtime.motion.axis import Axis
from st_runtime.motion.error_ids import ErrorID
from st_runtime.native import NativeFB

from test_optimiser_equivalence import snapshot
from test_motion_fbs import axis_config
from test_motion_publish import AXES as PUBLISH_AXES

# Both ideal (no servo lag): the axes a sync stream's step is spelt out for.
AXES = [{key: value for key, value in axis.items() if key != "servo_lag"} for axis in PUBLISH_AXES]

# Cyl1 follows a sine (a direction change about every 45 scans), holds it for 7 scans of
# every 37 (velocity 0), jumps 40 mm out of one period's reach at scan 90 (VelLimit), falls
# and rises again while busy at scan 150 (16#543B), is stopped in scans 200-219 and reset at
# 230; both axes power off in scans 300-309.  Cyl2's sine passes its soft limit of 5 mm
# (16#6440) and is reset every 100 scans.
PROGRAM = """
PROGRAM Main
VAR
    Power1 : MC_Power; Power2 : MC_Power;
    Sync1 : MC_SyncMoveAbsolute; Sync2 : MC_SyncMoveAbsolute;
    Stop1 : MC_Stop; Reset1 : MC_Reset; Reset2 : MC_Reset;
    Scan : DINT;
    Target1 : LREAL; Target2 : LREAL; Jump : LREAL;
END_VAR
Scan := Scan + 1;
IF Scan MOD 37 < 30 THEN Target1 := 10.0 * SIN(DINT_TO_LREAL(Scan) * 0.07) + Jump; END_IF;
IF Scan = 90 THEN Jump := 40.0; END_IF;
Target2 := 6.0 * SIN(DINT_TO_LREAL(Scan) * 0.05);
Power1(Axis := Cyl1, Enable := Scan < 300 OR Scan >= 310);
Power2(Axis := Cyl2, Enable := Scan < 300 OR Scan >= 310);
Sync1(Axis := Cyl1, Execute := Power1.Status AND Scan <> 150 AND (Scan < 200 OR Scan >= 240),
      Position := Target1, BufferMode := _mcAborting);
Sync2(Axis := Cyl2, Execute := Power2.Status AND NOT Cyl2.Status.ErrorStop AND Scan MOD 100 < 95,
      Position := Target2, BufferMode := _mcAborting);
Stop1(Axis := Cyl1, Execute := Scan >= 200 AND Scan < 220, Deceleration := 0.0);
Reset1(Axis := Cyl1, Execute := (Scan >= 230 AND Scan < 235) OR (Scan >= 160 AND Scan < 165));
Reset2(Axis := Cyl2, Execute := Scan MOD 100 >= 96);
END_PROGRAM
"""

AXIS_FIELDS = ("state", "power_requested", "powered", "homed", "cmd_pos", "act_pos", "cmd_vel", "cmd_accdec",
               "act_vel", "fault_code", "observation_code", "vel_limit", "in_pos_waiting")


def make_plc(general: bool = False):
    """The program on the two axes; `general`: the motion processing as `Axis.step` and the
    writer on every axis (no stream step, short or whole)."""
    task = MotionTask.from_tables(AXES)
    project = load_sources({"axes.st": task.globals_source(), "main.st": PROGRAM}, dialect="nj")
    assert not [d for d in project.diagnostics if d.is_error]
    plc = project.controller(period="1ms")
    task.install(plc.controller)
    if general:
        def after_programs(ctx):
            for writer in task._writers:
                Axis.step(writer.axis, ctx.period_ns * 1e-9)
                writer.write()
            task._published = False                 # a feedback in every scan

        plc.controller.after_hooks[:] = [after_programs]
    main = plc.add_program("Main")
    return plc, main, task


def _fb_state(fb) -> tuple:
    members = sorted((k, snapshot(v)) for k, v in vars(fb).items() if k.startswith("v_") and k != "v_AXIS")
    command = getattr(fb, "_command", None)
    return tuple(members) + (getattr(fb, "_previous_execute", None),
                             command and snapshot([getattr(command, slot) for slot in command.__slots__]))


def state(plc, task) -> tuple:
    """Globals (the axis variables), the program with its motion FBs, the axes (floats by
    their bits), the faults and the NJ time of the last scan."""
    controller = plc.controller
    instance = controller.instances["Main"]
    fbs = tuple(_fb_state(getattr(instance, name)) for name in type(instance).__slots__
                if isinstance(getattr(instance, name, None), NativeFB))
    axes = tuple(snapshot([getattr(axis, field) for field in AXIS_FIELDS]) for axis in task.axes)
    faults = [(f.code, f.line, f.scan) for f in controller.faults]
    return snapshot(controller.compiled.globals), snapshot(instance), fbs, axes, faults, \
        controller.task_times["Primary"][-1]


def run_observed(plc, task, chunks) -> tuple[list, int]:
    """The state after every scan (a read-only observer, so a run stays one epoch), and how
    many scans ended with an axis streaming in the epoch it started the scan in."""
    states, short = [], []
    epochs = {}

    def observe(controller):
        states.append(state(plc, task))
        short.append(sum(axis._stream_epoch is task._epoch and epochs.get("start") is task._epoch
                         for axis in task.axes))
        epochs["start"] = task._epoch

    plc.controller.add_observer(observe, reads_only=True)
    for scans in chunks:
        plc.run(scans)
        epochs["start"] = None              # the caller's code ran: no epoch goes on
    return states, sum(short)


def test_a_run_with_the_short_stream_step_ends_every_scan_as_the_whole_test():
    plc, main, task = make_plc()
    fast, short_steps = run_observed(plc, task, [400])
    reference, _, reference_task = make_plc()
    whole, whole_short = run_observed(reference, reference_task, [1] * 400)
    general, _, general_task = make_plc(general=True)
    steps, _ = run_observed(general, general_task, [400])
    for scan, (got, expected, stepped) in enumerate(zip(fast, whole, steps), start=1):
        assert got == expected, scan
        assert got == stepped, scan
    assert len(fast) == len(whole) == len(steps) == 400
    assert whole_short == 0                         # one scan a run: every scan a new epoch
    assert short_steps > 400                        # the short step ran on both axes
    assert len(fast[0][2]) == 7                     # the motion FBs are compared too


def test_the_program_goes_through_what_it_is_meant_to():
    """The cases the equality above covers: direction changes, velocity 0, VelLimit, the
    soft limit's error and 16#543B, the stop and the power off."""
    plc, main, task = make_plc()
    seen = {"directions": set(), "held": 0, "vel_limit": 0, "codes": set(), "states": set()}

    def observe(controller):
        cyl1, cyl2 = task.axes
        seen["directions"].add(math.copysign(1.0, cyl1.cmd_vel) if cyl1.cmd_vel else 0.0)
        seen["held"] += cyl1.cmd_vel == 0.0 and cyl1.state == 2
        seen["vel_limit"] += cyl1.vel_limit
        seen["codes"].update({int(cyl1.fault_code), int(cyl2.fault_code)})
        seen["states"].update({cyl1.state.name, cyl2.state.name})

    plc.controller.add_observer(observe, reads_only=True)
    plc.run(400)
    assert seen["directions"] == {-1.0, 0.0, 1.0}
    assert seen["held"] > 10
    assert seen["vel_limit"] >= 30                  # 40 mm at 1 mm a scan
    assert {int(ErrorID.TARGET_POSITIVE_SOFT_LIMIT), int(ErrorID.RE_EXECUTION_DISABLED)} <= seen["codes"]
    assert {"DISCRETE", "STOPPING", "ERRORSTOP", "DISABLED", "STANDSTILL"} <= seen["states"]


def test_an_axis_changed_between_runs_takes_the_whole_test():
    """Python may change an axis between two runs: the next run starts a new epoch."""
    runs = []
    for chunks in ([1] * 120, [60, 60]):
        plc, main, task = make_plc()
        states = []
        for scans in chunks:
            plc.run(scans)
            if plc.controller.scan_count == 60:
                assert task.axes[0].command.kind == "sync"
                task.axes[0].command = None          # the stream's command taken from the axis
                task.axes[1].observation_code = ErrorID.FOLLOWING_ERROR_WARNING
            states.append(state(plc, task))
        runs.append(states[-1])
    assert runs[0] == runs[1]


@pytest.mark.parametrize("change", [
    lambda axis: axis.request_power(False),
    lambda axis: axis.start_sync(),
    lambda axis: axis.start_move_absolute(1.0, 10.0, 0.0, 0.0),
    lambda axis: axis.start_stop(0.0),
    lambda axis: axis.release_stop(axis.start_stop(0.0)),
    lambda axis: axis.reset(),
    lambda axis: axis.fault(ErrorID.FOLLOWING_ERROR_EXCEEDED),
    lambda axis: axis.step(0.001),
])
def test_every_change_of_an_axis_ends_its_epoch(change):
    axis = Axis(axis_config(max_acceleration=100.0))
    axis.request_power(True)
    axis.step(0.001)
    epoch = axis._stream_epoch = object()
    change(axis)
    assert axis._stream_epoch is None and axis._stream_epoch is not epoch


def test_homing_ends_the_epoch():
    axis = Axis(axis_config())
    axis.request_power(True)
    axis.step(0.001)
    axis._stream_epoch = object()
    axis.start_home()
    assert axis._stream_epoch is None


def test_a_power_request_changed_by_mc_power_ends_the_epoch():
    plc, main, task = make_plc()
    plc.run(20)
    cyl1 = task.axes[0]
    assert cyl1._stream_epoch is task._epoch        # streaming in this run's epoch
    main["Scan"] = 299                               # the next scan powers off
    plc.run(1)
    assert cyl1.power_requested is False and not cyl1.powered
    assert cyl1._stream_epoch is None


def test_binding_again_replaces_the_installed_after_hook():
    """`bind` builds the motion step (the `after` hook) again: the controller runs the new one."""
    plc, main, task = make_plc()
    plc.run(50)
    before = plc.controller.after_hooks[:]
    task.bind(lambda name: getattr(plc.controller.globals, "v_" + name.upper()))
    assert plc.controller.after_hooks == [task._after_programs] and before != [task._after_programs]
    plc.run(50)
    reference, _, reference_task = make_plc()
    reference.run(100)
    assert state(plc, task) == state(reference, reference_task)


def test_a_foreign_before_hook_in_place_of_the_feedback_in_ends_every_epoch():
    """With another `before` hook in place of the task's own, that hook runs between two
    motion processings: no epoch goes on, so its changes are stepped as in a scan of its own."""
    states = []
    for chunks in ([1] * 120, [120]):
        plc, main, task = make_plc()

        def foreign(ctx, task=task):
            if ctx.scan == 61:
                assert task.axes[0].command.kind == "sync"
                task.axes[0].command = None          # the stream's command taken from the axis

        plc.controller.before_hooks[:] = [foreign]
        for scans in chunks:
            plc.run(scans)
        states.append(state(plc, task))
    assert states[0] == states[1]
