"""The Python API: what `stgen run` and `stgen call` do, for Python callers.

    from st_runtime import load

    project = load(["plc/"])                  # parse, check, compile (raises LoadError)
    plc = project.controller(period="1ms")    # a simulated controller
    main = plc.add_program("Main")            # a PROGRAM instance on the primary task
    main["Setpoint"] = 12.5                   # set a variable (JSON-like values)
    trace = plc.trace(["Count", "Timer.ET"], program="Main")
    plc.run(1000)                             # 1000 scans of 1 ms
    print(main["Count"], main.to_json())      # read one variable or all of them
    print(plc.faults)                         # runtime faults (FaultRecord)

    project.call("Clamp", {"X": 5})           # a FUNCTION: {"return": ..., outputs...}
    project.call("Debounce", {"In": True}, until="Q", max_cycles=100)   # an FB, scan by scan

Simulated servo axes (what `stgen run --axes FILE.toml` does):

    from st_runtime.motion import MotionTask

    axes = MotionTask.from_toml(open("axes.toml").read())   # [[axis]] tables
    project = load(["plc/"], extra_sources={"axes": axes.globals_source()})
    plc = project.controller()
    axes.install(plc.controller)              # feedback in, programs, motion processing

Values go in and come out as JSON-like Python values (see `values.to_json`):
BOOL as bool, integers as int, REAL/LREAL as float, TIME as "T#1s500ms",
arrays as nested lists, structs and FB instances as dicts.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field

from .process_image import ImageView
from .controller import DEFAULT_BUDGET, Controller
from .ast import Pos
from .diagnostics import Diagnostic
from .faults import FaultRecord
from .native import mangle
from .objects import is_aggregate
from .types import ArrayType, FBType, StructType, resolve_alias
from .values import object_to_json, to_json as value_to_json  # the one JSON walk


class LoadError(Exception):
    """The files do not parse or check: `diagnostics` says why."""

    def __init__(self, diagnostics: list[Diagnostic], sources: dict[str, str]):
        self.diagnostics = diagnostics
        self.sources = sources
        super().__init__("\n".join(d.header() for d in diagnostics if d.is_error))

    def render(self) -> str:
        return "\n".join(d.render(self.sources.get(d.pos.file)) for d in self.diagnostics)


# ------------------------------------------------------------------ loading


def load(paths, dialect: str = "iec", extra_sources: dict[str, str] | None = None,
         memory_limit: int | None = None) -> "Project":
    """Load ST files and directories as one program: parse, check, compile.

    A `.xml` file (PLCopen TC6 XML or IEC 61131-10, e.g. a Sysmac Studio
    export) contributes its ST POUs, data types and global variables
    (`st_runtime.xml_reader`). `extra_sources` (name -> ST text) are loaded with the files, e.g. the axis
    globals of `MotionTask.globals_source()`; `memory_limit`: bytes a variable,
    a POU instance or the project may need (default 64 MiB, checker/memory.py).
    """
    from . import loader

    return _compiled(loader.load([os.fspath(p) for p in paths], dialect, extra_sources, memory_limit))


def load_text(text: str, path: str = "<text>", dialect: str = "iec", memory_limit: int | None = None) -> "Project":
    """Load one ST text (tests, notebooks)."""
    return load_sources({path: text}, dialect, memory_limit)


def load_sources(sources: dict[str, str], dialect: str = "iec", memory_limit: int | None = None) -> "Project":
    """Load in-memory ST texts (path -> text) as one program."""
    from . import loader

    return _compiled(loader.load_texts(dict(sources), dialect, memory_limit))


def _compiled(result) -> "Project":
    from .compiler import CompileError, compile_program

    if result.program is None:
        raise LoadError(result.diagnostics, result.sources)
    try:
        compiled = compile_program(result.program)
    except CompileError as exc:
        diagnostic = Diagnostic("E-COMPILE-001", exc.message, exc.pos)
        raise LoadError(result.diagnostics + [diagnostic], result.sources) from None
    except (RecursionError, MemoryError):
        raise
    except Exception as exc:  # a compiler bug must still read as a diagnostic
        first = next((p for p in result.sources if p != "<builtin>"), "<input>")
        diagnostic = Diagnostic("E-COMPILE-001", f"internal compiler error: {type(exc).__name__}: {exc}",
                                Pos(first, 0, 0))
        raise LoadError(result.diagnostics + [diagnostic], result.sources) from None
    return Project(compiled, result.diagnostics, result.sources)


# ------------------------------------------------------------------ project


@dataclass
class Project:
    compiled: object
    diagnostics: list          # warnings of a successful load
    sources: dict = field(default_factory=dict)
    _controllers: int = field(default=0, repr=False)

    @property
    def program(self):
        return self.compiled.checked

    def pou(self, name: str):
        pou = self.program.pous.get(name.upper())
        if pou is None:
            raise KeyError(f"no POU named {name}")
        return pou

    def controller(self, period="1ms", budget=DEFAULT_BUDGET, stop_on_fault: bool = False,
                   time_limit=None) -> "Plc":
        """A simulated controller with its own memory.

        A task run whose estimated NJ501 time passes `time_limit` (default:
        the task's period; a duration like `period`) ends with F-PERIOD.
        `budget` (loop iterations) is deprecated and ignored.

        The first controller runs `self.compiled`; each further one gets a
        fresh compilation, so no two controllers share global variables.
        """
        from .compiler import compile_program

        compiled = self.compiled
        if self._controllers:
            compiled = compile_program(self.program)
        self._controllers += 1
        limit = parse_period(time_limit) if time_limit is not None else None
        return Plc(Controller(compiled, parse_period(period), budget, stop_on_fault, limit))

    def call(self, name: str, inputs: dict | None = None, until: str | None = None,
             max_cycles: int = 1000, period="1ms") -> dict:
        """Call a FUNCTION once, or an FB instance once per scan until `until`.

        Returns {"outputs": {declared name: JSON-like value, ..., "return"
        (FUNCTION), "cycles"}, "cycles": int, "faults": [FaultRecord],
        "reached": bool (whether `until` became TRUE)}.  `outputs["cycles"]`
        is the count only when the POU declares no output or in-out of that
        name (a declared one is never overwritten); `result["cycles"]` is
        always the count.
        """
        return call_pou(self, name, inputs or {}, until, max_cycles, parse_period(period))


def parse_period(period) -> int:
    """`"1ms"`, `"T#2ms"`, or an int of nanoseconds."""
    if isinstance(period, int):
        return period
    from .values import parse_time

    text = str(period).strip()
    if "#" not in text:
        text = "T#" + text
    return parse_time(text)


# ------------------------------------------------------------ instances


class Instance:
    """A PROGRAM/FB instance (or struct) seen through declared names."""

    def __init__(self, obj, dialect: str = "iec"):
        object.__setattr__(self, "obj", obj)
        object.__setattr__(self, "dialect", dialect)  # how STRING[n] counts (st_runtime.types.STRING_UNITS)

    @property
    def layout(self) -> dict:
        return type(self.obj)._st_vars

    def _locate(self, path: str):
        """(container, attribute-or-index, type) of a dotted path."""
        from .trace import parse_path

        steps = parse_path(path)
        obj = self.obj
        container, slot, t = None, None, None
        for kind, value in steps:
            if kind == "name":
                if t is not None:
                    obj = _read(container, slot)
                layout = getattr(type(obj), "_st_vars", None) if not isinstance(obj, dict) else {}
                if layout is None:      # a member of an elementary value or an array (a.__class__)
                    raise KeyError(f"{path}: '{value}' is no member: only a STRUCT or an FB instance has members")
                entry = layout.get(value.upper())
                if entry is None:
                    raise KeyError(f"{path}: no variable '{value}'")
                container, slot, t = obj, mangle(value), entry[1]
            else:
                arr = resolve_alias(t)
                if not isinstance(arr, ArrayType) or len(value) != len(arr.dims):
                    raise KeyError(f"{path}: wrong indexing")
                seq = _read(container, slot)
                offset, stride = 0, 1
                for i, (lo, hi) in reversed(list(zip(value, arr.dims))):
                    if not lo <= i <= hi:
                        raise KeyError(f"{path}: index {i} out of bounds {lo}..{hi}")
                    offset += (i - lo) * stride
                    stride *= hi - lo + 1
                container, slot, t = seq, offset, arr.element
        return container, slot, t

    def __getitem__(self, path: str):
        container, slot, t = self._locate(path)
        return value_to_json(_read(container, slot), t)

    def raw(self, path: str):
        """The stored Python value (objects and lists themselves)."""
        container, slot, _ = self._locate(path)
        return _read(container, slot)

    def __setitem__(self, path: str, value) -> None:
        from .trace import parse_path
        from .values import from_json

        head = parse_path(path)[0][1].upper()
        if head in getattr(type(self.obj), "_st_constants", ()):
            raise KeyError(f"{path}: '{head}' is a CONSTANT")

        container, slot, t = self._locate(path)
        stored = from_json(value, t, path, self.dialect)
        _store(container, slot, t, stored)

    def to_json(self) -> dict:
        """Every variable (not VAR_IN_OUT/VAR_EXTERNAL/VAR_TEMP) by declared name."""
        return object_to_json(self.obj)


def _read(container, slot):
    if isinstance(slot, int):
        return container[slot]
    return getattr(container, slot)


def _store(container, slot, t, stored) -> None:
    """Store a value made by `values.from_json` (plain data) into an object."""
    t = resolve_alias(t)
    if isinstance(t, ArrayType):
        target = _read(container, slot)
        if is_aggregate(t.element):
            for i, item in enumerate(stored):
                _store(target, i, t.element, item)
        else:
            target[:] = stored
    elif isinstance(t, (StructType, FBType)):
        target = _read(container, slot)
        layout = type(target)._st_vars
        for k, item in stored.items():
            name, ft = layout[k.upper()]
            _store(target, mangle(name), ft, item)
    elif isinstance(slot, int):
        container[slot] = stored
    else:
        setattr(container, slot, stored)


class Plc:
    """A controller with name-based access (what `stgen run` drives)."""

    def __init__(self, controller: Controller):
        self.controller = controller
        self.compiled = controller.compiled     # the program image this controller runs

    def add_program(self, name: str, task: str | None = None) -> Instance:
        return Instance(self.controller.add_program(name, task), self.compiled.checked.dialect)

    def add_task(self, name: str, period) -> None:
        self.controller.add_task(name, parse_period(period))

    def add_io_hook(self, before=None, after=None) -> None:
        self.controller.add_io_hook(before, after)

    def program(self, name: str) -> Instance:
        for key, obj in self.controller.instances.items():
            if key.upper() == name.upper():
                return Instance(obj, self.compiled.checked.dialect)
        raise KeyError(f"no program instance {name}")

    @property
    def globals(self) -> Instance:
        return Instance(self.controller.globals, self.compiled.checked.dialect)

    @property
    def image(self) -> ImageView:
        """The process image: `plc.image["%IX0.0"] = True`, `plc.image["%QW3"]`
        (a bit as BOOL, a B/W/D/L address as an unsigned integer)."""
        return ImageView(self.compiled.image)

    def run(self, cycles: int = 1) -> int:
        return self.controller.run(cycles)

    def scan(self) -> bool:
        return self.controller.scan()

    @property
    def faults(self) -> list[FaultRecord]:
        return self.controller.faults

    @property
    def now_ns(self) -> int:
        return self.controller.now_ns

    def trace(self, paths: list[str], program: str | None = None):
        """Record `paths` (in `program`, else in the globals) after every scan."""
        from .trace import Trace

        roots = [self.program(program).obj] if program else []
        roots.append(self.controller.globals)
        trace = Trace.for_objects(paths, roots)
        self.controller.add_observer(lambda c: trace.sample(c.ctx.now_ns, c.ctx.scan), reads_only=True)
        return trace


# ------------------------------------------------------------------ calls


class CallError(Exception):
    """A call that cannot be made as asked (unknown POU, input, output)."""


class _FunctionJob:
    """Adapts a FUNCTION call to the controller's `execute(ctx)` interface."""

    def __init__(self, fn, args):
        self.fn = fn
        self.args = args
        self.result = None

    def execute(self, ctx):
        self.result = self.fn(ctx, *self.args)


def call_pou(project: Project, name: str, inputs: dict, until: str | None,
             max_cycles: int, period_ns: int) -> dict:
    """See `Project.call`."""
    pou = project.program.pous.get(name.upper())
    if pou is None or pou.kind not in ("FUNCTION", "FUNCTION_BLOCK"):
        raise CallError(f"no FUNCTION or FUNCTION_BLOCK named {name}")
    params = {k: s for k, s in pou.variables.items() if s.kind in ("VAR_INPUT", "VAR_IN_OUT")}
    for key in inputs:
        if key.upper() not in params:
            raise CallError(f"{pou.name} has no input named {key} "
                            f"(inputs: {', '.join(s.name for s in params.values()) or 'none'})")
    given = {k.upper(): v for k, v in inputs.items()}
    in_outs = {key: _Cell(project.compiled, symbol, given.get(key))
               for key, symbol in params.items() if symbol.kind == "VAR_IN_OUT"}
    controller = Controller(project.compiled, period_ns)
    if pou.kind == "FUNCTION":
        if until:
            raise CallError("--until applies to FB outputs; a FUNCTION is called once")
        out = _call_function(project.compiled, pou, params, given, in_outs, controller)
        cycles, reached = 1, True
    else:
        out, cycles, reached = _call_fb(project.compiled, pou, params, given, in_outs, controller,
                                        until, max_cycles)
    for key, cell in in_outs.items():
        out[params[key].name] = cell.to_json()
    if not any(key.upper() == "CYCLES" for key in out):
        out["cycles"] = cycles          # last, after the outputs
    return {"outputs": out, "cycles": cycles, "faults": controller.faults, "reached": reached}


def _call_function(compiled, pou, params: dict, given: dict, in_outs: dict, controller) -> dict:
    from .values import from_json

    args = []
    for key, symbol in params.items():
        if symbol.kind == "VAR_IN_OUT":
            args.append(in_outs[key].arg)
        elif key in given:
            args.append(_plain_value(compiled, symbol, from_json(given[key], symbol.type, symbol.name,
                                                                 compiled.checked.dialect)))
        else:
            args.append(_initial(compiled, symbol))
    job = _FunctionJob(compiled.functions[pou.name.upper()], args)
    controller.tasks[0].programs.append((pou.name, job))
    controller.run(1)
    out = {}
    result = job.result
    if pou.outputs:     # the function returned (result, outputs...) unless a fault stopped it
        values = list(result) if result is not None else [None] * (1 + len(pou.outputs))
        result = values[0]
        for symbol, value in zip(pou.outputs, values[1:]):
            if value is not None:
                out[symbol.name] = value_to_json(value, symbol.type)
    if pou.return_type is not None and result is not None:
        out["return"] = value_to_json(result, pou.return_type)
    return out


def _call_fb(compiled, pou, params: dict, given: dict, in_outs: dict, controller,
             until: str | None, max_cycles: int) -> tuple[dict, int, bool]:
    instance = compiled.new(pou.name)
    view = Instance(instance, compiled.checked.dialect)
    for key, symbol in params.items():
        if symbol.kind == "VAR_IN_OUT":
            setattr(instance, mangle(symbol.name), in_outs[key].arg)
        elif key in given:
            view[symbol.name] = given[key]
    flag = None
    if until:
        flag = pou.variables.get(until.upper())
        if flag is None or flag.kind != "VAR_OUTPUT" or str(resolve_alias(flag.type)) != "BOOL":
            raise CallError(f"--until needs a BOOL output of {pou.name}; '{until}' is not one")
    controller.tasks[0].programs.append((pou.name, instance))
    cycles, reached = 0, flag is None
    limit = max_cycles if flag is not None else 1
    while cycles < limit:
        cycles += 1
        if not controller.scan():
            break
        if flag is not None and getattr(instance, mangle(flag.name)):
            reached = True
            break
    out = {s.name: value_to_json(getattr(instance, mangle(s.name)), s.type) for s in pou.outputs}
    return out, cycles, reached


class _Cell:
    """A variable owned by the caller, passed to a VAR_IN_OUT (`arg`)."""

    def __init__(self, compiled, symbol, data=None):
        from .objects import ItemRef
        from .values import from_json

        self.symbol = symbol
        self.holder = [_initial(compiled, symbol)]
        if data is not None:
            _store(self.holder, 0, symbol.type, from_json(data, symbol.type, symbol.name, compiled.checked.dialect))
        aggregate = is_aggregate(symbol.type)
        self.arg = self.holder[0] if aggregate else ItemRef(self.holder, 0)

    def to_json(self):
        return value_to_json(self.holder[0], self.symbol.type)


def _initial(compiled, symbol):
    from .compiler.initial import InitialValues

    initial = InitialValues(compiled.checked, compiled.classes).of_symbol(symbol)
    return initial.const if initial.is_const else initial.maker()


def _plain_value(compiled, symbol, stored):
    """A `from_json` result as the compiled code stores it (objects for structs)."""
    if not is_aggregate(symbol.type):
        return stored
    holder = [_initial(compiled, symbol)]
    _store(holder, 0, symbol.type, stored)
    return holder[0]
