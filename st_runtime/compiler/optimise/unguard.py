"""No `try` around an assignment that cannot raise.

The code of an assignment cannot raise when it is `local = expression`
where the expression uses only Python locals, numeric literals, parentheses
and `+ - *`: every local of an elementary variable holds an int or a float
(set in the prologue, so always bound), and + - * of ints and floats never
raise in Python (a float overflow gives inf).  Attribute reads, subscripts,
calls, `**`, division and comparisons keep their handler.
"""

from __future__ import annotations

import re

_ASSIGNMENT = re.compile(r"\s*[A-Za-z_]\w* = ([\w\s()+\-*.]+)")
_ATTRIBUTE_OR_CALL = re.compile(r"[A-Za-z_]\w*\s*[.(]")


def cannot_fault(lines: list[str]) -> bool:
    for line in lines:
        match = _ASSIGNMENT.fullmatch(line)
        if match is None or "**" in match.group(1) or _ATTRIBUTE_OR_CALL.search(match.group(1)):
            return False
    return bool(lines)
