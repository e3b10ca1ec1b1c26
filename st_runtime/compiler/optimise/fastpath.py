"""The per-POU fast path: a body whose worst-case NJ time is known, run without budget checks.

A body qualifies when its cost is bounded at compile time: every loop is a
FOR with constant bounds and step whose body leaves its variable alone (no
WHILE, REPEAT or data-dependent count), and every FUNCTION or FB written in
ST that it calls qualifies too (no METHOD or PROPERTY: they are dispatched
at run time, nor an FB that extends or is extended).  `worst_case` adds
every charge the body could make on any path (every condition, label and
branch, every iteration) and its callees' worst cases: an upper bound of
what one call takes from `_ctx.budget`.

The body is then compiled twice (statements.py), when its exact code has at
least `WORTH` budget checks (a second copy costs load time):

    if _ctx.budget >= <worst case>:
        <the body without budget checks, its charges merged>
    else:
        <the body as before>

An iteration of a FOR whose count is data and which may leave early (the
FK's Newton loop) is tested the same way, against `_ctx.budget - _spent`.
When the budget covers the worst case no check could fire (a check compares
what the body and its callees have charged since it began with the budget it
began with), so leaving them out changes nothing; otherwise the exact path
runs and F-PERIOD lands where it did.
`_spent` is read only when the body returns (or a fault with stop_on_fault
ends the scan), so within a straight run of blocks (`Segments`) the charges
can be added once, at the run's first block: the run ends after a statement
that may leave it (EXIT, CONTINUE, RETURN, a call of ST code, which ends the
scan when a fault in it stops the run), and a fault handler takes
back what was charged ahead of it while `_ctx.fault` runs, so a fault that
stops the run sees `_spent` as the exact path has it.
"""

from __future__ import annotations

import re
from dataclasses import replace

from ... import ast
from ...types import ArrayType, SubrangeType, resolve_alias
from ..scope import assigned_in, once, walk

_JUMPS = (ast.Exit, ast.Continue, ast.Return)
WORTH = 8               # budget checks the exact code must have (the LU: 64, the FK: 23)
MAX_VALUES = 64         # values of a loop variable the bound is worked out for one by one
_TOKEN = re.compile("\x02([SA])([0-9:,]*)\x02")


def listed_in_outs(compiler, body) -> dict[str, str]:
    """A FUNCTION's VAR_IN_OUT arrays (not ARRAY[*]) that `body` names: upper name ->
    the parameter's Python name.  The fast path runs only when each holds a Python list
    (`_type(v) is _list`; not the NullRef of an unconnected in-out passed on), so in it
    their reads and stores at indices in range cannot fault (branches.py, unguard.py)."""
    if compiler.pou.kind != "FUNCTION":
        return {}
    named = {n.name.upper() for n in walk(body) if isinstance(n, ast.Name)}
    found = {}
    for key, symbol in compiler.pou.variables.items():
        t = resolve_alias(symbol.type)
        if symbol.kind == "VAR_IN_OUT" and key in named and isinstance(t, ArrayType) and not t.is_open:
            place = compiler.scope.places.get(key)
            if place is not None and place.how == "alias":
                found[key] = place.name
    return found


def worst_case(compiler, body) -> int | None:
    """Units the body charges at most in one run, its callees' charges included, or
    None when that is not bounded here."""
    properties = compiler.program.properties
    if properties and any(id(node) in properties for node in walk(body)):
        return None             # a PROPERTY's accessor runs ST code
    if body is not compiler.body or compiler.unrolled:
        return _bound(compiler, body)
    # A POU's whole body is bounded once a load: for a caller (`_pou_bound`) and for itself.
    return once(compiler.unit.__dict__.setdefault("body_bounds", {}), body, lambda: _bound(compiler, body))


def _bound(compiler, body) -> int | None:
    cost = compiler.cost
    total = 0
    for s in body or ():
        if isinstance(s, ast.Empty):
            continue
        if isinstance(s, (ast.While, ast.Repeat)):
            return None
        parts = []
        for part in _parts(compiler, s, cost):
            if part is None:
                return None         # (the parts after it are not looked at)
            parts.append(part)
        total += sum(parts)
    return total


def _parts(compiler, s, cost):
    """The units of the parts of the statement `s`, in order; None for a part that is not
    bounded (then the statement is not)."""
    if isinstance(s, ast.If):
        for b in s.branches:
            yield cost.condition(b.condition)
        for b in s.branches:
            yield _calls(compiler, b.condition)
        for b in s.branches:
            yield _bound(compiler, b.body)
        yield _bound(compiler, s.else_body)
    elif isinstance(s, ast.Case):
        yield cost.expr(s.selector)
        yield _calls(compiler, s.selector)
        yield sum(cost.case_labels(c) for c in s.clauses) * cost.w["branch"]
        for c in s.clauses:
            yield _bound(compiler, c.body)
        yield _bound(compiler, s.else_body)
    elif isinstance(s, ast.For):
        values = _values(compiler, s)
        if values is None:
            yield None
            return
        yield cost.for_setup(s)
        yield _iterations(compiler, s, values)
    else:
        yield compiler._simple_cost(s)
        yield _calls(compiler, s)


def _calls(compiler, node) -> int | None:
    """Units the ST code that `node`'s calls run charges at most (its own blocks)."""
    total = 0
    for n in walk(node):
        if isinstance(n, ast.Call):
            target = compiler.program.call_targets.get(id(n))
            callee = _callee(compiler, target)
            if callee is not None:
                units = _pou_bound(compiler, callee)
                if units is None:
                    return None
                total += units
            elif target is None or target.kind in ("method", "super_body"):
                return None     # unknown, or dispatched at run time
    return total


def _callee(compiler, target):
    """The POU written in ST that a call runs, or None (a standard function, a native FB).
    A project's own FB named like a native one (TON, W-DECL-001) runs its ST body: it is
    a callee, as the compiler's `_execute` calls it (its POU has no native class)."""
    if target is None or target.kind not in ("function", "fb"):
        return None
    pou = getattr(target, "pou", None)
    if pou is None or pou.node is None or pou.native is not None:
        return None
    return pou


def _pou_bound(compiler, pou) -> int | None:
    """A user FUNCTION's or FB's worst case, once per compilation (None if an FB that
    extends or is extended: the instance may run another body)."""
    program = compiler.program
    if pou.kind == "FUNCTION_BLOCK" and (pou.parent is not None
                                         or any(p.parent is pou for p in program.pous.values())):
        return None
    known = compiler.unit.__dict__.setdefault("worst_cases", {})
    key = pou.name.upper()
    if key not in known:
        known[key] = None           # (a recursive call: not bounded)
        callee = _bounding_compiler(program, pou, compiler.unit)
        known[key] = worst_case(callee, callee.body)
    return known[key]


# The passes whose analyses a BodyCompiler makes as it is created, for the code it will
# write; a compiler that only bounds a callee writes none (load time).
_CODE_ANALYSES = dict(ranges=False, cse=False, aliases=False, stores=False, reuse=False)


def _bounding_compiler(program, pou, unit):
    """A compiler of `pou` for `worst_case` only: its scope, constants (`fold`) and cost
    model as when its code is compiled, none of the analyses only code generation reads."""
    from ..statements import BodyCompiler

    optimise = unit.optimise
    unit.optimise = replace(optimise, **_CODE_ANALYSES)
    try:
        callee = BodyCompiler(program, pou, unit, method=pou.kind != "FUNCTION")
    finally:
        unit.optimise = optimise
    callee.opt = optimise
    return callee


def may_leave(compiler, stmt) -> bool:
    """Whether control may leave `stmt` other than by its end: a jump, or a call of ST code
    (a fault in it with stop_on_fault ends the scan).  The charges that follow must wait.
    Asked once a statement (an unrolled loop's copies are its statements again)."""
    return once(compiler.__dict__.setdefault("_may_leave", {}), stmt, lambda: _may_leave(compiler, stmt))


def _may_leave(compiler, stmt) -> bool:
    for n in walk(stmt) if not isinstance(stmt, _JUMPS) else (stmt,):
        if isinstance(n, _JUMPS):
            return True
        if isinstance(n, ast.Call):
            target = compiler.program.call_targets.get(id(n))
            if target is None or target.kind in ("method", "super_body") or _callee(compiler, target):
                return True
        if id(n) in compiler.program.properties:
            return True
    return False


def _iterations(compiler, s, values: range) -> int | None:
    """Units of all iterations: the body's bound times the count, or, when an inner
    loop's bounds depend on the variable (`FOR Row := K + 1 TO SIZE`), summed over
    the values the variable takes, each seen as a constant (as unroll.py does)."""
    inner = _bound(compiler, s.body)
    if inner is not None:
        return len(values) * (compiler.cost.loop() + inner)
    if len(values) > MAX_VALUES:
        return None
    key = s.variable.upper()
    saved = compiler.unrolled.get(key)
    total = 0
    try:
        for value in values:
            compiler.unrolled[key] = value
            inner = _bound(compiler, s.body)
            if inner is None:
                return None
            total += compiler.cost.loop() + inner
    finally:
        if saved is None:
            compiler.unrolled.pop(key, None)
        else:
            compiler.unrolled[key] = saved
    return total


def _values(compiler, s) -> range | None:
    """The values of a FOR that runs over a constant range, else None."""
    start, end = compiler.constant_of(s.start), compiler.constant_of(s.end)
    step = 1 if s.step is None else compiler.constant_of(s.step)
    if not all(type(v) is int for v in (start, end, step)) or step == 0:
        return None
    if tests_its_variable(compiler, s, compiler.scope.place_of(ast.Name(s.variable, pos=s.pos))):
        return None         # a loop that tests its variable: its count is data
    return range(start, end + (1 if step > 0 else -1), step)


def tests_its_variable(compiler, s, place) -> bool:
    """Whether a FOR runs as a loop that stores and tests its variable each iteration
    (statements._for_as_while) rather than over a range computed once: when the body may
    change the variable (a global can change in any call), or when the variable is of a
    subrange type, whose every store is checked (F-SUBRANGE, also the last increment)."""
    return (place.how == "global" or s.variable.upper() in assigned_in(compiler, s.body)
            or isinstance(resolve_alias(place.symbol.type), SubrangeType))


def worth_it(exact_lines: list[str]) -> bool:
    """Whether the exact code has budget checks enough to pay for a second copy (its load time)."""
    return sum(1 for line in exact_lines if line.lstrip().startswith("if _ctx.budget <")) >= WORTH


class Segments:
    """The charges of the fast body: one `_spent +=` per straight run of blocks.

    A level is one body compiled by `statements` (a branch, a loop's body);
    its open segment takes every charge until a jump closes it.  The amounts
    are known only when the body is compiled, so the lines carry tokens that
    `resolve` replaces."""

    def __init__(self):
        self.totals: list[int] = []
        self.levels: list[list] = []        # per level: [open segment or None]

    def enter(self) -> None:
        self.levels.append([None])

    def leave(self) -> None:
        self.levels.pop()

    def close(self) -> None:
        self.levels[-1][0] = None

    def charge(self, ps: int) -> str | None:
        """Add `ps` to the open segment; the line to emit when this opens one."""
        level = self.levels[-1]
        if level[0] is None:
            level[0] = len(self.totals)
            self.totals.append(ps)
            return f"_spent += \x02S{level[0]}\x02"
        self.totals[level[0]] += ps
        return None

    def ahead(self) -> str:
        """A token for what the open segments have charged beyond this point so far."""
        marks = [f"{level[0]}:{self.totals[level[0]]}" for level in self.levels if level[0] is not None]
        return f"\x02A{','.join(marks)}\x02"

    def resolve(self, lines: list[str]) -> list[str]:
        """The lines with the amounts in place; a fault handler's take-back of 0 is left out."""
        out = []
        for line in lines:
            if "\x02" not in line:
                out.append(line)
                continue
            text = _TOKEN.sub(self._amount, line)
            if text.lstrip() in ("_spent -= 0", "_spent += 0"):
                continue
            out.append(text)
        return out

    def _amount(self, match) -> str:
        if match.group(1) == "S":
            return str(self.totals[int(match.group(2))])
        marks = [m.split(":") for m in match.group(2).split(",") if m]
        return str(sum(self.totals[int(seg)] - int(seen) for seg, seen in marks))
