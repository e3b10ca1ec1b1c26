"""The 3rd edition's object orientation in the checker (IEC 61131-3 6.6.5-6.6.6).

A FUNCTION_BLOCK may EXTEND another (it inherits the variables and methods;
a method of the same name overrides, unless the base's is FINAL), IMPLEMENT
interfaces (it must then have every method they name, unless it is
ABSTRACT), and hold METHODs.  A METHOD is checked like a FUNCTION whose
scope also holds its FB's variables and THIS (the instance); SUPER.M()
calls the base's M.  Access: PRIVATE methods are called only inside their
FB, PROTECTED ones inside it and the FBs that extend it; PUBLIC (the
default) and INTERNAL (no namespaces yet: same as PUBLIC) anywhere.
"""

from __future__ import annotations

from .. import ast
from .. import types as T
from ..ast import key
from ..symbols import PouInfo
from .context import a_or_an

ACCESS_DEFAULT = "PUBLIC"


def method_info(owner: PouInfo, node: ast.Method) -> PouInfo:
    return PouInfo(node.name, "METHOD", node, file=node.pos.file, owner=owner,
                   access=node.access or ACCESS_DEFAULT, modifiers=node.modifiers)


def find_method(info: PouInfo | None, name: str) -> PouInfo | None:
    while info is not None:
        found = info.methods.get(key(name) if " " not in name else name)
        if found is not None:
            return found
        found = next((m for i in info.interfaces for m in [find_method(i, name)] if m), None)
        if found is not None and info.kind == "INTERFACE":
            return found
        info = info.parent
    return None


def accessor_key(method: ast.Method) -> str:
    """The key of a method in `PouInfo.methods`; a PROPERTY's getter and setter
    are "GET NAME" and "SET NAME" (a space: no identifier collides)."""
    for word in ("GET", "SET"):
        if word in method.modifiers:
            return f"{word} {key(method.name)}"
    return key(method.name)


def find_property(info: PouInfo | None, name: str) -> tuple:
    """(getter, setter) of a PROPERTY (either may be None), or (None, None)."""
    return find_method(info, f"GET {key(name)}"), find_method(info, f"SET {key(name)}")


def may_call(method: PouInfo, caller_fb: PouInfo | None) -> bool:
    if method.access == "PRIVATE":
        return caller_fb is method.owner
    if method.access == "PROTECTED":
        return caller_fb is not None and caller_fb.descends_from(method.owner)
    return True


class ObjectModel:
    """Builds EXTENDS / IMPLEMENTS / METHOD for the Declarations pass."""

    def __init__(self, decls) -> None:
        self.decls = decls
        self.ctx = decls.ctx
        self.program = decls.program

    def _pou(self, name: str, kind: str, pos, what: str) -> PouInfo | None:
        info = self.program.pous.get(key(name))
        if info is None or info.kind != kind:
            found = a_or_an(info.kind) if info is not None else "nothing of that name"
            self.ctx.error("E-DECL-016", f"{what} '{name}': expected {a_or_an(kind)}, found {found}", pos)
            return None
        return info

    def inherit(self, info: PouInfo, node: ast.Pou) -> None:
        """Before the FB's own variables: the base's variables and methods."""
        if node.kind == "INTERFACE":
            info.interfaces = tuple(i for i in (self._pou(n, "INTERFACE", node.pos, "EXTENDS")
                                                for n in node.extends) if i is not None)
            return
        if len(node.extends) > 1:
            self.ctx.error("E-DECL-016", f"FUNCTION_BLOCK {node.name} EXTENDS {len(node.extends)} "
                           f"function blocks: expected one (interfaces are IMPLEMENTed)", node.pos)
        if node.extends:
            parent = self._pou(node.extends[0], "FUNCTION_BLOCK", node.pos, "EXTENDS")
            if parent is not None:
                # The base first: a cycle through it (A EXTENDS B, B EXTENDS A) shows only then.
                self.decls.ensure_interface(parent)
            if parent is not None and parent.descends_from(info):
                self.ctx.error("E-DECL-016", f"FUNCTION_BLOCK {node.name} extends itself "
                               f"(through {parent.name})", node.pos)
                parent = None
            if parent is not None and "FINAL" in parent.modifiers:
                self.ctx.error("E-DECL-016", f"{node.name} EXTENDS {parent.name}, which is FINAL",
                               node.pos)
            if parent is not None:
                info.parent = parent
                info.variables.update(parent.variables)
                info.methods.update(parent.methods)
        info.interfaces = tuple(i for i in (self._pou(n, "INTERFACE", node.pos, "IMPLEMENTS")
                                            for n in node.implements) if i is not None)
        info.modifiers = node.modifiers

    def declare_methods(self, info: PouInfo, node: ast.Pou) -> None:
        for m in node.methods:
            k = accessor_key(m)
            # A PROPERTY's accessors are keyed "GET X"/"SET X", but a caller writes
            # `fb.X`, which would then name both the property and the variable: refused
            # as a METHOD named like a variable is (no CODESYS page was found saying
            # how CODESYS itself reports it).
            own = info.variables.get(key(m.name))
            if own is not None and own.kind != "RETURN":
                what = "property" if k != key(m.name) else "method"
                self.ctx.error("E-DECL-002", f"{what} {m.name} has the name of a variable of "
                               f"{node.name}", m.pos)
                continue
            inherited = info.methods.get(k)
            if inherited is not None and inherited.owner is info:
                self.ctx.error("E-DECL-002", f"method {m.name} is declared twice in {node.name}", m.pos)
                continue
            if inherited is not None and "FINAL" in inherited.modifiers:
                self.ctx.error("E-DECL-016", f"method {m.name} overrides the FINAL method of "
                               f"{inherited.owner.name}", m.pos)
            if "ABSTRACT" in m.modifiers and "ABSTRACT" not in node.modifiers and node.kind != "INTERFACE":
                self.ctx.error("E-DECL-016", f"ABSTRACT method {m.name} in {node.name}, which is "
                               f"not ABSTRACT", m.pos)
            mi = method_info(info, m)
            self.decls.method_interface(mi, m)
            info.methods[k] = mi

    def check_contracts(self, info: PouInfo, node: ast.Pou) -> None:
        """A concrete FB has every method of its interfaces and no ABSTRACT one left."""
        if node.kind != "FUNCTION_BLOCK" or "ABSTRACT" in node.modifiers:
            return
        for method in info.methods.values():
            # (its own ABSTRACT method is refused where it is declared: one diagnostic)
            if "ABSTRACT" in method.modifiers and method.owner is not info:
                self.ctx.error("E-DECL-016", f"{node.name} must implement the ABSTRACT method "
                               f"{method.name} of {method.owner.name} (or be ABSTRACT itself)", node.pos)
        seen = set()
        fb = info
        while fb is not None:
            for interface in fb.interfaces:
                for name, prototype in _interface_methods(interface).items():
                    if name in seen:
                        continue
                    seen.add(name)
                    if find_method(info, name) is None or find_method(info, name).owner.kind == "INTERFACE":
                        self.ctx.error("E-DECL-016", f"{node.name} IMPLEMENTS {interface.name} but has "
                                       f"no method {prototype.name}", node.pos)
            fb = fb.parent


def _interface_methods(interface: PouInfo) -> dict:
    methods = {}
    for base in interface.interfaces:
        methods.update(_interface_methods(base))
    methods.update(interface.methods)
    return methods


def interface_methods(interface: PouInfo) -> dict:
    return _interface_methods(interface)


def assignable_reference(src, dst) -> bool:
    """An FB instance or interface value stored in an interface variable."""
    if not isinstance(dst, T.InterfaceType):
        return False
    if isinstance(src, T.FBType):
        info = getattr(src, "info", None)
        return info is not None and info.implements(dst.info)
    if isinstance(src, T.InterfaceType):
        return src.info is dst.info or src.info.extends_interface(dst.info)
    return False
