"""The checker: from parsed files to a `CheckedProgram`, or to diagnostics.

    program, diagnostics = check(files, dialect="iec")

Passes, each in its own module: `declarations` (types, POUs, globals),
`statements`/`expressions`/`calls` (bodies), `recursion`, `nj_rules` (identifiers),
`nj_build` (what Sysmac Studio refuses at Build).  The
checker never raises on any AST: every problem is a `Diagnostic`, and an
expression that already produced one has the type `typesys.ERROR`, which is
compatible with everything (one root cause, one diagnostic).

What the CheckedProgram holds (the compiler's contract):

* `types`: every TYPE by upper-case name, resolved (an alias maps to its
  target type, never an AliasType), plus every FUNCTION_BLOCK as its FBType.
* `pous`: PouInfo per POU; `variables` in declaration order, a FUNCTION's
  result first as kind "RETURN" (named like the function).  FBType.variables
  is the same dict.  Native FBs from the prelude carry `native`.
* `globals`: VAR_GLOBAL symbols.  A VAR_EXTERNAL is a local Symbol of kind
  "VAR_EXTERNAL" with the global's type; a global used without VAR_EXTERNAL
  refers to the global Symbol directly.
* `expr_types`: every expression node, with two exceptions: the callee Name
  of a function call (see `call_targets`) and an FB call statement's Call.
  The literal typing rule is in `expressions.py`.
* `name_refs`: every Name used as a value or target -> Symbol; an enumeration
  value -> its int.  FB instance callees are included (Symbol of the instance).
* `call_targets`: every Call that checked; kinds "function" (user: `pou` set;
  standard: `generic_type` is the instantiation type, or None), "fb",
  "conversion" (`name` like "INT_TO_REAL", `generic_type` the target type).
* `constants`: folded values of constant expressions (literals, CONSTANT
  variables, enumeration values, operators on them), stored as the runtime
  stores them in the node's type (integers wrapped, REAL rounded to float32).
* `for_vars`: id(For) -> Symbol of its control variable.
* `subranges`: every place typed with a subrange (variable, element, member,
  dereference) -> that SubrangeType; its `expr_types` entry is the base type.
"""

from __future__ import annotations

import sys
from itertools import islice

from .. import ast
from ..diagnostics import Diagnostic, register
from ..symbols import CheckedProgram
from . import codes  # noqa: F401  (registers the codes)
from .context import Context, FastSink, Scope
from .declarations import Declarations
from .dialects import check_dialect
from .sfc import lower_charts
from .expressions import ExprChecker
from .nj_build import check_build_rules
from .limits import check_files
from .memory import check_memory
from .nj_rules import check_identifiers
from .prelude_base import prelude_base
from .loop_writes import check_calls_in_loops, check_references_in_loops
from .recursion import check_recursion
from .statements import StatementChecker

DIALECTS = ("iec", "nj", "codesys")
RECURSION_LIMIT = 30_000

register({
    "E-LIMIT-001": "the program is nested too deeply to be checked",
    "E-CHECK-999": "internal checker error (a bug: please report it)",
})


def check(files: list[ast.SourceFile], dialect: str = "iec",
          memory_limit: int | None = None,
          open_instances: bool = False,
          share_prelude: bool = True) -> tuple[CheckedProgram, list[Diagnostic]]:
    """Check parsed files as one program; `dialect` is "iec" or "nj".

    `memory_limit`: bytes a variable, a POU instance or the project may need
    (default `memory.DEFAULT_LIMIT`). `open_instances` lets code read and
    write every variable of an FB instance from outside (`stgen test`:
    STruC++'s tests see inside instances, st_runtime/testing/lowering.py).
    When the first file is the native prelude ("<builtin>"), its declarations
    come from the process's shared checked prelude (`prelude_base`), with the
    same result; `share_prelude=False` checks it again (the tests compare).
    """
    files = [f for f in files if f is not None]
    # The checker walks expressions recursively; a generated sum of 720
    # products (an unrolled Leibniz determinant) is 720 levels deep.
    old_limit = sys.getrecursionlimit()
    sys.setrecursionlimit(max(old_limit, RECURSION_LIMIT))
    try:
        return _check(files, dialect, memory_limit, open_instances, share_prelude)
    finally:
        sys.setrecursionlimit(old_limit)


def _check(files, dialect, memory_limit=None, open_instances=False, share_prelude=True):
    program = CheckedProgram(files=list(files))
    ctx = Context(program, FastSink(), dialect if dialect in DIALECTS else "iec", open_instances)
    program.dialect = ctx.dialect
    try:
        if not check_files(ctx, files):       # structural limits first (limits.py)
            return program, list(ctx.sink.items)
        base = prelude_base(files, ctx.dialect, open_instances) if share_prelude else None
        # a chart body becomes statements (sfc.py); the shared prelude has none
        program.files = lower_charts(ctx, files, base.file if base is not None else None)
        if base is not None and not base.clashes(program.files[1:]):
            base.seed(ctx)
            program.prelude = base
            declarations = Declarations(ctx, base)
            declarations.run(program.files[1:])
        else:
            declarations = Declarations(ctx)
            declarations.run(program.files)
        pous = iter(program.pous.values())
        if program.prelude is not None and program.prelude.memo("bodiless", lambda: all(
                info.node is None or info.native is not None for info in base.pous.values())):
            pous = islice(pous, len(base.pous), None)     # (its POUs lead the table: none to check)
        for info in pous:
            if info.node is None or info.native is not None:
                continue
            StatementChecker(declarations.body_checker(info)).block(info.node.body)
            for method in info.methods.values():
                if method.owner is info and info.kind == "FUNCTION_BLOCK":
                    ex = ExprChecker(ctx, Scope(ctx, method), declared=True)
                    StatementChecker(ex).block(method.node.body)
        check_recursion(ctx)
        check_calls_in_loops(ctx)
        check_references_in_loops(ctx)
        check_dialect(ctx, files)
        if not any(d.code == "E-REC-001" for d in ctx.sink.items):   # sizes need acyclic types
            check_memory(ctx, memory_limit)
        check_identifiers(ctx, files)
        check_build_rules(ctx, files)
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
