"""What may be written: assignment targets, output (`=>`) targets and
VAR_IN_OUT arguments."""

from __future__ import annotations

from .. import ast
from .. import types as T
from ..dialects import accepting
from . import typesys as ts
from .loop_writes import note_write, note_write_through


def root_name(e) -> ast.Name | None:
    """The variable at the root of `a.b[i].c`, or None if `e` is no variable path."""
    while isinstance(e, (ast.Member, ast.Index, ast.Deref, ast.BitAccess)):
        e = e.base
    return e if isinstance(e, ast.Name) else None


def is_variable_path(e) -> bool:
    return isinstance(e, (ast.Name, ast.Member, ast.Index, ast.Deref, ast.BitAccess)) \
        and root_name(e) is not None


#: The classes of a variable path's steps from a node to its base (`a.b[i]^.%X1`).
_STEPS = frozenset((ast.Member, ast.Index, ast.Deref, ast.BitAccess))


def _root_and_reference(e) -> tuple[ast.Name | None, bool]:
    """(`root_name(e)`, whether the path writes what a reference refers to: `r^`, `r^.x`,
    `a[i]^`), by one walk down the path."""
    through = False
    while type(e) in _STEPS:
        through = through or type(e) is ast.Deref
        e = e.base
    return (e if type(e) is ast.Name else None), through


def controls_a_loop(ex, sym) -> bool:
    """`sym` is the control variable of a FOR that encloses the statement being checked
    (IEC 61131-3 3rd ed. 7.3.3.4.2: the repeated statements shall not alter it)."""
    return bool(ex.loop_vars) and any(sym is loop_var for loop_var in ex.loop_vars)


def check_store(ex, target, what: str = "assignment"):
    """Type `target` as something written to; report when it may not be.

    Returns the target's type (ERROR after a report, so that the value is not
    also reported).
    """
    if type(target) is ast.Name:      # the commonest: no step, no call, no property, no reference
        t = ex.infer(target)
        return t if t is ts.ERROR else _writable(ex, target, target, t, what)
    if isinstance(target, ast.DirectVar):     # a place of the process image
        return ex.infer(target)
    root, through = _root_and_reference(target)
    if root is None:                          # no variable path
        ex.infer(target)
        ex.ctx.error("E-TYPE-014", f"{what}: expected a variable, found "
                     f"{_describe(target)}", target.pos)
        return ts.ERROR
    outer, ex.storing = ex.storing, target      # (a call in `target` may store its outputs)
    t = ex.infer(target)
    ex.storing = outer
    accessors = ex.program.properties.get(id(target))
    if accessors is not None and t is not ts.ERROR:
        if accessors[1] is None:
            ex.ctx.error("E-ASSIGN-004", f"{what}: property '{target.name}' has no SET", target.pos)
            return ts.ERROR
        return t
    if t is ts.ERROR:
        return t
    if through:
        note_write_through(ex, target)
        return t                   # (the referenced variable was writable where REF took it)
    return _writable(ex, target, root, t, what)


def _writable(ex, target, root: ast.Name, t, what: str):
    """`t` when the variable path `target` (typed `t`, no ERROR), whose root is `root`, may be
    written here, else ERROR after a report: no enumeration value, no CONSTANT, no input
    of this POU, no enclosing FOR's control variable, no FB instance's output."""
    sym = ex.program.name_refs.get(id(root))
    if not hasattr(sym, "kind"):  # an enumeration value
        ex.ctx.error("E-TYPE-014", f"{what}: '{root.name}' is an enumeration value, not a variable",
                     target.pos)
        return ts.ERROR
    if sym.constant:
        ex.ctx.error("E-ASSIGN-001", f"{what}: '{sym.name}' is CONSTANT and cannot be written",
                     target.pos)
        return ts.ERROR
    if sym.kind == "VAR_INPUT" and ex.scope.is_local(sym) and not ex.ctx.rules.accepts("INPUT_WRITE"):
        ex.ctx.error("E-ASSIGN-002", f"{what}: '{sym.name}' is a VAR_INPUT of "
                     f"{ex.scope.pou.name} and is read-only inside it "
                     f"({accepting('INPUT_WRITE')} accepts writing it)", target.pos)
        return ts.ERROR
    if controls_a_loop(ex, sym):
        ex.ctx.error("E-ASSIGN-003", f"{what}: '{sym.name}' is the control variable of an "
                     f"enclosing FOR loop", target.pos)
        return ts.ERROR
    note_write(ex.ctx, ex.scope, sym)
    # (a Name is no FB's member: `_fb_member` finds nothing without a step)
    member = None if ex.ctx.open_instances or target is root else _fb_member(ex, target)
    if member is not None:
        fb, var = member
        ex.ctx.error("E-ASSIGN-004", f"{what}: '{var.name}' is a {var.kind} of function block "
                     f"{fb.name}; only its inputs may be written from outside", target.pos)
        return ts.ERROR
    return t


def in_out_problem(ex, target, sym) -> str | None:
    """Why the variable path `target` (root variable `sym`) cannot be passed
    to a VAR_IN_OUT, which the callee may write; None when it can."""
    if sym.constant:
        return f"CONSTANT '{sym.name}'"
    if sym.kind == "VAR_INPUT" and ex.scope.is_local(sym):
        return (f"VAR_INPUT '{sym.name}' of {ex.scope.pou.name} (inputs are read-only inside "
                f"their POU)")
    if controls_a_loop(ex, sym):
        return f"'{sym.name}', the control variable of an enclosing FOR loop"
    member = None if ex.ctx.open_instances else _fb_member(ex, target)
    if member is not None:
        fb, var = member
        return (f"'{var.name}', a {var.kind} of function block {fb.name} (only its inputs may be "
                f"written from outside)")
    return None


def no_address(ex, target) -> str | None:
    """What the typed variable path `target` is when it has no address of its own to pass by
    reference (to a VAR_IN_OUT, REF, ADR): a bit of a variable, or a PROPERTY, whose accessors
    run code (CODESYS: "A bit access must not be assigned to a VAR_IN_OUT variable"); None for
    a variable."""
    if isinstance(target, ast.BitAccess):
        return "a bit access"
    if id(target) in ex.program.properties:
        return f"property '{target.name}'"
    return None


def _fb_member(ex, target):
    """(FBType, Symbol) when the path writes a non-input variable of an FB instance."""
    e = target
    while isinstance(e, (ast.Member, ast.Index, ast.BitAccess)):
        if isinstance(e, ast.Member):
            base_t = ex.program.expr_types.get(id(e.base))
            this = isinstance(e.base, ast.Name) and ast.key(e.base.name) == "THIS"
            if isinstance(base_t, T.FBType) and not this:
                var = base_t.variables.get(ast.key(e.name))
                if var is not None and var.kind != "VAR_INPUT":
                    return base_t, var
        e = e.base
    return None


def _describe(e) -> str:
    if isinstance(e, (ast.IntLiteral, ast.RealLiteral, ast.BoolLiteral, ast.StringLiteral,
                      ast.TimeLiteral, ast.DateTimeLiteral, ast.EnumLiteral)):
        return "a literal"
    if isinstance(e, ast.Call):
        return "a call"
    return "an expression"
