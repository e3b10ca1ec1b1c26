"""Standard functions of IEC 61131-3 (numeric, selection, bit string, string).

`FUNCTIONS` maps the upper-case ST name to a Python callable that takes the
arguments in IEC order (positional) and returns the result.  The compiler
stores the result with the usual wrap/round of the destination, so these
functions do not wrap integers or round REALs themselves, with one
exception: bit-string functions mask to the width they are told.

Calling conventions the compiler must follow:

* Width-dependent functions take the bit width of the IN operand's type as a
  trailing argument: `SHL(IN, N, bits)`, `SHR(IN, N, bits)`,
  `ROL(IN, N, bits)`, `ROR(IN, N, bits)`, `NOT(IN, bits)` (bits = 1 for BOOL
  gives logical NOT).  The compiler appends `ElementaryType.bits` of IN's
  type as a literal.
* Extensible functions take any number of inputs: MIN, MAX, MUX (after K),
  AND, OR, XOR, CONCAT.
* MID(IN, L, P), LEFT(IN, L), RIGHT(IN, L), INSERT(IN1, IN2, P),
  DELETE(IN, L, P), REPLACE(IN1, IN2, L, P), FIND(IN1, IN2): positions are
  1-based as in IEC; a position or length out of range is an F-STRING fault.

Math domain errors.  The NJ computes REAL/LREAL with IEEE 754 rules and does
not stop on them: "illegal calculations result in nonnumeric data", overflow
gives +/-infinity (NJ-series CPU Unit Software User's Manual W501, section
"Data Processing" / "Special Value Calculations"), and LN/LOG list -inf as a
valid output (Instructions Reference W502, LN and LOG).  `FUNCTIONS` does the
same: SQRT(-1) = NaN, LN(0) = -inf, ASIN(2) = NaN, EXP(1000) = +inf, no
fault.  The compiled code uses `FUNCTIONS` only, for calls and for the `**`
operator alike, and the constant folders call the same EXPT, so every path
gives the NJ's result.  `STRICT_FUNCTIONS` is the same table with those cases
raising `STFault("F-MATH", ...)` instead, for Python callers that want to
stop at the first non-finite value; no controller option selects it.
"""

from __future__ import annotations

import math
from functools import reduce
from typing import Callable

from ..faults import FAULT_CODES, STFault
from .bcd import BCD_FUNCTIONS
from .conversions import CONVERSIONS, conversion  # noqa: F401  (re-exported)

FAULT_CODES.setdefault("F-STRING", "string function position or length out of range")

_INF = math.inf
_NAN = math.nan


# ---------------------------------------------------------------------------
# Numeric functions (IEEE results, as the NJ)

def ABS(x):
    return abs(x)


def SQRT(x: float) -> float:
    if x < 0:
        return _NAN
    return math.sqrt(x)


def LN(x: float) -> float:
    if x > 0:
        return math.log(x) if x != _INF else _INF
    if x == 0:
        return -_INF
    return _NAN          # negative or NaN


def LOG(x: float) -> float:
    if x > 0:
        return math.log10(x) if x != _INF else _INF
    if x == 0:
        return -_INF
    return _NAN


def EXP(x: float) -> float:
    try:
        return math.exp(x)
    except OverflowError:
        return _INF


def EXPT(base, exponent):
    """IN1 ** IN2 with IEEE 754 pow() special cases (C99 Annex F)."""
    if isinstance(base, int) and isinstance(exponent, int) and not isinstance(base, bool):
        if exponent >= 0:
            return base ** exponent
        base = float(base)
    try:
        return math.pow(base, exponent)
    except OverflowError:
        negative = base < 0 and float(exponent).is_integer() and int(exponent) % 2 == 1
        return -_INF if negative else _INF
    except ValueError:
        if base == 0:            # 0 ** negative: pole
            odd = float(exponent).is_integer() and int(exponent) % 2 == 1
            return math.copysign(_INF, base) if odd else _INF
        return _NAN              # negative ** non-integer


def _trig(fn: Callable[[float], float]) -> Callable[[float], float]:
    def call(x: float) -> float:
        try:
            return fn(x)
        except ValueError:       # sin/cos/tan of +/-inf
            return _NAN
    call.__name__ = fn.__name__.upper()
    return call


SIN = _trig(math.sin)
COS = _trig(math.cos)
TAN = _trig(math.tan)
ATAN = math.atan         # raises for no float (atan(+/-inf) = +/-pi/2): no wrapper to call


def ASIN(x: float) -> float:
    return math.asin(x) if -1.0 <= x <= 1.0 else _NAN


def ACOS(x: float) -> float:
    return math.acos(x) if -1.0 <= x <= 1.0 else _NAN


def TRUNC(x: float) -> int:
    """Toward zero (TRUNC(-3.55) = -3, W502).  Non-finite input: F-CONVERT."""
    if not math.isfinite(x):
        raise STFault("F-CONVERT", f"TRUNC({x!r}): not a finite number")
    return int(x)


# ---------------------------------------------------------------------------
# Selection

def MIN(*values):
    return min(values)


def MAX(*values):
    return max(values)


def LIMIT(mn, value, mx):
    """IEC: LIMIT(MN, IN, MX) = MIN(MAX(IN, MN), MX)."""
    return min(max(value, mn), mx)


def SEL(g: bool, in0, in1):
    return in1 if g else in0


def MUX(k: int, *inputs):
    if not 0 <= k < len(inputs):
        raise STFault("F-INDEX", f"MUX selector K={k} outside 0..{len(inputs) - 1}")
    return inputs[k]


def MOVE(x):
    return x


# ---------------------------------------------------------------------------
# Bit strings (width passed by the compiler, see module docstring)

def _check_shift(name: str, n: int) -> None:
    if n < 0:
        raise STFault("F-MATH", f"{name}: negative shift count {n}")


def SHL(value: int, n: int, bits: int) -> int:
    _check_shift("SHL", n)
    if n >= bits:
        return 0
    return (value << n) & ((1 << bits) - 1)


def SHR(value: int, n: int, bits: int) -> int:
    """Logical shift: zeros come in from the left (IEC)."""
    _check_shift("SHR", n)
    if n >= bits:
        return 0
    return (value & ((1 << bits) - 1)) >> n


def ROL(value: int, n: int, bits: int) -> int:
    _check_shift("ROL", n)
    mask = (1 << bits) - 1
    value &= mask
    n %= bits
    return ((value << n) | (value >> (bits - n))) & mask


def ROR(value: int, n: int, bits: int) -> int:
    _check_shift("ROR", n)
    mask = (1 << bits) - 1
    value &= mask
    n %= bits
    return ((value >> n) | (value << (bits - n))) & mask


def AND(*values):
    return reduce(lambda a, b: a & b, values)


def OR(*values):
    return reduce(lambda a, b: a | b, values)


def XOR(*values):
    return reduce(lambda a, b: a ^ b, values)


def NOT(value, bits: int):
    if bits == 1:
        return not value
    return ~value & ((1 << bits) - 1)


# ---------------------------------------------------------------------------
# Strings (1-based positions)

def _string_fault(message: str) -> STFault:
    return STFault("F-STRING", message)


def LEN(s: str) -> int:
    return len(s)


def CONCAT(*parts: str) -> str:
    return "".join(parts)


def LEFT(s: str, length: int) -> str:
    if length < 0:
        raise _string_fault(f"LEFT: negative length {length}")
    return s[:length]


def RIGHT(s: str, length: int) -> str:
    if length < 0:
        raise _string_fault(f"RIGHT: negative length {length}")
    return s[len(s) - length:] if length < len(s) else s


def _check_position(name: str, s: str, p: int, allow_end: bool = False) -> None:
    last = len(s) + 1 if allow_end else len(s)
    if not 1 <= p <= max(last, 1):
        raise _string_fault(f"{name}: position P={p} outside 1..{max(last, 1)} of a {len(s)}-character string")


def MID(s: str, length: int, p: int) -> str:
    """L characters of IN starting at position P (1-based)."""
    if length < 0:
        raise _string_fault(f"MID: negative length {length}")
    _check_position("MID", s, p)
    return s[p - 1:p - 1 + length]


def INSERT(s1: str, s2: str, p: int) -> str:
    """IN2 inserted after the P-th character of IN1 (P = 0 inserts in front)."""
    if not 0 <= p <= len(s1):
        raise _string_fault(f"INSERT: position P={p} outside 0..{len(s1)}")
    return s1[:p] + s2 + s1[p:]


def DELETE(s: str, length: int, p: int) -> str:
    """IN with L characters removed from position P."""
    if length < 0:
        raise _string_fault(f"DELETE: negative length {length}")
    _check_position("DELETE", s, p)
    return s[:p - 1] + s[p - 1 + length:]


def REPLACE(s1: str, s2: str, length: int, p: int) -> str:
    """IN1 with L characters from position P replaced by IN2."""
    if length < 0:
        raise _string_fault(f"REPLACE: negative length {length}")
    _check_position("REPLACE", s1, p, allow_end=True)
    return s1[:p - 1] + s2 + s1[p - 1 + length:]


def FIND(s1: str, s2: str) -> int:
    """Position (1-based) of the first IN2 in IN1, 0 when absent."""
    return s1.find(s2) + 1


# ---------------------------------------------------------------------------
# Tables

FUNCTIONS: dict[str, Callable] = {
    name: fn for name, fn in globals().items()
    if name.isupper() and callable(fn) and not name.startswith("_")
    and name not in ("CONVERSIONS", "FAULT_CODES", "FUNCTIONS")
}
FUNCTIONS.update({name: fn for name, (_, _, fn) in BCD_FUNCTIONS.items()})


def _strict(name: str, fn: Callable, bad: Callable[[float], bool]) -> Callable:
    def call(*args):
        result = fn(*args)
        if isinstance(result, float) and not math.isfinite(result) and bad(*args):
            raise STFault("F-MATH", f"{name}({', '.join(map(repr, args))}) is not a finite number")
        return result
    call.__name__ = name
    return call


def _finite_args(*args) -> bool:
    """A non-finite result from finite arguments is a domain/range error."""
    return all(math.isfinite(a) for a in args if isinstance(a, float))


STRICT_FUNCTIONS: dict[str, Callable] = dict(FUNCTIONS)
for _name in ("SQRT", "LN", "LOG", "EXP", "EXPT", "ASIN", "ACOS", "TAN"):
    STRICT_FUNCTIONS[_name] = _strict(_name, FUNCTIONS[_name], _finite_args)
del _name

# Functions whose last argument is the operand's bit width, appended by the
# compiler (see the module docstring).
WIDTH_ARGUMENT = frozenset({"SHL", "SHR", "ROL", "ROR", "NOT"})
