"""`loops`: a FOR loop of float sums with SIN and COS computed by one native call (native.py).

TRJ_OceanWave's component loop is, in a fast copy, the loop

    for v_COMPONENT in _t15:
        _t19 = v_COMPONENT - 1
        v_PSI = ((((_t21 := v_WAVENUMBER[_t19]) * v_LATCHEDRESTPOSITION) - (v_ANGULARFREQUENCY[_t19] * v_WAVETIME)) + v_PHASERAD[_t19])
        _c211 = (True if (v_PSI < 1e309 and v_PSI > -1e309) else False)     (the finite test)
        ...     (SIN and COS of v_PSI behind _c211, three sums of products)
    else:
        v_COMPONENT = (_t16 + 1 if 1 <= _t16 else 1)

about 50 bytecodes and ten new floats a component.  This pass, run on a body's finished
lines after `kernels`, replaces such a loop by

    _kr = _k9(_t15, v_WAVENUMBER, v_LATCHEDRESTPOSITION, ...)
    if _kr is None:
        <the loop as it was>
    else:
        v_PSI, v_SINESUM, v_COSINESUM, v_SLOPESUM, = _kr
        <the loop's else lines>

A loop qualifies when it runs over a name (the range the compiler made), its first line is
`_tI = v_X - 1` and the rest are assignments of plain names of fully parenthesised `+ - *`,
unary minus, float literals, names, elements `L[_tI]`, walrus temporaries, `_m_sin(x)` and
`_m_cos(x)` (math.sin and math.cos), the compiler's finite test of a name and the SIN or
COS it guards; it calls SIN or COS, has an `else` (the loop variable's value after it), and
no line of the body outside the loop names its temporaries (`_tI`, the walrus targets, the
finite tests): the kernel returns the names it sets that the rest of the body names.

Exactness: `+ - *` are the IEEE-754 instructions on the same operands in the same order
(native.py: no fast-math flags, no FMA); `sin` and `cos` are called in the C library the
process has loaded, the very functions math.sin and math.cos call (`libm_symbols`: the
address the dynamic linker gives the name, which is what the math module's calls go
through), and for a finite argument math.sin and math.cos return the C function's result
unchanged.  The kernel computes only when the range is `range(1, stop)` with step 1 and at
least one iteration, every list is a list holding at least as many elements, every element
and float argument is a Python float and every value it computes (each operation, each
argument of SIN and COS) is finite; otherwise it returns None and the loop runs in Python
as written, from its start (the kernel stores nothing).  The arguments are read before the
loop instead of inside it: the loop stores only its own local names, so each read sees what
the loop would have read.

Off without llvmlite or with `ST_RUNTIME_NATIVE=0` (native.enabled), and by its switch.
"""

from __future__ import annotations

import ast
import functools
import itertools
import re

from . import native

#: `for v_X in _tR:` at some indentation.
_FOR = re.compile(r"( *)for (v_\w+) in (_t\d+):\Z")
_INDEX = re.compile(r" *(_t\d+) = (v_\w+) - 1\Z")
_ASSIGN = re.compile(r" *([A-Za-z_]\w*) = (.+)\Z")
_LIBM = re.compile(r"_m_(?:sin|cos)\(")
_WORD = re.compile(r"\w+")
_BINARY = {ast.Add: "fadd", ast.Sub: "fsub", ast.Mult: "fmul"}
_CALLS = {"_m_sin": "sin", "_m_cos": "cos"}
_GUARDED = {"_m_sin": "_sf_SIN", "_m_cos": "_sf_COS"}
_RANGE_START, _RANGE_STOP, _RANGE_STEP = 16, 24, 32       # rangeobject's start, stop, step
_DIGIT = 24                                               # a PyLongObject's first 30-bit digit


class _NotPure(Exception):
    """The loop is not of the forms the kernel computes."""


@functools.lru_cache(maxsize=4096)
def _expression(text: str):
    """The expression's tree (Python's ast), None when it does not parse."""
    try:
        return ast.parse(text, mode="eval").body
    except SyntaxError:
        return None


class _Loop:
    """The kernel's IR of one loop: arguments checked in the entry, values computed in the body."""

    def __init__(self, variable: str, index: str):
        self.variable, self.index = variable, index
        self.w = native.Writer()
        self.texts: list[str] = []            # each argument's Python expression, after the range
        self.lists: dict[str, str] = {}       # list argument -> its items pointer
        self.floats: dict[str, str] = {}      # float argument -> its double
        self.carried: dict[str, str] = {}     # name set in the loop -> its phi in the header
        self.env: dict[str, str] = {}         # name -> its value now (in this iteration)
        self.tests: dict[str, str] = {}       # finite test's name -> the value it tested
        self.finite: set[str] = set()         # the values checked to be finite
        self.private: set[str] = {index}      # names the loop sets that it does not return
        self.body = native.Writer("in")       # the body's IR, written after the entry's (blocks in1, in2 ...)
        self.count = 0
        self.set_in_loop: set[str] = set()    # every name the body assigns (a read of one before
        self.temporaries: set[str] = set()    # its line is the last iteration's value); walrus targets

    def value(self) -> str:
        self.count += 1
        return f"%v{self.count}"

    def assign(self, target: str, text: str) -> None:
        tree = _expression(text)
        if tree is None:
            raise _NotPure(text)
        tested = _finite_test(tree)
        if tested is not None:
            self.tests[target] = self._finite(self._read(tested))
            self.private.add(target)
            return
        self._set(target, self._value_of(tree))

    def names_set(self, lines: list[tuple[str, str]]) -> None:
        """Before the body: every name its assignments set (statements and walrus targets)."""
        for target, text in lines:
            tree = _expression(text)
            if tree is None:
                raise _NotPure(text)
            walrus = {node.target.id for node in ast.walk(tree) if isinstance(node, ast.NamedExpr)}
            self.temporaries |= walrus
            if _finite_test(tree) is None:
                self.set_in_loop |= walrus | {target}
            else:
                self.temporaries.add(target)
        for name in sorted(self.set_in_loop):
            self.carried[name] = f"%{name}.phi"

    def _set(self, target: str, value: str) -> None:
        if target in self.tests or target in (self.variable, self.index) or target in self.lists:
            raise _NotPure(target)
        self.env[target] = value

    def _read(self, name: str) -> str:
        if name in self.env:
            return self.env[name]
        if name in self.tests or name in self.lists or name in (self.variable, self.index):
            raise _NotPure(name)
        if name in self.temporaries:              # no value before the loop
            raise _NotPure(name)
        if name not in self.floats:
            self.texts.append(name)
            self.floats[name] = f"%{name}.in"
        if name in self.set_in_loop:              # set later in the loop: its value from the last iteration
            return self.carried[name]
        return self.floats[name]

    def _value_of(self, tree) -> str:
        if isinstance(tree, ast.Constant) and type(tree.value) is float:
            return native.ir_double(tree.value)
        if isinstance(tree, ast.Name):
            return self._read(tree.id)
        if isinstance(tree, ast.NamedExpr):
            value = self._value_of(tree.value)
            self._set(tree.target.id, value)
            self.private.add(tree.target.id)
            return value
        if isinstance(tree, ast.Subscript):
            return self._element(tree)
        if isinstance(tree, ast.BinOp) and type(tree.op) in _BINARY:
            return self._operation(_BINARY[type(tree.op)], self._value_of(tree.left), self._value_of(tree.right))
        if isinstance(tree, ast.UnaryOp) and isinstance(tree.op, ast.USub):
            return self._operation("fneg", self._value_of(tree.operand))
        if isinstance(tree, ast.IfExp):
            return self._guarded(tree)
        if _call_of(tree) in _CALLS:
            return self._libm(_CALLS[tree.func.id], self._value_of(tree.args[0]))
        raise _NotPure(type(tree).__name__)

    def _element(self, tree) -> str:
        """`L[_tI]`: the list's element at the iteration's index, checked to be a float."""
        if not (isinstance(tree.value, ast.Name) and isinstance(tree.slice, ast.Name) and tree.slice.id == self.index):
            raise _NotPure("subscript")
        name = tree.value.id
        if name in self.env or name in self.carried or name in self.floats or name in self.tests:
            raise _NotPure(name)
        if name not in self.lists:
            self.texts.append(name)
            self.lists[name] = f"%{name}.items"
        item = f"%{name}.{self.value()[1:]}"
        self.add(f"{item}.at = getelementptr inbounds ptr, ptr {self.lists[name]}, i64 %i",
                 f"{item} = load ptr, ptr {item}.at, align 8")
        self.body.has_type(item, "PyFloat_Type")
        double = self.value()
        self.add(f"{double}.at = getelementptr inbounds i8, ptr {item}, i64 {native.OB_FVAL}",
                 f"{double} = load double, ptr {double}.at, align 8")
        return double

    def _guarded(self, tree) -> str:
        """`(_m_sin(x) if _cB else _sf_SIN(x))` where `_cB` tested x: the kernel's x is finite."""
        call, other = _call_of(tree.body), _call_of(tree.orelse)
        if not (call in _GUARDED and other == _GUARDED[call] and isinstance(tree.test, ast.Name)
                and tree.test.id in self.tests):
            raise _NotPure("if")
        argument = self._value_of(tree.body.args[0])
        if ast.dump(tree.body.args[0]) != ast.dump(tree.orelse.args[0]) or self.tests[tree.test.id] != argument:
            raise _NotPure("guard")
        return self._libm(_CALLS[call], argument)

    def _libm(self, function: str, argument: str) -> str:
        self._finite(argument)
        value = self.value()
        self.add(f"{value} = call double @{function}(double {argument}) #0")
        return value

    def _operation(self, instruction: str, *operands: str) -> str:
        value = self.value()
        self.add(f"{value} = {instruction} double {', '.join(operands)}")
        return self._finite(value)

    def _finite(self, value: str) -> str:
        """Leave for `exact` unless `value` is finite (false for NaN); `value` returned."""
        if value in self.finite:
            return value
        self.finite.add(value)
        self.add(f"{value}.abs = call double @llvm.fabs.f64(double {value})",
                 f"{value}.fin = fcmp olt double {value}.abs, {native.INFINITY}")
        self.body.check(f"{value}.fin")
        return value

    def add(self, *lines: str) -> None:
        self.body.add(*lines)

    def outputs(self) -> list[str]:
        """The names the loop sets and returns: the floats that are not its temporaries."""
        return [name for name in self.carried if name not in self.private]

    def keep_only(self, named: set[str]) -> None:
        """Return only the names the rest of the body names: the others are temporaries too."""
        self.private |= set(self.carried) - named

    def ir(self) -> str:
        """The kernel `run(range, arguments ...)`: a new tuple of the outputs' last values, or None."""
        w = self.w
        w.add(f"%n.ok = icmp eq i64 %nargs, {len(self.texts) + 1}")
        w.check("%n.ok")
        self._range(w)
        for j, name in enumerate(self.texts, start=1):
            arg = w.object_of(f"a{j}", "%args", 8 * j)
            if name in self.lists:
                w.has_type(arg, "PyList_Type")
                w.has_at_least(arg, "%n")
                w.object_of(f"{name}.items", arg, native.OB_ITEM)
            else:
                w.float_value(f"{name}.in", arg)
        entry = f"ok{w.checks}"
        w.lines += ["  br label %loop", "loop:", f"  %i = phi i64 [0, %{entry}], [%i.next, %latch]"]
        for name, phi in self.carried.items():
            first = self.floats.get(name, "0.0")   # a name set before it is read needs no value in
            w.lines.append(f"  {phi} = phi double [{first}, %{entry}], [{self.env[name]}, %latch]")
        w.lines += ["  %done = icmp eq i64 %i, %n", "  br i1 %done, label %finish, label %body", "body:"]
        w.lines += self.body.lines
        w.lines += ["  br label %latch", "latch:", "  %i.next = add i64 %i, 1", "  br label %loop", "finish:"]
        w.returns_tuple([self.carried[name] for name in self.outputs()])
        w.lines += ["exact:", "  call void @Py_IncRef(ptr @stgen_none)", "  ret ptr @stgen_none"]
        return (native.DECLARATIONS + _DECLARATIONS + "\ndefine ptr @run(ptr %self, ptr %args, i64 %nargs) {\n"
                "entry:\n" + "\n".join(w.lines) + "\n}\nattributes #0 = { nobuiltin }\n")

    @staticmethod
    def _range(w) -> None:
        """`%n`: the iterations of args[0], a `range(1, stop)` of step 1 with stop a small int
        above 1 (the values 1 .. stop - 1 of the loop variable, the indices 0 .. stop - 2)."""
        rng = w.object_of("range", "%args", 0)
        w.has_type(rng, "PyRange_Type")
        for part, offset, one in (("start", _RANGE_START, True), ("step", _RANGE_STEP, True), ("stop", _RANGE_STOP, False)):
            obj = w.object_of(part, rng, offset)
            w.has_type(obj, "PyLong_Type")
            w.has_size(obj, 1)                            # one digit: 1 <= value < 2**30
            w.add(f"%{part}.digit.at = getelementptr inbounds i8, ptr {obj}, i64 {_DIGIT}",
                  f"%{part}.digit = load i32, ptr %{part}.digit.at, align 4")
            if one:
                w.add(f"%{part}.one = icmp eq i32 %{part}.digit, 1")
                w.check(f"%{part}.one")
        w.add("%stop.wide = zext i32 %stop.digit to i64", "%n = sub i64 %stop.wide, 1",
              "%n.some = icmp sgt i64 %n, 0")
        w.check("%n.some")


_DECLARATIONS = native.libm_declarations(("sin", "cos")) + """\
@PyLong_Type = external global i8
@PyRange_Type = external global i8
"""


def _call_of(tree) -> str | None:
    """The name a call of one positional argument calls, None for anything else."""
    if isinstance(tree, ast.Call) and isinstance(tree.func, ast.Name) and len(tree.args) == 1 and not tree.keywords:
        return tree.func.id
    return None


def _finite_test(tree) -> str | None:
    """x for the compiler's finite test of a name, `(True if (x < 1e309 and x > -1e309) else False)`."""
    if not (isinstance(tree, ast.IfExp) and isinstance(tree.body, ast.Constant) and tree.body.value is True
            and isinstance(tree.orelse, ast.Constant) and tree.orelse.value is False
            and isinstance(tree.test, ast.BoolOp) and isinstance(tree.test.op, ast.And) and len(tree.test.values) == 2):
        return None
    below, above = tree.test.values
    if not (_compares(below, ast.Lt, 1e309) and _compares(above, ast.Gt, -1e309)
            and below.left.id == above.left.id):
        return None
    return below.left.id


def _compares(tree, op, bound: float) -> bool:
    """`name op bound` (a negative bound is Python's `-literal`)."""
    if not (isinstance(tree, ast.Compare) and isinstance(tree.left, ast.Name) and len(tree.ops) == 1
            and isinstance(tree.ops[0], op)):
        return False
    right = tree.comparators[0]
    if isinstance(right, ast.UnaryOp) and isinstance(right.op, ast.USub) and isinstance(right.operand, ast.Constant):
        return -right.operand.value == bound
    return isinstance(right, ast.Constant) and right.value == bound


def libm_symbols() -> dict[str, int]:
    """The addresses the kernels' `sin`, `cos` and type symbols bind to: native.libm_symbols'
    `sin` and `cos` (the very functions math.sin and math.cos call), int and range."""
    return {**native.libm_symbols(), "PyLong_Type": id(int), "PyRange_Type": id(range)}


@functools.cache
def ranges_are_cpythons() -> bool:
    """Whether a range's start, stop and step and a small int's size and first digit lie where
    the kernels read them (CPython 3.11; 3.12 keeps an int's size as a tag, and a kernel
    there would answer None on every call)."""
    import ctypes

    r = range(1, 37, 1)
    word = ctypes.c_void_p.from_address
    return (word(id(r) + _RANGE_START).value == id(r.start) and word(id(r) + _RANGE_STOP).value == id(r.stop)
            and word(id(r) + _RANGE_STEP).value == id(r.step)
            and ctypes.c_int64.from_address(id(r.stop) + native.OB_SIZE).value == 1
            and ctypes.c_uint32.from_address(id(r.stop) + _DIGIT).value == 37)


#: The kernel where this interpreter's ints or ranges are not where the kernels read: None.
_NONE = (native.DECLARATIONS + "\ndefine ptr @run(ptr %self, ptr %args, i64 %nargs) {\nentry:\n"
         "  call void @Py_IncRef(ptr @stgen_none)\n  ret ptr @stgen_none\n}\n")


def _ir_of(loop: _Loop):
    def ir() -> str:
        if not ranges_are_cpythons():
            return _NONE
        native.bind_symbols(libm_symbols())
        return loop.ir()
    return ir


def replace(lines: list[str], start: int, register, bind) -> None:
    """Replace each qualifying FOR loop in `lines[start:]` (a body's finished lines) by a
    kernel call.  `register(value)`: the namespace name bound to a value; `bind(name,
    value)` rebinds it (the kernel in place of its first call)."""
    body = lines[start:]
    text = "\n".join(body)
    if "_m_sin(" not in text and "_m_cos(" not in text:
        return              # (one C search a body: no Python loop over the lines of a load)
    found = list(map(_FOR.match, body))
    for n in reversed(list(itertools.compress(range(len(body)), found))):    # from the last: the indices stay true
        new = _kernel_loop(body, n, found[n], register, bind)
        if new is not None:
            lines[start + n:start + n + new[0]] = new[1]


def _kernel_loop(body: list[str], n: int, found, register, bind):
    """(lines replaced, the new lines) for the loop at `body[n]`, None if it does not qualify."""
    indent, variable, iterated = found.groups()
    inner = indent + "    "
    end = n + 1
    while end < len(body) and body[end].startswith(inner):
        end += 1
    if end >= len(body) or body[end] != f"{indent}else:":
        return None
    after = end + 1
    while after < len(body) and body[after].startswith(inner):
        after += 1
    index = _INDEX.match(body[n + 1]) if n + 1 < end else None
    if index is None or index.group(2) != variable or not any(map(_LIBM.search, body[n + 2:end])):
        return None         # (a loop without SIN or COS: `kernels`' runs are its kind of work)
    loop = _Loop(variable, index.group(1))
    try:
        assignments = []
        for line in body[n + 2:end]:
            assigned = _ASSIGN.match(line)
            if assigned is None or line[len(inner)] == " ":
                raise _NotPure(line)
            assignments.append(assigned.groups())
        loop.names_set(assignments)
        for target, text in assignments:
            loop.assign(target, text)
    except (_NotPure, AttributeError):
        return None
    outside = "\n".join(body[:n] + body[end:])
    named = (set(loop.carried) | loop.private) & set(_WORD.findall(outside))   # (each an identifier: a whole word)
    if named & loop.private:
        return None
    loop.keep_only(named)
    if not loop.outputs():
        return None
    kernel = register(None)
    bind(kernel, native.on_first_call(_ir_of(loop), lambda built: bind(kernel, built)))
    original = body[n:after]
    new = ([f"{indent}_kr = {kernel}({', '.join([iterated] + loop.texts)})", f"{indent}if _kr is None:"]
           + ["    " + line for line in original]
           + [f"{indent}else:", f"{indent}    {', '.join(loop.outputs())}, = _kr"]
           + body[end + 1:after])
    return after - n, new
