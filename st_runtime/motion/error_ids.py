"""ErrorIDs of the simulated axes and motion FBs: one table, one docstring each.

On the NJ an ErrorID (and `MFaultLvl.Code`, `Obsr.Code`) is the upper four hex
digits of the event code: event 16#64480000 is ErrorID 16#6448.  Each member
says where its code comes from:

* **OMRON** -- the code and its meaning are OMRON's, with the source;
* **simulator's own** -- the simulator reports a case for which no OMRON code
  was found; the number is ours, kept stable so that ST can compare against it,
  and it may coincide with an unrelated OMRON code.  Do not rely on it on a
  real controller.

Sources (see docs/nj501.md, "OMRON's motion kernel"):

[W503] NJ-series Troubleshooting Manual (W503), event tables, as quoted with
       page numbers in a public event-code table (GitHub code index, file id
       59678352956: 16#644C0000 p.3-549, 16#64480000 p.3-527, 16#64470000
       p.3-526, 16#64410000 p.3-645); event classification (first digit 5: user
       software error, 6: observation of user settings), W503 p.1-11,
       https://www.easymanua.ls/omron/nj-series/manual/438985?p=37
[SPEC7] the project's summary of the Sysmac Studio help pages of
       MC_SyncMoveAbsolute, MC_Stop and MC_Reset (../shared/SPEC.md section 7).

An instruction error is reported on the FB (`Error`, `ErrorID`) and leaves the
axis as it was, except where a member says it also puts the axis in ErrorStop.
An axis error puts the axis in ErrorStop with `MFaultLvl.Active` and
`MFaultLvl.Code`; the FB that was moving the axis ends with `CommandAborted`.
An observation (`Obsr.Active`, `Obsr.Code`) does not stop the axis.
"""

from __future__ import annotations

import functools
from enum import IntEnum


class ErrorID(IntEnum):
    NONE = 0x0000
    """No error."""

    # --- instruction errors (reported on the FB) ---------------------------
    AXIS_NOT_ASSIGNED = 0x5401
    """Simulator's own: the AXIS_REF given to the FB is not bound to a
    configured axis (`Cfg.AxEnable` is FALSE: e.g. a local AXIS_REF
    variable).  Sysmac Studio only accepts axis variables there."""

    AXIS_DISABLED = 0x5402
    """Simulator's own: a motion FB was started on an axis whose servo is
    off (Disabled)."""

    AXIS_MOVING = 0x5405
    """Simulator's own: MC_Home was started while the axis is moving (the
    simulation homes an absolute encoder at standstill only)."""

    PARAMETER_OUT_OF_RANGE = 0x5410
    """Simulator's own: a numeric input is out of range: Velocity <= 0 or
    above the axis maximum, a negative Acceleration/Deceleration, or a value
    that is not finite."""

    BUFFER_MODE_NOT_SUPPORTED = 0x5411
    """Simulator's own: BufferMode other than _mcAborting (the only mode
    simulated)."""

    RE_EXECUTION_DISABLED = 0x543B
    """OMRON [SPEC7] (Motion Control Instruction Re-execution Disabled):
    a rising edge of Execute on an MC_SyncMoveAbsolute that is still Busy.
    Assumed (not confirmed): the axis also goes to ErrorStop with this code."""

    # --- axis errors (axis -> ErrorStop) ------------------------------------
    TARGET_POSITIVE_SOFT_LIMIT = 0x6440
    """OMRON (Target Position Positive Software Limit Exceeded; name by
    symmetry with 16#6441 [W503]): the target of MC_MoveAbsolute lies above
    the positive software limit (Error on the FB, axis in ErrorStop).  Assumed:
    also a Position of MC_SyncMoveAbsolute above the limit (the command is not
    applied); no source found for what a streamed position raises."""

    TARGET_NEGATIVE_SOFT_LIMIT = 0x6441
    """OMRON [W503 p.3-645] (Target Position Negative Software Limit
    Exceeded): as TARGET_POSITIVE_SOFT_LIMIT, below the negative limit."""

    IN_POSITION_CHECK_TIME_EXCEEDED = 0x6447
    """OMRON [W503 p.3-526] (In-position Check Time Exceeded): MC_MoveAbsolute
    reached its target but the actual position stayed outside the in-position
    range for longer than the in-position check time."""

    FOLLOWING_ERROR_EXCEEDED = 0x6448
    """OMRON [W503 p.3-527] (Following Error Limit Exceeded): |command
    position - actual position| exceeds the following-error limit."""

    COMMAND_NOT_FINITE = 0x6405
    """Simulator's own: the Position of MC_SyncMoveAbsolute is NaN or
    infinite (a REAL cannot hold it on the NJ); the command is not applied."""

    # --- observations (no stop) ---------------------------------------------
    FOLLOWING_ERROR_WARNING = 0x644C
    """OMRON [W503 p.3-549] (Following Error Warning), an observation:
    |command position - actual position| exceeds the following-error warning
    value.  The axis goes on; `Obsr.Active`/`Obsr.Code` show it until
    MC_Reset."""


def describe(code: int) -> str:
    """One line for a code: its name and its docstring."""
    try:
        member = ErrorID(code)
    except ValueError:
        return f"16#{code:04X}: unknown ErrorID"
    return f"16#{code:04X} {member.name}: {_member_docs()[member]}"


# Enum members do not keep their docstrings; read them from the source once,
# when first asked (not at import: `stgen check` never needs them).
@functools.cache
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
