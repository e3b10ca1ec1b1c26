"""`aliases`: an aggregate or a read-only cached variable used in one branch is loaded there.

A body aliases each instance or global aggregate it names by a local in its prologue
(`v_X = self.v_X`, `v_X = _G.v_X`; scope.py): the object's identity never changes, so
the alias is the object for the whole call.  An elementary variable the body reads
often but never stores is cached the same way (`v_X = self.v_X`, no store at the end):
no code but the body's can change it while the body runs (scope.py caches nothing a
reference, a METHOD or THIS can reach), so its value is the same at any point.  When every occurrence of the name is
inside one IF branch or CASE clause (the innermost such branch that holds them all,
looking no deeper than the first loop around an occurrence), the alias line moves to
the start of that branch's code: a call that does not take the branch does not load it
(the controller's cold paths: power-on, locate, point-to-point, faults).  Exact: the
line is the same load of the same object, made before any use of the local (every use
is compiled inside that branch), and the load cannot raise; nothing else changes.
A variable the body stores keeps its load in the prologue (its store at the end runs
on every call).  With `spread`, names used in branches of one IF or CASE and not
around them (SP_Controller's CASE of states, each state naming its own FB instances)
are loaded at the start of each branch that names them (`spread_branches`): a call
runs one at most, so it loads no more than before, and a state that names none loads
none.

Left as they are: a body compiled as one CSE region (its reads may move to the top),
names the walk does not find as often as the body has them (a safety net).
"""

from __future__ import annotations

import itertools
import re
from bisect import bisect_right
from collections import Counter

from ... import ast
from ..scope import _nodes, listed, of_classes, root_name
from . import branches, mentions
from .charges import may_set

_ALIAS_LINE = re.compile(r"(v_\w+) = (?:self|_G)\.(v_\w+)")


def drop_unused(lines: list[str], start: int) -> None:
    """Leave out each load `v_X = self.v_X` / `v_X = _G.v_X` (from `start` on) whose local
    nothing else in the function names: an alias of a constant array every read of which
    was folded (SP_InverseKinematics' joint tables), a constant the compiler wrote as a
    literal (with `spread`, one such load in each branch that named it).  The load only
    binds the local, so leaving it out changes nothing else."""
    text = "\n".join(lines[start:])
    found = [(start + n, match) for n, line in enumerate(text.split("\n"))
             if ("= self.v_" in line or "= _G.v_" in line) and (match := _LOAD_LINE.fullmatch(line))]
    if not found:
        return                  # (no load to leave out: no name needs counting)
    counts = Counter(_LOCAL_NAME.findall(text))
    loads = Counter(match.group(2) for _, match in found)
    drop: set[int] = set()
    for i, match in found:
        if counts[match.group(2)] != loads[match.group(2)]:
            continue
        indent = len(match.group(1))
        j = i - 1
        while j in drop:
            j -= 1              # (the line before it that stays)
        after = lines[i + 1] if i + 1 < len(lines) else ""
        if lines[j].rstrip().endswith(":") and len(after) - len(after.lstrip()) < indent:
            continue            # (the only line of its block stays)
        drop.add(i)
    for i in sorted(drop, reverse=True):
        del lines[i]


_LOAD_LINE = re.compile(r"( *+)(v_\w+) = (?:self|_G)\.\2")      # a whole line
#: A local `v_...` not after a dot or a word character.  Spelled with the literal `v`
#: first and the look-behind after it (the same matches): the regex engine then skips
#: to each `v` instead of trying the look-behind at every character (9x faster).
_LOCAL_NAME = re.compile(r"(v(?<![.\w]v)_\w+)")
_SET = re.compile(r"        ((?:self\.)?\w+) = (.+)")
_COPY = re.compile(r"        v_\w+\[_WHOLE\] = v_\w+")
_INLINE_TRIG = re.compile(r"\(_m_(?:sin|cos|tan)\((_t\d+)\) if \(\1 := ((?:self\.)?\w+)\) < 1e309 and \1 > -1e309"
                          r" else _sf_(?:SIN|COS|TAN)\(\1\)\)")          # (pysrc.finite_test)
#: The same with the finite test a value of `reuse` (`finite`): `_cN` is that test of x.
_TESTED_TRIG = re.compile(r"\(_m_(?:sin|cos|tan)\(((?:self\.)?v_\w+)\) if _c\d+ else _sf_(?:SIN|COS|TAN)\(\1\)\)")


def drop_unread(lines: list[str], start: int, deferred: bool = False) -> None:
    """Leave out the load `v_X = self.v_X` of a method's cached variable that the body sets
    before it reads it and before anything can raise: the straight lines the body begins
    with (`try:` at the top, then charges and assignments that cannot raise) set it, so its
    value is never read and the store back at the end finds it set (SP_InverseKinematics'
    rotation matrix: 17 loads).

    `deferred`: budget checks among those lines do not end them; a load left out for a
    variable set after a check is made in that check's branch instead, before `_overrun`
    (SP_InverseKinematics' U, V, W, LegX, LegY, LegZ).  An overrun there stores back the
    value the load at entry would have given (nothing before the check stores the
    variable or calls code that could), so the instance ends the same; a call that
    passes the checks loads nothing."""
    try:
        body = lines.index("    try:", start)
    except ValueError:
        return
    loads = {}
    for i in range(start, body):
        match = _ALIAS_LINE.fullmatch(lines[i].strip())
        if match and match.group(1) == match.group(2) and lines[i].startswith("    v_"):
            loads[match.group(1)] = i
    if not loads:
        return                  # (no load to leave out: the lines after need no reading)
    unread, seen = set(), set()
    checks: dict[int, list[str]] = {}          # line of a budget check -> the loads it makes
    for i in range(body + 1, len(lines)):
        line = lines[i]
        if line.startswith("        _spent += "):
            continue
        if _COPY.fullmatch(line):
            continue            # (a copy of a list left without a guard: unguard.py)
        if deferred and line.startswith(_CHECK + "_overrun("):
            checks[i] = []
            continue
        match = _SET.fullmatch(line)
        if match is None:
            break
        value = _TESTED_TRIG.sub(r"\1", _INLINE_TRIG.sub(lambda m: m.group(2), match.group(2)))
        if "\x03" in value or not branches.code_cannot_fault(value):
            break
        seen.update(_LOCAL_NAME.findall(value))
        target = match.group(1)
        if target in loads and target not in seen:
            unread.add(loads[target])
            for made in checks.values():
                made.append(lines[loads[target]].strip())
        seen.add(target)
    for i, made in checks.items():
        if made:
            lines[i] = _CHECK + "; ".join(made) + "; " + lines[i][len(_CHECK):]
    if unread:
        lines[start:] = [line for i, line in enumerate(lines[start:], start) if i not in unread]


_CHECK = "        if _ctx.budget < _spent: "


def store_early(lines: list[str], start: int) -> None:
    """A method's cached variable that the body sets once, at the top level of its `try`,
    before any line names it, is stored into its slot by that line (`self.v_X = v_X = ...`),
    not loaded at the start and stored back at the end: until that line the slot holds what
    the load would have read (a fault, an overrun or a RETURN before it stores back that same
    value), after it the slot holds what the local does (no line sets the local again), and
    no code but the body's reads the slot while the body runs (scope.py caches nothing a
    reference, a METHOD or THIS can reach).  (SP_Controller's SyncExecute, StopExecute and
    ResetExecute: set after the motion calls that may raise, one load a scan each fewer.)"""
    try:
        body = lines.index("    try:", start)
        end = lines.index("    finally:", body)
    except ValueError:
        return
    loads = {}
    for i in range(start, body):
        match = _LOAD_LINE.fullmatch(lines[i])
        if match is not None and lines[i] == f"    {match.group(2)} = self.{match.group(2)}":
            loads[match.group(2)] = i
    stores = {line: i for i in range(end + 1, len(lines)) if (line := lines[i]).startswith("        self.v_")}
    flat = "\n".join(lines[body + 1:end])
    starts = list(itertools.accumulate(map((1).__add__, map(len, lines[body + 1:end])), initial=0))
    moved = {}
    for name, load in loads.items():
        back = stores.get(f"        self.{name} = {name}")
        if back is None:
            continue            # (a variable the body only reads: loaded, never stored back)
        # The lines that name it, the first of which must be its one set.
        naming = list(dict.fromkeys(body + bisect_right(starts, at) for at in mentions.places(flat, name)))
        if not naming or not lines[naming[0]].startswith(f"        {name} = "):
            continue
        first = naming[0]
        if mentions.count(lines[first][len(f"        {name} = "):], name) \
                or any(may_set(name, lines[i]) for i in naming[1:]):
            continue
        moved[first] = f"        self.{name} = {lines[first].lstrip()}"
        moved[load] = moved[back] = None
    for i, line in moved.items():
        lines[i] = line
    if moved:
        lines[start:] = [line for line in lines[start:] if line is not None]


def late_loads(compiler, body) -> dict[int, list[str]]:
    """Move eligible alias lines out of `compiler.scope.prologue`; id(branch body) -> lines."""
    scope = compiler.scope
    stored = {line.split(" = ", 1)[1] for line in scope.epilogue if isinstance(line, str)}
    names = {place.name: key for key, place in scope.places.items()
             if place.how == "alias" or (place.how == "local" and place.name not in stored)}
    candidates = {}
    for line in scope.prologue:
        match = _ALIAS_LINE.fullmatch(line) if isinstance(line, str) else None
        if match and match.group(1) == match.group(2) and match.group(1) in names:
            candidates[names[match.group(1)]] = line
    if not candidates:
        return {}
    seen = occurrences(compiler, body)
    loads: dict[int, list[str]] = {}
    for key, line in candidates.items():
        found = seen.paths.get(key, [])
        if len(found) != seen.counts[key]:
            continue
        places = spread_branches(found, seen.parents) if compiler.opt.spread else [common_branch(found)]
        if places and all(places):
            scope.prologue.remove(line)
            for place in places:
                loads.setdefault(place[-1], []).append(line)
    return loads


_NAME = frozenset({ast.Name})
_RECORDED = frozenset({ast.Name, ast.Assign, ast.For, ast.Arg})     # what `_record` notes


class Occurrences:
    """Where the names of a body occur: `paths[key]` has the path (ids of the IF branch and
    CASE clause bodies around it, outermost first) of each occurrence of the name, and
    `paths["=", key]` of each store into it (assignment targets, FOR variables, outputs
    `=>`), looking no deeper than the first loop (a loop is one statement); `counts[key]`
    how often the name occurs in the whole body (what the paths must all have found);
    `bodies` the branch bodies by id, `parents` the id of the IF or CASE of each."""

    def __init__(self, body):
        self.body = body
        self.paths: dict = {}
        self.bodies: dict[int, tuple] = {}
        self.parents: dict[int, int] = {}
        self.counts = Counter(node.name.upper() for node in of_classes(listed(body), _NAME))
        _visit(body, (), self)


def occurrences(compiler, body) -> Occurrences:
    """The body's `Occurrences`, found once for the passes that ask (aliases, stores)."""
    seen = getattr(compiler, "_occurrences", None)
    if seen is None or seen.body is not body:
        seen = compiler._occurrences = Occurrences(body)
    return seen


def common_branch(paths: list[tuple]) -> tuple | None:
    """The longest path all of `paths` start with; None when there is none, or no path."""
    if not paths:
        return None
    first, last = min(paths), max(paths)    # (what the first and last in order share, all share)
    n = 0
    for a, b in zip(first, last):
        if a != b:
            break
        n += 1
    return first[:n] or None


def spread_branches(paths: list[tuple], parents: dict[int, int]) -> list[tuple] | None:
    """The paths of branches that hold `paths` between them and of which one call runs one at
    most (optimise `spread`): the longest common path, or, when every path goes on below it
    into branches of one IF or CASE (none ends there), each of those branches that holds some,
    spread again.  None when the paths have no common branch and cannot be spread."""
    shortest = min(map(len, paths), default=0)
    if not shortest:
        return None             # (no path, or one at the top level)
    common = common_branch(paths)
    depth = len(common) if common else 0
    if shortest == depth:
        return [common]
    groups: dict[int, list[tuple]] = {}
    for path in paths:
        groups.setdefault(path[depth], []).append(path)
    if len({parents[branch] for branch in groups}) != 1:
        return [common] if common else None     # (branches of two statements: both may run)
    return [place for group in groups.values() for place in spread_branches(group, parents)]


def _visit(stmts, path: tuple, seen: Occurrences) -> None:
    for stmt in stmts or ():
        if isinstance(stmt, ast.If):
            for branch in stmt.branches:
                _record(branch.condition, path, seen.paths)
                _enter(stmt, branch.body, path, seen)
            if stmt.else_body:
                _enter(stmt, stmt.else_body, path, seen)
        elif isinstance(stmt, ast.Case):
            _record(stmt.selector, path, seen.paths)
            for clause in stmt.clauses:
                _record(clause.labels, path, seen.paths)
                _enter(stmt, clause.body, path, seen)
            if stmt.else_body:
                _enter(stmt, stmt.else_body, path, seen)
        else:       # a simple statement, or a loop: every name in it at this path
            _record(stmt, path, seen.paths)


def _enter(stmt, body, path: tuple, seen: Occurrences) -> None:
    seen.bodies[id(body)] = body
    seen.parents[id(body)] = id(stmt)
    _visit(body, path + (id(body),), seen)


def _record(node, path: tuple, paths: dict) -> None:
    for n in of_classes(_nodes(node), _RECORDED):
        cls = type(n)
        if cls is ast.Name:
            name = n.name.upper()
        elif cls is ast.Assign:
            name = root_name(n.target)
            name = name and ("=", name)
        elif cls is ast.For:
            name = "=", n.variable.upper()
        elif n.direction == "out":      # (an Arg)
            name = root_name(n.value)
            name = name and ("=", name)
        else:
            continue
        if name:
            found = paths.get(name)
            if found is None:
                paths[name] = [path]
            else:
                found.append(path)
