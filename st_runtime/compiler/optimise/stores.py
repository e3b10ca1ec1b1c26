"""`stores`: a cached variable stored in one branch only is written back at that branch's end.

A FUNCTION_BLOCK or PROGRAM body caches an elementary variable it uses often in a
Python local: loaded in the prologue (`v_X = self.v_X`), stored back in the
`finally` that ends every call (`self.v_X = v_X`; scope.py).  When every store of
the variable in the body is inside one IF branch or CASE clause (the innermost
that holds them all, looking no deeper than the first loop around a store, as
the `aliases` pass looks for uses), its store back moves to a `finally` around
that branch's code:

    <branch's loads>
    try:
        <the branch>
    finally:
        self.v_X = v_X

and when every use is inside that branch too, the load moves to the start of the
branch as well.  A call that does not take the branch neither loads nor stores
the variable (TRJ_OceanWave's latch of a new wave, SP_Controller's cold states).

With `spread`, a variable whose uses all lie in branches of one IF or CASE and not
around them (`aliases.spread_branches`) is loaded at the start of each of those
branches and stored back around each that stores it (SP_Controller's flags of the
locate and point-to-point states): a call runs one of them at most.

Exact: no code but the body's can read or change the slot while the body runs
(scope.py caches nothing a reference, a METHOD or THIS can reach), so the slot
only has to hold the local's value when the call ends; outside the branch the
local is not changed, so the store at the branch's end (on every way out: its
end, RETURN, a fault that stops the run) leaves the slot as the store at the
call's end would.  The store and the load cannot raise, and `try`/`finally`
costs no instruction on CPython 3.11 when nothing is raised, so faults,
charges and F-PERIOD are as before.  A branch nested more than `MAX_DEPTH`
deep, or holding loops more than `MAX_LOOPS` deep, is left alone (CPython
allows 20 nested blocks).
Left as they are: a body compiled as one CSE region (its reads may move to
the top), names the walk does not find as often as the body has them.
"""

from __future__ import annotations

import re

from ... import ast
from ..scope import _LOOPS
from .aliases import common_branch, occurrences, spread_branches

_STORE_BACK = re.compile(r"self\.(v_\w+) = (v_\w+)")
MAX_DEPTH = 4           # IF/CASE levels a branch may be nested in
MAX_LOOPS = 4           # loops a branch with a store back may nest


class LateStores:
    """What moves: id(branch body) -> load lines, and -> store-back lines."""

    def __init__(self):
        self.loads: dict[int, list[str]] = {}
        self.stores: dict[int, list[str]] = {}


def late_stores(compiler, body) -> LateStores:
    """Move eligible store-back lines out of `compiler.scope.epilogue` (and their loads out
    of its prologue when every use is in the same branch)."""
    scope = compiler.scope
    late = LateStores()
    local_keys = {p.name: k for k, p in scope.places.items() if p.how == "local"}
    candidates = {}
    for line in scope.epilogue:
        match = _STORE_BACK.fullmatch(line) if isinstance(line, str) else None
        if match and match.group(1) == match.group(2) and match.group(1) in local_keys:
            candidates[local_keys[match.group(1)]] = line
    if not candidates:
        return late
    seen = occurrences(compiler, body)
    depths: dict[int, int] = {}

    def fits(places: list) -> bool:
        """Each branch nested and holding loops no deeper than the limits."""
        for place in places:
            if place is None or len(place) > MAX_DEPTH:
                return False
            if place[-1] not in depths:
                depths[place[-1]] = _loop_depth(seen.bodies[place[-1]])
            if depths[place[-1]] > MAX_LOOPS:
                return False
        return True

    for key, line in candidates.items():
        uses = seen.paths.get(key, [])
        if len(uses) != seen.counts[key]:
            continue            # a use the walk of branches did not see: leave it
        stores = seen.paths.get(("=", key), [])
        load = f"{scope.places[key].name} = self.{scope.places[key].name}"
        if compiler.opt.spread and load in scope.prologue:
            places = spread_branches(uses, seen.parents)
            if places and len(places) > 1 and fits(places):
                # every use in branches of which a call runs one at most: load in each,
                # store back in each that stores
                scope.epilogue.remove(line)
                scope.prologue.remove(load)
                for place in places:
                    late.loads.setdefault(place[-1], []).append(load)
                    if any(path[:len(place)] == place for path in stores):
                        late.stores.setdefault(place[-1], []).append(line)
                continue
        branch = common_branch(stores)
        if not fits([branch]):
            continue
        scope.epilogue.remove(line)
        late.stores.setdefault(branch[-1], []).append(line)
        if load in scope.prologue and common_branch(uses) == branch:
            scope.prologue.remove(load)
            late.loads.setdefault(branch[-1], []).append(load)
    return late


def _loop_depth(body) -> int:
    """How deep loops nest in the statements `body`."""
    deepest = 0
    for stmt in body:
        inner = _branch_bodies(stmt) + ([stmt.body] if isinstance(stmt, _LOOPS) else [])
        depth = max((_loop_depth(b) for b in inner), default=0) + (1 if isinstance(stmt, _LOOPS) else 0)
        deepest = max(deepest, depth)
    return deepest


def _branch_bodies(node) -> list[tuple]:
    if isinstance(node, ast.If):
        return [b.body for b in node.branches] + ([node.else_body] if node.else_body else [])
    if isinstance(node, ast.Case):
        return [c.body for c in node.clauses] + ([node.else_body] if node.else_body else [])
    return []
