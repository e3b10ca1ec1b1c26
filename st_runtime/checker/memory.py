"""The memory model: how many bytes each variable needs, from its type, and a
diagnostic where a variable, a POU instance or the whole project needs more
than a limit (issue 15: `ARRAY[0..9999999] OF ARRAY[0..999] OF LREAL` or
`STRING[2000000000]` passed the checker and then allocated until the process
died).

Sizes follow OMRON's allocation rules for NJ/NX variables (NJ-series CPU Unit
Software User's Manual W501, appendix "Variable memory allocation", and the
NJ/NX Built-in EtherNet/IP Port User's Manual W506, A-47: the table of
alignments and amounts per data type):

| type | alignment | bytes |
|---|---|---|
| BOOL | 2 | 2 (a BOOL array: 2 bytes per 16 elements, rounded up) |
| BYTE, USINT, SINT | 1 | 1 |
| WORD, UINT, INT | 2 | 2 |
| DWORD, UDINT, DINT, REAL | 4 | 4 |
| LWORD, ULINT, LINT, LREAL, TIME, DATE, TOD, DT | 8 | 8 |
| STRING[n] (n characters) | 1 | n + 1 (the NULL) |
| enumeration | 4 | 4 |
| array | of its element | element bytes x elements |
| structure | largest of its members | members at multiples of their alignment, rounded up to the structure's |

Assumed (OMRON gives no rule we found): WSTRING[n] as 2(n + 1) bytes with
alignment 2; an FB instance laid out like a structure of its own variables
(VAR_IN_OUT as an 8-byte reference); a REF_TO (POINTER TO) or INTERFACE
variable as an 8-byte reference as well (the NJ has neither; issue 16: they
counted 0 bytes, so `ARRAY[0..99999999] OF REF_TO INT` passed the limit). The runtime's own memory per element
is larger (Python objects), so the default limit is well below what would
exhaust a machine.

Limits: every variable, every POU instance (its variables) and the project
(globals plus one instance of every PROGRAM) must fit in `limit` bytes
(default DEFAULT_LIMIT, configurable through `check(..., memory_limit=)`).
Under `--dialect nj`, where STRING[n] means n bytes with the NULL as in
Sysmac Studio, n is at most NJ_STRING_MAX_BYTES (the NJ's largest STRING,
1,986 bytes including the NULL: devicewise's OMRON NJ/NX
driver notes, https://docs.devicewise.com/Content/Products/GatewayDevelopersGuide/Devices/DeviceTypes/Omron/Omron-NJ-or-NX-supported-access.htm;
not found in an OMRON manual). The NJ's limits on elements per array
dimension and on total variable memory per CPU model were not found: not
checked.
"""

from __future__ import annotations

from itertools import islice

from .. import types as T
from ..dialects import DIALECTS
from ..diagnostics import register
from .context import BUILTIN_FILE
from .typesys import innermost

#: Bytes a variable, a POU instance or the project may need by default (64 MiB).
DEFAULT_LIMIT = 64 * 2**20
#: The NJ's largest STRING: 1,986 bytes including the terminating NULL.
NJ_STRING_MAX_BYTES = DIALECTS["nj"].string_max_bytes

register({
    "E-LIMIT-008": "a variable needs more memory than the limit",
    "E-LIMIT-009": "a POU instance needs more memory than the limit",
    "E-LIMIT-010": "the project's variables need more memory than the limit",
    "E-LIMIT-011": "a STRING longer than the NJ's 1,986 bytes (--dialect nj)",
})

_ELEMENTARY = {"bool": (2, 2), "time": (8, 8), "date": (8, 8), "tod": (8, 8), "dt": (8, 8)}
# Variables an instance stores (VAR_EXTERNAL is the global's, VAR_TEMP lives during a call only).
_STORED = ("VAR", "VAR_INPUT", "VAR_OUTPUT", "VAR_IN_OUT", "RETURN")
_REFERENCE = (8, 8)


def _elementary_layout(t: T.ElementaryType) -> tuple[int, int]:
    if t.kind in _ELEMENTARY:
        return _ELEMENTARY[t.kind]
    size = max(1, t.bits // 8)
    return size, size


#: id of each elementary type (a singleton, alive for the process) -> its layout, computed once
#: a process where each load's MemoryModel computed it again (a subrange is laid out as met).
_ELEMENTARY_LAYOUTS = {id(t): _elementary_layout(t) for t in T.ELEMENTARY.values()}


class MemoryModel:
    """Bytes and alignment of types, memoised (a type is laid out once)."""

    def __init__(self) -> None:
        self._layouts: dict[int, tuple[int, int]] = dict(_ELEMENTARY_LAYOUTS)

    def layout(self, t) -> tuple[int, int]:
        """(bytes, alignment) of a value of type `t` (the checker's types hold no alias: a TYPE
        alias maps to its target, `checker/__init__.py`)."""
        known = self._layouts.get(id(t))
        if known is not None:
            return known
        self._layouts[id(t)] = (0, 1)       # a cycle (refused elsewhere) counts nothing
        result = self._compute(t)
        self._layouts[id(t)] = result
        return result

    def _compute(self, t) -> tuple[int, int]:
        if isinstance(t, T.ElementaryType):
            return _elementary_layout(t)
        if isinstance(t, T.StringType):
            return ((t.length + 1) * 2, 2) if t.wide else (t.length + 1, 1)
        if isinstance(t, T.EnumType):
            return 4, 4
        if isinstance(t, T.ArrayType):
            element = t.element
            if isinstance(element, T.ElementaryType) and element.kind == "bool":
                return 2 * ((t.size - 1) // 16 + 1), 2
            size, align = self.layout(element)
            return size * t.size, align
        if isinstance(t, T.StructType):
            return _pack(self.layout(member) for _, member in t.fields.values())
        if isinstance(t, T.FBType):
            return _pack(_REFERENCE if sym.kind == "VAR_IN_OUT" else self.layout(sym.type)
                         for sym in t.variables.values() if sym.kind in _STORED)
        if isinstance(t, (T.RefType, T.InterfaceType)):
            return _REFERENCE
        return 0, 1


def _pack(members) -> tuple[int, int]:
    """Members in order, each at a multiple of its alignment; the whole
    rounded up to the largest alignment (OMRON's structure rule)."""
    offset, largest = 0, 1
    for size, align in members:
        offset = -(-offset // align) * align + size
        largest = max(largest, align)
    return -(-offset // largest) * largest, largest


def check_memory(ctx, limit: int | None = None) -> None:
    """Report each variable, POU instance and the project beyond `limit`
    bytes, and (dialect nj) each STRING beyond the NJ's largest."""
    limit = DEFAULT_LIMIT if limit is None else limit
    program = ctx.program
    model = MemoryModel()
    layout = model.layout
    string_max = ctx.rules.string_max_bytes

    def variable_bytes(sym, owner: str) -> int:
        size = _REFERENCE[0] if sym.kind == "VAR_IN_OUT" else model.layout(sym.type)[0]
        if sym.decl is not None:
            if size > limit:
                ctx.error("E-LIMIT-008", f"{owner}{sym.name} needs {size:,} bytes ({sym.type}), above the"
                          f" memory limit of {limit:,} bytes", sym.decl.pos)
            if string_max is not None:
                _nj_strings(ctx, sym)
        return size

    reported = len(ctx.sink.items)
    total = 0
    for sym in program.globals.values():
        total += variable_bytes(sym, "global ")
    pous = iter(program.pous.values())
    base = program.prelude      # the shared prelude's POUs lead the table
    if base is not None and _within(base.memo("bytes", lambda: _sizes(base.pous.values())), limit,
                                    string_max):
        pous = islice(pous, len(base.pous), None)   # within the limit: nothing to report or count
    for info in pous:
        if info.node is None:
            continue
        stored = [s for s in info.variables.values() if s.kind in _STORED]
        owner, instance = f"{info.name}.", 0
        for sym in stored:
            size = _REFERENCE[0] if sym.kind == "VAR_IN_OUT" else layout(sym.type)[0]
            if size > limit or string_max is not None:     # (something to report: said there)
                size = variable_bytes(sym, owner)
            instance += size
        if instance > limit and not any(variable_bytes_over(model, s, limit) for s in stored):
            ctx.error("E-LIMIT-009", f"an instance of {info.name} needs {instance:,} bytes, above the memory"
                      f" limit of {limit:,} bytes", info.node.pos)
        if info.kind == "PROGRAM":
            total += instance
    if total > limit and len(ctx.sink.items) == reported:     # not already said variable by variable
        # at the project's first POU (the prelude's TON leads the table), else its first global
        places = [info.node.pos for info in program.pous.values() if info.node is not None] + \
            [sym.decl.pos for sym in program.globals.values() if sym.decl is not None]
        first = next((pos for pos in places if pos.file != BUILTIN_FILE), None)
        if first is not None:
            ctx.error("E-LIMIT-010", f"the project's variables need {total:,} bytes (globals and one"
                      f" instance of each PROGRAM), above the memory limit of {limit:,} bytes", first)


def _sizes(pous) -> tuple:
    """(largest variable, largest instance, a STRING anywhere, a PROGRAM among them) of POUs."""
    model = MemoryModel()
    largest = instance = 0
    strings = program = False
    for info in pous:
        if info.node is None:
            continue
        sizes = [_REFERENCE[0] if s.kind == "VAR_IN_OUT" else model.layout(s.type)[0]
                 for s in info.variables.values() if s.kind in _STORED]
        largest, instance = max([largest, *sizes]), max(instance, sum(sizes))
        strings = strings or any(isinstance(innermost(s.type), T.StringType) for s in info.variables.values())
        program = program or info.kind == "PROGRAM"
    return largest, instance, strings, program


def _within(sizes: tuple, limit: int, string_max) -> bool:
    """Whether check_memory would say nothing of a POU of these `_sizes` and count none of it."""
    largest, instance, strings, program = sizes
    return largest <= limit and instance <= limit and not program and not (strings and string_max is not None)


def variable_bytes_over(model: MemoryModel, sym, limit: int) -> bool:
    """Whether this one variable is already beyond the limit (reported on its own)."""
    return sym.kind != "VAR_IN_OUT" and model.layout(sym.type)[0] > limit


def _nj_strings(ctx, sym) -> None:
    """E-LIMIT-011 for a STRING (or an array of them) beyond the NJ's largest."""
    t = innermost(sym.type)
    # In Sysmac Studio STRING[n] reserves n bytes, the NULL included (W501: "STRING[11]" for 10 characters).
    if isinstance(t, T.StringType) and not t.wide and t.length > NJ_STRING_MAX_BYTES:
        ctx.error("E-LIMIT-011", f"{sym.name}: {t} is longer than the NJ's largest STRING,"
                  f" STRING[{NJ_STRING_MAX_BYTES}] ({NJ_STRING_MAX_BYTES:,} bytes with the NULL)", sym.decl.pos)
