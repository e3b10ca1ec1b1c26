"""The orders in which the load's walks list a syntax tree, spelled recursively
(the walks themselves are iterative): the references their tests compare with."""

from __future__ import annotations

from st_runtime import ast


def walk_order(node, tuples_from_last: bool = False):
    """A node, then the nodes of its fields from the last to the first; the items of
    a tuple in order (`compiler.scope.walk`), or from the last (`checker.limits`,
    a stack that pushes them in order)."""
    if isinstance(node, tuple):
        for item in (reversed(node) if tuples_from_last else node):
            yield from walk_order(item, tuples_from_last)
    elif isinstance(node, ast.Node):
        yield node
        for name in reversed(ast.fields_of(type(node))):
            yield from walk_order(getattr(node, name), tuples_from_last)
