"""Recursion: cycles in the graph of calls and FB instance declarations.

IEC 61131-3 and OMRON NJ forbid recursion.  The graph has an edge A -> B when
POU A calls function B, calls an instance of FB type B, or declares an
instance of FB type B, directly or inside a STRUCT (an FB that contains
itself, directly or through other FBs and STRUCTs, would be infinitely
large).  Each cycle is reported once.
"""

from __future__ import annotations

from itertools import islice

from .. import types as T
from ..ast import key
from .context import Context, a_or_an
from .declarations import _INSTANCE_KINDS
from .typesys import innermost


def _edges(ctx: Context) -> dict[str, list]:
    """POU key -> its edges out, read only by the search.

    With the shared prelude, its POUs (which lead the table) are left out, and every
    edge into them: they were checked alone without a cycle (prelude_base), and no
    edge leads from them to the user's POUs (their declarations name only the
    prelude's, and their bodies are native), so a cycle holds none of them and the
    user's POUs are met in the search in the same order, with the same components.

    `ctx.calls` holds every call of every body, a METHOD's too (its node 'FB.M' holds a
    '.', no POU's key): the edges between POUs are this check's, the rest W-ASSIGN-001's
    (loop_writes.py), so a call from or to a METHOD stays out of this graph."""
    pous = iter(ctx.program.pous.items())
    base = ctx.program.prelude
    if base is not None:
        pous = islice(pous, len(base.pous), None)
    graph = {k: _declared_edges(info) for k, info in pous}
    for caller, calls in ctx.calls.items():
        if caller in graph:
            edges = graph[caller]
            for callee, pos in calls:
                if callee in graph:
                    edges.append((callee, pos, "calls"))
    return graph


def _declared_edges(info) -> list[tuple[str, object, str]]:
    """The edges of a POU's instance declarations (FBs, and FBs inside STRUCTs): of a
    variable whose type, or its arrays' element type, is an FB or a STRUCT."""
    edges = []
    for sym in info.variables.values():
        t = sym.type
        if type(t) is T.ElementaryType or sym.kind not in _INSTANCE_KINDS or sym.decl is None:
            continue       # (an INT holds no instance: the commonest variable, passed first)
        t = innermost(t)
        if isinstance(t, T.FBType):
            edges.append((key(t.name), sym.decl.pos, "declares an instance of"))
        elif isinstance(t, T.StructType):
            for struct, inner in _fbs_inside_structs(t):
                how = f"declares {a_or_an(struct)} holding an instance of"
                edges.append((key(inner.name), sym.decl.pos, how))
    return edges


def _fbs_inside_structs(t) -> list[tuple[str, object]]:
    """(struct name, FB type) of every FB instance held, at any depth, inside the
    STRUCT (or array of STRUCT) `t`: a STRUCT member of an FB type F makes the
    declaring POU contain an F as surely as an F variable does (issue 15: an FB
    F with an input of STRUCT S whose member is an F recursed forever at run
    time).  Iterative; STRUCT-STRUCT cycles are refused elsewhere (E-DECL-005)
    and skipped here."""
    found = []
    seen: set[int] = set()
    work = [(t, None)]
    while work:
        t, outer = work.pop()
        t = innermost(t)
        if isinstance(t, T.FBType) and outer is not None:
            found.append((outer, t))
        elif isinstance(t, T.StructType) and id(t) not in seen:
            seen.add(id(t))
            work.extend((member, outer or t.name) for _, member in t.fields.values())
    return found


def _components(graph) -> list[list[str]]:
    """Strongly connected components (Tarjan, iterative)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    on_stack: set[str] = set()
    stack: list[str] = []
    result: list[list[str]] = []
    counter = 0
    for root in graph:
        if root in index:
            continue
        work = [(root, 0)]
        while work:
            node, i = work.pop()
            if i == 0:
                index[node] = low[node] = counter
                counter += 1
                stack.append(node)
                on_stack.add(node)
            recurse = False
            edges = graph[node]
            while i < len(edges):
                succ = edges[i][0]
                i += 1
                if succ not in index:
                    work.append((node, i))
                    work.append((succ, 0))
                    recurse = True
                    break
                if succ in on_stack:
                    low[node] = min(low[node], index[succ])
            if recurse:
                continue
            if low[node] == index[node]:
                comp = []
                while True:
                    w = stack.pop()
                    on_stack.discard(w)
                    comp.append(w)
                    if w == node:
                        break
                result.append(comp)
            if work:
                parent = work[-1][0]
                low[parent] = min(low[parent], low[node])
    return result


def _cycle(graph, members: set[str], start: str):
    """A path of edges start -> ... -> start inside one component (BFS)."""
    previous: dict[str, tuple[str, tuple]] = {}
    frontier = [start]
    while frontier:
        nxt = []
        for node in frontier:
            for edge in graph[node]:
                succ = edge[0]
                if succ not in members:
                    continue
                if succ == start:
                    path = [(node, edge)]
                    while node != start:
                        node, e = previous[node]
                        path.append((node, e))
                    return list(reversed(path))
                if succ not in previous:
                    previous[succ] = (node, edge)
                    nxt.append(succ)
        frontier = nxt
    return []


def check_recursion(ctx: Context) -> None:
    graph = _edges(ctx)
    pous = ctx.program.pous
    # A POU with no edge out (most: the prelude's FBs) is in no cycle: left out, the
    # components found and their order are the same (it would be a component alone).
    live = {k: [e for e in edges if graph.get(e[0])] for k, edges in graph.items() if edges}
    for comp in _components(live):
        members = set(comp)
        if len(comp) == 1 and not any(e[0] == comp[0] for e in graph[comp[0]]):
            continue
        start = min(comp, key=lambda k: _order(pous[k]))
        path = _cycle(graph, members, start)
        if not path:
            continue
        steps = ", ".join(f"{pous[a].name} {how} {pous[b].name}" for a, (b, _, how) in path)
        first_pos = path[0][1][1]
        ctx.error("E-REC-001", f"recursion: {steps}; IEC 61131-3 and OMRON NJ forbid recursion",
                  first_pos)


def _order(info):
    node = info.node
    if node is None:
        return ("", 0, 0)
    return (node.pos.file, node.pos.line, node.pos.col)
