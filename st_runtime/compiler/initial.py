"""Initial values: constant initializers evaluated once, at compile time.

An initial value is either a constant (an immutable Python value the
generated `__init__` writes as a literal) or a maker (a zero-argument
callable that builds a fresh array, struct or FB instance).  Initializers
are constant expressions (the checker enforces it); the checker's folded
values are used where it recorded them.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

from .. import ast
from ..objects import default_value, is_aggregate, store_value
from ..types import ArrayType, ElementaryType, EnumType, FBType, StructType, Type, resolve_alias
from ..checker.constfold import NOT_CONSTANT, DivisionByZero, apply_binary
from .pysrc import pyident


class CompileError(Exception):
    """A construct the compiler cannot translate; carries the position."""

    def __init__(self, message: str, pos: ast.Pos):
        super().__init__(message)
        self.message = message
        self.pos = pos


@dataclass(frozen=True)
class Initial:
    """`const` is set for an elementary value, `maker` for an aggregate."""

    const: object = None
    maker: Callable | None = None

    @property
    def is_const(self) -> bool:
        return self.maker is None


class InitialValues:
    """Evaluates initializers of one checked program."""

    def __init__(self, program, classes: dict[str, type]):
        self.program = program
        self.classes = classes
        #: STRUCT name -> {MEMBER: init}; TYPE name -> init
        self.member_inits, self.type_inits = _initializers(program)

    def member_init(self, struct_key: str, member_key: str):
        """A STRUCT member's initializer: its own, else its TYPE's (IEC 61131-3:2013 table 11:
        a derived type's initial value is the default of every variable of that type)."""
        init = self.member_inits.get(struct_key, {}).get(member_key)
        if isinstance(init, ast.NamedType):
            return self.type_inits.get(init.name.upper())
        return init

    # ---------------------------------------------------------- constants

    def const(self, expr):
        """The value of a constant expression (Python bool/int/float/str)."""
        folded = self.program.constants.get(id(expr))
        if folded is not None:
            return folded
        if isinstance(expr, (ast.IntLiteral, ast.RealLiteral, ast.BoolLiteral, ast.StringLiteral)):
            return expr.value
        if isinstance(expr, ast.TimeLiteral):
            return expr.nanoseconds
        if isinstance(expr, ast.DateTimeLiteral):
            return expr.nanoseconds
        if isinstance(expr, ast.EnumLiteral):
            return self.enum_value(expr.type_name, expr.value_name, expr.pos)
        if isinstance(expr, ast.Name):
            ref = self.program.name_refs.get(id(expr))
            if isinstance(ref, int) and not isinstance(ref, bool):
                return ref
            if ref is not None and getattr(ref, "init", None) is not None and ref.constant:
                return self.const(ref.init)
            raise CompileError(f"'{expr.name}' is not a constant", expr.pos)
        if isinstance(expr, ast.Unary):
            v = self.const(expr.operand)
            if expr.op == "-":
                return -v
            if expr.op == "+":
                return v
            return not v if isinstance(v, bool) else ~v
        if isinstance(expr, ast.Binary):
            return _fold_binary(expr.op, self.const(expr.left), self.const(expr.right), expr.pos)
        raise CompileError("initial value is not a constant expression", expr.pos)

    def enum_value(self, type_name: str, value_name: str, pos) -> int:
        t = resolve_alias(self.program.types.get(type_name.upper()))
        if isinstance(t, EnumType) and value_name.upper() in t.values:
            return t.values[value_name.upper()][1]
        raise CompileError(f"unknown enumeration value {type_name}#{value_name}", pos)

    # ------------------------------------------------------------ values

    def of_symbol(self, symbol) -> Initial:
        t = symbol.type
        if symbol.init is None and type(t) is ElementaryType:
            # (most variables: what `of` gives them, at once; no TYPE initializer is an elementary
            # type's, whose name cannot be declared again, E-DECL-003)
            return _elementary_default(t)
        t = resolve_alias(t)
        if not (symbol.init is not None and isinstance(t, ArrayType) and not is_aggregate(resolve_alias(t.element))):
            return self.of(symbol.type, symbol.init, symbol.decl.pos if symbol.decl else ast.NOWHERE)
        # An initialised array of elementary values depends on nothing but its symbol: flattened
        # once, though the class, the range analysis and the fold pass all ask (the Leibniz table).
        cache = self.__dict__.setdefault("_arrays", {})
        found = cache.get(id(symbol))
        if found is None or found[0] is not symbol:
            found = cache[id(symbol)] = (symbol, self.of(symbol.type, symbol.init,
                                                         symbol.decl.pos if symbol.decl else ast.NOWHERE))
        return found[1]

    def of(self, t: Type, init, pos) -> Initial:
        """The initial value of a variable of type `t` with initializer `init`."""
        raw = t
        t = resolve_alias(t)
        if init is None:
            init = self.type_inits.get((getattr(raw, "name", None) or "").upper())   # keys are upper case
        if not is_aggregate(t):
            if init is None:
                if type(t) is ElementaryType:       # (most variables: the kind's default, one Initial)
                    return _elementary_default(t)
                return Initial(const=default_value(t, self.classes)())
            return Initial(const=store_value(t, self.const(init), self.program.dialect))
        if isinstance(t, ArrayType):
            return Initial(maker=self._array_maker(t, init, pos))
        return Initial(maker=self._object_maker(t, init, pos))

    def _array_maker(self, t: ArrayType, init, pos) -> Callable:
        if init is None:
            if t.element_init is None and \
                    self.type_inits.get((getattr(t.element, "name", None) or "").upper()) is None:
                return default_value(t, self.classes)
            items = []      # elements of a TYPE declared with an initial value take it (below)
        elif not isinstance(init, ast.ArrayInit):
            raise CompileError("an array needs an array initializer [...]", getattr(init, "pos", pos))
        else:
            items = self._flatten(init, t.element)
        if len(items) > t.size:
            raise CompileError(f"{len(items)} initial values for {t.size} elements", init.pos)
        items += [self.of(t.element, t.element_init, pos)] * (t.size - len(items))
        if all(item.is_const for item in items):
            proto = [item.const for item in items]
            return proto.copy
        makers = [item.maker if not item.is_const else _constant(item.const) for item in items]
        return lambda: [make() for make in makers]

    def _flatten(self, init: ast.ArrayInit, element: Type) -> list[Initial]:
        out: list[Initial] = []
        for item in init.items:
            count = 1 if item.count is None else self.const(item.count)
            if isinstance(item.value, ast.ArrayInit) and not isinstance(resolve_alias(element), ArrayType):
                one = self._flatten(item.value, element)   # nested brackets of a multi-dim array
                out.extend(one * count)
            else:
                out.extend([self.of(element, item.value, item.pos)] * count)
        return out

    def _object_maker(self, t: StructType | FBType, init, pos) -> Callable:
        cls = self.classes[t.name.upper()]
        if init is None:
            return cls
        if not isinstance(init, ast.StructInit):
            raise CompileError(f"{t.name} needs a structure initializer (...)", getattr(init, "pos", pos))
        members = _members(t)
        overrides = []
        for field in init.fields:
            member_type = members.get(field.name.upper())
            if member_type is None:
                raise CompileError(f"{t.name} has no member '{field.name}'", field.pos)
            value = self.of(member_type, field.value, field.pos)
            overrides.append((pyident(field.name), value))

        def make():
            obj = cls()
            for attr, value in overrides:
                setattr(obj, attr, value.const if value.is_const else value.maker())
            return obj

        return make


#: elementary kind -> the Initial of its default (frozen, so one serves every variable)
_ELEMENTARY_DEFAULTS: dict[str, Initial] = {}


def _elementary_default(t: ElementaryType) -> Initial:
    """`Initial(const=default_value(t)())` of an elementary type (not a subrange): its kind's
    default, which depends on nothing else, made once a kind."""
    found = _ELEMENTARY_DEFAULTS.get(t.kind)
    if found is None:
        found = _ELEMENTARY_DEFAULTS[t.kind] = Initial(const=default_value(t, {})())
    return found


def _constant(value) -> Callable:
    return lambda: value


def _members(t) -> dict[str, Type]:
    if isinstance(t, StructType):
        return {key: ft for key, (_, ft) in t.fields.items()}
    return {key: sym.type for key, sym in t.variables.items()}


def _initializers(program) -> tuple[dict, dict]:
    """(STRUCT name -> {MEMBER: init}, TYPE name -> init) of the program's files, in one
    reading of their items, the shared prelude's file read once a process."""
    members: dict[str, dict] = {}
    types: dict[str, object] = {}
    files = program.files
    base = getattr(program, "prelude", None)
    if base is not None and files and files[0] is base.file:
        prelude = base.memo("initializers", lambda: _initializers_of([base.file], {}, {}))
        members.update(prelude[0])
        types.update(prelude[1])
        files = files[1:]
    return _initializers_of(files, members, types)


def _initializers_of(files, members: dict, types: dict) -> tuple[dict, dict]:
    """`_initializers` of `files`, added to `members` and `types`."""
    for sf in files:
        for item in sf.items:
            if not isinstance(item, ast.TypeDecl):
                continue
            if isinstance(item.spec, ast.StructType):
                # a member without its own initial value whose type is a TYPE name keeps
                # that name (resolved by InitialValues.member_init: the type may hold one)
                members[item.name.upper()] = {m.name.upper(): m.init if m.init is not None or not
                                              isinstance(m.type, ast.NamedType) else m.type
                                              for m in item.spec.members}
            if item.init is not None:
                types[item.name.upper()] = item.init
    return members, types


def _fold_binary(op: str, a, b, pos):
    """The checker's folder (one set of IEC rules for constants), or a CompileError."""
    try:
        value = apply_binary(op, a, b)
    except DivisionByZero:
        value = NOT_CONSTANT
    if value is NOT_CONSTANT:
        raise CompileError(f"cannot evaluate constant expression with '{op}'", pos)
    return value
