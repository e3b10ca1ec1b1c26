"""The `shortcut` pass (st_runtime/compiler/optimise/shortcut.py): an IF condition tested in
place tests its AND and OR of BOOLs as Python's `and` and `or`.  Nothing a program can see
changes: the branch each scan takes, results, faults (code, file, line, column, scan),
instance states and the NJ time charged are equal bit for bit with the pass on and off, also
when F-PERIOD cuts the scan or a fault stops the run.
"""

from __future__ import annotations

from dataclasses import replace

import pytest

from st_runtime import api
from st_runtime.compiler import Optimisations, compile_program
from st_runtime.controller import Controller
from test_optimiser_equivalence import run_both, same_alone_and_with_all, stopped_runs

ON = Optimisations()
WITHOUT = replace(ON, shortcut=False)

EDGES = """
PROGRAM Main
VAR
    N : INT; A, B, C, D : BOOL; W : WORD; K : INT; Zero : INT;
    Both, Any, Mixed, Chain, Words, Faulting : INT;
    Flags : ARRAY[1..3] OF BOOL;
END_VAR
N := N + 1;
A := N MOD 2 = 1; B := N MOD 3 = 0; C := N MOD 5 < 2; D := N > 6;
Flags[1] := A; Flags[2] := B; Flags[3] := NOT C;
W := INT_TO_WORD(N);
K := N MOD 4;
IF A AND B THEN Both := Both + 1; END_IF;
IF A OR B OR Flags[3] THEN Any := Any + 1; ELSE Any := Any - 1; END_IF;
IF (A OR B) AND NOT (C AND D) THEN Mixed := Mixed + 1; END_IF;
IF K = 0 AND A THEN Chain := 1;
ELSIF K = 1 OR (B AND C) THEN Chain := 2;
ELSIF Flags[1] & Flags[2] THEN Chain := 3;
ELSE Chain := 4;
END_IF;
IF (W AND WORD#16#3) = WORD#16#2 OR (W OR WORD#16#1) = WORD#16#7 THEN Words := Words + 1; END_IF;
IF A AND 10 / Zero > 1 THEN Faulting := Faulting + 1; END_IF;    (* can fault: left as it was *)
END_PROGRAM
"""

FAULT = EDGES.split("\n").index("IF A AND 10 / Zero > 1 THEN Faulting := Faulting + 1; END_IF;    (* can fault: left as it was *)") + 1


def _program():
    return api.load_text(EDGES).program


def test_conditions_that_cannot_fault_use_and_or():
    source = compile_program(_program(), optimise=ON).python_sources["MAIN"]
    plain = compile_program(_program(), optimise=WITHOUT).python_sources["MAIN"]
    assert "if (v_A and v_B):" in source and "if (v_A & v_B):" in plain
    assert "if ((v_A or v_B) or v_FLAGS[2]):" in source
    assert "elif (v_FLAGS[0] and v_FLAGS[1]):" in source          # `&` is AND too
    assert "and (not (v_C & " in source                          # (under NOT: as it was)
    assert " and " not in plain and " or " not in plain
    # WORD AND / OR stay bit operations; a condition that can fault keeps its `&`
    assert "& 3)" in source and "| 1)" in source
    fault_line = [line for line in source.splitlines() if "_idiv" in line]
    assert fault_line and all(" and " not in line for line in fault_line)


def test_each_scan_takes_the_branch_worked_by_hand():
    controller = Controller(compile_program(_program(), optimise=ON))
    main = controller.add_program("Main")
    both = any_ = mixed = words = 0
    for n in range(1, 31):
        controller.run(1)
        a, b, c, d = n % 2 == 1, n % 3 == 0, n % 5 < 2, n > 6
        both += a and b
        any_ += 1 if (a or b or not c) else -1
        mixed += (a or b) and not (c and d)
        words += (n & 3) == 2 or (n | 1) == 7
        k = n % 4
        chain = 1 if (k == 0 and a) else 2 if (k == 1 or (b and c)) else 3 if (a and b) else 4
        assert (main.v_BOTH, main.v_ANY, main.v_MIXED, main.v_CHAIN, main.v_WORDS) == (both, any_, mixed, chain, words)
    assert main.v_FAULTING == 0
    assert {(f.code, f.line) for f in controller.faults} == {("F-DIV-ZERO", FAULT)}
    assert len(controller.faults) == 30          # ST evaluates both operands: every scan divides


def test_the_scans_see_the_same_with_and_without_the_pass():
    faults = same_alone_and_with_all(_program, 20, "shortcut")[0]
    assert {code for code, *_ in faults} == {"F-DIV-ZERO"}


@pytest.mark.parametrize("budget_ns", [200, 500, 900, 1_500, 3_000])
def test_f_period_lands_on_the_same_statement_with_the_pass(budget_ns):
    off, on = run_both(_program(), 12, budget_ns, optimise=Optimisations.only("branches", "shortcut"))
    assert on == off


def test_the_time_charged_and_a_stopping_fault_are_the_same():
    outcomes = stopped_runs(_program(), 4, WITHOUT, ON)
    assert outcomes[0] == outcomes[1]
    assert outcomes[1][0] == [("F-DIV-ZERO", FAULT, 1)]


# AND and OR of comparisons anywhere: each operand is a Python bool.
STORES = """
PROGRAM Main
VAR
    N : INT; X : LREAL; Zero : LREAL; Flag : BOOL; K : INT; Z : INT;
    InRange, Outside, Nested, WithNot, WithBool, MayFault : BOOL;
    Inputs : ARRAY[0..4] OF LREAL;
END_VAR
Inputs[0] := 12.5; Inputs[1] := -1.0; Inputs[2] := 700.0; Inputs[3] := Zero / Zero; Inputs[4] := 600.0;
X := Inputs[N MOD 5];
Flag := N MOD 2 = 1;
InRange := X >= 0.0 AND X <= 600.0;
Outside := X < 0.0 OR X > 600.0;
Nested := (X >= 0.0 AND X <= 600.0) OR X = 700.0;
WithNot := NOT Flag AND X > 1.0;
WithBool := Flag AND X > 1.0;                       (* Flag may be 0/1 elsewhere: `&` *)
MayFault := X > 1.0 AND 10 / Z > 1;                 (* the right one can fault: `&` *)
N := N + 1;
END_PROGRAM
"""


def test_comparisons_anywhere_use_and_or():
    source = compile_program(api.load_text(STORES).program, optimise=ON).python_sources["MAIN"]
    plain = compile_program(api.load_text(STORES).program, optimise=WITHOUT).python_sources["MAIN"]
    # (a stored comparison of numbers is tested for a jump: `True if ... else False`)
    assert "self.v_INRANGE = (True if ((v_X >= 0.0) and (v_X <= 600.0)) else False)" in source
    assert "self.v_OUTSIDE = (True if ((v_X < 0.0) or (v_X > 600.0)) else False)" in source
    assert "self.v_NESTED = (True if (((v_X >= 0.0) and (v_X <= 600.0)) or (v_X == 700.0)) else False)" in source
    assert "self.v_WITHNOT = ((not self.v_FLAG) and (v_X > 1.0))" in source
    assert "self.v_WITHBOOL = (self.v_FLAG and (self.v_FLAG & (v_X > 1.0)))" in source
    assert " and " not in plain and " or " not in plain and "True if" not in plain
    assert "self.v_MAYFAULT = (True if ((v_X > 1.0) & (_idiv(10, self.v_Z, " in source


def test_comparisons_anywhere_hold_the_values_worked_by_hand():
    controller = Controller(compile_program(api.load_text(STORES).program, optimise=ON))
    main = controller.add_program("Main")
    for n, x in enumerate([12.5, -1.0, 700.0, float("nan"), 600.0] * 2):
        controller.run(1)
        flag = n % 2 == 1
        assert (main.v_INRANGE, main.v_OUTSIDE, main.v_NESTED, main.v_WITHNOT, main.v_WITHBOOL) == \
            (0.0 <= x <= 600.0, x < 0.0 or x > 600.0, 0.0 <= x <= 600.0 or x == 700.0,
             not flag and x > 1.0, flag and x > 1.0), (n, x)
        assert type(main.v_INRANGE) is bool and type(main.v_NESTED) is bool


@pytest.mark.parametrize("budget_ns", [100, 200, 400, 500_000])
def test_comparisons_anywhere_run_the_same(budget_ns):
    off, alone = run_both(api.load_text(STORES).program, 10, budget_ns, optimise=Optimisations.only("shortcut"))
    assert alone == off
    off, every = run_both(api.load_text(STORES).program, 10, budget_ns, optimise=ON)
    assert every == off
    assert [code for code, *_ in every[0]].count("F-DIV-ZERO") in (10, 0)   # each scan, unless cut before


# A stored AND whose left operand is a BOOL read from a variable: tested first (`X and X & R`;
# an FB input `X if not X else X & R`).  A BOOL set from Python may hold 0 or 1: the value and
# its type are `&`'s.
HELD = """
PROGRAM Main
VAR Flag : BOOL; Other : BOOL; X : LREAL; WithNot, WithTest, Compared : BOOL; END_VAR
WithNot := Flag AND NOT Other;
WithTest := Flag AND X > 1.0;
Compared := X > 1.0;
END_PROGRAM
"""


@pytest.mark.parametrize("optimise", [ON, WITHOUT], ids=["on", "off"])
def test_a_stored_and_keeps_the_value_and_type_of_its_bool(optimise):
    controller = Controller(compile_program(api.load_text(HELD).program, optimise=optimise))
    main = controller.add_program("Main")
    for flag in (0, 1, False, True):
        for other, x in ((False, 0.5), (True, 2.0), (0, 2.0), (1, float("nan"))):
            main.v_FLAG, main.v_OTHER, main.v_X = flag, other, x
            controller.run(1)
            # by hand: `&` of the held value with a bool (0 & True is 0, False & True is False)
            with_not, with_test = flag & (not other), flag & (x > 1.0)
            assert (main.v_WITHNOT, main.v_WITHTEST, main.v_COMPARED) == (with_not, with_test, x > 1.0)
            assert (type(main.v_WITHNOT), type(main.v_WITHTEST), type(main.v_COMPARED)) == \
                (type(with_not), type(with_test), bool), (flag, other, x)
