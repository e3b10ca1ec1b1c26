"""State shared by the checker's passes: the program being built, the
diagnostics, and the name scopes."""

from __future__ import annotations

from dataclasses import dataclass, field

from .. import ast
from ..ast import key
from ..dialects import DIALECTS, Dialect, refusal
from ..diagnostics import ERROR, Diagnostic, DiagnosticSink
from ..symbols import CheckedProgram, PouInfo, Symbol
from .loop_writes import WriteGraph

BUILTIN_FILE = "<builtin>"


def a_or_an(word: str) -> str:
    """`word` after its indefinite article, for messages: "an INTERFACE", "a FUNCTION",
    "a UINT" (a U said as "you": UINT, USINT, UDINT, ULINT, UNION)."""
    return ("an " if word[0] in "AEIOaeio" else "a ") + word


@dataclass
class FastSink(DiagnosticSink):
    """A DiagnosticSink whose duplicate test is a set lookup, not a list scan
    (a file with thousands of faulty lines stays fast)."""

    seen: set = field(default_factory=set)

    def add(self, code: str, message: str, pos: ast.Pos, severity: str = ERROR) -> None:
        diag = Diagnostic(code, message, pos, severity)
        if diag not in self.seen:
            self.seen.add(diag)
            self.items.append(diag)


@dataclass(eq=False, init=False)
class Context:
    """What one check of a program gathers.  Made once a load: `__init__` written out, like
    CheckedProgram's."""

    program: CheckedProgram
    sink: DiagnosticSink
    dialect: str = "iec"
    open_instances: bool = False     # `stgen test`: every FB variable visible from outside
    # upper-case name -> declaration, for lazy type resolution
    type_decls: dict[str, ast.TypeDecl] = field(default_factory=dict)
    pou_decls: dict[str, ast.Pou] = field(default_factory=dict)
    # upper-case enumeration value -> enum types declaring it
    enum_values: dict[str, list] = field(default_factory=dict)
    # id(Symbol) -> folded value of a CONSTANT variable
    symbol_values: dict[int, object] = field(default_factory=dict)
    # every call of every body: caller -> [(callee, pos)], a node a POU's key or "FB.M" for a
    # METHOD (loop_writes.node_of); the recursion check takes the POUs' edges, W-ASSIGN-001 all
    calls: dict[str, list[tuple[str, ast.Pos]]] = field(default_factory=dict)
    # calls and writes gathered for the FOR control variable check (loop_writes.py)
    writes: WriteGraph = field(default_factory=WriteGraph)
    namespaces: set = field(default_factory=set)     # upper-case "A", "A.B"
    direct_types: dict = field(default_factory=dict)  # "%MW1" -> type declared AT it
    # id(item) -> what the structural walk (limits.check_files) found in it for later passes
    walked: dict = field(default_factory=dict)

    def __init__(self, program: CheckedProgram, sink: DiagnosticSink, dialect: str = "iec",
                 open_instances: bool = False) -> None:
        self.program = program
        self.sink = sink
        self.dialect = dialect
        self.open_instances = open_instances
        self.type_decls = {}
        self.pou_decls = {}
        self.enum_values = {}
        self.symbol_values = {}
        self.calls = {}
        self.writes = WriteGraph()
        self.namespaces = set()
        self.direct_types = {}
        self.walked = {}

    @property
    def rules(self) -> Dialect:
        """What the dialect refuses and how it names pins (st_runtime/dialects.py)."""
        return DIALECTS[self.dialect]

    def accepts(self, construct: str, pos: ast.Pos) -> bool:
        """Whether the dialect accepts `construct` (st_runtime/dialects.py CONSTRUCTS);
        if not, E-DIALECT-001 naming the dialects that would."""
        if self.rules.accepts(construct):
            return True
        self.error("E-DIALECT-001", refusal(construct, self.dialect), pos)
        return False

    def nj_rule(self, rule: str, message: str, pos: ast.Pos) -> None:
        """Report OMRON NJ rule `rule`: an error where the dialect refuses it, else a warning."""
        code = self.rules.nj_code(rule)
        (self.error if code.startswith("E") else self.warning)(code, message, pos)

    def foreign_pin(self, fb: str, name: str) -> str | None:
        """The E-PIN-001 message when `name` is not a pin of standard FB `fb` in this
        dialect but another dialect's name for one of its pins, else None."""
        found = self.rules.foreign_pin(fb, name)
        if found is None:
            return None
        other, mine = found
        return (f"{fb} has no pin '{name}' under --dialect {self.dialect}: that is the "
                f"{other} dialect's name; here the pin is '{mine}' (st_runtime/dialects.py)")

    def error(self, code: str, message: str, pos: ast.Pos) -> None:
        self.sink.error(code, message, pos)

    def warning(self, code: str, message: str, pos: ast.Pos) -> None:
        self.sink.warning(code, message, pos)

    def in_namespace(self, space: str, name: str) -> ast.Pou | ast.TypeDecl | None:
        """The POU or TYPE `name` declared in NAMESPACE `space` ("A.B"), else None: a
        qualified name `A.B.name` names an element of that namespace (IEC 61131-3 3rd
        ed. 6.9), never one of another namespace or of none.  POUs and TYPEs share one
        name space (a second declaration of a name is refused), so one table holds it."""
        k = key(name)
        item = self.pou_decls.get(k) or self.type_decls.get(k)
        return item if item is not None and key(item.namespace) == key(space) else None


class Scope:
    """Name lookup inside one POU (or at global level when `pou` is None)."""

    def __init__(self, ctx: Context, pou: PouInfo | None = None):
        self.ctx = ctx
        self.pou = pou
        # An FB's body and its methods also see the FB's variables and THIS.
        self.fb = pou.owner if pou is not None and pou.kind == "METHOD" else (
            pou if pou is not None and pou.kind == "FUNCTION_BLOCK" else None)
        self._this = None

    def lookup(self, name: str) -> Symbol | None:
        k = key(name)
        if self.pou is not None:
            sym = self.pou.variables.get(k)
            if sym is not None:
                return sym
            if self.fb is not None:
                sym = self.fb.variables.get(k)
                if sym is not None:
                    return sym
                if k == "THIS" and self.fb.owner is None and self.fb.kind == "FUNCTION_BLOCK":
                    if self._this is None:
                        self._this = Symbol("THIS", self.ctx.program.types[key(self.fb.name)], "THIS")
                    return self._this
        return self.ctx.program.globals.get(k)

    def is_local(self, sym: Symbol) -> bool:
        if self.pou is None:
            return False
        k = key(sym.name)
        return self.pou.variables.get(k) is sym or (
            self.fb is not None and self.fb.variables.get(k) is sym)
