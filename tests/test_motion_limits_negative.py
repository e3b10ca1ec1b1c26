"""Motion limit checks in the negative direction (issue 16).

The positive direction is covered in test_motion_axis.py; here each check is
driven with negative positions and velocities, values by hand next to each.
OMRON's behaviours (saturation at the maximum velocity with VelLimit, the
software limit errors 16#6440 / 16#6441, the sign of Cmd.AccDec) are cited in
docs/nj501.md ("OMRON's motion kernel") and SPEC section 7.
"""

import math

import pytest

from st_runtime.motion.axis import AxisState, MotionRefused
from st_runtime.motion.error_ids import ErrorID
from test_motion_axis import DT, powered_axis  # 1 ms; 100 mm/s, soft limits +-50
from test_motion_omron import SATURATING
from test_motion_st import AXIS, make_plc


def test_negative_step_at_velocity_limit_is_accepted_and_above_it_saturates():
    axis = powered_axis()  # 100 mm/s -> at most 0.1 mm per 1 ms scan
    command = axis.start_sync()
    command.target = -0.1
    axis.step(DT)
    assert axis.cmd_pos == -0.1 and not axis.vel_limit and axis.state == AxisState.DISCRETE
    command.target = -0.1 - 0.1001  # -100.1 mm/s
    axis.step(DT)
    assert axis.vel_limit and axis.state == AxisState.DISCRETE
    assert axis.cmd_pos == pytest.approx(-0.2) and axis.cmd_vel == pytest.approx(-100.0)
    axis.step(DT)  # the remaining -0.0001 mm
    assert axis.cmd_pos == pytest.approx(-0.2001) and not axis.vel_limit
    assert not command.aborted and axis.fault_code == ErrorID.NONE


def test_negative_far_target_moves_one_maximum_step_per_period():
    axis = powered_axis()
    command = axis.start_sync()
    command.target = -0.35
    positions = []
    for _ in range(4):
        axis.step(DT)
        positions.append((axis.cmd_pos, axis.vel_limit))
    # -0.1, -0.2, -0.3 saturated, then the last -0.05 fits one period.
    assert [p for p, _ in positions] == pytest.approx([-0.1, -0.2, -0.3, -0.35])
    assert [v for _, v in positions] == [True, True, True, False]


def test_command_beyond_negative_software_limit_faults():
    axis = powered_axis(soft_limit_min=-0.15, soft_limit_max=0.0)
    command = axis.start_sync()
    command.target = -0.1
    axis.step(DT)
    command.target = -0.15  # on the limit: allowed
    axis.step(DT)
    assert axis.state == AxisState.DISCRETE and axis.fault_code == ErrorID.NONE
    command.target = -0.1500001
    axis.step(DT)
    assert axis.state == AxisState.ERRORSTOP
    assert axis.fault_code == ErrorID.TARGET_NEGATIVE_SOFT_LIMIT == 0x6441
    assert axis.cmd_pos == -0.15


def test_far_target_beyond_negative_limit_faults_before_saturating():
    # The target is refused although one saturated step (-0.1) would stay inside.
    axis = powered_axis(soft_limit_min=-0.5)
    command = axis.start_sync()
    command.target = -0.6
    axis.step(DT)
    assert axis.fault_code == ErrorID.TARGET_NEGATIVE_SOFT_LIMIT
    assert axis.cmd_pos == 0.0 and not axis.vel_limit


def test_positive_limit_is_not_checked_against_a_negative_target():
    # A negative target inside [min, max] with max negative is fine; the
    # positive limit must not refuse it (a sign slip would).
    axis = powered_axis(soft_limit_min=-10.0, soft_limit_max=-1.0, initial_position=-2.0)
    command = axis.start_sync()
    command.target = -2.05
    axis.step(DT)
    assert axis.fault_code == ErrorID.NONE and axis.cmd_pos == -2.05


def test_negative_move_absolute_beyond_soft_limit_is_refused():
    axis = powered_axis()
    with pytest.raises(MotionRefused) as refused:
        axis.start_move_absolute(-50.0000001, 10.0, 0.0, 0.0)
    assert refused.value.code == ErrorID.TARGET_NEGATIVE_SOFT_LIMIT
    assert axis.state == AxisState.ERRORSTOP
    axis.reset()
    move = axis.start_move_absolute(-50.0, 100.0, 0.0, 0.0)  # on the limit: accepted
    assert axis.state == AxisState.DISCRETE and not move.done


def test_negative_move_absolute_holds_its_velocity_and_arrives():
    axis = powered_axis()
    move = axis.start_move_absolute(-0.05, 10.0, 0.0, 0.0)  # velocity step: 0.01 mm per scan
    positions = []
    while not move.done and len(positions) < 20:
        axis.step(DT)
        positions.append(axis.cmd_pos)
    assert positions == pytest.approx([-0.01, -0.02, -0.03, -0.04, -0.05], abs=1e-12)
    assert axis.state == AxisState.STANDSTILL


def test_negative_move_absolute_accelerates_then_decelerates():
    # From 0 to -0.3 mm at 100 mm/s, 100,000 mm/s^2: +-100 mm/s per 1 ms scan.
    # Speeds 100 (a step of 0.1), 100, then the last 0.1 (arrival): -0.1, -0.2, -0.3.
    axis = powered_axis()
    move = axis.start_move_absolute(-0.3, 100.0, 100_000.0, 100_000.0)
    speeds = []
    while not move.done and len(speeds) < 20:
        axis.step(DT)
        speeds.append(axis.cmd_vel)
    assert axis.cmd_pos == -0.3
    assert all(-100.0 - 1e-9 <= v <= 0.0 for v in speeds)
    assert speeds[0] == pytest.approx(-100.0)


def test_accdec_sign_follows_speed_magnitude_in_the_negative_direction():
    # OMRON's sign rule: Cmd.AccDec is + while |velocity| rises, - while it falls.
    axis = powered_axis()
    command = axis.start_sync()
    command.target = -0.05  # 0 -> -50 mm/s in 1 ms: |v| rises
    axis.step(DT)
    assert axis.cmd_vel == pytest.approx(-50.0)
    assert axis.cmd_accdec == pytest.approx(50_000.0)
    axis.step(DT)  # -50 -> 0 mm/s: |v| falls
    assert axis.cmd_accdec == pytest.approx(-50_000.0)


def test_stop_decelerates_a_negative_move():
    axis = powered_axis()
    move = axis.start_move_absolute(-10.0, 50.0, 0.0, 0.0)
    for _ in range(3):
        axis.step(DT)                 # -50 mm/s: -0.05, -0.10, -0.15
    stop = axis.start_stop(10000.0)   # 10 mm/s less per scan
    assert move.aborted
    positions = []
    for _ in range(5):
        axis.step(DT)
        positions.append(axis.cmd_pos)
    # Speeds -40, -30, -20, -10, 0 mm/s.
    assert positions == pytest.approx([-0.19, -0.22, -0.24, -0.25, -0.25], abs=1e-12)
    assert stop.done and axis.cmd_vel == 0.0


def test_error_deceleration_continues_in_the_negative_direction():
    # Moving at -100 mm/s (saturated), the next target is beyond -0.35: the
    # axis faults and its command decelerates at 20,000 mm/s^2 (20 mm/s less
    # per scan): speeds 80, 60, 40, 20, 0 -> steps -0.08, -0.06, -0.04, -0.02, 0.
    axis = powered_axis(soft_limit_min=-0.35, error_deceleration=20_000.0)
    command = axis.start_sync()
    command.target = -0.1
    axis.step(DT)
    command.target = -0.2
    axis.step(DT)
    command.target = -0.4
    positions = []
    for _ in range(6):
        axis.step(DT)
        positions.append(axis.cmd_pos)
    assert axis.fault_code == ErrorID.TARGET_NEGATIVE_SOFT_LIMIT
    assert positions == pytest.approx([-0.28, -0.34, -0.38, -0.40, -0.40, -0.40], abs=1e-12)


def test_following_error_counts_a_negative_lag():
    # A step of -0.05 through a 10 ms lag: the actual moves -0.05 (1 - e^-0.1)
    # = -0.00476, the error is 0.0452 > 0.03: 16#6448 as in the positive case.
    axis = powered_axis(servo_lag=0.01, following_error_limit=0.03)
    command = axis.start_sync()
    command.target = -0.05
    axis.step(DT)
    assert axis.fault_code == ErrorID.FOLLOWING_ERROR_EXCEEDED


SATURATING_NEGATIVE = SATURATING.replace("Goal : LREAL := 1.0;", "Goal : LREAL := -1.0;")
assert "-1.0" in SATURATING_NEGATIVE


def test_st_sync_to_a_negative_far_target_saturates_with_vellimit():
    # As test_motion_omron's positive case: commands -0.1 ... -1.0 in scans 2..11,
    # VelLimit TRUE in scans 2..10, no error.
    plc, main, _ = make_plc(SATURATING_NEGATIVE, AXIS)
    rows = []
    plc.controller.add_observer(lambda c: rows.append(
        (plc.globals["Cyl1.Cmd.Pos"], plc.globals["Cyl1.Details.VelLimit"], plc.globals["Cyl1.Cmd.Vel"])))
    plc.run(12)
    assert [r[0] for r in rows] == pytest.approx([0.0] + [-0.1 * k for k in range(1, 11)] + [-1.0])
    assert [r[1] for r in rows] == [False] + [True] * 9 + [False, False]
    assert rows[5][2] == pytest.approx(-100.0)
    assert plc.faults == [] and not main["Sync.Error"]


def test_actual_velocity_and_zero_accdec_at_constant_negative_speed():
    # Survivors of the motion mutation run: Act.Vel = (Act.Pos - previous) / period,
    # and Cmd.AccDec is 0 while the command velocity stays the same.
    axis = powered_axis()
    command = axis.start_sync()
    for n in (1, 2):
        command.target = -0.05 * n     # -50 mm/s both periods
        axis.step(DT)
    assert axis.act_vel == pytest.approx(-50.0)
    assert axis.cmd_vel == pytest.approx(-50.0)
    assert axis.cmd_accdec == 0.0
    lagged = powered_axis(servo_lag=0.01)   # act moves -0.05 (1 - e^-0.1) in 1 ms
    sync = lagged.start_sync()
    sync.target = -0.05
    lagged.step(DT)
    assert lagged.act_vel == pytest.approx(-0.05 * (1 - math.exp(-0.1)) / DT)
