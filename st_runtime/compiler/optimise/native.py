"""`native`: a run of vector.py computed by machine code LLVM makes (llvmlite), one call a run.

vector.py's graph (inputs, then `+ - *` operations in order, then the outputs) is written
out as LLVM IR, one `fmul`/`fadd`/`fsub` of doubles per operation on the same two operands
in the same order, and compiled by MCJIT the first time the run is called (a program that
never calls it compiles nothing; a graph compiled once is kept for the process, by its IR
text, so the exact and fast copies of a body and every load of one program share it).

Exactness: LLVM's floating-point instructions without fast-math flags are IEEE-754
binary64 operations rounded to nearest, Python's float `* + -`, and its optimisations keep
them so (no reassociation; a fold such as `x * 1.0 -> x` is the same value except for a
NaN's payload).  No multiply and add are contracted into one FMA (one rounding fewer): the
instructions carry no `contract` flag, the target machine is a generic x86-64 (no FMA
instruction at all) and the emitted code is checked for `vfmadd` by the tests.  When every
output is finite, every value was (a non-finite value never becomes finite through
`+ - *`), and the outputs are Python's bit for bit.  Otherwise (an inf or a NaN somewhere,
whose sign or payload could differ), or when an input is not a Python float or the list
not of its size, the kernel returns what vector.py's `exact` returns: the run in Python,
operation by operation.

The crossing: the kernel is a CPython builtin function (`METH_FASTCALL`, its `__self__`
the `Vectorised` helper) that the generated code calls as it called NumPy's kernel,
`_kN(list, (inputs ...))`: it reads the floats straight from the list and the tuple
(`ob_item`, `ob_fval`: CPython's object layout, checked on this interpreter before the
first kernel is built, else NumPy's kernel stays) and returns a new tuple of new floats.
No ctypes call, no packing: a call of the 6x6 determinant (2,670 operations) takes
4,395 machine instructions, NumPy's kernel 95,917 (docs/performance.md, session 19).

Without llvmlite (not installed, or `ST_RUNTIME_NATIVE=0`) the pass is off and vector.py's
NumPy kernel runs, as before this module.
"""

from __future__ import annotations

import functools
import importlib.util
import os
import struct
import sys
import types

#: Compiled kernels by their IR text: (execution engine, address of `run`).
_KERNELS: dict[str, tuple] = {}
_llvm = None            # llvmlite.binding, imported by the first kernel built
_target_machine = None
#: The method a kernel calls on its helper where it cannot compute the run itself.
_EXACT = sys.intern("exact")
_METH_FASTCALL = 0x0080
#: CPython's object layout (64-bit, GIL build): the offsets the kernels read at.
OB_TYPE, OB_SIZE, OB_ITEM, OB_FVAL = 8, 16, 24, 16      # ob_type, ob_size, list ob_item / tuple items, ob_fval


def enabled() -> bool:
    """Whether native kernels may be built: llvmlite found (not imported: loads stay as
    fast) and not switched off by `ST_RUNTIME_NATIVE=0` (to compare with NumPy's kernel).
    The environment is read at each call (a test may switch it), llvmlite looked for once."""
    if os.environ.get("ST_RUNTIME_NATIVE", "1").strip().lower() in ("0", "off", "no", "false"):
        return False
    return _llvmlite_found()


@functools.cache
def _llvmlite_found() -> bool:
    """Whether llvmlite is installed: `find_spec` walks the import path (~90 us), and the
    answer does not change while the process runs."""
    return importlib.util.find_spec("llvmlite") is not None


def layout_is_cpythons() -> bool:
    """Whether this interpreter's floats, lists and tuples lie where the kernels read them."""
    if sys.implementation.name != "cpython" or struct.calcsize("P") != 8:
        return False
    import sysconfig

    if sysconfig.get_config_var("Py_GIL_DISABLED"):
        return False
    import ctypes

    x = 1.5
    items, pair = [x], (x, x)
    word = ctypes.c_void_p.from_address
    return (ctypes.c_double.from_address(id(x) + OB_FVAL).value == x and word(id(x) + OB_TYPE).value == id(float)
            and word(id(items) + OB_TYPE).value == id(list) and word(id(items) + OB_SIZE).value == 1
            and word(word(id(items) + OB_ITEM).value).value == id(x)
            and word(id(pair) + OB_TYPE).value == id(tuple) and word(id(pair) + OB_SIZE).value == 2
            and word(id(pair) + OB_ITEM + 8).value == id(x))


def ir_double(value: float) -> str:
    """An LLVM IR double constant with `value`'s bits exactly (LLVM's 64-bit hex form)."""
    return "0x%016X" % struct.unpack("<Q", struct.pack("<d", value))[0]


_INSTRUCTION = {"*": "fmul", "+": "fadd", "-": "fsub"}

#: +inf as an IR double: `|x| < INFINITY` (fcmp olt) holds for every finite x, not for inf or NaN.
INFINITY = "0x7FF0000000000000"

#: The C API and types every kernel's IR may name (kernels.py's and loops.py's prepend it).
DECLARATIONS = """\
declare double @llvm.fabs.f64(double)
declare double @llvm.sqrt.f64(double)
declare void @Py_IncRef(ptr)
declare ptr @PyFloat_FromDouble(double)
declare ptr @PyTuple_New(i64)
declare void @Py_DecRef(ptr)
declare ptr @PyObject_CallMethodObjArgs(ptr, ptr, ...)
@PyFloat_Type = external global i8
@PyList_Type = external global i8
@PyTuple_Type = external global i8
@stgen_exact = external global i8
@stgen_none = external global i8
"""


class Writer:
    """The lines of a kernel's IR: a block per check, each failing one to `exact`; `label`
    names the blocks the checks open (`ok1`, `ok2` ...), another for a second writer whose
    lines go into the same function."""

    def __init__(self, label: str = "ok"):
        self.lines: list[str] = []
        self.checks = 0
        self.label = label

    def add(self, *lines: str) -> None:
        self.lines += [f"  {line}" for line in lines]

    def check(self, condition: str) -> None:
        """Go on when `condition` (an i1) holds, else to `%exact`."""
        self.checks += 1
        self.add(f"br i1 {condition}, label %{self.label}{self.checks}, label %exact")
        self.lines.append(f"{self.label}{self.checks}:")

    def object_of(self, name: str, pointer: str, offset: int) -> str:
        """`%name` = the object pointer at `pointer + offset` bytes."""
        self.add(f"%{name}.at = getelementptr inbounds i8, ptr {pointer}, i64 {offset}",
                 f"%{name} = load ptr, ptr %{name}.at, align 8")
        return f"%{name}"

    def has_type(self, obj: str, type_symbol: str) -> None:
        t = self.object_of(f"{obj[1:]}.type", obj, OB_TYPE)
        self.add(f"%{obj[1:]}.is = icmp eq ptr {t}, @{type_symbol}")
        self.check(f"%{obj[1:]}.is")

    def has_size(self, obj: str, size: int) -> None:
        self.size_is(obj, "eq", size, "sized")

    def has_at_least(self, obj: str, size) -> None:
        """Go on when the list `obj` holds at least `size` items (an int or an i64's name)."""
        self.size_is(obj, "sge", size, "long")

    def size_is(self, obj: str, comparison: str, size, tag: str) -> None:
        """Go on when `obj`'s ob_size compares to `size` by `comparison` (`icmp`'s)."""
        self.add(f"%{obj[1:]}.size.at = getelementptr inbounds i8, ptr {obj}, i64 {OB_SIZE}",
                 f"%{obj[1:]}.size = load i64, ptr %{obj[1:]}.size.at, align 8",
                 f"%{obj[1:]}.{tag} = icmp {comparison} i64 %{obj[1:]}.size, {size}")
        self.check(f"%{obj[1:]}.{tag}")

    def returns_tuple(self, values: list[str]) -> None:
        """Return a new tuple of new floats of the doubles `values` (NULL on no memory): one
        object, its items inline (a list would allocate its items apart, and free them)."""
        self.add(f"%tuple = call ptr @PyTuple_New(i64 {len(values)})",
                 "%made = icmp ne ptr %tuple, null")
        self.lines += ["  br i1 %made, label %fill, label %failed", "fill:"]
        for j, value in enumerate(values):
            self.add(f"%out{j} = call ptr @PyFloat_FromDouble(double {value})",
                     f"%out{j}.at = getelementptr inbounds i8, ptr %tuple, i64 {OB_ITEM + 8 * j}",
                     f"store ptr %out{j}, ptr %out{j}.at, align 8",          # NULL on no memory: the tuple's
                     f"%out{j}.made = icmp ne ptr %out{j}, null")              # Py_DecRef skips it
            self.lines += [f"  br i1 %out{j}.made, label %made{j}, label %dropped", f"made{j}:"]
        self.lines += ["  ret ptr %tuple",
                       "dropped:", "  call void @Py_DecRef(ptr %tuple)", "  br label %failed",
                       "failed:", "  ret ptr null"]

    def stores_floats(self, stores: list[tuple]) -> list[str]:
        """Store a new float of each (list, index, double) of `stores` into the list, freeing
        the item it replaces; the floats made first, so that no memory means no store made
        (NULL returned; between the checks and the stores no Python code runs, the lists
        stay as checked).  The blocks that free them on no memory are returned, for the
        function's end."""
        for n, (_, _, value) in enumerate(stores):
            self.add(f"%st{n} = call ptr @PyFloat_FromDouble(double {value})", f"%st{n}.made = icmp ne ptr %st{n}, null")
            self.lines += [f"  br i1 %st{n}.made, label %st{n}.ok, label %undo{n}", f"st{n}.ok:"]
        undo = []
        for n, (obj, k, _) in enumerate(stores):
            items = self.object_of(f"st{n}.items", obj, OB_ITEM)
            self.add(f"%st{n}.at = getelementptr inbounds ptr, ptr {items}, i64 {k}",
                     f"%st{n}.old = load ptr, ptr %st{n}.at, align 8",
                     f"store ptr %st{n}, ptr %st{n}.at, align 8",
                     f"call void @Py_DecRef(ptr %st{n}.old)")
            undo += [f"undo{n}:"] + ([f"  call void @Py_DecRef(ptr %st{n - 1})", f"  br label %undo{n - 1}"]
                                     if n else ["  ret ptr null"])
        return undo

    def float_value(self, name: str, item: str) -> str:
        """`%name`: the double of the Python float `item` (checked to be one)."""
        self.has_type(item, "PyFloat_Type")
        self.add(f"%{name}.at = getelementptr inbounds i8, ptr {item}, i64 {OB_FVAL}",
                 f"%{name} = load double, ptr %{name}.at, align 8")
        return f"%{name}"


def ir_text(n_inputs: int, sources: dict[int, tuple[str, int]], constants: dict[int, float],
            ops: list[tuple[str, int, int]], live: list[int], outputs: list[int],
            n_list: int, n_tuple: int) -> str:
    """The IR of `PyObject *run(PyObject *self, PyObject *const *args, Py_ssize_t nargs)`,
    called as `run(list, tuple)`: input i is element k of the list (`sources[i]` ==
    ("list", k)) or of the tuple (("tuple", k)), or the literal `constants[i]`; operation k
    (value n_inputs + k) is `ops[k]` of two earlier values, for each k in `live`, in order;
    the result is a new tuple of the outputs' floats, or `self.exact(list, tuple)` when an
    argument is not as compiled for (a list of n_list floats, a tuple of n_tuple) or an
    output is not finite."""
    w = Writer()
    w.add("%two = icmp eq i64 %nargs, 2")
    w.lines += ["  br i1 %two, label %start, label %wrong", "start:"]
    whole = w.object_of("whole", "%args", 0)
    inputs = w.object_of("inputs", "%args", 8)
    if n_list:
        w.has_type(whole, "PyList_Type")
        w.has_size(whole, n_list)
        items = w.object_of("items", whole, OB_ITEM)
    w.has_type(inputs, "PyTuple_Type")
    w.has_size(inputs, n_tuple)
    name = {i: ir_double(c) for i, c in constants.items()}
    for i, (where, k) in sources.items():
        item = w.object_of(f"x{i}", items if where == "list" else inputs,
                           8 * k if where == "list" else OB_ITEM + 8 * k)
        name[i] = w.float_value(f"v{i}", item)
    for k in live:
        op, a, b = ops[k]
        v = n_inputs + k
        w.add(f"%v{v} = {_INSTRUCTION[op]} double {name[a]}, {name[b]}")
        name[v] = f"%v{v}"
    for j, o in enumerate(outputs):
        w.add(f"%abs{j} = call double @llvm.fabs.f64(double {name[o]})",
              f"%finite{j} = fcmp olt double %abs{j}, {INFINITY}")
        w.check(f"%finite{j}")
    w.returns_tuple([name[o] for o in outputs])
    w.lines += ["exact:",
                "  %slow = call ptr (ptr, ptr, ...) @PyObject_CallMethodObjArgs(ptr %self, ptr @stgen_exact,"
                " ptr %whole, ptr %inputs, ptr null)",
                "  ret ptr %slow",
                "wrong:",                         # not two arguments: exact's own TypeError
                "  %none = call ptr (ptr, ptr, ...) @PyObject_CallMethodObjArgs(ptr %self, ptr @stgen_exact, ptr null)",
                "  ret ptr %none"]
    return (DECLARATIONS + "\ndefine ptr @run(ptr %self, ptr %args, i64 %nargs) {\nentry:\n"
            + "\n".join(w.lines) + "\n}\n")


def run_ir(arguments: list, ops: list[tuple], outputs: list[str], distinct=(), stores=()) -> str:
    """The IR of `PyObject *run(PyObject *self, PyObject *const *args, Py_ssize_t nargs)` for
    kernels.py's runs of statements, called as `run(a0, a1, ...)`: `arguments[j]` is
    ("float", value) (args[j] a Python float, whose double is `value`) or ("list", {k:
    value}, size) (args[j] a list of at least `size` elements, the one at every index k a
    Python float); `distinct` holds pairs (j, k) of arguments that must be two objects.
    `ops[i]` is (value, op, operands...): op "*", "+" or "-" of two operands, "neg",
    "sqrt", "sin", "cos" or "atan" (the C library's: `libm_symbols`) of one, or "finite" of one
    (value None: the operand only checked to be finite); an operand a value's name or an
    IR double literal.  Each of `stores`, (j, k, value), stores a new float of `value` into
    element k of the list args[j] (the item there checked a float: freeing it runs no code).
    The result is a new tuple of the doubles named by `outputs`, the stores made, or None (a
    new reference, nothing stored) when an argument is not as compiled for or a value
    computed is not finite."""
    w = Writer()
    w.add(f"%n.ok = icmp eq i64 %nargs, {len(arguments)}")
    w.check("%n.ok")
    for j, (kind, held, *size) in enumerate(arguments):
        arg = w.object_of(f"a{j}", "%args", 8 * j)
        if kind == "float":
            w.float_value(held[1:], arg)
            continue
        w.has_type(arg, "PyList_Type")
        w.has_at_least(arg, max(size or [0], default=0) if size else max(held) + 1)
        if held:
            items = w.object_of(f"a{j}.items", arg, OB_ITEM)
        for k, value in sorted(held.items()):
            w.float_value(value[1:], w.object_of(f"a{j}.{k}", items, 8 * k))
    for j, k in distinct:
        w.add(f"%a{j}.not.a{k} = icmp ne ptr %a{j}, %a{k}")
        w.check(f"%a{j}.not.a{k}")
    for n, (j, k, _) in enumerate(stores):
        w.has_type(w.object_of(f"old{n}", w.object_of(f"old{n}.items", f"%a{j}", OB_ITEM), 8 * k), "PyFloat_Type")
    finite = "true"
    for i, (value, op, *operands) in enumerate(ops):
        if op == "finite":                        # the value a finite test tested: checked, not computed
            value = operands[0]
        elif op == "sqrt":
            w.add(f"{value} = call double @llvm.sqrt.f64(double {operands[0]})")
        elif op in LIBM:
            w.add(f"{value} = call double @{op}(double {operands[0]}) #0")
        elif op == "neg":
            w.add(f"{value} = fneg double {operands[0]}")
        else:
            w.add(f"{value} = {_INSTRUCTION[op]} double {operands[0]}, {operands[1]}")
        w.add(f"%abs.{i} = call double @llvm.fabs.f64(double {value})",
              f"%fin.{i} = fcmp olt double %abs.{i}, {INFINITY}",
              f"%all.{i} = and i1 {finite}, %fin.{i}")
        finite = f"%all.{i}"
    w.check(finite)
    undo = w.stores_floats([(f"%a{j}", k, value) for j, k, value in stores])
    w.returns_tuple(outputs)
    w.lines += ["exact:",                         # the statements in Python, as written
                "  call void @Py_IncRef(ptr @stgen_none)",
                "  ret ptr @stgen_none"] + undo
    libm = sorted({op for _, op, *_ in ops if op in LIBM})
    return (DECLARATIONS + libm_declarations(libm)
            + "\ndefine ptr @run(ptr %self, ptr %args, i64 %nargs) {\nentry:\n"
            + "\n".join(w.lines) + "\n}\n" + ("attributes #0 = { nobuiltin }\n" if libm else ""))


#: The C library's functions a kernel may call (`libm_symbols`), by the name the IR calls.
LIBM = ("sin", "cos", "atan")


def libm_declarations(functions) -> str:
    """The IR declarations of the C library's `functions` (names of LIBM), in their order."""
    return "".join(f"declare double @{f}(double)\n" for f in functions)


def libm_symbols() -> dict[str, int]:
    """The addresses the kernels' `sin`, `cos` and `atan` bind to: the C library's functions as the
    dynamic linker resolves them for the whole process (`dlsym` of the global scope: the
    math module's calls go through the same resolution, so the same function, the same CPU
    variant of glibc's IFUNC).  For a finite argument math.sin, math.cos and math.atan return
    that function's result unchanged (mathmodule.c `math_1`)."""
    import ctypes

    process = ctypes.CDLL(None)
    return {name: ctypes.cast(getattr(process, name), ctypes.c_void_p).value for name in LIBM}


def _machine():
    """The target machine: the host's triple; on x86-64 the generic `x86-64` CPU (SSE2, no
    FMA instruction to contract into).  The C API the kernels call, by its addresses here."""
    global _llvm, _target_machine
    if _target_machine is None:
        import ctypes

        import llvmlite.binding as llvm

        llvm.initialize_native_target()
        llvm.initialize_native_asmprinter()
        api = ctypes.pythonapi
        for function in ("PyFloat_FromDouble", "PyTuple_New", "Py_DecRef", "Py_IncRef", "PyObject_CallMethodObjArgs"):
            llvm.add_symbol(function, ctypes.cast(getattr(api, function), ctypes.c_void_p).value)
        for symbol, obj in (("PyFloat_Type", float), ("PyList_Type", list), ("PyTuple_Type", tuple),
                            ("stgen_exact", _EXACT), ("stgen_none", None)):
            llvm.add_symbol(symbol, id(obj))
        triple = llvm.get_process_triple()
        cpu = "x86-64" if triple.startswith("x86_64") else ""
        _target_machine = llvm.Target.from_triple(triple).create_target_machine(cpu=cpu, features="", opt=2)
        _llvm = llvm
    return _target_machine


def compiled(ir: str) -> int:
    """The address of the C function `ir` defines (`run`), compiled once per process."""
    found = _KERNELS.get(ir)
    if found is None:
        machine = _machine()
        module = _llvm.parse_assembly(ir)
        module.verify()
        engine = _llvm.create_mcjit_compiler(module, machine)
        engine.finalize_object()
        found = _KERNELS[ir] = (engine, engine.get_function_address("run"))
    return found[1]


def assembly(ir: str) -> str:
    """The machine code `ir` compiles to, as assembly text (for the tests' FMA check)."""
    machine = _machine()
    return machine.emit_assembly(_llvm.parse_assembly(ir))


_new_function = _MethodDef = None      # PyCFunction_NewEx and a PyMethodDef, by ctypes (imported then)


def builtin(helper, address: int):
    """A CPython builtin function calling the kernel at `address`, its `__self__` `helper`."""
    global _new_function, _MethodDef
    import ctypes

    if _new_function is None:
        class _MethodDef(ctypes.Structure):
            _fields_ = [("ml_name", ctypes.c_char_p), ("ml_meth", ctypes.c_void_p),
                        ("ml_flags", ctypes.c_int), ("ml_doc", ctypes.c_char_p)]
        _new_function = ctypes.pythonapi.PyCFunction_NewEx
        _new_function.restype = ctypes.py_object
        _new_function.argtypes = [ctypes.c_void_p, ctypes.py_object, ctypes.c_void_p]
    helper.method_def = _MethodDef(b"native_run", address, _METH_FASTCALL, None)    # lives with the helper
    return _new_function(ctypes.addressof(helper.method_def), helper, None)


def first_call(helper, bind):
    """What the generated code calls before a `Vectorised` helper's kernel is built:
    `on_first_call` of its IR, the kernel's `__self__` the helper, NumPy's kernel
    (`helper.run`, its arrays made then) kept where this interpreter's layout is not
    CPython's; a method of the helper, as the kernel that takes its place is."""
    build = on_first_call(lambda: helper_ir(helper), bind, helper, helper.numpy_run)

    def first(self, whole, inputs):
        return build(whole, inputs)
    return types.MethodType(first, helper)


class _Kernel:
    """What `builtin` needs of a kernel's `__self__` (it keeps the method's definition)."""


def on_first_call(ir, bind, owner=None, fallback=None):
    """What the generated code calls before a kernel is built: the first call writes its IR
    (`ir()`: a load writes none) and builds the kernel (its `__self__` `owner`, or a new
    `_Kernel`; where this interpreter's layout is not CPython's, what `fallback()` gives
    (NumPy's kernel, made only then), by default a function answering None: the lines run
    in Python), binds it in its own place by `bind(kernel)` and calls it."""
    def first(*arguments):
        if layout_is_cpythons():
            built = builtin(_Kernel() if owner is None else owner, compiled(ir()))
        else:
            built = _python if fallback is None else fallback()
        bind(built)
        return built(*arguments)
    return first


def _python(*arguments):
    """The kernel where none can be built: the lines run as written."""
    return None


def bind_symbols(symbols: dict[str, int]) -> None:
    """Let the kernels' IR name each of `symbols` (name -> address in this process)."""
    _machine()
    for symbol, address in symbols.items():
        _llvm.add_symbol(symbol, address)


def helper_ir(helper) -> str:
    """The IR of a `Vectorised` helper's run."""
    sources = {i: ("tuple", p) for p, i in enumerate(helper.variable_inputs)}
    sources.update((i, ("list", k)) for i, k in helper.elements.items())
    return ir_text(helper.n_inputs, sources, dict(helper.constants), helper.ops, helper.live,
                   helper.output_refs, helper.n_list, len(helper.variable_inputs))
