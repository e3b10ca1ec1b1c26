"""`pivots`: a pivot search's largest `abs` kept in a local across its IFs (value numbering).

SP_LuSolve's partial pivoting, `IF ABS(Matrix[Row, K]) > ABS(Matrix[PivotRow, K]) THEN
PivotRow := Row; END_IF`, unrolled over the rows, reads the best candidate again for every
row, at a data index, and takes its `abs`:

    if (abs(v_MATRIX_e13) > abs(v_MATRIX[v_PIVOTROW * 6 - 5])):
        _spent += 1196
        v_PIVOTROW = 3
    if (abs(v_MATRIX_e19) > abs(v_MATRIX[v_PIVOTROW * 6 - 5])):
    ...
    if (-0.0 <= v_MATRIX[v_PIVOTROW * 6 - 5] <= 0.0):       # ABS(Matrix[PivotRow, K]) <= 0.0

In a fast copy such a chain keeps the best `abs` in `_best`, set before the first test and
again in each branch that moves the pivot row, from the candidate's `abs` kept by a walrus:

    _best = abs(v_MATRIX[v_PIVOTROW * 6 - 5])
    if ((_cand := abs(v_MATRIX_e13)) > _best):
        _spent += 1196
        v_PIVOTROW = 3
        _best = _cand
    ...
    if (_best <= 0.0):

Exact because

* `abs` of a number raises nothing and reads nothing else, and the element `X[P * a - b]`
  is read where the first test read it (its read at a data index cannot fault in a fast
  copy: `ranges` proved it in range, or the line would be guarded); the candidate's `abs`
  is computed first, as before;
* in a branch that sets `P = R`, the candidate read is element `R * a - b` of the list: the
  list element at that literal index (`X[r]`), or the local `scalars` holds for it
  (`X_er`), which equals the list there (the list is read at a data index by each test, so
  `scalars` wrote every newer local back before the chain);
* between the tests only charges, the pivot row's literal stores and stores of plain names
  (not P, not X) stand: nothing changes X or P otherwise, so `_best` is `abs(X[P * a - b])`
  at each test, and `-B <= x <= B` is `abs(x) <= B` for any B (absolute.py).

The same comparisons of the same values in the same order; charges untouched.  Anything else
ends the chain where it stands.
"""

from __future__ import annotations

import re

from ..pysrc import indentation, statement_end
from .sums import quiet_store

#: A candidate's test: `if (abs(E) > abs(X[P * a - b])):`, E a list element or a local.
_CANDIDATE = re.compile(r"( *+)if \(abs\(([A-Za-z_]\w*(?:\[\d+\])?)\) > abs\(([A-Za-z_]\w*)\[([A-Za-z_]\w*)"
                        r"(?: \* (\d+))? - (\d+)\]\)\):")
_ROW = re.compile(r"([A-Za-z_]\w*) = (\d+)")
_CHARGE = re.compile(r"_spent (?:\+=|=) \d+")
_BEST, _CANDIDATE_ABS = "_best", "_cand"
_HINT = ") > abs("


def keep(lines: list[str], start: int) -> None:
    """Keep the best `abs` of each pivot search in `lines[start:]` (a fast copy), in place."""
    out = lines[:start]
    n = start
    for i in _candidate_lines(lines, start):
        match = _CANDIDATE.fullmatch(lines[i]) if i >= n else None
        chain = _chain(lines, i, match) if match else None
        if chain is not None:
            out.extend(lines[n:i])
            n, rewritten = chain
            out.extend(rewritten)
    if n > start:
        lines[:] = out + lines[n:]


def _candidate_lines(lines: list[str], start: int) -> list[int]:
    """The lines of `lines[start:]` that hold `) > abs(`, found in their joined text (the
    regular expression is tried on those only: the LU's fast copy has some 700 lines)."""
    text = "\n".join(lines[start:])
    found, line, last = [], start, 0
    at = text.find(_HINT)
    while at >= 0:
        line += text.count("\n", last, at)
        found.append(line)
        last = text.find("\n", at)
        if last < 0:
            break
        at = text.find(_HINT, last)
    return found


def _chain(lines: list[str], n: int, first) -> tuple[int, list[str]] | None:
    """(end, lines) of the chain of candidate tests starting at line n, rewritten; None when
    a test's branch is not the pivot row's move (or the candidate is not the row it moves to)."""
    pad, element = first.group(1), _element(first)
    out = [f"{pad}{_BEST} = abs({element})"]
    tests = 0
    while n < len(lines):
        line = lines[n]
        match = _CANDIDATE.fullmatch(line)
        if match is not None and match.group(1) == pad and _element(match) == element:
            end, branch = _test(lines, n, match)
            if branch is None:
                break
            out.extend(branch)
            tests += 1
            n = end
        elif indentation(line) == len(pad) and _passable(line.strip(), first):
            out.append(line)
            n += 1
        else:
            bound = _zero_test(line, pad, element)
            if bound is not None:
                out.append(bound)
                n += 1
            break
    return (n, out) if tests else None


def _passable(line: str, first) -> bool:
    """A store between the tests that changes neither the list, nor the pivot row, nor the
    pass's names, nor a local `scalars` holds for an element of the list (a candidate read
    after it would differ from the list): into a plain name (an element store might reach
    the list through another name), of a value that cannot raise."""
    match = quiet_store(line)
    return match is not None and match.group(2) is None and \
        match.group(1) not in (first.group(3), first.group(4), _BEST, _CANDIDATE_ABS) and \
        _index(match.group(1), first.group(3)) is None          # (nor `scalars`' local of X)


def _test(lines: list[str], n: int, match) -> tuple[int, list[str] | None]:
    """The candidate test at line n rewritten (its end, its lines), or (n, None)."""
    pad = match.group(1)
    candidate, row_name = match.group(2), match.group(4)
    scale, offset = int(match.group(5) or 1), int(match.group(6))
    end = statement_end(lines, n, len(pad))
    body = lines[n + 1:end]
    rows = [_ROW.fullmatch(line.strip()) for line in body]
    moves = [row for row in rows if row is not None and row.group(1) == row_name]
    if len(moves) != 1 or not all(row is not None or _CHARGE.fullmatch(line.strip())
                                  for row, line in zip(rows, body)):
        return n, None
    if any(row is not None and row.group(1) != row_name for row in rows) or \
            _index(candidate, match.group(3)) != int(moves[0].group(2)) * scale - offset:
        return n, None
    inner = " " * indentation(body[0])
    out = [f"{pad}if (({_CANDIDATE_ABS} := abs({candidate})) > {_BEST}):", *body,
           f"{inner}{_BEST} = {_CANDIDATE_ABS}"]
    if end < len(lines) and lines[end] == f"{pad}else:":
        after = statement_end(lines, end, len(pad))
        if not all(_CHARGE.fullmatch(line.strip()) for line in lines[end + 1:after]):
            return n, None
        out += lines[end:after]
        end = after
    if end < len(lines) and indentation(lines[end]) == len(pad) and lines[end].strip().startswith("elif "):
        return n, None
    return end, out


def _element(match) -> str:
    """The best candidate's element as the test reads it, `X[P * a - b]`."""
    scale = f" * {match.group(5)}" if match.group(5) else ""
    return f"{match.group(3)}[{match.group(4)}{scale} - {match.group(6)}]"


def _index(candidate: str, name: str) -> int | None:
    """The list index a candidate `X[r]` or `X_er` (scalars' local of element r) reads."""
    literal = re.fullmatch(rf"{name}\[(\d+)\]", candidate)
    local = re.fullmatch(rf"{name}_e(\d+)", candidate)
    found = literal or local
    return int(found.group(1)) if found else None


def _zero_test(line: str, pad: str, element: str) -> str | None:
    """`if (-B <= X[P * a - b] <= B):` (absolute.py's `ABS(x) <= B`, `<` too) as
    `if (_best <= B):`, B a literal; else None."""
    match = re.fullmatch(rf"{pad}if \((\S+) (<=|<) {re.escape(element)} \2 (\S+)\):", line)
    if match is None:
        return None
    low, op, high = match.groups()
    try:
        if repr(-float(high)) != low or repr(float(high)) != high:
            return None
    except ValueError:
        return None
    return f"{pad}if ({_BEST} {op} {high}):"

