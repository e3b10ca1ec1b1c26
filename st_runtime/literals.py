"""Decoding of IEC 61131-3 literal texts into Python values.

Every function takes the literal as written (one lexer token) and returns its
value, or raises `LiteralError` with a message fit for a diagnostic.  Exact
arithmetic (`Fraction`) is used for durations so that `T#0.1s` is exactly
100_000_000 ns.

Encodings: durations, times of day and date-times are integer nanoseconds;
DATE and DATE_AND_TIME count from 1970-01-01 (the IEC/NJ epoch).
"""

from __future__ import annotations

import datetime
import re
from fractions import Fraction

NS_PER_UNIT = {
    "D": 86_400 * 10**9,
    "H": 3_600 * 10**9,
    "M": 60 * 10**9,
    "S": 10**9,
    "MS": 10**6,
    "US": 10**3,
    "NS": 1,
}
# Longest units first so that "ms" is not read as "m" followed by "s".
_TIME_PART = re.compile(r"([0-9][0-9_]*(?:\.[0-9_]+)?)(ms|us|ns|d|h|m|s)_?", re.IGNORECASE)
_EPOCH = datetime.date(1970, 1, 1)
_NS_PER_DAY = 86_400 * 10**9

REAL_TYPES = frozenset({"REAL", "LREAL"})
BOOL_TYPES = frozenset({"BOOL"})
DURATION_PREFIXES = frozenset({"T", "TIME", "LT", "LTIME"})


class LiteralError(ValueError):
    """A literal that the lexer accepted but that has no valid value."""


def _digits(text: str) -> str:
    if text.startswith("_") or text.endswith("_") or "__" in text:
        raise LiteralError(f"misplaced '_' separator in '{text}'")
    return text.replace("_", "")


def decode_int(text: str) -> int:
    """`1_000` -> 1000."""
    return int(_digits(text))


def decode_based(text: str) -> int:
    """`16#FF` -> 255, `2#1010_0101` -> 165, `8#17` -> 15."""
    base_text, _, digits = text.partition("#")
    base = int(base_text)
    if base not in (2, 8, 16):
        raise LiteralError(f"base {base} is not allowed in '{text}' (use 2#, 8# or 16#)")
    clean = _digits(digits)
    try:
        return int(clean, base)
    except ValueError:
        raise LiteralError(f"'{digits}' is not a base-{base} number in '{text}'") from None


def decode_real(text: str) -> float:
    """`1.5E-3` -> 0.0015; `1E6` -> 1000000.0."""
    mantissa, sep, exponent = text.upper().partition("E")
    return float(_digits(mantissa) + sep + exponent.replace("_", ""))


def decode_number(text: str) -> int | float:
    """An integer, based or real number (the part after a type prefix)."""
    sign = 1
    if text[:1] in "+-":
        sign = -1 if text[0] == "-" else 1
        text = text[1:]
    if "#" in text:
        return sign * decode_based(text)
    if "." in text or "e" in text or "E" in text:
        return sign * decode_real(text)
    return sign * decode_int(text)


def decode_duration(text: str) -> int:
    """`T#1s500ms` -> 1_500_000_000 ns; `TIME#-2.5s` -> -2_500_000_000 ns."""
    _, _, body = text.partition("#")
    sign = 1
    if body[:1] in "+-":
        sign = -1 if body[0] == "-" else 1
        body = body[1:]
    total = Fraction(0)
    pos = 0
    for match in _TIME_PART.finditer(body):
        if match.start() != pos:
            break
        total += Fraction(_digits(match.group(1))) * NS_PER_UNIT[match.group(2).upper()]
        pos = match.end()
    if pos != len(body) or pos == 0:
        raise LiteralError(f"'{text}' is not a valid duration (e.g. T#1s500ms)")
    return sign * round(total)


def _date_ns(year: str, month: str, day: str, text: str) -> int:
    try:
        date = datetime.date(int(year), int(month), int(day))
    except ValueError as exc:
        raise LiteralError(f"'{text}' is not a valid date: {exc}") from None
    return (date - _EPOCH).days * _NS_PER_DAY


def _clock_ns(hours: str, minutes: str, seconds: str | None, text: str) -> int:
    h, m = int(hours), int(minutes)
    s = Fraction(seconds) if seconds else Fraction(0)
    if h > 23 or m > 59 or s >= 60:
        raise LiteralError(f"'{text}' is not a valid time of day")
    return round((h * 3600 + m * 60 + s) * 10**9)


def decode_date(text: str) -> int:
    """`D#1970-01-02` -> 86_400_000_000_000 ns since 1970-01-01."""
    year, month, day = text.partition("#")[2].split("-")
    return _date_ns(year, month, day, text)


def decode_time_of_day(text: str) -> int:
    """`TOD#12:30:15.5` -> ns since midnight."""
    parts = text.partition("#")[2].split(":")
    return _clock_ns(parts[0], parts[1], parts[2] if len(parts) > 2 else None, text)


def decode_date_and_time(text: str) -> int:
    """`DT#1970-01-01-00:00:01` -> 1_000_000_000 ns since the epoch."""
    body = text.partition("#")[2]
    year, month, day, clock = body.split("-", 3)
    parts = clock.split(":")
    return _date_ns(year, month, day, text) + _clock_ns(
        parts[0], parts[1], parts[2] if len(parts) > 2 else None, text
    )


_ESCAPES = {"$": "$", "'": "'", '"': '"', "L": "\n", "N": "\n", "R": "\r", "T": "\t", "P": "\f"}


def decode_string(text: str) -> str:
    """The value of `'...'` (STRING, `$hh` escapes) or `"..."` (WSTRING, `$hhhh`).

    `'It$'s'` -> "It's"; `'a$Nb'` -> "a\\nb"; `'$41'` -> "A".
    """
    quote, body = text[0], text[1:-1]
    hex_width = 2 if quote == "'" else 4
    out: list[str] = []
    i = 0
    n = len(body)
    while i < n:
        ch = body[i]
        if ch != "$":
            out.append(ch)
            i += 1
            continue
        nxt = body[i + 1 : i + 2]
        if nxt.upper() in _ESCAPES and nxt:
            out.append(_ESCAPES[nxt.upper()])
            i += 2
            continue
        code = body[i + 1 : i + 1 + hex_width]
        if len(code) == hex_width and all(c in "0123456789abcdefABCDEF" for c in code):
            value = int(code, 16)
            i += 1 + hex_width
            if 0xD800 <= value <= 0xDFFF:       # a UTF-16 surrogate: only a pair is a character
                value, i = _surrogate_pair(body, i, value, code)
            out.append(chr(value))
            continue
        shown = nxt if nxt.isprintable() and nxt else repr(nxt)
        raise LiteralError(
            f"invalid escape '${shown}' in string (use $$ $' $\" $L $N $R $T $P or "
            f"${'hh' if hex_width == 2 else 'hhhh'})"
        )
    return "".join(out)


def _surrogate_pair(body: str, i: int, high: int, code: str) -> tuple[int, int]:
    """(code point, next index) of the pair `$Dhhh$Dhhh` whose first half was
    `high` and whose second half starts at `i`; LiteralError for a lone half,
    which is no character at all (issue 15: it passed the checker, then broke
    the CSV writer)."""
    low = body[i + 1 : i + 5]
    if (0xD800 <= high <= 0xDBFF and body[i : i + 1] == "$" and len(low) == 4
            and all(c in "0123456789abcdefABCDEF" for c in low) and 0xDC00 <= int(low, 16) <= 0xDFFF):
        return 0x10000 + ((high - 0xD800) << 10) + (int(low, 16) - 0xDC00), i + 5
    raise LiteralError(f"'${code}' is half of a UTF-16 surrogate pair, not a character: write the"
                       " pair ($D83D$DE00) or the character itself")


def encode_string(value: str, wide: bool = False) -> str:
    """The ST source text of a string value (inverse of `decode_string`)."""
    quote = '"' if wide else "'"
    out = [quote]
    for ch in value:
        if ch == "$":
            out.append("$$")
        elif ch == quote:
            out.append("$" + ch)
        elif ch == "\n":
            out.append("$N")
        elif ch == "\r":
            out.append("$R")
        elif ch == "\t":
            out.append("$T")
        elif ch == "\f":
            out.append("$P")
        elif ch.isprintable():
            out.append(ch)
        elif ord(ch) < 256:
            out.append(f"${ord(ch):02X}")
        elif wide and ord(ch) < 0x10000:
            out.append(f"${ord(ch):04X}")
        else:
            out.append(ch)  # no escape exists for it: keep the character itself
    out.append(quote)
    return "".join(out)


def encode_duration(nanoseconds: int, prefix: str = "T") -> str:
    """`1_500_000_000` -> `T#1s500ms` (inverse of `decode_duration`)."""
    sign = "-" if nanoseconds < 0 else ""
    rest = abs(nanoseconds)
    if rest == 0:
        return f"{prefix}#0s"
    parts = []
    for unit in ("D", "H", "M", "S", "MS", "US", "NS"):
        size = NS_PER_UNIT[unit]
        count, rest = divmod(rest, size)
        if count:
            parts.append(f"{count}{unit.lower()}")
    return f"{prefix}#{sign}{''.join(parts)}"


def encode_date(nanoseconds: int) -> str:
    days = nanoseconds // _NS_PER_DAY
    return "D#" + (_EPOCH + datetime.timedelta(days=days)).isoformat()


def _clock_text(nanoseconds: int) -> str:
    seconds, ns = divmod(nanoseconds, 10**9)
    h, rem = divmod(seconds, 3600)
    m, s = divmod(rem, 60)
    text = f"{h:02d}:{m:02d}:{s:02d}"
    if ns:
        text += "." + f"{ns:09d}".rstrip("0")
    return text


def encode_time_of_day(nanoseconds: int) -> str:
    return "TOD#" + _clock_text(nanoseconds)


def encode_date_and_time(nanoseconds: int) -> str:
    days, clock = divmod(nanoseconds, _NS_PER_DAY)
    return f"DT#{(_EPOCH + datetime.timedelta(days=days)).isoformat()}-{_clock_text(clock)}"
