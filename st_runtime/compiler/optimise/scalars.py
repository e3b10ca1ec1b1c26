"""`scalars`: a fast FUNCTION's in-out array elements kept in Python locals (scalar replacement).

The LU's fast copy, unrolled, reads and stores `v_MATRIX[k]` at literal indices hundreds of
times a call (a subscript each: the list, the index, the lookup).  In the fast copy those
elements live in locals `v_MATRIX_ek` instead, and the list is brought up to date only where
something may look at it:

* before a line that reads the list at an index that is data, or names it whole, or names
  another list that may be the same one (an in-out, an input or a global array of as many
  elements: a caller may pass one array twice), the elements stored since (dirty) are
  written back;
* after a line that stores into the list at a data index (or into such another list, or
  names either whole), every local is stale: the list is read again (one unpack of all
  its elements) at the next use outside a branch, and used as it is inside one;
* before a `return`, `break`, `continue` or `raise`, a line that names `_ctx` (code that
  may record a fault, which may end the scan), at the end of the fast copy, and at the
  start of a fault handler (before `_ctx.fault`), the dirty elements are written back,
  so every reader, a fault's too, sees the list as the exact code leaves it.  A handler
  starts with the elements held at every point of its `try` body.

The same operations on the same values in the same order, on locals instead of list slots:
results, faults (a division or an index fault inside a `try` raises before its store, as
before) and charges (the `_spent` lines are not touched) are the same.  The pass applies to a
FUNCTION (its locals are its own, a call's lists live no longer than it) whose body calls no
ST code (a callee could reach the list through a global), dereferences no pointer, and whose
other aggregate variables that could be the list are plain arrays of elementary elements;
lists of another length cannot be it.  Within a branch the state of each element is followed
per path and joined after the statement: an element dirty on one path is loaded at the end
of the clauses that do not hold it (or written back at the end of the paths that do, when
the path through no clause lacks it), and an IF's clause that holds none loads the whole
list at its end when another path holds elements (the LU's row exchange, which leaves every
local stale, loads them again; the path without it keeps them).  A loop keeps its text,
with the dirty elements written back before it and every local stale after it.  Anything it does not know how to
follow (an `else` of a `try` or loop, a `finally`, an augmented store) leaves the lines as
they were.
"""

from __future__ import annotations

import re

from ... import ast
from ...types import ArrayType, ElementaryType, resolve_alias
from ..scope import walk
from ..pysrc import indentation, pyident
from . import fastpath

#: Literal accesses a list needs in the fast copy to repay its unpack and write-backs.
MIN_ACCESSES = 16
#: Dirty elements written back with one slice store rather than one store each.
SLICE_FROM = 4

_LOCALS = ("VAR", "VAR_TEMP", "VAR_OUTPUT", "RETURN")
#: A line that may leave the copy, or hand the context to code that may record a fault
#: and end the scan: every dirty element is written back before it.
_LEAVES = re.compile(r"\b(return|raise|break|continue|_ctx)\b")
#: Code given the context (not `_ctx.fault`, which records a fault and reaches no list): it
#: may reach the list through a global the caller passed, so every local is stale after it.
_HANDS_ON = re.compile(r"\b_ctx\b(?!\.fault\()")
_OPENERS = ("if ", "elif ", "else:", "try:", "except", "finally:", "for ", "while ")


def candidates(compiler, body, listed: dict[str, str]) -> dict[str, tuple[int, tuple[str, ...]]]:
    """The in-outs of `listed` (upper name -> Python name) the pass may keep in locals:
    Python name -> (elements, Python names of the lists that may be the same one)."""
    if compiler.pou.kind != "FUNCTION" or not listed or not _self_contained(compiler, body):
        return {}
    found = {}
    for key, name in listed.items():
        t = resolve_alias(compiler.pou.variables[key].type)
        if not isinstance(resolve_alias(t.element), ElementaryType):
            continue
        others = _may_be_the_same(compiler, key, t.size)
        if others is not None:
            found[name] = (t.size, others)
    return found


def _self_contained(compiler, body) -> bool:
    """Whether `body` calls no ST code (nor anything dispatched at run time) and dereferences
    no pointer: nothing it runs reaches a list other than by the names it writes."""
    targets = compiler.program.call_targets
    for node in walk(body):
        if isinstance(node, ast.Deref):
            return False
        if isinstance(node, ast.Call):
            target = targets.get(id(node))
            if target is None or target.kind in ("method", "super_body") or fastpath._callee(compiler, target):
                return False
    return True


def _may_be_the_same(compiler, key: str, size: int) -> tuple[str, ...] | None:
    """The Python names of the body's other variables that may hold the list of in-out
    `key` (`size` elements), or None when one may hold it other than as a plain array."""
    variables = compiler.pou.variables
    others = []
    for other in sorted(compiler.scope.usage.used):
        if other == key:
            continue
        symbol = variables.get(other)
        if symbol is not None and symbol.kind in _LOCALS:
            continue            # the call's own object
        place = compiler.scope.places.get(other)
        symbol = place.symbol if place is not None else compiler.program.globals.get(other)
        if symbol is None:
            continue            # (a name that is no variable: a function's)
        t = resolve_alias(symbol.type)
        if isinstance(t, ElementaryType):
            continue
        if not isinstance(t, ArrayType) or t.is_open or not isinstance(resolve_alias(t.element), ElementaryType):
            return None
        if t.size == size:
            others.append(place.name if place is not None else pyident(symbol.name))
    return tuple(others)


def replace(lines: list[str], start: int, lists: dict[str, tuple[int, tuple[str, ...]]]) -> None:
    """Keep each list of `lists` in locals in `lines[start:]` (a fast copy), in place."""
    for name, (size, others) in lists.items():
        fast = lines[start:]
        if len(_literal(name).findall("\n".join(fast))) < MIN_ACCESSES:
            continue
        if any(_quoted(name, line) for line in fast):
            continue            # (an ST string that spells the name: not rewritten)
        try:
            lines[start:] = _Rewrite(name, size, others).whole(fast)
        except _Unknown:
            pass


_STRING = re.compile(r"'(?:[^'\\]|\\.)*'|\"(?:[^\"\\]|\\.)*\"|#.*")


def _quoted(name: str, line: str) -> bool:
    """Whether `name` occurs in a string literal or comment of `line`."""
    return name in line and any(name in m.group(0) for m in _STRING.finditer(line))


class _Unknown(Exception):
    """Code the pass does not follow: the lines stay as they were."""


def _literal(name: str):
    return re.compile(rf"(?<![\w.]){name}\[(\d+)\]")


def _local(name: str, k: int) -> str:
    """The local of element `k`: a lower-case letter, which no ST name has in Python (`v_`
    and its upper-case spelling, native.mangle) nor the compiler's own (`_t1`, `_spent`)."""
    return f"{name}_e{k}"


class _Rewrite:
    """One list's rewrite.  A state maps each element held in its local to whether the
    local is newer than the list (dirty); an element not in it is read from the list."""

    def __init__(self, name: str, size: int, others: tuple[str, ...]):
        self.name, self.size = name, size
        self.literal = _literal(name)
        self.store = re.compile(rf"(\s*){name}\[(\d+)\] = ")
        self.named = re.compile(rf"(?<![\w.])(?:_G\.)?(?:{'|'.join([name, *others])})\b")
        self.augmented = re.compile(rf"(?<![\w.])(?:{'|'.join([name, *others])})\[[^\]]*\] (?:[-+*/%&|^@]|//|\*\*|<<|>>)= ")

    def whole(self, lines: list[str]) -> list[str]:
        indent = indentation(lines[0]) if lines else 0
        out: list[str] = []
        state = self.block(lines, indent, {}, 0, out, None)
        if state is not None:
            out.extend(self.flush(state, indent))
        return out

    # ------------------------------------------------------------- structure
    def block(self, lines, indent, state, depth, out, points):
        """Rewrite the statements of one block (`lines`, all at `indent` or deeper) into
        `out`; the state after it, None when it does not end by falling through.  `depth`
        counts the IF branches around it; `points` gathers the states a fault may see."""
        starts = _starts(lines, indent)
        n = 0
        while n < len(starts) - 1:
            i, end = starts[n], starts[n + 1]
            n += 1
            head = lines[i].strip()
            if head.startswith(("if ", "try:")) and head.endswith(":"):
                n = _clauses_end(lines, starts, n, ("elif ", "else:") if head[0] == "i" else ("except",))
            if state is None:
                out.extend(lines[i:starts[n]])  # (after a return: code no path reaches)
                continue
            if points is not None:
                points.append(dict(state))
            if head.startswith("if ") and head.endswith(":"):
                state = self.if_chain(lines[i:starts[n]], indent, state, depth, out, points)
            elif head == "try:":
                out.extend(self.ready("\n".join(lines[i + 1:end]), state, indent, depth))
                state = self.try_block(lines[i:starts[n]], indent, state, depth, out, points)
            elif head.startswith(("for ", "while ")) and head.endswith(":"):
                if _clauses_end(lines, starts, n, ("else:",)) != n:
                    raise _Unknown
                out.extend(self.flush(state, indent))
                out.extend(lines[i:end])
                state = {}
                if points is not None:
                    points.append({})       # (inside it: the list as the loop leaves it)
            elif head.endswith(":") and head.startswith(_OPENERS) or end != i + 1:
                raise _Unknown
            else:
                state = self.simple(lines[i], state, depth, out)
        return state

    def if_chain(self, lines, indent, state, depth, out, points):
        clauses = _clauses(lines, indent)
        conditions = " ".join(lines[at] for at, _ in clauses)
        if self.bare(conditions):
            raise _Unknown      # (a list passed whole in a test: not followed)
        state = dict(state)
        out.extend(self.ready(conditions, state, indent, depth))
        if _HANDS_ON.search(conditions):
            raise _Unknown      # (code given the context in a test: not followed)
        if self.seen_whole(conditions):
            out.extend(self.flush(state, indent))
        paths = []
        for at, end in clauses:
            body: list[str] = []
            paths.append([self.rewrite_reads(lines[at], state), body,
                          self.block(lines[at + 1:end], indent + 4, dict(state), depth + 1, body, points)])
        if lines[clauses[-1][0]].strip() != "else:":
            paths.append([None, [], dict(state)])
        return self.join(paths, indent + 4, out)

    def try_block(self, lines, indent, state, depth, out, points):
        clauses = _clauses(lines, indent)
        body: list[str] = []
        seen: list[dict] = []
        paths = [[lines[0], body, self.block(lines[1:clauses[0][1]], indent + 4, state, depth, body, seen)]]
        if not body:
            body.append(" " * (indent + 4) + "pass")
        if points is not None:
            points.extend(seen)
        for at, end in clauses[1:]:
            if not lines[at].strip().startswith("except"):
                raise _Unknown
            raised = self.at_fault(seen)
            handler = self.flush(raised, indent + 4)
            paths.append([lines[at], handler, self.block(lines[at + 1:end], indent + 4, raised, depth, handler, points)])
        return self.join(paths, indent + 4, out, reload=False)

    def at_fault(self, seen: list[dict]) -> dict:
        """The state a handler starts in: an element held at every point of the try body
        that may raise, dirty when it is at any (written back at the handler's start)."""
        if not seen:
            return {}
        held = set(seen[0]).intersection(*seen[1:])
        dirty = _dirty(seen)
        if not dirty <= held:
            raise _Unknown      # dirty at one point, stale at another: not followed
        return {k: k in dirty for k in held}

    def join(self, paths, indent, out, reload=True):
        """Emit a branching statement's clauses ([header, body lines, end state], the state
        None for a path that does not fall through; a header None for the path through no
        clause) and return the state after it.  An element held on every path is held
        after; one dirty on a path is loaded from the list at the end of each clause that
        does not hold it, else written back at the end of the paths that do; with `reload`
        (an IF's clauses, not a try's handler), one held on a path is loaded also by the
        clauses that hold none (one unpack: an exchange of rows at a data index, which
        leaves every local stale, loads them again at its end, not the path without it)."""
        ends = [(header, s) for header, _, s in paths if s is not None]
        joined = None
        if ends:
            states = [s for _, s in ends]
            held = set(states[0]).intersection(*states[1:])
            dirty = _dirty(states)
            for k in set().union(*states) - held:
                lacking = [(h, t) for h, t in ends if k not in t]
                if all(h is not None and (k in dirty or reload and not t) for h, t in lacking):
                    held.add(k)
            joined = {k: k in dirty for k in held}
        for header, body, s in paths:
            if s is not None:
                body.extend(self.flush({k: True for k, dirty in s.items() if dirty and k not in held}, indent))
                body.extend(self.load(sorted(held - set(s)), not s, indent))
            if header is not None:
                out.append(header)
                out.extend(body)
        return joined

    def load(self, elements: list[int], none_held: bool, indent: int) -> list[str]:
        """Lines loading `elements` into their locals: one unpack of the whole list when
        none is held yet."""
        pad = " " * indent
        if none_held and elements:
            names = ", ".join(_local(self.name, k) for k in range(self.size))
            return [f"{pad}{names}{',' if self.size == 1 else ''} = {self.name}"]
        return [f"{pad}{_local(self.name, k)} = {self.name}[{k}]" for k in elements]

    # ------------------------------------------------------------- lines
    def simple(self, line: str, state: dict, depth: int, out: list[str]):
        indent = indentation(line)
        leaves = line.strip().startswith(("return", "raise", "break", "continue"))
        if not self.named.search(line):
            if _LEAVES.search(line):
                out.extend(self.flush(state, indent))
            out.append(line)
            return None if leaves else {} if _HANDS_ON.search(line) else state
        if self.augmented.search(line):
            raise _Unknown
        out.extend(self.ready(line, state, indent, depth))
        if self.seen_whole(line) or _LEAVES.search(line):
            out.extend(self.flush(state, indent))
        stored = self.store.match(line)
        text = self.rewrite_reads(line, state, stored)
        if stored is not None:
            k = int(stored.group(2))
            if k in state or depth == 0:
                text = f"{stored.group(1)}{_local(self.name, k)} = " + text[stored.end():]
                state[k] = True
        out.append(text)
        if leaves:
            return None
        return {} if self.changes_whole(line) or _HANDS_ON.search(line) else state

    def ready(self, text: str, state: dict, indent: int, depth: int) -> list[str]:
        """Loads before a line that reads the elements of `text`'s literal reads: outside
        branches, an element not held is loaded (all of them in one unpack when none is)."""
        store = self.store.match(text)
        wanted = {int(m.group(1)) for m in self.literal.finditer(text)
                  if store is None or m.start() != store.end(1)}
        missing = sorted(k for k in wanted if k not in state)
        if not missing or depth:
            return []
        elements = list(range(self.size)) if not state else missing
        lines = self.load(elements, not state, indent)
        state.update((k, False) for k in elements)
        return lines

    def rewrite_reads(self, line: str, state: dict, stored=None) -> str:
        """`line` with each literal read of a held element read from its local (the
        store's own target, `stored`, left as it is)."""
        target = stored.end(1) if stored is not None else -1

        def element(m):
            k = int(m.group(1))
            return _local(self.name, k) if m.start() != target and k in state else m.group(0)
        return self.literal.sub(element, line)

    def flush(self, state: dict, indent: int) -> list[str]:
        """Lines writing the dirty elements of `state` back (it keeps them, now clean)."""
        dirty = sorted(k for k, d in state.items() if d)
        for k in dirty:
            state[k] = False
        pad = " " * indent
        if len(dirty) >= SLICE_FROM and all(k in state for k in range(dirty[0], dirty[-1] + 1)):
            span = range(dirty[0], dirty[-1] + 1)
            values = ", ".join(_local(self.name, k) for k in span)
            return [f"{pad}{self.name}[{span.start}:{span.stop}] = ({values})"]
        return [f"{pad}{self.name}[{k}] = {_local(self.name, k)}" for k in dirty]

    # ------------------------------------------------------------- what a line does
    def seen_whole(self, text: str) -> bool:
        """Whether `text` may read the list other than through its locals: a subscript
        that is not a literal, a list that may be it, or the list named whole."""
        for m in self.named.finditer(text):
            rest = text[m.end():]
            if m.group(0) != self.name or not re.match(r"\[\d+\]", rest):
                return True
        return False

    def bare(self, text: str) -> bool:
        """Whether `text` names the list, or one that may be it, other than subscripted
        (passed or compared whole)."""
        return any(not text[m.end():].startswith("[") for m in self.named.finditer(text))

    def changes_whole(self, line: str) -> bool:
        """Whether `line` may store into the list other than at a literal index: a store
        at a data index, into a list that may be it, or the list named whole."""
        if self.bare(line):
            return True
        target = self.named.match(line.lstrip())
        return target is not None and " = " in line and self.store.match(line) is None

def _dirty(states) -> set[int]:
    """The elements dirty in any of `states`."""
    return {k for s in states for k, dirty in s.items() if dirty}



def _starts(lines, indent: int) -> list[int]:
    """The index of each statement of a block at `indent` (a line no deeper), and its end."""
    deeper = " " * (indent + 1)
    return [j for j, line in enumerate(lines) if not line.startswith(deeper) and line.strip()] + [len(lines)]


def _clauses_end(lines, starts: list[int], n: int, continuations) -> int:
    """The index in `starts` after a compound statement's clauses (`elif`, `except`, ...)
    from `starts[n]` on."""
    while n < len(starts) - 1 and lines[starts[n]].lstrip().startswith(continuations):
        n += 1
    return n


def _clauses(lines, indent: int) -> list[tuple[int, int]]:
    """(header index, end) of each clause of one compound statement."""
    starts = _starts(lines, indent)
    return list(zip(starts, starts[1:]))
