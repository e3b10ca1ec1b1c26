"""Feedback in: the programs of every scan see the axes as they are when the scan starts.

The motion task publishes the axes into their AXIS_REF variables after the motion
processing, and again before the programs (feedback in) unless nothing can have changed
them since: the next scan of one `Controller.run` call, no observer but read-only ones
(a trace), no other I/O hook (`ScanContext.resumed`).  These tests hold the skipped publication to the one that was
not skipped (scan by scan, each scan a call of its own) and show that every way code can
reach the axes between two scans still gets its change published before the programs.
"""

from __future__ import annotations

import pytest

from st_runtime.api import load_sources
from st_runtime.motion import MotionTask
from st_runtime.motion.error_ids import ErrorID
from st_runtime.motion.types import AxisRefWriter

from test_optimiser_equivalence import snapshot

AXES = [
    {"name": "Cyl1", "max_velocity": 1000.0, "soft_limit_min": -50.0, "soft_limit_max": 50.0,
     "servo_lag": 0.004},
    {"name": "Cyl2", "max_velocity": 1000.0, "soft_limit_min": -50.0, "soft_limit_max": 5.0},
]

# Ramps both axes by 0.25 mm a scan (exact in binary), Cyl2 beyond its soft limit (ErrorStop),
# stops, resets, powers off; records what it reads of the axis variables at its start.
PROGRAM = """
PROGRAM Main
VAR
    Power1 : MC_Power; Power2 : MC_Power;
    Sync1 : MC_SyncMoveAbsolute; Sync2 : MC_SyncMoveAbsolute;
    Stop1 : MC_Stop; Stop2 : MC_Stop;
    Reset1 : MC_Reset; Reset2 : MC_Reset;
    Scan : DINT;
    Target : LREAL;
    CmdAtStart1 : LREAL; CmdAtStart2 : LREAL; ActAtStart1 : LREAL;
    ErrorAtStart2 : BOOL; CodeAtStart2 : WORD; ObsrAtStart1 : WORD; IdleAtStart1 : BOOL;
    FaultSeenAt : DINT; CodeWhenSeen : WORD; ObsrSeenAt : DINT;
END_VAR
CmdAtStart1 := Cyl1.Cmd.Pos;
CmdAtStart2 := Cyl2.Cmd.Pos;
ActAtStart1 := Cyl1.Act.Pos;
ErrorAtStart2 := Cyl2.Status.ErrorStop;
CodeAtStart2 := Cyl2.MFaultLvl.Code;
ObsrAtStart1 := Cyl1.Obsr.Code;
IdleAtStart1 := Cyl1.Details.Idle;
Scan := Scan + 1;
IF ErrorAtStart2 AND FaultSeenAt = 0 THEN FaultSeenAt := Scan; CodeWhenSeen := CodeAtStart2; END_IF;
IF ObsrAtStart1 <> 0 AND ObsrSeenAt = 0 THEN ObsrSeenAt := Scan; END_IF;
Power1(Axis := Cyl1, Enable := Scan < 260);
Power2(Axis := Cyl2, Enable := Scan < 260);
IF Scan < 150 THEN Target := Target + 0.25; END_IF;
Sync1(Axis := Cyl1, Execute := Power1.Status AND Scan < 120, Position := Target, BufferMode := _mcAborting);
Sync2(Axis := Cyl2, Execute := Power2.Status AND Scan < 120, Position := Target, BufferMode := _mcAborting);
Stop1(Axis := Cyl1, Execute := Scan >= 120 AND Scan < 180, Deceleration := 500.0);
Stop2(Axis := Cyl2, Execute := Scan >= 120 AND Scan < 180, Deceleration := 500.0);
Reset1(Axis := Cyl1, Execute := Scan >= 200 AND Scan < 205);
Reset2(Axis := Cyl2, Execute := Scan >= 200 AND Scan < 205);
END_PROGRAM
"""


def make_plc(hook_first=None):
    """The program on the two axes; `hook_first`: a `before` I/O hook installed ahead of the
    motion task (it runs before the feedback in)."""
    task = MotionTask.from_tables(AXES)
    project = load_sources({"axes.st": task.globals_source(), "main.st": PROGRAM}, dialect="nj")
    assert not [d for d in project.diagnostics if d.is_error]
    plc = project.controller(period="1ms")
    if hook_first is not None:
        plc.add_io_hook(before=hook_first)
    task.install(plc.controller)
    main = plc.add_program("Main")
    return plc, main, task


def warn_at(task, scan: int):
    """A hook or observer that gives Cyl1 an observation in scan `scan` (or after it)."""
    def change(where):
        now = where.scan_count if hasattr(where, "scan_count") else where.scan   # controller or ctx
        if now == scan:
            task.axes[0].observation_code = ErrorID.FOLLOWING_ERROR_WARNING
    return change


def state(plc, task) -> tuple:
    """Globals (the axis variables), program instances and axes, floats by their bits."""
    controller = plc.controller
    axes = tuple((axis.cmd_pos.hex(), axis.act_pos.hex(), axis.cmd_vel.hex(), axis.act_vel.hex(),
                  int(axis.state), int(axis.fault_code), int(axis.observation_code), axis.vel_limit)
                 for axis in task.axes)
    instances = tuple((name, snapshot(instance)) for name, instance in sorted(controller.instances.items()))
    faults = [(f.code, f.line, f.scan) for f in controller.faults]
    return snapshot(controller.compiled.globals), instances, axes, faults, list(controller.task_times["Primary"])


@pytest.fixture
def count_writes(monkeypatch):
    calls = []
    original = AxisRefWriter.write

    def counting(self):
        calls.append(self.axis.name)
        original(self)

    monkeypatch.setattr(AxisRefWriter, "write", counting)
    return calls


def test_one_run_call_ends_as_scan_by_scan(count_writes):
    runs = []
    for chunks in ([1] * 300, [1, 7, 150, 42, 100], [300]):
        plc, main, task = make_plc()
        for scans in chunks:
            assert plc.run(scans) == scans
        runs.append(state(plc, task))
    scan_by_scan, chunked, whole = runs
    assert chunked == scan_by_scan
    assert whole == scan_by_scan
    # Per axis: one publication when installed, then scan by scan a feedback in and a
    # publication each scan; in one run call the feedback in of its first scan only.
    assert count_writes.count("Cyl1") == (1 + 600) + (1 + 5 + 300) + (1 + 1 + 300)


def test_the_programs_see_an_axis_error_in_the_scan_after_it():
    plc, main, task = make_plc()
    plc.run(300)
    # The Position of scan s is 0.25 s mm (the sync starts in scan 2, once powered): 5.25 mm,
    # beyond Cyl2's soft limit of 5 mm, in the motion processing of scan 21 (16#6440, W507);
    # the programs read ErrorStop from the start of scan 22.
    assert main["FaultSeenAt"] == 22
    assert main["CodeWhenSeen"] == int(ErrorID.TARGET_POSITIVE_SOFT_LIMIT)
    assert main["CodeAtStart2"] == 0                 # reset in scan 200
    # MC_Stop aborted Cyl1's sync in scan 120 and held scan 119's command (an immediate stop
    # under MC_SyncMoveAbsolute, docs/nj501.md); after the servo off of scan 260 the command
    # follows the actual position, 4 ms of lag behind and long since settled.
    assert main["CmdAtStart1"] == pytest.approx(119 * 0.25, abs=1e-9)


def test_an_axis_changed_between_two_runs_is_seen_by_the_next_scan():
    plc, main, task = make_plc()
    plc.run(20)
    task.axes[0].observation_code = ErrorID.FOLLOWING_ERROR_WARNING
    plc.run(5)
    assert main["ObsrSeenAt"] == 21


def test_an_axis_changed_by_an_observer_is_seen_by_the_next_scan():
    plc, main, task = make_plc()
    plc.controller.add_observer(warn_at(task, 10))       # after scan 10
    plc.run(30)
    assert main["ObsrSeenAt"] == 11


def test_an_axis_changed_by_an_after_hook_is_seen_by_the_next_scan():
    plc, main, task = make_plc()
    plc.add_io_hook(after=warn_at(task, 10))          # after the motion processing of scan 10
    plc.run(30)
    assert main["ObsrSeenAt"] == 11


def test_an_axis_changed_by_a_hook_before_the_feedback_in_is_seen_in_the_same_scan():
    holder = {}
    plc, main, task = make_plc(hook_first=lambda ctx: holder["hook"](ctx))
    holder["hook"] = warn_at(task, 10)
    plc.run(30)
    assert main["ObsrSeenAt"] == 10


def test_a_traced_run_ends_as_scan_by_scan_and_keeps_skipping(count_writes):
    plc, main, task = make_plc()
    trace = plc.trace(["Cyl1.Cmd.Pos", "Cyl2.Status.ErrorStop", "CmdAtStart1"], program="Main")
    plc.run(300)
    traced = state(plc, task)
    assert count_writes.count("Cyl1") == 1 + 1 + 300      # bound, first feedback in, publications
    reference, _, reference_task = make_plc()
    for _ in range(300):
        reference.run(1)
    assert traced == state(reference, reference_task)
    data = trace.to_numpy()
    assert list(data["scan"]) == list(range(1, 301))
    assert (data["CmdAtStart1"][1:] == data["Cyl1.Cmd.Pos"][:-1]).all()   # each scan reads the last


def test_an_observer_that_says_it_only_reads_keeps_the_skip(count_writes):
    plc, main, task = make_plc()
    seen = []
    plc.controller.add_observer(lambda controller: seen.append(main["CmdAtStart1"]), reads_only=True)
    plc.run(50)
    assert count_writes.count("Cyl1") == 1 + 1 + 50
    assert len(seen) == 50


def _axis_bits(axis) -> tuple:
    return tuple(v.hex() if isinstance(v, float) else v for v in
                 (axis.state, axis.powered, axis.cmd_pos, axis.act_pos, axis.cmd_vel, axis.cmd_accdec,
                  axis.act_vel, axis.fault_code, axis.observation_code, axis.vel_limit))


def test_the_stream_step_of_the_motion_task_is_axis_step_bit_for_bit():
    """MotionTask.process spells out Axis.step for a sync stream on an ideal axis: held against
    Axis.step and the writer on a twin, through targets within reach, out of reach (VelLimit),
    beyond a soft limit (ErrorStop), not finite, a new period, a servo lag and power off."""
    import math
    import random

    from st_runtime.motion import fbs
    from st_runtime.motion.axis import Axis
    from motion_rig import PERIOD_S, make_fb
    from test_motion_fbs import axis_config, powered_rig

    generator = random.Random(17)
    for lag in (0.0, 0.002):
        rigs = [powered_rig(servo_lag=lag, following_error_limit=5.0, following_error_warning=0.5)
                for _ in range(2)]
        syncs = [make_fb(fbs.MC_SyncMoveAbsolute) for _ in rigs]
        resets = [make_fb(fbs.MC_Reset) for _ in rigs]
        seen = set()
        walk, targets = 0.0, []
        for scan in range(450):
            walk += generator.choice((0.001, 0.05, 0.099, 0.1, -0.1, -0.05)) + (0.3 if scan % 40 == 39 else 0.0)
            targets.append(walk if scan % 97 else (50.5, math.nan, math.inf, -math.inf, 49.99)[scan // 97])
        for scan, target in enumerate(targets):
            dt = PERIOD_S if scan < 300 else 2 * PERIOD_S
            enable = scan % 150 != 149
            outcome = []
            for twin, ((rig, power), sync, reset) in enumerate(zip(rigs, syncs, resets)):
                rig.task.feedback_in()
                rig.call(power, Enable=enable)
                rig.call(reset, Execute=scan % 97 == 1)
                rig.call(sync, Execute=scan % 97 != 0, Position=target)
                if twin == 0:
                    rig.task.process(dt)
                else:                                  # what process did before the stream step
                    for axis in rig.task.axes:
                        Axis.step(axis, dt)
                    for writer in rig.task._writers:
                        writer.write()
                outcome.append((_axis_bits(rig.task.axes[0]), snapshot(vars(rig.ref().v_CMD)),
                                snapshot(vars(rig.ref().v_ACT)), snapshot(vars(rig.ref().v_STATUS)),
                                snapshot(vars(rig.ref().v_DETAILS))))
            assert outcome[0] == outcome[1], (lag, scan)
            axis = rigs[0][0].task.axes[0]
            seen.add((axis.state.name, axis.vel_limit, axis.observation_code != 0))
        assert {("DISCRETE", False, False), ("DISCRETE", True, False), ("ERRORSTOP", False, False),
                ("DISABLED", False, False)} <= seen, seen
