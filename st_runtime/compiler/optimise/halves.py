"""`halves`: a CASE of many clauses reaches its clause by halves of the labels' values.

A CASE is compiled as `if sel == a: ... elif sel in (b, c): ...`, its clauses tested in
the order written: the ninth clause takes nine tests.  With no ELSE and integer labels, a
test `sel < P` first picks the clauses whose labels all lie below P or the clauses whose
labels all lie at or above it (no clause has labels on both sides), and so on while a
group has more than `LEAF` clauses; each group tests its clauses in the order written.
The same clause runs for every value of the selector: a value below P can only match a
clause of the lower group, and the first of them in the order written that matches is the
first of all clauses that matches (so also where the labels of two clauses overlap).  Nothing else
changes: the clause charges what its labels' comparisons cost on the NJ (the leads of
cost.py, written in each clause), and the selector is read once, before the tests.
(SP_Controller's CASE of 14 states: its wave state, the ninth clause, 9 tests -> 4.)

A test of the selector whose branch is long (`jump_far`) is `True if <test> else False`:
CPython 3.11 specialises a comparison only when its jump follows it at once, and a jump past
more than 255 code units takes an EXTENDED_ARG first, so the comparison of two ints ran the
generic rich comparison; the conditional expression's own jump is short, and the same bool
decides the same branch.  (The wave state's four tests, each some 90 machine instructions.)
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from ... import ast
from ...types import ElementaryType, EnumType

MIN_CLAUSES = 6     # fewer clauses are tested in a row
LEAF = 3            # a group of this many clauses or fewer is tested in a row
FAR = 24            # lines of a branch past which its test's jump takes an EXTENDED_ARG (about)
_SINGLE_TEST = re.compile(r"( *+(?:el)?if )(_t\d+ (?:==|<) -?\d+):")


@dataclass(frozen=True)
class Split:
    """`sel < pivot`: the `below` tree, else the `above` tree (a tree: a Split or a list of
    clause indices, tested in a row)."""
    pivot: int
    below: "Split | list[int]"
    above: "Split | list[int]"


def selector_is_integer(t) -> bool:
    """An integer, bit-string or enumeration selector: a Python int at run time."""
    if isinstance(t, EnumType):
        return True
    return isinstance(t, ElementaryType) and t.kind in ("int", "bits")


def spans(labels: list[list[tuple[int, int]]]) -> list[tuple[int, int]] | None:
    """The lowest and highest label value of each clause; None unless every label is an int."""
    out = []
    for clause in labels:
        values = [v for span in clause for v in span]
        if not values or any(type(v) is not int for v in values):
            return None
        out.append((min(values), max(values)))
    return out


def tree(extent: list[tuple[int, int]]) -> "Split | list[int]":
    """The dispatch of clauses with these label extents (source order), by halves."""
    if len(extent) < MIN_CLAUSES:
        return list(range(len(extent)))
    return _split(list(range(len(extent))), extent)


def _split(indices: list[int], extent) -> "Split | list[int]":
    if len(indices) <= LEAF:
        return indices
    best = None
    for pivot in sorted({extent[i][0] for i in indices}):
        below = [i for i in indices if extent[i][1] < pivot]
        above = [i for i in indices if extent[i][0] >= pivot]
        if below and above and len(below) + len(above) == len(indices):
            balance = abs(len(below) - len(above))
            if best is None or balance < best[0]:
                best = (balance, pivot, below, above)
    if best is None:
        return indices
    _, pivot, below, above = best
    return Split(pivot, _split(below, extent), _split(above, extent))


def label_spans(compiler, clause) -> list[tuple[object, object]]:
    """The clause's labels as (low, high) values: a single label is (v, v)."""
    out = []
    for label in clause.labels:
        if isinstance(label, ast.CaseRange):
            out.append((compiler._label(label.lo), compiler._label(label.hi)))
        else:
            value = compiler._label(label)
            out.append((value, value))
    return out


def jump_far(lines: list[str], head: int, switched_on: bool = True) -> None:
    """Line `head`, `if`/`elif <selector> == or < <int>:`, as `True if <test> else False`
    when its branch (the lines after it) is long (module docstring; with the `halves` switch)."""
    if switched_on and len(lines) - head - 1 > FAR:
        match = _SINGLE_TEST.fullmatch(lines[head])
        if match is not None:
            lines[head] = f"{match.group(1)}(True if {match.group(2)} else False):"
