"""`reuse`: a float value computed again over unchanged operands is computed once.

Across the statements of a body (not only inside a CSE region), these values
are remembered as they are compiled, with the variables they read:

* an element of the POU's own array read at a literal index (`v_POSE[2]`);
* a `+ - *` of LREAL/REAL operands that are such values, literals or plain
  variables (a local, a slot of the instance or of the globals; not located,
  not reached through a reference);
* SIN, COS, TAN or SQRT of such a value, compiled inline (calls.py `_GUARDED`).

None of them can raise (float `+ - *` gives inf or NaN, a list read at a literal
index in range cannot fail, the inline math calls test their argument), and none
has a side effect.  When the same text comes again while it is valid, the second
use reads a name the first statement set instead: `_cN = text` is put before
the statement that first computed it, at that statement's own level (outside
its guard and its conditions, so it runs whenever any later use can), and a
value used only once keeps its text where it was.  SP_InverseKinematics' six
legs read `v_POSE[0]`, `v_POSE[1]` and compute `(v_POSE[2] + 1374.0) - 95.0`
once; TRJ_OceanWave's iteration computes `SIN(Psi)` once for two sums.

A value stays valid while nothing can change what it read: a store into one of
its variables ends it (after the statement that stores, or before a loop whose
body stores it, which would run the use again after the store); a statement
with a call of ST code, REF or a store through a reference, an in-out, a
located or a global variable ends every value; a WHILE's or REPEAT's condition
runs again after its body, so no value is set for it (its body's statements set
their own, in the body); the end of the IF branch, CASE
clause or loop body it was computed in ends it (an unrolled copy of a loop runs
where it is written: its values stay for the next copy).  The same operations
on the same operands in the same order give the same float, so results,
faults, charges and F-PERIOD are as before.  Left alone: a CSE region and a
fast body (their own passes rearrange those lines).
"""

from __future__ import annotations

import re

from ... import ast
from ...types import ArrayType, ElementaryType, resolve_alias
from ..pysrc import finite_test, pyident
from ..scope import _LOOPS, _nodes, root_name
from . import branches      # (branches imports this module: its names are read at call time)

_TOKEN = re.compile("\x03(\\d+)\x03")
_MARKER = re.compile("^( *+)\x04([\\d,]+)\x04$", re.M)
_NUMBER = re.compile(r"-?\(?-?\d[\d.e+-]*\)?")
_VARIABLE = re.compile(r"(?:self\.|_G\.)?(v_\w+)")
_TESTABLE = re.compile(r"(?:self\.)?v_\w+")      # a local, or a slot of the instance itself
_ELEMENT = re.compile(r"(v_\w+)\[\d+\]")
_FINITE_TEST = re.compile(r"\(((?:self\.)?v_\w+) < 1e309 and \1 > -1e309\)")     # what `finite` writes
_PLAIN_KINDS = {"VAR", "VAR_INPUT", "VAR_OUTPUT", "VAR_TEMP", "RETURN", "VAR_GLOBAL", "VAR_EXTERNAL"}
_MATH = {"SIN", "COS", "TAN", "SQRT"}
_NO_VARIABLES: frozenset = frozenset()


class _Value:
    __slots__ = ("key", "text", "deps", "uses", "level")

    def __init__(self, key: str, text: str, deps: frozenset, level: int):
        self.key, self.text, self.deps, self.uses, self.level = key, text, deps, 1, level


class Reuse:
    """The values of one function being compiled (see the module docstring)."""

    def __init__(self, compiler):
        self.compiler = compiler
        self.values: list[_Value] = []
        self.known: dict[str, int] = {}          # text -> index of its value in `values`
        self.readers: dict[str, list[str]] = {}  # variable -> the texts of the values that read it
        self.levels = [0]                        # the statement lists being compiled, outermost first
        self.opened = 0
        self.pending: list[list[int]] = []       # per statement being compiled: values it computes first
        self.closed = 0                          # > 0 inside a statement that ends every value
        self._summaries: dict[int, tuple] = {}   # id(statement) -> _summary (the AST lives as long)
        self.owned: dict[str, object] = {}       # name -> its symbol when plain storage (`_own`)
        self.element_store: tuple | None = None   # (element, value index) the statement stores (`stored`)

    # ------------------------------------------------------------ levels

    def enter(self) -> None:
        self.opened += 1
        self.levels.append(self.opened)

    def leave(self) -> None:
        self.levels.pop()

    def begin(self, stmt) -> tuple:
        stored, opaque, loops = self._summary(stmt)
        if opaque:
            self._forget_all()
            self.closed += 1
        elif loops:
            self._forget(stored)
        # A WHILE's or REPEAT's condition runs again after its body: no value of it is set before it.
        self.pending.append(None if isinstance(stmt, (ast.While, ast.Repeat)) else [])
        return stored, opaque

    def _summary(self, stmt) -> tuple[frozenset, bool, bool]:
        """(Python names of the variables `stmt` stores into, whether it may change any
        variable: a call of ST code or REF, a store through a reference, an in-out, a
        located or a global variable; whether it holds a loop), built from its
        statements' (each statement is summed up once: unrolled copies share them)."""
        known = self._summaries.get(id(stmt))
        if known is not None:
            return known
        c = self.compiler
        stored: set[str] = set()
        opaque, loops = False, isinstance(stmt, _LOOPS)
        expressions, bodies = [], []
        if isinstance(stmt, ast.Assign):
            expressions = [stmt.target, stmt.value]
            name = _stored(c, stmt.target)
            opaque = name is None
            stored.add(name)
        elif isinstance(stmt, ast.CallStmt):
            opaque = True
        elif isinstance(stmt, ast.If):
            expressions = [b.condition for b in stmt.branches]
            bodies = [b.body for b in stmt.branches] + [stmt.else_body or ()]
        elif isinstance(stmt, ast.Case):
            expressions = [stmt.selector]
            bodies = [clause.body for clause in stmt.clauses] + [stmt.else_body or ()]
        elif isinstance(stmt, ast.For):
            expressions = [e for e in (stmt.start, stmt.end, stmt.step) if e is not None]
            bodies = [stmt.body]
            name = _stored(c, ast.Name(stmt.variable, pos=stmt.pos))
            opaque = name is None
            stored.add(name)
        elif isinstance(stmt, (ast.While, ast.Repeat)):
            expressions, bodies = [stmt.condition], [stmt.body]
        elif not isinstance(stmt, (ast.Exit, ast.Continue, ast.Return, ast.Empty)):
            opaque = True
        opaque = opaque or any(_calls_st(c, e) for e in expressions)
        for body in bodies:
            for inner in body:
                s, o, l = self._summary(inner)
                stored |= s
                opaque, loops = opaque or o, loops or l
        known = self._summaries[id(stmt)] = (frozenset(stored - {None}), opaque, loops)
        return known

    def end(self, began: tuple, mark: int) -> None:
        stored, opaque = began
        first = self.pending.pop()
        if first:
            self.compiler.out.insert(mark, [f"\x04{','.join(map(str, first))}\x04"])
        element_store, self.element_store = self.element_store, None
        if opaque:
            self.closed -= 1
            self._forget_all()
        else:
            self._forget(stored)
            if element_store is not None:
                self._read_back(*element_store)

    def _forget(self, names) -> None:
        for name in names:
            for key in self.readers.pop(name, ()):
                self.known.pop(key, None)

    def _forget_all(self) -> None:
        self.known.clear()
        self.readers.clear()

    # ------------------------------------------------------------ values

    def active(self) -> bool:
        c = self.compiler
        return bool(self.pending) and self.pending[-1] is not None and not self.closed \
            and c.region is None and c._segments is None

    def value(self, key: str, text: str, deps: frozenset) -> str:
        """A token for the value `key`, computed by `text` (which cannot raise), that
        `resolve` turns into a name or back into `text`."""
        index = self.known.get(key)
        if index is not None and self.values[index].level in self.levels:
            self.values[index].uses += 1
            return f"\x03{index}\x03"
        index = len(self.values)
        self.values.append(_Value(key, text, deps, self.levels[-1]))
        self.known[key] = index
        for name in deps:
            self.readers.setdefault(name, []).append(key)
        self.pending[-1].append(index)
        return f"\x03{index}\x03"

    def operand(self, node, code: str) -> frozenset | None:
        """The variables `code` (of `node`) reads when it is a value this pass can use."""
        if code[0] == "\x03":
            match = _TOKEN.fullmatch(code)
            return self.values[int(match.group(1))].deps if match else None
        if not isinstance(node, ast.Name):
            return _NO_VARIABLES if _NUMBER.fullmatch(code) else None
        match = _VARIABLE.fullmatch(code)
        if match is None:
            return _NO_VARIABLES if _NUMBER.fullmatch(code) else None
        if node.name.upper() not in self.compiler.unrolled:
            symbol = self._own(node)
            if symbol is not None and isinstance(resolve_alias(symbol.type), ElementaryType):
                return frozenset((match.group(1),))
        return None

    def _own(self, name):
        """`_own` of the name, found once."""
        key = name.name.upper()
        if key not in self.owned:
            self.owned[key] = _own(self.compiler, name)
        return self.owned[key]

    def element(self, node, code: str) -> str:
        """An own array's element read at a literal index, as a value."""
        match = self.active() and _ELEMENT.fullmatch(code)
        if not (match and isinstance(node.base, ast.Name)):
            return code
        symbol = self._own(node.base)
        t = resolve_alias(symbol.type) if symbol is not None else None
        if not (isinstance(t, ArrayType) and isinstance(resolve_alias(t.element), ElementaryType)):
            return code
        return self.value(code, code, frozenset((match.group(1),)))

    def binary(self, e, op: str, left: str, right: str) -> str | None:
        """`(left op right)` of floats as a value, or None."""
        if op not in ("+", "-", "*") or not self.active() or not _is_float(self.compiler.ty(e)):
            return None         # (not active in a region or a fast body: asked first, it is cheaper)
        a = self.operand(e.left, left)
        b = self.operand(e.right, right) if a is not None else None
        if b is None:
            return None
        text = f"({left} {op} {right})"
        return self.value(text, text, a | b)

    def math(self, name: str, arg, code: str, text: str) -> str:
        """SIN/COS/TAN/SQRT of a float, compiled inline to `text`, as a value."""
        if not (self.active() and name in _MATH and _is_float(self.compiler.ty(arg))):
            return text
        deps = self.operand(arg, code)
        return text if deps is None else self.value(f"{name}({code})", text, deps)

    def finite(self, arg, code: str) -> str | None:
        """The finite test of a float local or own slot (`self.v_X`; pysrc.finite_test:
        `code < 1e309 and code > -1e309`), as a value: inline SIN, COS and TAN of one unchanged variable test
        it once (`finite`).  A slot is read twice, with nothing run between the reads."""
        if not (self.compiler.opt.finite and self.active() and _TESTABLE.fullmatch(code)
                and _is_float(self.compiler.ty(arg))):
            return None
        deps = self.operand(arg, code)
        if deps is None:
            return None
        text = f"({finite_test(code, code)})"
        return self.value(text, text, deps)

    def stored(self, target, code: str, value: str) -> None:
        """`code = value` was compiled for `target := ...`: when it stores a value of this
        pass as it is into an own array's element at a literal index (a store that cannot
        fail), a later read of that element is that value (`stores_read`)."""
        if not (self.compiler.opt.stores_read and self.active() and isinstance(target, ast.Index)
                and isinstance(target.base, ast.Name)):
            return
        match, element = _TOKEN.fullmatch(value), _ELEMENT.fullmatch(code)
        if match is None or element is None:
            return
        symbol = self._own(target.base)
        t = resolve_alias(symbol.type) if symbol is not None else None
        if isinstance(t, ArrayType) and isinstance(resolve_alias(t.element), ElementaryType):
            self.element_store = (code, element.group(1), int(match.group(1)))

    def _read_back(self, code: str, array: str, index: int) -> None:
        """After the store `code = <value index>` (its array forgotten): the element read
        is that value while neither the array nor what the value reads changes."""
        value = self.values[index]
        if self.known.get(value.key) != index or value.level not in self.levels:
            return              # (the value read the array it was stored into: it ended)
        self.known[code] = index
        for name in value.deps | {array}:
            self.readers.setdefault(name, []).append(code)

    # ------------------------------------------------------------ resolve

    def resolve(self, lines: list[str], start: int) -> None:
        """Tokens and markers out of `lines[start:]`: a value used twice or more is set
        where it was first computed and read by name, one used once keeps its text."""
        if not self.values:
            return
        text = "\n".join(lines[start:])
        self._count_uses(text)
        names = {}

        def text_of(index: int) -> str:
            return _TOKEN.sub(token, self.values[index].text)

        def token(match) -> str:
            index = int(match.group(1))
            if self.values[index].uses >= 2:
                return names.setdefault(index, f"_c{index}")
            return text_of(index)

        text = _TOKEN.sub(token, text)
        new = text.split("\n")
        out, done, line, at = [], 0, 0, 0
        for marker in _MARKER.finditer(text):
            line += text.count("\n", at, marker.start())
            at = marker.start()
            indent = marker.group(1)
            defs = [f"{indent}_c{index} = {_kept(text_of(index))}"
                    for index in map(int, marker.group(2).split(",")) if self.values[index].uses >= 2]
            out.extend(new[done:line])
            before = out[-1] if out else ""
            after = new[line + 1] if line + 1 < len(new) else ""
            if not defs and before.rstrip().endswith(":") and len(after) - len(after.lstrip()) < len(indent):
                defs = [f"{indent}pass"]        # (the only line of its block)
            out.extend(defs)
            done = line + 1
        out.extend(new[done:])
        lines[start:] = out

    def _count_uses(self, text: str) -> None:
        """Each value's uses in the code as it will be: its tokens in the lines, and in the
        text of each value that uses it, once where that value is set (used twice or more)
        or where its one use puts it back (a value's operands come before it)."""
        counts = [0] * len(self.values)
        for index in _TOKEN.findall(text):
            counts[int(index)] += 1
        for index in range(len(self.values) - 1, -1, -1):
            if counts[index]:
                for inner in _TOKEN.findall(self.values[index].text):
                    counts[int(inner)] += 1
        for value, count in zip(self.values, counts):
            value.uses = count


def _kept(text: str) -> str:
    """The value `text` as set into its name: `finite`'s test as `True if test else False`,
    the same bool, its comparison specialised by CPython 3.11 (shortcut.stored)."""
    return f"(True if {text} else False)" if _FINITE_TEST.fullmatch(text) else text


def is_token(code: str) -> bool:
    """`code` is one value of this pass (a name once resolved, or text that cannot raise)."""
    return _TOKEN.fullmatch(code) is not None


def as_names(code: str) -> str:
    """`code` with each token as a name (what it may become: a value that cannot raise)."""
    return _TOKEN.sub(lambda m: f"_c{m.group(1)}", code) if "\x03" in code else code


def _is_float(t) -> bool:
    t = resolve_alias(t) if t is not None else None
    return isinstance(t, ElementaryType) and t.kind == "real"


def _own(compiler, name):
    """The symbol of `name` when it is plain storage of the POU or the globals (no
    reference, not located); else None."""
    symbol = branches._symbol(compiler, name)
    if symbol is None or symbol.kind not in _PLAIN_KINDS:
        return None
    if symbol.decl is not None and getattr(symbol.decl, "location", None) is not None:
        return None
    place = compiler.scope.places.get(name.name.upper())
    if place is not None and place.how not in ("local", "self", "alias", "global"):
        return None
    return symbol


def _stored(compiler, target) -> str | None:
    """The Python name of the plain own variable a store into `target` changes; None for
    a store through a reference, into an in-out, a located or a global variable."""
    name = root_name(target)
    if name is None or any(isinstance(x, ast.Deref) for x in _nodes(target)):
        return None
    symbol = _own(compiler, ast.Name(name, pos=target.pos))
    if symbol is None or symbol.kind in ("VAR_GLOBAL", "VAR_EXTERNAL"):
        return None
    place = compiler.scope.places.get(name)
    return place.name if place is not None else pyident(symbol.name)


def _calls_st(compiler, expr) -> bool:
    """`expr` calls code that may store (ST code, an FB, REF, a method): not only a
    standard function or conversion."""
    for n in _nodes(expr):
        if isinstance(n, ast.Call):
            target = compiler.program.call_targets.get(id(n))
            if target is None or target.kind not in ("function", "conversion") or target.pou is not None:
                return True
    return False
