"""Reuse of an array element read again within one iteration of a FOR loop (with `cse`).

A FOR body (not unrolled) whose lines are all assignments to Python names (`name = code`,
or augmented), that calls nothing but the numeric library (`_m_sin`, `_sf_SIN` and the
like: functions of floats) and stores into no array element and no attribute, changes no
array while one iteration runs.  So an element read `v_A[_tN]` (a local holding the array,
a temporary holding the index) that the iteration reads again, neither name assigned
between, gives the value the first read gave: the first read keeps it (`(_tM :=
v_A[_tN])`) and the later ones read that name, one list subscript fewer each.

The first read keeps it only where it is always evaluated: on a line without a conditional
expression, `and` or `or` (whose operands may be skipped).  There, as in every expression of
names, subscripts, calls and arithmetic, Python evaluates the operands in the order they are
written, so a later read of the same line comes after it.  A read that faults (an index out
of range) is still the first read, where it was.  (TRJ_OceanWave's component loop reads
`LatchedAmplitude[k]` three times and `Wavenumber[k]` twice an iteration.)
"""

from __future__ import annotations

import re

from ..pysrc import indentation, statement_end

_ASSIGNMENT = re.compile(r"( *+)([A-Za-z_]\w*) ((?:[-+*/%&|^]|//|\*\*|<<|>>)?=) (.+)")
_CALLED = re.compile(r"([A-Za-z_][\w.]*)\(")
_NUMERIC = re.compile(r"_m_(?:sin|cos|tan|sqrt)|_sf_(?:SIN|COS|TAN|ASIN|ACOS|ATAN|SQRT|LN|LOG|EXP|EXPT|ABS)")
_ELEMENT = re.compile(r"(?<![\w.])(v_\w+)\[(_t\d+)\]")
_SKIPPING = re.compile(r"\b(?:if|else|and|or|lambda|for)\b")
_CHAINED = re.compile(r"(?<![=!<>:])=(?!=)")
_WALRUS = re.compile(r"([A-Za-z_]\w*)\s*:=")


def share_in_loops(lines: list[str], start: int, temp) -> None:
    """`shared_reads` in the body of each `for` loop of the code from line `start` whose
    body is a run of lines of one indentation (what follows, from its `else:` on, is not)."""
    n = start
    while n < len(lines):
        line = lines[n]
        if line.lstrip().startswith("for ") and line.endswith(":"):
            end = statement_end(lines, n, indentation(line))
            lines[n + 1:end] = shared_reads(lines[n + 1:end], temp)
        n += 1


def shared_reads(lines: list[str], temp) -> list[str]:
    """The body `lines` of a FOR loop with each element read that the iteration reads again
    kept by its first read (module docstring); `temp()` gives new local names.  The lines as
    they are when the body is not of that kind."""
    parsed = [_ASSIGNMENT.fullmatch(line) for line in lines]
    if not parsed or None in parsed or len({match.group(1) for match in parsed}) != 1:
        return lines
    if any(not _NUMERIC.fullmatch(name) for match in parsed for name in _CALLED.findall(match.group(4))):
        return lines
    if any(_CHAINED.search(match.group(4)) for match in parsed):
        return lines            # (`a = b = c` stores into b too)
    # A name set by `:=` inside a line is set where no line's target says so: no element
    # of an array of that name, or at an index of that name, is kept.
    walrus = {name for match in parsed for name in _WALRUS.findall(match.group(4))}
    if not any(len(_ELEMENT.findall(match.group(4))) for match in parsed):
        return lines
    kept: dict[tuple[str, str], str] = {}        # (array, index) -> the name holding the element
    out = []
    for n, match in enumerate(parsed):
        indent, target, operator, code = match.groups()
        always = _SKIPPING.search(code) is None

        def read(element: re.Match) -> str:
            key = element.groups()
            name = kept.get(key)
            if name is not None:
                return name
            if not always or walrus.intersection(key) or not _read_again(key, parsed, n, element.end()):
                return element.group(0)
            name = kept[key] = temp()
            return f"({name} := {element.group(0)})"

        out.append(f"{indent}{target} {operator} {_ELEMENT.sub(read, code)}")
        kept = {key: name for key, name in kept.items() if target not in key}
    return out


def _read_again(key: tuple[str, str], parsed: list[re.Match], n: int, position: int) -> bool:
    """Whether the element `key` is read after `position` of line `n`'s code, before a line
    assigns its array or index name (that line's own code, evaluated first, included)."""
    if key in _elements(parsed[n].group(4)[position:]):
        return True
    if parsed[n].group(2) in key:
        return False
    for match in parsed[n + 1:]:
        if key in _elements(match.group(4)):
            return True
        if match.group(2) in key:
            return False
    return False


def _elements(code: str) -> list[tuple[str, str]]:
    return _ELEMENT.findall(code)
