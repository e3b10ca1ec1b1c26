"""Writing Python source safely: literals through `repr`, indented lines.

No text of an ST program reaches the generated Python except through
`pyliteral` (values) and `mangle` (identifiers, `v_` + upper case, which the
checker has already restricted to letters, digits and `_`).
"""

from __future__ import annotations

import functools
import math
import re

_IDENT = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")


def indentation(line: str) -> int:
    """The spaces a generated line is indented by (the emitter indents with spaces only)."""
    return len(line) - len(line.lstrip(" "))


def statement_end(lines: list[str], n: int, indent: int) -> int:
    """The index after line n and the lines after it indented deeper than `indent` (its body)."""
    end = n + 1
    while end < len(lines) and indentation(lines[end]) > indent:
        end += 1
    return end


def pyliteral(value) -> str:
    """Python source for a constant value (bool, int, float, str)."""
    if isinstance(value, bool):
        return "True" if value else "False"
    if isinstance(value, int):
        return repr(int(value))
    if isinstance(value, float):
        if math.isnan(value):
            return "_NAN"
        if math.isinf(value):
            return "_INF" if value > 0 else "(-_INF)"
        return repr(value)
    if isinstance(value, str):
        return repr(value)
    if isinstance(value, tuple):
        inner = ", ".join(pyliteral(v) for v in value)
        return f"({inner},)" if len(value) == 1 else f"({inner})"
    if value is None:
        return "None"
    raise TypeError(f"no Python literal for {type(value).__name__}")


def safe_name(name: str) -> str:
    """Assert that a generated Python identifier is a plain identifier."""
    if not _IDENT.match(name):
        raise ValueError(f"not a safe Python identifier: {name!r}")
    return name


def finite_test(first: str, again: str) -> str:
    """Python for "x is finite" (a bool), x read as `first` and then as `again` (a name, or
    `first` itself when reading it twice gives the same value): `x < inf and x > -inf`.
    False for either infinity and NaN, True for every other float and every int, as `x - x
    == 0.0` is; but two comparisons that CPython 3.11 specialises (each followed by its
    jump) instead of a subtraction that makes and frees a float.  `1e309` overflows to the
    float infinity: a literal, so both bounds are constants of the code object."""
    return f"{first} < 1e309 and {again} > -1e309"


@functools.lru_cache(maxsize=8192)   # a pure function, asked again for every variable of every load
def pyident(st_name: str) -> str:
    """The Python name of an ST identifier: `mangle`, checked to be plain."""
    from ..native import mangle

    return safe_name(mangle(st_name))


class Emitter:
    """Collects indented lines of Python source."""

    def __init__(self) -> None:
        self.lines: list[str] = []
        self.depth = 0

    def line(self, text: str) -> None:
        self.lines.append("    " * self.depth + text)

    def indent(self) -> None:
        self.depth += 1

    def dedent(self) -> None:
        self.depth -= 1

    def mark(self) -> int:
        return len(self.lines)

    def insert(self, mark: int, lines: list[str]) -> None:
        """Insert lines at `mark` with the current indentation."""
        pad = "    " * self.depth
        self.lines[mark:mark] = [pad + line for line in lines]

    def ensure_body(self, mark: int) -> None:
        """Emit `pass` when nothing was emitted since `mark` (empty block)."""
        if len(self.lines) == mark:
            self.line("pass")

    def source(self) -> str:
        return "\n".join(self.lines) + "\n"
