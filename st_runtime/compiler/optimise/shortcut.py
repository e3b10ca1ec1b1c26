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
"""

from __future__ import annotations

from ...types import ElementaryType

_WORDS = {"AND": ("&", "and"), "&": ("&", "and"), "OR": ("|", "or")}


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
