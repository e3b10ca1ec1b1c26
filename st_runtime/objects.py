"""The runtime object model: how ST values live in Python.

* Elementary values are Python values (see `values.py`): bool, int (integers,
  bit strings, enums, TIME/DATE/TOD/DT as nanoseconds), float, str.
* An ARRAY is a flat Python `list`, row-major, offset 0 at the lower bound of
  every dimension; the bounds live in its `ArrayType`, and the compiled code
  checks them inline.  Assignment of an array copies it into the target list,
  so a list's identity never changes and a VAR_IN_OUT can hold the list.
* A STRUCT value, an FB instance and a PROGRAM instance are objects of
  generated classes with `__slots__` named by `mangle()` (`v_<NAME>`).  Each
  class knows its ST variables (`_st_vars`: upper-case name -> (declared name,
  Type)) so tools can walk it (JSON, trace, dotted paths).
* A VAR_IN_OUT of an elementary type holds a `Ref` to the caller's variable
  (`AttrRef` for a variable or member, `ItemRef` for an array element);
  aggregates are passed as the object itself.
"""

from __future__ import annotations

from typing import Callable

from .faults import STFault
from .native import mangle
from .store_rules import f32, wrap_int
from .types import (
    SubrangeType,
    InterfaceType,
    RefType,
    AliasType,
    ArrayType,
    ElementaryType,
    EnumType,
    FBType,
    StringType,
    StructType,
    Type,
    fit_string,
    resolve_alias,
)

Maker = Callable[[], object]


# --------------------------------------------------------------- references


class AttrRef:
    """A reference to an attribute of an object (a variable or member)."""

    __slots__ = ("obj", "attr")

    def __init__(self, obj, attr: str):
        self.obj = obj
        self.attr = attr

    def __eq__(self, other) -> bool:      # REF(x) = REF(x): the same variable
        return type(other) is AttrRef and other.obj is self.obj and other.attr == self.attr

    def __hash__(self) -> int:
        return hash((id(self.obj), self.attr))

    def get(self):
        return getattr(self.obj, self.attr)

    def set(self, value) -> None:
        setattr(self.obj, self.attr, value)


class ItemRef:
    """A reference to an element of an array (a list and a flat offset)."""

    __slots__ = ("seq", "index")

    def __init__(self, seq: list, index: int):
        self.seq = seq
        self.index = index

    def __eq__(self, other) -> bool:
        return type(other) is ItemRef and other.seq is self.seq and other.index == self.index

    def __hash__(self) -> int:
        return hash((id(self.seq), self.index))

    def get(self):
        return self.seq[self.index]

    def set(self, value) -> None:
        self.seq[self.index] = value


class NullRef:
    """What an unconnected VAR_IN_OUT of an ST FB holds: any use is a fault."""

    __slots__ = ("name",)

    def __init__(self, name: str):
        self.name = name

    def _fault(self, *args):
        raise STFault("F-NULL-REF", f"VAR_IN_OUT '{self.name}' was not passed a variable")

    get = set = __getitem__ = __setitem__ = _assign = execute = _fault

    def __getattr__(self, attr):
        if attr.startswith("v_"):
            self._fault()
        raise AttributeError(attr)


# ------------------------------------------------------------- aggregates


class STObject:
    """Base of struct values, ST FB instances and PROGRAM instances."""

    __slots__ = ()
    _st_name: str = ""
    _st_vars: dict = {}            # upper-case name -> (declared name, Type)

    def _assign(self, other: "STObject") -> None:
        """`self := other`: copy every member, deep, keeping identities."""
        for attr in self.__slots__:
            mine = getattr(self, attr)
            theirs = getattr(other, attr)
            if isinstance(mine, STObject):
                mine._assign(theirs)
            elif isinstance(mine, list):
                assign_list(mine, theirs)
            elif isinstance(mine, bytearray):      # a UNION's shared bytes: copied
                mine[:] = theirs
            else:
                setattr(self, attr, theirs)

    def __repr__(self) -> str:
        inner = ", ".join(f"{name}={getattr(self, mangle(name))!r}" for name, _ in self._st_vars.values())
        return f"{self._st_name}({inner})"


def assign_list(target: list, source: list) -> None:
    """Array assignment: copy `source` into `target` element by element."""
    if target and isinstance(target[0], STObject):
        for mine, theirs in zip(target, source):
            mine._assign(theirs)
    elif target and isinstance(target[0], list):  # pragma: no cover - flat arrays only
        for mine, theirs in zip(target, source):
            assign_list(mine, theirs)
    else:
        target[:] = source


def st_vars_of(obj) -> dict:
    """The ST variables of a struct value, FB instance or PROGRAM instance."""
    layout = getattr(type(obj), "_st_vars", None)
    if layout is None:
        raise TypeError(f"{type(obj).__name__} is not an ST object")
    return layout


# ------------------------------------------------------- initial values


def default_value(t: Type, classes: dict[str, type]) -> Maker:
    """A maker of the default initial value of type `t` (no initializer)."""
    t = resolve_alias(t)
    if isinstance(t, SubrangeType):
        low = t.lo
        return lambda: low
    if isinstance(t, ElementaryType):
        value = _ELEMENTARY_DEFAULTS[t.kind]
        return lambda: value
    if isinstance(t, StringType):
        return lambda: ""
    if isinstance(t, EnumType):
        first = next(iter(t.values.values()))[1] if t.values else 0
        return lambda: first
    if isinstance(t, ArrayType):
        element = default_value(t.element, classes)
        size = t.size
        if is_aggregate(t.element):
            return lambda: [element() for _ in range(size)]
        proto = [element()] * size
        return proto.copy
    if isinstance(t, (StructType, FBType)):
        return classes[t.name.upper()]
    if isinstance(t, (InterfaceType, RefType)):
        return lambda: None          # refers to nothing (NULL)
    raise TypeError(f"no default value for {t}")


_ELEMENTARY_DEFAULTS = {
    "bool": False, "int": 0, "bits": 0, "real": 0.0,
    "time": 0, "date": 0, "tod": 0, "dt": 0,
}


def is_aggregate(t: Type) -> bool:
    """Arrays, structs and FB instances: stored as mutable objects."""
    while isinstance(t, AliasType):     # (resolve_alias, inline: asked of every variable and store)
        t = t.target
    return isinstance(t, (ArrayType, StructType, FBType))


def store_value(t: Type, value, dialect: str = "iec"):
    """Convert a Python value to what a variable of type `t` stores.

    Used for initial values and values coming from outside (API, JSON): wraps
    integers, rounds REAL to float32, truncates strings.
    """
    t = resolve_alias(t)
    if isinstance(t, ElementaryType):
        if t.kind == "bool":
            return bool(value)
        if t.kind == "real":
            return f32(float(value)) if t.bits == 32 else float(value)
        if isinstance(value, bool) or not isinstance(value, int):
            if isinstance(value, float) and value.is_integer():
                value = int(value)
            else:
                raise TypeError(f"{t.name} needs an integer, got {value!r}")
        bits = 64 if t.kind in ("time", "date", "tod", "dt") else t.bits
        return wrap_int(value, bits, t.signed or t.kind in ("time", "date", "tod", "dt"))
    if isinstance(t, StringType):
        return fit_string(str(value), t.length, dialect)
    if isinstance(t, EnumType):
        return int(value)
    raise TypeError(f"{t} is not an elementary type")


# ---------------------------------------------------------- native layouts


def native_initializers(pou, make_initial) -> list[tuple[str, Maker]]:
    """(attribute, maker) pairs of a native FB's variables, declaration order.

    `make_initial(symbol)` gives the maker of a symbol's initial value (the
    compiler's, so native and ST FBs follow the same rules).
    """
    pairs = []
    for symbol in pou.variables.values():
        if symbol.kind == "VAR_IN_OUT":
            pairs.append((mangle(symbol.name), _none))
        else:
            pairs.append((mangle(symbol.name), make_initial(symbol)))
    return pairs


def _none():
    return None
