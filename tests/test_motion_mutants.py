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
