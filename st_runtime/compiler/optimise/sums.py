"""`sums`: a run of finite tests of array elements in a fast copy folded into one test of their sum.

SP_ForwardKinematics tests every element of the Jacobian and the residual for a NaN or an
infinity, `IF NOT (ABS(JacobianMatrix[Row, Column]) <= SP_LREAL_MAX) THEN AllFinite := FALSE`,
which the fast copy, unrolled, runs as 41 tests between the residual's statements:

    if (not (-1.7976931348623157e+308 <= v_JACOBIANMATRIX[0] <= 1.7976931348623157e+308)):
        _spent += 1196
        v_ALLFINITE = False

(`absolute.py`: `ABS(x) <= B` as a chained comparison).  Such tests of one block whose bodies
are the same are moved to the place of the last one and run only when the sum of the tested
elements is not finite:

    if not (-1.7976931348623157e+308 <= (_sum(v_JACOBIANMATRIX, _sum(v_RESIDUAL, 0.0))) <= 1.7976931348623157e+308):
        <the tests as they were, in their order>

Exact because

* a sum of floats that holds a NaN or an infinity is not finite, in any order of its
  additions (an infinity absorbs every finite addend, opposite infinities give a NaN, a NaN
  absorbs everything): a finite sum means every test would fail to fire.  A sum that
  overflows while every element is finite runs the tests, which fire for none.  The elements
  are REAL or LREAL (Python floats); `_sum` is Python's `sum`, used for a list every element
  of which is tested (a list's length is its array's): a C loop, about a third of the
  tests' machine instructions;
* a test reads one element at a literal index of a plain local list and stores nothing; its
  body only adds to `_spent` and stores literals into variables (the same body in every test
  of the run, so the bodies commute: the same total charge, the same values stored);
* a test moves down only past lines that cannot raise and see nothing it does: a store of
  `+ - *` of names, literals and elements at literal indices (no call, attribute or
  division, so no fault, no charge, no budget check between) into a plain local or an
  element at a literal index, which neither names a variable a body stores nor `_spent`,
  nor rebinds a tested list, nor stores into a tested element: an element of the same list
  at another literal index, or of another list that cannot be the same object (both the
  POU's own VAR or VAR_TEMP arrays, each its own list).  Anything else (a call, an IF, a
  loop, a `try`, a budget check, another store) ends the run where it stands.

So when every element is finite nothing of the tests runs, and otherwise the same tests run
on the same values with the same charges; the run's last test is where they all read, and
nothing between changed what they read.  A run of fewer than `MIN_TESTS` tests is left as it
is.  Applied to a fast copy (fastpath.py), after `chains` and `scalars`: in the exact code
budget checks stand between the tests.
"""

from __future__ import annotations

import re

from ...types import ArrayType, ElementaryType, resolve_alias
from ..pysrc import indentation, statement_end
from .unguard import _ATTRIBUTE_OR_CALL

#: Tests a run needs to be folded (its sum and test must cost less than the tests it skips).
MIN_TESTS = 4

_BOUND = r"1\.7976931348623157e\+308"
#: The end of a finite test's line: a line without it is no test.
_MARK = " <= 1.7976931348623157e+308)):"
#: A finite test of a list's element at a literal index (absolute.py's chained comparison).
_TEST = re.compile(rf"if \(not \(-{_BOUND} <= ([A-Za-z_]\w*)\[(\d+)\] <= {_BOUND}\)\):")
#: A line of a test's body: a charge, or a literal stored into a plain name.
_CHARGE = re.compile(r"_spent \+= \d+")
_LITERAL_STORE = re.compile(r"([A-Za-z_]\w*) = (?:True|False|-?\d+(?:\.\d+)?(?:e[-+]?\d+)?)")
#: A store between tests: `name = value` or `name[k] = value`, the value made of names,
#: numbers, elements at literal indices, `+ - *` and parentheses.
_STORE = re.compile(r"([A-Za-z_]\w*)(?:\[(\d+)\])? = ([\w\s()+\-*.\[\]]+)")
_DATA_INDEX = re.compile(r"\[(?!\d+\])")
_NAME = re.compile(r"(?<![\w.])[A-Za-z_]\w*")
_OWN_KINDS = ("VAR", "VAR_TEMP")


def arrays(compiler) -> dict[str, tuple[int, bool, bool]]:
    """The body's arrays of elementary elements, by Python name: (elements, whether they are
    REAL or LREAL, whether the array is the POU's own VAR or VAR_TEMP list)."""
    found = {}
    variables = compiler.pou.variables
    for key, place in compiler.scope.places.items():
        if place.how != "alias" or place.symbol is None:
            continue
        t = resolve_alias(place.symbol.type)
        if not isinstance(t, ArrayType) or t.is_open:
            continue
        element = resolve_alias(t.element)
        if not isinstance(element, ElementaryType):
            continue
        symbol = variables.get(key)
        own = symbol is place.symbol and symbol.kind in _OWN_KINDS and \
            getattr(symbol.decl, "location", None) is None
        found[place.name] = (t.size, element.kind == "real", own)
    return found


def fold(lines: list[str], start: int, lists: dict[str, tuple[int, bool, bool]]) -> None:
    """Fold the runs of finite tests in `lines[start:]` (a fast copy), in place."""
    if not any(info[1] for info in lists.values()) or _MARK not in "\n".join(lines[start:]):
        return
    out = lines[:start]
    run: _Run | None = None
    n = start
    while n < len(lines):
        line = lines[n]
        if run is None and _MARK not in line:
            out.append(line)                # (no run open and no test: the common line)
            n += 1
            continue
        indent = indentation(line)
        end = statement_end(lines, n, indent)
        test = _test(lines, n, end, lists) if _MARK in line else None
        if run is not None and not (indent == run.indent and run.admits(test, lines[n:end])):
            run.close(out)
            run = None
        if test is None:
            out.append(line)
            n += 1
            continue
        if run is None:
            run = _Run(indent, test[2], lists)
        run.add(len(out), lines[n:end], test[0], test[1])     # (held, not in out)
        n = end
    if run is not None:
        run.close(out)
    lines[:] = out


class _Run:
    """The tests of one block gathered so far, and where each stood in the output."""

    def __init__(self, indent: int, body: tuple[str, ...], lists):
        self.indent, self.body, self.lists = indent, body, lists
        #: (where it stood in the output without the tests, its lines, its list, its index)
        self.tests: list[tuple[int, list[str], str, int]] = []
        self.indices: dict[str, set[int]] = {}        # list -> the indices tested
        self.stored = {match.group(1) for match in map(_LITERAL_STORE.fullmatch, body) if match}

    def add(self, at: int, lines: list[str], name: str, k: int) -> None:
        self.tests.append((at, lines, name, k))
        self.indices.setdefault(name, set()).add(k)

    def admits(self, test, lines: list[str]) -> bool:
        """Whether the statement `lines` keeps the run open: a test with the run's body,
        or a store the tests may move past (module docstring)."""
        if test is not None:
            return test[2] == self.body
        return len(lines) == 1 and self._passable(lines[0].strip())

    def _passable(self, line: str) -> bool:
        match = quiet_store(line)
        if match is None:
            return False
        target, index = match.group(1), match.group(2)
        if target == "_spent" or target in self.stored or not self._reads_nothing_stored(match.group(3)):
            return False
        if index is None:
            return target not in self.indices
        return all(self._apart(target, int(index), name) for name in self.indices)

    def _reads_nothing_stored(self, value: str) -> bool:
        return all(name != "_spent" and name not in self.stored for name in _NAME.findall(value))

    def _apart(self, target: str, index: int, name: str) -> bool:
        """Whether a store into `target[index]` leaves the tested elements of list `name` as
        they are."""
        if target == name:
            return index not in self.indices[name]
        mine, theirs = self.lists.get(target), self.lists.get(name)
        return mine is not None and theirs is not None and mine[2] and theirs[2]

    def close(self, out: list[str]) -> None:
        """Put the run's tests, under the test of their sum, where the last one stood."""
        if len(self.tests) < MIN_TESTS:
            for at, lines, _, _ in reversed(self.tests):
                out[at:at] = lines
            return
        last = self.tests[-1][0]
        pad = " " * self.indent
        folded = [f"{pad}if not (-1.7976931348623157e+308 <= ({self._sum()}) <= 1.7976931348623157e+308):"]
        for _, lines, _, _ in self.tests:
            folded.extend("    " + line for line in lines)
        out[last:last] = folded

    def _sum(self) -> str:
        """The sum of the tested elements: the elements of a list not tested whole added as
        they are, then each list tested whole added by `_sum` (one C loop), from a float
        start (so `sum` takes its float path from the first element)."""
        by_list: dict[str, list[int]] = {}
        for _, _, name, k in self.tests:
            if k not in by_list.setdefault(name, []):
                by_list[name].append(k)
        whole = [name for name, ks in by_list.items() if len(ks) == self.lists[name][0] and len(ks) > 1]
        parts = [f"{name}[{k}]" for name, ks in by_list.items() if name not in whole for k in ks]
        total = " + ".join(parts) if parts else "0.0"
        for name in whole:
            total = f"_sum({name}, {total})"
        return total


def quiet_store(line: str):
    """The match (target, literal index or None, value) of `line` (stripped) when it is a store
    that cannot raise: into a plain name or an element at a literal index, of `+ - *` of names,
    numbers and elements at literal indices (no call, attribute, data index, division or
    power); else None."""
    match = _STORE.fullmatch(line)
    if match is None:
        return None
    value = match.group(3)
    if _ATTRIBUTE_OR_CALL.search(value) or _DATA_INDEX.search(value) or "**" in value:
        return None
    return match


def _test(lines: list[str], n: int, end: int, lists) -> tuple[str, int, tuple[str, ...]] | None:
    """(list, index, body) when `lines[n:end]` is a finite test of a REAL or LREAL element
    whose body only charges and stores literals, with no `elif` or `else` after it."""
    match = _TEST.fullmatch(lines[n].strip())
    if match is None or end == n + 1:
        return None
    name, k = match.group(1), int(match.group(2))
    info = lists.get(name)
    if info is None or not info[1] or k >= info[0]:
        return None
    body = tuple(line.strip() for line in lines[n + 1:end])
    if indentation(lines[n + 1]) != indentation(lines[n]) + 4 or \
            not all(_CHARGE.fullmatch(line) or _LITERAL_STORE.fullmatch(line) for line in body):
        return None
    if any(_LITERAL_STORE.fullmatch(line) and _LITERAL_STORE.fullmatch(line).group(1) in (name, "_spent")
           for line in body):
        return None
    if end < len(lines) and indentation(lines[end]) == indentation(lines[n]) and \
            lines[end].strip().startswith(("elif ", "else:")):
        return None
    return name, k, body

