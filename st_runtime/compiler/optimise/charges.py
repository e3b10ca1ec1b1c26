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

_CHARGE = re.compile(r"( *)_spent \+= (\d+)")
_BARRIER = re.compile(r"\btry:|\bexcept\b|_ctx|_overrun|\breturn\b|\bbreak\b|\bcontinue\b|^\s*(?:for|while|with)\b"
                      r"|\.execute\(|_fn_|\bfinally:")


def merge(lines: list[str], start: int) -> None:
    """Add each charge that may join the one before it in its level to that one."""
    open_at: dict[int, int] = {}        # indentation -> index of the charge that takes later ones
    drop = set()
    for i in range(start, len(lines)):
        line = lines[i]
        indent = len(line) - len(line.lstrip(" "))
        for level in [level for level in open_at if level > indent]:
            del open_at[level]          # (that level has ended)
        match = _CHARGE.fullmatch(line)
        if match:
            first = open_at.get(indent)
            if first is not None:
                head = _CHARGE.fullmatch(lines[first])
                lines[first] = f"{head.group(1)}_spent += {int(head.group(2)) + int(match.group(2))}"
                drop.add(i)
            else:
                open_at[indent] = i
            continue
        if _BARRIER.search(line):
            open_at.clear()
        elif line.rstrip().endswith(":") and not line.lstrip().startswith(("if ", "elif ", "else:")):
            open_at.clear()
    if drop:
        lines[start:] = [line for i, line in enumerate(lines[start:], start) if i not in drop]
