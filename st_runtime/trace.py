"""Trace: record chosen variables every scan, write CSV, read it back, NumPy.

A watched path is an ST designator: `x`, `fb.Q`, `Axis.Cmd.Pos`, `a[3]`,
`m[1,2]`, `arr[2].Member`.  A path whose value is an array, a struct or an
FB instance expands to one column per elementary leaf, named like the ST
designator of that leaf (`Pose[1]` ... `Pose[6]`, `m[1,1]`, `fb.Q`, `fb.ET`).

Two ways to say where values come from:

* `Trace.for_objects(paths, roots)`: `roots` are ST objects (a PROGRAM
  instance, the globals object, ...) with their `_st_vars` layout; each path
  is resolved once into a chain of attribute/index steps, so a sample costs a
  few attribute loads per column.
* `Trace(paths, resolve, type_of=None)`: any callable `resolve(path) ->
  value`, called once per watched path and scan; `type_of(path) -> Type`
  tells how to expand arrays (their bounds).  Without it, STObjects expand
  by their layout and a list by 0-based position.

The CSV has a header row: `time_s` (seconds, exact decimal: the simulated
clock during the scan, (k - 1) * period for scan k, as `stgen demo`'s CSV), `scan`, then one
column per leaf.  Cells: BOOL as TRUE/FALSE, integers in decimal, REAL/LREAL
in shortest round-trip form, TIME/DATE/TOD/DT as IEC literals, strings as
they are.  `read_csv` turns each column back into a NumPy array (bool,
int64, float64, int64 nanoseconds for time literals, or str).
"""

from __future__ import annotations

import csv
import io
import itertools
import math
import re
from dataclasses import dataclass
from typing import Callable, Iterable

import numpy as np

from .types import ArrayType, ElementaryType, EnumType, FBType, StringType, StructType, resolve_alias
from .values import FORMATTERS, HIDDEN_KINDS, NS_PER_S, PARSERS, ValueFormatError, shortest_real32

Getter = Callable[[object], object]


class TracePathError(ValueError):
    """A watched path that does not name a variable."""


# ---------------------------------------------------------------------------
# Paths

_STEP = re.compile(r"\s*(?:\.\s*([A-Za-z_]\w*)|\[\s*([^\]]*)\])")
_HEAD = re.compile(r"\s*([A-Za-z_]\w*)")


def parse_path(path: str) -> list[tuple[str, object]]:
    """`a.b[1, 2].c` -> [("name", "a"), ("name", "b"), ("index", (1, 2)), ("name", "c")]."""
    m = _HEAD.match(path)
    if not m:
        raise TracePathError(f"{path!r}: a path starts with a variable name")
    steps: list[tuple[str, object]] = [("name", m.group(1))]
    pos = m.end()
    while pos < len(path.rstrip()):
        m = _STEP.match(path, pos)
        if not m:
            raise TracePathError(f"{path!r}: unexpected text at {path[pos:]!r}")
        if m.group(1):
            steps.append(("name", m.group(1)))
        else:
            try:
                steps.append(("index", tuple(int(p) for p in m.group(2).split(","))))
            except ValueError:
                raise TracePathError(f"{path!r}: array indices must be integer literals") from None
        pos = m.end()
    return steps


def _layout(obj) -> dict:
    layout = getattr(type(obj), "_st_vars", None)
    if layout is None:
        layout = getattr(obj, "_st_vars", None)
    return layout or {}


def _flat_index(t: ArrayType, index: tuple[int, ...], path: str) -> int:
    if len(index) != len(t.dims):
        raise TracePathError(f"{path!r}: {t} needs {len(t.dims)} indices, got {len(index)}")
    flat = 0
    for i, (lo, hi) in zip(index, t.dims):
        if not lo <= i <= hi:
            raise TracePathError(f"{path!r}: index {i} outside {lo}..{hi}")
        flat = flat * (hi - lo + 1) + (i - lo)
    return flat


def _attr_getter(attr: str) -> Getter:
    return lambda obj: getattr(obj, attr)


def _item_getter(i: int) -> Getter:
    return lambda seq: seq[i]


def _identity(value):
    return value


def _chain(getters: list[Getter]) -> Getter:
    getters = [g for g in getters if g is not _identity]
    if not getters:
        return _identity
    if len(getters) == 1:
        return getters[0]

    def get(obj):
        for g in getters:
            obj = g(obj)
        return obj
    return get


def resolve_in_objects(path: str, roots: Iterable[object]):
    """(root, getter from root, Type, canonical path) for a path, by layouts."""
    steps = parse_path(path)
    head = steps[0][1].upper()
    for root in roots:
        layout = _layout(root)
        if head in layout:
            break
    else:
        raise TracePathError(f"{path!r}: no variable named {steps[0][1]!r}")
    declared, t = layout[head]
    getters: list[Getter] = [_attr_getter("v_" + head)]
    text = declared
    for kind, arg in steps[1:]:
        t = resolve_alias(t)
        if kind == "index":
            if not isinstance(t, ArrayType):
                raise TracePathError(f"{path!r}: {text} is not an array")
            getters.append(_item_getter(_flat_index(t, arg, path)))
            text += "[" + ",".join(map(str, arg)) + "]"
            t = t.element
        else:
            members = _members_of_type(t)
            if members is None or arg.upper() not in members:
                raise TracePathError(f"{path!r}: {text} has no member {arg!r}")
            declared, t = members[arg.upper()]
            getters.append(_attr_getter("v_" + arg.upper()))
            text += "." + declared
    return root, _chain(getters), t, text


def _members_of_type(t) -> dict | None:
    t = resolve_alias(t)
    if isinstance(t, StructType):
        return dict(t.fields)
    if isinstance(t, FBType):   # the members JSON shows (no temps, in-outs, externals)
        return {key: (sym.name, sym.type) for key, sym in t.variables.items()
                if sym.kind not in HIDDEN_KINDS}
    return None


# ---------------------------------------------------------------------------
# Expansion of a value into leaf columns

@dataclass(frozen=True)
class Column:
    name: str
    get: Getter            # from the watched path's value to the leaf value
    type: object = None    # ElementaryType / StringType / EnumType, None if unknown


def _expand(name: str, t, sample) -> list[Column]:
    """Columns of one watched value of type `t` (None: infer from `sample`)."""
    t = resolve_alias(t) if t is not None else None
    if isinstance(t, ArrayType):
        columns = []
        ranges = [range(lo, hi + 1) for lo, hi in t.dims]
        for flat, index in enumerate(itertools.product(*ranges)):
            element_name = f"{name}[{','.join(map(str, index))}]"
            element = sample[flat] if sample is not None else None
            for col in _expand(element_name, t.element, element):
                columns.append(Column(col.name, _chain([_item_getter(flat), col.get]), col.type))
        return columns
    members = _members_of_type(t) if t is not None else None
    if members is None and t is None and sample is not None and _layout(sample):
        members = dict(_layout(sample))
    if members is not None:
        columns = []
        for key, (declared, mt) in members.items():
            attr = "v_" + key
            member = getattr(sample, attr, None) if sample is not None else None
            for col in _expand(f"{name}.{declared}", mt, member):
                columns.append(Column(col.name, _chain([_attr_getter(attr), col.get]), col.type))
        return columns
    if t is None and isinstance(sample, (list, tuple)):
        columns = []
        for i, element in enumerate(sample):
            for col in _expand(f"{name}[{i}]", None, element):
                columns.append(Column(col.name, _chain([_item_getter(i), col.get]), col.type))
        return columns
    return [Column(name, _identity, t)]


# ---------------------------------------------------------------------------
# Cell text

def _cell(value, t) -> str:
    if isinstance(t, ElementaryType):
        if t.kind in FORMATTERS:
            return FORMATTERS[t.kind](int(value))
        if t.kind == "bool":
            return "TRUE" if value else "FALSE"
        if t.kind == "real" and t.bits == 32:
            value = shortest_real32(float(value))   # 0.01, not its double 0.009999999776482582
    if isinstance(t, EnumType):
        for name, number in t.values.values():
            if number == value:
                return name
    if isinstance(value, bool):
        return "TRUE" if value else "FALSE"
    if isinstance(value, float):
        return repr(value) if math.isfinite(value) else ("nan" if math.isnan(value) else
                                                          ("inf" if value > 0 else "-inf"))
    return str(value)


def _seconds(ns: int) -> str:
    sign = "-" if ns < 0 else ""
    whole, frac = divmod(abs(ns), NS_PER_S)
    text = f"{sign}{whole}"
    if frac:
        text += "." + f"{frac:09d}".rstrip("0")
    return text


# ---------------------------------------------------------------------------
# The trace

class Trace:
    """Samples of watched variables, one row per scan."""

    def __init__(self, paths: list[str], resolve: Callable[[str], object],
                 type_of: Callable[[str], object] | None = None):
        self.paths = list(paths)
        self._sources: list[tuple[Callable[[], object], list[Column]]] = []
        for path in self.paths:
            t = type_of(path) if type_of else None
            source = (lambda p=path: resolve(p))
            self._sources.append((source, _expand(path, t, source())))
        self._init_rows()

    @classmethod
    def for_objects(cls, paths: list[str], roots: list[object]) -> "Trace":
        """A trace reading directly from ST objects (PROGRAM instance, globals)."""
        self = cls.__new__(cls)
        self.paths = list(paths)
        self._sources = []
        for path in self.paths:
            root, get, t, _ = resolve_in_objects(path, roots)
            source = (lambda r=root, g=get: g(r))
            self._sources.append((source, _expand(path.strip(), t, source())))
        self._init_rows()
        return self

    def _init_rows(self) -> None:
        self.columns: list[Column] = [c for _, cols in self._sources for c in cols]
        self.times_ns: list[int] = []
        self.scans: list[int] = []
        self.rows: list[tuple] = []
        # One getter per column that starts from the watched value.
        self._plan = [(source, tuple(c.get for c in cols)) for source, cols in self._sources]

    @property
    def column_names(self) -> list[str]:
        return [c.name for c in self.columns]

    def sample(self, time_ns: int, scan: int) -> None:
        """Record the current value of every column."""
        row = []
        for source, getters in self._plan:
            value = source()
            for get in getters:
                row.append(get(value))
        self.times_ns.append(time_ns)
        self.scans.append(scan)
        self.rows.append(tuple(row))

    def __len__(self) -> int:
        return len(self.rows)

    # -- output --------------------------------------------------------------

    def write_csv(self, target) -> None:
        """Write to a path or an open text file."""
        if isinstance(target, (str, bytes)) or hasattr(target, "__fspath__"):
            with open(target, "w", newline="", encoding="utf-8") as fh:
                self._write(fh)
        else:
            self._write(target)

    def _write(self, fh) -> None:
        writer = csv.writer(fh, lineterminator="\n")
        writer.writerow(["time_s", "scan"] + self.column_names)
        types = [c.type for c in self.columns]
        for t_ns, scan, row in zip(self.times_ns, self.scans, self.rows):
            writer.writerow([_seconds(t_ns), scan] + [_cell(v, t) for v, t in zip(row, types)])

    def to_csv_text(self) -> str:
        buf = io.StringIO()
        self._write(buf)
        return buf.getvalue()

    def to_numpy(self) -> dict[str, np.ndarray]:
        """`time` (s, float64), `time_ns`, `scan`, then one array per column."""
        out: dict[str, np.ndarray] = {
            "time": np.array(self.times_ns, dtype=np.int64) / NS_PER_S,
            "time_ns": np.array(self.times_ns, dtype=np.int64),
            "scan": np.array(self.scans, dtype=np.int64),
        }
        for i, col in enumerate(self.columns):
            values = [row[i] for row in self.rows]
            out[col.name] = _array(values, col.type)
        return out


def _array(values: list, t) -> np.ndarray:
    t = resolve_alias(t) if t is not None else None
    if isinstance(t, ElementaryType):
        if t.kind == "bool":
            return np.array(values, dtype=bool)
        if t.kind == "real":
            return np.array(values, dtype=np.float64)
        if t.kind in ("int", "bits") and not t.signed and t.bits == 64:
            return np.array(values, dtype=np.uint64)
        return np.array(values, dtype=np.int64)
    if isinstance(t, EnumType):
        return np.array(values, dtype=np.int64)
    if isinstance(t, StringType):
        return np.array(values, dtype=str)
    return _infer_array(values)


def _infer_array(values: list) -> np.ndarray:
    if values and all(isinstance(v, bool) for v in values):
        return np.array(values, dtype=bool)
    if values and all(isinstance(v, int) and not isinstance(v, bool) for v in values):
        try:
            return np.array(values, dtype=np.int64)
        except OverflowError:
            return np.array(values, dtype=np.uint64)
    if values and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values):
        return np.array(values, dtype=np.float64)
    return np.array(values, dtype=str if all(isinstance(v, str) for v in values) else object)


# ---------------------------------------------------------------------------
# Reading back

_INT_CELL = re.compile(r"^[+-]?\d+$")
_TIME_PARSERS = (("T#", PARSERS["time"]), ("D#", PARSERS["date"]),
                 ("TOD#", PARSERS["tod"]), ("DT#", PARSERS["dt"]))


def _parse_column(cells: list[str]) -> np.ndarray:
    if not cells:
        return np.array([], dtype=np.float64)
    upper = [c.strip().upper() for c in cells]
    if all(c in ("TRUE", "FALSE") for c in upper):
        return np.array([c == "TRUE" for c in upper], dtype=bool)
    if all(_INT_CELL.match(c) for c in upper):
        ints = [int(c) for c in upper]
        try:
            return np.array(ints, dtype=np.int64)
        except OverflowError:
            return np.array(ints, dtype=np.uint64)
    for prefix, parse in sorted(_TIME_PARSERS, key=lambda p: -len(p[0])):
        if all(c.startswith(prefix) for c in upper):
            try:
                return np.array([parse(c) for c in cells], dtype=np.int64)
            except ValueFormatError:
                break
    try:
        return np.array([float(c) for c in cells], dtype=np.float64)
    except ValueError:
        return np.array(cells, dtype=str)


def read_csv(source) -> dict[str, np.ndarray]:
    """A trace CSV (path or open text file) as {column: array}.

    `time` comes back in seconds (float64) and, exactly, as `time_ns`.
    """
    if isinstance(source, (str, bytes)) or hasattr(source, "__fspath__"):
        with open(source, newline="", encoding="utf-8") as fh:
            rows = list(csv.reader(fh))
    else:
        rows = list(csv.reader(source))
    if not rows or rows[0][:2] not in (["time_s", "scan"], ["time", "scan"]):   # "time": before units
        raise ValueError("not a trace CSV: the header must start with time_s,scan")
    header, body = rows[0], rows[1:]
    columns = list(zip(*body)) if body else [[] for _ in header]
    out: dict[str, np.ndarray] = {}
    out["time_ns"] = np.array([_parse_seconds(c) for c in columns[0]], dtype=np.int64)
    out["time"] = out["time_ns"] / NS_PER_S
    out["scan"] = np.array([int(c) for c in columns[1]], dtype=np.int64)
    for name, cells in zip(header[2:], columns[2:]):
        out[name] = _parse_column(list(cells))
    return out


def _parse_seconds(text: str) -> int:
    sign = -1 if text.startswith("-") else 1
    whole, _, frac = text.lstrip("+-").partition(".")
    return sign * (int(whole) * NS_PER_S + int(frac.ljust(9, "0")[:9] or 0))
