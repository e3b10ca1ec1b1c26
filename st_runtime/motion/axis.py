"""Simulation of one PLCopen servo axis, advanced one task period at a time.

The axis has the PLCopen states (Disabled, Standstill, DiscreteMotion,
ContinuousMotion, SynchronizedMotion, Stopping, ErrorStop, Homing), a command
position/velocity produced by the active motion command, and an actual
position/velocity that follows the command through a first-order servo lag
(time constant `servo_lag`; 0 is an ideal axis whose actual position equals
its command exactly).

Motion FBs call `start_*` during the user programs; the motion processing
calls `step(dt)` once per primary period after them.  So a Position given to
MC_SyncMoveAbsolute in scan k becomes the command position of scan k.

Motion processing checks every new command position before applying it:
software limits, the per-scan step against the maximum velocity, and (for
synchronized motion, when configured) the change of velocity against the
maximum acceleration.  A refused command puts the axis in ErrorStop, the
command position holds where it was (an immediate stop of the command), and
the actual position settles onto it.  After the servo moved, the following
error is checked against its limit.

Simplifications (documented, not hidden): profiles are trapezoidal without
jerk limitation (the arrival scan of a move may brake by up to twice its
Deceleration, taking up the remainder); an aborting move that cannot stop in time brakes harder than
its Deceleration; servo on/off takes effect at the next motion processing.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from enum import IntEnum

from .axis_config import AxisConfig
from .error_ids import ErrorID

# Relative slack on limit checks so that a step of exactly max_velocity * period
# (rounded in float64) is accepted.
_LIMIT_SLACK = 1e-9


# A move whose remaining distance is below this (relative to the target) has
# arrived; it absorbs the rounding of summing many per-scan steps.
_ARRIVAL_EPS = 1e-12


def _discrete_stopping_speed(deceleration: float, remaining: float, dt: float) -> float:
    """Highest speed for this scan from which steps of `deceleration * dt` less
    per scan still stop within `remaining`.

    With v = n*a*dt the scans cover a*dt^2 * n(n+1)/2; solved for n:
    v = (-a*dt + sqrt((a*dt)^2 + 8*a*remaining)) / 2.  (The continuous
    sqrt(2*a*s) would brake harder than `a` in the last scans.)
    """
    if not math.isfinite(deceleration):
        return math.inf
    a_dt = deceleration * dt
    return (-a_dt + math.sqrt(a_dt * a_dt + 8.0 * deceleration * remaining)) / 2.0


class AxisState(IntEnum):
    DISABLED = 0
    STANDSTILL = 1
    DISCRETE = 2
    CONTINUOUS = 3
    SYNCHRONIZED = 4
    STOPPING = 5
    ERRORSTOP = 6
    HOMING = 7


class MotionRefused(Exception):
    """A motion FB may not start: `code` is the ErrorID for the FB."""

    def __init__(self, code: ErrorID):
        super().__init__(code.name)
        self.code = code


@dataclass(eq=False, slots=True)
class MotionCommand:
    """One started motion; the FB that started it watches `done`/`aborted`.

    kind: "sync" | "move" | "stop" | "home".  `target` is the position of a
    move, or the latest Position of a synchronized motion.
    """

    kind: str
    target: float = 0.0
    velocity: float = 0.0
    acceleration: float = math.inf
    deceleration: float = math.inf
    done: bool = False
    aborted: bool = False
    released: bool = False  # MC_Stop: Execute has fallen, leave Stopping when stopped
    reached: bool = False   # move: the command position has arrived at the target


class Axis:
    """One simulated axis.  Positions in command units, velocities per second."""

    def __init__(self, config: AxisConfig, axis_no: int = 0):
        self.config = config
        self.axis_no = axis_no
        self.state = AxisState.DISABLED
        self.power_requested = False
        self.powered = False
        self.homed = False
        self.cmd_pos = config.initial_position
        self.act_pos = config.initial_position
        self.cmd_vel = 0.0
        self.act_vel = 0.0
        self.fault_code = ErrorID.NONE
        self.command: MotionCommand | None = None
        # Per-period constants of the checks and the servo (see _set_period).
        self._soft_min = config.soft_limit_min
        self._soft_max = config.soft_limit_max
        self._following_limit = config.following_error_limit
        self._dt = 0.0
        self._max_step = self._max_dv = 0.0
        self._lag_gain = 1.0

    # ------------------------------------------------------------ queries
    @property
    def name(self) -> str:
        return self.config.name

    @property
    def following_error(self) -> float:
        return self.cmd_pos - self.act_pos

    @property
    def fault_active(self) -> bool:
        return self.state == AxisState.ERRORSTOP

    # ------------------------------------------------ requests from FBs
    def request_power(self, on: bool) -> None:
        """MC_Power's Enable; applied by the next motion processing."""
        self.power_requested = bool(on)

    def start_sync(self) -> MotionCommand:
        """MC_SyncMoveAbsolute: take the axis into synchronized motion."""
        self._check_can_move()
        command = MotionCommand("sync", target=self.cmd_pos)
        self._take(command, AxisState.SYNCHRONIZED)
        return command

    def start_move_absolute(
        self, position: float, velocity: float, acceleration: float, deceleration: float
    ) -> MotionCommand:
        """MC_MoveAbsolute: trapezoidal move to `position`."""
        self._check_can_move()
        limit = self.config.max_velocity * (1 + _LIMIT_SLACK)
        if not (math.isfinite(position) and 0 < velocity <= limit):
            raise MotionRefused(ErrorID.PARAMETER_OUT_OF_RANGE)
        acc = self._rate(acceleration)
        dec = self._rate(deceleration)
        if not self.config.within_soft_limits(position):
            self.fault(ErrorID.TARGET_BEYOND_SOFT_LIMIT)
            raise MotionRefused(ErrorID.TARGET_BEYOND_SOFT_LIMIT)
        command = MotionCommand("move", target=position, velocity=velocity,
                                acceleration=acc, deceleration=dec)
        self._take(command, AxisState.DISCRETE)
        return command

    def start_stop(self, deceleration: float) -> MotionCommand:
        """MC_Stop: decelerate to zero velocity, then hold the axis in Stopping."""
        if not self.powered:
            raise MotionRefused(ErrorID.AXIS_DISABLED)
        if self.state == AxisState.ERRORSTOP:
            raise MotionRefused(ErrorID.AXIS_IN_ERRORSTOP)
        command = MotionCommand("stop", deceleration=self._rate(deceleration))
        self._take(command, AxisState.STOPPING)
        return command

    def release_stop(self, command: MotionCommand) -> None:
        """MC_Stop's Execute fell: leave Stopping for Standstill once stopped."""
        command.released = True
        if command is self.command and command.done:
            self._finish(AxisState.STANDSTILL)

    def start_home(self) -> MotionCommand:
        """MC_Home for an absolute encoder: no motion, the axis becomes homed."""
        self._check_can_move()
        if self.state != AxisState.STANDSTILL:
            raise MotionRefused(ErrorID.AXIS_MOVING)
        command = MotionCommand("home", target=self.cmd_pos)
        self._take(command, AxisState.HOMING)
        return command

    def reset(self) -> bool:
        """MC_Reset: clear ErrorStop.  False when the cause persists."""
        if self.state != AxisState.ERRORSTOP:
            return True
        limit = self.config.following_error_limit
        if limit > 0 and abs(self.following_error) > limit:
            return False
        self.fault_code = ErrorID.NONE
        self.cmd_vel = 0.0
        self.state = AxisState.STANDSTILL if self.powered else AxisState.DISABLED
        return True

    def fault(self, code: ErrorID) -> None:
        """Enter ErrorStop with `code` (the first fault's code is kept)."""
        if self.state == AxisState.ERRORSTOP:
            return
        self._abort_command()
        self.state = AxisState.ERRORSTOP
        self.fault_code = code
        self.cmd_vel = 0.0

    # --------------------------------------------------- motion processing
    def step(self, dt: float) -> None:
        """Advance one period of `dt` seconds: command, servo, checks.

        Runs for every axis every scan, so the common case (a command within
        all limits) takes a short path; any doubt goes to `_check_command`.
        """
        if self.power_requested != self.powered:
            self._apply_power()
        if not self.powered:
            # Servo off: nothing drives the axis; the command follows the actual position.
            self.cmd_pos = self.act_pos
            self.cmd_vel = self.act_vel = 0.0
            return
        if dt != self._dt:
            self._set_period(dt)
        old_cmd, old_act = self.cmd_pos, self.act_pos
        command = self.command
        if command is None:
            new_cmd = old_cmd
        elif command.kind == "sync":
            new_cmd = command.target
            delta = new_cmd - old_cmd
            max_step = self._max_step
            if not (self._soft_min <= new_cmd <= self._soft_max and -max_step <= delta <= max_step
                    and (self._max_dv == 0 or abs(delta / dt - self.cmd_vel) <= self._max_dv)):
                new_cmd = self._checked(new_cmd, old_cmd, dt)
        else:
            new_cmd = self._next_command_position(dt)
            if new_cmd != old_cmd:
                new_cmd = self._checked(new_cmd, old_cmd, dt)
        self.cmd_pos = new_cmd
        self.cmd_vel = (new_cmd - old_cmd) / dt
        if self._lag_gain == 1.0:
            self.act_pos = new_cmd  # ideal axis: exactly the command
        else:
            self.act_pos = old_act + (new_cmd - old_act) * self._lag_gain
        self.act_vel = (self.act_pos - old_act) / dt
        limit = self._following_limit
        if limit > 0 and abs(new_cmd - self.act_pos) > limit:
            self.fault(ErrorID.FOLLOWING_ERROR_EXCEEDED)
        if self.command is not None and self.command.reached:
            self._complete_commands()

    def _checked(self, new_cmd: float, old_cmd: float, dt: float) -> float:
        """`new_cmd` if it passes every check, else fault and hold `old_cmd`."""
        refusal = self._check_command(new_cmd, old_cmd, dt)
        if refusal is None:
            return new_cmd
        self.fault(refusal)
        return old_cmd

    def _set_period(self, dt: float) -> None:
        """Cache what the checks and the servo need for periods of `dt`."""
        cfg = self.config
        self._dt = dt
        self._max_step = cfg.max_velocity * dt * (1 + _LIMIT_SLACK)
        self._max_dv = cfg.max_acceleration * dt * (1 + _LIMIT_SLACK)
        tau = cfg.servo_lag
        self._lag_gain = 1.0 if tau == 0 else 1.0 - math.exp(-dt / tau)

    # ------------------------------------------------------------ internals
    def _check_can_move(self) -> None:
        if not self.powered:
            raise MotionRefused(ErrorID.AXIS_DISABLED)
        if self.state == AxisState.ERRORSTOP:
            raise MotionRefused(ErrorID.AXIS_IN_ERRORSTOP)
        if self.state == AxisState.STOPPING:
            raise MotionRefused(ErrorID.AXIS_STOPPING)

    def _rate(self, value: float) -> float:
        """An Acceleration/Deceleration input: 0 means the axis maximum (none: a step)."""
        if not (math.isfinite(value) and value >= 0):
            raise MotionRefused(ErrorID.PARAMETER_OUT_OF_RANGE)
        if value == 0:
            return self.config.max_acceleration or math.inf
        return value

    def _take(self, command: MotionCommand, state: AxisState) -> None:
        self._abort_command()
        self.command = command
        self.state = state

    def _abort_command(self) -> None:
        if self.command is not None and not self.command.done:
            self.command.aborted = True
        self.command = None

    def _finish(self, state: AxisState) -> None:
        self.command.done = True
        self.command = None
        self.state = state

    def _apply_power(self) -> None:
        if self.power_requested == self.powered:
            return
        self.powered = self.power_requested
        if self.powered:
            self.cmd_pos = self.act_pos
            if self.state == AxisState.DISABLED:
                self.state = AxisState.STANDSTILL
        else:
            self._abort_command()
            if self.state != AxisState.ERRORSTOP:
                self.state = AxisState.DISABLED

    def _next_command_position(self, dt: float) -> float:
        command = self.command
        if command is None:
            return self.cmd_pos
        if command.kind == "sync":
            return command.target
        if command.kind == "move":
            return self._trapezoid_step(command, dt)
        if command.kind == "stop":
            return self._stop_step(command, dt)
        command.reached = True  # homing an absolute encoder does not move
        return self.cmd_pos

    def _trapezoid_step(self, c: MotionCommand, dt: float) -> float:
        distance = c.target - self.cmd_pos
        if distance == 0:
            c.reached = True
            return c.target
        direction = 1.0 if distance > 0 else -1.0
        speed = self.cmd_vel * direction  # negative when moving away from the target
        remaining = abs(distance)
        speed_to_stop = _discrete_stopping_speed(c.deceleration, remaining, dt)
        rate = c.acceleration if speed >= 0 else c.deceleration
        new_speed = min(speed + rate * dt, c.velocity, speed_to_stop)
        # Arrive when this step covers what remains (up to float64 rounding of the sum).
        if remaining - new_speed * dt <= _ARRIVAL_EPS * max(1.0, abs(c.target)):
            c.reached = True
            return c.target
        return self.cmd_pos + direction * new_speed * dt

    def _stop_step(self, c: MotionCommand, dt: float) -> float:
        speed = abs(self.cmd_vel)
        new_speed = max(speed - c.deceleration * dt, 0.0) if math.isfinite(c.deceleration) else 0.0
        if new_speed == 0.0:
            c.reached = True
        return self.cmd_pos + math.copysign(new_speed * dt, self.cmd_vel)

    def _check_command(self, new_cmd: float, old_cmd: float, dt: float) -> ErrorID | None:
        cfg = self.config
        if not math.isfinite(new_cmd):
            return ErrorID.COMMAND_NOT_FINITE
        if not cfg.within_soft_limits(new_cmd):
            return ErrorID.SOFT_LIMIT_EXCEEDED
        step = abs(new_cmd - old_cmd)
        if step > cfg.max_velocity * dt * (1 + _LIMIT_SLACK):
            return ErrorID.VELOCITY_LIMIT_EXCEEDED
        if self.state == AxisState.SYNCHRONIZED and cfg.max_acceleration > 0:
            new_vel = (new_cmd - old_cmd) / dt
            if abs(new_vel - self.cmd_vel) > cfg.max_acceleration * dt * (1 + _LIMIT_SLACK):
                return ErrorID.ACCELERATION_LIMIT_EXCEEDED
        return None

    def _complete_commands(self) -> None:
        c = self.command
        if c is None or not c.reached:
            return
        if c.kind == "move":
            if abs(self.act_pos - c.target) <= self.config.in_position_range:
                self._finish(AxisState.STANDSTILL)
        elif c.kind == "stop":
            c.done = True
            if c.released:
                self._finish(AxisState.STANDSTILL)
        elif c.kind == "home":
            self.homed = True
            self._finish(AxisState.STANDSTILL)
