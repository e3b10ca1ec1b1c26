"""E-DIALECT-001: the constructs a file uses that its dialect refuses.

Which dialect accepts which construct is data, in st_runtime/dialects.py
(CONSTRUCTS); this module only names the constructs of the syntax tree (the
checker's structural walk, `limits.check_files`, finds them on its way).
"""

from __future__ import annotations

from itertools import chain

from .. import ast
from ..dialects import DIALECTS, refusal


def check_dialect(ctx, files) -> None:
    """Report the first use, per file, of each construct the dialect refuses
    (one root cause, one diagnostic; the count says how many more).  The
    constructs inside each item come from the structural walk
    (`limits.check_files`, run first: `ctx.walked`)."""
    dialect = ctx.dialect
    rules = DIALECTS[dialect]
    for f in files:
        if f.path == "<builtin>":
            continue
        first: dict[str, ast.Pos] = {}
        count: dict[str, int] = {}
        for item in f.items:
            for name, pos in chain(_item_constructs(item), ctx.walked[id(item)].constructs):
                if not rules.accepts(name):
                    first[name] = min(first.get(name, pos), pos, key=lambda p: (p.line, p.col))
                    count[name] = count.get(name, 0) + 1
        for name, pos in first.items():
            more = f" ({count[name] - 1} more use(s) in this file)" if count[name] > 1 else ""
            ctx.error("E-DIALECT-001", refusal(name, dialect) + more, pos)


def _item_constructs(item):
    """(construct name, position) of each dialect-dependent construct of an item itself
    (its kind, its methods), before those of the nodes inside it."""
    if getattr(item, "namespace", ""):
        yield "NAMESPACE", item.pos
    if isinstance(item, ast.Pou):
        if item.sfc is not None:
            yield "SFC", item.sfc.pos
        if item.kind == "INTERFACE":
            yield "INTERFACE", item.pos
        if item.extends and item.kind == "FUNCTION_BLOCK":
            yield "EXTENDS", item.pos
        if item.implements:
            yield "IMPLEMENTS", item.pos
        for method in item.methods:
            kinds = set(method.modifiers)
            yield ("ACTION" if "ACTION" in kinds else "PROPERTY" if kinds & {"GET", "SET"}
                   else "METHOD"), method.pos


def _deref(node) -> str | None:       # (CODESYS's SUPER^() is refused as SUPER_BODY, at the call)
    return None if isinstance(node.base, ast.Name) and node.base.name.upper() == "SUPER" else "DEREF"


#: node class -> the dialect-dependent construct a node of it is, or None: one look-up a
#: node where the walk (limits.check_limits) would otherwise test its class eight times.
CONSTRUCTS = {
    ast.RefType: lambda node: "POINTER" if node.pointer else "REF_TO",
    ast.Deref: _deref,
    ast.Assign: lambda node: "SET_RESET" if node.mode != ":=" else None,
    ast.Call: lambda node: "TRAILING_COMMA" if node.trailing_comma else None,
    ast.StructType: lambda node: "UNION" if node.union else None,
    ast.VarDecl: lambda node: "EDGE_NAME" if node.name.upper() in ("R_EDGE", "F_EDGE") else None,
    ast.NullLiteral: lambda node: "NULL",
    ast.BitAccess: lambda node: "BIT_ACCESS" if not node.size else None,     # x.%X3 is the standard's
}

#: The node classes `construct_of` names (the walk passes the others by).
CONSTRUCT_NODES = frozenset(CONSTRUCTS)


def construct_of(node) -> str | None:
    """The dialect-dependent construct a node of a class in CONSTRUCT_NODES is, or None."""
    construct = CONSTRUCTS.get(type(node))
    return construct(node) if construct is not None else None
