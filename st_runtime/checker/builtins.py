"""Signatures and type rules of the IEC 61131-3 standard functions.

A parameter's category is a generic type class (`ANY_NUM`, `ANY_REAL`, ...).
Parameters marked `generic` share one type T: the call is instantiated at the
common type of their arguments, and the result is T where `result` is "T".
`extensible` functions (MIN, MAX, MUX, CONCAT, AND, ...) accept more
arguments of the last parameter's kind, named IN3, IN4, ... as in the standard.

`<A>_TO_<B>` conversions exist for every pair of elementary types (and
STRING); `conversion()` recognises their names.
"""

from __future__ import annotations

from dataclasses import dataclass

from .. import types as T
from . import typesys as ts


@dataclass(frozen=True, slots=True)
class Param:
    name: str
    category: str
    generic: bool = False


@dataclass(frozen=True, slots=True)
class Builtin:
    name: str
    params: tuple[Param, ...]
    result: str             # "T" (the generic type) or a category/type name
    extensible: bool = False

    @property
    def min_args(self) -> int:
        return len(self.params)


def _g(name: str, category: str) -> Param:
    return Param(name, category, generic=True)


def _table() -> dict[str, Builtin]:
    table: dict[str, Builtin] = {}

    def add(name, params, result, extensible=False):
        table[name] = Builtin(name, tuple(params), result, extensible)

    add("ABS", [_g("IN", "ANY_NUM")], "T")
    for name in ("SQRT", "LN", "LOG", "EXP", "SIN", "COS", "TAN", "ASIN", "ACOS", "ATAN"):
        add(name, [_g("IN", "ANY_REAL")], "T")
    add("EXPT", [_g("IN1", "ANY_REAL"), Param("IN2", "ANY_NUM")], "T")
    add("MIN", [_g("IN1", "ANY_ELEMENTARY"), _g("IN2", "ANY_ELEMENTARY")], "T", True)
    add("MAX", [_g("IN1", "ANY_ELEMENTARY"), _g("IN2", "ANY_ELEMENTARY")], "T", True)
    add("LIMIT", [_g("MN", "ANY_ELEMENTARY"), _g("IN", "ANY_ELEMENTARY"), _g("MX", "ANY_ELEMENTARY")], "T")
    add("SEL", [Param("G", "BOOL"), _g("IN0", "ANY"), _g("IN1", "ANY")], "T")
    add("MUX", [Param("K", "ANY_INT"), _g("IN0", "ANY"), _g("IN1", "ANY")], "T", True)
    add("MOVE", [_g("IN", "ANY")], "T")
    add("TRUNC", [Param("IN", "ANY_REAL")], "ANY_INT")
    for name in ("SHL", "SHR", "ROL", "ROR"):
        add(name, [_g("IN", "ANY_BITS"), Param("N", "ANY_INT")], "T")
    for name in ("AND", "OR", "XOR"):
        add(name, [_g("IN1", "ANY_BIT"), _g("IN2", "ANY_BIT")], "T", True)
    add("NOT", [_g("IN", "ANY_BIT")], "T")
    add("LEN", [Param("IN", "STRING")], "INT")
    add("CONCAT", [Param("IN1", "STRING"), Param("IN2", "STRING")], "STRING", True)
    add("LEFT", [Param("IN", "STRING"), Param("L", "ANY_INT")], "STRING")
    add("RIGHT", [Param("IN", "STRING"), Param("L", "ANY_INT")], "STRING")
    add("MID", [Param("IN", "STRING"), Param("L", "ANY_INT"), Param("P", "ANY_INT")], "STRING")
    add("INSERT", [Param("IN1", "STRING"), Param("IN2", "STRING"), Param("P", "ANY_INT")], "STRING")
    add("DELETE", [Param("IN", "STRING"), Param("L", "ANY_INT"), Param("P", "ANY_INT")], "STRING")
    add("REPLACE", [Param("IN1", "STRING"), Param("IN2", "STRING"), Param("L", "ANY_INT"),
                    Param("P", "ANY_INT")], "STRING")
    add("FIND", [Param("IN1", "STRING"), Param("IN2", "STRING")], "INT")
    from ..stdlib.bcd import BCD_FUNCTIONS

    for name, (category, result, _fn) in BCD_FUNCTIONS.items():
        add(name, [Param("IN", category)], result)
    return table


STANDARD_FUNCTIONS: dict[str, Builtin] = _table()


def extra_param(fn: Builtin, index: int) -> Param:
    """The parameter at position `index` (0-based) of an extensible function."""
    if index < len(fn.params):
        return fn.params[index]
    last = fn.params[-1]
    if fn.name == "MUX":
        return Param(f"IN{index - 1}", last.category, last.generic)
    return Param(f"IN{index + 1}", last.category, last.generic)


CATEGORY_TEXT = {
    "ANY_NUM": "a number (ANY_NUM)",
    "ANY_REAL": "REAL or LREAL (ANY_REAL)",
    "ANY_INT": "an integer (ANY_INT)",
    "ANY_BITS": "a bit string BYTE, WORD, DWORD or LWORD",
    "ANY_BIT": "BOOL or a bit string (ANY_BIT)",
    "ANY_ELEMENTARY": "an elementary value (ANY_ELEMENTARY)",
    "ANY": "a value",
    "STRING": "a STRING",
    "BOOL": "BOOL",
}


def describe(category: str) -> str:
    return CATEGORY_TEXT.get(category, category)


def in_category(t, category: str) -> bool:
    """Whether type `t` belongs to a generic category (or is the named type)."""
    if t is ts.ERROR:
        return True
    if category == "ANY_NUM":
        return ts.is_num(t)
    if category == "ANY_REAL":
        return ts.is_real(t)
    if category == "ANY_INT":
        return ts.is_int(t)
    if category == "ANY_BITS":
        return ts.is_bits(t)
    if category == "ANY_BIT":
        return ts.is_bits(t) or ts.is_bool(t)
    if category == "ANY_ELEMENTARY":
        return isinstance(t, (T.ElementaryType, T.StringType))
    if category == "ANY":
        return not isinstance(t, T.FBType)
    if category == "STRING":
        return ts.is_string(t)
    if category == "BOOL":
        return ts.is_bool(t)
    return T.ELEMENTARY.get(category) is t      # a parameter of one named type


# Elementary types that take part in `A_TO_B` conversions, by their spellings.
CONVERTIBLE: dict[str, object] = {
    name: t for name, t in T.ELEMENTARY.items()
}
CONVERTIBLE["STRING"] = T.StringType()


def conversion(name: str):
    """(source type, target type) for a conversion function name, else None."""
    upper = name.upper()
    if "_TO_" not in upper:
        return None
    # Type names may contain underscores (TIME_OF_DAY); try every split.
    start = 0
    while True:
        i = upper.find("_TO_", start)
        if i < 0:
            return None
        src, dst = upper[:i], upper[i + 4:]
        if src in CONVERTIBLE and dst in CONVERTIBLE and CONVERTIBLE[src] != CONVERTIBLE[dst]:
            return CONVERTIBLE[src], CONVERTIBLE[dst]
        start = i + 1


def is_standard_name(name: str) -> bool:
    upper = name.upper()
    return upper in STANDARD_FUNCTIONS or conversion(upper) is not None
