"""The ST parser: the accept corpus, AST shapes by hand, positions, keywords.

Expected values are worked out by hand from IEC 61131-3 (precedence table,
literal syntax), never copied from the parser's output.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from st_runtime import ast
from st_runtime.parser import parse

CORPUS = Path(__file__).parent / "corpus" / "accept"
ACCEPT = sorted(CORPUS.glob("*.st"))


def parse_ok(text: str, path: str = "t.st") -> ast.SourceFile:
    tree, diagnostics = parse(text, path)
    assert not diagnostics, "\n".join(d.render(text) for d in diagnostics)
    assert tree is not None
    return tree


def body_of(statements: str, decls: str = "x, y, z : INT; a, b, c, d : BOOL;") -> tuple:
    tree = parse_ok(f"PROGRAM P\nVAR\n{decls}\nEND_VAR\n{statements}\nEND_PROGRAM\n")
    return tree.items[0].body


def expr_of(text: str):
    (stmt,) = body_of(f"x := {text};")
    return stmt.value


def N(name):  # noqa: N802 - short builders keep the expected trees readable
    return ast.Name(name)


def I(value, prefix=None):  # noqa: N802
    return ast.IntLiteral(value, prefix)


def B(op, left, right):  # noqa: N802
    return ast.Binary(op, left, right)


def U(op, operand):  # noqa: N802
    return ast.Unary(op, operand)


# ------------------------------------------------------------------ corpus


def test_accept_corpus_is_large_enough():
    assert len(ACCEPT) >= 150


@pytest.mark.parametrize("path", ACCEPT, ids=lambda p: p.stem)
def test_accept_corpus_parses_cleanly(path: Path):
    text = path.read_text(encoding="utf-8")
    tree = parse_ok(text, str(path))
    assert tree.items, "a corpus file declares at least one item"


def test_corpus_files_start_with_a_comment_naming_the_construct():
    for path in ACCEPT:
        assert path.read_text(encoding="utf-8").startswith("(* "), path.name


# -------------------------------------------------------------- precedence

PRECEDENCE = [
    ("1 + 2 * 3", B("+", I(1), B("*", I(2), I(3)))),
    ("(1 + 2) * 3", B("*", B("+", I(1), I(2)), I(3))),
    ("10 - 3 - 2", B("-", B("-", I(10), I(3)), I(2))),
    ("100 / 10 / 5", B("/", B("/", I(100), I(10)), I(5))),
    ("17 MOD 5 * 2", B("*", B("MOD", I(17), I(5)), I(2))),
    ("2 ** 3 ** 2", B("**", B("**", I(2), I(3)), I(2))),
    ("-y ** 2", U("-", B("**", N("y"), I(2)))),
    ("2 ** -1", B("**", I(2), U("-", I(1)))),
    ("- -y", U("-", U("-", N("y")))),
    ("-5", U("-", I(5))),
    ("+y * 2", B("*", U("+", N("y")), I(2))),
    ("-y * 2", B("*", U("-", N("y")), I(2))),
    ("NOT a AND b", B("AND", U("NOT", N("a")), N("b"))),
    ("NOT (a AND b)", U("NOT", B("AND", N("a"), N("b")))),
    ("a OR b XOR c AND d", B("OR", N("a"), B("XOR", N("b"), B("AND", N("c"), N("d"))))),
    ("a AND b OR c", B("OR", B("AND", N("a"), N("b")), N("c"))),
    ("a & b", B("AND", N("a"), N("b"))),
    ("x < y = a", B("=", B("<", N("x"), N("y")), N("a"))),
    ("x + 1 > y * 2", B(">", B("+", N("x"), I(1)), B("*", N("y"), I(2)))),
    ("x <> y AND x <= z", B("AND", B("<>", N("x"), N("y")), B("<=", N("x"), N("z")))),
    ("x >= 1 OR x < -1", B("OR", B(">=", N("x"), I(1)), B("<", N("x"), U("-", I(1))))),
    ("((((1))))", I(1)),
]


@pytest.mark.parametrize("text,expected", PRECEDENCE, ids=[t for t, _ in PRECEDENCE])
def test_precedence(text, expected):
    assert expr_of(text) == expected


def test_postfix_chains_and_calls():
    expected = B("+",
                 ast.Member(ast.Index(ast.Member(N("a"), "b"), (I(1), I(2))), "c"),
                 ast.Call(N("MAX"), (ast.Arg(None, I(1)), ast.Arg(None, N("y")))))
    assert expr_of("a.b[1, 2].c + MAX(1, y)") == expected


# ---------------------------------------------------------------- literals

T = 10**9
LITERALS = [
    ("42", ast.IntLiteral(42)),
    ("1_000_000", ast.IntLiteral(1000000)),
    ("16#FF", ast.IntLiteral(255)),
    ("16#ab_cd", ast.IntLiteral(0xABCD)),
    ("2#1010_0101", ast.IntLiteral(165)),
    ("8#17", ast.IntLiteral(15)),
    ("3.25", ast.RealLiteral(3.25)),
    ("1.5E-3", ast.RealLiteral(0.0015)),
    ("1E6", ast.RealLiteral(1_000_000.0)),
    ("2.5e+2", ast.RealLiteral(250.0)),
    ("1_000.000_1", ast.RealLiteral(1000.0001)),
    ("LREAL#1.5", ast.RealLiteral(1.5, "LREAL")),
    ("REAL#2", ast.RealLiteral(2.0, "REAL")),
    ("INT#-5", ast.IntLiteral(-5, "INT")),
    ("int#7", ast.IntLiteral(7, "INT")),
    ("WORD#16#FFFF", ast.IntLiteral(65535, "WORD")),
    ("BOOL#1", ast.BoolLiteral(True, "BOOL")),
    ("BOOL#FALSE", ast.BoolLiteral(False, "BOOL")),
    ("TRUE", ast.BoolLiteral(True)),
    ("false", ast.BoolLiteral(False)),
    ("Color#Red", ast.EnumLiteral("Color", "Red")),
    ("T#1s500ms", ast.TimeLiteral(1_500_000_000)),
    ("TIME#-2.5s", ast.TimeLiteral(-2_500_000_000)),
    ("t#100ms", ast.TimeLiteral(100_000_000)),
    ("T#1d2h3m4s5ms6us7ns", ast.TimeLiteral(86_400 * T + 7_200 * T + 180 * T + 4 * T
                                            + 5_000_000 + 6_000 + 7)),
    ("T#1.5m", ast.TimeLiteral(90 * T)),
    ("T#1h_30m", ast.TimeLiteral(5_400 * T)),
    ("T#0.1s", ast.TimeLiteral(100_000_000)),
    ("LTIME#5us", ast.TimeLiteral(5_000)),
    ("D#1970-01-02", ast.DateTimeLiteral("DATE", 86_400 * T)),
    ("DATE#1971-01-01", ast.DateTimeLiteral("DATE", 365 * 86_400 * T)),
    ("TOD#12:30:15.5", ast.DateTimeLiteral("TOD", (12 * 3600 + 30 * 60 + 15) * T + T // 2)),
    ("TIME_OF_DAY#08:00:00", ast.DateTimeLiteral("TOD", 8 * 3600 * T)),
    ("DT#1970-01-01-00:00:01", ast.DateTimeLiteral("DT", T)),
    ("DATE_AND_TIME#1970-01-02-01:00:00", ast.DateTimeLiteral("DT", (86_400 + 3600) * T)),
    ("'hello'", ast.StringLiteral("hello")),
    ("''", ast.StringLiteral("")),
    ("'It$'s'", ast.StringLiteral("It's")),
    ("'$41$62'", ast.StringLiteral("Ab")),
    ("'$$ $L$N$R$T$P'", ast.StringLiteral("$ \n\n\r\t\f")),
    ("'a$nb$tc'", ast.StringLiteral("a\nb\tc")),
    ("'say \"hi\"'", ast.StringLiteral('say "hi"')),
    ("'(* no *) // no'", ast.StringLiteral("(* no *) // no")),
    ('"wide $0041"', ast.StringLiteral("wide A", wide=True)),
    ('"it\'s $""', ast.StringLiteral("it's \"", wide=True)),
]


@pytest.mark.parametrize("text,expected", LITERALS, ids=[t for t, _ in LITERALS])
def test_literal_values(text, expected):
    assert expr_of(text) == expected


def test_typed_negative_literal_is_one_literal_but_minus_is_unary():
    assert expr_of("INT#-5") == ast.IntLiteral(-5, "INT")
    assert expr_of("-5") == U("-", I(5))


# -------------------------------------------------------------- statements


def test_if_elsif_else_shape():
    (stmt,) = body_of("IF a THEN x := 1; ELSIF b THEN x := 2; ELSE x := 3; END_IF;")
    assign = lambda v: ast.Assign(N("x"), I(v))  # noqa: E731
    assert stmt == ast.If(
        (ast.IfBranch(N("a"), (assign(1),)), ast.IfBranch(N("b"), (assign(2),))),
        (assign(3),),
    )


def test_if_without_else_differs_from_empty_else():
    (no_else,) = body_of("IF a THEN x := 1; END_IF;")
    (empty_else,) = body_of("IF a THEN x := 1; ELSE END_IF;")
    assert no_else.else_body is None
    assert empty_else.else_body == ()


def test_semicolon_after_end_if_is_optional():
    with_semi = body_of("IF a THEN x := 1; END_IF; y := 2;")
    without = body_of("IF a THEN x := 1; END_IF y := 2;")
    assert with_semi == without
    assert [type(s) for s in with_semi] == [ast.If, ast.Assign]


def test_empty_statements_are_kept():
    stmts = body_of("x := 1;; ;")
    assert [type(s) for s in stmts] == [ast.Assign, ast.Empty, ast.Empty]


def test_case_groups_labels_and_statements():
    (stmt,) = body_of("CASE x OF 1, 3..5: y := 1; z := 2; Red: ; ELSE y := 0; END_CASE;")
    assert stmt.selector == N("x")
    first, second = stmt.clauses
    assert first.labels == (I(1), ast.CaseRange(I(3), I(5)))
    assert first.body == (ast.Assign(N("y"), I(1)), ast.Assign(N("z"), I(2)))
    assert second.labels == (N("Red"),)
    assert second.body == (ast.Empty(),)
    assert stmt.else_body == (ast.Assign(N("y"), I(0)),)


def test_case_enum_label_next_to_assignment_starting_with_identifier():
    (stmt,) = body_of("CASE x OF Red: y := 1; Green: Blue := 2; END_CASE;",
                      "x, y, Blue : INT;")
    assert [c.labels for c in stmt.clauses] == [(N("Red"),), (N("Green"),)]
    assert stmt.clauses[1].body == (ast.Assign(N("Blue"), I(2)),)


def test_case_negative_range_labels():
    (stmt,) = body_of("CASE x OF -2..-1: y := 1; END_CASE;")
    assert stmt.clauses[0].labels == (ast.CaseRange(U("-", I(2)), U("-", I(1))),)


def test_for_with_and_without_step():
    with_step, without = body_of("FOR x := 10 TO 1 BY -1 DO END_FOR; FOR x := 1 TO y DO END_FOR;")
    assert with_step == ast.For("x", I(10), I(1), U("-", I(1)), ())
    assert without == ast.For("x", I(1), N("y"), None, ())


def test_while_repeat_exit_continue_return():
    stmts = body_of("WHILE a DO EXIT; END_WHILE; REPEAT CONTINUE; UNTIL b END_REPEAT; RETURN;")
    assert stmts == (ast.While(N("a"), (ast.Exit(),)),
                     ast.Repeat((ast.Continue(),), N("b")),
                     ast.Return())


def test_call_argument_forms():
    (stmt,) = body_of("t(IN := a, 5, Q => b, NOT ET => c, PT =>);", "t : TON; a, b, c : BOOL;")
    assert stmt == ast.CallStmt(ast.Call(N("t"), (
        ast.Arg("IN", N("a")),
        ast.Arg(None, I(5)),
        ast.Arg("Q", N("b"), "out"),
        ast.Arg("ET", N("c"), "out", negated=True),
        ast.Arg("PT", None, "out"),
    )))


def test_call_on_array_element_and_member():
    first, second = body_of("fbs[2](); a.b();", "fbs : ARRAY[1..3] OF TON;")
    assert first.call.callee == ast.Index(N("fbs"), (I(2),))
    assert second.call.callee == ast.Member(N("a"), "b")
    assert first.call.args == ()


# ------------------------------------------------------------ declarations


def decls_of(text: str) -> tuple:
    tree = parse_ok(f"PROGRAM P\nVAR\n{text}\nEND_VAR\nEND_PROGRAM\n")
    return tree.items[0].var_blocks[0].decls


def test_multiple_names_share_type_and_initial_value():
    a, b = decls_of("a, b : INT := 3;")
    assert (a.name, b.name) == ("a", "b")
    assert a.type == b.type == ast.NamedType("INT")
    assert a.init == b.init == I(3)


def test_array_type_with_negative_and_expression_bounds():
    (decl,) = decls_of("m : ARRAY[-1..N - 1, 0..2, 1..3] OF Point;")
    assert decl.type == ast.ArrayType(
        (ast.Subrange(U("-", I(1)), B("-", N("N"), I(1))),
         ast.Subrange(I(0), I(2)), ast.Subrange(I(1), I(3))),
        ast.NamedType("Point"))


def test_string_lengths():
    a, b, c, w = decls_of("a : STRING; b : STRING[20]; c : STRING(5); w : WSTRING[4];")
    assert a.type == ast.StringType(None)
    assert b.type == ast.StringType(I(20))
    assert c.type == ast.StringType(I(5))
    assert w.type == ast.StringType(I(4), wide=True)


def test_array_initializers():
    a, b, c, d = decls_of(
        "a : ARRAY[1..6] OF INT := [1, 2, 4(0)];"
        "b : ARRAY[1..3] OF INT := 1, 2, 3;"
        "c : ARRAY[1..6] OF LREAL := 6(0.0);"
        "d : ARRAY[1..4] OF INT := [4()];")
    item = ast.ArrayInitItem
    assert a.init == ast.ArrayInit((item(I(1)), item(I(2)), item(I(0), I(4))))
    assert b.init == ast.ArrayInit((item(I(1)), item(I(2)), item(I(3))))
    assert c.init == ast.ArrayInit((item(ast.RealLiteral(0.0), I(6)),))
    assert d.init == ast.ArrayInit((item(None, I(4)),))


def test_struct_initializer_nested():
    (decl,) = decls_of("f : Frame := (a := 1, b := (c := 2), d := [1, 2]);")
    assert decl.init == ast.StructInit((
        ast.FieldInit("a", I(1)),
        ast.FieldInit("b", ast.StructInit((ast.FieldInit("c", I(2)),))),
        ast.FieldInit("d", ast.ArrayInit((ast.ArrayInitItem(I(1)), ast.ArrayInitItem(I(2))))),
    ))


def test_parenthesised_initial_value_is_an_expression():
    (decl,) = decls_of("x : INT := (1 + 2);")
    assert decl.init == B("+", I(1), I(2))


def test_var_block_kinds_and_qualifiers():
    tree = parse_ok("FUNCTION_BLOCK F\nVAR_INPUT a : INT; END_VAR\nVAR_OUTPUT b : INT; END_VAR\n"
                    "VAR_IN_OUT c : INT; END_VAR\nVAR_TEMP d : INT; END_VAR\n"
                    "VAR CONSTANT e : INT := 1; END_VAR\nVAR RETAIN f : INT; END_VAR\n"
                    "VAR_EXTERNAL g : INT; END_VAR\nEND_FUNCTION_BLOCK\n"
                    "VAR_GLOBAL CONSTANT RETAIN h : INT := 2; END_VAR\n")
    blocks = tree.items[0].var_blocks
    assert [b.kind for b in blocks] == ["VAR_INPUT", "VAR_OUTPUT", "VAR_IN_OUT", "VAR_TEMP",
                                        "VAR", "VAR", "VAR_EXTERNAL"]
    assert [(b.constant, b.retain) for b in blocks][4:6] == [(True, False), (False, True)]
    glob = tree.items[1]
    assert (glob.kind, glob.constant, glob.retain) == ("VAR_GLOBAL", True, True)


def test_type_declarations():
    tree = parse_ok("TYPE\n Color : (Red, Green := 5, Blue) := Green;\n"
                    " Pt : STRUCT x : LREAL; y : LREAL := 1.0; END_STRUCT;\n"
                    " Mm : LREAL;\n Pose : ARRAY[1..6] OF LREAL;\nEND_TYPE\n")
    color, pt, mm, pose = tree.items
    assert color == ast.TypeDecl("Color", ast.EnumType((
        ast.EnumValue("Red"), ast.EnumValue("Green", I(5)), ast.EnumValue("Blue"))), N("Green"))
    assert pt.spec == ast.StructType((
        ast.VarDecl("x", ast.NamedType("LREAL")),
        ast.VarDecl("y", ast.NamedType("LREAL"), ast.RealLiteral(1.0))))
    assert mm == ast.TypeDecl("Mm", ast.NamedType("LREAL"))
    assert pose.spec == ast.ArrayType((ast.Subrange(I(1), I(6)),), ast.NamedType("LREAL"))


def test_function_return_type_and_pou_kinds():
    tree = parse_ok("FUNCTION F : STRING[10]\nEND_FUNCTION\nFUNCTION_BLOCK B\nEND_FUNCTION_BLOCK\n"
                    "PROGRAM P\nEND_PROGRAM\n")
    kinds = [(p.kind, p.name, p.return_type) for p in tree.items]
    assert kinds == [("FUNCTION", "F", ast.StringType(I(10))),
                     ("FUNCTION_BLOCK", "B", None), ("PROGRAM", "P", None)]


def test_configuration_is_flattened():
    tree = parse_ok("CONFIGURATION C\n VAR_GLOBAL g : BOOL; END_VAR\n"
                    " RESOURCE R ON PLC\n  TASK Fast(INTERVAL := T#1ms, PRIORITY := 1);\n"
                    "  PROGRAM Inst WITH Fast : Prog;\n  PROGRAM Free : Prog;\n END_RESOURCE\n"
                    "END_CONFIGURATION\n")
    (config,) = tree.items
    assert config.name == "C"
    assert [b.kind for b in config.globals] == ["VAR_GLOBAL"]
    assert config.tasks == (ast.TaskDecl("Fast", ast.TimeLiteral(10**6), I(1)),)
    assert config.programs == (ast.ProgramInstance("Inst", "Fast", "Prog"),
                               ast.ProgramInstance("Free", None, "Prog"))


# --------------------------------------------------------------- positions


def test_positions_are_first_tokens_and_operator_for_binary():
    text = "PROGRAM P\nVAR\n  speed : INT;\nEND_VAR\n  IF speed > 1 THEN\n    speed := speed + 2;\n  END_IF;\nEND_PROGRAM\n"
    tree = parse_ok(text, "pos.st")
    pou = tree.items[0]
    assert pou.pos == ast.Pos("pos.st", 1, 1)
    assert pou.var_blocks[0].pos == ast.Pos("pos.st", 2, 1)
    assert pou.var_blocks[0].decls[0].pos == ast.Pos("pos.st", 3, 3)
    if_stmt = pou.body[0]
    assert if_stmt.pos == ast.Pos("pos.st", 5, 3)
    assert if_stmt.branches[0].condition.pos == ast.Pos("pos.st", 5, 12)  # the '>'
    assign = if_stmt.branches[0].body[0]
    assert assign.pos == ast.Pos("pos.st", 6, 5)
    assert assign.value.pos == ast.Pos("pos.st", 6, 20)                  # the '+'
    assert assign.value.left.pos == ast.Pos("pos.st", 6, 14)


def test_positions_do_not_affect_equality():
    a = parse_ok("PROGRAM P x := 1; END_PROGRAM", "a.st").items
    b = parse_ok("PROGRAM P\n\n   x   :=   1 ;\nEND_PROGRAM", "a.st").items
    assert a == b
    assert a[0].body[0].pos != b[0].body[0].pos


# -------------------------------------------------------- keywords, names


def test_keywords_in_any_case_identifiers_keep_spelling():
    lower = parse_ok("program p var MotorSpeed : lreal; end_var motorspeed := 1.0; end_program")
    pou = lower.items[0]
    assert pou.kind == "PROGRAM"
    assert pou.var_blocks[0].decls[0].name == "MotorSpeed"
    assert pou.body[0].target == N("motorspeed")


def test_identifiers_may_start_with_a_keyword():
    stmts = body_of("IFX := ENDING + DOOR;", "IFX, ENDING, DOOR : INT;")
    assert stmts[0] == ast.Assign(N("IFX"), B("+", N("ENDING"), N("DOOR")))


@pytest.mark.parametrize("word", ["IF", "then", "End_If", "VAR", "MOD", "TRUE", "ARRAY",
                                  "STRING", "of", "CONSTANT", "RETURN"])
def test_keywords_are_reserved(word):
    tree, diagnostics = parse(f"PROGRAM P\nVAR\n  {word} : INT;\nEND_VAR\nEND_PROGRAM\n", "k.st")
    assert tree is None
    assert len(diagnostics) == 1
    assert diagnostics[0].pos.line == 3


def test_comments_do_not_nest():
    tree, diagnostics = parse("PROGRAM P\n(* a (* b *) c *)\nEND_PROGRAM\n", "c.st")
    assert tree is None and diagnostics
    assert diagnostics[0].pos.line == 2


def test_empty_file_is_an_empty_source_file():
    tree = parse_ok("", "e.st")
    assert tree == ast.SourceFile("e.st", ())
    assert parse_ok("(* only a comment *)\n// and another\n", "e.st").items == ()


def test_byte_order_mark_and_crlf_are_blank():
    tree = parse_ok("\ufeffPROGRAM P\r\n\tx := 1;\r\nEND_PROGRAM\r\n", "bom.st")
    assert tree.items[0].body[0].pos == ast.Pos("bom.st", 2, 2)


def test_parse_returns_path_in_source_file():
    assert parse_ok("PROGRAM P END_PROGRAM", "dir/x.st").path == "dir/x.st"


def test_parse_body_reads_statements_alone():
    from st_runtime.parser import parse_body

    stmts, diagnostics = parse_body("x := 1;\nIF a THEN\n    y := x;\nEND_IF;\n", "Main.body.st")
    assert diagnostics == []
    assert stmts == (ast.Assign(N("x"), I(1)),
                     ast.If((ast.IfBranch(N("a"), (ast.Assign(N("y"), N("x")),)),)))
    assert stmts[1].pos == ast.Pos("Main.body.st", 2, 1)


def test_parse_body_reports_faults_like_parse():
    from st_runtime.parser import parse_body

    stmts, diagnostics = parse_body("x := 1\ny := 2;\nVAR z : INT; END_VAR\n", "b.st")
    assert stmts is None
    assert [(d.code, d.pos.line) for d in diagnostics] == [("E-PARSE-002", 1), ("E-PARSE-001", 3)]
