"""`dormant`: the call site of an idle Execute FB at rest skips its input stores too.

A call site of a native FB with a `REST` test (MC_Stop, MC_Reset, ...) stores the inputs it
gives every scan and then tests the rest note (calls.py `_execute`).  When it is the only
code of the program that writes the instance, the whole site runs under one test:

    if X is not False or <instance>._at_rest is not _ctx.seal:
        <the input stores>
        <the rest test and the call, as before>
        if <instance>.v_EXECUTE is not False:
            <instance>._at_rest = None

where X is the variable its Execute is given as (`Execute := X` or `X AND e`).  Skipped, the
site would have stored what the instance holds already and found it at rest:

* the note holds under the seal: the FB was found at rest under it, and since then no call
  (a call forgets it), no code but the scans' own (the seal is new after any other: a hook
  that writes, `--set`, the API) and no run of the site that stored an Execute other than
  the object False (the site's last lines forget it then: a BOOL may hold 0 or 1, and
  forgetting only makes the next rest test the full one);
* nothing else of the program writes the instance (`_SoleSites`): it is a PROGRAM's VAR (or
  one element, by a constant index, of a VAR array); every Name of it in the PROGRAM's code
  is this one call or the base of a member read outside any assignment's target and any
  call's arguments; and the project's texts spell it no more often than those Names and its
  declaration (another POU, a member named like it, a comment: a mention the census cannot
  place spoils it; the checker refuses a program's variable named from another POU, and a
  VAR_ACCESS path is read by nothing).  So its inputs are what this site stored when it
  last ran, Execute the object False;
* the site stores the same values again: each other input is a constant or the in-out an
  aggregate variable (one object for the whole run: aggregates are copied in place, never
  rebound), and Execute is X itself while X is False (`X`, or `(X if not X else ...)`, the
  `shortcut` pass's `X AND e`; `e` a read that cannot fault or call, left out either way).

Every other site, and one with `=>` outputs or an input of another kind, keeps its code.
"""

from __future__ import annotations

import re
from typing import NamedTuple

from ... import ast
from ...objects import is_aggregate
from ...symbols import Symbol
from ...types import ElementaryType, resolve_alias
from ..scope import listed, of_classes, walk
from . import mentions

# The reads a skipped `X AND e` may leave out: variables, members, literals, NOT and logic.
_PURE = (ast.Name, ast.Member, ast.BoolLiteral, ast.Unary, ast.Binary)
_LOGIC = frozenset(("AND", "&", "OR", "XOR", "NOT"))


class Execute(NamedTuple):
    """X of a dormant site: its Python and its Symbol."""

    code: str
    symbol: Symbol


class Site(NamedTuple):
    """A dormant site as compiled, for `Groups`: its first line (the test), X, the instance's
    Python and the FB's RestTest."""

    test: str
    execute: Execute
    fb: str
    rest: object


def guard(ec, call, inputs: dict, variables: dict, codes: dict) -> Execute | None:
    """X when the site of `call` may run under `X is not False or <unnoted>` (the module
    docstring), else None.  `codes`: input key -> the Python the site stores."""
    if ec.pou.kind != "PROGRAM" or id(call) not in sole_sites(ec):
        return None
    execute = None
    for key, arg in inputs.items():
        symbol = variables[key]             # (fb_call has refused an input the FB lacks)
        if key == "EXECUTE" and symbol.kind == "VAR_INPUT":
            execute = _execute_variable(ec, arg.value, codes[key])
            if execute is None:
                return None
        elif not (_fixed_aggregate(ec, symbol, arg.value) or ec.constant_of(arg.value) is not None):
            return None
    return execute


def forget_lines(instance: str, rest) -> list[str]:
    """The last lines of a dormant site: an Execute that is not the object False drops the
    note (the module docstring; an FB never writes its inputs, so the call left it as stored)."""
    return [f"if {instance}.v_EXECUTE is not False:", f"    {rest.forget.format(fb=instance)}"]


def site(ec, call, execute: Execute, fb: str, rest, stores: list[str], lines: list[str]) -> list[str]:
    """The dormant site of `call` (instance `fb`): the stores and the rest of the call under
    one test, kept for `Groups` (the site compiled last for each call)."""
    test = f"if {execute.code} is not False or {rest.unnoted.format(fb=fb)}:"
    ec.__dict__.setdefault("dormant_sites", {})[id(call)] = Site(test, execute, fb, rest)
    return [test, *("    " + line for line in stores + lines)]


def _execute_variable(ec, value, code: str) -> Execute | None:
    """X for `Execute := X` or `X AND e` (X a BOOL variable, e a pure read) stored as X while
    X is False, else None."""
    if type(value) is ast.Binary and value.op in ("AND", "&") and _pure(value.right):
        value = value.left
    symbol = ec.program.name_refs.get(id(value)) if type(value) is ast.Name else None
    if not isinstance(symbol, Symbol) or not _is_bool(ec, value):
        return None
    x = ec.expr(value)
    return Execute(x, symbol) if code == x or code.startswith(f"({x} if not {x} else ") else None


def _pure(node) -> bool:
    """`node` reads only: names, members, literals, NOT and logic operators; no index (which
    may fault), no call, no dereference."""
    for part in walk(node):
        if not isinstance(part, _PURE):
            return False
        if type(part) in (ast.Unary, ast.Binary) and part.op.upper() not in _LOGIC:
            return False
    return True


def _is_bool(ec, node) -> bool:
    t = resolve_alias(ec.ty(node))
    return isinstance(t, ElementaryType) and t.kind == "bool"


def _fixed_aggregate(ec, symbol, value) -> bool:
    """An in-out given a variable that holds an aggregate: one object for the whole run."""
    if symbol.kind != "VAR_IN_OUT" or type(value) is not ast.Name:
        return False
    target = ec.program.name_refs.get(id(value))
    return isinstance(target, Symbol) and target.kind in ("VAR", "VAR_GLOBAL", "VAR_EXTERNAL") \
        and is_aggregate(target.type)


def sole_sites(ec) -> frozenset[int]:
    """id() of every CallStmt's Call in the PROGRAM being compiled that is the only writer of
    its instance (a VAR of it, or a constant element of one); worked out once a load and POU."""
    table = ec.unit.__dict__.setdefault("dormant_sites", {})
    key = ec.pou.name.upper()
    if key not in table:
        table[key] = _SoleSites(ec.program, ec.pou).sites()
    return table[key]


_CALL_STMT, _MEMBER, _NAME = frozenset({ast.CallStmt}), frozenset({ast.Member}), frozenset({ast.Name})
_WRITERS = frozenset({ast.Assign, ast.Call})


class _SoleSites:
    """The census of `sole_sites` for one PROGRAM: its VARs' mentions in its code, and the
    project's texts for every other mention (another POU, a member named like it, a comment:
    any word spelt like it that is not one of those mentions spoils it)."""

    def __init__(self, program, pou) -> None:
        self.refs = program.name_refs
        self.constants = program.constants
        self.words = _Words(program.sources.values())
        self.nodes = listed(pou.node.body)    # (kept from the compile's own walks; a mention
        #  anywhere else, declarations, methods, a chart, is one the texts count and no Name here)
        self.owned = {id(symbol): symbol for symbol in pou.variables.values() if symbol.kind == "VAR"}

    def sites(self) -> frozenset[int]:
        calls: dict[tuple, list[int]] = {}      # (symbol, index) -> ids of the calls
        allowed: set[int] = set()               # ids of the Names mentioned as allowed
        for statement in of_classes(self.nodes, _CALL_STMT):
            name, index = self._instance(statement.call.callee)
            if name is not None:
                calls.setdefault((id(self.refs[id(name)]), index), []).append(id(statement.call))
                allowed.add(id(name))
        written = self._written()
        for member in of_classes(self.nodes, _MEMBER):
            name, _ = self._instance(member.base)
            if name is not None and id(member) not in written:
                allowed.add(id(name))
        spoilt = self._spoilt(allowed)
        return frozenset(ids[0] for (symbol, _), ids in calls.items() if len(ids) == 1 and symbol not in spoilt)

    def _instance(self, node):
        """(the Name, index) of `V` or `V[c]`, V a VAR of the PROGRAM and c a constant, else (None, None)."""
        index = None
        if type(node) is ast.Index and len(node.indices) == 1 and id(node.indices[0]) in self.constants:
            index, node = self.constants[id(node.indices[0])], node.base
        if type(node) is ast.Name and id(self.refs.get(id(node))) in self.owned:
            return node, index
        return None, None

    def _written(self) -> set[int]:
        """ids of the nodes a statement may write through: an assignment's target (and value,
        for `REF=` and the like), every call's arguments (in-outs, outputs, REF(), ADR())."""
        written: set[int] = set()
        for node in of_classes(self.nodes, _WRITERS):
            if type(node) is ast.Call:
                written.update(map(id, listed(node.args)))
            else:
                written.update(map(id, listed(node.target)))
                if node.mode != ":=":
                    written.update(map(id, listed(node.value)))
        return written

    def _spoilt(self, allowed: set[int]) -> set[int]:
        """id() of the VARs mentioned but as `allowed`, or spelt in the project's texts more
        often than their declaration and their Names here."""
        names: dict[int, int] = {}
        spoilt: set[int] = set()
        for node in of_classes(self.nodes, _NAME):
            symbol = id(self.refs.get(id(node)))
            if symbol in self.owned:
                names[symbol] = names.get(symbol, 0) + 1
                if id(node) not in allowed:
                    spoilt.add(symbol)
        for symbol, count in names.items():
            if symbol not in spoilt and self.words.count(self.owned[symbol].name) != count + 1:
                spoilt.add(symbol)
        return spoilt


class _Words:
    """The project's texts, to count how often a word stands in them, in any case: each text
    lowered once and the word found there by `str.find` (C), not one pattern per word read
    through every text by the regex engine (the load's cost: 45 times the time).  Exact for
    ASCII texts and words (where `re.IGNORECASE` folds a letter as `str.lower` does, and a word
    character is `isalnum` or `_`); any other text is read by the pattern, as before."""

    def __init__(self, texts) -> None:
        self.texts = list(texts)
        self.lowered = [text.lower() for text in self.texts if text.isascii()]
        self.others = [text for text in self.texts if not text.isascii()]

    def count(self, word: str) -> int:
        """How often `word` stands in the texts (any case), not next to a word character."""
        if not word.isascii():
            return _count_by_pattern(word, self.texts)
        key = word.lower()
        found = sum(len(mentions.places(text, key, attributes=True)) for text in self.lowered)
        return found + (_count_by_pattern(word, self.others) if self.others else 0)


def _count_by_pattern(word: str, texts: list[str]) -> int:
    pattern = re.compile(rf"(?<![\w]){re.escape(word)}(?![\w])", re.IGNORECASE)
    return sum(len(pattern.findall(text)) for text in texts)


class Groups:
    """The dormant sites of one block of simple statements, two or more apart only by other
    call statements, as one group: the group's first lines test what the sites would test
    (each X, and a note that all were found at rest) once, and each site runs only when that
    test was true (SP_Controller: six MC_Stop and six MC_Reset between its six
    MC_SyncMoveAbsolute, one test a scan where there were twelve):

        if X1 is not False or X2 is not False or <first>._group_at_rest is not _ctx.seal:
            _dormantN = True
            <first>._group_at_rest = None
        else:
            _dormantN = False
        ...
        if _dormantN and (X1 is not False or <instance>._at_rest is not _ctx.seal):  (each site)
        ...
        if _dormantN and not (<each instance>._at_rest is not _ctx.seal or ...):      (after the last)
            <first>._group_at_rest = _ctx.seal

    The group's note (`RestTest.group` of its first instance) holds only while every site's
    own note holds: it is dropped before any site of the group may run and set after the
    last one only when all their notes hold (a scan that ends between, by a fault, leaves it
    dropped).  A site's note changes only at its own site (each is its instance's only
    writer, `_SoleSites`) or with a new seal.  So while the group's note holds and each X is
    the object False, every site's own test would be false where it stands: X is a local of
    the body (a Python name: no reference, METHOD or other POU reaches it) that no statement
    between the sites names, and the sites themselves only store into their own instances.
    A skipped site, as before, is one that would have stored what its instance holds.
    """

    def __init__(self, ec) -> None:
        self.ec = ec
        self.placed: list[tuple] = []       # (statement, its first line, the line after it)

    def add(self, statement, start: int) -> None:
        self.placed.append((statement, start, len(self.ec.out.lines)))

    def close(self) -> None:
        """Rewrite the block's lines, each group as the class docstring shows."""
        sites = self.ec.__dict__.get("dormant_sites")
        if sites and len(self.placed) > 1:
            for group in reversed(self._groups(sites)):
                self._rewrite(group)

    def _groups(self, sites: dict) -> list[list[tuple[int, Site]]]:
        """Runs of sites ((index, Site), two or more) with only other call statements between
        them, none naming an X of its run."""
        runs, run, between = [], [], []
        enables = self.ec.program.enables
        for index, (statement, _, _) in enumerate(self.placed):
            site = sites.get(id(statement.call)) if type(statement) is ast.CallStmt else None
            if site is not None and enables.get(id(statement.call)) is None \
                    and site.execute.code.isidentifier():
                if between:
                    run.extend(between)
                    between = []
                run.append((index, site))
            elif type(statement) is ast.CallStmt and run:
                between.append((index, None))
            else:
                runs.append(run)
                run, between = [], []
        runs.append(run)
        return [members for members in map(self._checked, runs) if len(members) > 1]

    def _checked(self, run: list) -> list[tuple[int, Site]]:
        """The sites of `run`, or none when a statement between them names one of their X."""
        members = [(index, site) for index, site in run if site is not None]
        xs = {id(site.execute.symbol) for _, site in members}
        refs = self.ec.program.name_refs
        for index, site in run:
            if site is None and any(type(node) is ast.Name and id(refs.get(id(node))) in xs
                                    for node in walk(self.placed[index][0])):
                return []
        return members

    def _rewrite(self, group: list[tuple[int, Site]]) -> None:
        lines, pad = self.ec.out.lines, "    " * self.ec.out.depth
        tests = []
        for index, site in group:
            _, start, end = self.placed[index]
            found = [n for n in range(start, end) if lines[n].strip() == site.test]
            if len(found) != 1:
                return                          # (not the site as `site` wrote it: no group)
            tests.append(found[0])
        count = self.ec.__dict__["dormant_groups"] = self.ec.__dict__.get("dormant_groups", 0) + 1
        awake, first = f"_dormant{count}", group[0][1]
        note = first.rest.group.format(fb=first.fb)
        unnoted = " or ".join(site.rest.unnoted.format(fb=site.fb) for _, site in group)
        lines[self.placed[group[-1][0]][2]:self.placed[group[-1][0]][2]] = [
            f"{pad}if {awake} and not ({unnoted}):", f"{pad}    {note} = _ctx.seal"]
        for n in tests:
            indent = lines[n][:len(lines[n]) - len(lines[n].lstrip())]
            lines[n] = f"{indent}if {awake} and ({lines[n].strip()[3:-1]}):"
        xs = dict.fromkeys(site.execute.code for _, site in group)
        start = self.placed[group[0][0]][1]
        lines[start:start] = [
            f"{pad}if {' or '.join(f'{x} is not False' for x in xs)} or {note} is not _ctx.seal:",
            f"{pad}    {awake} = True", f"{pad}    {note} = None", f"{pad}else:", f"{pad}    {awake} = False"]
