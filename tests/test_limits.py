"""Structural limits (issue 15): whatever `check` accepts, `load` compiles and
the controller runs; beyond a limit, one checker diagnostic names the
construct, and the API raises LoadError, never RecursionError.

The limits are those of st_runtime/checker/limits.py; the programs at each
limit run, the programs one step beyond are refused with the code below.
"""

from __future__ import annotations

import pytest

from st_runtime.api import LoadError, load_text
from st_runtime.checker import limits
from tree_order import walk_order


#: One control variable per loop level (IEC 61131-3 7.3.3.4.2: a FOR nested in a FOR over the
#: same variable would alter it, E-ASSIGN-003), one more than the deepest nesting allowed.
LOOP_VARIABLES = " ".join(f"i{k} : DINT;" for k in range(1, limits.MAX_LOOP_DEPTH + 2))


def program(body: str, decls: str = "x : DINT; i : DINT; r : LREAL; " + LOOP_VARIABLES) -> str:
    return f"PROGRAM P\nVAR {decls} END_VAR\n{body}\nEND_PROGRAM\n"


def runs(text: str) -> dict:
    plc = load_text(text, "limits.st").controller()
    main = plc.add_program("P")
    plc.run(1)
    assert plc.faults == []
    return main.to_json()


def refused(text: str) -> list:
    with pytest.raises(LoadError) as info:
        load_text(text, "limits.st")
    return info.value.diagnostics


def nested_ifs(n: int) -> str:
    return "IF x = 0 THEN\n" * n + "x := 1;\n" + "END_IF;\n" * n


def nested_loops(n: int) -> str:
    return "".join(f"FOR i{k} := 1 TO 1 DO\n" for k in range(1, n + 1)) + "x := x + 1;\n" + "END_FOR;\n" * n


def elsif_chain(n: int) -> str:
    return "IF x = 0 THEN x := 1;\n" + "".join(f"ELSIF x = {k} THEN x := {k};\n" for k in range(1, n + 1)) + "END_IF;"


def case_of(n: int) -> str:
    return "CASE x OF\n" + "".join(f"{k}: x := {k} + 1;\n" for k in range(n)) + "END_CASE;"


def sum_of(n: int) -> str:
    return "r := " + " + ".join(["1.0"] * n) + ";"   # a left-deep tree of n - 1 additions


# ------------------------------------------------------------ at the limit: runs

def test_statements_nested_to_the_limit_run():
    assert runs(program(nested_ifs(limits.MAX_BLOCK_DEPTH)))["x"] == 1


def test_loops_nested_to_the_limit_run():
    assert runs(program(nested_loops(limits.MAX_LOOP_DEPTH)))["x"] == 1


def test_an_expression_at_the_limit_runs():
    # n terms: n - 1 additions nested, plus the terms: depth n.
    assert runs(program(sum_of(limits.MAX_EXPRESSION_DEPTH)))["r"] == limits.MAX_EXPRESSION_DEPTH


def test_elsif_chain_at_the_limit_with_deep_conditions_runs():
    # Each condition is itself a deep expression: the chain must not add nesting to it.
    deep = " + ".join(["0"] * (limits.MAX_EXPRESSION_DEPTH - 2))
    chain = "IF x = 1 THEN x := 1;\n" + "".join(
        f"ELSIF x = {k} + {deep} THEN x := {k};\n" for k in range(2, limits.MAX_ELSIF + 2)) + "ELSE x := -1;\nEND_IF;"
    assert runs(program("x := 7;\n" + chain))["x"] == 7


def test_case_at_the_limit_runs():
    assert runs(program(case_of(limits.MAX_CASE_CLAUSES)))["x"] == 1   # x = 0: clause 0 sets 0 + 1


# ------------------------------------------------------------ beyond: one diagnostic each

@pytest.mark.parametrize("body, code, line", [
    (nested_ifs(limits.MAX_BLOCK_DEPTH + 1), "E-LIMIT-003", 3 + limits.MAX_BLOCK_DEPTH),
    (nested_loops(limits.MAX_LOOP_DEPTH + 1), "E-LIMIT-004", 3 + limits.MAX_LOOP_DEPTH),
    (elsif_chain(limits.MAX_ELSIF + 1), "E-LIMIT-005", 3),
    (case_of(limits.MAX_CASE_CLAUSES + 1), "E-LIMIT-006", 3),
    (sum_of(limits.MAX_EXPRESSION_DEPTH + 1), "E-LIMIT-002", 3),
])
def test_beyond_a_limit_is_one_checker_diagnostic(body, code, line):
    diagnostics = refused(program(body))
    assert [d.code for d in diagnostics] == [code]
    assert diagnostics[0].pos.file == "limits.st" and diagnostics[0].pos.line == line
    assert diagnostics[0].message.endswith(" in P")


def test_too_many_statements():
    lines = ["x := 1; " * 10] * (limits.MAX_STATEMENTS // 10) + ["x := 1;"]     # ten a line
    diagnostics = refused(program("\n".join(lines)))
    assert [d.code for d in diagnostics] == ["E-LIMIT-007"]
    assert f"{limits.MAX_STATEMENTS + 1} statements" in diagnostics[0].message


# ------------------------------------------------------------ the hostile cases

@pytest.mark.parametrize("body", [
    "x := " + "- " * 10_000 + "1;",                       # 10,000 unary minus
    "r := " + " ** ".join(["1.0"] * 10_000) + ";",        # a 10,000-long ** chain
    nested_ifs(3_000),                                    # was a RecursionError at run time
    elsif_chain(20_000),                                  # was "too many nested parentheses"
    "x := " + "ABS(" * 5_000 + "x" + ")" * 5_000 + ";",   # calls nested 5,000 deep
])
def test_hostile_nesting_is_a_load_error_never_a_recursion_error(body):
    diagnostics = refused(program(body))
    assert diagnostics and all(d.code.startswith("E-LIMIT-") for d in diagnostics)


def test_deep_nesting_through_the_cli_is_a_diagnostic(tmp_path, capsys):
    from stgen.cli import main

    path = tmp_path / "deep.st"
    path.write_text(program(nested_ifs(3_000)))
    assert main(["run", str(path), "--program", "P"]) == 1
    err = capsys.readouterr().err
    assert "error[E-LIMIT-003]" in err and "internal error" not in err


def test_a_type_nested_20000_deep_is_a_limit_not_a_recursion_error():
    text = "TYPE T : " + "ARRAY[1..2] OF " * 20_000 + "INT; END_TYPE\n" + program("x := 1;", "a : T; x : DINT;")
    diagnostics = refused(text)
    assert [d.code for d in diagnostics] == ["E-LIMIT-002"]
    assert "type nested more than" in diagnostics[0].message and diagnostics[0].message.endswith(" in T")


def test_the_recursion_backstop_is_still_a_diagnostic(monkeypatch):
    # What the limits do not foresee and still recurses is E-LIMIT-001, never an exception.
    from st_runtime.checker import check
    from st_runtime.checker import statements
    from st_runtime.parser import parse

    def recurse(*args, **kwargs):
        raise RecursionError("maximum recursion depth exceeded")

    monkeypatch.setattr(statements.StatementChecker, "block", recurse)
    parsed, _ = parse(program("x := 1;"), "limits.st")
    _, diagnostics = check([parsed])
    assert [d.code for d in diagnostics] == ["E-LIMIT-001"]


def test_case_label_uniqueness_over_many_labels_and_ranges():
    # 20,000 single labels, two ranges, then one duplicate of each kind: the overlaps found
    # are the ones by hand (a dict and a sorted range list: near-linear, issue 15).
    labels = ", ".join(str(k) for k in range(20_000))
    text = program("CASE x OF\n"
                   f"{labels}: x := 1;\n"            # line 4
                   "30000..30010: x := 2;\n"        # line 5
                   "40000..40010: x := 3;\n"        # line 6
                   "19999: x := 4;\n"               # line 7: a single seen on line 4
                   "30005..30020: x := 5;\n"        # line 8: overlaps line 5
                   "25000..35000: x := 6;\n"        # line 9: overlaps line 5 (and 6? no: ends 35000)
                   "39990..40000: x := 7;\n"        # line 10: touches line 6 at 40000
                   "20000..29999: x := 8;\n"        # line 11: fits between, no overlap
                   "END_CASE;")
    diagnostics = refused(text)
    assert [(d.code, d.pos.line, d.message) for d in diagnostics] == [
        ("E-TYPE-013", 7, "CASE label 19999 overlaps a label at line 4"),
        ("E-TYPE-013", 8, "CASE label 30005..30020 overlaps a label at line 5"),
        ("E-TYPE-013", 9, "CASE label 25000..35000 overlaps a label at line 5"),
        ("E-TYPE-013", 10, "CASE label 39990..40000 overlaps a label at line 6"),
    ]


def test_a_file_beyond_the_line_limit_is_refused_before_parsing():
    text = program("x := 1;\n" * (limits.MAX_FILE_LINES + 1))
    diagnostics = refused(text)
    assert [(d.code, d.pos.line) for d in diagnostics] == [("E-LIMIT-012", 1)]
    assert f"at most {limits.MAX_FILE_LINES:,}" in diagnostics[0].message


def test_the_structural_walk_notes_what_the_later_passes_look_for():
    """check_files notes, per item, each dialect construct in the order of a walk of
    every node, and whether a CASE, or an Index or a Member of a member (`a.b[1]`,
    `a.b.c`: the only ones NJ rule 006 looks further at), is inside (the NJ build
    rules' walk is skipped otherwise): on every file of the corpora."""
    from pathlib import Path

    from st_runtime import ast
    from st_runtime.checker.context import Context, FastSink
    from st_runtime.checker.dialects import CONSTRUCT_NODES, construct_of
    from st_runtime.parser import parse
    from st_runtime.symbols import CheckedProgram

    root = Path(__file__).resolve().parent
    paths = sorted(root.glob("corpus/*/*.st")) + sorted(root.glob("st_dialects/*.st"))
    constructs = build = 0
    for path in paths:
        parsed, _ = parse(path.read_text(encoding="utf-8"), str(path))
        if parsed is None:
            continue
        ctx = Context(CheckedProgram(files=[parsed]), FastSink())
        if not limits.check_files(ctx, [parsed]):
            continue
        for item in parsed.items:
            nodes = list(walk_order(item, tuples_from_last=True))
            expected = [(construct_of(n), n.pos) for n in nodes if type(n) in CONSTRUCT_NODES]
            walked = ctx.walked[id(item)]
            assert walked.constructs == [(name, pos) for name, pos in expected if name is not None]
            assert walked.build_nodes == any(
                isinstance(n, ast.Case) or isinstance(n, (ast.Index, ast.Member)) and isinstance(n.base, ast.Member)
                for n in nodes)
            constructs += len(walked.constructs)
            build += walked.build_nodes
    assert constructs > 20 and build > 20


def test_a_leaf_beyond_the_depth_is_the_place_reported():
    """`r := 1.0 + 1.0 + ...` of 65 terms: the innermost addition is 64 deep and its two
    terms 65; the walk meets its right term first (children are pushed in order and
    popped last first): the second `1.0`, at column 6 + len("1.0 + ") = 12.  A leaf
    at or above the limit is not walked at all (limits._QUIET), one beyond it is."""
    diagnostics = refused(program(sum_of(limits.MAX_EXPRESSION_DEPTH + 1)))
    assert [(d.code, d.pos.line, d.pos.col) for d in diagnostics] == [("E-LIMIT-002", 3, 12)]


DEEP = limits.MAX_EXPRESSION_DEPTH


@pytest.mark.parametrize("body, col", [
    # 64 nested calls: the innermost at depth 64, its argument (an Arg, transparent) x at 65,
    # at column 6 + 4 * 64 (after "x := " and the 64 "ABS(").
    ("x := " + "ABS(" * DEEP + "x" + ")" * DEEP + ";", 6 + 4 * DEEP),
    # `a[1]` the first of 64 terms: 63 additions, a[1] at depth 64, its index 1 (an item of
    # a tuple field) at 65, at column 8 (after "r := a[").
    ("r := a[1]" + " + 1.0" * (DEEP - 1) + ";", 8),
])
def test_a_leaf_inside_a_tuple_beyond_the_depth_is_the_place_reported(body, col):
    """The walk does not push a node of a tuple field (an argument, a declaration, an index)
    whose visit would add nothing (limits._Items); at the deepest level a leaf under it
    is too deep, and it is the place reported.  One level less is within the limit."""
    decls = "x : DINT; r : LREAL; a : ARRAY[1..1] OF LREAL;"
    diagnostics = refused(program(body, decls))
    assert [(d.code, d.pos.line, d.pos.col) for d in diagnostics] == [("E-LIMIT-002", 3, col)]
    shallower = body.replace("ABS(", "", 1).replace(")", "", 1).replace(" + 1.0", "", 1)
    runs(program(shallower, decls))


def test_the_walk_takes_a_nodes_fields_from_the_last():
    """`p^ := NULL;`: the Assign's fields are (target, value); the walk pushes them in
    field order and pops the last first, so the NULL (column 7) is noted before the
    DEREF (column 1), the order the dialect pass reports them in.  A walk taking the
    fields in another order (limits._children_getter) fails here."""
    from st_runtime.checker.context import Context, FastSink
    from st_runtime.parser import parse
    from st_runtime.symbols import CheckedProgram

    parsed, _ = parse(program("p^ := NULL;", "p : REF_TO DINT;"), "limits.st")
    ctx = Context(CheckedProgram(files=[parsed]), FastSink())
    assert limits.check_files(ctx, [parsed])
    constructs = [(what, pos.line, pos.col) for what, pos in ctx.walked[id(parsed.items[0])].constructs]
    assert constructs == [("NULL", 3, 7), ("DEREF", 3, 1), ("REF_TO", 2, 9)]
