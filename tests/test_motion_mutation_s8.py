"""Motion behaviour that the seed-23 mutation sample found unchecked (issue 16, docs/mutation.md).

Expected values are worked out by hand from the rules the motion package documents (OMRON's
MC_SyncMoveAbsolute and MC_Stop as docs/nj501.md summarises them, the NJ's 127-byte names),
not read from a run.
"""

from __future__ import annotations

import pytest

from motion_rig import make_axis_ref, make_fb
from test_motion_fbs import powered_rig
from test_motion_mutants import config, powered
from test_motion_st import AXIS, make_plc
from st_runtime.motion import MotionTask, fbs
from st_runtime.motion.axis import AxisState
from st_runtime.motion.error_ids import ErrorID

DT = 0.001


# --- the axis, driven directly ---------------------------------------------------------------------

def test_a_sync_position_across_zero_saturates_at_one_step_towards_it():
    # From -10 mm, Position +10 mm is 20 mm away: at 100 mm/s one period reaches 0.1 mm, so the
    # command moves to -9.9 mm with Details.VelLimit (the distance is target - command, not a sum).
    axis = powered(initial_position=-10.0)
    command = axis.start_sync()
    command.target = 10.0
    axis.step(DT)
    assert axis.cmd_pos == pytest.approx(-9.9, abs=1e-12) and axis.vel_limit is True
    assert axis.cmd_vel == pytest.approx(100.0)


def test_a_move_refused_on_the_way_decelerates_at_the_error_deceleration():
    # A stop that would carry the command past the +10 mm limit faults the axis (16#6440); with
    # error_deceleration 1000 mm/s^2 the command then loses 1000 * 1 ms = 1 mm/s in that very
    # period and in each one after it, in the direction it was moving, until it stands.
    axis = powered(soft_limit_min=-10.0, soft_limit_max=10.0, error_deceleration=1000.0)
    axis.start_move_absolute(10.0, 100.0, 1e5, 1e5)
    for _ in range(50):
        axis.step(DT)
    axis.start_stop(100.0)
    while axis.state != AxisState.ERRORSTOP:
        old_pos, old_vel = axis.cmd_pos, axis.cmd_vel
        axis.step(DT)
    assert axis.fault_code == ErrorID.TARGET_POSITIVE_SOFT_LIMIT
    assert axis.cmd_vel == pytest.approx(old_vel - 1.0, rel=1e-9)
    assert axis.cmd_pos == pytest.approx(old_pos + (old_vel - 1.0) * DT, rel=1e-12)
    speeds = []
    while axis.cmd_vel > 0:
        axis.step(DT)
        speeds.append(axis.cmd_vel)
    assert speeds[0] == pytest.approx(old_vel - 2.0, rel=1e-9) and speeds[-1] == 0.0


def test_an_axis_name_may_have_127_bytes_not_128():
    # The name becomes an ST global: the NJ takes identifiers of at most 127 bytes
    # (checker/nj_rules.py, E-NJ-001).
    assert config(name="A" * 127).name == "A" * 127
    with pytest.raises(ValueError, match="key 'name'"):
        config(name="A" * 128)


# --- the FBs on the bench --------------------------------------------------------------------------

@pytest.mark.parametrize("fb_class", [fbs.MC_Reset, fbs.MC_Home, fbs.MC_Stop, fbs.MC_MoveAbsolute,
                                      fbs.MC_SyncMoveAbsolute])
def test_the_compiled_callers_idle_test_is_true_exactly_when_a_call_can_change_something(fb_class):
    # CALL_NEEDED, the test a compiled caller makes before calling the FB (compiler/calls.py): true
    # while Execute or Busy is TRUE, a final output or ErrorID is shown, the remembered Execute is
    # TRUE, or (MC_Stop) a command is left; false only for an idle FB.  A class made now, so that
    # its test is spelt out in this process (the package's classes were made at import).
    probe = make_fb(type("Probe", (fb_class,), {}))
    needed = lambda: eval(type(probe).CALL_NEEDED.format(fb="fb"), {"fb": probe})   # noqa: E731
    assert not needed()            # a condition of the compiled caller: read as a truth value
    flags = ["v_EXECUTE", "v_BUSY", *fb_class.FINAL_OUTPUTS, "v_ERRORID", "_previous_execute"]
    for flag in flags:
        old = getattr(probe, flag)
        setattr(probe, flag, 0x5401 if flag == "v_ERRORID" else True)
        assert needed(), flag
        setattr(probe, flag, old)
    if fb_class.AFTER_CALL:
        probe._command = object()
        assert needed()


def test_a_sync_started_again_while_mc_stop_holds_the_axis_is_command_aborted():
    # Execute of a running MC_SyncMoveAbsolute fell (it goes on, Busy), then in one scan MC_Stop
    # starts and the sync's Execute rises again: started while MC_Stop holds the axis, the sync
    # ends with CommandAborted, not with the re-execution error 16#543B (OMRON's
    # MC_SyncMoveAbsolute; fbs.py), and the axis stays in Stopping, not ErrorStop.
    rig, _ = powered_rig()
    sync, stop = make_fb(fbs.MC_SyncMoveAbsolute), make_fb(fbs.MC_Stop)
    rig.scan(lambda: rig.call(sync, Execute=True, Position=0.0, BufferMode=0))
    rig.scan(lambda: rig.call(sync, Execute=False, Position=0.0, BufferMode=0))
    assert sync.v_BUSY
    rig.scan(lambda: rig.call(stop, Execute=True, Deceleration=1000.0, BufferMode=0),
             lambda: rig.call(sync, Execute=True, Position=0.0, BufferMode=0))
    assert (sync.v_COMMANDABORTED, sync.v_ERROR, sync.v_ERRORID, sync.v_BUSY) == (True, False, 0, False)
    assert rig.ref().v_STATUS.v_STOPPING and not rig.ref().v_STATUS.v_ERRORSTOP


@pytest.mark.parametrize("fb_class, inputs", [
    (fbs.MC_MoveAbsolute, dict(Position=40.0, Velocity=10.0, Acceleration=100.0, Deceleration=100.0,
                               BufferMode=0)),
    (fbs.MC_SyncMoveAbsolute, dict(Position=0.0, BufferMode=0))])
def test_a_running_command_called_with_an_unbound_axis_variable_ends_command_aborted(fb_class, inputs):
    # While Busy, the FB is called with an AXIS_REF that names no axis (Cfg.AxEnable FALSE, as a
    # local AXIS_REF): the command can no longer be followed, the FB ends with CommandAborted
    # (exactly one final output, Busy and Active FALSE) and does not fail on the missing axis.
    rig, _ = powered_rig()
    fb = make_fb(fb_class)
    rig.scan(lambda: rig.call(fb, Execute=True, **inputs))
    rig.scan(lambda: rig.call(fb, Execute=True, **inputs))
    assert fb.v_BUSY and not fb.v_COMMANDABORTED

    def call_unbound():
        fb.v_AXIS = make_axis_ref()
        fb.execute(rig.ctx)

    rig.scan(call_unbound)
    assert (fb.v_COMMANDABORTED, fb.v_BUSY, fb.v_ACTIVE, fb.v_ERROR) == (True, False, False, False)


# --- the motion task --------------------------------------------------------------------------------

def test_a_controller_without_a_motion_attribute_takes_a_motion_task():
    # install() gives the controller its `motion` attribute; one that has none yet (not only one
    # whose motion is None) takes the task.
    plc, _, _ = make_plc("PROGRAM Main\nEND_PROGRAM\n")
    task = plc.controller.motion
    controller = plc.controller
    del controller.motion
    controller.before_hooks.clear()
    controller.after_hooks.clear()
    second = MotionTask.from_tables([AXIS])
    second.install(controller)
    assert controller.motion is second and task is not second


def test_an_axis_table_that_is_not_a_table_is_named_axis_by_default():
    from st_runtime.motion.axis_config import AxisConfigError, axis_config_from_dict

    with pytest.raises(AxisConfigError, match=r"^axis: expected a table of axis settings, found int$"):
        axis_config_from_dict(5)


def test_dir_follows_the_sign_of_a_slow_command_velocity():
    # Dir.Posi / Dir.Nega show the sign of the command velocity, however small (a creep
    # below 1 mm/s included): the writer rewrites them whenever that sign changes.
    from st_runtime.motion.types import bind_axis_ref

    axis = powered()
    ref = make_axis_ref()
    writer = bind_axis_ref(ref, axis)
    assert (ref.v_DIR.v_POSI, ref.v_DIR.v_NEGA) == (False, False)
    for velocity, shown in ((0.5, (True, False)), (-0.5, (False, True)), (0.0, (False, False))):
        axis.cmd_vel = velocity
        writer.write()
        assert (ref.v_DIR.v_POSI, ref.v_DIR.v_NEGA) == shown, velocity
