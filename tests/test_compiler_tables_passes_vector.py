"""The `vector` pass's table (issue 16, session 13; docs/mutation.md, compiler, "Session 13,
optimise"): every decision of vector.py on a family of runs, each checked in full.

The reference is Python's own float arithmetic: the lines the compiler wrote, executed as
they are.  vector.py's contract (its docstring): a qualifying run becomes one call whose
results are those floats bit for bit (signed zeros, infinities and NaN where Python gives
them), temporaries no one reads after the run are not stored, and a run that does not
qualify stays as written.  The runs are built here the way cse.py and fuse.py write them
(`_tN = (a * b)`, `v_D = ((v_D + x) - y)`), seeded, each family aimed at one decision:
depths of products, chains (in place over one depth's products, or gathered), outputs read
before a chain overwrites them, literals, one list passed whole, inputs NumPy must not see.
"""

from __future__ import annotations

import math
import random
import struct

import numpy as np
import pytest

from st_runtime.compiler.optimise import vector

FLOATS = [f"_t{i}" for i in range(1, 9)] + ["v_X", "v_Y", "v_D", "v_E"]
ELEMENTS = {f"_e{k}": ("v_M", k, 12) for k in range(12)}           # v_M: a list of 12 floats


def _bits(x: float) -> bytes:
    return struct.pack("<d", x)


def _same(a, b) -> bool:
    if isinstance(a, list):
        return isinstance(b, list) and len(a) == len(b) and all(map(_same, a, b))
    return (math.isnan(a) and math.isnan(b)) or _bits(a) == _bits(b)


def _register(bound: dict):
    def register(value):
        bound[f"_k{len(bound)}"] = value
        return f"_k{len(bound) - 1}"
    return register


def _vectorised(lines: list[str], floats=FLOATS, elements=None):
    """The lines after the pass, and the namespace its calls need."""
    bound: dict = {}
    out = list(lines)
    vector.vectorise(out, 0, len(out), set(floats + list(ELEMENTS)).__contains__, _register(bound),
                     None if elements is None else elements.get)
    return out, bound


def _run(lines: list[str], env: dict, bound: dict) -> dict:
    """The lines executed; NumPy raising where it would warn (the pass's contract: NumPy
    never sees an inf or a NaN, and no value it computes overflows)."""
    scope = dict(env)
    scope["v_M"] = list(env["v_M"])
    with np.errstate(over="raise", invalid="raise", divide="raise"):
        exec("\n".join(line.strip() for line in lines), dict(bound), scope)
    return scope


def _inputs(rng: random.Random, special=None) -> dict:
    env = {name: rng.uniform(-3.0, 3.0) for name in FLOATS}
    env["v_M"] = [rng.uniform(-2.0, 2.0) for _ in range(12)]
    env.update({f"_e{k}": env["v_M"][k] for k in range(12)})
    if special is not None:
        name, value = special
        if name.startswith("_e"):
            env["v_M"][int(name[2:])] = value
        env[name] = value
    return env


SPECIALS = [None, ("_t1", math.inf), ("_t2", -math.inf), ("_t3", math.nan), ("v_D", -0.0),
            ("_t4", 1e200), ("_t5", -1e155), ("_t6", 5e-324), ("_e3", math.nan), ("_e0", 1e300),
            ("v_X", 0.0)]


def _check(lines: list[str], after: list[str], bound: dict, reads_after=(), seed: int = 0):
    """Every value a later line can read is Python's, bit for bit, for ordinary inputs and
    for each special one; a temporary nobody reads after the run is not stored."""
    rng = random.Random(seed)
    for special in SPECIALS:
        env = _inputs(rng, special)
        want, got = _run(lines, env, {}), _run(after, env, bound)
        for name, value in want.items():
            if name.startswith("_t") and name not in reads_after and name not in env:
                continue
            assert name in got and _same(got[name], value), (special, name, value, got.get(name))
        for name in got:
            if name.startswith("_t") and name not in env:
                assert name in want and (name in reads_after or len(after) == len(lines)), name


# ------------------------------------------------------------------ families of runs


def _products(rng, count, depth_of, operands):
    """`count` product temps, each of two operands (inputs or earlier products)."""
    lines, made = [], []
    for _ in range(count):
        a, b = rng.choice(operands + made), rng.choice(operands + made)
        name = f"_t{100 + len(made)}"
        lines.append(f"{name} = ({a} * {b})")
        made.append(name)
    return lines, made


def leibniz(rng, terms=140, head="v_D", literal=True, temps=200):
    """Depth-2 products each added to one chain, in the table's order (the in-place shape:
    the chain's terms are one depth's products, in order)."""
    lines = []
    for i in range(terms):
        a, b, c = rng.sample(FLOATS[:8] + ["v_X"], 3)
        lines.append(f"_t{temps + i} = ({a} * {b})")
        lines.append(f"_t{temps + 200 + i} = (_t{temps + i} * {c if not literal or i % 5 else '-0.5'})")
    for i in range(terms):
        lines.append(f"{head} = ({head} {'+' if i % 3 else '-'} _t{temps + 200 + i})")
    return lines


def mixed(rng, lines_count=180):
    """Nested products and sums inside one line, two chains, literals of both signs."""
    lines = []
    for i in range(lines_count):
        a, b, c, d = (rng.choice(FLOATS[:8] + ["2.0", "-0.25", "v_Y"]) for _ in range(4))
        head = "v_D" if i % 2 else "v_E"
        lines.append(f"{head} = (({head} + ({a} * {b})) - (({c} * {d}) * {a}))")
    return lines


def with_elements(rng, lines_count=150):
    """Inputs that are elements of one list, read before the region (passed whole)."""
    lines = []
    for i in range(lines_count):
        a, b = rng.sample(list(ELEMENTS), 2)
        lines.append(f"_t{300 + i} = ({a} * {b})")
        lines.append(f"v_D = (v_D + (_t{300 + i} * _t1))")
    return lines


FAMILIES = {
    "in place, temps unread": lambda rng: (leibniz(rng), ()),
    "in place, a product read after": lambda rng: (leibniz(rng), ("_t400", "_t457")),
    "in place, no literal": lambda rng: (leibniz(rng, literal=False), ()),
    "two chains, nested": lambda rng: (mixed(rng), ()),
    "a list passed whole": lambda rng: (with_elements(rng), ("_t300",)),
}


@pytest.mark.parametrize("seed", [1, 2])
@pytest.mark.parametrize("family", FAMILIES.values(), ids=FAMILIES.keys())
def test_a_qualifying_run_is_one_call_with_pythons_floats(family, seed: int):
    rng = random.Random(seed)
    lines, reads_after = family(rng)
    later = [f"v_R{k} = abs({name})" for k, name in enumerate(reads_after)]
    elements = ELEMENTS if "_e0" in "\n".join(lines) else None
    after, bound = _vectorised(lines + later, elements=elements)
    assert len(bound) == 1 and after[0].split(" = ")[1].startswith("_k0(")     # one call
    assert after[len(after) - len(later):] == later
    if elements is not None:
        assert after[0].split(" = ")[1].startswith("_k0(v_M, (")                # the list whole
    else:
        assert after[0].split(" = ")[1].startswith("_k0(None, (")
    _check(lines + later, after, bound, reads_after, seed)


def test_outputs_are_the_stores_a_later_line_can_read_in_first_store_order():
    rng = random.Random(5)
    lines = mixed(rng)
    after, bound = _vectorised(lines + ["v_Z = 1"])
    assert after[0].startswith("v_E, v_D, = _k0(None, (") and after[1:] == ["v_Z = 1"]


def test_a_literal_store_in_a_run_is_kept_after_the_call():
    rng = random.Random(6)
    lines = leibniz(rng)
    lines.insert(30, "v_N = 721")
    lines.insert(31, "v_F = True")
    after, bound = _vectorised(lines)
    assert after[1:] == ["v_N = 721", "v_F = True"]
    _check(lines, after, bound)


RUN_ENDERS = {
    "a call": "v_D = _f32(v_D)",
    "a subscript": "v_D = (v_D + v_M[2])",
    "an attribute": "v_D = (v_D + self.v_Q)",
    "a division": "v_D = (v_D / _t1)",
    "an int operand": "v_D = (v_D + v_K)",
    "an int literal": "v_D = (v_D + 2)",
    "no parentheses": "v_D = v_D + _t1",
    "a comparison": "v_F = (v_D < _t1)",
    "a budget check": "if _ctx.budget < _spent: _overrun(('X', 'x.st', 3, 1))",
}


@pytest.mark.parametrize("ender", RUN_ENDERS.values(), ids=RUN_ENDERS.keys())
def test_a_line_the_graph_cannot_hold_ends_the_run_and_stays(ender: str):
    rng = random.Random(7)
    first, second = leibniz(rng, 140, "v_D"), leibniz(rng, 140, "v_E", temps=1000)
    lines = first + [ender] + second
    after, bound = _vectorised(lines)
    assert after.count(ender) == 1 and len(bound) == 2            # two runs, each one call
    assert after[1] == ender and after[0].startswith("v_D, = _k0(") and after[2].startswith("v_E, = _k1(")


def test_short_runs_and_runs_of_unknown_types_stay_as_written():
    rng = random.Random(8)
    short = leibniz(rng, 80)                  # 240 operations: fewer than MIN_OPERATIONS
    assert 3 * 80 < vector.MIN_OPERATIONS <= 3 * 90
    after, bound = _vectorised(short)
    assert after == short and bound == {}
    just = leibniz(rng, 86)                   # 258
    after, bound = _vectorised(just)
    assert len(after) == 1 and len(bound) == 1
    after, bound = _vectorised(just, floats=[n for n in FLOATS if n != "v_D"])
    assert after == just and bound == {}      # v_D not known to be a float (an INT's int?)


UNPLANNABLE = {
    # a product of a chain's sum, a sum of a sum, a chain that branches: NumPy's plan has
    # no place for them, the run stays Python's
    "a product of a sum": "v_P = (v_D * _t1)",
    "a sum of a sum": "v_E = (v_E + v_D)",
    "a branching chain": None,
}


@pytest.mark.parametrize("shape", UNPLANNABLE.values(), ids=UNPLANNABLE.keys())
def test_runs_the_plan_cannot_take_stay_as_written(shape):
    rng = random.Random(9)
    lines = leibniz(rng)
    if shape is None:
        k = len(lines) - 60
        lines = lines[:k] + ["v_E = (v_D + _t1)"] + [line.replace("v_D", "v_E") for line in lines[k:]] \
            + ["v_G = (v_E + _t1)"]
        lines.insert(k + 1, "v_D = (v_D + _t2)")
        lines.append("_t901 = (v_D * 1.5)")
    else:
        lines.append(shape)
        lines.append("v_Z = (v_E * 2.0)")
    floats = FLOATS + ["v_G"]
    after, bound = _vectorised(lines, floats=floats)
    assert after == lines and bound == {}
    _check(lines, after, bound)


def test_a_run_whose_values_may_overflow_stays_or_checks_its_inputs():
    # A literal of 1e299 in a product: with the sums of the chain, c * B**d passes 1e300 at
    # B = 1 already (the plan refuses the run); with 1e100 the chain's bound is about
    # 3e101 * B**2, so inputs near 1e99 and above must take the Python run (NumPy would
    # overflow), those below NumPy's.
    rng = random.Random(10)
    lines = [line.replace("-0.5", "1e299") for line in leibniz(rng)]
    after, bound = _vectorised(lines)
    assert after == lines and bound == {}
    lines = [line.replace("-0.5", "1e100") for line in leibniz(rng)]
    after, bound = _vectorised(lines)
    assert len(bound) == 1
    for big in (1e60, 1e90, 1e99, 1e100, 1e101, 1e150, 1e200):
        env = _inputs(random.Random(1), ("_t1", big))
        want, got = _run(lines, env, {}), _run(after, env, bound)
        assert _same(got["v_D"], want["v_D"]), big


PARSE = [
    ("a", ("name", "a")),
    ("1.5", ("const", 1.5)),
    ("2", ("const", 2)),
    ("1e3", ("const", 1000.0)),
    ("2.5E-2", ("const", 0.025)),
    ("True", ("const", True)),
    ("False", ("const", False)),
    ("(a + b)", ("bin", "+", ("name", "a"), ("name", "b"))),
    ("(a - 0.5)", ("bin", "-", ("name", "a"), ("const", 0.5))),
    ("(a * -0.5)", ("bin", "*", ("name", "a"), ("const", -0.5))),
    ("-0.5", ("const", -0.5)),
    ("(-0.5)", ("const", -0.5)),
    ("(x)", ("name", "x")),
    ("((a * b) - (c * d))", ("bin", "-", ("bin", "*", ("name", "a"), ("name", "b")),
                             ("bin", "*", ("name", "c"), ("name", "d")))),
    ("(((a + b) + c) + d)", ("bin", "+", ("bin", "+", ("bin", "+", ("name", "a"), ("name", "b")),
                                             ("name", "c")), ("name", "d"))),
    ("  (a + b)  ", ("bin", "+", ("name", "a"), ("name", "b"))),    # spaces around tokens are skipped
    ("(a + b)  ", ("bin", "+", ("name", "a"), ("name", "b"))),
    ("a + b", None), ("(a + b", None), ("(a + b c", None), ("(a + b c)", None), ("(a + b))", None),
    ("(a / b)", None), ("(a ** b)", None), ("f(a)", None), ("(a + f(b))", None), ("v[1]", None),
    ("self.v_X", None), ("(a < b)", None), ("()", None), ("(", None), ("-a", None), ("(a +)", None),
    ("(a + * b)", None), ("((a) + (b))", ("bin", "+", ("name", "a"), ("name", "b"))),
    ("(a (b)", None), ("(a b c)", None), ("(a b)", None),    # a token that is no operator where one belongs
]


@pytest.mark.parametrize("text, tree", PARSE, ids=[p[0] for p in PARSE])
def test_the_parse_of_a_line_s_value(text, tree):
    assert vector._parse(text) == tree


def test_a_literal_of_1e300_makes_the_run_refused():
    # c = max(|1e300|, 1) reaches 1e300: some value might overflow, the run stays as written
    rng = random.Random(11)
    lines = [line.replace("-0.5", "1e300") for line in leibniz(rng)]
    after, bound = _vectorised(lines)
    assert after == lines and bound == {}


def test_a_value_that_reaches_1e300_exactly_makes_the_run_refused():
    # each output x * 1e300 has c = 1e300 (a literal's magnitude times an input's 1): the
    # bound "no value reaches 1e300" fails at equality already
    lines = [f"v_P{k} = ({FLOATS[k % 8]} * 1e300)" for k in range(260)]
    after, bound = _vectorised(lines)
    assert after == lines and bound == {}
    lines = [f"v_P{k} = ({FLOATS[k % 8]} * 1e299)" for k in range(260)]
    after, bound = _vectorised(lines)
    assert len(after) == 1 and len(bound) == 1


@pytest.mark.parametrize("family", FAMILIES.values(), ids=FAMILIES.keys())
def test_finite_inputs_take_numpy_and_the_others_python(family):
    """vector.py's contract: only inputs that are not finite or could overflow take the run
    in Python (`exact`); ordinary ones are computed by NumPy (else the pass is no pass)."""
    rng = random.Random(3)
    lines, _ = family(rng)
    elements = ELEMENTS if "_e0" in "\n".join(lines) else None
    after, bound = _vectorised(lines, elements=elements)
    helper = bound["_k0"].__self__
    calls = []
    original = helper.exact

    def exact(whole, inputs):
        calls.append(1)
        return original(whole, inputs)
    helper.exact = exact
    helper._compile_run()                  # (the run binds exact when it is written)
    for special, python in ((None, 0), (("_t1", math.inf), 1), (("_e2", math.nan), 1), (("_t1", 1e200), 1)):
        if special is not None and special[0].startswith("_e") and elements is None:
            continue
        calls.clear()
        env = _inputs(random.Random(4), special)
        got = _run(after, env, {**bound, "_k0": helper.run})
        assert len(calls) == python, special
        want = _run(lines, env, {})
        assert all(_same(got[k], v) for k, v in want.items() if k in got)


def test_a_run_that_stores_nothing_read_after_it_stays():
    """A run whose every store is a temporary that no later line reads (nothing to return)
    is left as it is; and an empty block, or a block of one line, has no run."""
    lines = [f"_t{9 + k} = ({FLOATS[k % 8]} * {FLOATS[(k + 3) % 8]})" for k in range(300)]
    assert _vectorised(lines) == (lines, {})
    after, bound = _vectorised(lines + ["v_X = _t9"])       # (one read after: the run returns v_X)
    assert len(bound) == 1 and len(after) == 1 and after[0].startswith("v_X, = _k0(")
    for block in ([], ["v_X = (_t1 * _t2)"]):
        assert _vectorised(block) == (block, {})


def test_a_product_whose_right_operand_is_a_product():
    """`x * (y * z)`: the inner product is computed before the outer (its depth counts from
    both operands), bit for bit as Python computes the lines, ordinary inputs and specials."""
    lines = [f"v_P{k} = ({FLOATS[k % 8]} * ({FLOATS[(k + 1) % 8]} * {FLOATS[(k + 5) % 8]}))" for k in range(130)]
    after, bound = _vectorised(lines)
    assert len(after) == 1 and len(bound) == 1
    for special in SPECIALS:
        env = _inputs(random.Random(7), special)
        want, got = _run(lines, env, {}), _run(after, env, bound)
        assert all(_same(got[f"v_P{k}"], want[f"v_P{k}"]) for k in range(130)), special
