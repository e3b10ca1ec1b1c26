"""`ranges`: the values an integer local can hold at each point of the code, for bounds checks.

`PivotRow := K;` in an unrolled copy (K a constant), then `IF ... THEN PivotRow := Row;
END_IF` for each later Row: from there on PivotRow is within [K, SIZE], so
`Matrix[PivotRow, Column]` needs no bounds check (exprs.py skips a check where
`static_range` proves the index in bounds).  The compiler follows the code in the
order it writes it:

* after `V := e`: V's range is `e`'s static range when `e` cannot fault (a constant,
  a name) and fits V's type (no wrap); when `e` may fault the statement may be
  abandoned and V keep its value, so the union of both; otherwise unknown;
* after an IF or CASE: the union over the branches and the path that takes none
  (a fault in a condition or selector takes none);
* a loop that is not unrolled: what its body assigns is unknown in the body and
  after it (the body may run any number of times);
* a body compiled twice (a CSE region and its fallback): each from the same state,
  the union after.

Loop versions (statements.py, `_versioned`): a FOR with step 1 whose start has a static
range but whose end is data runs over a Python range; the checks its body makes on the
variable itself are recorded while the loop is compiled as before, and when the start
cannot be below any such array's lower bound a second copy is compiled with the variable
known in [start, smallest upper bound] and run when `range.stop` is at most that bound
plus 1, the loop as before otherwise.  Every value the variable takes in the copy is in
the bounds of every array it indexes, so each check left out would have passed; both
copies charge the same time at the same points (the loop's charge is before the choice).

Only plain Python locals of an integer type are followed, and only those no one
else can write: never a FOR variable, the root of an element/member/bit store, a
call's argument that is a variable (VAR_IN_OUT, REF, ADR, an output `=>`), or a
variable passed by reference.  At the start of a body nothing is known (an FB's
cached variable holds whatever the instance held).  Exact: a check is left out only
where it can never fail, which is what the compiler did already for FOR variables.
"""

from __future__ import annotations

from ... import ast
from ..exprs import int_bounds
from ..scope import listed, of_classes, root_name, walk

_LVALUES = (ast.Name, ast.Member, ast.Index, ast.Deref, ast.BitAccess)
_EXCLUDING = frozenset({ast.For, ast.Assign, ast.Arg})      # the nodes that may exclude a variable


class Flow:
    """The followed variables of one body and their ranges (kept in `compiler.known_ranges`)."""

    def __init__(self, compiler, body):
        self.compiler = compiler
        self._assigned: dict[int, set[str]] = {}       # id(loop body) -> followed names it assigns
        self.bounds: dict[str, tuple[int, int]] = {}
        candidates = {key: bounds for key, place in compiler.scope.places.items()
                      if place.how == "local" and (bounds := int_bounds(place.symbol.type)) is not None}
        if not candidates:
            return          # (nothing to follow: no walk for what no one else may write)
        excluded: set[str] = set(compiler.scope.usage.referenced)
        For, Assign, Arg = ast.For, ast.Assign, ast.Arg
        for node in of_classes(listed(body), _EXCLUDING):
            cls = type(node)
            if cls is For:
                excluded.add(node.variable.upper())
            elif cls is Assign and (not isinstance(node.target, ast.Name) or node.mode != ":="):
                name = root_name(node.target)
                if name:
                    excluded.add(name)
            elif cls is Arg and isinstance(node.value, _LVALUES):
                name = root_name(node.value)
                if name:
                    excluded.add(name)
        self.bounds = {key: bounds for key, bounds in candidates.items() if key not in excluded}

    # ----------------------------------------------------------- states

    def state(self) -> dict:
        bounds = self.bounds
        return {key: r for key, r in self.compiler.known_ranges.items() if key in bounds}

    def set(self, state: dict) -> None:
        known, bounds = self.compiler.known_ranges, self.bounds
        for key in [key for key in known if key in bounds and key not in state]:
            del known[key]
        known.update(state)

    def join(self, states: list[dict]) -> None:
        """The union of `states` becomes the state (a variable unknown in one is unknown)."""
        joined = {}
        for key, r in (states[0].items() if states else ()):
            ranges = [s.get(key) for s in states]
            if all(x is not None for x in ranges):
                joined[key] = (min(x[0] for x in ranges), max(x[1] for x in ranges))
        self.set(joined)

    def forget(self, body) -> None:
        """Every followed variable `body` assigns becomes unknown."""
        names = self._assigned.get(id(body))
        if names is None:       # (an unrolled loop compiles the loops in its body once a copy)
            names = self._assigned[id(body)] = {
                node.target.name.upper() for node in walk(body)
                if isinstance(node, ast.Assign) and isinstance(node.target, ast.Name)} & set(self.bounds)
        known = self.compiler.known_ranges
        for key in names:
            known.pop(key, None)

    # ------------------------------------------------------- statements

    def assigned(self, s) -> None:
        """After `s` (an Assign) was compiled."""
        if not isinstance(s.target, ast.Name):
            return
        key = s.target.name.upper()
        if key not in self.bounds:
            return
        compiler = self.compiler
        known = compiler.known_ranges
        old = known.get(key)
        new = compiler.static_range(s.value)
        lo, hi = self.bounds[key]
        if new is not None and not lo <= new[0] <= new[1] <= hi:
            new = None                              # it would wrap
        cannot_fault = compiler.constant_of(s.value) is not None or (
            isinstance(s.value, ast.Name) and _is_plain_local(compiler, s.value.name.upper()))
        if new is not None and not cannot_fault:
            new = None if old is None else (min(old[0], new[0]), max(old[1], new[1]))
        if new is None:
            known.pop(key, None)
        else:
            known[key] = new


def _is_plain_local(compiler, key: str) -> bool:
    """A Python local: reading it cannot fault (an unconnected VAR_IN_OUT can)."""
    place = compiler.scope.places.get(key)
    return key in compiler.unrolled or (place is not None and place.how == "local")
