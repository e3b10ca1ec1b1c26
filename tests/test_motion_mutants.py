"""Motion details that mutation testing found unchecked (issue 16).

Messages are asserted word for word (a clear error is part of the
behaviour); the ErrorID texts are the docstrings of st_runtime/motion/error_ids.py,
read afresh by `_member_docs` (the table is built at import time).
"""

from __future__ import annotations

import math

import pytest

from st_runtime.motion import error_ids
from st_runtime.motion.axis_config import AxisConfigError, axis_config_from_dict
from st_runtime.motion.error_ids import ErrorID


# --- ErrorID descriptions --------------------------------------------------------------------

def test_every_error_id_has_its_docstring_on_one_line():
    docs = error_ids._member_docs()
    assert set(docs) == set(ErrorID)
    assert docs[ErrorID.NONE] == "No error."
    assert docs[ErrorID.AXIS_DISABLED] == ("Simulator's own: a motion FB was started on an axis whose "
                                           "servo is off (Disabled).")
    assert docs[ErrorID.FOLLOWING_ERROR_EXCEEDED] == (
        "OMRON [W503 p.3-527] (Following Error Limit Exceeded): |command position - actual position| "
        "exceeds the following-error limit.")


def test_describe_names_code_member_and_text():
    assert error_ids.describe(0x5402) == ("16#5402 AXIS_DISABLED: Simulator's own: a motion FB was started "
                                          "on an axis whose servo is off (Disabled).")
    assert error_ids.describe(0x0) == "16#0000 NONE: No error."
    assert error_ids.describe(0x9999) == "16#9999: unknown ErrorID"


# --- axis configuration rules --------------------------------------------------------------------

def config(**keys):
    return axis_config_from_dict({"name": "X", "max_velocity": 100.0, **keys}, where="axis 1")


def rejects(**keys):
    with pytest.raises(AxisConfigError) as err:
        config(**keys)
    return str(err.value)


@pytest.mark.parametrize("value", [0.0, -1.0, math.inf])
def test_max_velocity_must_be_positive_and_finite(value):
    assert rejects(max_velocity=value) == f"axis 'X': key 'max_velocity' must be a positive finite number, found {value!r}"


@pytest.mark.parametrize("key", ["max_acceleration", "following_error_limit", "following_error_warning",
                                 "error_deceleration", "in_position_check_time", "servo_lag"])
def test_optional_limits_are_finite_and_not_negative(key):
    assert getattr(config(**{key: 0.0}), key) == 0.0          # 0 disables it
    for value in (-1.0, math.inf):
        assert rejects(**{key: value}) == f"axis 'X': key {key!r} must be finite and >= 0 (0 disables it), found {value!r}"


def test_following_error_warning_up_to_the_limit():
    assert config(following_error_limit=2.0, following_error_warning=2.0).following_error_warning == 2.0
    assert config(following_error_limit=0.0, following_error_warning=5.0).following_error_warning == 5.0
    assert rejects(following_error_limit=1.0, following_error_warning=2.0) == (
        "axis 'X': key 'following_error_warning' must not exceed 'following_error_limit', found 2.0 > 1.0")


@pytest.mark.parametrize("value", [0.0, math.inf])
def test_in_position_range_must_be_positive_and_finite(value):
    assert rejects(in_position_range=value) == (
        f"axis 'X': key 'in_position_range' must be a positive finite number, found {value!r}")


def test_soft_limits_and_initial_position():
    assert rejects(soft_limit_min=5.0, soft_limit_max=5.0) == (
        "axis 'X': key 'soft_limit_min' must be below 'soft_limit_max', found 5.0 >= 5.0")
    assert rejects(initial_position=math.inf) == "axis 'X': key 'initial_position' must be finite, found inf"
    assert rejects(soft_limit_min=0.0, soft_limit_max=5.0, initial_position=10.0) == (
        "axis 'X': key 'initial_position' must lie within the software limits [0.0, 5.0], found 10.0")
    assert config(soft_limit_min=0.0, soft_limit_max=5.0, initial_position=5.0).initial_position == 5.0
    assert config(soft_limit_min=0.0, soft_limit_max=5.0, initial_position=0.0).initial_position == 0.0


# --- a new axis ---------------------------------------------------------------------------------------

def test_a_new_axis_is_disabled_at_rest_at_its_initial_position():
    from st_runtime.motion.axis import Axis, AxisState

    axis = Axis(config(initial_position=12.5), axis_no=3)
    assert axis.axis_no == 3 and axis.state == AxisState.DISABLED
    assert (axis.power_requested, axis.powered, axis.homed) == (False, False, False)
    assert all(flag is False for flag in (axis.power_requested, axis.powered, axis.homed,
                                          axis.vel_limit, axis.in_pos_waiting))
    assert (axis.cmd_pos, axis.act_pos) == (12.5, 12.5)
    assert (axis.cmd_vel, axis.cmd_accdec, axis.act_vel) == (0.0, 0.0, 0.0)
    assert axis.fault_code is ErrorID.NONE and axis.observation_code is ErrorID.NONE
    assert axis.command is None


def test_motion_fb_declaration_takes_the_axis_by_reference_first():
    from st_runtime.motion import fbs

    assert fbs._axis_fb_declaration("MC_X", "Execute : BOOL;", "Done : BOOL;") == (
        "\nFUNCTION_BLOCK MC_X\n"
        "VAR_IN_OUT\n    Axis : AXIS_REF;\nEND_VAR\n"
        "VAR_INPUT\n    Execute : BOOL;\nEND_VAR\n"
        "VAR_OUTPUT\n    Done : BOOL;\nEND_VAR\n"
        "END_FUNCTION_BLOCK\n")


# --- the axis, driven directly (1 ms periods) ----------------------------------------------------------

DT = 0.001


def powered(**keys):
    from st_runtime.motion.axis import Axis

    axis = Axis(config(**keys))
    axis.request_power(True)
    axis.step(DT)
    assert axis.powered
    return axis


def test_reset_of_a_healthy_axis_succeeds_and_clears_the_observation():
    axis = powered()
    axis.observation_code = ErrorID.FOLLOWING_ERROR_WARNING
    assert axis.reset() is True
    assert axis.observation_code == ErrorID.NONE


def test_a_fault_without_error_deceleration_stops_the_command_at_once():
    axis = powered()
    command = axis.start_sync()
    command.target = 0.05
    axis.step(DT)
    assert axis.cmd_vel == pytest.approx(50.0)               # 0.05 mm in 1 ms
    axis.fault(ErrorID.FOLLOWING_ERROR_EXCEEDED)
    assert axis.cmd_vel == 0.0 and axis.reset() is True      # nothing left to decelerate


def test_sync_starts_where_the_command_is_and_moves_accept_slow_velocities():
    axis = powered(initial_position=12.5)
    assert axis.start_sync().target == 12.5
    assert axis.start_move_absolute(13.0, 0.5, 0.0, 0.0).velocity == 0.5    # 0 < 0.5 mm/s <= 100


def test_an_ideal_axis_is_exactly_at_its_command():
    # No servo lag: Act.Pos = Cmd.Pos, bit for bit (0.07 + (0.01 - 0.07) would be 0.010000000000000002).
    axis = powered()
    command = axis.start_sync()
    for target in (0.07, 0.01):
        command.target = target
        axis.step(DT)
        assert axis.act_pos == axis.cmd_pos == target
        assert axis.vel_limit is False                        # within one period's reach


def test_the_command_holds_after_a_move_even_with_an_error_deceleration():
    from st_runtime.motion.axis import AxisState

    axis = powered(error_deceleration=1000.0)
    axis.start_move_absolute(1.0, 100.0, 1e5, 1e5)
    for _ in range(100):
        axis.step(DT)
    assert axis.state == AxisState.STANDSTILL and axis.command is None
    assert (axis.cmd_pos, axis.cmd_vel) == (1.0, 0.0)


def test_in_position_waiting_ends_when_the_lagging_axis_arrives():
    from st_runtime.motion.axis import AxisState

    axis = powered(servo_lag=0.005, in_position_range=0.001)
    axis.start_move_absolute(1.0, 100.0, 1e5, 1e5)
    waited = False
    for _ in range(200):
        axis.step(DT)
        waited = waited or axis.in_pos_waiting
    assert waited                                              # the lag made it wait
    assert axis.state == AxisState.STANDSTILL and axis.in_pos_waiting is False


# --- configuration messages -----------------------------------------------------------------------------

def test_axis_names_that_are_keywords_in_any_case_are_refused():
    for name in ("if", "IF", "Repeat"):
        with pytest.raises(AxisConfigError) as err:
            axis_config_from_dict({"name": name, "max_velocity": 1.0}, where="axis 1")
        assert str(err.value) == (f"axis 1: key 'name' must not be an ST keyword, found {name!r} "
                                  "(the axis becomes a global variable of that name)")


def test_unknown_keys_and_non_numbers_name_the_axis():
    with pytest.raises(AxisConfigError) as err:
        axis_config_from_dict({"name": "X", "max_velocity": 1.0, "speed": 2}, where="axis 1")
    assert str(err.value) == (
        "axis 1: unknown key 'speed' (known keys: name, max_velocity, soft_limit_min, soft_limit_max, "
        "max_acceleration, in_position_range, in_position_check_time, following_error_limit, "
        "following_error_warning, error_deceleration, servo_lag, initial_position)")
    assert rejects(max_velocity="fast") == "axis 'X': key 'max_velocity' must be a number, found 'fast'"


# --- the motion task ------------------------------------------------------------------------------------

def test_motion_task_refuses_duplicate_names_a_second_task_and_undeclared_axes():
    from types import SimpleNamespace

    from st_runtime.motion import MotionTask

    with pytest.raises(ValueError) as err:
        MotionTask([config(), axis_config_from_dict({"name": "x", "max_velocity": 1.0})])
    assert str(err.value) == "axis names must be unique (case-insensitive)"
    task = MotionTask([config()])
    with pytest.raises(ValueError) as err:
        task.install(SimpleNamespace(motion=object(), globals=object()))
    assert str(err.value) == "this controller already has a motion task"
    with pytest.raises(ValueError) as err:
        task.install(SimpleNamespace(motion=None, globals=object()))     # no ST globals at all
    assert str(err.value) == ("axis X: the global variable X is not declared; load "
                              "MotionTask.globals_source() with the program to declare it as AXIS_REF")


# --- what the ST program sees (OMRON's _sAXIS_REF members) ------------------------------------------------

DIR_PROGRAM = """
PROGRAM Main
VAR
    Local : AXIS_REF;
    Off : MC_Power;
    Power : MC_Power;
    Home : MC_Home;
    Sync : MC_SyncMoveAbsolute;
    Scan : INT;
    Target : LREAL;
END_VAR
Scan := Scan + 1;
Off(Axis := Local, Enable := FALSE);          (* unassigned, not enabled: no error *)
IF Scan = 1 THEN
    Power(Axis := Local, Enable := TRUE);      (* not a configured axis: 16#5401 *)
ELSE
    Power(Axis := Cyl1, Enable := TRUE);
END_IF;
Home(Axis := Cyl1, Execute := Power.Status);
IF Scan > 6 THEN
    Target := Target - 0.01;
    Sync(Axis := Cyl1, Execute := TRUE, Position := Target, BufferMode := _mcAborting);
END_IF;
END_PROGRAM
"""


def test_direction_flags_and_power_error_id_seen_from_st():
    from test_motion_st import AXIS, make_plc

    plc, main, _ = make_plc(DIR_PROGRAM, AXIS)
    plc.run(1)
    assert main["Power.Error"] and main["Power.ErrorID"] == 0x5401
    assert main["Off.Error"] is False and main["Off.ErrorID"] == 0
    assert main["Off.Status"] is False and main["Off.Busy"] is False
    plc.run(5)
    # Homed, at rest: neither direction (Dir.Posi/Nega follow the sign of Cmd.Vel).
    assert plc.globals["Cyl1.Details.Homed"] is True and plc.globals["Cyl1.Cmd.Vel"] == 0.0
    assert plc.globals["Cyl1.Dir.Posi"] is False and plc.globals["Cyl1.Dir.Nega"] is False
    assert main["Power.Error"] is False and main["Power.ErrorID"] == 0
    plc.run(3)
    # Synchronized to a falling target: moving in the negative direction.
    assert plc.globals["Cyl1.Cmd.Vel"] < 0
    assert plc.globals["Cyl1.Dir.Nega"] is True and plc.globals["Cyl1.Dir.Posi"] is False


def test_reset_allowed_with_a_following_error_at_its_limit():
    # MC_Reset fails while the following error is above the limit (the simulator's own rule):
    # at the limit itself the error would not come back, so the reset succeeds.
    axis = powered(following_error_limit=0.5)
    axis.fault(ErrorID.FOLLOWING_ERROR_EXCEEDED)
    axis.cmd_pos, axis.act_pos = 0.5, 0.0
    assert axis.reset() is True
    axis.fault(ErrorID.FOLLOWING_ERROR_EXCEEDED)
    axis.cmd_pos = 0.75
    assert axis.reset() is False


# --- from the second motion sample (seed 17) ------------------------------------------------------------

def test_axis_number_defaults_to_zero_and_lookup_by_number():
    from st_runtime.motion import MotionTask
    from st_runtime.motion.axis import Axis

    assert Axis(config()).axis_no == 0
    task = MotionTask([config()])
    assert task.axis_by_number(0) is task.axes[0]
    assert task.axis_by_number(1) is None and task.axis_by_number(-1) is None


def test_motion_of_a_context_without_a_task():
    from types import SimpleNamespace

    from st_runtime.motion.motion_task import motion_of

    assert motion_of(SimpleNamespace()) is None
    assert motion_of(SimpleNamespace(controller=SimpleNamespace())) is None
    task = object()
    assert motion_of(SimpleNamespace(controller=SimpleNamespace(motion=task))) is task


def test_move_accelerates_at_acceleration_not_deceleration():
    # Trapezoid from rest: the first 1 ms step reaches Acceleration * dt = 1000 * 0.001 = 1 mm/s.
    axis = powered()
    axis.start_move_absolute(10.0, 100.0, 1000.0, 100_000.0)
    axis.step(DT)
    assert axis.cmd_vel == pytest.approx(1.0)


def test_small_error_deceleration_still_decelerates():
    # error_deceleration 0.5 mm/s^2 (> 0, so not an immediate stop): one period after the fault at
    # 50 mm/s the command moves on by (50 - 0.5 * 0.001) * 0.001 mm.
    axis = powered(error_deceleration=0.5)
    command = axis.start_sync()
    command.target = 0.05
    axis.step(DT)
    axis.fault(ErrorID.FOLLOWING_ERROR_EXCEEDED)
    axis.step(DT)
    assert axis.cmd_pos == pytest.approx(0.05 + (50.0 - 0.0005) * 0.001, rel=1e-12)


def test_accdec_is_negative_when_the_speed_does_not_grow():
    # OMRON's Cmd.AccDec sign: + while |velocity| grows, - otherwise; +50 mm/s to -50 mm/s in one period.
    axis = powered()
    command = axis.start_sync()
    command.target = 0.05
    axis.step(DT)
    command.target = 0.0
    axis.step(DT)
    assert axis.cmd_vel == pytest.approx(-50.0)
    assert axis.cmd_accdec == pytest.approx(-100_000.0)


def test_a_warning_of_zero_is_disabled():
    axis = powered(servo_lag=0.01)              # the lag leaves a following error
    command = axis.start_sync()
    command.target = 0.05
    axis.step(DT)
    assert axis.following_error > 0 and axis.observation_code == ErrorID.NONE


def test_more_configuration_messages():
    from st_runtime.motion.axis_config import axis_configs_from_tables, axis_configs_from_toml

    with pytest.raises(AxisConfigError) as err:
        axis_config_from_dict([1, 2], where="axis 1")
    assert str(err.value) == "axis 1: expected a table of axis settings, found list"
    with pytest.raises(AxisConfigError) as err:
        axis_configs_from_tables([{"name": "X", "max_velocity": 1.0}, {"name": "if", "max_velocity": 1.0}])
    assert str(err.value).startswith("axis[1]: key 'name' must not be an ST keyword")
    for text in ("", "axis = []", "[axis]\nname = 'X'\nmax_velocity = 1.0"):
        with pytest.raises(AxisConfigError) as err:
            axis_configs_from_toml(text)
        assert str(err.value) == "axis configuration: expected at least one [[axis]] table"
    with pytest.raises(AxisConfigError) as err:
        axis_configs_from_toml("a = " + "[" * 5000 + "]" * 5000)
    assert str(err.value) == ("axis configuration is not valid TOML: arrays or inline tables nested "
                              "too deeply")


def test_rising_target_direction_drive_status_and_act_vel():
    from test_motion_st import AXIS, SYNC_RAMP, make_plc

    plc, main, _ = make_plc(SYNC_RAMP, AXIS)
    plc.run(5)
    assert plc.globals["Cyl1.Cmd.Vel"] == pytest.approx(10.0)        # 0.01 mm a ms
    assert plc.globals["Cyl1.Act.Vel"] == pytest.approx(10.0)        # ideal axis
    assert plc.globals["Cyl1.Dir.Posi"] is True and plc.globals["Cyl1.Dir.Nega"] is False
    assert plc.globals["Cyl1.DrvStatus.Ready"] is True and plc.globals["Cyl1.DrvStatus.MainPower"] is True


def test_programs_see_the_axis_state_at_the_start_of_their_scan():
    # Feedback in (before the programs): a fault raised between scans is what the next scan reads.
    from test_motion_st import AXIS, make_plc

    program = ("PROGRAM Main\nVAR\n    Power : MC_Power;\n    Seen : BOOL;\nEND_VAR\n"
               "Seen := Cyl1.MFaultLvl.Active;\nPower(Axis := Cyl1, Enable := TRUE);\nEND_PROGRAM\n")
    plc, main, task = make_plc(program, AXIS)
    plc.run(3)
    assert main["Seen"] is False
    task.axis("Cyl1").fault(ErrorID.FOLLOWING_ERROR_EXCEEDED)
    plc.run(1)
    assert main["Seen"] is True


# --- the five survivors of the seed-17 run (docs/mutation.md, motion) ------------------------------

@pytest.mark.parametrize("direction, code", [(1.0, ErrorID.TARGET_POSITIVE_SOFT_LIMIT),
                                             (-1.0, ErrorID.TARGET_NEGATIVE_SOFT_LIMIT)])
def test_a_stop_that_would_pass_a_software_limit_is_refused_with_its_code(direction, code):
    # At 100 mm/s, 5 mm before a limit at +-10 mm, MC_Stop at 100 mm/s^2 would need 50 mm:
    # the command position would leave the limits on the way, which faults the axis with the
    # software limit's ErrorID (the rule for a target beyond it, error_ids.py).
    from st_runtime.motion.axis import AxisState

    axis = powered(soft_limit_min=-10.0, soft_limit_max=10.0)
    axis.start_move_absolute(10.0 * direction, 100.0, 1e5, 1e5)
    for _ in range(50):
        axis.step(DT)
    assert axis.cmd_pos == pytest.approx(5.0 * direction)
    axis.start_stop(100.0)
    for _ in range(100):
        axis.step(DT)
    assert axis.state == AxisState.ERRORSTOP and axis.fault_code == code
    assert -10.0 <= axis.cmd_pos <= 10.0


def test_in_position_range_includes_its_bound():
    # "within the in-position range" (InPosition, fbs.py): |Act.Pos - target| equal to the
    # range (0.25 mm, exact in binary) completes the move; a hair more keeps it waiting.
    from st_runtime.motion.axis import AxisState

    for act, done in ((0.75, True), (0.7499999, False)):
        axis = powered(servo_lag=0.005, in_position_range=0.25)
        command = axis.start_move_absolute(1.0, 100.0, 1e5, 1e5)
        while not command.reached:
            axis.step(DT)
        axis.act_pos = act
        axis._complete_commands(DT)
        assert (axis.state == AxisState.STANDSTILL, command.done) == (done, done)
        assert axis.in_pos_waiting is not done


def scans_to_arrive(target: float, velocity: float) -> int:
    """Scans of 1/1024 s (exact in binary) an ideal axis at 0 takes to reach `target`
    at `velocity` with infinite acceleration: every step is velocity/1024, exactly."""
    axis = powered(max_velocity=1e5)
    command = axis.start_move_absolute(target, velocity, 0.0, 0.0)   # 0: the axis maximum, none
    for scan in range(1, 100):
        axis.step(1 / 1024)
        if command.done:
            assert axis.cmd_pos == target
            return scan
    raise AssertionError("never arrived")


def test_arrival_tolerance_is_1e_12_of_the_target_but_at_least_of_1_mm():
    # axis.py _ARRIVAL_EPS: a step that leaves at most 1e-12 * max(1, |target|) to go
    # (float64 rounding of the summed steps) arrives.  Every number below is exact in binary.
    # 1024 mm + 2^-39 mm (1.8e-12) at 64 mm a step: after 16 steps 2^-39 is left, below
    # 1e-12 * 1024 = 1.0e-9: the 16th step arrives (a tolerance of 1e-12 / 1024 would not).
    assert scans_to_arrive(1024.0 + 2.0**-39, 65536.0) == 16
    # 1 mm + 1.5e-12 at 1/16 mm a step: 1.5e-12 left is beyond 1e-12 * 1: a 17th step
    # (a tolerance of 2e-12 would arrive at the 16th).
    assert scans_to_arrive(1.0 + 6756 * 2.0**-52, 64.0) == 17
    # Bound included: a target of 2^-39 mm in one step of 2^-39 - fl(1e-12) leaves exactly
    # fl(1e-12) = 1e-12 * max(1, 2^-39): it arrives at once.
    target = 2.0**-39
    step = target - 1e-12
    assert target - step == 1e-12
    assert scans_to_arrive(target, step * 1024) == 1
