"""Type relations of IEC 61131-3: implicit conversions, common types, literals.

Implicit conversions follow IEC 61131-3 (3rd ed.), the implicit-conversion
figure/table: only widening conversions that keep every value, plus
integer-to-real conversions where the real's mantissa holds the integer
(SINT, INT, USINT, UINT to REAL; every integer to LREAL).  Everything else
needs an explicit `A_TO_B` conversion.
"""

from __future__ import annotations

import struct

from .. import types as T
from ..types import ElementaryType


class ErrorType:
    """The type of an expression that already produced a diagnostic.

    It is compatible with everything, so one root cause yields one diagnostic.
    """

    name = "<error>"

    def __str__(self) -> str:
        return self.name

    def __repr__(self) -> str:
        return "ERROR"


ERROR = ErrorType()

# Direct implicit conversions; the relation used is their transitive closure.
_DIRECT: dict[str, tuple[str, ...]] = {
    "SINT": ("INT", "REAL"),
    "INT": ("DINT", "REAL"),
    "DINT": ("LINT", "LREAL"),
    "LINT": ("LREAL",),
    "USINT": ("UINT", "INT"),
    "UINT": ("UDINT", "DINT", "REAL"),
    "UDINT": ("ULINT", "LINT", "LREAL"),
    "ULINT": ("LREAL",),
    "REAL": ("LREAL",),
    "BOOL": ("BYTE",),
    "BYTE": ("WORD",),
    "WORD": ("DWORD",),
    "DWORD": ("LWORD",),
}


def _closure() -> dict[str, frozenset[str]]:
    result: dict[str, frozenset[str]] = {}
    for start in _DIRECT:
        seen: set[str] = set()
        todo = list(_DIRECT[start])
        while todo:
            name = todo.pop()
            if name not in seen:
                seen.add(name)
                todo.extend(_DIRECT.get(name, ()))
        result[start] = frozenset(seen)
    return result


WIDENS_TO: dict[str, frozenset[str]] = _closure()

# Candidate common types, narrowest first (used to find the smallest type
# both operands of a binary operator convert to).
_COMMON_ORDER = [
    "BOOL", "BYTE", "WORD", "DWORD", "LWORD",
    "USINT", "SINT", "UINT", "INT", "UDINT", "DINT", "ULINT", "LINT", "REAL", "LREAL",
]


def is_error(t) -> bool:
    return t is ERROR


def elementary(t) -> ElementaryType | None:
    return t if isinstance(t, ElementaryType) else None


def kind_of(t) -> str | None:
    return t.kind if isinstance(t, ElementaryType) else None


def is_int(t) -> bool:
    return isinstance(t, ElementaryType) and t.kind == "int"


def is_real(t) -> bool:
    return isinstance(t, ElementaryType) and t.kind == "real"


def is_num(t) -> bool:
    return isinstance(t, ElementaryType) and t.kind in ("int", "real")


def is_bits(t) -> bool:
    """ANY_BIT without BOOL: BYTE, WORD, DWORD, LWORD."""
    return isinstance(t, ElementaryType) and t.kind == "bits"


def is_bool(t) -> bool:
    return t is T.BOOL


def is_string(t) -> bool:
    return isinstance(t, T.StringType)


def innermost(t):
    """The type under all of `t`'s array dimensions: an array's element type, at any depth
    (`ARRAY[..] OF ARRAY[..] OF F` gives F); `t` itself when it is no array."""
    while isinstance(t, T.ArrayType):
        t = t.element
    return t


def same_type(a, b) -> bool:
    if a is b:
        return True
    if isinstance(a, ElementaryType) and isinstance(b, ElementaryType):
        return a.name == b.name or T.ELEMENTARY.get(a.name) is T.ELEMENTARY.get(b.name)
    if isinstance(a, T.StringType) and isinstance(b, T.StringType):
        return a.wide == b.wide
    if isinstance(a, T.ArrayType) and isinstance(b, T.ArrayType):
        return a.dims == b.dims and same_type(a.element, b.element)
    if isinstance(a, T.RefType) and isinstance(b, T.RefType):
        # REF_TO T is one type wherever it is written (IEC 61131-3 3rd ed. 6.4.4.10): a
        # VAR_EXTERNAL matches its VAR_GLOBAL, a VAR_IN_OUT binds a variable of it.  A
        # POINTER TO (codesys) and a REF_TO of one target stay two types.
        return a.pointer == b.pointer and same_type(a.target, b.target)
    return False


def implicitly_converts(src, dst) -> bool:
    """True when a value of `src` may be stored in `dst` without a conversion call."""
    if src is ERROR or dst is ERROR:
        return True
    if same_type(src, dst):
        return True
    if isinstance(src, ElementaryType) and isinstance(dst, ElementaryType):
        return dst.name in WIDENS_TO.get(src.name, ())
    if isinstance(src, T.StringType) and isinstance(dst, T.StringType):
        return src.wide == dst.wide  # lengths may differ: the value is truncated
    return False


def common_type(a, b):
    """The narrowest elementary type both convert to implicitly, or None."""
    if a is ERROR or b is ERROR:
        return ERROR
    if implicitly_converts(a, b):
        return b
    if implicitly_converts(b, a):
        return a
    if isinstance(a, ElementaryType) and isinstance(b, ElementaryType):
        # Two integers never meet in a REAL: ULINT + LINT has no common type.
        same_kind = a.kind if a.kind == b.kind else None
        for name in _COMMON_ORDER:
            target = T.ELEMENTARY[name]
            if same_kind is not None and target.kind != same_kind:
                continue
            if implicitly_converts(a, target) and implicitly_converts(b, target):
                return target
    return None


def omron_ranked(a: ElementaryType, b: ElementaryType) -> ElementaryType:
    """The type OMRON gives an integer `a op b` (`Dialect.omron_integer_ranking`):
    the wider operand's, and of one signed and one unsigned of the same size,
    the unsigned one (W501 6-5-3, data type ranking table)."""
    if a.bits != b.bits:
        return a if a.bits > b.bits else b
    return b if a.signed and not b.signed else a


def conversion_hint(src, dst) -> str:
    """A suggestion such as `; use DINT_TO_INT` when a standard conversion exists."""
    if isinstance(src, ElementaryType) and isinstance(dst, ElementaryType) and src.name != dst.name:
        return f"; convert explicitly with {short_name(src)}_TO_{short_name(dst)}"
    if isinstance(src, ElementaryType) and isinstance(dst, T.StringType):
        return f"; convert explicitly with {short_name(src)}_TO_STRING"
    if isinstance(src, T.StringType) and isinstance(dst, ElementaryType):
        return f"; convert explicitly with STRING_TO_{short_name(dst)}"
    return ""


def short_name(t: ElementaryType) -> str:
    return {"TIME_OF_DAY": "TOD", "DATE_AND_TIME": "DT"}.get(t.name, t.name)


def type_name(t) -> str:
    return str(t)


# ------------------------------------------------------------------ literals

_SIGNED_BY_SIZE = ("SINT", "INT", "DINT", "LINT")
_BITS_BY_SIZE = ("BYTE", "WORD", "DWORD", "LWORD")


#: id of each elementary integer and bit-string type (a singleton, alive for the process) ->
#: its (min, max), read once: `min` and `max` are computed properties.  A subrange is not here.
INT_RANGES: dict[int, tuple[int, int]] = {
    id(t): (t.min, t.max) for t in T.ELEMENTARY.values() if t.kind in ("int", "bits")}

#: id of each elementary type whose constants `coerce_constant` leaves as they are (BOOL, the
#: times and dates: no wrap, no rounding).
STORED_AS_IS: frozenset[int] = frozenset(
    id(t) for t in T.ELEMENTARY.values() if t.kind not in ("int", "bits", "real"))


def fits(value: int, t) -> bool:
    """Whether an integer value lies in the range of an integer or bit-string type."""
    limits = INT_RANGES.get(id(t))
    if limits is not None:
        return limits[0] <= value <= limits[1]
    if isinstance(t, ElementaryType) and t.kind in ("int", "bits"):     # a subrange
        return t.min <= value <= t.max
    if t is T.BOOL:
        return value in (0, 1)
    return False


def smallest_int_type(*values: int):
    """The narrowest of SINT, INT, DINT, LINT (then ULINT) holding every value."""
    for name in _SIGNED_BY_SIZE + ("ULINT",):
        t = T.ELEMENTARY[name]
        if all(t.min <= v <= t.max for v in values):
            return t
    return None


def smallest_bits_type(value: int):
    for name in _BITS_BY_SIZE:
        t = T.ELEMENTARY[name]
        if 0 <= value <= t.max:
            return t
    return None


def wrap_int(value: int, t: ElementaryType) -> int:
    """Two's-complement wrap of an integer to the width of `t`."""
    mask = (1 << t.bits) - 1
    value &= mask
    if t.signed and value > t.max:
        value -= 1 << t.bits
    return value


def to_float32(value: float) -> float:
    try:
        return struct.unpack("f", struct.pack("f", value))[0]
    except OverflowError:
        return value


def coerce_constant(value, t):
    """A folded constant as the runtime would store it in type `t`."""
    if isinstance(value, bool) or value is None:
        return value
    if isinstance(t, ElementaryType):
        if t.kind in ("int", "bits") and isinstance(value, int):
            return wrap_int(value, t)
        if t.kind == "real":
            value = float(value)
            return to_float32(value) if t.bits == 32 else value
    return value
