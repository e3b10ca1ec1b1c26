"""Axis configuration: defaults, TOML tables, and messages that name key and rule."""

import math
import tomllib

import pytest

from st_runtime.motion.axis_config import (
    AxisConfig,
    AxisConfigError,
    axis_config_from_dict,
    axis_configs_from_tables,
)
from st_runtime.motion.error_ids import ErrorID, describe


def test_minimal_table_gets_documented_defaults():
    config = axis_config_from_dict({"name": "Cyl1", "max_velocity": 200})
    assert config == AxisConfig(name="Cyl1", max_velocity=200.0)
    assert config.soft_limit_min == -math.inf and config.soft_limit_max == math.inf
    assert not config.has_soft_limits
    assert config.servo_lag == 0.0 and config.following_error_limit == 0.0


def test_toml_axis_tables():
    text = """
    [[axis]]
    name = "Cylinder1"
    soft_limit_min = 0.0
    soft_limit_max = 600
    max_velocity = 200.0
    following_error_limit = 5.0
    servo_lag = 0.002
    initial_position = 10.0

    [[axis]]
    name = "Cylinder2"
    max_velocity = 150.0
    """
    configs = axis_configs_from_tables(tomllib.loads(text)["axis"])
    assert [c.name for c in configs] == ["Cylinder1", "Cylinder2"]
    assert configs[0].soft_limit_max == 600.0 and configs[0].servo_lag == 0.002
    assert configs[0].within_soft_limits(600.0) and not configs[0].within_soft_limits(600.001)


@pytest.mark.parametrize(
    "table, fragment",
    [
        ({"max_velocity": 1.0}, "key 'name' must be an ST identifier"),
        ({"name": "_Ax", "max_velocity": 1.0}, "key 'name'"),
        ({"name": "Ax_", "max_velocity": 1.0}, "key 'name'"),
        ({"name": "A__x", "max_velocity": 1.0}, "key 'name'"),
        ({"name": "x; END_VAR", "max_velocity": 1.0}, "key 'name'"),
        ({"name": "A" * 128, "max_velocity": 1.0}, "key 'name'"),
        ({"name": "Ax"}, "key 'max_velocity' is required"),
        ({"name": "Ax", "max_velocity": 0}, "'max_velocity' must be a positive finite number, found 0.0"),
        ({"name": "Ax", "max_velocity": "fast"}, "'max_velocity' must be a number, found 'fast'"),
        ({"name": "Ax", "max_velocity": True}, "'max_velocity' must be a number"),
        ({"name": "Ax", "max_velocity": 1, "servo_lag": -0.1}, "'servo_lag' must be finite and >= 0"),
        ({"name": "Ax", "max_velocity": 1, "following_error_limit": math.inf}, "'following_error_limit'"),
        ({"name": "Ax", "max_velocity": 1, "in_position_range": 0}, "'in_position_range' must be a positive"),
        ({"name": "Ax", "max_velocity": 1, "soft_limit_min": 5, "soft_limit_max": 5},
         "'soft_limit_min' must be below 'soft_limit_max', found 5.0 >= 5.0"),
        ({"name": "Ax", "max_velocity": 1, "soft_limit_min": 0, "initial_position": -1},
         "'initial_position' must lie within the software limits"),
        ({"name": "Ax", "max_velocity": 1, "maxvelocity": 2}, "unknown key 'maxvelocity'"),
        ({"name": "Ax", "max_velocity": 1, "error_deceleration": -1}, "'error_deceleration' must be finite"),
        ({"name": "Ax", "max_velocity": 1, "in_position_check_time": -1}, "'in_position_check_time'"),
        ({"name": "Ax", "max_velocity": 1, "following_error_limit": 1, "following_error_warning": 2},
         "'following_error_warning' must not exceed 'following_error_limit', found 2.0 > 1.0"),
    ],
)
def test_invalid_tables_name_key_and_rule(table, fragment):
    with pytest.raises(AxisConfigError) as error:
        axis_config_from_dict(table)
    assert fragment in str(error.value)


def test_duplicate_names_case_insensitive():
    with pytest.raises(AxisConfigError, match="duplicates"):
        axis_configs_from_tables([{"name": "Ax", "max_velocity": 1}, {"name": "AX", "max_velocity": 1}])


def test_every_error_id_is_distinct_and_documented():
    codes = [int(e) for e in ErrorID]
    assert len(codes) == len(set(codes))
    for member in ErrorID:
        assert 0 <= member <= 0xFFFF  # a WORD
        line = describe(member)
        assert line.startswith(f"16#{int(member):04X} {member.name}: ") and len(line) > 20
    assert describe(0x1234) == "16#1234: unknown ErrorID"


def test_axis_configs_from_toml_text():
    from st_runtime.motion import MotionTask, axis_configs_from_toml

    configs = axis_configs_from_toml('[[axis]]\nname = "A1"\nmax_velocity = 5\n')
    assert configs == [AxisConfig(name="A1", max_velocity=5.0)]
    task = MotionTask.from_toml('[[axis]]\nname = "A1"\nmax_velocity = 5\n[[axis]]\nname = "A2"\nmax_velocity = 6\n')
    assert [a.name for a in task.axes] == ["A1", "A2"] and task.axis("a2").axis_no == 1
    with pytest.raises(AxisConfigError, match="not valid TOML"):
        axis_configs_from_toml("[[axis]\n")
    with pytest.raises(AxisConfigError, match=r"at least one \[\[axis\]\] table"):
        axis_configs_from_toml("[axes]\nname = 1\n")
