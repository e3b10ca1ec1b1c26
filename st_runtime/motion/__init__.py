"""Simulated PLCopen servo axes for the ST runtime.

* `axis_config` -- one axis's settings, loaded from a dict / TOML table;
* `axis` -- the simulation of one axis (PLCopen states, limits, servo lag);
* `error_ids` -- the ErrorID table of the axes and motion FBs;
* `types` -- the AXIS_REF type as ST text, and copying state into it;
* `fbs` -- MC_Power, MC_Reset, MC_Home, MC_Stop, MC_MoveAbsolute,
  MC_SyncMoveAbsolute as native FBs (registered when this package is imported);
* `motion_task` -- the controller's axes: globals, feedback in, motion processing.
"""

from . import fbs  # noqa: F401  (registers AXIS_REF and the motion FBs)
from .axis import Axis, AxisState, MotionRefused
from .axis_config import (
    AxisConfig, AxisConfigError, axis_config_from_dict, axis_configs_from_tables, axis_configs_from_toml,
)
from .error_ids import ErrorID
from .motion_task import MotionTask

__all__ = [
    "Axis", "AxisConfig", "AxisConfigError", "AxisState", "ErrorID", "MotionRefused",
    "MotionTask", "axis_config_from_dict", "axis_configs_from_tables", "axis_configs_from_toml",
]
