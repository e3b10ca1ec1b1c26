"""Dialects as data: what each dialect refuses, and how it names standard FB pins.

The checker and the native prelude consult `DIALECTS[name]`; no other module
asks which dialect is active.  A reader can check every OMRON rule below
against its source (docs/nj501.md, "What Sysmac Studio builds", has one row
per rule with its test).

* `errors`: the NJ rule numbers (`E-NJ-<number>`) that are errors in this
  dialect; every other NJ rule is a warning (`W-NJ-<number>`): the code is
  valid IEC 61131-3 but Sysmac Studio would not build it.
* `pins`: standard FB -> {IEC pin name: this dialect's pin name}; a pin not
  listed keeps the IEC name.  The native prelude declares the FBs with these
  names (`NativeFB.declaration`), so a call or a member access uses them.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Mapping


@dataclass(frozen=True)
class NjRule:
    """One Sysmac Studio rule: what it refuses, where that is written, how sure we are."""

    number: str
    refuses: str
    source: str
    confidence: str     # documented | observed | assumed (docs/nj501.md)


NJ_RULES: Mapping[str, NjRule] = MappingProxyType({r.number: r for r in (
    NjRule("001", "an identifier longer than 127 bytes",
           "NJ-series CPU Unit Software User's Manual (W501), 6-3-12", "documented"),
    NjRule("002", "an identifier starting or ending with '_'", "W501, 6-3-12", "documented"),
    NjRule("003", "an identifier with '__'", "W501, 6-3-12", "documented"),
    NjRule("004", "an identifier equal to an instruction name", "W501, 6-3-12", "documented"),
    NjRule("005", "an identifier starting with 'P_' (system-defined variables)",
           "W501, 6-3-12; github.com/Dennych123/rb4axis CLAUDE.md (a POU named P_... "
           "is renamed silently)", "documented"),
    NjRule("006", "an element of an array or a member of a structure that is a variable "
                  "of a function block instance (Inst.Arr[i], Inst.Struct.M)",
           "Sysmac Studio Build error \"Cannot use an element of array or a member of "
           "structure for the reference of function block instance variables\", observed "
           "in github.com/Dennych123/rb4axis (CLAUDE.md, sim/SETUP.md): IK2.ROBOT_POS_OUTPUT[i] "
           "fails, IK2.DONE and the whole-array copy IK_OUT := IK2.ROBOT_POS_OUTPUT build",
           "observed"),
    NjRule("007", "a CASE label that is not an integer literal or an enumerator "
                  "(e.g. the name of a global constant)",
           "Sysmac Studio help, CASE: labels are integer constants (SPEC 7); a constant "
           "variable as a label is not shown accepted anywhere", "assumed"),
    NjRule("008", "an initial value that is not a literal (e.g. a constant's name)",
           "Sysmac Studio variable tables: the Initial Value column takes a literal "
           "(SPEC 7, issue 8); no public project shows a constant's name accepted", "assumed"),
)})


# OMRON's pin names where they differ from IEC 61131-3 (names compare without case,
# so TON's In/Clk of R_TRIG equal IEC's IN/CLK and need no entry).
#   CTD: "CTD_instance (CD, Load, PV, Q, CV)", NJ-series Instructions Reference
#        Manual (W502) 2-134 (easymanua.ls/omron/nj501-1500/manual?p=182).
#   CTUD: CU, CD, Reset, Load, PV, QU, QD, CV: OMRON's CTUD timing chart
#        (easymanua.ls/omron/nx-sl-series/manual?p=119).
#   CTU: Reset by the same family (CTUD's Reset); the CTU page itself was not reached.
#   SR/RS: OMRON's pin names were not found; the IEC names are kept (docs/nj501.md).
OMRON_PINS: Mapping[str, Mapping[str, str]] = MappingProxyType({
    "CTU": {"R": "Reset"},
    "CTD": {"LD": "Load"},
    "CTUD": {"R": "Reset", "LD": "Load"},
})


@dataclass(frozen=True)
class Dialect:
    name: str
    errors: frozenset = frozenset()
    pins: Mapping[str, Mapping[str, str]] = field(default_factory=dict)

    def nj_code(self, rule: str) -> str:
        """`E-NJ-<rule>` when this dialect refuses it, `W-NJ-<rule>` otherwise."""
        return ("E-NJ-" if rule in self.errors else "W-NJ-") + rule

    def pin(self, fb: str, iec_pin: str) -> str:
        return self.pins.get(fb.upper(), {}).get(iec_pin.upper(), iec_pin)

    def foreign_pin(self, fb: str, name: str) -> tuple[str, str] | None:
        """(other dialect, this dialect's name) when `name` is a pin of `fb` in another
        dialect only, e.g. ('iec', 'Reset') for CTU's 'R' under nj."""
        up = name.upper()
        for other in DIALECTS.values():
            if other is self:
                continue
            for iec_pin, renamed in other.pins.get(fb.upper(), {}).items():
                if renamed.upper() == up:
                    return other.name, self.pin(fb, iec_pin)
            mine = self.pins.get(fb.upper(), {})
            if up in mine and other.pin(fb, up).upper() == up:
                return other.name, mine[up]
        return None


IEC = Dialect("iec")
NJ = Dialect("nj", frozenset(NJ_RULES), OMRON_PINS)
# CODESYS/TwinCAT: IEC pin names and NJ rules as warnings; the constructs it
# adds are in checker/dialects.py (CONSTRUCTS).
CODESYS = Dialect("codesys")
DIALECTS: Mapping[str, Dialect] = MappingProxyType({d.name: d for d in (IEC, NJ, CODESYS)})
