"""SP_Controller running in the simulated NJ: one primary task, six simulated axes.

Scan order as on the NJ (``st_runtime.motion.motion_task``): axis feedback in,
SP_Controller, motion processing. The axes are the six cylinders: software
limits = the stroke, maximum velocity = the actuator's, an ideal servo (the
actual position equals the command) unless a servo lag is given, starting
where the IK of the start pose puts them.

The acceleration of the synchronised command is not limited by the axes
(``max_acceleration = 0``; OMRON's MC_SyncMoveAbsolute does not use it
either): the program must keep the set-points inside the actuator's velocity
and acceleration, and every scenario checks that
(:mod:`stgen.scenarios.setpoint_limits`). The study's start of the wave (a
lead-in ending at rest, then the wave at full speed) was a velocity step of
8.5 mm/s in one scan (8,486 mm/s² on a cylinder, random wave); the wave now
fades in from rest (TRJ_OceanWave, docs/mathematics.md section 4). The controller itself checks
stroke and per-scan step.
"""

from __future__ import annotations

import numpy as np

from stgen.config import PlatformConfig
from stgen.reference.kinematics import inverse_kinematics
from stgen.scenarios.actuators import actuator_limits, actuator_positions
from stgen.scenarios.program import AXIS_NAMES, CONTROLLER_PROGRAM, load_controller

#: Following-error limit of the simulated cylinders, mm (an ideal servo never reaches it).
FOLLOWING_ERROR_LIMIT_MM = 1.0
#: In-position range of the simulated cylinders, mm.
IN_POSITION_RANGE_MM = 0.01


def axis_tables(config: PlatformConfig, start_pose, servo_lag_s: float = 0.0, base_pose=None) -> list[dict]:
    """The six ``[[axis]]`` tables: cylinder i starts at q_i of ``start_pose``.

    ``servo_lag_s``: first-order lag of the actual position behind the command
    (0: an ideal servo). A platform variant: axis i is its actuator coordinate
    (:mod:`stgen.scenarios.actuators`; crank angles in degrees), ``base_pose``
    the base's pose at the start (a moving base).
    """
    if config.is_default_kind:
        ik = inverse_kinematics(config.geometry, np.asarray(start_pose, dtype=float), config.stroke)
        if not bool(np.all(ik.in_stroke)):
            raise ValueError(f"start pose {tuple(start_pose)} puts a cylinder outside the stroke")
        positions = ik.positions
    else:
        from stgen.reference.feasibility import check_pose

        report = check_pose(config, start_pose, base_pose)
        if not report.feasible:
            raise ValueError(f"start pose {tuple(start_pose)} is not feasible: "
                             + "; ".join(str(v) for v in report.violations))
        positions = actuator_positions(config, start_pose, base_pose)
    low, high = actuator_limits(config)
    return [
        {
            "name": name,
            "soft_limit_min": low,
            "soft_limit_max": high,
            "max_velocity": config.actuator.max_velocity,
            "max_acceleration": 0.0,
            "in_position_range": IN_POSITION_RANGE_MM,
            "following_error_limit": FOLLOWING_ERROR_LIMIT_MM,
            "servo_lag": servo_lag_s,
            "initial_position": float(position),
        }
        for name, position in zip(AXIS_NAMES, positions)
    ]


class ControllerSimulation:
    """SP_Controller with its six axes, scan by scan.

    ``globals`` reads and writes the command/status variables by name
    (``sim.globals["SpPowerOn"] = True``); ``axes`` are the simulated axes
    (``st_runtime.motion.axis.Axis``), in cylinder order. ``playback``: a
    :class:`~stgen.reference.playback.PlaybackTable` the controller is rendered with (SpPlaybackStart).
    """

    def __init__(
        self, config: PlatformConfig | None = None, start_pose=(0.0, 0.0, 0.0, 0.0, 0.0, 0.0), servo_lag_s: float = 0.0,
        base_pose=None,
        playback=None,
    ):
        from st_runtime.motion.motion_task import MotionTask

        self.config = config if config is not None else PlatformConfig.default()
        self.motion = MotionTask.from_tables(axis_tables(self.config, start_pose, servo_lag_s, base_pose))
        project = load_controller(self.config, playback)
        period_ns = round(self.config.task.period_s * 1e9)
        self.plc = project.controller(period=period_ns)
        self.program = self.plc.add_program(CONTROLLER_PROGRAM)
        self.motion.install(self.plc.controller)
        self.axes = self.motion.axes
        self.globals = self.plc.globals
        self.codes = _global_codes(self.globals)
        if self.config.moving_base:  # the IMU's first reading, before the first scan
            self.set_pose("SpBasePose", base_pose if base_pose is not None else (0.0,) * 6)

    @property
    def scan_count(self) -> int:
        return self.plc.controller.scan_count

    @property
    def runtime_faults(self) -> list:
        return self.plc.faults

    def run(self, scans: int) -> None:
        self.plc.run(scans)

    def run_until(self, condition, max_scans: int) -> int:
        """Scan until ``condition()`` holds after a scan; returns the scans run; TimeoutError past ``max_scans``."""
        scan = self.plc.controller.scan
        for count in range(1, max_scans + 1):
            scan()
            if condition():
                return count
        raise TimeoutError(f"condition not met within {max_scans} scans (state {self.state_name})")

    @property
    def state(self) -> int:
        return self.globals["SpState"]

    @property
    def state_name(self) -> str:
        state = self.state
        for name, value in self.codes.items():
            if name.startswith("SP_STATE_") and value == state:
                return name
        return str(state)

    def command_positions(self) -> np.ndarray:
        """The six axes' command positions (mm), cylinder order."""
        return np.array([axis.cmd_pos for axis in self.axes])

    def power_on(self, max_scans: int = 200) -> int:
        """SpPowerOn := TRUE and scan until STANDBY; returns the scans it took."""
        self.globals["SpPowerOn"] = True
        return self.run_until(lambda: self.globals["SpReady"], max_scans)

    def set_pose(self, name: str, pose) -> None:
        self.globals[name] = [float(v) for v in pose]


def _global_codes(globals_) -> dict[str, int]:
    """SP_STATE_xxx, SP_FAULT_xxx and SP_REFUSED_xxx as the loaded program holds them."""
    codes = {}
    for key, (name, _type) in globals_.layout.items():
        if key.startswith(("SP_STATE_", "SP_FAULT_", "SP_REFUSED_")):
            codes[name] = globals_[name]
    return codes
