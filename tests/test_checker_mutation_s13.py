"""Checker results that the whole-module fresh sample of session 13 (seed 28) found unchecked
(issue 16, docs/mutation.md, checker, "Session 13: a whole-module fresh seed 28").

Each test states what a user sees: a program accepted and what it computes after one scan, or
every diagnostic of a snippet in full (code, line, column counted by hand, message), or what the
checker hands the compiler (its call targets, read by the cost model).
"""

from __future__ import annotations

from checker_helpers import checked, diagnostics, nodes, program
from st_runtime import ast
from st_runtime.symbols import CallTarget
from test_checker_mutants_third import after_one_scan

# ------------------------------------------------------------------ properties

SETTER_ONLY = """FUNCTION_BLOCK Valve
VAR_OUTPUT
    opening : INT;
END_VAR
PROPERTY PUBLIC Target : INT
SET
    opening := Target * 2;
END_SET
END_PROPERTY
END_FUNCTION_BLOCK
PROGRAM Main
VAR
    v : Valve;
    seen : INT;
END_VAR
v.Target := 21;
seen := v.opening;
END_PROGRAM
"""


def test_a_property_with_only_a_setter_is_written_with_its_type():
    """A PROPERTY (CODESYS) without GET has the type of its SET's value: the store of 21 is an INT
    store into the setter, which doubles it."""
    assert diagnostics(SETTER_ONLY, "codesys") == []
    assert after_one_scan(SETTER_ONLY, "codesys")["seen"] == 42


# ------------------------------------------------------------------ calls

def _at(text: str, line: int, mark: str, code: str, message: str) -> tuple[str, int, int, str]:
    """A diagnostic placed at `mark` in line `line` of `text` (the column counted from the text)."""
    return code, line, text.splitlines()[line - 1].index(mark) + 1, message


def test_the_arguments_after_an_output_given_to_a_standard_function_are_checked_on():
    """MAX and LIMIT have no outputs (IEC 61131-3 table 29): `=>` is refused at its argument, and
    the arguments after it are still checked, each diagnostic in full."""
    twice = program("    y, a : INT;", "y := MAX(IN1 => a, IN2 := 1, IN2 := 2);")
    assert diagnostics(twice) == [
        _at(twice, 5, "IN1", "E-CALL-005", "MAX has no outputs: 'IN1' cannot be read with =>"),
        _at(twice, 5, "IN2 := 2", "E-CALL-003", "call of MAX: parameter 'IN2' is given twice")]
    undeclared = program("    y, a : INT;", "y := LIMIT(MN => a, IN := q, MX := 1);")
    assert diagnostics(undeclared) == [
        _at(undeclared, 5, "MN", "E-CALL-005", "LIMIT has no outputs: 'MN' cannot be read with =>"),
        _at(undeclared, 5, "q", "E-DECL-001", "undeclared name 'q'")]


FB_CALLS = """FUNCTION_BLOCK Counter
VAR_INPUT
    step : INT;
END_VAR
VAR_OUTPUT
    total : INT;
END_VAR
total := total + step;
END_FUNCTION_BLOCK
PROGRAM Main
VAR
    t : TON;
    c : Counter;
END_VAR
t(IN := TRUE, PT := T#1s);
c(step := 3);
END_PROGRAM
"""


def test_an_fb_call_names_its_fb_type_for_the_compiler():
    """checker/__init__.py: an FB instance call's target is kind "fb" with the FB type's upper-case
    name and its POU: the cost model charges a standard FB (TON) its instruction by that name."""
    prog = checked(FB_CALLS)
    calls = [s for s in prog.pous["MAIN"].node.body if isinstance(s, ast.CallStmt)]
    targets = [prog.call_targets[id(s.call)] for s in calls]
    assert targets == [CallTarget("fb", "TON", prog.pous["TON"]), CallTarget("fb", "COUNTER", prog.pous["COUNTER"])]


def test_a_standard_fb_call_is_charged_as_its_instruction():
    from st_runtime.api import load_text
    from st_runtime.compiler.cost import PICOSECONDS_PER_UNIT, WEIGHTS as w

    # t(IN := TRUE, PT := T#1s): a standard FB instruction and two arguments, each a load (cost.py's
    # weights, as test_cost_model's); Counter is charged as a call, its own body's blocks as they run.
    plc = load_text(FB_CALLS.replace("c(step := 3);\n", ""), "m.st").controller()
    plc.add_program("Main")
    plc.run(1)
    units = w["standard_fb"] + 2 * (w["argument"] + w["load"])
    assert plc.controller.task_times["Primary"][0] == int(round(units * PICOSECONDS_PER_UNIT))


# ------------------------------------------------------------------ the shared prelude

def test_only_a_check_that_starts_with_the_prelude_shares_it():
    """checker.check: "When the first file is the native prelude ("<builtin>"), its declarations come
    from the process's shared checked prelude"; a check of the user's files alone has none (the
    compiler then compiles every POU itself: compiler._shared_prelude "None for a program checked
    without one"), even when the first file would check alone cleanly."""
    from st_runtime.checker import check
    from st_runtime.parser import parse
    from st_runtime.prelude import prelude_file

    text = "TYPE Pair : STRUCT a : INT; b : INT; END_STRUCT; END_TYPE\nFUNCTION F : INT\nF := 1;\nEND_FUNCTION\n"
    user, errors = parse(text, "u.st")
    assert errors == []
    alone, diagnostics_alone = check([user])
    assert diagnostics_alone == [] and alone.prelude is None
    _, builtin, _ = prelude_file()
    shared, diagnostics_shared = check([builtin, user])
    assert diagnostics_shared == [] and shared.prelude is not None and shared.prelude.file is builtin
