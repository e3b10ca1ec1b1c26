"""Compiler behaviours that survivors of the fresh seed-21 mutation sample pinned down (issue 16).

The sample: `python tools/mutation.py compiler --sample 150 --seed 21` (docs/mutation.md,
"st_runtime/compiler/").  Each test loads ST through the public entry point, runs scans
and takes its expected values from IEC 61131-3 or a hand calculation stated beside it.
"""

from __future__ import annotations

from st_runtime.api import load_text
from test_compiler_mutants import run


def faults(plc):
    return [(f.code, f.line) for f in plc.faults]


# ------------------------------------------------------ outputs read with `=>`

AGGREGATE_OUTPUTS = """
TYPE Pt : STRUCT x : INT; y : INT; END_STRUCT; END_TYPE

FUNCTION_BLOCK Pair
VAR_OUTPUT Out : ARRAY[1..2] OF INT; S : Pt; END_VAR
Out[1] := 3; Out[2] := 4; S.x := 5; S.y := 6;
END_FUNCTION_BLOCK

FUNCTION Mk : INT
VAR_INPUT k : INT; END_VAR
VAR_OUTPUT Arr : ARRAY[0..1] OF INT; P : Pt; e : INT; END_VAR
Arr[0] := k; Arr[1] := k + 1; P.x := 10 * k; P.y := -k; e := k + 2; Mk := 2 * k;
END_FUNCTION

PROGRAM Main
VAR
    F : Pair; A : ARRAY[1..2] OF INT; Q : Pt;
    B : ARRAY[0..1] OF INT; U : Pt; Res : INT; e1 : INT;
    C : ARRAY[0..1] OF INT; T : Pt; e2 : INT;
END_VAR
F(Out => A, S => Q);
A[1] := 9; Q.x := 8;                    (* copies: the FB's outputs keep their values *)
Res := Mk(k := 7, Arr => B, P => U, e => e1) + 1;
Mk(k := 3, Arr => C, P => T, e => e2);
END_PROGRAM
"""


def test_array_and_structure_outputs_are_copied_into_their_targets():
    # IEC 61131-3 6.6.1.2: `=>` assigns the output to the variable after the call; an
    # aggregate is assigned by value.  Mk(7): Arr = [7, 8], P = (70, -7), e = 9, Mk = 14.
    main, plc = run(AGGREGATE_OUTPUTS)
    assert plc.faults == []
    assert (main["A"], main["Q.x"], main["Q.y"]) == ([9, 4], 8, 6)
    assert (main["F.Out"], main["F.S.x"]) == ([3, 4], 5)
    # a call inside an expression (the outputs stored while the expression is evaluated)
    assert (main["B"], main["U.x"], main["U.y"], main["e1"], main["Res"]) == ([7, 8], 70, -7, 9, 15)
    # the same function called as a statement
    assert (main["C"], main["T.x"], main["T.y"], main["e2"]) == ([3, 4], 30, -3, 5)


def test_a_function_output_inside_an_expression_written_to_a_property():
    # CODESYS dialect: a PROPERTY is written through its SET, here from an output of a call
    # inside an expression.  Split(47): 47 / 10 = 4 (integer division), Rest = 47 MOD 10 = 7.
    main, plc = run("""
FUNCTION Split : INT
VAR_INPUT X : INT; END_VAR
VAR_OUTPUT Rest : INT; END_VAR
Split := X / 10; Rest := X MOD 10;
END_FUNCTION
FUNCTION_BLOCK Box
VAR Raw : INT; Writes : INT; END_VAR
PROPERTY Value : INT
GET
    Value := Raw;
END_GET
SET
    Raw := Value; Writes := Writes + 1;
END_SET
END_PROPERTY
END_FUNCTION_BLOCK
PROGRAM Main
VAR B : Box; Q : INT; END_VAR
Q := Split(X := 47, Rest => B.Value) + 1;
END_PROGRAM
""", dialect="codesys")
    assert plc.faults == []
    assert (main["Q"], main["B.Raw"], main["B.Writes"]) == (5, 7, 1)


# ------------------------------------------------------------------------ loops

def test_a_repeat_condition_is_checked_with_what_the_body_changed():
    # i := 1 before the loop, but the body runs first (IEC: REPEAT tests after the body) and
    # makes i = 0: UNTIL's arr[i] is below arr's 1..4, F-INDEX at line 7, which ends the loop.
    main, plc = run("""PROGRAM Main
VAR arr : ARRAY[1..4] OF INT := [10, 20, 30, 40]; i : INT; n : INT; END_VAR
i := 1;
REPEAT
    i := i - 1;
    n := n + 1;
UNTIL arr[i] > 25
END_REPEAT;
END_PROGRAM
""")
    assert faults(plc) == [("F-INDEX", 7)]
    assert (main["i"], main["n"]) == (0, 1)


# -------------------------------------------- a function body compiled as one region

def run_region(body: str) -> tuple[float, list]:
    """F's body reads M's elements at literal indices often enough (8) and stores only its
    own locals, so the optimiser compiles it as one region (cse.py); M = [1.5, 2.25, 4.0, 0.5]."""
    main, plc = run(f"""FUNCTION F : LREAL
VAR_IN_OUT M : ARRAY[1..4] OF LREAL; END_VAR
VAR p : LREAL; q : LREAL; r : LREAL; END_VAR
{body}
END_FUNCTION
PROGRAM Main
VAR a : ARRAY[1..4] OF LREAL := [1.5, 2.25, 4.0, 0.5]; res : LREAL; END_VAR
res := F(M := a);
END_PROGRAM
""")
    return main["res"], faults(plc)


def test_a_region_reads_an_element_used_only_as_a_whole_value():
    # q := M[2] alone: p = 1.5 * 4.0 + 0.5 = 6.5, q = 2.25, r = 1.5 * 0.5 + 4.0 * 1.5 = 6.75,
    # F = 6.5 * 2.25 + 6.75 = 21.375 (every number exact in binary).
    assert run_region("""p := M[1] * M[3] + M[4];
q := M[2];
r := M[1] * M[4] + M[3] * M[1];
F := p * q + r;""") == (21.375, [])


def test_two_sums_in_a_row_stay_two_sums():
    # p = 1 + 1.5 * 2.25 = 4.375, q = 2 + 4.0 * 0.5 = 4.0, r = 8.25: F = 437.5 + 40 + 8.25.
    assert run_region("""p := 1.0;
q := 2.0;
p := p + M[1] * M[2];
q := q + M[3] * M[4];
r := M[1] + M[2] + M[3] + M[4];
F := p * 100.0 + q * 10.0 + r;""") == (485.75, [])


# ------------------------------------------------- the task period and a long FOR

def run_for(body: str, count: int):
    """A FOR of `count` iterations over `body` in a 1 ms task (the NJ time limit = the period)."""
    plc = load_text(f"""FUNCTION_BLOCK Work
VAR_OUTPUT n : DINT; END_VAR
n := n + 1;
END_FUNCTION_BLOCK
PROGRAM Main
VAR i : DINT; k : DINT := {count}; w : Work; s : DINT; after : INT; END_VAR
FOR i := 1 TO k DO
    {body}
END_FOR;
after := after + 1;
END_PROGRAM
""", "m.st", "iec").controller(period="1ms")
    main = plc.add_program("Main")
    plc.run(1)
    return main, faults(plc)


def test_a_for_with_a_branch_is_tested_against_the_period_when_it_ends():
    # A FOR that runs its whole count is charged and tested up front for its overhead and its
    # body's first block (the IF's test); the IF's branch is charged per iteration without a test,
    # and the total is tested when the loop ends (statements.py, s_For).  220000 iterations fit
    # the up-front test but not the total: F-PERIOD at the FOR (line 7) after every iteration
    # ran, and the statement after it does not run.
    main, seen = run_for("IF i > 0 THEN s := s + 1; END_IF;", 220_000)
    assert seen == [("F-PERIOD", 7)]
    assert (main["s"], main["after"]) == (220_000, 0)


def test_a_for_of_straight_code_is_tested_up_front_only():
    # A body of simple statements (here an FB call, whose own body is charged where it runs) is
    # tested up front only; the time the calls add is caught where straight-line code is, after
    # the program (F-PERIOD at the PROGRAM, line 5): the statement after the loop still runs.
    main, seen = run_for("w();", 120_000)
    assert seen == [("F-PERIOD", 5)]
    assert (main["w.n"], main["after"]) == (120_000, 1)


def test_a_store_to_a_structure_member_wraps_to_the_member_type():
    # An INT member holds 16 bits: 300 * 200 = 60000 is stored as 60000 - 65536 = -5536.
    main, plc = run("""TYPE Pt : STRUCT x : INT; END_STRUCT; END_TYPE
PROGRAM Main
VAR s : Pt; i : INT := 300; END_VAR
s.x := i * 200;
END_PROGRAM
""")
    assert plc.faults == []
    assert main["s.x"] == -5536
