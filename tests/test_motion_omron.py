"""OMRON's motion kernel, behaviour by behaviour, from ST programs (issue 8).

Each test runs an ST program against simulated axes (1 ms period) and checks
values computed by hand next to it.  The sources of the behaviours are in
docs/nj501.md ("OMRON's motion kernel") and docs/nj501.md."""

import math

import pytest

from st_runtime.api import LoadError, load_sources
from st_runtime.motion import MotionTask
from test_motion_st import AXIS, make_plc

DT = 0.001


def per_scan(plc, *names, program=None):
    """Values of `names` after every scan (after motion processing)."""
    rows = []

    def read(name):
        return program[name] if program is not None and not name.startswith("Cyl1.") else plc.globals[name]

    plc.controller.add_observer(lambda c: rows.append(tuple(read(n) for n in names)))
    return rows


SATURATING = """
PROGRAM Main
VAR
    Power : MC_Power;
    Sync : MC_SyncMoveAbsolute;
    Goal : LREAL := 1.0;
END_VAR
Power(Axis := Cyl1, Enable := TRUE);
IF Power.Status THEN
    Sync(Axis := Cyl1, Execute := TRUE, Position := Goal);
END_IF;
END_PROGRAM
"""


def test_sync_target_too_far_saturates_at_the_maximum_velocity():
    # 100 mm/s, 1 ms: at most 0.1 mm per period.  Scan 1 powers the axis;
    # scan 2 asks for 1.0 mm.  Commands 0.1, 0.2, ... 1.0 in scans 2..11,
    # VelLimit TRUE in scans 2..10 (the last 0.1 mm fits one period), no error,
    # although a 100 mm/s step in 1 ms is 100,000 mm/s^2 against a configured
    # 10 mm/s^2: the maximum acceleration is not used.
    plc, main, task = make_plc(SATURATING, dict(AXIS, max_acceleration=10.0))
    rows = per_scan(plc, "Cyl1.Cmd.Pos", "Cyl1.Details.VelLimit", "Cyl1.Status.Discrete",
                    "Cyl1.Status.ErrorStop", "Cyl1.Cmd.AccDec")
    plc.run(12)
    cmd = [r[0] for r in rows]
    assert cmd == pytest.approx([0.0] + [0.1 * k for k in range(1, 11)] + [1.0])
    assert [r[1] for r in rows] == [False] + [True] * 9 + [False, False]
    assert all(r[2] for r in rows[1:]) and not any(r[3] for r in rows)
    assert rows[1][4] == pytest.approx(100.0 / DT)   # 0 -> 100 mm/s in one period
    assert rows[10][4] == pytest.approx(0.0, abs=1e-6)  # the last 0.1 mm: still 100 mm/s
    assert rows[11][4] == pytest.approx(-100.0 / DT)  # 100 -> 0 mm/s (minus: decelerating)
    assert plc.faults == [] and not main["Sync.Error"] and not main["Sync.CommandAborted"]


def test_sync_active_one_period_after_execute_and_in_position_against_the_target():
    # Busy in the call of the rising edge (scan 2), Active from scan 3.
    # InPosition compares the actual position with the target (1.0), not with
    # the saturated command: the ideal axis has Act.Pos = Cmd.Pos every period,
    # yet InPosition stays FALSE until the axis is at 1.0 (scan 11), and the
    # FB shows it in the call after that motion processing (scan 12).
    plc, main, task = make_plc(SATURATING)
    rows = per_scan(plc, "Sync.Busy", "Sync.Active", "Sync.InPosition", "Cyl1.Act.Pos",
                    "Cyl1.Cmd.Pos", program=main)
    plc.run(13)
    assert [r[0] for r in rows] == [False] + [True] * 12
    assert [r[1] for r in rows] == [False, False] + [True] * 11
    assert [r[2] for r in rows] == [False] * 11 + [True, True]
    assert all(r[3] == r[4] for r in rows)


START_REFUSED = """
PROGRAM Main
VAR
    Power : MC_Power;
    Halt : MC_Stop;
    MoveAbs : MC_MoveAbsolute;
    Sync : MC_SyncMoveAbsolute;
    DoStop : BOOL;
    DoMove : BOOL;
    DoSync : BOOL;
    MoveTarget : LREAL := 60.0;
    SyncCode : WORD;
END_VAR
Power(Axis := Cyl1, Enable := TRUE);
Halt(Axis := Cyl1, Execute := DoStop, Deceleration := 100.0);
MoveAbs(Axis := Cyl1, Execute := DoMove, Position := MoveTarget, Velocity := 10.0);
Sync(Axis := Cyl1, Execute := DoSync, Position := 0.0);
SyncCode := Sync.ErrorID;
END_PROGRAM
"""


def test_sync_started_while_mc_stop_holds_the_axis_is_command_aborted():
    plc, main, _ = make_plc(START_REFUSED)
    plc.run(2)
    main["DoStop"] = True
    plc.run(2)
    assert plc.globals["Cyl1.Status.Stopping"] and main["Halt.Done"]
    main["DoSync"] = True
    plc.run(1)
    assert main["Sync.CommandAborted"] and not main["Sync.Error"] and main["SyncCode"] == 0
    assert not main["Sync.Busy"] and plc.globals["Cyl1.Status.Stopping"]


def test_sync_started_on_an_axis_with_an_error_is_command_aborted():
    # MC_MoveAbsolute to 60 mm beyond the +50 mm limit: Error 16#6440 and the
    # axis in ErrorStop; a sync started then ends with CommandAborted.
    plc, main, _ = make_plc(START_REFUSED)
    plc.run(2)
    main["DoMove"] = True
    plc.run(1)
    assert main["MoveAbs.Error"] and main["MoveAbs.ErrorID"] == 0x6440
    assert plc.globals["Cyl1.Status.ErrorStop"] and plc.globals["Cyl1.MFaultLvl.Code"] == 0x6440
    main["DoSync"] = True
    plc.run(1)
    assert main["Sync.CommandAborted"] and not main["Sync.Error"] and main["SyncCode"] == 0


def test_sync_cannot_be_re_executed():
    # Rising edge in scan 3, Execute FALSE in scan 4 (the sync goes on), a new
    # rising edge in scan 5 while Busy: Error 16#543B.
    plc, main, _ = make_plc(START_REFUSED)
    plc.run(2)
    main["DoSync"] = True
    plc.run(1)
    main["DoSync"] = False
    plc.run(1)
    assert main["Sync.Busy"]
    main["DoSync"] = True
    plc.run(1)
    assert main["Sync.Error"] and main["SyncCode"] == 0x543B and not main["Sync.Busy"]
    assert plc.globals["Cyl1.MFaultLvl.Code"] == 0x543B  # assumed: an axis error too


STOP_A_MOVE = """
PROGRAM Main
VAR
    Power : MC_Power;
    MoveAbs : MC_MoveAbsolute;
    Halt : MC_Stop;
    DoStop : BOOL;
END_VAR
Power(Axis := Cyl1, Enable := TRUE);
MoveAbs(Axis := Cyl1, Execute := Power.Status, Position := 10.0, Velocity := 50.0);
Halt(Axis := Cyl1, Execute := DoStop, Deceleration := 0.0);
END_PROGRAM
"""


def test_stop_with_deceleration_zero_is_an_immediate_stop():
    # No max_acceleration: the move steps to 50 mm/s, 0.05 mm per period from
    # scan 2: 0.05, 0.10, 0.15.  MC_Stop with Deceleration 0 in scan 5: the
    # command holds at 0.15 at once.
    plc, main, _ = make_plc(STOP_A_MOVE)
    plc.run(4)
    assert plc.globals["Cyl1.Cmd.Pos"] == pytest.approx(0.15)
    main["DoStop"] = True
    plc.run(1)
    assert plc.globals["Cyl1.Cmd.Pos"] == pytest.approx(0.15) and plc.globals["Cyl1.Cmd.Vel"] == 0.0
    plc.run(1)
    assert main["Halt.Done"] and main["MoveAbs.CommandAborted"]


LAGGING_RAMP = """
PROGRAM Main
VAR
    Power : MC_Power;
    Sync : MC_SyncMoveAbsolute;
    Reset : MC_Reset;
    Target : LREAL;
    DoReset : BOOL;
END_VAR
Power(Axis := Cyl1, Enable := TRUE);
IF Power.Status AND NOT Cyl1.Status.ErrorStop THEN
    Target := Target + 0.05;
    Sync(Axis := Cyl1, Execute := TRUE, Position := Target);
END_IF;
Reset(Axis := Cyl1, Execute := DoReset);
END_PROGRAM
"""

TAU = 0.01


def ramp_following_error(n: int, step: float = 0.05) -> float:
    """Following error after n periods of a ramp of `step` per period through a
    first-order lag: e_n = (e_(n-1) + step)(1 - g), g = 1 - e^(-dt/tau), so
    e_n = step (1 - g)(1 - (1 - g)^n) / g."""
    keep = math.exp(-DT / TAU)
    return step * keep * (1 - keep ** n) / (1 - keep)


def test_following_error_warning_644C_then_limit_6448():
    # e_1..e_6 = 0.0452, 0.0862, 0.1232, 0.1567, 0.1871, 0.2145 mm.  Warning
    # 0.1 mm: exceeded in ramp period 3 (scan 4), observation 16#644C, the
    # axis goes on.  Limit 0.2 mm: exceeded in period 6 (scan 7), 16#6448.
    assert [round(ramp_following_error(n), 4) for n in range(1, 7)] == [
        0.0452, 0.0862, 0.1232, 0.1567, 0.1871, 0.2145]
    plc, main, task = make_plc(LAGGING_RAMP, dict(AXIS, servo_lag=TAU, following_error_warning=0.1,
                                                  following_error_limit=0.2))
    rows = per_scan(plc, "Cyl1.Obsr.Active", "Cyl1.Obsr.Code", "Cyl1.Status.ErrorStop",
                    "Cyl1.MFaultLvl.Code", "Cyl1.Cmd.Pos", "Cyl1.Act.Pos")
    plc.run(8)
    assert [r[0] for r in rows] == [False, False, False, True, True, True, True, True]
    assert [r[1] for r in rows] == [0, 0, 0] + [0x644C] * 5
    assert [r[2] for r in rows] == [False] * 6 + [True, True]
    assert [r[3] for r in rows] == [0] * 6 + [0x6448, 0x6448]
    for scan in range(2, 7):
        assert rows[scan - 1][4] - rows[scan - 1][5] == pytest.approx(ramp_following_error(scan - 1))


def test_reset_fails_while_the_axis_decelerates_for_its_error():
    # As above without the warning, with error_deceleration 10,000 mm/s^2:
    # 16#6448 in scan 7 at 50 mm/s (command 0.30); the command then slows by
    # 10 mm/s per period: 0.34, 0.37, 0.39, 0.40, 0.40 (scans 8..12).  ErrorStop
    # is TRUE all along; MC_Reset in scan 8 (Cmd.Vel 50) and scan 10 (Cmd.Vel
    # 30) fails; once stopped and the lag has caught up, it succeeds.
    plc, main, task = make_plc(LAGGING_RAMP, dict(AXIS, servo_lag=TAU, following_error_limit=0.2,
                                                  error_deceleration=10_000.0))
    rows = per_scan(plc, "Cyl1.Cmd.Pos", "Cyl1.Status.ErrorStop")
    plc.run(7)
    assert plc.globals["Cyl1.MFaultLvl.Code"] == 0x6448
    main["DoReset"] = True
    plc.run(1)
    assert main["Reset.Failure"] and not main["Reset.Done"] and main["Reset.ErrorID"] == 0
    main["DoReset"] = False
    plc.run(1)
    main["DoReset"] = True
    plc.run(1)
    assert main["Reset.Failure"]
    plc.run(2)
    assert [r[0] for r in rows[6:]] == pytest.approx([0.30, 0.34, 0.37, 0.39, 0.40, 0.40])
    assert all(r[1] for r in rows[6:])
    main["DoReset"] = False
    plc.run(60)        # the lag closes: following error 0.2 e^(-60 ms / 10 ms) < 0.001 mm
    main["DoReset"] = True
    plc.run(1)
    assert main["Reset.Done"] and plc.globals["Cyl1.Status.Standstill"]


def test_details_idle_is_false_while_the_command_decelerates_for_an_error():
    # As above: 16#6448 in scan 7 at 50 mm/s, then 10 mm/s less per period:
    # Cmd.Vel 50, 40, 30, 20, 10, 0 in scans 7..12.  Details.Idle: "no command
    # value is being produced" - FALSE while the error deceleration still moves
    # the command (and before, under MC_SyncMoveAbsolute), TRUE once it stands.
    plc, main, task = make_plc(LAGGING_RAMP, dict(AXIS, servo_lag=TAU, following_error_limit=0.2,
                                                  error_deceleration=10_000.0))
    rows = per_scan(plc, "Cyl1.Cmd.Vel", "Cyl1.Details.Idle", "Cyl1.Status.ErrorStop")
    plc.run(13)
    assert [r[0] for r in rows[6:12]] == pytest.approx([50.0, 40.0, 30.0, 20.0, 10.0, 0.0])
    assert [r[1] for r in rows[1:13]] == [False] * 10 + [True, True]
    assert [r[2] for r in rows[6:13]] == [True] * 7


IN_POSITION_MOVE = """
PROGRAM Main
VAR
    Power : MC_Power;
    MoveAbs : MC_MoveAbsolute;
END_VAR
Power(Axis := Cyl1, Enable := TRUE);
MoveAbs(Axis := Cyl1, Execute := Power.Status, Position := 0.35, Velocity := 100.0);
END_PROGRAM
"""


def test_in_position_check_time_exceeded_6447():
    # 100 mm/s, no max_acceleration: commands 0.1, 0.2, 0.3, 0.35 in scans
    # 2..5 (the target reached in scan 5).  With a 10 ms lag the actual
    # position is far from 0.35 (more than 0.01) for the next periods:
    # InPosWaiting in scans 5 and 6, and with a 2 ms check time the third
    # waiting period (scan 7) is error 16#6447.
    plc, main, task = make_plc(IN_POSITION_MOVE, dict(AXIS, servo_lag=TAU, in_position_check_time=0.002))
    rows = per_scan(plc, "Cyl1.Cmd.Pos", "Cyl1.Details.InPosWaiting", "Cyl1.Details.Idle",
                    "Cyl1.MFaultLvl.Code", "Cyl1.Act.Pos")
    plc.run(7)
    assert [r[0] for r in rows] == pytest.approx([0.0, 0.1, 0.2, 0.3, 0.35, 0.35, 0.35])
    assert [r[1] for r in rows] == [False] * 4 + [True, True, False]
    assert [r[2] for r in rows] == [True] + [False] * 5 + [True]
    assert [r[3] for r in rows] == [0] * 6 + [0x6447]
    assert 0.35 - rows[6][4] > 0.01
    plc.run(1)  # the FB sees the axis error in its next call
    assert main["MoveAbs.CommandAborted"] and plc.globals["Cyl1.Status.ErrorStop"]


def test_axis_variable_has_omrons_members_and_no_dev():
    task = MotionTask.from_tables([AXIS])

    def diagnostics(expression):
        program = f"PROGRAM Main\nVAR\n    x : LREAL;\n    b : BOOL;\nEND_VAR\n{expression};\nEND_PROGRAM\n"
        try:
            project = load_sources({"axes.st": task.globals_source(), "main.st": program}, dialect="nj")
        except LoadError as error:
            return [d for d in error.diagnostics if d.is_error]
        return [d for d in project.diagnostics if d.is_error]

    for ok in ("b := Cyl1.Details.Idle", "b := Cyl1.Details.VelLimit", "b := Cyl1.Details.InPosWaiting",
               "b := Cyl1.Status.Ready", "b := Cyl1.Status.Coordinated", "b := Cyl1.Obsr.Active",
               "b := Cyl1.Dir.Posi", "b := Cyl1.DrvStatus.ServoOn", "x := Cyl1.Cmd.AccDec",
               "x := Cyl1.Act.Trq"):
        assert diagnostics(ok) == [], ok
    rejected = diagnostics("x := Cyl1.Dev.Pos")
    assert rejected and "no member 'Dev'" in rejected[0].message


def test_status_ready_is_the_same_as_standstill_in_every_state():
    # OMRON W508, 2-1-2 Axis Variables: Status.Ready is "TRUE when preparations
    # for axis execution are finished and the axis is stopped", the same status
    # as Status.Standstill.  Walk the axis through Disabled, Standstill,
    # Discrete (a 0.05 mm move at 10 mm/s: five periods), Stopping (MC_Stop
    # held) and ErrorStop (a move to 60 mm, beyond the +50 mm limit).
    plc, main, _ = make_plc(START_REFUSED)
    states = ("Disabled", "Standstill", "Discrete", "Stopping", "ErrorStop")
    names = ("Cyl1.Status.Ready", *(f"Cyl1.Status.{s}" for s in states))
    before = tuple(plc.globals[name] for name in names)  # before the first scan: Disabled
    scans = per_scan(plc, *names)
    main["MoveTarget"] = 0.05
    plc.run(3)
    main["DoMove"] = True
    plc.run(10)
    main["DoMove"], main["DoStop"] = False, True
    plc.run(3)
    main["DoStop"] = False
    plc.run(2)
    main["MoveTarget"], main["DoMove"] = 60.0, True
    plc.run(2)
    rows = [before, *scans]
    seen = {state for row in rows for state, on in zip(states, row[1:]) if on}
    assert seen == set(states)
    assert [row[0] for row in rows] == [row[2] for row in rows]
