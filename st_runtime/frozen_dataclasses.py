"""`@dataclass(frozen=True, slots=True)` for many classes, made cheaply.

The AST has some sixty node classes.  `dataclass` writes and compiles six
functions for each (`__init__`, `__repr__`, `__eq__`, `__hash__`, the frozen
`__setattr__` and `__delattr__`): about 400 calls of `exec`, a fifth of
`stgen check`'s start-up.  Here `dataclass` only makes the fields, the
slots and `__match_args__` (`init=False, repr=False, eq=False`, not frozen),
and `make_methods` gives each class:

* `__init__`: the dataclass's parameters (the fields in order, their
  defaults, `kw_only` fields after a `*`) and annotations, each field stored
  through its slot's own descriptor (a third of the cost of the
  `object.__setattr__` a frozen dataclass's `__init__` calls); the
  `__init__` of every class given are compiled as one source;
* `__repr__`, `__eq__`, `__hash__`: what the dataclass's own code does, on
  the tuple of the fields with `repr=True` (repr) or `compare=True` (eq,
  hash), read by an `attrgetter` (closures: nothing to compile);
* `__getstate__`, `__setstate__` (pickling, as a frozen slotted dataclass
  has): the field values as a list, stored back through the descriptors;
* `__setattr__`, `__delattr__`: `FrozenInstanceError` for any name
  (`__dataclass_params__.frozen` is False: nothing reads it);
* a class without a docstring gets dataclass's, its name and signature.

No class given may have a `__post_init__`, a `default_factory`, an
`init=False` field or a method of those names of its own (`make_methods`
refuses it).  `tests/test_load_fast_paths.py` compares every AST class
with what `dataclass(frozen=True, slots=True)` makes of the same fields.
"""

from __future__ import annotations

import inspect
from dataclasses import MISSING, FrozenInstanceError, dataclass
from operator import attrgetter

#: The methods `make_methods` writes (a class of its own must not define them).
WRITTEN = ("__init__", "__repr__", "__eq__", "__hash__", "__getstate__", "__setstate__",
           "__setattr__", "__delattr__")


def frozen_dataclass(cls: type) -> type:
    """The fields and slots of `@dataclass(frozen=True, slots=True)`; the methods
    come from `make_methods`, which must be called before an instance is made."""
    undocumented = not cls.__dict__.get("__doc__")
    cls = dataclass(slots=True, init=False, repr=False, eq=False)(cls)
    if undocumented:     # (dataclass's docstring spells the signature of an __init__ not yet made)
        _UNDOCUMENTED.add(cls)
    return cls


#: Classes without a docstring: make_methods gives them dataclass's, the class's signature.
_UNDOCUMENTED: set[type] = set()


def _frozen_setattr(self, name, value):
    raise FrozenInstanceError(f"cannot assign to field {name!r}")


def _frozen_delattr(self, name):
    raise FrozenInstanceError(f"cannot delete field {name!r}")


def make_methods(classes: list[type]) -> None:
    """Give every class of `classes` its methods (see the module's docstring)."""
    scope: dict = {}
    lines: list[str] = []
    for number, cls in enumerate(classes):
        _write_init(cls, f"_{number}_", scope, lines)
    exec("\n".join(lines), scope)
    for number, cls in enumerate(classes):
        fields = list(cls.__dataclass_fields__.values())
        init = scope[f"_{number}___init__"]
        init.__name__, init.__qualname__ = "__init__", f"{cls.__qualname__}.__init__"
        init.__annotations__ = {**{f.name: f.type for f in fields}, "return": None}
        methods = _methods([f.name for f in fields if f.repr], [f.name for f in fields if f.compare],
                           [f.name for f in fields], [getattr(cls, f.name).__set__ for f in fields])
        for function in (init, *methods):
            if function.__name__ != "__init__":
                function.__qualname__ = f"{cls.__qualname__}.{function.__name__}"
            setattr(cls, function.__name__, function)
        cls.__setattr__, cls.__delattr__ = _frozen_setattr, _frozen_delattr
        if cls in _UNDOCUMENTED:
            cls.__doc__ = cls.__name__ + str(inspect.signature(cls)).replace(" -> None", "")


def _write_init(cls: type, prefix: str, scope: dict, lines: list[str]) -> None:
    if any(name in vars(cls) for name in ("__post_init__", *WRITTEN)):
        raise TypeError(f"{cls.__name__} defines a method make_methods writes")
    positional, keyword, stores = [], [], []
    for f in cls.__dataclass_fields__.values():
        if f.default_factory is not MISSING or not f.init:
            raise TypeError(f"{cls.__name__}.{f.name}: a default_factory or init=False field")
        scope[f"{prefix}set_{f.name}"] = getattr(cls, f.name).__set__
        if f.default is not MISSING:
            scope[f"{prefix}default_{f.name}"] = f.default
        spelled = f.name if f.default is MISSING else f"{f.name}={prefix}default_{f.name}"
        (keyword if f.kw_only else positional).append(spelled)
        stores.append(f"    {prefix}set_{f.name}(self, {f.name})")
    parameters = ", ".join(["self", *positional] + (["*", *keyword] if keyword else []))
    lines += [f"def {prefix}__init__({parameters}):", *(stores or ["    pass"])]


def _tuple_of(names: list[str]):
    """A function giving the tuple of these attributes of its argument."""
    if len(names) > 1:
        return attrgetter(*names)
    if names:
        one = attrgetter(names[0])
        return lambda self: (one(self),)
    return lambda self: ()


def _methods(shown: list[str], compared: list[str], every: list[str], setters: list) -> tuple:
    """__repr__, __eq__, __hash__, __getstate__, __setstate__ of a class with these fields."""
    shown_values, key, values = _tuple_of(shown), _tuple_of(compared), _tuple_of(every)
    labels = [f"{name}=" for name in shown]

    def __repr__(self):
        return self.__class__.__qualname__ + "(" + ", ".join(
            label + repr(value) for label, value in zip(labels, shown_values(self))) + ")"

    def __eq__(self, other):
        if other.__class__ is self.__class__:
            return key(self) == key(other)
        return NotImplemented

    def __hash__(self):
        return hash(key(self))

    def __getstate__(self):
        return list(values(self))

    def __setstate__(self, state):
        for store, value in zip(setters, state):
            store(self, value)

    return __repr__, __eq__, __hash__, __getstate__, __setstate__
