"""Compile a checked program to Python: one function per POU body.

`compile_program(checked)` returns a `CompiledProgram`: a class per STRUCT,
FUNCTION_BLOCK and PROGRAM (instances are objects with `__slots__`, see
`objects.py`), a Python function per FUNCTION, and the instance of the
global variables.  Each POU body is written as Python source (kept in
`python_sources` for reading), `compile()`d once, and executed into one
namespace shared by the whole program.  The rules of the translation live
in `exprs.py`, `statements.py`, `calls.py` and `scope.py`.

Semantic choices (each has a test in tests/test_semantics*.py):

* Integers wrap to their width on every store; intermediate results are
  exact Python ints (so + - * agree with wrapping arithmetic; `/` and MOD
  truncate toward zero / take the dividend's sign; a zero divisor is
  F-DIV-ZERO).  REAL is rounded to float32 on every store, intermediate
  results are float64; real division by zero gives IEEE inf/nan.
* A runtime fault abandons the statement it happens in (at any nesting
  level); the POU goes on with the next statement.
* FOR evaluates its bounds once.  When the body cannot change the control
  variable it runs over a Python `range` (its estimated NJ501 time is
  charged per iteration, or up front when its body is one basic block); otherwise, and for a global control variable,
  it runs as a loop that tests the variable each time, as a PLC does.
  After a normal end the variable holds the first value past the end.  (A
  `range` FOR up to the type's maximum ends; on a PLC its variable would
  wrap and the loop never end.)
* Bounds checks are skipped only where a static range proves the index in
  bounds (constant indices, FOR variables with constant bounds, elements of
  CONSTANT integer tables).
"""

from __future__ import annotations

import functools
import math
import os
from dataclasses import dataclass, field
from itertools import islice
from operator import is_, methodcaller

from .. import ast
from ..dialects import DIALECTS
from ..diagnostics import register
from ..faults import STFault
from ..native import NATIVE_FBS
from ..objects import AttrRef, ItemRef, NullRef, STObject, assign_list, native_initializers
from ..types import StructType, fit_string, resolve_alias
from .. import values
from ..process_image import ProcessImage, located_property, parse_address, union_property
from . import support
from .calls import Calls
from .initial import CompileError, Initial, InitialValues
from .optimise import Optimisations, native
from .pysrc import pyliteral, safe_name, pyident
from .scope import edge_inputs, edge_slot, forget_walks
from .statements import BodyCompiler

__all__ = ["compile_program", "CompiledProgram", "CompileError", "Optimisations"]

register({"E-COMPILE-001": "a construct the checker accepted but the runtime cannot execute"})

_FAULTS = (STFault, ArithmeticError, ValueError)


@dataclass
class CompiledProgram:
    checked: object
    classes: dict[str, type] = field(default_factory=dict)       # STRUCT/FB/PROGRAM upper name ->
    functions: dict[str, object] = field(default_factory=dict)   # FUNCTION upper name -> callable
    globals: object = None
    python_sources: dict[str, str] = field(default_factory=dict)  # POU upper name -> source
    namespace: dict = field(default_factory=dict)
    image: ProcessImage = field(default_factory=ProcessImage)    # %I, %Q, %M (located variables)

    def pou(self, name: str):
        return self.checked.pous[name.upper()]

    def new(self, name: str):
        """A fresh instance of a PROGRAM, FB or STRUCT type."""
        return self.classes[name.upper()]()


#: What the generated code may call of Python's builtins.
_BUILTINS = {"len": len, "range": range, "float": float, "int": int, "abs": abs, "min": min, "max": max}

#: The names every namespace starts with, in order; `__builtins__` (a copy of _BUILTINS)
#: and `_truncate` (per dialect) are set for each.
_NAMESPACE = {
    "__builtins__": None,
    "_f32": support.f32, "_idiv": support.idiv, "_imod": support.imod,
    "_rdiv": support.rdiv, "_time_mul": values.time_mul, "_time_div": values.time_div,
    "_index_fault": support.index_fault, "_index_fault_n": support.index_fault_n,
    "_overrun": support.overrun, "_for_range": support.for_range,
    "_truncate": None,
    "_subrange": support.subrange, "_method": support.bound_method, "_deref": support.deref,
    "_ArrayView": support.ArrayView, "_setbit": support.set_bit, "_AttrRef": AttrRef, "_ItemRef": ItemRef,
    "_setattr": setattr, "_assign_list": assign_list, "_FAULTS": _FAULTS,
    "_INF": math.inf, "_NAN": math.nan, "_NINF": -math.inf,
    "_m_sin": math.sin, "_m_cos": math.cos, "_m_tan": math.tan, "_m_sqrt": math.sqrt,
    "_type": type, "_list": list, "_sum": sum,
    "_WHOLE": slice(None),       # an array copy's slice (calls.copy_statement)
    "_FROM_0": support.FROM_0, "_FROM_1": support.FROM_1,     # FOR ranges (statements._for_range)
}


class CompileUnit:
    """The shared state of one compilation: namespace, makers, bindings."""

    def __init__(self, program):
        self.program = program
        self.classes: dict[str, type] = {}
        self.namespace: dict = dict(_NAMESPACE)
        self.namespace["__builtins__"] = dict(_BUILTINS)
        self.namespace["_truncate"] = functools.partial(fit_string, dialect=program.dialect)
        self.makers = 0
        self.init_makers: dict[str, int] = {}     # class key -> makers its __init__ registered
        #: POU key -> (its instance variables, its edge inputs), as `_make_classes` laid them out
        self.instance_layouts: dict[str, tuple[list, list]] = {}
        self.guard_statements = True
        self.charge_costs = True
        self.initial = InitialValues(program, self.classes)
        self.calls = Calls(self)
        self.sources: dict[str, str] = {}
        self.constant_ranges: dict[int, tuple | None] = {}   # id(Symbol) -> element range
        # id(statement) -> its charged units (BodyCompiler._simple_cost / _head_cost): from the
        # ST text only, so one table a load (fastpath bounds a callee with its own compile's)
        self.head_costs: dict[int, float] = {}
        self.image = ProcessImage()
        #: "types", "pous" -> how many first entries of the table are the shared prelude's
        self.prelude_lead: dict[str, int] = {}
        #: whether native kernels may be built (native.enabled: an environment read, once a load)
        self.native = native.enabled()

    def register_maker(self, maker) -> str:
        self.makers += 1
        name = f"_mk{self.makers}"
        self.namespace[name] = maker
        return name

    def register_constant(self, value) -> str:
        """Bind a Python value (a constant range, a shared constant array) by name."""
        self.makers += 1
        name = f"_k{self.makers}"
        self.namespace[name] = value
        return name

    def bind_function(self, name: str, pos) -> str:
        from ..stdlib.functions import FUNCTIONS

        fn = FUNCTIONS.get(name)
        if fn is None:
            raise CompileError(f"standard function {name} is not implemented", pos)
        pyname = safe_name("_sf_" + name)
        self.namespace[pyname] = fn
        return pyname

    def bind_conversion(self, name: str, pos) -> str:
        from ..stdlib.conversions import CONVERSIONS, time_scaled

        unit = DIALECTS[getattr(self.program, "dialect", "iec")].time_unit_ns
        scaled = time_scaled(name, unit)
        if scaled is not None:          # this dialect's TIME counts ms, say
            pyname = safe_name(f"_cv_{name.upper()}_{unit}")
            self.namespace[pyname] = scaled
            return pyname
        fn = CONVERSIONS.get(name.upper())
        if fn is None:
            raise CompileError(f"conversion {name} is not implemented", pos)
        pyname = safe_name("_cv_" + name.upper())
        self.namespace[pyname] = fn
        return pyname

    def run_source(self, key: str, source: str, pos=ast.NOWHERE) -> None:
        self.sources[key] = self.sources.get(key, "") + source
        try:
            code = _code_of(source, f"<st:{key}>")
        except (SyntaxError, RecursionError, MemoryError) as exc:
            # CPython limits nesting (20 loops/try blocks, 100 indentation levels).
            raise CompileError(f"POU {key} is nested too deeply for the runtime ({exc.msg if isinstance(exc, SyntaxError) else type(exc).__name__})", pos) from None
        exec(code, self.namespace)  # the source is generated; ST text only as repr literals


#: (file name, generated source) -> code: every load compiles the same
#: initializers of the prelude's types again, and a code object is immutable,
#: so one compiled once serves every later namespace (exact; bounded).
_CODE: dict[tuple[str, str], object] = {}
_CODE_ENTRIES = 2048


def _code_of(source: str, filename: str):
    code = _CODE.get((filename, source))
    if code is None:
        code = compile(source, filename, "exec")
        if len(_CODE) >= _CODE_ENTRIES:
            _CODE.clear()
        _CODE[(filename, source)] = code
    return code


def _optimisations_of_environment() -> Optimisations:
    """`Optimisations.from_environment()`, made again only when ST_RUNTIME_OPTIMISE
    changes (the options are frozen: one serves every compile)."""
    global _ENVIRONMENT_OPTIMISATIONS
    value = os.environ.get("ST_RUNTIME_OPTIMISE")
    if _ENVIRONMENT_OPTIMISATIONS is None or _ENVIRONMENT_OPTIMISATIONS[0] != value:
        _ENVIRONMENT_OPTIMISATIONS = (value, Optimisations.from_environment())
    return _ENVIRONMENT_OPTIMISATIONS[1]


_ENVIRONMENT_OPTIMISATIONS: tuple | None = None


def compile_program(program, guard_statements: bool = True, charge_costs: bool = True,
                    optimise: Optimisations | None = None) -> CompiledProgram:
    """Translate a CheckedProgram; raises CompileError on unsupported input.

    `guard_statements=False` leaves out the per-statement fault handlers (a
    fault then abandons the whole scan); `charge_costs=False` leaves out the
    NJ501 execution-time charges (no F-PERIOD, a runaway loop never ends).
    Only the benchmarks use them, to show what the handlers and charges cost.
    `optimise` switches the exact optimisation passes (optimise/); None takes
    `Optimisations.from_environment()` (all, unless ST_RUNTIME_OPTIMISE says).
    """
    forget_walks()      # (what a compile lists of its nodes is its own: none kept from another)
    try:
        return _compile(program, guard_statements, charge_costs, optimise)
    finally:
        forget_walks()


def _compile(program, guard_statements, charge_costs, optimise) -> CompiledProgram:
    unit = CompileUnit(program)
    unit.optimise = optimise if optimise is not None else _optimisations_of_environment()
    unit.guard_statements = guard_statements
    unit.charge_costs = charge_costs
    shared = _shared_prelude(program)
    if shared is not None:
        unit.prelude_lead = shared.lead(program)
    _make_classes(unit, shared)
    _make_initializers(unit, shared)
    for address, t, init in program.image_inits:      # `AT %QX0.1 : BOOL := 1;`
        unit.image.set(address, resolve_alias(t).kind, unit.initial.of(t, init, init.pos).const)
    globals_obj = unit.classes["<GLOBALS>"]()
    unit.namespace["_G"] = globals_obj
    functions = {}
    for key, pou in _after_prelude(unit, "pous"):
        if pou.node is None or pou.native is not None or pou.kind == "INTERFACE":
            continue
        if pou.kind == "FUNCTION_BLOCK":
            _compile_methods(unit, key, pou)
            if not pou.node.body and pou.parent is not None:
                continue         # an FB that only extends keeps its base's body
        if pou.kind == "FUNCTION":
            pyname = safe_name("_fn_" + key)
            unit.run_source(key, BodyCompiler(program, pou, unit, method=False).function_source(pyname),
                            pou.node.pos)
            functions[key] = unit.namespace[pyname]
        else:
            pyname = safe_name("_body_" + key)
            unit.run_source(key, BodyCompiler(program, pou, unit, method=True).function_source(pyname),
                            pou.node.pos)
            unit.classes[key].execute = unit.namespace[pyname]
    classes = dict(unit.classes)
    del classes["<GLOBALS>"]
    return CompiledProgram(program, classes, functions, globals_obj, unit.sources, unit.namespace,
                           unit.image)


def method_attr(name: str, accessor: str = "") -> str:
    """The class attribute of a METHOD: `m` + the mangled name (no ST text in
    Python); a PROPERTY's getter / setter: `mg` / `ms` + the mangled name."""
    return {"": "m", "GET": "mg", "SET": "ms"}[accessor] + pyident(name)


def _compile_methods(unit: CompileUnit, key: str, pou) -> None:
    """Each own METHOD is a Python function `(self, _ctx, inputs...)` set on the
    FB's class; derived classes inherit or override it (dynamic dispatch)."""
    for method in pou.methods.values():
        if method.owner is not pou or "ABSTRACT" in method.modifiers:
            continue
        pyname = safe_name(f"_m_{key}_{method.name.upper()}" + "".join(
            "_" + w for w in ("GET", "SET") if w in method.modifiers))
        compiler = BodyCompiler(unit.program, method, unit, method=False)
        unit.run_source(f"{key}.{method.name.upper()}", compiler.function_source(pyname),
                        method.node.pos)
        accessor = next((w for w in ("GET", "SET") if w in method.modifiers), "")
        setattr(unit.classes[key], method_attr(method.name, accessor), unit.namespace[pyname])


# ------------------------------------------------------------------ classes


def _instance_variables(pou) -> list:
    """The variables an FB/PROGRAM instance stores (not TEMP, not EXTERNAL)."""
    return [s for s in pou.variables.values() if s.kind not in ("VAR_TEMP", "VAR_EXTERNAL", "VAR_GLOBAL")]


def _make_classes(unit: CompileUnit, shared=None) -> None:
    program = unit.program
    own = shared.types if shared is not None else {}
    if unit.prelude_lead.get("types"):
        unit.classes.update(shared.struct_classes)      # (what the loop below would add for them)
    for key, t in _after_prelude(unit, "types"):
        if own.get(key) is t:               # the shared prelude's: its STRUCT class, if one
            if key in shared.inits:
                unit.classes[key] = shared.classes[key]
            continue
        t = resolve_alias(t)
        if isinstance(t, StructType) and t.name.upper() == key and t.union:
            layout = {k: (name, ft) for k, (name, ft) in t.fields.items()}
            cls = _new_class(t.name, ("_bytes",), layout)
            for name, ft in t.fields.values():      # the members share `_bytes`
                setattr(cls, pyident(name), union_property(resolve_alias(ft)))
            size = max([max(resolve_alias(ft).bits // 8, 1) for _, ft in t.fields.values()] or [1])
            unit.classes[key] = _union_storage(cls, size)
        elif isinstance(t, StructType) and t.name.upper() == key:
            slots = tuple(pyident(name) for name, _ in t.fields.values())
            layout = {k: (name, ft) for k, (name, ft) in t.fields.items()}
            unit.classes[key] = _new_class(t.name, slots, layout)
    if shared is not None:       # the prelude's POUs lead program.pous, none has a base
        unit.classes.update(shared.install_layouts())
    for key, pou in _bases_first(_after_prelude(unit, "pous"),
                                 shared.pous if shared is not None else {}):
        if pou.kind in ("FUNCTION", "INTERFACE"):
            continue
        if pou.node is None or pou.native is not None:
            native = pou.native or NATIVE_FBS.get(key)
            if native is None:
                raise CompileError(f"native FB {pou.name} has no Python class", ast.NOWHERE)
            native._st_vars = {k: (s.name, s.type) for k, s in pou.variables.items()
                               if s.kind not in ("VAR_TEMP", "VAR_EXTERNAL")}
            native._st_kinds = {k: s.kind for k, s in pou.variables.items()}
            native._st_name = pou.name
            unit.classes[key] = native
            continue
        variables, edges = unit.instance_layouts[key] = _instance_variables(pou), edge_inputs(pou)
        inherited = pou.parent.variables if pou.parent is not None else {}
        slots = tuple(pyident(s.name) for s in variables
                      if located_at(s) is None and inherited.get(s.name.upper()) is not s) + \
            tuple(edge_slot(s) for s in edges if inherited.get(s.name.upper()) is not s)
        layout = {s.name.upper(): (s.name, s.type) for s in variables}
        base = unit.classes[pou.parent.name.upper()] if pou.parent is not None else STObject
        unit.classes[key] = _new_class(pou.name, slots, layout, pou.kind, base)
        unit.classes[key]._st_kinds = {s.name.upper(): s.kind for s in variables}
        unit.classes[key]._st_constants = frozenset(s.name.upper() for s in variables if s.constant)
        _locate_variables(unit, unit.classes[key], variables)
    gl = [s for s in program.globals.values()]
    if not gl:
        unit.classes["<GLOBALS>"] = _NO_GLOBALS
        return
    unit.classes["<GLOBALS>"] = _new_class(
        "Globals", tuple(pyident(s.name) for s in gl if located_at(s) is None),
        {s.name.upper(): (s.name, s.type) for s in gl})
    _locate_variables(unit, unit.classes["<GLOBALS>"], gl)
    unit.classes["<GLOBALS>"]._st_constants = frozenset(s.name.upper() for s in gl if s.constant)


def located_at(symbol):
    """The process-image Address of a located variable, None otherwise (and for %I*)."""
    if symbol.decl is None or symbol.decl.location is None:
        return None
    return parse_address(symbol.decl.location)[0]


def _locate_variables(unit: CompileUnit, cls: type, variables) -> None:
    """A located variable is a property that reads and writes the process image."""
    for symbol in variables:
        address = located_at(symbol)
        if address is not None:
            setattr(cls, pyident(symbol.name), located_property(unit.image, address,
                                                               resolve_alias(symbol.type)))


def _union_storage(cls: type, size: int) -> type:
    """A UNION class whose instances first get their zeroed shared bytes."""
    def __new__(klass, *args, **kwargs):
        obj = object.__new__(klass)
        obj._bytes = bytearray(size)
        return obj

    cls.__new__ = __new__
    return cls


def _bases_first(pous, done=()) -> list:
    """The POUs (key, PouInfo) with every FB after the FB it extends (classes derive
    from their base's); those in `done` (classes made already) left out."""
    ordered, placed = [], set(done)

    def place(key, pou):
        if key in placed:
            return
        placed.add(key)
        if pou.parent is not None:
            place(pou.parent.name.upper(), pou.parent)
        ordered.append((key, pou))

    for key, pou in pous:
        place(key, pou)
    return ordered


def _new_class(name: str, slots: tuple, layout: dict, kind: str = "STRUCT", base=STObject) -> type:
    cls = type(safe_name("ST_" + name.upper()), (base,), {
        "__slots__": slots, "_st_name": name, "_st_vars": layout, "_st_kind": kind,
    })
    return cls


def _make_initializers(unit: CompileUnit, shared=None) -> None:
    program = unit.program
    initial = unit.initial
    own = shared.types if shared is not None else {}
    if unit.prelude_lead.get("types"):
        shared.add_inits(unit)              # (what the loop below would add for them)
    for key, t in _after_prelude(unit, "types"):
        if own.get(key) is t:               # the shared prelude's: its STRUCT's __init__, if one
            if key in shared.inits:
                shared.add_init(unit, key)
            continue
        t = resolve_alias(t)
        if isinstance(t, StructType) and t.name.upper() == key:
            members = [(pyident(name), initial.of(ft, initial.member_init(key, fkey), ast.NOWHERE))
                       for fkey, (name, ft) in t.fields.items()]
            _install_init(unit, key, members)
    own = shared.pous if shared is not None else {}
    for key, pou in _after_prelude(unit, "pous"):
        if pou.kind in ("FUNCTION", "INTERFACE") or own.get(key) is pou:
            continue      # (the prelude's native layouts are whole already)
        if pou.node is None or pou.native is not None:
            cls = unit.classes[key]
            pairs = native_initializers(pou, lambda s: _maker_of(initial.of_symbol(s)))
            cls.set_initializers(pairs)
            continue
        variables, edges = unit.instance_layouts.get(key) or (_instance_variables(pou), edge_inputs(pou))
        members = [(pyident(s.name), _unconnected(s) if s.kind == "VAR_IN_OUT" else initial.of_symbol(s))
                   for s in variables]
        members += [(edge_slot(s), Initial(const=False)) for s in edges]
        _install_init(unit, key, members)
    members = [(pyident(s.name), initial.of_symbol(s)) for s in program.globals.values()]
    _install_init(unit, "<GLOBALS>", members)


def _unconnected(symbol) -> Initial:
    """A VAR_IN_OUT before its first call: a NullRef, so a use is F-NULL-REF."""
    null = NullRef(symbol.name)
    return Initial(maker=lambda: null)


def _maker_of(value):
    if value.is_const:
        const = value.const
        return lambda: const
    return value.maker


def _install_init(unit: CompileUnit, key: str, members: list) -> None:
    """The class's `__init__`: a source of one store a member, compiled, or (for the globals,
    a PROGRAM, or no member: made once per run) the same stores by `_store_members`, the
    source kept for reading.  The source's lines written as they are (one level, no block
    but the `def`), without an `Emitter`: a class's few lines cost more to emit than to write."""
    makers = unit.makers
    pyname = "_init_" + str(len(unit.sources))
    cls = unit.classes[key]
    compiled = bool(members) and key != "<GLOBALS>" and cls._st_kind != "PROGRAM"
    lines = [f"def {pyname}(self):"]
    steps = []
    for attr, value in members:
        if value.maker is None:         # (a constant: Initial.is_const)
            lines.append(f"    self.{attr} = {pyliteral(value.const)}")
            if not compiled:
                steps.append((attr, None, _plain(value.const)))
        else:
            lines.append(f"    self.{attr} = {unit.register_maker(value.maker)}()")
            steps.append((attr, value.maker, None))
    if not members:
        lines.append("    pass")
    source = "\n".join(lines) + "\n"
    if compiled:
        unit.run_source("init:" + key, source)
        cls.__init__ = unit.namespace[pyname]
    else:
        unit.sources["init:" + key] = unit.sources.get("init:" + key, "") + source
        if cls is not _NO_GLOBALS:      # (whose __init__ sets nothing already)
            cls.__init__ = _store_members(tuple(steps))
    unit.init_makers[key] = unit.makers - makers


def _store_members(steps: tuple):
    """An `__init__` that does what the source `_install_init` writes: each
    attribute in order, from its maker or its constant."""
    def __init__(self):
        for attr, maker, const in steps:
            setattr(self, attr, const if maker is None else maker())
    return __init__


#: The class of a program without globals, the same for all: no variable, no
#: constant, an `__init__` that sets nothing (`_install_init`), so nothing of one
#: program is in it.  A class costs more to make than a small file's whole check.
_NO_GLOBALS = _new_class("Globals", (), {})
_NO_GLOBALS._st_constants = frozenset()
_NO_GLOBALS.__init__ = _NO_GLOBALS_INIT = _store_members(())


def _plain(value):
    """The value the literal `pyliteral(value)` evaluates to (plain bool, int,
    float, str, tuple; NaN and infinities as _NAN and _INF)."""
    if isinstance(value, bool):
        return bool(value)
    if isinstance(value, int):
        return int(value)
    if isinstance(value, float):
        return math.nan if math.isnan(value) else float(value)
    if isinstance(value, str):
        return str(value)
    if isinstance(value, tuple):
        return tuple(_plain(v) for v in value)
    if value is None:
        return None
    raise TypeError(f"no Python literal for {type(value).__name__}")


# ------------------------------------------------------------ shared prelude


def _after_prelude(unit: CompileUnit, name: str):
    """The items of the program's table `name` ("types" or "pous") after the shared
    prelude's when those lead it (`CompileUnit.prelude_lead`), else all of them."""
    table = getattr(unit.program, name)
    lead = unit.prelude_lead.get(name)
    return islice(table.items(), lead, None) if lead else table.items()


def _shared_prelude(program):
    """The compiled native prelude of `program.prelude` (the checker's shared prelude),
    compiled once per process on first use; None for a program checked without one."""
    base = getattr(program, "prelude", None)
    if base is None:
        return None
    if base.compiled is None:
        base.compiled = SharedPrelude(base)
    return base.compiled


class SharedPrelude:
    """The prelude's STRUCT classes (with their `__init__`) and its native FBs' layouts,
    compiled once from the shared checked prelude and read by every compile.

    A class holds no instance state (each program makes its own instances), and no
    compile changes a prelude class: a compile only installs a native FB's layout,
    as before (the class is process-wide, and the dialect decides its pin names).
    A compile uses them only for the types and POUs that are the base's own objects
    (a project that declares a prelude name is checked, and compiled, in full).
    """

    def __init__(self, base) -> None:
        from ..symbols import CheckedProgram

        self.base = base
        program = CheckedProgram(files=[base.file], dialect=base.dialect)
        for name, table in base.program_tables.items():
            setattr(program, name, table)
        program.types = base.types
        unit = CompileUnit(program)
        _make_classes(unit)
        _make_initializers(unit)
        self.classes = {k: c for k, c in unit.classes.items() if k != "<GLOBALS>"}
        #: STRUCT key -> (its __init__'s source, the makers it registered)
        self.inits = {k[len("init:"):]: (source, unit.init_makers[k[len("init:"):]])
                      for k, source in unit.sources.items() if k != "init:<GLOBALS>"}
        #: native FB key -> (class, _st_vars, _st_kinds, _st_name, _st_initializers)
        self.layouts = {k: (c, c._st_vars, c._st_kinds, c._st_name, c._st_initializers)
                        for k, c in self.classes.items()
                        if base.pous.get(k) is not None and base.pous[k].native is c}
        self.native_classes = {k: layout[0] for k, layout in self.layouts.items()}
        #: (classes, their _st_vars, their _st_initializers) as `install_layouts` sets them
        self.installed = tuple(zip(*[(c, v, i) for c, v, _, _, i in self.layouts.values()])) or ((), (), ())
        self.types, self.pous = base.types, base.pous
        #: per table ("types", "pous"): its keys and its very objects, in order
        self.tables = {name: (list(table), list(table.values()))
                       for name, table in (("types", base.types), ("pous", base.pous))}
        #: in the prelude's order: its STRUCT classes; their __init__ sources; the makers of all
        self.struct_classes = {k: self.classes[k] for k in base.types if k in self.inits}
        self.init_sources = {"init:" + k: self.inits[k][0] for k in base.types if k in self.inits}
        self.init_makers = sum(self.inits[k][1] for k in base.types if k in self.inits)

    def leads(self, program, table: str) -> bool:
        """Whether `program`'s table ("types" or "pous") begins with the prelude's whole
        table, in its order, the very objects (as in most loads: then a compile does for
        them at once what it would do for each; the prelude's POUs always lead)."""
        keys, values = self.tables[table]
        mine = getattr(program, table)
        return list(islice(mine, len(keys))) == keys \
            and all(map(is_, islice(mine.values(), len(keys)), values))

    def lead(self, program) -> dict[str, int]:
        """table name -> how many of its first entries are the prelude's (`leads`), or 0."""
        return {name: len(keys) if self.leads(program, name) else 0
                for name, (keys, _) in self.tables.items()}

    def add_inits(self, unit: CompileUnit) -> None:
        """`add_init` of every prelude STRUCT, in the prelude's order."""
        unit.sources.update(self.init_sources)
        unit.makers += self.init_makers

    def add_init(self, unit: CompileUnit, key: str) -> None:
        """A STRUCT's __init__ counted in `unit` as if compiled there (sources, makers)."""
        source, makers = self.inits[key]
        unit.sources["init:" + key] = source
        unit.makers += makers

    def install_layouts(self) -> dict[str, type]:
        """Each native FB's layout of this dialect on its class, as every compile did
        (a class serves every dialect: the last compile's pin names hold); key -> class."""
        classes, st_vars, initializers = self.installed
        if all(map(is_, map(_OWN_VARS, map(vars, classes)), st_vars)) and \
                all(map(is_, map(_OWN_INITIALIZERS, map(vars, classes)), initializers)):
            return self.native_classes          # (all in place: the loop below would set none)
        for cls, st_vars, kinds, name, initializers in self.layouts.values():
            if cls.__dict__.get("_st_vars") is not st_vars or cls.__dict__.get("_st_initializers") \
                    is not initializers:
                cls._st_vars, cls._st_kinds, cls._st_name = st_vars, kinds, name
                cls._st_initializers = initializers
        return self.native_classes


#: A class's own `_st_vars` and `_st_initializers` (not a base's), from `vars(cls)`.
_OWN_VARS = methodcaller("get", "_st_vars")
_OWN_INITIALIZERS = methodcaller("get", "_st_initializers")

_native_layouts_installed = False


def install_native_layouts() -> None:
    """Check and compile the native prelude on its own, which installs every
    native FB's layout (`NativeFB.set_initializers`).

    Needed only to instantiate a native FB outside a compiled program (a unit
    test of the library); compiling any program installs them too.
    """
    global _native_layouts_installed
    if _native_layouts_installed:
        return
    from ..checker import check      # the checker is not the compiler's: only here
    from ..prelude import prelude_file

    _text, prelude, diagnostics = prelude_file()
    program, more = check([prelude] if prelude is not None else [], "iec")
    errors = [d for d in diagnostics + more if d.is_error]
    if errors:
        raise RuntimeError("native prelude does not check: " + "; ".join(d.header() for d in errors))
    compile_program(program)
    _native_layouts_installed = True
