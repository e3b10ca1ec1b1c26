"""`rowswap`: the loop that exchanges two rows of a matrix through a buffer, as two slices.

    FOR Column := 1 TO SIZE DO                      (the whole last dimension)
        Held := Matrix[K, Column];
        Matrix[K, Column] := Matrix[PivotRow, Column];
        Matrix[PivotRow, Column] := Held;
    END_FOR;

(the LU's row exchange) unrolled is 3 x SIZE statements, each computing its
indices; it becomes, when the matrix is a Python list and both rows are in range:

    _a = (K - lo) * n; _b = (PivotRow - lo) * n
    Matrix[_a:_a + n], Matrix[_b:_b + n] = Matrix[_b:_b + n], Matrix[_a:_a + n]
    Held = Matrix[_b + n - 1]

Exact: the list holds its elements flattened row by row, so row r is the slice
`(r - lo) * n` to `+ n`; two different rows do not overlap and the statements
exchange them element by element, the same row exchanges nothing either way,
and the buffer ends holding the first row's last element (now the last of the
second row).  The elements are moved, not converted: the buffer has the
element type (an elementary number or BOOL: a store would neither round nor
wrap a value of its own type).  No statement of the loop can fault then (a list
of the declared size, indices in range), so none is recorded; the charges are
the loop's (charged up front by the FOR, which runs its whole count), and the
control variable gets the loop's final value as the unrolled copy sets it.
Otherwise (an unconnected VAR_IN_OUT, a row out of range: faults, each at its
statement) the unrolled loop runs as before.
"""

from __future__ import annotations

from dataclasses import dataclass

from ... import ast
from ...types import ArrayType, resolve_alias
from ..exprs import elementary


@dataclass
class RowSwap:
    matrix: str                 # Python name of the list
    held: str                   # Python name of the buffer
    rows: tuple                 # each row: an int (constant) or a Python local name
    lo: int                     # the first dimension's lower bound
    rows_hi: int                # ... upper bound
    width: int                  # elements of a row (the last dimension's length)


def match(compiler, s, values: range) -> RowSwap | None:
    """The row exchange `s` (an ast.For about to be unrolled over `values`) performs, or None."""
    body = s.body
    if len(body) != 3 or not all(isinstance(b, ast.Assign) and b.mode == ":=" for b in body):
        return None
    first, second, third = body
    column = s.variable.upper()
    held = _local(compiler, first.target)
    if held is None or not _same_name(third.value, first.target):
        return None
    a_first, a_second, a_third = first.value, second.target, second.value
    if not (_is_index(a_first) and _is_index(a_second) and _is_index(a_third) and _is_index(third.target)):
        return None
    name = _name_of(a_first.base)
    if name is None or any(_name_of(e.base) != name for e in (a_second, a_third, third.target)):
        return None
    place = compiler.scope.places.get(name)
    if place is None or place.how != "alias":
        return None
    t = resolve_alias(place.symbol.type)
    if not isinstance(t, ArrayType) or len(t.dims) != 2 or t.is_open:
        return None
    element = elementary(t.element)
    if element is None or element.kind not in ("real", "int", "bits", "bool") \
            or resolve_alias(compiler.scope.places[first.target.name.upper()].symbol.type) != resolve_alias(t.element):
        return None
    (lo, hi), (lo2, hi2) = t.dims
    if values != range(lo2, hi2 + 1):
        return None
    # row expressions: a_first and a_second the same row (K), a_third and third.target the other
    if any(not (isinstance(e.indices[1], ast.Name) and e.indices[1].name.upper() == column)
           for e in (a_first, a_second, a_third, third.target)):
        return None
    row_k, row_p = _row(compiler, a_first.indices[0]), _row(compiler, a_third.indices[0])
    if row_k is None or row_p is None or _row(compiler, a_second.indices[0]) != row_k \
            or _row(compiler, third.target.indices[0]) != row_p:
        return None
    row_names = {r for r in (row_k, row_p) if isinstance(r, str)}
    loop_place = compiler.scope.places.get(column)
    if held in row_names or column == first.target.name.upper() or (
            loop_place is not None and loop_place.name in row_names):
        return None
    if any(isinstance(r, int) and not lo <= r <= hi for r in (row_k, row_p)):
        return None         # a row out of range faults: the statements as they are
    return RowSwap(place.name, held, (row_k, row_p), lo, hi, hi2 - lo2 + 1)


def emit(compiler, swap: RowSwap, after) -> None:
    """The fast path and its guard; the caller writes the unrolled loop in the `else:`."""
    o = compiler.out
    names = compiler.unit.namespace
    if names.get("_type") is not type:      # (the generated code sees only a few builtins)
        names["_type"], names["_list"] = type, list
    guard = [f"_type({swap.matrix}) is _list"]
    guard += [f"{swap.lo} <= {r} <= {swap.rows_hi}" for r in swap.rows if isinstance(r, str)]
    o.line(f"if {' and '.join(guard)}:")
    o.indent()
    n, m = swap.width, swap.matrix
    starts, ends = [], []
    for r in swap.rows:
        if isinstance(r, int):                  # a constant row: its slice written out
            starts.append(str((r - swap.lo) * n))
            ends.append(str((r - swap.lo) * n + n))
        else:
            start = compiler.temp()
            o.line(f"{start} = ({r} - {swap.lo}) * {n}")
            starts.append(start)
            ends.append(f"{start} + {n}")
    (a, b), (a_end, b_end) = starts, ends
    o.line(f"{m}[{a}:{a_end}], {m}[{b}:{b_end}] = {m}[{b}:{b_end}], {m}[{a}:{a_end}]")
    o.line(f"{swap.held} = {m}[{b_end} - 1]")
    after()
    o.dedent()
    o.line("else:")


def _local(compiler, e) -> str | None:
    if not isinstance(e, ast.Name):
        return None
    place = compiler.scope.places.get(e.name.upper())
    return place.name if place is not None and place.how == "local" else None


def _row(compiler, e):
    """A row index: its constant (an unrolled K), or the Python name of an integer local."""
    value = compiler.constant_of(e)
    if isinstance(value, int) and not isinstance(value, bool):
        return value
    name = _local(compiler, e)
    if name is None or elementary(compiler.scope.places[e.name.upper()].symbol.type) is None \
            or elementary(compiler.scope.places[e.name.upper()].symbol.type).kind != "int":
        return None
    return name


def _same_name(a, b) -> bool:
    return isinstance(a, ast.Name) and isinstance(b, ast.Name) and a.name.upper() == b.name.upper()


def _is_index(e) -> bool:
    return isinstance(e, ast.Index) and len(e.indices) == 2


def _name_of(e) -> str | None:
    return e.name.upper() if isinstance(e, ast.Name) else None
