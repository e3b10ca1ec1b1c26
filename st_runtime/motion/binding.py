"""Which axis an axis FB's AXIS_REF stands for, kept without reading `Cfg` on every call.

An axis FB resolves its `Axis` in-out through `Cfg.AxEnable` and `Cfg.AxNo`
(`fbs.resolve_axis`) and keeps the AXIS_REF value and the axis it found.  The binding
holds while the FB is given the same AXIS_REF value and nothing else is stored in that
value's `Cfg` (nor another `Cfg` put in its place): so the test of a call is one identity
test, and a store of another value into a watched `Cfg` ends every binding (the next call
of each FB resolves again, which finds what it found before unless the store changed it).
Such stores are rare (binding the axes, a program that points a variable at another
axis), so ending every binding costs nothing a scan sees; a store of the value a member
already holds (a program that copies an AXIS_REF every scan) ends none.

A watched value is the same object with its class swapped for a subclass whose
`__setattr__` ends the bindings: its name and `__slots__` are its class's, so everything
that reads a struct member by member sees it as before.  Every store (the compiled ST's,
`STObject._assign`'s, Python's) goes through `__setattr__`.
"""

from __future__ import annotations

import weakref

from ..objects import STObject

# FBs that hold a binding (`end_binding` on each when a watched value is written).
_HOLDERS: "weakref.WeakSet" = weakref.WeakSet()


def _store_and_unbind(self, name: str, value) -> None:
    unchanged = getattr(self, name, _HOLDERS) is value     # (a program copying an AXIS_REF each scan)
    type(self).__mro__[1].__setattr__(self, name, value)        # the struct class's own store
    if unchanged:
        return
    holders = list(_HOLDERS)
    _HOLDERS.clear()
    for holder in holders:
        holder.end_binding()


def _watched_class(cls: type) -> type:
    """The watched subclass of struct class `cls`, made once and kept on `cls` (so it goes
    with the compiled program that made `cls`)."""
    watched = cls.__dict__.get("_st_watched")
    if watched is None:
        watched = type(cls.__name__, (cls,), {"__slots__": (), "__setattr__": _store_and_unbind,
                                              "__qualname__": cls.__qualname__, "__module__": cls.__module__})
        watched.__slots__ = cls.__slots__    # members as the struct's own (read member by member)
        cls._st_watched = watched
    return watched


def _watch(value) -> bool:
    if type(value).__setattr__ is _store_and_unbind:
        return True
    if not isinstance(value, STObject):
        return False
    value.__class__ = _watched_class(type(value))
    return True


def hold(fb, ref) -> bool:
    """Watch `ref` and its `Cfg` for `fb`'s binding to it; False if they cannot be watched
    (not ST structs: then the FB must resolve on every call)."""
    if not (_watch(ref) and _watch(ref.v_CFG)):
        return False
    _HOLDERS.add(fb)
    return True
