"""Standard library details that mutation testing found unchecked (issue 16).

Each expected value is worked out by hand (the comment says how) from the IEC
61131-3 definition, OMRON's documentation as cited in the module under test,
or IEEE 754 / C99 Annex F for EXPT.  Several helpers build their tables at
import time (`conversions._table`, `bcd._table`, `functions._strict`,
`functions._trig`): those are called here afresh, so that a change in them is
seen (the tables built at import time never run a changed builder).
Error messages are asserted word for word: a clear message is part of the
behaviour.
"""

import math
from types import SimpleNamespace

import pytest

from st_runtime.faults import STFault
from st_runtime.stdlib import bcd, conversions, fbs, functions
from st_runtime.stdlib.conversions import time_scaled
from st_runtime.types import ELEMENTARY
from st_runtime.values import ValueFormatError

MS = 1_000_000
S = 1_000_000_000
DAY = 86_400 * S
REAL_0_1 = 0.100000001490116119384765625   # the float32 nearest to 0.1: 13421773 / 2**27


def fault(fn, *args):
    with pytest.raises(STFault) as err:
        fn(*args)
    return err.value.code, err.value.message


# --- BCD (IEC 61131-3 2nd ed. / 3rd ed. table 23: one decimal digit a nibble) --

def test_from_bcd_reads_one_digit_per_nibble():
    assert bcd.from_bcd("BCD_TO_INT", 0x1234) == 1234
    assert bcd.from_bcd("BCD_TO_INT", 0x0105) == 105         # a zero digit in the middle
    assert bcd.from_bcd("BCD_TO_INT", 0x9999) == 9999
    assert bcd.from_bcd("BCD_TO_INT", 0) == 0
    assert bcd.from_bcd("BCD_TO_LINT", 0x9876543210) == 9876543210
    assert fault(bcd.from_bcd, "BCD_TO_INT", 0x12A4) == (
        "F-CONVERT", "BCD_TO_INT(16#12A4): nibble A is not a BCD digit")


def test_to_bcd_writes_one_digit_per_nibble_and_checks_the_width():
    assert bcd.to_bcd("INT_TO_BCD", 1234, 16) == 0x1234
    assert bcd.to_bcd("INT_TO_BCD", 105, 16) == 0x0105
    assert bcd.to_bcd("INT_TO_BCD", 0, 16) == 0
    assert bcd.to_bcd("INT_TO_BCD", 9999, 16) == 0x9999       # 4 nibbles: at most 9999
    assert bcd.to_bcd("DINT_TO_BCD", 99_999_999, 32) == 0x99999999
    assert fault(bcd.to_bcd, "INT_TO_BCD", 10000, 16) == (
        "F-CONVERT", "INT_TO_BCD(10000): expected 0..9999, the digits a 16-bit BCD value holds")
    assert fault(bcd.to_bcd, "SINT_TO_BCD", 100, 8) == (
        "F-CONVERT", "SINT_TO_BCD(100): expected 0..99, the digits a 8-bit BCD value holds")
    assert fault(bcd.to_bcd, "INT_TO_BCD", -1, 16)[0] == "F-CONVERT"


def test_bcd_coders_carry_their_name():
    decode, encode = bcd._decoder("BCD_TO_DINT"), bcd._encoder("UINT_TO_BCD_WORD", 16)
    assert (decode.__name__, encode.__name__) == ("BCD_TO_DINT", "UINT_TO_BCD_WORD")
    assert decode(0x42) == 42 and encode(42) == 0x42
    assert fault(decode, 0xF)[1] == "BCD_TO_DINT(16#F): nibble F is not a BCD digit"
    assert fault(encode, 10000)[1] == ("UINT_TO_BCD_WORD(10000): expected 0..9999, "
                                       "the digits a 16-bit BCD value holds")


# 2nd edition: <int>_TO_BCD gives the bit string of the integer's width and
# BCD_TO_<int> takes any bit string; 3rd edition: <bits>_BCD_TO_<uint> and
# <uint>_TO_BCD_<bits>.
BITS = {"SINT": "BYTE", "USINT": "BYTE", "INT": "WORD", "UINT": "WORD",
        "DINT": "DWORD", "UDINT": "DWORD", "LINT": "LWORD", "ULINT": "LWORD"}
WIDTH = {"BYTE": 8, "WORD": 16, "DWORD": 32, "LWORD": 64}
UNSIGNED = {"BYTE": "USINT", "WORD": "UINT", "DWORD": "UDINT", "LWORD": "ULINT"}


def test_bcd_table_signatures_and_widths():
    table = bcd._table()
    expected = {}
    for integer, bits in BITS.items():
        expected[f"BCD_TO_{integer}"] = ("ANY_BITS", integer)
        expected[f"{integer}_TO_BCD"] = ("ANY_INT", bits)
    for bits, integer in UNSIGNED.items():
        expected[f"{bits}_BCD_TO_{integer}"] = (bits, integer)
        expected[f"{integer}_TO_BCD_{bits}"] = (integer, bits)
    assert {name: entry[:2] for name, entry in table.items()} == expected
    for name, (_, _, fn) in table.items():
        assert fn.__name__ == name
        if "BCD_TO" in name:
            assert fn(0x95) == 95
        else:
            digits = WIDTH[table[name][1]] // 4
            assert fn(10 ** digits - 1) == int("9" * digits, 16)
            assert fault(fn, 10 ** digits)[1].startswith(f"{name}({10 ** digits}): expected 0..")


# --- numeric functions --------------------------------------------------------

def test_sqrt_asin_acos_at_the_ends_of_their_domain():
    assert functions.SQRT(0.0) == 0.0
    assert functions.ASIN(1.0) == math.pi / 2 and functions.ASIN(-1.0) == -math.pi / 2
    assert functions.ACOS(1.0) == 0.0 and functions.ACOS(-1.0) == math.pi
    assert math.isnan(functions.ASIN(-1.5)) and math.isnan(functions.ACOS(1.5))


def test_expt_integer_exponents():
    assert functions.EXPT(5, 0) == 1 and isinstance(functions.EXPT(5, 0), int)
    assert functions.EXPT(True, 2) == 1.0 and isinstance(functions.EXPT(True, 2), float)
    assert functions.EXPT(10.0, 400) == math.inf          # 1e400 overflows a double
    assert functions.EXPT(0, -1) == math.inf              # pole, C99 F.9.4.4


def test_expt_overflow_keeps_the_sign_of_an_odd_power():
    # C99 F.9.4.4: pow(x, y) overflows to +-inf; the sign is that of x**y.
    assert functions.EXPT(-10.0, 401.0) == -math.inf       # odd power of a negative base
    assert functions.EXPT(-10.0, 400.0) == math.inf        # even power
    assert functions.EXPT(10.0, 401.0) == math.inf         # positive base
    assert functions.EXPT(0.5, -1025.0) == math.inf        # 2**1025 > the largest double


def test_expt_pole_at_zero():
    # C99 F.9.4.4: pow(+-0, y) for an odd integer y < 0 is +-inf, otherwise +inf.
    assert functions.EXPT(0.0, -3.0) == math.inf
    assert functions.EXPT(-0.0, -3.0) == -math.inf
    assert functions.EXPT(-0.0, -2.0) == math.inf
    assert functions.EXPT(-0.0, -0.5) == math.inf


def test_trig_wrapper_names_and_infinities():
    sin = functions._trig(math.sin)
    assert sin.__name__ == "SIN"
    assert sin(0.5) == math.sin(0.5)
    assert math.isnan(sin(math.inf))


def test_trunc_fault_message():
    assert fault(functions.TRUNC, math.inf) == ("F-CONVERT", "TRUNC(inf): not a finite number")


def test_strict_wrapper_names_the_call():
    sqrt = functions._strict("SQRT", functions.SQRT, functions._finite_args)
    expt = functions._strict("EXPT", functions.EXPT, functions._finite_args)
    assert sqrt.__name__ == "SQRT"
    assert sqrt(4.0) == 2.0 and expt(2, 3) == 8
    assert math.isnan(sqrt(math.nan))
    assert fault(sqrt, -1.0) == ("F-MATH", "SQRT(-1.0) is not a finite number")
    assert fault(expt, 0.0, -1.0) == ("F-MATH", "EXPT(0.0, -1.0) is not a finite number")


# --- selection and bit strings ---------------------------------------------------

def test_mux_bounds_and_message():
    assert functions.MUX(0, 10, 20) == 10
    assert fault(functions.MUX, 3, 10, 20, 30) == ("F-INDEX", "MUX selector K=3 outside 0..2")
    assert fault(functions.MUX, -1, 10, 20)[1] == "MUX selector K=-1 outside 0..1"


@pytest.mark.parametrize("name", ["SHL", "SHR", "ROL", "ROR"])
def test_negative_shift_counts_fault_with_the_function_name(name):
    assert fault(getattr(functions, name), 1, -1, 8) == ("F-MATH", f"{name}: negative shift count -1")


def test_shr_keeps_only_the_operand_width():
    assert functions.SHR(0x1FF, 1, 8) == 0x7F      # BYTE 16#FF >> 1; bit 8 is not part of a BYTE


def test_rotations_by_hand():
    assert functions.ROL(0x1234, 4, 16) == 0x2341
    assert functions.ROR(0x1234, 4, 16) == 0x4123
    assert functions.ROL(0x80000001, 1, 32) == 0x00000003
    assert functions.ROR(0x00000003, 1, 32) == 0x80000001
    assert functions.ROL(0x81, 0, 8) == 0x81
    assert functions.ROL(0x1234, 16, 16) == 0x1234          # a full turn
    assert functions.ROR(0x1234, 20, 16) == 0x4123          # 20 mod 16 = 4
    assert functions.ROL(0x181, 1, 8) == 0x03               # a BYTE: bit 8 is dropped first


# --- strings (1-based positions, F-STRING faults) ----------------------------------

def test_zero_lengths_are_allowed():
    assert functions.LEFT("ABC", 0) == ""
    assert functions.RIGHT("ABC", 0) == ""
    assert functions.MID("ABC", 0, 1) == ""
    assert functions.DELETE("ABC", 0, 1) == "ABC"
    assert functions.REPLACE("ABC", "X", 0, 1) == "XABC"


def test_right_longer_than_the_string():
    assert functions.RIGHT("ABC", 3) == "ABC"
    assert functions.RIGHT("ABC", 5) == "ABC"


def test_first_and_last_positions():
    assert functions.MID("ABC", 1, 1) == "A"
    assert functions.MID("ABC", 1, 3) == "C"
    assert functions.MID("", 0, 1) == ""                    # P = 1 in an empty string
    assert functions.REPLACE("ABC", "X", 0, 4) == "ABCX"   # P = LEN + 1 appends
    assert functions.INSERT("ABC", "X", 0) == "XABC"
    assert functions.INSERT("ABC", "X", 3) == "ABCX"


@pytest.mark.parametrize("call, message", [
    (lambda: functions.LEFT("ABC", -1), "LEFT: negative length -1"),
    (lambda: functions.RIGHT("ABC", -1), "RIGHT: negative length -1"),
    (lambda: functions.MID("ABC", -1, 1), "MID: negative length -1"),
    (lambda: functions.DELETE("ABC", -1, 1), "DELETE: negative length -1"),
    (lambda: functions.REPLACE("ABC", "X", -1, 1), "REPLACE: negative length -1"),
    (lambda: functions.MID("ABC", 1, 0), "MID: position P=0 outside 1..3 of a 3-character string"),
    (lambda: functions.MID("ABC", 1, 4), "MID: position P=4 outside 1..3 of a 3-character string"),
    (lambda: functions.MID("", 0, 2), "MID: position P=2 outside 1..1 of a 0-character string"),
    (lambda: functions.DELETE("ABC", 1, 4), "DELETE: position P=4 outside 1..3 of a 3-character string"),
    (lambda: functions.REPLACE("ABC", "X", 0, 5),
     "REPLACE: position P=5 outside 1..4 of a 3-character string"),
    (lambda: functions.INSERT("ABC", "X", 4), "INSERT: position P=4 outside 0..3"),
    (lambda: functions.INSERT("ABC", "X", -1), "INSERT: position P=-1 outside 0..3"),
])
def test_string_faults_word_for_word(call, message):
    with pytest.raises(STFault) as err:
        call()
    assert (err.value.code, err.value.message) == ("F-STRING", message)


# --- standard FBs on a 1 ms clock ----------------------------------------------------

def make(cls):
    from st_runtime.compiler import install_native_layouts
    install_native_layouts()
    return cls()


def run(fb, steps, outputs, **fixed):
    """Call `fb` once a millisecond (t = 0, 1, 2 ... ms) with the inputs of
    each step; the named outputs after every call."""
    ctx = SimpleNamespace(now_ns=0, scan=0, period_ns=MS)
    seen = []
    for inputs in steps:
        ctx.scan += 1
        for name, value in {**fixed, **inputs}.items():
            setattr(fb, "v_" + name, value)
        fb.execute(ctx)
        ctx.now_ns += MS
        seen.append(tuple(getattr(fb, "v_" + o) for o in outputs))
    return seen


def test_ton_restarts_from_zero_after_in_drops():
    # IEC TON, PT = 3 ms: ET counts from the rising edge of IN and returns to 0
    # (Q FALSE) as soon as IN is FALSE; a new rising edge starts from 0 again.
    ins = [False, False, True, True, False, True, True, True, True, True, False]
    got = run(make(fbs.TON), [{"IN": i} for i in ins], ("Q", "ET"), PT=3 * MS)
    assert got == [(False, 0), (False, 0), (False, 0), (False, MS), (False, 0),
                   (False, 0), (False, MS), (False, 2 * MS), (True, 3 * MS), (True, 3 * MS),
                   (False, 0)]
    assert got[-1][0] is False


def test_tof_q_is_false_after_the_delay():
    # IEC TOF, PT = 2 ms: IN falls at t = 1 ms; Q stays TRUE until ET = PT at 3 ms.
    ins = [True, False, False, False, False, True]
    got = run(make(fbs.TOF), [{"IN": i} for i in ins], ("Q", "ET"), PT=2 * MS)
    assert got == [(True, 0), (True, 0), (True, MS), (False, 2 * MS), (False, 2 * MS), (True, 0)]
    assert got[3][0] is False


def test_tp_et_returns_to_zero_once_in_is_false():
    # IEC TP, PT = 2 ms: the pulse lasts 2 ms; ET holds PT while IN stays TRUE
    # and is 0 once IN is FALSE after the pulse.
    ins = [True, True, True, True, False]
    got = run(make(fbs.TP), [{"IN": i} for i in ins], ("Q", "ET"), PT=2 * MS)
    assert got == [(True, 0), (True, MS), (False, 2 * MS), (False, 2 * MS), (False, 0)]
    assert got[2][0] is False


def test_ctd_counts_rising_edges_only_and_stops_at_int_min():
    ctd = make(fbs.CTD)
    steps = [{"LD": True}, {"LD": False}, {"CD": True}, {"CD": True}, {"CD": False}, {"CD": True}]
    assert run(ctd, steps, ("CV", "Q"), PV=2, CD=False) == [
        (2, False), (2, False), (1, False), (1, False), (1, False), (0, True)]
    steps = [{"LD": True}, {"LD": False, "CD": False}, {"CD": True}]
    assert run(ctd, steps, ("CV",), PV=-32768) == [(-32768,), (-32768,), (-32768,)]


def test_ctud_edges_and_int_limits():
    ctud = make(fbs.CTUD)
    steps = [{"LD": True}, {"LD": False}, {"CD": True}, {"CD": True}, {"CD": False}, {"CU": True}]
    assert run(ctud, steps, ("CV", "QU", "QD"), PV=5, CU=False, CD=False, R=False) == [
        (5, True, False), (5, True, False), (4, False, False), (4, False, False),
        (4, False, False), (5, True, False)]
    steps = [{"LD": True, "CU": False}, {"LD": False}, {"CU": True}]
    assert [cv for cv, in run(ctud, steps, ("CV",), PV=32767, CD=False)] == [32767, 32767, 32767]
    steps = [{"LD": True, "CD": False}, {"LD": False}, {"CD": True}]
    assert [cv for cv, in run(ctud, steps, ("CV",), PV=-32768, CU=False)] == [-32768, -32768, -32768]


# --- conversions: text ---------------------------------------------------------------

def test_real_to_text():
    assert conversions.real_to_text(math.nan, 32) == "NaN"
    assert conversions.real_to_text(math.inf, 64) == "Inf"
    assert conversions.real_to_text(-math.inf, 32) == "-Inf"
    assert conversions.real_to_text(REAL_0_1, 32) == "0.1"        # shortest text of the float32
    assert conversions.real_to_text(REAL_0_1, 64) == "0.10000000149011612"   # of the double


@pytest.mark.parametrize("text, value", [
    ("16#FF", 255), ("-16#F_F", -255), ("16#F__F", 255), ("2#1010", 10), ("8#17", 15),
    ("1_000", 1000), ("1__0", 10), (" +42 ", 42),
])
def test_parse_int_text(text, value):
    assert conversions.parse_int_text(text) == value


@pytest.mark.parametrize("text", ["12_", "16#FF_", "2#12", "16#G", "1.5", ""])
def test_parse_int_text_rejects(text):
    with pytest.raises(ValueFormatError) as err:
        conversions.parse_int_text(text)
    assert str(err.value) == f"{text!r} is not an integer"


def test_parse_real_and_bool_text():
    assert conversions.parse_real_text("1__000.5") == 1000.5
    assert conversions.parse_real_text("-2.5e3") == -2500.0
    with pytest.raises(ValueFormatError) as err:
        conversions.parse_real_text("x1")
    assert str(err.value) == "'x1' is not a number"
    assert conversions.parse_bool_text("1") is True and conversions.parse_bool_text(" true ") is True
    assert conversions.parse_bool_text("0") is False and conversions.parse_bool_text("false") is False
    with pytest.raises(ValueFormatError) as err:
        conversions.parse_bool_text("yes")
    assert str(err.value) == "'yes' is not TRUE or FALSE"


# --- conversions: builders called afresh ---------------------------------------------

def test_real_to_integer_ranges_and_messages():
    # Bit strings take the signed range of their width (the NJ's Real Number-to-Bit String table).
    to_word = conversions._real_to_integer("REAL", ELEMENTARY["WORD"])
    assert to_word(-1.6) == 0xFFFE and to_word(32767.0) == 0x7FFF and to_word(-32768.0) == 0x8000
    assert fault(to_word, 32768.0) == ("F-CONVERT", "REAL_TO_WORD(32768.0): result 32768 outside -32768..32767")
    assert fault(to_word, -32769.0)[1] == "REAL_TO_WORD(-32769.0): result -32769 outside -32768..32767"
    to_uint = conversions._real_to_integer("LREAL", ELEMENTARY["UINT"])
    assert to_uint(65535.0) == 65535 and to_uint(0.0) == 0 and to_uint(2.5) == 2
    assert fault(to_uint, -1.0)[1] == "LREAL_TO_UINT(-1.0): result -1 outside 0..65535"
    assert fault(to_uint, math.nan) == ("F-CONVERT", "LREAL_TO_UINT(nan): not a finite number")


def test_text_to():
    assert conversions._text_to("BOOL")("TRUE") is True
    assert conversions._text_to("INT")("16#7FFF") == 32767
    assert conversions._text_to("INT")("-32768") == -32768
    assert conversions._text_to("WORD")("16#FFFF") == 65535
    assert conversions._text_to("REAL")("0.1") == REAL_0_1
    assert conversions._text_to("LREAL")("0.1") == 0.1
    assert conversions._text_to("TIME")("T#1s500ms") == 1_500_000_000
    assert conversions._text_to("DATE")("D#1970-01-02") == DAY
    assert fault(conversions._text_to("INT"), "32768") == (
        "F-CONVERT", "STRING_TO_INT: 32768 is outside -32768..32767")
    assert fault(conversions._text_to("REAL"), "x")[1] == "STRING_TO_REAL: 'x' is not a number"


def test_to_text():
    assert conversions._to_text("BOOL")(True) == "TRUE" and conversions._to_text("BOOL")(False) == "FALSE"
    assert conversions._to_text("INT")(-5) == "-5"
    assert conversions._to_text("WORD")(65535) == "65535"
    assert conversions._to_text("REAL")(REAL_0_1) == "0.1"
    assert conversions._to_text("LREAL")(REAL_0_1) == "0.10000000149011612"
    assert conversions._to_text("STRING")("abc") == "abc"
    assert conversions._to_text("TIME")(1_500_000_000) == "T#1s500ms"


@pytest.mark.parametrize("src, dst, value, result", [
    ("INT", "STRING", -5, "-5"),
    ("STRING", "INT", "42", 42),
    ("BOOL", "INT", True, 1),
    ("INT", "BOOL", 0, False), ("INT", "BOOL", 5, True), ("REAL", "BOOL", 0.5, True),
    ("INT", "SINT", 4223, 127),                 # module docstring: the low 8 bits
    ("DINT", "INT", 65665, 129),
    ("REAL", "INT", 2.5, 2),                    # W502: ties to even
    ("REAL", "WORD", -1.6, 0xFFFE),
    ("TIME", "LINT", S, S),
    ("DINT", "REAL", 16_777_217, 16_777_216.0),     # 2**24 + 1: a float32 tie, to even
    ("LINT", "LREAL", 16_777_217, 16_777_217.0),    # exact in a double
    ("LREAL", "REAL", 0.1, REAL_0_1),
    ("REAL", "LREAL", REAL_0_1, REAL_0_1),
    ("REAL", "TIME", 2.5, 2),                   # nanoseconds, ties to even
    ("LINT", "TIME", 5, 5),
    ("ULINT", "TIME", 2 ** 64 - 1, -1),         # 64 bits kept, read as signed
    ("DT", "DATE", DAY + 5, DAY),
    ("LINT", "DATE", -1, -DAY),                 # the day that holds -1 ns starts at -1 day
    ("DT", "TOD", 3 * DAY + 7, 7),
    ("LINT", "TOD", -1, DAY - 1),
])
def test_build_by_hand(src, dst, value, result):
    got = conversions._build(src, dst)(value)
    assert got == result and type(got) is type(result)


def test_build_faults_name_the_conversion():
    assert fault(conversions._build("LREAL", "TIME"), math.nan) == (
        "F-CONVERT", "LREAL_TO_TIME(nan): not a finite number")
    # TIME converts through LINT; the fault names TIME (it said LINT before issue 16's run).
    assert fault(conversions._build("REAL", "DATE"), 1e19)[1] == (
        "REAL_TO_DATE(1e+19): result 10000000000000000000 outside "
        "-9223372036854775808..9223372036854775807")
    assert fault(conversions._build("REAL", "INT"), 1e10)[1] == (
        "REAL_TO_INT(10000000000.0): result 10000000000 outside -32768..32767")
    lint_min = -2 ** 63
    assert fault(conversions._build("LINT", "DATE"), lint_min)[1] == (
        f"LINT_TO_DATE({lint_min}): the day starts outside the DATE range")
    assert fault(conversions._drop_time_of_day, "LINT", "DATE", lint_min) == (
        "F-CONVERT", f"LINT_TO_DATE({lint_min}): the day starts outside the DATE range")
    assert conversions._kind("STRING") == "string" and conversions._kind("TOD") == "tod"


TYPES = ["BOOL", "SINT", "INT", "DINT", "LINT", "USINT", "UINT", "UDINT", "ULINT",
         "BYTE", "WORD", "DWORD", "LWORD", "REAL", "LREAL", "TIME", "DATE", "TOD", "DT", "STRING"]
SPELLINGS = {"TOD": ("TOD", "TIME_OF_DAY"), "DT": ("DT", "DATE_AND_TIME")}


def test_conversion_table_has_every_pair_and_spelling():
    table = conversions._table()
    expected = {f"{s}_TO_{d}" for a in TYPES for b in TYPES if a != b
                for s in SPELLINGS.get(a, (a,)) for d in SPELLINGS.get(b, (b,))}
    assert set(table) == expected
    assert table["TIME_OF_DAY_TO_DATE_AND_TIME"] is table["TOD_TO_DT"]
    assert table["INT_TO_SINT"](4223) == 127
    assert table["DT_TO_TOD"](DAY + 7) == 7


def test_conversion_lookup_message():
    with pytest.raises(KeyError) as err:
        conversions.conversion("foo", "int")
    assert err.value.args == ("no conversion FOO_TO_INT",)


# --- TIME counted in another unit (the NJ counts TIME conversions in ns; a
#     dialect may count ms: the number is the TIME divided by the unit,
#     truncated toward zero like an integer division) ----------------------------------

def test_time_scaled_to_and_from_numbers():
    assert time_scaled("TIME_TO_DINT", MS)(1_500_000) == 1
    assert time_scaled("TIME_TO_DINT", MS)(-1_500_000) == -1
    assert time_scaled("time_to_dint", MS)(2 * MS) == 2
    assert time_scaled("TIME_TO_LREAL", MS)(1_500_000) == 1.5
    assert time_scaled("TIME_TO_DWORD", MS)(1_500_000) == 1          # bit strings count too
    assert time_scaled("DINT_TO_TIME", MS)(3) == 3 * MS
    assert time_scaled("LREAL_TO_TIME", MS)(1.5) == 1_500_000
    # 9e12 ms + 999_999 ns: the quotient needs more digits than a double has.
    big = 9_000_000_000_000 * MS + 999_999
    assert time_scaled("TIME_TO_LINT", MS)(big) == 9_000_000_000_000
    assert time_scaled("TIME_TO_LINT", MS)(-big) == -9_000_000_000_000


@pytest.mark.parametrize("name, unit", [
    ("TIME_TO_DINT", 1), ("NOT_A_CONVERSION", MS), ("DINT_TO_LINT", MS),
    ("DATE_TO_DINT", MS), ("TIME_TO_DATE", MS), ("STRING_TO_TIME", MS),
])
def test_time_scaled_only_for_time_and_numbers(name, unit):
    assert time_scaled(name, unit) is None
