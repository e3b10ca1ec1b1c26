"""PLCopen / OMRON NJ motion FBs as native FBs on the simulated axes.

Interfaces follow the NJ motion control instructions (W508): `Axis` is a
VAR_IN_OUT AXIS_REF, `ErrorID` a WORD (codes in `error_ids`).  The FB finds
its simulated axis through `Axis.Cfg.AxNo` in the controller's motion task
(`motion_task.motion_of(ctx)`); an AXIS_REF that is not bound to a configured axis gives
`Error` with AXIS_NOT_ASSIGNED.

Execute-type FBs follow the PLCopen output rules:
* a rising edge of `Execute` starts the command (a new rising edge while Busy
  restarts it with the new inputs);
* `Busy` is TRUE while the command runs; exactly one of `Done`, `Error`,
  `CommandAborted` (or MC_Reset's `Failure`) ends it;
* that final output is held while `Execute` stays TRUE and is reset when it
  falls; if `Execute` fell before the end, it is TRUE for one call only;
* the command goes on after `Execute` falls (MC_SyncMoveAbsolute keeps
  taking `Position` every call until it is aborted).

An axis error (ErrorStop) during a command ends it with `CommandAborted`; the
cause is on the axis (`MFaultLvl.Code`).  A command started while the axis has
an error or while MC_Stop holds it ends with `CommandAborted` too, not with
`Error` (SPEC 7, documented for MC_SyncMoveAbsolute; the simulator applies it
to every motion FB).  Inputs that the simulation does not
model are accepted and ignored: `Jerk` (profiles are trapezoidal) and
`Direction` (linear axes).  `BufferMode` must be `_mcAborting`.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..native import NativeFB, RestTest, fb_declaration, native_fb
from . import binding
from . import types as _types  # noqa: F401  (registers AXIS_REF before the FBs)
from .axis import Axis, MotionAborted, MotionCommand, MotionRefused
from .error_ids import ErrorID
from .generated import define
from .motion_task import motion_of
from .types import BUFFER_MODE_ABORTING


def resolve_axis(ref, ctx) -> Axis | None:
    """The simulated axis an AXIS_REF value stands for, or None if unbound."""
    motion = motion_of(ctx)
    if ref is None or motion is None or not ref.v_CFG.v_AXENABLE:
        return None
    return motion.axis_by_number(ref.v_CFG.v_AXNO)


_UNBOUND = object()  # `_AxisFB._bound_ref` while no AXIS_REF value is resolved


class _AxisFB(NativeFB):
    """A native FB with an `Axis` in-out; remembers which axis it resolved (`binding`)."""

    def __init__(self) -> None:
        super().__init__()
        # The AXIS_REF value last resolved and its axis, while `binding.hold` watches its Cfg.
        self._bound_ref, self._bound_axis = _UNBOUND, None

    def _axis(self, ctx) -> Axis | None:
        ref = self.v_AXIS
        if ref is self._bound_ref:
            return self._bound_axis
        axis = resolve_axis(ref, ctx)
        if axis is not None and binding.hold(self, ref):
            self._bound_ref, self._bound_axis = ref, axis
        else:
            self.end_binding()
        return axis

    def end_binding(self) -> None:
        """Resolve the axis again at the next call (its AXIS_REF's Cfg was written)."""
        self._bound_ref, self._bound_axis = _UNBOUND, None


# `_AxisFB._axis`'s cached case as an expression: the AXIS_REF is the one resolved before.
_BOUND = "{fb}.v_AXIS is {fb}._bound_ref"

# An LREAL input's value `{0}` as a Python float: itself when it is one (`_type`, the compiled
# code's `type`: a call CPython 3.11 specialises, where the load of `x.__class__` is not).
_AS_FLOAT = "{0} if _type({0}) is float else float({0})"

# An axis FB's `execute`, spelt out from its HotPath (`{pre}`: `True` when it has none).
_HOT_EXECUTE = """
def execute(self, ctx):
    if {pre}:
        if {bound}:
            axis = self._bound_axis
        else:
            axis = self._axis(ctx)
        if axis is not None:
{body}
            return
    self.{cold}(ctx)
"""


@dataclass(frozen=True)
class HotPath:
    """The call of most scans of an axis FB, as Python source: the FB's own `execute` is
    built from it, and the compiled caller puts it in place of the call (`NativeFB.HOT_PATH`,
    under the `inline` pass), which saves a Python call per FB and scan.

    When `pre` holds (no `pre`: always) and the FB's AXIS_REF is the one it resolved before,
    `body` is the whole call, with `{axis}` its axis and `{fb}` the instance; else `execute`
    resolves the axis (`_AxisFB._axis`) and runs `body` with it, or calls method `cold` when
    `pre` fails or no axis is found.  `pre` and the test of the binding only read.
    `temps`: the other names the source uses (locals of the caller, one set per call site).
    `floats`: (temp, input) pairs, an LREAL input the body reads into that temp and needs as a
    Python float, as `{<temp>_float}`: the temp itself where the call site has just stored the
    input as a float (`inline`'s `floats`), else `_type(t) is float` tests it (`_AS_FLOAT`).
    """

    pre: str
    body: tuple[str, ...]
    temps: tuple[str, ...]
    cold: str
    floats: tuple[tuple[str, str], ...] = ()

    def inline(self, fb: str, temp, floats: frozenset[str] = frozenset()) -> tuple[str, list[str]]:
        """(test, statements) of the call of `fb` (a Python name), new locals from `temp()`;
        `floats`: the inputs (attribute names) the call site stored as Python floats."""
        names = {"fb": fb, "axis": temp(), **{name: temp() for name in self.temps}}
        names.update(self._as_floats(names, floats))
        test = " and ".join(part for part in (self.pre, _BOUND) if part).format(**names)
        return test, [f"{names['axis']} = {fb}._bound_axis"] + [line.format(**names) for line in self.body]

    def _as_floats(self, names: dict[str, str], floats: frozenset[str]) -> dict[str, str]:
        """`{<temp>_float}` of each of `self.floats`, the temps named as in `names`."""
        return {f"{name}_float": names[name] if attribute in floats else _AS_FLOAT.format(names[name])
                for name, attribute in self.floats}

    def install(self, cls) -> None:
        """`cls.execute` from this path."""
        names = {"fb": "self", "axis": "axis", **{name: name for name in self.temps}}
        names.update(self._as_floats(names, frozenset()))
        body = "\n".join(" " * 12 + line.format(**names) for line in self.body)
        source = _HOT_EXECUTE.format(pre=(self.pre or "True").format(**names), bound=_BOUND.format(**names),
                                     body=body, cold=self.cold)
        cls.execute = define(source, f"{cls.__name__} hot path", {"_type": type})["execute"]   # (as compiled code names it)


class _ExecuteFB(_AxisFB):
    """Edge handling and exclusive final outputs shared by Execute-type FBs.

    Subclasses implement `_begin(axis)` (start the command and return it;
    raise MotionRefused to fail) and may implement `_poll(axis, command,
    first_call)` (called every call while the command runs) and
    `_after_call(axis, execute)`.
    """

    FINAL_OUTPUTS = ("v_DONE", "v_COMMANDABORTED", "v_ERROR")
    AFTER_CALL = False  # `_after_call` acts on a remembered command (MC_Stop)
    ACTIVE_OUTPUT = True  # the FB has an `Active` output
    ACTIVE_AT_START = True  # `Active` in the call of the rising edge (else one period later)

    def __init__(self) -> None:
        super().__init__()
        self._previous_execute = False
        self._command: MotionCommand | None = None
        self._at_rest = None    # the ScanContext.seal under which a caller found the FB at rest
        self._group_at_rest = None      # the same for its caller's group of sites (`RestTest.group`)

    def __init_subclass__(cls, **kwargs) -> None:
        super().__init_subclass__(**kwargs)
        _spell_out_idle_call(cls)

    def _run(self, ctx) -> None:
        """A call that is not idle (`execute`, `_IDLE_CALL`: the rules after the idle test)."""
        execute = bool(self.v_EXECUTE)
        axis = self._axis(ctx)
        if execute and not self._previous_execute:
            self._clear_outputs()
            self._start(axis)
        elif self.v_BUSY:
            self._follow(axis)
        self._previous_execute = execute
        self._after_call(axis, execute)

    def _start(self, axis: Axis | None) -> None:
        if axis is None:
            self._fail(ErrorID.AXIS_NOT_ASSIGNED)
            return
        try:
            self._command = self._begin(axis)
        except MotionRefused as refused:
            self._fail(refused.code)
            return
        except MotionAborted:
            self._command = None
            self._end("v_COMMANDABORTED")
            return
        self.v_BUSY = True
        if self.ACTIVE_OUTPUT and self.ACTIVE_AT_START:
            self.v_ACTIVE = True
        self._follow(axis, first_call=True)

    def _follow(self, axis: Axis | None, first_call: bool = False) -> None:
        command = self._command
        if axis is None or command is None or command.aborted:
            self._end("v_COMMANDABORTED")
        elif command.done:
            self._end("v_DONE")
        else:
            self._poll(axis, command, first_call)

    def _end(self, output: str) -> None:
        self.v_BUSY = False
        if self.ACTIVE_OUTPUT:
            self.v_ACTIVE = False
        setattr(self, output, True)

    def _fail(self, code: ErrorID) -> None:
        self._end("v_ERROR")
        self.v_ERRORID = int(code)

    def _clear_outputs(self) -> None:
        # Called every scan an idle FB is called: write only what is set (same state, fewer stores).
        if not self._final_shown():
            return
        for output in self.FINAL_OUTPUTS:
            if getattr(self, output):
                setattr(self, output, False)
        if self.v_ERRORID:
            self.v_ERRORID = 0

    # hooks
    def _begin(self, axis: Axis) -> MotionCommand:  # pragma: no cover - abstract
        raise NotImplementedError

    def _poll(self, axis: Axis, command: MotionCommand, first_call: bool) -> None:
        pass

    def _after_call(self, axis: Axis | None, execute: bool) -> None:
        pass


# An Execute FB's idle call (no Execute, not Busy: the call of most scans) and the test
# of its final outputs, spelt out from the class's FINAL_OUTPUTS: attribute loads in the
# call itself, no call of a helper (each costs more than the test; any() over an
# attrgetter five times the loads).  Held (or one-call) final outputs end; nothing starts
# or runs and `_after_call` has nothing to do, so the axis need not be looked up.  Every call
# forgets that a caller found the FB at rest (`_REST`).
_IDLE_CALL = """
def _final_shown(self):
    return {shown}

def _execute_rules(self, ctx):
    self._at_rest = None
    if not self.v_EXECUTE and not self.v_BUSY:
        if {shown}:
            self._clear_outputs()
        if self._command is None or not self.AFTER_CALL:
            self._previous_execute = False
            return
    self._run(ctx)
"""


# An idle Execute FB at rest: noted by its compiled caller under the controller's seal, which
# is new whenever code other than the scans' own may have stored into the FB (ScanContext.seal).
_REST = RestTest(awake="{fb}.v_EXECUTE or {fb}._at_rest is not _ctx.seal", note="{fb}._at_rest = _ctx.seal",
                 forget="{fb}._at_rest = None", unnoted="{fb}._at_rest is not _ctx.seal",
                 group="{fb}._group_at_rest")


def _spell_out_idle_call(cls) -> None:
    """`_final_shown` and `_execute_rules` of `cls` from `_IDLE_CALL`; `execute` is
    `_execute_rules` unless the class writes its own (which then calls it)."""
    outputs = (*cls.FINAL_OUTPUTS, "v_ERRORID")
    if not all(output.isidentifier() for output in outputs):
        raise ValueError(f"{cls.__name__}.FINAL_OUTPUTS: attribute names only, not {outputs!r}")
    shown = " or ".join(f"self.{output}" for output in outputs)
    namespace = define(_IDLE_CALL.format(shown=shown), f"{cls.__name__} idle call")   # names checked above
    cls._final_shown = namespace["_final_shown"]
    cls._execute_rules = namespace["_execute_rules"]
    if "execute" not in cls.__dict__:
        cls.execute = cls._execute_rules
    # The idle call changes nothing once its outputs are clear and the Execute it remembers is
    # FALSE (and, with `_after_call`, no command is left): the compiled caller tests that itself.
    rest = ("_previous_execute", *(("_command is not None",) if cls.AFTER_CALL else ()))
    cls.CALL_NEEDED = " or ".join("{fb}." + test for test in ("v_EXECUTE", "v_BUSY", *outputs, *rest))
    # Found at rest once (CALL_NEEDED false), the FB stays so until it is called (`_execute_rules`
    # forgets it) or until code other than the scans may have written it (a new seal).  Only
    # for a class whose calls all go through `_execute_rules` (not one with a HotPath).
    cls.REST = _REST if cls.HOT_PATH is None and cls.execute is cls._execute_rules else None


_spell_out_idle_call(_ExecuteFB)


# The outputs every command that moves the axis has after its own first one.
MOVE_OUTPUTS = "Busy : BOOL; Active : BOOL; CommandAborted : BOOL; Error : BOOL; ErrorID : WORD;"


def _axis_fb_declaration(name: str, inputs: str, outputs: str) -> str:
    """A motion FB's declaration: the axis by reference (VAR_IN_OUT Axis :
    AXIS_REF, as Sysmac declares it), then its inputs and outputs."""
    return fb_declaration(name, in_outs="Axis : AXIS_REF;", inputs=inputs, outputs=outputs)


def _check_buffer_mode(mode: int) -> None:
    if mode != BUFFER_MODE_ABORTING:
        raise MotionRefused(ErrorID.BUFFER_MODE_NOT_SUPPORTED)


@native_fb
class MC_Power(_AxisFB):
    """Servo on while `Enable` is TRUE; `Status` once the axis is powered.

    The servo switches at the motion processing after the call, so `Status`
    follows `Enable` one scan later; `Busy` is TRUE during that transition.
    """

    NAME = "MC_Power"
    DECLARATION = _axis_fb_declaration(
        "MC_Power",
        inputs="Enable : BOOL;",
        outputs="Status : BOOL; Busy : BOOL; Error : BOOL; ErrorID : WORD;")

    # Every scan of every axis: Status follows the servo, Busy while it switches.  The
    # request is stored only when it is not that bool already: a change ends the axis's
    # stream epoch as `Axis.request_power` does (the store of the same object changes nothing).
    # Busy is FALSE without the comparison when Powered is the very bool Enable is (a bool
    # equals itself): CPython 3.11 does not specialise a comparison of bools whose value is
    # stored, an identity test it runs at once.
    HOT_PATH = HotPath(
        pre="",
        body=("{enable} = True if {fb}.v_ENABLE else False",    # bool(), without the call
              "if {axis}.power_requested is not {enable}:",     # axis.request_power, inlined
              "    {axis}.power_requested = {enable}",
              "    {axis}._stream_epoch = None",
              "{powered} = {axis}.powered",
              "{fb}.v_STATUS = {powered}",
              "{fb}.v_BUSY = False if {enable} is {powered} else {enable} != {powered}",
              "{fb}.v_ERROR = False",
              "{fb}.v_ERRORID = 0"),
        temps=("enable", "powered"),
        cold="_unassigned")

    def _unassigned(self, ctx) -> None:
        """No axis for the AXIS_REF: Error while Enable is TRUE."""
        self.v_STATUS = self.v_BUSY = False
        self.v_ERROR = bool(self.v_ENABLE)
        self.v_ERRORID = int(ErrorID.AXIS_NOT_ASSIGNED) if self.v_ENABLE else 0


MC_Power.HOT_PATH.install(MC_Power)


@native_fb
class MC_Reset(_ExecuteFB):
    """Clear the axis error (ErrorStop -> Standstill if powered, else Disabled).

    Completes in the call of the rising edge.  `Failure` (ErrorID 0) while
    the axis still decelerates for its error (SPEC 7, OMRON's MC_Reset), or
    while the following error is still above its limit (the simulator's own
    rule).  Resetting an axis without error is Done and clears an observation
    (`Obsr`).
    """

    NAME = "MC_Reset"
    DECLARATION = _axis_fb_declaration(
        "MC_Reset",
        inputs="Execute : BOOL;",
        outputs="Done : BOOL; Busy : BOOL; Failure : BOOL; Error : BOOL; ErrorID : WORD;")
    FINAL_OUTPUTS = ("v_DONE", "v_FAILURE", "v_ERROR")
    ACTIVE_OUTPUT = False

    def _start(self, axis: Axis | None) -> None:
        if axis is None:
            self._fail(ErrorID.AXIS_NOT_ASSIGNED)
        elif axis.reset():
            self._end("v_DONE")
        else:
            self._end("v_FAILURE")


@native_fb
class MC_Home(_ExecuteFB):
    """Define home for an absolute encoder: no motion; Details.Homed TRUE.

    Done on the call after the motion processing that homed the axis.
    """

    NAME = "MC_Home"
    DECLARATION = _axis_fb_declaration(
        "MC_Home",
        inputs="Execute : BOOL;",
        outputs="Done : BOOL; Busy : BOOL; CommandAborted : BOOL; Error : BOOL; ErrorID : WORD;")
    ACTIVE_OUTPUT = False

    def _begin(self, axis: Axis) -> MotionCommand:
        return axis.start_home()


@native_fb
class MC_Stop(_ExecuteFB):
    """Decelerate to a stop and hold the axis in Stopping while Execute is TRUE.

    Aborts whatever moves the axis (that FB ends with CommandAborted).  `Done`
    once the command velocity is zero; when `Execute` is FALSE (and the axis
    has stopped) the axis goes to Standstill.  An immediate stop (the command
    position holds where it is) when Deceleration is 0 or when the axis is
    under MC_SyncMoveAbsolute, whose Deceleration is then ignored (SPEC 7,
    OMRON's MC_Stop): a controlled stop from synchronous motion must be ramped
    by the program first.  On an axis with an error: CommandAborted.
    """

    NAME = "MC_Stop"
    DECLARATION = _axis_fb_declaration(
        "MC_Stop",
        inputs="Execute : BOOL; Deceleration : LREAL; Jerk : LREAL; BufferMode : _eMC_BUFFER_MODE;",
        outputs="Done : BOOL; " + MOVE_OUTPUTS)

    def _begin(self, axis: Axis) -> MotionCommand:
        _check_buffer_mode(self.v_BUFFERMODE)
        return axis.start_stop(float(self.v_DECELERATION))

    AFTER_CALL = True

    def _after_call(self, axis: Axis | None, execute: bool) -> None:
        if not execute and self._command is not None and axis is not None:
            axis.release_stop(self._command)
            if self._command.done or self._command.aborted:
                self._command = None


@native_fb
class MC_MoveAbsolute(_ExecuteFB):
    """Trapezoidal positioning to `Position` at `Velocity` (> 0, <= axis max).

    Acceleration/Deceleration 0 use the axis's maximum acceleration (a
    velocity step if none is configured).  A Position outside the software
    limits is an Error (16#6440 above, 16#6441 below) and puts the axis in
    ErrorStop.  Done once the command is at the target and the actual
    position is within the in-position range.
    """

    NAME = "MC_MoveAbsolute"
    DECLARATION = _axis_fb_declaration(
        "MC_MoveAbsolute",
        inputs="Execute : BOOL; Position : LREAL; Velocity : LREAL; Acceleration : LREAL;"
               " Deceleration : LREAL; Jerk : LREAL; Direction : _eMC_DIRECTION;"
               " BufferMode : _eMC_BUFFER_MODE;",
        outputs="Done : BOOL; " + MOVE_OUTPUTS)

    def _begin(self, axis: Axis) -> MotionCommand:
        _check_buffer_mode(self.v_BUFFERMODE)
        return axis.start_move_absolute(
            float(self.v_POSITION), float(self.v_VELOCITY),
            float(self.v_ACCELERATION), float(self.v_DECELERATION),
        )


@native_fb
class MC_SyncMoveAbsolute(_ExecuteFB):
    """Cyclic synchronous absolute positioning: `Position` is the target of
    every period in which the FB is called, from the rising edge of Execute
    until another command (e.g. MC_Stop) or an axis error aborts it.  Never
    `Done`.  Follows OMRON's help page as summarised in SPEC 7:

    * the axis is in Status.Discrete while the FB drives it;
    * the Position given in scan k is the target of the motion processing of
      scan k; one too far for one period is not an error: the command moves at
      the axis maximum velocity, the rest follows in later periods, and
      Details.VelLimit is TRUE meanwhile (maximum acceleration/deceleration
      are not used);
    * `Busy` in the call of the rising edge, `Active` from the next call;
    * started while the axis has an error or MC_Stop holds it: CommandAborted;
    * a new rising edge while Busy: Error 16#543B (re-execution disabled), and
      (assumed) the axis goes to ErrorStop with that code;
    * `InPosition`: the actual position is within the in-position range of
      the target (the Position that motion processing worked to), not of the
      saturated Cmd.Pos.

    A Position beyond the software limits is an axis error, 16#6440/16#6441
    (assumed: no source found for what a streamed position raises).
    """

    NAME = "MC_SyncMoveAbsolute"
    DECLARATION = _axis_fb_declaration(
        "MC_SyncMoveAbsolute",
        inputs="Execute : BOOL; Position : LREAL; Direction : _eMC_DIRECTION; BufferMode : _eMC_BUFFER_MODE;",
        outputs="InPosition : BOOL; " + MOVE_OUTPUTS)
    FINAL_OUTPUTS = ("v_COMMANDABORTED", "v_ERROR")
    ACTIVE_AT_START = False

    def _begin(self, axis: Axis) -> MotionCommand:
        _check_buffer_mode(self.v_BUFFERMODE)
        return axis.start_sync()

    # The call of every scan while synchronized (no edge, command alive); everything else
    # goes through the general rules.  InPosition as `_poll` computes it, |d| <= range as
    # -range <= d <= range (the same answer for every float d and range > 0, NaN included;
    # the axis holds both bounds, made from its config once, so no float is made a call),
    # tested by jumps, which CPython 3.11 specialises (a comparison whose value is stored it
    # does not), without the call of abs() and its float; Position as a float (`floats`: no
    # test where the caller has just stored it as one).  With Execute TRUE, `pre` found the Execute the FB
    # remembers TRUE (the FB only ever stores a bool there): only a FALSE one is stored.
    HOT_PATH = HotPath(
        pre=("{fb}.v_BUSY and ({command} := {fb}._command) is not None and not {command}.aborted"
             " and ({fb}._previous_execute or not {fb}.v_EXECUTE)"),
        body=("if not {fb}.v_EXECUTE:",
              "    {fb}._previous_execute = False",
              "{fb}.v_ACTIVE = True",                         # _poll(axis, command, False), inlined
              "{fb}.v_INPOSITION = (True if {axis}._in_position_floor"
              " <= {axis}.act_pos - {command}.target <= {axis}._in_position_range else False)",
              "{position} = {fb}.v_POSITION",
              "{command}.target = {position_float}"),
        temps=("command", "position"),
        cold="_execute_rules",
        floats=(("position", "v_POSITION"),))

    def _start(self, axis: Axis | None) -> None:
        command = self._command
        if self.v_BUSY and command is not None and not command.aborted and axis is not None:
            self._fail(ErrorID.RE_EXECUTION_DISABLED)
            axis.fault(ErrorID.RE_EXECUTION_DISABLED)
            return
        super()._start(axis)

    def _poll(self, axis: Axis, command: MotionCommand, first_call: bool) -> None:
        if not first_call:
            self.v_ACTIVE = True
            self.v_INPOSITION = abs(axis.act_pos - command.target) <= axis.config.in_position_range
        command.target = float(self.v_POSITION)

    def _end(self, output: str) -> None:
        super()._end(output)
        self.v_INPOSITION = False


MC_SyncMoveAbsolute.HOT_PATH.install(MC_SyncMoveAbsolute)
