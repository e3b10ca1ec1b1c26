"""Motion FBs on the simulated axes: PLCopen state machine and output rules."""

import pytest

from st_runtime.motion import fbs
from st_runtime.motion.axis_config import AxisConfig
from st_runtime.motion.error_ids import ErrorID
from motion_rig import Rig, make_axis_ref, make_fb


def axis_config(**overrides):
    settings = dict(name="Ax", max_velocity=100.0, soft_limit_min=-50.0, soft_limit_max=50.0)
    settings.update(overrides)
    return AxisConfig(**settings)


def powered_rig(**overrides):
    rig = Rig(axis_config(**overrides))
    power = make_fb(fbs.MC_Power)
    rig.scan(lambda: rig.call(power, Enable=True))
    rig.scan(lambda: rig.call(power, Enable=True))
    assert power.v_STATUS and rig.ref().v_STATUS.v_STANDSTILL
    return rig, power


def outputs(fb, *names):
    return tuple(getattr(fb, "v_" + n.upper()) for n in names)


def test_bind_marks_the_axis_ref():
    rig = Rig(axis_config(name="A0"), axis_config(name="A1", initial_position=4.0))
    assert rig.ref("A1").v_CFG.v_AXNO == 1 and rig.ref("A1").v_CFG.v_AXENABLE
    assert rig.ref("A1").v_ACT.v_POS == 4.0
    assert rig.ref("A0").v_STATUS.v_DISABLED


def test_power_status_follows_enable_one_scan_later():
    rig = Rig(axis_config())
    power = make_fb(fbs.MC_Power)
    rig.scan(lambda: rig.call(power, Enable=True))
    assert outputs(power, "Status", "Busy", "Error") == (False, True, False)
    assert rig.ref().v_STATUS.v_STANDSTILL  # published by motion processing
    rig.scan(lambda: rig.call(power, Enable=True))
    assert outputs(power, "Status", "Busy") == (True, False)
    rig.scan(lambda: rig.call(power, Enable=False))
    rig.scan(lambda: rig.call(power, Enable=False))
    assert not power.v_STATUS and rig.ref().v_STATUS.v_DISABLED


def test_unbound_axis_ref_is_an_error():
    rig = Rig(axis_config())
    move = make_fb(fbs.MC_MoveAbsolute)
    move.v_AXIS = make_axis_ref()  # a local AXIS_REF: AxEnable FALSE
    move.v_EXECUTE, move.v_VELOCITY = True, 1.0
    move.execute(rig.ctx)
    assert outputs(move, "Error", "ErrorID", "Busy") == (True, ErrorID.AXIS_NOT_ASSIGNED, False)


@pytest.mark.parametrize("fb_class", [fbs.MC_SyncMoveAbsolute, fbs.MC_MoveAbsolute, fbs.MC_Stop, fbs.MC_Home])
def test_motion_fb_on_disabled_axis_fails(fb_class):
    rig = Rig(axis_config())
    fb = make_fb(fb_class)
    rig.scan(lambda: rig.call(fb, Execute=True, Velocity=1.0) if fb_class is fbs.MC_MoveAbsolute
             else rig.call(fb, Execute=True))
    assert outputs(fb, "Error", "ErrorID", "Busy") == (True, ErrorID.AXIS_DISABLED, False)
    assert rig.ref().v_STATUS.v_DISABLED and not rig.ref().v_MFAULTLVL.v_ACTIVE
    # The error is held while Execute stays TRUE, and cleared when it falls.
    rig.scan(lambda: rig.call(fb, Execute=True))
    assert fb.v_ERROR and fb.v_ERRORID == ErrorID.AXIS_DISABLED
    rig.scan(lambda: rig.call(fb, Execute=False))
    assert outputs(fb, "Error", "ErrorID") == (False, 0)


def test_sync_position_of_scan_k_is_the_command_of_scan_k():
    rig, power = powered_rig()
    sync = make_fb(fbs.MC_SyncMoveAbsolute)
    seen_at_start = []
    for k in range(1, 6):
        def user_program(k=k):
            seen_at_start.append(rig.ref().v_CMD.v_POS)  # feedback in: previous scan's command
            rig.call(power, Enable=True)
            rig.call(sync, Execute=True, Position=0.01 * k)
        rig.scan(user_program)
        assert rig.task.axis("Ax").cmd_pos == 0.01 * k  # applied in the same scan
        assert rig.ref().v_CMD.v_POS == 0.01 * k       # and published after it
    assert seen_at_start == pytest.approx([0.0, 0.01, 0.02, 0.03, 0.04])
    assert outputs(sync, "Busy", "Active", "InPosition") == (True, True, True)
    # Changed in issue 8: Status.Discrete, not Synchronized (OMRON, docs/nj501.md).
    assert rig.ref().v_STATUS.v_DISCRETE and not rig.ref().v_STATUS.v_SYNCHRONIZED


def test_sync_continues_after_execute_falls():
    rig, power = powered_rig()
    sync = make_fb(fbs.MC_SyncMoveAbsolute)
    rig.scan(lambda: rig.call(sync, Execute=True, Position=0.05))
    rig.scan(lambda: rig.call(sync, Execute=False, Position=0.1))
    assert rig.task.axis("Ax").cmd_pos == 0.1 and sync.v_BUSY


def test_sync_step_above_max_velocity_saturates_instead_of_faulting():
    # Changed in issue 8: a 200 mm/s step put the axis in ErrorStop with an
    # invented code (16#6402); OMRON saturates the command velocity at the
    # axis maximum (100 mm/s: 0.1 mm per 1 ms) and outputs the rest later.
    rig, power = powered_rig()
    sync = make_fb(fbs.MC_SyncMoveAbsolute)
    rig.scan(lambda: rig.call(sync, Execute=True, Position=0.1))
    rig.scan(lambda: rig.call(sync, Execute=True, Position=0.3))  # 0.2 mm in 1 ms = 200 mm/s
    ref = rig.ref()
    assert not ref.v_STATUS.v_ERRORSTOP and ref.v_DETAILS.v_VELLIMIT
    assert ref.v_CMD.v_POS == pytest.approx(0.2) and ref.v_CMD.v_VEL == pytest.approx(100.0)
    rig.scan(lambda: rig.call(sync, Execute=True, Position=0.3))
    assert ref.v_CMD.v_POS == pytest.approx(0.3) and not ref.v_DETAILS.v_VELLIMIT
    assert outputs(sync, "CommandAborted", "Busy", "Active", "Error") == (False, True, True, False)


def test_soft_limit_fault_then_reset_back_to_standstill():
    rig, power = powered_rig(soft_limit_max=0.15)
    sync = make_fb(fbs.MC_SyncMoveAbsolute)
    reset = make_fb(fbs.MC_Reset)
    rig.scan(lambda: rig.call(sync, Execute=True, Position=0.1))
    rig.scan(lambda: rig.call(sync, Execute=True, Position=0.16))
    assert rig.ref().v_MFAULTLVL.v_CODE == ErrorID.TARGET_POSITIVE_SOFT_LIMIT
    # A new start on the faulted axis ends with CommandAborted, not Error
    # (changed in issue 8: it was Error 16#5403, invented; OMRON, docs/nj501.md).
    move = make_fb(fbs.MC_MoveAbsolute)
    rig.scan(lambda: rig.call(move, Execute=True, Position=0.0, Velocity=1.0))
    assert outputs(move, "CommandAborted", "Error", "ErrorID", "Busy") == (True, False, 0, False)
    rig.scan(lambda: (rig.call(power, Enable=True), rig.call(reset, Execute=True)))
    assert outputs(reset, "Done", "Busy", "Failure", "Error") == (True, False, False, False)
    ref = rig.ref()
    assert ref.v_STATUS.v_STANDSTILL and not ref.v_MFAULTLVL.v_ACTIVE and ref.v_MFAULTLVL.v_CODE == 0


def test_reset_failure_while_following_error_persists():
    rig, power = powered_rig(servo_lag=0.01, following_error_limit=0.03)
    sync = make_fb(fbs.MC_SyncMoveAbsolute)
    reset = make_fb(fbs.MC_Reset)
    rig.scan(lambda: rig.call(sync, Execute=True, Position=0.05))  # error 0.0452 > 0.03
    assert rig.ref().v_MFAULTLVL.v_CODE == ErrorID.FOLLOWING_ERROR_EXCEEDED
    rig.scan(lambda: rig.call(reset, Execute=True))
    # Changed in issue 8: ErrorID was an invented 16#5420; Failure is not an
    # Error and carries no ErrorID.
    assert outputs(reset, "Done", "Failure", "Error", "ErrorID") == (False, True, False, 0)
    assert rig.ref().v_STATUS.v_ERRORSTOP


def test_stop_aborts_sync_and_axis_ends_in_standstill():
    # Changed in issue 8: the stop decelerated at 10,000 mm/s^2; on an axis
    # under MC_SyncMoveAbsolute OMRON's MC_Stop is an immediate stop, its
    # Deceleration ignored (docs/nj501.md).  A start while Stopping is CommandAborted
    # (it was Error 16#5404, invented).
    rig, power = powered_rig()
    sync = make_fb(fbs.MC_SyncMoveAbsolute)
    stop = make_fb(fbs.MC_Stop)
    for k in range(1, 4):
        rig.scan(lambda k=k: rig.call(sync, Execute=True, Position=0.05 * k))  # 50 mm/s
    rig.scan(lambda: (rig.call(sync, Execute=True, Position=0.2),
                      rig.call(stop, Execute=True, Deceleration=10000.0)))
    # The stop took the axis in this scan: the sync Position 0.2 was not
    # applied, and the command stopped at once at 0.15.
    assert rig.task.axis("Ax").cmd_pos == pytest.approx(0.15)
    assert rig.ref().v_CMD.v_VEL == 0.0
    assert outputs(stop, "Busy", "Active", "Done") == (True, True, False)
    rig.scan(lambda: (rig.call(sync, Execute=True, Position=0.25), rig.call(stop, Execute=True)))
    assert outputs(sync, "CommandAborted", "Busy", "Active") == (True, False, False)
    assert outputs(stop, "Done", "Busy", "Active") == (True, False, False)
    assert rig.ref().v_STATUS.v_STOPPING  # held while Execute is TRUE
    assert rig.task.axis("Ax").cmd_pos == pytest.approx(0.15)
    # A motion FB started while the axis is held in Stopping: CommandAborted.
    move = make_fb(fbs.MC_MoveAbsolute)
    rig.scan(lambda: (rig.call(stop, Execute=True), rig.call(move, Execute=True, Velocity=1.0)))
    assert outputs(move, "CommandAborted", "Error", "ErrorID") == (True, False, 0)
    rig.scan(lambda: rig.call(stop, Execute=False))
    assert rig.ref().v_STATUS.v_STANDSTILL
    assert outputs(stop, "Done", "Busy") == (False, False)
    # CommandAborted of the sync FB is held while its Execute stays TRUE, then cleared.
    rig.scan(lambda: rig.call(sync, Execute=True))
    assert sync.v_COMMANDABORTED
    rig.scan(lambda: rig.call(sync, Execute=False))
    assert not sync.v_COMMANDABORTED


def test_move_absolute_done_for_one_scan_when_execute_fell_early():
    rig, power = powered_rig()
    move = make_fb(fbs.MC_MoveAbsolute)
    rig.scan(lambda: rig.call(move, Execute=True, Position=0.25, Velocity=100.0))
    assert outputs(move, "Busy", "Active") == (True, True)
    assert rig.ref().v_STATUS.v_DISCRETE
    rig.scan(lambda: rig.call(move, Execute=False))  # the move goes on
    assert move.v_BUSY and not move.v_DONE
    rig.scan(lambda: rig.call(move, Execute=False))  # 3 x 0.1 mm covers 0.25: arrived
    rig.scan(lambda: rig.call(move, Execute=False))
    assert outputs(move, "Done", "Busy", "Active") == (True, False, False)
    assert rig.ref().v_STATUS.v_STANDSTILL and rig.ref().v_CMD.v_POS == 0.25
    rig.scan(lambda: rig.call(move, Execute=False))
    assert not move.v_DONE  # one call only


def test_move_absolute_done_held_while_execute_true():
    rig, power = powered_rig()
    move = make_fb(fbs.MC_MoveAbsolute)
    for _ in range(4):
        rig.scan(lambda: rig.call(move, Execute=True, Position=-0.2, Velocity=100.0))
    assert move.v_DONE
    rig.scan(lambda: rig.call(move, Execute=True))
    assert move.v_DONE
    rig.scan(lambda: rig.call(move, Execute=False))
    assert not move.v_DONE


def test_move_absolute_beyond_soft_limit_is_an_error_and_an_axis_fault():
    rig, power = powered_rig()
    move = make_fb(fbs.MC_MoveAbsolute)
    rig.scan(lambda: rig.call(move, Execute=True, Position=51.0, Velocity=10.0))
    # OMRON's code (changed in issue 8 from an invented 16#5412).
    assert outputs(move, "Error", "ErrorID") == (True, ErrorID.TARGET_POSITIVE_SOFT_LIMIT)
    assert rig.ref().v_STATUS.v_ERRORSTOP
    assert rig.ref().v_MFAULTLVL.v_CODE == 0x6440


def test_buffer_mode_other_than_aborting_is_refused():
    rig, power = powered_rig()
    sync = make_fb(fbs.MC_SyncMoveAbsolute)
    rig.scan(lambda: rig.call(sync, Execute=True, BufferMode=1))
    assert outputs(sync, "Error", "ErrorID") == (True, ErrorID.BUFFER_MODE_NOT_SUPPORTED)


def test_home_sets_homed():
    rig, power = powered_rig()
    home = make_fb(fbs.MC_Home)
    assert not rig.ref().v_DETAILS.v_HOMED
    rig.scan(lambda: rig.call(home, Execute=True))
    assert home.v_BUSY  # the motion processing after the call homes the axis
    assert rig.ref().v_DETAILS.v_HOMED
    rig.scan(lambda: rig.call(home, Execute=True))
    assert outputs(home, "Done", "Busy") == (True, False)
    assert rig.ref().v_DETAILS.v_HOMED and rig.ref().v_STATUS.v_STANDSTILL


def test_power_off_aborts_motion():
    rig, power = powered_rig()
    sync = make_fb(fbs.MC_SyncMoveAbsolute)
    rig.scan(lambda: rig.call(sync, Execute=True, Position=0.05))
    rig.scan(lambda: (rig.call(power, Enable=False), rig.call(sync, Execute=True, Position=0.1)))
    rig.scan(lambda: rig.call(sync, Execute=True, Position=0.1))
    assert sync.v_COMMANDABORTED and rig.ref().v_STATUS.v_DISABLED


def test_new_rising_edge_while_busy_restarts_with_new_inputs():
    rig, power = powered_rig()
    move = make_fb(fbs.MC_MoveAbsolute)
    rig.scan(lambda: rig.call(move, Execute=True, Position=5.0, Velocity=100.0))
    rig.scan(lambda: rig.call(move, Execute=False))
    rig.scan(lambda: rig.call(move, Execute=True, Position=-0.1, Velocity=100.0))
    assert move.v_BUSY and not move.v_COMMANDABORTED  # its own restart is no abort
    for _ in range(10):
        rig.scan(lambda: rig.call(move, Execute=True))
    assert move.v_DONE and rig.task.axis("Ax").cmd_pos == -0.1


def test_second_sync_instance_takes_the_axis_and_aborts_the_first():
    rig, power = powered_rig()
    first, second = make_fb(fbs.MC_SyncMoveAbsolute), make_fb(fbs.MC_SyncMoveAbsolute)
    rig.scan(lambda: rig.call(first, Execute=True, Position=0.05))
    rig.scan(lambda: (rig.call(first, Execute=True, Position=0.1), rig.call(second, Execute=True, Position=0.12)))
    assert rig.task.axis("Ax").cmd_pos == 0.12  # the later call in the scan owns the axis
    rig.scan(lambda: (rig.call(first, Execute=True, Position=0.3), rig.call(second, Execute=True, Position=0.14)))
    assert first.v_COMMANDABORTED and not first.v_BUSY
    assert second.v_BUSY and rig.task.axis("Ax").cmd_pos == 0.14


@pytest.mark.parametrize("fb_class", [fbs.MC_Reset, fbs.MC_Home, fbs.MC_Stop, fbs.MC_MoveAbsolute,
                                      fbs.MC_SyncMoveAbsolute])
def test_the_idle_test_of_final_outputs_covers_exactly_each_fbs_final_outputs(fb_class):
    # `_final_shown` (and the idle call's test) spells out FINAL_OUTPUTS and ErrorID,
    # generated per class (speed): each of them alone makes it true, none makes it false.
    fb = make_fb(fb_class)
    assert not fb._final_shown()
    for output in (*fb_class.FINAL_OUTPUTS, "v_ERRORID"):
        setattr(fb, output, 0x6440 if output == "v_ERRORID" else True)
        assert fb._final_shown(), output
        setattr(fb, output, 0 if output == "v_ERRORID" else False)
        assert not fb._final_shown()


def test_the_idle_call_is_spelt_out_per_class_and_only_from_attribute_names():
    for fb_class in (fbs.MC_Reset, fbs.MC_Home, fbs.MC_Stop, fbs.MC_MoveAbsolute):
        assert fb_class.execute is fb_class._execute_rules
    assert fbs.MC_SyncMoveAbsolute.execute is not fbs.MC_SyncMoveAbsolute._execute_rules   # its own short path
    with pytest.raises(ValueError, match="attribute names only"):
        type("Odd", (fbs._ExecuteFB,), {"FINAL_OUTPUTS": ("v_DONE; import os",)})


@pytest.mark.parametrize("offset, in_position", [
    (0.0, True), (-0.25, True), (0.25, True), (-0.5, True), (0.5, True),    # the bounds count
    (-0.5000000001, False), (0.5000000001, False), (-3.0, False), (3.0, False), (float("nan"), False),
])
def test_sync_in_position_is_the_range_either_side_of_the_target(offset, in_position):
    """InPosition while synchronized: the actual position within the in-position range of the
    target, either side (docs/nj501.md, SPEC 7: the simulator compares with the target), as the
    hot path of every synchronized call computes it: |act - target| <= range."""
    rig, power = powered_rig(in_position_range=0.5)
    sync = make_fb(fbs.MC_SyncMoveAbsolute)
    rig.scan(lambda: rig.call(sync, Execute=True, Position=0.0))
    rig.task.axis("Ax").act_pos = offset             # the target stays 0.0
    rig.call(sync, Execute=True, Position=0.0)
    assert sync.v_ACTIVE and sync.v_INPOSITION is in_position
