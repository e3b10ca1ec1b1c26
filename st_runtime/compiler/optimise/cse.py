"""Reuse inside an unrolled loop: array reads and `+ - *` results computed once.

A `Region` is active while an unrolled loop (unroll.py) is compiled, when its
body stores only plain Python locals (`how == "local"`) and calls nothing:
then no array element can change while the region runs (no store reaches an
array, no callee runs, no VAR_IN_OUT alias is written).  So:

* an element read at a constant index (`v_MATRIX[7]`) is read once, into a
  name set before the region (`reads`);
* a `+`, `-` or `*` whose operands are such names, literals or earlier
  shared results is computed once, where first needed, and reused
  (`shared`).  The text of the operation is its key: the same operands in
  the same order and grouping, so the reused value is the value the
  expression would have computed again (left-to-right partial products of
  the Leibniz terms are shared; nothing is reassociated).

A new shared result is defined only in straight-line code of the region
(`straight`): code that is skipped would leave the name unset.  The element
reads may fault (an unconnected VAR_IN_OUT); the region then does not run:
the caller emits `if <reads succeeded>: <region> else: <the loop as before>`.
"""

from __future__ import annotations

import re

from ... import ast
from ..scope import walk

_READ = re.compile(r"[A-Za-z_]\w*\[\d+\]")
_NUMBER = re.compile(r"-?\(?-?\d[\d.e+-]*\)?")


class Region:
    def __init__(self, temp):
        self.temp = temp
        self.reads: dict[str, str] = {}      # `v_A[7]` -> name read before the region
        self.shared: dict[str, str] = {}     # `(x * y)` -> name holding it
        self.names: set[str] = set()         # names that hold a value fixed for the region
        self.straight = True
        self.whole = None                    # the value expression of the assignment being compiled
        self.enclosing_straight = True       # `straight` outside the compound statement being compiled

    def read(self, code: str) -> str:
        if not _READ.fullmatch(code):
            return code
        name = self.reads.get(code)
        if name is None:
            name = self.reads[code] = self.temp()
            self.names.add(name)
        return name

    def fixed(self, code: str) -> bool:
        return code in self.names or bool(_NUMBER.fullmatch(code))

    def binary(self, op: str, left: str, right: str, out, define: bool = True) -> str | None:
        """The name of the shared `left op right`, or None when it cannot be shared.

        `define=False`: reuse only (the whole value of an assignment, which is
        stored at once and, when it repeats, found by the next use's lookup)."""
        if op not in ("+", "-", "*") or not (self.fixed(left) and self.fixed(right)):
            return None
        text = f"({left} {op} {right})"
        name = self.shared.get(text)
        if name is None:
            if not self.straight or not define:
                return None
            name = self.shared[text] = self.temp()
            self.names.add(name)
            out.line(f"{name} = {text}")
        return name


def region_allowed(compiler, body) -> bool:
    """Whether `body` stores only plain locals and calls nothing (see the module docstring)."""
    for node in walk(body):
        if isinstance(node, (ast.Call, ast.CallStmt)):
            return False
        if isinstance(node, ast.Assign):
            if not isinstance(node.target, ast.Name) or not _is_local(compiler, node.target):
                return False
        elif isinstance(node, ast.For):
            if not _is_local(compiler, ast.Name(node.variable, pos=node.pos)):
                return False
    return True


def _is_local(compiler, name) -> bool:
    place = compiler.scope.places.get(name.name.upper())
    return place is not None and place.how == "local"
