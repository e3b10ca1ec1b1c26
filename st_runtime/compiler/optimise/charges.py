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

Then a charge that an IF chain follows (with nothing between that is such a line, and no
condition one) goes into the chain: into each branch's first charge, or written at the start
of a branch that opens with none it may take, and a chain without ELSE gets one that charges
it.  Every path through the chain charges the same total, and no read of `_spent` lies between
the two places.  (SP_Controller's six axes: `_spent += 1196` and the IF/ELSIF/ELSE of the axis's
fault tests, each branch with its charge, charge once an axis; in CPython 3.11 a charge is an
int beyond the cached small ones, made and freed: about 200 machine instructions.)
"""

from __future__ import annotations

import re

_CHARGE = re.compile(r"( *)_spent \+= (\d+)")
# A line that can raise, check the budget or leave the level: a word of these (the first
# test: a substring, then the word as a whole), a loop's head, or a line opening a block
# other than a branch of an IF (`try:`, `for ...:`; not `if`, `elif`, `else:`).
_BARRIER_WORDS = ("try:", "except", "finally:", "_ctx", "_overrun", "return", "break", "continue",
                  ".execute(", "_fn_")
_BARRIER_WORD = re.compile(r"\btry:|\bexcept\b|\bfinally:|_ctx|_overrun|\breturn\b|\bbreak\b|\bcontinue\b"
                           r"|\.execute\(|_fn_")
_LOOP = re.compile(r" *(?:for|while|with)\b")
_BRANCH = re.compile(" *(?:if |elif |else:)")


def merge(lines: list[str], start: int) -> None:
    """Add each charge that may join the one before it in its level to that one."""
    joined = "\n".join(lines[start:])
    if joined.count("_spent += ") < 2:
        return                  # (fewer than two charges: none to join, no line to read)
    text = joined.split("\n")
    found = [(n, match) for n, line in enumerate(text)
             if "_spent += " in line and (match := _CHARGE.fullmatch(line))]
    if len(found) < 2:
        return
    totals = [int(match.group(2)) for _, match in found]
    taker: dict[int, int] = {}          # indentation -> the charge that takes later ones
    # indentation -> the first line after the taker still to be read: the lines up to a
    # joined charge were read and are joinable, so only the lines after it are read again
    checked: dict[int, int] = {}
    stops = _Stops(text)
    dropped = set()
    for k, (n, match) in enumerate(found):
        indent = len(match.group(1))
        first = taker.get(indent)
        if first is not None and stops.joinable(checked[indent], n, indent):
            totals[first] += totals[k]
            dropped.add(k)
        else:
            taker[indent] = k
        checked[indent] = n + 1
    new = list(text)
    for k, (n, match) in enumerate(found):
        if k in dropped:
            new[n] = None
        elif totals[k] != int(match.group(2)):
            new[n] = f"{match.group(1)}_spent += {totals[k]}"
    lines[start:] = _sunk([line for line in new if line is not None])


def _sunk(text: list[str]) -> list[str]:
    """`text` with each charge that an IF chain follows (nothing between that is a barrier, no
    condition one) added to each branch's first charge instead (one written at the branch's
    start when the branch opens with none it may take; a chain without ELSE gets one that
    charges it): every path through the chain charges the same total, and no read of
    `_spent` lies between the two places.  A branch's charge then goes on into a chain of its
    own (the text is read again while a charge moved: a few times, as deep as chains nest)."""
    candidates = [n for n, line in enumerate(text) if "_spent += " in line]
    for _ in range(_ROUNDS):
        moved = _sink_once(text, candidates)
        if moved is None:
            break
        text, candidates = moved        # (the charges it changed or wrote: only they may move on)
    return text


_ROUNDS = 8
_LOOK_AHEAD = 16        # statements between a charge and the IF it may sink into (the load's cost)


def _sink_once(text: list[str], candidates: list[int]) -> tuple[list[str], list[int]] | None:
    """`_sunk`'s one reading of `text` for the charges on lines `candidates`: (the text, the
    lines of the charges it changed or wrote), or None when no charge moved."""
    stops = _Stops(text)
    sunk: dict[int, int] = {}           # line -> the amount added to it (or written before it)
    elses: dict[int, list] = {}         # line -> the ELSEs written before it (deepest first)
    gone = set()
    for n in candidates:
        match = _CHARGE.fullmatch(text[n])
        if match is None:
            continue
        indent = match.group(1)
        chain = _chain(text, n + 1, indent, stops)
        if chain is None:
            continue
        heads, end = chain
        amount = int(match.group(2)) + sunk.get(n, 0)
        for head in heads:
            target = _branch_charge(text, head + 1, len(indent) + 4, stops)
            sunk[target] = sunk.get(target, 0) + amount
        if text[heads[-1]] != indent + "else:":
            elses.setdefault(end, []).append((indent + "else:", f"{indent}    _spent += {amount}"))
        gone.add(n)
    if not gone:
        return None
    out, done, changed = [], 0, []
    for n in sorted(gone | sunk.keys() | elses.keys()):
        out.extend(text[done:n])
        done = n + 1
        for branch in sorted(elses.get(n, ()), key=lambda lines: -len(lines[0])):
            out.extend(branch)
            changed.append(len(out) - 1)
        if n == len(text):
            break
        line, amount = text[n], sunk.get(n)
        if n in gone:
            continue
        match = _CHARGE.fullmatch(line) if amount and "_spent += " in line else None
        if match is not None:
            changed.append(len(out))
            out.append(f"{match.group(1)}_spent += {int(match.group(2)) + amount}")
            continue
        if amount:
            changed.append(len(out))
            out.append(f"{' ' * (len(line) - len(line.lstrip(' ')))}_spent += {amount}")
        out.append(line)
    out.extend(text[done:])
    return out, changed


def _chain(text: list[str], first: int, indent: str, stops) -> tuple[list[int], int] | None:
    """(the head lines (`if`, `elif`, `else:`), the line after the last branch) of the IF
    chain of indentation `indent` that follows line `first - 1` after lines that are no
    barrier, when no head is a barrier; else None."""
    n, end, head = first, min(len(text), first + _LOOK_AHEAD), indent + "if "
    while n < end and not (text[n].startswith(head) and text[n].endswith(":")):
        if not text[n].startswith(indent) or text[n][len(indent)] == " ":
            return None         # (a line of another level)
        n += 1
    if n == end or any(stops.stop(k) for k in range(first, n)):
        return None             # (no IF near, or a line between that can raise or leave)
    end = len(text)
    heads, inner = [], indent + " "
    while n < end:
        line = text[n]
        if line.startswith(inner):
            n += 1
            continue
        if not heads or (line.startswith(indent + "elif ") or line == indent + "else:") \
                and text[heads[-1]] != indent + "else:":
            if stops.stop(n):
                return None
            heads.append(n)
            n += 1
            continue
        break
    return (heads, n) if heads else None


def _branch_charge(text: list[str], first: int, indent: int, stops) -> int:
    """The line of the branch starting at `first` (indentation `indent`) that takes a charge
    sunk into it: its first charge of that indentation after lines that are no barrier, else
    its first line."""
    for n in range(first, len(text)):
        line = text[n]
        if len(line) - len(line.lstrip(" ")) < indent:
            break
        if line.startswith(" " * indent + "_spent += ") and _CHARGE.fullmatch(line):
            return n
        if stops.stop(n):
            break
    return first


class _Stops:
    """Per line of the code, read once: whether it is a barrier (it can raise, check the
    budget or leave its block) and its indentation (a line less indented than two charges
    leaves their block)."""

    def __init__(self, text: list[str]):
        self.text = text
        self.barrier: dict[int, bool] = {}

    def stop(self, n: int) -> bool:
        """Whether line `n` is a barrier."""
        stop = self.barrier.get(n)
        if stop is None:
            stop = self.barrier[n] = _is_barrier(self.text[n])
        return stop

    def joinable(self, first: int, end: int, indent: int) -> bool:
        """Whether the lines `first` to `end - 1`, between two charges of one indentation,
        are of their block (no line less indented) and none is a barrier."""
        for n in range(first, end):
            if indent:
                head = self.text[n][:indent].lstrip(" ")      # (what the indentation holds but spaces)
                if head and not head[0].isspace():
                    return False
            if self.stop(n):
                return False
        return True


def _is_barrier(line: str) -> bool:
    return (line.endswith(":") and not _BRANCH.match(line)) or _LOOP.match(line) is not None \
        or any(word in line for word in _BARRIER_WORDS) and _BARRIER_WORD.search(line) is not None
