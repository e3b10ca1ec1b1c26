"""Qualified calls `NS.F(...)` (issue 16, docs/mutation.md, "Session 15, gaps").

IEC 61131-3 3rd ed. 6.9: a namespace holds declared language elements (data
types, functions, function block types, classes, interfaces, namespaces), and a
fully qualified name `NS.F` names the element F of namespace NS.  A variable of
the calling POU, or a method of its FB, named F is not in the namespace and is
never what `NS.F` names.  Before this file the checker lowered `NS.F(...)` to
`F(...)` and looked F up in the calling scope first: a local FB instance F was
accepted and the load then failed in the compiler, a local INT F refused a
valid call, and a METHOD F of the calling FB was silently called instead of
the namespace's FUNCTION.

Each shape is one row, run through the API (load, one scan) and through the
CLI (`stgen check`, then `stgen run --json`); the expected values are worked
out by hand from the snippets (the namespace's F returns 42 and sets its
output to 42; the local FB Cnt, if it were called, would count 1).
"""

from __future__ import annotations

import json
from dataclasses import dataclass

import pytest

from checker_helpers import diagnostics
from st_runtime import load_text
from stgen.cli import main

# A FUNCTION F of NS: result 42, output n 42.
NS_F = ("NAMESPACE NS\nFUNCTION F : INT\nVAR_OUTPUT n : INT; END_VAR\nF := 42;\nn := 42;\n"
        "END_FUNCTION\nEND_NAMESPACE\n")                                        # 7 lines
# A local FB type whose instance, when called, counts its output n up by 1.
CNT = "FUNCTION_BLOCK Cnt\nVAR_OUTPUT n : INT; END_VAR\nn := n + 1;\nEND_FUNCTION_BLOCK\n"  # 4 lines
# An FB type Acc of NS, adding 10 to its output n per call, with a METHOD Total.
NS_ACC = ("NAMESPACE NS\nFUNCTION_BLOCK Acc\nVAR_OUTPUT n : INT; END_VAR\nMETHOD Total : INT\n"
          "Total := n;\nEND_METHOD\nn := n + 10;\nEND_FUNCTION_BLOCK\nEND_NAMESPACE\n")  # 9 lines


def main_program(decls: str, body: str) -> str:
    return f"PROGRAM Main\nVAR\n{decls}\nEND_VAR\n{body}\nEND_PROGRAM\n"


@dataclass(frozen=True)
class Row:
    name: str
    text: str
    values: dict | None = None           # Main's variables after one scan (accepted)
    diagnostic: tuple | None = None      # (code, line, column, message) (refused)


ROWS = [
    # A FUNCTION of NS called as a statement, the caller has an FB instance F: the
    # function runs (y = 42 through its output), the instance does not (F.n = 0).
    Row("function_statement_beside_a_local_fb_instance",
        NS_F + CNT + main_program("    F : Cnt; y, c : INT;", "NS.F(n => y);\nc := F.n;"),
        values={"y": 42, "c": 0}),
    # The same in an expression: 42 + F.n = 42 (was E-CALL-010, the local instance
    # "called inside an expression").
    Row("function_in_an_expression_beside_a_local_fb_instance",
        NS_F + CNT + main_program("    F : Cnt; x : INT;", "x := NS.F() + F.n;"),
        values={"x": 42}),
    # A local INT named F: 42 + 5 = 47 (was E-CALL-001 "found a variable of type INT").
    Row("function_beside_a_local_int_variable",
        NS_F + main_program("    F : INT := 5; x : INT;", "x := NS.F() + F;"),
        values={"x": 47}),
    # A METHOD F of the calling FB: NS.F() is the namespace's function (42; was the
    # method's 7), the unqualified F() the method (7).
    Row("function_beside_a_method_of_the_same_name",
        NS_F + "FUNCTION_BLOCK Box\nVAR_OUTPUT q, m : INT; END_VAR\nMETHOD F : INT\nF := 7;\n"
        "END_METHOD\nq := NS.F();\nm := F();\nEND_FUNCTION_BLOCK\n"
        + main_program("    b : Box; x, z : INT;", "b();\nx := b.q;\nz := b.m;"),
        values={"x": 42, "z": 7}),
    # EN / ENO on a qualified call (IEC 6.6.1.2: every function has them), beside a
    # local F: was E-DECL-001 "undeclared name 'NS'".
    Row("function_with_en_and_eno_beside_a_local_variable",
        NS_F + main_program("    F : INT := 5; x : INT; ok : BOOL;", "x := NS.F(EN := TRUE, ENO => ok);"),
        values={"x": 42, "ok": True}),
    # A nested namespace A.B, the caller has an FB instance F: 5.
    Row("function_of_a_nested_namespace_beside_a_local_fb_instance",
        "NAMESPACE A.B\nFUNCTION F : INT\nF := 5;\nEND_FUNCTION\nEND_NAMESPACE\n" + CNT
        + main_program("    F : Cnt; x : INT;", "x := A.B.F();"),
        values={"x": 5}),
    # An instance of a namespace's FB type, called, then its METHOD: 10 and 10.
    Row("instance_of_a_qualified_fb_type_and_its_method",
        NS_ACC + main_program("    inst : NS.Acc; x, t : INT;", "inst();\nx := inst.n;\nt := inst.Total();"),
        values={"x": 10, "t": 10}),
    # An FB type of NS called by its qualified name, beside a local instance named
    # like it: the type is called (E-CALL-001), not the instance (was accepted,
    # then the compiler refused the load).  Line 14 (9 lines, then the body
    # is line 5 of Main), column 1.
    Row("fb_type_called_beside_a_local_instance_of_that_name",
        NS_ACC + main_program("    Acc : NS.Acc; x : INT;", "NS.Acc();\nx := Acc.n;"),
        diagnostic=("E-CALL-001", 14, 1, "'NS.Acc' is a FUNCTION_BLOCK type: declare an instance "
                                         "(inst : NS.Acc;) and call the instance")),
    # An INTERFACE of NS called: it has no body (was "'NS.I' is a PROGRAM"): line 11, column 6.
    Row("interface_called_by_its_qualified_name",
        "NAMESPACE NS\nINTERFACE I\nMETHOD M : INT\nEND_METHOD\nEND_INTERFACE\nEND_NAMESPACE\n"
        + main_program("    x : INT;", "x := NS.I();"),
        diagnostic=("E-CALL-001", 11, 6, "'NS.I' is an INTERFACE: call a method of an instance that implements it")),
    # A local FB instance named through a namespace: a variable is no namespace
    # element (line 14, column 1).
    Row("local_instance_named_through_the_namespace",
        NS_ACC + main_program("    inst : NS.Acc;", "NS.inst();"),
        diagnostic=("E-DECL-001", 14, 1, "NAMESPACE NS declares no POU 'inst'")),
    # NS.F() where NS declares no F and the caller has an FB instance F: line 18
    # (9 + 4 lines, then line 5 of Main).
    Row("namespace_without_f_beside_a_local_fb_instance",
        NS_ACC + CNT + main_program("    F : Cnt;", "NS.F();"),
        diagnostic=("E-DECL-001", 18, 1, "NAMESPACE NS declares no POU 'F'")),
    # NS a struct variable (not an FB instance holding F), a local instance F: line 10.
    Row("struct_variable_prefix_beside_a_local_fb_instance",
        CNT + "TYPE S : STRUCT a : INT; END_STRUCT; END_TYPE\n"
        + main_program("    F : Cnt; NS : S;", "NS.F();"),
        diagnostic=("E-TYPE-009", 10, 1, "struct S has no member 'F' (members: a)")),
    # Names of a namespace read as values (6.9: NS.X names a POU or a type declared in NS,
    # never a variable); each was "undeclared name 'NS'".  A METHOD named through the FB
    # type, not an instance: line 14, column 6.
    Row("method_named_through_a_qualified_fb_type",
        NS_ACC + main_program("    x : INT;", "x := NS.Acc.Total();"),
        diagnostic=("E-TYPE-016", 14, 6, "'NS.Acc' is a FUNCTION_BLOCK, not a variable: declare an "
                                         "instance (inst : NS.Acc;) and use the instance")),
    # A FUNCTION of NS read without its call: line 12 (7 lines, then line 5 of Main).
    Row("function_of_a_namespace_read_without_a_call",
        NS_F + main_program("    x : INT;", "x := NS.F + 1;"),
        diagnostic=("E-TYPE-016", 12, 6, "'NS.F' is a FUNCTION, not a variable; call it as NS.F(...)")),
    # A type of NS read as a value: line 8 (3 lines, then line 5 of Main).
    Row("type_of_a_namespace_read_as_a_value",
        "NAMESPACE NS\nTYPE Speed : INT; END_TYPE\nEND_NAMESPACE\n" + main_program("    x : INT;", "x := NS.Speed;"),
        diagnostic=("E-TYPE-016", 8, 6, "'NS.Speed' is a type, not a variable")),
    # A name NS does not declare: line 12.
    Row("name_a_namespace_does_not_declare",
        NS_F + main_program("    x : INT;", "x := NS.Nope;"),
        diagnostic=("E-DECL-001", 12, 6, "NAMESPACE NS declares no 'Nope'")),
]


@pytest.mark.parametrize("row", ROWS, ids=[r.name for r in ROWS])
def test_api(row):
    found = diagnostics(row.text)
    if row.diagnostic is not None:
        assert found == [row.diagnostic]
        return
    assert found == []
    plc = load_text(row.text).controller(period="1ms")
    main_instance = plc.add_program("Main")
    plc.run(1)
    assert {name: main_instance[name] for name in row.values} == row.values


@pytest.mark.parametrize("row", ROWS, ids=[r.name for r in ROWS])
def test_cli(row, tmp_path, capsys):
    path = tmp_path / "main.st"
    path.write_text(row.text)
    checked = main(["check", str(path)])
    out = capsys.readouterr()
    ran = main(["run", str(path), "--program", "Main", "--json"])
    run_out = capsys.readouterr()
    if row.diagnostic is not None:
        code, line, column, message = row.diagnostic
        assert checked == 1
        assert f"{path}:{line}:{column}: error[{code}]: {message}" in out.out + out.err
        assert ran != 0 and "Traceback" not in run_out.out + run_out.err
        return
    assert checked == 0, out.out + out.err
    assert ran == 0, run_out.out + run_out.err
    state = json.loads(run_out.out)
    assert {name: state[name] for name in row.values} == row.values
