"""Tables of what the compiler's core files emit and decide (issue 16, session 13):
st_runtime/compiler/exprs.py, statements.py, calls.py, cost.py, initial.py, scope.py,
support.py, pysrc.py and __init__.py (not optimise/, whose passes have their own tests).

One row per behaviour, checked in full with `==`.  Expected values come from IEC 61131-3
(integer division truncates toward zero, MOD takes the dividend's sign, stores wrap to the
type's width, FOR leaves its variable at the first value past the end), OMRON's W501 6-5-3
as docs/nj501.md cites it (the `nj` dialect: integer `+ - *` overflow in the expression's
type, REAL operations in single precision), NumPy's float32, Python's exact integers and
the weights of docs/nj501.md "What a scan costs" by hand - never from running the code under
test.  Every row runs with every optimisation pass and with none, and under the dialects
where the row's value differs.  Operands are variables set from outside before the scan: the
checker folds constants, and a variable's initial value could be known to a pass.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from st_runtime import loader
from st_runtime.compiler import Optimisations, compile_program
from st_runtime.controller import Controller

EVERY, NONE = Optimisations(), Optimisations.none()
PASSES = pytest.mark.parametrize("optimise", [EVERY, NONE], ids=["every pass", "no pass"])
PS_PER_UNIT = 598       # docs/nj501.md: 49.5e6 ps / 82,816.5 units, rounded


def checked(src: str, dialect: str = "iec"):
    result = loader.load_texts({"m.st": src}, dialect, None)
    errors = [d.header() for d in result.diagnostics if d.is_error]
    assert result.program is not None and not errors, errors
    return result.program


def run(src: str, optimise: Optimisations = EVERY, dialect: str = "iec", scans: int = 1,
        inputs: dict | None = None, limit_ns: int | None = None, program: str = "Main"):
    """`program` of `src` after `scans` scans: (instance, [(code, line, scan)], [ps per scan])."""
    controller = Controller(compile_program(checked(src, dialect), optimise=optimise), time_limit_ns=limit_ns)
    main = controller.add_program(program)
    for name, value in (inputs or {}).items():
        setattr(main, "v_" + name.upper(), value)
    controller.run(scans)
    return main, [(f.code, f.line, f.scan) for f in controller.faults], list(controller.task_times["Primary"])


def line_of(src: str, text: str) -> int:
    """The 1-based line of `src` holding `text` (once)."""
    lines = [n for n, line in enumerate(src.splitlines(), start=1) if text in line]
    assert len(lines) == 1, (text, lines)
    return lines[0]


# ----------------------------------------------------------------- exact arithmetic (IEC)

def wrap(value: int, bits: int, signed: bool) -> int:
    value &= (1 << bits) - 1
    return value - (1 << bits) if signed and value >= 1 << (bits - 1) else value


def trunc_div(a: int, b: int) -> int:
    """IEC `/` on integers: the quotient truncated toward zero."""
    q = abs(a) // abs(b)
    return q if (a < 0) == (b < 0) else -q


def iec_mod(a: int, b: int) -> int:
    """IEC MOD: a - b * (a / b), the sign of the dividend."""
    return a - b * trunc_div(a, b)


def f32(x: float) -> float:
    return float(np.float32(x))


# ======================================================= exprs.py: operators x elementary types

INTEGERS = {  # name: (bits, signed)
    "SINT": (8, True), "INT": (16, True), "DINT": (32, True), "LINT": (64, True),
    "USINT": (8, False), "UINT": (16, False), "UDINT": (32, False), "ULINT": (64, False)}


def integer_pairs(bits: int, signed: bool) -> list[tuple[int, int]]:
    lo, hi = (-(1 << (bits - 1)), (1 << (bits - 1)) - 1) if signed else (0, (1 << bits) - 1)
    pairs = [(hi - 1, 7), (3, 7), (hi, 2), (lo + 1, 3), (5, 5)]      # + and * wrap, - wraps
    if signed:
        pairs += [(-7, 2), (7, -2), (-7, -2), (lo, -1), (lo + 1, -7)]   # signs of / and MOD; MIN / -1
    return pairs


ARITHMETIC = """PROGRAM Main
VAR a, b, r_add, r_sub, r_mul, r_div, r_mod, r_neg : {t}; c_eq, c_ne, c_lt, c_le, c_gt, c_ge : BOOL; END_VAR
r_add := a + b;
r_sub := a - b;
r_mul := a * b;
r_div := a / b;
r_mod := a MOD b;
r_neg := -a;
c_eq := a = b;
c_ne := a <> b;
c_lt := a < b;
c_le := a <= b;
c_gt := a > b;
c_ge := a >= b;
END_PROGRAM"""


@pytest.mark.parametrize("dialect", ["iec", "nj"])
@PASSES
@pytest.mark.parametrize("name", INTEGERS)
def test_every_integer_operator_on_every_integer_type(name: str, optimise, dialect: str):
    # One store of one operation in the operands' own type: exact, then wrapped to the type
    # (IEC; under nj the expression overflows in that type: the same stored value).
    bits, signed = INTEGERS[name]
    src = ARITHMETIC.format(t=name)
    compiled = compile_program(checked(src, dialect), optimise=optimise)
    for a, b in integer_pairs(bits, signed):
        controller = Controller(compiled)
        main = controller.add_program("Main")
        main.v_A, main.v_B = a, b
        controller.run(1)
        got = (main.v_R_ADD, main.v_R_SUB, main.v_R_MUL, main.v_R_DIV, main.v_R_MOD, main.v_R_NEG,
               main.v_C_EQ, main.v_C_NE, main.v_C_LT, main.v_C_LE, main.v_C_GT, main.v_C_GE)
        w = lambda v: wrap(v, bits, signed)     # noqa: E731
        assert got == (w(a + b), w(a - b), w(a * b), w(trunc_div(a, b)), w(iec_mod(a, b)), w(-a),
                       a == b, a != b, a < b, a <= b, a > b, a >= b), (name, a, b)
        assert controller.faults == []


@PASSES
@pytest.mark.parametrize("name", INTEGERS)
def test_integer_division_and_mod_by_zero_fault_and_abandon_only_their_statement(name: str, optimise):
    src = ARITHMETIC.format(t=name)
    main, faults, _ = run(src, optimise, inputs={"a": 9, "b": 0, "r_div": 4, "r_mod": 5})
    # F-DIV-ZERO on the `/` and MOD lines; those stores are abandoned (old values kept);
    # every other statement ran.
    assert faults == [("F-DIV-ZERO", line_of(src, "a / b"), 1), ("F-DIV-ZERO", line_of(src, "a MOD b"), 1)]
    bits, signed = INTEGERS[name]
    assert (main.v_R_ADD, main.v_R_SUB, main.v_R_DIV, main.v_R_MOD, main.v_R_NEG, main.v_C_GT) == \
        (9, 9, 4, 5, wrap(-9, bits, signed), True)


BITS = {"BYTE": 8, "WORD": 16, "DWORD": 32, "LWORD": 64}

BITWISE = """PROGRAM Main
VAR a, b, r_and, r_amp, r_or, r_xor, r_not : {t}; c_eq, c_ne, c_lt, c_ge : BOOL; END_VAR
r_and := a AND b;
r_amp := a & b;
r_or := a OR b;
r_xor := a XOR b;
r_not := NOT a;
c_eq := a = b;
c_ne := a <> b;
c_lt := a < b;
c_ge := a >= b;
END_PROGRAM"""


@PASSES
@pytest.mark.parametrize("name", BITS)
def test_every_bit_string_operator_on_every_bit_string_type(name: str, optimise):
    bits = BITS[name]
    mask = (1 << bits) - 1
    compiled = compile_program(checked(BITWISE.format(t=name)), optimise=optimise)
    for a, b in [(0b1100, 0b1010), (mask, 1), (0, mask), (1 << (bits - 1), (1 << (bits - 1)) | 5)]:
        controller = Controller(compiled)
        main = controller.add_program("Main")
        main.v_A, main.v_B = a, b
        controller.run(1)
        assert (main.v_R_AND, main.v_R_AMP, main.v_R_OR, main.v_R_XOR, main.v_R_NOT,
                main.v_C_EQ, main.v_C_NE, main.v_C_LT, main.v_C_GE) == \
            (a & b, a & b, a | b, a ^ b, mask - a, a == b, a != b, a < b, a >= b), (name, a, b)


@PASSES
def test_every_boolean_operator_on_bool(optimise):
    src = """PROGRAM Main
VAR a, b, r_and, r_amp, r_or, r_xor, r_not, c_eq, c_ne : BOOL; END_VAR
r_and := a AND b;
r_amp := a & b;
r_or := a OR b;
r_xor := a XOR b;
r_not := NOT a;
c_eq := a = b;
c_ne := a <> b;
END_PROGRAM"""
    compiled = compile_program(checked(src), optimise=optimise)
    for a in (False, True):
        for b in (False, True):
            controller = Controller(compiled)
            main = controller.add_program("Main")
            main.v_A, main.v_B = a, b
            controller.run(1)
            got = (main.v_R_AND, main.v_R_AMP, main.v_R_OR, main.v_R_XOR, main.v_R_NOT, main.v_C_EQ, main.v_C_NE)
            assert got == (a and b, a and b, a or b, a != b, not a, a == b, a != b)
            assert all(type(v) is bool for v in got)


REALS = """PROGRAM Main
VAR a, b, r_add, r_sub, r_mul, r_div, r_neg, r_pow : {t}; c_eq, c_ne, c_lt, c_le, c_gt, c_ge : BOOL; END_VAR
r_add := a + b;
r_sub := a - b;
r_mul := a * b;
r_div := a / b;
r_neg := -a;
r_pow := a ** b;
c_eq := a = b;
c_ne := a <> b;
c_lt := a < b;
c_le := a <= b;
c_gt := a > b;
c_ge := a >= b;
END_PROGRAM"""


def same(x: float, y: float) -> bool:
    return (math.isnan(x) and math.isnan(y)) or (x == y and math.copysign(1, x) == math.copysign(1, y))


@pytest.mark.parametrize("dialect", ["iec", "nj"])
@PASSES
@pytest.mark.parametrize("name", ["REAL", "LREAL"])
def test_every_real_operator_on_real_and_lreal(name: str, optimise, dialect: str):
    # REAL: the operands are float32 values; one operation's double result rounded once to
    # float32 is the float32 operation's result (NumPy's float32 arithmetic), under iec
    # (rounded at the store) and nj (rounded where computed) alike.  A zero divisor gives
    # IEEE 754's infinities and NaN, not a fault.
    rnd = f32 if name == "REAL" else float
    compiled = compile_program(checked(REALS.format(t=name), dialect), optimise=optimise)
    for a, b in [(1.1, 3.3), (-2.5, 0.1), (3.0, 0.0), (-3.0, 0.0), (0.0, 0.0), (1e30, 1e10), (2.0, 0.5)]:
        a, b = rnd(a), rnd(b)
        controller = Controller(compiled)
        main = controller.add_program("Main")
        main.v_A, main.v_B = a, b
        controller.run(1)
        if name == "REAL":
            x, y = np.float32(a), np.float32(b)
            with np.errstate(all="ignore"):
                expected = [float(x + y), float(x - y), float(x * y), float(x / y), float(-x)]
        else:
            with np.errstate(all="ignore"):
                expected = [a + b, a - b, a * b, float(np.float64(a) / np.float64(b)), -a]
        with np.errstate(all="ignore"):
            expected.append(rnd(float(np.power(np.float64(a), np.float64(b)))) if a > 0 else None)
        got = [main.v_R_ADD, main.v_R_SUB, main.v_R_MUL, main.v_R_DIV, main.v_R_NEG, main.v_R_POW]
        if expected[-1] is None:
            got[-1] = None
        assert all(same(g, e) if e is not None else g is None for g, e in zip(got, expected)), (a, b, got, expected)
        assert (main.v_C_EQ, main.v_C_NE, main.v_C_LT, main.v_C_LE, main.v_C_GT, main.v_C_GE) == \
            (a == b, a != b, a < b, a <= b, a > b, a >= b)
        assert controller.faults == []


@pytest.mark.parametrize("dialect", ["iec", "nj"])
@PASSES
def test_time_operators(optimise, dialect: str):
    # TIME is a signed 64-bit count of nanoseconds; TIME * REAL rounds to the nearest ns.
    src = """PROGRAM Main
VAR a, b, r_add, r_sub, r_mul, r_div, r_mulr, r_rmul : TIME; k : INT; f : LREAL; c_lt, c_eq : BOOL; END_VAR
r_add := a + b;
r_sub := a - b;
r_mul := a * k;
r_div := a / k;
r_mulr := a * f;
r_rmul := f * a;
c_lt := a < b;
c_eq := a = b;
END_PROGRAM"""
    half = 1 << 62
    for a, b, k, f in [(1_500_000_000, 250_000_000, -3, 0.5), (half, half, 4, 1.25), (7, 2, 2, 0.3)]:
        main, faults, _ = run(src, optimise, dialect, inputs={"a": a, "b": b, "k": k, "f": f})
        assert (main.v_R_ADD, main.v_R_SUB, main.v_R_MUL, main.v_R_DIV, main.v_R_MULR, main.v_R_RMUL,
                main.v_C_LT, main.v_C_EQ) == \
            (wrap(a + b, 64, True), wrap(a - b, 64, True), wrap(a * k, 64, True), trunc_div(a, k),
             wrap(round(a * f), 64, True), wrap(round(a * f), 64, True), a < b, a == b), (a, b, k, f)
        assert faults == []


MIXED = """PROGRAM Main
VAR i, j : INT; d, e : DINT; q : DINT; big : BOOL; r1, r2, r3 : REAL; l1, l2 : LREAL; k, m : INT; n : DINT;
    ud : UDINT; dd : DINT; uq : UDINT; END_VAR
d := i + j;
big := i + j > 0;
q := (i + j) / 2;
e := d + i * j;
l1 := r1 / r2;
l2 := (r1 + r2) * r3;
n := k / m;
END_PROGRAM"""


@PASSES
@pytest.mark.parametrize("dialect", ["iec", "codesys", "nj"])
def test_mixed_widths_and_reals_differ_by_dialect_as_w501_says(optimise, dialect: str):
    # i = j = 30000 (INT): iec/codesys keep the exact 60000 (wrapped only when stored); nj
    # computes INT + INT in INT: 60000 overflows to -5536 before it is stored into a DINT,
    # compared or divided (W501 6-5-3).  `d + i * j`: under nj the INT product 900,000,000
    # overflows in INT before the DINT sum takes it.
    # REAL / REAL into an LREAL: the double quotient (iec), the float32 one (nj).
    # INT#-32768 / -1 into a DINT: 32768 exact; nj overflows the INT quotient to -32768.
    main, faults, _ = run(MIXED, optimise, dialect, inputs={
        "i": 30000, "j": 30000, "r1": f32(0.1), "r2": f32(0.2), "r3": 3.0, "k": -32768, "m": -1})
    a, b, c = np.float32(0.1), np.float32(0.2), np.float32(3.0)
    if dialect == "nj":
        s = wrap(60000, 16, True)
        expected = (s, False, trunc_div(s, 2), s + wrap(900_000_000, 16, True),
                    float(a / b), float((a + b) * c), -32768)
    else:
        expected = (60000, True, 30000, 60000 + 900_000_000,
                    float(a) / float(b), (float(a) + float(b)) * float(c), 32768)
    assert (main.v_D, main.v_BIG, main.v_Q, main.v_E, main.v_L1, main.v_L2, main.v_N) == expected
    assert faults == []


def test_nj_divides_a_signed_operand_as_the_unsigned_type():
    # W501's ranking: UDINT / DINT is UDINT, so DINT -1 is 4294967295: 10 / 4294967295 = 0.
    src = """PROGRAM Main
VAR ud : UDINT; dd : DINT; uq, um : UDINT; END_VAR
uq := ud / dd;
um := ud MOD dd;
END_PROGRAM"""
    for optimise in (EVERY, NONE):
        main, faults, _ = run(src, optimise, "nj", inputs={"ud": 10, "dd": -1})
        assert (main.v_UQ, main.v_UM, faults) == (0, 10, [])
