"""Dialects as data: one table the checker, the compiler and the runtime consult.

`DIALECTS[name]` says, for `iec` (IEC 61131-3 3rd edition, strict), `nj`
(OMRON NJ/NX, Sysmac Studio) and `codesys` (CODESYS / TwinCAT):

* `CONSTRUCTS`: which dialects accept each construct outside the common core
  (METHOD, POINTER TO, S=, ...), each row with its source.  A construct used
  under a dialect that refuses it is E-DIALECT-001, naming the dialects that
  would accept it (`accepting`);
* `time_unit_ns`: what one unit of a number is when a TIME converts to or
  from it (TIME_TO_DINT, ...);
* `string_unit` / `string_max_bytes`: what the n of STRING[n] counts, and the
  largest STRING the target holds;
* `errors` and `pins`: OMRON's Build rules and pin names (below);
* `wraps_in_expressions`: whether an integer `+ - *` result that leaves its
  type's range overflows where it is used (compared, divided, converted to
  REAL, stored into a wider type), not only when it is stored;
* `omron_integer_ranking`, `rounds_real_operations`: the type an operation
  on mixed integers has, and whether a REAL operation is rounded to single
  precision where it is computed (OMRON's implicit cast rules);
* `signed_to_unsigned_assignment`: whether `UintVar := IntVar` needs no
  conversion function.

No other module asks which dialect is active (`if dialect == ...`).  A reader can check every OMRON rule below
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
class Construct:
    """A construct outside the common core: which dialects accept it, and the source."""

    what: str
    accepted_by: frozenset
    source: str


# Sysmac Studio's POUs are programs, function blocks and functions (NJ-series
# CPU Unit Software User's Manual W501, 6-2 "POUs"); the manual describes no
# METHOD, INTERFACE, inheritance, REF_TO or pointer.  This is an absence, not
# an explicit statement of OMRON's: to be confirmed against Sysmac Studio.
_NJ_NO_OO = "W501 6-2 lists programs, FBs and functions only (no OO; absence, to be confirmed)"
_CODESYS_ONLY = "CODESYS extension, not in IEC 61131-3"

CONSTRUCTS: Mapping[str, Construct] = MappingProxyType({
    "METHOD": Construct("METHOD", frozenset({"iec", "codesys"}), _NJ_NO_OO),
    "INTERFACE": Construct("INTERFACE", frozenset({"iec", "codesys"}), _NJ_NO_OO),
    "EXTENDS": Construct("EXTENDS", frozenset({"iec", "codesys"}), _NJ_NO_OO),
    "IMPLEMENTS": Construct("IMPLEMENTS", frozenset({"iec", "codesys"}), _NJ_NO_OO),
    "REF_TO": Construct("REF_TO", frozenset({"iec", "codesys"}), _NJ_NO_OO),
    "DEREF": Construct("the dereference ^", frozenset({"iec", "codesys"}), _NJ_NO_OO),
    "NULL": Construct("NULL", frozenset({"iec", "codesys"}), _NJ_NO_OO),
    "POINTER": Construct("POINTER TO", frozenset({"codesys"}),
                         "CODESYS extension; IEC 61131-3 3rd ed. has REF_TO instead"),
    "ADR": Construct("ADR()", frozenset({"codesys"}),
                     "CODESYS extension; IEC 61131-3 3rd ed. has REF() instead"),
    "TRAILING_COMMA": Construct("a comma after the last argument", frozenset({"codesys"}),
                                "CODESYS accepts it; IEC 61131-3's grammar does not"),
    "UNION": Construct("UNION", frozenset({"codesys", "nj"}),
                       "CODESYS; the NJ has union data types (W501 6-7-2 lists union data type "
                       "names); not in IEC 61131-3"),
    "PROPERTY": Construct("PROPERTY", frozenset({"codesys"}), _CODESYS_ONLY),
    "ACTION": Construct("ACTION", frozenset({"codesys"}), _CODESYS_ONLY),
    "NAMESPACE": Construct("NAMESPACE", frozenset({"iec"}),
                           "IEC 61131-3 3rd ed. 6.9; the NJ has namespaces, set in Sysmac Studio and "
                           "written \\\\NS\\Name (W501 6-7)"),
    "SET_RESET": Construct("S= / R=", frozenset({"codesys"}), _CODESYS_ONLY),
    "INPUT_WRITE": Construct("writing a VAR_INPUT inside its own POU", frozenset({"codesys"}),
                             "CODESYS compiles it (OSCAT BASIC 3.35, built with CODESYS, writes "
                             "inputs: BINOM's K, REPLACE_CHARS's SRC); iec and nj keep inputs "
                             "read-only inside the POU (E-ASSIGN-002)"),
    "SUPER_BODY": Construct("SUPER^() (the base FB's body)", frozenset({"codesys"}),
                            "CODESYS online help, SUPER: SUPER^() calls the body of the base "
                            "function block; IEC 61131-3 3rd ed. has SUPER.method() only"),
    "SFC": Construct("a Sequential Function Chart body (INITIAL_STEP, TRANSITION)", frozenset({"iec"}),
                     "IEC 61131-3 3rd ed. 6.7 (textual form); W501 lists ladder and ST as the NJ's "
                     "languages (no SFC; section to be confirmed), CODESYS edits SFC graphically (its textual form is not "
                     "documented as accepted; to be confirmed)"),
    "EDGE_NAME": Construct("a variable named R_EDGE or F_EDGE (IEC 61131-3 keywords)",
                           frozenset({"codesys"}),
                           "IEC 61131-3 lists R_EDGE and F_EDGE as keywords; CODESYS compiles "
                           "them as names (OSCAT BASIC's MANUAL_1 declares R_EDGE : BOOL)"),
    "ENUM_DOT": Construct("an enumeration value written Type.Value", frozenset({"codesys"}),
                          "CODESYS online help, Enumerations: a value qualified by its type "
                          "with a dot (E_Color.Red); IEC 61131-3 writes E_Color#Red"),
    "BIT_ACCESS": Construct("bit access x.3", frozenset({"codesys", "nj"}),
                            "CODESYS; the NJ specifies bits of integer variables the same "
                            "way (W501, section to be confirmed); not in IEC 61131-3"),
})


def accepting(construct: str) -> str:
    """`--dialect a or --dialect b`: the dialects that accept `construct`."""
    return " or ".join(f"--dialect {d}" for d in sorted(CONSTRUCTS[construct].accepted_by))


def refusal(construct: str, dialect: str) -> str:
    """The E-DIALECT-001 message: `construct` under `dialect`, and who accepts it."""
    return (f"{CONSTRUCTS[construct].what} is not accepted by --dialect {dialect}; "
            f"{accepting(construct)} accepts it")


@dataclass(frozen=True)
class Dialect:
    name: str
    errors: frozenset = frozenset()
    pins: Mapping[str, Mapping[str, str]] = field(default_factory=dict)
    time_unit_ns: int = 1
    string_unit: str = "character"
    string_max_bytes: int | None = None
    # The NJ evaluates an expression in the data type of its highest-ranked
    # operand and overflows there ("NJ-series CPU Unit Software User's Manual"
    # W501, 6-5-3, "Implicit Casts": `(UdintVar + DintVar) / DINT#2` with
    # UDINT#16#FFFF_FFFF and 1 "overflows and 0 is assigned" to a LINT).
    # IEC 61131-3 leaves overflow to the implementation and CODESYS computes
    # in at least 32-bit registers: there intermediate results stay exact
    # (wrapped only when stored), this project's behaviour before.
    wraps_in_expressions: bool = False
    # The type of an integer `+ - * / MOD` under OMRON's ranking (W501 6-5-3,
    # "Casting Rules When the Right-hand Side of an Assignment Statement Is an
    # Arithmetic Expression", p. 6-106): the operand of the higher rank
    # (ranks by size: SINT/USINT, INT/UINT, DINT/UDINT, LINT/ULINT), and of a
    # signed and an unsigned integer of one rank, the unsigned one: UDINT +
    # DINT is UDINT, ULINT + LINT is ULINT.  IEC 61131-3 takes the narrowest
    # type both widen to (UDINT + DINT is LINT; ULINT + LINT has none).
    omron_integer_ranking: bool = False
    # The same rule for REAL: a REAL `+ - * /` is computed in single precision,
    # each result rounded to float32 (W501 6-5-3: the right-hand side has the
    # type of its highest-ranked operand, REAL when no operand is LREAL).
    # Elsewhere REAL intermediate results stay doubles until stored.
    rounds_real_operations: bool = False
    # Assignment casts beyond IEC's widening: a signed integer into an
    # unsigned one of the same or a larger size, the bits kept (W501 6-5-3,
    # "Casting Rules When You Assign the Right-hand Value to the Left-hand
    # Side", p. 6-107: SINT->USINT->UINT->UDINT->ULINT are connected, so
    # `ULINT := SINT` builds; `uintVar := intVar` with -1 gives 16#FFFF).
    # The chart itself could not be read here: DINT->UDINT and LINT->ULINT
    # follow the pattern of the two pairs the text shows; other arrows of
    # the chart (UINT->INT? narrowing?) are not taken, so they stay errors.
    signed_to_unsigned_assignment: bool = False

    def accepts(self, construct: str) -> bool:
        return self.name in CONSTRUCTS[construct].accepted_by

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


# time_unit_ns: the NJ counts nanoseconds (W501, TIME data type; its
# TimeToNanoSec / NanoSecToTime); CODESYS and TwinCAT count milliseconds (TIME
# is a 32-bit count of ms: TIME_TO_DINT(T#1s) = 1000).  IEC 61131-3 leaves it
# to the implementation; `iec` keeps the NJ's nanoseconds.
# string_unit: what the n of STRING[n] counts, the same in the checker, the
# compiled code and values from outside (`--set`, the API):
# * iec (and codesys): characters (IEC 61131-3 STRING: single-byte characters);
# * nj: bytes of UTF-8. OMRON sizes NJ strings in bytes, NULL-terminated
#   (myOMRON knowledge base 1668, https://www.myomron.com/index.php?action=kb&article=1668:
#   "define the STRING in the Sysmac NJ one byte longer"); that the bytes are
#   UTF-8 was not confirmed by a source at hand (assumed, docs/nj501.md).
# string_max_bytes: the NJ's largest STRING is STRING[1986], the NULL included
# (docs/nj501.md, memory model rows).
IEC = Dialect("iec")
NJ = Dialect("nj", frozenset(NJ_RULES), OMRON_PINS, string_unit="byte", string_max_bytes=1986,
             wraps_in_expressions=True, omron_integer_ranking=True, signed_to_unsigned_assignment=True,
             rounds_real_operations=True)
# CODESYS/TwinCAT: IEC pin names and NJ rules as warnings.
CODESYS = Dialect("codesys", time_unit_ns=1_000_000)
DIALECTS: Mapping[str, Dialect] = MappingProxyType({d.name: d for d in (IEC, NJ, CODESYS)})
