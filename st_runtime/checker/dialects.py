"""E-DIALECT-001: the constructs a file uses that its dialect refuses.

Which dialect accepts which construct is data, in st_runtime/dialects.py
(CONSTRUCTS); this module only finds the constructs in the syntax tree.
"""

from __future__ import annotations

from .. import ast
from ..dialects import DIALECTS, refusal


def check_dialect(ctx, files) -> None:
    """Report the first use, per file, of each construct the dialect refuses
    (one root cause, one diagnostic; the count says how many more)."""
    dialect = ctx.dialect
    rules = DIALECTS[dialect]
    for f in files:
        if f.path == "<builtin>":
            continue
        first: dict[str, ast.Pos] = {}
        count: dict[str, int] = {}
        for item in f.items:
            for name, pos in _constructs(item):
                if not rules.accepts(name):
                    first[name] = min(first.get(name, pos), pos, key=lambda p: (p.line, p.col))
                    count[name] = count.get(name, 0) + 1
        for name, pos in first.items():
            more = f" ({count[name] - 1} more use(s) in this file)" if count[name] > 1 else ""
            ctx.error("E-DIALECT-001", refusal(name, dialect) + more, pos)


def _constructs(item):
    """(construct name, position) of each dialect-dependent construct in an item."""
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
    stack = [item]
    push, Node = stack.append, ast.Node
    while stack:
        node = stack.pop()
        if isinstance(node, tuple):
            stack.extend(node)
            continue
        if not isinstance(node, Node):
            continue
        kind = type(node)
        if kind in _CONSTRUCT_NODES:
            if kind is ast.RefType:
                yield ("POINTER" if node.pointer else "REF_TO"), node.pos
            elif kind is ast.Deref:
                yield "DEREF", node.pos
            elif kind is ast.Assign and node.mode != ":=":
                yield "SET_RESET", node.pos
            elif kind is ast.Call and node.trailing_comma:
                yield "TRAILING_COMMA", node.pos
            elif kind is ast.StructType and node.union:
                yield "UNION", node.pos
            elif kind is ast.VarDecl and node.name.upper() in ("R_EDGE", "F_EDGE"):
                yield "EDGE_NAME", node.pos
            elif kind is ast.NullLiteral:
                yield "NULL", node.pos
            elif kind is ast.BitAccess and not node.size:      # x.%X3 is the standard's
                yield "BIT_ACCESS", node.pos
        for name in ast._FIELDS.get(kind) or ast.fields_of(kind):
            value = getattr(node, name)
            if isinstance(value, (Node, tuple)):
                push(value)


#: The node classes `_constructs` looks at (the others it only walks through).
_CONSTRUCT_NODES = frozenset({ast.RefType, ast.Deref, ast.Assign, ast.Call, ast.StructType, ast.VarDecl,
                              ast.NullLiteral, ast.BitAccess})
