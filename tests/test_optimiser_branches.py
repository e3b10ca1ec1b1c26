"""The `branches` pass (st_runtime/compiler/optimise/branches.py): IF conditions and CASE
selectors that cannot fault are tested in place, and nothing a program can see changes.

Equivalence: results, faults (code, file, line, column, scan), the time charged and the
state of every instance are equal bit for bit with the pass on and off, also when F-PERIOD
cuts the scan at many budgets; conditions that can fault (a division, an index out of
range, an unconnected VAR_IN_OUT) keep their guard and abandon the whole IF as before.
"""

from __future__ import annotations

from dataclasses import replace

import pytest

from st_runtime import api
from st_runtime.compiler import Optimisations, compile_program
from st_runtime.compiler.optimise.branches import cannot_fault_judged, code_cannot_fault
from test_optimiser_equivalence import _Context, compiled_lines, run_both, snapshot

ON = Optimisations()
WITHOUT = replace(ON, branches=False)

CHAINS = """
TYPE Point : STRUCT X : LREAL; Y : LREAL; END_STRUCT; END_TYPE
FUNCTION_BLOCK Reader
VAR_IN_OUT P : Point; END_VAR
VAR_OUTPUT Seen : INT; END_VAR
IF P.X > 1.0 THEN Seen := 1; ELSIF P.Y > 1.0 THEN Seen := 2; ELSE Seen := 3; END_IF;
END_FUNCTION_BLOCK
PROGRAM Main
VAR
    N : INT; D : INT; State : INT; Path : INT; Hits : ARRAY[1..4] OF INT;
    Q : Point := (X := 0.5, Y := 2.0); R : Reader; Z : LREAL; Level : LREAL;
    Table : ARRAY[1..3] OF LREAL := [1.0, 2.0, 3.0]; I : INT; Edge, Last : BOOL;
END_VAR
N := N + 1;
Edge := (N MOD 3 = 0) AND NOT Last; Last := N MOD 3 = 0;
Level := Level + 0.75;
(* conditions that cannot fault: a plain chain *)
IF Edge AND State = 0 THEN Path := 1;
ELSIF ABS(Level - 2.0) < 0.5 THEN Path := 2;
ELSIF Q.X * 2.0 + Table[2] > 10.0 THEN Path := 3;
ELSIF N >= 5 THEN Path := 4; Hits[1] := Hits[1] + 1;
ELSE Path := 5;
END_IF;
IF NOT Edge THEN Hits[2] := Hits[2] + 1; ELSE Hits[3] := Hits[3] + 1; END_IF;
(* conditions that can fault keep their guard: the whole IF is abandoned *)
IF N > 100 THEN Path := 6;
ELSIF 10 / D > 1 THEN Path := 7;          (* D = 0: F-DIV-ZERO, no branch runs *)
ELSE Path := 8;
END_IF;
I := N MOD 5;
IF Table[I] > 1.5 THEN Hits[4] := Hits[4] + 1; END_IF;   (* I = 0 or 4: out of range *)
CASE State OF
    0: IF N >= 2 THEN State := 1; END_IF;
    1, 3: State := State + 1;
    2: State := 5;
    4..6: State := 0;
ELSE State := 0;
END_CASE;
CASE Hits[I] OF         (* a selector that can fault *)
    0: Z := Z + 1.0;
ELSE Z := Z - 1.0;
END_CASE;
R(P := Q);
Q.X := Q.X + 0.25;
END_PROGRAM
"""


def _program(text):
    return api.load_text(text).program


def test_safe_conditions_are_tested_in_place_and_the_rest_keep_their_guard():
    source = compile_program(_program(CHAINS), optimise=ON).python_sources["MAIN"]
    plain = compile_program(_program(CHAINS), optimise=WITHOUT).python_sources["MAIN"]
    lines, plain_lines = source.splitlines(), plain.splitlines()
    first = [i for i, line in enumerate(lines) if line.strip() == "if (self.v_EDGE and (v_STATE == 0)):"]   # shortcut
    plain_first = [i for i, line in enumerate(plain_lines) if line.strip() == "if (self.v_EDGE & (v_STATE == 0)):"]
    assert lines[first[0] + 1].strip() == "v_PATH = 1"                 # the branch itself, in place
    assert plain_lines[plain_first[0] + 1].strip().endswith(" = 0")    # without: the branch's index
    assert source.count(" == 4:") < plain.count(" == 4:")   # fewer index comparisons
    assert "if (not self.v_EDGE):" in source
    division = [i for i, line in enumerate(lines) if "_idiv(10, " in line]
    assert len(division) == 1 and lines[division[0] + 1].strip().endswith(" = 1")   # guarded: an index


def test_a_chain_runs_the_same_with_and_without_the_pass():
    off, on = run_both(_program(CHAINS), 12, optimise=Optimisations.only("branches"))
    assert on == off
    faults = on[0]
    assert {code for code, *_ in faults} >= {"F-DIV-ZERO", "F-INDEX"}
    off, on = run_both(_program(CHAINS), 12, optimise=ON)
    assert on == off


@pytest.mark.parametrize("budget_ns", [500, 1_000, 2_000, 3_000, 4_000, 6_000])
def test_f_period_lands_on_the_same_statement_with_the_pass(budget_ns):
    off, on = run_both(_program(CHAINS), 4, budget_ns, optimise=Optimisations.only("branches"))
    assert on == off


def test_a_condition_on_an_unconnected_in_out_keeps_its_guard():
    """Reader's P is a VAR_IN_OUT: unconnected, reading it is F-NULL-REF, and the IF is abandoned."""
    outcomes = []
    for optimise in (WITHOUT, ON):
        compiled = compile_program(_program(CHAINS), optimise=optimise)
        instance, context = compiled.new("Reader"), _Context()
        type(instance).execute(instance, context)
        outcomes.append((context.faults, context.budget, snapshot(instance)))
    assert outcomes[0] == outcomes[1]
    assert [code for _, code, _ in outcomes[1][0]] == ["F-NULL-REF"]
    assert outcomes[1][2][-1] == ("v_SEEN", 0)      # no branch ran


def test_the_code_check_refuses_what_can_raise():
    assert code_cannot_fault("((v_A >= 0) & (self.v_B.v_C <= 8)) | (not v_D[3])")
    assert code_cannot_fault("(abs((v_X - _G.v_Y)) > 0.25)")
    assert code_cannot_fault("min(v_A, 2)")
    assert not code_cannot_fault("(v_A / v_B) > 1.0")        # ZeroDivisionError
    assert not code_cannot_fault("(v_A // v_B) > 1")
    assert not code_cannot_fault("(v_A % v_B) > 1")
    assert not code_cannot_fault("(v_A ** v_B) > 1.0")       # OverflowError
    assert not code_cannot_fault("(v_A << v_B) > 1")         # ValueError for a negative shift
    assert not code_cannot_fault("v_T[(v_I - 1) if 1 <= v_I <= 8 else _index_fault(v_I, 1, 8, 'T', w)] > 0")
    assert not code_cannot_fault("_cv_LINT_TO_LREAL(v_A) > 0.0")
    assert code_cannot_fault("(_t1 := v_A) > 0")              # setting a temporary cannot raise
    assert code_cannot_fault("((_t1 := (v_X - v_Y)) > 0.25 or _t1 < -0.25)")   # absolute.py's ABS(x) > B
    assert not code_cannot_fault("(v_A := 1) > 0")             # an ST variable: refused
    assert code_cannot_fault("(v_S not in {0, 8, 9, 10})")     # sets.py: a set of int literals
    assert not code_cannot_fault("{v_A: 1}")                   # a dict display: refused
    assert not code_cannot_fault("v_R.get() > 0")
    assert not code_cannot_fault(" * ".join(["v_A"] * 16) + " > 0.5")   # an int beyond 2**1024
    assert not code_cannot_fault("")


# The `aliases` pass (optimise/aliases.py): a variable loaded at the start of the one
# branch that uses it instead of in the prologue.
COLD = """
FUNCTION_BLOCK Mover
VAR_INPUT Go : BOOL; END_VAR
VAR
    Table : ARRAY[1..4] OF LREAL := [1.0, 2.0, 3.0, 4.0]; Gain : LREAL := 0.5;
    Target : ARRAY[1..4] OF LREAL; Calls : INT; Both : ARRAY[1..2] OF INT;
END_VAR
Calls := Calls + 1;
IF Go THEN
    IF Calls > 2 THEN
        Target[1] := Table[1] * Gain + Table[2] * Gain + Table[3] * Gain + Table[4] * Gain;
        Both[1] := Both[1] + 1;
    END_IF;
ELSE
    Both[2] := Both[2] + 1;
END_IF;
END_FUNCTION_BLOCK
PROGRAM Main
VAR M : Mover; N : INT; END_VAR
N := N + 1;
M(Go := N MOD 2 = 0);
END_PROGRAM
"""


def test_a_variable_used_in_one_branch_is_loaded_there():
    source = compile_program(_program(COLD), optimise=replace(ON, spread=False)).python_sources["MOVER"]
    lines = [line.strip() for line in source.splitlines()]
    prologue = lines[1:lines.index("_spent = 0")]
    assert "v_BOTH = self.v_BOTH" in prologue                     # used in both branches
    spread = compiled_lines(_program(COLD), "MOVER", ON)
    assert "v_BOTH = self.v_BOTH" not in spread[1:spread.index("_spent = 0")]
    assert spread.count("v_BOTH = self.v_BOTH") == 2              # (spread: in each branch)
    assert "v_TABLE = self.v_TABLE" not in prologue and "v_GAIN = self.v_GAIN" not in prologue
    inner = lines.index("if (self.v_CALLS > 2):")
    assert {"v_TABLE = self.v_TABLE", "v_GAIN = self.v_GAIN"} <= set(lines[inner + 1:inner + 4])
    plain = compile_program(_program(COLD), optimise=replace(ON, aliases=False)).python_sources["MOVER"]
    assert "    v_TABLE = self.v_TABLE" in plain.splitlines()[1:8]


@pytest.mark.parametrize("budget_ns", [400, 1_000, 500_000])
def test_late_loads_run_the_same(budget_ns):
    off, on = run_both(_program(COLD), 8, budget_ns, optimise=Optimisations.only("aliases"))
    assert on == off
    off, on = run_both(_program(CHAINS), 12, budget_ns, optimise=Optimisations.only("aliases"))
    assert on == off


def test_the_code_check_reads_literals_and_operators_right():
    assert code_cannot_fault("(abs(v_A) <= 1.7976931348623157e+308) & (v_B >= -1e-05)")
    assert code_cannot_fault("(v_A == 1) | (v_B != 2) | (v_C <= 3)")
    assert not code_cannot_fault("v_A = 1")
    assert not code_cannot_fault("v_A == 'x'")               # a string: refused, to be safe
    assert not code_cannot_fault("lambda: 1")


def test_the_code_check_kept_for_the_process_answers_as_the_check():
    # asked twice each: a kept answer is the check's own, for texts that can raise and not
    for _ in range(2):
        assert cannot_fault_judged("((v_A >= 0) & (self.v_B.v_C <= 8)) | (not v_D[3])")
        assert not cannot_fault_judged("(v_A / v_B) > 1.0")          # ZeroDivisionError
        assert not cannot_fault_judged("(v_A ** v_B) > 1.0")         # OverflowError
        assert not cannot_fault_judged("_cv_LINT_TO_LREAL(v_A) > 0.0")
        assert not cannot_fault_judged(" * ".join(["v_A"] * 16) + " > 0.5")
        assert cannot_fault_judged(" * ".join(["v_A"] * 15) + " > 0.5")   # 14 operators: at most 2**1024
