"""Straight-line clean-up of a CSE region's Python lines, each step exact.

Runs on the lines of a region (cse.py) once it is compiled, where every store
is to a plain Python local and the element reads were taken before it.  Only
*pure* lines take part: `name = expression` at the region's own level whose
expression is names, numbers, parentheses and `+ - *` -- it cannot raise,
calls nothing and reads no memory, so when it is evaluated changes nothing
but the float objects made.

* `substitute`: `P = X` followed by a line that reads `P` once becomes that
  line with `(X)` in place of `P`, when the next line that mentions `P` sets
  it again and only pure lines lie between: no one can see the skipped store
  (no fault, no overrun check, no branch between).  The Leibniz terms:
  `Product := ...; Determinant := Determinant + Product;`.
* `merge`: `D = (D op A)` followed by `D = (D op B)`, with `B` not reading
  `D`, becomes `D = ((D op A) op B)`: the same operations in the same order
  (never reassociated), only the store between is skipped.  Chains are
  capped at `MERGE_CAP` operations (Python's parser nests them).
* `rename`: the temporaries defined and used only inside the region share a
  few Python names (a temporary's lines span a range; ranges that do not
  overlap take the same name), so the function keeps fewer than 256 locals
  and CPython needs no EXTENDED_ARG before each access.  Only when the
  region has no loop (ranges in straight or forward-branching code).

The results are the same floats in the same order; `fuse` is a switch of
its own (`Optimisations.fuse`).
"""

from __future__ import annotations

import re

from . import TEMP_NAME, remembered
from .mentions import count, places

MERGE_CAP = 24

_PURE = re.compile(r"^(\s*+)([A-Za-z_]\w*) = ([\w\s.()+*-]+)$")
_ACCUMULATE = re.compile(r"^(\s*+)([A-Za-z_]\w*) = \(\2 ([+*-]) (.+)\)$")
_LOOP = re.compile(r"^\s*+(for|while) ")
# A call `f(` (`\w\s*\(`) is searched for read backwards, `\(\s*\w`: the pattern's first
# character a literal, the regex engine tries it at each `(` only, not at every character
# (a fifth of the machine instructions); an attribute `.x` where the code holds a dot.
_CALL_BACKWARDS = re.compile(r"\(\s*\w")
_ATTRIBUTE = re.compile(r"\.[A-Za-z_]")
_PARENTHESIS = re.compile(r"[()]")


def _pure(line: str):
    """(indent, name, expression) of a pure assignment, else None."""
    match = _PURE.match(line)
    if match is None:
        return None
    expression = match.group(3)
    if _CALL_BACKWARDS.search(expression[::-1]) or "." in expression and _ATTRIBUTE.search(expression):
        return None
    return match.groups()


def _enclosed(text: str) -> bool:
    """Whether `text` is one parenthesised group (its first '(' closes at its end)."""
    if not (text.startswith("(") and text.endswith(")")):
        return False
    depth, last = 0, len(text) - 1
    for match in _PARENTHESIS.finditer(text):    # (the depth changes only there)
        depth += 1 if match.group() == "(" else -1
        if depth == 0 and match.start() < last:
            return False
    return True


_UNREAD = object()


def substitute(lines: list[str], start: int) -> None:
    i, head = start, _UNREAD
    pure = remembered(_pure)        # (`_set_again` reads the lines ahead again)
    while i < len(lines) - 1:
        if head is _UNREAD:
            head = pure(lines[i])
        use = pure(lines[i + 1])
        if head and use and head[0] == use[0] and head[1] != use[1] and not head[1].startswith("_t") \
                and count(head[2], head[1]) == 0 and count(use[2], head[1]) == 1 \
                and _set_again(lines, i + 2, head[0], head[1], pure):
            value = head[2] if _enclosed(head[2]) else f"({head[2]})"
            at = places(use[2], head[1])[0]        # (its one place: `count` above)
            expression = f"{use[2][:at]}{value}{use[2][at + len(head[1]):]}"
            lines[i:i + 2] = [f"{use[0]}{use[1]} = {expression}"]
            head = _UNREAD
            continue
        i, head = i + 1, use          # (the next line's head: read once)


def _set_again(lines: list[str], j: int, indent: str, name: str, pure_of=_pure) -> bool:
    """Whether the next line mentioning `name` sets it from what does not read it, with
    only pure lines at `indent` before it."""
    for k in range(j, len(lines)):      # (not a copy of the rest, nor `islice`: it steps over the first j)
        pure = pure_of(lines[k])
        if pure is None or pure[0] != indent:
            return False
        if pure[1] == name:
            return count(pure[2], name) == 0
        if count(pure[2], name):
            return False
    return False


def merge(lines: list[str], start: int) -> None:
    out = lines[:start]
    length = 0
    appended = None         # the match of out[-1] when it is a step appended as it was
    for line in lines[start:]:
        step = _ACCUMULATE.match(line) if _pure(line) else None
        if step and out and length and length < MERGE_CAP:
            previous = appended if length == 1 else _ACCUMULATE.match(out[-1])
            indent, name, op, operand = step.groups()
            if previous and previous.group(1) == indent and previous.group(2) == name \
                    and count(operand, name) == 0:
                value = out[-1][len(indent) + len(name) + 3:]
                out[-1] = f"{indent}{name} = ({value} {op} {operand})"
                length += 1
                continue
        out.append(line)
        length = 1 if step else 0
        appended = step
    lines[:] = out


def rename(lines: list[str], start: int, fresh) -> None:
    body = lines[start:]
    if any(_LOOP.match(line) for line in body):
        return
    span: dict[str, list[int]] = {}
    for i, line in enumerate(body):
        for temp in TEMP_NAME.findall(line):
            span.setdefault(temp, [i, i])[1] = i
    outside = set()
    for line in lines[:start]:
        outside.update(TEMP_NAME.findall(line))
    names = {}
    free: list[str] = []
    ends: dict[int, list[str]] = {}
    for temp, (first, last) in sorted(span.items(), key=lambda item: item[1][0]):
        head = body[first].lstrip()
        if temp in outside or not head.startswith(f"{temp} = ") or count(head[len(temp) + 3:], temp):
            continue
        # names whose last line is before `first` are free again
        for line_no in sorted(k for k in ends if k < first):
            free.extend(ends.pop(line_no))
        names[temp] = free.pop() if free else fresh()
        ends.setdefault(last, []).append(names[temp])
    if names:
        lines[start:] = [TEMP_NAME.sub(lambda m: names.get(m.group(), m.group()), line) for line in body]
