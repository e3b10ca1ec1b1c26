"""A FOR control variable written by a POU called inside its loop: W-ASSIGN-001.

IEC 61131-3 3rd ed. 7.3.3.4.2: the control variable "shall not be altered by any
of the repeated statements".  A statement of the loop that writes it is refused
where it stands (stores.py, E-ASSIGN-003).  A write made by a callee is not in
the loop's text, and no compiler we found refuses it (CODESYS compiles even the
direct write; its static analysis, SA0072, looks at the loop's own statements).
Such a program runs: the loop tests the variable as the callee left it, which the
compiler keeps and tests/test_compiler_tables_core.py pins.  So the checker warns,
at the call, naming the chain of calls.

When the control variable is a global (a VAR_GLOBAL, named through VAR_EXTERNAL
or, where the dialect allows, directly), a FUNCTION or FB instance called in the
loop alters it if its body writes that global, itself or through the FUNCTIONs
and FBs it calls: the pass follows the recursion check's call graph
(`Context.calls`) from each such call.  Inside a FUNCTION_BLOCK, for a FOR over
one of its own variables, a METHOD called on this instance (`M()`, `THIS.M()`,
`SUPER.M()`) alters it when its body writes that variable, itself or through the
methods it calls on this instance; the method is the one the name resolves to
here (an override in an FB extending this one is not looked at).

Not followed (they need alias analysis): methods called on another instance, and
writes through a reference, a pointer or a VAR_IN_OUT bound to the variable
somewhere else.
"""

from __future__ import annotations

from .. import ast
from ..ast import key
from .context import Context

#: Symbol kinds that name a global variable.
GLOBAL_KINDS = frozenset({"VAR_GLOBAL", "VAR_EXTERNAL"})


def note_write(ctx: Context, scope, sym) -> None:
    """Record that the POU being checked writes `sym` (a store, or a FOR over it), when `sym`
    is a global, or a variable of the FB whose METHOD is being checked."""
    if sym.kind in GLOBAL_KINDS:
        pou = scope.pou_key
        if pou is not None:
            ctx.global_writes.setdefault(pou, set()).add(key(sym.name))
    elif scope.fb is not None and scope.pou.kind == "METHOD" \
            and scope.fb.variables.get(key(sym.name)) is sym:
        ctx.member_writes.setdefault(method_key(scope.pou), set()).add(id(sym))


def note_loop_call(ex, callee: str, pos) -> None:
    """Record a call of POU `callee` made inside FOR loops over globals."""
    loops = {key(sym.name): sym.name for sym in ex.loop_vars if sym.kind in GLOBAL_KINDS}
    if loops:
        ex.ctx.loop_calls.append((callee, pos, loops))


def method_key(method) -> str:
    """'FB.M': a METHOD in the tables below (methods are outside the recursion check's graph)."""
    return f"{key(method.owner.name)}.{key(method.name)}"


def note_this_call(ex, method, callee, how: str, pos) -> None:
    """Record a call of `method` on this instance (made in an FB's body or one of its methods)."""
    if how not in ("self", "super") and not _on_this(callee):
        return
    scope, ctx = ex.scope, ex.ctx
    if scope.pou.kind == "METHOD":
        ctx.this_calls.setdefault(method_key(scope.pou), []).append((method_key(method), method.name))
    members = scope.fb.variables
    loops = {id(sym): sym.name for sym in ex.loop_vars if members.get(key(sym.name)) is sym}
    if loops:
        ctx.loop_method_calls.append((method_key(method), method.name, pos, loops))


def _on_this(callee) -> bool:
    """`THIS.M`: a virtual call on this instance (`callee` is a Member: a "virtual" or
    "interface" call names its instance)."""
    base = callee.base
    return isinstance(base, ast.Name) and key(base.name) == "THIS"


def check_calls_in_loops(ctx: Context) -> None:
    """W-ASSIGN-001 at each call, made in a FOR over a global or over a variable of the FB,
    of a POU or METHOD that writes it."""
    pous = ctx.program.pous
    for callee, pos, loops in ctx.loop_calls:
        for global_key, name in loops.items():
            path = _path_to_writer(callee, lambda pou: global_key in ctx.global_writes.get(pou, ()),
                                   lambda pou: (edge[0] for edge in ctx.calls.get(pou, ())))
            if path:
                names = [pous[pou].name for pou in path]
                _warn(ctx, f"{names[0]} alters global '{name}'", names, pos)
                break
    method_names = {k: name for calls in ctx.this_calls.values() for k, name in calls}
    for callee, callee_name, pos, loops in ctx.loop_method_calls:
        method_names[callee] = callee_name
        for sym_id, name in loops.items():
            path = _path_to_writer(callee, lambda m: sym_id in ctx.member_writes.get(m, ()),
                                   lambda m: (k for k, _ in ctx.this_calls.get(m, ())))
            if path:
                _warn(ctx, f"method {callee_name} alters '{name}'", [method_names[m] for m in path], pos)
                break


def _warn(ctx: Context, what: str, names: list[str], pos) -> None:
    chain = f"{names[0]} writes it" if len(names) == 1 else \
        f"{names[0]} calls " + ", which calls ".join(names[1:]) + ", which writes it"
    ctx.warning("W-ASSIGN-001", f"call of {what}, the control variable of an enclosing FOR loop "
                f"({chain}): IEC 61131-3 forbids it; the loop goes on from the value left", pos)


def _path_to_writer(start: str, writes, callees) -> list[str]:
    """The shortest chain of calls from `start` to a callee for which `writes` holds, else []."""
    previous = {start: None}
    frontier = [start]
    while frontier:
        following = []
        for pou in frontier:
            if writes(pou):
                path = []
                while pou is not None:
                    path.append(pou)
                    pou = previous[pou]
                return path[::-1]
            for callee in callees(pou):
                if callee not in previous:
                    previous[callee] = pou
                    following.append(callee)
        frontier = following
    return []
