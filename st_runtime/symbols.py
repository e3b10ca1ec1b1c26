"""The checked program: what the checker hands to the compiler.

The checker fills these tables once; the compiler and the runtime only read
them.  Expression types are kept in a side table keyed by `id(node)` (the AST
is immutable and lives as long as the CheckedProgram, so ids are stable).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from . import ast
from .types import Type


@dataclass(eq=False, slots=True)
class Symbol:
    """A declared variable of a POU, a global, or a struct member."""

    name: str              # as declared
    type: Type
    kind: str              # one of ast.VAR_KINDS, or "RETURN" for a function's result
    decl: ast.VarDecl | None = None
    constant: bool = False
    retain: bool = False
    init: ast.Initializer | None = None


@dataclass(eq=False, slots=True)
class PouInfo:
    """A POU with its resolved variables in declaration order."""

    name: str
    kind: str                                   # PROGRAM | FUNCTION | FUNCTION_BLOCK
    node: ast.Pou | None                        # None for native POUs
    variables: dict[str, Symbol] = field(default_factory=dict)   # upper-case name ->
    return_type: Type | None = None
    file: str = "<builtin>"
    native: object = None                       # Python class/function for native POUs
    # 3rd edition object orientation.  A METHOD is a PouInfo of kind "METHOD"
    # whose `owner` is its FUNCTION_BLOCK (or INTERFACE); `methods` holds an
    # FB's methods by upper-case name, inherited ones included.
    owner: "PouInfo | None" = None
    parent: "PouInfo | None" = None             # the FB this one EXTENDS
    methods: dict = field(default_factory=dict)
    interfaces: tuple = ()                      # PouInfos of the INTERFACEs implemented
    access: str | None = None                   # METHOD: PUBLIC | PRIVATE | PROTECTED | INTERNAL
    modifiers: tuple = ()                       # ABSTRACT, FINAL, OVERRIDE

    def descends_from(self, other: "PouInfo") -> bool:
        """This FB is `other` or extends it (directly or not)."""
        info = self
        while info is not None:
            if info is other:
                return True
            info = info.parent
        return False

    def implements(self, interface: "PouInfo") -> bool:
        info = self
        while info is not None:
            if any(i is interface or i.extends_interface(interface) for i in info.interfaces):
                return True
            info = info.parent
        return False

    def extends_interface(self, interface: "PouInfo") -> bool:
        return any(i is interface or i.extends_interface(interface) for i in self.interfaces)

    def of_kind(self, *kinds: str) -> list[Symbol]:
        return [s for s in self.variables.values() if s.kind in kinds]

    @property
    def inputs(self) -> list[Symbol]:
        return self.of_kind("VAR_INPUT")

    @property
    def outputs(self) -> list[Symbol]:
        return self.of_kind("VAR_OUTPUT")

    @property
    def in_outs(self) -> list[Symbol]:
        return self.of_kind("VAR_IN_OUT")

    @property
    def result(self) -> Symbol | None:
        """A FUNCTION's or METHOD's result, the variable named like it (kind RETURN), else None."""
        symbol = self.variables.get(ast.key(self.name))
        return symbol if symbol is not None and symbol.kind == "RETURN" else None


@dataclass(frozen=True, slots=True)
class CallTarget:
    """How a Call node was resolved.

    kind: "function" (user or standard function: `name` is its upper-case
    name), "fb" (an FB instance call: `fb_type` is the FBType), or
    "conversion" (`A_TO_B`), "super_body" (CODESYS's `SUPER^()`: `name` is the
    base FB).  `generic_type` is the type a generic standard
    function was instantiated at (e.g. LREAL for MAX on LREAL operands).
    """

    kind: str
    name: str
    pou: PouInfo | None = None
    generic_type: Type | None = None


@dataclass(eq=False, init=False)
class CheckedProgram:
    """Everything the compiler needs, resolved and typed.  Made once a load: its `__init__`
    is written out (`{}` for each table) where the dataclass's tests a sentinel and calls
    the field's factory, eight bytecodes a table more (tests/test_checker_tables.py holds
    the two to the same fields)."""

    files: list[ast.SourceFile]
    types: dict[str, Type] = field(default_factory=dict)           # upper-case name ->
    pous: dict[str, PouInfo] = field(default_factory=dict)         # upper-case name ->
    globals: dict[str, Symbol] = field(default_factory=dict)       # upper-case name ->
    expr_types: dict[int, Type] = field(default_factory=dict)      # id(expr) ->
    call_targets: dict[int, CallTarget] = field(default_factory=dict)  # id(Call) ->
    # id(Name) -> the Symbol it refers to, or an int for an enum value.
    name_refs: dict[int, object] = field(default_factory=dict)
    # id(expr) -> value, for expressions the checker folded to a constant.
    constants: dict[int, object] = field(default_factory=dict)
    sources: dict[str, str] = field(default_factory=dict)          # path -> text
    dialect: str = "iec"                                           # "iec" or "nj", as checked
    # Added by the checker: id(For) -> the Symbol of its control variable.
    for_vars: dict[int, Symbol] = field(default_factory=dict)
    # id(expr) -> the subrange a place (variable, element, member, dereference) is declared
    # with; its `expr_types` entry is the base type it reads as (IEC 61131-3 6.4.4.4).
    subranges: dict[int, Type] = field(default_factory=dict)
    # id(Call) -> the operator expression a call such as ADD(a, b) stands for.
    lowered: dict[int, ast.Expr] = field(default_factory=dict)
    dialect: str = "iec"                                           # --dialect checked under
    # id(Member) -> (getter, setter) PouInfos of a PROPERTY read or written there.
    properties: dict[int, tuple] = field(default_factory=dict)
    # (Address, type, initializer) of unnamed located variables (`AT %QX0.1 : BOOL := 1;`)
    image_inits: list = field(default_factory=list)
    # id(Call) -> (EN expression or None, ENO Arg or None, the call without them).
    enables: dict[int, tuple] = field(default_factory=dict)
    # The shared checked prelude this program's native declarations come from
    # (checker/prelude_base.py), or None; the compiler shares its classes too.
    prelude: object = None

    def __init__(self, files: list[ast.SourceFile], dialect: str = "iec") -> None:
        self.files = files
        self.types = {}
        self.pous = {}
        self.globals = {}
        self.expr_types = {}
        self.call_targets = {}
        self.name_refs = {}
        self.constants = {}
        self.sources = {}
        self.dialect = dialect
        self.for_vars = {}
        self.subranges = {}
        self.lowered = {}
        self.properties = {}
        self.image_inits = []
        self.enables = {}
        self.prelude = None

    def type_of(self, expr: ast.Node) -> Type:
        return self.expr_types[id(expr)]
