"""Type conversion functions `<A>_TO_<B>` between elementary types.

`conversion("REAL", "INT")` returns the Python function of `REAL_TO_INT`;
`CONVERSIONS` maps every defined name (`"REAL_TO_INT"`, also with the long
names `TIME_OF_DAY`/`DATE_AND_TIME`) to its function.  Every function takes
the stored source value and returns the stored destination value (already
wrapped/rounded for the destination type).

Rules (IEC 61131-3 3rd ed. table 22 and the OMRON NJ where IEC is silent):

* integer/bit string -> integer/bit string: keeps the low bits (two's
  complement), e.g. INT_TO_SINT(4223) = 127, DINT_TO_INT(65665) = 129.
* REAL/LREAL -> integer/bit string: rounds to nearest, ties to even, as the
  NJ does (W502, Real Number-to-Integer Conversion Group: 1.5 -> 2, 2.5 -> 2,
  -1.5 -> -2, -2.5 -> -2).  The NJ leaves "an illegal value" when the result
  is outside the destination's range; the simulator instead raises F-CONVERT
  (also for NaN and infinities) so such a value can never pass unnoticed.
  For bit strings the valid range is that of the signed integer of the same
  width and the result is its two's complement (REAL_TO_WORD(-1.6) =
  16#FFFE), as in the NJ's Real Number-to-Bit String table.
* integer -> REAL: one rounding to float32, ties to even; -> LREAL likewise.
* anything -> BOOL: FALSE for 0 (0.0, T#0s, ''), TRUE otherwise; STRING is
  parsed ('TRUE'/'FALSE'/'1'/'0').  BOOL -> number: 0 or 1.
* TIME and the date types store nanoseconds; conversions to, from and
  between them carry that count of nanoseconds (the NJ's TIME unit, cf. its
  TimeToNanoSec/NanoSecToTime): REAL_TO_TIME(2.5) = 2 ns (ties to even),
  TIME_TO_LINT(T#1s) = 1000000000.  A DATE destination drops the time of
  day, a TOD destination keeps the time within the day; so DT_TO_DATE,
  DT_TO_TOD and DATE_TO_DT behave as IEC defines them.
* -> STRING: decimal for numbers and bit strings, shortest round-trip text
  for reals, IEC literals for TIME/DATE/TOD/DT, 'TRUE'/'FALSE' for BOOL.
  STRING -> X parses that text (integers also as `16#FF`/`2#1010`/`8#17`,
  underscores allowed) and raises F-CONVERT on anything else or on a value
  out of range.  Truncation to STRING[n] happens on store, not here.

Every ordered pair of distinct types is defined (the checker accepts every
`<A>_TO_<B>` name); `conversion` raises `KeyError` only for unknown names.
"""

from __future__ import annotations

import math
import re
from typing import Callable

from ..faults import STFault
from ..types import ELEMENTARY, ElementaryType
from ..values import (
    LINT_MIN,
    NS_PER_DAY,
    FORMATTERS,
    PARSERS,
    ValueFormatError,
    int_to_real32,
    int_wrapper,
    round_half_even,
    shortest_real32,
    to_real32,
)

STRING = "STRING"

# Canonical names in a stable order; TOD and DT are the short spellings.
TYPE_NAMES = (
    "BOOL", "SINT", "INT", "DINT", "LINT", "USINT", "UINT", "UDINT", "ULINT",
    "BYTE", "WORD", "DWORD", "LWORD", "REAL", "LREAL",
    "TIME", "DATE", "TOD", "DT", STRING,
)
LONG_NAMES = {"TOD": "TIME_OF_DAY", "DT": "DATE_AND_TIME"}
_CANONICAL = {"TIME_OF_DAY": "TOD", "DATE_AND_TIME": "DT"}


def _kind(name: str) -> str:
    return "string" if name == STRING else ELEMENTARY[name].kind


def _fault(src: str, dst: str, value, why: str) -> STFault:
    return STFault("F-CONVERT", f"{src}_TO_{dst}({value!r}): {why}")


# ---------------------------------------------------------------------------
# Text helpers

def real_to_text(x: float, bits: int) -> str:
    """Shortest decimal text that reads back to the same REAL/LREAL value."""
    if math.isnan(x):
        return "NaN"
    if math.isinf(x):
        return "Inf" if x > 0 else "-Inf"
    text = repr(shortest_real32(x) if bits == 32 else x)
    return text


_INT_TEXT = re.compile(r"^([+-]?)(?:(2|8|16)#([0-9A-Fa-f_]+)|(\d[\d_]*))$")
_REAL_TEXT = re.compile(r"^[+-]?\d[\d_]*(?:\.\d[\d_]*)?(?:[eE][+-]?\d+)?$")


def parse_int_text(text: str) -> int:
    m = _INT_TEXT.match(text.strip())
    if not m or (m.group(3) or m.group(4) or "").endswith("_"):
        raise ValueFormatError(f"{text!r} is not an integer")
    sign = -1 if m.group(1) == "-" else 1
    if m.group(2):
        try:
            return sign * int(m.group(3).replace("_", ""), int(m.group(2)))
        except ValueError:
            raise ValueFormatError(f"{text!r} is not an integer") from None
    return sign * int(m.group(4).replace("_", ""))


def parse_real_text(text: str) -> float:
    src = text.strip()
    if not _REAL_TEXT.match(src):
        raise ValueFormatError(f"{text!r} is not a number")
    return float(src.replace("_", ""))


def parse_bool_text(text: str) -> bool:
    word = text.strip().upper()
    if word in ("TRUE", "1"):
        return True
    if word in ("FALSE", "0"):
        return False
    raise ValueFormatError(f"{text!r} is not TRUE or FALSE")


# ---------------------------------------------------------------------------
# Builders: one per (source kind, destination kind)

def _real_to_integer(src: str, dst: ElementaryType, shown: str = "") -> Callable:
    """`shown`: the destination named in faults when it is not `dst` (TIME
    and the dates convert through LINT)."""
    wrap = int_wrapper(dst)
    shown = shown or dst.name
    if dst.kind == "bits":   # the NJ's valid range: the signed integer of that width
        lo, hi = -(1 << (dst.bits - 1)), (1 << (dst.bits - 1)) - 1
    else:
        lo, hi = dst.min, dst.max

    def convert(x: float) -> int:
        if not math.isfinite(x):
            raise _fault(src, shown, x, "not a finite number")
        n = round_half_even(x)
        if not lo <= n <= hi:
            raise _fault(src, shown, x, f"result {n} outside {lo}..{hi}")
        return wrap(n)

    return convert


def _text_to(dst: str) -> Callable:
    kind = _kind(dst)
    if kind == "bool":
        parse = parse_bool_text
        finish = bool
    elif kind in ("int", "bits"):
        t = ELEMENTARY[dst]
        parse = parse_int_text
        lo, hi = t.min, t.max

        def finish(n: int) -> int:
            if not lo <= n <= hi:
                raise ValueFormatError(f"{n} is outside {lo}..{hi}")
            return n
    elif kind == "real":
        parse = parse_real_text
        finish = to_real32 if ELEMENTARY[dst].bits == 32 else float
    else:
        parse = PARSERS[kind]
        finish = int

    def convert(text: str):
        try:
            return finish(parse(text))
        except ValueFormatError as exc:
            raise STFault("F-CONVERT", f"STRING_TO_{dst}: {exc}") from None

    return convert


def _to_text(src: str) -> Callable:
    kind = _kind(src)
    if kind == "bool":
        return lambda v: "TRUE" if v else "FALSE"
    if kind in ("int", "bits"):
        return lambda v: str(int(v))
    if kind == "real":
        bits = ELEMENTARY[src].bits
        return lambda v: real_to_text(v, bits)
    if kind == "string":
        return lambda v: v
    return FORMATTERS[kind]


def _nonzero(v) -> bool:
    return v != 0


def _build(src: str, dst: str) -> Callable:
    sk, dk = _kind(src), _kind(dst)
    if dk == "string":
        return _to_text(src)
    if sk == "string":
        return _text_to(dst)
    s_t, d_t = ELEMENTARY[src], ELEMENTARY[dst]
    if dk == "bool":
        if sk == "bool":
            return bool
        return _nonzero
    if dk in ("int", "bits"):
        wrap = int_wrapper(d_t)
        if sk == "real":
            return _real_to_integer(src, d_t)
        return lambda v: wrap(int(v))        # bool, integers, bit strings, time
    if dk == "real":
        if d_t.bits == 32:
            if sk == "real":
                return to_real32
            return lambda v: int_to_real32(int(v))
        return float
    # destination is TIME, DATE, TOD or DT: through the nanosecond count
    if sk == "real":
        to_ns = _real_to_integer(src, ELEMENTARY["LINT"], dst)
    else:
        wrap64 = int_wrapper(ELEMENTARY["LINT"])
        to_ns = (lambda v: wrap64(int(v)))
    if dk == "date":
        return lambda v: _drop_time_of_day(src, dst, to_ns(v))
    if dk == "tod":
        return lambda v: to_ns(v) % NS_PER_DAY
    return to_ns


def _drop_time_of_day(src: str, dst: str, ns: int) -> int:
    """The start of the day of `ns`; the first ~12 hours of the 64-bit range
    lie in a day that starts before it, which no DATE can hold."""
    day = ns - ns % NS_PER_DAY
    if day < LINT_MIN:
        raise _fault(src, dst, ns, "the day starts outside the DATE range")
    return day


def _table() -> dict[str, Callable]:
    table: dict[str, Callable] = {}
    for src in TYPE_NAMES:
        for dst in TYPE_NAMES:
            if src == dst:
                continue
            fn = _build(src, dst)
            for s in (src, LONG_NAMES.get(src, src)):
                for d in (dst, LONG_NAMES.get(dst, dst)):
                    table[f"{s}_TO_{d}"] = fn
    return table


CONVERSIONS: dict[str, Callable] = _table()


def time_scaled(name: str, unit_ns: int) -> Callable | None:
    """`name` when a TIME's number counts `unit_ns` nanoseconds (1 ms: 10**6),
    or None when the conversion does not turn a TIME into a number or back."""
    parts = split_conversion_name(name)
    if parts is None or unit_ns == 1:
        return None
    src, dst = parts
    base = CONVERSIONS[name.upper()]
    numeric = ("int", "bits", "real")
    if src == "TIME" and _kind(dst) in numeric:
        if _kind(dst) == "real":
            return lambda ns: base(ns) / unit_ns
        return lambda ns: base(ns // unit_ns if ns >= 0 else -(-ns // unit_ns))
    if dst == "TIME" and _kind(src) in numeric:
        return lambda v: base(v * unit_ns)
    return None


def canonical(name: str) -> str:
    name = name.upper()
    return _CANONICAL.get(name, name)


def conversion(src: str, dst: str) -> Callable:
    """The function of `<src>_TO_<dst>` (any spelling of the type names)."""
    key = f"{canonical(src)}_TO_{canonical(dst)}"
    fn = CONVERSIONS.get(key)
    if fn is None:
        raise KeyError(f"no conversion {src.upper()}_TO_{dst.upper()}")
    return fn


def split_conversion_name(name: str) -> tuple[str, str] | None:
    """`"LREAL_TO_DINT"` -> ("LREAL", "DINT"); None when it is no conversion."""
    upper = name.upper()
    if upper not in CONVERSIONS:
        return None
    for src in sorted(set(TYPE_NAMES) | set(LONG_NAMES.values()), key=len, reverse=True):
        prefix = src + "_TO_"
        if upper.startswith(prefix) and upper[len(prefix):]:
            return canonical(src), canonical(upper[len(prefix):])
    return None
