"""The axis variable type ST sees: `AXIS_REF`, declared as ST TYPE text.

Members follow the OMRON NJ axis variable (`_sAXIS_REF`) for what a program
reads; the member type names drop OMRON's leading underscore, which the NJ
forbids in user identifiers.  The motion task writes the members (feedback in
before the programs, and again after motion processing); ST only reads them.

    Axis.Cmd.Pos / Axis.Cmd.Vel         command position / velocity
    Axis.Act.Pos / Axis.Act.Vel         actual position / velocity
    Axis.Dev.Pos                        following error (Cmd.Pos - Act.Pos)
    Axis.Status.Disabled ... .Homing    PLCopen state, exactly one TRUE
    Axis.Details.Homed                  home defined
    Axis.MFaultLvl.Active / .Code       axis error (ErrorStop) and its ErrorID
    Axis.Cfg.AxNo / Axis.Cfg.AxEnable   which simulated axis this variable is
                                        (AxEnable FALSE: not bound to any axis)

Also the enumerations of the motion FB inputs, with OMRON's names:
`_eMC_BUFFER_MODE` and `_eMC_DIRECTION`.
"""

from __future__ import annotations

from ..native import mangle, native_types
from .axis import Axis, AxisState

AXIS_REF_SOURCE = """
TYPE
    AXIS_REF_STA : STRUCT
        Disabled : BOOL;
        Standstill : BOOL;
        Discrete : BOOL;
        Continuous : BOOL;
        Synchronized : BOOL;
        Stopping : BOOL;
        ErrorStop : BOOL;
        Homing : BOOL;
    END_STRUCT;
    AXIS_REF_DET : STRUCT
        Homed : BOOL;
    END_STRUCT;
    AXIS_REF_CMD_DATA : STRUCT
        Pos : LREAL;
        Vel : LREAL;
    END_STRUCT;
    AXIS_REF_ACT_DATA : STRUCT
        Pos : LREAL;
        Vel : LREAL;
    END_STRUCT;
    AXIS_REF_DEV_DATA : STRUCT
        Pos : LREAL;
    END_STRUCT;
    MC_REF_EVENT : STRUCT
        Active : BOOL;
        Code : WORD;
    END_STRUCT;
    AXIS_REF_CFG : STRUCT
        AxNo : UINT;
        AxEnable : BOOL;
    END_STRUCT;
    AXIS_REF : STRUCT
        Status : AXIS_REF_STA;
        Details : AXIS_REF_DET;
        Cmd : AXIS_REF_CMD_DATA;
        Act : AXIS_REF_ACT_DATA;
        Dev : AXIS_REF_DEV_DATA;
        MFaultLvl : MC_REF_EVENT;
        Cfg : AXIS_REF_CFG;
    END_STRUCT;
    _eMC_BUFFER_MODE : (_mcAborting := 0, _mcBuffered := 1, _mcBlendingLow := 2,
        _mcBlendingPrevious := 3, _mcBlendingNext := 4, _mcBlendingHigh := 5);
    _eMC_DIRECTION : (_mcPositiveDirection := 0, _mcShortestWay := 1,
        _mcNegativeDirection := 2, _mcCurrentDirection := 3, _mcNoDirection := 4);
END_TYPE
"""

native_types(AXIS_REF_SOURCE)

BUFFER_MODE_ABORTING = 0

# AxisState -> the Status member that is TRUE in it.
_STATUS_ATTR = {
    AxisState.DISABLED: mangle("Disabled"),
    AxisState.STANDSTILL: mangle("Standstill"),
    AxisState.DISCRETE: mangle("Discrete"),
    AxisState.CONTINUOUS: mangle("Continuous"),
    AxisState.SYNCHRONIZED: mangle("Synchronized"),
    AxisState.STOPPING: mangle("Stopping"),
    AxisState.ERRORSTOP: mangle("ErrorStop"),
    AxisState.HOMING: mangle("Homing"),
}


def bind_axis_ref(ref, axis: Axis) -> "AxisRefWriter":
    """Mark an AXIS_REF struct value as the variable of `axis` and fill it."""
    ref.v_CFG.v_AXNO = axis.axis_no
    ref.v_CFG.v_AXENABLE = True
    writer = AxisRefWriter(axis, ref)
    writer.write()
    return writer


class AxisRefWriter:
    """Copies the simulation state of one axis into its AXIS_REF value.

    Runs twice per scan for every axis, so it keeps the member structs at hand
    (struct identities never change) and rewrites the Status, Details and
    MFaultLvl members only when the state, homing or fault code changed.
    """

    __slots__ = ("axis", "ref", "_cmd", "_act", "_dev", "_status", "_details", "_fault", "_shown")

    def __init__(self, axis: Axis, ref):
        self.axis = axis
        self.ref = ref
        self._cmd, self._act, self._dev = ref.v_CMD, ref.v_ACT, ref.v_DEV
        self._status, self._details, self._fault = ref.v_STATUS, ref.v_DETAILS, ref.v_MFAULTLVL
        self._shown = None  # (state, homed, fault code) last written

    def write(self) -> None:
        axis = self.axis
        cmd, act = self._cmd, self._act
        cmd.v_POS = axis.cmd_pos
        cmd.v_VEL = axis.cmd_vel
        act.v_POS = axis.act_pos
        act.v_VEL = axis.act_vel
        self._dev.v_POS = axis.cmd_pos - axis.act_pos
        shown = (axis.state, axis.homed, axis.fault_code)
        if shown != self._shown:
            self._shown = shown
            status = self._status
            for state, attr in _STATUS_ATTR.items():
                setattr(status, attr, state == axis.state)
            self._details.v_HOMED = axis.homed
            self._fault.v_ACTIVE = axis.state == AxisState.ERRORSTOP
            self._fault.v_CODE = int(axis.fault_code)
