"""The axis variable type ST sees: `AXIS_REF`, declared as ST TYPE text.

Members are those of OMRON's NJ axis variable (`_sAXIS_REF`) that the
simulator can confirm, and no others: a program that uses a member the NJ does
not have fails the checker here as it fails Build in Sysmac Studio (there is
no `Dev` member: the following error is `Cmd.Pos - Act.Pos`).  The member type
names drop OMRON's leading underscore, which the NJ forbids in user
identifiers.  The motion task writes the members (feedback in before the
programs, and again after motion processing); ST only reads them.

Sources (docs/nj501.md, "OMRON's motion kernel"):
* member lists of Status, Details, DrvStatus and the event structure
  (`_sMC_REF_EVENT`: Active, Code WORD) as Sysmac data types: GitHub code index
  file id 48709232398;
* the whole axis variable member by member (Cfg, Scale, Status, Details, Dir,
  DrvStatus, Cmd, Act, MFaultLvl) in a public OPC UA client for NJ/NX axes:
  GitHub code index file id 36696277754;
* Cmd members and meanings (Pos, Vel, AccDec with its sign rule, Jerk, Trq):
  W507 p.6-28, https://easymanua.ls/omron/nx701-1/manual?p=180.
* `Obsr` (axis observation, e.g. 16#644C): not found in the two public lists;
  kept, not refused, because OMRON has observation-level axis events and the
  common motion variable has `_MC_COM.Obsr.Active` in a real Sysmac project
  (GitHub code index file id 59319135740).  Unconfirmed.

Left out because their types are not confirmed: `Cfg.AxType`, `Scale.Units`,
`Scale.CountMode` (OMRON enumerations).  `Cfg.AxEnable` is a BOOL here; on the
NJ it may be an enumeration (unconfirmed).

    Axis.Cmd.Pos / .Vel / .AccDec       command position / velocity / acc.-dec.
    Axis.Act.Pos / .Vel                 actual position / velocity
    Axis.Status.Disabled ... .Homing    PLCopen state, exactly one TRUE
                                        (.Ready: the same as .Standstill, W508 2-1-2)
    Axis.Details.Idle / .InPosWaiting / .Homed / .VelLimit
    Axis.Dir.Posi / .Nega               command velocity direction
    Axis.DrvStatus.ServoOn / .Ready / .MainPower
    Axis.MFaultLvl.Active / .Code       axis error (ErrorStop) and its ErrorID
    Axis.Obsr.Active / .Code            axis observation (no stop)
    Axis.Cfg.AxNo / Axis.Cfg.AxEnable   which simulated axis this variable is
                                        (AxEnable FALSE: not bound to any axis)

Members the simulation does not model hold 0/FALSE: Cmd.Jerk, Cmd.Trq,
Act.Trq, Act.TimeStamp, Details.InHome, Status.Coordinated, the drive inputs.

Also the enumerations of the motion FB inputs, with OMRON's names:
`_eMC_BUFFER_MODE` and `_eMC_DIRECTION`.
"""

from __future__ import annotations

from ..native import mangle, native_types
from .axis import Axis, AxisState

AXIS_REF_SOURCE = """
TYPE
    AXIS_REF_STA : STRUCT
        Ready : BOOL;
        Disabled : BOOL;
        Standstill : BOOL;
        Discrete : BOOL;
        Continuous : BOOL;
        Synchronized : BOOL;
        Homing : BOOL;
        Stopping : BOOL;
        ErrorStop : BOOL;
        Coordinated : BOOL;
    END_STRUCT;
    AXIS_REF_DET : STRUCT
        Idle : BOOL;
        InPosWaiting : BOOL;
        Homed : BOOL;
        InHome : BOOL;
        VelLimit : BOOL;
    END_STRUCT;
    AXIS_REF_DIR : STRUCT
        Posi : BOOL;
        Nega : BOOL;
    END_STRUCT;
    AXIS_REF_STA_DRV : STRUCT
        ServoOn : BOOL;
        Ready : BOOL;
        MainPower : BOOL;
        P_OT : BOOL;
        N_OT : BOOL;
        HomeSw : BOOL;
        Home : BOOL;
        ImdStop : BOOL;
        Latch1 : BOOL;
        Latch2 : BOOL;
        DrvAlarm : BOOL;
        DrvWarning : BOOL;
        ILA : BOOL;
        CSP : BOOL;
        CSV : BOOL;
        CST : BOOL;
    END_STRUCT;
    AXIS_REF_CMD_DATA : STRUCT
        Pos : LREAL;
        Vel : LREAL;
        AccDec : LREAL;
        Jerk : LREAL;
        Trq : LREAL;
    END_STRUCT;
    AXIS_REF_ACT_DATA : STRUCT
        Pos : LREAL;
        Vel : LREAL;
        Trq : LREAL;
        TimeStamp : ULINT;
    END_STRUCT;
    MC_REF_EVENT : STRUCT
        Active : BOOL;
        Code : WORD;
    END_STRUCT;
    AXIS_REF_CFG : STRUCT
        AxNo : UINT;
        AxEnable : BOOL;
        NodeAddress : UINT;
    END_STRUCT;
    AXIS_REF_SCALE : STRUCT
        Num : UDINT;
        Den : LREAL;
        MaxPos : LREAL;
        MinPos : LREAL;
    END_STRUCT;
    AXIS_REF : STRUCT
        Cfg : AXIS_REF_CFG;
        Scale : AXIS_REF_SCALE;
        Status : AXIS_REF_STA;
        Details : AXIS_REF_DET;
        Dir : AXIS_REF_DIR;
        DrvStatus : AXIS_REF_STA_DRV;
        Cmd : AXIS_REF_CMD_DATA;
        Act : AXIS_REF_ACT_DATA;
        MFaultLvl : MC_REF_EVENT;
        Obsr : MC_REF_EVENT;
    END_STRUCT;
    _eMC_BUFFER_MODE : (_mcAborting := 0, _mcBuffered := 1, _mcBlendingLow := 2,
        _mcBlendingPrevious := 3, _mcBlendingNext := 4, _mcBlendingHigh := 5);
    _eMC_DIRECTION : (_mcPositiveDirection := 0, _mcShortestWay := 1,
        _mcNegativeDirection := 2, _mcCurrentDirection := 3, _mcNoDirection := 4);
END_TYPE
"""

native_types(AXIS_REF_SOURCE)

BUFFER_MODE_ABORTING = 0
_ERRORSTOP = AxisState.ERRORSTOP

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
    (struct identities never change) and rewrites the Status, Details, Dir,
    DrvStatus, MFaultLvl and Obsr members only when what they show changed.
    """

    __slots__ = ("axis", "ref", "_cmd", "_act", "_status", "_details", "_dir", "_drive",
                 "_fault", "_obsr", "_shown")

    def __init__(self, axis: Axis, ref):
        self.axis = axis
        self.ref = ref
        self._cmd, self._act = ref.v_CMD, ref.v_ACT
        self._status, self._details, self._dir = ref.v_STATUS, ref.v_DETAILS, ref.v_DIR
        self._drive, self._fault, self._obsr = ref.v_DRVSTATUS, ref.v_MFAULTLVL, ref.v_OBSR
        self._shown = None  # what the flag members showed when last written

    def write(self) -> None:
        axis = self.axis
        cmd = self._cmd
        cmd.v_POS = axis.cmd_pos
        cmd.v_VEL = velocity = axis.cmd_vel
        cmd.v_ACCDEC = axis.cmd_accdec
        act = self._act
        act.v_POS = axis.act_pos
        act.v_VEL = axis.act_vel
        # axis.idle, inlined (twice a scan for every axis) and ordered so that a running
        # command decides it at once; a bool whenever Axis keeps its flags bools
        command, state, waiting = axis.command, axis.state, axis.in_pos_waiting
        idle = ((command is None or command.done or command.reached) and not waiting
                and not (state == _ERRORSTOP and velocity != 0.0))
        shown = (state, axis.homed, axis.fault_code, axis.observation_code, axis.vel_limit,
                 waiting, idle, axis.powered, velocity > 0.0, velocity < 0.0)
        if shown != self._shown:
            self._shown = shown
            self._write_flags(axis, (velocity > 0.0) - (velocity < 0.0))

    def _write_flags(self, axis: Axis, direction: int) -> None:
        status = self._status
        for state, attr in _STATUS_ATTR.items():
            setattr(status, attr, state == axis.state)
        status.v_READY = axis.state == AxisState.STANDSTILL
        details = self._details
        details.v_IDLE = axis.idle
        details.v_INPOSWAITING = axis.in_pos_waiting
        details.v_HOMED = axis.homed
        details.v_VELLIMIT = axis.vel_limit
        self._dir.v_POSI = direction > 0
        self._dir.v_NEGA = direction < 0
        drive = self._drive
        drive.v_SERVOON = axis.powered
        drive.v_READY = drive.v_MAINPOWER = True
        self._fault.v_ACTIVE = axis.state == AxisState.ERRORSTOP
        self._fault.v_CODE = int(axis.fault_code)
        self._obsr.v_ACTIVE = axis.observation_code != 0
        self._obsr.v_CODE = int(axis.observation_code)
