"""A FOR control variable written by a POU called inside its loop: W-ASSIGN-001.

IEC 61131-3 3rd ed. 7.3.3.4.2: the control variable "shall not be altered by any
of the repeated statements".  A statement of the loop that writes it is refused
where it stands (stores.py, E-ASSIGN-003).  A write made by a callee is not in
the loop's text, and no compiler we found refuses it (CODESYS compiles even the
direct write; its static analysis, SA0072, looks at the loop's own statements).
Such a program runs: the loop tests the variable as the callee left it, which the
compiler keeps and tests/test_compiler_tables_core.py pins.  So the checker warns,
at the call, naming the chain of calls.

A callee alters the control variable only by writing the same storage.  The pass
follows the two ways a callee names that storage without a reference:

* a global (a VAR_GLOBAL, named through VAR_EXTERNAL or, where the dialect allows,
  directly): every POU names the same variable, so a FUNCTION, FB instance or
  METHOD (of any instance) called in the loop alters it if its body writes that
  global, itself or through what it calls;
* a variable of the FB running the loop: only this instance's METHODs name it
  (`M()`, `THIS.M()`, `SUPER.M()`), so for a FOR over one of them a method called
  on this instance alters it when its body writes it, itself or through the
  methods it calls on this instance.  A method of another instance (`other.M()`,
  `peer.M()` for a VAR_IN_OUT, `others[1].M()`) writes that instance's variable
  of the name, other storage, unless the instance is this one reached through a
  reference or a VAR_IN_OUT bound to THIS, which is alias analysis (not done).

Which METHOD a call runs: `SUPER.M()` the base FB's M; `inst.M()` on an instance
held by value (a VAR, an input, an array element, a STRUCT member: its type is
the declared one) the declared type's M; `M()`, `THIS.M()` and a call through a
VAR_IN_OUT or a dereferenced reference run the M of the instance's dynamic type,
which may be any FB extending the declared one (an instance of a derived FB runs
its base's code, and a derived instance binds to a base VAR_IN_OUT), and
`itf.M()` the M of any FB implementing the INTERFACE.  The checker does not know
the dynamic type, so it follows every candidate in the program (the declared
FB's first) and names, in the warning, the derived FB whose override writes.

A reference alters the variable it refers to.  The pass knows what a reference
refers to when it is a VAR or VAR_TEMP (written only by the code of its POU, and
of its FB's methods; a reference takes no initial value, E-DECL-008) whose every
store is an assignment
`r := REF(i)` (or `ADR(i)`) of one variable: then `r` refers to `i` or is NULL
(a write through NULL faults instead), wherever the assignment stands (a VAR
keeps the reference from one call to the next).  A write through it (`r^ := ...`)
in a FOR over `i` is warned of where it stands, and so is a call in the loop that
hands `r` to an input of a FUNCTION, FB or METHOD whose body writes through that
input (the callee's own text: what it passes on is not followed).

Not followed: a reference with another store (`r := NULL`, `r := q`, an output
or VAR_IN_OUT bound to it, `REF(r)`), one held in an array, a STRUCT, an input or
a global, a reference to a global or to the FB's variable taken in another POU,
a VAR_IN_OUT bound to the variable somewhere else (alias analysis), and the body
of a derived FB run by a call of an FB instance through a VAR_IN_OUT of its base
type.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import NamedTuple

from .. import ast
from .. import types as T
from ..ast import key

#: Symbol kinds that name a global variable.
GLOBAL_KINDS = frozenset({"VAR_GLOBAL", "VAR_EXTERNAL"})


class LoopCall(NamedTuple):
    """A call made inside FOR loops: the nodes it may run (the declared one first), the
    loops' globals ({upper-case name: name}) and, for a call on this instance, the loops'
    variables of the FB ({id(symbol): name})."""

    callees: tuple[str, ...]
    pos: ast.Pos
    globals: dict[str, str]
    members: dict[int, str]


class ThroughReference(NamedTuple):
    """A write through reference variable `ref` in FOR loops ({id(control variable): name}):
    in the loop's text, or by the callees (the nodes a call may run) given it as input `param`."""

    ref: object
    pos: ast.Pos
    loops: dict[int, str]
    callees: tuple[str, ...] = ()
    param: str = ""


@dataclass(init=False)
class WriteGraph:
    """What the bodies' check gathers for this pass.  A node is a POU's key, or 'FB.M' for
    a METHOD (a POU key holds no '.': namespaces share one name space).  Every call is in
    the checker's one graph of calls, `Context.calls`, by the same nodes.  Made once a load:
    `__init__` written out, like CheckedProgram's."""

    infos: dict = field(default_factory=dict)                 # node -> its PouInfo
    global_writes: dict[str, set[str]] = field(default_factory=dict)
    member_writes: dict[str, set[int]] = field(default_factory=dict)     # method node ->
    this_calls: dict[str, list[str]] = field(default_factory=dict)       # methods on THIS
    loop_calls: list[LoopCall] = field(default_factory=list)
    ref_stores: dict[int, int] = field(default_factory=dict)         # id(reference) -> count
    ref_targets: dict[int, list] = field(default_factory=dict)       # -> [(symbol, how, pos)]
    param_writes: dict[str, set[str]] = field(default_factory=dict)  # node -> written through
    through_references: list[ThroughReference] = field(default_factory=list)
    heirs: dict[tuple, list] = field(default_factory=dict)   # _heirs' table, filled lazily

    def __init__(self) -> None:
        self.infos = {}
        self.global_writes = {}
        self.member_writes = {}
        self.this_calls = {}
        self.loop_calls = []
        self.ref_stores = {}
        self.ref_targets = {}
        self.param_writes = {}
        self.through_references = []
        self.heirs = {}


def node_of(graph: WriteGraph, pou) -> str:
    """The node of POU or METHOD `pou`, registered."""
    node = f"{key(pou.owner.name)}.{key(pou.name)}" if pou.kind == "METHOD" else key(pou.name)
    graph.infos.setdefault(node, pou)
    return node


def note_write(ctx, scope, sym) -> None:
    """Record that the POU being checked writes `sym` (a store, or a FOR over it), when `sym`
    is a global, or a variable of the FB whose METHOD is being checked."""
    if scope.pou is None:
        return
    graph = ctx.writes
    if _is_reference(sym):
        _count_store(graph, sym)
    if sym.kind in GLOBAL_KINDS:
        graph.global_writes.setdefault(node_of(graph, scope.pou), set()).add(key(sym.name))
    elif scope.pou.kind == "METHOD" and scope.fb.variables.get(key(sym.name)) is sym:
        graph.member_writes.setdefault(node_of(graph, scope.pou), set()).add(id(sym))


def _is_reference(sym) -> bool:
    return isinstance(sym.type, T.RefType)     # (the checker's types hold no alias)


def _count_store(graph: WriteGraph, ref) -> None:
    graph.ref_stores[id(ref)] = graph.ref_stores.get(id(ref), 0) + 1


def _loops(ex) -> dict[int, str]:
    """{id(control variable): its name} of the FOR loops enclosing the statement checked."""
    return {id(sym): sym.name for sym in ex.loop_vars}


def note_in_out(ex, value) -> None:
    """Record a reference variable bound to a VAR_IN_OUT: the callee may store into it."""
    sym = ex.program.name_refs.get(id(value))        # (None but for a Name)
    if hasattr(sym, "kind") and _is_reference(sym):
        _count_store(ex.ctx.writes, sym)


def note_assignment(ex, target, value) -> None:
    """Record `r := REF(x)` / `r := ADR(x)`: reference `r` refers to variable `x`."""
    how = ex.program.call_targets.get(id(value))       # (a checked REF's argument is a variable)
    if isinstance(target, ast.Name) and how is not None and how.kind == "ref" \
            and isinstance(value.args[0].value, ast.Name):
        names = ex.program.name_refs
        ex.ctx.writes.ref_targets.setdefault(id(names[id(target)]), []).append(
            (names[id(value.args[0].value)], how.name, value.pos))


def note_write_through(ex, target) -> None:
    """Record a store through reference variable `r` (`r^ := ...`, `r^.x := ...`): in FOR loops,
    and by a POU through one of its own variables (its inputs among them)."""
    inner = target
    while isinstance(inner.base, (ast.Member, ast.Index, ast.Deref, ast.BitAccess)):
        inner = inner.base
    if not isinstance(inner, ast.Deref):       # `s.r^`, `refs[1]^`: not a variable's reference
        return
    graph, ref = ex.ctx.writes, ex.program.name_refs[id(inner.base)]
    if ex.scope.pou.variables.get(key(ref.name)) is ref:
        graph.param_writes.setdefault(node_of(graph, ex.scope.pou), set()).add(key(ref.name))
    if ex.loop_vars:
        graph.through_references.append(ThroughReference(ref, inner.base.pos, _loops(ex)))


def note_argument(ex, pou, param, value, pos) -> None:
    """Record reference variable `value` given to input `param` of `pou` in FOR loops."""
    ref = ex.program.name_refs.get(id(value))        # (None but for a Name)
    if ex.loop_vars and hasattr(ref, "kind") and _is_reference(ref):
        graph = ex.ctx.writes
        graph.through_references.append(
            ThroughReference(ref, pos, _loops(ex), (node_of(graph, pou),), param.name))


def note_call(ex, pou, pos) -> None:
    """Record a call of FUNCTION or FB `pou` (its body)."""
    _note(ex, (node_of(ex.ctx.writes, pou),), pos, this=False)


def note_method_call(ex, method, callee, how: str, pos) -> None:
    """Record a call of `method` (as resolved where it is written, `how` the checker's kind
    of call: "self", "super", "virtual" or "interface")."""
    graph = ex.ctx.writes
    candidates = tuple(node_of(graph, m) for m in _candidates(ex, method, callee, how))
    _note(ex, candidates, pos, this=how in ("self", "super") or _on_this(callee))


def _note(ex, callees: tuple[str, ...], pos, this: bool) -> None:
    scope, graph = ex.scope, ex.ctx.writes
    if scope.pou is not None:
        caller = node_of(graph, scope.pou)
        ex.ctx.calls.setdefault(caller, []).extend([(callee, pos) for callee in callees])
        if this and scope.pou.kind == "METHOD":
            graph.this_calls.setdefault(caller, []).extend(callees)
    if not ex.loop_vars:
        return
    globals_ = {key(sym.name): sym.name for sym in ex.loop_vars if sym.kind in GLOBAL_KINDS}
    members = {}
    if this:
        fields = scope.fb.variables
        members = {id(sym): sym.name for sym in ex.loop_vars if fields.get(key(sym.name)) is sym}
    if globals_ or members:
        graph.loop_calls.append(LoopCall(callees, pos, globals_, members))


def _candidates(ex, method, callee, how: str) -> list:
    """The METHODs a call may run: `method`, then the overrides a dynamic type may run."""
    if how == "super" or (how == "virtual" and _by_value(ex, callee.base)):
        return [method]
    if how == "interface":
        fbs = _heirs(ex.ctx, method.owner, by_interface=True)
    else:
        fbs = _heirs(ex.ctx, ex.scope.fb if how == "self" else ex.program.expr_types[id(callee.base)].info)
    found = [method]
    for fb in fbs:
        override = fb.methods.get(key(method.name))
        if override is not None and override not in found:
            found.append(override)
    return found


def _heirs(ctx, declared, by_interface: bool = False) -> list:
    """The program's FBs, in its order, that extend FB `declared` (itself among them), or that
    implement INTERFACE `declared`: found once a load for each (the bodies' check declares none)."""
    table = ctx.writes.heirs
    found = table.get((id(declared), by_interface))
    if found is None:
        fbs = [info for info in ctx.program.pous.values() if info.kind == "FUNCTION_BLOCK"]
        found = table[id(declared), by_interface] = [
            fb for fb in fbs if (fb.implements(declared) if by_interface else fb.descends_from(declared))]
    return found


def _by_value(ex, instance) -> bool:
    """Whether the instance a call names is of its declared type: not THIS, a VAR_IN_OUT or a
    dereferenced reference, which may hold an FB extending it (a member or an element of any
    instance is stored by value)."""
    if isinstance(instance, ast.Deref):
        return False
    sym = ex.program.name_refs.get(id(instance))      # (None for a member or an element)
    return sym is None or sym.kind not in ("VAR_IN_OUT", "THIS")


def _on_this(callee) -> bool:
    """`THIS.M`: a virtual call on this instance (`callee` is a Member: a "virtual" or
    "interface" call names its instance)."""
    base = callee.base
    return isinstance(base, ast.Name) and key(base.name) == "THIS"


def check_calls_in_loops(ctx) -> None:
    """W-ASSIGN-001 at each call, made in a FOR over a global or over a variable of the FB,
    of a POU or METHOD that writes it."""
    graph = ctx.writes
    if not graph.loop_calls:
        return

    def callees(node):
        return [callee for callee, _ in ctx.calls.get(node, ())]

    def on_this(node):
        return graph.this_calls.get(node, ())

    for call in graph.loop_calls:
        for global_key, name in call.globals.items():
            if _warn_first(ctx, call, f"global '{name}'",
                           lambda node: global_key in graph.global_writes.get(node, ()), callees):
                break
        for sym_id, name in call.members.items():
            if _warn_first(ctx, call, f"'{name}'",
                           lambda node: sym_id in graph.member_writes.get(node, ()), on_this):
                break


def check_references_in_loops(ctx) -> None:
    """W-ASSIGN-001 at each write through, or call handed, a reference known to refer to the
    control variable of an enclosing FOR."""
    graph = ctx.writes
    for use in graph.through_references:
        target = _sole_target(graph, use.ref)
        if target is None or id(target[0]) not in use.loops:
            continue
        sym, how, pos = target
        refers = f"'{use.ref.name}' refers to it: {use.ref.name} := {how}({sym.name}) on line {pos.line}"
        if not use.callees:
            _say(ctx, f"write through '{use.ref.name}' alters '{sym.name}'", refers, use.pos)
            continue
        callee = graph.infos[use.callees[0]]
        if key(use.param) in graph.param_writes.get(use.callees[0], ()):
            _say(ctx, f"call of {_called(callee)} alters '{sym.name}'",
                 f"{callee.name} writes through its input '{use.param}', given '{use.ref.name}'; "
                 f"{refers}", use.pos)


def _sole_target(graph: WriteGraph, ref):
    """(variable, "REF" or "ADR", position) of the one variable reference `ref` is ever made to
    refer to, when every store into it is such an assignment; else None."""
    taken = graph.ref_targets.get(id(ref))
    if ref.kind not in ("VAR", "VAR_TEMP") or not taken \
            or len(taken) != graph.ref_stores[id(ref)] or any(sym is not taken[0][0] for sym, _, _ in taken):
        return None
    return taken[0]


def _warn_first(ctx, call: LoopCall, what: str, writes, callees) -> bool:
    """Warn of the first of the call's candidates that reaches a writer (`callees(node)` the
    nodes a node calls); whether one did."""
    infos = ctx.writes.infos
    declared = infos[call.callees[0]]
    for callee in call.callees:
        path = _path_to_writer(callee, writes, callees)
        if path:
            names = [infos[node].name for node in path]
            when = ""
            if callee != call.callees[0]:           # an override: name its FB
                owner = infos[callee].owner.name
                when, names[0] = f"for an instance of {owner}, ", f"{owner}.{names[0]}"
            _warn(ctx, f"{_called(declared)} alters {what}", when, names, call.pos)
            return True
    return False


def _called(info) -> str:
    return f"method {info.name}" if info.kind == "METHOD" else info.name


def _warn(ctx, what: str, when: str, names: list[str], pos) -> None:
    chain = f"{names[0]} writes it" if len(names) == 1 else \
        f"{names[0]} calls " + ", which calls ".join(names[1:]) + ", which writes it"
    _say(ctx, f"call of {what}", when + chain, pos)


def _say(ctx, what: str, why: str, pos) -> None:
    ctx.warning("W-ASSIGN-001", f"{what}, the control variable of an enclosing FOR loop ({why}): "
                f"IEC 61131-3 forbids it; the loop goes on from the value left", pos)


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
