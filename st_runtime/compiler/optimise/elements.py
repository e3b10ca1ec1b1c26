"""`elements`: an IF chain's conditions read an array element once.

An IF/ELSIF chain tested in place (branches.py: its conditions read owned storage only,
call nothing that may raise, store nothing) evaluates its conditions one after another
with nothing else between them.  An element `v_A[k]` of a local array at a literal index
read by two or more of them is the same object at each read: no condition stores into A
or binds `v_A` again (a condition's only binding is a walrus temp `_tN`).  So the first
read takes the element into a temp, `(_tM := v_A[k])`, and the later ones read the temp,
where the first read runs whenever its condition does: only `+ - *`, names, literals,
parentheses, NOT and walrus temps before it in its condition, no `and`, `or`,
comparison, conditional expression or call that could leave it out.  A later read may
stand anywhere: when its condition runs, every earlier condition ran whole.
(SP_Controller's axes: `AxisSync[k].Error`, `.CommandAborted` and `.Active` in three
ELSIFs: `v_AXISSYNC[k]` read once, not three times.)
"""

from __future__ import annotations

import re

_ELEMENT = re.compile(r"(?<![\w.])v_\w+\[\d+\]")
# What may stand before an element read in its condition for the read to run whenever the
# condition does: evaluated left to right with nothing left out.
_ALWAYS_BEFORE = re.compile(r"(?:[\s()+\-*]|not\b|_t\d+ := |(?:self\.|_G\.)?v_\w+(?:\[\d+\])?(?:\.v_\w+)*"
                            r"|\d+(?:\.\d*)?(?:e-?\d+)?)*")
MIN_READS = 2       # reads of one element in a chain's conditions that share one


def shared(conditions: list[str], temp) -> list[str]:
    """`conditions`, an IF chain's in order, with each element read in two or more of them
    read once (module docstring); `temp()` gives a fresh temp name."""
    counts: dict[str, int] = {}
    for condition in conditions:
        for element in _ELEMENT.findall(condition):
            counts[element] = counts.get(element, 0) + 1
    repeated = {element for element, count in counts.items() if count >= MIN_READS}
    if not repeated:
        return conditions
    names: dict[str, str] = {}          # element -> the temp its first read set
    out = []
    for condition in conditions:
        out.append(_ELEMENT.sub(lambda m: _read(m, repeated, names, temp), condition))
    return out


def _read(match, repeated: set, names: dict, temp) -> str:
    """The text for one element read: as written, its first read into a temp, or the temp."""
    element = match.group(0)
    if element not in repeated:
        return element
    name = names.get(element)
    if name is not None:
        return name
    if not _ALWAYS_BEFORE.fullmatch(match.string, 0, match.start()):
        repeated.discard(element)       # (its first read may be left out: every read as written)
        return element
    names[element] = name = temp()
    return f"({name} := {element})"
