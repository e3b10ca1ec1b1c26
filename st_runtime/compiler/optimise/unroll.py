"""Loop unrolling: a FOR with constant bounds written out iteration by iteration.

Only when the unrolled loop behaves exactly as the loop: the bounds and step
are constants (so is the iteration count), the body cannot leave the loop
alone (no EXIT) nor skip (CONTINUE), the control variable is a Python local of
this body that the body does not assign (so nothing else can see it while
the loop runs), and the statements unrolled in the POU stay within `UNROLL_CAP`.
Each copy of the body sees the variable as a constant (fold.py); after the
last copy the variable gets the value the loop leaves in it.  The charges are
the loop's: the up-front charge and test stay before it, the body's later
blocks charge in each copy, and the final test stays after it.

A body with RETURN (it leaves the whole POU, which a Python `return` in the
unrolled copy does too) charges and tests per iteration as its loop does:
each copy charges the loop overhead with its first block and tests there
(LU elimination: `FOR K := 1 TO SIZE` with a RETURN for a singular pivot,
whose inner loops `FOR Row := K + 1 TO SIZE` get constant bounds in each copy).
A RETURN from a copy first stores that copy's value of the variable (statements.s_Return),
which the loop would hold when it returned.
"""

from __future__ import annotations

from ... import ast
from ..scope import walk
from . import UNROLL_CAP


def can_unroll(compiler, body, place, count: int | None, assigned: set[str], key: str) -> bool:
    """Whether the FOR can be unrolled; takes its size from the POU's budget of
    `UNROLL_CAP` unrolled statements (nested unrolled loops multiply)."""
    if count is None or count < 0 or place.how != "local" or key in assigned:
        return False
    if any(isinstance(node, (ast.Exit, ast.Continue)) for node in walk(body)):
        return False
    need = count * max(_unrolled_size(compiler, body), 1)
    left = getattr(compiler, "unroll_left", UNROLL_CAP)
    if need > left:
        return False
    compiler.unroll_left = left - need
    return True


def _unrolled_size(compiler, body) -> int:
    """Statements `body` becomes when every FOR in it with constant bounds is unrolled."""
    total = 0
    for stmt in body or ():
        if isinstance(stmt, ast.For):
            start, end = compiler.constant_of(stmt.start), compiler.constant_of(stmt.end)
            step = 1 if stmt.step is None else compiler.constant_of(stmt.step)
            inner = _unrolled_size(compiler, stmt.body)
            if all(isinstance(v, int) and not isinstance(v, bool) for v in (start, end, step)) and step:
                total += 1 + len(range(start, end + (1 if step > 0 else -1), step)) * inner
            else:
                total += 1 + inner
        elif isinstance(stmt, ast.If):
            total += 1 + sum(_unrolled_size(compiler, b.body) for b in stmt.branches) \
                + _unrolled_size(compiler, stmt.else_body)
        elif isinstance(stmt, ast.Case):
            total += 1 + sum(_unrolled_size(compiler, c.body) for c in stmt.clauses) \
                + _unrolled_size(compiler, stmt.else_body)
        elif isinstance(stmt, (ast.While, ast.Repeat)):
            total += 1 + _unrolled_size(compiler, stmt.body)
        else:
            total += 1
    return total


def emit(compiler, s, key: str, values: range, after, returns: bool = False, where: str = "") -> bool:
    """Write the unrolled loop; True when the loop as before must follow (in an `else:`
    block the caller fills), because the region's element reads may fault.
    `returns`: the body has a RETURN; each copy charges and tests at `where` as
    an iteration of the loop does."""
    from .cse import Region, close_region, region_allowed, vector_hooks

    o = compiler.out
    outer = compiler.region
    region = None
    if (outer is None and not returns and compiler.opt.cse and compiler.unit.guard_statements
            and region_allowed(compiler, s.body)):
        region = compiler.region = Region(compiler.temp)
        flag = compiler.temp()
        mark = o.mark()
        o.line(f"if {flag}:")
        o.indent()
    if outer is not None:       # the copies run in order whenever the loop runs
        outer.straight = outer.enclosing_straight
    segments = compiler._segments if region is not None else None
    if segments is not None:        # the copies run only if the reads do not fault: charges of their own
        segments.enter()
    try:
        for value in values:
            compiler.unrolled[key] = value
            if returns:
                compiler.statements(s.body, compiler.cost.loop(), where, level=False)
            else:
                compiler.statements(s.body, first_charged=True, level=False)
        compiler.unrolled.pop(key, None)
        after()
    finally:
        compiler.unrolled.pop(key, None)
        if outer is not None:
            outer.straight = False
        if segments is not None:
            segments.leave()
    if region is None:
        return False
    compiler.region = None
    close_region(o, region, mark, flag, compiler.opt.fuse, vector_hooks(compiler, region))  # a fault in its reads: the loop runs as before
    return True
