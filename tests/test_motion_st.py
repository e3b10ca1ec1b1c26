"""Motion end to end: ST programs drive simulated axes through the controller.

Scan order as on the NJ: axis feedback in, user programs, motion processing."""

import pytest

from st_runtime.api import load_sources
from st_runtime.motion import MotionTask
from st_runtime.motion.error_ids import ErrorID

AXIS = {"name": "Cyl1", "max_velocity": 100.0, "soft_limit_min": -50.0, "soft_limit_max": 50.0}


def make_plc(program: str, *axes: dict, dialect: str = "nj"):
    task = MotionTask.from_tables(axes or [AXIS])
    project = load_sources({"axes.st": task.globals_source(), "main.st": program}, dialect=dialect)
    assert not [d for d in project.diagnostics if d.is_error]
    plc = project.controller(period="1ms")
    task.install(plc.controller)
    main = plc.add_program("Main")
    return plc, main, task


SYNC_RAMP = """
PROGRAM Main
VAR
    Power : MC_Power;
    Sync : MC_SyncMoveAbsolute;
    Target : LREAL;
    CmdAtStart : LREAL;
END_VAR
CmdAtStart := Cyl1.Cmd.Pos;   (* feedback in: the command of the previous scan *)
Power(Axis := Cyl1, Enable := TRUE);
IF Power.Status THEN
    Target := Target + 0.01;
    Sync(Axis := Cyl1, Execute := TRUE, Position := Target, BufferMode := _mcAborting);
END_IF;
END_PROGRAM
"""


def test_position_written_in_scan_k_is_the_command_of_scan_k():
    plc, main, task = make_plc(SYNC_RAMP)
    trace = plc.trace(["Target", "CmdAtStart", "Cyl1.Cmd.Pos", "Cyl1.Act.Pos"], program="Main")
    plc.run(6)
    # Scan 1 powers the axis (Status TRUE from scan 2); scans 2..6 command 0.01 .. 0.05.
    assert main["Target"] == pytest.approx(0.05)
    assert plc.globals["Cyl1.Cmd.Pos"] == main["Target"]
    assert task.axis("Cyl1").cmd_pos == main["Target"]
    assert main["CmdAtStart"] == pytest.approx(0.04)  # what scan 6 read: scan 5's command
    assert main["Sync.Busy"] and main["Sync.Active"] and main["Sync.InPosition"]
    # Discrete, not Synchronized (changed in issue 8: OMRON's MC_SyncMoveAbsolute
    # keeps the axis in Status.Discrete, docs/nj501.md).
    assert plc.globals["Cyl1.Status.Discrete"] and not plc.globals["Cyl1.Status.Synchronized"]
    assert plc.faults == []
    data = trace.to_numpy()
    target, cmd, at_start = data["Target"], data["Cyl1.Cmd.Pos"], data["CmdAtStart"]
    assert list(data["scan"]) == [1, 2, 3, 4, 5, 6]
    assert (cmd == target).all()                 # every scan: its own Position is its command
    assert (at_start[1:] == cmd[:-1]).all()      # and the programs see it in the next scan
    assert cmd[-1] == pytest.approx(0.05)


def test_position_of_each_scan_in_the_trace():
    plc, main, task = make_plc(SYNC_RAMP)
    samples = []
    plc.controller.add_observer(lambda c: samples.append(
        (main["Target"], plc.globals["Cyl1.Cmd.Pos"], main["CmdAtStart"])))
    plc.run(5)
    for k, (target, cmd, at_start) in enumerate(samples[1:], start=2):
        assert cmd == target == pytest.approx(0.01 * (k - 1))      # scan k's Position is scan k's Cmd.Pos
        assert at_start == pytest.approx(0.01 * (k - 2))           # seen by ST in the next scan


def test_motion_fb_on_disabled_axis_fails_in_st():
    plc, main, _ = make_plc("""
PROGRAM Main
VAR
    MoveAbs : MC_MoveAbsolute;
    Failed : BOOL;
    Code : WORD;
END_VAR
MoveAbs(Axis := Cyl1, Execute := TRUE, Position := 10.0, Velocity := 5.0);
Failed := MoveAbs.Error AND MoveAbs.ErrorID = WORD#16#5402;
Code := MoveAbs.ErrorID;
END_PROGRAM
""")
    plc.run(2)
    assert main["Failed"] and main["Code"] == ErrorID.AXIS_DISABLED
    assert plc.globals["Cyl1.Status.Disabled"] and not plc.globals["Cyl1.MFaultLvl.Active"]


FAULT_AND_RESET = """
PROGRAM Main
VAR
    Power : MC_Power;
    Sync : MC_SyncMoveAbsolute;
    Reset : MC_Reset;
    Step : LREAL := 0.05;
    Target : LREAL;
    DoReset : BOOL;
    FaultSeen : BOOL;
    FaultCode : WORD;
END_VAR
Power(Axis := Cyl1, Enable := TRUE);
IF Cyl1.MFaultLvl.Active THEN
    FaultSeen := TRUE;
    FaultCode := Cyl1.MFaultLvl.Code;
END_IF;
IF Power.Status AND NOT Cyl1.Status.ErrorStop AND NOT DoReset THEN
    Target := Target + Step;
    Sync(Axis := Cyl1, Execute := TRUE, Position := Target);
ELSE
    Sync(Axis := Cyl1, Execute := FALSE, Position := Target);
END_IF;
Reset(Axis := Cyl1, Execute := DoReset);
END_PROGRAM
"""


def test_soft_limit_fault_errorstop_then_reset_to_standstill():
    # Changed in issue 8: this test faulted the axis with a step above the
    # maximum velocity (an invented error, 16#6402); OMRON saturates such a
    # step (test_motion_omron.py), so the fault is now the software limit.
    plc, main, task = make_plc(FAULT_AND_RESET, dict(AXIS, soft_limit_max=0.12))
    plc.run(3)                      # powered in scan 2: 0.05, 0.10
    plc.run(1)                      # 0.15 > 0.12: not applied, ErrorStop
    assert plc.globals["Cyl1.Status.ErrorStop"] and plc.globals["Cyl1.MFaultLvl.Active"]
    assert plc.globals["Cyl1.MFaultLvl.Code"] == ErrorID.TARGET_POSITIVE_SOFT_LIMIT == 0x6440
    assert plc.globals["Cyl1.Cmd.Pos"] == pytest.approx(0.10)   # the refused step is not applied
    plc.run(1)
    assert main["FaultSeen"] and main["FaultCode"] == 0x6440
    # The FB noticed the abort in this scan, with Execute already FALSE: one scan only.
    assert main["Sync.CommandAborted"] and not main["Sync.Busy"]
    plc.run(1)
    assert not main["Sync.CommandAborted"]
    main["DoReset"] = True
    plc.run(1)
    assert main["Reset.Done"]
    assert plc.globals["Cyl1.Status.Standstill"] and not plc.globals["Cyl1.MFaultLvl.Active"]
    assert plc.globals["Cyl1.MFaultLvl.Code"] == 0


def test_software_limit_fault_in_st():
    plc, main, _ = make_plc(FAULT_AND_RESET, dict(AXIS, soft_limit_max=0.12))
    plc.run(4)  # commands 0.05, 0.10, then 0.15 > 0.12
    assert plc.globals["Cyl1.MFaultLvl.Code"] == ErrorID.TARGET_POSITIVE_SOFT_LIMIT
    assert plc.globals["Cyl1.Cmd.Pos"] == pytest.approx(0.10)


def test_following_error_fault_with_servo_lag():
    # tau = 10 ms, 0.05 mm per scan: the lag grows towards 0.475 mm; limit 0.2 mm.
    plc, main, task = make_plc(FAULT_AND_RESET, dict(AXIS, servo_lag=0.01, following_error_limit=0.2))
    plc.run(30)
    assert plc.globals["Cyl1.MFaultLvl.Code"] == ErrorID.FOLLOWING_ERROR_EXCEEDED == 0x6448
    assert main["FaultCode"] == 0x6448 and plc.globals["Cyl1.MFaultLvl.Active"]


STOP_DURING_SYNC = """
PROGRAM Main
VAR
    Power : MC_Power;
    Sync : MC_SyncMoveAbsolute;
    Halt : MC_Stop;
    Target : LREAL;
    StopNow : BOOL;
    WasStopping : BOOL;
END_VAR
Power(Axis := Cyl1, Enable := TRUE);
IF Power.Status THEN
    Target := Target + 0.05;
    Sync(Axis := Cyl1, Execute := TRUE, Position := Target);
END_IF;
Halt(Axis := Cyl1, Execute := StopNow, Deceleration := 10000.0);
WasStopping := WasStopping OR Cyl1.Status.Stopping;
END_PROGRAM
"""


def test_stop_aborts_synchronized_motion_and_ends_in_standstill():
    # Changed in issue 8: the stop decelerated at 10,000 mm/s^2 (40, 30, 20,
    # 10, 0 mm/s); on an axis under MC_SyncMoveAbsolute OMRON's MC_Stop is an
    # immediate stop and its Deceleration is ignored (docs/nj501.md).
    plc, main, task = make_plc(STOP_DURING_SYNC)
    plc.run(4)                        # synchronized at 50 mm/s: 0.05, 0.10, 0.15
    main["StopNow"] = True
    plc.run(1)
    assert main["Halt.Busy"] and plc.globals["Cyl1.Status.Stopping"]
    assert plc.globals["Cyl1.Cmd.Vel"] == 0.0 and plc.globals["Cyl1.Cmd.Pos"] == pytest.approx(0.15)
    plc.run(1)
    assert main["Sync.CommandAborted"] and not main["Sync.Busy"]
    assert main["Halt.Done"] and plc.globals["Cyl1.Status.Stopping"]
    main["StopNow"] = False
    plc.run(1)
    assert plc.globals["Cyl1.Status.Standstill"] and main["WasStopping"]
    assert not main["Halt.Done"]
    assert plc.globals["Cyl1.Cmd.Pos"] == pytest.approx(0.15)
    assert plc.faults == []


PULSED_MOVE = """
PROGRAM Main
VAR
    Power : MC_Power;
    MoveAbs : MC_MoveAbsolute;
    Go : BOOL;
    DoneScans : INT;
END_VAR
Power(Axis := Cyl1, Enable := TRUE);
MoveAbs(Axis := Cyl1, Execute := Go, Position := 0.35, Velocity := 100.0);
IF MoveAbs.Done THEN
    DoneScans := DoneScans + 1;
END_IF;
END_PROGRAM
"""


def test_move_absolute_execute_pulse_gives_done_for_one_scan():
    plc, main, _ = make_plc(PULSED_MOVE)
    plc.run(2)
    main["Go"] = True
    plc.run(1)
    assert main["MoveAbs.Busy"] and main["MoveAbs.Active"] and plc.globals["Cyl1.Status.Discrete"]
    main["Go"] = False               # Execute falls early: the move goes on
    plc.run(10)
    assert plc.globals["Cyl1.Cmd.Pos"] == pytest.approx(0.35)
    assert plc.globals["Cyl1.Status.Standstill"]
    assert main["DoneScans"] == 1


def test_axis_passed_through_a_user_fb():
    plc, main, task = make_plc("""
FUNCTION_BLOCK Drive
VAR_IN_OUT
    Ax : AXIS_REF;
END_VAR
VAR_INPUT
    Position : LREAL;
END_VAR
VAR
    Power : MC_Power;
    Sync : MC_SyncMoveAbsolute;
END_VAR
Power(Axis := Ax, Enable := TRUE);
Sync(Axis := Ax, Execute := Power.Status, Position := Position);
END_FUNCTION_BLOCK

PROGRAM Main
VAR
    D1 : Drive;
    D2 : Drive;
END_VAR
D1(Ax := Cyl1, Position := 1.0 * Cyl1.Act.Pos + 0.02);
D2(Ax := Cyl2, Position := Cyl2.Act.Pos - 0.03);
END_PROGRAM
""", AXIS, dict(AXIS, name="Cyl2", initial_position=5.0))
    plc.run(4)  # powered after scan 1; scans 2, 3, 4 move
    assert task.axis("Cyl1").cmd_pos == pytest.approx(0.06)
    assert task.axis("Cyl2").cmd_pos == pytest.approx(5.0 - 0.09)
    assert plc.globals["Cyl2.Cfg.AxNo"] == 1


def test_local_axis_ref_is_not_an_axis():
    plc, main, _ = make_plc("""
PROGRAM Main
VAR
    Spare : AXIS_REF;
    Power : MC_Power;
END_VAR
Power(Axis := Spare, Enable := TRUE);
END_PROGRAM
""")
    plc.run(1)
    assert main["Power.Error"] and main["Power.ErrorID"] == ErrorID.AXIS_NOT_ASSIGNED


def test_globals_source_and_install_once():
    task = MotionTask.from_tables([AXIS, dict(AXIS, name="Cyl2")])
    assert task.globals_source() == (
        "VAR_GLOBAL\n    Cyl1 : AXIS_REF; (* axis 0 *)\n    Cyl2 : AXIS_REF; (* axis 1 *)\nEND_VAR\n"
    )
    plc, main, task = make_plc(SYNC_RAMP)
    with pytest.raises(ValueError, match="already has a motion task"):
        MotionTask.from_tables([AXIS]).install(plc.controller)


@pytest.mark.parametrize("declaration, message", [
    ("", "is not declared"),
    ("VAR_GLOBAL\n    Cyl1 : LREAL;\nEND_VAR\n", "is declared as LREAL"),
])
def test_install_needs_the_axis_globals(declaration, message):
    task = MotionTask.from_tables([AXIS])
    program = declaration + "PROGRAM Main\nVAR\n    x : INT;\nEND_VAR\nx := 1;\nEND_PROGRAM\n"
    plc = load_sources({"main.st": program}).controller()
    with pytest.raises(ValueError, match=message):
        task.install(plc.controller)
