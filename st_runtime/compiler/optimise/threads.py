"""`threads`: a test of a local that every path into it has already decided is not made again.

An IF chain S1 followed by an IF chain S2 whose first test reads one local alone
(`if (v_X == 4):`, `if (v_X != 0):`, `if v_X:`, `if (not v_X):`, the shapes the `settle`
pass reads) tests that local on every path through S1, though each path may already tell
the answer: a branch of S1 set the local to a literal, or S1's own test of it let the path
in (its `== c` branch knows the value, a later clause knows the value is not c).  When every
path's end tells it, S2 runs at the end of each path instead, as that path would take it:
its first branch where the test holds, the rest of the chain (`elif` as `if`, or the ELSE's
body, or nothing) where it fails; S2's test is made nowhere (jump threading).  A path that
ends in a chain without ELSE gets one to hold what it runs then.

Exact: each path runs the same statements in the same order; the test left out is a
comparison of a Python local with a literal, or its truth, which reads nothing else and
cannot raise; no other code can set a Python local, and a line of the path that may set the
local (not to a literal, or inside a compound statement) makes it unknown, and S2 is kept.
A path that leaves early (RETURN, EXIT, a fault) skips what is put at its end, as it skipped
S2.  The charges are lines of the branches (cost.py charges a test in its branches), so they
move with them; the `charges` and `settle` passes then join each path's own.  A part of S2
longer than `SMALL` lines goes to one path at most, so the code grows by small parts only.
(SP_Controller's six axes: `IF NewFault = 0 THEN` (the axis's fault tests) `END_IF` each;
the path through an axis's tests that found nothing knows NewFault = 0 and runs the next
axis's tests at once, the paths that set a fault code know the next test fails and run its
charge: five tests a scan fewer.)
"""

from __future__ import annotations

import itertools
import re
from bisect import bisect_left, bisect_right

from ..pysrc import indentation
from . import margins
from .charges import LITERAL_STORE, LITERALS, LOCAL_TEST, may_set
from .halves import FAR

#: The longest part of S2 (in lines) that more than one path may run (a charge, a store).
SMALL = 4
#: The deepest indentation (spaces) a threaded line may get: CPython's tokenizer allows 100
#: levels; the code stays well inside it.
DEEPEST = 4 * 48

#: The most chains threaded in one body (each threading may copy small parts to many paths).
LIMIT = 64

_ELSE = "else:"


def thread(lines: list[str], start: int) -> bool:
    """The `threads` pass on the body from line `start`; whether it changed a line.  Each
    threading changes the lines of the two chains only: the lines before them and after them
    keep their indentation and their being candidates (each a property of its line alone), so
    only the changed lines are read again (the body's other lines once)."""
    text = lines[start:]
    candidates = _candidates(text, 0, len(text))
    if not candidates:
        return False
    indents = _indents(text)
    done, after = 0, 0
    while done < LIMIT:
        for m in candidates[bisect_left(candidates, after):]:
            threaded = _threaded(text, indents, m)
            if threaded is not None:
                out, indents, after, changed, end = threaded
                shift = len(out) - len(text)
                candidates = [*candidates[:bisect_left(candidates, after)], *_candidates(out, after, changed),
                              *(n + shift for n in candidates[bisect_left(candidates, end):])]
                text, done = out, done + 1
                break
        else:
            break
    lines[start:] = text
    return done > 0


# The `if` line of a chain whose first test reads a local alone (`LOCAL_TEST`'s shapes), with
# the line break before it: the pattern's first character a literal, the regex engine finds
# each line's start in C and tries the rest there only (`^` tried at every character: 3 to 5
# times the time).  The text searched starts with a line break.
_CANDIDATE = re.compile(r"\n *+if \(?(?:not )?v_\w+(?: (?:==|!=) -?\d+)?\)?:$", re.MULTILINE)


def _candidates(text: list[str], first: int, end: int) -> list[int]:
    """The lines from `first` to `end - 1` that open a chain testing a local alone (found in C)."""
    starts = list(itertools.accumulate(map((1).__add__, map(len, text[first:end])), initial=0))
    return [first + bisect_right(starts, match.start()) - 1
            for match in _CANDIDATE.finditer("\n" + "\n".join(text[first:end]))]


def _threaded(text: list[str], indents: list[int], m: int):
    """(the text with the chain opening at line `m` threaded into the chain before it, its
    lines' indentation, the line to look on from (the chain's first), the first line after the
    lines it changed, the first line after them in `text`), or None when it cannot be;
    `indents`: each line's indentation."""
    indent = indents[m]
    first = _chain_start_before(text, indents, m, indent)
    if first is None:
        return None
    test = LOCAL_TEST.fullmatch(text[m])
    local = test.group(2)
    if local not in "\n".join(text[first:m]):
        return None             # (no path through the chain before knows anything of it)
    ends = _chain_ends(text, indents, first, indent, None, local)
    if ends is None:
        return None
    end = _chain_end(text, indents, m, indent)
    taken, rest = _parts(text, indents, m, end, indent)
    verdicts = [_decided(test, facts) for _, _, _, facts in ends]
    if None in verdicts:
        return None
    for part, verdict in ((taken, True), (rest, False)):
        if len(part) > SMALL and verdicts.count(verdict) > 1:
            return None
    deepest = max((indentation(line) for line in taken + rest), default=0)
    if max(at for _, at, _, _ in ends) + deepest > DEEPEST:
        return None
    out = text[:m] + text[end:]
    # Inserted from the last place back (the earlier places keep their numbers), and at one
    # place from the last in the text back (`_place`).
    for (place, at, opener, _), verdict in sorted(zip(ends, verdicts), key=_place, reverse=True):
        part = taken if verdict else rest
        if not part:
            continue
        body = [" " * at + line for line in part]
        if opener is not None:
            body.insert(0, " " * opener + _ELSE)
        out[place:place] = body
    changed = len(out) - (len(text) - end)          # (the lines from `first` up to here are new)
    out_indents = [*indents[:first], *_indents(out[first:changed]), *indents[end:]]
    if _nearer(out, out_indents, first, indent):
        out_indents[first:changed] = _indents(out[first:changed])
    return out, out_indents, first, changed, end


def _nearer(text: list[str], indents: list[int], first: int, indent: int) -> bool:
    """The chain at `first`, if `if (v_X == c):` with a long first branch and a short ELSE, as
    `if (v_X != c):` with the two branches swapped (`==` and `!=` the other way round): the
    same branch runs for every number, and the test's jump is to a near line (halves.py: a jump
    past some 255 code units takes an EXTENDED_ARG, and CPython 3.11 then does not specialise
    the comparison before it; threading made the first branch long).  `indents`: each line's
    indentation; whether it swapped them."""
    test = LOCAL_TEST.fullmatch(text[first])
    if test is None or test.group(1) or test.group(3) is None:
        return False
    clauses = _clauses(text, indents, first, indent)
    if len(clauses) != 2 or text[clauses[1][0]].lstrip(" ") != _ELSE:
        return False
    (_, middle), (other, end) = clauses
    taken, otherwise = text[first + 1:middle], text[other + 1:end]
    if len(taken) > FAR >= len(otherwise):
        swapped = "!=" if test.group(3) == "==" else "=="
        text[first:end] = [f"{' ' * indent}if ({test.group(2)} {swapped} {test.group(4)}):", *otherwise,
                           " " * indent + _ELSE, *taken]
        return True
    return False


def _place(item) -> tuple:
    """Where an end's code goes in the text: by line, and at one line (a chain whose last clause
    ends with a chain, neither with an ELSE) the innermost clause's end first, then the ELSEs
    opened there from the innermost chain's out."""
    place, _, opener, _ = item[0]
    return (place, 0, 0) if opener is None else (place, 1, -opener)


def _chain_start_before(text: list[str], indents: list[int], m: int, indent: int) -> int | None:
    """The `if` line of the IF chain that ends right before line `m` at `indent`; None when the
    statement before it is no such chain (or there is none in its block)."""
    k = _back_to(indents, m - 1, indent)
    while k >= 0 and indents[k] == indent:
        head = text[k].lstrip(" ")
        if head.startswith("if ") and head.endswith(":"):
            return k
        if not (head.startswith("elif ") and head.endswith(":") or head == _ELSE):
            return None
        k = _back_to(indents, k - 1, indent)
    return None


def _back_to(indents: list[int], k: int, indent: int) -> int:
    """The last line from `k` back not deeper than `indent` (-1: none)."""
    found = margins.first_passing(indents, k, indent.__ge__, -1)
    return -1 if found is None else found


def _indents(text: list[str]) -> list[int]:
    """Each line's indentation (found in C)."""
    return margins.widths(text)


def _clauses(text: list[str], indents: list[int], first: int, indent: int) -> list[tuple[int, int]]:
    """The (header line, end) of each clause of the IF chain opening at `first`."""
    clauses = []
    n = first
    while True:
        # (the first later line not deeper than the chain, found in C)
        end = margins.first_passing(indents, n + 1, indent.__ge__)
        if end is None:
            end = len(text)
        clauses.append((n, end))
        if end < len(text) and indents[end] == indent \
                and (text[end].lstrip(" ").startswith("elif ") or text[end].lstrip(" ") == _ELSE):
            n = end
            continue
        return clauses


def _chain_end(text: list[str], indents: list[int], first: int, indent: int) -> int:
    return _clauses(text, indents, first, indent)[-1][1]


def _parts(text: list[str], indents: list[int], m: int, end: int, indent: int) -> tuple[list[str], list[str]]:
    """(the first branch's body, the rest of the chain as a statement), their indentation taken
    off: what a path runs where the first test holds and where it fails."""
    clauses = _clauses(text, indents, m, indent)
    header, clause_end = clauses[0]
    body_indent = indentation(text[header + 1])
    taken = [line[body_indent:] for line in text[header + 1:clause_end]]
    if len(clauses) == 1:
        return taken, []
    second = clauses[1][0]
    if text[second].lstrip(" ") == _ELSE:
        else_indent = indentation(text[second + 1])
        return taken, [line[else_indent:] for line in text[second + 1:end]]
    rest = [line[indent:] for line in text[second:end]]
    rest[0] = rest[0][2:]           # (`elif` -> `if`)
    return taken, rest


# A path's facts about the local: None (nothing), ("is", v) or ("not", v), v an int.

def _chain_ends(text, indents, first, indent, facts, local):
    """The ends of the paths through the IF chain opening at `first`: (line where its code
    goes, its indentation, the indentation of an ELSE to open there or None, facts); None
    when a path's end cannot be told apart (a clause whose body is not deeper)."""
    ends = []
    rest = facts
    has_else = False
    for header, end in _clauses(text, indents, first, indent):
        line = text[header]
        if line.lstrip(" ") == _ELSE:
            taken = rest
            has_else = True
        else:
            test = LOCAL_TEST.fullmatch(line)
            if test is not None and test.group(2) == local:
                taken, rest = _split(test, rest)
            elif may_set(local, line):
                taken = rest = None
            else:
                taken = rest
        if header + 1 >= end or indents[header + 1] <= indent:
            return None
        inner = _block_ends(text, indents, header + 1, end, taken, local)
        if inner is None:
            return None
        ends += inner
    if not has_else:
        step = indents[first + 1] - indent
        ends.append((_chain_end(text, indents, first, indent), indent + step, indent, rest))
    return ends


def _block_ends(text, indents, first, end, facts, local):
    """The ends of the paths through the block of lines `first` to `end - 1`."""
    indent = indents[first]
    n = first
    while n < end:
        line = text[n]
        head = line.lstrip(" ")
        if head.startswith("if ") and line.endswith(":"):
            chain_end = _chain_end(text, indents, n, indent)
            if chain_end >= end:
                return _chain_ends(text, indents, n, indent, facts, local)
            facts = _after(text, n, chain_end, facts, local)
            n = chain_end
            continue
        statement_end = n + 1
        while statement_end < end and indents[statement_end] > indent:
            statement_end += 1
        facts = _after(text, n, statement_end, facts, local)
        n = statement_end
    return [(end, indent, None, facts)]


def _after(text, first, end, facts, local):
    """What is known of the local after the statement on lines `first` to `end - 1`."""
    if end == first + 1:
        store = LITERAL_STORE.fullmatch(text[first])
        if store is not None and store.group(1) == local:
            literal = store.group(2)
            return "is", LITERALS[literal] if literal in LITERALS else int(literal)
    if facts is not None and any(local in line and may_set(local, line) for line in text[first:end]):
        return None
    return facts


def _split(test, facts):
    """(the facts where the clause's test holds, those where it fails)."""
    equal, constant = _compared(test)
    known = _known(facts)
    same = known or ("is", constant)
    other = known or ("not", constant)
    return (same, other) if equal else (other, same)


def _compared(test) -> tuple[bool, int]:
    """(whether the test holds where the local equals the constant, the constant): `if v_X:`
    holds where it is not 0, `if (not v_X):` where it is (a number's truth)."""
    negated, _, operator, literal = test.groups()
    if operator is None:
        return bool(negated), 0
    return (operator == "==") != bool(negated), int(literal)


def _known(facts):
    return facts if facts is not None and facts[0] == "is" else None


def _decided(test, facts) -> bool | None:
    """Whether the test holds on a path with `facts`; None when the facts do not tell."""
    if facts is None:
        return None
    equal, constant = _compared(test)
    kind, value = facts
    if kind == "is":
        same = value == constant
    elif value == constant:
        same = False
    else:
        return None
    return same if equal else not same
