"""Reuse inside an unrolled loop: array reads and `+ - *` results computed once.

A `Region` is active while an unrolled loop (unroll.py) is compiled, when its
body stores only plain Python locals (`how == "local"`) and calls nothing:
then no array element can change while the region runs (no store reaches an
array, no callee runs, no VAR_IN_OUT alias is written).  So:

* an element read at a constant index (`v_MATRIX[7]`) is read once, into a
  name set before the region (`reads`);
* a `+`, `-` or `*` whose operands are such names, literals or earlier
  shared results is computed once, where first needed, and reused
  (`shared`).  The text of the operation is its key: the same operands in
  the same order and grouping, so the reused value is the value the
  expression would have computed again (left-to-right partial products of
  the Leibniz terms are shared; nothing is reassociated).

A region also covers a whole POU body that qualifies and reads at least
`BODY_READS` array elements at literal indices (an unrolled loop written out
in the ST, such as the unrolled Leibniz determinant).

A new shared result is defined only in straight-line code of the region
(`straight`): code that is skipped would leave the name unset.  The element
reads may fault (an unconnected VAR_IN_OUT); the region then does not run:
the caller emits `if <reads succeeded>: <region> else: <the loop as before>`.
"""

from __future__ import annotations

import re
from dataclasses import replace

from ... import ast
from ..scope import walk
from . import TEMP_NAME, fuse, vector

_READ = re.compile(r"[A-Za-z_]\w*\[\d+\]")
_NUMBER = re.compile(r"-?\(?-?\d[\d.e+-]*\)?")


class Region:
    def __init__(self, temp):
        self.temp = temp
        self.reads: dict[str, str] = {}      # `v_A[7]` -> name read before the region
        self.shared: dict[str, str] = {}     # `(x * y)` -> name holding it
        self.names: set[str] = set()         # names that hold a value fixed for the region
        self.straight = True
        self.whole = None                    # the value expression of the assignment being compiled
        self.enclosing_straight = True       # `straight` outside the compound statement being compiled

    def read(self, code: str) -> str:
        if not _READ.fullmatch(code):
            return code
        name = self.reads.get(code)
        if name is None:
            name = self.reads[code] = self.temp()
            self.names.add(name)
        return name

    def fixed(self, code: str) -> bool:
        return code in self.names or bool(_NUMBER.fullmatch(code))

    def binary(self, op: str, left: str, right: str, out, define: bool = True) -> str | None:
        """The name of the shared `left op right`, or None when it cannot be shared.

        `define=False`: reuse only (the whole value of an assignment, which is
        stored at once and, when it repeats, found by the next use's lookup)."""
        if op not in ("+", "-", "*") or not (self.fixed(left) and self.fixed(right)):
            return None
        text = f"({left} {op} {right})"
        name = self.shared.get(text)
        if name is None:
            if not self.straight or not define:
                return None
            name = self.shared[text] = self.temp()
            self.names.add(name)
            out.line(f"{name} = {text}")
        return name


def region_allowed(compiler, body) -> bool:
    """Whether `body` stores only plain locals and calls nothing (see the module docstring)."""
    for node in walk(body):
        if isinstance(node, (ast.Call, ast.CallStmt)):
            return False
        if isinstance(node, ast.Assign):
            if not isinstance(node.target, ast.Name) or not _is_local(compiler, node.target):
                return False
        elif isinstance(node, ast.For):
            if not _is_local(compiler, ast.Name(node.variable, pos=node.pos)):
                return False
    return True


def _is_local(compiler, name) -> bool:
    place = compiler.scope.places.get(name.name.upper())
    return place is not None and place.how == "local"


BODY_READS = 8


def inline_single_uses(region, lines: list[str], start: int) -> None:
    """Put back a shared result used only once into its use (a name stored and read once
    costs more than it saves).  Exact: its operands are fixed for the region, and it
    cannot raise, so computing it at its use gives the same value."""
    shared = {name: text for text, name in region.shared.items()}
    uses: dict[str, list[int]] = {}
    for i in range(start, len(lines)):
        for name in TEMP_NAME.findall(lines[i]):
            if name in shared:
                uses.setdefault(name, []).append(i)
    removed = set()
    for name, where in uses.items():            # in order of first occurrence: the definition
        if len(where) != 2:
            continue
        definition, use = where
        head = lines[definition].lstrip()
        if not head.startswith(f"{name} = "):
            continue
        text = head[len(name) + 3:]
        lines[use] = _put_in(lines[use], name, text)
        # a later inlining may read this line again: keep `where` lists pointing at it
        removed.add(definition)
    lines[start:] = [line for i, line in enumerate(lines[start:], start) if i not in removed]


def _put_in(line: str, name: str, text: str) -> str:
    """`line` with `text` in place of the first occurrence of the temporary `name` (a whole
    word: the first `TEMP_NAME` token that is `name`)."""
    for match in TEMP_NAME.finditer(line):
        if match.group() == name:
            return line[:match.start()] + text + line[match.end():]
    return line


def worth_a_region(compiler, body) -> bool:
    """Whether a whole body qualifies for a region and reads enough elements at literal indices."""
    reads = sum(1 for node in walk(body) if isinstance(node, ast.Index)
                and all(isinstance(i, ast.IntLiteral) for i in node.indices))
    return reads >= BODY_READS and region_allowed(compiler, body)


def emit_region(compiler, compile_body) -> None:
    """`compile_body()` once in a region and once as before, chosen by whether the reads fault."""
    o = compiler.out
    region = compiler.region = Region(compiler.temp)
    flag = compiler.temp()
    mark = o.mark()
    o.line(f"if {flag}:")
    o.indent()
    inner = o.mark()
    flow = compiler.flow        # ranges.py: both paths start from the same state
    before = flow.state() if flow is not None else None
    try:
        compile_body()
    finally:
        compiler.region = None
    o.ensure_body(inner)
    close_region(o, region, mark, flag, compiler.opt.fuse, vector_hooks(compiler, region))
    inner = o.mark()
    saved = compiler.opt        # the path that never runs unless a read faults: kept small
    compiler.opt = replace(saved, unroll=False, cse=False)
    first = None
    if flow is not None:
        first = flow.state()
        flow.set(before)
    try:
        compile_body()
    finally:
        compiler.opt = saved
    if flow is not None:
        flow.join([first, flow.state()])
    o.ensure_body(inner)
    o.dedent()


def vector_hooks(compiler, region):
    """(is_float, register, element_of, bind) for vector.py when the `vector` pass is on,
    else None; `bind` (the namespace's setter) when the `native` pass is on and llvmlite is
    there (native.py)."""
    if not compiler.opt.vector:
        return None
    return (vector.float_names(compiler, region), compiler.unit.register_constant,
            vector.region_elements(compiler, region),
            compiler.unit.namespace.__setitem__ if compiler.opt.native and compiler.unit.native else None)


def _needed_reads(region, block: list[str]) -> list[tuple[str, str]]:
    """The element reads the block still uses, and each list's highest element read: that
    read faults exactly when one of the others would (a list has every lower index; an
    unconnected VAR_IN_OUT faults on any), so the region runs exactly when it ran before
    even where vector.py passes the list whole instead of its elements."""
    used = set(TEMP_NAME.findall("\n".join(block)))
    highest: dict[str, tuple[int, str]] = {}
    for code, name in region.reads.items():
        base, index = code[:-1].split("[", 1)
        if int(index) >= highest.get(base, (-1,))[0]:
            highest[base] = (int(index), name)
    probes = {name for _, name in highest.values()}
    return [(code, name) for code, name in region.reads.items() if name in used or name in probes]


def close_region(o, region, mark: int, flag: str, tidy: bool = False, hooks=None) -> None:
    """End the region's `if flag:` block (begun at `mark`): single uses put back, the
    element reads put before it (a fault there sets `flag` False), and `else:` opened.
    `tidy`: the lines go through fuse.py (stores no one sees skipped, temporaries renamed).
    `hooks` (vector_hooks): long runs of float arithmetic go to NumPy (vector.py)."""
    inline_single_uses(region, o.lines, mark + 1)
    if tidy:
        fuse.substitute(o.lines, mark + 1)
        fuse.merge(o.lines, mark + 1)
        fuse.rename(o.lines, mark + 1, region.temp)
    if hooks is not None:
        vector.vectorise(o.lines, mark + 1, len(o.lines), *hooks)
    o.dedent()
    reads = [f"{name} = {code}" for code, name in _needed_reads(region, o.lines[mark + 1:])]
    o.insert(mark, ["try:"] + ["    " + line for line in reads + [f"{flag} = True"]]
             + ["except _FAULTS:", f"    {flag} = False"])
    o.line("else:")
    o.indent()
