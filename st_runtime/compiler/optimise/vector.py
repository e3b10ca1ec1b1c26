"""`vector`: a long straight run of floating-point `+ - *` in a CSE region, computed with NumPy.

After cse.py and fuse.py a Leibniz determinant is ~1,500 lines of Python such as
`_t7 = (_t2 * _t3)` and `v_D = ((v_D + ((_t7 * _t9) * _t11)) - ...)`: 2,670 float
operations, each a bytecode instruction that allocates a float.  This pass reads such a
run as a graph of values and computes it with a few NumPy calls instead:

* a product whose operands are inputs or products: every product of the same depth
  in one `np.multiply` of two gathers (each product keeps its own two operands, so
  the left-to-right partial products are those of the ST); a depth whose left
  operands are consecutive values in turn, each once (a Leibniz table's last
  factor: each partial product of five times its one remaining column), reads them
  in place and gathers only its right operands (`_in_place`);
* a chain `D := D + a; D := D - b; ...`: the terms, negated where subtracted, and
  `np.add.accumulate`, which adds left to right (`r[i] = r[i-1] + a[i]`, NumPy's
  documented meaning of accumulate; not the pairwise summation of `np.sum`).

Exactness: for finite values a NumPy float64 `*` or `+` is the IEEE-754 result Python's
float gives (both round to nearest double), and `x - y` is `x + (-y)` bit for bit
(signed zeros included).  Every value computed feeds an output (dead ones are not
computed), and a non-finite value never becomes finite again through `+ - *`; so when
every output is finite, every value was, and the results are Python's bit for bit.
When an output is not finite (an inf or a NaN somewhere, whose sign or payload the two
could set differently) the run is evaluated again in Python, operation by operation in
the original order: the exact result in every case.

A run qualifies when its operands are typed REAL/LREAL (a Python float, never an int),
it has no call, no subscript, no charge and no branch (those end a run), and it has at
least `MIN_PRODUCTS` operations.  Python cannot raise on `+ - *` of floats, so the run
charges and faults as before (it had no charge and no fault inside).
"""

from __future__ import annotations

import functools
import math
import re
import struct
import textwrap
import types

from ...types import ArrayType, resolve_alias
from . import TEMP_NAME, remembered

MIN_OPERATIONS = 256         # a NumPy call costs ~20 float operations: below this, no gain
_TEMP = re.compile(r"_t\d+\Z")
_ASSIGN = re.compile(r"([A-Za-z_]\w*) = (.*)\Z")
np = _abs = _multiply = _accumulate = None     # NumPy, imported by the first run


def _import_numpy() -> None:
    """NumPy is imported when a run first qualifies (a program without one loads as fast
    as before: importing NumPy takes a tenth of a second or more)."""
    global np, _abs, _multiply, _accumulate
    if np is None:
        import numpy

        _abs, _multiply, _accumulate = numpy.absolute, numpy.multiply, numpy.add.accumulate
        np = numpy


class _NotVector(Exception):
    """The run cannot be computed by this pass (an int, a call, a unary minus ...)."""


class _Graph:
    """The values of a run: inputs (index < len(inputs)), then operations (op, left, right)."""

    def __init__(self, is_float):
        self.is_float = is_float
        self.inputs: list[str] = []          # Python expressions read before the run
        self.constants: list[float] = []     # literal operands, an input each
        self.input_of: dict[str, int] = {}
        self.ops: list[tuple[str, int, int]] = []
        self.env: dict[str, tuple] = {}      # name -> ("v", index) | ("lit", text)

    def operand(self, node) -> int:
        kind = node[0]
        if kind == "name":
            bound = self.env.get(node[1])
            if bound is not None:
                if bound[0] == "v":
                    return bound[1]
                return self._literal(bound[2])
            if not self.is_float(node[1]):
                raise _NotVector(node[1])
            return self._input(node[1])
        if kind == "const":
            return self._literal(node[1])
        left, right = self.operand(node[2]), self.operand(node[3])
        self.ops.append((node[1], left, right))
        return -len(self.ops)            # operations: negative until numbered

    def _literal(self, value) -> int:
        if type(value) is not float:
            raise _NotVector(repr(value))
        return self._input(repr(value), value)

    def _input(self, text: str, constant=None) -> int:
        index = self.input_of.get(text)
        if index is None:
            index = self.input_of[text] = len(self.inputs)
            self.inputs.append(text)
            self.constants.append(constant)
        return index

    def assign(self, line: str) -> bool:
        """Add `name = expression` to the graph; False (the graph unchanged) when it cannot be."""
        match = _ASSIGN.fullmatch(line)
        if match is None:
            return False
        target, text = match.groups()
        tree = _parse(text)
        if tree is None:
            return False
        if tree[0] == "const":              # `v_TERM = 721`: kept as a literal store
            self.env[target] = ("lit", text, tree[1])
            return True
        n_ops, n_inputs = len(self.ops), len(self.inputs)
        try:
            value = self.operand(tree)
        except _NotVector:                  # undo what the line added
            del self.ops[n_ops:]
            for text in self.inputs[n_inputs:]:
                del self.input_of[text]
            del self.inputs[n_inputs:], self.constants[n_inputs:]
            return False
        self.env[target] = ("v", value)
        return True


_TOKEN = re.compile(r"\s*+(?:([()+*-])|([A-Za-z_]\w*)|(\d+(?:\.\d*)?(?:[eE][+-]?\d+)?))")
_WORDS = {"True": True, "False": False}


@functools.lru_cache(maxsize=8192)
def _parse(text: str):
    """The tree of a fully parenthesised `+ - *` of names and number literals, as the
    compiler writes them: ("name", n) | ("const", value) | ("bin", op, left, right);
    None for anything else (a call, a subscript, an attribute, an operator without
    parentheses ...).  A literal's value is Python's (`float(text)` rounds as the
    compiler of the literal does; `-0.5` is the negated constant, as Python folds it).
    Kept by text (a tree is tuples, never changed): the same lines come back in every
    load of a program and in its fast and exact copies."""
    tokens = []
    pos, end = 0, len(text.rstrip())
    while pos < end:
        m = _TOKEN.match(text, pos)
        if m is None:
            return None
        tokens.append(m.groups())
        pos = m.end()
    try:
        tree, i = _expression(tokens, 0)
    except (IndexError, RecursionError):
        return None
    return tree if tree is not None and i == len(tokens) else None


def _expression(tokens, i):
    punct, name, number = tokens[i]
    if number is not None:
        is_float = any(c in number for c in ".eE")
        return ("const", float(number) if is_float else int(number)), i + 1
    if name is not None:
        if name in _WORDS:
            return ("const", _WORDS[name]), i + 1
        return ("name", name), i + 1
    if punct == "-" and tokens[i + 1][2] is not None:
        value, i = _expression(tokens, i + 1)
        return ("const", -value[1]), i
    if punct != "(":
        return None, i
    left, i = _expression(tokens, i + 1)
    if left is None:
        return None, i
    if tokens[i][0] == ")":                 # `(x)`, `(-0.5)`
        return left, i + 1
    op = tokens[i][0]
    if op not in ("+", "-", "*"):
        return None, i
    right, i = _expression(tokens, i + 1)
    if right is None or tokens[i][0] != ")":
        return None, i
    return ("bin", op, left, right), i + 1


def _in_place(lefts: list[int]) -> int | None:
    """`first` when the positions `lefts` of a level's left operands are `first`, `first + 1`,
    ... in turn: the level's multiply reads them where they are, and only its right operands
    are gathered (each product keeps its own two operands: exact).  (A level that uses each
    left operand k > 1 times in a row could read them in place too, k multiplies writing
    every k-th product; measured slower than the gather: a strided multiply is not NumPy's
    vector loop, and each use costs a call.)"""
    first = lefts[0]
    return first if lefts == list(range(first, first + len(lefts))) else None


def _index(graph: _Graph, ref: int) -> int:
    """Inputs first, then operations in order: one index space."""
    return ref if ref >= 0 else len(graph.inputs) + (-ref - 1)


class Vectorised:
    """A run's values computed by NumPy; `__call__(inputs)` returns the outputs' floats.

    One buffer holds the inputs (those passed first, then the literals), the products
    by depth, and each chain (its head, then its steps; a head placed last among the
    inputs is the chain's first slot itself).  The inputs are checked first:
    when one is not finite or so large that some value could overflow (`limit`, from
    the graph), the run is computed in Python instead (`exact`), so NumPy never sees
    an inf or a NaN (and never warns).  The passed inputs reach the buffer through one
    `struct.pack_into` (`=d`: the double's bits unchanged, as NumPy's conversion keeps
    them; cheaper than converting a list and a tuple); what it cannot pack runs `exact`."""

    def __init__(self, graph: _Graph, outputs: list[int], source=None, numpy_now: bool = True):
        """`source`: (size, {input: element}) when inputs are elements of one list, which
        is then passed whole (`__call__(list, others)`) instead of read element by element.
        `numpy_now` False: the plan is made (it decides whether the run qualifies) but NumPy's
        arrays and the run's code only at the first call of `run`: where a native kernel takes
        the run's place before any call (`native.first_call`), a load never imports NumPy
        (about 320 million machine instructions, a sixth of a first load of generated/iec)."""
        n_in = len(graph.inputs)
        self.n_list, self.elements = source if source is not None else (0, {})
        ops = [(op, _index(graph, a), _index(graph, b)) for op, a, b in graph.ops]
        self.n_inputs = n_in
        self.ops = ops                                   # the Python fallback, in order
        self.constants = [(i, c) for i, c in enumerate(graph.constants) if c is not None]
        self.variable_inputs = [i for i, c in enumerate(graph.constants)
                                if c is None and i not in self.elements]     # passed in a tuple
        self.output_refs = outputs
        needed = set(outputs)                            # only what feeds an output is computed
        for k in range(len(ops) - 1, -1, -1):
            if n_in + k in needed:
                needed.update(ops[k][1:])
        self.live = [k for k in range(len(ops)) if n_in + k in needed]
        self.limit = self._limit()
        self._plan(outputs)
        if numpy_now:
            self._materialise()
        else:
            self.run = self._run_first

    def _run_first(self, whole, inputs):
        """`run` before the arrays are made: makes them, then runs."""
        return self.numpy_run()(whole, inputs)

    def numpy_run(self):
        """`run`, NumPy's arrays made first if they are not yet."""
        if self.run == self._run_first:
            self._materialise()
        return self.run

    def _materialise(self) -> None:
        """NumPy's arrays of the plan's positions, the buffer's views and `run` itself."""
        _import_numpy()
        self.levels = [(np.array(gathered, dtype=np.intp), n, start, stop)
                       for gathered, n, start, stop in self.levels]
        self.chains = [(head, None if terms is None else np.array(terms, dtype=np.intp), np.array(signs), start, stop)
                       for head, terms, signs, start, stop in self.chains]
        self.early_positions = np.array(self.early_positions, dtype=np.intp)
        self.outputs = np.array(self.outputs, dtype=np.intp)
        self._views(self._size)
        self._compile_run()

    def _limit(self) -> float:
        """A bound on the passed inputs' magnitude under which no value of the run reaches
        1e300: with every passed input |x| <= B (B >= 1), a value is at most c * B**d (an
        input: c = 1, d = 1; a literal: c = max(|x|, 1), d = 0; a product: c and d multiply
        and add; a sum: c adds, d is the larger)."""
        n_in = self.n_inputs
        bound = {i: (1.0, 1) for i in self.variable_inputs + list(self.elements)}
        bound.update((i, (max(abs(c), 1.0), 0)) for i, c in self.constants)
        exponent = math.inf
        for k in self.live:
            op, a, b = self.ops[k]
            (ca, da), (cb, db) = bound[a], bound[b]
            c, d = bound[n_in + k] = (ca * cb, da + db) if op == "*" else (ca + cb, max(da, db))
            if c >= 1e300:
                raise _NotVector("values that may overflow")
            if d:
                exponent = min(exponent, (300.0 - math.log10(c)) / d)
        if exponent < 0.0:
            raise _NotVector("values that may overflow")
        return 10.0 ** min(exponent, 300.0)

    def _plan(self, outputs: list[int]) -> None:
        n_in, ops = self.n_inputs, self.ops
        depth: dict[int, int] = {}
        chain_of: dict[int, tuple[int, int]] = {}      # sum value -> (chain, step)
        chains: list[dict] = []
        products_by_depth: dict[int, list[int]] = {}
        for k in self.live:
            op, a, b = ops[k]
            v = n_in + k
            if op == "*":
                if a in chain_of or b in chain_of:
                    raise _NotVector("a product of a sum")
                depth[v] = 1 + max(depth.get(a, 0), depth.get(b, 0))
                products_by_depth.setdefault(depth[v], []).append(v)
                continue
            if b in chain_of:
                raise _NotVector("a sum of a sum")
            if a in chain_of and chain_of[a][1] == len(chains[chain_of[a][0]]["terms"]) - 1:
                c = chain_of[a][0]          # `a` is its chain's last value: this continues it
            else:
                if a in chain_of:
                    raise _NotVector("a chain that branches")
                c = len(chains)
                chains.append({"head": a, "terms": [], "signs": []})
            chains[c]["terms"].append(b)
            chains[c]["signs"].append(1.0 if op == "+" else -1.0)
            chain_of[v] = (c, len(chains[c]["terms"]) - 1)
        # the list passed whole, the inputs passed in the tuple (one slice assignment each),
        # then the literals
        order = self.variable_inputs + [i for i, _ in self.constants]
        position = {i: self.n_list + p for p, i in enumerate(order)}
        position.update(self.elements)
        self.n_passed = self.n_list + len(self.variable_inputs)
        size = self.n_list + len(order)
        # a chain whose terms are one depth's products, in order, gets them written in place
        # (the sums overwrite them: not when another chain reads them; outputs read before)
        in_place = {}
        for c, chain in enumerate(chains):
            others = {x for o, other in enumerate(chains) if o != c for x in other["terms"] + [other["head"]]}
            for d, values in products_by_depth.items():
                if chain["terms"] == values and d not in in_place.values() and not others & set(values):
                    in_place[c] = d
        chain_start = {}
        for c, chain in enumerate(chains):
            # a head that is the input placed last is the chain's first slot itself (the
            # sign 1.0 and the accumulate leave it as it is): no copy a call
            head_last = chain["head"] < n_in and position[chain["head"]] == size - 1
            chain_start[c] = size - 1 if head_last else size
            size = chain_start[c] + 1 + len(chain["terms"])
        self.levels = []            # (gathered operand positions, count, out start, out stop)
        self.firsts = []            # per level: its first left operand's position when they are read in place
        for d in sorted(products_by_depth):
            values = products_by_depth[d]
            chain = next((c for c, dd in in_place.items() if dd == d), None)
            base = size if chain is None else chain_start[chain] + 1
            for offset, v in enumerate(values):
                position[v] = base + offset
            lefts = [position[ops[v - n_in][1]] for v in values]
            rights = [position[ops[v - n_in][2]] for v in values]
            first = _in_place(lefts)
            gathered = lefts + rights if first is None else rights
            self.levels.append((gathered, len(values), base, base + len(values)))
            self.firsts.append(first)
            if chain is None:
                size += len(values)
        self.chains = []            # (head position, term positions or None: in place, signs, start, stop)
        #                             (positions and signs as lists until `_materialise`)
        for c, chain in enumerate(chains):
            start = chain_start[c]
            terms = None if c in in_place else [position[t] for t in chain["terms"]]
            signs = [1.0] + chain["signs"]
            self.chains.append((position[chain["head"]], terms, signs, start, start + len(signs)))
        for v, (c, step) in chain_of.items():
            position[v] = self.chains[c][3] + 1 + step
        overwritten = {t for c in in_place for t in chains[c]["terms"]}
        self.early = [k for k, o in enumerate(outputs) if o in overwritten]
        self.early_positions = [position[outputs[k]] for k in self.early]
        self.outputs = [position[o] for o in outputs]
        self._size = size

    def _views(self, size: int) -> None:
        v = self.buffer = np.zeros(size)
        for k, (_, c) in enumerate(self.constants):
            v[self.n_passed + k] = c
        self.passed = v[:self.n_passed]
        # the passed inputs are written by one struct call into the buffer's first bytes
        # (`=d`: IEEE binary64 in the machine's order, NumPy's float64; a float's bits as
        # they are), instead of NumPy converting a list and a tuple element by element
        self.pack = struct.Struct(f"={self.n_passed}d").pack_into
        self.memory = memoryview(v).cast("B")
        self.scratch = np.empty(self.n_passed)
        self.steps = []             # (gathered positions, gathered values, left, right, out)
        for (both, n, start, stop), first in zip(self.levels, self.firsts):
            pair = np.empty(len(both))
            if first is None:
                self.steps.append((both, pair, pair[:n], pair[n:], v[start:stop]))
            else:
                self.steps.append((both, pair, v[first:first + n], pair, v[start:stop]))
        self.sums = [(head, terms, signs, v[start:stop], v[start + 1:stop])
                     for head, terms, signs, start, stop in self.chains]

    def __call__(self, whole, inputs):
        return self.run(whole, inputs)

    def _compile_run(self) -> None:
        """`self.run`: the call written out for this run (a bound method the generated code
        calls): every level's gather and product, each chain, the outputs read by
        `ndarray.item`, with the arrays bound as closure constants.  The same NumPy
        operations in the same order as a loop over `steps` and `sums` would make, without
        the loop: a 6x6 determinant: 265 -> 166 bytecodes a call."""
        names = {"exact": self.exact, "pack": self.pack, "memory": self.memory, "passed": self.passed,
                 "scratch": self.scratch, "limit": self.limit, "buffer": self.buffer,
                 "absolute": _abs, "multiply": _multiply, "accumulate": _accumulate,
                 "error": struct.error}
        lines = []
        if self.n_list:
            lines.append(f"if type(whole) is not list or len(whole) != {self.n_list}: return exact(whole, inputs)")
        lines += ["try: pack(memory, 0, *(whole or ()), *inputs)",
                  "except (error, TypeError, OverflowError): return exact(whole, inputs)",
                  # the largest |input| (argmax finds the first NaN, if any: then False), read
                  # by `item` (ndarray methods in C: a third of maximum.reduce's time)
                  "if not scratch.item(absolute(passed, scratch).argmax()) < limit: return exact(whole, inputs)",
                  "take = buffer.take"]
        for k, (both, pair, left, right, out) in enumerate(self.steps):
            names.update({f"both{k}": both, f"pair{k}": pair, f"left{k}": left, f"right{k}": right, f"out{k}": out})
            lines += [f"take(both{k}, None, pair{k}, 'wrap')", f"multiply(left{k}, right{k}, out{k})"]
        # values the chains overwrite in place, read before they do
        lines += [f"early{k} = buffer.item({int(p)})" for k, p in enumerate(self.early_positions)]
        for c, (head, terms, signs, out, steps) in enumerate(self.sums):
            names.update({f"signs{c}": signs, f"chain{c}": out, f"terms{c}": terms, f"steps{c}": steps})
            if head != self.chains[c][3]:
                lines.append(f"chain{c}[0] = buffer[{head}]")
            if terms is not None:
                lines.append(f"take(terms{c}, None, steps{c}, 'wrap')")
            lines += [f"multiply(chain{c}, signs{c}, chain{c})", f"accumulate(chain{c}, 0, None, chain{c})"]
        early = {k: f"early{e}" for e, k in enumerate(self.early)}
        results = ", ".join(early.get(k, f"buffer.item({int(p)})") for k, p in enumerate(self.outputs))
        lines.append(f"return [{results}]")
        source = "def run(self, whole, inputs):\n" + "".join(f"    {line}\n" for line in lines)
        factory = "def factory(" + ", ".join(names) + "):\n" + textwrap.indent(source, "    ") + "    return run\n"
        scope: dict = {}
        exec(compile(factory, "<vector run>", "exec"), scope)
        self.run = types.MethodType(scope["factory"](**names), self)

    def exact(self, whole, inputs):
        """The run in Python, operation by operation in the original order."""
        values = [0.0] * self.n_inputs
        for i, c in self.constants:
            values[i] = c
        for i, x in zip(self.variable_inputs, inputs):
            values[i] = x
        for i, k in self.elements.items():
            values[i] = whole[k]
        for op, a, b in self.ops:
            x, y = values[a], values[b]
            values.append(x * y if op == "*" else x + y if op == "+" else x - y)
        return [values[o] for o in self.output_refs]


def vectorise(lines: list[str], start: int, end: int, is_float, register, element_of=None,
              bind=None) -> None:
    """Replace qualifying runs in `lines[start:end]` (a region's block, one indentation)
    by one call each.  `is_float(name)`: the name holds a Python float (REAL/LREAL) before
    a run; `register(value)`: the namespace name bound to a Python value;
    `element_of(name)`: (list, index, the list's length) when the name holds an element
    read before the region (then the list is passed whole), else None; `bind(name, value)`:
    rebinds a registered name, given when each run is to be computed by native.py's
    machine code (bound in place of NumPy's kernel, compiled by its first call)."""
    if start >= end:
        return
    indent = lines[start][: len(lines[start]) - len(lines[start].lstrip())]
    i = start
    while i < end:
        graph, j = _Graph(is_float), i
        while j < end and lines[j].startswith(indent) and not lines[j][len(indent):len(indent) + 1].isspace() \
                and graph.assign(lines[j][len(indent):]):
            j += 1
        written = _replace_run(lines, i, j, indent, graph, register, element_of, bind) if j > i else None
        if written is None:
            i = max(j, i + 1)
        else:
            end += written - (j - i)
            i += written


def _replace_run(lines, i, j, indent, graph, register, element_of=None, bind=None):
    """The number of lines written in place of `lines[i:j]` (the run `graph` holds), or
    None when the run does not qualify."""
    if len(graph.ops) < MIN_OPERATIONS:
        return None
    read_later = set(TEMP_NAME.findall("\n".join(lines[j:])))
    stores, literals = [], []
    for name, bound in graph.env.items():
        if _TEMP.match(name) and name not in read_later:
            continue                               # a temporary no one reads after the run
        if bound[0] == "lit":
            literals.append(f"{name} = {bound[1]}")
        else:
            stores.append((name, _index(graph, bound[1])))
    if not stores:
        return None
    whole, source = _whole_list(graph, element_of)
    try:
        helper = Vectorised(graph, [ref for _, ref in stores], source, numpy_now=bind is None)
    except _NotVector:
        return None
    arguments = "".join(f"{graph.inputs[k]}, " for k in helper.variable_inputs)
    kernel = register(helper.run)
    if bind is not None:
        from .native import first_call

        bind(kernel, first_call(helper, lambda run: bind(kernel, run)))
    call = f"{', '.join(name for name, _ in stores)}, = {kernel}({whole}, ({arguments}))"
    new = [indent + call] + [indent + line for line in literals]
    lines[i:j] = new
    return len(new)


MIN_ELEMENTS = 8      # elements of one list worth passing it whole


def _whole_list(graph: _Graph, element_of):
    """("v_M", (length, {input: index})) when at least MIN_ELEMENTS inputs are elements of
    one list and no other list's (each element then sits at its own index), else ("None", None)."""
    if element_of is None:
        return "None", None
    found = {i: element_of(text) for i, text in enumerate(graph.inputs) if graph.constants[i] is None}
    bases = {f[0] for f in found.values() if f is not None}
    if len(bases) != 1:
        return "None", None
    elements = {i: f[1] for i, f in found.items() if f is not None}
    if len(elements) < MIN_ELEMENTS:
        return "None", None
    base = bases.pop()
    return base, (next(f[2] for f in found.values() if f is not None), elements)


def float_names(compiler, region):
    """`is_float` for `vectorise`: a region's element read or a plain local of a REAL/LREAL
    type (a Python float; an integer would be computed as a float by NumPy)."""
    from ..exprs import is_real

    symbols = {place.name: place for place in compiler.scope.places.values()}
    reads = {name: code for code, name in region.reads.items()}

    def _is_float(name: str) -> bool:
        if name in reads:
            place = symbols.get(reads[name].split("[", 1)[0])
            t = resolve_alias(place.symbol.type) if place is not None else None
            return isinstance(t, ArrayType) and is_real(t.element)
        place = symbols.get(name)
        return place is not None and place.how == "local" and is_real(place.symbol.type)
    return remembered(_is_float)


def region_elements(compiler, region):
    """`element_of` for `vectorise`: a region's read `v_M[7]` -> ("v_M", 7, the array's
    element count) when v_M is a whole array (a Python list of that length)."""
    symbols = {place.name: place for place in compiler.scope.places.values()}
    reads = {name: code for code, name in region.reads.items()}

    def element_of(name: str):
        code = reads.get(name)
        if code is None:
            return None
        base, index = code[:-1].split("[", 1)
        place = symbols.get(base)
        t = resolve_alias(place.symbol.type) if place is not None else None
        if not isinstance(t, ArrayType):
            return None
        size = 1
        for lo, hi in t.dims:
            size *= hi - lo + 1
        return base, int(index), size
    return element_of
