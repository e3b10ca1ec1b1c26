"""Standard functions and type conversions, called directly from Python."""

import math

import numpy as np
import pytest

from st_runtime import types as T
from st_runtime.faults import STFault
from st_runtime.stdlib import CONVERSIONS, FUNCTIONS, STRICT_FUNCTIONS, conversion, split_conversion_name
from st_runtime.stdlib.conversions import TYPE_NAMES
from st_runtime.values import to_real32

F = FUNCTIONS
MS = 1_000_000
S = 1_000_000_000


# --- math against NumPy -----------------------------------------------------

RNG = np.random.default_rng(3)
UNIT = RNG.uniform(-1, 1, 200)
POSITIVE = 10.0 ** RNG.uniform(-6, 6, 200)
ANGLES = RNG.uniform(-10, 10, 200)


@pytest.mark.parametrize("name, ref, xs", [
    ("SQRT", np.sqrt, POSITIVE), ("LN", np.log, POSITIVE), ("LOG", np.log10, POSITIVE),
    ("EXP", np.exp, ANGLES), ("SIN", np.sin, ANGLES), ("COS", np.cos, ANGLES),
    ("TAN", np.tan, ANGLES), ("ASIN", np.arcsin, UNIT), ("ACOS", np.arccos, UNIT),
    ("ATAN", np.arctan, ANGLES), ("ABS", np.abs, ANGLES),
])
def test_math_matches_numpy(name, ref, xs):
    got = np.array([F[name](float(x)) for x in xs])
    np.testing.assert_allclose(got, ref(xs), rtol=1e-15, atol=0)


def test_expt_matches_numpy_and_keeps_integers():
    bases = 10.0 ** RNG.uniform(-3, 3, 100)
    exps = RNG.uniform(-4, 4, 100)
    got = np.array([F["EXPT"](float(b), float(e)) for b, e in zip(bases, exps)])
    np.testing.assert_allclose(got, np.power(bases, exps), rtol=1e-14)
    assert F["EXPT"](2, 10) == 1024 and isinstance(F["EXPT"](2, 10), int)
    assert F["EXPT"](2, -1) == 0.5
    assert F["EXPT"](-2.0, 3) == -8.0


def test_math_domain_errors_give_ieee_values_like_the_nj():
    assert math.isnan(F["SQRT"](-1.0))
    assert F["LN"](0.0) == -math.inf
    assert math.isnan(F["LN"](-1.0))
    assert F["LOG"](0.0) == -math.inf
    assert math.isnan(F["ASIN"](1.5))
    assert math.isnan(F["ACOS"](-1.0001))
    assert F["EXP"](1000.0) == math.inf
    assert F["EXPT"](0.0, -1.0) == math.inf
    assert math.isnan(F["EXPT"](-8.0, 1.0 / 3.0))
    assert F["EXPT"](10.0, 400.0) == math.inf
    assert math.isnan(F["SIN"](math.inf))


@pytest.mark.parametrize("name, args", [
    ("SQRT", (-1.0,)), ("LN", (0.0,)), ("LOG", (-2.0,)), ("ASIN", (2.0,)),
    ("ACOS", (-2.0,)), ("EXP", (1000.0,)), ("EXPT", (0.0, -1.0)),
])
def test_strict_table_faults_on_domain_errors(name, args):
    with pytest.raises(STFault) as err:
        STRICT_FUNCTIONS[name](*args)
    assert err.value.code == "F-MATH"
    assert name in err.value.message


def test_strict_table_passes_finite_results_and_nan_inputs():
    assert STRICT_FUNCTIONS["SQRT"](4.0) == 2.0
    assert math.isnan(STRICT_FUNCTIONS["SQRT"](math.nan))   # NaN in, NaN out: not a new error


def test_trunc():
    assert F["TRUNC"](-3.55) == -3          # W502 example
    assert F["TRUNC"](1.6) == 1
    with pytest.raises(STFault):
        F["TRUNC"](math.nan)


# --- selection ------------------------------------------------------------

def test_selection_functions():
    assert F["MIN"](3, -1, 2) == -1
    assert F["MAX"](3.5, 7.25) == 7.25
    assert F["LIMIT"](0, 15, 10) == 10
    assert F["LIMIT"](0, -5, 10) == 0
    assert F["LIMIT"](0, 5, 10) == 5
    assert F["SEL"](False, "a", "b") == "a"
    assert F["SEL"](True, "a", "b") == "b"
    assert F["MUX"](2, 10, 20, 30) == 30
    assert F["MOVE"](42) == 42
    with pytest.raises(STFault) as err:
        F["MUX"](3, 10, 20, 30)
    assert "K=3" in err.value.message


# --- bit strings ------------------------------------------------------------

def test_shifts_and_rotations_on_byte():
    assert F["SHL"](0x81, 1, 8) == 0x02      # 1000_0001 << 1 = 0000_0010 (carry lost)
    assert F["SHR"](0x81, 1, 8) == 0x40      # logical: a zero comes in
    assert F["ROL"](0x81, 1, 8) == 0x03      # the top bit comes round to bit 0
    assert F["ROR"](0x81, 1, 8) == 0xC0
    assert F["ROL"](0x81, 9, 8) == 0x03      # rotation counts modulo the width
    assert F["SHL"](0xFF, 8, 8) == 0
    assert F["SHL"](0x0001, 15, 16) == 0x8000
    assert F["ROR"](1, 1, 64) == 1 << 63
    with pytest.raises(STFault):
        F["SHL"](1, -1, 8)


def test_bitwise_functions():
    assert F["AND"](0b1100, 0b1010) == 0b1000
    assert F["OR"](0b1100, 0b1010, 0b0001) == 0b1111
    assert F["XOR"](0b1100, 0b1010) == 0b0110
    assert F["NOT"](0x0F, 8) == 0xF0
    assert F["NOT"](0, 16) == 0xFFFF
    assert F["NOT"](True, 1) is False
    assert F["AND"](True, False) is False


# --- strings ----------------------------------------------------------------

def test_string_functions_use_one_based_positions():
    assert F["LEN"]("ABCDE") == 5
    assert F["CONCAT"]("AB", "CD", "E") == "ABCDE"
    assert F["LEFT"]("ABCDE", 3) == "ABC"
    assert F["RIGHT"]("ABCDE", 3) == "CDE"
    assert F["RIGHT"]("AB", 5) == "AB"
    assert F["MID"]("ABCDE", 2, 2) == "BC"   # IEC: MID(IN, L, P)
    assert F["MID"]("ABCDE", 10, 4) == "DE"
    assert F["INSERT"]("ABCDE", "XY", 2) == "ABXYCDE"
    assert F["DELETE"]("ABCDE", 2, 3) == "ABE"
    assert F["REPLACE"]("ABCDE", "X", 2, 3) == "ABXE"
    assert F["FIND"]("ABCBC", "BC") == 2
    assert F["FIND"]("ABC", "Z") == 0


@pytest.mark.parametrize("call", [
    lambda: F["MID"]("ABC", 1, 0), lambda: F["MID"]("ABC", 1, 4),
    lambda: F["LEFT"]("ABC", -1), lambda: F["DELETE"]("ABC", 1, 9),
    lambda: F["INSERT"]("ABC", "X", 4),
])
def test_string_position_errors_are_faults(call):
    with pytest.raises(STFault) as err:
        call()
    assert err.value.code == "F-STRING"


# --- conversions ------------------------------------------------------------

@pytest.mark.parametrize("x, expected", [
    (1.49, 1), (1.5, 2), (2.5, 2), (-1.5, -2), (-2.5, -2), (1.51, 2), (-1.6, -2), (3.5, 4),
])
def test_real_to_int_rounds_half_to_even_like_the_nj(x, expected):
    # OMRON W502, Real Number-to-Integer Conversion Group: REAL#2.5 -> INT#2,
    # REAL#1.5 -> INT#2, REAL#-2.5 -> INT#-2
    assert conversion("REAL", "INT")(to_real32(x)) == expected
    assert conversion("LREAL", "DINT")(x) == expected
    assert CONVERSIONS["LREAL_TO_LINT"](x) == expected


def test_real_to_bit_string_uses_twos_complement():
    # W502 examples: 1.6 -> 16#0002, 3.5 -> 16#0004, -1.6 -> 16#FFFE
    to_word = conversion("LREAL", "WORD")
    assert to_word(1.6) == 0x0002
    assert to_word(3.5) == 0x0004
    assert to_word(-1.6) == 0xFFFE


@pytest.mark.parametrize("src, dst, x", [
    ("REAL", "INT", 32768.0), ("LREAL", "SINT", -129.0), ("LREAL", "UINT", -1.0),
    ("LREAL", "DINT", math.nan), ("REAL", "DINT", math.inf), ("LREAL", "BYTE", 200.0),
])
def test_real_to_integer_out_of_range_is_a_fault(src, dst, x):
    with pytest.raises(STFault) as err:
        conversion(src, dst)(x)
    assert err.value.code == "F-CONVERT"


def test_integer_conversions_keep_low_bits():
    assert CONVERSIONS["INT_TO_SINT"](4223) == 127          # 16#107F -> 16#7F
    assert CONVERSIONS["DINT_TO_INT"](65665) == 129         # 16#0001_0081 -> 16#0081
    assert CONVERSIONS["DINT_TO_SINT"](65665) == -127       # 16#81 as SINT
    assert CONVERSIONS["INT_TO_UINT"](-1) == 65535
    assert CONVERSIONS["WORD_TO_INT"](0x8000) == -32768
    assert CONVERSIONS["SINT_TO_LWORD"](-1) == 2**64 - 1
    assert CONVERSIONS["BOOL_TO_INT"](True) == 1
    assert CONVERSIONS["INT_TO_BOOL"](-3) is True
    assert CONVERSIONS["INT_TO_BOOL"](0) is False


def test_numeric_to_real():
    assert CONVERSIONS["DINT_TO_REAL"](16777217) == 16777216.0   # float32 keeps 24 bits
    assert CONVERSIONS["DINT_TO_LREAL"](16777217) == 16777217.0
    assert CONVERSIONS["LREAL_TO_REAL"](0.1) == float(np.float32(0.1))
    assert CONVERSIONS["REAL_TO_LREAL"](to_real32(0.1)) == float(np.float32(0.1))
    assert CONVERSIONS["BOOL_TO_LREAL"](True) == 1.0


def test_time_conversions_count_nanoseconds():
    assert CONVERSIONS["TIME_TO_LINT"](1_500_000_000) == 1_500_000_000
    assert CONVERSIONS["DINT_TO_TIME"](5 * MS) == 5 * MS
    assert CONVERSIONS["LREAL_TO_TIME"](2.5) == 2             # ties to even
    assert CONVERSIONS["TIME_TO_LREAL"](3 * S) == 3e9
    day = 86_400 * S
    dt = 3 * day + 3600 * S
    assert CONVERSIONS["DT_TO_DATE"](dt) == 3 * day
    assert CONVERSIONS["DT_TO_TOD"](dt) == 3600 * S
    assert CONVERSIONS["DATE_AND_TIME_TO_TIME_OF_DAY"](dt) == 3600 * S
    assert CONVERSIONS["DATE_TO_DT"](3 * day) == 3 * day


def test_to_string_and_back():
    assert CONVERSIONS["INT_TO_STRING"](-42) == "-42"
    assert CONVERSIONS["BYTE_TO_STRING"](255) == "255"
    assert CONVERSIONS["BOOL_TO_STRING"](True) == "TRUE"
    assert CONVERSIONS["REAL_TO_STRING"](to_real32(0.1)) == "0.1"
    assert CONVERSIONS["REAL_TO_STRING"](2.0) == "2.0"
    assert CONVERSIONS["LREAL_TO_STRING"](0.1) == "0.1"
    assert CONVERSIONS["TIME_TO_STRING"](1_500_000_000) == "T#1s500ms"
    assert CONVERSIONS["DATE_TO_STRING"](0) == "D#1970-01-01"
    assert CONVERSIONS["STRING_TO_INT"](" -42 ") == -42
    assert CONVERSIONS["STRING_TO_WORD"]("16#FF_FF") == 0xFFFF
    assert CONVERSIONS["STRING_TO_USINT"]("2#1010") == 10
    assert CONVERSIONS["STRING_TO_LREAL"]("1.5e3") == 1500.0
    assert CONVERSIONS["STRING_TO_REAL"]("0.1") == to_real32(0.1)
    assert CONVERSIONS["STRING_TO_BOOL"]("true") is True
    assert CONVERSIONS["STRING_TO_TIME"]("T#2s") == 2 * S
    assert CONVERSIONS["STRING_TO_DT"]("DT#1970-01-01-00:00:01") == S


@pytest.mark.parametrize("name, text", [
    ("STRING_TO_INT", "40000"), ("STRING_TO_INT", "abc"), ("STRING_TO_INT", "1.5"),
    ("STRING_TO_LREAL", "nan"), ("STRING_TO_BOOL", "yes"), ("STRING_TO_TIME", "5"),
    ("STRING_TO_BYTE", "-1"), ("STRING_TO_DINT", "16#"),
])
def test_string_parse_errors_are_faults(name, text):
    with pytest.raises(STFault) as err:
        CONVERSIONS[name](text)
    assert err.value.code == "F-CONVERT"


def test_every_pair_of_distinct_types_is_defined():
    names = list(TYPE_NAMES) + ["TIME_OF_DAY", "DATE_AND_TIME"]
    for src in names:
        for dst in names:
            if T.ELEMENTARY.get(src, src) != T.ELEMENTARY.get(dst, dst):
                assert f"{src}_TO_{dst}" in CONVERSIONS, (src, dst)
    assert "INT_TO_INT" not in CONVERSIONS
    with pytest.raises(KeyError):
        conversion("INT", "FOO")


def test_names_agree_with_the_checker():
    builtins = pytest.importorskip("st_runtime.checker.builtins")
    for name in builtins.STANDARD_FUNCTIONS:
        assert name in FUNCTIONS, name
    for src in builtins.CONVERTIBLE:
        for dst in builtins.CONVERTIBLE:
            name = f"{src}_TO_{dst}"
            assert (builtins.conversion(name) is not None) == (name in CONVERSIONS), name


def test_time_family_conversions_normalise_the_destination():
    day = 86_400 * S
    assert CONVERSIONS["TIME_TO_TOD"](day + 5 * S) == 5 * S
    assert CONVERSIONS["TIME_TO_DATE"](day + 5 * S) == day
    assert CONVERSIONS["TOD_TO_DATE"](5 * S) == 0
    assert CONVERSIONS["LREAL_TO_DT"](1e9) == S
    assert CONVERSIONS["BOOL_TO_TIME"](True) == 1


def test_split_conversion_name():
    assert split_conversion_name("lreal_to_dint") == ("LREAL", "DINT")
    assert split_conversion_name("DATE_AND_TIME_TO_DATE") == ("DT", "DATE")
    assert split_conversion_name("TIME_OF_DAY_TO_STRING") == ("TOD", "STRING")
    assert split_conversion_name("FOO_TO_BAR") is None


def test_function_names_are_upper_case_and_complete():
    required = {"ABS", "SQRT", "LN", "LOG", "EXP", "EXPT", "SIN", "COS", "TAN", "ASIN",
                "ACOS", "ATAN", "MIN", "MAX", "LIMIT", "SEL", "MUX", "MOVE", "TRUNC",
                "SHL", "SHR", "ROL", "ROR", "AND", "OR", "XOR", "NOT",
                "LEN", "CONCAT", "LEFT", "RIGHT", "MID"}
    assert required <= set(FUNCTIONS)
    assert all(name == name.upper() for name in FUNCTIONS)


# --- properties (seeded, bounded) -------------------------------------------

from hypothesis import given, settings, strategies as st  # noqa: E402


@settings(max_examples=300, deadline=None, derandomize=True)
@given(st.floats(-2.1e9, 2.1e9, allow_nan=False) | st.integers(-2**31, 2**31 - 1).map(lambda n: n + 0.5))
def test_lreal_to_dint_agrees_with_numpy_rint(x):
    # numpy.rint rounds half to even, the NJ's rule
    expected = int(np.rint(x))
    if -2**31 <= expected < 2**31:
        assert conversion("LREAL", "DINT")(x) == expected


@settings(max_examples=300, deadline=None, derandomize=True)
@given(st.integers(0, 255), st.integers(0, 20))
def test_byte_rotations_invert_and_shifts_match_python(value, n):
    assert F["ROR"](F["ROL"](value, n, 8), n, 8) == value
    assert F["SHL"](value, n, 8) == (value << n) & 0xFF
    assert F["SHR"](value, n, 8) == value >> n
    assert F["NOT"](F["NOT"](value, 8), 8) == value


@settings(max_examples=200, deadline=None, derandomize=True)
@given(st.integers(-2**63, 2**63 - 1))
def test_lint_string_round_trip(n):
    assert CONVERSIONS["STRING_TO_LINT"](CONVERSIONS["LINT_TO_STRING"](n)) == n


@settings(max_examples=200, deadline=None, derandomize=True)
@given(st.floats(width=32, allow_nan=False, allow_infinity=False))
def test_real_string_round_trip(x):
    assert CONVERSIONS["STRING_TO_REAL"](CONVERSIONS["REAL_TO_STRING"](x)) == x


def test_to_date_keeps_the_day_and_faults_below_the_first_whole_day():
    day = 86_400 * 10**9
    # -1 ns is 1969-12-31-23:59:59.999999999: its day starts one day before the epoch
    assert conversion("LINT", "DATE")(-1) == -day
    assert conversion("DT", "DATE")(3 * day + 5) == 3 * day
    # -2**63 ns lies in a day that starts before -2**63: no 64-bit DATE holds it
    for src in ("LINT", "TIME", "DT"):
        with pytest.raises(STFault, match="F-CONVERT|outside"):
            conversion(src, "DATE")(-2**63)


_EDGE_SAMPLES = {
    "BOOL": [False, True],
    "REAL": [0.0, -1.5, 2.5, 3.4e38, -3.4e38, math.inf, math.nan, 1e-45],
    "LREAL": [0.0, -0.0, -1.5, 2.5, 1.7e308, -math.inf, math.nan, 9.3e18],
    "STRING": ["", "42", "-1", "abc", "T#1s", "1.5", "TRUE", "16#FF", "D#2024-01-01",
               "99999999999999999999999"],
}


@pytest.mark.parametrize("src", TYPE_NAMES)
def test_the_whole_matrix_on_edge_values_faults_or_stays_in_range(src):
    # Every <src>_TO_<dst> on the limits of src: a value of dst's kind and
    # range, or an F-CONVERT fault; nothing else (found: LINT_TO_DATE(-2**63)
    # gave a day start below -2**63).
    t = T.ELEMENTARY.get(src)
    values = _EDGE_SAMPLES.get(src) or sorted({t.min, t.max, 0, 1, t.max // 2, t.min // 2})
    for dst in TYPE_NAMES:
        if dst == src:
            continue
        d = T.ELEMENTARY.get(dst)
        for value in values:
            try:
                result = conversion(src, dst)(value)
            except STFault as fault:
                assert fault.code in ("F-CONVERT", "F-STRING"), (src, dst, value, fault.code)
                continue
            if dst == "STRING":
                assert isinstance(result, str), (src, dst, value)
            elif d.kind == "bool":
                assert isinstance(result, bool), (src, dst, value)
            elif d.kind == "real":
                assert isinstance(result, float), (src, dst, value)
            else:
                assert isinstance(result, int) and not isinstance(result, bool), (src, dst, value)
                assert d.min <= result <= d.max, (src, dst, value, result)
