"""`shortcut`: an IF condition that cannot fault tests its BOOL AND and OR as `and`, `or`.

An AND (OR) of BOOLs is compiled as `&` (`|`): both operands evaluated, then combined.  In
an IF condition tested in place (branches.py: nothing in it can raise, it reads owned
storage only and calls nothing but `abs`, `min`, `max`), only whether the whole is true
decides, and for operands that are bools (a BOOL is held as a Python bool, or 0 or 1)
`a and b` is true exactly when `a & b` is, `a or b` when `a | b` is.  The right operand is
left unevaluated when the left one decides, which nothing can see: it reads, stores and
raises nothing.  The charges are the ST's, written before the IF and in its branches
(cost.py), so the NJ time is the same.  (SP_Controller's `(MoveEdge OR WaveEdge OR PathEdge
OR PlaybackEdge) AND NOT (...)`: no edge, one test each and no `|`, `&` or `not` of the
rest; its axes' `SyncCalls >= 1 AND AxisSync[k].CommandAborted`: no `&`.)

Each AND and OR of BOOLs records its operands' code as it is compiled (exprs.py); the
condition is rebuilt from them only when they give back the code just compiled, `&` and `|`
for `and` and `or`.

An AND or OR of two comparisons (or NOTs, or such ANDs and ORs) is `and`/`or` wherever it stands (a store, an input), when
the right one cannot fault (branches.py's rule): each comparison is a Python bool, so
`a and b` is the bool `a & b` is, and the right one left out reads, stores and raises
nothing (SP_InverseKinematics' `LegInStroke[Leg] := Position[Leg] >= 0.0 AND Position[Leg]
<= Stroke`: no `&` of two bools, which goes through the number protocol).

A BOOL stored from a comparison of numbers (or an AND/OR of such) is tested for a jump,
`True if ... else False`, and a stored `X AND R` of a BOOL variable X is `X and X & R` (an
FB input: `X if not X else X & R`; `stored`: CPython 3.11 specialises a comparison only
where a jump follows it).
"""

from __future__ import annotations

import re

from ... import ast
from ...types import ElementaryType, resolve_alias

_WORDS = {"AND": ("&", "and"), "&": ("&", "and"), "OR": ("|", "or")}
_COMPARISONS = {"=", "<>", "<", ">", "<=", ">="}


def condition(compiler, node, code: str) -> str:
    """The IF condition `node`, compiled to `code` and tested in place, with `and`/`or`."""
    if not compiler.opt.shortcut:
        return code
    rebuilt = _rebuilt(compiler, node)
    return rebuilt[1] if rebuilt is not None and rebuilt[0] == code else code


def record(compiler, e, left: str, right: str) -> None:
    """An AND/OR/& of two BOOLs compiled as `(left op right)`."""
    t = compiler.ty(e)
    if e.op in _WORDS and isinstance(t, ElementaryType) and t.kind == "bool":
        compiler.logic_parts[id(e)] = (left, right)


def of_comparisons(compiler, e, left: str, right: str) -> str | None:
    """`(left and right)` / `(left or right)` for an AND/OR of two Python bools (comparisons,
    NOT of a BOOL, such an AND/OR itself) whose right one cannot fault; else None."""
    if e.op not in _WORDS or compiler.region is not None:
        return None
    if not (_is_bool(compiler, e.left) and _is_bool(compiler, e.right)):
        return None
    from . import branches      # (branches imports scope, which imports exprs: read at call time)

    if not branches.expr_cannot_fault(compiler, e.right, right):
        return None
    compiler.logic_short.add(id(e))
    return f"({left} {_WORDS[e.op][1]} {right})"


def stored(compiler, node, code: str, kept: bool = False) -> str:
    """The value `code` of `node`, a BOOL about to be stored: a comparison of numbers (or an
    AND/OR of such) as `True if code else False`.  Its value is a Python bool either way (a
    comparison of ints, floats and bools is one, and `and`/`or`/`&`/`|` of two bools is one of
    them); tested for a jump, CPython 3.11 specialises each comparison (`COMPARE_OP_FLOAT_JUMP`),
    where a comparison whose value is kept takes the generic path (`PyObject_RichCompare` and
    a new reference to the bool, some 90 machine instructions more).

    `X & R` of a BOOL X read from a variable (a local or a slot: the same value read twice,
    nothing runs between) and a Python bool R that cannot fault is `X if not X else X & R`:
    a false X (FALSE or 0) is what `X & R` gives then (`False & b` is False, `0 & b` is 0),
    and leaving R out reads, stores and raises nothing; `&` of two values goes through the
    number protocol, the test of X is a jump (SP_Controller's six edges `Start AND NOT
    Previous`, its MC_Stop's `StopExecute AND NOT ErrorStop`).  Stored into a variable
    (`kept`), it is `X and X & R`: Python's `and` is that test (X when X is false, else the
    right operand), with one read of X fewer where X is false (the edges of a held input);
    an FB input keeps the conditional, which dormant.py reads."""
    if type(node) is not ast.Binary or (node.op not in _COMPARISONS and node.op not in _WORDS) \
            or not compiler.opt.shortcut:
        return code         # (most stores: asked first, it is cheaper)
    if _compares_numbers(compiler, node) and (node.op in _COMPARISONS or _COMPARED.search(code)):
        return f"(True if {code} else False)"
    parts = compiler.logic_parts.get(id(node))
    if parts is not None and node.op in ("AND", "&") and code == f"({parts[0]} & {parts[1]})" \
            and _READ.fullmatch(parts[0]) and _is_bool(compiler, node.right):
        from . import branches      # (see of_comparisons)

        if branches.expr_cannot_fault(compiler, node.right, parts[1]):
            return f"({parts[0]} and {code})" if kept else f"({parts[0]} if not {parts[0]} else {code})"
    return code         # (`sets`' `x in (...)`: CPython 3.11 specialises no `in`)


_COMPARED = re.compile(r"[<>]|[=!]=")
_READ = re.compile(r"(?:self\.|_G\.)?v_\w+")      # a local, or a slot of the instance or of the globals
_NUMBER_KINDS = {"bool", "int", "bits", "real", "time", "date", "tod", "dt"}


def _compares_numbers(compiler, e) -> bool:
    """`e` is a comparison of two elementary numbers (held as Python bools, ints or floats), or
    an AND/OR of two such."""
    if not isinstance(e, ast.Binary):
        return False
    if e.op in _COMPARISONS:
        return all(isinstance(t := resolve_alias(compiler.ty(side)), ElementaryType) and t.kind in _NUMBER_KINDS
                   for side in (e.left, e.right))
    return e.op in _WORDS and _compares_numbers(compiler, e.left) and _compares_numbers(compiler, e.right)


def _is_bool(compiler, e) -> bool:
    """`e`'s code gives a Python bool (a BOOL variable may hold 0 or 1)."""
    if isinstance(e, ast.Binary):
        return e.op in _COMPARISONS or id(e) in compiler.logic_short
    return isinstance(e, ast.Unary) and e.op.upper() == "NOT" and _is_bool_typed(compiler, e.operand)


def _is_bool_typed(compiler, e) -> bool:
    t = compiler.ty(e)
    return isinstance(t, ElementaryType) and t.kind == "bool"


def _rebuilt(compiler, node) -> tuple[str, str] | None:
    """(`&`/`|` code, `and`/`or` code) of `node` from the recorded operands; None for a leaf."""
    parts = compiler.logic_parts.get(id(node))
    if parts is None:
        return None
    symbol, word = _WORDS[node.op]
    sides = []
    for operand, code in zip((node.left, node.right), parts):
        inner = _rebuilt(compiler, operand)
        sides.append(inner if inner is not None and inner[0] == code else (code, code))
    (left, short_left), (right, short_right) = sides
    return f"({left} {symbol} {right})", f"({short_left} {word} {short_right})"
