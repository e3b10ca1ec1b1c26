"""Where each variable of a POU body lives in the generated Python.

Method bodies (PROGRAM, FUNCTION_BLOCK: `execute(self, _ctx)`):

* elementary VAR/VAR_INPUT/VAR_OUTPUT are copied into Python locals at
  entry and written back at exit (in a `finally`, so a scan overrun or a
  RETURN keeps them) -- unless the body passes them to a VAR_IN_OUT, then
  they stay `self.v_X` so a reference to them sees every store;
* arrays, structs and FB instances are aliased by a local (their identity
  never changes: assignment copies into them);
* VAR_TEMP is a local initialised on every call;
* elementary VAR_IN_OUT hold a `Ref` (`.get()`/`.set()`), aggregates the
  caller's object;
* globals (VAR_GLOBAL, VAR_EXTERNAL) are attributes of `_G`.

Function bodies (`_fn_F(_ctx, inputs...)`): every variable is a Python
local, initialised on every call; elementary variables passed to a
VAR_IN_OUT live in a one-element list (a cell) so a reference can reach
them; aggregate inputs the body modifies are copied at entry (by value).
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import compress
from operator import attrgetter

from .. import ast
from ..objects import is_aggregate
from ..per_class import PerClass
from .exprs import LValue
from .pysrc import pyident
from .initial import CompileError


# An instance variable is copied into a Python local when it occurs this often
# (an occurrence inside a loop counts 10): the load at entry and the store at
# exit then cost less than `self.v_X` at every occurrence.
CACHE_THRESHOLD = 4


@dataclass
class VarPlace:
    symbol: object
    how: str          # "local" | "cell" | "self" | "ref" | "alias" | "global"
    name: str         # Python local name (v_X) or attribute name


def walk(node):
    """Every AST node under `node` (tuples and dataclass fields), preorder.

    A body (a tuple of statements) or a statement is walked by several passes of
    one compile (usage, ranges, CSE, the fast path's tests, once per unrolled copy):
    its nodes are listed once and kept for the next walk of the same node (the
    AST is immutable; `_WALKED` holds the node itself, so its id cannot be
    another's while the entry lives)."""
    return iter(listed(node))


def listed(node):
    """`walk(node)` as a sequence (shared: read it only)."""
    if type(node) is tuple:
        if len(node) == 1 and type(node[0]) in _LEAVES:
            return node            # (one leaf, as `walk((expr,))` often asks: nothing to keep)
    elif type(node) in _LEAVES:
        return (node,)
    return _nodes(node)


def of_classes(nodes, classes: frozenset):
    """Those of `nodes` whose class is one of `classes`, in order, picked in C (a node's
    class is its kind: the node classes have no subclasses)."""
    return compress(nodes, map(classes.__contains__, map(type, nodes)))


def kinds(node) -> set:
    """The node classes under `node` (its walk's, counted in C): what a pass looks for
    is absent from a body when its class is not there."""
    return set(map(type, listed(node)))


_WALKED: dict[int, tuple] = {}
_WALKED_ENTRIES = 16384     # (a compile of generated/iec lists about 3,000 distinct nodes)


def forget_walks() -> None:
    """Drop the nodes `walk` and `_nodes` keep (compile_program, before and after a compile:
    they serve one compile, and would keep an earlier load's AST alive)."""
    _WALKED.clear()


def once(table: dict, node, work):
    """`work()` for `node`, worked out once: kept in `table` by id with the node itself (so
    no other node can take that id while the entry lives).  For what one compile or load asks
    of the same node again: an unrolled loop compiles its body once per copy."""
    hit = table.get(id(node))
    if hit is None or hit[0] is not node:
        hit = table[id(node)] = (node, work())
    return hit[1]


def assigned_in(compiler, body) -> set[str]:
    """The variables `body` stores into (`Usage.assigned`), found once a load."""
    return once(compiler.unit.__dict__.setdefault("assigned_in", {}), body,
                lambda: Usage(compiler.program, body, None).assigned)

#: Node classes with no child node (a walk of one of them is the node alone).
_LEAVES = frozenset({ast.Name, ast.IntLiteral, ast.RealLiteral, ast.BoolLiteral, ast.StringLiteral,
                     ast.TimeLiteral, ast.DateTimeLiteral, ast.EnumLiteral, ast.Exit, ast.Continue,
                     ast.Return, ast.Empty})


_LOOPS = (ast.For, ast.While, ast.Repeat)
_USAGE_NODES = frozenset((ast.Assign, ast.Call) + _LOOPS)     # what `Usage` reads besides names
_READ_BY_USAGE = _USAGE_NODES | {ast.Name}


def _nodes(node) -> list:
    """The nodes under `node` in the walk's order: a node, then the nodes of its fields
    from the last to the first, the items of a tuple in order.  Listed once and kept,
    as `walk` keeps them (the optimiser's passes ask again for a statement or an
    expression a pass before them listed): the list is shared, read it only."""
    if type(node) in _LEAVES:
        return [node]
    hit = _WALKED.get(id(node))
    if hit is None or hit[0] is not node:
        if len(_WALKED) >= _WALKED_ENTRIES:
            _WALKED.clear()
        hit = _WALKED[id(node)] = (node, _listed(node))
    return hit[1]


def _listed(node) -> list:
    """`_nodes(node)`, listed: a stack of what is still to list, each item taken as its
    class says (`_HOW`).  A node's child fields go on as they are, in order (so they come
    off from the last), a tuple among them whole: its items go on when it comes off,
    where they would have gone on had they been pushed then (nothing above it is left)."""
    out = []
    stack = [node]
    pop, push, extend, add, how = stack.pop, stack.append, stack.extend, out.append, _HOW
    while stack:
        n = pop()
        children = how[type(n)]
        if children is _LEAF:
            add(n)
        elif children is _TUPLE:
            extend(reversed(n))
        elif children is _SKIP:
            continue
        elif type(children) is str:     # (one child field)
            add(n)
            push(getattr(n, children))
        else:
            add(n)
            extend(filter(None, children(n)))     # (None and empty tuples hold no node)
    return out


_LEAF, _TUPLE, _SKIP = object(), object(), object()


def _how_listed(cls: type):
    """How `_listed` takes an item of class `cls`: a node without child fields is a leaf;
    a tuple's items are listed; a node's one child field is named, its two or more are
    read by one `attrgetter` (in C); anything else (None, a name) holds no node."""
    if issubclass(cls, ast.Node):
        fields = ast.CHILD_FIELDS[cls]
        return _LEAF if not fields else fields[0] if len(fields) == 1 else attrgetter(*fields)
    return _TUPLE if issubclass(cls, tuple) else _SKIP


_HOW: dict[type, object] = PerClass(_how_listed)


def root_name(e) -> str | None:
    while isinstance(e, (ast.Member, ast.Index, ast.Deref, ast.BitAccess)):
        e = e.base
    return e.name.upper() if isinstance(e, ast.Name) else None


class Usage:
    """Which variables a body reads, assigns, and passes by reference."""

    def __init__(self, program, body, calls) -> None:
        self.used: set[str] = set()
        self.assigned: set[str] = set()      # direct stores to the variable (root)
        self.referenced: set[str] = set()    # passed whole to a VAR_IN_OUT
        self.count: dict[str, int] = {}      # occurrences; inside a loop they count 10
        self.nodes = nodes = listed(body)    # the body's nodes, in the walk's order (read only)
        self.kinds = set(map(type, nodes))   # their classes (`kinds`): the passes' gates
        in_loops: set[int] = set()      # every node of a loop (a walk meets the loop first)
        used, count, Name = self.used, self.count, ast.Name
        for node in of_classes(nodes, _READ_BY_USAGE):
            cls = type(node)
            if cls is Name:
                key = node.name.upper()
                used.add(key)
                count[key] = count.get(key, 0) + (10 if in_loops and id(node) in in_loops else 1)
            else:                   # (one of _USAGE_NODES)
                if cls is ast.Assign:
                    self._store(node.target)
                    continue
                if cls is ast.Call:
                    self._call(program, node, calls)
                    continue
                if id(node) not in in_loops:    # (an inner loop's are in)
                    in_loops.update(map(id, _nodes(node)))
                if cls is ast.For:
                    key = node.variable.upper()
                    used.add(key)
                    self.assigned.add(key)
                    count[key] = count.get(key, 0) + 10   # stored every iteration

    def _store(self, target) -> None:
        name = root_name(target)
        if name:
            self.assigned.add(name)

    def _call(self, program, call, calls) -> None:
        target = program.call_targets.get(id(call))
        if target is not None and target.kind == "ref" and call.args:
            name = root_name(call.args[0].value)       # REF(x): x must stay addressable
            if name:
                self.assigned.add(name)
                if isinstance(call.args[0].value, ast.Name):
                    self.referenced.add(name)
            return
        variables = {}
        if target is not None and target.pou is not None:
            variables = target.pou.variables
        elif target is not None and target.kind == "fb":
            t = program.expr_types.get(id(call.callee))
            variables = getattr(t, "variables", {}) or {}
        params = [s for s in variables.values() if s.kind in ("VAR_INPUT", "VAR_IN_OUT")]
        position = 0
        for arg in call.args:
            if arg.direction == "out":
                self._store(arg.value)
                continue
            if arg.name is None:
                symbol = params[position] if position < len(params) else None
                position += 1
            else:
                symbol = variables.get(arg.name.upper())
            if symbol is not None and symbol.kind == "VAR_IN_OUT":
                name = root_name(arg.value)
                if name:
                    self.assigned.add(name)
                    if isinstance(arg.value, ast.Name):
                        self.referenced.add(name)


def edge_inputs(pou) -> list:
    """The FB's BOOL inputs declared R_EDGE / F_EDGE (IEC 61131-3 6.5.1.2)."""
    return [s for s in pou.variables.values()
            if s.kind == "VAR_INPUT" and s.decl is not None and s.decl.edge]


def edge_slot(symbol) -> str:
    """The hidden slot holding an edge input's value at the previous call."""
    return "_edge" + pyident(symbol.name)


def edge_input_lines(symbol, name: str) -> list[str]:
    """Inside the body an edge input reads TRUE only on its edge.

    As an R_TRIG / F_TRIG whose memory starts FALSE (the standard's F_TRIG
    keeps M := NOT CLK with M initially 1: the same thing).  The instance
    keeps the raw input (what a caller reads as `fb.CLK`) and, in a hidden
    slot, the raw value of the previous call.
    """
    memory = edge_slot(symbol)
    edge = f"self.{name} and not self.{memory}" if symbol.decl.edge == "R_EDGE" \
        else f"self.{memory} and not self.{name}"
    return [f"{name} = {edge}", f"self.{memory} = self.{name}"]


class Scope:
    def __init__(self, program, pou, method: bool, usage: Usage, globals_name: str = "_G"):
        self.program = program
        self.pou = pou
        self.method = method
        self.usage = usage
        self.places: dict[str, VarPlace] = {}
        self.prologue: list[str] = []
        self.epilogue: list[str] = []
        self.params: list[str] = []
        self._plan()
        self.alias_globals()

    # ------------------------------------------------------------ layout

    def _shares_instance(self) -> bool:
        """Whether code other than this body may change the instance's variables
        while it runs (its methods, THIS): then nothing is cached in locals."""
        pou = self.pou
        if "THIS" in self.usage.used:
            return True
        while pou is not None and pou.kind == "FUNCTION_BLOCK":
            if pou.methods:
                return True
            pou = pou.parent
        return False

    def _plan(self) -> None:
        u = self.usage
        no_cache = self.method and self._shares_instance()
        for key, symbol in self.pou.variables.items():
            name = pyident(symbol.name)
            aggregate = is_aggregate(symbol.type)
            kind = symbol.kind
            if kind == "VAR_EXTERNAL" or kind == "VAR_GLOBAL":
                self.places[key] = VarPlace(symbol, "global", name)
                continue
            if kind == "VAR_IN_OUT":
                self.places[key] = VarPlace(symbol, "alias" if aggregate else "ref", name)
                if self.method:
                    if key in u.used:
                        self.prologue.append(f"{name} = self.{name}")
                else:
                    self.params.append(name)
                continue
            referenced = key in u.referenced
            if self.method and symbol.decl is not None and symbol.decl.edge:
                self.places[key] = VarPlace(symbol, "local", name)
                self.prologue.extend(edge_input_lines(symbol, name))
                continue
            if self.method and kind != "VAR_TEMP":
                if aggregate:
                    self.places[key] = VarPlace(symbol, "alias", name)
                    if key in u.used:
                        self.prologue.append(f"{name} = self.{name}")
                elif referenced or no_cache or u.count.get(key, 0) < CACHE_THRESHOLD or \
                        (symbol.decl is not None and symbol.decl.location is not None):
                    # (A located variable is never cached: others may share its bits.)
                    # Passed by reference, or used too rarely to repay a load and a store.
                    self.places[key] = VarPlace(symbol, "self", name)
                else:
                    self.places[key] = VarPlace(symbol, "local", name)
                    if key in u.used:
                        self.prologue.append(f"{name} = self.{name}")
                    if key in u.assigned:
                        self.epilogue.append(f"self.{name} = {name}")
                continue
            # Function variables and VAR_TEMP: Python locals.
            how = "alias" if aggregate else ("cell" if referenced else "local")
            self.places[key] = VarPlace(symbol, how, name)
            if not self.method and kind == "VAR_INPUT":
                self.params.append(name)
                if aggregate and key in u.assigned:
                    self.prologue.append(("copy", symbol, name))
                elif how == "cell":
                    self.prologue.append(f"{name} = [{name}]")
                continue
            if key in u.used or kind in ("VAR_OUTPUT", "RETURN"):
                if symbol.constant and aggregate:
                    how = "shared"      # a CONSTANT array/struct: one instance for every call
                self.prologue.append(("init", symbol, name, how))

    # ----------------------------------------------------------- lookups

    def place_of(self, e) -> VarPlace:
        key = e.name.upper()
        place = self.places.get(key)
        if place is not None:
            return place
        owner = self.pou.owner if self.pou.kind == "METHOD" else (
            self.pou if self.pou.kind == "FUNCTION_BLOCK" else None)
        if key == "THIS" and owner is not None:
            return VarPlace(None, "this", "self")
        if self.pou.kind == "METHOD" and key in owner.variables:
            # A METHOD reaches its FB's variables through the instance.
            symbol = owner.variables[key]
            name = pyident(symbol.name)
            how = "ref" if symbol.kind == "VAR_IN_OUT" and not is_aggregate(symbol.type) else "self"
            place = VarPlace(symbol, how, f"self.{name}" if how == "ref" else name)
            self.places[key] = place
            return place
        symbol = self.program.globals.get(key)
        if symbol is not None:
            place = VarPlace(symbol, "global", pyident(symbol.name))
            self.places[key] = place
            return place
        raise CompileError(f"'{e.name}' is not a variable here", e.pos)

    def alias_globals(self) -> None:
        """Alias the global arrays/structs the body uses in locals (identity is stable)."""
        for key in sorted(self.usage.used):
            if key in self.places:
                place = self.places[key]
                if place.how != "global":
                    continue
            else:
                symbol = self.program.globals.get(key)
                if symbol is None:
                    continue
                place = VarPlace(symbol, "global", pyident(symbol.name))
            if is_aggregate(place.symbol.type):
                self.places[key] = VarPlace(place.symbol, "alias", place.name)
                self.prologue.append(f"{place.name} = _G.{place.name}")

    def lvalue_of_name(self, ec, e) -> LValue:
        place = self.place_of(e)
        if place.how == "this":
            return LValue("local", ec.ty(e), name="self")
        t = place.symbol.type
        how = place.how
        if how in ("local", "alias"):
            return LValue("local", t, name=place.name)
        if how == "cell":
            return LValue("item", t, obj=place.name, key="0")
        if how == "self":
            return LValue("attr", t, obj="self", key=place.name)
        if how == "ref":
            return LValue("ref", t, name=place.name)
        return LValue("attr", t, obj="_G", key=place.name)
