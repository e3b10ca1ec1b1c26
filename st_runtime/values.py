"""The value model: how each elementary ST type is stored in Python.

* BOOL: `bool`.  Integers and bit strings: `int`, wrapped to their width on
  every store (`wrap`, or the faster per-type `int_wrapper`).
* REAL: a Python float holding a float32 value (`to_real32` on every store);
  LREAL: a Python float.
* TIME: signed 64-bit count of nanoseconds.  DATE and DATE_AND_TIME:
  nanoseconds since 1970-01-01-00:00:00 (the NJ's epoch); TIME_OF_DAY:
  nanoseconds since midnight.
* STRING: `str`.

This module also formats and parses the IEC literals of the time types
(`T#1s500ms`, `D#2024-01-02`, `TOD#12:30:00.5`, `DT#2024-01-02-12:30:00`),
holds the TIME arithmetic, and converts values to and from JSON.
Conversion functions (`INT_TO_REAL`, ...) live in `stdlib/conversions.py`.
"""

from __future__ import annotations

import array
import datetime as _dt
import json
import math
import re
from fractions import Fraction
from typing import Callable

from .faults import STFault
from .literals import (NS_PER_UNIT, encode_date, encode_date_and_time, encode_duration,
                       encode_time_of_day)
from .native import mangle
from .types import (
    ArrayType,
    ElementaryType,
    EnumType,
    FBType,
    STRING_UNITS,
    StringType,
    StructType,
    resolve_alias,
    string_size,
)

NS_PER_US = 1_000
NS_PER_MS = 1_000_000
NS_PER_S = 1_000_000_000
NS_PER_MIN = 60 * NS_PER_S
NS_PER_H = 60 * NS_PER_MIN
NS_PER_DAY = 24 * NS_PER_H

LINT_MIN = -(1 << 63)
LINT_MAX = (1 << 63) - 1


# ---------------------------------------------------------------------------
# Integers and bit strings

def _make_wrapper(bits: int, signed: bool) -> Callable[[int], int]:
    mask = (1 << bits) - 1
    if signed:
        lo = -(1 << (bits - 1))
        hi = (1 << (bits - 1)) - 1
        half = 1 << (bits - 1)

        def wrap_signed(v: int) -> int:
            # Fast path: a value already in range needs no arithmetic.
            if lo <= v <= hi:
                return v
            return ((v + half) & mask) - half

        return wrap_signed

    def wrap_unsigned(v: int) -> int:
        return v & mask

    return wrap_unsigned


def _wrap_bool(v) -> bool:
    return bool(v)


_WRAPPERS: dict[str, Callable] = {}


def int_wrapper(t: ElementaryType) -> Callable:
    """The store function of an integer, bit-string, BOOL or time type.

    Bind it once (the compiler does) and call it on every store: a value in
    range comes back unchanged, anything else keeps its low `bits` bits with
    the type's signedness (INT: 32768 -> -32768; BYTE: 256 -> 0).
    """
    fn = _WRAPPERS.get(t.name)
    if fn is None:
        if t.kind == "bool":
            fn = _wrap_bool
        elif t.kind in ("int", "bits"):
            fn = _make_wrapper(t.bits, t.signed)
        elif t.kind in ("time", "date", "tod", "dt"):
            fn = _make_wrapper(64, True)
        else:
            raise TypeError(f"{t.name} is not stored as an integer")
        _WRAPPERS[t.name] = fn
    return fn


def wrap(value: int, t: ElementaryType) -> int:
    """`value` wrapped to the width and signedness of `t`."""
    return int_wrapper(t)(value)


wrap_lint = _make_wrapper(64, True)


def int_div(a: int, b: int) -> int:
    """IEC integer division: truncates toward zero (-7 / 2 = -3)."""
    if b == 0:
        raise STFault("F-DIV-ZERO", "integer division by zero")
    q = abs(a) // abs(b)
    return q if (a < 0) == (b < 0) else -q


def int_mod(a: int, b: int) -> int:
    """IEC MOD: the remainder takes the sign of the dividend (-7 MOD 2 = -1)."""
    if b == 0:
        raise STFault("F-DIV-ZERO", "MOD by zero")
    r = abs(a) % abs(b)
    return -r if a < 0 else r


# ---------------------------------------------------------------------------
# REAL (float32)
#
# Benchmarked on this machine (Python 3.11, per call): array('f') store+load
# 59 ns, struct pack/unpack 77 ns, ctypes.c_float 92 ns, numpy.float32 164 ns.
# The array is the fastest; it rounds to nearest-even like the NJ (W501,
# "Rounding": ties take the mantissa whose last bit is 0) and turns overflow
# into +/-inf as the NJ does.  The buffer is shared, which is safe because a
# controller runs on one thread.

_F32 = array.array("f", [0.0])


def to_real32(x: float) -> float:
    """`x` rounded to the nearest float32 value (ties to even), as a float."""
    buf = _F32
    buf[0] = x
    return buf[0]


def shortest_real32(x: float) -> float:
    """The float with the fewest decimal digits that rounds to the same REAL.

    JSON and CSV show a REAL holding 0.1f as 0.1 rather than as its exact
    double value 0.10000000149011612; reading it back gives the same REAL.
    """
    if not math.isfinite(x):
        return x
    for digits in range(1, 10):
        candidate = float(f"{x:.{digits}g}")
        if to_real32(candidate) == x:
            return candidate
    return x


_EXACT_IN_FLOAT64 = 1 << 53


def int_to_real32(v: int) -> float:
    """An integer rounded once (ties to even) to float32.

    Going through float64 first would round twice for |v| > 2**53.
    """
    if -_EXACT_IN_FLOAT64 <= v <= _EXACT_IN_FLOAT64:
        return to_real32(float(v))
    mag = abs(v)
    shift = mag.bit_length() - 24
    q, r = divmod(mag, 1 << shift)
    half = 1 << (shift - 1)
    if r > half or (r == half and q & 1):
        q += 1
    return to_real32(math.copysign(float(q << shift), v))


def round_half_even(x: float) -> int:
    """Nearest integer, ties to even: the NJ's rule for real-to-integer.

    Source: OMRON NJ-series Instructions Reference Manual (W502), Real
    Number-to-Integer and Real Number-to-Bit String Conversion Groups, table
    "how values are rounded": fraction < 0.5 truncated, > 0.5 rounded up,
    exactly 0.5 rounded to the even neighbour (1.5 -> 2, 2.5 -> 2,
    -1.5 -> -2, -2.5 -> -2).  Python's round() implements exactly this.
    """
    return round(x)


def real_div(a: float, b: float) -> float:
    """REAL/LREAL `/` with IEEE 754 results, no fault, as the NJ: x / 0 is
    +-inf by the signs of x and of the zero, 0 / 0 and NaN / 0 are NaN."""
    try:
        return a / b
    except ZeroDivisionError:
        if a == 0 or a != a:
            return math.nan
        return math.copysign(math.inf, a) * math.copysign(1.0, b)


# ---------------------------------------------------------------------------
# TIME arithmetic (all in nanoseconds; results wrap to 64 bits as on the NJ,
# whose MULTIME/DIVTIME raise no error on overflow)

def time_add(a: int, b: int) -> int:
    return wrap_lint(a + b)


def time_sub(a: int, b: int) -> int:
    return wrap_lint(a - b)


def time_mul(t: int, k) -> int:
    """TIME * ANY_NUM.

    A real factor rounds the exact product to the nearest nanosecond, ties to
    even; 0 gives T#0s and a non-finite factor gives the most negative TIME
    (both as the NJ's MULTIME, W502 "Time and Time of Day Instructions").
    """
    if isinstance(k, float):
        if k == 0.0:
            return 0
        if not math.isfinite(k):
            return LINT_MIN
        return wrap_lint(round(Fraction(t) * Fraction(k)))
    return wrap_lint(t * int(k))


def time_div(t: int, k) -> int:
    """TIME / ANY_NUM: integer divisors truncate toward zero, real divisors
    round to the nearest nanosecond (ties to even); zero is a fault."""
    if isinstance(k, float):
        if k == 0.0:
            raise STFault("F-DIV-ZERO", "TIME divided by zero")
        if not math.isfinite(k):
            return 0 if math.isinf(k) else LINT_MIN
        return wrap_lint(round(Fraction(t) / Fraction(k)))
    return wrap_lint(int_div(t, int(k)))


# ---------------------------------------------------------------------------
# Formatting of time literals

class ValueFormatError(ValueError):
    """Text that is not a valid literal for the requested type."""


# The JSON text of a TIME or date value is its IEC literal, written by the
# same encoders as the pretty-printer's (one spelling of a literal).

def format_time(ns: int, prefix: str = "T#") -> str:
    """A TIME as its shortest IEC literal: `T#1s500ms`, `T#-2s500ms`, `T#0s`."""
    return encode_duration(ns, prefix.rstrip("#"))


def format_date(ns: int) -> str:
    return encode_date(ns)


def format_tod(ns: int) -> str:
    return encode_time_of_day(ns % NS_PER_DAY)


def format_dt(ns: int) -> str:
    return encode_date_and_time(ns)


_EPOCH = _dt.datetime(1970, 1, 1)


FORMATTERS: dict[str, Callable[[int], str]] = {
    "time": format_time, "date": format_date, "tod": format_tod, "dt": format_dt,
}


# ---------------------------------------------------------------------------
# Parsing of time literals (for JSON input and STRING_TO_* conversions)

_TIME_PREFIX = re.compile(r"(?i)^(?:T|TIME|LT|LTIME)#")
_TIME_PART = re.compile(r"(?i)(\d+(?:\.\d+)?)(ms|us|ns|d|h|m|s)")
_UNIT_NS = {unit.lower(): size for unit, size in NS_PER_UNIT.items()}


def parse_time(text: str) -> int:
    """`T#1s500ms`, `TIME#-2.5s`, `t#1h_30m` (or without prefix) -> ns.

    Fractions are exact; the total is rounded to the nanosecond, ties to even.
    """
    src = text.strip()
    body = _TIME_PREFIX.sub("", src, count=1).replace("_", "")
    sign = 1
    if body[:1] in "+-" and body:
        sign = -1 if body[0] == "-" else 1
        body = body[1:]
    total = Fraction(0)
    pos = 0
    seen = []
    for match in _TIME_PART.finditer(body):
        if match.start() != pos:
            break
        unit = match.group(2).lower()
        total += Fraction(match.group(1)) * _UNIT_NS[unit]
        seen.append(unit)
        pos = match.end()
    if not seen or pos != len(body):
        raise ValueFormatError(f"{text!r} is not a TIME literal (expected e.g. T#1s500ms)")
    ns = sign * round(total)
    if not LINT_MIN <= ns <= LINT_MAX:
        raise ValueFormatError(f"{text!r} is outside the TIME range")
    return ns


_DATE_RE = r"(\d{4})-(\d{1,2})-(\d{1,2})"
_CLOCK_RE = r"(\d{1,2}):(\d{1,2}):(\d{1,2})(?:\.(\d{1,9}))?"
_DATE_LIT = re.compile(rf"(?i)^(?:D|DATE)#{_DATE_RE}$|^{_DATE_RE}$")
_TOD_LIT = re.compile(rf"(?i)^(?:TOD|TIME_OF_DAY)#{_CLOCK_RE}$|^{_CLOCK_RE}$")
_DT_LIT = re.compile(rf"(?i)^(?:DT|DATE_AND_TIME)#{_DATE_RE}-{_CLOCK_RE}$|^{_DATE_RE}-{_CLOCK_RE}$")


def _groups(match: re.Match) -> list:
    """The groups of whichever alternative matched (with or without prefix)."""
    groups = match.groups()
    n = len(groups) // 2
    first = groups[:n]
    return list(first if any(g is not None for g in first) else groups[n:])


def _days(text: str, y: str, mo: str, d: str) -> int:
    try:
        return (_dt.datetime(int(y), int(mo), int(d)) - _EPOCH).days
    except ValueError as exc:
        raise ValueFormatError(f"{text!r}: {exc}") from None


def _clock_ns(text: str, h: str, m: str, s: str, frac: str | None) -> int:
    hh, mm, ss = int(h), int(m), int(s)
    if hh > 23 or mm > 59 or ss > 59:
        raise ValueFormatError(f"{text!r}: clock time out of range")
    ns = ((hh * 60 + mm) * 60 + ss) * NS_PER_S
    if frac:
        ns += int(frac.ljust(9, "0"))
    return ns


def parse_date(text: str) -> int:
    m = _DATE_LIT.match(text.strip())
    if not m:
        raise ValueFormatError(f"{text!r} is not a DATE literal (expected e.g. D#2024-01-31)")
    return _days(text, *_groups(m)) * NS_PER_DAY


def parse_tod(text: str) -> int:
    m = _TOD_LIT.match(text.strip())
    if not m:
        raise ValueFormatError(f"{text!r} is not a TIME_OF_DAY literal (expected e.g. TOD#12:30:00.5)")
    return _clock_ns(text, *_groups(m))


def parse_dt(text: str) -> int:
    m = _DT_LIT.match(text.strip())
    if not m:
        raise ValueFormatError(
            f"{text!r} is not a DATE_AND_TIME literal (expected e.g. DT#2024-01-31-12:30:00)")
    g = _groups(m)
    return _days(text, *g[:3]) * NS_PER_DAY + _clock_ns(text, *g[3:])


PARSERS: dict[str, Callable[[str], int]] = {
    "time": parse_time, "date": parse_date, "tod": parse_tod, "dt": parse_dt,
}


# ---------------------------------------------------------------------------
# Default (zero) values

def default_value(t):
    """The IEC default initial value of a type (arrays/structs: plain data)."""
    t = resolve_alias(t)
    if isinstance(t, ElementaryType):
        if t.kind == "bool":
            return False
        if t.kind == "real":
            return 0.0
        return 0
    if isinstance(t, StringType):
        return ""
    if isinstance(t, EnumType):
        return min(v for _, v in t.values.values()) if t.values else 0
    if isinstance(t, ArrayType):
        return [default_value(t.element) for _ in range(t.size)]
    if isinstance(t, (StructType, FBType)):
        return {name.upper(): default_value(ft) for name, ft in _members(t)}
    raise TypeError(f"no default value for {t}")


# ---------------------------------------------------------------------------
# JSON

class JsonValueError(ValueError):
    """A JSON value that does not fit the ST type; the message names the path."""


# Variables of an FB or PROGRAM instance that JSON and traces do not show:
# VAR_IN_OUT and VAR_EXTERNAL belong to someone else, VAR_TEMP lives only
# during a call (an instance does not store it), VAR_GLOBAL is the
# configuration's.
HIDDEN_KINDS = frozenset({"VAR_IN_OUT", "VAR_EXTERNAL", "VAR_TEMP", "VAR_GLOBAL"})


def json_members(t) -> list[tuple[str, object]]:
    """(declared name, type) of the members a struct or FB instance shows."""
    if isinstance(t, StructType):
        return list(t.fields.values())
    return [(sym.name, sym.type) for sym in t.variables.values() if sym.kind not in HIDDEN_KINDS]


_members = json_members

#: What the JSON of a standard (native) FB shows: its IEC interface. Its
#: memory (TON's StartTime and Running, a counter's edge memory) stays
#: readable by an explicit path (`Timer.StartTime`), not in the JSON.
INTERFACE_KINDS = frozenset({"VAR_INPUT", "VAR_OUTPUT"})


def shown_members(t) -> list[tuple[str, object]]:
    """The members the JSON of a value of type `t` shows: a native FB's
    inputs and outputs, every other struct or FB's `json_members`."""
    if isinstance(t, FBType) and t.native is not None:
        return [(sym.name, sym.type) for sym in t.variables.values() if sym.kind in INTERFACE_KINDS]
    return json_members(t)


def _member_value(obj, name: str):
    if isinstance(obj, dict):
        if name.upper() in obj:
            return obj[name.upper()]
        return obj[name]
    return getattr(obj, mangle(name))


def object_to_json(obj) -> dict:
    """A struct value, FB or PROGRAM instance as a dict by declared name.

    Walks the object's own layout (`_st_vars`, `_st_kinds`), so it also
    serves PROGRAM instances, which have no type of their own.
    """
    kinds = getattr(type(obj), "_st_kinds", None) or {}
    out = {}
    for key, (name, t) in type(obj)._st_vars.items():
        if kinds.get(key) in HIDDEN_KINDS:
            continue
        out[name] = to_json(getattr(obj, mangle(name)), t)
    return out


def _nest(flat: list, dims: tuple[tuple[int, int], ...]) -> list:
    if len(dims) == 1:
        return flat
    inner = 1
    for lo, hi in dims[1:]:
        inner *= hi - lo + 1
    return [_nest(flat[i * inner:(i + 1) * inner], dims[1:])
            for i in range(dims[0][1] - dims[0][0] + 1)]


def to_json(value, t):
    """A stored value of type `t` as a JSON-able Python value.

    BOOL -> bool, integers -> int, REAL/LREAL -> float (a REAL in its shortest
    form that reads back to the same float32, 0.1 rather than
    0.10000000149011612; non-finite values stay float here: `json_text`
    writes them as the strings "NaN", "Infinity", "-Infinity"), STRING -> str, TIME and
    the date types -> IEC literal strings, enums -> the value's name, arrays ->
    nested lists (one level per dimension), structs and FB instances -> objects
    keyed by declared name.
    """
    t = resolve_alias(t)
    if type(t).__name__ == "InterfaceType":    # a reference: what it refers to
        return None if value is None else type(value)._st_name
    if type(t).__name__ == "RefType":          # NULL, or "REF" (the target is shown where it lives)
        return None if value is None else "REF"
    if isinstance(t, ElementaryType):
        kind = t.kind
        if kind == "bool":
            return bool(value)
        if kind in ("int", "bits"):
            return int(value)
        if kind == "real":
            return shortest_real32(value) if t.bits == 32 else float(value)
        return FORMATTERS[kind](int(value))
    if isinstance(t, StringType):
        return str(value)
    if isinstance(t, EnumType):
        for name, number in t.values.values():
            if number == value:
                return name
        return int(value)
    if isinstance(t, ArrayType):
        flat = [to_json(v, t.element) for v in _flat_elements(value)]
        return _nest(flat, t.dims)
    if isinstance(t, (StructType, FBType)):
        return {name: to_json(_member_value(value, name), ft) for name, ft in shown_members(t)}
    raise TypeError(f"cannot convert a value of type {t} to JSON")


# Strict JSON (RFC 8259) has no NaN or infinity; Python's json module would
# write the bare words NaN/Infinity, which JSON.parse, jq or serde refuse.
# They go out as strings instead: nothing is lost (+inf, -inf and NaN stay
# apart), float("Infinity") and JavaScript's Number("Infinity") read them
# back, and `from_json` takes them for a REAL or LREAL.
NON_FINITE_NAMES = {"NaN": math.nan, "Infinity": math.inf, "-Infinity": -math.inf}


def _finite_only(data):
    if isinstance(data, float) and not math.isfinite(data):
        return "NaN" if math.isnan(data) else ("Infinity" if data > 0 else "-Infinity")
    if isinstance(data, list):
        return [_finite_only(item) for item in data]
    if isinstance(data, dict):
        return {key: _finite_only(item) for key, item in data.items()}
    return data


def json_text(data) -> str:
    """`to_json` output as strict JSON text: non-finite reals as "NaN",
    "Infinity" or "-Infinity" strings (what `stgen run/call --json` print)."""
    return json.dumps(_finite_only(data), allow_nan=False)


def _flat_elements(value) -> list:
    """The row-major elements of a stored array (a flat list, or an object
    that iterates over its elements in that order)."""
    return list(value)


def _describe(data) -> str:
    if isinstance(data, bool):
        return "true" if data else "false"
    if data is None:
        return "null"
    if isinstance(data, str):
        return f"string {data!r}"
    if isinstance(data, list):
        return f"a list of {len(data)}"
    if isinstance(data, dict):
        return "an object"
    return repr(data)


def from_json(data, t, path: str = "value", dialect: str = "iec"):
    """A JSON value (as loaded by `json.loads`) as a stored value of type `t`.

    Arrays come back as flat row-major lists, structs and FB instances as
    dicts keyed by upper-case member name (missing members take their
    default); the caller copies them into its objects.  Anything that does
    not fit raises `JsonValueError` naming `path` and what was expected.
    """
    t = resolve_alias(t)

    def fail(expected: str):
        raise JsonValueError(f"{path}: expected {expected}, got {_describe(data)}")

    if isinstance(t, ElementaryType):
        kind = t.kind
        if kind == "bool":
            if isinstance(data, bool):
                return data
            if isinstance(data, int) and data in (0, 1):
                return bool(data)
            fail("BOOL (true or false)")
        if kind in ("int", "bits"):
            if isinstance(data, bool):
                fail(f"{t.name} integer")
            if isinstance(data, float) and data.is_integer():
                data = int(data)
            if not isinstance(data, int):
                fail(f"{t.name} integer")
            if not t.min <= data <= t.max:
                raise JsonValueError(
                    f"{path}: {data} is outside the range of {t.name} ({t.min}..{t.max})")
            return data
        if kind == "real":
            if isinstance(data, str) and data in NON_FINITE_NAMES:
                data = NON_FINITE_NAMES[data]
            if isinstance(data, bool) or not isinstance(data, (int, float)):
                names = ' (or "NaN", "Infinity", "-Infinity")' if isinstance(data, str) else ""
                fail(f"{t.name} number{names}")
            try:
                value = float(data)
            except OverflowError:       # an int beyond the double range
                value = math.inf
            stored = to_real32(value) if t.bits == 32 else value
            if math.isinf(stored) and not (isinstance(data, float) and math.isinf(data)):
                raise JsonValueError(f"{path}: {data} is outside the range of {t.name}")
            return stored
        if not isinstance(data, str):
            examples = {"time": "T#1s500ms", "date": "D#2024-01-31",
                        "tod": "TOD#12:30:00", "dt": "DT#2024-01-31-12:30:00"}
            fail(f"{t.name} literal string such as \"{examples[kind]}\"")
        try:
            return PARSERS[kind](data)
        except ValueFormatError as exc:
            raise JsonValueError(f"{path}: {exc}") from None
    if isinstance(t, StringType):
        if not isinstance(data, str):
            fail(f"{t} string")
        if string_size(data, dialect) > t.length:
            raise JsonValueError(f"{path}: string of {string_size(data, dialect)} {STRING_UNITS[dialect]}s "
                                 f"exceeds {t}")
        return data
    if isinstance(t, EnumType):
        if isinstance(data, str):
            for key, (_, number) in t.values.items():
                if key == data.upper():
                    return number
            fail(f"a value of {t.name} ({', '.join(n for n, _ in t.values.values())})")
        if isinstance(data, int) and not isinstance(data, bool):
            if data in {v for _, v in t.values.values()}:
                return data
        fail(f"a value of {t.name}")
    if isinstance(t, ArrayType):
        return _array_from_json(data, t, path, dialect)
    if isinstance(t, (StructType, FBType)):
        if not isinstance(data, dict):
            fail(f"an object for {t.name}")
        members = {name.upper(): (name, ft) for name, ft in _members(t)}
        out = {key: default_value(ft) for key, (_, ft) in members.items()}
        for key, item in data.items():
            member = members.get(str(key).upper())
            if member is None:
                raise JsonValueError(
                    f"{path}: {t.name} has no member {key!r} "
                    f"(members: {', '.join(n for n, _ in members.values())})")
            out[member[0].upper()] = from_json(item, member[1], f"{path}.{member[0]}", dialect)
        return out
    raise JsonValueError(f"{path}: values of type {t} cannot be given as JSON")


def _array_from_json(data, t: ArrayType, path: str, dialect: str = "iec") -> list:
    flat: list = []

    def walk(item, level: int, prefix: list[int]):
        lo, hi = t.dims[level]
        n = hi - lo + 1
        where = f"{path}[{', '.join(map(str, prefix))}]" if prefix else path
        if not isinstance(item, list) or len(item) != n:
            raise JsonValueError(
                f"{where}: expected a list of {n} elements ({lo}..{hi}), got {_describe(item)}")
        for i, element in enumerate(item):
            index = prefix + [lo + i]
            if level + 1 < len(t.dims):
                walk(element, level + 1, index)
            else:
                flat.append(from_json(element, t.element, f"{path}[{', '.join(map(str, index))}]", dialect))

    walk(data, 0, [])
    return flat
