"""`kernels`: a straight run of float assignments computed by one native call (native.py).

SP_InverseKinematics' legs are, once unrolled and shared by reuse.py, runs of lines such as

    v_U = (((v_R11 * -144.63258944329948) + (v_R12 * 361.0588824152176)) + _c36)
    v_LEGX = (v_U + (_c48 - 145.10370179947358))
    _c89 = (_m_sqrt((((v_LEGX * v_LEGX) + (v_LEGY * v_LEGY)) + (v_LEGZ * v_LEGZ))) - 1192.63)

each operation a bytecode that makes a float.  This pass, run on a body's finished lines,
replaces each run of at least `MIN_OPERATIONS` consecutive such lines at one indentation by

    _kr = _k7(v_POSE, v_R11, v_R12, ...)
    if _kr is None:
        <the lines as they were>
    else:
        v_U, v_LEGX, _c89, = _kr

where `_k7` is machine code LLVM makes from the run (native.run_ir), compiled by its first
call.  A line qualifies when it assigns a plain name a fully parenthesised `+ - *` or unary
minus of names, float literals, elements of a list at a literal index (`v_POSE[2]`) and
`_m_sqrt(...)` (the namespace's `math.sqrt`).

Exactness: each operation is the IEEE-754 binary64 instruction on the same operands in the
same order (`fmul`/`fadd`/`fsub`/`fneg`, no fast-math flags, no FMA: see native.py), and
`llvm.sqrt.f64` is correctly rounded, as `math.sqrt` is (IEEE-754 requires both).  The
kernel returns the values only when every argument is what the lines read as a float (a
Python float, a list long enough whose elements are floats) and every value it computed is
finite; otherwise None, and the lines run in Python as written, so an int operand, a short
list (its IndexError), a negative SQRT argument (its ValueError), an inf or a NaN (whose sign
or payload could differ) all take today's code, statement for statement.  The arguments are
read before the run instead of where the lines read them: nothing in the run stores
anything but its own local names, so each reads what the lines would have read.  Every name
the run assigns gets its last value, as after the lines.

Off without llvmlite or with `ST_RUNTIME_NATIVE=0` (native.enabled), and by its switch.
"""

from __future__ import annotations

import functools
import itertools
import re

from . import native

MIN_OPERATIONS = 16      # a crossing costs about as much as a dozen float operations in Python
#: A line that may qualify: `name = ` and only the characters of the forms above.
_CANDIDATE = re.compile(r"( *)([A-Za-z_]\w*) = ([\w.()+*\[\] -]+)\Z")
_TOKEN = re.compile(r" *(?:(\d+\.\d*(?:e[+-]?\d+)?|\d+e[+-]?\d+)|([A-Za-z_]\w*)|(\d+)|(\S))")
_NOT_NAMES = frozenset({"True", "False", "None", "_m_sqrt", "_kr"})


class _NotPure(Exception):
    """The line is not of the forms the kernel computes."""


@functools.lru_cache(maxsize=8192)
def _tree(text: str):
    """(tree, names read as floats, lists read) of an expression the kernel computes, None
    for any other: a tree is ("c", IR literal) | ("n", name) | ("e", list, index) |
    (op, operand...) with op "*", "+", "-", "neg" or "sqrt".  Kept by text: the same lines
    come back in every load of a program and in its fast and exact copies."""
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
        return ("c", native._double(float(number))), i + 1
    if char == "(":
        tree, i = _sum(tokens, i + 1, names)
        if tokens[i][3] != ")":
            raise _NotPure("(")
        return tree, i + 1
    if char == "-":
        if tokens[i + 1][0]:                      # `-1.5`: Python's constant, folded
            return ("c", native._double(-float(tokens[i + 1][0]))), i + 2
        operand, i = _primary(tokens, i + 1, names)
        return ("neg", operand), i
    if name == "_m_sqrt" and tokens[i + 1][3] == "(":
        operand, i = _sum(tokens, i + 2, names)
        if tokens[i][3] != ")":
            raise _NotPure("sqrt")
        return ("sqrt", operand), i + 1
    if not name or name in _NOT_NAMES:
        raise _NotPure(name or char or integer)
    if i + 1 < len(tokens) and tokens[i + 1][3] == "[":
        if not tokens[i + 2][2] or tokens[i + 3][3] != "]":
            raise _NotPure(name)
        names[1].add(name)
        return ("e", name, int(tokens[i + 2][2])), i + 4
    names[0].add(name)
    return ("n", name), i + 1


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
        self.count = 0

    def value(self) -> str:
        self.count += 1
        return f"%v{self.count}"

    def assign(self, target: str, text: str) -> bool:
        """Add `target = text`; False, the run unchanged, when the line does not qualify
        (not of the forms, or a name read both as a float and as a list in the run)."""
        parsed = _tree(text)
        if parsed is None:
            return False
        tree, floats, lists = parsed
        if any(name in self.env for name in lists) or any(self.kind.get(name) == "list" for name in floats):
            return False
        self.env[target] = self._value_of(tree)
        self.assigned[target] = None
        return True

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
            held = self.lists.get(tree[1])
            if held is None:
                held = self.lists[tree[1]] = self._argument(tree[1], "list", {})
            if tree[2] not in held:
                held[tree[2]] = self.value()
            return held[tree[2]]
        operands = [self._value_of(operand) for operand in tree[1:]]
        value = self.value()
        self.ops.append((value, kind, *operands))
        return value

    def _argument(self, text: str, kind: str, held):
        self.texts.append(text)
        self.kind[text] = kind
        self.arguments.append((kind, held))
        return held


def replace(lines: list[str], start: int, register, bind) -> None:
    """Replace the qualifying runs in `lines[start:]` (a body's finished lines) by a kernel
    call each.  `register(value)`: the namespace name bound to a value; `bind(name, value)`
    rebinds it (the kernel in place of its first call)."""
    body = lines[start:]
    text = "".join(body)
    if text.count("*") + text.count("+") + text.count("-") + text.count("_m_sqrt(") < MIN_OPERATIONS:
        return          # (each operation of a run but a unary minus shows one of these: too few)
    matches = list(map(_CANDIDATE.match, body))               # (one C loop over every line)
    runs, end = [], 0
    for i in itertools.compress(range(len(matches)), matches):
        if i < end:
            continue
        indent, run, end = matches[i].group(1), _Run(), i
        while end < len(matches) and matches[end] is not None and matches[end].group(1) == indent \
                and run.assign(matches[end].group(2), matches[end].group(3)):
            end += 1
        end = max(end, i + 1)
        if sum(op[1] != "neg" for op in run.ops) >= MIN_OPERATIONS:
            runs.append((start + i, start + end, _call(lines[start + i:start + end], indent, run, register, bind)))
    for i, j, new in reversed(runs):           # from the last: the indices stay true
        lines[i:j] = new


def _call(original: list[str], indent: str, run: _Run, register, bind) -> list[str]:
    """The lines that call the run's kernel, with `original` where it returns None."""
    targets = list(run.assigned)
    outputs = [run.env[t] for t in targets]
    kernel = register(None)
    bind(kernel, _first_call(lambda: native.run_ir(run.arguments, run.ops, outputs),
                             lambda built: bind(kernel, built)))
    return ([f"{indent}_kr = {kernel}({', '.join(run.texts)})", f"{indent}if _kr is None:"]
            + ["    " + line for line in original]
            + [f"{indent}else:", f"{indent}    {', '.join(targets)}, = _kr"])


class _Kernel:
    """What native.builtin needs of a kernel's `__self__` (it keeps the method's definition)."""


def _first_call(ir, bind):
    """The run's first call: writes its IR (`ir()`: a load writes none) and builds the kernel
    (None where this interpreter's layout is not CPython's: then the lines run in Python),
    binds it in its own place and calls it."""
    def first(*arguments):
        built = native.builtin(_Kernel(), native.compiled(ir())) if native.layout_is_cpythons() else _python
        bind(built)
        return built(*arguments)
    return first


def _python(*arguments):
    """The kernel where none can be built: the lines run as written."""
    return None
