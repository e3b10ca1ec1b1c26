"""The `spread` pass (st_runtime/compiler/optimise/aliases.py `spread_branches`): a variable
every use of which lies in branches of one IF or CASE (of which a call runs one at most) is
loaded at the start of each such branch, and, when stored, stored back at the end of each
that stores it, not in the prologue and epilogue of every call.  Nothing a program can see
changes: results, faults (code, file, line, column, scan) and instance states are equal bit
for bit with the pass on and off, also when F-PERIOD cuts the scan inside a clause, a RETURN
leaves one, or a fault stops the run in one.
"""

from __future__ import annotations

from dataclasses import replace

import pytest

from st_runtime import api
from st_runtime.compiler import Optimisations, compile_program
from st_runtime.controller import Controller
from test_optimiser_equivalence import compiled_lines, run_both, snapshot

ON = Optimisations()
WITHOUT = replace(ON, spread=False)
PLACES = Optimisations.only("aliases", "stores", "spread")

MACHINE = """
FUNCTION_BLOCK Counter
VAR_INPUT Step : LREAL; END_VAR
VAR_OUTPUT Total : LREAL; END_VAR
Total := Total + Step;
END_FUNCTION_BLOCK
FUNCTION_BLOCK Machine
VAR_INPUT Divisor : INT; END_VAR
VAR_OUTPUT Out : LREAL; END_VAR
VAR
    State : INT;
    Tool : Counter;                 (* an FB instance used in clauses 1 and 2 only *)
    Limit : LREAL := 2.5;           (* read only, in clauses 1 and 3 only *)
    Level : LREAL;                  (* read and stored in clauses 1, 2 and 3 only *)
    Hold : LREAL;                   (* stored in clause 2 only, read after the CASE too *)
END_VAR
VAR CONSTANT Steps : ARRAY[1..2] OF LREAL := [1.0, 1.0]; END_VAR     (* every read folded *)
CASE State OF
0:
    State := 1;
1:
    Tool(Step := Limit);
    Level := Level + Tool.Total;
    IF Level > Limit * 40.0 THEN Level := Limit; END_IF;
    State := 2;
2:
    Tool(Step := Steps[1]);
    IF Level > 12.0 THEN
        Level := Level - 12.0;
        Hold := Level;
        RETURN;                                         (* leaves the clause and the FB *)
    ELSE
        Level := Level * 2.0;
    END_IF;
    Hold := Hold + 1.0;
    State := 3;
3:
    Level := Level + Limit * Steps[2];
    Level := Level + INT_TO_LREAL(100 / Divisor);       (* Divisor 0: F-DIV-ZERO *)
    Level := Level - Limit;
    State := 1;
END_CASE;
Out := Hold;
END_FUNCTION_BLOCK
PROGRAM Main
VAR M : Machine; N : INT; D : INT := 1; END_VAR
N := N + 1;
IF N MOD 7 = 0 THEN D := 0; ELSE D := 1; END_IF;
M(Divisor := D);
END_PROGRAM
"""


DIVISION = MACHINE.split("\n").index("    Level := Level + INT_TO_LREAL(100 / Divisor);       (* Divisor 0: F-DIV-ZERO *)") + 1


def _program():
    return api.load_text(MACHINE).program


def _lines(optimise):
    return compiled_lines(_program(), "MACHINE", optimise)


def test_each_clause_that_uses_a_variable_loads_it_and_stores_it_back():
    lines, plain = _lines(ON), _lines(WITHOUT)
    prologue, epilogue = lines[1:lines.index("_spent = 0")], lines[lines.index("_ctx.budget -= _spent"):]
    for name in ("v_TOOL", "v_LIMIT", "v_LEVEL"):
        assert f"{name} = self.{name}" not in prologue
        assert f"{name} = self.{name}" in plain[1:plain.index("_spent = 0")]   # (without it: on every call)
    assert "self.v_LEVEL = v_LEVEL" not in epilogue and "self.v_LEVEL = v_LEVEL" in plain
    assert lines.count("v_TOOL = self.v_TOOL") == 2 and lines.count("v_LIMIT = self.v_LIMIT") == 2
    assert lines.count("v_LEVEL = self.v_LEVEL") == 3 and lines.count("self.v_LEVEL = v_LEVEL") == 3
    assert "v_HOLD = self.v_HOLD" in prologue         # read after the CASE: loaded on entry
    assert "v_STEPS = self.v_STEPS" not in lines      # (`unused`: no clause loads the folded table)


def test_the_scans_see_the_same_with_and_without_the_pass():
    for optimise in (PLACES, ON):
        off, on = run_both(_program(), 30, optimise=optimise)
        assert on == off
    faults = on[0]
    assert faults and {(code, line) for code, _, line, _, _ in faults} == {("F-DIV-ZERO", DIVISION)}


def test_the_clauses_keep_their_values_between_calls():
    """By hand, with the pass: scan 1 State 0 -> 1; scan 2 Tool.Total 2.5, Level 2.5; scan 3
    Tool.Total 3.5, Level 5.0, Hold 1.0; scan 4 Level 5.0 + 2.5 + 100.0 - 2.5 = 105.0."""
    controller = Controller(compile_program(_program(), optimise=ON))
    main = controller.add_program("Main")
    controller.run(4)
    machine = main.v_M
    assert (machine.v_STATE, machine.v_LEVEL, machine.v_HOLD, machine.v_OUT) == (1, 105.0, 1.0, 1.0)
    assert machine.v_TOOL.v_TOTAL == 3.5
    # scan 5: Total 6.0, Level 111.0 > 100.0: 2.5; scan 6: Total 7.0, Level 5.0, Hold 2.0; scan 7:
    # Level 7.5, F-DIV-ZERO (the store skipped), 5.0; scan 8: Total 9.5, Level 14.5; scan 9: Total
    # 10.5, Level 14.5 > 12.0: 2.5, Hold 2.5, RETURN (State stays 2, Out stays 2.0)
    controller.run(5)
    assert (machine.v_STATE, machine.v_LEVEL, machine.v_HOLD, machine.v_OUT) == (2, 2.5, 2.5, 2.0)
    assert machine.v_TOOL.v_TOTAL == 10.5 and [(f.code, f.scan) for f in controller.faults] == [("F-DIV-ZERO", 7)]


@pytest.mark.parametrize("budget_ns", [300, 800, 1_500, 3_000, 6_000])
def test_f_period_lands_on_the_same_statement_with_the_pass(budget_ns):
    off, on = run_both(_program(), 12, budget_ns, optimise=PLACES)
    assert on == off


def test_a_fault_that_stops_the_run_in_a_clause_leaves_the_same_state():
    """stop_on_fault: F-DIV-ZERO at scan 7 (Divisor 0) in clause 3, after Level was stored."""
    outcomes = []
    for optimise in (WITHOUT, ON):
        controller = Controller(compile_program(_program(), optimise=optimise), stop_on_fault=True)
        main = controller.add_program("Main")
        controller.run(12)
        outcomes.append(([(f.code, f.line, f.scan) for f in controller.faults], snapshot(main)))
    assert outcomes[0] == outcomes[1]
    assert outcomes[1][0] == [("F-DIV-ZERO", DIVISION, 7)]
