"""Statements: assignments, calls, IF/CASE/FOR/WHILE/REPEAT, EXIT/CONTINUE."""

from __future__ import annotations

import bisect

from .. import ast
from .. import types as T
from ..ast import key
from ..per_class import PerClass
from . import typesys as ts
from .constfold import NOT_CONSTANT
from .expressions import ExprChecker, start_pos
from .loop_writes import note_assignment, note_write
from .stores import check_store, controls_a_loop


def _check_of(cls: type):
    """The StatementChecker method that checks a statement of `cls` (`_` + the class name),
    or `_nothing` (EMPTY, RETURN): `_CHECKS[cls]`, found on a class's first statement."""
    return getattr(StatementChecker, "_" + cls.__name__, _nothing)


def _nothing(checker, s) -> None:
    """A statement with nothing to check."""


_CHECKS = PerClass(_check_of)


class StatementChecker:
    def __init__(self, ex: ExprChecker):
        self.ex = ex
        self.ctx = ex.ctx
        self.program = ex.program
        self.loop_depth = 0

    def block(self, stmts) -> None:
        for stmt in stmts or ():
            _CHECKS[type(stmt)](self, stmt)

    # ------------------------------------------------------------ simple
    def _Assign(self, s: ast.Assign) -> None:
        if s.mode != ":=":          # S= / R=: a BOOL set or reset when the value is TRUE
            target = check_store(self.ex, s.target, s.mode)
            if target is not ts.ERROR:
                self.ex.require_assignable(T.BOOL, target, s.target.pos, s.mode)
            self.ex.check_value(s.value, T.BOOL, s.mode)
            return
        target = check_store(self.ex, s.target)
        if target is ts.ERROR:
            if s.value is not None:
                self.ex.infer(s.value)
            return
        # A constant outside a subrange target's limits is refused here, as it is for an input.
        self.ex.check_value(s.value, self.program.subranges.get(id(s.target), target), "assignment")
        if type(s.value) is ast.Call:     # (what note_assignment records is a REF's or ADR's)
            note_assignment(self.ex, s.target, s.value)

    def _CallStmt(self, s: ast.CallStmt) -> None:
        self.ex.calls.check_call(s.call, None, statement=True)

    def _Exit(self, s) -> None:
        if self.loop_depth == 0:
            self.ctx.error("E-FLOW-001", "EXIT outside a loop: expected inside FOR, WHILE or REPEAT", s.pos)

    def _Continue(self, s) -> None:
        if self.loop_depth == 0:
            self.ctx.error("E-FLOW-002", "CONTINUE outside a loop: expected inside FOR, WHILE or "
                           "REPEAT", s.pos)

    # ------------------------------------------------------------ control
    def condition(self, e, what: str) -> None:
        t = self.ex.infer(e, T.BOOL)
        if t is not ts.ERROR and t is not T.BOOL:
            self.ctx.error("E-TYPE-003", f"{what} condition: expected BOOL, found {t}", start_pos(e))

    def _If(self, s: ast.If) -> None:
        for n, branch in enumerate(s.branches):
            self.condition(branch.condition, "IF" if n == 0 else "ELSIF")
            self.block(branch.body)
        self.block(s.else_body)

    def _While(self, s: ast.While) -> None:
        self.condition(s.condition, "WHILE")
        self._loop_body(s.body)

    def _Repeat(self, s: ast.Repeat) -> None:
        self._loop_body(s.body)
        self.condition(s.condition, "UNTIL")

    def _loop_body(self, body) -> None:
        self.loop_depth += 1
        try:
            self.block(body)
        finally:
            self.loop_depth -= 1

    def _For(self, s: ast.For) -> None:
        sym = self.ex.scope.lookup(s.variable)
        var_t = ts.ERROR
        if sym is None:
            self.ctx.error("E-DECL-001", f"undeclared FOR control variable '{s.variable}'", s.pos)
        elif not ts.is_int(sym.type):
            self.ctx.error("E-TYPE-010", f"FOR control variable '{sym.name}': expected an integer "
                           f"variable, found {sym.type}", s.pos)
        elif sym.constant:
            self.ctx.error("E-ASSIGN-001", f"FOR control variable '{sym.name}' is CONSTANT", s.pos)
        elif sym.kind == "VAR_INPUT" and self.ex.scope.is_local(sym) \
                and not self.ctx.rules.accepts("INPUT_WRITE"):
            self.ctx.error("E-ASSIGN-002", f"FOR control variable '{sym.name}' is a VAR_INPUT and "
                           f"read-only", s.pos)
        elif controls_a_loop(self.ex, sym):       # the inner FOR would alter the outer's variable
            self.ctx.error("E-ASSIGN-003", f"FOR control variable '{sym.name}' is already the control "
                           f"variable of an enclosing FOR loop", s.pos)
        else:
            var_t = sym.type
            self.program.for_vars[id(s)] = sym
        for part, what in ((s.start, "start"), (s.end, "end"), (s.step, "BY")):
            if part is None:
                continue
            t = self.ex.infer(part, var_t if var_t is not ts.ERROR else T.DINT, strict=var_t is not ts.ERROR)
            if t is ts.ERROR or var_t is ts.ERROR:
                continue
            if not ts.is_int(t):
                self.ctx.error("E-TYPE-010", f"FOR {what} value: expected an integer, found {t}", start_pos(part))
            else:
                self.ex.require_assignable(t, var_t, start_pos(part), f"FOR {what} value")
        if s.step is not None and self.ex.constant(s.step) == 0 and var_t is not ts.ERROR:
            self.ctx.error("E-TYPE-010", "FOR ... BY 0: the step must not be zero", start_pos(s.step))
        pushed = sym is not None and var_t is not ts.ERROR
        if pushed:
            note_write(self.ctx, self.ex.scope, sym)
            self.ex.loop_vars.append(sym)
        self.loop_depth += 1
        try:
            self.block(s.body)
        finally:
            self.loop_depth -= 1
            if pushed:
                self.ex.loop_vars.pop()

    def _Case(self, s: ast.Case) -> None:
        sel = self.ex.infer(s.selector)
        # IEC asks for ANY_INT or an enumeration; bit strings are accepted as
        # CODESYS and the NJ do (CASE w OF 16#01: ...).
        if sel is not ts.ERROR and not (ts.is_int(sel) or ts.is_bits(sel)
                                        or isinstance(sel, T.EnumType)):
            self.ctx.error("E-TYPE-011", f"CASE selector: expected an integer, bit string or "
                           f"enumeration, found {sel}", start_pos(s.selector))
            sel = ts.ERROR
        seen = _LabelSet()
        for clause in s.clauses:
            for label in clause.labels:
                if isinstance(label, ast.CaseRange):
                    lo = self._label(label.lo, sel)
                    hi = self._label(label.hi, sel)
                    if lo is None or hi is None:
                        continue
                    if lo > hi:
                        self.ctx.error("E-TYPE-012", f"CASE range {lo}..{hi}: expected the lower "
                                       f"bound first", start_pos(label))
                        continue
                    self._unique(seen, lo, hi, start_pos(label))
                else:
                    v = self._label(label, sel)
                    if v is not None:
                        self._unique(seen, v, v, start_pos(label))
            self.block(clause.body)
        self.block(s.else_body)

    def _label(self, label, sel):
        t = self.ex.infer(label, None if sel is ts.ERROR else sel, strict=sel is not ts.ERROR)
        if t is ts.ERROR or sel is ts.ERROR:
            return None
        value = self.ex.constant(label)
        if value is NOT_CONSTANT or isinstance(value, (bool, float, str)):
            self.ctx.error("E-TYPE-012", f"CASE label: expected a constant of type {sel}, found "
                           f"a non-constant expression" if value is NOT_CONSTANT
                           else f"CASE label: expected a constant of type {sel}, found {t}", start_pos(label))
            return None
        if isinstance(sel, T.EnumType) and t is not sel:
            self.ctx.error("E-TYPE-012", f"CASE label: expected a value of {sel}, found {t}", start_pos(label))
            return None
        if not isinstance(sel, T.EnumType) and not ts.implicitly_converts(t, sel):
            self.ctx.error("E-TYPE-012", f"CASE label: expected a constant of type {sel}, found {t}",
                           start_pos(label))
            return None
        return value

    def _unique(self, seen: "_LabelSet", lo, hi, pos) -> None:
        first = seen.overlap(lo, hi)
        if first is not None:
            what = f"{lo}" if lo == hi else f"{lo}..{hi}"
            self.ctx.error("E-TYPE-013", f"CASE label {what} overlaps a label at line {first.line}", pos)
            return
        seen.add(lo, hi, pos)


class _LabelSet:
    """The CASE labels seen so far, for the uniqueness check in (near) linear
    time (issue 15: 100,000 labels took over a minute as a list scan).

    Single values go in a dict; ranges, which are few in practice, in a list
    sorted by lower bound and disjoint (an overlapping label is reported and
    never added), searched by bisection.
    """

    def __init__(self) -> None:
        self.singles: dict[int, ast.Pos] = {}
        self.lows: list[int] = []
        self.ranges: list[tuple[int, int, ast.Pos]] = []

    def overlap(self, lo: int, hi: int):
        """The position of a label overlapping lo..hi, or None."""
        at = bisect.bisect_right(self.lows, hi)
        if at and self.ranges[at - 1][1] >= lo:      # the last range starting at or below hi
            return self.ranges[at - 1][2]
        if lo == hi:
            return self.singles.get(lo)
        if hi - lo < len(self.singles):
            for value in range(lo, hi + 1):
                if value in self.singles:
                    return self.singles[value]
            return None
        return next((pos for value, pos in self.singles.items() if lo <= value <= hi), None)

    def add(self, lo: int, hi: int, pos: ast.Pos) -> None:
        if lo == hi:
            self.singles[lo] = pos
            return
        at = bisect.bisect_left(self.lows, lo)
        self.lows.insert(at, lo)
        self.ranges.insert(at, (lo, hi, pos))
