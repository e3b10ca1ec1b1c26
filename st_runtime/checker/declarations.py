"""Declarations: data types, POUs and their variables, global variables.

Fills `CheckedProgram.types`, `.pous`, `.globals`.  Types are resolved lazily
(a TYPE may use another declared later) with cycle detection; every type in
the CheckedProgram is resolved: an alias maps to its target type (no
AliasType), a FUNCTION_BLOCK name maps to its FBType.
"""

from __future__ import annotations

import difflib

from .. import ast
from .. import native
from ..process_image import parse_address, type_fits
from .. import types as T
from ..ast import key
from ..symbols import PouInfo, Symbol
from . import builtins as B
from . import typesys as ts
from .configuration import check_config_inits, check_connections, check_program_access
from .constfold import NOT_CONSTANT
from .context import BUILTIN_FILE, Context, Scope, a_or_an
from .expressions import ExprChecker
from .oo import ObjectModel

_INSTANCE_KINDS = ("VAR", "VAR_INPUT", "VAR_OUTPUT", "VAR_TEMP")


def fb_type_of(t):
    """The FBType of an instance variable (or of an array's elements), else None."""
    t = ts.innermost(t)
    return t if isinstance(t, T.FBType) else None


class Declarations:
    """`base`: the shared checked prelude (`prelude_base`), already declared; `run` then
    gets the user's files only.  `record`: note what resolving each TYPE does
    (`type_events`), when building such a base."""

    def __init__(self, ctx: Context, base=None, record: bool = False):
        self.ctx = ctx
        self.program = ctx.program
        self.global_blocks: list[ast.VarBlock] = []
        self._global_ex: ExprChecker | None = None      # (`global_ex`, made at its first use)
        self._resolving: set[str] = set()
        self._names: dict[str, ast.Pos] = dict(base.names) if base is not None else {}
        self.configurations: list[ast.Configuration] = []
        self.objects = ObjectModel(self)
        self._interfaces_done: set[int] = set(base.interfaces_done) if base is not None else set()
        self.base = base
        # TYPE key -> [("call", key, None) | ("enum", value key, EnumType) | ("insert", key, None)]
        self.type_events: dict[str, list] | None = {} if record else None
        self._recording: list[str] = []
        self._adopted = False        # a prelude TYPE entered this load's tables already
        # id(PouInfo) -> the checker of its declarations, which its body's takes on (`body_checker`)
        self.checkers: dict[int, ExprChecker] = {}

    def body_checker(self, info: PouInfo) -> ExprChecker:
        """The expressions' checker of `info`'s body: the one its declarations were checked
        with, in the same scope, now that every name is declared (`ExprChecker.declared`),
        or a new one where this load checked none (a POU of the shared prelude)."""
        ex = self.checkers.pop(id(info), None)
        if ex is None:
            return ExprChecker(self.ctx, Scope(self.ctx, info), declared=True)
        ex.declared = True
        return ex

    @property
    def global_ex(self) -> ExprChecker:
        """The expressions' checker at global level (globals, TYPEs, configurations), made
        at its first use: a load of POUs alone never asks for it.  (Not a `cached_property`:
        its first use would make the instance's `__dict__` a real dict, and CPython 3.11 then
        reads `self.ctx` and every other attribute by a slower path.)"""
        ex = self._global_ex
        if ex is None:
            ex = self._global_ex = ExprChecker(self.ctx, Scope(self.ctx, None))
        return ex

    # ------------------------------------------------------------- driver
    def run(self, files: list[ast.SourceFile]) -> None:
        for f in files:
            for item in f.items:
                self._collect(item)
                space = getattr(item, "namespace", "")
                while space:            # NAMESPACE A.B declares A and A.B
                    self.ctx.namespaces.add(key(space))
                    space = space.rpartition(".")[0]
        # With a shared prelude, its POUs and TYPEs lead the tables: only the user's
        # are declared here (the prelude's are, and their checks found nothing).
        base = self.base
        pous = list(self.ctx.pou_decls.items())[len(base.context_tables["pou_decls"]) if base else 0:]
        self._create_pous(pous)
        # Global constants first: types may use them (ARRAY[1..N_LEGS]); types
        # are resolved on demand while globals are declared, the rest after.
        for block in sorted(self.global_blocks, key=lambda b: not b.constant):
            for decl in block.decls:
                self.declare(decl, block, self.program.globals, self.global_ex, None)
        type_keys = list(self.ctx.type_decls)
        if base is not None:
            count = len(base.context_tables["type_decls"])
            self._adopt_all(type_keys[:count])
            type_keys = type_keys[count:]
        for k in type_keys:
            self.type_named(k)
        for k, node in pous:
            self.ensure_interface(self.program.pous[k])
        for k, node in pous:
            self.objects.check_contracts(self.program.pous[k], node)
        for config in self.configurations:
            self._configuration(config)
        for k, node in pous:
            if getattr(node, "access", ()):
                info = self.program.pous[k]
                check_program_access(self, node.access, ExprChecker(self.ctx, Scope(self.ctx, info)))

    def _configuration(self, config: ast.Configuration) -> None:
        """Program instances name a declared PROGRAM and a declared TASK."""
        tasks = {key(t.name) for t in config.tasks}
        ex = self.global_ex
        for task in config.tasks:
            if task.interval is not None:
                ex.check_value(task.interval, T.TIME, f"INTERVAL of task {task.name}")
            if task.priority is not None:
                ex.check_value(task.priority, T.UINT, f"PRIORITY of task {task.name}")
        for inst in config.programs:
            pou = self.ctx.pou_decls.get(key(inst.program_type))
            if pou is None or pou.kind != "PROGRAM":
                found = a_or_an(pou.kind) if pou is not None else "nothing of that name"
                self.ctx.error("E-DECL-004", f"program instance {inst.name}: expected a PROGRAM "
                               f"'{inst.program_type}', found {found}", inst.pos)
            if inst.task is not None and key(inst.task) not in tasks:
                names = ", ".join(t.name for t in config.tasks) or "none"
                self.ctx.error("E-DECL-001", f"program instance {inst.name}: undeclared task "
                               f"'{inst.task}' (tasks: {names})", inst.pos)
            info = self.program.pous.get(key(inst.program_type))
            if info is not None and info.kind == "PROGRAM":
                check_connections(self.ctx, inst, info, ex)
        check_config_inits(self, config, ex)

    def _collect(self, item) -> None:
        if isinstance(item, ast.TypeDecl):
            if self._declare_name(item.name, item.pos):
                self.ctx.type_decls[key(item.name)] = item
        elif isinstance(item, ast.Pou):
            if self._replaces_standard_fb(item) or self._declare_name(item.name, item.pos):
                self.ctx.pou_decls[key(item.name)] = item
        elif isinstance(item, ast.VarBlock):
            self.global_blocks.append(item)
        elif isinstance(item, ast.Configuration):
            self.global_blocks.extend(item.globals)
            self.configurations.append(item)

    def _replaces_standard_fb(self, item: ast.Pou) -> bool:
        """A project's own FUNCTION_BLOCK named like a built-in one (TON, CTU, MC_Power)
        replaces it, with W-DECL-001: toolchains ship these as ST libraries (MATIEC's
        lib/*.txt, STruC++'s libs/sources), and a project built with them declares them.
        Whether IEC 61131-3 reserves the standard FB names was not confirmed from a
        source at hand, hence a warning, not silence.  A standard function stays
        E-DECL-003: its overloads (ANY_NUM ...) cannot be replaced by one POU."""
        k = key(item.name)
        first = self._names.get(k)
        builtin = self.ctx.pou_decls.get(k)
        if item.kind != "FUNCTION_BLOCK" or first is None or first.file != BUILTIN_FILE \
                or builtin is None or builtin.kind != "FUNCTION_BLOCK" or item.pos.file == BUILTIN_FILE:
            return False
        self._names[k] = item.pos
        self.ctx.warning("W-DECL-001", f"'{item.name}' replaces the built-in standard function "
                         f"block of that name in this project", item.pos)
        return True

    def _declare_name(self, name: str, pos: ast.Pos) -> bool:
        k = key(name)
        if k in T.ELEMENTARY or k in ("STRING", "WSTRING"):
            self.ctx.error("E-DECL-003", f"'{name}' is an elementary type name and cannot be "
                           f"declared again", pos)
        elif B.is_standard_name(k):
            self.ctx.error("E-DECL-003", f"'{name}' would redefine the standard function "
                           f"{k}", pos)
        elif k in self._names:
            first = self._names[k]
            self.ctx.error("E-DECL-003", f"duplicate declaration of '{name}': already declared "
                           f"at {first}", pos)
        else:
            self._names[k] = pos
            return True
        return False

    def _create_pous(self, pous) -> None:
        for k, node in pous:
            info = PouInfo(node.name, node.kind, node, file=node.pos.file)
            if node.kind == "INTERFACE":
                self.program.types[k] = T.InterfaceType(node.name, info)
            if node.kind == "FUNCTION_BLOCK":
                fb = T.FBType(node.name, info=info)
                fb.variables = info.variables
                if node.pos.file == BUILTIN_FILE and k in native.NATIVE_FBS:
                    fb.native = info.native = native.NATIVE_FBS[k]
                self.program.types[k] = fb
            self.program.pous[k] = info

    # --------------------------------------------------------------- types
    def type_named(self, k: str):
        """The resolved type declared as `k` (upper case), ERROR on a cycle, None if unknown."""
        t = self.program.types.get(k)
        if self._recording:
            self.type_events[self._recording[-1]].append(("call", k, None))
        if t is not None:
            return t
        decl = self.ctx.type_decls.get(k)
        if decl is None:
            return None
        if self.base is not None and k in self.base.type_events and self.base.types.get(k) is not None:
            return self._adopt(k)
        if k in self._resolving:
            self.ctx.error("E-DECL-005", f"type {decl.name} is defined in terms of itself", decl.pos)
            return ts.ERROR
        self._resolving.add(k)
        if self.type_events is not None:
            self.type_events[k] = []
            self._recording.append(k)
        try:
            try:
                t = self._type_spec(decl)
            finally:
                self._resolving.discard(k)
            self.program.types[k] = t
            if self.type_events is not None:
                self.type_events[k].append(("insert", k, None))
            if decl.init is not None and t is not ts.ERROR:
                self.initializer(decl.init, t, self.global_ex, f"initial value of type {decl.name}")
        finally:
            if self.type_events is not None:
                self._recording.pop()
        return t

    def _adopt_all(self, keys: list[str]) -> None:
        """Every prelude TYPE enters this load's tables, as the full check's loop over
        them does: at once in the base's order when none entered before (the base
        resolved them in this loop's order from nothing), else one by one."""
        base = self.base
        if self._adopted:
            for k in keys:
                self.type_named(k)
            return
        self._adopted = True
        self.program.types.update(base.types)
        enum_values = self.ctx.enum_values
        if not enum_values:         # (as the loop below makes them, at once)
            names, enums = base.enum_lists
            enum_values.update(zip(names, map(list, enums)))
            return
        for name, enums in base.enum_values.items():
            enum_values.setdefault(name, []).extend(enums)

    def _adopt(self, k: str):
        """A prelude TYPE enters this load's tables as resolving it did in the full check:
        the types it needed first, its enumeration values, then itself."""
        base = self.base
        self._adopted = True
        t = base.types[k]
        for kind, name, enum in base.type_events[k]:
            if kind == "call":
                self.type_named(name)
            elif kind == "enum":
                self.ctx.enum_values.setdefault(name, []).append(enum)
            elif k not in self.program.types:
                self.program.types[k] = t
        return self.program.types.get(k, t)

    def _type_spec(self, decl: ast.TypeDecl):
        spec = decl.spec
        if isinstance(spec, ast.StructType):
            if not spec.members:       # IEC 61131-3 Annex A, Struct_Decl: ( Struct_Elem_Decl ';' )+
                self.ctx.error("E-DECL-018", f"{'UNION' if spec.union else 'STRUCT'} {decl.name}: "
                               f"expected at least one member", spec.pos)
            fields: dict[str, tuple[str, object]] = {}
            for member in spec.members:
                mk = key(member.name)
                mt = self.resolve(member.type, self.global_ex)
                if mk in fields:
                    self.ctx.error("E-DECL-002", f"duplicate member '{member.name}' in struct "
                                   f"{decl.name}", member.pos)
                    continue
                if spec.union and mt is not ts.ERROR and not (
                        isinstance(mt, T.ElementaryType) and mt.kind in ("bool", "int", "bits", "real")):
                    self.ctx.error("E-DECL-017", f"UNION {decl.name}: member '{member.name}' is "
                                   f"{mt}; expected BOOL, an integer, a bit string or a real "
                                   f"(they share bytes)", member.pos)
                    continue
                if member.init is not None and mt is not ts.ERROR:
                    self.initializer(member.init, mt, self.global_ex,
                                     f"initial value of member '{member.name}'")
                fields[mk] = (member.name, mt)
            return T.StructType(decl.name, fields, spec.union)
        if isinstance(spec, ast.EnumType):
            return self._enum(decl, spec)
        return self.resolve(spec, self.global_ex)

    def _enum(self, decl, spec: ast.EnumType):
        enum = T.EnumType(decl.name)
        next_value = 0
        for ev in spec.values:
            ek = key(ev.name)
            value = next_value
            if ev.value is not None:
                self.global_ex.infer(ev.value, T.DINT, strict=True)
                folded = self.global_ex.constant(ev.value)
                if isinstance(folded, int) and not isinstance(folded, bool):
                    value = folded
                elif id(ev.value) in self.program.expr_types and \
                        self.program.expr_types[id(ev.value)] is not ts.ERROR:
                    self.ctx.error("E-DECL-008", f"value of '{ev.name}': expected a constant "
                                   f"integer", ev.value.pos)
            if ek in enum.values:
                self.ctx.error("E-DECL-002", f"duplicate value '{ev.name}' in enumeration "
                               f"{decl.name}", ev.pos)
                continue
            enum.values[ek] = (ev.name, value)
            next_value = value + 1
            self.ctx.enum_values.setdefault(ek, []).append(enum)
            if self._recording:
                self.type_events[self._recording[-1]].append(("enum", ek, enum))
        return enum

    def resolve(self, ref, ex: ExprChecker):
        """A declared type reference as a semantic type (ERROR after a report)."""
        if isinstance(ref, ast.NamedType):
            # An elementary type spelled in capitals (the usual `INT`, `LREAL`) is its own key:
            # one look-up, the type the steps below give it (no such key holds a '.' or is a STRING's).
            elementary = T.ELEMENTARY.get(ref.name)
            if elementary is not None:
                return elementary
        if isinstance(ref, ast.NamedType) and "." in ref.name:
            short = self.qualified(ref.name, ref.pos)
            if short is None:
                return ts.ERROR
            ref = ast.NamedType(short, pos=ref.pos)
        if isinstance(ref, ast.NamedType):
            k = key(ref.name)
            if k == "STRING":
                return T.StringType()
            if k == "WSTRING":
                return T.StringType(wide=True)
            if k in T.ELEMENTARY:
                return T.ELEMENTARY[k]
            if k == "LTIME":  # IEC 3rd ed.: TIME here is already 64-bit nanoseconds
                return T.TIME
            t = self.type_named(k)
            if t is not None:
                return t
            pou = self.ctx.pou_decls.get(k)
            if pou is not None:
                self.ctx.error("E-DECL-004", f"'{ref.name}' is a {pou.kind}, not a type", ref.pos)
            else:
                known = list(self.ctx.type_decls) + list(T.ELEMENTARY) + \
                    [n for n, p in self.ctx.pou_decls.items() if p.kind == "FUNCTION_BLOCK"]
                close = difflib.get_close_matches(k, known, n=1, cutoff=0.8)
                hint = f" (did you mean {close[0]}?)" if close else ""
                self.ctx.error("E-DECL-004", f"unknown type '{ref.name}'{hint}", ref.pos)
            return ts.ERROR
        if isinstance(ref, ast.SubrangeType):
            return self._subrange(ref, ex)
        if isinstance(ref, ast.RefType):
            target = self.resolve(ref.target, ex)
            return ts.ERROR if target is ts.ERROR else T.RefType(target, ref.pointer)
        if isinstance(ref, ast.StringType):
            if ref.length is None:
                return T.StringType(wide=ref.wide)
            n = self._const_int(ref.length, ex, "string length")
            if n is None:
                return ts.ERROR
            if n < 1:
                self.ctx.error("E-DECL-006", f"string length: expected a positive integer, found {n}",
                               ref.length.pos)
                return ts.ERROR
            return T.StringType(n, ref.wide)
        if isinstance(ref, ast.ArrayType):
            dims = []
            ok = True
            for sub in ref.ranges:
                if sub is None:          # ARRAY[*]
                    dims.append((None, None))
                    continue
                lo = self._const_int(sub.lo, ex, "array lower bound")
                hi = self._const_int(sub.hi, ex, "array upper bound")
                if lo is None or hi is None:
                    ok = False
                    continue
                if lo > hi:
                    self.ctx.error("E-DECL-006", f"array bounds {lo}..{hi}: expected the lower "
                                   f"bound not above the upper bound", sub.pos)
                    ok = False
                    continue
                dims.append((lo, hi))
            element = self.resolve(ref.element, ex)
            if not ok or element is ts.ERROR:
                return ts.ERROR
            return T.ArrayType(tuple(dims), element, self._default_init(ref.element))
        return ts.ERROR

    def qualified(self, name: str, pos) -> str | None:
        """`NS.Name` -> "Name" when Name is declared in namespace NS."""
        space, _, short = name.rpartition(".")
        if self.ctx.in_namespace(space, short) is None:
            self.ctx.error("E-DECL-004", f"unknown type '{name}'" + (
                "" if key(space) in self.ctx.namespaces else f" (no NAMESPACE {space})"), pos)
            return None
        return short

    def _subrange(self, ref: ast.SubrangeType, ex: ExprChecker):
        """`INT (0..100)`: an integer base, constant limits inside it, lo <= hi."""
        base = T.ELEMENTARY.get(key(ref.base))
        if base is None or base.kind != "int":
            self.ctx.error("E-DECL-014", f"subrange of '{ref.base}': expected an integer type "
                           f"(SINT ... ULINT) before the range", ref.pos)
            return ts.ERROR
        lo = self._const_int(ref.range.lo, ex, "subrange lower limit")
        hi = self._const_int(ref.range.hi, ex, "subrange upper limit")
        if lo is None or hi is None:
            return ts.ERROR
        if not (base.min <= lo <= hi <= base.max):
            self.ctx.error("E-DECL-014", f"subrange {lo}..{hi} of {base}: expected "
                           f"{base.min} <= lower <= upper <= {base.max}", ref.range.pos)
            return ts.ERROR
        return T.subrange_of(base, lo, hi)

    def _const_int(self, e, ex: ExprChecker, what: str):
        t = ex.infer(e, T.DINT)
        if t is ts.ERROR:
            return None
        value = ex.constant(e)
        if not ts.is_int(t) or value is NOT_CONSTANT or isinstance(value, bool):
            self.ctx.error("E-DECL-006", f"{what}: expected a constant integer, found "
                           + ("a non-constant expression" if value is NOT_CONSTANT else f"{t}"), e.pos)
            return None
        return value

    # ---------------------------------------------------------- variables
    def declare(self, decl: ast.VarDecl, block: ast.VarBlock, table: dict, ex: ExprChecker,
                pou: PouInfo | None, kind: str | None = None) -> Symbol | None:
        kind = kind or block.kind
        k = key(decl.name)
        t = self.resolve(decl.type, ex)
        if not decl.name:                     # `AT %IX1.1 : BOOL;`: a place, no symbol
            self._located(decl, kind, t, pou)
            address = parse_address(decl.location)[0]
            if address is not None and t is not ts.ERROR:
                self.ctx.direct_types[address.text] = t
                if decl.init is not None:
                    self.initializer(decl.init, t, ex, f"initial value of {decl.location}")
                    self.program.image_inits.append((address, t, decl.init))
            return None
        if k in table:
            first = table[k].decl.pos if table[k].decl is not None else None
            where = f" (first declared at {first})" if first is not None else ""
            scope = f"POU {pou.name}" if pou is not None else "the global variables"
            self.ctx.error("E-DECL-002", f"duplicate declaration of '{decl.name}' in {scope}{where}",
                           decl.pos)
            return None
        if type(t) is T.ElementaryType:       # (an INT is no FB, no array, nothing ABSTRACT)
            if decl.location is not None:
                self._located(decl, kind, t, pou)
        else:
            self._check_placed_type(decl, kind, t, pou)
        if decl.edge and (kind != "VAR_INPUT" or pou is None or pou.kind == "FUNCTION"
                          or (t is not ts.ERROR and not ts.is_bool(t))):
            self.ctx.error("E-DECL-013", f"'{decl.name}' is declared {decl.edge}: expected a BOOL "
                           f"VAR_INPUT of a FUNCTION_BLOCK or PROGRAM, found {a_or_an(f'{t} {kind}')}"
                           + (f" of FUNCTION {pou.name}" if pou is not None and pou.kind == "FUNCTION" else ""),
                           decl.pos)
        constant = block.constant
        if kind == "VAR_EXTERNAL":
            glob = self.program.globals.get(k)
            if glob is None:
                self.ctx.error("E-DECL-010", f"VAR_EXTERNAL '{decl.name}': expected a VAR_GLOBAL of "
                               f"that name, found none", decl.pos)
            elif t is not ts.ERROR and glob.type is not ts.ERROR and not ts.same_type(t, glob.type):
                self.ctx.error("E-DECL-010", f"VAR_EXTERNAL '{decl.name}': declared {t} here, but "
                               f"the VAR_GLOBAL is {glob.type}", decl.pos)
            else:
                constant = constant or glob.constant
        if decl.init is not None and kind in ("VAR_IN_OUT", "VAR_EXTERNAL"):
            self.ctx.error("E-DECL-012", f"{kind} '{decl.name}' refers to a variable declared "
                           f"elsewhere: expected no initial value, found one", decl.init.pos
                           if hasattr(decl.init, "pos") else decl.pos)
            decl = ast.VarDecl(decl.name, decl.type, None, pos=decl.pos)
        init = decl.init if decl.init is not None else self._default_init(decl.type)
        sym = Symbol(decl.name, t, kind, decl, constant=constant, retain=block.retain, init=init)
        if decl.init is not None and t is not ts.ERROR:
            self.initializer(decl.init, t, ex, f"initial value of '{decl.name}'")
            if constant:
                value = ex.constant(decl.init)
                if value is not NOT_CONSTANT:
                    self.ctx.symbol_values[id(sym)] = value
        elif kind == "VAR_EXTERNAL":
            glob = self.program.globals.get(k)
            if glob is not None and id(glob) in self.ctx.symbol_values:
                self.ctx.symbol_values[id(sym)] = self.ctx.symbol_values[id(glob)]
        elif block.constant and decl.init is None and t is not ts.ERROR \
                and not isinstance(t, T.FBType):
            self.ctx.error("E-DECL-011", f"CONSTANT '{decl.name}': expected an initial value, "
                           f"found none", decl.pos)
        table[k] = sym
        return sym

    def _check_placed_type(self, decl: ast.VarDecl, kind: str, t, pou: PouInfo | None) -> None:
        """What a variable's type (no elementary one) may not be where it is declared, in
        this order: an FB in a FUNCTION (E-DECL-009), its address (`_located`), ARRAY[*]
        outside a VAR_IN_OUT, an ABSTRACT FB's instance."""
        if pou is not None and pou.kind == "FUNCTION" and kind != "VAR_IN_OUT" and fb_type_of(t):
            self.ctx.error("E-DECL-009", f"FUNCTION {pou.name} declares '{decl.name}' of function "
                           f"block type {fb_type_of(t).name}: functions keep no state; use a "
                           f"FUNCTION_BLOCK", decl.pos)
        if decl.location is not None:
            self._located(decl, kind, t, pou)
        if isinstance(t, T.ArrayType) and t.is_open and kind != "VAR_IN_OUT":
            self.ctx.error("E-DECL-006", f"'{decl.name}' : {t}: ARRAY[*] is only for a VAR_IN_OUT "
                           f"(the bounds come with the argument)", decl.pos)
        fb_node = self.ctx.pou_decls.get(key(t.name)) if isinstance(t, T.FBType) else None
        if fb_node is not None and "ABSTRACT" in fb_node.modifiers:
            self.ctx.error("E-DECL-016", f"'{decl.name}': {t.name} is ABSTRACT and cannot be "
                           f"instantiated (declare an FB that extends it)", decl.pos)

    def _located(self, decl: ast.VarDecl, kind: str, t, pou) -> None:
        """`x AT %IW3 : INT` (IEC 61131-3 6.5.5): a valid address of the type's width,
        in a PROGRAM, a configuration or the globals; an FB may only say `%I*`."""
        address, problem = parse_address(decl.location)
        where = f"'{decl.name}' AT {decl.location}" if decl.name else decl.location
        if problem is not None:
            self.ctx.error("E-DECL-015", f"{where}: {problem}", decl.pos)
        elif kind not in ("VAR", "VAR_GLOBAL", "VAR_INPUT", "VAR_OUTPUT"):
            self.ctx.error("E-DECL-015", f"{where}: a {kind} cannot be located (VAR, VAR_GLOBAL, "
                           f"VAR_INPUT or VAR_OUTPUT can)", decl.pos)
        elif pou is not None and pou.kind == "FUNCTION":
            self.ctx.error("E-DECL-015", f"{where}: a FUNCTION keeps no variables between calls "
                           f"and cannot have located ones", decl.pos)
        elif address is not None and pou is not None and pou.kind == "FUNCTION_BLOCK":
            self.ctx.error("E-DECL-015", f"{where}: in a FUNCTION_BLOCK only %I*, %Q* or %M* "
                           f"(a place chosen by the configuration), found a full address", decl.pos)
        elif address is not None and t is not ts.ERROR and not type_fits(address, t):
            self.ctx.error("E-DECL-015", f"{where}: an address of size {address.size} holds "
                           f"{address.bits} bit(s); expected a type of that width, found {t}", decl.pos)
        elif address is not None and t is not ts.ERROR:
            self.ctx.direct_types.setdefault(address.text, t)    # `%IW1` in code reads as t

    def _default_init(self, ref):
        """The initial value a variable of type `ref` starts at when it declares none: its
        TYPE's, or, for a TYPE declared as another named type without one of its own, that
        type's, down the chain (IEC 61131-3:2013 table 11: a derived type's
        default is its parent's unless it gives its own). `seen` stops at a cycle, which
        the type checks refuse on their own."""
        if type(ref) is ast.NamedType and ref.name in T.ELEMENTARY:
            return None     # (`INT`: no TYPE takes an elementary type's name, `_declare_name`)
        seen: set[str] = set()
        type_decls = self.ctx.type_decls
        while isinstance(ref, ast.NamedType):
            name = key(ref.name)
            decl = type_decls.get(name)
            if decl is None:
                return None     # (an elementary type, or one refused: the usual end, looked up first)
            if decl.init is not None:
                return decl.init     # (never of a name seen: there, the same decl had none)
            if name in seen:
                return None
            seen.add(name)
            ref = decl.spec
        return None

    def initializer(self, init, t, ex: ExprChecker, what: str) -> None:
        """Check an initial value (expression, array or struct initializer) against `t`."""
        if isinstance(init, ast.ArrayInit):
            if not isinstance(t, T.ArrayType):
                self.ctx.error("E-DECL-007", f"{what}: expected a value of type {t}, found an "
                               f"array initializer", init.pos)
                return
            count = self._array_items(init, t.element, ex, what)
            if count > t.size:
                self.ctx.error("E-DECL-007", f"{what}: expected at most {t.size} element(s) for "
                               f"{t}, found {count}", init.pos)
            return
        if isinstance(init, ast.StructInit):
            if isinstance(t, T.StructType):
                members = {k: mt for k, (_, mt) in t.fields.items()}
            elif isinstance(t, T.FBType):
                members = {k: s.type for k, s in t.variables.items() if s.kind == "VAR_INPUT"}
            else:
                self.ctx.error("E-DECL-007", f"{what}: expected a value of type {t}, found a "
                               f"struct initializer", init.pos)
                return
            seen: set[str] = set()
            for f in init.fields:
                fk = key(f.name)
                if fk not in members:
                    self.ctx.error("E-DECL-007", f"{what}: {t} has no "
                                   f"{'input' if isinstance(t, T.FBType) else 'member'} "
                                   f"'{f.name}'", f.pos)
                    continue
                if fk in seen:
                    self.ctx.error("E-DECL-007", f"{what}: member '{f.name}' is initialised twice",
                                   f.pos)
                    continue
                seen.add(fk)
                self.initializer(f.value, members[fk], ex, what)
            return
        src = ex.check_value(init, t, what)
        if src is not ts.ERROR and ex.constant(init) is NOT_CONSTANT \
                and self.program.expr_types.get(id(init)) is not ts.ERROR:
            self.ctx.error("E-DECL-008", f"{what}: expected a constant expression, found one "
                           f"that reads variables or calls a function", init.pos)

    def _array_items(self, init: ast.ArrayInit, element, ex: ExprChecker, what: str) -> int:
        """Check the items of an array initializer; return how many elements they give.

        Nested brackets for a multi-dimensional array (`[[1, 2], [3, 4]]`)
        are flattened row by row, as the compiler does.
        """
        count = 0
        for item in init.items:
            n = 1
            if item.count is not None:
                n = self._const_int(item.count, ex, "repetition count")
                if n is None:
                    continue
                if n < 0:
                    self.ctx.error("E-DECL-006", f"repetition count: expected a non-negative "
                                   f"integer, found {n}", item.count.pos)
                    continue
            if isinstance(item.value, ast.ArrayInit) and not isinstance(element, T.ArrayType):
                count += n * self._array_items(item.value, element, ex, what)
                continue
            if item.value is not None:
                self.initializer(item.value, element, ex, what)
            count += n
        return count

    # --------------------------------------------------------------- POUs
    def ensure_interface(self, info: PouInfo) -> None:
        """Declare a POU's variables once (a base FB before the FBs extending it)."""
        if id(info) in self._interfaces_done or info.node is None:
            return
        self._interfaces_done.add(id(info))
        self._interface(info, info.node)

    def method_interface(self, info: PouInfo, node: ast.Method) -> None:
        """A METHOD's result and variables (its FB's come from the scope)."""
        ex = ExprChecker(self.ctx, Scope(self.ctx, info))
        if node.return_type is not None:
            info.return_type = self.resolve(node.return_type, ex)
            info.variables[key(node.name)] = Symbol(node.name, info.return_type, "RETURN", None,
                                                    init=self._default_init(node.return_type))
        for block in node.var_blocks:
            for decl in block.decls:
                self.declare(decl, block, info.variables, ex, info)

    def _interface(self, info: PouInfo, node: ast.Pou) -> None:
        scope = Scope(self.ctx, info)
        ex = self.checkers[id(info)] = ExprChecker(self.ctx, scope)
        if node.kind in ("FUNCTION_BLOCK", "INTERFACE"):
            self.objects.inherit(info, node)
        if node.kind == "FUNCTION" and node.return_type is not None:
            rt = self.resolve(node.return_type, ex)
            info.return_type = rt
            if fb_type_of(rt):
                self.ctx.error("E-DECL-009", f"FUNCTION {node.name} returns function block type "
                               f"{fb_type_of(rt).name}: expected a data type", node.return_type.pos)
            # a result of a derived type starts at that type's initial value (IEC 61131-3:2013
            # table 11), as a variable of the type does (`declare`)
            info.variables[key(node.name)] = Symbol(node.name, rt, "RETURN", None,
                                                    init=self._default_init(node.return_type))
        for block in node.var_blocks:
            if block.kind == "VAR_GLOBAL":
                for decl in block.decls:
                    self.declare(decl, block, self.program.globals, self.global_ex, None)
                continue
            for decl in block.decls:
                self.declare(decl, block, info.variables, ex, info)
        if node.methods:
            self.objects.declare_methods(info, node)
