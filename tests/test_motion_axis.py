"""The pure-Python axis simulation: PLCopen states, limits, servo lag.

Expected values come from hand calculation (stated next to each)."""

import math

import pytest

from st_runtime.motion.axis import Axis, AxisState, MotionAborted, MotionRefused
from st_runtime.motion.axis_config import AxisConfig
from st_runtime.motion.error_ids import ErrorID

DT = 0.001  # 1 ms primary period


def powered_axis(**overrides) -> Axis:
    settings = dict(name="Ax", max_velocity=100.0, soft_limit_min=-50.0, soft_limit_max=50.0)
    settings.update(overrides)
    axis = Axis(AxisConfig(**settings))
    axis.request_power(True)
    axis.step(DT)
    assert axis.state == AxisState.STANDSTILL
    return axis


def test_power_on_and_off_take_effect_at_motion_processing():
    axis = Axis(AxisConfig(name="Ax", max_velocity=10.0, initial_position=3.0))
    assert axis.state == AxisState.DISABLED
    axis.request_power(True)
    assert axis.state == AxisState.DISABLED  # not before the motion processing
    axis.step(DT)
    assert axis.state == AxisState.STANDSTILL and axis.powered
    assert axis.cmd_pos == axis.act_pos == 3.0
    command = axis.start_sync()
    axis.request_power(False)
    axis.step(DT)
    assert axis.state == AxisState.DISABLED
    assert command.aborted


@pytest.mark.parametrize("start", ["sync", "move", "stop", "home"])
def test_motion_on_disabled_axis_is_refused(start):
    axis = Axis(AxisConfig(name="Ax", max_velocity=10.0))
    starters = {
        "sync": axis.start_sync,
        "move": lambda: axis.start_move_absolute(1.0, 1.0, 0.0, 0.0),
        "stop": lambda: axis.start_stop(0.0),
        "home": axis.start_home,
    }
    with pytest.raises(MotionRefused) as refused:
        starters[start]()
    assert refused.value.code == ErrorID.AXIS_DISABLED
    assert axis.state == AxisState.DISABLED


def test_sync_position_is_the_command_of_the_same_period():
    axis = powered_axis()
    command = axis.start_sync()
    assert axis.state == AxisState.DISCRETE  # changed in issue 8: not SYNCHRONIZED (OMRON, docs/nj501.md)
    command.target = 0.05
    axis.step(DT)
    assert axis.cmd_pos == 0.05 and axis.act_pos == 0.05  # ideal axis
    assert axis.cmd_vel == pytest.approx(50.0)  # 0.05 mm in 1 ms


def test_a_streamed_sync_on_an_ideal_axis_follows_the_hand_formulas_bit_for_bit():
    # Each period: Cmd.Pos = Act.Pos = the target p_k; Cmd.Vel = (p_k - p_k-1) / dt;
    # Act.Vel likewise; Cmd.AccDec = |v_k - v_k-1| / dt, + while |v| grows, - while it
    # falls, 0 when v holds (W507 p.6-28).  Exact: the same operations give the same bits.
    axis = powered_axis()
    command = axis.start_sync()
    previous_pos, previous_vel = 0.0, 0.0
    for target in (0.01, 0.03, 0.05, 0.07, 0.06, 0.06, -0.02, -0.1, -0.15, -0.15):
        command.target = target
        axis.step(DT)
        vel = (target - previous_pos) / DT
        magnitude = abs(vel - previous_vel) / DT
        accdec = 0.0 if vel == previous_vel else (magnitude if abs(vel) > abs(previous_vel) else -magnitude)
        assert (axis.cmd_pos, axis.act_pos, axis.cmd_vel, axis.act_vel) == (target, target, vel, vel)
        assert axis.cmd_accdec == accdec and not axis.vel_limit
        assert axis.state == AxisState.DISCRETE and axis.fault_code == ErrorID.NONE
        previous_pos, previous_vel = target, vel


def test_step_at_velocity_limit_is_accepted_and_above_it_saturates():
    # Changed in issue 8: a step above the limit faulted the axis (invented
    # 16#6402); OMRON saturates at the maximum velocity and outputs the rest
    # in later periods, Details.VelLimit TRUE meanwhile (docs/nj501.md, W507 9-2).
    axis = powered_axis()  # 100 mm/s -> at most 0.1 mm per 1 ms scan
    command = axis.start_sync()
    command.target = 0.1
    axis.step(DT)
    assert axis.state == AxisState.DISCRETE and not axis.vel_limit
    command.target = 0.1 + 0.1001  # 100.1 mm/s
    axis.step(DT)
    assert axis.state == AxisState.DISCRETE and axis.vel_limit
    assert axis.cmd_pos == pytest.approx(0.2) and axis.cmd_vel == pytest.approx(100.0)
    axis.step(DT)  # the remaining 0.0001 mm
    assert axis.cmd_pos == pytest.approx(0.2001) and not axis.vel_limit
    assert not command.aborted


def test_command_beyond_software_limit_faults():
    axis = powered_axis(soft_limit_min=0.0, soft_limit_max=0.15)
    command = axis.start_sync()
    command.target = 0.1
    axis.step(DT)
    command.target = 0.15  # on the limit: allowed
    axis.step(DT)
    assert axis.state == AxisState.DISCRETE
    command.target = 0.1500001
    axis.step(DT)
    assert axis.state == AxisState.ERRORSTOP
    assert axis.fault_code == ErrorID.TARGET_POSITIVE_SOFT_LIMIT  # assumed code, see error_ids
    assert axis.cmd_pos == 0.15


def test_non_finite_command_faults():
    axis = powered_axis()
    command = axis.start_sync()
    command.target = math.nan
    axis.step(DT)
    assert axis.fault_code == ErrorID.COMMAND_NOT_FINITE
    assert axis.cmd_pos == 0.0


def test_sync_ignores_the_maximum_acceleration():
    # Changed in issue 8: this test faulted the axis when the sync velocity
    # changed faster than max_acceleration (invented 16#6403); OMRON does not
    # use the maximum acceleration/deceleration for MC_SyncMoveAbsolute.
    axis = powered_axis(max_acceleration=1000.0)  # at most 1 mm/s per 1 ms scan
    command = axis.start_sync()
    command.target = 0.05  # 0 -> 50 mm/s in one scan: 50,000 mm/s^2
    axis.step(DT)
    assert axis.state == AxisState.DISCRETE and axis.cmd_pos == 0.05
    assert axis.cmd_accdec == pytest.approx(50_000.0)
    command.target = 0.05  # 50 -> 0 mm/s: OMRON's sign rule, - while |v| falls
    axis.step(DT)
    assert axis.cmd_accdec == pytest.approx(-50_000.0)


def test_servo_lag_is_the_exact_first_order_response():
    tau = 0.01
    axis = powered_axis(servo_lag=tau)
    command = axis.start_sync()
    command.target = 0.1
    for _ in range(10):
        axis.step(DT)
    # A held step of 0.1 after t = 10 ms: 0.1 * (1 - e^(-t/tau)) = 0.1 * (1 - e^-1).
    assert axis.act_pos == pytest.approx(0.1 * (1 - math.exp(-1.0)), abs=1e-12)
    assert axis.cmd_pos == 0.1


def test_following_error_above_limit_faults_when_the_hand_formula_says():
    tau, step, limit = 0.01, 0.05, 0.3
    gain = 1 - math.exp(-DT / tau)
    # Ramp of `step` per scan through a first-order lag: e_n = (e_(n-1) + step)(1 - gain),
    # so e_n = step (1 - gain)(1 - (1 - gain)^n) / gain; it tends to 0.475 mm.
    expected_scan = next(
        n for n in range(1, 1000) if step * (1 - gain) * (1 - (1 - gain) ** n) / gain > limit
    )
    axis = powered_axis(servo_lag=tau, following_error_limit=limit)
    command = axis.start_sync()
    for n in range(1, expected_scan + 1):
        assert axis.state == AxisState.DISCRETE, n
        command.target = step * n
        axis.step(DT)
    assert axis.state == AxisState.ERRORSTOP
    assert axis.fault_code == ErrorID.FOLLOWING_ERROR_EXCEEDED
    assert abs(axis.following_error) > limit


def test_reset_returns_to_standstill_when_powered_and_disabled_when_not():
    axis = powered_axis()
    command = axis.start_sync()
    command.target = 60.0  # beyond +50
    axis.step(DT)
    assert axis.state == AxisState.ERRORSTOP
    with pytest.raises(MotionAborted):  # CommandAborted, not an error (issue 8, docs/nj501.md)
        axis.start_sync()
    assert axis.reset()
    assert axis.state == AxisState.STANDSTILL and axis.fault_code == ErrorID.NONE

    command = axis.start_sync()
    command.target = 60.0
    axis.step(DT)
    axis.request_power(False)
    axis.step(DT)
    assert axis.state == AxisState.ERRORSTOP  # power off does not clear an error
    assert axis.reset()
    assert axis.state == AxisState.DISABLED


def test_reset_fails_while_the_following_error_is_still_too_large():
    axis = powered_axis(servo_lag=0.01, following_error_limit=0.03)
    command = axis.start_sync()
    command.target = 0.05  # act moves 0.05 * (1 - e^-0.1) = 0.00476: error 0.0452 > 0.03
    axis.step(DT)
    assert axis.fault_code == ErrorID.FOLLOWING_ERROR_EXCEEDED
    assert not axis.reset()
    assert axis.state == AxisState.ERRORSTOP
    for _ in range(5):  # error 0.0452 e^(-0.1 n) < 0.03 from n = 5 on
        axis.step(DT)
    assert axis.reset()
    assert axis.state == AxisState.STANDSTILL


def test_stop_aborts_synchronized_motion_at_once():
    # Changed in issue 8: the stop decelerated at its 10,000 mm/s^2; OMRON's
    # MC_Stop on an axis under MC_SyncMoveAbsolute is an immediate stop, the
    # deceleration ignored (docs/nj501.md).  A start while Stopping: CommandAborted.
    axis = powered_axis()
    sync = axis.start_sync()
    for n in range(1, 4):
        sync.target = 0.05 * n  # 50 mm/s
        axis.step(DT)
    stop = axis.start_stop(10000.0)
    assert sync.aborted and axis.state == AxisState.STOPPING
    axis.step(DT)
    assert axis.cmd_pos == pytest.approx(0.15) and axis.cmd_vel == 0.0 and stop.done
    assert axis.state == AxisState.STOPPING  # held while MC_Stop's Execute is TRUE
    with pytest.raises(MotionAborted):
        axis.start_sync()
    axis.release_stop(stop)
    assert axis.state == AxisState.STANDSTILL


def test_stop_decelerates_a_move_and_deceleration_zero_stops_at_once():
    axis = powered_axis()
    move = axis.start_move_absolute(10.0, 50.0, 0.0, 0.0)  # no max_acceleration: a velocity step
    for _ in range(3):
        axis.step(DT)                 # 50 mm/s: 0.05, 0.10, 0.15
    stop = axis.start_stop(10000.0)   # 10 mm/s less per 1 ms scan
    assert move.aborted
    positions = []
    for _ in range(5):
        axis.step(DT)
        positions.append(axis.cmd_pos)
    # Speeds 40, 30, 20, 10, 0 mm/s: +0.04, +0.03, +0.02, +0.01, +0.
    assert positions == pytest.approx([0.19, 0.22, 0.24, 0.25, 0.25], abs=1e-12)
    assert stop.done
    axis.release_stop(stop)
    axis.start_move_absolute(10.0, 50.0, 0.0, 0.0)
    axis.step(DT)                     # 0.30 at 50 mm/s
    axis.start_stop(0.0)              # Deceleration 0: immediate stop (docs/nj501.md)
    axis.step(DT)
    assert axis.cmd_pos == pytest.approx(0.30) and axis.cmd_vel == 0.0


def test_stop_released_early_ends_in_standstill_when_stopped():
    # Changed in issue 8: started from a move, not from a sync (a stop from a
    # sync is immediate on the NJ, so nothing would be left to release early).
    axis = powered_axis()
    axis.start_move_absolute(10.0, 20.0, 0.0, 0.0)
    axis.step(DT)  # 20 mm/s
    stop = axis.start_stop(10000.0)
    axis.release_stop(stop)
    axis.step(DT)
    assert axis.state == AxisState.STOPPING  # 10 mm/s
    axis.step(DT)
    assert axis.state == AxisState.STANDSTILL and stop.done


def test_move_absolute_trapezoid():
    axis = powered_axis()
    move = axis.start_move_absolute(10.0, 10.0, 100.0, 100.0)
    assert axis.state == AxisState.DISCRETE
    speeds = []
    scans = 0
    while not move.done and scans < 5000:
        axis.step(DT)
        speeds.append(axis.cmd_vel)
        scans += 1
    # Trapezoid: T = d/v + v/a = 10/10 + 10/100 = 1.1 s -> 1100 scans (+- rounding).
    assert 1098 <= scans <= 1103
    assert axis.cmd_pos == 10.0 and axis.state == AxisState.STANDSTILL
    assert max(speeds) == pytest.approx(10.0)
    assert min(speeds) >= 0.0
    # Acceleration phase: +0.1 mm/s per scan (100 mm/s^2 * 1 ms).
    assert speeds[:3] == pytest.approx([0.1, 0.2, 0.3])


def test_move_absolute_waits_for_in_position_with_servo_lag():
    axis = powered_axis(servo_lag=0.005, in_position_range=0.001)
    move = axis.start_move_absolute(1.0, 100.0, 0.0, 0.0)  # no acc limit: 0.1 mm per scan
    for _ in range(10):
        axis.step(DT)
    assert axis.cmd_pos == 1.0 and not move.done  # command there, actual not yet
    for _ in range(100):
        axis.step(DT)
        if move.done:
            break
    assert move.done and abs(axis.act_pos - 1.0) <= 0.001


def test_move_absolute_beyond_soft_limit_faults_the_axis():
    axis = powered_axis()
    with pytest.raises(MotionRefused) as refused:
        axis.start_move_absolute(50.5, 10.0, 0.0, 0.0)
    assert refused.value.code == ErrorID.TARGET_POSITIVE_SOFT_LIMIT == 0x6440
    assert axis.state == AxisState.ERRORSTOP
    assert axis.fault_code == ErrorID.TARGET_POSITIVE_SOFT_LIMIT
    axis.reset()
    with pytest.raises(MotionRefused) as refused:
        axis.start_move_absolute(-50.5, 10.0, 0.0, 0.0)
    assert refused.value.code == ErrorID.TARGET_NEGATIVE_SOFT_LIMIT == 0x6441


@pytest.mark.parametrize("velocity, acc", [(0.0, 1.0), (-1.0, 1.0), (100.5, 1.0), (1.0, -1.0), (math.inf, 1.0)])
def test_move_absolute_parameter_out_of_range(velocity, acc):
    axis = powered_axis()
    with pytest.raises(MotionRefused) as refused:
        axis.start_move_absolute(1.0, velocity, acc, 0.0)
    assert refused.value.code == ErrorID.PARAMETER_OUT_OF_RANGE
    assert axis.state == AxisState.STANDSTILL


def test_new_move_aborts_the_previous_one():
    axis = powered_axis()
    first = axis.start_move_absolute(10.0, 10.0, 0.0, 0.0)
    axis.step(DT)
    second = axis.start_move_absolute(-1.0, 10.0, 0.0, 0.0)
    assert first.aborted and not second.aborted


def test_home_sets_homed_without_moving():
    axis = powered_axis(initial_position=7.5)
    assert not axis.homed
    home = axis.start_home()
    assert axis.state == AxisState.HOMING
    axis.step(DT)
    assert home.done and axis.homed
    assert axis.state == AxisState.STANDSTILL and axis.cmd_pos == 7.5


def test_home_needs_standstill():
    axis = powered_axis()
    axis.start_sync()
    with pytest.raises(MotionRefused) as refused:
        axis.start_home()
    assert refused.value.code == ErrorID.AXIS_MOVING


def test_move_absolute_never_brakes_harder_than_its_deceleration():
    axis = powered_axis()
    move = axis.start_move_absolute(-7.3, 12.0, 200.0, 50.0)
    speeds = [0.0]
    while not move.done:
        axis.step(DT)
        speeds.append(axis.cmd_vel)
    changes = [b - a for a, b in zip(speeds, speeds[1:])]
    # Accelerating (towards -): at most 200 mm/s^2 * 1 ms; braking at most 50 * 1 ms,
    # except the arrival scan, which takes up the remainder (less than one more step).
    for change in changes[:-1]:
        assert -0.2 * (1 + 1e-9) <= change <= 0.05 * (1 + 1e-9)
    assert 0 <= changes[-1] < 2 * 0.05
    assert axis.cmd_pos == -7.3
