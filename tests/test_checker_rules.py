"""Rules that the reject corpus does not show on its own: dialects, one root
cause one diagnostic, and a checker that never raises."""

from __future__ import annotations

import random
from pathlib import Path

from st_runtime import ast
from st_runtime.checker import check
from st_runtime.checker.nj_rules import identifier_problems
from st_runtime.parser import parse
from checker_helpers import load

CORPUS = Path(__file__).parent / "corpus"


# ------------------------------------------------------------- NJ rules

NJ_BAD = """PROGRAM Main
VAR
    _speed : LREAL;
    leg__len : LREAL;
    Limit : LREAL;
END_VAR
END_PROGRAM
"""


def test_nj_rules_are_warnings_under_iec():
    result, program = load(NJ_BAD, "iec")
    assert program is not None
    assert [(d.code, d.pos.line) for d in result.diagnostics] == [
        ("W-NJ-002", 3), ("W-NJ-003", 4), ("W-NJ-004", 5)]
    assert all(not d.is_error for d in result.diagnostics)


def test_nj_rules_are_errors_under_nj():
    result, program = load(NJ_BAD, "nj")
    assert program is None
    assert [d.code for d in result.errors] == ["E-NJ-002", "E-NJ-003", "E-NJ-004"]


def test_identifier_length_counts_utf8_bytes():
    assert identifier_problems("a" * 127) == []
    assert [r for r, _ in identifier_problems("a" * 128)] == ["001"]
    # 64 two-byte letters are 128 bytes although only 64 characters.
    assert [r for r, _ in identifier_problems("é" * 64)] == ["001"]
    result, _ = load("PROGRAM Main\nVAR\n    " + "x" * 130 + " : INT;\nEND_VAR\nEND_PROGRAM\n")
    assert [d.code for d in result.diagnostics] == ["W-NJ-001"]


def test_instruction_names_include_conversions_and_are_case_insensitive():
    assert [r for r, _ in identifier_problems("int_to_real")] == ["004"]
    assert [r for r, _ in identifier_problems("mOvE")] == ["004"]
    assert identifier_problems("SP_InverseKinematics") == []
    assert identifier_problems("CylinderPos") == []


def test_builtin_prelude_is_exempt_from_nj_rules():
    # TON, R_TRIG ... are instruction names themselves: declared in the prelude, not reported.
    result, program = load("PROGRAM Main\nVAR t : TON; END_VAR\nt(IN := TRUE, PT := T#1s);\nEND_PROGRAM\n", "nj")
    assert program is not None and result.diagnostics == []


# ----------------------------------------------- one root cause, one report

def test_undeclared_name_inside_expressions_gives_no_cascade():
    result, _ = load("PROGRAM Main\nVAR x : LREAL; i : INT; END_VAR\n"
                     "x := (ghost + 1) * 2.0 + SQRT(ghost) + LIMIT(0.0, ghost, 1.0);\n"
                     "i := Unknown(1) + 1;\n"
                     "IF ghost > 3 THEN i := 1; END_IF;\nEND_PROGRAM\n")
    assert [(d.code, d.pos.line) for d in result.errors] == [
        ("E-DECL-001", 3), ("E-DECL-001", 3), ("E-DECL-001", 3),
        ("E-DECL-001", 4), ("E-DECL-001", 5)]


def test_unknown_type_gives_one_error_not_one_per_use():
    result, _ = load("PROGRAM Main\nVAR p : Missing; x : LREAL; END_VAR\n"
                     "x := p.a + p.b;\np.c := x;\nEND_PROGRAM\n")
    assert [d.code for d in result.errors] == ["E-DECL-004"]


def test_bad_operand_does_not_also_fail_the_assignment():
    result, _ = load("PROGRAM Main\nVAR b : BOOL; i : INT; END_VAR\ni := (b + 1) * 2;\nEND_PROGRAM\n")
    assert [d.code for d in result.errors] == ["E-TYPE-001"]


def test_recursion_cycle_reported_once_with_its_path():
    result, _ = load("FUNCTION A : INT\nA := B();\nEND_FUNCTION\n"
                     "FUNCTION B : INT\nB := C();\nEND_FUNCTION\n"
                     "FUNCTION C : INT\nC := A();\nEND_FUNCTION\n")
    [d] = result.errors
    assert d.code == "E-REC-001"
    assert "A calls B, B calls C, C calls A" in d.message


def _calls_peer(method: str, body: str) -> str:
    """A holds a VAR_IN_OUT of B (no instance: no edge), B an instance of A (B -> A)."""
    return ("FUNCTION_BLOCK A\nVAR_IN_OUT peer : B; END_VAR\n"
            f"METHOD M\n{method}\nEND_METHOD\n{body}\nEND_FUNCTION_BLOCK\n"
            "FUNCTION_BLOCK B\nVAR a : A; END_VAR\nEND_FUNCTION_BLOCK\n")


def test_a_methods_calls_stay_out_of_the_recursion_graph():
    # recursion.py: the graph's call edges are the POU bodies' (a call in A's body is A -> B);
    # the checker's one graph of calls also holds the METHODs' (node 'A.M', for W-ASSIGN-001),
    # which are not A's: the same call in M closes no cycle.
    result, _ = load(_calls_peer("peer();", ";"), "codesys")
    assert result.diagnostics == []
    result, _ = load(_calls_peer(";", "peer();"), "codesys")
    assert [(d.code, d.pos.line, d.message) for d in result.errors] == [
        ("E-REC-001", 6, "recursion: A calls B, B declares an instance of A; "
                         "IEC 61131-3 and OMRON NJ forbid recursion")]


# --------------------------------------------------------- never raises

P0 = ast.Pos("h.st", 1, 1)


def _program(*stmts, var_blocks=()):
    return ast.SourceFile("h.st", (ast.Pou("PROGRAM", "Main", tuple(var_blocks), tuple(stmts), pos=P0),), pos=P0)


def test_hand_built_odd_asts_give_diagnostics_not_exceptions():
    odd = [
        ast.Assign(ast.IntLiteral(1), ast.Name("x")),
        ast.Assign(ast.Name("x"), None),
        ast.CallStmt(ast.Call(ast.IntLiteral(3), (ast.Arg(None, None),))),
        ast.CallStmt(ast.Call(ast.Name("MAX"), (ast.Arg("Q", ast.IntLiteral(1), "out"),))),
        ast.Assign(ast.Name("x"), ast.Binary("??", ast.IntLiteral(1), ast.IntLiteral(2))),
        ast.Assign(ast.Name("x"), ast.Unary("~", ast.Name("x"))),
        ast.For("x", ast.StringLiteral("a"), ast.BoolLiteral(True), None, ()),
        ast.Case(ast.Name("x"), (ast.CaseClause((ast.CaseRange(ast.Name("x"), ast.RealLiteral(1.5)),), ()),)),
        ast.Assign(ast.Index(ast.Name("x"), ()), ast.EnumLiteral("NoSuch", "V")),
        ast.Assign(ast.Name("x"), ast.IntLiteral(5, "NOSUCHTYPE")),
        ast.Assign(ast.Name("x"), ast.RealLiteral(float("nan"))),
        ast.Assign(ast.Name("x"), ast.Binary("**", ast.IntLiteral(10), ast.IntLiteral(100000))),
    ]
    blocks = [ast.VarBlock("VAR", (
        ast.VarDecl("x", ast.NamedType("INT")),
        ast.VarDecl("a", ast.ArrayType((), ast.NamedType("INT"))),
        ast.VarDecl("s", ast.StringType(ast.IntLiteral(-3))),
        ast.VarDecl("z", ast.NamedType("INT"), ast.ArrayInit((ast.ArrayInitItem(None, ast.IntLiteral(-1)),))),
    ))]
    for stmt in odd:
        program, diagnostics = check([_program(stmt, var_blocks=blocks)])
        codes = {d.code for d in diagnostics}
        assert "E-CHECK-999" not in codes, (stmt, diagnostics)
        assert codes >= {"E-DECL-006", "E-DECL-007"}  # the odd declarations are reported


def test_deeply_nested_expression_reports_a_limit_instead_of_crashing():
    expr = ast.IntLiteral(1)
    for _ in range(100_000):
        expr = ast.Binary("+", expr, ast.Name("x"))
    blocks = [ast.VarBlock("VAR", (ast.VarDecl("x", ast.NamedType("INT")),))]
    program, diagnostics = check([_program(ast.Assign(ast.Name("x"), expr), var_blocks=blocks)])
    # The structural limit (checker/limits.py) names it before any recursive walk.
    assert [d.code for d in diagnostics] == ["E-LIMIT-002"]


def test_mutated_corpus_programs_never_raise():
    rng = random.Random(20261121)
    texts = [p.read_text(encoding="utf-8") for p in sorted((CORPUS / "accept").glob("*.st"))]
    texts += [p.read_text(encoding="utf-8") for p in sorted((CORPUS / "reject").glob("*.st"))]
    checked = 0
    for _ in range(400):
        text = rng.choice(texts)
        words = text.split(" ")
        i = rng.randrange(len(words))
        op = rng.randrange(3)
        if op == 0:
            del words[i]
        elif op == 1:
            words.insert(i, rng.choice(["x", "1", "TRUE", "T#1s", "'s'", "TON", "MAX", "Red", "16#FF"]))
        else:
            words[i], words[-1 - i] = words[-1 - i], words[i]
        parsed, _ = parse(" ".join(words), "m.st")
        if parsed is not None:
            _, diagnostics = check([parsed], rng.choice(["iec", "nj"]))
            assert not any(d.code == "E-CHECK-999" for d in diagnostics), diagnostics
            checked += 1
    assert checked > 50


def test_internal_errors_become_a_diagnostic():
    # var_blocks must be a tuple; None is an AST no parser builds.
    sf = ast.SourceFile("h.st", (ast.Pou("PROGRAM", "Main", None, (), pos=P0),), pos=P0)
    program, diagnostics = check([sf])
    assert [(d.code, d.pos.file) for d in diagnostics] == [("E-CHECK-999", "h.st")]


def test_long_string_literal_is_a_truncation_warning():
    result, program = load("PROGRAM Main\nVAR s : STRING[4]; END_VAR\ns := 'abcdef';\ns := 'abcd';\nEND_PROGRAM\n")
    assert program is not None
    assert [(d.code, d.pos.line) for d in result.diagnostics] == [("W-TYPE-001", 3)]
    assert "6 characters" in result.diagnostics[0].message and "STRING[4]" in result.diagnostics[0].message


def test_unrolled_leibniz_sum_of_720_products_in_one_expression_is_a_limit():
    import itertools

    terms = []
    for perm in itertools.permutations(range(1, 7)):
        inversions = sum(1 for i in range(6) for j in range(i + 1, 6) if perm[i] > perm[j])
        product = " * ".join(f"m[{i + 1}, {perm[i]}]" for i in range(6))
        terms.append(("- " if inversions % 2 else "+ ") + product)
    text = ("FUNCTION Det : LREAL\nVAR_INPUT m : ARRAY[1..6, 1..6] OF LREAL; END_VAR\nDet := 0.0\n"
            + "\n".join(terms) + ";\nEND_FUNCTION\n")
    result, program = load(text)
    # One expression 720 additions deep: beyond what the compiled code can nest (it ended in a
    # RecursionError at load), so the checker names the limit; the generated unrolled
    # determinant writes one statement per product instead.
    assert program is None
    assert [d.code for d in result.diagnostics] == ["E-LIMIT-002"]
    assert "in Det" in result.diagnostics[0].message
