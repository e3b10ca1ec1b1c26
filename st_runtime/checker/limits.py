"""Structural limits: what the checker accepts, the compiler compiles and the
controller runs (issue 15: never an internal RecursionError after `check`).

ST compiles to Python source, and CPython bounds that source: at most 200
nested parentheses in an expression, 100 indentation levels, 20 statically
nested blocks (loops and `try`), and its own compiler recursion for long
`elif` chains.  The limits below keep every accepted POU inside those bounds
with a margin (measured: an expression of 196 nested operators, 96 nested IFs
and 17 nested loops still compile; an IF with 200 branches does, CASE with
4,000 clauses does not), and each one that is exceeded is one diagnostic
naming the construct, at its position.  The walk is iterative, so a POU
nested 100,000 levels deep costs time linear in its size, never a
RecursionError.  It is the checker's one walk of every node of the user's
files: on the way it notes what two later passes look for (`Walked`), the
dialect's constructs and whether an item holds a node of the NJ build rules,
so that neither walks the tree again.

| code | limit |
|---|---|
| E-LIMIT-002 | expressions (operators, calls, indexes) and types (ARRAY OF ...) nested at most MAX_EXPRESSION_DEPTH levels |
| E-LIMIT-003 | statements nested at most MAX_BLOCK_DEPTH levels (IF, CASE, FOR, WHILE, REPEAT) |
| E-LIMIT-004 | loops nested at most MAX_LOOP_DEPTH levels |
| E-LIMIT-005 | at most MAX_ELSIF ELSIF branches in one IF |
| E-LIMIT-006 | at most MAX_CASE_CLAUSES clauses in one CASE |
| E-LIMIT-007 | at most MAX_STATEMENTS statements in one POU |
| E-LIMIT-012 | at most MAX_FILE_LINES lines and MAX_FILE_BYTES characters in one source file (the loader, before parsing) |
"""

from __future__ import annotations

from operator import attrgetter

from .. import ast
from ..diagnostics import register
from ..per_class import PerClass
from .context import BUILTIN_FILE
from .dialects import CONSTRUCTS

MAX_EXPRESSION_DEPTH = 64
MAX_BLOCK_DEPTH = 40
MAX_LOOP_DEPTH = 12
MAX_ELSIF = 150
MAX_CASE_CLAUSES = 1_500
MAX_STATEMENTS = 100_000
#: A source file is read whole and parsed at some 10,000 to 30,000 lines a second: beyond
#: these, the parse alone would take seconds and hundreds of MB (1,000,000 statements: 54 s).
MAX_FILE_LINES = 100_000
MAX_FILE_BYTES = 16 * 2**20

register({
    "E-LIMIT-002": f"an expression or a type is nested more than {MAX_EXPRESSION_DEPTH} levels deep",
    "E-LIMIT-003": f"statements are nested more than {MAX_BLOCK_DEPTH} levels deep",
    "E-LIMIT-004": f"loops are nested more than {MAX_LOOP_DEPTH} levels deep",
    "E-LIMIT-005": f"an IF has more than {MAX_ELSIF} ELSIF branches",
    "E-LIMIT-006": f"a CASE has more than {MAX_CASE_CLAUSES} clauses",
    "E-LIMIT-007": f"a POU has more than {MAX_STATEMENTS} statements",
    "E-LIMIT-012": f"a source file has more than {MAX_FILE_LINES:,} lines or {MAX_FILE_BYTES:,} bytes",
})


def file_too_large(text: str) -> str | None:
    """Why `text` is too large to parse (E-LIMIT-012), or None."""
    lines = text.count("\n") + 1
    if lines > MAX_FILE_LINES:
        return f"{lines:,} lines: a source file has at most {MAX_FILE_LINES:,} (split it into several files)"
    if len(text) > MAX_FILE_BYTES:
        return f"{len(text):,} characters: a source file has at most {MAX_FILE_BYTES:,} (split it)"
    return None

_BLOCKS = (ast.If, ast.Case, ast.For, ast.While, ast.Repeat)
_LOOPS = (ast.For, ast.While, ast.Repeat)
_STATEMENTS = _BLOCKS + (ast.Assign, ast.CallStmt, ast.Exit, ast.Continue, ast.Return, ast.Empty)
# Nodes that hold statements or expressions but add no nesting of their own.
_TRANSPARENT = (ast.IfBranch, ast.CaseClause, ast.CaseRange, ast.Arg, ast.Pou, ast.VarBlock, ast.VarDecl,
                ast.ArrayInit, ast.ArrayInitItem, ast.StructInit, ast.FieldInit, ast.TypeDecl,
                ast.Configuration, ast.TaskDecl, ast.ProgramInstance, ast.StructType, ast.EnumType, ast.EnumValue)


#: The node classes of the NJ build rules (nj_build.py: rules 006 and 007).
_BUILD_NODES = (ast.Index, ast.Member, ast.Case)


def _shape(cls: type) -> tuple:
    """(statement, block, loop, transparent, dialect construct (its function of
    `dialects.CONSTRUCTS`, or None), build rule node, children): what check_limits asks
    of every node of `cls`; `children(node)` is the tuple of the node's fields that may
    hold a node, in field order."""
    return (issubclass(cls, _STATEMENTS), issubclass(cls, _BLOCKS), issubclass(cls, _LOOPS),
            issubclass(cls, _TRANSPARENT), CONSTRUCTS.get(cls), cls in _BUILD_NODES,
            _children_getter(ast.CHILD_FIELDS[cls]))


_SHAPES: dict[type, tuple] = PerClass(_shape)


def _no_children(node) -> tuple:
    return ()


def _children_getter(names: tuple[str, ...]):
    """A function of a node giving the tuple of its fields `names`: `attrgetter` (one C call)
    where it gives a tuple, that is for two fields or more."""
    if len(names) > 1:
        return attrgetter(*names)
    if names:
        name, = names
        return lambda node: (getattr(node, name),)
    return _no_children


#: What the walk does with a child field's value, by its class: PUSH a node (walk it),
#: look into a TUPLE of them, or SKIP it (None, a scalar).  `_QUIET` skips an
#: expression's plain leaf too (a name, a literal: `_is_leaf`), whose depth's check
#: cannot fail above the deepest level; `_LOUD` pushes it, for a node at that level.
SKIP, PUSH, TUPLE = 0, 1, 2


def _quiet_kind(cls: type) -> int:
    """`_QUIET[cls]`: `_loud_kind`, but SKIP for a plain leaf."""
    if issubclass(cls, ast.Node):
        return SKIP if _is_leaf(cls) else PUSH
    return _loud_kind(cls)


def _loud_kind(cls: type) -> int:
    """`_LOUD[cls]`: PUSH a node, look into a TUPLE, SKIP anything else."""
    if issubclass(cls, ast.Node):
        return PUSH
    return TUPLE if issubclass(cls, tuple) else SKIP


def _is_leaf(cls: type) -> bool:
    """Whether a node of `cls` is a plain leaf of an expression (a name, a literal): no
    child, no statement, construct or build rule node, so all the walk does with it is
    its depth's check, which cannot fail below the deepest level."""
    statement, _, _, transparent, construct, build_node, _ = _SHAPES[cls]
    return not (statement or transparent or construct or build_node or ast.CHILD_FIELDS[cls])


_QUIET, _LOUD = PerClass(_quiet_kind), PerClass(_loud_kind)
#: The table a node's fields are walked under, by its depth (at most the deepest level: a
#: node beyond is reported, not walked): `_QUIET` above the deepest level, where a leaf
#: below cannot be too deep, `_LOUD` at it.
_KINDS_AT = (_QUIET,) * MAX_EXPRESSION_DEPTH + (_LOUD,)


def _item_kind(cls: type):
    """What the walk does with a node of `cls` inside a tuple field (a VAR block's
    declarations, a call's arguments): SKIP it, PUSH it, or ask `test(node, kinds)`
    whether walking it would add nothing (`_hollow_test`), then push it only if not.
    A leaf's test is `_leaf_adds_nothing`: nothing above the deepest level."""
    if not issubclass(cls, ast.Node):
        return SKIP
    if _is_leaf(cls):
        return _leaf_adds_nothing
    return _hollow_test(cls) if _may_be_hollow(cls) else PUSH


def _leaf_adds_nothing(node, kinds) -> bool:
    return kinds is _QUIET


def _may_be_hollow(cls: type) -> bool:
    """Whether a node of `cls` may add nothing to the walk: one that neither nests (a
    transparent node) nor counts (no statement, no build rule node), whose fields hold
    no tuple; it adds nothing when each of its fields is skipped (None, a scalar, a
    leaf above the deepest level) and it names no construct (`VarDecl`, `Arg`, `CaseRange`)."""
    statement, _, _, transparent, _, build_node, _ = _SHAPES[cls]
    declared = cls.__dataclass_fields__
    return transparent and not statement and not build_node and not any(
        declared[name].type.startswith("tuple[") for name in ast.CHILD_FIELDS[cls])


def _hollow_test(cls: type):
    """Whether a node of `cls` (`_may_be_hollow`) adds nothing to the walk: what its visit
    would do, without the visit.  A transparent node's fields are walked at its parent's
    depth, so `kinds` is the parent's."""
    *_, construct, _, children = _SHAPES[cls]
    names = ast.CHILD_FIELDS[cls]
    if construct is None and len(names) == 1:     # an argument, an enumeration value
        field = attrgetter(*names)
        return lambda node, kinds: not kinds[type(field(node))]

    def adds_nothing(node, kinds) -> bool:
        for value in children(node):
            if kinds[type(value)]:
                return False
        return construct is None or construct(node) is None
    return adds_nothing


_ITEMS = PerClass(_item_kind)


class Walked:
    """What the walk found in one item for the passes after it: `constructs`, the
    (construct, position) of each node a dialect may refuse (`dialects.CONSTRUCTS`),
    in the walk's order; `build_nodes`, whether any node is one the NJ build rules
    look at (a CASE, or an Index or a Member of a member: `a.b[1]`, `a.b.c`; rule 006's
    test, `_fb_variable_part`, passes over any other), else their walk of the item is
    skipped."""

    __slots__ = ("constructs", "build_nodes")

    def __init__(self) -> None:
        self.constructs: list[tuple[str, ast.Pos]] = []
        self.build_nodes = False


def check_files(ctx, files) -> bool:
    """Check the limits of every POU, type and global block of `files`; True
    when all are within them (otherwise nothing else should walk them).
    What each item holds for later passes goes to `ctx.walked` (`Walked`)."""
    ok = True
    for source in files:
        if source.path == BUILTIN_FILE:
            continue   # the native prelude: declarations only, within every limit, and walked on every load
        for item in source.items:
            walked = ctx.walked[id(item)] = Walked()
            ok = check_limits(ctx, item, getattr(item, "name", None) or source.path, walked) and ok
    return ok


def check_limits(ctx, pou, name: str, walked: Walked | None = None) -> bool:
    """Report every limit `pou` (a POU, a type or a VAR_GLOBAL block named
    `name`) exceeds, one diagnostic per kind at the first place; True when it
    is within all of them.  `walked` collects what later passes need (`Walked`):
    complete only when the item is within every limit."""
    found: set[str] = set()
    walked = walked if walked is not None else Walked()
    constructs, build_nodes = walked.constructs, False

    def report(code: str, message: str, node) -> None:
        if code not in found:
            found.add(code)
            ctx.error(code, f"{message} in {name}", node.pos)

    statements = 0
    # (node, statement depth, loop depth, expression depth)
    stack = [(pou, 0, 0, 0)]
    push, pop, shapes, kinds_at, items = stack.append, stack.pop, _SHAPES, _KINDS_AT, _ITEMS
    while stack:
        node, blocks, loops, depth = pop()
        is_statement, is_block, is_loop, transparent, construct, build_node, children = shapes[type(node)]
        if construct:
            what = construct(node)
            if what is not None:
                constructs.append((what, node.pos))
        if build_node and not build_nodes:
            build_nodes = isinstance(node, ast.Case) or isinstance(node.base, ast.Member)
        if is_statement:
            statements += 1
            depth = 0
            if is_block:       # (IF and CASE are blocks, loops too)
                blocks += 1
                if blocks > MAX_BLOCK_DEPTH:
                    report("E-LIMIT-003", f"statements nested more than {MAX_BLOCK_DEPTH} levels deep"
                           f" ({type(node).__name__.upper()} here)", node)
                    continue
                if is_loop:
                    loops += 1
                    if loops > MAX_LOOP_DEPTH:
                        report("E-LIMIT-004", f"loops nested more than {MAX_LOOP_DEPTH} levels deep", node)
                        continue
                elif isinstance(node, ast.If):
                    if len(node.branches) - 1 > MAX_ELSIF:
                        report("E-LIMIT-005", f"IF with {len(node.branches) - 1} ELSIF branches (at most"
                               f" {MAX_ELSIF}; a CASE takes many more)", node)
                elif isinstance(node, ast.Case) and len(node.clauses) > MAX_CASE_CLAUSES:
                    report("E-LIMIT-006", f"CASE with {len(node.clauses)} clauses (at most {MAX_CASE_CLAUSES})",
                           node)
        elif not transparent:
            depth += 1
            if depth > MAX_EXPRESSION_DEPTH:
                what = ("type" if isinstance(node, (ast.NamedType, ast.StringType, ast.ArrayType, ast.Subrange))
                        else "expression")
                report("E-LIMIT-002", f"{what} nested more than {MAX_EXPRESSION_DEPTH} levels deep"
                       " (split it with intermediate variables or types)", node)
                continue
        kinds = kinds_at[depth]
        for value in children(node):     # the child nodes in field order, tuples flattened
            kind = kinds[type(value)]
            if not kind:           # (None, a scalar, a quiet leaf: the commonest, tested first)
                continue
            if kind == PUSH:
                push((value, blocks, loops, depth))
            else:
                for item in value:   # (a node that would add nothing is not pushed: `_ITEMS`)
                    test = items[type(item)]
                    if test == PUSH or test and not test(item, kinds):
                        push((item, blocks, loops, depth))
    if statements > MAX_STATEMENTS:
        report("E-LIMIT-007", f"{statements} statements (at most {MAX_STATEMENTS}; split the POU)", pou)
    walked.build_nodes = build_nodes
    return not found
