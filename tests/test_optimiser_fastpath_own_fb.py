"""A project's own FUNCTION_BLOCK named like a native one (TON: W-DECL-001, it replaces the
built-in) in the fast path's bound and in the NJ estimate (issue 16; docs/mutation.md,
"Session 15, gaps").

Its call runs its ST body (the compiler's `_execute`: its POU has no native class), so:
- fastpath.py's worst case of a caller includes that body, as for any FB written in ST (it was
  left out, as for the native TON: the bound under-counted, and the fast copy ran where the
  exact path would land F-PERIOD on a later statement of the caller);
- cost.py charges the call as a user POU call, 10 units plus its arguments, its body's blocks
  charging themselves (docs/nj501.md, "The weights": "a user POU call 10 plus 1 per argument
  element passed by value"; "a standard FB instruction (TON, R_TRIG, ...) 20" is the native
  instruction); it was charged the standard FB's 20 on top of its body.
Expected values are sums of the weights table by hand.
"""

from __future__ import annotations

from test_compiler_tables_passes import EVERY, NONE, _landings
from test_compiler_tables_passes_s14 import OWN_TON as WHILE_TON

from st_runtime.api import load_text
from st_runtime.compiler import CompileUnit, Optimisations, compile_program
from st_runtime.compiler.cost import PICOSECONDS_PER_UNIT, WEIGHTS as w
from st_runtime.compiler.optimise import fastpath
from st_runtime.compiler.statements import BodyCompiler
from st_runtime.controller import Controller

OWN_TON = """FUNCTION_BLOCK TON
VAR_INPUT IN : BOOL; PT : TIME; END_VAR VAR_OUTPUT Q : BOOL; ET : TIME; END_VAR VAR n, i : INT; END_VAR
FOR i := 1 TO 4 DO n := n + i; END_FOR;
Q := IN;
END_FUNCTION_BLOCK
"""
MAIN = """PROGRAM Main
VAR t : TON; END_VAR
t(IN := TRUE, PT := T#1s);
END_PROGRAM
"""
# The call statement: the call, and two arguments of one element each (1) with their
# literal (a load): 10 + 2 * (1 + 1) = 14.
CALL = w["call"] + 2 * (w["argument"] + w["load"])
STANDARD_CALL = w["standard_fb"] + 2 * (w["argument"] + w["load"])            # 24
# The own TON's body: the FOR's bounds 1 and 4 and its variable set (3), four iterations
# of the loop's step (2) and n := n + i (two loads, an addition, a store: 4), Q := IN (2).
BODY = (2 * w["load"] + w["store"]) + 4 * (w["loop"] + 2 * w["load"] + w["int_op"] + w["store"]) \
    + w["load"] + w["store"]                                                   # 29


def _worst_case_of_main(text: str):
    program = load_text(text).program
    unit = CompileUnit(program)
    unit.optimise = Optimisations()
    main = BodyCompiler(program, program.pous["MAIN"], unit, method=True)
    return fastpath.worst_case(main, main.body)


def _scan_time(text: str, optimise) -> list[int]:
    controller = Controller(compile_program(load_text(text).program, optimise=optimise))
    controller.add_program("Main")
    controller.run(1)
    return list(controller.task_times["Primary"])


def test_the_worst_case_of_a_caller_includes_its_own_ton_s_body():
    assert (CALL, BODY) == (14, 29)
    assert _worst_case_of_main(OWN_TON + MAIN) == CALL + BODY                   # 43 (was 24)
    assert _worst_case_of_main(MAIN) == STANDARD_CALL                           # the native TON


def test_a_call_of_an_own_ton_is_charged_as_a_user_fb_call():
    """43 units = 25,714 ps (was 53: 20 for the standard instruction besides the body's 29);
    the same FB named MyTon costs the same; the native TON's instruction 24 units = 14,352 ps."""
    for optimise in (NONE, EVERY):
        assert _scan_time(OWN_TON + MAIN, optimise) == [(CALL + BODY) * PICOSECONDS_PER_UNIT] == [25714]
        renamed = (OWN_TON + MAIN).replace("TON", "MyTon")
        assert _scan_time(renamed, optimise) == [25714]
        assert _scan_time(MAIN, optimise) == [STANDARD_CALL * PICOSECONDS_PER_UNIT] == [14352]


# Session 14's own TON (test_compiler_tables_passes_s14) with a bounded body (a FOR of 200 for
# its WHILE of 200) and a FOR in the caller after the call (for its IF): where the budget covers
# the caller's blocks but not also the TON's body, the exact path lands F-PERIOD at that FOR
# (line 18).  With the body left out of the bound the fast copy ran there: no check at line 18,
# the fault landed later (line 20) with s = 209, and, below, the charges after the call were
# made ahead of it.


def _replaced(text: str, *pairs) -> str:
    for old, new in pairs:
        assert text.count(old) == 1, old
        text = text.replace(old, new)
    return text


LONG_TON = _replaced(WHILE_TON, ("VAR n : INT; END_VAR", "VAR n, i : INT; END_VAR"),
                     ("WHILE n < 200 DO n := n + 1; END_WHILE;", "FOR i := 1 TO 200 DO n := n + 1; END_FOR;"),
                     ("IF t.Q THEN s := s + 1; END_IF;", "FOR k := 1 TO 9 DO s := s + k; END_FOR;"))


def test_f_period_lands_the_same_with_a_long_own_ton_at_every_budget():
    """Budgets 5 ns apart from 1 ns to past the scan's whole time, stop_on_fault: F-PERIOD's
    line and scan, the values and the budget left are those of no pass with fastpath alone
    and with every pass.  Without a fault s = 2 + ... + 9 (LOOPS8: 164) + 45 = 209 = r."""
    ((_, faults, state, (left,)),) = _landings(LONG_TON, NONE, [10_000_000], scans=1, stop=True)
    assert (faults, state[-1]) == ([], ("v_R", 209))
    budgets = list(range(1, 10_000_000 - left // 1000 + 20, 5))
    expected = _landings(LONG_TON, NONE, budgets, scans=1, stop=True)
    assert any(faults == [("F-PERIOD", 18, 1)] for _, faults, _, _ in expected)    # the caller's FOR
    assert any(faults == [("F-PERIOD", 4, 1)] for _, faults, _, _ in expected)     # the TON's FOR
    for optimise in (Optimisations.only("fastpath"), EVERY):
        compiled = compile_program(load_text(LONG_TON, "m.st").program, optimise=optimise)
        assert "if _ctx.budget >= " in compiled.python_sources["OUTER"]           # a fast copy
        assert _landings(LONG_TON, optimise, budgets, scans=1, stop=True) == expected
