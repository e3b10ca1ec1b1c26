"""The checked native prelude, shared by every load of a process.

Every load checks the user's files after the native prelude (the "<builtin>"
file: TON, R_TRIG, MC_Power, AXIS_REF, ...).  The prelude is the same AST
object in every load (`st_runtime.prelude` parses it once per dialect), so
its declarations check to the same result every time.  `prelude_base()`
checks it once per (prelude file, dialect, open_instances) and keeps a
snapshot: its symbols, POU infos, types and the side tables of its
initializers.  A later load starts from copies of the snapshot's tables and
declares only the user's files (`Declarations(ctx, base)`).

Why the result is exactly today's (the full check of prelude + user files):

* The prelude refers to nothing of the user's (it checks alone without a
  diagnostic, else no snapshot is made), and the checker never changes a
  symbol, POU info or type once declared: a load adds its own entries to
  its own copies of the tables, so nothing of one load reaches the next.
* A load whose files declare a name the prelude declares (a project's own
  TON, W-DECL-001, or a duplicate E-DECL-003) is checked in full, as before.
* Dictionary order is kept: the prelude's POUs come first, as in a full
  check, and a prelude TYPE enters `program.types` (and its enumeration
  values `ctx.enum_values`) at the moment the full check would resolve it,
  by replaying what resolving it did (`type_events`), since a user global
  may resolve a prelude type before the others.
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields
from functools import cached_property

from .. import ast
from ..symbols import CheckedProgram
from .context import BUILTIN_FILE, Context, FastSink

#: Context and CheckedProgram tables that are not copied from the snapshot:
#: types and enumeration values enter lazily (see the module docstring).
_LAZY = ("types", "enum_values")
_PROGRAM_TABLES = tuple(f.name for f in fields(CheckedProgram)
                        if f.name not in ("files", "sources", "dialect", "prelude") + _LAZY)
_CONTEXT_TABLES = ("type_decls", "pou_decls", "symbol_values", "calls", "namespaces", "direct_types")


@dataclass(eq=False)
class PreludeBase:
    """The checked prelude: read-only once built (loads copy its tables)."""

    file: ast.SourceFile
    dialect: str
    open_instances: bool
    names: dict                      # Declarations._names: upper-case name -> Pos
    pou_types: dict                  # FBType / InterfaceType of each prelude POU
    types: dict                      # every prelude type, resolved
    type_events: dict                # TYPE key -> what resolving it did, in order
    program_tables: dict             # CheckedProgram field -> its table after the prelude
    context_tables: dict             # Context field -> its table after the prelude
    interfaces_done: frozenset       # id(PouInfo) of the prelude POUs
    enum_values: dict                # Context.enum_values after the prelude
    compiled: object = field(default=None, repr=False)   # the compiler's share, built lazily
    _memo: dict = field(default_factory=dict, repr=False)

    def memo(self, what: str, compute):
        """What a whole-program pass found about the prelude alone (`compute()`, once):
        the same in every load, since no load changes the prelude."""
        found = self._memo.get(what)
        if found is None:
            found = self._memo[what] = compute()
        return found

    def __repr__(self) -> str:
        return f"PreludeBase({self.dialect}, {len(self.pous)} POUs, {len(self.types)} types)"

    @property
    def pous(self) -> dict:
        return self.program_tables["pous"]

    def seed(self, ctx: Context) -> None:
        """Fill a new load's Context and CheckedProgram with copies of the prelude's tables
        (types and enumeration values excepted: they enter lazily, in the full check's order).
        A table the prelude left empty is not copied: a new Context or CheckedProgram holds
        an empty one of the same kind already (most of them: `filled`).  By `setattr`, not by
        one `vars(...).update`: that makes the object's `__dict__` a real dict, after which
        CPython 3.11 reads none of its attributes by the specialised instance-value path, and a
        round of the accept corpus cost 8 million machine instructions more (session 25)."""
        program = ctx.program
        program_tables, context_tables = self.filled
        for name, table in program_tables:
            setattr(program, name, table.copy())
        for name, table in context_tables:
            setattr(ctx, name, table.copy())
        program.types = dict(self.pou_types)    # (its TYPEs enter later, see Declarations)
        if self.context_tables["calls"]:
            ctx.calls = {caller: list(edges) for caller, edges in self.context_tables["calls"].items()}

    @cached_property
    def filled(self) -> tuple[tuple, tuple]:
        """The (name, table) of the program and context tables the prelude filled."""
        return (tuple((name, table) for name, table in self.program_tables.items() if table),
                tuple((name, table) for name, table in self.context_tables.items()
                      if table and name != "calls"))

    @cached_property
    def enum_lists(self) -> tuple[tuple, tuple]:
        """`enum_values` as (its keys, their tuples): a load's lists are made from them at once."""
        return tuple(self.enum_values), tuple(self.enum_values.values())

    def clashes(self, files: list[ast.SourceFile]) -> bool:
        """Whether a user file declares a TYPE or POU named like one of the prelude's."""
        names = self.names
        return any(isinstance(item, (ast.TypeDecl, ast.Pou)) and item.name.upper() in names
                   for f in files for item in f.items)


#: (id(prelude file), dialect, open_instances) -> PreludeBase or None (does not check alone).
_BASES: dict[tuple, PreludeBase | None] = {}
_MAX_BASES = 16


def prelude_base(files: list[ast.SourceFile], dialect: str, open_instances: bool) -> PreludeBase | None:
    """The shared checked prelude for a check of `files` (the prelude first), or None:
    no "<builtin>" first file, or a prelude that does not check alone without a diagnostic."""
    if not files or files[0].path != BUILTIN_FILE:
        return None
    prelude = files[0]
    cache_key = (id(prelude), dialect, open_instances)
    if cache_key in _BASES:
        base = _BASES[cache_key]
        if base is None or base.file is prelude:    # (a base keeps its file, so the id is its own)
            return base
    if len(_BASES) >= _MAX_BASES:
        _BASES.clear()
    base = _BASES[cache_key] = _build(prelude, dialect, open_instances)
    return base


def _build(prelude: ast.SourceFile, dialect: str, open_instances: bool) -> PreludeBase | None:
    from .declarations import Declarations    # (declarations imports this module)

    if not all(isinstance(item, ast.TypeDecl) or isinstance(item, ast.Pou) and item.sfc is None
               for item in prelude.items):
        return None      # globals, configurations or charts: not what a prelude declares
    program = CheckedProgram(files=[prelude])
    program.dialect = dialect
    ctx = Context(program, FastSink(), dialect, open_instances)
    decls = Declarations(ctx, record=True)
    try:
        decls.run([prelude])
    except Exception:     # the full check reports it, load by load
        return None
    if ctx.sink.items:
        return None
    pou_types = {k: program.types[k] for k in program.pous if k in program.types}
    return PreludeBase(
        file=prelude, dialect=dialect, open_instances=open_instances,
        names=dict(decls._names), pou_types=pou_types, types=dict(program.types),
        type_events={k: tuple(events) for k, events in decls.type_events.items()},
        program_tables={name: getattr(program, name) for name in _PROGRAM_TABLES},
        context_tables={name: getattr(ctx, name) for name in _CONTEXT_TABLES},
        interfaces_done=frozenset(decls._interfaces_done),
        enum_values={name: tuple(enums) for name, enums in ctx.enum_values.items()})
