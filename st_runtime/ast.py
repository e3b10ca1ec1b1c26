"""Abstract syntax tree of IEC 61131-3 Structured Text.

Every node is a small frozen dataclass.  Positions (`pos`) are kept for
diagnostics but excluded from equality, so two parses of the same program
compare equal even when their layout differs (the printer round trip relies
on it).  Identifiers keep the spelling of the source; ST is case-insensitive,
so consumers compare them through `key()` (upper case).

Tuples, never lists, hold children so that every node is hashable.
"""

from __future__ import annotations

from dataclasses import MISSING, dataclass, field
from typing import Union


@dataclass(frozen=True, slots=True)
class Pos:
    """A place in a source file: 1-based line and column."""

    file: str
    line: int
    col: int

    def __str__(self) -> str:
        return f"{self.file}:{self.line}:{self.col}"


NOWHERE = Pos("<builtin>", 0, 0)


def key(name: str) -> str:
    """The case-insensitive identity of an ST identifier."""
    return name.upper()


#: node class -> its fields but `pos`, in order (what every walk of the tree reads)
_FIELDS: dict[type, tuple[str, ...]] = {}


def fields_of(cls: type) -> tuple[str, ...]:
    """A node class's dataclass fields but `pos`, in declaration order, looked up once
    per class (the walks of the checker and compiler ask it of every node)."""
    names = _FIELDS.get(cls)
    if names is None:
        names = _FIELDS[cls] = tuple(name for name in cls.__dataclass_fields__ if name != "pos")
    return names


#: The annotations of fields that never hold a node (names, operators, flags, numbers).
_SCALARS = frozenset({"str", "str | None", "bool", "bool | None", "int", "int | None", "float",
                      "tuple[str, ...]"})


class _ChildFields(dict):
    """node class -> the fields of `fields_of(cls)` that may hold a node or a tuple of
    nodes, in order, worked out on first use: a walk of the tree need not look at the
    others (`Name.name`, `Binary.op`).  `CHILD_FIELDS[type(node)]`, one lookup."""

    def __missing__(self, cls: type) -> tuple[str, ...]:
        declared = cls.__dataclass_fields__
        names = self[cls] = tuple(name for name in fields_of(cls) if declared[name].type not in _SCALARS)
        return names


CHILD_FIELDS: dict[type, tuple[str, ...]] = _ChildFields()


@dataclass(frozen=True, slots=True)
class Node:
    pos: Pos = field(default=NOWHERE, compare=False, repr=False, kw_only=True)


# --------------------------------------------------------------------- types
# Type references as written in declarations; the checker resolves them.


@dataclass(frozen=True, slots=True)
class NamedType(Node):
    """An elementary type (`LREAL`), a user type, or an FB type, by name."""

    name: str


@dataclass(frozen=True, slots=True)
class StringType(Node):
    """`STRING` or `STRING[n]` (`length` None means the default, 80)."""

    length: Expr | None = None
    wide: bool = False


@dataclass(frozen=True, slots=True)
class Subrange(Node):
    lo: Expr
    hi: Expr


@dataclass(frozen=True, slots=True)
class SubrangeType(Node):
    """`INT (0..100)`: an integer type limited to a range."""

    base: str
    range: Subrange


@dataclass(frozen=True, slots=True)
class RefType(Node):
    """`REF_TO INT` (3rd ed. 6.4.4.10); `POINTER TO INT` in the codesys dialect."""

    target: TypeRef
    pointer: bool = False


@dataclass(frozen=True, slots=True)
class ArrayType(Node):
    """`ARRAY[lo..hi, ...] OF element` (up to three dimensions); a range of
    None is `*` (ARRAY[*] in a VAR_IN_OUT: the bounds come with the argument)."""

    ranges: tuple[Subrange | None, ...]
    element: TypeRef


@dataclass(frozen=True, slots=True)
class StructType(Node):
    """`STRUCT ... END_STRUCT` (or `UNION ... END_UNION`: the members share
    their storage), only inside a TYPE declaration."""

    members: tuple[VarDecl, ...]
    union: bool = False


@dataclass(frozen=True, slots=True)
class EnumValue(Node):
    name: str
    value: Expr | None = None


@dataclass(frozen=True, slots=True)
class EnumType(Node):
    """`(Red, Green := 5, Blue)`, only inside a TYPE declaration."""

    values: tuple[EnumValue, ...]


TypeRef = Union[NamedType, StringType, ArrayType, SubrangeType, RefType]
TypeSpec = Union[NamedType, StringType, ArrayType, SubrangeType, StructType, EnumType]


# --------------------------------------------------------------- expressions


@dataclass(frozen=True, slots=True)
class IntLiteral(Node):
    """An integer literal; `type_prefix` is e.g. `INT` for `INT#-5`."""

    value: int
    type_prefix: str | None = None


@dataclass(frozen=True, slots=True)
class RealLiteral(Node):
    value: float
    type_prefix: str | None = None


@dataclass(frozen=True, slots=True)
class BoolLiteral(Node):
    value: bool
    type_prefix: str | None = None


@dataclass(frozen=True, slots=True)
class StringLiteral(Node):
    """The decoded text (`$N` already a newline); `wide` for `"..."`."""

    value: str
    wide: bool = False


@dataclass(frozen=True, slots=True)
class TimeLiteral(Node):
    """A duration in integer nanoseconds (`T#1s500ms`, `TIME#-2.5s`)."""

    nanoseconds: int


@dataclass(frozen=True, slots=True)
class DateTimeLiteral(Node):
    """DATE, TIME_OF_DAY or DATE_AND_TIME; `value` in ns since epoch/midnight."""

    kind: str  # "DATE" | "TOD" | "DT"
    nanoseconds: int


@dataclass(frozen=True, slots=True)
class EnumLiteral(Node):
    """`Color#Red`: an enumeration value qualified by its type."""

    type_name: str
    value_name: str


@dataclass(frozen=True, slots=True)
class Name(Node):
    """A variable, constant, or unqualified enumeration value."""

    name: str


@dataclass(frozen=True, slots=True)
class Member(Node):
    """`base.name`: a struct member or FB instance variable."""

    base: Expr
    name: str


@dataclass(frozen=True, slots=True)
class Index(Node):
    """`base[i, j]`."""

    base: Expr
    indices: tuple[Expr, ...]


@dataclass(frozen=True, slots=True)
class Unary(Node):
    op: str  # "-" | "+" | "NOT"
    operand: Expr


@dataclass(frozen=True, slots=True)
class Binary(Node):
    """op is one of: ** * / MOD + - < > <= >= = <> AND XOR OR  (& is AND)."""

    op: str
    left: Expr
    right: Expr


@dataclass(frozen=True, slots=True)
class Deref(Node):
    """`r^`: the variable a reference refers to."""

    base: Expr


@dataclass(frozen=True, slots=True)
class BitAccess(Node):
    """`x.3`: bit 3 of an integer or bit-string variable (CODESYS, NJ); with a
    `size` the 3rd edition's partial access `x.%X3`, `w.%B1`, `d.%W0` (6.5.5.2)."""

    base: Expr
    bit: int
    size: str = ""          # "" (x.3) | X | B | W | D | L


@dataclass(frozen=True, slots=True)
class DirectVar(Node):
    """`%IX0.0`, `%QW3` used in code: a place of the process image (6.5.5)."""

    address: str


@dataclass(frozen=True, slots=True)
class NullLiteral(Node):
    """NULL: a reference (or interface variable) that refers to nothing."""


@dataclass(frozen=True, slots=True)
class Arg(Node):
    """One argument of a call.

    Positional: `name` is None.  Formal input `In := x`: direction "in".
    Formal output `Out => y`: direction "out" (value is the target);
    `NOT Out => y` sets `negated`.
    """

    name: str | None
    value: Expr | None
    direction: str = "in"  # "in" | "out"
    negated: bool = False


@dataclass(frozen=True, slots=True)
class Call(Node):
    """A function call, or (as a statement) an FB instance call.

    `callee` is a Name for functions and simple instances, or a Member/Index
    for `inst.sub(...)`, `fbs[i](...)`.
    """

    callee: Expr
    args: tuple[Arg, ...]
    trailing_comma: bool = False    # `F(a, b,)`: CODESYS accepts it, IEC does not


Expr = Union[
    IntLiteral, RealLiteral, BoolLiteral, StringLiteral, TimeLiteral,
    DateTimeLiteral, EnumLiteral, Name, Member, Index, Unary, Binary, Call,
]


# ---------------------------------------------------------------- statements


@dataclass(frozen=True, slots=True)
class Assign(Node):
    target: Expr
    value: Expr
    mode: str = ":="     # CODESYS "S=" (set the BOOL when value) / "R=" (reset)


@dataclass(frozen=True, slots=True)
class CallStmt(Node):
    call: Call


@dataclass(frozen=True, slots=True)
class IfBranch(Node):
    condition: Expr
    body: tuple[Stmt, ...]


@dataclass(frozen=True, slots=True)
class If(Node):
    """`branches[0]` is the IF, the rest the ELSIFs; `else_body` None = none."""

    branches: tuple[IfBranch, ...]
    else_body: tuple[Stmt, ...] | None = None


@dataclass(frozen=True, slots=True)
class CaseRange(Node):
    lo: Expr
    hi: Expr


@dataclass(frozen=True, slots=True)
class CaseClause(Node):
    """`labels` are expressions (constants, enum values) or CaseRanges."""

    labels: tuple[Expr | CaseRange, ...]
    body: tuple[Stmt, ...]


@dataclass(frozen=True, slots=True)
class Case(Node):
    selector: Expr
    clauses: tuple[CaseClause, ...]
    else_body: tuple[Stmt, ...] | None = None


@dataclass(frozen=True, slots=True)
class For(Node):
    variable: str
    start: Expr
    end: Expr
    step: Expr | None
    body: tuple[Stmt, ...]


@dataclass(frozen=True, slots=True)
class While(Node):
    condition: Expr
    body: tuple[Stmt, ...]


@dataclass(frozen=True, slots=True)
class Repeat(Node):
    body: tuple[Stmt, ...]
    condition: Expr


@dataclass(frozen=True, slots=True)
class Exit(Node):
    pass


@dataclass(frozen=True, slots=True)
class Continue(Node):
    pass


@dataclass(frozen=True, slots=True)
class Return(Node):
    pass


@dataclass(frozen=True, slots=True)
class Empty(Node):
    """A lone `;`."""


Stmt = Union[Assign, CallStmt, If, Case, For, While, Repeat, Exit, Continue, Return, Empty]


# -------------------------------------------------------------- declarations


@dataclass(frozen=True, slots=True)
class ArrayInitItem(Node):
    """`value` or `count(value)`; `count(())` is written `count()`: value None."""

    value: Initializer | None
    count: Expr | None = None


@dataclass(frozen=True, slots=True)
class ArrayInit(Node):
    items: tuple[ArrayInitItem, ...]


@dataclass(frozen=True, slots=True)
class FieldInit(Node):
    name: str
    value: Initializer


@dataclass(frozen=True, slots=True)
class StructInit(Node):
    fields: tuple[FieldInit, ...]


Initializer = Union[Expr, ArrayInit, StructInit]


@dataclass(frozen=True, slots=True)
class VarDecl(Node):
    """One variable (`a, b : INT` yields two VarDecls); pos is the name's."""

    name: str
    type: TypeRef
    init: Initializer | None = None
    edge: str | None = None     # "R_EDGE" | "F_EDGE" on an FB's BOOL input
    location: str | None = None  # "%IX0.0": a located variable (AT ...)


VAR_KINDS = (
    "VAR", "VAR_INPUT", "VAR_OUTPUT", "VAR_IN_OUT", "VAR_TEMP",
    "VAR_GLOBAL", "VAR_EXTERNAL",
)


@dataclass(frozen=True, slots=True)
class VarBlock(Node):
    kind: str  # one of VAR_KINDS
    decls: tuple[VarDecl, ...]
    constant: bool = False
    retain: bool = False


@dataclass(frozen=True, slots=True)
class TypeDecl(Node):
    """One entry of a TYPE ... END_TYPE block."""

    name: str
    spec: TypeSpec
    init: Initializer | None = None
    namespace: str = ""      # "A.B" inside NAMESPACE A.B (3rd ed. 6.9)


@dataclass(frozen=True, slots=True)
class Method(Node):
    """`METHOD PUBLIC Area : LREAL ... END_METHOD` (IEC 61131-3 3rd ed. 6.6.5)."""

    name: str
    var_blocks: tuple[VarBlock, ...]
    body: tuple[Stmt, ...]
    return_type: TypeRef | None = None
    access: str | None = None             # PUBLIC | PRIVATE | PROTECTED | INTERNAL
    modifiers: tuple[str, ...] = ()       # ABSTRACT, FINAL, OVERRIDE


@dataclass(frozen=True, slots=True)
class ActionAssociation(Node):
    """`Fill(N);` in a step: an action with its qualifier (IEC 61131-3 3rd ed. 6.7.4.5)."""

    action: str
    qualifier: str = "N"                  # N R S L D P SD DS SL P1 P0
    time: Expr | None = None              # L, D, SD, DS, SL: the duration
    indicator: str | None = None          # an indicator variable (table 59)


@dataclass(frozen=True, slots=True)
class Step(Node):
    """`INITIAL_STEP Start: ... END_STEP` or `STEP Fill: ... END_STEP` (6.7.2)."""

    name: str
    initial: bool
    actions: tuple[ActionAssociation, ...] = ()


@dataclass(frozen=True, slots=True)
class Transition(Node):
    """`TRANSITION FROM (A, B) TO C := cond; END_TRANSITION` (6.7.3)."""

    sources: tuple[str, ...]
    targets: tuple[str, ...]
    condition: Expr
    name: str | None = None


@dataclass(frozen=True, slots=True)
class Sfc(Node):
    """A POU body written as a Sequential Function Chart in its textual form (6.7)."""

    steps: tuple[Step, ...]
    transitions: tuple[Transition, ...]
    actions: tuple[Method, ...]           # ACTION name: ... END_ACTION (modifiers ("ACTION",))


@dataclass(frozen=True, slots=True)
class Pou(Node):
    kind: str  # "PROGRAM" | "FUNCTION" | "FUNCTION_BLOCK" | "INTERFACE"
    name: str
    var_blocks: tuple[VarBlock, ...]
    body: tuple[Stmt, ...]
    return_type: TypeRef | None = None  # FUNCTION only
    # 3rd edition object orientation (FUNCTION_BLOCK; INTERFACE: extends, methods)
    extends: tuple[str, ...] = ()
    implements: tuple[str, ...] = ()
    methods: tuple[Method, ...] = ()
    modifiers: tuple[str, ...] = ()       # ABSTRACT, FINAL
    namespace: str = ""                   # "A.B" inside NAMESPACE A.B (3rd ed. 6.9)
    sfc: Sfc | None = None                # a body in SFC (then `body` is empty)
    access: tuple[AccessPath, ...] = ()   # a PROGRAM's VAR_ACCESS


@dataclass(frozen=True, slots=True)
class TaskDecl(Node):
    name: str
    interval: Expr | None
    priority: Expr | None


@dataclass(frozen=True, slots=True)
class ProgramInstance(Node):
    name: str
    task: str | None
    program_type: str
    # `PROGRAM G : Gravel (Start := %IX0.0, Lamp => %QX4.0)` (3rd ed. 6.8.2, table 62)
    connections: tuple[Arg, ...] = ()


@dataclass(frozen=True, slots=True)
class AccessPath(Node):
    """`Name : Prog.Var : INT READ_ONLY;` in VAR_ACCESS (3rd ed. 6.8.2, table 62)."""

    name: str
    path: Expr
    type: TypeRef
    read_write: bool = False


@dataclass(frozen=True, slots=True)
class ConfigInit(Node):
    """`Res.Prog.Inst.Var AT %QX1.0 : BOOL := TRUE;` in VAR_CONFIG (3rd ed. 6.8.2)."""

    path: tuple[str, ...]
    type: TypeRef
    init: Initializer | None = None
    location: str | None = None


@dataclass(frozen=True, slots=True)
class Configuration(Node):
    """CONFIGURATION/RESOURCE/TASK: accepted, flattened to its contents."""

    name: str
    globals: tuple[VarBlock, ...]
    tasks: tuple[TaskDecl, ...]
    programs: tuple[ProgramInstance, ...]
    config_inits: tuple[ConfigInit, ...] = ()
    access: tuple[AccessPath, ...] = ()


Item = Union[Pou, TypeDecl, VarBlock, Configuration]


@dataclass(frozen=True, slots=True)
class SourceFile(Node):
    """A parsed file: POUs, type declarations, VAR_GLOBAL blocks in order."""

    path: str
    items: tuple[Item, ...]


# ------------------------------------------------------------ test files
# `stgen test` (st_runtime/testing): the blocks of a test file in STruC++'s
# form.  They appear only in the SourceFile that `parser.parse_tests` returns.


@dataclass(frozen=True, slots=True)
class TestSetup(Node):
    """SETUP [VAR ...] statements END_SETUP: run before each test of the file."""

    __test__ = False   # not a pytest class

    var_blocks: tuple[VarBlock, ...]
    body: tuple[Stmt, ...]


@dataclass(frozen=True, slots=True)
class TestTeardown(Node):
    """TEARDOWN statements END_TEARDOWN: run after each test of the file."""

    __test__ = False   # not a pytest class

    body: tuple[Stmt, ...]


@dataclass(frozen=True, slots=True)
class TestCase(Node):
    """TEST 'name' [VAR ...] statements END_TEST."""

    __test__ = False   # not a pytest class

    name: str
    var_blocks: tuple[VarBlock, ...]
    body: tuple[Stmt, ...]


# ------------------------------------------------------------ construction
# A parse makes thousands of nodes and positions.  A frozen dataclass's
# __init__ stores each field through `object.__setattr__(self, name, value)`;
# the one below stores it through the slot's own descriptor, which does the
# same at a third of the cost.  Same parameters (the fields in order, their defaults, `pos` keyword
# only), same stores, and no node class has a __post_init__ or a default_factory.


def _fast_init(cls: type) -> None:
    fields = list(cls.__dataclass_fields__.values())
    scope: dict = {}
    positional, keyword, stores = [], [], []
    for f in fields:
        scope[f"_set_{f.name}"] = getattr(cls, f.name).__set__
        if f.default is not MISSING:
            scope[f"_default_{f.name}"] = f.default
        spelled = f.name if f.default is MISSING else f"{f.name}=_default_{f.name}"
        (keyword if f.kw_only else positional).append(spelled)
        stores.append(f"    _set_{f.name}(self, {f.name})\n")
    parameters = ", ".join(["self", *positional] + (["*", *keyword] if keyword else []))
    exec(f"def __init__({parameters}):\n{''.join(stores)}", scope)
    init = scope["__init__"]
    init.__qualname__ = f"{cls.__qualname__}.__init__"
    init.__annotations__ = dict(cls.__init__.__annotations__)
    _DATACLASS_INITS[cls] = cls.__init__
    cls.__init__ = init


#: class -> the __init__ dataclass wrote (the tests compare the two)
_DATACLASS_INITS: dict[type, object] = {}

for _cls in [Pos] + [c for c in list(globals().values()) if isinstance(c, type) and issubclass(c, Node)]:
    _fast_init(_cls)
