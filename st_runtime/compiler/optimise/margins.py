"""Each line's leading spaces in generated code, found in C for every line at once: the text
passes (charges, threads) read every line's indentation on each walk.

`str.lstrip(" ")` reads each space through a search of its argument (ten times the machine
instructions of `str.lstrip()`); where no line holds a white space but the space, the two
strip the same, so the plain one is used there.
"""

from __future__ import annotations

import itertools
from operator import sub


def stripped(text: list[str], flat: str | None = None) -> list[str]:
    """Each line without its leading spaces (`flat`: the lines joined, when the caller has it)."""
    if flat is None:
        flat = "".join(text)
    if _plain(flat):
        return list(map(str.lstrip, text))
    return list(map(str.lstrip, text, itertools.repeat(" ")))


def widths(text: list[str], stripped_lines: list[str] | None = None) -> list[int]:
    """Each line's count of leading spaces (`stripped_lines`: `stripped(text)`, when the caller
    has it); an empty line's is 0."""
    if stripped_lines is None:
        stripped_lines = stripped(text)
    return list(map(sub, map(len, text), map(len, stripped_lines)))


def first_passing(indents: list[int], n: int, test, step: int = 1) -> int | None:
    """The first line from line `n` on (`step` -1: from `n` back) whose indentation passes
    `test` (a C callable, `depth.__ge__`: not deeper than `depth`), None when no line does.
    Read in C, in windows that grow fourfold: a scan costs what the lines up to the one found
    cost (`islice` from `n` would step over every line before `n` first)."""
    size, end = 16, len(indents)
    while 0 <= n < end:
        if step == 1:
            window = indents[n:n + size]
        else:
            window = indents[max(0, n - size + 1):n + 1]
            window.reverse()
        found = next(itertools.compress(itertools.count(n, step), map(test, window)), None)
        if found is not None:
            return found
        n, size = n + step * len(window), size * 4
    return None


def _plain(flat: str) -> bool:
    """Whether the text `flat` holds no white space but the space."""
    return flat.isascii() and not any(map(flat.__contains__, _WHITE_SPACE_BUT_SPACE))


# The ASCII white space but the space (`str.isspace`).
_WHITE_SPACE_BUT_SPACE = ("\n", "\t", "\x0b", "\x0c", "\r", "\x1c", "\x1d", "\x1e", "\x1f")
