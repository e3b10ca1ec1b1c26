"""Simulation of one PLCopen servo axis, advanced one task period at a time,
following OMRON's NJ motion kernel where its behaviour is documented.

The axis has the PLCopen states (Disabled, Standstill, DiscreteMotion,
ContinuousMotion, SynchronizedMotion, Stopping, ErrorStop, Homing), a command
position/velocity produced by the active motion command, and an actual
position/velocity that follows the command through a first-order servo lag
(time constant `servo_lag`; 0 is an ideal axis whose actual position equals
its command exactly).

Motion FBs call `start_*` during the user programs; the motion processing
calls `step(dt)` once per primary period after them.  So a Position given to
MC_SyncMoveAbsolute in scan k becomes the command of scan k.

What follows OMRON (sources in docs/nj501.md, "OMRON's motion kernel"):

* MC_SyncMoveAbsolute puts the axis in Status.Discrete (not Synchronized).  A
  Position too far for one period is not an error: the command moves by the
  maximum velocity x period, the rest follows in later periods, and
  Details.VelLimit is TRUE meanwhile; maximum acceleration/deceleration are not
  used (W507 9-2 for synchronized control; SPEC 7 for MC_SyncMoveAbsolute).
* A motion command started while the axis has an error (ErrorStop) or while
  MC_Stop holds it (Stopping) ends with CommandAborted (`MotionAborted`), not
  with an error.
* MC_Stop on an axis under MC_SyncMoveAbsolute stops it at once (its
  Deceleration is ignored); Deceleration = 0 is an immediate stop too.
* An axis error puts the axis in ErrorStop.  The command then stops at once,
  or decelerates at `error_deceleration` when one is configured; Status.ErrorStop
  is TRUE all along, and MC_Reset fails while the command still decelerates.
* Following error above `following_error_limit`: error 16#6448; above
  `following_error_warning`: observation 16#644C, the axis goes on.

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


def _bounded_step_velocity(slack: float, dt: float) -> bool:
    """Whether no step of at most `slack` in `dt` s is an infinite velocity: the motion task's
    stream step takes only such axes (its AccDec relies on it: motion_task._LANE_SHORT).  A `dt`
    of 0 divides by zero in the step itself first, as before; a negative one never streams."""
    return dt == 0.0 or not math.isinf(slack / dt)


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


class MotionAborted(Exception):
    """A motion FB started while the axis has an error or MC_Stop holds it:
    the FB ends with CommandAborted, not Error (SPEC 7, MC_SyncMoveAbsolute)."""


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


class StreamStamp:
    """The epoch in which every axis of a motion task took a sync stream's step, while none has
    been changed since but by such a step (else None): one test a scan instead of one an axis
    (`motion_task._STEADY_LANES`).  Every end of an axis's epoch ends it too."""

    __slots__ = ("epoch",)

    def __init__(self):
        self.epoch = None


class Axis:
    """One simulated axis.  Positions in command units, velocities per second."""

    # Slots: the motion task's lanes and the FBs' hot paths read and store these every scan
    # (CPython 3.11 specialises a slot's load and store to a fixed offset, no values array to
    # check); `__dict__` keeps any other attribute (a test's stand-in `step`, say) as before.
    __slots__ = ("config", "axis_no", "state", "power_requested", "powered", "homed", "cmd_pos", "act_pos",
                 "cmd_vel", "cmd_accdec", "act_vel", "fault_code", "observation_code", "vel_limit",
                 "in_pos_waiting", "_in_pos_wait_s", "command", "_soft_min", "_soft_max", "_following_limit",
                 "_following_warning", "_dt", "_max_step", "_step_slack", "_lag_gain", "_stream_dt",
                 "_streamed_in", "_task_stamp", "_in_position_range", "_in_position_floor", "__dict__")

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
        self.cmd_accdec = 0.0   # OMRON sign: + while |velocity| grows, - while it falls
        self.act_vel = 0.0
        self.fault_code = ErrorID.NONE
        self.observation_code = ErrorID.NONE
        self.vel_limit = False       # Details.VelLimit: the sync command is saturated
        self.in_pos_waiting = False  # Details.InPosWaiting: a move waits for in-position
        self._in_pos_wait_s = 0.0
        self.command: MotionCommand | None = None
        # Per-period constants of the checks and the servo (see _set_period).
        self._soft_min = config.soft_limit_min
        self._soft_max = config.soft_limit_max
        self._following_limit = config.following_error_limit
        self._following_warning = config.following_error_warning
        self._dt = 0.0
        self._max_step = self._step_slack = 0.0
        self._lag_gain = 1.0
        self._stream_dt = None  # _dt for an ideal axis (no servo lag), else None: MotionTask.process
        # The motion task's epoch in which this axis last took a sync stream's step, while
        # nothing has changed it since but that step's data (MotionTask.process); every
        # method that changes the axis ends it (`_changed`), and with it the task's stamp.
        self._streamed_in = None
        self._task_stamp = StreamStamp()     # the axis's own until a motion task shares one
        # MC_SyncMoveAbsolute's InPosition window (its hot path), made once: no negation a call.
        self._in_position_range = config.in_position_range
        self._in_position_floor = -config.in_position_range

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

    @property
    def decelerating_for_error(self) -> bool:
        """In ErrorStop with the command still moving (error_deceleration > 0)."""
        return self.state == AxisState.ERRORSTOP and self.cmd_vel != 0.0

    @property
    def idle(self) -> bool:
        """Details.Idle: no command value is being produced (and no move waits
        for in-position)."""
        command = self.command
        busy = command is not None and not command.done and not command.reached
        return not (busy or self.in_pos_waiting or self.decelerating_for_error)

    # ------------------------------------------------ requests from FBs
    @property
    def _stream_epoch(self):
        """The motion task's epoch in which this axis last took a sync stream's step (None
        once anything else may have changed it)."""
        return self._streamed_in

    @_stream_epoch.setter
    def _stream_epoch(self, epoch) -> None:
        """Ended (None) also for the task's stamp; MC_Power's hot path ends it so."""
        if epoch is None:
            self._task_stamp.epoch = None
        self._streamed_in = epoch

    def _changed(self) -> None:
        """Something beyond a sync stream's step may change: the next step checks it all."""
        self._task_stamp.epoch = self._streamed_in = None

    def request_power(self, on: bool) -> None:
        """MC_Power's Enable; applied by the next motion processing."""
        self._changed()
        self.power_requested = bool(on)

    def start_sync(self) -> MotionCommand:
        """MC_SyncMoveAbsolute: the axis follows Position every period, in
        Status.Discrete (SPEC 7)."""
        self._changed()
        self._check_can_move()
        command = MotionCommand("sync", target=self.cmd_pos)
        self._take(command, AxisState.DISCRETE)
        return command

    def start_move_absolute(
        self, position: float, velocity: float, acceleration: float, deceleration: float
    ) -> MotionCommand:
        """MC_MoveAbsolute: trapezoidal move to `position`."""
        self._changed()
        self._check_can_move()
        limit = self.config.max_velocity * (1 + _LIMIT_SLACK)
        if not (math.isfinite(position) and 0 < velocity <= limit):
            raise MotionRefused(ErrorID.PARAMETER_OUT_OF_RANGE)
        acc = self._rate(acceleration)
        dec = self._rate(deceleration)
        beyond = self._soft_limit_code(position)
        if beyond is not None:
            self.fault(beyond)
            raise MotionRefused(beyond)
        command = MotionCommand("move", target=position, velocity=velocity,
                                acceleration=acc, deceleration=dec)
        self._take(command, AxisState.DISCRETE)
        return command

    def start_stop(self, deceleration: float) -> MotionCommand:
        """MC_Stop: decelerate to zero velocity, then hold the axis in Stopping.

        Deceleration = 0, or an axis under MC_SyncMoveAbsolute, is an
        immediate stop: the command position holds where it is (SPEC 7).
        """
        self._changed()
        if self.state == AxisState.ERRORSTOP:
            raise MotionAborted()
        if not self.powered:
            raise MotionRefused(ErrorID.AXIS_DISABLED)
        if not (math.isfinite(deceleration) and deceleration >= 0):
            raise MotionRefused(ErrorID.PARAMETER_OUT_OF_RANGE)
        under_sync = self.command is not None and self.command.kind == "sync"
        rate = math.inf if deceleration == 0 or under_sync else deceleration
        command = MotionCommand("stop", deceleration=rate)
        self._take(command, AxisState.STOPPING)
        return command

    def release_stop(self, command: MotionCommand) -> None:
        """MC_Stop's Execute fell: leave Stopping for Standstill once stopped."""
        self._changed()
        command.released = True
        if command is self.command and command.done:
            self._finish(AxisState.STANDSTILL)

    def start_home(self) -> MotionCommand:
        """MC_Home for an absolute encoder: no motion, the axis becomes homed."""
        self._changed()
        self._check_can_move()
        if self.state != AxisState.STANDSTILL:
            raise MotionRefused(ErrorID.AXIS_MOVING)
        command = MotionCommand("home", target=self.cmd_pos)
        self._take(command, AxisState.HOMING)
        return command

    def reset(self) -> bool:
        """MC_Reset: clear the axis error and observation.  False (Failure)
        while the command still decelerates for the error (SPEC 7), or while
        the following error is still above its limit (the simulator's own
        rule: the error would come back at once)."""
        self._changed()
        if self.state != AxisState.ERRORSTOP:
            self.observation_code = ErrorID.NONE
            return True
        if self.cmd_vel != 0.0:
            return False
        limit = self.config.following_error_limit
        if limit > 0 and abs(self.following_error) > limit:
            return False
        self.fault_code = self.observation_code = ErrorID.NONE
        self.state = AxisState.STANDSTILL if self.powered else AxisState.DISABLED
        return True

    def fault(self, code: ErrorID) -> None:
        """Enter ErrorStop with `code` (the first fault's code is kept).

        The command stops at once, or decelerates at `error_deceleration`."""
        self._changed()
        if self.state == AxisState.ERRORSTOP:
            return
        self._abort_command()
        self.state = AxisState.ERRORSTOP
        self.fault_code = code
        if self.config.error_deceleration <= 0:
            self.cmd_vel = 0.0

    # --------------------------------------------------- motion processing
    def step(self, dt: float) -> None:
        """Advance one period of `dt` seconds: command, servo, checks.

        (The motion task spells out the common case, an ideal axis following a
        sync Position within one period's reach: `MotionTask.process`.)
        """
        self._task_stamp.epoch = self._streamed_in = None    # _changed(), without the call
        if self.power_requested != self.powered:
            self._apply_power()
        if not self.powered:
            # Servo off: nothing drives the axis; the command follows the actual position.
            self.cmd_pos = self.act_pos
            self.cmd_vel = self.act_vel = self.cmd_accdec = 0.0
            self.vel_limit = False
            return
        if dt != self._dt:
            self._set_period(dt)
        command = self.command
        old_cmd, old_act, old_vel = self.cmd_pos, self.act_pos, self.cmd_vel
        if command is None:
            new_cmd = self._error_stop_position(dt) if self.state == AxisState.ERRORSTOP else old_cmd
        elif command.kind == "sync":
            target = command.target     # _sync_position's first case, inlined (every scan)
            slack = self._step_slack
            if -slack <= target - old_cmd <= slack and self._soft_min <= target <= self._soft_max:
                self.vel_limit = False
                new_cmd = target
            else:
                new_cmd = self._sync_position(target, old_cmd, dt)
        else:
            new_cmd = self._next_command_position(dt)
            if new_cmd != old_cmd:
                new_cmd = self._checked(new_cmd, old_cmd, dt)
        self.cmd_pos = new_cmd
        self.cmd_vel = new_vel = (new_cmd - old_cmd) / dt
        if new_vel != old_vel:
            magnitude = abs(new_vel - old_vel) / dt
            self.cmd_accdec = magnitude if abs(new_vel) > abs(old_vel) else -magnitude
        else:
            self.cmd_accdec = 0.0
        if self._lag_gain == 1.0:
            self.act_pos = new_cmd  # ideal axis: exactly the command
        else:
            self.act_pos = old_act + (new_cmd - old_act) * self._lag_gain
        self.act_vel = (self.act_pos - old_act) / dt
        deviation = abs(new_cmd - self.act_pos)
        limit = self._following_limit
        if limit > 0 and deviation > limit:
            self.fault(ErrorID.FOLLOWING_ERROR_EXCEEDED)
        warning = self._following_warning
        if warning > 0 and deviation > warning and self.observation_code == ErrorID.NONE:
            self.observation_code = ErrorID.FOLLOWING_ERROR_WARNING
        if self.command is not None and self.command.reached:
            self._complete_commands(dt)

    def _sync_position(self, target: float, old_cmd: float, dt: float) -> float:
        """This period's command for a sync Position: the target, or one
        maximum-velocity step towards it (Details.VelLimit)."""
        delta = target - old_cmd
        if -self._step_slack <= delta <= self._step_slack and self._soft_min <= target <= self._soft_max:
            self.vel_limit = False
            return target
        refusal = self._target_code(target)
        if refusal is not None:
            self.fault(refusal)
            return self._error_stop_position(dt)
        if -self._step_slack <= delta <= self._step_slack:
            self.vel_limit = False
            return target
        self.vel_limit = True
        return old_cmd + math.copysign(self._max_step, delta)

    def _checked(self, new_cmd: float, old_cmd: float, dt: float) -> float:
        """`new_cmd` if it passes every check, else fault and stop."""
        refusal = self._target_code(new_cmd)
        if refusal is None:
            return new_cmd
        self.fault(refusal)
        return self._error_stop_position(dt)

    def _error_stop_position(self, dt: float) -> float:
        """The command in ErrorStop: held, or one step of `error_deceleration`
        less speed in the direction it was moving."""
        rate = self.config.error_deceleration
        speed = abs(self.cmd_vel)
        if rate <= 0 or speed == 0.0:
            return self.cmd_pos
        new_speed = max(speed - rate * dt, 0.0)
        return self.cmd_pos + math.copysign(new_speed * dt, self.cmd_vel)

    def _set_period(self, dt: float) -> None:
        """Cache what the checks and the servo need for periods of `dt`."""
        cfg = self.config
        self._dt = dt
        self._max_step = cfg.max_velocity * dt
        self._step_slack = self._max_step * (1 + _LIMIT_SLACK)
        tau = cfg.servo_lag
        self._lag_gain = 1.0 if tau == 0 else 1.0 - math.exp(-dt / tau)
        self._stream_dt = dt if self._lag_gain == 1.0 and _bounded_step_velocity(self._step_slack, dt) else None

    # ------------------------------------------------------------ internals
    def _check_can_move(self) -> None:
        if self.state in (AxisState.ERRORSTOP, AxisState.STOPPING):
            raise MotionAborted()
        if not self.powered:
            raise MotionRefused(ErrorID.AXIS_DISABLED)

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
        self.vel_limit = self.in_pos_waiting = False

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

    def _target_code(self, position: float) -> ErrorID | None:
        """Why a command position may not be applied, or None."""
        if not math.isfinite(position):
            return ErrorID.COMMAND_NOT_FINITE
        return self._soft_limit_code(position)

    def _soft_limit_code(self, position: float) -> ErrorID | None:
        if position > self.config.soft_limit_max:
            return ErrorID.TARGET_POSITIVE_SOFT_LIMIT
        if position < self.config.soft_limit_min:
            return ErrorID.TARGET_NEGATIVE_SOFT_LIMIT
        return None

    def _complete_commands(self, dt: float) -> None:
        c = self.command
        if c.kind == "move":
            if abs(self.act_pos - c.target) <= self.config.in_position_range:
                self.in_pos_waiting = False
                self._in_pos_wait_s = 0.0
                self._finish(AxisState.STANDSTILL)
                return
            # Reached, waiting for in-position (Details.InPosWaiting); error
            # 16#6447 once that takes longer than the in-position check time.
            self._in_pos_wait_s = self._in_pos_wait_s + dt if self.in_pos_waiting else dt
            self.in_pos_waiting = True
            check = self.config.in_position_check_time
            if check > 0 and self._in_pos_wait_s > check * (1 + _LIMIT_SLACK):
                self.fault(ErrorID.IN_POSITION_CHECK_TIME_EXCEEDED)
        elif c.kind == "stop":
            c.done = True
            if c.released:
                self._finish(AxisState.STANDSTILL)
        elif c.kind == "home":
            self.homed = True
            self._finish(AxisState.STANDSTILL)
