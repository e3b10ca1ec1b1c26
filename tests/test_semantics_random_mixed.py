"""Random integer expressions over operands of mixed size and signedness,
against a reference evaluator written here from the rules of each dialect.

`nj` (OMRON W501 6-5-3, "Implicit Casts"): an operation takes the type of its
higher-ranked operand (ranks by size; of a signed and an unsigned operand of
one size, the unsigned type), is computed in that type and overflows there.
`iec`: the IEC common type, intermediate results exact, wrapped only when
stored (into LINT here).  Each expression runs with its operands as
variables and as CONSTANTs (which the checker folds): both must give the
reference value.
"""

from __future__ import annotations

import random

import pytest

from st_runtime.api import load_text
from test_semantics_random import DivZero, iec_div as trunc_div

TYPES = {"SINT": (8, True), "USINT": (8, False), "INT": (16, True), "UINT": (16, False),
         "DINT": (32, True), "UDINT": (32, False)}


def wrap(v: int, bits: int, signed: bool) -> int:
    v &= (1 << bits) - 1
    return v - (1 << bits) if signed and v >= 1 << (bits - 1) else v


def run_once(src: str, dialect: str):
    """One scan of PROGRAM Main in `src`, with no fault; its instance."""
    plc = load_text(src, "main.st", dialect=dialect).controller()
    main = plc.add_program("Main")
    plc.run(1)
    assert not plc.faults
    return main


def ranked(a: str, b: str) -> str:
    (abits, asigned), (bbits, bsigned) = TYPES[a], TYPES[b]
    if abits != bbits:
        return a if abits > bbits else b
    return b if asigned and not bsigned else a


def apply(op: str, x: int, y: int) -> int:
    if op == "+":
        return x + y
    if op == "-":
        return x - y
    if op == "*":
        return x * y
    q = trunc_div(x, y)
    return q if op == "/" else x - q * y


def random_expr(rng: random.Random, operands: dict, depth: int):
    """(ST text, nj reference value and type, iec reference value); DivZero when
    either reference divides by zero (the expression is then not used)."""
    if depth == 0 or rng.random() < 0.3:
        name = rng.choice(sorted(operands))
        t, v = operands[name]
        return name, (v, t), v
    op = rng.choice(["+", "-", "*", "/", "MOD"])
    lt, (lv, ltype), lexact = random_expr(rng, operands, depth - 1)
    rt, (rv, rtype), rexact = random_expr(rng, operands, depth - 1)
    t = ranked(ltype, rtype)
    bits, signed = TYPES[t]
    nj = wrap(apply(op, wrap(lv, bits, signed), wrap(rv, bits, signed)), bits, signed)
    return f"({lt} {op} {rt})", (nj, t), apply(op, lexact, rexact)


def program(rng: random.Random, block: str):
    operands = {}
    for i, t in enumerate(rng.choices(sorted(TYPES), k=8)):
        bits, signed = TYPES[t]
        lo, hi = (-(1 << (bits - 1)), (1 << (bits - 1)) - 1) if signed else (0, (1 << bits) - 1)
        operands[f"v{i}"] = (t, rng.choice([lo, hi, rng.randint(lo, hi), rng.randint(-9, 9) % (hi + 1)]))
    exprs = []
    while len(exprs) < 60:
        try:
            text, (nj, _), exact = random_expr(rng, operands, 3)
        except DivZero:
            continue
        exprs.append((text, nj, exact))
    decls = " ".join(f"{n} : {t} := {v};" for n, (t, v) in operands.items())
    body = "\n".join(f"r[{i}] := {text};" for i, (text, _, _) in enumerate(exprs, 1))
    src = (f"PROGRAM Main\nVAR r : ARRAY[1..{len(exprs)}] OF LINT; END_VAR\n{block}\n{decls}\nEND_VAR\n"
           f"{body}\nEND_PROGRAM\n")
    return src, exprs


@pytest.mark.parametrize("seed", [1, 2, 3, 15, 20, 31, 35, 38])  # 15-38 found the MOD fold
@pytest.mark.parametrize("block", ["VAR", "VAR CONSTANT"])
@pytest.mark.parametrize("dialect", ["nj", "iec"])
def test_mixed_integer_expressions_follow_the_dialect(dialect, block, seed):
    src, exprs = program(random.Random(seed), block)
    main = run_once(src, dialect)
    want = [wrap(nj if dialect == "nj" else exact, 64, True) for _, nj, exact in exprs]
    got = main["r"]
    wrong = [(text, g, w) for (text, _, _), g, w in zip(exprs, got, want) if g != w]
    assert not wrong, wrong[:5]


# REAL: under `nj` each `+ - * /` is computed in single precision (the right-hand
# side has the type REAL, W501 6-5-3); under `iec` intermediate results stay
# doubles and are rounded once, when stored.  The references use NumPy's
# float32 and float64 arithmetic (IEEE 754, round to nearest even).
REAL_VALUES = (0.1, 1.0 / 3.0, 2.7182817, 1.0e-3, 123.456, 7.0e5, -0.3, 3.0e38)


def random_real_expr(rng: random.Random, names: list, depth: int) -> str:
    if depth == 0 or rng.random() < 0.3:
        return rng.choice(names)
    return f"({random_real_expr(rng, names, depth - 1)} {rng.choice('+-*/')} {random_real_expr(rng, names, depth - 1)})"


@pytest.mark.parametrize("seed", [1, 2])
@pytest.mark.parametrize("block", ["VAR", "VAR CONSTANT"])
@pytest.mark.parametrize("dialect", ["nj", "iec"])
def test_real_expressions_round_where_the_dialect_rounds(dialect, block, seed):
    import numpy as np

    rng = random.Random(seed)
    names = ["a", "b", "c", "d"]
    values = {n: rng.choice(REAL_VALUES) for n in names}
    exprs = [random_real_expr(rng, names, 3) for _ in range(60)]
    decls = " ".join(f"{n} : REAL := {v!r};" for n, v in values.items())
    body = "\n".join(f"r[{i}] := {text};" for i, text in enumerate(exprs, 1))
    src = (f"PROGRAM Main\nVAR r : ARRAY[1..{len(exprs)}] OF REAL; END_VAR\n{block}\n{decls}\nEND_VAR\n"
           f"{body}\nEND_PROGRAM\n")
    main = run_once(src, dialect)
    f32 = {n: np.float32(v) for n, v in values.items()}
    f64 = {n: np.float64(v) for n, v in f32.items()}     # REAL variables hold float32 values
    with np.errstate(all="ignore"):
        want = [float(np.float32(eval(text, {}, f32 if dialect == "nj" else f64))) for text in exprs]
    got = main["r"]         # the API shows a REAL by its shortest decimal: compare as float32
    wrong = [(text, g, w) for text, g, w in zip(exprs, got, want)
             if np.float32(g) != np.float32(w) and not (g != g and w != w)]
    assert not wrong, wrong[:5]
