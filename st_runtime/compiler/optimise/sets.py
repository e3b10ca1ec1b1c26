"""`sets`: `X = a OR X = b OR ...` is one test `X in {a, b, ...}`.

An OR (or AND) chain of comparisons is compiled as `|` (`&`) of bools, every
operand evaluated.  Where consecutive operands of the chain compare one plain
variable X with integer constants, `(X == a) | (X == b) | ...` is
`X in {a, b, ...}` and `(X != a) & (X != b) & ...` is `X not in {a, b, ...}`:
for an integer X both give the same bool (a set's `in` finds an element of equal
hash that is X or `==` X, which for ints is `==`), and reading X once
instead of several times changes nothing: X is a Python local, or an attribute
of the instance or of the globals that is a plain slot (not located, not a
VAR_IN_OUT or REF_TO: `unguard`'s owned storage), and nothing runs between the
reads.  The other operands keep their order; `|` and `&` of bools are
associative, so grouping a run of them gives the same bool.
(`SP_Controller`'s `SyncExecute := State = 3 OR State = 4 OR ... OR State = 18`:
12 comparisons and 11 `|`, 48 bytecode instructions, become 4.)  The set display of
constants after `in` is a frozenset constant of the code object (CPython's compiler): one
hash and one probe, where a tuple compares X with each value until one is equal (the
wave state, 6, took four comparisons, each a generic rich comparison).
"""

from __future__ import annotations

from ... import ast
from ...types import ElementaryType, EnumType, resolve_alias
from ..initial import CompileError

_TESTS = {"OR": ("=", "in"), "AND": ("<>", "not in")}
_JOIN = {"OR": "|", "AND": "&"}
MIN_RUN = 2         # comparisons of one variable a membership test replaces


def chain(compiler, e) -> str | None:
    """Python source of the OR/AND chain `e` with its runs of comparisons of one variable
    as membership tests; None when it has no such run."""
    if e.op not in _TESTS or id(e) in compiler.plain_chains:
        return None
    operands = _flatten(e, e.op)
    tested = [_tested(compiler, operand, e.op) for operand in operands]
    if not any(a is not None and b is not None and a[0] == b[0] for a, b in zip(tested, tested[1:])):
        _inner_chains(e, e.op, compiler.plain_chains)      # no run in them either
        return None
    parts, i = [], 0
    while i < len(operands):
        j = i
        while tested[i] is not None and j + 1 < len(operands) and tested[j + 1] is not None \
                and tested[j + 1][0] == tested[i][0]:
            j += 1
        if j - i + 1 >= MIN_RUN:
            values = ", ".join(str(tested[k][1]) for k in range(i, j + 1))
            parts.append(f"({tested[i][0]} {_TESTS[e.op][1]} {{{values}}})")
        else:
            parts.extend(compiler.expr(operands[k]) for k in range(i, j + 1))
        i = j + 1
    code = parts[0]
    for part in parts[1:]:
        code = f"({code} {_JOIN[e.op]} {part})"
    return code


def _inner_chains(e, op: str, seen: set) -> None:
    """Note the ids of the chain's `op` nodes below `e`: their operands are a run of `e`'s."""
    for side in (e.left, e.right):
        if isinstance(side, ast.Binary) and side.op == op:
            seen.add(id(side))
            _inner_chains(side, op, seen)


def _flatten(e, op: str) -> list:
    """The operands of a chain of `op`, left to right."""
    if isinstance(e, ast.Binary) and e.op == op:
        return _flatten(e.left, op) + _flatten(e.right, op)
    return [e]


def _tested(compiler, e, op: str) -> tuple[str, int] | None:
    """(the variable's Python read, the constant) when `e` is `X = c` (OR) or `X <> c`
    (AND) with X a plain integer variable and c an integer constant."""
    if not isinstance(e, ast.Binary) or e.op != _TESTS[op][0]:
        return None
    for variable, other in ((e.left, e.right), (e.right, e.left)):
        value = compiler.constant_of(other)
        if isinstance(value, int) and not isinstance(value, bool) and _plain_integer(compiler, variable):
            return compiler.expr(variable), value
    return None


def _plain_integer(compiler, e) -> bool:
    """`e` names an integer or enumeration variable held in a local or a slot (of the
    instance or the globals): not a constant, an in-out's reference, nor a cell."""
    if not isinstance(e, ast.Name) or compiler.constant_of(e) is not None \
            or e.name.upper() in compiler.unrolled:
        return False
    t = resolve_alias(compiler.ty(e))
    if not (isinstance(t, EnumType) or isinstance(t, ElementaryType) and t.kind in ("int", "bits")):
        return False
    if isinstance(compiler.program.name_refs.get(id(e)), int):
        return False        # an enumeration value
    try:
        return compiler.scope.place_of(e).how in ("local", "self", "global")
    except CompileError:
        return False
