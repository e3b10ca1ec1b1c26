"""`kernels`: a straight run of float assignments computed by one native call (native.py).

SP_InverseKinematics' legs are, once unrolled and shared by reuse.py, runs of lines such as

    v_U = (((v_R11 * -144.63258944329948) + (v_R12 * 361.0588824152176)) + _c36)
    v_LEGX = (v_U + (_c48 - 145.10370179947358))
    _c89 = (_m_sqrt((((v_LEGX * v_LEGX) + (v_LEGY * v_LEGY)) + (v_LEGZ * v_LEGZ))) - 1192.63)

each operation a bytecode that makes a float.  This pass, run on a body's finished lines,
replaces each span of runs with at least `MIN_OPERATIONS` operations in all by

    _kr = _k7(v_POSE, v_R11, v_R12, ..., v_POSITION)
    if _kr is None:
        <the lines as they were>
    else:
        v_U, v_LEGX, _c89, = _kr
        <the span's statements between its runs, in their order, but its finite tests>

where `_k7` is machine code LLVM makes from the runs (native.run_ir), compiled by its first
call.  A run line assigns a plain name a fully parenthesised `+ - *` or unary minus of
names, float literals, elements of a list at a literal index (`v_POSE[2]`) and
`_m_sqrt(...)` (the namespace's `math.sqrt`), and reads no variable declared of another
type than REAL/LREAL (`not_floats`); or it is the compiler's finite test of a name
`_cN = (True if (x < 1e309 and x > -1e309) else False)` (where the kernel answers x is
checked finite: `_cN = True` after it), or SIN or COS of a name behind such a test of the
same value, `(_m_cos(x) if _cN else _sf_COS(x))` (the C library's `cos`, the very function
math.cos calls: native.libm_symbols), or behind its own test of the name kept in the
compiler's temporary, `(_m_cos(_t1) if (_t1 := x) < 1e309 and _t1 > -1e309 else _sf_COS(_t1))`
(the kernel checks x finite; it leaves `_t1` unset: exprs.py's `temp` is read only in the
statement that sets it, and the next statement sets it before reading it).  A name may be
an instance's variable, `self.v_X` (read as an argument, or set: always returned); `_sf_ATAN(...)` is the C library's `atan`
where the library's ATAN is math.atan.  A run line may store into a list element at a
literal index, `L[k] = <expression>` (the kernel returns the value as `_kvN`, stored after
it as a deferred statement), and may be the one line of a `try:` whose `except _FAULTS`
handler cannot run where the kernel answers (nothing in the line raises there).  A span (`_Span`) goes on across, at its indentation:

* a finite test `if (not (x < 1e309 and x > -1e309)):` (no `else`) of a value the kernel
  computed: where it answers every such value is finite, so the branch is not taken there;
* a statement that cannot raise on floats, ints and bools (`_Span._defer`): a store of a
  run's value or of a test into a list element at a literal index, a test's `if`/`else`,
  a charge `_spent += <int>`, an assignment of a test to a name no run line reads or sets.
  Where the kernel answers these run after it, in their order; a run line that would read
  or change what one of them reads or sets ends the span before it (a run line reading an
  element stored in the span reads the run's value stored there, any other ends it).  The
  kernel checks each list stored into is a list long enough and no other list it reads, so
  no store can raise or change what it read.  The charges total the same on every path;
* one budget check (`_Span._budget_check`), which runs in its place among those statements
  (the charges before it made, the names the runs set before it set), where a run line
  after it may set only reuse.py's shared values `_cN` and the variables the check's
  branch loads before `_overrun`: where it fails, the body ends (ScanOverrun) with every
  variable it stores back as without the kernel (SP_InverseKinematics: the prologue, the
  rotation and the six legs one kernel).

Exactness: each operation is the IEEE-754 binary64 instruction on the same operands in the
same order (`fmul`/`fadd`/`fsub`/`fneg`, no fast-math flags, no FMA: see native.py), and
`llvm.sqrt.f64` is correctly rounded, as `math.sqrt` is (IEEE-754 requires both).  The
kernel returns the values only when every argument is what the lines read (a Python float,
a list long enough whose elements it reads are floats, lists stored into distinct from the
others) and every value it computed is finite; otherwise None, and the lines run in Python
as written, so an int operand, a short list (its IndexError), a negative SQRT argument (its
ValueError), an inf or a NaN (whose sign or payload could differ) all take today's code,
statement for statement.  The arguments are read before the span instead of where the lines
read them: nothing in it stores anything the runs read but their own local names and the
elements they then read as the values stored, so each reads what the lines would have read.
The kernel returns the names the span sets that a line outside it or a statement it keeps
names, each with its last value, as after the lines (the others are never read again).

Off without llvmlite or with `ST_RUNTIME_NATIVE=0` (native.enabled), and by its switch.
"""

from __future__ import annotations

import collections
import functools
import itertools
import re

from . import native

MIN_OPERATIONS = 16      # a crossing costs about as much as a dozen float operations in Python
#: A line that may qualify: `name = `, `self.name = ` or `list[k] = ` (not an element of an
#: instance's array: its list may be one a local name holds too) and only the characters of
#: the forms above.
_CANDIDATE = re.compile(r"( *)((?:self\.)?[A-Za-z_]\w*|[A-Za-z_]\w*\[\d+\]) = ([\w.()+*\[\]<> -]+"
                        r"|\(_m_(?:sin|cos)\(_t\d+\) if \(_t\d+ := [\w.]+\) < 1e309 and _t\d+ > -1e309 else _sf_\w+\(_t\d+\)\))\Z")
_TOKEN = re.compile(r" *(?:(\d+\.\d*(?:e[+-]?\d+)?|\d+e[+-]?\d+)|((?:self\.)?[A-Za-z_]\w*)|(\d+)|(\S))")
#: The compiler's finite test of a name kept in a temporary (calls.py, pysrc.finite_test).
_TEST = re.compile(r"\(True if \(((?:self\.)?[A-Za-z_]\w*) < 1e309 and \1 > -1e309\) else False\)\Z")
#: SIN or COS of a name behind that test (calls.py `_GUARDED`): `(_m_sin(x) if _cN else _sf_SIN(x))`.
_GUARDED = re.compile(r"\(_m_(?P<f>sin|cos)\((?P<x>(?:self\.)?[A-Za-z_]\w*)\) if (?P<test>[A-Za-z_]\w*)"
                      r" else _sf_(?P<F>SIN|COS)\((?P=x)\)\)\Z")
#: SIN or COS of a name kept in the compiler's temporary behind its finite test, where no local
#: holds the test (calls.py `_GUARDED`): `(_m_sin(_t1) if (_t1 := x) < 1e309 and _t1 > -1e309 else _sf_SIN(_t1))`.
_TEMP_GUARDED = re.compile(r"\(_m_(?P<f>sin|cos)\((?P<t>_t\d+)\) if \((?P=t) := (?P<x>(?:self\.)?[A-Za-z_]\w*)\)"
                           r" < 1e309 and (?P=t) > -1e309 else _sf_(?P<F>SIN|COS)\((?P=t)\)\)\Z")
_NAME = re.compile(r"(?<![\w.])[A-Za-z_]\w*")
_NOT_NAMES = frozenset({"True", "False", "None", "_m_sqrt", "_sf_ATAN", "_kr"})
#: A store's target `L[k]`: the list and the index.
_STORE = re.compile(r"([A-Za-z_]\w*)\[(\d+)\]\Z")
_NAME_ONLY = re.compile(r"[A-Za-z_]\w*\Z")


class _NotPure(Exception):
    """The line is not of the forms the kernel computes."""


@functools.lru_cache(maxsize=8192)
def _tree(text: str):
    """(tree, names read as floats, lists read) of an expression the kernel computes, None
    for any other: a tree is ("c", IR literal) | ("n", name) | ("e", list, index) |
    (op, operand...) with op "*", "+", "-", "neg" or "sqrt" | ("test", ("n", name)) (the
    finite test) | ("sin" or "cos", ("n", name), the test's name, or None where the line
    tests the name itself in the compiler's temporary `_tN`).  Kept by text: the same
    lines come back in every load of a program and in its fast and exact copies."""
    test = _TEST.match(text)
    if test is not None:
        return ("test", ("n", test[1])), frozenset([test[1]]), frozenset()
    guarded = _GUARDED.match(text) or _TEMP_GUARDED.match(text)
    if guarded is not None:
        if guarded["f"].upper() != guarded["F"]:
            return None
        return (guarded["f"], ("n", guarded["x"]), guarded.groupdict().get("test")), frozenset([guarded["x"]]), frozenset()
    tokens = _TOKEN.findall(text)
    names: tuple[set, set] = (set(), set())
    try:
        tree, i = _sum(tokens, 0, names)
    except (_NotPure, IndexError):
        return None
    if i != len(tokens) or names[0] & names[1]:
        return None
    return tree, frozenset(names[0]), frozenset(names[1])


def _sum(tokens, i, names):
    """`primary [op primary]` (the compiler parenthesises every operation)."""
    left, i = _primary(tokens, i, names)
    if i < len(tokens) and tokens[i][3] in ("+", "-", "*"):
        op = tokens[i][3]
        right, i = _primary(tokens, i + 1, names)
        return (op, left, right), i
    return left, i


def _primary(tokens, i, names):
    number, name, integer, char = tokens[i]
    if number:
        return ("c", native.ir_double(float(number))), i + 1
    if char == "(":
        tree, i = _sum(tokens, i + 1, names)
        if tokens[i][3] != ")":
            raise _NotPure("(")
        return tree, i + 1
    if char == "-":
        if tokens[i + 1][0]:                      # `-1.5`: Python's constant, folded
            return ("c", native.ir_double(-float(tokens[i + 1][0]))), i + 2
        operand, i = _primary(tokens, i + 1, names)
        return ("neg", operand), i
    if (name == "_m_sqrt" or name == "_sf_ATAN" and _atan_is_maths()) and tokens[i + 1][3] == "(":
        operand, i = _sum(tokens, i + 2, names)
        if tokens[i][3] != ")":
            raise _NotPure(name)
        return ("sqrt" if name == "_m_sqrt" else "atan", operand), i + 1
    if not name or name in _NOT_NAMES:
        raise _NotPure(name or char or integer)
    if i + 1 < len(tokens) and tokens[i + 1][3] == "[":
        if not tokens[i + 2][2] or tokens[i + 3][3] != "]":
            raise _NotPure(name)
        names[1].add(name)
        return ("e", name, int(tokens[i + 2][2])), i + 4
    names[0].add(name)
    return ("n", name), i + 1


@functools.cache
def _atan_is_maths() -> bool:
    """Whether `_sf_ATAN`, the library's ATAN the compiler binds (CompileUnit.bind_function),
    is math.atan itself (stdlib/functions.py: no wrapper), which calls the C library's `atan`
    and returns its result unchanged for every float (mathmodule.c `math_1`: atan is finite)."""
    import math

    from ...stdlib.functions import FUNCTIONS

    return FUNCTIONS.get("ATAN") is math.atan


class _Run:
    """The values of a run: arguments read before it, then operations in order."""

    def __init__(self):
        self.arguments: list[tuple] = []      # ("float", value) | ("list", {k: value}) by argument
        self.texts: list[str] = []            # each argument's Python expression
        self.kind: dict[str, str] = {}        # an argument's text -> "float" | "list"
        self.lists: dict[str, dict] = {}      # a list argument's text -> {index: value}
        self.env: dict[str, str] = {}         # local name -> its value now
        self.ops: list[tuple] = []
        self.assigned: dict[str, None] = {}   # the names the run sets, in order
        self.results: set[str] = set()        # the values operations computed
        self.overrides: dict[tuple, str] = {} # (list, index) -> the value stored there in the span
        self.tests: dict[str, str] = {}       # a finite test's name -> the value it tested
        self.count = 0

    def value(self) -> str:
        self.count += 1
        return f"%v{self.count}"

    def assign(self, target: str, text: str, overrides: dict) -> bool:
        """Add `target = text`, reading the list elements in `overrides` as those values;
        False, the run unchanged, when the line does not qualify (not of the forms, or a
        name read both as a float and as a list in the run)."""
        parsed = _tree(text)
        if parsed is None:
            return False
        tree, floats, lists = parsed
        if any(name in self.env for name in lists) or any(self.kind.get(name) == "list" for name in floats):
            return False
        if target in self.tests or not floats.isdisjoint(self.tests) or tree[0] in ("sin", "cos") and tree[2] and (
                tree[2] not in self.tests or self.tests[tree[2]] != self.env.get(tree[1][1])):
            return False            # (a test is read only as the guard of SIN or COS of the value it tested)
        self.overrides.update(overrides)
        if tree[0] in ("sin", "cos") and tree[2] is None:     # the line's own test: checked finite
            self.ops.append((None, "finite", self._value_of(tree[1])))
        if tree[0] == "test":       # True where the kernel answers: the value it tested is checked finite
            self.tests[target] = tested = self._value_of(tree[1])
            self.ops.append((None, "finite", tested))
            self.env[target] = "test"
        else:
            self.env[target] = self._value_of(tree)
        self.assigned[target] = None
        return True

    def computed(self, name: str) -> bool:
        """Whether `name`'s value now is one an operation of the run computed."""
        return self.env.get(name) in self.results

    def finished(self, stored: dict[str, set]) -> tuple[list, list]:
        """The kernel's arguments, the lists `stored` (list -> indices) added (each checked
        long enough for the stores), and the pairs of arguments that must not be one list
        (a store into one would change what the kernel read of the other)."""
        sizes = {}
        for name, indices in stored.items():
            if name not in self.kind:
                self._argument(name, "list", {})
            sizes[name] = max(indices) + 1
        arguments = [(kind, held, max(sizes.get(text, 0), max(held, default=-1) + 1)) if kind == "list"
                     else (kind, held) for text, (kind, held) in zip(self.texts, self.arguments)]
        lists = [j for j, text in enumerate(self.texts) if self.kind[text] == "list"]
        distinct = [(j, k) for j in lists for k in lists if j < k and (self.texts[j] in stored or self.texts[k] in stored)]
        return arguments, distinct

    def _value_of(self, tree) -> str:
        kind = tree[0]
        if kind == "c":
            return tree[1]
        if kind == "n":
            value = self.env.get(tree[1])
            if value is None:
                value = self.env[tree[1]] = self._argument(tree[1], "float", self.value())
            return value
        if kind == "e":
            if (tree[1], tree[2]) in self.overrides:
                return self.overrides[tree[1], tree[2]]
            held = self.lists.get(tree[1])
            if held is None:
                held = self.lists[tree[1]] = self._argument(tree[1], "list", {})
            if tree[2] not in held:
                held[tree[2]] = self.value()
            return held[tree[2]]
        operands = [self._value_of(operand) for operand in (tree[1:2] if kind in native.LIBM else tree[1:])]
        value = self.value()
        self.ops.append((value, kind, *operands))
        self.results.add(value)
        return value

    def _argument(self, text: str, kind: str, held):
        self.texts.append(text)
        self.kind[text] = kind
        self.arguments.append((kind, held))
        return held


def replace(lines: list[str], start: int, register, bind, not_float=None) -> None:
    """Replace the qualifying spans in `lines[start:]` (a body's finished lines) by a kernel
    call each.  `register(value)`: the namespace name bound to a value; `bind(name, value)`
    rebinds it (the kernel in place of its first call); `not_float(name, element)`: whether
    a name (an element of it) is declared of a type other than REAL/LREAL (`not_floats`),
    read by no run line: its kernel would answer None at every call."""
    body = lines[start:]
    text = "\n".join(body)
    if text.count("*") + text.count("+") + text.count("-") + text.count("_m_sqrt(") < MIN_OPERATIONS:
        return          # (each operation of a run but a unary minus shows one of these: too few)
    matches = list(map(_CANDIDATE.match, body))               # (one C loop over every line)
    offsets = list(itertools.accumulate(map(len, body), initial=0))   # line k starts at offsets[k] + k
    spans, end, mentions, blocks = [], 0, None, None
    for i in itertools.compress(range(len(matches)), matches):
        if i < end or _tree(matches[i].group(3)) is None:      # (a span starts with a run line)
            continue
        if blocks is None:      # (once a line may start a span: each line's block end and count once)
            blocks, operations = _block_ends(body), _operations_before(body)
        block = blocks[i]
        if operations[block] - operations[i] < MIN_OPERATIONS:
            end = block     # (no span from a line of the block reaches the minimum: none built)
            continue
        span = _Span(body, matches, i, text, offsets, not_float)
        end = max(span.end, i + 1)
        if sum(op[1] not in ("neg", "finite") for op in span.run.ops) >= MIN_OPERATIONS:
            mentions = mentions or collections.Counter(_NAME.findall(text))
            stores = span.stores_in_kernel()
            live = _read_after(span, body[i:span.end], mentions, one=not stores)
            spans.append((start + i, start + span.end, _call(body[i:span.end], span, live, stores, register, bind)))
    for i, j, new in reversed(spans):          # from the last: the indices stay true
        lines[i:j] = new


def _block_ends(lines: list[str]) -> list[int]:
    """For each line, the first line after it indented less, blank lines aside (a line of
    spaces, or whose first character after them is other white space); len(lines) for a line
    of the outermost indentation or none such after it: a span from a line of the block
    (indented as deep or deeper) ends before it (`_Span`: a run line, a `try:` and a
    statement it goes on across are at its indentation, their blocks deeper).  One walk:
    the lines still open are held on a stack, indented no less than those below them."""
    ends = [len(lines)] * len(lines)
    open_lines: list[tuple[int, int]] = []          # (indentation, line)
    for j, line in enumerate(lines):
        stripped = line.lstrip(" ")
        if not stripped or stripped[0].isspace():
            continue
        indent = len(line) - len(stripped)
        while open_lines and open_lines[-1][0] > indent:
            ends[open_lines.pop()[1]] = j
        open_lines.append((indent, j))
    return ends


def _operations_before(lines: list[str]) -> list[int]:
    """For each line k (and len(lines)), at least the operations `_Span` counts of the run
    lines before it, counted in every line that holds ` = ` (every run line is one; a
    charge's `+=`, an `if` are none): a `+`, `-` or `*` each, or a call of `_m_sqrt`,
    `_sf_ATAN`, `_m_sin` or `_m_cos`; but the finite tests' `-1e309` (in no run line but the
    finite test, whose operation is not counted).  Lines i to j count `result[j] - result[i]`:
    those of a block, the same or more than a span from a line of it (the block from there a
    part of it), each line counted once."""
    return list(itertools.accumulate([len(_OPERATION.findall(line)) - line.count("> -1e309") if " = " in line else 0
                                      for line in lines], initial=0))


#: What `_operations_before` counts, in one C scan of a line (no two of its parts overlap).
_OPERATION = re.compile(r"[*+-]|_m_(?:sqrt|sin|cos)\(|_sf_ATAN\(")


@functools.cache
def _statement_break(indent: int) -> re.Pattern:
    """A line break before a line that does not go on a statement indented by `indent`: one
    not indented deeper, nor its `else:` or `elif`."""
    at = " " * indent
    return re.compile(rf"\n(?!{at} |{at}else:|{at}elif )")


def _read_after(span, original: list[str], mentions: collections.Counter, one=True) -> list[str]:
    """The names the span sets that a line outside it or a statement it keeps names, and
    the instance's variables it sets (`self.v_X`): the others are never read again, the
    kernel need not return them; with `one`, at least one value (a kernel that stores
    nothing itself returns one)."""
    inside = collections.Counter(_NAME.findall("\n".join(original)))
    kept = set(_NAME.findall("\n".join(line for lines in span.kept for line in lines)))
    names = list(span.run.assigned)
    return ([name for name in names if mentions[name] > inside[name] or name in kept or name.startswith("self.")]
            or [name for name in names if name not in span.run.tests][-1:] * one)


#: `if (not (x < 1e309 and x > -1e309)):`, the compiler's test that a REAL is finite.
_FINITE_TEST = re.compile(r"( *)if \(not \(([A-Za-z_]\w*) < 1e309 and \2 > -1e309\)\):\Z")
#: The tokens of a statement that may run after the kernel (`_Span.defer`).
_SAFE_TOKEN = re.compile(r" *(?:(\d+\.\d*(?:e[+-]?\d+)?|\d+e[+-]?\d+|\d+)|([A-Za-z_]\w*)(?:\[(\d+)\])?"
                         r"|(<=|>=|==|!=|\+=|[<>()=:-]))")
_KEYWORDS = frozenset({"True", "False", "not", "and", "or", "if", "else", "elif"})
_CHARGE = "_spent"          # the compiler's charge counter, an int (charges.py)
#: A budget check (statements.py `_charge`), with the loads aliases.py `drop_unread` makes
#: in its branch of the variables set after it: `if _ctx.budget < _spent: v_U = self.v_U; _overrun((...))`.
_BUDGET_CHECK = re.compile(r"( *)if _ctx\.budget < _spent: ((?:(\w+) = self\.\3; )*)_overrun\(\([^()]*\)\)\Z")
_RELOAD = re.compile(r"(\w+) = self\.\1; ")
#: reuse.py's shared values: locals of the body, never the instance's (no store back).
_SHARED = re.compile(r"_c\d+\Z|_kv\d+\Z")            # (and this pass's own values of stores)
#: A kept line that stores into a list element, and one that stores a value of `_store`.
_STORED = re.compile(r" *([A-Za-z_]\w*)\[(\d+)\] = ")
_OWN_STORE = re.compile(r" *([A-Za-z_]\w*)\[(\d+)\] = _kv\d+\Z")


class _Span:
    """The lines from `body[first]` on that one kernel computes: runs of float assignments
    (`_Run`), separated by statements that run after the kernel where it answers (stores
    of its values into list elements, tests and charges that cannot raise: `_defer`) and by
    finite tests of values it computed (never taken where it answers: dropped there).  It
    stops before the first line that is none of these, or that would read or change what a
    line before or after it must see; it ends after its last run line or finite test."""

    def __init__(self, body: list[str], matches: list, first: int, text: str, offsets: list[int], not_float=None):
        self.run = _Run()
        self.not_float = not_float
        self.text, self.offsets = text, offsets  # the body's lines joined, where each starts (`replace`)
        self.indent = matches[first].group(1)
        self.kept: list[list[str]] = []          # the deferred statements' lines, in order
        self.stored: dict[str, set] = {}         # list -> indices the kept statements store into
        self.elements: dict[tuple, object] = {}  # (list, index) stored -> the run's value, or None
        self.read_later: set[str] = set()        # names the deferred statements read
        self.targets: set[str] = {_CHARGE}       # names the deferred statements set (and the charge)
        self.reloaded: set[str] | None = None    # after a budget check: the names its branch loads
        self.before_check: set[str] = set()      # the names the runs set before it
        self.own: list[tuple] = []               # the stores of the run line just added
        self.values = 0                          # the values of stores made (`_kv0`, `_kv1` ...)
        self.end = first
        if not self._assign(matches[first].group(2), matches[first].group(3)):
            return                               # (a span starts with a run line)
        self._keep([])
        pending: list[tuple] = []                # deferred since the last run line or finite test
        i = self.end = first + 1
        while i < len(body):
            match = matches[i]
            if match is not None and match.group(1) == self.indent and self._assign(match.group(2), match.group(3)):
                i += 1
            elif (j := self._guarded_line(body, i, matches)) is not None:
                i = j
            else:
                j = self._statement_end(body, i)
                if j is None:
                    break
                if not self._finite_test(body[i:j]):
                    deferred = self._budget_check(body[i:j]) or self._defer(body[i:j])
                    if deferred is None:
                        break
                    pending.append(deferred)
                    i = j
                    continue
                i = j
            self._keep(pending)
            pending, self.end = [], i

    def stores_in_kernel(self) -> list[tuple[str, int, str]]:
        """The stores of the run's values `L[k] = _kvN` (`_store`) the kernel makes itself,
        taken out of the kept statements, as (list, index, value): each one before the budget
        check, into an element no other kept statement stores into.  Where the kernel answers
        it makes them after every check, so they happen exactly where the kept statements
        before them happen (none of those raises, none reads the element: a kept statement
        reads only elements stored before it, `_safe`) and the ones after them read what they
        store; L is a list the kernel checks (long enough, no other list it reads)."""
        stored = collections.Counter(store.groups() for lines in self.kept for line in lines
                                     if (store := _STORED.match(line)) is not None)
        moved, kept, checked = [], [], False
        for lines in self.kept:
            own = _OWN_STORE.match(lines[0]) if len(lines) == 1 and not checked else None
            if own is not None and stored[own.groups()] == 1:
                moved.append((own[1], int(own[2]), self.elements[own[1], int(own[2])]))
            else:
                checked = checked or _BUDGET_CHECK.match(lines[0]) is not None
                kept.append(lines)
        self.kept = kept
        return moved

    def _keep(self, pending: list[tuple]) -> None:
        """Keep the deferred statements `pending`, then the stores of the run line after them."""
        for lines, stores in pending + self.own:
            self.kept.append(lines)
            for name, index in stores:
                self.stored.setdefault(name, set()).add(index)
        self.own = []

    def _guarded_line(self, body: list[str], i: int, matches: list):
        """The end of `try:`, a run line, `except _FAULTS as _e:` and its handler at `body[i]`
        (the line added to the run), None for anything else: where the kernel answers the line
        raises nothing (floats, lists long enough, every value finite), so the handler does not
        run there."""
        if body[i] != self.indent + "try:" or i + 2 >= len(body) or body[i + 2] != self.indent + "except _FAULTS as _e:":
            return None
        inner = matches[i + 1]
        j = i + 3
        while j < len(body) and body[j].startswith(self.indent + " "):
            j += 1
        if (inner is None or inner.group(1) != self.indent + "    " or j == i + 3
                or j < len(body) and body[j].startswith((self.indent + "else:", self.indent + "finally:", self.indent + "except"))):
            return None
        return j if self._assign(inner.group(2), inner.group(3)) else None

    def _statement_end(self, body: list[str], i: int):
        """The end of the statement at `body[i]`: its block and any `elif`/`else`; None when
        it is not at the span's indentation."""
        if not body[i].startswith(self.indent) or body[i][len(self.indent):len(self.indent) + 1] in ("", " "):
            return None
        at = self.offsets[i] + i                  # (line i's start in the text: one C search)
        found = _statement_break(len(self.indent)).search(self.text, at)
        return len(body) if found is None else i + 1 + self.text.count("\n", at, found.start())

    def _finite_test(self, lines: list[str]) -> bool:
        """Whether `lines` are an `if` without `else` testing that a value the run computed is
        finite: where the kernel answers, every such value is, and the branch is not taken."""
        test = _FINITE_TEST.match(lines[0])
        return (test is not None and test.group(1) == self.indent and self.run.computed(test.group(2))
                and not any(line.startswith(self.indent) and line[len(self.indent)] != " " for line in lines[1:]))

    def _budget_check(self, lines: list[str]):
        """(lines, no stores) when `lines` are the span's first budget check: it runs after
        the kernel where it answers, in its place among the deferred statements, so the
        charges before it are made and the names the runs set before it are set when it
        fails; a run line after it may set only reuse.py's shared values (locals no store
        back writes) and the variables its branch loads (`_assign`): when it fails, those
        hold what they held without the kernel.  Its fault (support.overrun's ScanOverrun,
        none of the `_FAULTS` a handler in the body catches) ends the body: its locals are
        seen after it only through the store back of its variables."""
        check = _BUDGET_CHECK.match(lines[0]) if len(lines) == 1 and self.reloaded is None else None
        if check is None or check.group(1) != self.indent:
            return None
        self.reloaded = set(_RELOAD.findall(check.group(2)))
        self.before_check = set(self.run.assigned)
        return lines, []

    def _store(self, name: str, index: int, text: str) -> bool:
        """`L[k] = <expression>`: the run computes the expression as a value `_kvN` the kernel
        returns, and the store of it is a deferred statement (`_defer`'s conditions).  A
        store of a name is `_defer`'s: the run's value is stored as it is, no value more."""
        if _NAME_ONLY.match(text) or name in self.run.env or name in self.read_later or self.run.kind.get(name) == "float" or name == _CHARGE:
            return False
        value = f"_kv{self.values}"
        if not self._assign(value, text):
            return False
        self.values += 1
        self.elements[(name, index)] = self.run.env[value]
        self.targets.add(name)
        self.own.append(([f"{self.indent}{name}[{index}] = {value}"], [(name, index)]))
        return True

    def _assign(self, target: str, text: str) -> bool:
        """Add a run's line, unless it sets what a deferred statement reads or sets, reads
        what one sets, or reads a list element one stored other than a value of the run;
        after a budget check, unless it sets a variable the check's branch does not load.
        A target `L[k]` is a store (`_store`)."""
        store = _STORE.match(target)
        if store is not None:
            return self._store(store[1], int(store[2]), text)
        parsed = _tree(text)
        if parsed is None or target in self.read_later or target in self.targets:
            return False
        if self.reloaded is not None and not (
                _SHARED.match(target) or target in self.reloaded and target not in self.before_check):
            return False
        tree, floats, lists = parsed
        if floats & self.targets or self.not_float is not None and (
                any(self.not_float(_variable(name), False) for name in floats)
                or any(self.not_float(_variable(name), True) for name in lists)):
            return False
        overrides = {element: self.elements[element] for element in _elements(tree)
                     if element in self.elements} if self.elements else {}
        if None in overrides.values():
            return False
        return self.run.assign(target, text, overrides)

    def _defer(self, lines: list[str]):
        """(lines, stores) when the statement `lines` may run after the kernel where it
        answers, else None.  Each line is `if/elif <test>:`, `else:`, `_spent += <int>`,
        `_spent = <int>` or `<name or list[int]> = <test>`, a test made of the run's names
        (floats where it answers) that no later run line sets, elements this span stored
        before, numbers, `True`/`False`, comparisons, `not`, `and`, `or` and `x if c else y`:
        none of it can raise on floats, ints and bools.  A list it stores into is one the
        kernel checks (a list, long enough, no other list it reads); a name it sets is one
        no run line reads or sets."""
        stores, reads, targets = [], set(), set()
        for line in lines:
            words = _words(line)
            if words is None:
                return None
            if words[0] in (("if", ""), ("elif", "")) and words[-1] == ":":
                expression = words[1:-1]
            elif words == [("else", ""), ":"]:
                continue
            elif words[0] == (_CHARGE, "") and len(words) == 3 and words[1] in ("+=", "=") and words[2].isdigit():
                continue
            elif len(words) > 2 and words[1] == "=" and isinstance(words[0], tuple) and words[0][0] != _CHARGE \
                    and words[0][0] not in _KEYWORDS:
                (name, index), expression = words[0], words[2:]
                if name in self.run.env or name in self.read_later or self.run.kind.get(name) == "float" \
                        or not index and name in self.run.kind:
                    return None
                if index:
                    stores.append((name, int(index)))
                    value = expression[0] if len(expression) == 1 else None
                    self.elements[(name, int(index))] = (
                        self.run.env.get(value[0]) if isinstance(value, tuple) and not value[1] else None)
                else:
                    targets.add(name)
            else:
                return None
            if not self._safe(expression, reads):
                return None
        self.read_later |= reads
        self.targets |= targets | {name for name, _ in stores}
        return lines, stores

    def _safe(self, words: list, reads: set) -> bool:
        """Whether the expression `words` is a test as `_defer` describes (its names into
        `reads`): no call (a name before `(`), a minus only the sign of a number."""
        for previous, word, following in zip([""] + words, words, words[1:] + [""]):
            if isinstance(word, tuple):
                name, index = word
                if following == "(" and name not in _KEYWORDS:
                    return False
                if index:
                    if (name, int(index)) not in self.elements:
                        return False
                elif name in _KEYWORDS:
                    continue
                elif name in self.run.env and self.run.kind.get(name) != "list":
                    reads.add(name)
                else:
                    return False
            elif word == "-":
                operand_before = (previous[0] not in _KEYWORDS if isinstance(previous, tuple)
                                  else previous == ")" or previous[:1].isdigit())
                if operand_before or isinstance(following, tuple) or not following[:1].isdigit():
                    return False
            elif word not in ("(", ")", "<", ">", "<=", ">=", "==", "!=") and not word[0].isdigit():
                return False
        return bool(words)


@functools.lru_cache(maxsize=8192)
def _words(line: str):
    """A line's tokens: (name, index or "") for a name or a list element, else the text;
    None when the line holds anything else.  Kept by text, as `_tree`."""
    tokens = _SAFE_TOKEN.findall(line)
    if "".join(map(_text, tokens)) != line.replace(" ", ""):
        return None
    return [(t[1], t[2]) if t[1] else t[0] or t[3] for t in tokens] or None


def _text(token: tuple) -> str:
    number, name, index, char = token
    return f"{name}[{index}]" if index else number or name or char


def not_floats(places):
    """`replace`'s `not_float` for a scope's `places`: a variable (or an array's element) of a
    declared type other than REAL/LREAL; a name no place has (a compiler temporary) is not
    known to be one."""
    from ...types import ArrayType, resolve_alias
    from ..exprs import is_real

    symbols, known = {}, {}

    def not_float(name: str, element: bool) -> bool:
        answer = known.get((name, element))
        if answer is None:
            answer = known[name, element] = _declared_not_float(name, element)
        return answer

    def _declared_not_float(name: str, element: bool) -> bool:
        if not symbols:
            symbols.update((place.name, place) for place in places.values())
            symbols.setdefault("", None)
        place = symbols.get(name)
        if place is None:
            return False
        t = resolve_alias(place.symbol.type)
        if element:
            return not (isinstance(t, ArrayType) and is_real(t.element))
        return not is_real(t)
    return not_float


def _variable(name: str) -> str:
    """The variable a name of the generated code holds: `self.v_X` and `v_X` are `v_X`."""
    return name[5:] if name.startswith("self.") else name


def _elements(tree):
    """The (list, index) elements a tree reads."""
    if tree[0] == "e":
        yield tree[1], tree[2]
    elif tree[0] not in ("c", "n"):
        for operand in tree[1:2] if tree[0] in native.LIBM else tree[1:]:     # (SIN's test name no operand)
            yield from _elements(operand)


def _call(original: list[str], span: _Span, targets: list[str], stores: list[tuple], register, bind) -> list[str]:
    """The lines that call the span's kernel, returning `targets` and making `stores` (list,
    index, value), with `original` where it returns None."""
    run, indent = span.run, span.indent
    tests = [t for t in targets if t in run.tests]          # True where the kernel answers
    targets = [t for t in targets if t not in run.tests]
    outputs = [run.env[t] for t in targets]
    arguments, distinct = run.finished(span.stored)
    kernel = register(None)
    libm = any(op[1] in native.LIBM for op in run.ops)

    def ir() -> str:
        if libm:
            native.bind_symbols(native.libm_symbols())
        return native.run_ir(arguments, run.ops, outputs, distinct,
                             [(run.texts.index(name), k, value) for name, k, value in stores])
    bind(kernel, native.on_first_call(ir, lambda built: bind(kernel, built)))
    return ([f"{indent}_kr = {kernel}({', '.join(run.texts)})", f"{indent}if _kr is None:"]
            + ["    " + line for line in original]
            + _else(indent, [f"    {', '.join(targets)}, = _kr"] * bool(targets) + [f"    {t} = True" for t in tests]
                    + ["    " + line[len(indent):] for lines in span.kept for line in lines]))


def _else(indent: str, lines: list[str]) -> list[str]:
    """`else:` and `lines` under it, nothing without lines (a kernel that stores all it makes)."""
    return [f"{indent}else:"] + [indent + line for line in lines] if lines else []
