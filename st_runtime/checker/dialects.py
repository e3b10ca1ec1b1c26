"""Which dialect accepts which construct: data the checker consults.

`iec` is IEC 61131-3 3rd edition, strict.  `codesys` adds CODESYS/TwinCAT
constructs (POINTER TO, ADR).  `nj` is OMRON's NJ/NX (Sysmac Studio): what it
refuses is refused, with the source.  Each row: the construct, the dialects
that accept it, and why (a source, or what is still to be confirmed).  A
construct used under a dialect that refuses it is E-DIALECT-001, naming the
dialects that would accept it.
"""

from __future__ import annotations

from dataclasses import dataclass

from .. import ast

ALL = frozenset({"iec", "codesys", "nj"})

# Sysmac Studio's POUs are programs, function blocks and functions (NJ-series
# CPU Unit Software User's Manual W501, 6-2 "POUs"); the manual describes no
# METHOD, INTERFACE, inheritance, REF_TO or pointer.  This is an absence, not
# an explicit statement of OMRON's: to be confirmed against Sysmac Studio.
_NJ_NO_OO = "W501 6-2 lists programs, FBs and functions only (no OO; absence, to be confirmed)"


@dataclass(frozen=True, slots=True)
class Construct:
    what: str
    accepted_by: frozenset
    source: str


CONSTRUCTS = {
    "METHOD": Construct("METHOD", frozenset({"iec", "codesys"}), _NJ_NO_OO),
    "INTERFACE": Construct("INTERFACE", frozenset({"iec", "codesys"}), _NJ_NO_OO),
    "EXTENDS": Construct("EXTENDS", frozenset({"iec", "codesys"}), _NJ_NO_OO),
    "IMPLEMENTS": Construct("IMPLEMENTS", frozenset({"iec", "codesys"}), _NJ_NO_OO),
    "REF_TO": Construct("REF_TO", frozenset({"iec", "codesys"}), _NJ_NO_OO),
    "DEREF": Construct("the dereference ^", frozenset({"iec", "codesys"}), _NJ_NO_OO),
    "NULL": Construct("NULL", frozenset({"iec", "codesys"}), _NJ_NO_OO),
    "POINTER": Construct("POINTER TO", frozenset({"codesys"}),
                         "CODESYS extension; IEC 61131-3 3rd ed. has REF_TO instead"),
    "TRAILING_COMMA": Construct("a comma after the last argument", frozenset({"codesys"}),
                                "CODESYS accepts it; IEC 61131-3's grammar does not"),
    "UNION": Construct("UNION", frozenset({"codesys", "nj"}),
                        "CODESYS; the NJ has union data types (W501 6-7-2 lists union data type "
                        "names); not in IEC 61131-3"),
    "PROPERTY": Construct("PROPERTY", frozenset({"codesys"}), "CODESYS extension, not in IEC 61131-3"),
    "ACTION": Construct("ACTION", frozenset({"codesys"}), "CODESYS extension, not in IEC 61131-3"),
    "NAMESPACE": Construct("NAMESPACE", frozenset({"iec"}),
                           "IEC 61131-3 3rd ed. 6.9; the NJ has namespaces, set in Sysmac Studio and "
                           "written \\\\NS\\Name (W501 6-7)"),
    "SET_RESET": Construct("S= / R=", frozenset({"codesys"}), "CODESYS extension, not in IEC 61131-3"),
    "BIT_ACCESS": Construct("bit access x.3", frozenset({"codesys", "nj"}),
                            "CODESYS; the NJ specifies bits of integer variables the same "
                            "way (W501, section to be confirmed); not in IEC 61131-3"),
}


# What one unit of a number is when a TIME converts to or from it
# (TIME_TO_DINT, DINT_TO_TIME, ...), in nanoseconds.  The NJ counts
# nanoseconds (W501, TIME data type; its TimeToNanoSec / NanoSecToTime);
# CODESYS and TwinCAT count milliseconds (TIME is a 32-bit count of ms:
# TIME_TO_DINT(T#1s) = 1000).  IEC 61131-3 leaves it to the implementation;
# `iec` keeps the NJ's nanoseconds.
TIME_UNIT_NS = {"iec": 1, "nj": 1, "codesys": 1_000_000}


def accepting(name: str) -> str:
    return " or ".join(f"--dialect {d}" for d in sorted(CONSTRUCTS[name].accepted_by))


def check_dialect(ctx, files) -> None:
    """Report the first use, per file, of each construct the dialect refuses
    (one root cause, one diagnostic; the count says how many more)."""
    dialect = ctx.dialect
    for f in files:
        if f.path == "<builtin>":
            continue
        first: dict[str, ast.Pos] = {}
        count: dict[str, int] = {}
        for item in f.items:
            for name, pos in _constructs(item):
                if dialect not in CONSTRUCTS[name].accepted_by:
                    first[name] = min(first.get(name, pos), pos, key=lambda p: (p.line, p.col))
                    count[name] = count.get(name, 0) + 1
        for name, pos in first.items():
            more = f" ({count[name] - 1} more use(s) in this file)" if count[name] > 1 else ""
            ctx.error("E-DIALECT-001", f"{CONSTRUCTS[name].what} is not accepted by --dialect "
                      f"{dialect}; {accepting(name)} accepts it{more}", pos)


def _constructs(item):
    """(construct name, position) of each dialect-dependent construct in an item."""
    if getattr(item, "namespace", ""):
        yield "NAMESPACE", item.pos
    if isinstance(item, ast.Pou):
        if item.kind == "INTERFACE":
            yield "INTERFACE", item.pos
        if item.extends and item.kind == "FUNCTION_BLOCK":
            yield "EXTENDS", item.pos
        if item.implements:
            yield "IMPLEMENTS", item.pos
        for method in item.methods:
            kinds = set(method.modifiers)
            yield ("ACTION" if "ACTION" in kinds else "PROPERTY" if kinds & {"GET", "SET"}
                   else "METHOD"), method.pos
    stack = [item]
    while stack:
        node = stack.pop()
        if isinstance(node, tuple):
            stack.extend(node)
            continue
        if not isinstance(node, ast.Node):
            continue
        kind = type(node)
        if kind is ast.RefType:
            yield ("POINTER" if node.pointer else "REF_TO"), node.pos
        elif kind is ast.Deref:
            yield "DEREF", node.pos
        elif kind is ast.Assign and node.mode != ":=":
            yield "SET_RESET", node.pos
        elif kind is ast.Call and node.trailing_comma:
            yield "TRAILING_COMMA", node.pos
        elif kind is ast.StructType and node.union:
            yield "UNION", node.pos
        elif kind is ast.NullLiteral:
            yield "NULL", node.pos
        elif kind is ast.BitAccess and not node.size:      # x.%X3 is the standard's
            yield "BIT_ACCESS", node.pos
        for name in node.__dataclass_fields__:
            if name != "pos":
                value = getattr(node, name)
                if isinstance(value, (ast.Node, tuple)):
                    stack.append(value)
