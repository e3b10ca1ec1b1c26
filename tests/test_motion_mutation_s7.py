"""Motion behaviour that the seed-21 mutation sample found unchecked (issue 16, docs/mutation.md).

Expected values are worked out by hand from the rules in st_runtime/motion (OMRON's sign rule
for Cmd.AccDec, W507 p.6-28; Dir.Posi/Nega follow the sign of Cmd.Vel), not read from a run.
"""

from __future__ import annotations

import copy
from types import SimpleNamespace

import pytest

from motion_rig import Rig, make_fb
from test_motion_fbs import axis_config, powered_rig
from test_motion_mutants import powered
from st_runtime.motion import fbs
from st_runtime.motion.axis import Axis, AxisState
from st_runtime.motion.axis_config import AxisConfig
from st_runtime.motion.error_ids import ErrorID

DT = 0.001


# --- the axis, driven directly ---------------------------------------------------------------------

def test_a_first_period_of_one_second_sets_the_step_limits():
    # The period's limits are set by the first step whatever its length: at 100 mm/s a 1 s period
    # reaches 100 mm, so a sync Position 50 mm away is taken at once (not saturated).
    axis = Axis(AxisConfig(name="Ax", max_velocity=100.0))
    axis.request_power(True)
    axis.step(1.0)
    command = axis.start_sync()
    command.target = 50.0
    axis.step(1.0)
    assert (axis.cmd_pos, axis.vel_limit) == (50.0, False)
    assert axis.cmd_vel == 50.0                                   # 50 mm in 1 s


def test_a_following_error_limit_of_zero_does_not_hold_back_a_reset():
    # following_error_limit 0 disables the check (axis_config.py), MC_Reset's rule included:
    # an axis with a lagging servo resets although Act.Pos is still behind Cmd.Pos.
    axis = powered(servo_lag=0.01)
    command = axis.start_sync()
    command.target = 0.05
    axis.step(DT)
    axis.fault(ErrorID.FOLLOWING_ERROR_EXCEEDED)
    assert axis.following_error > 0 and axis.cmd_vel == 0.0
    assert axis.reset() is True
    assert axis.state == AxisState.STANDSTILL and axis.fault_code == ErrorID.NONE


def test_cmd_accdec_of_a_trapezoid_and_of_a_stop():
    # Acceleration 1000 mm/s^2 at 1 ms: 1, 2 mm/s after two steps, AccDec +1000 (|v| grows).
    axis = powered()
    axis.start_move_absolute(100.0, 50.0, 1000.0, 1000.0)
    axis.step(DT)
    axis.step(DT)
    assert axis.cmd_vel == pytest.approx(2.0, rel=1e-9)
    assert axis.cmd_accdec == pytest.approx(1000.0, rel=1e-6)
    # At 10 mm/s (acceleration 0: the axis maximum, none configured: a step), MC_Stop at
    # 1000 mm/s^2 takes 1 mm/s off each period: 9 mm/s, AccDec -1000 (|v| falls).
    axis = powered()
    axis.start_move_absolute(100.0, 10.0, 0.0, 0.0)
    axis.step(DT)
    axis.step(DT)
    assert axis.cmd_vel == pytest.approx(10.0, rel=1e-9) and axis.cmd_accdec == 0.0
    axis.start_stop(1000.0)
    axis.step(DT)
    assert axis.cmd_vel == pytest.approx(9.0, rel=1e-9)
    assert axis.cmd_accdec == pytest.approx(-1000.0, rel=1e-6)


@pytest.mark.parametrize("deceleration", [-1.0, float("nan"), float("inf")])
def test_mc_stop_with_a_bad_deceleration_is_parameter_out_of_range(deceleration):
    rig, _ = powered_rig()
    stop = make_fb(fbs.MC_Stop)
    rig.scan(lambda: rig.call(stop, Execute=True, Deceleration=deceleration))
    assert (stop.v_ERROR, stop.v_ERRORID, stop.v_BUSY) == (True, 0x5410, False)
    assert rig.ref().v_STATUS.v_STANDSTILL                      # an instruction error: the axis goes on


# --- the FBs on the bench --------------------------------------------------------------------------

def test_an_fb_without_an_axis_or_without_a_motion_task_is_not_assigned():
    # resolve_axis: no AXIS_REF given (a bench FB's in-out is None), or a context whose
    # controller has no motion task: Error with 16#5401, no exception.
    rig = Rig(axis_config())
    power = make_fb(fbs.MC_Power)
    power.v_ENABLE = True
    power.execute(rig.ctx)                                     # v_AXIS never given
    assert (power.v_ERROR, power.v_ERRORID, power.v_STATUS) == (True, 0x5401, False)
    home = make_fb(fbs.MC_Home)
    home.v_AXIS, home.v_EXECUTE = rig.ref(), True              # bound to axis 0 ...
    home.execute(SimpleNamespace(controller=SimpleNamespace()))   # ... of no motion task here
    assert (home.v_ERROR, home.v_ERRORID, home.v_BUSY) == (True, 0x5401, False)
    assert fbs.resolve_axis(None, rig.ctx) is None
    assert fbs.resolve_axis(rig.ref(), rig.ctx) is rig.task.axes[0]


def test_a_sync_goes_on_when_called_with_a_copy_of_its_axis_variable():
    # A copy of the AXIS_REF value (the same Cfg.AxNo, AxEnable TRUE) names the same axis:
    # the synchronized motion takes the new Position from it as from the variable itself.
    rig, _ = powered_rig()
    sync = make_fb(fbs.MC_SyncMoveAbsolute)
    rig.scan(lambda: rig.call(sync, Execute=True, Position=0.01, BufferMode=0))
    twin = copy.deepcopy(rig.ref())

    def call_with_twin():
        sync.v_AXIS, sync.v_POSITION = twin, 0.02
        sync.execute(rig.ctx)

    rig.scan(call_with_twin)
    assert (sync.v_BUSY, sync.v_ACTIVE, sync.v_ERROR, sync.v_COMMANDABORTED) == (True, True, False, False)
    assert rig.task.axes[0].cmd_pos == 0.02


def test_dir_nega_when_a_held_sync_starts_down():
    # Synchronized and holding (Cmd.Vel 0, neither direction), then Position 0.01 mm lower:
    # Cmd.Vel -10 mm/s, Dir.Nega TRUE, nothing else about the axis having changed.
    rig, _ = powered_rig()
    sync = make_fb(fbs.MC_SyncMoveAbsolute)
    for _ in range(2):
        rig.scan(lambda: rig.call(sync, Execute=True, Position=0.0, BufferMode=0))
    ref = rig.ref()
    assert ref.v_STATUS.v_DISCRETE and ref.v_CMD.v_VEL == 0.0
    assert (ref.v_DIR.v_POSI, ref.v_DIR.v_NEGA) == (False, False)
    rig.scan(lambda: rig.call(sync, Execute=True, Position=-0.01, BufferMode=0))
    assert ref.v_CMD.v_VEL == pytest.approx(-10.0)
    assert (ref.v_DIR.v_POSI, ref.v_DIR.v_NEGA) == (False, True)


def test_dir_posi_at_a_slow_speed():
    # 0.0005 mm a period is 0.5 mm/s: positive, however slow.
    rig, _ = powered_rig()
    sync = make_fb(fbs.MC_SyncMoveAbsolute)
    for scan in range(1, 4):
        rig.scan(lambda: rig.call(sync, Execute=True, Position=0.0005 * scan, BufferMode=0))
    ref = rig.ref()
    assert ref.v_CMD.v_VEL == pytest.approx(0.5)
    assert (ref.v_DIR.v_POSI, ref.v_DIR.v_NEGA) == (True, False)
