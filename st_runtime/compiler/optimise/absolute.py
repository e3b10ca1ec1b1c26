"""`ABS(x) < B`, `ABS(x) <= B`, `ABS(x) > B`, `ABS(x) >= B` without the call (the `inline` switch).

For any numbers x and B (Python ints or floats), `abs(x) <= B` is `-B <= x <= B` and
`abs(x) < B` is `-B < x < B`: a NaN on either side fails both; below zero, B admits no
x either way (-B > B), and B = -0.0 admits only the zeros with `<=`, none with `<`;
-0.0 and 0.0 compare equal; ints and floats compare exactly.  The chained comparison
evaluates x once, as the call did (`abs` of a number cannot raise), and B is a literal
or a local, read twice with the same value.  Two float comparisons cost less than a
builtin call: the FK's convergence test and the LU's zero-pivot test take this form.
With B the largest double and x a local or a value of the `reuse` pass (a name, read
twice with the same value), `abs(x) <= B` is finiteness, `x < 1e309 and x > -1e309`
(pysrc.finite_test: false for an infinity or a NaN; two comparisons, no float made): the
IK's and FK's `NOT (ABS(Position[Leg]) <= SP_LREAL_MAX)`.  `abs(x) > B` is `x > B or
x < -B` and `abs(x) >= B` is `x >= B or x <= -B`, for the same reasons (a NaN fails both
tests, as it fails the one; below zero B admits every other x either way), x set into a temp
by the first test when it is not a name: SP_Controller's six `ABS(IkCylinderPos[k] -
SpCylinderSetpoint[k]) > 0.25` without a call and its float.
"""

from __future__ import annotations

import math
import sys

from ... import ast
from ..pysrc import finite_test, pyliteral

_MIRROR = {"<": ">", "<=": ">=", ">": "<", ">=": "<="}


def bounded(compiler, e, left: str, right: str) -> str | None:
    """Python for the comparison `e` (codes `left`, `right`) as a chained comparison, or None."""
    op = e.op
    if op not in _MIRROR:
        return None
    if _is_abs(compiler, e.right) and not _is_abs(compiler, e.left):
        op, left, right, bound = _MIRROR[op], right, left, e.left
    elif _is_abs(compiler, e.left):
        bound = e.right
    else:
        return None
    if not (left.startswith("abs(") and left.endswith(")")):
        return None
    if op in (">", ">="):
        return _outside(compiler, op, left[4:-1], right)
    if right.isidentifier():            # a local: read twice, the same value, no fault
        return f"(-{right} {op} {left[4:-1]} {op} {right})"
    value = _literal(right)
    if value is None or not math.isfinite(value):
        return None
    from .reuse import is_token     # (reuse imports the compiler's scope, which imports exprs)

    x = left[4:-1]
    if op == "<=" and value == sys.float_info.max and (x.isidentifier() or is_token(x)):
        return f"({finite_test(x, x)})"
    return f"({pyliteral(-value)} {op} {x} {op} {right})"


def _outside(compiler, op: str, x: str, right: str) -> str | None:
    """`abs(x) > B` as `x > B or x < -B` (`>=`: `x >= B or x <= -B`), x read once (a name, or
    set into a temp by the first comparison), B a local or a finite literal."""
    if right.isidentifier():
        low = f"-{right}"
    else:
        value = _literal(right)
        if value is None or not math.isfinite(value):
            return None
        low = pyliteral(-value)
    from .reuse import is_token

    first = again = x
    if not (x.isidentifier() or is_token(x)):
        again = compiler.temp()
        first = f"({again} := {x})"
    return f"({first} {op} {right} or {again} {_MIRROR[op]} {low})"


def _literal(code: str):
    """The number a Python literal `code` is (the bound exactly as the comparison reads it)."""
    try:
        value = float(code) if any(c in code for c in ".eE") else int(code)
    except ValueError:
        return None
    return value if pyliteral(value) == code else None


def _is_abs(compiler, node) -> bool:
    if not (isinstance(node, ast.Call) and len(node.args) == 1):
        return False
    target = compiler.program.call_targets.get(id(node))
    return (target is not None and target.kind == "function" and getattr(target, "pou", None) is None
            and str(target.name).upper() == "ABS")
