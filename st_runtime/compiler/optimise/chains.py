"""`chains`: consecutive updates of one array element in a fast copy written as one store.

The LU's substitutions, unrolled, update one element again and again:

    v_SOLUTION[3] = (v_SOLUTION[3] - (v_MATRIX[18] * v_SOLUTION[0]))
    v_SOLUTION[3] = (v_SOLUTION[3] - (v_MATRIX[19] * v_SOLUTION[1]))

become `v_SOLUTION[3] = ((v_SOLUTION[3] - (v_MATRIX[18] * v_SOLUTION[0])) - (v_MATRIX[19]
* v_SOLUTION[1]))`: one store and one read fewer a step.  Exact when

* both lines stand on their own, not in a `try` body: unguard.py left them unguarded,
  so neither can raise (a fault between the two cannot happen);
* the second reads the element once, as the left operand of its outermost `+ - *`,
  and the rest of it reads lists at literal indices other than k only (another list
  read at k, or at an index that is data, might be the element: the same list passed
  twice), so it reads the same values either way;
* they are adjacent lines of one block: no charge, budget check or branch between.

The first value is computed, then the rest, then the operation: the same operations on
the same floats (or ints) in the same order, and the element ends with the same value.
"""

from __future__ import annotations

import re

from ..pysrc import indentation

_STORE = re.compile(r"(\s*+)((?:self\.)?[A-Za-z_]\w*)\[(\d+)\] = (.+)")
_LITERAL_INDEX = re.compile(r"\[(\d+)\]")


def merge(lines: list[str], start: int) -> None:
    """Merge such pairs in `lines[start:]`, in place."""
    out: list[str] = []
    # The lines a later line may stand in, innermost last: (indentation, is `try:`); the
    # nearest line before out[-1] that is less indented is the last (one pass, not a
    # search back from each pair: the LU's fast body has hundreds of pairs).
    openers: list[tuple[int, bool]] = []
    free = True             # out[-1] is not the body of a `try:` (a merge keeps its indentation)
    for n, line in enumerate(lines):
        if n >= start and len(out) > start and free:
            merged = _merged(out[-1], line)
            if merged is not None:
                out[-1] = merged
                continue
        depth = indentation(line)
        while openers and openers[-1][0] >= depth:
            openers.pop()
        free = not openers or not openers[-1][1]
        openers.append((depth, line.strip() == "try:"))
        out.append(line)
    lines[:] = out


def _merged(first: str, second: str) -> str | None:
    a, b = _STORE.fullmatch(first), _STORE.fullmatch(second)
    if a is None or b is None or a.group(1) != b.group(1) or a.group(2, 3) != b.group(2, 3):
        return None
    indent, target, index, value = b.groups()
    element = f"{target}[{index}]"
    head = f"({element} "
    if not (value.startswith(head) and value[len(head)] in "+-*" and value[len(head) + 1] == " "):
        return None
    rest = value[len(head):]
    literal = _LITERAL_INDEX.findall(rest)
    if rest.count("[") != len(literal) or index in literal:
        return None             # an index that is k, or may be (data): the store could be seen
    return f"{indent}{element} = ({_atom(a.group(4))} {rest}"


def _atom(code: str) -> str:
    """`code` as an operand: as it is when one pair of parentheses encloses it all."""
    if code.startswith("(") and code.endswith(")"):
        depth = 0
        for i, c in enumerate(code):
            depth += c == "("
            depth -= c == ")"
            if depth == 0 and i < len(code) - 1:
                break
        else:
            return code
    return f"({code})"
