"""The `stores` pass (st_runtime/compiler/optimise/stores.py): a cached variable stored in one
branch only is stored back at that branch's end (and loaded at its start when every use is
there), and nothing a program can see changes: results, faults (code, file, line, column,
scan) and instance states are equal bit for bit with the pass on and off, also when F-PERIOD
cuts the scan inside the branch, a RETURN leaves it, or a fault stops the run in it.
"""

from __future__ import annotations

from dataclasses import replace

import pytest

from st_runtime import api
from st_runtime.compiler import Optimisations, compile_program
from st_runtime.controller import Controller
from test_optimiser_equivalence import compiled_lines, run_both, same_alone_and_with_all, snapshot

ON = Optimisations()
WITHOUT = replace(ON, stores=False)

LATCH = """
FUNCTION_BLOCK Wave
VAR_INPUT Enable : BOOL; Divisor : INT; END_VAR
VAR_OUTPUT Value : LREAL; END_VAR
VAR
    Previous : BOOL; Count : INT; Gain : LREAL; Offset : LREAL; Phase : LREAL;
    Spare : LREAL; Latches : INT; K : INT;
END_VAR
IF Enable AND NOT Previous THEN
    (* the latch: Gain, Offset, Spare and Latches are stored here only *)
    Latches := Latches + 1;
    Gain := 0.5 * INT_TO_LREAL(Latches);
    Offset := Gain + 1.0;
    Spare := Offset * 2.0; Spare := Spare + Gain; Spare := Spare - 1.0;
    Count := 3;
    FOR K := 1 TO Count DO
        Phase := Phase + Gain;
        IF K = 2 AND Latches = 2 THEN RETURN; END_IF;      (* leaves the branch and the FB *)
    END_FOR;
    Offset := Offset + INT_TO_LREAL(10 / Divisor);         (* Divisor 0: F-DIV-ZERO *)
END_IF;
Previous := Enable;
IF Enable THEN
    Phase := Phase + 0.25;
    Value := Gain * Phase + Offset;
    Count := Count + 1;
END_IF;
END_FUNCTION_BLOCK
PROGRAM Main
VAR W : Wave; N : INT; D : INT := 1; END_VAR
N := N + 1;
IF N MOD 4 = 0 THEN D := 1 - D; END_IF;
W(Enable := N MOD 3 <> 0, Divisor := D);
END_PROGRAM
"""


def _program():
    return api.load_text(LATCH).program


def _lines(optimise):
    return compiled_lines(_program(), "WAVE", optimise)


def test_stores_in_one_branch_are_stored_back_at_its_end():
    lines, plain = _lines(ON), _lines(WITHOUT)
    epilogue = lines[lines.index("_ctx.budget -= _spent"):]
    prologue = lines[1:lines.index("_spent = 0")]
    for name in ("v_LATCHES", "v_SPARE", "v_K"):            # every use in the latch: load and store there
        assert f"self.{name} = {name}" not in epilogue and f"{name} = self.{name}" not in prologue
        assert f"self.{name} = {name}" in plain[plain.index("_ctx.budget -= _spent"):]
    for name in ("v_GAIN", "v_OFFSET"):              # read after the latch too: loaded on entry
        assert f"self.{name} = {name}" not in epilogue and f"{name} = self.{name}" in prologue
    assert "self.v_PHASE = v_PHASE" in epilogue      # stored in both branches
    assert "self.v_COUNT = v_COUNT" in epilogue
    branch = lines.index("if (self.v_ENABLE and (not self.v_PREVIOUS)):")     # (shortcut)
    latch = lines.index("try:", branch)
    opening = [line for line in lines[branch + 1:latch] if not line.startswith("_spent")]   # (a charge may open it)
    assert {"v_LATCHES = self.v_LATCHES", "v_SPARE = self.v_SPARE", "v_K = self.v_K"} == set(opening)
    back = lines.index("finally:", latch)
    assert {"self.v_LATCHES = v_LATCHES", "self.v_SPARE = v_SPARE", "self.v_GAIN = v_GAIN",
            "self.v_OFFSET = v_OFFSET", "self.v_K = v_K"} == set(lines[back + 1:back + 6])


def test_the_scans_see_the_same_with_and_without_the_pass():
    faults = same_alone_and_with_all(_program, 24, "stores")[0]
    assert [code for code, *_ in faults] == ["F-DIV-ZERO"] * len(faults) and faults


def test_the_latch_keeps_its_values_between_calls():
    """By hand: latch 1 at N = 1 (Gain 0.5, Offset 1.5), Phase 3 * 0.5 then + 0.25 each call."""
    controller = Controller(compile_program(_program(), optimise=ON))
    main = controller.add_program("Main")
    controller.run(2)
    wave = main.v_W
    assert (wave.v_LATCHES, wave.v_GAIN, wave.v_OFFSET, wave.v_SPARE) == (1, 0.5, 1.5 + 10.0, 3.5 - 1.0 + 0.0)
    assert wave.v_PHASE == 1.5 + 0.25 + 0.25 and wave.v_VALUE == 0.5 * 2.0 + 11.5


@pytest.mark.parametrize("budget_ns", [300, 800, 1_500, 3_000, 6_000])
def test_f_period_lands_on_the_same_statement_with_the_pass(budget_ns):
    off, on = run_both(_program(), 12, budget_ns, optimise=Optimisations.only("stores"))
    assert on == off


def test_a_fault_that_stops_the_run_in_the_branch_leaves_the_same_state():
    """stop_on_fault: F-DIV-ZERO in the third latch (N = 5, Divisor 0: the second, at N = 4,
    RETURNs before the division and before Previous is set) ends the run there; the variables the latch stored are in
    their slots as the store at the call's end left them."""
    outcomes = []
    for optimise in (WITHOUT, ON):
        controller = Controller(compile_program(_program(), optimise=optimise), stop_on_fault=True)
        main = controller.add_program("Main")
        controller.run(12)
        outcomes.append(([(f.code, f.line, f.scan) for f in controller.faults], snapshot(main)))
    assert outcomes[0] == outcomes[1]
    assert outcomes[1][0] == [("F-DIV-ZERO", 20, 5)]
    assert ("v_LATCHES", 3) in outcomes[1][1][1][-1]
