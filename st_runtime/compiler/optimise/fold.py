"""Constant folding: `VAR CONSTANT` array elements and constant IF conditions.

`PERMUTATION[3, 2]` of a CONSTANT array with constant indices is the
element's initial value (a constant can never change), so the compiler
writes the literal instead of an indexed read.  Inside an unrolled loop the
control variable is a constant too (unroll.py), which is what makes the
Leibniz table's reads constant.  An IF whose conditions are all constant
(`PERMUTATION_SIGN[7] > 0`) compiles to the branch taken only; the branch
charges what it charged before (its lead, statements.py).
"""

from __future__ import annotations

import operator

from ... import ast
from ...dialects import DIALECTS
from ...types import ArrayType, resolve_alias
from ..initial import CompileError
from . import kept

_COMPARE = {"=": operator.eq, "<>": operator.ne, "<": operator.lt, "<=": operator.le,
            ">": operator.gt, ">=": operator.ge}
_INT_OPS = {"+": operator.add, "-": operator.sub, "*": operator.mul}


def constant_element(compiler, e: ast.Index):
    """The value of `e` when it reads a CONSTANT array at constant, in-range indices; else None."""
    found = _plan(compiler, e)
    if found is None:
        return None
    steps, values = found
    offset = 0
    unrolled = compiler.unrolled
    for index, name, lo, hi, stride in steps:      # (the last index first, as ever)
        if name is not None:        # a FOR variable: constant only in an unrolled copy
            value = unrolled.get(name)
        else:
            value = compiler.constant_of(index)
        if not isinstance(value, int) or isinstance(value, bool) or not lo <= value <= hi:
            return None                         # out of range: left to the runtime's fault
        offset += (value - lo) * stride
    if offset >= len(values):
        return None
    value = values[offset]
    return value if isinstance(value, (int, float)) else None


def _plan(compiler, e):
    """`_element_plan` of `e`, found once (kept by id: the AST outlives the compile)."""
    cache = kept(compiler, "_constant_arrays", dict)
    found = cache.get(id(e), cache)         # (the cache itself: not looked at yet)
    if found is cache:
        found = cache[id(e)] = _element_plan(compiler, e) if isinstance(e.base, ast.Name) else None
    return found


def _element_plan(compiler, e):
    """(steps, flat values) of a read of a whole CONSTANT array: a step per index from the
    last, (index, its upper name when `constant_of` can only find it among the unrolled
    FOR variables, lo, hi, stride); None for another read."""
    found = _constant_array(compiler, e)
    if found is None:
        return None
    dims, values = found
    steps = []
    for index, (lo, hi, stride) in zip(reversed(e.indices), dims):
        name = index.name.upper() if type(index) is ast.Name \
            and compiler.program.constants.get(id(index)) is None else None
        steps.append((index, name, lo, hi, stride))
    return tuple(steps), values


def _constant_array(compiler, e):
    """((lo, hi, stride) per dimension from the last, flat initial values) when `e` indexes a whole
    CONSTANT array, else None."""
    try:
        place = compiler.scope.place_of(e.base)
    except CompileError:
        return None
    symbol = place.symbol
    if symbol.kind == "VAR_EXTERNAL":           # the global's declaration holds the values
        symbol = compiler.program.globals.get(e.base.name.upper(), symbol)
    t = resolve_alias(symbol.type)
    if symbol.init is None or not symbol.constant or not isinstance(t, ArrayType) \
            or isinstance(resolve_alias(t.element), ArrayType) or len(e.indices) != len(t.dims):
        return None
    values = _flat_values(compiler, symbol)
    return None if values is None else (_strided(t.dims), values)


def _strided(dims) -> tuple:
    """(lo, hi, stride) of each dimension, the last first (it varies fastest)."""
    out, stride = [], 1
    for lo, hi in reversed(dims):
        out.append((lo, hi, stride))
        stride *= hi - lo + 1
    return tuple(out)


def _flat_values(compiler, symbol):
    cache = compiler.unit.__dict__.setdefault("constant_values", {})
    if id(symbol) not in cache:
        value = compiler.unit.initial.of_symbol(symbol).maker()
        cache[id(symbol)] = list(value) if isinstance(value, list) else None
    return cache[id(symbol)]


def constant_condition(compiler, e):
    """True/False when `e` is a condition made of constants only (comparisons,
    AND/OR/XOR/NOT of BOOLs, integer + - *), else None."""
    value = _evaluate(compiler, e)
    return value if isinstance(value, bool) else None


def constant_integer(compiler, e):
    """An integer + - * of constants (exact, as intermediate integers are here), else None."""
    if _never(compiler, e):
        return None
    value = _evaluate(compiler, e)
    return value if _is_int(value) else None


def _never(compiler, e) -> bool:
    """Whether `_evaluate(e)` is None in every unrolled copy: an operation the checker did
    not fold whose left operand is so (evaluated first), or a read of an array that is not
    CONSTANT (the Leibniz products: `Matrix[1, ...] * Matrix[2, ...] * ...`).  Once a node."""
    cache = kept(compiler, "_never_constant", dict)
    hit = cache.get(id(e))
    if hit is None or hit[0] is not e:
        cls = type(e)
        if cls is ast.Binary:
            never = compiler.folded(e) is None and _never(compiler, e.left)
        elif cls is ast.Index:
            never = compiler.program.constants.get(id(e)) is None and _plan(compiler, e) is None
        else:
            never = False
        hit = cache[id(e)] = (e, never)
    return hit[1]


def _evaluate(compiler, e):
    # constant_of asks constant_integer about a Binary: only the checker's folding here.
    value = compiler.folded(e) if isinstance(e, ast.Binary) else compiler.constant_of(e)
    if value is not None:
        return value
    if isinstance(e, ast.Unary) and e.op.upper() == "NOT":
        inner = _evaluate(compiler, e.operand)
        return (not inner) if isinstance(inner, bool) else None
    if not isinstance(e, ast.Binary):
        return None
    op = e.op.upper()
    left = _evaluate(compiler, e.left)
    if left is None:
        return None
    right = _evaluate(compiler, e.right)
    if right is None or type(left) is not type(right) or not isinstance(left, (bool, int)):
        return None
    if op in _COMPARE:
        return _COMPARE[op](left, right)
    if isinstance(left, bool):
        return {"AND": left and right, "&": left and right, "OR": left or right,
                "XOR": left != right}.get(op)
    if op in _INT_OPS:          # exact under iec; under nj while inside the type (_unwrapped)
        return _unwrapped(compiler, e, _INT_OPS[op](left, right))
    return None


def _unwrapped(compiler, e, value: int) -> int | None:
    """`value` of the integer operation `e`, or None where the dialect wraps inside expressions
    (the NJ) and `value` leaves `e`'s type: the code wraps it where it is compared (exprs.py
    `settled`), so the condition is left to the code (under `iec` the code is exact too)."""
    from ..exprs import int_bounds      # (exprs imports the passes: read at call time)

    if not DIALECTS[compiler.program.dialect].wraps_in_expressions:
        return value
    bounds = int_bounds(compiler.ty(e))
    return value if bounds is None or bounds[0] <= value <= bounds[1] else None


def _is_int(value) -> bool:
    return isinstance(value, int) and not isinstance(value, bool)
