"""Compiler behaviours that survivors of the mutation samples of seeds 25 and 27 left open,
pinned down as classes (issue 16, session 12; docs/mutation.md, "st_runtime/compiler/",
"Session 12").

Each test loads ST through the public entry point and takes its expected values from
IEC 61131-3, OMRON's manuals as docs/nj501.md cites them, NumPy, or a hand calculation
stated beside it; where a pass is named, the program runs with every pass and with none.
"""

from __future__ import annotations

import pytest

from st_runtime import api
from st_runtime.compiler import Optimisations, compile_program
from st_runtime.controller import Controller

EVERY, NONE = Optimisations(), Optimisations.none()


def run_with(src: str, optimise: Optimisations, scans: int = 1, dialect: str = "iec"):
    """PROGRAM Main of `src` after `scans` scans compiled with `optimise`; (instance, faults)."""
    controller = Controller(compile_program(api.load_text(src, "m.st", dialect).program, optimise=optimise))
    main = controller.add_program("Main")
    controller.run(scans)
    return main, [(f.code, f.line) for f in controller.faults]


# ------------------------------------ a loop's body stores what a value before the loop read

LOOPS = {
    "WHILE": "WHILE i < n DO z := z + x * 2.0; x := x + 1.0; i := i + 1; END_WHILE;",
    "REPEAT": "REPEAT z := z + x * 2.0; x := x + 1.0; i := i + 1; UNTIL i >= n END_REPEAT;",
    "FOR": "FOR i := 1 TO n DO z := z + x * 2.0; x := x + 1.0; END_FOR;",
    "IF around WHILE": "IF n > 0 THEN WHILE i < n DO z := z + x * 2.0; x := x + 1.0; i := i + 1; "
                       "END_WHILE; END_IF;",
    "CASE around FOR": "CASE n OF 3: FOR i := 1 TO n DO z := z + x * 2.0; x := x + 1.0; END_FOR; END_CASE;",
}


@pytest.mark.parametrize("optimise", [EVERY, NONE], ids=["every pass", "no pass"])
@pytest.mark.parametrize("loop", LOOPS.values(), ids=LOOPS.keys())
def test_a_value_computed_before_a_loop_is_computed_again_after_the_body_stores_its_operand(
        loop: str, optimise: Optimisations):
    # `x * 2.0` is computed before the loop (y); the body uses it before it stores x, so each
    # pass of the body sees the x of that pass (IEC 61131-3: a loop runs its statements in
    # order, again): x = 1, 2, 3 gives z = 2 + 4 + 6 = 12, and x ends at 4. The reuse pass
    # may keep y's value for the body's first use only if the loop stored nothing it read;
    # the loop may be inside an IF or a CASE (n is a variable: the FOR is not unrolled).
    main, faults = run_with(f"""PROGRAM Main
VAR n : INT := 3; i : INT; x : LREAL := 1.0; y : LREAL; z : LREAL; END_VAR
y := x * 2.0;
{loop}
END_PROGRAM""", optimise)
    assert (main.v_Y, main.v_Z, main.v_X, faults) == (2.0, 12.0, 4.0, [])


def test_a_function_local_read_before_a_while_and_stored_in_it():
    # The same in a FUNCTION's locals (Python locals): x = 1, then 3; z = x + 1.0 is 2 in the
    # first pass and 4 in the second; F = z + y = 4 + 2 = 6.
    main, faults = run_with("""FUNCTION F : REAL
VAR_INPUT n : INT; END_VAR
VAR x : REAL := 1.0; y : REAL; z : REAL; i : INT; END_VAR
y := x + 1.0;
WHILE i < n DO
  z := x + 1.0;
  x := x + 2.0;
  i := i + 1;
END_WHILE
F := z + y;
END_FUNCTION
PROGRAM Main
VAR r : REAL; END_VAR
r := F(2);
END_PROGRAM""", EVERY)
    assert (main.v_R, faults) == (6.0, [])
