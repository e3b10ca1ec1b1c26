"""The printer: round trip on the whole corpus, minimal parentheses, layout."""

from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from st_runtime import ast
from st_runtime.parser import parse
from st_runtime.printer import format_expr, format_source, format_stmt

ACCEPT = sorted((Path(__file__).parent / "corpus" / "accept").glob("*.st"))


def parse_ok(text: str, path: str = "p.st") -> ast.SourceFile:
    tree, diagnostics = parse(text, path)
    assert not diagnostics, "\n".join(d.render(text) for d in diagnostics)
    return tree


@pytest.mark.parametrize("path", ACCEPT, ids=lambda p: p.stem)
def test_round_trip_corpus(path: Path):
    original = parse_ok(path.read_text(encoding="utf-8"), path.name)
    printed = format_source(original)
    again = parse_ok(printed, path.name)
    assert again == original
    assert format_source(again) == printed  # printing is stable


def N(name):  # noqa: N802
    return ast.Name(name)


def I(value):  # noqa: N802
    return ast.IntLiteral(value)


def B(op, left, right):  # noqa: N802
    return ast.Binary(op, left, right)


def U(op, operand):  # noqa: N802
    return ast.Unary(op, operand)


EXPRESSIONS = [
    (B("+", I(1), B("*", I(2), I(3))), "1 + 2 * 3"),
    (B("*", B("+", I(1), I(2)), I(3)), "(1 + 2) * 3"),
    (B("-", N("a"), B("-", N("b"), N("c"))), "a - (b - c)"),
    (B("-", B("-", N("a"), N("b")), N("c")), "a - b - c"),
    (B("**", B("**", N("a"), N("b")), N("c")), "a ** b ** c"),
    (B("**", N("a"), B("**", N("b"), N("c"))), "a ** (b ** c)"),
    (U("-", B("**", N("a"), N("b"))), "-a ** b"),
    (B("**", U("-", N("a")), N("b")), "(-a) ** b"),
    (B("**", N("a"), U("-", N("b"))), "a ** (-b)"),
    (U("-", U("-", N("a"))), "-(-a)"),
    (U("-", B("+", N("a"), N("b"))), "-(a + b)"),
    (U("NOT", B("AND", N("a"), N("b"))), "NOT (a AND b)"),
    (B("AND", U("NOT", N("a")), N("b")), "NOT a AND b"),
    (B("OR", N("a"), B("AND", N("b"), N("c"))), "a OR b AND c"),
    (B("AND", B("OR", N("a"), N("b")), N("c")), "(a OR b) AND c"),
    (B("=", B("<", N("x"), N("y")), N("b")), "x < y = b"),
    (B("<", N("x"), B("=", N("y"), N("b"))), "x < (y = b)"),
    (B("*", N("a"), U("-", N("b"))), "a * -b"),
    (ast.Member(ast.Index(N("a"), (I(1), I(2))), "b"), "a[1, 2].b"),
    (ast.Call(N("MAX"), (ast.Arg(None, I(1)), ast.Arg("IN", N("x")))), "MAX(1, IN := x)"),
    (ast.RealLiteral(1e-9), "1.0E-09"),
    (ast.RealLiteral(2.0, "LREAL"), "LREAL#2.0"),
    (ast.IntLiteral(-5, "INT"), "INT#-5"),
    (ast.TimeLiteral(1_500_000_000), "T#1s500ms"),
    (ast.TimeLiteral(-2_500_000_000), "T#-2s500ms"),
    (ast.StringLiteral("It's $5\n"), "'It$'s $$5$N'"),
    (ast.EnumLiteral("Color", "Red"), "Color#Red"),
]


@pytest.mark.parametrize("node,text", EXPRESSIONS, ids=[t for _, t in EXPRESSIONS])
def test_format_expr(node, text):
    assert format_expr(node) == text


def test_format_stmt_indents_nested_blocks():
    stmt = ast.If(
        (ast.IfBranch(N("a"), (ast.For("i", I(1), I(3), None, (ast.Assign(N("x"), N("i")),)),)),),
        (ast.Exit(),))
    assert format_stmt(stmt) == (
        "IF a THEN\n"
        "    FOR i := 1 TO 3 DO\n"
        "        x := i;\n"
        "    END_FOR;\n"
        "ELSE\n"
        "    EXIT;\n"
        "END_IF;")


def test_format_source_layout():
    text = ("type pt : struct x : lreal; end_struct; end_type "
            "function_block fb var_input a : INT := 1; end_var "
            "case a of 1, 2..3: a := 0; else ; end_case end_function_block")
    assert format_source(parse_ok(text)) == (
        "TYPE\n"
        "    pt : STRUCT\n"
        "        x : lreal;\n"
        "    END_STRUCT;\n"
        "END_TYPE\n"
        "\n"
        "FUNCTION_BLOCK fb\n"
        "VAR_INPUT\n"
        "    a : INT := 1;\n"
        "END_VAR\n"
        "    CASE a OF\n"
        "        1, 2..3:\n"
        "            a := 0;\n"
        "    ELSE\n"
        "        ;\n"
        "    END_CASE;\n"
        "END_FUNCTION_BLOCK\n")


def test_long_generated_sum_prints_without_recursion_limit():
    expr = ast.Name("a0")
    for i in range(1, 5000):
        expr = B("+" if i % 2 else "-", expr, B("*", N(f"a{i}"), N("b")))
    text = format_expr(expr)
    assert text.startswith("a0 + a1 * b - a2 * b + a3 * b")
    assert text.count(" * b") == 4999


# ------------------------------------------- round trip of random expressions

_names = st.sampled_from(["a", "b", "Speed", "x1"]).map(ast.Name)
_leaves = st.one_of(
    _names,
    st.integers(0, 10**12).map(ast.IntLiteral),
    st.floats(0, 1e30, allow_nan=False, allow_infinity=False).map(ast.RealLiteral),
    st.integers(-10**15, 10**15).map(ast.TimeLiteral),
    st.booleans().map(ast.BoolLiteral),
    st.text(max_size=8).map(ast.StringLiteral),
)
_binary_ops = st.sampled_from(["OR", "XOR", "AND", "=", "<>", "<", ">", "<=", ">=",
                               "+", "-", "*", "/", "MOD", "**"])


def _extend(children):
    return st.one_of(
        st.builds(ast.Binary, _binary_ops, children, children),
        st.builds(ast.Unary, st.sampled_from(["-", "+", "NOT"]), children),
        st.builds(ast.Member, _names, st.sampled_from(["x", "Q"])),
        st.builds(ast.Index, _names, st.lists(children, min_size=1, max_size=3).map(tuple)),
        st.builds(ast.Call, st.sampled_from(["MAX", "F"]).map(ast.Name),
                  st.lists(children.map(lambda e: ast.Arg(None, e)), max_size=3).map(tuple)),
    )


expressions = st.recursive(_leaves, _extend, max_leaves=12)


@settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(expressions)
def test_random_expressions_round_trip(expr):
    text = f"PROGRAM P\n    y := {format_expr(expr)};\nEND_PROGRAM\n"
    tree = parse_ok(text)
    assert tree.items[0].body[0].value == expr


GENERATED = Path(__file__).parent.parent / "generated"


@pytest.mark.parametrize("path", sorted((GENERATED / "iec").glob("*.st")), ids=lambda p: p.stem)
def test_round_trip_generated_iec_files(path: Path):
    original = parse_ok(path.read_text(encoding="utf-8"), path.name)
    assert parse_ok(format_source(original), path.name) == original


@pytest.mark.parametrize("path", sorted((GENERATED / "nj501").glob("*.st")), ids=lambda p: p.stem)
def test_generated_nj_bodies_parse(path: Path):
    from st_runtime.parser import parse_body

    text = path.read_text(encoding="utf-8")
    body, diagnostics = parse_body(text, path.name)
    assert not diagnostics, "\n".join(d.render(text) for d in diagnostics)
    assert body


def test_round_trip_sfc_chart():
    # Steps with qualified actions (N, P, L with a duration), named and
    # unnamed transitions, actions print back as they were written.
    path = Path(__file__).parent / "corpus" / "accept" / "sfc_filler.st"
    original = parse_ok(path.read_text(encoding="utf-8"), path.name)
    printed = format_source(original)
    assert "Blink(L, T#2s);" in printed and "TRANSITION Done FROM Fill TO Idle" in printed
    again = parse_ok(printed, path.name)
    assert again == original
    assert format_source(again) == printed
