"""Configuration of a simulated servo axis, loaded from a dict or a TOML table.

Units are the axis's command units (mm for a linear axis) and seconds.  One
table per axis, e.g. in TOML:

    [[axis]]
    name = "Cylinder1"
    soft_limit_min = 0.0          # software limits; leave both out for none
    soft_limit_max = 600.0
    max_velocity = 200.0          # MC_SyncMoveAbsolute saturates at it (Details.VelLimit)
    max_acceleration = 0.0        # Acceleration/Deceleration 0 of MC_MoveAbsolute; 0: a step
    in_position_range = 0.01      # Done / InPosition window
    in_position_check_time = 0.0  # s; longer InPosWaiting: error 16#6447; 0: no time limit
    following_error_limit = 5.0   # error 16#6448 above it; 0: not checked
    following_error_warning = 0.0 # observation 16#644C above it (no stop); 0: not checked
    error_deceleration = 0.0      # command deceleration in ErrorStop; 0: immediate stop
    servo_lag = 0.0               # first-order lag time constant in s; 0: ideal axis
    initial_position = 0.0        # actual position when the simulation starts

A mistake raises `AxisConfigError` whose message names the axis, the key and
the rule broken.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import Any, Iterable, Mapping

# An axis name becomes an ST global variable name: a plain identifier that
# also obeys the NJ rules (no leading/trailing '_', no '__', <= 127 bytes).
_IDENTIFIER = re.compile(r"[A-Za-z][A-Za-z0-9_]*\Z")


class AxisConfigError(ValueError):
    """A configuration value breaks a rule; the message says which."""


@dataclass(frozen=True, slots=True)
class AxisConfig:
    name: str
    max_velocity: float
    soft_limit_min: float = -math.inf
    soft_limit_max: float = math.inf
    max_acceleration: float = 0.0
    in_position_range: float = 0.01
    in_position_check_time: float = 0.0
    following_error_limit: float = 0.0
    following_error_warning: float = 0.0
    error_deceleration: float = 0.0
    servo_lag: float = 0.0
    initial_position: float = 0.0

    @property
    def has_soft_limits(self) -> bool:
        return math.isfinite(self.soft_limit_min) or math.isfinite(self.soft_limit_max)

    def within_soft_limits(self, position: float) -> bool:
        return self.soft_limit_min <= position <= self.soft_limit_max


_NUMERIC_KEYS = (
    "max_velocity",
    "soft_limit_min",
    "soft_limit_max",
    "max_acceleration",
    "in_position_range",
    "in_position_check_time",
    "following_error_limit",
    "following_error_warning",
    "error_deceleration",
    "servo_lag",
    "initial_position",
)
_KEYS = ("name",) + _NUMERIC_KEYS


def axis_config_from_dict(table: Mapping[str, Any], where: str = "axis") -> AxisConfig:
    """Validate one axis table and build its AxisConfig."""
    if not isinstance(table, Mapping):
        raise AxisConfigError(f"{where}: expected a table of axis settings, found {type(table).__name__}")
    unknown = sorted(set(table) - set(_KEYS))
    if unknown:
        raise AxisConfigError(f"{where}: unknown key {unknown[0]!r} (known keys: {', '.join(_KEYS)})")
    name = table.get("name")
    if not isinstance(name, str) or not _is_valid_name(name):
        raise AxisConfigError(
            f"{where}: key 'name' must be an ST identifier (letter first, then letters, digits"
            f" or single '_', no trailing '_', at most 127 bytes), found {name!r}"
        )
    where = f"axis {name!r}"
    if "max_velocity" not in table:
        raise AxisConfigError(f"{where}: key 'max_velocity' is required")
    values = {key: _number(table[key], where, key) for key in _NUMERIC_KEYS if key in table}
    config = AxisConfig(name=name, **values)
    _check_rules(config, where)
    return config


def axis_configs_from_tables(tables: Iterable[Mapping[str, Any]]) -> list[AxisConfig]:
    """Validate a list of axis tables (e.g. TOML `[[axis]]`); names must be unique."""
    configs: list[AxisConfig] = []
    seen: set[str] = set()
    for index, table in enumerate(tables):
        config = axis_config_from_dict(table, where=f"axis[{index}]")
        if config.name.upper() in seen:
            raise AxisConfigError(f"axis {config.name!r}: key 'name' duplicates another axis (names are case-insensitive)")
        seen.add(config.name.upper())
        configs.append(config)
    return configs


def axis_configs_from_toml(text: str) -> list[AxisConfig]:
    """The `[[axis]]` tables of a TOML text, validated."""
    import tomllib

    try:
        document = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise AxisConfigError(f"axis configuration is not valid TOML: {exc}") from None
    tables = document.get("axis")
    if not isinstance(tables, list) or not tables:
        raise AxisConfigError("axis configuration: expected at least one [[axis]] table")
    return axis_configs_from_tables(tables)


def _is_valid_name(name: str) -> bool:
    return (
        bool(_IDENTIFIER.match(name))
        and "__" not in name
        and not name.endswith("_")
        and len(name.encode()) <= 127
    )


def _number(value: Any, where: str, key: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise AxisConfigError(f"{where}: key {key!r} must be a number, found {value!r}")
    number = float(value)
    if math.isnan(number):
        raise AxisConfigError(f"{where}: key {key!r} must be a number, found NaN")
    return number


def _check_rules(c: AxisConfig, where: str) -> None:
    def fail(key: str, rule: str, value: float) -> None:
        raise AxisConfigError(f"{where}: key {key!r} must be {rule}, found {value!r}")

    if not (c.max_velocity > 0 and math.isfinite(c.max_velocity)):
        fail("max_velocity", "a positive finite number", c.max_velocity)
    for key in ("max_acceleration", "following_error_limit", "following_error_warning",
                "error_deceleration", "in_position_check_time", "servo_lag"):
        value = getattr(c, key)
        if not (value >= 0 and math.isfinite(value)):
            fail(key, "finite and >= 0 (0 disables it)", value)
    if 0 < c.following_error_limit < c.following_error_warning:
        raise AxisConfigError(
            f"{where}: key 'following_error_warning' must not exceed 'following_error_limit',"
            f" found {c.following_error_warning!r} > {c.following_error_limit!r}"
        )
    if not (c.in_position_range > 0 and math.isfinite(c.in_position_range)):
        fail("in_position_range", "a positive finite number", c.in_position_range)
    if not c.soft_limit_min < c.soft_limit_max:
        raise AxisConfigError(
            f"{where}: key 'soft_limit_min' must be below 'soft_limit_max',"
            f" found {c.soft_limit_min!r} >= {c.soft_limit_max!r}"
        )
    if not math.isfinite(c.initial_position):
        fail("initial_position", "finite", c.initial_position)
    if not c.within_soft_limits(c.initial_position):
        raise AxisConfigError(
            f"{where}: key 'initial_position' must lie within the software limits"
            f" [{c.soft_limit_min!r}, {c.soft_limit_max!r}], found {c.initial_position!r}"
        )
