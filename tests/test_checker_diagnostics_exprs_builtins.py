"""The checker's tables of the standard functions, stated in full from IEC 61131-3
(issue 16, docs/mutation.md, checker, session 12).

builtins.py and operator_calls.py are mostly data: the text of each generic
category, the operators in call form (the signatures of the standard
functions are test_checker_mutants.py's).  A mutant of one entry changes what
a call accepts or says, so each table is compared here in full with the
standard's (3rd ed. 2013, tables 29-31 and 36), built afresh where the module
builds it at import, and each category rule, conversion name and constant
fold on both sides.
"""

from __future__ import annotations

import math

import pytest

from st_runtime import types as T
from st_runtime.checker import builtins as B
from st_runtime.checker import typesys as ts
from st_runtime.checker.constfold import NOT_CONSTANT, DivisionByZero, apply_binary, apply_unary
from st_runtime.checker import operator_calls
from st_runtime.checker.operator_calls import OPERATOR_FUNCTIONS, OperatorFunction, lower, ordered_inputs
from st_runtime import ast


def test_the_inputs_after_the_declared_ones_are_numbered_on():
    """MAX's third input is IN3, MUX's (after K, IN0, IN1) IN2; each of the last
    declared input's category and genericity."""
    assert B.extra_param(B.STANDARD_FUNCTIONS["MAX"], 2) == B.Param("IN3", "ANY_ELEMENTARY", True)
    assert B.extra_param(B.STANDARD_FUNCTIONS["MAX"], 1) == B.Param("IN2", "ANY_ELEMENTARY", True)
    assert B.extra_param(B.STANDARD_FUNCTIONS["MUX"], 3) == B.Param("IN2", "ANY", True)
    assert B.extra_param(B.STANDARD_FUNCTIONS["CONCAT"], 4) == B.Param("IN5", "STRING", False)


# The members of each generic category by name, from IEC 61131-3 (3rd ed. 2013) figure 5 and table 10
# (the elementary types): not from builtins.py.  ANY_BITS is the checker's name for figure 5's ANY_BIT
# without BOOL, the bit strings of 8, 16, 32 and 64 bits (typesys.is_bits).
_INTEGERS = {"SINT", "INT", "DINT", "LINT", "USINT", "UINT", "UDINT", "ULINT"}
_BIT_STRINGS = {"BYTE", "WORD", "DWORD", "LWORD"}
_ELEMENTARY = (_INTEGERS | _BIT_STRINGS | {"BOOL", "REAL", "LREAL", "STRING", "TIME", "DATE",
                                            "TIME_OF_DAY", "TOD", "DATE_AND_TIME", "DT"})
IEC_MEMBERS = {
    "ANY_NUM": _INTEGERS | {"REAL", "LREAL"},
    "ANY_REAL": {"REAL", "LREAL"},
    "ANY_INT": _INTEGERS,
    "ANY_BITS": _BIT_STRINGS,
    "ANY_BIT": _BIT_STRINGS | {"BOOL"},
    "ANY_ELEMENTARY": _ELEMENTARY,
    "ANY": _ELEMENTARY,
    "STRING": {"STRING"},
    "BOOL": {"BOOL"},
}


def _words(text: str) -> list[str]:
    return text.replace(",", " ").split()


def test_every_generic_parameter_of_a_standard_function_is_described_in_words():
    """A parameter of a generic category gets words in E-TYPE-004; one of a single named type
    (BCD's BYTE .. LWORD, UINT ..) is named as it is."""
    used = {p.category for fn in B.STANDARD_FUNCTIONS.values() for p in fn.params}
    used |= {c for fn in OPERATOR_FUNCTIONS.values() for c in fn.operands}
    generic = {c for c in used if c.startswith("ANY")}
    assert generic <= set(B.CATEGORY_TEXT)
    assert set(B.CATEGORY_TEXT) <= set(IEC_MEMBERS)
    for named in used - set(B.CATEGORY_TEXT):
        assert B.describe(named) == named
    assert B.describe("WORD") == "WORD"


@pytest.mark.parametrize("category", sorted(IEC_MEMBERS))
def test_each_category_is_described_by_its_members(category):
    """What each category's words may say, from figure 5: every type they name belongs to it; they
    name the category itself in parentheses at the end, or else name exactly its members (ANY, which
    holds every type, names none: "a value"); the other words are lower-case English, after the
    article that agrees with the next word (context.a_or_an's rule, or none before a type name)."""
    text = B.describe(category)
    words = _words(text)
    named_types = {w for w in words if w in _ELEMENTARY}
    assert named_types <= IEC_MEMBERS[category]
    if words[-1] == f"({category})":
        words = words[:-1]
    elif category == "ANY":
        assert named_types == set()
    else:
        assert named_types == IEC_MEMBERS[category]
    assert all(w in _ELEMENTARY or w in {"a", "an", "or"} or (w.isalpha() and w.islower()) for w in words)
    if words[0] in {"a", "an"}:
        assert words[0] == ("an" if words[1][0] in "AEIOaeio" else "a")
    else:
        assert words[0] in _ELEMENTARY


# (category, types in it, types not in it) - 3rd ed. figure 5, the generic data types
CATEGORIES = [
    ("ANY_NUM", [T.SINT, T.ULINT, T.REAL, T.LREAL], [T.BOOL, T.WORD, T.TIME, T.StringType()]),
    ("ANY_REAL", [T.REAL, T.LREAL], [T.DINT, T.LWORD]),
    ("ANY_INT", [T.SINT, T.INT, T.UDINT, T.ULINT], [T.REAL, T.BYTE, T.BOOL]),
    ("ANY_BITS", [T.BYTE, T.LWORD], [T.BOOL, T.INT]),
    ("ANY_BIT", [T.BOOL, T.BYTE, T.DWORD], [T.SINT, T.REAL]),
    ("ANY_ELEMENTARY", [T.BOOL, T.TIME, T.LREAL, T.StringType()], [T.ArrayType(((1, 2),), T.INT)]),
    ("ANY", [T.INT, T.ArrayType(((1, 2),), T.INT)], [T.FBType("TON", {})]),
    ("STRING", [T.StringType(), T.StringType(10)], [T.INT, T.BYTE]),
    ("BOOL", [T.BOOL], [T.BYTE, T.SINT]),
    ("WORD", [T.WORD], [T.UINT, T.DWORD]),
]


@pytest.mark.parametrize("category, members, others", CATEGORIES, ids=[c[0] for c in CATEGORIES])
def test_each_category_holds_its_types_and_no_other(category, members, others):
    assert [B.in_category(t, category) for t in members] == [True] * len(members)
    assert [B.in_category(t, category) for t in others] == [False] * len(others)
    assert B.in_category(ts.ERROR, category)          # (already reported: no second error)


@pytest.mark.parametrize("name, pair", [
    ("INT_TO_DINT", (T.INT, T.DINT)),
    ("int_to_lreal", (T.INT, T.LREAL)),
    ("TIME_OF_DAY_TO_DT", (T.TOD, T.DT)),              # an underscore inside the source type
    ("DATE_AND_TIME_TO_TIME_OF_DAY", (T.DT, T.TOD)),
    ("TOD_TO_TIME_OF_DAY", None),                      # the same type: no conversion
    ("INT_TO_INT", None),
    ("INT_TO_FOO", None),
    ("INTTODINT", None),
    ("_TO_INT", None),
    ("STRING_TO_INT", "STRING"),
    ("WORD_TO_STRING", "STRING"),
])
def test_conversion_names(name, pair):
    found = B.conversion(name)
    if pair == "STRING":
        src, dst = found
        assert {type(src), type(dst)} == {T.StringType, T.ElementaryType}
        assert B.is_standard_name(name)
    else:
        assert found == pair
        assert B.is_standard_name(name) == (pair is not None)


def test_standard_names():
    assert B.is_standard_name("max") and B.is_standard_name("WORD_BCD_TO_UINT")
    assert not B.is_standard_name("MAXIMUM")


# ------------------------------------------------------------------ operators in call form

def test_the_operators_in_call_form():
    """3rd ed. tables 29-31 and 36: the arithmetic and comparison functions, and the
    named time arithmetic (with the operand types each requires)."""
    def entry(fn: OperatorFunction):
        return fn.op, fn.extensible, fn.operands, fn.result

    assert {name: entry(fn) for name, fn in OPERATOR_FUNCTIONS.items()} == {
        "ADD": ("+", True, (), None), "MUL": ("*", True, (), None),
        "SUB": ("-", False, (), None), "DIV": ("/", False, (), None), "MOD": ("MOD", False, (), None),
        "GT": (">", True, (), None), "GE": (">=", True, (), None), "EQ": ("=", True, (), None),
        "NE": ("<>", False, (), None), "LE": ("<=", True, (), None), "LT": ("<", True, (), None),
        "ADD_TIME": ("+", False, ("TIME", "TIME"), "TIME"),
        "SUB_TIME": ("-", False, ("TIME", "TIME"), "TIME"),
        "MULTIME": ("*", False, ("TIME", "ANY_NUM"), "TIME"),
        "MUL_TIME": ("*", False, ("TIME", "ANY_NUM"), "TIME"),
        "DIVTIME": ("/", False, ("TIME", "ANY_NUM"), "TIME"),
        "DIV_TIME": ("/", False, ("TIME", "ANY_NUM"), "TIME"),
        "ADD_TOD_TIME": ("+", False, ("TIME_OF_DAY", "TIME"), "TIME_OF_DAY"),
        "ADD_DT_TIME": ("+", False, ("DATE_AND_TIME", "TIME"), "DATE_AND_TIME"),
        "SUB_DATE_DATE": ("-", False, ("DATE", "DATE"), "TIME"),
        "SUB_TOD_TIME": ("-", False, ("TIME_OF_DAY", "TIME"), "TIME_OF_DAY"),
        "SUB_TOD_TOD": ("-", False, ("TIME_OF_DAY", "TIME_OF_DAY"), "TIME"),
        "SUB_DT_TIME": ("-", False, ("DATE_AND_TIME", "TIME"), "DATE_AND_TIME"),
        "SUB_DT_DT": ("-", False, ("DATE_AND_TIME", "DATE_AND_TIME"), "TIME"),
    }
    # (the time entries' builder, called afresh: the table above was built at import)
    assert operator_calls._time("-", "DATE", "DATE", "TIME") == \
        OperatorFunction("-", False, ("DATE", "DATE"), "TIME")


def _arg(value, name=None, direction="in"):
    return ast.Arg(name, value, direction)


def test_inputs_are_put_in_order_by_name_and_position():
    add = OPERATOR_FUNCTIONS["ADD"]
    a, b, c = ast.Name("a"), ast.Name("b"), ast.Name("c")
    assert ordered_inputs("ADD", add, [_arg(a), _arg(b)]) == ([a, b], None)
    assert ordered_inputs("ADD", add, [_arg(c, "IN3"), _arg(a, "in1"), _arg(b, "IN2")]) == ([a, b, c], None)
    assert ordered_inputs("ADD", add, [_arg(a), _arg(b, "IN2"), _arg(c, "IN3")]) == ([a, b, c], None)
    assert ordered_inputs("SUB", OPERATOR_FUNCTIONS["SUB"], [_arg(a, "IN1"), _arg(b, "INX")]) == \
        ([], ("E-CALL-002", "SUB has no parameter 'INX' (parameters: IN1, IN2)"))
    assert ordered_inputs("SUB", OPERATOR_FUNCTIONS["SUB"], [_arg(a, "IN1"), _arg(b, "IN2"), _arg(c, "IN3")]) == \
        ([], ("E-CALL-006", "SUB: expected 2 argument(s), found 3"))


def test_a_chained_comparison_is_every_neighbouring_pair():
    """GT(a, b, c) is a > b AND b > c (3rd ed. table 31: the extensible comparisons
    hold for every neighbouring pair); ADD(a, b, c) is (a + b) + c."""
    a, b, c = ast.Name("a"), ast.Name("b"), ast.Name("c")
    pos = ast.Pos("t.st", 3, 7)
    chain = lower(OPERATOR_FUNCTIONS["GT"], [a, b, c], pos)
    assert (chain.op, chain.left.op, chain.right.op) == ("AND", ">", ">")
    assert (chain.left.left, chain.left.right, chain.right.left, chain.right.right) == (a, b, b, c)
    assert chain.pos == chain.left.pos == chain.right.pos == pos
    total = lower(OPERATOR_FUNCTIONS["ADD"], [a, b, c], pos)
    assert (total.op, total.left.op, total.left.left, total.left.right, total.right) == ("+", "+", a, b, c)
    pair = lower(OPERATOR_FUNCTIONS["GE"], [a, b], pos)
    assert (pair.op, pair.left, pair.right, pair.pos) == (">=", a, b, pos)


# ------------------------------------------------------------------ constant folding

@pytest.mark.parametrize("op, a, b, value", [
    ("AND", True, False, False), ("&", True, True, True), ("OR", False, True, True), ("XOR", True, True, False),
    ("AND", 0b1100, 0b1010, 0b1000), ("&", 0b1100, 0b1010, 0b1000), ("OR", 0b1100, 0b1010, 0b1110),
    ("XOR", 0b1100, 0b1010, 0b0110), ("AND", True, 3, 1), ("XOR", True, 3, 2),     # BOOL as bit 1 with a bit string
    ("=", 2, 3, False), ("<>", 2, 3, True), ("<", 2, 3, True), (">", 2, 3, False), ("<=", 3, 3, True),
    (">=", 2, 3, False), ("<", "ab", "b", True), ("=", "a", 1, NOT_CONSTANT),
    ("+", 2, 3, 5), ("-", 2, 3, -1), ("*", 2, 3, 6),
    ("/", 7, -2, -3), ("/", -7, 2, -3),             # integer / truncates toward zero
    ("MOD", -7, 2, -1), ("MOD", 7, -2, 1),          # MOD takes the dividend's sign
    ("/", 1.0, 4, 0.25), ("/", 1.0, 0.0, math.inf), ("MOD", 7.0, 2, NOT_CONSTANT),
    ("**", 2.0, 3, 8.0), ("**", 0.0, -1.0, math.inf),
    ("+", True, 1, NOT_CONSTANT), ("+", NOT_CONSTANT, 1, NOT_CONSTANT), ("+", 1, NOT_CONSTANT, NOT_CONSTANT),
    ("AND", 1.5, 1, NOT_CONSTANT), ("?", 1, 2, NOT_CONSTANT),
])
def test_binary_folds(op, a, b, value):
    found = apply_binary(op, a, b)
    assert found == value and type(found) is type(value)


@pytest.mark.parametrize("op, a", [("/", 1), ("MOD", 1)])
def test_integer_division_by_zero_is_reported(op, a):
    with pytest.raises(DivisionByZero):
        apply_binary(op, a, 0)


def test_unary_folds():
    assert [apply_unary("-", 5), apply_unary("-", 2.5), apply_unary("+", -3), apply_unary("NOT", True)] == \
        [-5, -2.5, -3, False]
    assert [apply_unary("-", True), apply_unary("+", "s"), apply_unary("NOT", 5), apply_unary("?", 1)] == \
        [NOT_CONSTANT] * 4
