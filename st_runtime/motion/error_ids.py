"""ErrorIDs of the simulated axes and motion FBs: one table, one docstring each.

The codes are WORDs in the style of the OMRON NJ: instruction errors (bad
parameters, wrong axis state) in the 16#54xx range, axis errors detected by
motion processing (limits, following error) in the 16#64xx range.  They are
this simulator's own numbers, not OMRON's catalogue; what matters is that each
cause has its own stable code that ST can compare against.

An instruction error is reported on the FB (`Error`, `ErrorID`) and leaves the
axis as it was, except `TARGET_BEYOND_SOFT_LIMIT`, which also puts the axis in
ErrorStop (as a command beyond the software limits does on the NJ).  An axis
error puts the axis in ErrorStop with `MFaultLvl.Active` and `MFaultLvl.Code`;
the FB that was moving the axis ends with `CommandAborted`.
"""

from __future__ import annotations

from enum import IntEnum


class ErrorID(IntEnum):
    NONE = 0x0000
    """No error."""

    # --- instruction errors (reported on the FB) ---------------------------
    AXIS_NOT_ASSIGNED = 0x5401
    """The AXIS_REF given to the FB is not bound to a configured axis
    (`Cfg.AxEnable` is FALSE: e.g. a local AXIS_REF variable)."""

    AXIS_DISABLED = 0x5402
    """A motion FB was started on an axis whose servo is off (Disabled)."""

    AXIS_IN_ERRORSTOP = 0x5403
    """A motion FB was started while the axis is in ErrorStop; MC_Reset first."""

    AXIS_STOPPING = 0x5404
    """A motion FB was started while MC_Stop holds the axis (state Stopping)."""

    AXIS_MOVING = 0x5405
    """MC_Home was started while the axis is moving (it needs Standstill)."""

    PARAMETER_OUT_OF_RANGE = 0x5410
    """A numeric input is out of range: Velocity <= 0 or above the axis
    maximum, a negative Acceleration/Deceleration, or a value that is not
    finite."""

    BUFFER_MODE_NOT_SUPPORTED = 0x5411
    """BufferMode other than _mcAborting (the only mode simulated)."""

    TARGET_BEYOND_SOFT_LIMIT = 0x5412
    """MC_MoveAbsolute target position outside the software limits; the
    axis also goes to ErrorStop with this code."""

    RESET_FAILED = 0x5420
    """MC_Reset could not clear the error because its cause persists (the
    following error is still above its limit)."""

    # --- axis errors (motion processing; axis -> ErrorStop) ----------------
    SOFT_LIMIT_EXCEEDED = 0x6401
    """The command position (e.g. the Position of MC_SyncMoveAbsolute) lies
    outside the software limits; the command is not applied."""

    VELOCITY_LIMIT_EXCEEDED = 0x6402
    """The command position moved by more than max velocity x period in one
    scan (|dPos| / period > max velocity); the command is not applied."""

    ACCELERATION_LIMIT_EXCEEDED = 0x6403
    """The command velocity changed by more than max acceleration x period
    in one scan (checked for synchronized motion when a maximum acceleration
    is configured); the command is not applied."""

    FOLLOWING_ERROR_EXCEEDED = 0x6404
    """|command position - actual position| exceeds the following-error
    limit after the servo has moved."""

    COMMAND_NOT_FINITE = 0x6405
    """The command position is NaN or infinite; the command is not applied."""


def describe(code: int) -> str:
    """One line for a code: its name and its docstring."""
    try:
        member = ErrorID(code)
    except ValueError:
        return f"16#{code:04X}: unknown ErrorID"
    return f"16#{code:04X} {member.name}: {_DOCS[member]}"


# Enum members do not keep their docstrings; read them from the source once.
def _member_docs() -> dict[ErrorID, str]:
    import ast
    import inspect

    tree = ast.parse(inspect.getsource(ErrorID))
    docs: dict[ErrorID, str] = {}
    body = tree.body[0].body
    for stmt, following in zip(body, body[1:] + [None]):
        if isinstance(stmt, ast.Assign) and isinstance(following, ast.Expr):
            name = stmt.targets[0].id
            text = following.value.value
            docs[ErrorID[name]] = " ".join(text.split())
    return docs


_DOCS = _member_docs()

