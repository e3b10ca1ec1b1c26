"""A global FOR control variable written by a POU called inside its loop.

IEC 61131-3 3rd ed. 7.3.3.4.2: the control variable "shall not be altered by any
of the repeated statements".  A statement of the loop that writes it is refused
where it stands (stores.py, E-ASSIGN-003).  When the control variable is a global
(a VAR_GLOBAL, named through VAR_EXTERNAL or, where the dialect allows, directly),
a FUNCTION or FB instance called in the loop alters it as well if its body writes
that global, itself or through the FUNCTIONs and FBs it calls: this pass follows
the recursion check's call graph (`Context.calls`) from each such call.

Not followed (they need alias analysis, and stay accepted): METHOD calls (outside
the call graph), and writes through a reference, a pointer or a VAR_IN_OUT bound
to the global somewhere else.
"""

from __future__ import annotations

from ..ast import key
from .context import Context

#: Symbol kinds that name a global variable (callers test it before `note_global_write`).
GLOBAL_KINDS = frozenset({"VAR_GLOBAL", "VAR_EXTERNAL"})


def note_global_write(ctx: Context, scope, sym) -> None:
    """Record that the POU being checked writes the global `sym`."""
    pou = scope.pou_key
    if pou is not None:
        ctx.global_writes.setdefault(pou, set()).add(key(sym.name))


def note_loop_call(ex, callee: str, pos) -> None:
    """Record a call of POU `callee` made inside FOR loops over globals."""
    loops = {key(sym.name): sym.name for sym in ex.loop_vars if sym.kind in GLOBAL_KINDS}
    if loops:
        ex.ctx.loop_calls.append((callee, pos, loops))


def check_calls_in_loops(ctx: Context) -> None:
    """E-ASSIGN-003 at each call, made in a FOR over a global, of a POU that writes it."""
    for callee, pos, loops in ctx.loop_calls:
        for global_key, name in loops.items():
            path = _path_to_writer(ctx, callee, global_key)
            if path:
                ctx.error("E-ASSIGN-003", f"call of {ctx.program.pous[callee].name} alters global "
                          f"'{name}', the control variable of an enclosing FOR loop "
                          f"({_described(ctx, path)})", pos)
                break


def _path_to_writer(ctx: Context, start: str, global_key: str) -> list[str]:
    """The shortest chain of calls from `start` to a POU that writes the global, else []."""
    previous = {start: None}
    frontier = [start]
    while frontier:
        following = []
        for pou in frontier:
            if global_key in ctx.global_writes.get(pou, ()):
                path = []
                while pou is not None:
                    path.append(pou)
                    pou = previous[pou]
                return path[::-1]
            for callee, _ in ctx.calls.get(pou, ()):
                if callee not in previous:
                    previous[callee] = pou
                    following.append(callee)
        frontier = following
    return []


def _described(ctx: Context, path: list[str]) -> str:
    """'F writes it', or 'F calls G, which calls H, which writes it'."""
    names = [ctx.program.pous[pou].name for pou in path]
    if len(names) == 1:
        return f"{names[0]} writes it"
    return f"{names[0]} calls " + ", which calls ".join(names[1:]) + ", which writes it"
