"""The checker: from parsed files to a `CheckedProgram`, or to diagnostics.

    program, diagnostics = check(files, dialect="iec")

Passes, each in its own module: `declarations` (types, POUs, globals),
`statements`/`expressions`/`calls` (bodies), `recursion`, `nj_rules`.  The
checker never raises on any AST: every problem is a `Diagnostic`, and an
expression that already produced one has the type `typesys.ERROR`, which is
compatible with everything (one root cause, one diagnostic).
"""

from __future__ import annotations

from .. import ast
from ..diagnostics import Diagnostic, DiagnosticSink, register
from ..symbols import CheckedProgram
from . import codes  # noqa: F401  (registers the codes)
from .context import Context, Scope
from .declarations import Declarations
from .expressions import ExprChecker
from .nj_rules import check_identifiers
from .recursion import check_recursion
from .statements import StatementChecker

DIALECTS = ("iec", "nj")

register({
    "E-LIMIT-001": "the program is nested too deeply to be checked",
    "E-CHECK-999": "internal checker error (a bug: please report it)",
})


def check(files: list[ast.SourceFile], dialect: str = "iec") -> tuple[CheckedProgram, list[Diagnostic]]:
    """Check parsed files as one program; `dialect` is "iec" or "nj"."""
    files = [f for f in files if f is not None]
    program = CheckedProgram(files=list(files))
    ctx = Context(program, DiagnosticSink(), dialect if dialect in DIALECTS else "iec")
    try:
        Declarations(ctx).run(files)
        for info in program.pous.values():
            if info.node is None or info.native is not None:
                continue
            ex = ExprChecker(ctx, Scope(ctx, info))
            StatementChecker(ex).block(info.node.body)
        check_recursion(ctx)
        check_identifiers(ctx, files)
    except RecursionError:
        ctx.error("E-LIMIT-001", "the program is nested too deeply to be checked "
                  "(expressions or statements nested hundreds of levels)", _where(files))
    except Exception as exc:  # the promise: diagnostics, never a traceback
        ctx.error("E-CHECK-999", f"internal checker error: {type(exc).__name__}: {exc}",
                  _where(files))
    return program, list(ctx.sink.items)


def _where(files) -> ast.Pos:
    for f in files:
        if f.path != "<builtin>":
            return ast.Pos(f.path, 1, 1)
    return ast.NOWHERE
