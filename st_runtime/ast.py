"""Abstract syntax tree of IEC 61131-3 Structured Text.

Every node is a small frozen dataclass.  Positions (`pos`) are kept for
diagnostics but excluded from equality, so two parses of the same program
compare equal even when their layout differs (the printer round trip relies
on it).  Identifiers keep the spelling of the source; ST is case-insensitive,
so consumers compare them through `key()` (upper case).

Tuples, never lists, hold children so that every node is hashable.
"""

from __future__ import annotations

from dataclasses import field
from typing import Union

from .frozen_dataclasses import frozen_dataclass, make_methods


@frozen_dataclass
class Pos:
    """A place in a source file: 1-based line and column."""

    file: str
    line: int
    col: int

    def __str__(self) -> str:
        return f"{self.file}:{self.line}:{self.col}"


make_methods([Pos])
NOWHERE = Pos("<builtin>", 0, 0)


#: The case-insensitive identity of an ST identifier: `str.upper` itself, so that a call
#: runs in C with no Python frame (a round of the accept corpus's checks calls it 5,800 times).
key = str.upper


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


@frozen_dataclass
class Node:
    pos: Pos = field(default=NOWHERE, compare=False, repr=False, kw_only=True)


# --------------------------------------------------------------------- types
# Type references as written in declarations; the checker resolves them.


@frozen_dataclass
class NamedType(Node):
    """An elementary type (`LREAL`), a user type, or an FB type, by name."""

    name: str


@frozen_dataclass
class StringType(Node):
    """`STRING` or `STRING[n]` (`length` None means the default, 80)."""

    length: Expr | None = None
    wide: bool = False


@frozen_dataclass
class Subrange(Node):
    lo: Expr
    hi: Expr


@frozen_dataclass
class SubrangeType(Node):
    """`INT (0..100)`: an integer type limited to a range."""

    base: str
    range: Subrange


@frozen_dataclass
class RefType(Node):
    """`REF_TO INT` (3rd ed. 6.4.4.10); `POINTER TO INT` in the codesys dialect."""

    target: TypeRef
    pointer: bool = False


@frozen_dataclass
class ArrayType(Node):
    """`ARRAY[lo..hi, ...] OF element` (up to three dimensions); a range of
    None is `*` (ARRAY[*] in a VAR_IN_OUT: the bounds come with the argument)."""

    ranges: tuple[Subrange | None, ...]
    element: TypeRef


@frozen_dataclass
class StructType(Node):
    """`STRUCT ... END_STRUCT` (or `UNION ... END_UNION`: the members share
    their storage), only inside a TYPE declaration."""

    members: tuple[VarDecl, ...]
    union: bool = False


@frozen_dataclass
class EnumValue(Node):
    name: str
    value: Expr | None = None


@frozen_dataclass
class EnumType(Node):
    """`(Red, Green := 5, Blue)`, only inside a TYPE declaration."""

    values: tuple[EnumValue, ...]


TypeRef = Union[NamedType, StringType, ArrayType, SubrangeType, RefType]
TypeSpec = Union[NamedType, StringType, ArrayType, SubrangeType, StructType, EnumType]


# --------------------------------------------------------------- expressions


@frozen_dataclass
class IntLiteral(Node):
    """An integer literal; `type_prefix` is e.g. `INT` for `INT#-5`."""

    value: int
    type_prefix: str | None = None


@frozen_dataclass
class RealLiteral(Node):
    value: float
    type_prefix: str | None = None


@frozen_dataclass
class BoolLiteral(Node):
    value: bool
    type_prefix: str | None = None


@frozen_dataclass
class StringLiteral(Node):
    """The decoded text (`$N` already a newline); `wide` for `"..."`."""

    value: str
    wide: bool = False


@frozen_dataclass
class TimeLiteral(Node):
    """A duration in integer nanoseconds (`T#1s500ms`, `TIME#-2.5s`)."""

    nanoseconds: int


@frozen_dataclass
class DateTimeLiteral(Node):
    """DATE, TIME_OF_DAY or DATE_AND_TIME; `value` in ns since epoch/midnight."""

    kind: str  # "DATE" | "TOD" | "DT"
    nanoseconds: int


@frozen_dataclass
class EnumLiteral(Node):
    """`Color#Red`: an enumeration value qualified by its type."""

    type_name: str
    value_name: str


@frozen_dataclass
class Name(Node):
    """A variable, constant, or unqualified enumeration value."""

    name: str


@frozen_dataclass
class Member(Node):
    """`base.name`: a struct member or FB instance variable."""

    base: Expr
    name: str


@frozen_dataclass
class Index(Node):
    """`base[i, j]`."""

    base: Expr
    indices: tuple[Expr, ...]


@frozen_dataclass
class Unary(Node):
    op: str  # "-" | "+" | "NOT"
    operand: Expr


@frozen_dataclass
class Binary(Node):
    """op is one of: ** * / MOD + - < > <= >= = <> AND XOR OR  (& is AND)."""

    op: str
    left: Expr
    right: Expr


@frozen_dataclass
class Deref(Node):
    """`r^`: the variable a reference refers to."""

    base: Expr


@frozen_dataclass
class BitAccess(Node):
    """`x.3`: bit 3 of an integer or bit-string variable (CODESYS, NJ); with a
    `size` the 3rd edition's partial access `x.%X3`, `w.%B1`, `d.%W0` (6.5.5.2)."""

    base: Expr
    bit: int
    size: str = ""          # "" (x.3) | X | B | W | D | L


@frozen_dataclass
class DirectVar(Node):
    """`%IX0.0`, `%QW3` used in code: a place of the process image (6.5.5)."""

    address: str


@frozen_dataclass
class NullLiteral(Node):
    """NULL: a reference (or interface variable) that refers to nothing."""


@frozen_dataclass
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


@frozen_dataclass
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


@frozen_dataclass
class Assign(Node):
    target: Expr
    value: Expr
    mode: str = ":="     # CODESYS "S=" (set the BOOL when value) / "R=" (reset)


@frozen_dataclass
class CallStmt(Node):
    call: Call


@frozen_dataclass
class IfBranch(Node):
    condition: Expr
    body: tuple[Stmt, ...]


@frozen_dataclass
class If(Node):
    """`branches[0]` is the IF, the rest the ELSIFs; `else_body` None = none."""

    branches: tuple[IfBranch, ...]
    else_body: tuple[Stmt, ...] | None = None


@frozen_dataclass
class CaseRange(Node):
    lo: Expr
    hi: Expr


@frozen_dataclass
class CaseClause(Node):
    """`labels` are expressions (constants, enum values) or CaseRanges."""

    labels: tuple[Expr | CaseRange, ...]
    body: tuple[Stmt, ...]


@frozen_dataclass
class Case(Node):
    selector: Expr
    clauses: tuple[CaseClause, ...]
    else_body: tuple[Stmt, ...] | None = None


@frozen_dataclass
class For(Node):
    variable: str
    start: Expr
    end: Expr
    step: Expr | None
    body: tuple[Stmt, ...]


@frozen_dataclass
class While(Node):
    condition: Expr
    body: tuple[Stmt, ...]


@frozen_dataclass
class Repeat(Node):
    body: tuple[Stmt, ...]
    condition: Expr


@frozen_dataclass
class Exit(Node):
    pass


@frozen_dataclass
class Continue(Node):
    pass


@frozen_dataclass
class Return(Node):
    pass


@frozen_dataclass
class Empty(Node):
    """A lone `;`."""


Stmt = Union[Assign, CallStmt, If, Case, For, While, Repeat, Exit, Continue, Return, Empty]


# -------------------------------------------------------------- declarations


@frozen_dataclass
class ArrayInitItem(Node):
    """`value` or `count(value)`; `count(())` is written `count()`: value None."""

    value: Initializer | None
    count: Expr | None = None


@frozen_dataclass
class ArrayInit(Node):
    items: tuple[ArrayInitItem, ...]


@frozen_dataclass
class FieldInit(Node):
    name: str
    value: Initializer


@frozen_dataclass
class StructInit(Node):
    fields: tuple[FieldInit, ...]


Initializer = Union[Expr, ArrayInit, StructInit]


@frozen_dataclass
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


@frozen_dataclass
class VarBlock(Node):
    kind: str  # one of VAR_KINDS
    decls: tuple[VarDecl, ...]
    constant: bool = False
    retain: bool = False


@frozen_dataclass
class TypeDecl(Node):
    """One entry of a TYPE ... END_TYPE block."""

    name: str
    spec: TypeSpec
    init: Initializer | None = None
    namespace: str = ""      # "A.B" inside NAMESPACE A.B (3rd ed. 6.9)


@frozen_dataclass
class Method(Node):
    """`METHOD PUBLIC Area : LREAL ... END_METHOD` (IEC 61131-3 3rd ed. 6.6.5)."""

    name: str
    var_blocks: tuple[VarBlock, ...]
    body: tuple[Stmt, ...]
    return_type: TypeRef | None = None
    access: str | None = None             # PUBLIC | PRIVATE | PROTECTED | INTERNAL
    modifiers: tuple[str, ...] = ()       # ABSTRACT, FINAL, OVERRIDE


@frozen_dataclass
class ActionAssociation(Node):
    """`Fill(N);` in a step: an action with its qualifier (IEC 61131-3 3rd ed. 6.7.4.5)."""

    action: str
    qualifier: str = "N"                  # N R S L D P SD DS SL P1 P0
    time: Expr | None = None              # L, D, SD, DS, SL: the duration
    indicator: str | None = None          # an indicator variable (table 59)


@frozen_dataclass
class Step(Node):
    """`INITIAL_STEP Start: ... END_STEP` or `STEP Fill: ... END_STEP` (6.7.2)."""

    name: str
    initial: bool
    actions: tuple[ActionAssociation, ...] = ()


@frozen_dataclass
class Transition(Node):
    """`TRANSITION FROM (A, B) TO C := cond; END_TRANSITION` (6.7.3)."""

    sources: tuple[str, ...]
    targets: tuple[str, ...]
    condition: Expr
    name: str | None = None


@frozen_dataclass
class Sfc(Node):
    """A POU body written as a Sequential Function Chart in its textual form (6.7)."""

    steps: tuple[Step, ...]
    transitions: tuple[Transition, ...]
    actions: tuple[Method, ...]           # ACTION name: ... END_ACTION (modifiers ("ACTION",))


@frozen_dataclass
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


@frozen_dataclass
class TaskDecl(Node):
    name: str
    interval: Expr | None
    priority: Expr | None


@frozen_dataclass
class ProgramInstance(Node):
    name: str
    task: str | None
    program_type: str
    # `PROGRAM G : Gravel (Start := %IX0.0, Lamp => %QX4.0)` (3rd ed. 6.8.2, table 62)
    connections: tuple[Arg, ...] = ()


@frozen_dataclass
class AccessPath(Node):
    """`Name : Prog.Var : INT READ_ONLY;` in VAR_ACCESS (3rd ed. 6.8.2, table 62)."""

    name: str
    path: Expr
    type: TypeRef
    read_write: bool = False


@frozen_dataclass
class ConfigInit(Node):
    """`Res.Prog.Inst.Var AT %QX1.0 : BOOL := TRUE;` in VAR_CONFIG (3rd ed. 6.8.2)."""

    path: tuple[str, ...]
    type: TypeRef
    init: Initializer | None = None
    location: str | None = None


@frozen_dataclass
class Configuration(Node):
    """CONFIGURATION/RESOURCE/TASK: accepted, flattened to its contents."""

    name: str
    globals: tuple[VarBlock, ...]
    tasks: tuple[TaskDecl, ...]
    programs: tuple[ProgramInstance, ...]
    config_inits: tuple[ConfigInit, ...] = ()
    access: tuple[AccessPath, ...] = ()


Item = Union[Pou, TypeDecl, VarBlock, Configuration]


@frozen_dataclass
class SourceFile(Node):
    """A parsed file: POUs, type declarations, VAR_GLOBAL blocks in order."""

    path: str
    items: tuple[Item, ...]


# ------------------------------------------------------------ test files
# `stgen test` (st_runtime/testing): the blocks of a test file in STruC++'s
# form.  They appear only in the SourceFile that `parser.parse_tests` returns.


@frozen_dataclass
class TestSetup(Node):
    """SETUP [VAR ...] statements END_SETUP: run before each test of the file."""

    __test__ = False   # not a pytest class

    var_blocks: tuple[VarBlock, ...]
    body: tuple[Stmt, ...]


@frozen_dataclass
class TestTeardown(Node):
    """TEARDOWN statements END_TEARDOWN: run after each test of the file."""

    __test__ = False   # not a pytest class

    body: tuple[Stmt, ...]


@frozen_dataclass
class TestCase(Node):
    """TEST 'name' [VAR ...] statements END_TEST."""

    __test__ = False   # not a pytest class

    name: str
    var_blocks: tuple[VarBlock, ...]
    body: tuple[Stmt, ...]


# ------------------------------------------------------------ construction
# Every node class is what @dataclass(frozen=True, slots=True) makes of it,
# its methods compiled in one go (frozen_dataclasses.py: a fifth of start-up).

make_methods([c for c in list(globals().values()) if isinstance(c, type) and issubclass(c, Node)])
