"""Exact folding of constant expressions (IEC semantics on Python values).

Values are Python `bool`, `int` (integers, bit strings, TIME nanoseconds) and
`float`.  Integer `/` truncates toward zero and `MOD` takes the sign of the
dividend, as on the controller (the run time's `values.int_div`/`int_mod`);
`**` is the library's EXPT and real `/`
is `values.real_div`, so a folded `0.0 ** -1.0` or `1.0 / 0.0` is +inf
exactly as at run time.  A fold that cannot be done (a division by
zero, an operator on unsuitable values) yields `NOT_CONSTANT`, and the
caller reports what it must.
"""

from __future__ import annotations

from ..faults import STFault
from ..stdlib.functions import EXPT
from ..values import int_div, int_mod, real_div


class _NotConstant:
    def __repr__(self) -> str:
        return "NOT_CONSTANT"


NOT_CONSTANT = _NotConstant()


class DivisionByZero(Exception):
    pass


def _is_number(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def apply_unary(op: str, v):
    """`-`, `+` on numbers; `NOT` on BOOL (bit strings are handled by the caller)."""
    if op == "-" and _is_number(v):
        return -v
    if op == "+" and _is_number(v):
        return v
    if op == "NOT" and isinstance(v, bool):
        return not v
    return NOT_CONSTANT


def apply_binary(op: str, a, b):
    """Fold `a op b`; raises DivisionByZero for an integer division by zero."""
    if a is NOT_CONSTANT or b is NOT_CONSTANT:
        return NOT_CONSTANT
    if op in ("AND", "&", "OR", "XOR"):
        if isinstance(a, bool) and isinstance(b, bool):
            return {"AND": a and b, "&": a and b, "OR": a or b, "XOR": a != b}[op]
        if isinstance(a, int) and isinstance(b, int):
            return {"AND": a & b, "&": a & b, "OR": a | b, "XOR": a ^ b}[op]
        return NOT_CONSTANT
    if op in ("=", "<>", "<", ">", "<=", ">="):
        if isinstance(a, str) != isinstance(b, str):
            return NOT_CONSTANT
        return {
            "=": a == b, "<>": a != b, "<": a < b,
            ">": a > b, "<=": a <= b, ">=": a >= b,
        }[op]
    if not (_is_number(a) and _is_number(b)):
        return NOT_CONSTANT
    both_int = isinstance(a, int) and isinstance(b, int)
    try:
        if op == "+":
            return a + b
        if op == "-":
            return a - b
        if op == "*":
            return a * b
        if op == "/":
            if both_int:
                return int_div(a, b)
            return real_div(float(a), float(b))     # x / 0.0 is +-inf or NaN, as at run time
        if op == "MOD":
            return int_mod(a, b) if both_int else NOT_CONSTANT
        if op == "**":      # the runtime's EXPT: IEEE results (+inf, NaN), no fault, as the NJ
            return EXPT(float(a), b)
    except STFault:         # values.int_div/int_mod: the run-time fault of a zero divisor
        raise DivisionByZero() from None
    except (OverflowError, ZeroDivisionError, ValueError):
        return NOT_CONSTANT
    return NOT_CONSTANT
