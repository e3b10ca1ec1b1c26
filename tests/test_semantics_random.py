"""Random integer and real expressions: compiled ST against a small reference
evaluator written here from the IEC rules (seeded, one program per test)."""

from __future__ import annotations

import math
import random

import numpy as np
import pytest

from st_runtime.api import load_text

VARS = {"a": 0, "b": 0, "c": 0, "d": 0}


class DivZero(Exception):
    pass


def iec_div(a: int, b: int) -> int:
    if b == 0:
        raise DivZero
    q = abs(a) // abs(b)
    return q if (a >= 0) == (b >= 0) else -q


def iec_mod(a: int, b: int) -> int:
    return a - iec_div(a, b) * b


def wrap(v: int, bits: int) -> int:
    v &= (1 << bits) - 1
    return v - (1 << bits) if v >= 1 << (bits - 1) else v


def random_int_expr(rng: random.Random, depth: int):
    """(ST text, reference function of the variable values)."""
    if depth == 0 or rng.random() < 0.25:
        # Leaves hold a variable, so the checker folds nothing away.
        name = rng.choice(list(VARS))
        if rng.random() < 0.5:
            return name, lambda env, n=name: env[n]
        k = rng.randint(-50, 300)
        return f"({name} + {k})", lambda env, n=name, k=k: env[n] + k
    op = rng.choice(["+", "-", "*", "/", "MOD", "neg"])
    if op == "neg":
        text, f = random_int_expr(rng, depth - 1)
        return f"-({text})", lambda env: -f(env)
    lt, lf = random_int_expr(rng, depth - 1)
    rt, rf = random_int_expr(rng, depth - 1)
    funcs = {"+": lambda x, y: x + y, "-": lambda x, y: x - y, "*": lambda x, y: x * y,
             "/": iec_div, "MOD": iec_mod}
    g = funcs[op]
    return f"({lt} {op} {rt})", lambda env: g(lf(env), rf(env))


def test_random_integer_expressions_match_the_iec_rules():
    rng = random.Random(2024)
    env = {name: rng.randint(-2000, 2000) for name in VARS}
    exprs = [random_int_expr(rng, 4) for _ in range(150)]
    n = len(exprs)
    decls = " ".join(f"{k} : INT := {v};" for k, v in env.items())
    body = "\n".join(f"r[{i}] := {text}; s[{i}] := {text};" for i, (text, _) in enumerate(exprs, 1))
    src = (f"PROGRAM Main\nVAR {decls}\nr : ARRAY[1..{n}] OF INT; s : ARRAY[1..{n}] OF DINT;\n"
           f"END_VAR\n{body}\nEND_PROGRAM\n")
    plc = load_text(src).controller()
    main = plc.add_program("Main")
    plc.run(1)
    expected_r, expected_s, zero_divisions = [], [], 0
    for _, f in exprs:
        try:
            v = f(env)
            expected_r.append(wrap(v, 16))
            expected_s.append(wrap(v, 32))    # INT arithmetic is not wrapped before the store
        except DivZero:
            zero_divisions += 1
            expected_r.append(0)        # the faulting statement is abandoned
            expected_s.append(0)
    assert main["r"] == expected_r
    assert main["s"] == expected_s
    assert len(plc.faults) == 2 * zero_divisions
    assert all(f.code == "F-DIV-ZERO" for f in plc.faults)


def test_random_real_expressions_round_to_float32_on_store():
    rng = random.Random(7)
    xs = [rng.uniform(-100, 100) for _ in range(40)]
    ys = [rng.uniform(0.5, 10) for _ in range(40)]
    body = "\n".join(
        f"f[{i}] := LREAL_TO_REAL({x!r} * {y!r} + {x!r} / {y!r}); g[{i}] := {x!r} * {y!r} + {x!r} / {y!r};"
        for i, (x, y) in enumerate(zip(xs, ys), 1))
    src = (f"PROGRAM Main\nVAR f : ARRAY[1..40] OF REAL; g : ARRAY[1..40] OF LREAL; END_VAR\n"
           f"{body}\nEND_PROGRAM\n")
    plc = load_text(src).controller()
    main = plc.add_program("Main")
    plc.run(1)
    f_values = main.raw("f")
    g_values = main.raw("g")
    for x, y, fv, gv in zip(xs, ys, f_values, g_values):
        exact = x * y + x / y
        assert gv == exact
        assert fv == float(np.float32(exact))
        assert math.isclose(fv, exact, rel_tol=1e-6)


# ------------------------------------------------- comparisons, BOOL and bits
#
# The oracle below is plain Python on Python ints, bools and NumPy float32;
# it shares nothing with the compiler.  Integer operands are variables of
# mixed widths (INT, DINT, LINT), combined without division so that no
# operand faults (whether AND/OR evaluate their right side after a FALSE /
# TRUE left one is then unobservable).

INT_VARS = {"a": "INT", "b": "INT", "e": "DINT", "g": "LINT"}
CMP_OPS = {"<": lambda x, y: x < y, "<=": lambda x, y: x <= y, ">": lambda x, y: x > y,
           ">=": lambda x, y: x >= y, "=": lambda x, y: x == y, "<>": lambda x, y: x != y}


def random_sum_expr(rng: random.Random, depth: int):
    """An integer expression of + - * and negation over INT_VARS."""
    if depth == 0 or rng.random() < 0.3:
        name = rng.choice(list(INT_VARS))
        if rng.random() < 0.6:
            return name, lambda env, n=name: env[n]
        k = rng.randint(-20, 20)
        return f"({name} + {k})", lambda env, n=name, k=k: env[n] + k
    op = rng.choice(["+", "-", "*", "neg"])
    if op == "neg":
        text, f = random_sum_expr(rng, depth - 1)
        return f"-({text})", lambda env: -f(env)
    lt, lf = random_sum_expr(rng, depth - 1)
    rt, rf = random_sum_expr(rng, depth - 1)
    g = {"+": lambda x, y: x + y, "-": lambda x, y: x - y, "*": lambda x, y: x * y}[op]
    return f"({lt} {op} {rt})", lambda env: g(lf(env), rf(env))


def random_bool_expr(rng: random.Random, depth: int):
    """A BOOL expression: comparisons of integer expressions, BOOL variables,
    AND / & / OR / XOR / NOT and = / <> between BOOLs."""
    if depth == 0 or rng.random() < 0.3:
        if rng.random() < 0.25:
            name = rng.choice(["p", "q"])
            return name, lambda env, n=name: env[n]
        op = rng.choice(list(CMP_OPS))
        lt, lf = random_sum_expr(rng, 2)
        # Equal operands half the time: where < and <=, > and >= differ.
        rt, rf = (lt, lf) if rng.random() < 0.2 else random_sum_expr(rng, 2)
        c = CMP_OPS[op]
        return f"({lt} {op} {rt})", lambda env: c(lf(env), rf(env))
    op = rng.choice(["AND", "&", "OR", "XOR", "NOT", "=", "<>"])
    if op == "NOT":
        text, f = random_bool_expr(rng, depth - 1)
        return f"NOT ({text})", lambda env: not f(env)
    lt, lf = random_bool_expr(rng, depth - 1)
    rt, rf = random_bool_expr(rng, depth - 1)
    g = {"AND": lambda x, y: x and y, "&": lambda x, y: x and y, "OR": lambda x, y: x or y,
         "XOR": lambda x, y: x != y, "=": lambda x, y: x == y, "<>": lambda x, y: x != y}[op]
    return f"({lt} {op} {rt})", lambda env: g(lf(env), rf(env))


def run_main(decls: str, body: str):
    plc = load_text(f"PROGRAM Main\nVAR {decls}\nEND_VAR\n{body}\nEND_PROGRAM\n").controller()
    main = plc.add_program("Main")
    plc.run(1)
    assert plc.faults == []
    return main


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_random_comparisons_and_boolean_expressions(seed):
    rng = random.Random(seed)
    env = {"a": rng.randint(-300, 300), "b": rng.randint(-300, 300),
           "e": rng.randint(-100_000, 100_000), "g": rng.randint(-(2**40), 2**40),
           "p": rng.random() < 0.5, "q": rng.random() < 0.5}
    # Some equal operands so that the comparisons meet at equality.
    env["b"] = env["a"] if seed == 2 else env["b"]
    exprs = [random_bool_expr(rng, 3) for _ in range(120)]
    n = len(exprs)
    decls = " ".join(f"{k} : {t} := {env[k]};" for k, t in INT_VARS.items())
    decls += f" p : BOOL := {str(env['p']).upper()}; q : BOOL := {str(env['q']).upper()};"
    decls += f" r : ARRAY[1..{n}] OF BOOL;"
    body = "\n".join(f"r[{i}] := {text};" for i, (text, _) in enumerate(exprs, 1))
    main = run_main(decls, body)
    expected = [f(env) for _, f in exprs]
    assert main["r"] == expected
    assert 0 < sum(expected) < n     # both outcomes occur


BIT_WIDTH = 16
MASK = (1 << BIT_WIDTH) - 1


def rotate_left(v: int, n: int) -> int:
    n %= BIT_WIDTH
    return ((v << n) | (v >> (BIT_WIDTH - n))) & MASK


def random_word_expr(rng: random.Random, depth: int):
    """A WORD expression of AND OR XOR NOT SHL SHR ROL ROR over w1..w3."""
    if depth == 0 or rng.random() < 0.25:
        name = rng.choice(["w1", "w2", "w3"])
        return name, lambda env, n=name: env[n]
    op = rng.choice(["AND", "OR", "XOR", "NOT", "SHL", "SHR", "ROL", "ROR"])
    text, f = random_word_expr(rng, depth - 1)
    if op == "NOT":
        return f"NOT ({text})", lambda env: ~f(env) & MASK
    if op in ("SHL", "SHR", "ROL", "ROR"):
        k = rng.randint(0, BIT_WIDTH - 1)
        g = {"SHL": lambda v: (v << k) & MASK, "SHR": lambda v: v >> k,
             "ROL": lambda v: rotate_left(v, k), "ROR": lambda v: rotate_left(v, BIT_WIDTH - k)}[op]
        return f"{op}({text}, {k})", lambda env: g(f(env))
    rt, rf = random_word_expr(rng, depth - 1)
    g = {"AND": lambda x, y: x & y, "OR": lambda x, y: x | y, "XOR": lambda x, y: x ^ y}[op]
    return f"({text} {op} {rt})", lambda env: g(f(env), rf(env))


@pytest.mark.parametrize("seed", [11, 12])
def test_random_bit_string_expressions(seed):
    rng = random.Random(seed)
    env = {name: rng.randrange(1 << BIT_WIDTH) for name in ("w1", "w2", "w3")}
    exprs = [random_word_expr(rng, 4) for _ in range(100)]
    n = len(exprs)
    decls = " ".join(f"{k} : WORD := {v};" for k, v in env.items())
    decls += f" r : ARRAY[1..{n}] OF WORD; c : ARRAY[1..{n}] OF BOOL;"
    # Each WORD result also compared with w1: a comparison of bit strings.
    body = "\n".join(f"r[{i}] := {text}; c[{i}] := ({text}) > w1;" for i, (text, _) in enumerate(exprs, 1))
    main = run_main(decls, body)
    expected = [f(env) for _, f in exprs]
    assert main["r"] == expected
    assert main["c"] == [v > env["w1"] for v in expected]


@pytest.mark.parametrize("seed", [21, 22])
def test_random_mixed_real_and_lreal_comparisons(seed):
    # A REAL holds the literal rounded to float32 (NumPy here), an LREAL the
    # float64: 0.1 as REAL is 0.100000001490116..., above 0.1 as LREAL.  The
    # REAL operand is widened exactly, so the comparison sees that difference.
    rng = random.Random(seed)
    literals = [repr(round(rng.uniform(-10, 10), rng.randint(0, 7))) for _ in range(12)]
    literals += ["0.1", "0.2", "1.0E-8", "-0.0", "0.0", "16777217.0"]
    pairs = [(rng.choice(literals), rng.choice(literals)) for _ in range(60)]
    pairs += [(x, x) for x in literals]          # the same literal as REAL and LREAL
    ops = [rng.choice(list(CMP_OPS)) for _ in pairs]
    n = len(pairs)
    decls = " ".join(f"x{i} : REAL := {a}; y{i} : LREAL := {b};" for i, (a, b) in enumerate(pairs, 1))
    decls += f" r : ARRAY[1..{n}] OF BOOL;"
    body = "\n".join(f"r[{i}] := x{i} {op} y{i};" for i, op in enumerate(ops, 1))
    main = run_main(decls, body)
    expected = [CMP_OPS[op](float(np.float32(float(a))), float(b)) for op, (a, b) in zip(ops, pairs)]
    assert main["r"] == expected
