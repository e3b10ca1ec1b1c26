"""Relational, boolean and bit operators executed at run time, on variables.

The checker folds operators on constants, so these tests keep every operand
in a variable: the compiled Python operator is what runs.  Each case is
worked out by hand; the six comparisons are checked together so that a
swapped operator (`>=` compiled as `>`, `<` as `<=`, ...) shows at the pair
where they differ (equal operands) and at the ones where they agree.

NaN: IEC 61131-3 does not say; IEEE 754-2008 section 5.11 makes every
ordered comparison and `=` with a NaN operand FALSE and `<>` TRUE (the runtime
produces NaN from 0.0 / 0.0, see `values.real_div`).  OMRON's W502 comparison
instructions were not checked against this: an open question for the NJ.
"""

from __future__ import annotations

import pytest

from st_runtime.api import load_text

OPS = ["<", "<=", ">", ">=", "=", "<>"]


def run(decls: str, body: str, cycles: int = 1):
    src = f"PROGRAM Main\nVAR\n{decls}\nEND_VAR\n{body}\nEND_PROGRAM\n"
    plc = load_text(src, "main.st").controller()
    main = plc.add_program("Main")
    plc.run(cycles)
    assert plc.faults == []
    return main


def compare(type_name: str, a: str, b: str) -> dict[str, bool]:
    """The six comparisons of `a` and `b` (ST literals) held in variables of `type_name`."""
    names = ["lt", "le", "gt", "ge", "eq", "ne"]
    decls = f"a : {type_name} := {a}; b : {type_name} := {b};\n" + " ".join(f"{n} : BOOL;" for n in names)
    body = "\n".join(f"{n} := a {op} b;" for n, op in zip(names, OPS))
    main = run(decls, body)
    return {op: main[n] for n, op in zip(names, OPS)}


LESS = {"<": True, "<=": True, ">": False, ">=": False, "=": False, "<>": True}
EQUAL = {"<": False, "<=": True, ">": False, ">=": True, "=": True, "<>": False}
GREATER = {"<": False, "<=": False, ">": True, ">=": True, "=": False, "<>": True}

# (type, a, b, expected): the extremes of each type, neighbours, and equality.
INTEGER_CASES = [
    ("SINT", "-128", "127", LESS), ("SINT", "-1", "0", LESS), ("SINT", "-128", "-128", EQUAL),
    ("SINT", "127", "126", GREATER),
    ("INT", "-32768", "32767", LESS), ("INT", "-1", "-1", EQUAL), ("INT", "0", "-1", GREATER),
    ("DINT", "-2147483648", "2147483647", LESS), ("DINT", "2147483647", "2147483647", EQUAL),
    ("DINT", "-2147483647", "-2147483648", GREATER),
    # LINT beyond 2**53: compared as integers, not as floats (2**62 + 1 > 2**62).
    ("LINT", "4611686018427387904", "4611686018427387905", LESS),
    ("LINT", "-9223372036854775808", "-9223372036854775808", EQUAL),
    ("LINT", "9223372036854775807", "9223372036854775806", GREATER),
    ("USINT", "0", "255", LESS), ("USINT", "255", "255", EQUAL), ("USINT", "128", "127", GREATER),
    ("UINT", "0", "65535", LESS), ("UINT", "32768", "32768", EQUAL), ("UINT", "65535", "32767", GREATER),
    ("UDINT", "2147483647", "2147483648", LESS), ("UDINT", "4294967295", "4294967295", EQUAL),
    ("UDINT", "4294967295", "0", GREATER),
    ("ULINT", "18446744073709551614", "18446744073709551615", LESS),
    ("ULINT", "9223372036854775808", "9223372036854775808", EQUAL),
    ("ULINT", "9223372036854775808", "9223372036854775807", GREATER),
    ("BYTE", "16#7F", "16#80", LESS), ("WORD", "16#FFFF", "16#FFFF", EQUAL),
    ("DWORD", "16#80000000", "16#7FFFFFFF", GREATER),
    ("TIME", "T#-1ms", "T#0ms", LESS), ("TIME", "T#1s", "T#1000ms", EQUAL),
    ("TIME", "T#1s1ns", "T#1s", GREATER),
]


@pytest.mark.parametrize("type_name, a, b, expected", INTEGER_CASES)
def test_integer_comparisons_on_variables(type_name, a, b, expected):
    assert compare(type_name, a, b) == expected


REAL_CASES = [
    ("REAL", "-3.4028235E38", "3.4028235E38", LESS),
    ("REAL", "1.0", "1.0000001", LESS),        # 1.0000001 rounds to 1 + 2**-23
    # 1.00000001 is nearer 1.0 than 1 + 2**-23: the same REAL, different LREALs.
    ("REAL", "1.00000001", "1.0", EQUAL),
    ("LREAL", "1.00000001", "1.0", GREATER),
    ("REAL", "16777217.0", "16777216.0", EQUAL),  # 2**24 + 1 is a tie, to even 2**24
    ("LREAL", "16777217.0", "16777216.0", GREATER),
    ("REAL", "1.4E-45", "0.0", GREATER),         # the smallest subnormal REAL
    ("REAL", "-0.0", "0.0", EQUAL),              # IEEE 754: -0 = +0
    ("LREAL", "-0.0", "0.0", EQUAL),
    ("REAL", "-1.5", "-1.5", EQUAL), ("REAL", "-2.5", "-1.5", LESS),
    ("LREAL", "1.7976931348623157E308", "-1.7976931348623157E308", GREATER),
    ("LREAL", "4.9E-324", "0.0", GREATER),
]


@pytest.mark.parametrize("type_name, a, b, expected", REAL_CASES)
def test_real_comparisons_on_variables(type_name, a, b, expected):
    assert compare(type_name, a, b) == expected


@pytest.mark.parametrize("type_name", ["REAL", "LREAL"])
def test_nan_compares_unordered(type_name):
    names = ["lt", "le", "gt", "ge", "eq", "ne"]
    decls = (f"z, n, one : {type_name}; " + " ".join(f"{x}, {x}2 : BOOL;" for x in names))
    body = ("one := 1.0; n := z / z;\n"
            + "\n".join(f"{x} := n {op} one; {x}2 := n {op} n;" for x, op in zip(names, OPS)))
    main = run(decls, body)
    expected = {"lt": False, "le": False, "gt": False, "ge": False, "eq": False, "ne": True}
    assert {x: main[x] for x in names} == expected
    assert {x: main[x + "2"] for x in names} == expected


@pytest.mark.parametrize("type_name", ["REAL", "LREAL"])
def test_infinity_compares_beyond_every_finite_value(type_name):
    big = "3.4028235E38" if type_name == "REAL" else "1.7976931348623157E308"
    main = run(f"z, one, inf, big : {type_name}; gt, eq, lt_neg : BOOL;",
               f"one := 1.0; big := {big}; inf := one / z;\n"
               "gt := inf > big; eq := inf = inf; lt_neg := -inf < -big;")
    assert (main["gt"], main["eq"], main["lt_neg"]) == (True, True, True)


def test_mixed_width_comparisons_compare_values():
    # An INT -1 against a DINT 5 and a UINT 3 against the literal 4 (implicit widening).
    main = run("i : INT := -1; d : DINT := 5; s : SINT := -128; u : UINT := 3; r : LREAL := 2.5;\n"
               "c1, c2, c3, c4 : BOOL; x : REAL := 2.5;",
               "c1 := i < d; c2 := s <= i; c3 := u >= 4; c4 := x = r;")
    assert (main["c1"], main["c2"], main["c3"], main["c4"]) == (True, True, False, True)


def test_chained_comparison_results_are_booleans_usable_in_expressions():
    # (a < b) = (c > d): TRUE = TRUE; (a >= b) OR (c <= d): FALSE OR FALSE.
    main = run("a : INT := 1; b : INT := 2; c : INT := 4; d : INT := 3; e, f, g : BOOL;",
               "e := (a < b) = (c > d); f := (a >= b) OR (c <= d); g := (a <> b) AND NOT (c = d);")
    assert (main["e"], main["f"], main["g"]) == (True, False, True)


@pytest.mark.parametrize("p, q", [(False, False), (False, True), (True, False), (True, True)])
def test_boolean_operators_truth_tables(p, q):
    st = {False: "FALSE", True: "TRUE"}
    main = run(f"p : BOOL := {st[p]}; q : BOOL := {st[q]}; a, a2, o, x, n, imp : BOOL;",
               "a := p AND q; a2 := p & q; o := p OR q; x := p XOR q; n := NOT p; imp := NOT p OR q;")
    assert main["a"] is (p and q) and main["a2"] is (p and q)
    assert main["o"] is (p or q)
    assert main["x"] is (p != q)
    assert main["n"] is (not p)
    assert main["imp"] is ((not p) or q)


@pytest.mark.parametrize("type_name, a, b, and_, or_, xor, not_a", [
    ("BYTE", "16#C3", "16#A5", 0x81, 0xE7, 0x66, 0x3C),
    ("WORD", "16#F00F", "16#0FF0", 0x0000, 0xFFFF, 0xFFFF, 0x0FF0),
    ("DWORD", "16#80000001", "16#00000003", 0x00000001, 0x80000003, 0x80000002, 0x7FFFFFFE),
    ("LWORD", "16#FFFFFFFF00000000", "16#0000FFFFFFFF0000",
     0x0000FFFF00000000, 0xFFFFFFFFFFFF0000, 0xFFFF0000FFFF0000, 0x00000000FFFFFFFF),
])
def test_bit_string_operators_on_variables(type_name, a, b, and_, or_, xor, not_a):
    main = run(f"a : {type_name} := {a}; b : {type_name} := {b}; r1, r2, r3, r4 : {type_name};",
               "r1 := a AND b; r2 := a OR b; r3 := a XOR b; r4 := NOT a;")
    assert (main["r1"], main["r2"], main["r3"], main["r4"]) == (and_, or_, xor, not_a)


def test_comparison_drives_if_branches_at_equality():
    # Counting with `>=` and `>` from 0 to 3 over 5 scans: `>=` stops one earlier.
    main = run("i, j, k : INT; ge_hits, gt_hits : INT;",
               "i := i + 1;\nIF i >= 3 THEN ge_hits := ge_hits + 1; END_IF;\n"
               "IF i > 3 THEN gt_hits := gt_hits + 1; END_IF;", cycles=5)
    assert (main["ge_hits"], main["gt_hits"]) == (3, 2)     # i = 3, 4, 5 and i = 4, 5


# ----------------------------------------------------------- LINT_TO_REAL ties


@pytest.mark.parametrize("value, expected", [
    # Near 2**53 a REAL's step is 2**30; 2**53 + 2**29 is halfway: the tie goes
    # to the even mantissa, 2**53 (2**23 * 2**30, last mantissa bit 0).
    (2**53 + 2**29, 2.0**53),
    (-(2**53 + 2**29), -(2.0**53)),
    # 2**53 + 3 * 2**29: halfway between 2**53 + 2**30 (odd mantissa) and
    # 2**53 + 2**31 (even): up to 2**53 + 2**31.
    (2**53 + 3 * 2**29, 2.0**53 + 2.0**31),
    (-(2**53 + 3 * 2**29), -(2.0**53 + 2.0**31)),
    # Just above and below the first tie: no tie, nearest.
    (2**53 + 2**29 + 1, 2.0**53 + 2.0**30),
    (2**53 + 2**29 - 1, 2.0**53),
    # 2**62 + 2**38: halfway between 2**62 and 2**62 + 2**39 -> 2**62.
    (2**62 + 2**38, 2.0**62),
    (2**62 + 3 * 2**38, 2.0**62 + 2.0**40),
    # Below 2**53 through float64 exactly: 2**24 + 1 -> 2**24, 2**24 + 3 -> 2**24 + 4.
    (2**24 + 1, 2.0**24), (2**24 + 3, 2.0**24 + 4.0),
    (9223372036854775807, 2.0**63),    # LINT max rounds up to 2**63
])
def test_lint_to_real_rounds_ties_to_even(value, expected):
    main = run(f"l : LINT := {value}; r : REAL; d : LREAL;", "r := LINT_TO_REAL(l); d := LINT_TO_LREAL(l);")
    assert main.raw("r") == expected
    assert main.raw("d") == float(value)    # float64 rounding, ties to even, by Python


def test_ulint_to_real_rounds_ties_to_even():
    # 2**64 - 2**39 is halfway between 2**64 - 2**40 (odd mantissa 2**24 - 1)
    # and 2**64 (even): rounds up to 2**64.
    main = run("u : ULINT := 18446743523953737728; r : REAL;", "r := ULINT_TO_REAL(u);")
    assert main.raw("r") == 2.0**64
