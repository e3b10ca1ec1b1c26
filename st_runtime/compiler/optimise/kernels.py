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

import re

from . import native

MIN_OPERATIONS = 16      # a crossing costs about as much as a dozen float operations in Python
#: A line that may qualify: `name = ` and only the characters of the forms above.
_CANDIDATE = re.compile(r"( *)([A-Za-z_]\w*) = ([\w.()+*\[\] -]+)\Z")
_TOKEN = re.compile(r" *(?:(\d+\.\d*(?:e[+-]?\d+)?|\d+e[+-]?\d+)|([A-Za-z_]\w*)|(\d+)|(\S))")
_NOT_NAMES = frozenset({"True", "False", "None", "_m_sqrt", "_kr"})


class _NotPure(Exception):
    """The line is not of the forms the kernel computes."""


class _Run:
    """The values of a run: arguments read before it, then operations in order."""

    def __init__(self):
        self.arguments: list[tuple] = []      # ("float", value) | ("list", {k: value}) by argument
        self.texts: list[str] = []            # each argument's Python expression
        self.env: dict[str, str] = {}         # local name -> its value now
        self.ops: list[tuple] = []
        self.assigned: dict[str, None] = {}   # the names the run sets, in order
        self.count = 0

    def value(self) -> str:
        self.count += 1
        return f"%v{self.count}"

    def assign(self, target: str, text: str) -> bool:
        """Add `target = text`; False, the run unchanged, when the line does not qualify."""
        state = (len(self.arguments), len(self.ops), dict(self.env), self.count,
                 {j: dict(held) for j, (kind, held) in enumerate(self.arguments) if kind == "list"})
        try:
            tokens = [t for t in _TOKEN.findall(text)]
            value, rest = self._sum(tokens, 0)
            if rest != len(tokens):
                raise _NotPure(text)
        except (_NotPure, IndexError):
            n_args, n_ops, self.env, self.count, lists = state
            del self.arguments[n_args:], self.texts[n_args:], self.ops[n_ops:]
            for j, held in lists.items():
                self.arguments[j] = ("list", held)
            return False
        self.env[target] = value
        self.assigned[target] = None
        return True

    def _sum(self, tokens, i):
        """`primary [op primary]` (the compiler parenthesises every operation)."""
        left, i = self._primary(tokens, i)
        if i < len(tokens) and tokens[i][3] in ("+", "-", "*"):
            op = tokens[i][3]
            right, i = self._primary(tokens, i + 1)
            return self._op(op, left, right), i
        return left, i

    def _primary(self, tokens, i):
        number, name, integer, char = tokens[i]
        if number:
            return native._double(float(number)), i + 1
        if char == "(":
            value, i = self._sum(tokens, i + 1)
            if tokens[i][3] != ")":
                raise _NotPure("(")
            return value, i + 1
        if char == "-":
            if tokens[i + 1][0]:                      # `-1.5`: Python's constant, folded
                return native._double(-float(tokens[i + 1][0])), i + 2
            operand, i = self._primary(tokens, i + 1)
            return self._op("neg", operand), i
        if name == "_m_sqrt" and tokens[i + 1][3] == "(":
            operand, i = self._sum(tokens, i + 2)
            if tokens[i][3] != ")":
                raise _NotPure("sqrt")
            return self._op("sqrt", operand), i + 1
        if not name or name in _NOT_NAMES:
            raise _NotPure(name or char or integer)
        if i + 1 < len(tokens) and tokens[i + 1][3] == "[":
            if not tokens[i + 2][2] or tokens[i + 3][3] != "]" or name in self.env:
                raise _NotPure(name)
            return self._element(name, int(tokens[i + 2][2])), i + 4
        if name in self.env:
            return self.env[name], i + 1
        return self._argument(name, "float"), i + 1

    def _op(self, op, *operands) -> str:
        value = self.value()
        self.ops.append((value, op, *operands))
        return value

    def _argument(self, text: str, kind: str):
        if text in self.texts:
            j = self.texts.index(text)
            if self.arguments[j][0] != kind:
                raise _NotPure(text)
            return j
        self.texts.append(text)
        self.arguments.append((kind, self.value() if kind == "float" else {}))
        if kind == "float":
            self.env[text] = self.arguments[-1][1]
            return self.arguments[-1][1]
        return len(self.arguments) - 1

    def _element(self, name: str, k: int) -> str:
        j = self._argument(name, "list")
        held = self.arguments[j][1]
        if k not in held:
            held[k] = self.value()
        return held[k]


def replace(lines: list[str], start: int, register, bind) -> None:
    """Replace the qualifying runs in `lines[start:]` (a body's finished lines) by a kernel
    call each.  `register(value)`: the namespace name bound to a value; `bind(name, value)`
    rebinds it (the kernel in place of its first call)."""
    i = start
    while i < len(lines):
        match = _CANDIDATE.match(lines[i])
        if match is None:
            i += 1
            continue
        indent, run, j = match.group(1), _Run(), i
        while j < len(lines):
            line = _CANDIDATE.match(lines[j])
            if line is None or line.group(1) != indent or not run.assign(line.group(2), line.group(3)):
                break
            j += 1
        if j > i and sum(op[1] != "neg" for op in run.ops) >= MIN_OPERATIONS:
            new = _call(lines[i:j], indent, run, register, bind)
            lines[i:j] = new
            i += len(new)
        else:
            i = max(j, i + 1)


def _call(original: list[str], indent: str, run: _Run, register, bind) -> list[str]:
    """The lines that call the run's kernel, with `original` where it returns None."""
    targets = list(run.assigned)
    ir = native.run_ir(run.arguments, run.ops, [run.env[t] for t in targets])
    kernel = register(None)
    bind(kernel, _first_call(ir, lambda built: bind(kernel, built)))
    return ([f"{indent}_kr = {kernel}({', '.join(run.texts)})", f"{indent}if _kr is None:"]
            + ["    " + line for line in original]
            + [f"{indent}else:", f"{indent}    {', '.join(targets)}, = _kr"])


class _Kernel:
    """What native.builtin needs of a kernel's `__self__` (it keeps the method's definition)."""


def _first_call(ir: str, bind):
    """The run's first call: builds the kernel (None where this interpreter's layout is not
    CPython's: then the lines run in Python), binds it in its own place and calls it."""
    def first(*arguments):
        built = native.builtin(_Kernel(), native.compiled(ir)) if native.layout_is_cpythons() else _python
        bind(built)
        return built(*arguments)
    return first


def _python(*arguments):
    """The kernel where none can be built: the lines run as written."""
    return None
