"""`charges`: two charges of a straight run with nothing between that sees `_spent` are one.

The exact code charges each block of the ST source where it starts (`_spent += N`,
statements.py).  `_spent` is read only by a budget check (`if _ctx.budget < _spent`),
by the `finally` that ends the call (after a RETURN, or an exception: an overrun, a
fault that stops the run from its handler), and, in a fast body, by a fault handler's
take-back.  So when a later charge of the same block level follows an earlier one and
nothing between them can raise, check the budget or leave the level (no `try`, no
`_ctx`, no call of ST code, no loop, RETURN, EXIT or CONTINUE: only assignments and IF
tests that cannot raise, with their own branches' charges), the later amount can be
added by the earlier line: every read of `_spent` sees the same total, and the total
charged is the same.  (SP_InverseKinematics: the six legs' charges are one.)
"""

from __future__ import annotations

import re

_CHARGE = re.compile(r"^( *)_spent \+= (\d+)$", re.M)
_BARRIER = re.compile(r"\btry:|\bexcept\b|\bfinally:|_ctx|_overrun|\breturn\b|\bbreak\b|\bcontinue\b|\.execute\("
                      r"|_fn_|^ *(?:for|while|with)\b|^(?! *(?:if |elif |else:))[^\n]*:$", re.M)


def merge(lines: list[str], start: int) -> None:
    """Add each charge that may join the one before it in its level to that one."""
    text = "\n".join(lines[start:])
    found = list(_CHARGE.finditer(text))
    if len(found) < 2:
        return
    line_of, line, at = [], 0, 0
    for match in found:
        line += text.count("\n", at, match.start())
        at = match.start()
        line_of.append(line)
    totals = [int(match.group(2)) for match in found]
    taker: dict[int, int] = {}          # indentation -> the charge that takes later ones
    # indentation -> where the code between the taker and the next charge is still to be
    # read: the text up to a joined charge's line was read and is joinable, and no match
    # of _joinable's patterns crosses that line's start (they stay within a line, and
    # the line is indented as the taker), so only the text after it is read again
    checked: dict[int, int] = {}
    dropped = set()
    for k, match in enumerate(found):
        indent = len(match.group(1))
        first = taker.get(indent)
        if first is not None and _joinable(text, checked[indent], match.start(), indent):
            totals[first] += totals[k]
            dropped.add(k)
            checked[indent] = match.start()
        else:
            taker[indent] = k
            checked[indent] = match.end()
    if not dropped:
        return
    new = text.split("\n")
    for k, match in enumerate(found):
        if k in dropped:
            new[line_of[k]] = None
        elif totals[k] != int(match.group(2)):
            new[line_of[k]] = f"{match.group(1)}_spent += {totals[k]}"
    lines[start:] = [line for line in new if line is not None]


def _joinable(text: str, start: int, end: int, indent: int) -> bool:
    """Whether the code between two charges of one indentation is of their block (no line
    less indented) and cannot raise, check the budget or leave it (no barrier)."""
    between = text[start:end]
    if indent and re.search(rf"\n {{0,{indent - 1}}}\S", between):
        return False
    return not _BARRIER.search(between)
