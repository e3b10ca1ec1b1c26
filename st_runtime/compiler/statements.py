"""Statements and whole POU bodies.

Runtime faults.  Every assignment and call, at every nesting level, is
wrapped in `try: ... except _FAULTS as _e: _ctx.fault(_e, <where>)`: a
faulting statement is abandoned (as an NJ abandons a faulting instruction and
sets its error flag) and execution goes on with the next statement.  IF,
CASE, FOR, WHILE and REPEAT guard only the expressions they evaluate
themselves: a fault in an IF/ELSIF condition or a CASE selector abandons the
whole statement, in FOR bounds the whole loop, in a WHILE/UNTIL condition it
ends the loop.  (So Python blocks nest only as deep as the ST loops: CPython
allows 20.)  In CPython 3.11+ a `try` costs nothing until something is raised
(zero-cost exception tables): benchmarks/bench_runtime.py shows the same
times with and without the guards.

Execution time.  Every basic block of the ST source (a run of assignments
and calls, with the IF condition, CASE selector or FOR bounds that ends it)
adds its estimated NJ501 time (cost.py, picoseconds) to the local
`_spent` once, at its start (a local: the cheapest charge Python has); an
ELSIF or CASE branch also charges the tests it took to reach it.  Each
compiled POU body flushes `_spent` into `_ctx.budget` when it returns
(`finally`), so a caller sees its callees' time in `_ctx.budget` and the
time left is always `_ctx.budget - _spent`.  A loop charges its overhead,
its test and its body's first block once per iteration and checks there:
when nothing is left the scan ends with `ScanOverrun` (F-PERIOD), which the
per-statement handlers let through.  A FOR whose body is one block and
cannot leave early charges all its iterations once, before it starts (its
bounds are evaluated once, so the count is known).  Straight-line code is
checked by the controller after the program.  The charges come from the ST
text only, so any change of the Python generated for it leaves them as
they are.  Where the worst case of a body is bounded and the time left
covers it, a second copy without checks runs instead (optimise/fastpath.py).
"""

from __future__ import annotations

from .. import ast
from ..objects import is_aggregate
from ..types import SubrangeType, resolve_alias
from .calls import copy_statement
from .cost import CostModel, picoseconds
from .exprs import ExprCompiler, int_bounds
from .initial import CompileError
from .optimise import (aliases, branches, chains, charges, cse, elements, fastpath, fold, gather, halves, kernels, loops,
                       pivots, ranges, reads, reuse, scalars, seal, shortcut, stores, sums, threads, unguard, unroll)
from .optimise import branched, dormant, may_reuse
from .pysrc import Emitter, pyliteral, pyident
from .scope import Scope, Usage, assigned_in, kinds, once, walk
from .support import SMALL_END


class BodyCompiler(ExprCompiler):
    def __init__(self, program, pou, unit, method: bool):
        body = pou.node.body if pou.node is not None else ()
        usage = Usage(program, body, unit.calls)
        scope = Scope(program, pou, method, usage)
        super().__init__(program, pou, scope, unit)
        self.method = method
        self.body = body
        self.out = Emitter()
        self.cost = CostModel(program)
        self._head_costs = unit.head_costs
        self._blocks_memo: dict[int, tuple] = {}       # id(body) -> (body, `_costed_blocks`)
        self._entries_memo: dict[int, tuple] = {}      # id(IF) -> (IF, `_if_entries`)
        flow = ranges.Flow(self, body) if self.opt.ranges else None
        self.flow = flow if flow is not None and flow.bounds else None     # integer locals' ranges, if any
        if not method:
            self._add_return_variable()
        # the whole body compiled as one CSE region, and once as before (cse.body_region)
        self._whole_region = self.opt.cse and unit.guard_statements and ast.Index in usage.kinds \
            and cse.worth_a_region(self, body)
        late = not self._whole_region and branched(body)    # (lines move into branches only)
        # id(branch body) -> alias lines moved there from the prologue (optimise/aliases.py)
        self._late_loads = aliases.late_loads(self, body) if self.opt.aliases and late else {}
        # id(branch body) -> store-back lines (and their loads) moved there (optimise/stores.py)
        self._late_stores = stores.late_stores(self, body) if self.opt.stores and method and late \
            else stores.LateStores()
        self._segments: fastpath.Segments | None = None     # while the fast body is compiled
        self.reuse = reuse.Reuse(self) if self.opt.reuse and may_reuse(self) else None
        self.listed_in_outs: dict[str, str] = {}    # in-outs the fast body runs with as lists
        # a PROGRAM's dormant call sites may form groups (optimise/dormant.py)
        self._dormant_groups = self.opt.dormant and self.opt.inline and pou.kind == "PROGRAM"

    def _add_return_variable(self) -> None:
        key = self.pou.name.upper()
        if key not in self.scope.places and self.pou.return_type is not None:
            from ..symbols import Symbol
            from .scope import VarPlace

            symbol = self.pou.result or Symbol(self.pou.name, self.pou.return_type, "RETURN")
            how = "cell" if key in self.scope.usage.referenced else ("alias" if is_aggregate(symbol.type) else "local")
            self.scope.places[key] = VarPlace(symbol, how, pyident(self.pou.name))
            self.scope.prologue.append(("init", symbol, pyident(self.pou.name), how))

    # -------------------------------------------------------------- units

    def function_source(self, pyname: str) -> str:
        """`def pyname(self, _ctx)` or `def pyname(_ctx, inputs...)`."""
        o = self.out
        params = ["self", "_ctx"] if self.method else ["_ctx"] + self.scope.params
        if not self.method and self.pou.owner is not None:
            params = ["self"] + params          # a METHOD: its instance first
        o.line(f"def {pyname}({', '.join(params)}):")
        start = o.mark()
        o.indent()
        prologue = [self._prologue_line(item) for item in self.scope.prologue]
        if self.opt.gather:
            prologue = gather.prologue(prologue, self.unit.register_constant)
        for line in prologue:
            o.line(line)
        charge = self.unit.charge_costs
        if charge:
            o.line("_spent = 0")        # this call's own charges (ps), flushed into _ctx.budget on exit
        if (self.method and self.scope.epilogue) or charge:
            o.line("try:")
            o.indent()
            mark = o.mark()
            self._body()
            o.ensure_body(mark)
            if not self.method:
                o.line(self._return_statement())
            o.dedent()
            o.line("finally:")
            o.indent()
            if charge:
                o.line("_ctx.budget -= _spent")
            for line in self.scope.epilogue if self.method else ():
                o.line(line)
            o.dedent()
        else:
            mark = o.mark()
            self._body()
            o.ensure_body(mark)
            if not self.method:
                o.line(self._return_statement())
        o.dedent()
        if self.reuse is not None:
            self.reuse.resolve(o.lines, start)
        if self.opt.cse and ast.For in self.scope.usage.kinds:     # (no FOR, no loop to look in)
            reads.share_in_loops(o.lines, start, self.lasting_temp)
        if self.opt.unused:
            aliases.drop_unused(o.lines, start)
            if self.method and self.unit.guard_statements:   # (a line without `try` then cannot raise)
                aliases.drop_unread(o.lines, start, self.opt.deferred)
        if self.opt.early and self.method:
            aliases.store_early(o.lines, start)
        merging = self.opt.charges and charge and self.unit.guard_statements
        if merging:
            charges.merge(o.lines, start)
        if self.opt.threads and threads.thread(o.lines, start) and merging:
            charges.merge(o.lines, start)       # (the charges each path now runs in a row)
        if self.opt.settle and charge:
            charges.settle(o.lines, start)
        if self.opt.seal:
            seal.hoist(o.lines, start)
        if self.opt.kernels and self.unit.native:
            kernels.replace(o.lines, start, self.unit.register_constant, self.unit.namespace.__setitem__,
                            kernels.not_floats(self.scope.places))
        if self.opt.loops and self.unit.native:
            loops.replace(o.lines, start, self.unit.register_constant, self.unit.namespace.__setitem__)
        return o.source()

    def _body(self) -> None:
        """The body; with the fast path (optimise/fastpath.py), once without budget
        checks, run when the budget covers the worst case, and once as before."""
        worst = self._worst_case(self.body)
        if worst is None:
            self._statements_of_body()
        else:
            self._fast_or_exact(f"_ctx.budget >= {picoseconds(worst)}", self._statements_of_body,
                                self._statements_of_body, self.body)

    def _fast_or_exact(self, test: str, fast, exact, body) -> None:
        """The code `exact()` emits; when it has at least `fastpath.WORTH` budget checks,
        `if test:` the code `fast()` emits without them, its charges merged
        (fastpath.Segments), `else:` the exact code.  Both from the same state.
        The fast code runs only when the FUNCTION's in-out arrays `body` names are
        Python lists, and is compiled knowing it (fastpath.listed_in_outs)."""
        o = self.out
        mark = o.mark()
        before = self.flow.state() if self.flow is not None else None
        unroll_left = getattr(self, "unroll_left", None)
        exact()
        if not fastpath.worth_it(o.lines[mark:]):
            return
        exact_lines = o.lines[mark:]
        del o.lines[mark:]
        if unroll_left is not None:         # the same unrolling in both (unroll.can_unroll's budget)
            self.unroll_left = unroll_left
        elif hasattr(self, "unroll_left"):  # (not set yet: unroll.can_unroll starts from the cap)
            del self.unroll_left
        after_exact = None
        if self.flow is not None:
            after_exact = self.flow.state()
            self.flow.set(before)
        listed = fastpath.listed_in_outs(self, body) if self.opt.unguard or self.opt.branches else {}
        o.line(f"if {test}{''.join(f' and _type({name}) is _list' for name in listed.values())}:")
        o.indent()
        inner = o.mark()
        self._segments = fastpath.Segments()
        self.listed_in_outs = listed
        try:
            fast()
            o.lines[inner:] = self._segments.resolve(o.lines[inner:])
            if self.opt.chains:
                chains.merge(o.lines, inner)
            if self.opt.scalars and listed:
                scalars.replace(o.lines, inner, scalars.candidates(self, body, listed))
            if self.opt.pivots:
                pivots.keep(o.lines, inner)
            if self.opt.sums:
                sums.fold(o.lines, inner, sums.arrays(self))
        finally:
            self._segments = None
            self.listed_in_outs = {}
        o.ensure_body(inner)
        o.dedent()
        o.line("else:")
        o.lines.extend("    " + line for line in exact_lines)
        if self.flow is not None:
            self.flow.join([self.flow.state(), after_exact])

    def _worst_case(self, body) -> int | None:
        """Units `body` charges at most, when the fast path applies to it (not already
        in a fast body, nor in a CSE region, whose code cse.py rearranges)."""
        if not (self.opt.fastpath and self.unit.charge_costs and self.unit.guard_statements
                and self._segments is None and self.region is None):
            return None
        if ast.For not in (self.scope.usage.kinds if body is self.body else kinds(body)):
            return None             # no loop, no budget check to leave out
        return fastpath.worst_case(self, body)

    def _statements_of_body(self) -> None:
        """The body's statements; twice when a whole-body region applies (cse.body_region)."""
        if not self._whole_region:
            self.statements(self.body)
            return
        cse.emit_region(self, lambda: self.statements(self.body))

    def _prologue_line(self, item) -> str:
        if isinstance(item, str):
            return item
        if item[0] == "copy":     # an aggregate input the body modifies: by value
            _, symbol, name = item
            maker = self.unit.register_maker(self.unit.initial.of(symbol.type, None, ast.NOWHERE).maker)
            held = "_in" + name
            return f"{held} = {name}; {name} = {maker}(); {copy_statement(name, held, symbol.type)}"
        _, symbol, name, how = item
        initial = self.unit.initial.of_symbol(symbol) if symbol.kind != "RETURN" \
            else self.unit.initial.of(symbol.type, symbol.init, ast.NOWHERE)
        value = self.literal(initial.const, symbol.type) if initial.is_const \
            else self.unit.register_maker(initial.maker) + "()"
        if how == "shared":
            shared = self.unit.register_constant(initial.maker())
            return f"{name} = {shared}"
        return f"{name} = [{value}]" if how == "cell" else f"{name} = {value}"

    def _return_statement(self) -> str:
        result = self.scope.lvalue_of_name(self, ast.Name(self.pou.name)).read() \
            if self.pou.return_type is not None else "None"
        outputs = [s for s in self.pou.variables.values() if s.kind == "VAR_OUTPUT"]
        if not outputs:
            return f"return {result}"
        values = [self.scope.lvalue_of_name(self, ast.Name(s.name)).read() for s in outputs]
        return f"return ({result}, {', '.join(values)})"

    # --------------------------------------------------------- statements

    def statements(self, body, lead: float = 0, check: str | None = None, charge: bool = True,
                   first_charged: bool = False, level: bool = True) -> None:
        """Compile `body` block by block, each block charged once at its start.

        `lead`: units charged with the first block (a loop's overhead and
        test, the tests an ELSIF took); `check`: the place of the loop whose
        iteration this is (the first charge then tests for an overrun);
        `charge=False`: the caller has charged the whole body already;
        `first_charged`: the caller has charged the first block; `level=False`
        (fast body only): `body` always runs where it is written (an unrolled
        copy), so its charges join the enclosing body's (fastpath.Segments).
        """
        segments = self._segments if level else None
        if segments is not None:
            segments.enter()
        values = self.reuse if level else None      # (an unrolled copy's values serve the next copy)
        if values is not None:
            values.enter()
        for line in self._late_loads.get(id(body), ()):
            self.out.line(line)
        for line in self._late_stores.loads.get(id(body), ()):
            self.out.line(line)
        stored_back = self._late_stores.stores.get(id(body))
        if stored_back:
            self.out.line("try:")
            self.out.indent()
            mark = self.out.mark()
        first = True
        for simple, compound, units in self._costed_blocks(body):
            if first:
                units += lead
            if charge and not (first and first_charged):
                self._charge(units, check if first else None)
            first = False
            if self._dormant_groups and len(simple) > 1:
                self._grouped(simple)
            else:
                for stmt in simple:
                    self._statement_with_values(stmt)
            if compound is not None:
                self._statement_with_values(compound)
        if stored_back:
            self.out.ensure_body(mark)
            self.out.dedent()
            self.out.line("finally:")
            for line in stored_back:
                self.out.line("    " + line)
        if segments is not None:
            segments.leave()
        if values is not None:
            values.leave()

    def _grouped(self, simple) -> None:
        """The simple statements of a block, their dormant call sites in groups (dormant.Groups)."""
        groups = dormant.Groups(self)
        for stmt in simple:
            start = self.out.mark()
            self._statement_with_values(stmt)
            groups.add(stmt, start)
        groups.close()

    def _costed_blocks(self, body) -> list[tuple[list, object, float]]:
        """`_blocks(body)`, each with the units it charges, once per body (an unrolled
        loop compiles its body once per copy)."""
        return once(self._blocks_memo, body, lambda: [
            (simple, compound, sum(self._simple_cost(st) for st in simple)
             + (self._head_cost(compound) if compound else 0)) for simple, compound in _blocks(body)])

    def _statement_with_values(self, stmt) -> None:
        """The statement, the values it computes first set before it (optimise/reuse.py);
        with `temps`, the next statement takes the temps' numbers again."""
        taken = self.temp_count
        if self.reuse is None:
            self._statement_in_segment(stmt)
        else:
            began = self.reuse.begin(stmt)
            mark = self.out.mark()
            self._statement_in_segment(stmt)
            self.reuse.end(began, mark)
        if self.opt.temps and self.region is None:
            self.temp_count = max(taken, self.temp_floor)

    def _statement_in_segment(self, stmt) -> None:
        self.statement(stmt)
        if self._segments is not None and fastpath.may_leave(self, stmt):
            self._segments.close()      # what follows may not run: its charges wait for it

    def _simple_cost(self, st) -> float:
        """cost.simple, memoised: an unrolled loop compiles its body once per iteration."""
        known = self._head_costs.get(id(st))
        if known is None:
            known = self._head_costs[id(st)] = self.cost.simple(st)
        return known

    def _head_cost(self, s) -> float:
        """What a compound statement charges with the block before it: what it
        evaluates on entry, and what every one of its branches charges first."""
        known = self._head_costs.get(id(s))
        if known is not None:       # memo: nested IFs would otherwise be walked once per ancestor
            return known
        units = 0
        if isinstance(s, ast.If):
            units = self.cost.condition(s.branches[0].condition) + self._if_entries(s)[1]
        elif isinstance(s, ast.Case):
            units = self.cost.expr(s.selector) + self._case_entries(s)[1]
        elif isinstance(s, ast.For):
            units = self.cost.for_setup(s)
        self._head_costs[id(s)] = units
        return units

    def _first_block(self, body) -> float:
        simple, compound = _blocks(body)[0]
        return sum(self._simple_cost(st) for st in simple) + (self._head_cost(compound) if compound else 0)

    def _shared(self, tests: list, bodies: list, exhaustive: bool) -> tuple[list, float]:
        """(lead of each branch, units every branch charges first).

        Branch i is reached after `tests[i]` units of tests; when some branch
        always runs (an ELSE), what they all charge first moves before the
        statement (one charge instead of one per branch; the sum per path is
        unchanged)."""
        shared = min(t + self._first_block(b) for t, b in zip(tests, bodies)) if exhaustive else 0
        return [t - shared for t in tests], shared

    def _if_entries(self, s) -> tuple[list, float]:
        """Leads of the IF's branches (then ELSE) and the shared first charge (read only;
        once per IF: an unrolled loop compiles its body once per copy)."""
        return once(self._entries_memo, s, lambda: self._if_entries_of(s))

    def _if_entries_of(self, s) -> tuple[list, float]:
        tests = [0.0]
        for branch in s.branches[1:]:       # the first test is charged before the IF
            tests.append(tests[-1] + self.cost.condition(branch.condition))
        bodies = [b.body for b in s.branches]
        if s.else_body:
            tests.append(tests[-1])
            bodies.append(s.else_body)
        return self._shared(tests, bodies, bool(s.else_body))

    def _case_entries(self, s) -> tuple[list, float]:
        """Leads of the CASE's clauses (then ELSE): the labels compared to reach each."""
        tests, bodies, labels = [], [], 0
        for clause in s.clauses:
            labels += self.cost.case_labels(clause)
            tests.append(labels * self.cost.w["branch"])
            bodies.append(clause.body)
        if s.else_body:
            tests.append(labels * self.cost.w["branch"])
            bodies.append(s.else_body)
        return self._shared(tests, bodies, bool(s.else_body))

    def _charge(self, units: float, check: str | None = None, times: str | None = None) -> None:
        """Charge `units` (times `times`, Python source) to the scan's time; test if `check`."""
        if not self.unit.charge_costs:
            return
        ps = picoseconds(units)
        if self._segments is not None and times is None:    # the fast body: merged charges, no checks
            line = self._segments.charge(ps) if ps else None
            if line:
                self.out.line(line)
            return
        if ps:
            self.out.line(f"_spent += {ps if times is None else f'{times} * {ps}'}")
        if check and self._segments is None:
            self.out.line(f"if _ctx.budget < _spent: _overrun({check})")

    def statement(self, stmt) -> None:
        if isinstance(stmt, ast.Empty):
            return
        method = getattr(self, "s_" + type(stmt).__name__, None)
        if method is None:
            raise CompileError(f"statement {type(stmt).__name__} is not supported by the runtime", stmt.pos)
        if isinstance(stmt, (ast.Assign, ast.CallStmt)):
            self.guard(stmt, lambda: method(stmt))
            if self.flow is not None and isinstance(stmt, ast.Assign):
                self.flow.assigned(stmt)
        elif isinstance(stmt, ast.If) and self.opt.fold and self._folded_if(stmt):
            return
        elif self.region is not None:       # code that may be skipped defines no shared values
            outer = self.region.straight
            self.region.straight, self.region.enclosing_straight = False, outer
            try:
                method(stmt)
            finally:
                self.region.straight = outer
        else:
            # Compound statements guard their own conditions and bounds, so
            # Python blocks nest only as deep as the ST loops do.
            method(stmt)

    def _folded_if(self, s) -> bool:
        """An IF whose conditions are constants: only the branch taken, with its lead (fold.py)."""
        conditions = [fold.constant_condition(self, b.condition) for b in s.branches]
        taken = None
        for i, value in enumerate(conditions):
            if value is None:
                return False
            if value:
                taken = i
                break
        leads, _ = self._if_entries(s)
        if taken is None and s.else_body:
            taken = len(s.branches)
        if taken is not None:
            body = s.branches[taken].body if taken < len(s.branches) else s.else_body
            self.statements(body or (), leads[taken])
        elif self._charges_no_branch(leads):
            self.statements((), leads[-1])
        return True

    def _charges_no_branch(self, leads: list) -> bool:
        """Whether the path through no branch (no ELSE, no test TRUE) has tests of its own to
        charge: every test after the first, which the last branch's lead holds (`_shared`
        moves nothing without an ELSE). docs/nj501.md: a path pays for what ran."""
        return bool(leads) and self.unit.charge_costs and picoseconds(leads[-1]) > 0

    def _no_branch(self, ends: list | None, leads: list, opener: str) -> None:
        """The no-ELSE path's charge, as a branch of its own (`opener` its Python test)."""
        if self._charges_no_branch(leads):
            self.out.line(opener)
            self._branch(ends, (), leads[-1])

    def guard(self, node, emit, on_fault=lambda: ()) -> None:
        """Emit `emit()` inside `try`; a fault is recorded, then `on_fault()` lines run."""
        o = self.out
        if not self.unit.guard_statements:
            emit()
            return
        if self.opt.unguard and isinstance(node, ast.Assign):
            mark = o.mark()
            emit()
            if unguard.cannot_fault(o.lines[mark:], self, node):
                return
            o.lines[mark:] = ["    " + line for line in o.lines[mark:]]
            o.insert(mark, ["try:"])
            if len(o.lines) == mark + 1:
                o.line("    pass")
        else:
            o.line("try:")
            o.indent()
            mark = o.mark()
            emit()
            o.ensure_body(mark)
            o.dedent()
        o.line("except _FAULTS as _e:")
        o.indent()
        if self._segments is not None:      # stop_on_fault ends the scan with `_spent` as charged so far
            ahead = self._segments.ahead()
            o.line(f"_spent -= {ahead}")
            o.line(f"_ctx.fault(_e, {self.where(node)})")
            o.line(f"_spent += {ahead}")
        else:
            o.line(f"_ctx.fault(_e, {self.where(node)})")
        for line in on_fault():
            o.line(line)
        o.dedent()

    def guarded_value(self, node, code: str, on_fault: str) -> tuple[str, bool]:
        """(name holding `code` evaluated under a guard, whether a guard was needed).

        After a fault the name holds `on_fault`.  Names and literals cannot
        fault and are used as they are.
        """
        if _cannot_fault(code):
            return code, False
        tmp = self.temp()
        self.guard(node, lambda: self.out.line(f"{tmp} = {code}"), lambda: [f"{tmp} = {on_fault}"])
        return tmp, True

    def block(self, body, lead: float = 0) -> None:
        self.out.indent()
        mark = self.out.mark()
        self.statements(body or (), lead)
        self.out.ensure_body(mark)
        self.out.dedent()

    def s_Assign(self, s):
        target = self.lvalue(s.target)
        if s.mode != ":=":
            self.out.line(f"if {self.expr(s.value)}: {target.store(repr(s.mode == 'S='))}")
            return
        t = resolve_alias(target.type)
        if is_aggregate(t):
            self.out.line(copy_statement(target.read(), self.aggregate(s.value), t))
            return
        if self.region is not None:
            self.region.whole = s.value
        value = self.convert(self.expr(s.value), self.ty(s.value), t, s.value)
        self.out.line(target.store(shortcut.stored(self, s.value, value, kept=True)))
        if self.reuse is not None:
            self.reuse.stored(s.target, target.read(), value)

    def s_CallStmt(self, s):
        for line in self.unit.calls.call_statement(self, s.call):
            self.out.line(line)

    def s_If(self, s):
        """A fault in a condition abandons the whole IF (no branch runs)."""
        o = self.out
        leads, _ = self._if_entries(s)
        ends = self._branches_begin()
        if len(s.branches) == 1:
            code = self.expr(s.branches[0].condition)
            test, guarded = (shortcut.condition(self, s.branches[0].condition, code), False) \
                if self._tested_in_place(s.branches[0].condition, code) else self.guarded_value(s, code, "None")
            o.line(f"if {test}:")
            self._branch(ends, s.branches[0].body, leads[0])
            if s.else_body:
                o.line(f"elif {test} is not None:" if guarded else "else:")
                self._branch(ends, s.else_body, leads[1])
            self._branches_end(ends)
            return
        # IF/ELSIF chain: the index of the branch taken, conditions evaluated in order,
        # as flat if/elif lines (a nested conditional expression would add one level
        # of parentheses per ELSIF to CPython's 200).
        n = len(s.branches)
        conditions = [self.expr(branch.condition) for branch in s.branches]
        if all(self._tested_in_place(b.condition, c) for b, c in zip(s.branches, conditions)):
            tests = [shortcut.condition(self, b.condition, c) for b, c in zip(s.branches, conditions)]
            if self.opt.elements and self.region is None:
                tests = elements.shared(tests, self.temp)
            for i, (branch, test) in enumerate(zip(s.branches, tests)):     # branches.py
                o.line(f"{'if' if i == 0 else 'elif'} {test}:")
                self._branch(ends, branch.body, leads[i])
            if s.else_body:
                o.line("else:")
                self._branch(ends, s.else_body, leads[n])
            else:
                self._no_branch(ends, leads, "else:")
            self._branches_end(ends)
            return
        which = self.temp()

        def choose():
            for i, condition in enumerate(conditions):
                o.line(f"{'if' if i == 0 else 'elif'} {condition}:")
                o.indent()
                o.line(f"{which} = {i}")
                o.dedent()
            o.line("else:")
            o.indent()
            o.line(f"{which} = {n}")
            o.dedent()

        self.guard(s, choose, lambda: [f"{which} = -1"])
        # The first test is charged before the IF; the later ones by the branch that took them.
        for i, branch in enumerate(s.branches):
            o.line(f"{'if' if i == 0 else 'elif'} {which} == {i}:")
            self._branch(ends, branch.body, leads[i])
        if s.else_body:
            o.line(f"elif {which} == {n}:")
            self._branch(ends, s.else_body, leads[n])
        else:
            self._no_branch(ends, leads, f"elif {which} == {n}:")
        self._branches_end(ends)

    def _tested_in_place(self, node, code: str) -> bool:
        """The condition or selector needs no guard (optimise/branches.py)."""
        return (self.opt.branches and self.unit.guard_statements
                and branches.expr_cannot_fault(self, node, code))

    def _branches_begin(self) -> list | None:
        """For ranges.py: the state before the branches of an IF or CASE, then each end."""
        return [self.flow.state()] if self.flow is not None else None

    def _branch(self, ends: list | None, body, lead: float) -> None:
        if ends is not None:
            self.flow.set(ends[0])          # each branch starts from the state before
        self.block(body, lead)
        if ends is not None:
            ends.append(self.flow.state())

    def _branches_end(self, ends: list | None) -> None:
        """After the branches: their union with the state before (a fault in a condition
        or a selector, or no branch taken, leaves the variables as they were)."""
        if ends is not None:
            self.flow.join(ends)

    def s_Case(self, s):
        """A fault in the selector abandons the whole CASE."""
        selector = self.temp()
        code = self.settled_expr(s.selector)
        if self._tested_in_place(s.selector, code):
            self.out.line(f"{selector} = {code}")
            self.out.line("if True:")       # (keeps the clauses' indentation)
        else:
            self.guard(s, lambda: self.out.line(f"{selector} = {code}"), lambda: [f"{selector} = None"])
            self.out.line(f"if {selector} is not None:")
        self.out.indent()
        t = self.ty(s.selector)
        ends = self._branches_begin()
        leads, _ = self._case_entries(s)     # labels compared to reach a clause, charged by that clause
        tests = [self._clause_test(clause, selector, t) for clause in s.clauses]
        dispatch: halves.Split | list[int] = list(range(len(s.clauses)))
        if self.opt.halves and not s.else_body and halves.selector_is_integer(t):
            extent = halves.spans([halves.label_spans(self, clause) for clause in s.clauses])
            if extent is not None:
                dispatch = halves.tree(extent)
        self._dispatch(dispatch, selector, tests, s.clauses, ends, leads, not s.else_body)
        if s.else_body:
            if not s.clauses:
                self.out.line("if True:")
            else:
                self.out.line("else:")
            self._branch(ends, s.else_body, leads[-1])
        self._branches_end(ends)
        self.out.dedent()

    def _clause_test(self, clause, selector: str, t) -> str:
        """The Python test of a CASE clause's labels."""
        singles: list[str] = []
        tests: list[str] = []
        for label in clause.labels:
            if isinstance(label, ast.CaseRange):
                lo = self.literal(self._label(label.lo), t)
                hi = self.literal(self._label(label.hi), t)
                tests.append(f"{lo} <= {selector} <= {hi}")
            else:
                singles.append(self.literal(self._label(label), t))
        if len(singles) == 1:
            tests.insert(0, f"{selector} == {singles[0]}")
        elif singles:
            tests.insert(0, f"{selector} in ({', '.join(singles)},)")
        return ' or '.join(tests) or 'False'

    def _dispatch(self, node, selector: str, tests: list[str], clauses, ends, leads,
                  no_else: bool) -> None:
        """The clauses of `node` (optimise/halves.py): in a row, or `selector < pivot` first.
        Without an ELSE, a selector no clause matches has compared every label (each leaf)."""
        if isinstance(node, halves.Split):
            head = self.out.mark()
            self.out.line(f"if {selector} < {node.pivot}:")
            for index, side in enumerate((node.below, node.above)):
                if index:
                    halves.jump_far(self.out.lines, head, self.opt.halves)
                    self.out.line("else:")
                self.out.indent()
                self._dispatch(side, selector, tests, clauses, ends, leads, no_else)
                self.out.dedent()
            return
        for position, index in enumerate(node):
            head = self.out.mark()
            self.out.line(f"{'elif' if position else 'if'} {tests[index]}:")
            self._branch(ends, clauses[index].body, leads[index])
            halves.jump_far(self.out.lines, head, self.opt.halves)
        if no_else and node:
            self._no_branch(ends, leads, "else:")

    def _label(self, label):
        value = self.constant_of(label)
        if value is None and isinstance(label, ast.Name):
            ref = self.program.name_refs.get(id(label))
            if isinstance(ref, int):
                return ref
        if value is None and isinstance(label, ast.EnumLiteral):
            return self.unit.initial.enum_value(label.type_name, label.value_name, label.pos)
        if value is None:
            value = self.unit.initial.const(label)
        return value

    def s_For(self, s):
        o = self.out
        var = ast.Name(s.variable, pos=s.pos)
        place = self.scope.place_of(var)
        target = self.scope.lvalue_of_name(self, var)
        var_t = place.symbol.type
        step_value = 1 if s.step is None else self.constant_of(s.step)
        where = self.where(s)
        const_step = _is_int(step_value)
        if const_step and step_value == 0:
            o.line(f"_overrun({where})")     # BY 0 never ends: the period is exceeded
            return
        key = s.variable.upper()
        assigned = assigned_in(self, s.body)
        if fastpath.tests_its_variable(self, s, place):
            self._for_as_while(s, target, var_t, step_value if const_step else None, assigned)
            return
        before = self.flow.state() if self.flow is not None else None
        setup: list = []
        const_range = _is_int(self.constant_of(s.start)) and _is_int(self.constant_of(s.end)) and const_step
        if const_range:
            setup.append(self._for_range(s, step_value, where))
        else:       # a fault while evaluating the bounds abandons the whole FOR
            self.guard(s, lambda: setup.append(self._for_range(s, step_value if const_step else None, where)),
                       lambda: [f"{setup[0][0]} = None"])
        rng, count, final = setup[0]
        if not const_range:
            o.line(f"if {rng} is not None:")
            o.indent()
        early = _leaves_early(s.body)
        # A loop that runs its whole count is bounded: its overhead and its
        # body's first block (which every iteration runs) are charged and
        # tested up front for all iterations, its other blocks per iteration
        # without a test, and the total is tested when it ends.  One that may
        # leave early charges and tests per iteration.
        blocks = self._costed_blocks(s.body)
        straight = len(blocks) == 1 and blocks[0][1] is None
        if not early and count != 0:
            units = self.cost.loop() + self._first_block(s.body)
            if count is None:
                self._charge(units, where, f"len({rng})")
            else:
                self._charge(units * count, where)
        saved = self.known_ranges.get(key)
        lo_r, hi_r = self.static_range(s.start), self.static_range(s.end)
        if lo_r and hi_r and const_step:
            self.known_ranges[key] = (lo_r[0], hi_r[1]) if step_value > 0 else (hi_r[0], lo_r[1])
        else:
            self.known_ranges.pop(key, None)
        fallback = False
        returns = early and not _has_own_exit(s.body)       # leaves only by RETURN
        if (const_range and (returns or not early) and self.opt.unroll
                and unroll.can_unroll(self, s.body, place, count, assigned, key)):
            if early and _outlives_call(self.pou, place.symbol):    # RETURN stores it (s_Return)
                self.unrolled_stores[key] = (target, var_t)
            fallback = unroll.emit(self, s, key, range(self.constant_of(s.start), self.constant_of(s.end)
                                                        + (1 if step_value > 0 else -1), step_value),
                                   lambda: self._after_for(target, var_t, final, lo_r, hi_r, step_value,
                                                           not early and not straight, where),
                                   returns=early, where=where)
            self.unrolled_stores.pop(key, None)
            if not fallback:
                if saved is None:
                    self.known_ranges.pop(key, None)
                else:
                    self.known_ranges[key] = saved
                return
        unrolled = self.flow.state() if fallback and self.flow is not None else None
        if self.flow is not None:       # (each copy of the loop forgets its body: _range_loop)
            self.flow.set(before)

        def emit_loop(end_high=None):
            self._range_loop(s, key, assigned, target, rng, early, where, saved,
                             lambda: self._after_for(target, var_t, final, lo_r, hi_r,
                                                     step_value if const_step else None,
                                                     not early and not straight, where, end_high))

        if self.opt.ranges and step_value == 1 and count is None and lo_r is not None:
            self._versioned(key, rng, lo_r[0], emit_loop)
        else:
            emit_loop()
        if not const_range:
            o.dedent()
        if fallback:        # the loop as before, when the unrolled copy's reads fault
            o.dedent()
        if self.flow is not None:
            self.flow.forget(s.body)
            if unrolled is not None:
                self.flow.join([unrolled, self.flow.state()])

    def _versioned(self, key: str, rng: str, low: int, emit_loop) -> None:
        """A FOR with step 1 whose end is known only at run time, emitted: when the body
        checks array bounds on its variable, in two versions, one without those checks
        run when the range lies inside every such array (optimise/ranges.py)."""
        o = self.out
        mark = o.mark()
        start = self.flow.state() if self.flow is not None else None
        known = self.known_ranges.get(key)          # the variable's static range, if any
        self._index_probe[key] = []
        try:
            emit_loop()                                 # the loop as before, checks recorded
            dims = self._index_probe[key]
        finally:
            del self._index_probe[key]
        if not dims or low < max(lo for lo, _ in dims):
            return
        high = min(hi for _, hi in dims)
        if known is not None:
            low, high = max(low, known[0]), min(high, known[1])
        checked = o.lines[mark:]
        del o.lines[mark:]
        after_checked = self.flow.state() if self.flow is not None else None
        if self.flow is not None:
            self.flow.set(start)
        o.line(f"if {rng}.stop <= {high + 1}:")       # every value of the variable in [low, high]
        o.indent()
        saved = self.known_ranges.get(key)
        self.known_ranges[key] = (low, high)
        emit_loop(high)
        if saved is None:
            self.known_ranges.pop(key, None)
        else:
            self.known_ranges[key] = saved
        o.dedent()
        o.line("else:")
        o.lines.extend("    " + line for line in checked)
        if self.flow is not None:
            self.flow.join([after_checked, self.flow.state()])

    def _range_loop(self, s, key, assigned, target, rng, early, where, saved, after) -> None:
        """`for v in rng:` with the body, then `else:` with what a normal end leaves."""
        o = self.out
        if self.flow is not None:       # the loop runs its body any number of times
            self.flow.forget(s.body)
        self.loops.append(_Loop(key, assigned, "FOR"))
        mark = o.mark()
        if target.kind == "ref":
            loop_var = self.temp()
            o.line(f"for {loop_var} in {rng}:")
            o.indent()
            o.line(target.store(loop_var))
            o.dedent()
        else:
            o.line(f"for {target.target} in {rng}:")
        o.indent()
        body_mark = o.mark()
        worst = self._worst_case(s.body) if early else None
        if worst is not None:       # each iteration: the fast path when the time left covers it
            self._fast_or_exact(f"_ctx.budget - _spent >= {picoseconds(worst + self.cost.loop())}",
                                lambda: self.statements(s.body, self.cost.loop()),
                                lambda: self.statements(s.body, self.cost.loop(), where), s.body)
        elif early:
            self.statements(s.body, self.cost.loop(), where)
        else:
            self.statements(s.body, first_charged=True)
        o.ensure_body(body_mark)
        o.dedent()
        self._place_loop_code(self.loops.pop(), mark, body_mark)
        if saved is None:
            self.known_ranges.pop(key, None)
        else:
            self.known_ranges[key] = saved
        # After a normal end the variable holds the first value that failed
        # the test (IEC: FOR is a WHILE loop that increments by BY).
        o.line("else:")
        o.indent()
        after()
        o.dedent()

    def _after_for(self, target, var_t, final, lo_r, hi_r, step_value, test: bool, where,
                   end_high: int | None = None) -> None:
        bounds = int_bounds(var_t)
        ends = None
        if lo_r and hi_r and step_value is not None:
            ends = (lo_r[0], lo_r[1], hi_r[0] + step_value, hi_r[1] + step_value)
        elif lo_r and end_high is not None:
            # A loop version run when the end is at most `end_high` (step 1): the final value
            # is the start when the loop does not run, else the end + 1, above the start.
            ends = (lo_r[0], lo_r[1], end_high + 1)
        if ends and bounds and bounds[0] <= min(ends) and max(ends) <= bounds[1]:
            var_t = None              # the final value cannot leave the type: no wrap
        self.out.line(target.store(final if var_t is None else self.convert(final, None, var_t)))
        if test:
            self._charge(0, where)          # what the body's blocks charged, tested once

    def _for_range(self, s, step: int | None, where: str) -> tuple[str, int | None, str]:
        """Emit the loop's range; (range source, iteration count if known, final value source).

        The bounds are evaluated once, before the loop (into temps).
        """
        o = self.out
        start_c, end_c = self.constant_of(s.start), self.constant_of(s.end)
        if step is not None and _is_int(start_c) and _is_int(end_c):
            r = range(start_c, end_c + (1 if step > 0 else -1), step)
            return self.unit.register_constant(r), len(r), pyliteral(start_c + len(r) * step)
        rng = self.temp()
        if step is None:
            step_code = self.temp()
            o.line(f"{step_code} = {self.expr(s.step)}")
            o.line(f"{rng} = _for_range({self.expr(s.start)}, {self.expr(s.end)}, {step_code}, {where})")
            return rng, None, f"{rng}.start + len({rng}) * {step_code}"
        start, end = self.expr(s.start), self.expr(s.end)
        if not _is_int(start_c):
            tmp = self.temp()
            o.line(f"{tmp} = {start}")
            start = tmp
        if not _is_int(end_c):
            tmp = self.temp()
            o.line(f"{tmp} = {end}")
            end = tmp
        if _is_int(end_c):
            edge = pyliteral(end_c + (1 if step > 0 else -1))
        else:
            edge = f"{end} + 1" if step > 0 else f"{end} - 1"
        if step == 1 and start_c in (0, 1) and _is_int(start_c):
            # (`end` a temp: read twice, made once)
            o.line(f"{rng} = (_FROM_{start_c}[{end}] if 0 <= {end} < {SMALL_END} else range({start}, {edge}))")
        else:
            o.line(f"{rng} = range({start}, {edge})" if step == 1 else f"{rng} = range({start}, {edge}, {step})")
        if step == 1:
            return rng, None, f"({edge} if {start} <= {end} else {start})"
        if step == -1:
            return rng, None, f"({edge} if {start} >= {end} else {start})"
        return rng, None, f"{start} + len({rng}) * {step}"

    def _place_loop_code(self, loop: "_Loop", mark: int, body_mark: int) -> None:
        """Put the per-iteration products at the top of the body and the hoisted
        invariants before the loop (both were collected while compiling the body)."""
        o = self.out
        if loop.scaled:
            per_iteration = []
            for text, (placeholder, uses) in loop.scaled.items():
                value = text
                if uses >= 2:
                    value = placeholder.strip("\x00")
                    per_iteration.append(f"{value} = {text}")
                o.lines[body_mark:] = [line.replace(placeholder, value) for line in o.lines[body_mark:]]
            o.indent()
            o.insert(body_mark, per_iteration)
            o.dedent()
        if loop.hoisted:
            o.insert(mark, [f"{name} = {code}" for code, name in loop.hoisted.items()])

    def _for_as_while(self, s, target, var_t, step, assigned) -> None:
        """FOR whose body changes its variable: a loop that tests it, as on a PLC."""
        o = self.out
        key = s.variable.upper()
        self.known_ranges.pop(key, None)
        self._forget(s.body)
        end_tmp = self.temp()
        step_code = pyliteral(step) if step is not None else self.temp()

        def setup():
            o.line(f"{end_tmp} = {self.expr(s.end)}")
            o.line(target.store(self.convert(self.expr(s.start), self.ty(s.start), var_t, s.start)))
            if step is None:
                o.line(f"{step_code} = {self.expr(s.step)}")

        self.guard(s, setup, lambda: [f"{end_tmp} = None"])
        if step is None:
            test = f"({target.read()} <= {end_tmp} if {step_code} > 0 else {target.read()} >= {end_tmp})"
        else:
            test = f"{target.read()} {'<=' if step > 0 else '>='} {end_tmp}"
        store = target.store(self.convert(f"{target.read()} + {step_code}", None, var_t))

        def increment():        # also what CONTINUE runs first (_Loop)
            if isinstance(resolve_alias(var_t), SubrangeType):
                # a store past the subrange is F-SUBRANGE in the FOR, which it ends (the
                # variable keeps its last value in range)
                self.guard(s, lambda: o.line(store), lambda: ["break"])
            else:
                o.line(store)
        o.line(f"if {end_tmp} is not None:")
        o.indent()
        o.line(f"while {test}:")
        o.indent()
        self.loops.append(_Loop(key, assigned, "WHILE", increment))
        self.statements(s.body, self.cost.loop() + self.cost.w["compare"], self.where(s))
        self._forget(s.body)
        self.loops.pop()
        increment()
        o.dedent()
        o.dedent()

    def s_While(self, s):
        """A fault in the condition ends the loop."""
        o = self.out
        self._forget(s.body)        # (before the condition: it is tested after each iteration too)
        cond = self.expr(s.condition)
        if _cannot_fault(cond):
            o.line(f"while {cond}:")
            o.indent()
        else:
            o.line("while True:")
            o.indent()
            self.guard(s, lambda: o.line(f"if not ({cond}): break"), lambda: ["break"])
        self.loops.append(_Loop("", set(), "WHILE"))
        self.statements(s.body, self.cost.loop() + self.cost.condition(s.condition), self.where(s))
        self._forget(s.body)
        self.loops.pop()
        o.dedent()

    def s_Repeat(self, s):
        """The condition is tested after the body (CONTINUE goes to the test)."""
        o = self.out
        self._forget(s.body)
        first = self.temp()
        cond = self.expr(s.condition)
        o.line(f"{first} = True")
        o.line("while True:")
        o.indent()
        o.line(f"if not {first}:")
        o.indent()
        self.guard(s, lambda: o.line(f"if {cond}: break"), lambda: ["break"])
        o.dedent()
        o.line(f"{first} = False")
        self.loops.append(_Loop("", set(), "WHILE"))
        self.statements(s.body, self.cost.loop() + self.cost.condition(s.condition), self.where(s))
        self._forget(s.body)
        self.loops.pop()
        o.dedent()

    def _forget(self, body) -> None:
        """A loop's body runs any number of times: what it assigns is unknown (ranges.py)."""
        if self.flow is not None:
            self.flow.forget(body)

    def s_Exit(self, s):
        self.out.line("break")

    def s_Continue(self, s):
        if self.loops:
            self.loops[-1].on_continue()
        self.out.line("continue")

    def s_Return(self, s):
        # In an unrolled copy the FOR variable is a constant, stored only after the last copy;
        # RETURN leaves the loop at this iteration, so the variable takes its value here.
        for key, (target, var_t) in self.unrolled_stores.items():
            if key in self.unrolled:
                self.out.line(target.store(self.literal(self.unrolled[key], var_t)))
        if self.method:
            self.out.line("return")
        else:
            self.out.line(self._return_statement())


class _Loop:
    """A loop being compiled: what its body leaves unchanged, what was hoisted."""

    def __init__(self, variable: str, assigned: set[str], kind: str, on_continue=lambda: None):
        self.variable = variable
        self.assigned = assigned
        self.hoistable = kind == "FOR"           # a range-based FOR: code may move before it
        self.on_continue = on_continue          # emits what CONTINUE runs first (an increment)
        self.hoisted: dict[str, str] = {}     # Python expression -> temp computed before the loop
        self.scaled: dict[str, list] = {}     # `i * k` -> [placeholder, uses]: once per iteration


_COMPOUND = (ast.If, ast.Case, ast.For, ast.While, ast.Repeat)


def _outlives_call(pou, symbol) -> bool:
    """Whether a variable's value is seen after its POU returns: an output, or a variable
    of a PROGRAM's or FB's instance (not a FUNCTION's or METHOD's locals, nor VAR_TEMP)."""
    if symbol.kind == "VAR_OUTPUT":
        return True
    return pou.kind in ("PROGRAM", "FUNCTION_BLOCK") and symbol.kind != "VAR_TEMP"


def _blocks(body) -> list[tuple[list, object]]:
    """`body` as basic blocks: (simple statements, the compound statement that ends them or None).

    An empty body is one empty block (a loop still charges its iterations).
    """
    blocks: list[tuple[list, object]] = []
    simple: list = []
    for stmt in body or ():
        if isinstance(stmt, ast.Empty):
            continue
        if isinstance(stmt, _COMPOUND):
            blocks.append((simple, stmt))
            simple = []
        else:
            simple.append(stmt)
    if simple or not blocks:
        blocks.append((simple, None))
    return blocks


def _cannot_fault(code: str) -> bool:
    """Python source that only reads a local or is a literal."""
    return code.isidentifier() or code in ("True", "False") or code.lstrip("-").replace(".", "", 1).isdigit()


def _is_int(value) -> bool:
    return isinstance(value, int) and not isinstance(value, bool)


def _leaves_early(body) -> bool:
    """Whether a loop body may leave its loop before the count runs out."""
    for node in walk(body):
        if isinstance(node, ast.Return):
            return True
    return _has_own_exit(body)


def _has_own_exit(body) -> bool:
    for stmt in body:
        if isinstance(stmt, ast.Exit):
            return True
        if isinstance(stmt, ast.If):
            if any(_has_own_exit(b.body) for b in stmt.branches) or _has_own_exit(stmt.else_body or ()):
                return True
        elif isinstance(stmt, ast.Case):
            if any(_has_own_exit(c.body) for c in stmt.clauses) or _has_own_exit(stmt.else_body or ()):
                return True
    return False
