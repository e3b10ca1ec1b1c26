"""What Sysmac Studio refuses at Build, beyond identifiers (NJ rules 006-008).

Run after the bodies are checked (it reads the expression types, name
references and folded constants).  Each rule's source and confidence are in
`st_runtime.dialects.NJ_RULES` and docs/nj501.md; the severity comes from the
dialect (`Context.nj_rule`): errors under `--dialect nj`, warnings under `iec`,
which allows all three.

* 006: `Inst.Var[i]` or `Inst.Var.M`, where `Inst` is a function block
  instance, in any position (read, assignment target, argument, `=>` target).
  The Build message speaks of any "reference"; the observed failure is a
  read of an indexed output, so writes and arguments are refused by the
  message's wording, not by an observation.  The whole variable (`Inst.Var`)
  and a scalar (`Inst.Done`) are fine; so is `Fbs[i].Done` (a member of an
  element of an array of instances: the instance's variable itself is scalar).
* 007: a CASE label is an integer literal (signed, typed or based) or an
  enumerator; anything else (a constant's name, an expression) is refused.
* 008: an initial value is a literal, an enumerator, or an array or structure
  initializer made of them; a constant's name or an expression is refused.
"""

from __future__ import annotations

from .. import ast
from .. import types as T
from ..per_class import PerClass
from ..printer import format_expr as _text
from ..values import FORMATTERS
from .context import BUILTIN_FILE, Context

_LITERALS = (ast.IntLiteral, ast.RealLiteral, ast.BoolLiteral, ast.StringLiteral,
             ast.TimeLiteral, ast.DateTimeLiteral, ast.EnumLiteral)


def check_build_rules(ctx: Context, files) -> None:
    for f in files:
        if f.path == BUILTIN_FILE:
            continue
        for item in f.items:
            if isinstance(item, ast.Pou):
                if ctx.walked[id(item)].build_nodes:    # (the structural walk saw one: limits.py)
                    for node in _walk(item.body):
                        if isinstance(node, _RULE_NODES):
                            _body_node(ctx, node)
                for block in item.var_blocks:
                    _initial_values(ctx, block.decls)
            elif isinstance(item, ast.VarBlock):
                _initial_values(ctx, item.decls)
            elif isinstance(item, ast.Configuration):
                for block in item.globals:
                    _initial_values(ctx, block.decls)
            elif isinstance(item, ast.TypeDecl):
                if item.init is not None:
                    _initial_value(ctx, item.name, item.init)
                if isinstance(item.spec, ast.StructType):
                    _initial_values(ctx, item.spec.members)


#: The nodes rules 006 and 007 look at (`_body_node`).
_RULE_NODES = (ast.Index, ast.Member, ast.Case)


def _last_field_first(cls: type) -> tuple:
    """A node class's child fields from the last to the first (pushed so, the walk pops
    them in field order)."""
    return tuple(reversed(ast.CHILD_FIELDS[cls]))


_LAST_FIELD_FIRST = PerClass(_last_field_first)


def _walk(node) -> list:
    """Every AST node below `node` (statements, expressions, labels), depth first."""
    out = []
    stack = [node]           # (iterative: the same preorder as recursing, in linear time)
    pop, push, extend, add, Node, last_first = stack.pop, stack.append, stack.extend, out.append, \
        ast.Node, _LAST_FIELD_FIRST
    while stack:
        item = pop()
        if isinstance(item, (tuple, list)):
            extend(reversed(item))
        elif isinstance(item, Node):
            add(item)
            for name in last_first[type(item)]:
                push(getattr(item, name))
    return out


def _body_node(ctx: Context, node) -> None:
    if isinstance(node, (ast.Index, ast.Member)):
        _fb_variable_part(ctx, node)
    elif isinstance(node, ast.Case):
        for clause in node.clauses:
            for label in clause.labels:
                for bound in ((label.lo, label.hi) if isinstance(label, ast.CaseRange) else (label,)):
                    _case_label(ctx, bound)


def _fb_variable_part(ctx: Context, node) -> None:
    """Rule 006 at `node` = Index or Member whose base is `Inst.Var`, `Inst` an FB instance."""
    var = node.base
    if not isinstance(var, ast.Member):
        return
    if not isinstance(ctx.program.expr_types.get(id(var.base)), T.FBType):
        return
    what = "an element of" if isinstance(node, ast.Index) else "a member of"
    path = _text(var)
    ctx.nj_rule("006", f"{what} '{path}', a variable of a function block instance: Sysmac "
                f"Studio refuses it at Build (\"Cannot use an element of array or a member of "
                f"structure for the reference of function block instance variables\"); copy "
                f"'{path}' whole into a local variable first", _start(node))


def _case_label(ctx: Context, label) -> None:
    if _is_literal(ctx, label, integer_only=True):
        return
    value = ctx.program.constants.get(id(label))
    hint = f": write {value} (* {_text(label)} *)" if isinstance(value, int) and \
        not isinstance(value, bool) else ""
    ctx.nj_rule("007", f"CASE label '{_text(label)}' is not an integer literal or an "
                f"enumerator; OMRON documents CASE labels as integer constants{hint}",
                _start(label))


def _initial_values(ctx: Context, decls) -> None:
    for decl in decls:
        if decl.init is not None:
            _initial_value(ctx, decl.name, decl.init)


def _initial_value(ctx: Context, name: str, init) -> None:
    if isinstance(init, ast.ArrayInit):
        for item in init.items:
            if item.count is not None:
                _initial_value(ctx, name, item.count)
            if item.value is not None:
                _initial_value(ctx, name, item.value)
        return
    if isinstance(init, ast.StructInit):
        for f in init.fields:
            _initial_value(ctx, name, f.value)
        return
    if _is_literal(ctx, init, integer_only=False):
        return
    value = ctx.program.constants.get(id(init))
    kind = getattr(ctx.program.expr_types.get(id(init)), "kind", None)
    hint = f": write {_st_value(value, kind)} (* {_text(init)} *)" if value is not None else ""
    ctx.nj_rule("008", f"initial value of '{name}': '{_text(init)}' is not a literal; a "
                f"variable table in Sysmac Studio takes literals{hint}", _start(init))


def _is_literal(ctx: Context, e, integer_only: bool) -> bool:
    if isinstance(e, ast.Unary) and e.op in ("-", "+"):
        e = e.operand
        if isinstance(e, (ast.EnumLiteral, ast.Name)):
            return False
    if isinstance(e, ast.IntLiteral) or isinstance(e, ast.EnumLiteral):
        return True
    if isinstance(e, ast.Member):      # CODESYS's Light.Red: an enumerator, typed as one
        return isinstance(ctx.program.expr_types.get(id(e)), T.EnumType) \
            and id(e) in ctx.program.constants
    if isinstance(e, ast.Name):        # an enumerator is an int in name_refs, a variable a Symbol
        ref = ctx.program.name_refs.get(id(e))
        return isinstance(ref, int) and not isinstance(ref, bool)
    return not integer_only and isinstance(e, _LITERALS)


def _st_value(value, kind: str | None) -> str:
    if isinstance(value, bool):
        return "TRUE" if value else "FALSE"
    if isinstance(value, float):
        return repr(value)
    if kind in FORMATTERS:      # a TIME or date is kept in ns: show its literal
        return FORMATTERS[kind](value)
    return str(value)


def _start(e) -> ast.Pos:
    while isinstance(e, (ast.Member, ast.Index, ast.Binary)):
        e = e.base if not isinstance(e, ast.Binary) else e.left
    return e.pos

