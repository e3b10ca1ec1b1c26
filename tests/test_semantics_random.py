"""Random integer and real expressions: compiled ST against a small reference
evaluator written here from the IEC rules (seeded, one program per test)."""

from __future__ import annotations

import math
import random

import numpy as np

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
