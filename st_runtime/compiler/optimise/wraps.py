"""`wraps`: a store of MIN or MAX of integers needs no wrap when their range fits the target.

`SyncCalls := MIN(SyncCalls + 1, 2);` (SP_Controller, every scan) was stored as
`((min(v + 1, 2) + 32768 & 65535) - 32768)`.  The value of MIN is one of its inputs,
so it is at most the least upper bound of any input and at least the least lower bound
of all of them (MAX the other way round); an integer variable always holds a value of
its type (every store wraps or checks, so does a value from outside: objects.py
`store_value`), a literal is itself, and `+ -` of such operands add their ranges.  Here
MIN lies in [-32767, 2], inside INT, so the wrap would give the value back: it is left
out.  Under a dialect that wraps inside expressions (exprs.py `settled`) each input is
wrapped into its type before MIN sees it (or shown to lie there), so its range is the
type's.  Exact: only a wrap that would return its operand is left out.

`tested`: a store that still wraps into DINT, UDINT, LINT or ULINT tests the value against
the type's range first and wraps only a value outside it:
`(_t if lo <= (_t := v) <= hi else <wrap of _t>)`.  The wrap of a value inside the range is
that value (an int: the store's operand is an integer operation), so the result is the same
int; TRJ_OceanWave's `ClockCount := ClockCount + 1` (LINT, every scan) then makes no
three-digit integers (`+ 2**63`, `& (2**64 - 1)`, `- 2**63`, each allocated), only two
comparisons.  Not below 32 bits, where the wrap's operands are one-digit integers.
"""

from __future__ import annotations

from ... import ast
from ...dialects import DIALECTS

_SELECTIONS = {"MIN": min, "MAX": max}


def selection_range(compiler, expr) -> tuple[int, int] | None:
    """A range holding every value of `expr` when it is MIN or MAX of integers; else None."""
    if not (isinstance(expr, ast.Call) and isinstance(expr.callee, ast.Name)
            and expr.callee.name.upper() in _SELECTIONS and expr.args):
        return None
    target = compiler.program.call_targets.get(id(expr))
    if target is None or target.kind != "function" or target.pou is not None or _bounds(compiler, expr) is None:
        return None
    settled = DIALECTS[compiler.program.dialect].wraps_in_expressions
    ranges = [_bounds(compiler, arg.value) if settled else _exact(compiler, arg.value) for arg in expr.args]
    if any(r is None for r in ranges):
        return None
    pick = _SELECTIONS[expr.callee.name.upper()]
    return pick(r[0] for r in ranges), pick(r[1] for r in ranges)


def _exact(compiler, expr) -> tuple[int, int] | None:
    """A range holding every value of the integer `expr`, computed exactly (no wrap)."""
    bounds = _bounds(compiler, expr)
    if bounds is None:
        return None
    known = compiler.static_range(expr)
    if known is None and isinstance(expr, ast.Name):
        known = bounds                      # a variable holds a value of its type
    elif known is None and isinstance(expr, ast.Binary) and expr.op in ("+", "-"):
        left, right = _exact(compiler, expr.left), _exact(compiler, expr.right)
        if left is not None and right is not None:
            known = (left[0] + right[0], left[1] + right[1]) if expr.op == "+" \
                else (left[0] - right[1], left[1] - right[0])
    return known


def _bounds(compiler, expr) -> tuple[int, int] | None:
    """The range of `expr`'s integer type (ANY_INT), else None."""
    from ..exprs import elementary, int_bounds

    t = elementary(compiler.ty(expr))
    return int_bounds(t) if t is not None and t.kind == "int" else None


def tested(value: str, e, temp) -> str | None:
    """`value` (an integer expression) as stored into the integer type `e` of 32 bits or
    more, tested against the type's range before its wrap (exprs.py `_wrapped`); else None."""
    from ..exprs import _wrapped, int_bounds

    if e.kind != "int" or e.bits < 32:
        return None
    low, high = int_bounds(e)
    name = temp()
    return f"({name} if {low} <= ({name} := {value}) <= {high} else {_wrapped(name, e)})"
