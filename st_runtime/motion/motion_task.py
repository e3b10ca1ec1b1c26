"""The motion task: the controller's axes, as on the NJ.

Every primary period, around the user programs:

1. `feedback_in()` (before the programs) copies each axis's simulation state
   into its global AXIS_REF variable, so the programs read this period's
   Cmd/Act/Status (skipped where step 3 of the previous scan already wrote the
   same values: the next scan of one `Controller.run` call, with no observer
   but read-only ones and no other I/O hook that could have changed an axis
   in between);
2. the programs run; motion FBs start commands and hand over positions;
3. `process(dt)` (after the programs) advances every axis by one period
   (command, limit checks, servo lag, following error) and publishes the new
   state into the AXIS_REF variables again, so a trace or a JSON dump taken
   at the end of scan k shows the command of scan k.

The axes are declared from the configuration: `globals_source()` gives the ST
text `VAR_GLOBAL <name> : AXIS_REF; ... END_VAR` to load with the user's
files, and `bind(lookup)` ties each global variable to its simulation.
`install(controller)` does the binding and hooks the two stages into the
controller's scan; native motion FBs then reach the task through the scan
context (`motion_of(ctx)`: `ctx.controller.motion`).  Inside one `Controller.run`,
the scans after the first run as one loop fused with the two stages while the
controller keeps this shape (`steady_scans.py`).
"""

from __future__ import annotations

import textwrap
from typing import Callable, Iterable, Mapping

from .axis import Axis, AxisState, StreamStamp
from .axis_config import AxisConfig, axis_configs_from_tables, axis_configs_from_toml
from . import steady_scans
from .generated import define
from ..native import mangle
from .types import AxisRefWriter, bind_axis_ref

_ERRORSTOP = AxisState.ERRORSTOP


# `Axis.step` and `AxisRefWriter.write` of one axis (`{axis}`, its writer `{writer}`, its Cmd and
# Act structs `{cmd}` and `{act}`) in one period of `dt` s.  An ideal, powered axis following a
# sync Position within one period's reach (every scan of a stream) is spelt out as one: each
# value is stored in the axis and in its variable at once.  Anything else takes Axis.step and
# the writer.  The actual position becomes the command, so the deviation is 0.0 and neither
# following-error check can fire; nothing completes a sync command.  AxisRefWriter.write's
# flags test is spelt out with what this path knows: a command (so idle is decided by it),
# VelLimit FALSE, the axis powered.  |new_vel| > |old_vel| without two calls of abs(): a
# comparison does not see the sign of a NaN, so the negations give the same answer.  The signs
# against 0.0, not 0: the same answer, and CPython compares a float with a float much faster.
# The general step comes first: the guard's jumps to it are then short, and CPython 3.11
# specialises a comparison only when a short jump follows it (a jump past the stream's code
# takes an EXTENDED_ARG); a comparison that jumps, not one whose value is stored, likewise.
# So AccDec tests `new_vel == old_vel` (its short branch first), not `!=` with the long one
# first: the same branch for every pair of floats, NaN included.
#
# The epoch (`epoch`, see `_AFTER_PROGRAMS`): while an axis carries the epoch of
# the run it streams in, nothing but the stream's own step has changed it since it last took
# one (every Axis method that changes it, and MC_Power's changed request, end it).  So its
# command is still that sync command, powered as requested, the period the same, VelLimit
# FALSE, the actual position the command (so the actual velocity is the command's), and the
# flags members show what they showed then: the short step tests only the data (|delta| <=
# slack is -slack <= delta <= slack for every float), and the flags only when the direction
# changes (neither velocity is a NaN then: the target passed the guard).  While the
# direction holds, Axis.step's `magnitude if |new_vel| > |old_vel| else -magnitude`, with
# magnitude = |new_vel - old_vel| / dt, is (new_vel - old_vel) / dt when both are positive
# and (old_vel - new_vel) / dt when both are negative, bit for bit: where the two differ,
# IEEE rounding is symmetric in sign (fl(b - a) = -fl(a - b), fl(-x / dt) = -fl(x / dt)), and
# where they are equal the difference is +0.0 (x - x for a finite x), Axis.step's 0.0 for
# equal velocities: new_vel is finite, |delta| <= slack and slack / dt finite (an axis has a
# `_stream_dt` only then, Axis._set_period).  So the signs are tested first, the equality only
# after them (a stream's velocity seldom repeats): no call of abs(), no negation.
_LANE_RENEWAL = """\
{command_before}if {axis}._streamed_in is not epoch:
{command_inside}    if not ({command} is not None and {command}.kind == "sync" and (powered := {axis}.powered)
            and {axis}.power_requested == powered and dt == {axis}._stream_dt
            and {floor_read} <= (delta := (target := {command}.target) - {axis}.cmd_pos) <= {slack_read}
            and {axis}._soft_min <= target <= {axis}._soft_max):
        {axis}.step(dt)
        {writer}.write()
    else:
        {axis}.vel_limit = False
        {act}.v_VEL = {axis}.act_vel = (target - {axis}.act_pos) / dt
        {cmd}.v_POS = {act}.v_POS = {axis}.cmd_pos = {axis}.act_pos = target
        old_vel = {axis}.cmd_vel
        {cmd}.v_VEL = {axis}.cmd_vel = new_vel = delta / dt
        if new_vel == old_vel:
            {cmd}.v_ACCDEC = {axis}.cmd_accdec = 0.0
        else:
            magnitude = abs(new_vel - old_vel) / dt
            if (new_vel if new_vel >= 0.0 else -new_vel) > (old_vel if old_vel >= 0.0 else -old_vel):
                {cmd}.v_ACCDEC = {axis}.cmd_accdec = magnitude
            else:
                {cmd}.v_ACCDEC = {axis}.cmd_accdec = -magnitude
{flags}
el"""

# The short step of an axis that carries the epoch (after `_LANE_RENEWAL`'s `el`, or alone).
_LANE_SHORT = """\
if not ({short_test}
        and target >= {soft_min} and target <= {soft_max}):
    {axis}.step(dt)
    {writer}.write()
else:
    {cmd}.v_POS = {act}.v_POS = {axis}.cmd_pos = {axis}.act_pos = target
    old_vel = {axis}.cmd_vel
    {act}.v_VEL = {axis}.act_vel = {cmd}.v_VEL = {axis}.cmd_vel = new_vel = delta / dt
    if new_vel > 0.0 and old_vel > 0.0:
        {cmd}.v_ACCDEC = {axis}.cmd_accdec = (new_vel - old_vel) / dt
    elif new_vel < 0.0 and old_vel < 0.0:
        {cmd}.v_ACCDEC = {axis}.cmd_accdec = (old_vel - new_vel) / dt
    elif new_vel == old_vel:
        {cmd}.v_ACCDEC = {axis}.cmd_accdec = 0.0
    else:
        magnitude = abs(new_vel - old_vel) / dt
        if (new_vel if new_vel >= 0.0 else -new_vel) > (old_vel if old_vel >= 0.0 else -old_vel):
            {cmd}.v_ACCDEC = {axis}.cmd_accdec = magnitude
        else:
            {cmd}.v_ACCDEC = {axis}.cmd_accdec = -magnitude
{flags}
"""

# The flags of a stream's step, as AxisRefWriter.write decides them; the axis then carries
# the epoch.
_LANE_FLAGS = """\
{axis}._streamed_in = epoch
state, waiting = {axis}.state, {axis}.in_pos_waiting
idle = (({command}.done or {command}.reached) and not waiting
        and not (state == _ERRORSTOP and new_vel != 0.0))
shown = (state, {axis}.homed, {axis}.fault_code, {axis}.observation_code, False,
         waiting, idle, {axis}.powered, new_vel > 0.0, new_vel < 0.0)
if shown != {writer}._shown:
    {writer}._shown = shown
    {writer}._write_flags({axis}, (new_vel > 0.0) - (new_vel < 0.0))
"""

# The motion task's `after` hook: the lanes of every axis with the task's bookkeeping around
# them (MotionTask._after_programs), one Python call a scan.  The epoch goes on while the
# previous scan's motion processing ran in this run (`ctx.resumed`: no observer but read-only
# ones since) and found the task's own hooks the controller's only ones: then nothing but
# the programs and the feedback-in hook has run since.
_AFTER_PROGRAMS = """\
def after_programs(ctx{arguments}):
    if not (ctx.resumed and task._continuing):
        task._epoch = object()
    task._published = task._continuing = False
    dt = ctx.period_ns * 1e-9
    epoch = task._epoch
{body}    controller = ctx.controller
    task._published = published = (len(hooks := controller.before_hooks) == 1
                                   and len(controller.after_hooks) == 1)
    task._continuing = published and hooks[0] is task._before_hook

def process(dt, epoch{arguments}):
{body}"""


# The steady loop's copies of an axis's step slack, its negation, soft limits and command, read
# once a call (see `_straight_line_process`).
_LANE_CONSTANTS = ("slack{n}, soft_min{n}, soft_max{n} = axis{n}._step_slack, axis{n}._soft_min, axis{n}._soft_max\n"
                   "floor{n}, command{n} = -slack{n}, axis{n}.command\n")

# The short step's test of the data, as the `after` hook and `process` make it and as the
# steady loop does: -slack <= delta <= slack is |delta| <= slack for every float (a NaN or an
# infinity fails both), without the call of abs() and the float it makes.  Each bound (and
# each soft limit, `_LANE_SHORT`) is a comparison of its own, not a chain: the same answer for
# every float (a comparison has no side effect, a NaN fails both), and a chained comparison
# spends a SWAP and a COPY keeping its middle operand.
_SHORT_TEST = "abs(delta := (target := command.target) - {axis}.cmd_pos) <= {axis}._step_slack"
_STEADY_SHORT_TEST = "(delta := (target := command{n}.target) - {axis}.cmd_pos) <= slack{n} and delta >= floor{n}"


def _lane_step(parts: dict, renewal: bool = True, **names) -> str:
    """The lane step of one axis (`parts`: its names), with the `_LANE_FLAGS` of
    `names["command"]`: `_LANE_RENEWAL` and `_LANE_SHORT`, or (not `renewal`) the short step
    alone."""
    flags = textwrap.indent(_LANE_FLAGS.format(command=names["command"], **parts), " " * 8).rstrip("\n")
    template = _LANE_RENEWAL + _LANE_SHORT if renewal else _LANE_SHORT
    return template.format(flags=flags, **names, **parts)


def _steady_lanes(short: list[str], whole: list[str], axes: list[str]) -> str:
    """The steady loop's motion processing: while the task's stamp shows that every axis
    carries the epoch, the `short` steps alone (no test of an axis's epoch); else the `whole`
    lane steps, which stamp the task when every axis carries the epoch after them.  Exact: only
    here is the stamp set, after testing each axis, and whatever ends an axis's epoch ends the
    stamp too (Axis._changed, Axis.step, MC_Power's changed request through the axis's
    `_stream_epoch`); a short step that fails takes Axis.step, which ends both, so the next
    scan takes the whole lanes again."""
    if not axes:
        return ""
    stamped = " and ".join(f"{axis}._streamed_in is epoch" for axis in axes)
    return (f"if stamp.epoch is epoch:\n{textwrap.indent(''.join(short), '    ')}else:\n"
            f"{textwrap.indent(''.join(whole), '    ')}    if {stamped}:\n        stamp.epoch = epoch\n")


def _straight_line_process(task: "MotionTask", lanes: list[tuple], stamp: StreamStamp):
    """(`after` hook, `process(dt, epoch)`, the steady loop of `steady_scans`) for these lanes
    as straight-line code: the lane step of every axis in turn, the task, axes, writers and
    structs as the functions' constants (no loop, no unpacking).

    The steady loop, which runs the lanes scan after scan, keeps each axis's step slack (and
    its negation), soft limits and command in locals for the short step.  The soft limits only
    change as an axis is made.  The command changes only through Axis methods, the slack only
    with the period (`Axis._set_period`, inside `Axis.step`): both end the epoch, and the whole
    test that stamps an axis with the epoch reads them again.  So while the axis carries the
    epoch, its locals are what that test saw."""
    names, steps, steady, short, constants = {"task": task, "stamp": stamp}, [], [], [], []
    for number, lane in enumerate(lanes):
        parts = {role: f"{role}{number}" for role in ("axis", "writer", "cmd", "act")}
        names.update(zip(parts.values(), lane))
        axis, steady_command = parts["axis"], f"command{number}"
        steps.append(_lane_step(parts, command="command", command_before=f"command = {axis}.command\n",
                                command_inside="", floor_read=f"-(slack := {axis}._step_slack)",
                                slack_read="slack", short_test=_SHORT_TEST.format(axis=axis),
                                soft_min=f"{axis}._soft_min", soft_max=f"{axis}._soft_max"))
        steady_names = dict(command=steady_command, command_before="",
                            command_inside=f"    {steady_command} = {axis}.command\n",
                            floor_read=f"(floor{number} := -(slack{number} := {axis}._step_slack))",
                            slack_read=f"slack{number}", short_test=_STEADY_SHORT_TEST.format(axis=axis, n=number),
                            soft_min=f"soft_min{number}", soft_max=f"soft_max{number}")
        steady.append(_lane_step(parts, **steady_names))
        short.append(_lane_step(parts, renewal=False, **steady_names))
        constants.append(_LANE_CONSTANTS.format(n=number))
    arguments = "".join(f", {name}={name}" for name in names)
    body = "".join(textwrap.indent(step, "    ") for step in steps) or "    pass\n"
    lanes = _steady_lanes(short, steady, [f"axis{number}" for number in range(len(lanes))])
    loop, values = steady_scans.source("".join(constants), lanes, names)
    namespace = define(_AFTER_PROGRAMS.format(arguments=arguments, body=body) + loop, "motion task process",
                       {"_ERRORSTOP": _ERRORSTOP, **values})
    after = namespace["after_programs"]
    after.__qualname__ = "MotionTask._after_programs"     # as a fault in a hook names it
    return after, namespace["process"], namespace["steady_scans"]


def motion_of(ctx) -> "MotionTask | None":
    """The motion task of the controller running `ctx` (None if it has none).

    A context may carry the task itself (`ctx.motion`, e.g. a test bench) or
    reach it through its controller (`ctx.controller.motion`).
    """
    motion = getattr(ctx, "motion", None)
    if motion is None:
        motion = getattr(getattr(ctx, "controller", None), "motion", None)
    return motion


class MotionTask:
    def __init__(self, configs: Iterable[AxisConfig]):
        self.axes: list[Axis] = [Axis(config, number) for number, config in enumerate(configs)]
        self._by_name = {axis.name.upper(): axis for axis in self.axes}
        if len(self._by_name) != len(self.axes):
            raise ValueError("axis names must be unique (case-insensitive)")
        self._writers: list[AxisRefWriter] = []
        self._step_lanes = self._step_axes      # `process`: see bind
        self._after_programs = self._step_after_programs    # the `after` hook: see bind
        self._steady_scans = None                # a run's scans fused with the hooks: see bind
        self._before_hook = self._before_programs               # the `before` hook installed
        self._controller = None                 # the controller it is installed in
        # The axis variables show the axes as they are: the motion processing has published
        # them and no other hook runs in the scan (see _before_programs).
        self._published = False
        # New whenever code other than the programs' motion FBs may have changed an axis
        # since the previous motion processing (see `_AFTER_PROGRAMS`, `_LANE_RENEWAL`).
        self._epoch = object()
        self._continuing = False

    @classmethod
    def from_tables(cls, tables: Iterable[Mapping]) -> "MotionTask":
        """From axis tables as in a TOML `[[axis]]` list (validated)."""
        return cls(axis_configs_from_tables(tables))

    @classmethod
    def from_toml(cls, text: str) -> "MotionTask":
        """From TOML text with one `[[axis]]` table per axis (AxisConfigError if invalid)."""
        return cls(axis_configs_from_toml(text))

    # ---------------------------------------------------------------- lookup
    def axis(self, name: str) -> Axis:
        """The axis of a configured name (case-insensitive); KeyError if none."""
        return self._by_name[name.upper()]

    def axis_by_number(self, number: int) -> Axis | None:
        if 0 <= number < len(self.axes):
            return self.axes[number]
        return None

    # ----------------------------------------------------------- declaration
    def globals_source(self) -> str:
        """ST text declaring one global AXIS_REF per configured axis."""
        lines = ["VAR_GLOBAL"]
        for axis in self.axes:
            lines.append(f"    {axis.name} : AXIS_REF; (* axis {axis.axis_no} *)")
        lines.append("END_VAR")
        return "\n".join(lines) + "\n"

    def bind(self, lookup: Callable[[str], object]) -> None:
        """Tie each axis to its global AXIS_REF value; `lookup(name)` finds it."""
        self._writers = [bind_axis_ref(lookup(axis.name), axis) for axis in self.axes]
        # What `process` works with, per axis: the axis, its writer and the Cmd and Act structs.
        hook = self._after_programs
        stamp = StreamStamp()
        for axis in self.axes:
            axis._task_stamp = stamp
        self._after_programs, self._step_lanes, self._steady_scans = _straight_line_process(
            self, [(writer.axis, writer, writer._cmd, writer._act) for writer in self._writers], stamp)
        self._epoch = object()
        hooks = getattr(self._controller, "after_hooks", ())
        for index, registered in enumerate(hooks):     # bound again once installed
            if registered is hook:
                hooks[index] = self._after_programs

    def install(self, controller) -> None:
        """Bind to `controller`'s global axis variables and run in its scans.

        The globals must have been declared with `globals_source()` in the
        loaded program.  Feedback in becomes a `before` hook, motion processing
        an `after` hook (quiet: they write axes and AXIS_REF variables, no FB instance);
        the controller gets a `motion` attribute for the FBs.
        """
        if getattr(controller, "motion", None) is not None:
            raise ValueError("this controller already has a motion task")
        globals_object = controller.globals
        layout = getattr(type(globals_object), "_st_vars", {})
        for axis in self.axes:
            declared = layout.get(axis.name.upper())
            if declared is None or str(declared[1]).upper() != "AXIS_REF":
                found = "is not declared" if declared is None else f"is declared as {declared[1]}"
                raise ValueError(
                    f"axis {axis.name}: the global variable {axis.name} {found}; load"
                    " MotionTask.globals_source() with the program to declare it as AXIS_REF"
                )
        self.bind(lambda name: getattr(globals_object, mangle(name)))
        controller.motion = self
        self._controller = controller
        controller.add_io_hook(before=self._before_hook, after=self._after_programs, quiet=True)
        controller.steady_scans = self._offer_steady_scans

    def _offer_steady_scans(self, controller):
        """The run's scans fused with this task's hooks while the controller's shape allows
        (`steady_scans.offer`), else None."""
        return steady_scans.offer(self, controller)

    def _before_programs(self, ctx) -> None:
        """Feedback in, unless the axis variables already show the axes: the previous scan's
        motion processing published them, it is the only hook of the controller, and nothing
        has run since (`ctx.resumed`: the next scan of one `Controller.run`, no observer but
        read-only ones), so
        a second publication would store the same values (the programs run after it)."""
        published, self._published = self._published, False
        if published and ctx.resumed:
            return
        self.feedback_in()

    def _step_after_programs(self, ctx) -> None:
        """The `after` hook while no variables are bound (`bind` makes it straight-line code:
        `_AFTER_PROGRAMS`)."""
        self._published = False
        self._step_lanes(ctx.period_ns * 1e-9)
        controller = ctx.controller
        self._published = len(controller.before_hooks) == 1 and len(controller.after_hooks) == 1

    # ---------------------------------------------------------------- cycle
    def feedback_in(self) -> None:
        """Before the programs: the axis variables show the simulation state."""
        for writer in self._writers:
            writer.write()

    def process(self, dt: float) -> None:
        """After the programs: every axis advances one period of `dt` seconds and its
        variable shows the result (an axis and its variable at a time: neither step nor
        publication reads another axis; `_straight_line_process` once bound).  Called from
        outside a scan: a new epoch."""
        self._epoch = object()
        self._step_lanes(dt, self._epoch)

    def _step_axes(self, dt: float, epoch=None) -> None:
        """`process` while no variables are bound (bind: all or none)."""
        for axis in self.axes:
            axis.step(dt)
