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
    # the fault names the operator's column: `/` and MOD at column 12 of `r_div := a / b;`
    controller = Controller(compile_program(checked(src), optimise=optimise))
    again = controller.add_program("Main")
    again.v_A, again.v_B = 9, 0
    controller.run(1)
    assert [(f.line, f.col) for f in controller.faults] == [(line_of(src, "a / b"), 12), (line_of(src, "a MOD b"), 12)]
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
VAR i, j : INT; d, e : DINT; q : DINT; big : BOOL; r1, r2, r3, r4, r5 : REAL; l1, l2 : LREAL; k, m : INT; n : DINT;
    ud : UDINT; dd : DINT; uq : UDINT; END_VAR
d := i + j;
big := i + j > 0;
q := (i + j) / 2;
e := d + i * j;
l1 := r4 / r5;
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
        "i": 30000, "j": 30000, "r1": f32(0.1), "r2": f32(0.2), "r3": 3.0, "r4": 2.0, "r5": 3.0,
        "k": -32768, "m": -1})
    a, b, c = np.float32(0.1), np.float32(0.2), np.float32(3.0)
    two, three = np.float32(2.0), np.float32(3.0)
    if dialect == "nj":       # 2 / 3 in float32: 0.6666666865348816 (docs/nj501.md)
        s = wrap(60000, 16, True)
        expected = (s, False, trunc_div(s, 2), s + wrap(900_000_000, 16, True),
                    float(two / three), float((a + b) * c), -32768)
    else:
        expected = (60000, True, 30000, 60000 + 900_000_000,
                    2.0 / 3.0, (float(a) + float(b)) * float(c), 32768)
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


# ================================== statements.py: every statement kind x every way it ends

def program(decls: str, body: str) -> str:
    return f"PROGRAM Main\nVAR {decls} END_VAR\n{body}\nEND_PROGRAM\n"


V = "x, y, z, w, k, s, i, j, n, lo, hi, st : INT;"

# id: (declarations, body, inputs, expected variables, faults as (code, text of the line))
STATEMENTS = {
    # ---- IF
    "IF then": (V, "IF x > 0 THEN y := 1; ELSE y := 2; END_IF;\nz := 3;", {"x": 5}, {"y": 1, "z": 3}, []),
    "IF else": (V, "IF x > 0 THEN y := 1; ELSE y := 2; END_IF;\nz := 3;", {"x": -5}, {"y": 2, "z": 3}, []),
    "IF false, no else": (V, "IF x > 0 THEN y := 1; END_IF;\nz := 3;", {"x": 0, "y": 9}, {"y": 9, "z": 3}, []),
    "IF condition faults: no branch": (V, "IF 10 / x > 0 THEN y := 1; ELSE y := 2; END_IF;\nz := 3;",
                                       {"x": 0, "y": 9}, {"y": 9, "z": 3}, [("F-DIV-ZERO", "IF 10")]),
    "IF condition faults, no else": (V, "IF 10 / x > 0 THEN y := 1; END_IF;\nz := 3;",
                                     {"x": 0, "y": 9}, {"y": 9, "z": 3}, [("F-DIV-ZERO", "IF 10")]),
    "IF branch statement faults": (V, "IF x > 0 THEN\n y := 10 / z;\n w := 1;\nEND_IF;",
                                   {"x": 1, "y": 9}, {"y": 9, "w": 1}, [("F-DIV-ZERO", "y := 10")]),
    "ELSIF first": (V, "IF x > 10 THEN y := 1; ELSIF x > 0 THEN y := 2; ELSIF x > -10 THEN y := 3; "
                       "ELSE y := 4; END_IF;", {"x": 50}, {"y": 1}, []),
    "ELSIF second": (V, "IF x > 10 THEN y := 1; ELSIF x > 0 THEN y := 2; ELSIF x > -10 THEN y := 3; "
                        "ELSE y := 4; END_IF;", {"x": 5}, {"y": 2}, []),
    "ELSIF third": (V, "IF x > 10 THEN y := 1; ELSIF x > 0 THEN y := 2; ELSIF x > -10 THEN y := 3; "
                       "ELSE y := 4; END_IF;", {"x": -5}, {"y": 3}, []),
    "ELSIF else": (V, "IF x > 10 THEN y := 1; ELSIF x > 0 THEN y := 2; ELSIF x > -10 THEN y := 3; "
                      "ELSE y := 4; END_IF;", {"x": -50}, {"y": 4}, []),
    "ELSIF none, no else": (V, "IF x > 10 THEN y := 1; ELSIF x > 0 THEN y := 2; END_IF;", {"x": -5, "y": 9},
                            {"y": 9}, []),
    "ELSIF condition faults: no branch": (V, "IF x > 10 THEN y := 1; ELSIF 10 / x > 0 THEN y := 2; "
                                             "ELSE y := 4; END_IF;\nz := 3;", {"x": 0, "y": 9},
                                          {"y": 9, "z": 3}, [("F-DIV-ZERO", "ELSIF 10")]),
    "ELSIF later condition not evaluated": (V, "IF x > 10 THEN y := 1; ELSIF 10 / (x - 50) > 0 THEN y := 2; "
                                               "END_IF;", {"x": 50}, {"y": 1}, []),
    # ---- CASE
    **{f"CASE {k}": (V, "CASE k OF 1: y := 10; 2, 3: y := 20; 5..7: y := 30; ELSE y := 40; END_CASE;\nz := 3;",
                     {"k": k}, {"y": y, "z": 3}, [])
       for k, y in [(1, 10), (2, 20), (3, 20), (4, 40), (5, 30), (6, 30), (7, 30), (8, 40), (-1, 40), (0, 40)]},
    **{f"CASE no else {k}": (V, "CASE k OF 1: y := 10; 2, 3: y := 20; 5..7: y := 30; END_CASE;",
                             {"k": k, "y": 9}, {"y": y}, [])
       for k, y in [(1, 10), (3, 20), (4, 9), (7, 30), (8, 9), (0, 9)]},
    **{f"CASE negative {k}": (V, "CASE k OF -5..-1: y := 1; 0: y := 2; -9, 9: y := 3; END_CASE;",
                              {"k": k, "y": 7}, {"y": y}, [])
       for k, y in [(-5, 1), (-1, 1), (0, 2), (-9, 3), (9, 3), (-6, 7), (1, 7)]},
    "CASE empty clause": (V, "CASE k OF 1: ; 2: y := 2; END_CASE;", {"k": 1, "y": 9}, {"y": 9}, []),
    "CASE only else": (V, "CASE k OF ELSE y := 2; END_CASE;", {"k": 1}, {"y": 2}, []),
    "CASE selector faults: no clause": (V, "CASE 10 / k OF 1: y := 1; ELSE y := 2; END_CASE;\nz := 3;",
                                        {"k": 0, "y": 9}, {"y": 9, "z": 3}, [("F-DIV-ZERO", "CASE")]),
    # ---- FOR
    "FOR constant": (V, "FOR i := 1 TO 5 DO s := s + i; END_FOR;", {}, {"s": 15, "i": 6}, []),
    "FOR BY 2": (V, "FOR i := 1 TO 10 BY 2 DO s := s + i; END_FOR;", {}, {"s": 25, "i": 11}, []),
    "FOR BY -1": (V, "FOR i := 5 TO 1 BY -1 DO s := s + i; END_FOR;", {}, {"s": 15, "i": 0}, []),
    "FOR BY -2": (V, "FOR i := 10 TO 1 BY -2 DO s := s + i; END_FOR;", {}, {"s": 30, "i": 0}, []),
    "FOR not run": (V, "FOR i := 5 TO 1 DO s := s + i; END_FOR;", {}, {"s": 0, "i": 5}, []),
    "FOR not run, BY -1": (V, "FOR i := 1 TO 5 BY -1 DO s := s + i; END_FOR;", {}, {"s": 0, "i": 1}, []),
    "FOR two blocks": (V, "FOR i := 1 TO 4 DO s := s + i; IF i > 2 THEN w := w + i; END_IF; z := z + 1; END_FOR;",
                       {}, {"s": 10, "w": 7, "z": 4, "i": 5}, []),
    "FOR variable bounds": (V, "FOR i := lo TO hi DO s := s + i; END_FOR;", {"lo": 3, "hi": 6},
                            {"s": 18, "i": 7}, []),
    "FOR variable bounds, not run": (V, "FOR i := lo TO hi DO s := s + i; END_FOR;", {"lo": 7, "hi": 3},
                                     {"s": 0, "i": 7}, []),
    "FOR variable bounds BY -1": (V, "FOR i := hi TO lo BY -1 DO s := s + i; END_FOR;", {"lo": 3, "hi": 6},
                                  {"s": 18, "i": 2}, []),
    "FOR variable bounds BY -1, not run": (V, "FOR i := hi TO lo BY -1 DO s := s + i; END_FOR;",
                                           {"lo": 6, "hi": 3}, {"s": 0, "i": 3}, []),
    "FOR variable start, constant end, BY -1": (V, "FOR i := hi TO 1 BY -1 DO s := s + i; END_FOR;", {"hi": 6},
                                                {"s": 21, "i": 0}, []),
    "FOR variable start, constant end, BY -1, not run": (V, "FOR i := hi TO 1 BY -1 DO s := s + i; END_FOR;",
                                                         {"hi": 0}, {"s": 0, "i": 0}, []),
    "FOR variable start, constant end, BY -2": (V, "FOR i := hi TO 1 BY -2 DO s := s + i; END_FOR;", {"hi": 6},
                                                {"s": 12, "i": 0}, []),
    "FOR variable bounds BY 3": (V, "FOR i := lo TO hi BY 3 DO s := s + i; END_FOR;", {"lo": 1, "hi": 10},
                                 {"s": 22, "i": 13}, []),
    "FOR variable step": (V, "FOR i := lo TO hi BY st DO s := s + i; END_FOR;", {"lo": 1, "hi": 10, "st": 3},
                          {"s": 22, "i": 13}, []),
    "FOR variable negative step": (V, "FOR i := lo TO hi BY st DO s := s + i; END_FOR;",
                                   {"lo": 10, "hi": 1, "st": -3}, {"s": 22, "i": -2}, []),
    "FOR variable step, not run": (V, "FOR i := lo TO hi BY st DO s := s + i; END_FOR;",
                                   {"lo": 10, "hi": 1, "st": 3}, {"s": 0, "i": 10}, []),
    "FOR variable step 0": (V, "FOR i := lo TO hi BY st DO s := s + i; END_FOR;",
                            {"lo": 1, "hi": 10, "st": 0}, {"s": 0}, [("F-PERIOD", "FOR")]),
    "FOR EXIT": (V, "FOR i := 1 TO 10 DO IF i = 4 THEN EXIT; END_IF; s := s + i; END_FOR;", {},
                 {"s": 6, "i": 4}, []),
    "FOR EXIT, variable end": (V, "FOR i := 1 TO hi DO IF i = 4 THEN EXIT; END_IF; s := s + i; END_FOR;",
                               {"hi": 10}, {"s": 6, "i": 4}, []),
    "FOR CONTINUE": (V, "FOR i := 1 TO 5 DO IF i = 3 THEN CONTINUE; END_IF; s := s + i; END_FOR;", {},
                     {"s": 12, "i": 6}, []),
    "FOR nested EXIT leaves the inner loop": (V, "FOR i := 1 TO 3 DO FOR j := 1 TO 3 DO IF j = 2 THEN EXIT; "
                                                 "END_IF; s := s + 10 * i + j; END_FOR; END_FOR;", {},
                                              {"s": 11 + 21 + 31, "i": 4, "j": 2}, []),
    "FOR bounds fault: no iteration": (V, "FOR i := 1 TO 10 / z DO s := s + 1; END_FOR;\nw := 1;", {"i": 7},
                                       {"s": 0, "i": 7, "w": 1}, [("F-DIV-ZERO", "FOR")]),
    "FOR start faults: no iteration": (V, "FOR i := 10 / z TO 5 DO s := s + 1; END_FOR;\nw := 1;", {"i": 7},
                                       {"s": 0, "i": 7, "w": 1}, [("F-DIV-ZERO", "FOR")]),
    "FOR body faults: the loop goes on": (V, "FOR i := 1 TO 3 DO\n s := s + 10 / (i - 2);\n w := w + 1;\nEND_FOR;",
                                          {}, {"s": 0, "w": 3, "i": 4}, [("F-DIV-ZERO", "s := s + 10")]),
    "FOR up to the type's maximum": ("k : SINT; s : DINT;", "FOR k := 125 TO 127 DO s := s + k; END_FOR;", {},
                                     {"s": 378, "k": -128}, []),
    # ---- WHILE
    "WHILE": (V, "WHILE i < 5 DO i := i + 1; s := s + i; END_WHILE;", {}, {"i": 5, "s": 15}, []),
    "WHILE not run": (V, "WHILE i < 5 DO i := i + 1; s := s + i; END_WHILE;", {"i": 7}, {"i": 7, "s": 0}, []),
    "WHILE EXIT": (V, "WHILE i < 50 DO i := i + 1; IF i = 3 THEN EXIT; END_IF; s := s + i; END_WHILE;", {},
                   {"i": 3, "s": 3}, []),
    "WHILE CONTINUE": (V, "WHILE i < 5 DO i := i + 1; IF i = 3 THEN CONTINUE; END_IF; s := s + i; END_WHILE;", {},
                       {"i": 5, "s": 12}, []),
    "WHILE condition faults: the loop ends": (V, "WHILE 10 / (3 - i) > 0 DO i := i + 1; END_WHILE;\nw := 1;", {},
                                              {"i": 3, "w": 1}, [("F-DIV-ZERO", "WHILE")]),
    "WHILE body faults: the loop goes on": (V, "WHILE i < 3 DO\n i := i + 1;\n s := s + 10 / (i - 2);\nEND_WHILE;",
                                            {}, {"i": 3, "s": -10 + 10}, [("F-DIV-ZERO", "s := s + 10")]),
    # ---- REPEAT
    "REPEAT": (V, "REPEAT i := i + 1; s := s + i; UNTIL i >= 3 END_REPEAT;", {}, {"i": 3, "s": 6}, []),
    "REPEAT runs once": (V, "REPEAT i := i + 1; UNTIL i > 0 END_REPEAT;", {"i": 7}, {"i": 8}, []),
    "REPEAT CONTINUE goes to the test": (V, "REPEAT i := i + 1; IF i < 3 THEN CONTINUE; END_IF; s := s + 1; "
                                            "UNTIL i >= 5 END_REPEAT;", {}, {"i": 5, "s": 3}, []),
    "REPEAT CONTINUE to a true test": (V, "REPEAT i := i + 1; IF i >= 2 THEN CONTINUE; END_IF; s := s + 1; "
                                          "UNTIL i >= 2 END_REPEAT;", {}, {"i": 2, "s": 1}, []),
    "REPEAT EXIT": (V, "REPEAT i := i + 1; IF i = 2 THEN EXIT; END_IF; s := s + 1; UNTIL i >= 5 END_REPEAT;", {},
                    {"i": 2, "s": 1}, []),
    "REPEAT condition faults: the loop ends": (V, "REPEAT i := i + 1; UNTIL 10 / (2 - i) < 0 END_REPEAT;\nw := 1;",
                                               {}, {"i": 2, "w": 1}, [("F-DIV-ZERO", "REPEAT")]),
    # ---- RETURN and EXIT around other statements
    "RETURN": (V, "s := 1;\nIF x > 0 THEN RETURN; END_IF;\ns := 2;", {"x": 1}, {"s": 1}, []),
    "RETURN not taken": (V, "s := 1;\nIF x > 0 THEN RETURN; END_IF;\ns := 2;", {"x": 0}, {"s": 2}, []),
    "RETURN in a WHILE": (V, "WHILE TRUE DO i := i + 1; IF i = 4 THEN RETURN; END_IF; END_WHILE;\nw := 1;", {},
                          {"i": 4, "w": 0}, []),
    "EXIT in a CASE in a loop": (V, "FOR i := 1 TO 5 DO CASE i OF 3: EXIT; END_CASE; s := s + i; END_FOR;", {},
                                 {"s": 3, "i": 3}, []),
    "index fault abandons the store": ("a : ARRAY[1..3] OF INT; i, w : INT;", "a[i] := 5;\nw := a[2] + 1;",
                                       {"i": 4}, {"w": 1}, [("F-INDEX", "a[i] := 5")]),
}


@PASSES
@pytest.mark.parametrize("row", STATEMENTS.values(), ids=STATEMENTS.keys())
def test_every_statement_kind_and_every_way_it_ends(row, optimise):
    decls, body, inputs, expected, faults = row
    src = program(decls, body)
    main, got, _ = run(src, optimise, inputs=inputs)
    assert {name: getattr(main, "v_" + name.upper()) for name in expected} == expected
    assert got == [(code, line_of(src, text), 1) for code, text in faults]


RETURN_IN_FOR = program(V, "FOR i := 1 TO 5 DO s := s + i; IF i = 2 THEN RETURN; END_IF; END_FOR;\nw := 1;")


def test_return_in_a_for_leaves_the_variable_at_its_iteration():
    # IEC 61131-3: RETURN leaves the POU at once; the FOR variable of a PROGRAM keeps the
    # value of the iteration that returned (2), s the sum so far (1 + 2).
    main, faults, _ = run(RETURN_IN_FOR, NONE)
    assert (main.v_S, main.v_I, main.v_W, faults) == (3, 2, 0, [])


@pytest.mark.parametrize("optimise", [EVERY, Optimisations.only("unroll")], ids=["every pass", "unroll"])
def test_return_in_an_unrolled_for_leaves_the_variable_at_its_iteration(optimise):
    main, faults, _ = run(RETURN_IN_FOR, optimise)
    assert (main.v_S, main.v_I, main.v_W, faults) == (3, 2, 0, [])


# The same in an FB instance and in nested loops (both unrolled, both variables kept), by hand:
# the inner loop returns at i = 2, j = 3 after s = 1*1 + 1*2 + 1*3 + 2*1 + 2*2 + 2*3 = 18.
RETURN_IN_FB_FORS = """FUNCTION_BLOCK Walk
VAR_OUTPUT s, i, j, w : INT; END_VAR
FOR i := 1 TO 3 DO FOR j := 1 TO 3 DO s := s + i * j; IF i * j = 6 THEN RETURN; END_IF; END_FOR; END_FOR;
w := 1;
END_FUNCTION_BLOCK
PROGRAM Main
VAR f : Walk; s, i, j, w : INT; END_VAR
f();
s := f.s; i := f.i; j := f.j; w := f.w;
END_PROGRAM
"""


@pytest.mark.parametrize("optimise", [NONE, EVERY, Optimisations.only("unroll")], ids=["none", "every pass", "unroll"])
def test_return_in_nested_fors_of_an_fb_leaves_both_variables_at_their_iteration(optimise):
    main, faults, _ = run(RETURN_IN_FB_FORS, optimise)
    assert (main.v_S, main.v_I, main.v_J, main.v_W, faults) == (18, 2, 3, 0, [])


# A FUNCTION's output as the FOR variable is seen by its caller: 1 + 2 + 3 = 6 when k = 3 returns.
RETURN_FROM_FUNCTION_FOR = """FUNCTION Upto : INT
VAR_OUTPUT k : INT; END_VAR
FOR k := 1 TO 5 DO Upto := Upto + k; IF k = 3 THEN RETURN; END_IF; END_FOR;
END_FUNCTION
PROGRAM Main
VAR s, i : INT; END_VAR
s := Upto(k => i);
END_PROGRAM
"""


@pytest.mark.parametrize("optimise", [NONE, EVERY, Optimisations.only("unroll")], ids=["none", "every pass", "unroll"])
def test_return_in_a_function_for_gives_its_output_variable_at_its_iteration(optimise):
    main, faults, _ = run(RETURN_FROM_FUNCTION_FOR, optimise)
    assert (main.v_S, main.v_I, faults) == (6, 3, [])


GLOBAL_FOR = """VAR_GLOBAL g : INT; END_VAR
FUNCTION Skip : INT
g := g + 1;
Skip := g;
END_FUNCTION
PROGRAM Main
VAR s, z, w, lo, hi, st : INT; END_VAR
{body}
END_PROGRAM
"""

# A FOR whose variable is a global runs as a loop that tests the variable each time (any call
# may change it, as on a PLC): the body's changes count, and CONTINUE still increments.
GLOBAL_FORS = {
    "constant": ("FOR g := 1 TO 5 DO s := s + g; END_FOR;", {}, {"s": 15, "g": 6}, []),
    "not run": ("FOR g := 5 TO 1 DO s := s + g; END_FOR;", {}, {"s": 0, "g": 5}, []),
    "BY -2": ("FOR g := 9 TO 1 BY -2 DO s := s + g; END_FOR;", {}, {"s": 25, "g": -1}, []),
    "a call changes it": ("FOR g := 1 TO 10 DO s := s + g; Skip(); END_FOR;", {}, {"s": 25, "g": 11}, []),
    "a call changes it, BY -2": ("FOR g := 9 TO 1 BY -2 DO s := s + g; Skip(); END_FOR;", {},
                                 {"s": 9 + 8 + 7 + 6 + 5 + 4 + 3 + 2 + 1, "g": 0}, []),
    "CONTINUE increments": ("FOR g := 1 TO 6 DO IF g = 3 THEN Skip(); CONTINUE; END_IF; s := s + g; END_FOR;", {},
                            {"s": 14, "g": 7}, []),
    "EXIT": ("FOR g := 1 TO 9 DO IF g = 4 THEN EXIT; END_IF; s := s + g; END_FOR;", {}, {"s": 6, "g": 4}, []),
    "variable bounds": ("FOR g := lo TO hi DO s := s + g; END_FOR;", {"lo": 3, "hi": 6}, {"s": 18, "g": 7}, []),
    "variable step": ("FOR g := lo TO hi BY st DO s := s + g; END_FOR;", {"lo": 1, "hi": 10, "st": 3},
                      {"s": 22, "g": 13}, []),
    "variable negative step": ("FOR g := lo TO hi BY st DO s := s + g; END_FOR;", {"lo": 10, "hi": 1, "st": -3},
                               {"s": 22, "g": -2}, []),
    "variable step, a call changes it": ("FOR g := lo TO hi BY st DO s := s + g; Skip(); END_FOR;",
                                         {"lo": 1, "hi": 10, "st": 2}, {"s": 1 + 4 + 7 + 10, "g": 13}, []),
    "end faults": ("g := 7;\nFOR g := 1 TO 10 / z DO s := s + 1; END_FOR;\nw := 1;", {}, {"s": 0, "g": 7, "w": 1},
                   [("F-DIV-ZERO", "FOR")]),
    "start faults": ("g := 7;\nFOR g := 10 / z TO 5 DO s := s + 1; END_FOR;\nw := 1;", {},
                     {"s": 0, "g": 7, "w": 1}, [("F-DIV-ZERO", "FOR")]),
    "up to the type's maximum": ("FOR g := 32766 TO 32767 DO s := s + 1; IF g = 32767 THEN EXIT; END_IF; END_FOR;",
                                 {}, {"s": 2, "g": 32767}, []),
}


@PASSES
@pytest.mark.parametrize("row", GLOBAL_FORS.values(), ids=GLOBAL_FORS.keys())
def test_a_for_over_a_global_tests_its_variable_each_time(row, optimise):
    body, inputs, expected, faults = row
    src = GLOBAL_FOR.format(body=body)
    compiled = compile_program(checked(src), optimise=optimise)
    controller = Controller(compiled)
    main = controller.add_program("Main")
    for name, value in inputs.items():
        setattr(main, "v_" + name.upper(), value)
    controller.run(1)
    got = {name: getattr(compiled.globals if name == "g" else main, "v_" + name.upper()) for name in expected}
    assert got == expected
    assert [(f.code, f.line, f.scan) for f in controller.faults] == \
        [(code, line_of(src, text), 1) for code, text in faults]


@PASSES
@pytest.mark.parametrize("dialect", ["iec", "nj"])
def test_a_case_selector_and_an_index_see_the_dialects_sum(optimise, dialect: str):
    # i + j = 60000 exact (iec); an INT overflow to -5536 under nj (W501 6-5-3: a CASE selector
    # and an array index see the value of the expression in its type).
    src = program("i, j, y, z : INT; a : ARRAY[-6000..-5000] OF INT;",
                  "CASE i + j OF -5536: y := 1; ELSE y := 2; END_CASE;\nz := a[i + j];")
    main, faults, _ = run(src, optimise, dialect, inputs={"i": 30000, "j": 30000})
    if dialect == "nj":
        assert (main.v_Y, main.v_Z, faults) == (1, 0, [])
    else:
        assert (main.v_Y, main.v_Z, faults) == (2, 0, [("F-INDEX", 4, 1)])


FUNCTION_RETURNS = """FUNCTION F : INT
VAR_INPUT n : INT; END_VAR
VAR i : INT; END_VAR
F := -1;
FOR i := 1 TO 10 DO
  IF i = n THEN F := i * 10; RETURN; END_IF;
END_FOR;
F := -2;
END_FUNCTION
FUNCTION G : INT
VAR_INPUT n : INT; END_VAR
G := 5;
WHILE TRUE DO
  G := G + 1;
  IF G >= n THEN RETURN; END_IF;
END_WHILE;
END_FUNCTION
FUNCTION H : INT
VAR_INPUT n : INT; END_VAR
H := 100 / n;
H := H + 1;
END_FUNCTION
PROGRAM Main
VAR a, b, c, d, e : INT; END_VAR
a := F(4);
b := F(11);
c := G(9);
d := H(0);
e := H(50);
END_PROGRAM
"""


@PASSES
def test_return_leaves_a_function_with_its_result_so_far(optimise):
    main, faults, _ = run(FUNCTION_RETURNS, optimise)
    # H(0): the division faults inside H (line 20); H := H + 1 still runs: 0 + 1.
    assert (main.v_A, main.v_B, main.v_C, main.v_D, main.v_E) == (40, -2, 9, 1, 3)
    assert faults == [("F-DIV-ZERO", 20, 1)]


@PASSES
def test_set_and_reset_assignments(optimise):
    src = program("a, b, c, d, x, y : BOOL;", "a S= x;\nb S= y;\nc R= x;\nd R= y;")
    main, _, _ = run(src, optimise, "codesys", inputs={"x": True, "y": False, "c": True, "d": True, "b": True})
    # S=: TRUE when the value is TRUE, else unchanged; R=: FALSE when TRUE, else unchanged.
    assert (main.v_A, main.v_B, main.v_C, main.v_D) == (True, True, False, True)


# ========================================== cost.py: every weight of the NJ time estimate

# docs/nj501.md "What a scan costs", by hand: load 1, store 1, integer op 1, integer / and
# MOD 4, REAL + - 2, REAL * 2, REAL / 8, compare 1, subscript 2, SQRT 8, transcendental 30,
# other standard function or conversion 4, user call 10, argument 1 (an aggregate: per
# element), element moved 2, branch 1, loop iteration 2, standard FB 20.  A block is charged
# round(units * 598) ps.
COST_POUS = {  # declared only where a row calls them (each row is a program of its own)
    "Pair": "TYPE Pair : STRUCT x : LREAL; y : ARRAY[1..3] OF INT; END_STRUCT; END_TYPE\n",
    "Acc": "FUNCTION_BLOCK Acc\nVAR_INPUT In : INT; END_VAR\nVAR_OUTPUT Out : INT; END_VAR\nOut := Out + In;\n"
           "END_FUNCTION_BLOCK\n",
    "F(": "FUNCTION F : INT\nVAR_INPUT a : INT; b : INT := 2; END_VAR\nF := a + b;\nEND_FUNCTION\n",
    "G(": "FUNCTION G : INT\nVAR_IN_OUT v : INT; END_VAR\nG := 1;\nEND_FUNCTION\n",
    "H(": "FUNCTION H : INT\nVAR_INPUT arr : ARRAY[1..5] OF INT; END_VAR\nH := 1;\nEND_FUNCTION\n",
    "KA(": "FUNCTION KA : INT\nVAR_IN_OUT arr : ARRAY[1..5] OF INT; END_VAR\nKA := 1;\nEND_FUNCTION\n",
}


def cost_program(body: str) -> str:
    pous = "".join(text for key, text in COST_POUS.items() if key in ("Pair", "Acc") or key in body)
    return pous + program(COST_VARS, body)


COST_VARS = ("i, j, k : INT; x, y, z : LREAL; r1, r2 : REAL; b, c : BOOL; w1, w2 : WORD; t : TIME; "
             "a, a2 : ARRAY[1..5] OF INT; m : ARRAY[1..3, 1..4] OF LREAL; p, q : Pair; "
             "s16, u16 : STRING[16]; s7, u7 : STRING[7]; acc : Acc; t1 : TON;")

COSTS = {  # body: units by hand (per path: every block that ran)
    "copy": ("i := j;", 2), "literal": ("i := 5;", 2),
    "INT +": ("i := j + k;", 4), "INT -": ("i := j - k;", 4), "INT *": ("i := j * k;", 4),
    "INT /": ("i := j / k;", 7), "INT MOD": ("i := j MOD k;", 7),
    "LREAL +": ("x := y + z;", 5), "LREAL -": ("x := y - z;", 5), "LREAL *": ("x := y * z;", 5),
    "LREAL /": ("x := y / z;", 11), "REAL +": ("r1 := r1 + r2;", 5), "REAL /": ("r1 := r1 / r2;", 11),
    "LREAL **": ("x := y ** z;", 33),
    **{f"compare {op}": (f"b := j {op} k;", 4) for op in ("=", "<>", "<", "<=", ">", ">=")},
    "REAL compare": ("b := x < y;", 4),
    "AND": ("b := b AND c;", 4), "OR": ("b := b OR c;", 4), "XOR": ("b := b XOR c;", 4), "&": ("b := b & c;", 4),
    "WORD AND": ("w1 := w1 AND w2;", 4),
    "INT negation": ("i := -j;", 3), "LREAL negation": ("x := -y;", 4), "NOT": ("b := NOT c;", 3),
    "WORD NOT": ("w1 := NOT w2;", 3),
    "subscript read": ("i := a[j];", 5), "constant subscript": ("i := a[2];", 5),
    "two subscripts": ("x := m[k, j];", 8), "subscript store": ("a[j] := i;", 5),
    "subscript in a subscript": ("i := a[a[j] + 1];", 10),
    "member read": ("x := p.x;", 2), "member store": ("p.x := y;", 2), "member's element": ("i := p.y[j];", 5),
    "array assignment": ("a := a2;", 10), "structure assignment": ("p := q;", 8),
    "STRING[16] assignment": ("s16 := u16;", 6), "STRING[7] assignment": ("s7 := u7;", 2),
    "SQRT": ("x := SQRT(y);", 11),
    **{name: (f"x := {name}(y);", 33) for name in ("SIN", "COS", "TAN", "ASIN", "ACOS", "ATAN", "EXP", "LN", "LOG")},
    "EXPT": ("x := EXPT(y, z);", 35),
    "ABS": ("i := ABS(j);", 7), "MIN": ("i := MIN(j, k);", 9), "LIMIT": ("i := LIMIT(j, k, i);", 11),
    "conversion": ("x := INT_TO_LREAL(j);", 7),
    "ADD as +": ("i := ADD(j, k);", 4), "GT as >": ("b := GT(j, k);", 4), "MUL as LREAL *": ("x := MUL(y, z);", 5),
    # a user FUNCTION: call 10 and its arguments by value (1 + the load), the callee's own block
    "FUNCTION": ("i := F(j, k);", 10 + 2 * 2 + 1 + 4),
    "FUNCTION with a default": ("i := F(a := j);", 10 + 2 + 1 + 4),
    "FUNCTION, in-out by reference": ("i := G(v := j);", 10 + 1 + 1 + 2),
    "FUNCTION, array by value": ("i := H(arr := a);", 10 + 5 + 1 + 2),
    "FUNCTION, array in-out": ("i := KA(arr := a);", 10 + 1 + 1 + 2),
    "FB in ST": ("acc(In := j);", 10 + 2 + 4), "standard FB": ("t1(IN := b, PT := t);", 20 + 2 * 2),
    "two statements": ("i := j;\nx := y + z;", 2 + 5),
}


def scan_times(src: str, inputs: dict) -> dict:
    """{pass switch: (faults, ps per scan)} of one scan of `src`, checked once, compiled with
    every pass and with none (the charges come from the ST text: the same either way)."""
    program_ = checked(src)
    out = {}
    for name, optimise in (("every pass", EVERY), ("no pass", NONE)):
        controller = Controller(compile_program(program_, optimise=optimise))
        main = controller.add_program("Main")
        for key, value in inputs.items():
            setattr(main, "v_" + key.upper(), value)
        controller.run(1)
        out[name] = ([(f.code, f.line) for f in controller.faults], list(controller.task_times["Primary"]))
    return out


@pytest.mark.parametrize("row", COSTS.values(), ids=COSTS.keys())
def test_every_weight_of_the_estimate(row):
    body, units = row
    expected = ([], [units * PS_PER_UNIT])
    assert scan_times(cost_program(body), {"j": 1, "k": 3, "y": 0.5, "z": 2.0}) == \
        {"every pass": expected, "no pass": expected}


BRANCHES = {  # body, inputs, units on that path
    "IF taken": ("IF b THEN i := 1; END_IF;", {"b": True}, 2 + 2),
    "IF not taken": ("IF b THEN i := 1; END_IF;", {"b": False}, 2),
    "IF ELSE, then": ("IF b THEN i := 1; ELSE i := 2; j := 3; END_IF;", {"b": True}, 2 + 2),
    "IF ELSE, else": ("IF b THEN i := 1; ELSE i := 2; j := 3; END_IF;", {"b": False}, 2 + 4),
    "ELSIF first": ("IF b THEN i := 1; ELSIF c THEN i := 2; ELSE i := 3; END_IF;", {"b": True}, 2 + 2),
    "ELSIF second": ("IF b THEN i := 1; ELSIF c THEN i := 2; ELSE i := 3; END_IF;", {"c": True}, 2 + 2 + 2),
    "ELSIF else": ("IF b THEN i := 1; ELSIF c THEN i := 2; ELSE i := 3; END_IF;", {}, 2 + 2 + 2),
    "IF comparison": ("IF j > k THEN i := 1; END_IF;", {"j": 4}, 4 + 2),
    # CASE: the selector, then one branch per label compared to reach the clause
    **{f"CASE {j}": ("CASE j OF 1: i := 1; 2, 3: i := 2; 4..6: i := 3; ELSE i := 4; END_CASE;", {"j": j}, units)
       for j, units in [(1, 1 + 1 + 2), (3, 1 + 3 + 2), (5, 1 + 4 + 2), (9, 1 + 4 + 2)]},
    "CASE selector sum": ("CASE j + k OF 1: i := 1; END_CASE;", {"j": 1, "k": 0}, 3 + 1 + 2),
    # FOR: bounds (and step) and the store of the variable, then per iteration the loop's 2
    # and the body's first block; a FOR that may EXIT charges each iteration as it runs
    "FOR constant": ("FOR k := 1 TO 3 DO i := i + k; END_FOR;", {}, 3 + 3 * (2 + 4)),
    "FOR BY 2": ("FOR k := 1 TO 6 BY 2 DO i := i + k; END_FOR;", {}, 4 + 3 * (2 + 4)),
    "FOR variable count": ("FOR k := 1 TO j DO i := i + k; END_FOR;", {"j": 4}, 3 + 4 * (2 + 4)),
    "FOR variable count 0": ("FOR k := 1 TO j DO i := i + k; END_FOR;", {"j": 0}, 3),
    "FOR variable step": ("FOR k := 1 TO 6 BY j DO i := i + k; END_FOR;", {"j": 2}, 4 + 3 * (2 + 4)),
    "FOR two blocks, IF taken": ("FOR k := 1 TO 2 DO i := i + k; IF b THEN j := j + 1; END_IF; END_FOR;",
                                 {"b": True}, 3 + 2 * (2 + 4 + 2) + 2 * 4),
    "FOR two blocks, IF not taken": ("FOR k := 1 TO 2 DO i := i + k; IF b THEN j := j + 1; END_IF; END_FOR;",
                                     {"b": False}, 3 + 2 * (2 + 4 + 2)),
    "FOR EXIT": ("FOR k := 1 TO 5 DO IF k = 3 THEN EXIT; END_IF; i := i + 1; END_FOR;", {},
                 3 + 2 * (2 + 4 + 4) + (2 + 4 + 1)),
    "FOR CONTINUE": ("FOR k := 1 TO 3 DO IF k = 2 THEN CONTINUE; END_IF; i := i + 1; END_FOR;", {},
                     3 + 2 * (2 + 4 + 4) + (2 + 4 + 1)),
    "nested FOR": ("FOR k := 1 TO 2 DO FOR j := 1 TO 3 DO i := i + 1; END_FOR; END_FOR;", {},
                   3 + 2 * (2 + 3 + 3 * (2 + 4))),
    # WHILE and REPEAT: per iteration the loop's 2, the test and its branch, the first block
    "WHILE": ("WHILE j < 3 DO j := j + 1; END_WHILE;", {"j": 0}, 3 * (2 + 4 + 4)),
    "WHILE not run": ("WHILE j < 3 DO j := j + 1; END_WHILE;", {"j": 5}, 0),
    "REPEAT": ("REPEAT j := j + 1; UNTIL j >= 3 END_REPEAT;", {"j": 0}, 3 * (2 + 4 + 4)),
    "REPEAT once": ("REPEAT j := j + 1; UNTIL j >= 3 END_REPEAT;", {"j": 5}, 2 + 4 + 4),
    "RETURN": ("i := 1;\nIF b THEN RETURN; END_IF;\ni := 2;", {"b": True}, 2 + 2 + 1),
    "RETURN not taken": ("i := 1;\nIF b THEN RETURN; END_IF;\ni := 2;", {"b": False}, 2 + 2 + 2),
}


@pytest.mark.parametrize("row", BRANCHES.values(), ids=BRANCHES.keys())
def test_every_path_charges_what_ran(row):
    body, inputs, units = row
    expected = ([], [units * PS_PER_UNIT])
    assert scan_times(cost_program(body), inputs) == {"every pass": expected, "no pass": expected}


RUNAWAY = program("n : DINT;", "WHILE TRUE DO n := n + 1; END_WHILE;")


@PASSES
@pytest.mark.parametrize("limit_ns", [1, 4, 5, 597, 598, 599, 1000, 5000])
def test_f_period_lands_after_the_iterations_the_budget_covers(limit_ns: int, optimise):
    # One iteration: loop 2 + TRUE loaded 1 + branch 1 + `n := n + 1` 4 = 8 units = 4784 ps,
    # charged before the body runs; the scan ends when the charges pass the limit, so
    # floor(limit / 4784) iterations run (598 ns: exactly 125).  The time reported is what
    # was charged, the failing iteration's included.
    main, faults, times = run(RUNAWAY, optimise, limit_ns=limit_ns)
    ran = limit_ns * 1000 // 4784
    assert (main.v_N, faults, times) == (ran, [("F-PERIOD", 3, 1)], [(ran + 1) * 4784])


@PASSES
@pytest.mark.parametrize("limit_ns, n, faults", [(360, 0, [("F-PERIOD", 3, 1)]), (361, 100, [])])
def test_a_whole_for_is_charged_and_tested_before_its_first_iteration(limit_ns, n, faults, optimise):
    # setup 3 units + 100 iterations x (loop 2 + `n := n + 1` 4) = 603 units = 360,594 ps.
    main, got, times = run(program("k, j : INT; n : DINT;", "FOR k := 1 TO j DO n := n + 1; END_FOR;"),
                           optimise, inputs={"j": 100}, limit_ns=limit_ns)
    assert (main.v_N, got, times) == (n, faults, [603 * PS_PER_UNIT])


SIX_CLAUSES = "CASE j OF 1: i := 1; 2: i := 2; 3: i := 3; 4: i := 4; 5: i := 5; 6: i := 6; END_CASE;"

NO_BRANCH = {  # body, inputs, units: with no ELSE, a path that takes no branch pays every test it made
    "ELSIF none": ("IF b THEN i := 1; ELSIF c THEN i := 2; END_IF;", {}, 2 + 2),
    "two ELSIFs none": ("IF b THEN i := 1; ELSIF c THEN i := 2; ELSIF j > k THEN i := 3; END_IF;", {}, 2 + 2 + 4),
    # a condition that may fault (INT division): the IF is not tested in place
    "ELSIF none, a division": ("IF b THEN i := 1; ELSIF j / k > k THEN i := 2; END_IF;", {"j": 1, "k": 3}, 2 + 9),
    "ELSIF none, constants": ("IF FALSE THEN i := 1; ELSIF FALSE THEN i := 2; END_IF;", {}, 2 + 2),
    "CASE no match": ("CASE j OF 1: i := 1; 2, 3: i := 2; END_CASE;", {"j": 9}, 1 + 3),
    # six clauses: with every pass the labels are tested by halves (optimise/halves.py)
    "CASE no match above, six clauses": (SIX_CLAUSES, {"j": 9}, 1 + 6),
    "CASE no match below, six clauses": (SIX_CLAUSES, {"j": 0}, 1 + 6),
    "CASE last of six": (SIX_CLAUSES, {"j": 6}, 1 + 6 + 2),
}


@pytest.mark.parametrize("row", NO_BRANCH.values(), ids=NO_BRANCH.keys())
def test_a_path_through_no_branch_pays_every_test_it_made(row):
    body, inputs, units = row
    expected = ([], [units * PS_PER_UNIT])
    assert scan_times(cost_program(body), inputs) == {"every pass": expected, "no pass": expected}


# ============================= exprs.py / support.py: subscripts out of range, by dimension

INDEXED = """TYPE Pair : STRUCT x : LREAL; y : ARRAY[1..3] OF INT; END_STRUCT; END_TYPE
FUNCTION Pick : LREAL
VAR_INPUT i, j : INT; END_VAR
VAR m : ARRAY[1..3, 1..4] OF LREAL; END_VAR
Pick := m[i, j] + 1.0;
END_FUNCTION
PROGRAM Main
VAR m : ARRAY[1..3, 1..4] OF LREAL; a : ARRAY[1..3] OF INT; p : Pair; i, j : INT; x : LREAL; w : INT;
    ps : ARRAY[0..1] OF Pair; END_VAR
{body}
w := 1;
END_PROGRAM
"""

INDEX_FAULTS = {  # body, i, j: the fault's message (F-INDEX names the first index out of range)
    "first of two": ("x := m[i, j];", 0, 1, "index 0 (dimension 1) of 'm' out of bounds 1..3"),
    "second of two": ("x := m[i, j];", 2, 5, "index 5 (dimension 2) of 'm' out of bounds 1..4"),
    "both of two": ("x := m[i, j];", 4, 9, "index 4 (dimension 1) of 'm' out of bounds 1..3"),
    "first of two, sums": ("x := m[i + 1, j - 1];", -1, 2, "index 0 (dimension 1) of 'm' out of bounds 1..3"),
    "store, first of two": ("m[i, j] := 2.0;", 0, 0, "index 0 (dimension 1) of 'm' out of bounds 1..3"),
    "store, second of two": ("m[i, j] := 2.0;", 1, 0, "index 0 (dimension 2) of 'm' out of bounds 1..4"),
    "in a FUNCTION": ("x := Pick(i, j);", 3, 7, "index 7 (dimension 2) of 'm' out of bounds 1..4"),
    "in a FUNCTION, first": ("x := Pick(i, j);", 9, 7, "index 9 (dimension 1) of 'm' out of bounds 1..3"),
    "one dimension": ("w := a[i];", 4, 0, "index 4 of 'a' out of bounds 1..3"),
    "one dimension, below": ("a[i] := 3;", -2, 0, "index -2 of 'a' out of bounds 1..3"),
    "a member's": ("w := p.y[j];", 0, 0, "index 0 of 'p.y' out of bounds 1..3"),
    "an element's member's": ("w := ps[i].y[j];", 1, 4, "index 4 of 'ps[...].y' out of bounds 1..3"),
}


@PASSES
@pytest.mark.parametrize("row", INDEX_FAULTS.values(), ids=INDEX_FAULTS.keys())
def test_a_subscript_out_of_range_faults_naming_its_dimension(row, optimise):
    # The statement is abandoned with F-INDEX (the next one runs); indices of PROGRAM
    # variables read once are evaluated into temps: all of them before the message is made
    # (a first index out of range crashed the scan with UnboundLocalError until session 13).
    body, i, j, message = row
    src = INDEXED.format(body=body)
    controller = Controller(compile_program(checked(src), optimise=optimise))
    main = controller.add_program("Main")
    main.v_I, main.v_J = i, j
    controller.run(1)
    line = 5 if "FUNCTION" in message or body.startswith("x := Pick") else line_of(src, body)
    assert [(f.code, f.message, f.line) for f in controller.faults] == [("F-INDEX", message, line)]
    assert main.v_W == 1


# ===================== calls.py: every POU kind x every parameter kind (and EN/ENO, defaults)

CALLS = """TYPE Pt : STRUCT c : INT; d : INT; END_STRUCT; END_TYPE
FUNCTION F : INT
VAR_INPUT a : INT; b : INT := 2; END_VAR
F := 10 * a + b;
END_FUNCTION
FUNCTION FO : INT
VAR_INPUT a : INT; END_VAR
VAR_OUTPUT o : INT; q : BOOL; END_VAR
o := a * 3;
q := a > 0;
FO := a + 1;
END_FUNCTION
FUNCTION Inc : INT
VAR_IN_OUT v : INT; END_VAR
v := v + 1;
Inc := v;
END_FUNCTION
FUNCTION Fill : INT
VAR_IN_OUT arr : ARRAY[1..3] OF INT; END_VAR
arr[2] := 77;
Fill := arr[1];
END_FUNCTION
FUNCTION ByValue : INT
VAR_INPUT arr : ARRAY[1..3] OF INT; pt : Pt; END_VAR
arr[1] := arr[1] + 100;
pt.c := 9;
ByValue := arr[1] + pt.c;
END_FUNCTION
FUNCTION Fresh : INT
VAR c : INT := 5; END_VAR
c := c + 1;
Fresh := c;
END_FUNCTION
FUNCTION SumOpen : DINT
VAR_IN_OUT vals : ARRAY[*] OF INT; END_VAR
VAR i : DINT; END_VAR
FOR i := LOWER_BOUND(vals, 1) TO UPPER_BOUND(vals, 1) DO SumOpen := SumOpen + vals[i]; END_FOR;
END_FUNCTION
FUNCTION_BLOCK Acc
VAR_INPUT In : INT; Tab : ARRAY[1..2] OF INT; END_VAR
VAR_OUTPUT Out : INT; Pos : BOOL; END_VAR
VAR_IN_OUT Ref : INT; END_VAR
Out := Out + In + Tab[1];
Pos := Out > 0;
Ref := Ref * 2;
END_FUNCTION_BLOCK
FUNCTION_BLOCK Box
VAR k : INT := 4; END_VAR
METHOD Times : INT
VAR_INPUT m : INT; END_VAR
Times := k * m;
k := k + 1;
END_METHOD
METHOD Twice : INT
Twice := THIS.Times(2);
END_METHOD
END_FUNCTION_BLOCK
PROGRAM Main
VAR j, k, n, r1, r2, r3, r4, r5, r6, r7, r8, r9, r10, r11, r12, r13, r14, r15, r16, r17 : INT;
    o1, o2, n2, n3, n4, n5 : INT; q1, ok1, ok2, ok3, ok4, en, neg : BOOL; arr, arr2 : ARRAY[1..3] OF INT;
    open1 : ARRAY[-2..1] OF INT; pt : Pt; acc, acc2 : Acc; box : Box; tab : ARRAY[1..2] OF INT;
    big : DINT; h : REAL; s1, low, high : DINT; END_VAR
r1 := F(j, k);
r2 := F(b := k, a := j);
r3 := F(a := j);
r4 := FO(j, o => o1, q => q1);
r5 := FO(a := k);
FO(a := j, o => o2);
r6 := Inc(v := n);
r7 := Inc(v := arr[3]) + Inc(v := pt.d);
arr[1] := 5;
r8 := Fill(arr := arr);
arr2[1] := 1;
pt.c := 1;
r9 := ByValue(arr := arr2, pt := pt);
r10 := Fresh() + Fresh();
r11 := F(EN := en, a := j, ENO => ok1);
r12 := F(EN := NOT en, a := j, ENO => ok2);
Inc(EN := en, v := n2, ENO => ok3);
Inc(EN := NOT en, v := n3, ENO => ok4);
open1[-2] := 3;
open1[1] := 4;
s1 := SumOpen(vals := open1);
low := LOWER_BOUND(open1, 1);
tab[1] := 10;
n4 := 3;
acc(In := 2, Tab := tab, Ref := n4, Out => r13, NOT Pos => neg);
tab[1] := 1000;
acc(Ref := n4);
r14 := acc.Out;
n5 := 5;
acc2(EN := en, In := 1, Ref := n5);
r15 := box.Times(3);
r16 := box.Twice();
r17 := box.Times(m := 1);
END_PROGRAM
"""


@PASSES
def test_calls_of_every_pou_kind_with_every_parameter_kind(optimise):
    # (codesys: a FUNCTION may write its VAR_INPUT, which shows that an array or a structure
    # input is the callee's own copy.)
    main, faults, _ = run(CALLS, optimise, "codesys", inputs={"j": 3, "k": 4, "n": 6, "en": False})
    got = {name: getattr(main, "v_" + name.upper()) for name in (
        "r1", "r2", "r3", "r4", "o1", "q1", "r5", "o2", "r6", "n", "r7", "r8", "r9", "r10", "r11", "ok1", "r12",
        "ok2", "n2", "ok3", "n3", "ok4", "s1", "low", "r13", "neg", "r14", "n4", "n5", "r15", "r16", "r17")}
    assert got == {
        "r1": 34, "r2": 34, "r3": 32,                       # positional, named in any order, default b = 2
        "r4": 4, "o1": 9, "q1": True, "r5": 5, "o2": 9,     # VAR_OUTPUT by `=>`, unconnected, in a statement
        "r6": 7, "n": 7, "r7": 2,                           # VAR_IN_OUT: the caller's variable, element, member
        "r8": 5,                                            # an in-out array is the caller's (below: arr[2])
        "r9": 101 + 9,                                      # inputs by value: the callee's own copies
        "r10": 12,                                          # a FUNCTION's locals start again every call
        "r11": 0, "ok1": False, "r12": 32, "ok2": True,     # EN FALSE: not called, the type's initial value
        "n2": 0, "ok3": False, "n3": 1, "ok4": True,
        "s1": 7, "low": -2,                                 # ARRAY[*]: the caller's bounds travel along
        "r13": 12, "neg": False, "r14": 24, "n4": 12,       # FB: inputs kept, arrays copied, in-out the caller's
        "n5": 5,                                            # FB with EN FALSE: not called
        "r15": 12, "r16": 10, "r17": 6,                     # METHODs on the instance's variables, THIS
    }
    assert (list(main.v_ARR), list(main.v_ARR2), main.v_PT.v_C, main.v_PT.v_D) == ([5, 77, 1], [1, 0, 0], 1, 1)
    assert faults == []


# ================================================= initial.py: initial values of every kind

INITIALS = """TYPE Seven : INT := 7; END_TYPE
TYPE Color : (Red, Green, Blue); END_TYPE
TYPE Level : (Low := 10, High := 20); END_TYPE
TYPE Percent : INT (5..100); END_TYPE
TYPE Pt : STRUCT c : INT := 11; d : INT; e : Seven; END_STRUCT; END_TYPE
FUNCTION_BLOCK Acc
VAR_INPUT In : INT; END_VAR
VAR_OUTPUT Out : INT; END_VAR
Out := Out + In;
END_FUNCTION_BLOCK
VAR_GLOBAL g1 : DINT := -40000; g2 : ARRAY[0..2] OF REAL := [0.1, 2(0.5)]; END_VAR
PROGRAM Main
VAR CONSTANT K : INT := 5; END_VAR
VAR
  s8 : SINT; u8 : USINT; i16 : INT; u64 : ULINT; r : REAL; l : LREAL; b : BOOL; s : STRING[5]; t : TIME; w : WORD;
  i1 : INT := -7; r1 : REAL := 0.1; l1 : LREAL := 0.1; b1 : BOOL := TRUE; t1 : TIME := T#1.5s;
  d1 : DATE := D#1970-01-02; tod1 : TOD := TOD#01:00:00; s1 : STRING[5] := 'abc'; w1 : WORD := 16#FFFF;
  c1 : INT := 3 * 4 + 1; c2 : INT := K * 2; c3 : LINT := -(1 + 2);
  a1 : ARRAY[1..6] OF INT := [1, 2(7), 3]; a2 : ARRAY[1..2, 1..3] OF INT := [[1, 2, 3], [4, 5, 6]];
  a3 : ARRAY[1..2] OF REAL := [0.1, 0.2]; a4 : ARRAY[1..3] OF Seven; a5 : ARRAY[1..2] OF Pt := [(c := 1), (d := 2)];
  p1 : Pt; p2 : Pt := (c := 3, e := 4); x7 : Seven; x8 : Seven := 8;
  e1 : Color; e2 : Color := Blue; e3 : Level; e4 : Level := High; pc : Percent;
  fb : Acc := (In := 5);
END_VAR
;
END_PROGRAM
"""


@PASSES
def test_every_kind_of_initial_value(optimise):
    # IEC 61131-3: a variable without an initial value takes its type's default (0, 0.0,
    # FALSE, '', T#0s; an enumeration's first value; a subrange's lower limit; a derived
    # type's own initial value, also as a member or an element); REAL initial values are
    # float32 values; an array initializer repeats with n(...) and leaves the rest 0.
    main, faults, _ = run(INITIALS, optimise)
    got = {name: getattr(main, "v_" + name.upper()) for name in (
        "s8", "u8", "i16", "u64", "r", "l", "b", "s", "t", "w", "i1", "r1", "l1", "b1", "t1", "d1", "tod1", "s1",
        "w1", "c1", "c2", "c3", "x7", "x8", "e1", "e2", "e3", "e4", "pc")}
    assert got == {"s8": 0, "u8": 0, "i16": 0, "u64": 0, "r": 0.0, "l": 0.0, "b": False, "s": "", "t": 0, "w": 0,
                   "i1": -7, "r1": f32(0.1), "l1": 0.1, "b1": True, "t1": 1_500_000_000,
                   "d1": 86_400 * 10**9, "tod1": 3_600 * 10**9, "s1": "abc", "w1": 0xFFFF,
                   "c1": 13, "c2": 10, "c3": -3, "x7": 7, "x8": 8, "e1": 0, "e2": 2, "e3": 10, "e4": 20, "pc": 5}
    assert all(type(got[k]) is float for k in ("r", "l", "r1", "l1")) and type(got["b"]) is bool
    assert list(main.v_A1) == [1, 7, 7, 3, 0, 0]
    assert list(main.v_A2) == [1, 2, 3, 4, 5, 6]
    assert list(main.v_A3) == [f32(0.1), f32(0.2)]
    assert list(main.v_A4) == [7, 7, 7]
    assert [(p.v_C, p.v_D, p.v_E) for p in main.v_A5] == [(1, 0, 7), (11, 2, 7)]
    assert (main.v_P1.v_C, main.v_P1.v_D, main.v_P1.v_E) == (11, 0, 7)
    assert (main.v_P2.v_C, main.v_P2.v_D, main.v_P2.v_E) == (3, 0, 4)
    assert (main.v_FB.v_IN, main.v_FB.v_OUT) == (5, 0)
    # every instance its own objects (a maker per aggregate, not a shared one)
    assert main.v_A5[0] is not main.v_A5[1] and main.v_P1 is not main.v_P2


def test_initial_values_of_globals_and_a_fresh_instance_each():
    compiled = compile_program(checked(INITIALS))
    assert (compiled.globals.v_G1, list(compiled.globals.v_G2)) == (-40000, [f32(0.1), 0.5, 0.5])
    one, two = compiled.new("Main"), compiled.new("Main")
    one.v_A1[0] = 99
    one.v_P1.v_C = 99
    assert (two.v_A1[0], two.v_P1.v_C) == (1, 11)


TEMPS = """FUNCTION_BLOCK Counter
VAR_INPUT step : INT; END_VAR
VAR_OUTPUT total : INT; tmp_seen : INT; END_VAR
VAR_TEMP t : INT := 100; END_VAR
t := t + step;
tmp_seen := t;
total := total + step;
END_FUNCTION_BLOCK
PROGRAM Main
VAR c : Counter; a, b : INT; END_VAR
c(step := 2);
a := c.tmp_seen;
c(step := 3);
b := c.tmp_seen;
END_PROGRAM
"""


@PASSES
def test_var_temp_starts_again_at_every_call_and_instance_variables_keep_their_values(optimise):
    main, faults, _ = run(TEMPS, optimise, scans=2)
    # scan 1: t = 100 + 2, then 100 + 3; total 2 + 3; scan 2: the same t, total 10
    assert (main.v_A, main.v_B, main.v_C.v_TOTAL, faults) == (102, 103, 10, [])


# ======================== scope.py: where variables live, seen from the values they end with

SCOPES = """VAR_GLOBAL gt : ARRAY[1..3] OF INT; gn : INT; END_VAR
FUNCTION Inc : INT
VAR_IN_OUT v : INT; END_VAR
v := v + 1;
Inc := v;
END_FUNCTION
FUNCTION PutGlobal : INT
VAR_INPUT i : INT; END_VAR
gt[i] := gt[i] + 10 * i;
gn := gn + 1;
PutGlobal := gn;
END_FUNCTION
FUNCTION_BLOCK Edges
VAR_INPUT up : BOOL R_EDGE; down : BOOL F_EDGE; END_VAR
VAR_OUTPUT ups, downs : INT; END_VAR
IF up THEN ups := ups + 1; END_IF;
IF down THEN downs := downs + 1; END_IF;
END_FUNCTION_BLOCK
FUNCTION_BLOCK Shared
VAR k : INT; seen : INT; END_VAR
METHOD Bump : INT
k := k + 10;
Bump := k;
END_METHOD
k := 1;
k := k + 1;
k := k + THIS.Bump();
seen := k + k;
END_FUNCTION_BLOCK
FUNCTION_BLOCK Early
VAR_INPUT x : INT; z : INT; END_VAR
VAR_OUTPUT s : INT; END_VAR
s := 1;
s := s + 1;
s := s + 100 / z;
IF x > 0 THEN RETURN; END_IF;
s := s * 10;
END_FUNCTION_BLOCK
PROGRAM Main
VAR e : Edges; sh : Shared; e1, e0 : Early; x, y, r : INT; clk : ARRAY[1..5] OF BOOL; i : INT; END_VAR
x := 5;
r := Inc(v := x) + x;
y := x;
FOR i := 1 TO 5 DO
  e(up := clk[i], down := clk[i]);
END_FOR;
sh();
e1(x := 1, z := 0);
e0(x := 0, z := 50);
PutGlobal(2);
PutGlobal(2);
END_PROGRAM
"""


@PASSES
def test_variables_live_where_every_reader_sees_every_store(optimise):
    main, faults, _ = run(SCOPES, optimise, inputs={"clk": [True, False, True, True, False]})
    assert (main.v_R, main.v_Y) == (12, 6)        # the in-out stored into x before `+ x` read it
    # R_EDGE counts FALSE -> TRUE (the memory starts FALSE): TRUE at 1 and 3; F_EDGE TRUE -> FALSE: at 2 and 5
    assert (main.v_E.v_UPS, main.v_E.v_DOWNS) == (2, 2)
    # a METHOD changes k while the body runs: the body reads it again (1 + 1, + (2 + 10))
    assert (main.v_SH.v_K, main.v_SH.v_SEEN) == (14, 28)
    # a fault and a RETURN keep what the body stored before them (s is used often: a local)
    assert (main.v_E1.v_S, main.v_E0.v_S) == (2, 40)
    assert faults == [("F-DIV-ZERO", line_of(SCOPES, "s := s + 100 / z"), 1)]


@PASSES
def test_a_global_array_changed_in_a_function_is_the_programs(optimise):
    compiled = compile_program(checked(SCOPES), optimise=optimise)
    controller = Controller(compiled)
    controller.add_program("Main")
    controller.run(2)
    assert (list(compiled.globals.v_GT), compiled.globals.v_GN) == ([0, 80, 0], 4)


# ============== classes the seed-28 survivors named (docs/mutation.md, session 13), each as a family

ENABLED = """TYPE Pt : STRUCT c : INT := 11; d : INT; END_STRUCT; END_TYPE
FUNCTION FS : Pt
VAR_INPUT a : INT; END_VAR
FS.c := a;
END_FUNCTION
FUNCTION FA : ARRAY[1..2] OF INT
VAR_INPUT a : INT; END_VAR
FA[2] := a;
END_FUNCTION
FUNCTION FI : INT
VAR_INPUT a : INT; END_VAR
FI := a;
END_FUNCTION
PROGRAM Main
VAR p, p2 : Pt; q, q2 : ARRAY[1..2] OF INT; i, i2 : INT; en : BOOL; ok1, ok2, ok3 : BOOL; END_VAR
p.c := -1;
q[1] := -1;
i := -1;
p := FS(EN := en, a := 3, ENO => ok1);
q := FA(EN := en, a := 4, ENO => ok2);
i := FI(EN := en, a := 5, ENO => ok3);
p2 := FS(EN := NOT en, a := 3);
q2 := FA(EN := NOT en, a := 4);
i2 := FI(EN := NOT en, a := 5);
END_PROGRAM
"""


@PASSES
def test_en_false_gives_the_initial_value_of_every_result_type(optimise):
    # IEC 61131-3 6.6.1.2: with EN FALSE the function does not run, ENO is FALSE and the result
    # is its type's initial value: a structure's members' initial values, an array of zeros.
    main, faults, _ = run(ENABLED, optimise, inputs={"en": False})
    assert ((main.v_P.v_C, main.v_P.v_D), list(main.v_Q), main.v_I) == ((11, 0), [0, 0], 0)
    assert (main.v_OK1, main.v_OK2, main.v_OK3) == (False, False, False)
    assert ((main.v_P2.v_C, main.v_P2.v_D), list(main.v_Q2), main.v_I2) == ((3, 0), [0, 4], 5)
    assert faults == []


DESCRIBED = """TYPE Pt : STRUCT y : ARRAY[1..3] OF INT; END_STRUCT; END_TYPE
PROGRAM Main
VAR arr3 : ARRAY[1..3] OF INT; ra : REF_TO ARRAY[1..3] OF INT; rp : REF_TO Pt; p : Pt; i, x, w : INT; END_VAR
ra := REF(arr3);
rp := REF(p);
x := ra^[i];
x := rp^.y[i];
ra^[i] := 1;
w := 1;
END_PROGRAM
"""


@PASSES
def test_a_subscript_of_a_dereferenced_array_names_it_in_its_fault(optimise):
    controller = Controller(compile_program(checked(DESCRIBED), optimise=optimise))
    main = controller.add_program("Main")
    main.v_I = 0
    controller.run(1)
    assert [f.message for f in controller.faults] == [
        "index 0 of 'array' out of bounds 1..3", "index 0 of 'array.y' out of bounds 1..3",
        "index 0 of 'array' out of bounds 1..3"]
    assert main.v_W == 1


SHADOWED = """VAR_GLOBAL CONSTANT T : ARRAY[1..2] OF INT := [1, 2]; END_VAR
PROGRAM Main
VAR CONSTANT T : ARRAY[1..2] OF INT := [5, 9]; END_VAR
VAR arr : ARRAY[1..9] OF INT; small : ARRAY[1..3] OF INT; i, x, y : INT; END_VAR
arr[9] := 90;
x := arr[T[i]];
y := small[T[i]];
END_PROGRAM
"""


@PASSES
def test_a_constant_table_is_the_one_in_scope(optimise):
    # The local CONSTANT T (5, 9) hides the global one (1, 2): its elements index `arr` (9)
    # and are out of `small`'s range (F-INDEX); the global's range would skip that check.
    main, faults, _ = run(SHADOWED, optimise, inputs={"i": 2})
    assert (main.v_X, main.v_Y, faults) == (90, 0, [("F-INDEX", 7, 1)])


CONSTANTS = """VAR_GLOBAL CONSTANT GR : REAL := 0.1; END_VAR
PROGRAM Main
VAR CONSTANT C : REAL := 0.1; L : LREAL := 0.1; D : TIME := T#1s; END_VAR
VAR x : REAL; y : LREAL; b1, b2, b3, b4, b5 : BOOL; t0, t1 : TIME; k : REAL; END_VAR
x := C;
y := L;
b1 := x = C;
b2 := x = GR;
b3 := y = L;
b4 := x = L;
b5 := k < C;
t1 := t0 + D * 1.5;
END_PROGRAM
"""


@PASSES
@pytest.mark.parametrize("dialect", ["iec", "nj"])
def test_a_named_real_constant_has_its_types_value_where_it_is_read(optimise, dialect: str):
    # A REAL constant is the float32 value 0.1f (0.100000001490116...); compared with a REAL
    # variable holding it: equal; an LREAL 0.1 is the double 0.1, which the REAL 0.1f is not.
    # k = 0.1f too: k < C is FALSE.  D * 1.5 is 1.5 s in whole ns.
    main, faults, _ = run(CONSTANTS, optimise, dialect, inputs={"k": f32(0.1), "t0": 7})
    assert (main.v_X, main.v_Y) == (f32(0.1), 0.1)
    assert (main.v_B1, main.v_B2, main.v_B3, main.v_B4, main.v_B5) == (True, True, True, False, False)
    assert (main.v_T1, type(main.v_T1), faults) == (1_500_000_007, int, [])


ROWS_IN_LOOPS = """PROGRAM Main
VAR m : ARRAY[1..3, 1..4] OF INT; s, i, j, n, k : INT; pt_c : INT; END_VAR
FOR j := 1 TO n DO
  m[i + 1, j] := 10 * (i + 1) + j;
  s := s + m[i + 1, j] + m[k, j];
END_FOR;
END_PROGRAM
"""


@PASSES
def test_a_row_chosen_by_an_expression_inside_a_for(optimise):
    # m[2, 1..4] := 21..24; s = (21 + 22 + 23 + 24) + m[3, j] (all 0)
    main, faults, _ = run(ROWS_IN_LOOPS, optimise, inputs={"i": 1, "n": 4, "k": 3})
    assert (list(main.v_M)[4:8], main.v_S, faults) == ([21, 22, 23, 24], 90, [])


FLOW = """VAR_GLOBAL g : INT; END_VAR
FUNCTION ThroughFor : INT
VAR_INPUT n : INT; END_VAR
VAR a : ARRAY[1..3] OF INT; x : INT; s : INT; END_VAR
x := 1;
FOR g := 1 TO n DO
  s := s + a[x];
  x := x + 5;
END_FOR;
ThroughFor := s + x;
END_FUNCTION
FUNCTION ThroughCase : INT
VAR_INPUT k : INT; END_VAR
VAR a : ARRAY[1..3] OF INT; x : INT; END_VAR
x := 1;
CASE k OF 1: x := 10; 2: x := 2; END_CASE;
ThroughCase := a[x];
ThroughCase := ThroughCase + x;
END_FUNCTION
FUNCTION ThroughIf : INT
VAR_INPUT k : INT; END_VAR
VAR a : ARRAY[1..3] OF INT; x : INT; END_VAR
x := 1;
IF k = 1 THEN x := 10; ELSIF k = 2 THEN x := 2; END_IF;
ThroughIf := a[x];
ThroughIf := ThroughIf + x;
END_FUNCTION
PROGRAM Main
VAR r1, r2, r3, r4, r5 : INT; END_VAR
r1 := ThroughFor(2);
r2 := ThroughCase(1);
r3 := ThroughCase(2);
r4 := ThroughIf(1);
r5 := ThroughIf(3);
END_PROGRAM
"""


@PASSES
def test_a_local_stored_in_a_loop_or_a_branch_is_checked_where_it_is_read_after(optimise):
    # ThroughFor: x = 1, then 6 in the second iteration: a[6] is F-INDEX, that store is
    # abandoned, x becomes 11: 0 + 11.  ThroughCase(1): x = 10, a[10] F-INDEX, result
    # 0 + 10; (2): a[2] = 0, 2.  ThroughIf likewise.
    main, faults, _ = run(FLOW, optimise)
    assert (main.v_R1, main.v_R2, main.v_R3, main.v_R4, main.v_R5) == (11, 10, 2, 10, 1)
    assert faults == [("F-INDEX", line_of(FLOW, text), 1)
                      for text in ("s := s + a[x]", "ThroughCase := a[x]", "ThroughIf := a[x]")]


UNCONNECTED = """FUNCTION_BLOCK Holder
VAR_IN_OUT arr : ARRAY[1..2] OF INT; END_VAR
METHOD M : INT
VAR r : INT; END_VAR
CASE arr[1] OF 1: r := 1; END_CASE;
M := 5;
END_METHOD
END_FUNCTION_BLOCK
PROGRAM Main
VAR h : Holder; x : INT; END_VAR
x := h.M();
END_PROGRAM
"""


@PASSES
def test_a_case_on_an_unconnected_in_out_faults_in_its_own_statement(optimise):
    # The METHOD reads its FB's in-out before any call connected it: F-NULL-REF abandons the
    # CASE (line 5) and the METHOD goes on: M = 5.
    main, faults, _ = run(UNCONNECTED, optimise)
    assert (main.v_X, faults) == (5, [("F-NULL-REF", 5, 1)])


ENUMS = """TYPE Color : (Red, Green, Blue); END_TYPE
PROGRAM Main
VAR e : Color := Color#Green; f : Color; x, y : INT; END_VAR
CASE e OF Color#Red: x := 1; Color#Green: x := 2; END_CASE;
f := Color#Blue;
IF f = Color#Blue THEN y := 3; END_IF;
END_PROGRAM
"""


@PASSES
def test_typed_enumeration_literals(optimise):
    main, faults, _ = run(ENUMS, optimise)
    assert (main.v_E, main.v_F, main.v_X, main.v_Y, faults) == (1, 2, 2, 3, [])


WRITE_ONLY = """FUNCTION_BLOCK Tank
VAR lvl : INT; END_VAR
PROPERTY WriteOnly : INT
SET
lvl := WriteOnly;
END_SET
END_PROPERTY
END_FUNCTION_BLOCK
PROGRAM Main
VAR t : Tank; x : INT; END_VAR
x := t.WriteOnly;
END_PROGRAM
"""


def test_reading_a_property_without_get_is_refused_at_load():
    # A PROPERTY without GET has no value to read: the checker refuses the program where it is
    # read (CODESYS C0143), before the compiler would generate a getter that does not exist.
    from st_runtime import api

    with pytest.raises(api.LoadError) as raised:
        api.load_text(WRITE_ONLY, "m.st", "codesys")
    assert [(d.code, d.pos.line, d.pos.col, d.message) for d in raised.value.diagnostics] == [
        ("E-TYPE-018", 11, 6, "property Tank.WriteOnly has no GET and cannot be read")]


# ============================================ support.py and pysrc.py: run-time helpers, literals

RUNTIME_FAULTS = """TYPE Percent : INT (0..100); END_TYPE
INTERFACE IThing
METHOD Get : INT
END_METHOD
END_INTERFACE
FUNCTION Cell : INT
VAR_IN_OUT grid : ARRAY[*, *] OF INT; END_VAR
VAR_INPUT r, c : DINT; END_VAR
Cell := grid[r, c];
END_FUNCTION
PROGRAM Main
VAR pc : Percent := 50; i : INT; ri : REF_TO INT; thing : IThing; g : ARRAY[1..2, 1..4] OF INT;
    a, b, c, d, e, w : INT; bits : INT; bb : BYTE; END_VAR
pc := i;
a := ri^;
b := thing.Get();
c := Cell(grid := g, r := 2, c := 5);
d := Cell(grid := g, r := 3, c := 5);
e := Cell(grid := g, r := 2, c := 4);
bits.15 := TRUE;
bb.7 := TRUE;
bb.0 := TRUE;
bits.0 := bb.7;
w := 1;
END_PROGRAM
"""


@PASSES
def test_run_time_faults_of_the_helpers(optimise):
    controller = Controller(compile_program(checked(RUNTIME_FAULTS, "codesys"), optimise=optimise))
    main = controller.add_program("Main")
    main.v_I = 200
    main.v_G[7] = 8       # g[2, 4]
    controller.run(1)
    assert [(f.code, f.line, f.message) for f in controller.faults] == [
        ("F-SUBRANGE", 14, "200 is outside the subrange 0..100"),
        ("F-NULL-REF", 15, "dereference of NULL (the reference refers to nothing)"),
        ("F-NULL-REF", 16, "method call through an interface variable that refers to no instance"),
        ("F-INDEX", 9, "index 5 (dimension 2) of 'grid' out of bounds 1..4"),
        ("F-INDEX", 9, "index 3 (dimension 1) of 'grid' out of bounds 1..2")]
    # the bits: INT bit 15 is the sign (-32768), then bit 0 from BYTE bit 7; BYTE 16#81
    assert (main.v_PC, main.v_E, main.v_BITS, main.v_BB, main.v_W) == (50, 8, -32767, 0x81, 1)


def test_python_literals_of_every_constant():
    from st_runtime.compiler.pysrc import pyliteral, safe_name

    assert [pyliteral(v) for v in (True, False, 0, -7, 2**70, 0.1, -0.0, math.inf, -math.inf, "a'b", (1,), (1, 2.5),
                                   None)] == \
        ["True", "False", "0", "-7", str(2**70), "0.1", "-0.0", "_INF", "(-_INF)", "\"a'b\"", "(1,)", "(1, 2.5)",
         "None"]
    assert pyliteral(math.nan) == "_NAN"
    with pytest.raises(TypeError):
        pyliteral(object())
    assert safe_name("v_X1") == "v_X1"
    for bad in ("1x", "a-b", "a b", "", "x;y"):
        with pytest.raises(ValueError):
            safe_name(bad)


FOLDED_REAL = """PROGRAM Main
VAR CONSTANT C : REAL := 0.1; END_VAR
VAR x : REAL; y, l1, l2, l3, l4 : LREAL; END_VAR
l1 := C * 3.0 + y;
l2 := x * 3.0 + y;
l3 := (C + C) / 3.0 + y;
l4 := (x + x) / 3.0 + y;
END_PROGRAM
"""


@PASSES
@pytest.mark.parametrize("dialect", ["iec", "nj"])
def test_a_folded_real_operation_has_the_value_of_the_same_operation_on_variables(optimise, dialect: str):
    # docs/nj501.md: a folded REAL constant has the value the expression has at run time under
    # each dialect.  iec: the product of the REAL 0.1f and 3.0 stays a double inside the LREAL
    # sum; nj: each REAL operation is rounded to float32 (until session 13 the folded product
    # was rounded to float32 under iec too).
    main, faults, _ = run(FOLDED_REAL, optimise, dialect, inputs={"x": f32(0.1), "y": 0.0})
    c = np.float32(0.1)
    if dialect == "nj":
        product, quotient = float(c * np.float32(3.0)), float((c + c) / np.float32(3.0))
    else:
        product, quotient = float(c) * 3.0, (float(c) + float(c)) / 3.0
    assert (main.v_L1, main.v_L2, main.v_L3, main.v_L4, faults) == (product, product, quotient, quotient, [])


STANDARD = """FUNCTION Roots : LREAL
VAR_INPUT v : LREAL; END_VAR
VAR x, r : LREAL; END_VAR
x := v;
r := SQRT(x);
Roots := r + SIN(x) * 0.0;
END_FUNCTION
PROGRAM Main
VAR b : BYTE; w : WORD; d : DWORD; rb1, rb2, rb3, rb4, rb5 : BYTE; rw1, rw2, rw3, rw4 : WORD; rd : DWORD;
    x, r1, r2 : LREAL; END_VAR
rb1 := ROL(b, 1);
rb2 := ROR(b, 1);
rb3 := SHL(b, 1);
rb4 := SHR(b, 1);
rb5 := ROL(IN := b, N := 9);
rw1 := ROL(w, 1);
rw2 := ROR(w, 1);
rw3 := SHL(w, 1);
rw4 := SHR(w, 1);
rd := ROR(d, 4);
r1 := SQRT(x);
r2 := Roots(x);
END_PROGRAM
"""


@PASSES
def test_bit_shifts_and_rotations_take_the_width_of_their_input(optimise):
    # IEC 61131-3 table 29: ROL/ROR rotate within the bits of IN's type, SHL/SHR shift in zeros.
    # SQRT of a negative REAL is NaN, not a fault (library rule), also in a FUNCTION's locals.
    main, faults, _ = run(STANDARD, optimise, inputs={"b": 0x81, "w": 0x8001, "d": 0x0000_00F1, "x": -4.0})
    assert (main.v_RB1, main.v_RB2, main.v_RB3, main.v_RB4, main.v_RB5) == (0x03, 0xC0, 0x02, 0x40, 0x03)
    assert (main.v_RW1, main.v_RW2, main.v_RW3, main.v_RW4, main.v_RD) == (0x0003, 0xC000, 0x0002, 0x4000,
                                                                           0x1000_000F)
    assert math.isnan(main.v_R1) and math.isnan(main.v_R2) and faults == []
