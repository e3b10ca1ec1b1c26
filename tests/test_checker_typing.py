"""Expression typing, the literal typing rule, constant folding and the
implicit conversions of IEC 61131-3 (expected values worked out by hand)."""

from __future__ import annotations

import pytest

from st_runtime import ast
from st_runtime import types as T
from st_runtime.checker import typesys as ts
from checker_helpers import checked, nodes, statement

E = T.ELEMENTARY


def program_with(decls: str, stmts: str):
    return checked(f"PROGRAM Main\nVAR\n{decls}\nEND_VAR\n{stmts}\nEND_PROGRAM\n")


def value_of(program, index: int):
    """(type, constant) of the right side of the index-th assignment."""
    s = statement(program, index)
    return program.expr_types[id(s.value)], program.constants.get(id(s.value))


# ------------------------------------------------------ implicit conversions

WIDENING = [
    ("SINT", "INT"), ("INT", "DINT"), ("DINT", "LINT"), ("SINT", "LINT"),
    ("USINT", "UINT"), ("UINT", "UDINT"), ("UDINT", "ULINT"),
    ("USINT", "INT"), ("UINT", "DINT"), ("UDINT", "LINT"),
    ("SINT", "REAL"), ("INT", "REAL"), ("UINT", "REAL"), ("REAL", "LREAL"),
    ("DINT", "LREAL"), ("INT", "LREAL"),
    ("BYTE", "WORD"), ("WORD", "DWORD"), ("DWORD", "LWORD"), ("BYTE", "LWORD"),
]
NARROWING_OR_CROSS = [
    ("INT", "SINT"), ("DINT", "INT"), ("LREAL", "REAL"), ("REAL", "DINT"),
    ("DINT", "REAL"), ("UDINT", "REAL"), ("INT", "UINT"), ("UINT", "INT"),
    ("SINT", "USINT"), ("WORD", "INT"), ("INT", "WORD"), ("BOOL", "INT"),
    ("TIME", "DINT"), ("DINT", "TIME"), ("LWORD", "DWORD"), ("REAL", "TIME"),
]


@pytest.mark.parametrize("src,dst", WIDENING)
def test_widening_conversions_are_implicit(src, dst):
    assert ts.implicitly_converts(E[src], E[dst])


@pytest.mark.parametrize("src,dst", NARROWING_OR_CROSS)
def test_other_conversions_are_not_implicit(src, dst):
    assert not ts.implicitly_converts(E[src], E[dst])


@pytest.mark.parametrize("a,b,common", [
    ("INT", "DINT", "DINT"), ("SINT", "USINT", "INT"), ("DINT", "REAL", "LREAL"),
    ("INT", "REAL", "REAL"), ("UINT", "INT", "DINT"), ("BYTE", "WORD", "WORD"),
    ("ULINT", "LINT", None), ("BOOL", "INT", None), ("TIME", "DINT", None),
])
def test_common_type_of_binary_operands(a, b, common):
    result = ts.common_type(E[a], E[b])
    assert (result.name if result is not None else None) == common


def test_assignment_error_names_both_types_and_the_conversion():
    from checker_helpers import load
    result, program = load("PROGRAM Main\nVAR i : INT; x : LREAL; END_VAR\ni := x;\nEND_PROGRAM\n")
    assert program is None
    [d] = result.errors
    assert d.code == "E-TYPE-004"
    assert "INT" in d.message and "LREAL" in d.message and "LREAL_TO_INT" in d.message


# ---------------------------------------------------------- literal typing

def test_untyped_literal_takes_the_other_operands_type():
    p = program_with("i : INT; x : LREAL; r : REAL;", "i := i + 1;\nx := x * 2;\nr := r * 0.1;")
    one = statement(p, 0).value.right
    assert p.expr_types[id(one)] is T.INT and p.constants[id(one)] == 1
    two = statement(p, 1).value.right
    assert p.expr_types[id(two)] is T.LREAL and p.constants[id(two)] == 2.0
    tenth = statement(p, 2).value.right
    assert p.expr_types[id(tenth)] is T.REAL
    # REAL constants are stored as float32: 0.1 becomes 0.100000001490116...
    assert p.constants[id(tenth)] == pytest.approx(0.10000000149011612, abs=0)


def test_literal_in_assignment_takes_the_targets_type():
    p = program_with("d : DINT; x : LREAL; b : BYTE;", "d := 70000;\nx := 3;\nb := 16#FF;")
    assert value_of(p, 0) == (T.DINT, 70000)
    t, v = value_of(p, 1)
    assert t is T.LREAL and v == 3.0 and isinstance(v, float)
    assert value_of(p, 2) == (T.BYTE, 255)


def test_integer_constant_expression_keeps_integer_division():
    # IEC: 1/2 of two integer literals is an integer division (0), converted afterwards.
    p = program_with("x : LREAL; d : DINT;", "x := 1 / 2;\nd := -7 / 2;\nd := -7 MOD 2;")
    t, v = value_of(p, 0)
    assert ts.is_int(t) and v == 0
    assert value_of(p, 1)[1] == -3      # truncation toward zero
    assert value_of(p, 2)[1] == -1      # sign of the dividend


def test_context_free_constant_gets_the_smallest_type_holding_it():
    p = program_with("b : BOOL;", "b := 100 + 100 > 150;\nb := 1 + 1 > 1;")
    big = statement(p, 0).value.left
    assert p.expr_types[id(big)] is T.INT and p.constants[id(big)] == 200
    assert p.constants[id(statement(p, 0).value)] is True
    small = statement(p, 1).value.left
    assert p.expr_types[id(small)] is T.SINT


def test_negative_literal_fits_its_signed_minimum():
    p = program_with("s : SINT;", "s := -128;")
    assert value_of(p, 0) == (T.SINT, -128)


def test_typed_literals_have_their_prefix_type():
    p = program_with("x : LREAL; i : INT; w : WORD;", "x := LREAL#1;\ni := INT#-5;\nw := WORD#16#00FF;")
    assert value_of(p, 0) == (T.LREAL, 1.0)
    assert value_of(p, 1) == (T.INT, -5)
    assert value_of(p, 2) == (T.WORD, 255)


@pytest.mark.parametrize("dialect, folded", [("nj", -56), ("iec", 200)])
def test_typed_constant_arithmetic_folds_like_the_runtime(dialect, folded):
    p = checked("PROGRAM Main\nVAR CONSTANT c : SINT := 100; END_VAR\nVAR s : SINT; END_VAR\n"
                "s := c + c;\nEND_PROGRAM\n", dialect)
    # SINT + SINT stays SINT.  The NJ overflows inside the expression: 200
    # wraps to 200 - 256 = -56 (W501 6-5-3); under iec the run time keeps the
    # exact sum until it is stored, and so does the fold.
    assert value_of(p, 0) == (T.SINT, folded)


# ------------------------------------------------------------- operators

def test_binary_result_is_the_common_type():
    p = program_with("i : INT; d : DINT; r : REAL; x : LREAL; u : UINT;",
                     "d := i + d;\nx := d + r;\nx := i * r;\nd := u + i;")
    assert value_of(p, 0)[0] is T.DINT
    assert value_of(p, 1)[0] is T.LREAL
    assert value_of(p, 2)[0] is T.REAL
    assert value_of(p, 3)[0] is T.DINT


def test_time_arithmetic():
    p = program_with("t : TIME; x : LREAL; tod1 : TOD; dt1 : DT; dt2 : DT;",
                     "t := t * 2;\nt := t / x;\nt := T#1s + T#500ms;\n"
                     "tod1 := tod1 + T#1h;\nt := dt1 - dt2;\nt := 3 * t;")
    assert value_of(p, 0)[0] is T.TIME
    assert value_of(p, 1)[0] is T.TIME
    assert value_of(p, 2) == (T.TIME, 1_500_000_000)
    assert value_of(p, 3)[0] is T.TOD
    assert value_of(p, 4)[0] is T.TIME
    assert value_of(p, 5)[0] is T.TIME


def test_comparisons_and_logic():
    p = program_with("i : INT; d : DINT; b : BOOL; w : WORD; bt : BYTE;",
                     "b := i < d AND b;\nw := w AND bt;\nb := NOT b XOR (i = 3);\nw := NOT w;")
    assert value_of(p, 0)[0] is T.BOOL
    assert value_of(p, 1)[0] is T.WORD
    assert value_of(p, 2)[0] is T.BOOL
    assert value_of(p, 3)[0] is T.WORD


def test_every_expression_node_has_a_type():
    p = program_with("i : INT; a : ARRAY[1..3] OF LREAL; x : LREAL;",
                     "x := a[i] * 2.0 + SQRT(ABS(a[1])) + INT_TO_LREAL(i MOD 2) ** 2.0;")
    s = statement(p, 0)
    exprs = [n for n in nodes(s, (ast.IntLiteral, ast.RealLiteral, ast.Name, ast.Index,
                                  ast.Binary, ast.Unary, ast.Call))
             if not (isinstance(n, ast.Name) and any(c.callee is n for c in nodes(s, ast.Call)))]
    missing = [n for n in exprs if id(n) not in p.expr_types]
    assert not missing


# --------------------------------------------------------------- calls

def test_standard_functions_are_instantiated_at_the_common_type():
    p = program_with("i : INT; x : LREAL; r : REAL; w : WORD; s : STRING[10];",
                     "i := MAX(i, 1000);\nx := LIMIT(0.0, x, 5);\nr := SQRT(r);\n"
                     "w := SHL(w, 3);\ni := LEN(s);\nx := SQRT(2);\ni := SEL(TRUE, i, 3);")
    expected = [T.INT, T.LREAL, T.REAL, T.WORD, None, T.LREAL, T.INT]
    for n, generic in enumerate(expected):
        call = statement(p, n).value
        target = p.call_targets[id(call)]
        assert target.kind == "function"
        assert target.generic_type is generic, (n, target)
    assert p.expr_types[id(statement(p, 4).value)] is T.INT


def test_conversion_call_target():
    p = program_with("i : INT; r : REAL; s : SINT;", "r := INT_TO_REAL(i);\nr := INT_TO_REAL(s);")
    target = p.call_targets[id(statement(p, 0).value)]
    assert (target.kind, target.name, target.generic_type) == ("conversion", "INT_TO_REAL", T.REAL)
    assert value_of(p, 1)[0] is T.REAL   # SINT widens into the INT input


def test_trunc_follows_its_integer_context():
    p = program_with("x : LREAL; i : INT; d : DINT;", "i := TRUNC(x);\nd := TRUNC(x);")
    assert value_of(p, 0)[0] is T.INT
    assert value_of(p, 1)[0] is T.DINT


# ------------------------------------------------------ the type under an array's dimensions

def test_innermost_strips_every_array_level_and_nothing_else():
    """`ARRAY[1..2] OF ARRAY[0..3] OF F` holds F's; an array of one level its element; a
    type that is no array is itself (a STRUCT of arrays is not looked into)."""
    fb = T.FBType("F")
    inner = T.ArrayType(((0, 3),), fb)
    assert ts.innermost(T.ArrayType(((1, 2),), inner)) is fb
    assert ts.innermost(inner) is fb
    assert ts.innermost(fb) is fb
    struct = T.StructType("S", {"A": ("A", inner)})
    assert ts.innermost(struct) is struct
