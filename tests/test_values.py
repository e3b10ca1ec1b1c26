"""The value model: wrap, float32, TIME arithmetic and literals, JSON."""

import json
import math

import numpy as np
import pytest

from st_runtime import types as T
from st_runtime.faults import STFault
from st_runtime.symbols import Symbol
from st_runtime.values import (
    JsonValueError,
    ValueFormatError,
    default_value,
    format_date,
    format_dt,
    format_time,
    format_tod,
    from_json,
    int_div,
    int_mod,
    int_to_real32,
    int_wrapper,
    parse_date,
    parse_dt,
    parse_time,
    parse_tod,
    round_half_even,
    time_add,
    time_div,
    time_mul,
    time_sub,
    to_json,
    to_real32,
    wrap,
)

MS = 1_000_000
S = 1_000_000_000


# --- integers ---------------------------------------------------------------

@pytest.mark.parametrize("type_, value, expected", [
    (T.INT, 32767, 32767),
    (T.INT, 32768, -32768),          # one past the top wraps to the bottom
    (T.INT, -32769, 32767),
    (T.INT, 65536 + 5, 5),
    (T.SINT, 128, -128),
    (T.SINT, 255, -1),
    (T.DINT, 2**31, -2**31),
    (T.LINT, 2**63, -2**63),
    (T.USINT, 256, 0),
    (T.USINT, -1, 255),
    (T.UINT, 70000, 70000 - 65536),
    (T.UDINT, -1, 2**32 - 1),
    (T.ULINT, 2**64 + 3, 3),
    (T.BYTE, 0x181, 0x81),
    (T.WORD, -1, 0xFFFF),
    (T.DWORD, 2**32, 0),
    (T.LWORD, -2, 2**64 - 2),
    (T.TIME, 2**63, -2**63),
])
def test_wrap_keeps_low_bits_with_signedness(type_, value, expected):
    assert wrap(value, type_) == expected
    assert int_wrapper(type_)(value) == expected


def test_wrap_bool_is_truth_value():
    assert wrap(2, T.BOOL) is True
    assert wrap(0, T.BOOL) is False


def test_wrapper_rejects_real():
    with pytest.raises(TypeError):
        int_wrapper(T.REAL)


@pytest.mark.parametrize("a, b, q, r", [
    (-7, 2, -3, -1),    # truncation toward zero; MOD takes the dividend's sign
    (7, -2, -3, 1),
    (-7, -2, 3, -1),
    (7, 2, 3, 1),
    (6, 3, 2, 0),
])
def test_integer_division_and_mod(a, b, q, r):
    assert int_div(a, b) == q
    assert int_mod(a, b) == r
    assert q * b + r == a


def test_division_by_zero_is_a_fault():
    with pytest.raises(STFault) as err:
        int_div(1, 0)
    assert err.value.code == "F-DIV-ZERO"
    with pytest.raises(STFault):
        int_mod(1, 0)


# --- REAL -------------------------------------------------------------------

def test_to_real32_matches_numpy_float32():
    rng = np.random.default_rng(7)
    samples = np.concatenate([rng.normal(0, 1e3, 300), rng.uniform(-1e-30, 1e-30, 50),
                              10.0 ** rng.uniform(-40, 38, 50)])
    for x in samples:
        assert to_real32(float(x)) == float(np.float32(x))


def test_to_real32_special_values():
    assert to_real32(0.1) == 0.100000001490116119384765625      # nearest float32 to 0.1
    assert math.isinf(to_real32(1e39)) and to_real32(1e39) > 0   # overflow -> +inf
    assert to_real32(-1e39) == -math.inf
    assert math.isnan(to_real32(math.nan))
    assert math.copysign(1.0, to_real32(-0.0)) == -1.0
    assert to_real32(1e-50) == 0.0                                # underflow -> 0
    # float32 max + half an ulp is a tie; ties go to even, which is infinity
    assert to_real32(3.4028235677973366e38) == math.inf
    assert to_real32(3.4028234663852886e38) == 3.4028234663852886e38


def test_int_to_real32_rounds_once():
    # 2**53 + 2**29 + 1 is just above the float32 midpoint between 2**53 and
    # 2**53 + 2**30; via float64 it would first round to the midpoint and
    # then (ties to even) down to 2**53.
    v = 2**53 + 2**29 + 1
    assert int_to_real32(v) == float(2**53 + 2**30)
    assert int_to_real32(-v) == -float(2**53 + 2**30)
    assert int_to_real32(16777217) == 16777216.0     # 2**24 + 1: tie to even
    assert int_to_real32(16777219) == 16777220.0


@pytest.mark.parametrize("x, n", [(1.49, 1), (1.5, 2), (2.5, 2), (-1.5, -2), (-2.5, -2),
                                  (1.51, 2), (-1.51, -2), (-1.49, -1), (0.5, 0), (3.5, 4)])
def test_round_half_even_as_nj(x, n):
    # W502 table: fraction 0.5 -> even neighbour
    assert round_half_even(x) == n


# --- TIME arithmetic --------------------------------------------------------

def test_time_add_sub_wrap_to_64_bits():
    assert time_add(1 * S, 500 * MS) == 1_500_000_000
    assert time_sub(1 * S, 3 * S) == -2 * S
    assert time_add(2**63 - 1, 1) == -2**63


def test_time_mul_and_div():
    assert time_mul(1500 * MS, 2) == 3 * S
    assert time_mul(3, 0.5) == 2             # 1.5 ns ties to even -> 2
    assert time_mul(5, 0.5) == 2             # 2.5 ns -> 2
    assert time_mul(1 * S, 0.0) == 0
    assert time_mul(1 * S, math.inf) == -2**63   # NJ MULTIME table
    assert time_div(7 * S, 2) == 3_500_000_000
    assert time_div(-7, 2) == -3             # integer divisor truncates
    assert time_div(5, 2.0) == 2             # real divisor rounds, ties to even
    with pytest.raises(STFault):
        time_div(S, 0)
    with pytest.raises(STFault):
        time_div(S, 0.0)


# --- literals -------------------------------------------------------------

@pytest.mark.parametrize("ns, text", [
    (0, "T#0s"),
    (1_500_000_000, "T#1s500ms"),
    (-2_500_000_000, "T#-2s500ms"),
    (5 * MS, "T#5ms"),
    (90 * 60 * S, "T#1h30m"),
    (86_400 * S + 1, "T#1d1ns"),
    (1_001_001, "T#1ms1us1ns"),
])
def test_format_and_parse_time(ns, text):
    assert format_time(ns) == text
    assert parse_time(text) == ns


@pytest.mark.parametrize("text, ns", [
    ("TIME#-2.5s", -2_500_000_000),
    ("t#1h_30m", 90 * 60 * S),
    ("T#1.5d", 36 * 3600 * S),
    ("LTIME#2ms", 2 * MS),
    ("250ms", 250 * MS),
    ("T#0.0000000015s", 2),                  # 1.5 ns rounds to even
])
def test_parse_time_variants(text, ns):
    assert parse_time(text) == ns


@pytest.mark.parametrize("text", ["T#", "T#1x", "T#1s 2ms", "1", "T#s", "", "T#1.s"])
def test_parse_time_rejects(text):
    with pytest.raises(ValueFormatError):
        parse_time(text)


def test_date_tod_dt_literals():
    day = 86_400 * S
    assert format_date(0) == "D#1970-01-01"
    assert parse_date("D#2024-02-29") == 19782 * day          # days from 1970-01-01
    assert format_date(19782 * day) == "D#2024-02-29"
    assert parse_date("DATE#1970-01-02") == day
    assert format_tod(12 * 3600 * S + 30 * 60 * S + 500 * MS) == "TOD#12:30:00.5"
    assert parse_tod("TIME_OF_DAY#23:59:59.999999999") == day - 1
    assert format_tod(0) == "TOD#00:00:00"
    assert parse_dt("DT#1970-01-02-01:00:00") == day + 3600 * S
    assert format_dt(day + 3600 * S + 250 * MS) == "DT#1970-01-02-01:00:00.25"
    with pytest.raises(ValueFormatError):
        parse_date("D#2023-02-29")
    with pytest.raises(ValueFormatError):
        parse_tod("TOD#24:00:00")
    with pytest.raises(ValueFormatError):
        parse_dt("DT#2024-01-01")


# --- JSON -----------------------------------------------------------------

def _point_type():
    return T.StructType("Point", {"X": ("X", T.LREAL), "FLAG": ("Flag", T.BOOL)})


def test_to_json_elementary_types():
    assert to_json(True, T.BOOL) is True
    assert to_json(-5, T.INT) == -5
    assert to_json(0.5, T.REAL) == 0.5
    assert to_json(to_real32(0.1), T.REAL) == 0.1          # shortest form of 0.1f
    assert from_json(to_json(to_real32(0.1), T.REAL), T.REAL) == to_real32(0.1)
    assert to_json(0.1, T.LREAL) == 0.1
    assert to_json(1_500_000_000, T.TIME) == "T#1s500ms"
    assert to_json(0, T.DATE) == "D#1970-01-01"
    assert to_json("abc", T.StringType(10)) == "abc"


def test_to_json_nested_arrays_structs_and_fbs():
    m = T.ArrayType(((1, 2), (0, 2)), T.INT)
    assert to_json([1, 2, 3, 4, 5, 6], m) == [[1, 2, 3], [4, 5, 6]]
    point = _point_type()
    assert to_json({"X": 1.5, "FLAG": True}, point) == {"X": 1.5, "Flag": True}

    class Obj:
        v_X = 2.0
        v_FLAG = False
    assert to_json(Obj(), point) == {"X": 2.0, "Flag": False}
    fb = T.FBType("MyFb", {
        "IN": Symbol("In", T.BOOL, "VAR_INPUT"),
        "PT": Symbol("PT", T.TIME, "VAR_INPUT"),
        "REF": Symbol("Ref", T.INT, "VAR_IN_OUT"),
    })

    class Inst:
        v_IN = True
        v_PT = 5 * MS
        v_REF = None
    assert to_json(Inst(), fb) == {"In": True, "PT": "T#5ms"}
    colour = T.EnumType("Colour", {"RED": ("Red", 0), "GREEN": ("Green", 1)})
    assert to_json(1, colour) == "Green"
    # the whole thing must be serialisable
    json.dumps(to_json([1, 2, 3, 4, 5, 6], m))


def test_from_json_round_trip():
    m = T.ArrayType(((1, 2), (0, 2)), T.INT)
    assert from_json([[1, 2, 3], [4, 5, 6]], m) == [1, 2, 3, 4, 5, 6]
    assert from_json("T#1s500ms", T.TIME) == 1_500_000_000
    assert from_json(0.1, T.REAL) == to_real32(0.1)
    assert from_json(3, T.LREAL) == 3.0 and isinstance(from_json(3, T.LREAL), float)
    assert from_json(2.0, T.INT) == 2
    assert from_json({"x": 1.0}, _point_type()) == {"X": 1.0, "FLAG": False}
    colour = T.EnumType("Colour", {"RED": ("Red", 0), "GREEN": ("Green", 1)})
    assert from_json("green", colour) == 1


@pytest.mark.parametrize("data, type_, fragment", [
    (40000, T.INT, "outside the range of INT (-32768..32767)"),
    ("5", T.INT, "expected INT integer, got string '5'"),
    (True, T.DINT, "expected DINT integer"),
    (1.5, T.INT, "expected INT integer"),
    ("x", T.LREAL, "expected LREAL number"),
    (1500, T.TIME, 'TIME literal string such as "T#1s500ms"'),
    ("T#1q", T.TIME, "not a TIME literal"),
    (2, T.BOOL, "expected BOOL"),
    ("toolong", T.StringType(3), "exceeds STRING[3]"),
])
def test_from_json_errors_name_the_problem(data, type_, fragment):
    with pytest.raises(JsonValueError) as err:
        from_json(data, type_, "Pose")
    assert fragment in str(err.value)
    assert str(err.value).startswith("Pose")


def test_from_json_array_shape_and_member_errors():
    pose = T.ArrayType(((1, 6),), T.LREAL)
    with pytest.raises(JsonValueError, match=r"Pose: expected a list of 6 elements \(1..6\), got a list of 5"):
        from_json([0, 0, 150, 0, 0], pose, "Pose")
    with pytest.raises(JsonValueError, match=r"Pose\[3\]: expected LREAL number, got null"):
        from_json([0, 0, None, 0, 0, 0], pose, "Pose")
    m = T.ArrayType(((1, 2), (1, 2)), T.INT)
    with pytest.raises(JsonValueError, match=r"M\[2\]: expected a list of 2"):
        from_json([[1, 2], [3]], m, "M")
    with pytest.raises(JsonValueError, match="has no member 'Z'"):
        from_json({"Z": 1}, _point_type(), "P")


def test_default_values():
    assert default_value(T.BOOL) is False
    assert default_value(T.REAL) == 0.0
    assert default_value(T.TIME) == 0
    assert default_value(T.ArrayType(((0, 2),), T.INT)) == [0, 0, 0]
    assert default_value(T.StringType(5)) == ""


# --- properties (seeded, bounded) -------------------------------------------

from hypothesis import given, settings, strategies as st  # noqa: E402

NUMPY_INT = {"SINT": np.int8, "INT": np.int16, "DINT": np.int32, "LINT": np.int64,
             "USINT": np.uint8, "UINT": np.uint16, "UDINT": np.uint32, "ULINT": np.uint64,
             "BYTE": np.uint8, "WORD": np.uint16, "DWORD": np.uint32, "LWORD": np.uint64}


@settings(max_examples=300, deadline=None, derandomize=True)
@given(st.sampled_from(sorted(NUMPY_INT)), st.integers(-2**63, 2**63 - 1))
def test_wrap_agrees_with_numpy_casting(name, value):
    # NumPy's integer casts keep the low bits (two's complement), as IEC stores do.
    expected = int(np.array([value], dtype=np.int64).astype(NUMPY_INT[name])[0])
    assert wrap(value, T.ELEMENTARY[name]) == expected


@settings(max_examples=300, deadline=None, derandomize=True)
@given(st.integers(-2**63, 2**63 - 1))
def test_time_literal_round_trip(ns):
    assert parse_time(format_time(ns)) == ns


@settings(max_examples=200, deadline=None, derandomize=True)
@given(st.integers(0, 4_000_000_000 * S))      # 1970 .. 2096
def test_dt_literal_round_trip(ns):
    assert parse_dt(format_dt(ns)) == ns
    assert parse_tod(format_tod(ns)) == ns % (86_400 * S)
    assert parse_date(format_date(ns)) == ns - ns % (86_400 * S)
