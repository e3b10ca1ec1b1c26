"""Semantic types of IEC 61131-3 ST, as resolved by the checker.

Elementary types are singletons looked up by name (`ELEMENTARY["LREAL"]`).
Derived types (arrays, structs, enums, FB types) are built by the checker
from declarations.  The compiler reads the same objects to decide how to
store a value (wrap an integer, round a REAL to float32, copy an array).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Union

from .dialects import DIALECTS


@dataclass(frozen=True, slots=True)
class ElementaryType:
    """An elementary type.

    kind: "bool" | "int" | "bits" | "real" | "time" | "date" | "tod" | "dt"
    bits: storage width; `signed` for integers.
    """

    name: str
    kind: str
    bits: int
    signed: bool = False

    def __str__(self) -> str:
        return self.name

    @property
    def is_integer(self) -> bool:
        return self.kind == "int"

    @property
    def is_bit_string(self) -> bool:
        return self.kind in ("bits", "bool")

    @property
    def is_real(self) -> bool:
        return self.kind == "real"

    @property
    def is_numeric(self) -> bool:
        return self.kind in ("int", "real")

    @property
    def min(self) -> int:
        return -(1 << (self.bits - 1)) if self.signed else 0

    @property
    def max(self) -> int:
        return (1 << (self.bits - 1)) - 1 if self.signed else (1 << self.bits) - 1


@dataclass(frozen=True, slots=True)
class SubrangeType(ElementaryType):
    """`INT (0..100)` (IEC 61131-3 6.4.4.4): the integer type with a narrower range.

    It is its base type everywhere (same name, kind, width) except for the
    range: `min`/`max` are the limits, every store outside them is an
    F-SUBRANGE fault, a constant outside them is refused, and the default
    initial value is the lower limit (6.4.2).
    """

    lo: int = 0
    hi: int = 0

    def __str__(self) -> str:
        return f"{self.name} ({self.lo}..{self.hi})"

    @property
    def min(self) -> int:
        return self.lo

    @property
    def max(self) -> int:
        return self.hi


def subrange_of(base: ElementaryType, lo: int, hi: int) -> SubrangeType:
    return SubrangeType(base.name, base.kind, base.bits, base.signed, lo, hi)


def _elementary() -> dict[str, ElementaryType]:
    table = [
        ElementaryType("BOOL", "bool", 1),
        ElementaryType("SINT", "int", 8, True),
        ElementaryType("INT", "int", 16, True),
        ElementaryType("DINT", "int", 32, True),
        ElementaryType("LINT", "int", 64, True),
        ElementaryType("USINT", "int", 8),
        ElementaryType("UINT", "int", 16),
        ElementaryType("UDINT", "int", 32),
        ElementaryType("ULINT", "int", 64),
        ElementaryType("BYTE", "bits", 8),
        ElementaryType("WORD", "bits", 16),
        ElementaryType("DWORD", "bits", 32),
        ElementaryType("LWORD", "bits", 64),
        ElementaryType("REAL", "real", 32, True),
        ElementaryType("LREAL", "real", 64, True),
        ElementaryType("TIME", "time", 64, True),
        ElementaryType("DATE", "date", 64, True),
        ElementaryType("TIME_OF_DAY", "tod", 64, True),
        ElementaryType("DATE_AND_TIME", "dt", 64, True),
    ]
    types = {t.name: t for t in table}
    # Short names are the same types.
    types["TOD"] = types["TIME_OF_DAY"]
    types["DT"] = types["DATE_AND_TIME"]
    return types


ELEMENTARY: dict[str, ElementaryType] = _elementary()

BOOL = ELEMENTARY["BOOL"]
SINT = ELEMENTARY["SINT"]
INT = ELEMENTARY["INT"]
DINT = ELEMENTARY["DINT"]
LINT = ELEMENTARY["LINT"]
USINT = ELEMENTARY["USINT"]
UINT = ELEMENTARY["UINT"]
UDINT = ELEMENTARY["UDINT"]
ULINT = ELEMENTARY["ULINT"]
BYTE = ELEMENTARY["BYTE"]
WORD = ELEMENTARY["WORD"]
DWORD = ELEMENTARY["DWORD"]
LWORD = ELEMENTARY["LWORD"]
REAL = ELEMENTARY["REAL"]
LREAL = ELEMENTARY["LREAL"]
TIME = ELEMENTARY["TIME"]
DATE = ELEMENTARY["DATE"]
TOD = ELEMENTARY["TIME_OF_DAY"]
DT = ELEMENTARY["DATE_AND_TIME"]


@dataclass(frozen=True, slots=True)
class StringType:
    length: int = 80
    wide: bool = False

    def __str__(self) -> str:
        base = "WSTRING" if self.wide else "STRING"
        return f"{base}[{self.length}]"


#: What the n of STRING[n] counts, per dialect (st_runtime/dialects.py, `string_unit`,
#: has the sources), the same in the checker, the compiled code and values from outside.
STRING_UNITS = {name: d.string_unit for name, d in DIALECTS.items()}


def string_size(text: str, dialect: str = "iec") -> int:
    """The size of `text` in the units STRING[n] counts under `dialect`."""
    return len(text.encode("utf-8")) if STRING_UNITS.get(dialect) == "byte" else len(text)


def fit_string(text: str, length: int, dialect: str = "iec") -> str:
    """`text` cut to what STRING[length] holds under `dialect` (never half a UTF-8 character)."""
    if STRING_UNITS.get(dialect) != "byte":
        return text if len(text) <= length else text[:length]
    data = text.encode("utf-8")
    if len(data) <= length:
        return text
    return data[:length].decode("utf-8", "ignore")


@dataclass(frozen=True, slots=True)
class ArrayType:
    """`dims` are inclusive (lo, hi) pairs, first dimension first."""

    dims: tuple[tuple[int, int], ...]
    element: "Type"
    # The initial value of an element whose type is a TYPE declared with one
    # (`ARRAY[1..3] OF Speed` with `TYPE Speed : INT := 42`): the element type
    # above is resolved to INT, so the declaration's value travels here (AST).
    element_init: object = field(default=None, compare=False, hash=False, repr=False)

    def __str__(self) -> str:
        ranges = ", ".join("*" if lo is None else f"{lo}..{hi}" for lo, hi in self.dims)
        return f"ARRAY[{ranges}] OF {self.element}"

    @property
    def is_open(self) -> bool:
        """ARRAY[*]: the bounds are the argument's, known at run time only."""
        return any(lo is None for lo, _ in self.dims)

    @property
    def size(self) -> int:
        if self.is_open:          # ARRAY[*]: refers to the argument, holds nothing itself
            return 0
        n = 1
        for lo, hi in self.dims:
            n *= hi - lo + 1
        return n


@dataclass(eq=False, slots=True)
class StructType:
    """A named STRUCT; `fields` maps the upper-case name to (name, type)."""

    name: str
    fields: dict[str, tuple[str, "Type"]] = field(default_factory=dict)
    union: bool = False      # UNION: every member starts at byte 0 of one storage

    def __str__(self) -> str:
        return self.name


@dataclass(eq=False, slots=True)
class EnumType:
    """`values` maps the upper-case value name to (name as declared, int)."""

    name: str
    values: dict[str, tuple[str, int]] = field(default_factory=dict)
    base: ElementaryType = INT

    def __str__(self) -> str:
        return self.name


@dataclass(eq=False, slots=True)
class FBType:
    """A FUNCTION_BLOCK type, written in ST or native (Python)."""

    name: str
    # Upper-case variable name -> Symbol (see symbols.py), filled by the checker.
    variables: dict = field(default_factory=dict)
    native: object = None  # the Python class for native FBs
    info: object = None    # its PouInfo (methods, base FB, interfaces)

    def __str__(self) -> str:
        return self.name


@dataclass(frozen=True, slots=True)
class RefType:
    """`REF_TO T` (or codesys `POINTER TO T`): refers to a variable of type T,
    or to nothing (NULL).  At run time an elementary target is a Ref object
    (`get`/`set`), an array/struct/FB target the object itself, NULL None."""

    target: "Type"
    pointer: bool = False

    def __str__(self) -> str:
        return ("POINTER TO " if self.pointer else "REF_TO ") + str(self.target)


@dataclass(frozen=True, slots=True)
class NullType:
    """The type of NULL: stores into any reference or interface variable."""

    def __str__(self) -> str:
        return "NULL"


NULL = NullType()


@dataclass(eq=False, slots=True)
class InterfaceType:
    """An INTERFACE (3rd ed. 6.6.6): a variable of it refers to an FB instance
    that implements it (or holds nothing: NULL); `info` is its PouInfo."""

    name: str
    info: object = None

    def __str__(self) -> str:
        return self.name


@dataclass(frozen=True, slots=True)
class AliasType:
    """`TYPE Distance : LREAL; END_TYPE` resolves to its target; kept for names."""

    name: str
    target: "Type"

    def __str__(self) -> str:
        return self.name


Type = Union[ElementaryType, StringType, ArrayType, StructType, EnumType, FBType, InterfaceType,
             RefType, NullType]


def resolve_alias(t: "Type | AliasType") -> Type:
    while isinstance(t, AliasType):
        t = t.target
    return t
