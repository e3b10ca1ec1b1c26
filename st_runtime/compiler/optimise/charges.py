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

An IF chain's ELSE charge goes the other way, up into the chain before it, when that one's
every path opens with a charge (`_lifted`): its six legs' tests charge their ELSE paths once.
The `settle` pass (`settled`) then writes a charge made where `_spent`'s value is known as a
store of that value.
"""

from __future__ import annotations

import functools
import itertools
import re
from bisect import bisect_left, bisect_right
from operator import is_not, itemgetter, not_

from ..pysrc import indentation
from . import margins, mentions

_CHARGE = re.compile(r"( *+)_spent \+= (\d+)")
# A line that can raise, check the budget or leave the level: one holding a barrier word
# (`_holds_barrier_word`), a loop's head, or a line opening a block other than a branch of an
# IF (`try:`, `for ...:`; not `if`, `elif`, `else:`).
_LOOP = re.compile(r" *+(?:for|while|with)\b")
_BRANCH = re.compile(" *+(?:if |elif |else:)")


def merge(lines: list[str], start: int) -> None:
    """Add each charge that may join the one before it in its level to that one."""
    joined = "\n".join(lines[start:])
    if joined.count("_spent += ") < 2:
        return                  # (fewer than two charges: none to join, no line to read)
    text = joined.split("\n")
    _out_of_try(text)
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
    lines[start:] = _lifted(_sunk([line for line in new if line is not None] if dropped else new))


def _out_of_try(text: list[str]) -> None:
    """Each charge that opens the body of a `try` (more lines after it) before the `try`
    instead: nothing runs between the two places, and a charge cannot raise, so every read
    of `_spent` (the handler's, the `finally`'s) sees the same; before it, the charge may
    join the one of the level above (`merge`): TRJ_OceanWave's body after its latch.  Not
    the `try` that holds the whole body (its charges join one another inside it)."""
    # (`compress` reads each line's end as the loop comes to it, after a swap before it: a
    # charge moved out of a `try` leaves that `try` the next line, read again as the loop did)
    for n in itertools.compress(itertools.count(), map(str.endswith, itertools.islice(text, len(text) - 2),
                                                       itertools.repeat("try:"))):
        line = text[n]
        if line.strip() == "try:" and "_spent += " in text[n + 1] \
                and text[n - 1].strip() != "_spent = 0":       # (the body's own `try`: its level joins)
            match = _CHARGE.fullmatch(text[n + 1])
            indent = indentation(line)
            if match is not None and len(match.group(1)) == indent + 4 and indentation(text[n + 2]) > indent:
                text[n], text[n + 1] = f"{line[:indent]}_spent += {match.group(2)}", line


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
            out.append(f"{' ' * indentation(line)}_spent += {amount}")
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
    heads, inner, size = [], indent + " ", len(indent) + 1
    while n < end:
        line = text[n]
        if line[:size] == inner:    # (`startswith` parses its arguments: four times the cost)
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
        if indentation(line) < indent:
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
    return (line[-1:] == ":" and not _BRANCH.match(line)) or _LOOP.match(line) is not None \
        or _holds_barrier_word(line)


def _holds_barrier_word(line: str) -> bool:
    """Whether `line` holds a barrier word: a part of a name anywhere (the handler's `_ctx`,
    the overrun test, an FB's `.execute(`, a FUNCTION's `_fn_`), or a keyword standing as a
    word (`try:`, `except`, `finally:`, `return`, `break`, `continue`: no word character
    before it, nor after one that ends with a letter).  Substring tests in C, written out
    (a generator over the words cost as much again), and a line holding a keyword's letters
    then read in Python: the regex engine's search of the words' alternation (a word
    boundary first, so tried at every character) cost 100,000 machine instructions a line."""
    if "_ctx" in line or "_overrun" in line or ".execute(" in line or "_fn_" in line:
        return True
    return ("try:" in line or "except" in line or "finally:" in line or "return" in line or "break" in line
            or "continue" in line) and any(mentions.places(line, word, attributes=True) for word in _KEYWORDS)


_KEYWORDS = ("try:", "except", "finally:", "return", "break", "continue")


def _lifted(text: list[str]) -> list[str]:
    """`text` with the ELSE charge of an IF chain B that follows another chain A moved into A.

    When every path through A ends in a branch that opens with a charge (or with a chain
    whose every branch does, and so on), nothing in A nor between A and B nor in B's tests
    can raise, check the budget or leave, and B's ELSE opens with a charge `_spent += E`
    and each of B's other branches with a charge it may take: E is added to each of A's
    opening charges and taken from each of B's others, and B's ELSE charges nothing.  Every
    path charges the same total (A's +E, then B's ELSE 0, or B's other branch -E) and no
    read of `_spent` lies between the places; no path charges more often, B's ELSE path
    once less.  Chains are taken from the last to the first, so a run of them charges its
    ELSE paths once, in the first: SP_Controller's six legs' tests (`IF NOT LegInStroke[k]
    ... ELSIF ABS(...) > 0.25 ... END_IF` in the unrolled FOR, each with the sunk ELSE
    that charges the tests).  A negative amount is written `_spent -= N`."""
    stops = _Stops(text)
    amounts: dict[int, int] = {}            # line of a charge -> its amount now
    chains = [n for n, line in enumerate(text) if line.endswith("else:") and n + 1 < len(text)
              and (charge := _CHARGE.fullmatch(text[n + 1])) and len(charge.group(1)) == indentation(line) + 4]
    shape = _Shape(text) if chains else None
    for else_line in reversed(chains):
        _lift(text, else_line, stops, amounts, shape)
    if not amounts:
        return text
    out, done = [], 0
    for n in sorted(amounts):           # (the lines between copied as they are)
        out.extend(text[done:n])
        done, line, amount = n + 1, text[n], amounts[n]
        if amount:
            indent = line[:indentation(line)]
            out.append(f"{indent}_spent += {amount}" if amount > 0 else f"{indent}_spent -= {-amount}")
        elif out[-1].strip() == "else:" and not _opens_block(text, n, indentation(out[-1])):
            out.pop()                   # (an ELSE left with nothing)
        elif indentation(out[-1]) < indentation(line) and not _opens_block(text, n, indentation(line) - 4):
            out.append(line[:indentation(line)] + "pass")
    out.extend(text[done:])
    return out


def _opens_block(text: list[str], n: int, indent: int) -> bool:
    """Whether the branch whose line `n` is (a dropped charge) holds more lines after it."""
    return n + 1 < len(text) and indentation(text[n + 1]) > indent


def _lift(text: list[str], else_line: int, stops, amounts: dict[int, int], shape: "_Shape") -> None:
    """`_lifted` for the chain B whose ELSE is on line `else_line`, if it may."""
    indents, before = shape.indent, shape.before
    indent = indents[else_line]
    heads = _heads_back(text, else_line, indent, shape)
    if heads is None or any(stops.stop(h) for h in heads):
        return
    b_entries = []
    for head in heads[:-1]:
        entries = _entries(text, head + 1, indent + 4, stops, shape)
        if entries is None:
            return
        b_entries += entries
    n = before[heads[0]]                # back over lines between A and B: none a barrier
    while n >= 0 and indents[n] == indent and not text[n].endswith(":"):
        if stops.stop(n):
            return
        n = before[n]
    if n < 0 or indents[n] != indent or text[n].strip() != "else:":
        return                          # (the statement before is not a chain with ELSE)
    a_heads = _heads_back(text, n, indent, shape)
    if a_heads is None or any(stops.stop(k) for k in range(a_heads[0], heads[0])):
        return
    a_entries = []
    for head in a_heads:
        entries = _entries(text, head + 1, indent + 4, stops, shape)
        if entries is None:
            return
        a_entries += entries
    charge = else_line + 1
    moved = amounts.get(charge, int(_CHARGE.fullmatch(text[charge]).group(2)))
    for k in a_entries:
        amounts[k] = amounts.get(k, _amount(text[k])) + moved
    for k in b_entries:
        amounts[k] = amounts.get(k, _amount(text[k])) - moved
    amounts[charge] = 0


def _amount(line: str) -> int:
    return int(_CHARGE.fullmatch(line).group(2))


def _heads_back(text: list[str], else_line: int, indent: int, shape: "_Shape") -> list[int] | None:
    """The head lines (`if`, `elif`s, `else:`) of the chain whose ELSE is on `else_line`."""
    heads, n = [else_line], shape.before[else_line]
    while n >= 0 and shape.indent[n] == indent and text[n].endswith(":"):
        body = text[n].lstrip(" ")
        if body.startswith("elif "):
            heads.insert(0, n)
        elif body.startswith("if "):
            heads.insert(0, n)
            return heads
        else:
            return None
        n = shape.before[n]
    return None


def _entries(text: list[str], first: int, indent: int, stops, shape: "_Shape") -> list[int] | None:
    """The charges that open every path through the branch starting at line `first`
    (indentation `indent`): its first charge after lines that are no barrier, or those of
    a chain with ELSE that comes first, each of whose branches has such; None if a path has
    none (or a barrier comes first)."""
    n, indents = first, shape.indent
    while n < len(text) and indents[n] == indent:
        line = text[n]
        if _CHARGE.fullmatch(line):
            return [n]
        if stops.stop(n):
            return None
        if line.endswith(":"):
            if not line.lstrip().startswith("if "):
                return None
            heads = [n]
            end = shape.after[n]
            while end < len(text) and indents[end] == indent and text[end].lstrip().startswith(("elif ", "else:")):
                heads.append(end)
                end = shape.after[end]
            if text[heads[-1]].strip() != "else:":
                return None
            found = []
            for head in heads:
                entries = _entries(text, head + 1, indent + 4, stops, shape)
                if entries is None:
                    return None
                found += entries
            return found
        n += 1
    return None


def settle(lines: list[str], start: int) -> None:
    """The `settle` pass: `settled` of the body from line `start`."""
    lines[start:] = settled(lines[start:])


def settled(text: list[str]) -> list[str]:
    """`text` with each charge made where `_spent`'s value is known as a store of the sum.

    The body sets `_spent = 0`; until the lines' paths join with different totals, the value
    at each charge is a constant, so `_spent += N` there is `_spent = <value + N>`: the same
    int, read by nothing in between, without the addition that makes a new int and frees the
    old one (in CPython 3.11 an int beyond the cached small ones: about 200 machine
    instructions a charge).  The value is followed into every branch of an IF chain and on
    after it when all its paths (an ELSE-less chain's untaken one too) end with one total;
    through a `try` statement that sets `_spent` nowhere; not into a loop or a handler, nor
    past any other line that sets `_spent` (a fast body's take-backs, a loop's charge of all
    its iterations).  (SP_Controller's first charge and its first axis's fault tests, IK's
    first charge, TRJ_OceanWave's ELSE of its enable edge.)

    Where paths join with different totals, each total is kept with what the path knows of
    the locals it set to a literal (`_Paths`): a later test of such a local (`if (v_X == 4):`,
    `if v_X:`, their negations) reads each path's own value and takes into a branch only the
    paths that reach it.  (SP_Controller's axes: `NewFault := 0`, then each axis's fault
    tests, whose every branch but the ELSE sets NewFault to a code; the next axis's tests run
    only `IF NewFault = 0`, which only the ELSE path reaches: its total is known.)"""
    if not any(map(str.__contains__, text, itertools.repeat("_spent += "))):
        return text             # (no charge: the walk replaces only `_CHARGE` lines)
    straight = _straight(text)
    if straight is not None:
        return straight
    out = list(text)
    try:
        _Settle(out).block(1 if out and out[0].startswith("def ") else 0, None, ended=False)
    except _Unread:
        return text             # (a line of a shape the walk does not know: nothing changed)
    return out


def _straight(text: list[str]) -> list[str] | None:
    """`settled(text)` of a body whose every charge stands at the top level of the `try` after
    its `_spent = 0`: each charge there is the running total, as the walk makes it (no line
    of the body but those charges sets `_spent`, so every path reaches each charge with one
    total).  None for any other body (the walk then), and for a shape the walk refuses
    (`_Unread`): a line more indented than its block's without a compound line before it, a
    line less indented than its block's and not at an open block's indentation, an empty line.
    One look at the lines that name `_spent` (`str.find`) and one at the indentations,
    instead of the walk's tables (its fixed cost was most of a small body's `settle`)."""
    first = 1 if text[:1] and text[0].startswith("def ") else 0      # (as `settled` starts the walk)
    if not text[first:first + 1] or not text[first].startswith(_LEVEL) or text[first][4:5] == " ":
        return None
    flat = "".join(text)
    if _DEEPER_SPENT in flat:
        return None             # (a line deeper than the body's top level names `_spent`: found in C)
    ends = list(itertools.accumulate(map(len, text)))
    holding = _lines_holding(flat, ends, "_spent")
    if len(holding) < 3 or text[holding[0]] != _ZERO or text[holding[-1]] != _FLUSH:
        return None
    zero = holding[0]
    if text[zero + 1:zero + 2] != [_OPEN] or \
            not all(map(str.startswith, text[first:zero], itertools.repeat(_LEVEL))):
        return None
    charges = holding[1:-1]
    matches = list(map(_TOP_CHARGE.fullmatch, map(text.__getitem__, charges)))
    if None in matches:
        return None
    last = _top_level_end(text, zero + 2)
    if last is None or text[last] != _FINALLY or charges and charges[-1] > last \
            or not all(map(str.startswith, text[last + 1:], itertools.repeat(_BODY_LEVEL))):
        return None
    out = list(text)
    total = 0
    for n, match in zip(charges, matches):
        total += int(match.group(1))
        out[n] = f"{_BODY_LEVEL}_spent = {total}"
    return out


def _top_level_end(text: list[str], first: int) -> int | None:
    """The first line from `first` (the first of the `try`'s body) back at `_LEVEL`, when the
    lines before it nest as the walk reads them (see `_straight`) and the body's first line
    is at `_BODY_LEVEL`; None when they do not."""
    depths, opened = [len(_LEVEL)], True
    for n in range(first, len(text)):
        line = text[n]
        depth = len(line) - len(line.lstrip(" "))
        if depth == len(line):
            return None
        if depth > depths[-1]:
            if not opened or (n == first and depth != len(_BODY_LEVEL)):
                return None
            depths.append(depth)
        else:
            if opened:
                return None
            while depth < depths[-1]:
                depths.pop()
            if depth != depths[-1]:
                return None
            if len(depths) == 1:
                return n
        opened = line[-1] == ":" and _COMPOUND.fullmatch(line) is not None
    return None


_LEVEL, _BODY_LEVEL = " " * 4, " " * 8
_ZERO, _OPEN, _FINALLY = _LEVEL + "_spent = 0", _LEVEL + "try:", _LEVEL + "finally:"
_FLUSH = _BODY_LEVEL + "_ctx.budget -= _spent"
_DEEPER_SPENT = _BODY_LEVEL + " _spent"
_TOP_CHARGE = re.compile(r" {8}_spent \+= (\d+)")


class _Unread(Exception):
    """A line more indented than its block's statements (no such line is generated)."""


_SETS = re.compile(r"\s*+_spent\s*+(?:[-+*]?=)")        # a line that sets `_spent`
_COMPOUND = re.compile(r" *+(if|elif|else|try|except|finally|for|while|with|def)\b.*:$")
# `v_X = 4`, `v_X = True`: a local set to a literal (a Python name the body assigns is local).
LITERAL_STORE = re.compile(r" *+(v_\w+) = (-?\d+|True|False)")
# A clause's test of a local alone: `if v_X:`, `elif (not v_X):`, `if (v_X == 4):`, `!=`.
LOCAL_TEST = re.compile(r" *+(?:if|elif) \(?(not )?(v_\w+)(?: (==|!=) (-?\d+))?\)?:")
LITERALS = {"True": 1, "False": 0}
_FIRST, _SECOND = itemgetter(0), itemgetter(1)
_IS_SOMETHING = functools.partial(is_not, None)
#: At most this many paths are told apart; beyond it only a total they all share is kept.
_PATH_CAP = 64
_UNKNOWN = {None}


class _Paths(frozenset):
    """What the walk knows where it stands: a set of paths, each `(total, facts)`: `_spent`'s
    value on that path (None: not known) and, as sorted `(local, value)` pairs, the locals it
    last set to a literal (a bool as 0 or 1).  Empty: no path reaches the place."""

    def total(self) -> int | None:
        """The value every path gives `_spent`, or None (no path, or not one value)."""
        totals = set(map(_FIRST, self))
        return totals.pop() if len(totals) == 1 and None not in totals else None

    def charged(self, amount: int) -> "_Paths":
        totals = list(map(_FIRST, self))
        if None in totals:
            return _Paths((None if total is None else total + amount, facts) for total, facts in self)
        return _Paths(zip(map(amount.__add__, totals), map(_SECOND, self)))

    def zeroed(self) -> "_Paths":
        return _Paths(zip(itertools.repeat(0), map(_SECOND, self)))

    def told(self, local: str, value: int | None) -> "_Paths":
        """Each path with `local` set to `value` (None: to what the walk does not know)."""
        return self._refacted(lambda facts: _told(facts, local, value))

    def locals(self) -> frozenset:
        """The locals some path knows the value of."""
        return frozenset(map(_FIRST, itertools.chain.from_iterable(map(_SECOND, self))))

    def forgetting(self, line: str) -> "_Paths":
        """Each path without what it knew of a local that `line` may set (`may_set`)."""
        lost = {local for local in self.locals() if local in line and may_set(local, line)}
        if not lost:
            return self
        return self._refacted(lambda facts: tuple(fact for fact in facts if fact[0] not in lost))

    def taking(self, local: str, test, held: int | None) -> "_Paths":
        """The paths on which `test(value of local)` may hold; a path that does not know the
        value knows it is `held` there (None: not one value)."""
        def fate(facts: tuple) -> tuple | None:
            value = dict(facts).get(local)
            if value is None:
                return facts if held is None else _told(facts, local, held)
            return facts if test(value) else None
        return self._refacted(fate)

    def _refacted(self, fate) -> "_Paths":
        """Each path with its facts `fate(facts)`, or without the path where that is None;
        `fate` asked once for each distinct facts (many paths share theirs: they differ by
        their totals), the paths rebuilt in C."""
        fates = {facts: fate(facts) for facts in set(map(_SECOND, self))}
        facts = list(map(fates.__getitem__, map(_SECOND, self)))
        pairs = zip(map(_FIRST, self), facts)
        return _Paths(itertools.compress(pairs, map(_IS_SOMETHING, facts)) if None in fates.values() else pairs)


def may_set(local: str, line: str) -> bool:
    """Whether `line` may set the Python local `local`: it names it as a target (`=`, `:=`,
    an augmented assignment, before a comma: a tuple's), or it is a line that binds names
    otherwise (`for`, `with ... as`, `except ... as`, `del`) and names it at all."""
    found = mentions.places(line, local)
    if not found:
        return False
    if _BINDS.match(line) or " as " in line:
        return True
    after = len(local)
    return any(_TARGET.match(line, at + after) for at in found)


# What follows a local that a line sets: an assignment's operator or a comma (a tuple's).
_TARGET = re.compile(r"\s*+(?::=|(?:[-+*/%&|^@]|//|\*\*|>>|<<)?=(?!=)|,)")
_BINDS = re.compile(r" *+(?:for|with|del|async|import|from|global|nonlocal|class|def|lambda)\b")


def _told(facts: tuple, local: str, value: int | None) -> tuple:
    others = tuple(fact for fact in facts if fact[0] != local)
    return others if value is None else tuple(sorted(others + ((local, value),)))


def _start(value: "_Paths | None") -> "_Paths":
    return _Paths({(None, ())}) if value is None else value


def _kept(paths: "_Paths") -> "_Paths | None":
    """`paths` as the walk carries them: None when nothing can be replaced until a
    `_spent = 0` (no path knows its total; or not one total and no path knows a local,
    which alone could tell the totals apart: every later line acts on all paths alike), one
    path of the total they share beyond `_PATH_CAP`."""
    if paths:
        totals = set(map(_FIRST, paths))
        if totals == _UNKNOWN or not any(map(_SECOND, paths)) and (len(totals) > 1 or None in totals):
            return None
    if len(paths) > _PATH_CAP:
        total = paths.total()
        return None if total is None else _Paths({(total, ())})
    return paths


def _taken(line: str, paths: "_Paths | None") -> tuple["_Paths | None", "_Paths | None"]:
    """(the paths that may take the clause on `line`, those that go on past its test): a test
    of a local alone (`LOCAL_TEST`) is read on each path that knows the local's value, and
    tells one that does not what `==` (or a false `!=`) found; any other test takes every
    path both ways, without what they knew of a local it names (it may set one: `:=`)."""
    if paths is None or line.strip() == "else:":
        return paths, _Paths()
    test = LOCAL_TEST.fullmatch(line)
    if test is None:
        paths = paths.forgetting(line)
        return paths, paths
    negated, local, operator, literal = test.groups()
    if operator is None:
        holds = (lambda value: value == 0) if negated else (lambda value: value != 0)
        return paths.taking(local, holds, None), paths.taking(local, lambda value: not holds(value), None)
    equal = (operator == "==") != bool(negated)        # (the clause is taken when the two are equal)
    constant = int(literal)
    if equal:
        return (paths.taking(local, lambda value: value == constant, constant),
                paths.taking(local, lambda value: value != constant, None))
    return (paths.taking(local, lambda value: value != constant, None),
            paths.taking(local, lambda value: value == constant, constant))


class _Settle:
    """`settled`'s walk: each block's lines in turn, with what is known of `_spent` (`_Paths`;
    None: nothing), replacing the charges it can.  Once nothing is known, what comes next that
    may be replaced is after a `_spent = 0` of the same block: the walk goes there at once,
    or to the block's end, or (a block whose end no one reads: the outermost, a `try`'s
    body) stops.  Each line's indentation is read once; a statement's end only when asked."""

    def __init__(self, text: list[str]):
        self.text = text
        flat = "".join(text)
        self.indent = _indents(text, margins.stripped(text, flat))
        self.after = _Nearest(self.indent, 1)     # (where a statement or clause ends)
        ends = list(itertools.accumulate(map(len, text)))     # (where each line ends in `flat`)
        # The locals a clause tests alone: only what a path knows of these may tell it apart.
        self.tested = {test.group(2) for n in _lines_holding(flat, ends, "if ")
                       if (test := LOCAL_TEST.fullmatch(text[n]))}
        # The lines that set `_spent`, and those that name a tested local (a substring): a
        # path's facts are of tested locals only, so any other line keeps them as they are.
        # (The walk reads only these lines of a region.)
        self.setting = [n for n in _lines_holding(flat, ends, "_spent") if _SETS.match(text[n])]
        self.sets_spent = set(self.setting)
        self.names = set().union(*(_lines_holding(flat, ends, local) for local in self.tested))
        self.naming = sorted(self.names)
        self.read = self.sets_spent | self.names      # (the lines `_simple` may act on)

    def block(self, n: int, value: "_Paths | None", ended: bool = True) -> tuple[int, "_Paths | None"]:
        """Read the block whose first line is `n` (its indentation: that line's); the line
        after it and what is known at its end.  `ended=False`: the caller reads neither, and
        the walk stops where nothing more can be replaced."""
        text, indents = self.text, self.indent
        indent = indents[n] if n < len(text) else 0
        while n < len(text) and indents[n] >= indent:
            if indents[n] > indent:
                raise _Unread(text[n])
            if value is None and text[n] != " " * indent + "_spent = 0":
                n = self._known_again(n, indent, ended)
                continue
            if value is not None and not value:        # (no path reaches the rest of the block)
                n = self._known_again(n, indent, True)
                continue
            line = text[n]
            head = _COMPOUND.fullmatch(line) if line[-1:] == ":" else None
            if head is None:
                if n in self.read:
                    value = self._simple(n, value)
                n += 1
            elif head.group(1) == "if":
                n, value = self._chain(n, indent, value)
            elif head.group(1) == "try":
                n, value = self._try(n, indent, value)
            else:                       # a loop, `with`, `def`: not followed into
                end = self.after[n]
                value = None if self._sets(n, end) else self._forgetting(value, n, end)
                n = end
        return n, value

    def _known_again(self, n: int, indent: int, ended: bool) -> int:
        """Where the walk of a block goes on from its statement on line `n` when nothing is
        known: its next `_spent = 0` of the block's indentation (no line between less
        indented), else the block's end (`ended`) or past the text's end (not `ended`).
        (Hopping from statement to statement there replaces nothing.)"""
        text, indents = self.text, self.indent
        try:
            zero = text.index(" " * indent + "_spent = 0", n + 1)
        except ValueError:
            zero = None
        if zero is not None and min(indents[n:zero]) >= indent:
            return zero
        if not ended and zero is None:
            return len(text)
        # (the first later line less indented than the block, found in C)
        found = margins.first_passing(indents, n + 1, indent.__gt__)
        return len(text) if found is None else found

    def _sets(self, first: int, end: int) -> bool:
        """Whether a line from `first` to `end - 1` sets `_spent`."""
        setting = self.setting
        k = bisect_left(setting, first)
        return k < len(setting) and setting[k] < end

    def _forgetting(self, value: "_Paths | None", first: int, end: int) -> "_Paths | None":
        """`value` without what it knew of a local named on a line from `first` to `end - 1`."""
        if value is not None:
            naming, text = self.naming, self.text
            for k in range(bisect_left(naming, first), bisect_left(naming, end)):
                value = value.forgetting(text[naming[k]])
        return value

    def _simple(self, n: int, value: "_Paths | None") -> "_Paths | None":
        """What is known after the simple statement on line `n`, one that sets `_spent` or
        names a tested local (any other keeps what is known)."""
        line = self.text[n]
        if n not in self.sets_spent:
            store = LITERAL_STORE.fullmatch(line)
            if store is not None and store.group(1) in self.tested:
                literal = store.group(2)
                return _start(value).told(store.group(1), LITERALS.get(literal) if literal in LITERALS
                                          else int(literal))
            return value if value is None else value.forgetting(line)
        match = _CHARGE.fullmatch(line)
        if line.strip() == "_spent = 0":
            return _start(value).zeroed()
        if match is None or value is None:
            return None
        total = value.total()
        if total is not None:
            self.text[n] = f"{match.group(1)}_spent = {total + int(match.group(2))}"
        return _kept(value.charged(int(match.group(2))))

    def _chain(self, n: int, indent: int, value: "_Paths | None") -> tuple[int, "_Paths | None"]:
        """An IF chain from its `if` line: each branch read with the paths that may take it
        (`_taken`); after the chain, the paths of every branch's end (and, without ELSE, those
        that took no branch)."""
        ends, text, rest, has_else = [], self.text, value, False
        while True:
            taken, rest = _taken(text[n], rest)
            n, end = self.block(n + 1, taken)
            ends.append(end)
            if n < len(text) and self.indent[n] == indent and text[n].lstrip().startswith(("elif ", "else:")):
                has_else = text[n].strip() == "else:"
                continue
            break
        if not has_else:
            ends.append(rest)
        if value is None or any(end is None for end in ends):
            return n, None
        return n, _kept(_Paths(frozenset().union(*ends)))

    def _try(self, n: int, indent: int, value: "_Paths | None") -> tuple[int, "_Paths | None"]:
        """A `try` statement: its body read with `value`, its handlers with none; `value`
        after it when nothing in it sets `_spent` (without what it knew of a local the
        statement names)."""
        end, _ = self.block(n + 1, value)       # (where its body ends: its first handler)
        body = self.indent[n + 1] if n + 1 < len(self.text) else 0
        if not body > indent >= (self.indent[end] if end < len(self.text) else 0):
            end = self.after[n]        # (a body not more indented than its `try`: no Python)
        while end < len(self.text) and self.indent[end] == indent \
                and self.text[end].lstrip().startswith(("except", "else:", "finally:")):
            end = self.after[end]
        return end, None if self._sets(n, end) else self._forgetting(value, n, end)


def _indents(text: list[str], stripped: list[str] | None = None) -> list[int]:
    """Each line's indentation (`indentation`: its leading spaces), of every line in C (the
    walks read every line's); an empty line's is 1 << 20, more than any line's.  `stripped`:
    `margins.stripped(text)`, when the caller has it."""
    indents = margins.widths(text, stripped)
    if "" in text:
        for n in itertools.compress(itertools.count(), map(not_, text)):
            indents[n] = 1 << 20
    return indents


def _lines_holding(flat: str, ends: list[int], part: str) -> list[int]:
    """The lines that hold `part`, in order: each place of it in `flat` (the lines joined
    without a break; `ends`: where each ends there) found by `str.find`, its line by
    bisection (a place across two lines is none), so that only the places are read in
    Python, not every line."""
    found, size = [], len(part)
    at = flat.find(part)
    while at >= 0:
        n = bisect_right(ends, at)
        if at + size <= ends[n]:
            found.append(n)
            at = flat.find(part, ends[n])
        else:
            at = flat.find(part, at + 1)
    return found


class _Shape:
    """The block structure of the code's lines: each line's indentation, read once, and,
    found when asked, the first later line not more indented (`after`: where a clause or
    statement ends) and the last earlier one (`before`), so that a walk hops over a nested
    block at once."""

    def __init__(self, text: list[str]):
        self.indent = _indents(text)
        self.after = _Nearest(self.indent, 1)
        self.before = _Nearest(self.indent, -1)


class _Nearest:
    """`nearest[n]`: the first line from line `n` in one direction (`step` 1: later, -1:
    earlier) that is not more indented than `n`; past the last line (the count of lines, or
    -1) when there is none.  A scan over the lines between, which a walk asks of a few
    lines only (a table of every line cost more than the walks that read it)."""

    def __init__(self, indent: list[int], step: int):
        self.indent, self.step = indent, step

    def __getitem__(self, n: int) -> int:
        indent, step = self.indent, self.step
        depth, m = indent[n], n + step
        if not (0 <= m < len(indent) and indent[m] > depth):
            return m            # (most often the next line: no scan set up)
        found = margins.first_passing(indent, m + step, depth.__ge__, step)     # (the scan in C)
        return (len(indent) if step == 1 else -1) if found is None else found
