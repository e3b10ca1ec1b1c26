"""Edges of the value model that a mutation run of st_runtime/values.py
showed untested (issue 16).  Every expected value is worked out by hand."""

from __future__ import annotations

import math

import numpy as np
import pytest

from st_runtime import types as T
from st_runtime import values
from st_runtime.faults import STFault
from st_runtime.values import (
    LINT_MAX,
    LINT_MIN,
    ValueFormatError,
    default_value,
    format_time,
    int_div,
    int_mod,
    int_to_real32,
    int_wrapper,
    parse_date,
    parse_dt,
    parse_time,
    parse_tod,
    shortest_real32,
    time_div,
    time_mul,
    to_json,
    to_real32,
)

S = 1_000_000_000


# ------------------------------------------------------------ integer stores


@pytest.mark.parametrize("bits, signed, value, stored", [
    (8, True, 127, 127), (8, True, 128, -128), (8, True, -129, 127), (8, True, -128, -128),
    (8, True, 255, -1), (8, True, 256, 0), (8, True, 1000, -24),          # 1000 - 4 * 256
    (8, False, 256, 0), (8, False, -1, 255), (8, False, 255, 255), (8, False, 0, 0),
    (16, True, 32768, -32768), (16, False, 65537, 1),
    (64, True, 2**63, -(2**63)), (64, True, -(2**63) - 1, 2**63 - 1), (64, False, -1, 2**64 - 1),
])
def test_make_wrapper_keeps_the_low_bits_with_the_signedness(bits, signed, value, stored):
    # Called directly: the module builds its wrappers at import time, so the
    # compiled programs alone would not notice a wrong wrapper factory.
    assert values._make_wrapper(bits, signed)(value) == stored


@pytest.mark.parametrize("type_name, value, stored", [
    ("BOOL", 2, True), ("BOOL", 0, False),
    ("SINT", 128, -128), ("USINT", 256, 0), ("INT", 32768, -32768), ("UINT", -1, 65535),
    ("DINT", 2**31, -(2**31)), ("UDINT", 2**32, 0), ("LINT", 2**63, -(2**63)), ("ULINT", 2**64 + 5, 5),
    ("BYTE", 0x1FF, 0xFF), ("WORD", 0x10000, 0), ("DWORD", -1, 2**32 - 1), ("LWORD", -1, 2**64 - 1),
    ("TIME", 2**63, -(2**63)), ("DATE", -1, -1), ("TOD", 5, 5), ("DT", 2**63 + 1, -(2**63) + 1),
])
def test_int_wrapper_built_afresh(monkeypatch, type_name, value, stored):
    monkeypatch.setattr(values, "_WRAPPERS", {})
    t = T.ELEMENTARY[type_name]
    fn = int_wrapper(t)
    assert fn(value) == stored and type(fn(value)) is type(stored)
    assert int_wrapper(t) is fn            # built once, then reused


def test_int_wrapper_refuses_a_real(monkeypatch):
    monkeypatch.setattr(values, "_WRAPPERS", {})
    with pytest.raises(TypeError, match="REAL is not stored as an integer"):
        int_wrapper(T.ELEMENTARY["REAL"])


def test_division_by_zero_faults_name_the_operation():
    for call, message in [(lambda: int_div(7, 0), "integer division by zero"),
                          (lambda: int_mod(7, 0), "MOD by zero"),
                          (lambda: time_div(S, 0.0), "TIME divided by zero")]:
        with pytest.raises(STFault) as fault:
            call()
        assert fault.value.code == "F-DIV-ZERO" and fault.value.message == message


# --------------------------------------------------------------------- REAL


@pytest.mark.parametrize("value, expected", [
    # 2**53 + 2**30 + 1: the kept mantissa is odd (2**23 + 1) but the rest (1)
    # is below half a step: down to 2**53 + 2**30, not up to the even neighbour.
    (2**53 + 2**30 + 1, 2.0**53 + 2.0**30),
    (-(2**53 + 2**30 + 1), -(2.0**53 + 2.0**30)),
    (2**53, 2.0**53), (-(2**53), -(2.0**53)),
    (2**53 + 1, 2.0**53), (2**64 - 1, 2.0**64),
])
def test_int_to_real32_more_ties_and_bounds(value, expected):
    assert int_to_real32(value) == expected


@pytest.mark.parametrize("x, shortest", [
    (0.1, 0.1), (1.0 / 3.0, 0.33333334), (3.4028234663852886e38, 3.4028235e38),
    (16777216.0, 16777216.0), (1.0e-45, 1.0e-45), (-2.5, -2.5),
])
def test_shortest_real32_is_the_fewest_digits_of_the_same_real(x, shortest):
    stored = to_real32(x)
    assert shortest_real32(stored) == shortest
    assert to_real32(shortest) == stored


def test_shortest_real32_keeps_non_finite_values():
    assert shortest_real32(math.inf) == math.inf and math.isnan(shortest_real32(math.nan))


def test_to_json_of_an_lreal_is_the_double_itself():
    # float32(0.1) held in an LREAL is 0.100000001490116..., not 0.1.
    f32 = float(np.float32(0.1))
    assert to_json(f32, T.ELEMENTARY["LREAL"]) == 0.10000000149011612
    assert to_json(f32, T.ELEMENTARY["REAL"]) == 0.1


# --------------------------------------------------------------------- TIME


def test_time_mul_by_real_one_zero_and_non_finite():
    assert time_mul(5 * S, 1.0) == 5 * S
    assert time_mul(5 * S, 0.0) == 0
    assert time_mul(5 * S, 0.5) == 2_500_000_000
    assert time_mul(5 * S, math.inf) == LINT_MIN and time_mul(5 * S, math.nan) == LINT_MIN


def test_time_div_by_infinity_is_zero_and_by_nan_the_most_negative_time():
    assert time_div(5 * S, math.inf) == 0 and time_div(5 * S, -math.inf) == 0
    assert time_div(5 * S, math.nan) == LINT_MIN
    assert time_div(5 * S, 2.0) == 2_500_000_000 and time_div(5 * S, 2) == 2_500_000_000


def test_format_time_keeps_the_given_prefix():
    assert format_time(1) == "T#1ns"
    assert format_time(1, "LTIME#") == "LTIME#1ns"
    assert format_time(-1_500_000, "TIME#") == "TIME#-1ms500us"


@pytest.mark.parametrize("text, ns", [
    ("T#+1s", S), ("+1s", S), ("T#-1s", -S), ("1.5s", 1_500_000_000), ("LTIME#1ns", 1),
])
def test_parse_time_signs_and_prefixes(text, ns):
    assert parse_time(text) == ns


@pytest.mark.parametrize("text", ["T#T#1s", "T#X1s", "T#", "T#1x", "T#--1s", "1s T#"])
def test_parse_time_refuses_malformed_text_and_names_it(text):
    with pytest.raises(ValueFormatError) as error:
        parse_time(text)
    assert str(error.value) == f"{text!r} is not a TIME literal (expected e.g. T#1s500ms)"


def test_parse_time_outside_the_range_says_so():
    with pytest.raises(ValueFormatError) as error:
        parse_time("T#107000d")     # 107,000 days > 2**63 ns (about 106,751 days)
    assert str(error.value) == "'T#107000d' is outside the TIME range"
    assert parse_time("T#106751d") == 106751 * 86400 * S


def test_dates_and_clock_times_with_and_without_prefix():
    assert parse_date("2024-01-15") == parse_date("D#2024-01-15") == 19737 * 86400 * S
    assert parse_tod("12:30:15.5") == parse_tod("TOD#12:30:15.5") == (45015 * S + S // 2)
    assert parse_dt("1970-01-02-00:00:01") == parse_dt("DT#1970-01-02-00:00:01") == 86401 * S
    assert parse_tod("TOD#23:59:59.999999999") == 86400 * S - 1


@pytest.mark.parametrize("parse, text, message", [
    (parse_tod, "TOD#12:60:00", "'TOD#12:60:00': clock time out of range"),
    (parse_tod, "TOD#12:00:60", "'TOD#12:00:60': clock time out of range"),
    (parse_tod, "TOD#24:00:00", "'TOD#24:00:00': clock time out of range"),
    (parse_dt, "DT#2024-01-01-23:60:00", "'DT#2024-01-01-23:60:00': clock time out of range"),
    (parse_date, "D#2023-02-29", "'D#2023-02-29': day is out of range for month"),
    (parse_dt, "DT#2023-02-29-00:00:00", "'DT#2023-02-29-00:00:00': day is out of range for month"),
    (parse_date, "D#2024-1", "'D#2024-1' is not a DATE literal (expected e.g. D#2024-01-31)"),
    (parse_tod, "TOD#1:2", "'TOD#1:2' is not a TIME_OF_DAY literal (expected e.g. TOD#12:30:00.5)"),
    (parse_dt, "DT#2024-01-01", "'DT#2024-01-01' is not a DATE_AND_TIME literal "
                                "(expected e.g. DT#2024-01-31-12:30:00)"),
])
def test_date_and_clock_errors_name_the_text(parse, text, message):
    with pytest.raises(ValueFormatError) as error:
        parse(text)
    assert str(error.value) == message


# ---------------------------------------------------------- default values


def test_default_values_have_the_type_of_their_kind():
    real = default_value(T.ELEMENTARY["REAL"])
    integer = default_value(T.ELEMENTARY["DINT"])
    assert real == 0.0 and type(real) is float
    assert integer == 0 and type(integer) is int
    assert default_value(T.ELEMENTARY["BOOL"]) is False


def test_default_enum_value_is_the_smallest_one():
    # TYPE Gear : (Low := 3, High := 5, Reverse := -1): the default is the
    # smallest value, -1 here, not 0 (which Gear does not have).
    gear = T.EnumType("Gear", {"LOW": ("Low", 3), "HIGH": ("High", 5), "REVERSE": ("Reverse", -1)})
    assert default_value(gear) == -1
    assert default_value(T.EnumType("Empty")) == 0


def test_default_struct_is_keyed_by_upper_case_member_name():
    point = T.StructType("Point", {"X": ("x", T.ELEMENTARY["LREAL"]), "N": ("n", T.ELEMENTARY["INT"])})
    value = default_value(point)
    assert value == {"X": 0.0, "N": 0} and type(value["X"]) is float


def test_default_value_refuses_what_has_none():
    with pytest.raises(TypeError, match="no default value for"):
        default_value(object())


def test_to_json_nests_three_dimensions_and_names_enum_values():
    cube = T.ArrayType(((1, 2), (0, 2), (-1, 0)), T.ELEMENTARY["INT"])
    flat = list(range(12))
    assert to_json(flat, cube) == [[[0, 1], [2, 3], [4, 5]], [[6, 7], [8, 9], [10, 11]]]
    gear = T.EnumType("Gear", {"LOW": ("Low", 3)})
    assert to_json(3, gear) == "Low"
    assert to_json(7, gear) == 7          # a number no name has stays a number
    with pytest.raises(TypeError, match="cannot convert a value of type"):
        to_json(1, object())


# --------------------------------------------------------------------- JSON

from st_runtime.api import load_text  # noqa: E402
from st_runtime.values import JsonValueError, from_json, json_text  # noqa: E402

E = T.ELEMENTARY
COLOR = T.EnumType("Color", {"RED": ("Red", 0), "GREEN": ("Green", 1), "BLUE": ("Blue", 2)})
POINT = T.StructType("Point", {"X": ("x", E["LREAL"]), "N": ("n", E["INT"])})


@pytest.mark.parametrize("data, t, stored", [
    (True, E["BOOL"], True), (1, E["BOOL"], True), (0, E["BOOL"], False),
    (-32768, E["INT"], -32768), (32767, E["INT"], 32767), (255, E["BYTE"], 255), (3.0, E["INT"], 3),
    (math.inf, E["REAL"], math.inf), ("-Infinity", E["LREAL"], -math.inf), (0.1, E["REAL"], to_real32(0.1)),
    ("abcd", T.StringType(4), "abcd"), ("green", COLOR, 1), (2, COLOR, 2),
    ({"x": 1.5}, POINT, {"X": 1.5, "N": 0}),
])
def test_from_json_accepts(data, t, stored):
    value = from_json(data, t)
    assert value == stored and type(value) is type(stored)


def test_from_json_nan_name():
    assert math.isnan(from_json("NaN", E["REAL"]))


@pytest.mark.parametrize("data, t, message", [
    (2, E["BOOL"], "value: expected BOOL (true or false), got 2"),
    ("x", E["BOOL"], "value: expected BOOL (true or false), got string 'x'"),
    (None, E["BOOL"], "value: expected BOOL (true or false), got null"),
    ([1, 2], E["BOOL"], "value: expected BOOL (true or false), got a list of 2"),
    ({}, E["BOOL"], "value: expected BOOL (true or false), got an object"),
    (True, E["INT"], "value: expected INT integer, got true"),
    (False, E["WORD"], "value: expected WORD integer, got false"),
    (1.5, E["INT"], "value: expected INT integer, got 1.5"),
    (256, E["BYTE"], "value: 256 is outside the range of BYTE (0..255)"),
    (-32769, E["INT"], "value: -32769 is outside the range of INT (-32768..32767)"),
    (32768, E["INT"], "value: 32768 is outside the range of INT (-32768..32767)"),
    ("x", E["REAL"], 'value: expected REAL number (or "NaN", "Infinity", "-Infinity"), got string \'x\''),
    (None, E["LREAL"], "value: expected LREAL number, got null"),
    (False, E["REAL"], "value: expected REAL number, got false"),
    (1e39, E["REAL"], "value: 1e+39 is outside the range of REAL"),
    (5, E["TIME"], 'value: expected TIME literal string such as "T#1s500ms", got 5'),
    (5, E["DATE"], 'value: expected DATE literal string such as "D#2024-01-31", got 5'),
    (5, E["TOD"], 'value: expected TIME_OF_DAY literal string such as "TOD#12:30:00", got 5'),
    (5, E["DT"], 'value: expected DATE_AND_TIME literal string such as "DT#2024-01-31-12:30:00", got 5'),
    ("1x", E["TIME"], "value: '1x' is not a TIME literal (expected e.g. T#1s500ms)"),
    (5, T.StringType(4), "value: expected STRING[4] string, got 5"),
    ("abcde", T.StringType(4), "value: string of 5 characters exceeds STRING[4]"),
    ("Purple", COLOR, "value: expected a value of Color (Red, Green, Blue), got string 'Purple'"),
    (7, COLOR, "value: expected a value of Color, got 7"),
    (True, COLOR, "value: expected a value of Color, got true"),
    (5, POINT, "value: expected an object for Point, got 5"),
    ({"q": 1}, POINT, "value: Point has no member 'q' (members: x, n)"),
    ({"n": "a"}, POINT, "value.n: expected INT integer, got string 'a'"),
    ([[1, 2], [3]], T.ArrayType(((1, 2), (0, 1)), E["INT"]),
     "value[2]: expected a list of 2 elements (0..1), got a list of 1"),
    ([[1, "a"], [3, 4]], T.ArrayType(((1, 2), (0, 1)), E["INT"]), "value[1, 1]: expected INT integer, got string 'a'"),
    (5, T.ArrayType(((1, 2),), E["INT"]), "value: expected a list of 2 elements (1..2), got 5"),
])
def test_from_json_refuses_with_the_path_and_what_was_expected(data, t, message):
    with pytest.raises(JsonValueError) as error:
        from_json(data, t)
    assert str(error.value) == message


def test_from_json_an_integer_beyond_the_double_range_is_out_of_range():
    with pytest.raises(JsonValueError) as error:
        from_json(10**400, E["LREAL"])
    assert str(error.value).endswith(" is outside the range of LREAL")


def test_from_json_a_type_json_cannot_give():
    with pytest.raises(JsonValueError, match="value: values of type .* cannot be given as JSON"):
        from_json(1, object())


def test_json_text_writes_non_finite_reals_as_strings_at_any_depth():
    data = {"a": [math.nan, math.inf, -math.inf, 1.5], "b": {"c": math.inf}, "d": "x", "e": 2}
    assert json_text(data) == ('{"a": ["NaN", "Infinity", "-Infinity", 1.5], "b": {"c": "Infinity"}, '
                               '"d": "x", "e": 2}')


def test_instance_json_leaves_out_external_and_in_out_variables_only():
    src = ("VAR_GLOBAL g : INT := 4; END_VAR\n"
           "PROGRAM Main\nVAR_EXTERNAL g : INT; END_VAR\nVAR a : INT := 1; END_VAR\n"
           "VAR b : BOOL := TRUE; END_VAR\nEND_PROGRAM\n")
    plc = load_text(src).controller()
    main = plc.add_program("Main")
    assert main.to_json() == {"a": 1, "b": True}


def test_fb_instance_json_leaves_out_its_in_out():
    # An FB instance stores its VAR_IN_OUT slot (a reference, unset here);
    # the JSON view shows only the values the FB owns.
    from st_runtime.api import Instance

    project = load_text("FUNCTION_BLOCK F\nVAR_IN_OUT io : INT; END_VAR\n"
                        "VAR_OUTPUT o : INT := 3; END_VAR\nEND_FUNCTION_BLOCK\n")
    assert Instance(project.compiled.new("F")).to_json() == {"o": 3}


def test_from_json_names_the_index_of_a_short_innermost_list():
    cube = T.ArrayType(((1, 2), (1, 2), (1, 1)), E["INT"])
    with pytest.raises(JsonValueError) as error:
        from_json([[[1], [2]], [[3], [4, 5]]], cube)
    assert str(error.value) == "value[2, 2]: expected a list of 1 elements (1..1), got a list of 2"


def test_globals_json_has_every_global():
    # The globals' class keeps no variable kinds: all of them are shown.
    plc = load_text("VAR_GLOBAL g : INT := 4; h : BOOL; END_VAR\nPROGRAM Main\nEND_PROGRAM\n").controller()
    assert plc.globals.to_json() == {"g": 4, "h": False}
