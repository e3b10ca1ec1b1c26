"""The threads pass (optimise/threads.py): an IF chain's test of a local that every path of the
chain before it has decided is not made; each path runs the branch it would take."""

from __future__ import annotations

from st_runtime import api
from st_runtime.compiler import Optimisations, compile_program
from st_runtime.compiler.optimise import halves, threads

from test_optimiser_equivalence import compiled_lines, run_both, same_alone_and_with_all

# Scan s: Bad[1] is s = 2 (Code 11), Bad[2] s = 3 (Code 12); otherwise Quotient := 100 / (s - 6)
# (F-DIV-ZERO at scan 6, line 13, inside the chain threaded into the first one's path), and at
# s = 5 Code := 5 MOD 3 = 2 (not a literal: the fourth chain's test stays).  Other is written
# through a reference (P^) from scan 4 on: it is no Python local, its test stays.
AXES = """
PROGRAM Main
VAR Scan, Code, Other, Quotient : INT; Bad : ARRAY[1..2] OF BOOL; Taken : ARRAY[1..3] OF INT;
    P : REF_TO INT; END_VAR
Scan := Scan + 1;
Bad[1] := Scan = 2; Bad[2] := Scan = 3;
Code := 0;
IF Code = 0 THEN
    IF Bad[1] THEN Code := 11; END_IF;
END_IF;
IF Code = 0 THEN
    IF Bad[2] THEN Code := 12;
    ELSE Quotient := 100 / (Scan - 6);
    END_IF;
END_IF;
IF Code = 0 THEN
    IF Scan = 5 THEN Code := Scan MOD 3; END_IF;
END_IF;
IF Code = 0 THEN Taken[1] := Taken[1] + 1;
ELSIF Code = 12 THEN Taken[2] := Taken[2] + 1;
END_IF;
Other := 0;
IF Scan > 3 THEN
    P := REF(Other);
    P^ := 7;
END_IF;
IF Other = 0 THEN Taken[3] := Taken[3] + 1; END_IF;
END_PROGRAM
"""


def _program():
    return api.load_text(AXES).program


def test_tests_every_path_has_decided_are_not_made():
    lines = compiled_lines(_program(), "MAIN", Optimisations())
    # The first chain's test, and the fourth's (after a path that set Code to MOD's value).
    assert lines.count("if (v_CODE == 0):") == 2
    assert lines.count("elif (v_CODE == 12):") == 1
    assert lines.count("if (self.v_OTHER == 0):") == 1        # (set through P^: a slot)
    # The second and third chains run inside the first one's path that found no fault.
    nested = lines.index("if v_BAD[1]:")
    assert lines.index("if v_BAD[0]:") < nested < lines.index("if (v_SCAN == 5):")
    assert lines.count("if (v_CODE == 0):") + 2 == \
        compiled_lines(_program(), "MAIN", Optimisations(threads=False)).count("if (v_CODE == 0):")


def test_the_branches_faults_and_charges_are_the_same():
    """By hand: Taken[1] counts the scans that end with Code = 0 (1, 4, 6 and 7: the division
    by zero at 6 leaves Code as it was), Taken[2] the scan with Code 12 (3), Taken[3] the scans
    before P^ := 7 (1 to 3); Quotient 100 / (7 - 6) at the last scan."""
    same_alone_and_with_all(_program, 7, "threads")
    off, on = run_both(_program(), 7)
    assert on == off
    faults, states = on
    assert faults == [("F-DIV-ZERO", "<text>", 13, 26, 6)]
    main = dict(states[-1][1][0][1][1:])
    assert main["v_TAKEN"] == (4, 1, 3) and main["v_QUOTIENT"] == 100 and main["v_CODE"] == 0


def _threaded(text: str) -> list[str]:
    lines = text.strip("\n").split("\n")
    threads.thread(lines, 0)
    return lines


def test_a_truth_test_and_a_not_equal_test_are_decided_by_literals():
    assert _threaded("""
if v_A:
    v_X = True
else:
    v_X = False
if (not v_X):
    f()
else:
    g()
""") == ["if v_A:", "    v_X = True", "    g()", "else:", "    v_X = False", "    f()"]
    assert _threaded("""
if v_A:
    v_X = 3
else:
    v_X = 0
if (v_X != 0):
    f()
""") == ["if v_A:", "    v_X = 3", "    f()", "else:", "    v_X = 0"]
    unknown = """
if v_A:
    v_X = 3
elif v_B:
    v_X = 0
if (v_X != 0):
    f()
"""
    assert _threaded(unknown) == unknown.strip("\n").split("\n")     # (neither taken: v_X unknown)


def test_paths_that_end_on_one_line_each_get_their_own_part():
    """The inner chain's branch, its untaken path and the outer chain's untaken path all end
    before the next chain's line: each gets its part, the ELSEs opened innermost first."""
    assert _threaded("""
if (v_X == 0):
    if v_A:
        v_X = 1
if (v_X == 0):
    f()
else:
    g()
""") == ["if (v_X == 0):", "    if v_A:", "        v_X = 1", "        g()", "    else:", "        f()",
         "else:", "    g()"]


def test_a_test_is_kept_where_a_path_may_have_set_the_local():
    for setter in ("v_X = g()", "v_X, v_Y = g()", "v_X += 1", "h(v_X := 0)"):
        text = f"""
if (v_X == 0):
    {setter}
else:
    v_Y = 1
if (v_X == 0):
    f()
"""
        assert _threaded(text) == text.strip("\n").split("\n"), setter
    inside = """
if (v_X == 0):
    try:
        v_X = 4
    except _FAULTS as _e:
        _ctx.fault(_e, ('Main', '<text>', 3, 1))
else:
    v_Y = 1
if (v_X == 0):
    f()
"""
    assert _threaded(inside) == inside.strip("\n").split("\n")
    tested = """
if (v_X == 0):
    v_Y = 1
elif (v_X := g()):
    v_Y = 2
else:
    v_Y = 3
if (v_X == 0):
    f()
"""
    assert _threaded(tested) == tested.strip("\n").split("\n")     # (a clause's test set it)


def test_a_long_part_goes_to_one_path_at_most():
    long_part = "\n".join(f"    f({k})" for k in range(threads.SMALL + 1))
    text = f"""
if v_A:
    v_X = 1
elif v_B:
    v_X = 1
else:
    v_X = 0
if (v_X == 1):
{long_part}
"""
    assert _threaded(text) == text.strip("\n").split("\n")
    short = text.replace(long_part, "    f(0)")
    assert _threaded(short) == ["if v_A:", "    v_X = 1", "    f(0)", "elif v_B:", "    v_X = 1", "    f(0)",
                                "else:", "    v_X = 0"]


def test_a_long_first_branch_made_by_threading_is_tested_the_other_way_round():
    """The chain before gets the next chain's code in its first branch: past `halves.FAR` lines
    its test is `!=` with the ELSE first, so the jump after the comparison is near."""
    body = "\n".join(f"    f({k})" for k in range(halves.FAR))
    text = f"""
if (v_X == 0):
    if v_A:
        v_X = 1
else:
    g()
if (v_X == 0):
{body}
"""
    assert _threaded(text) == ["if (v_X != 0):", "    g()", "else:", "    if v_A:", "        v_X = 1",
                               "    else:", *("    " + line for line in body.split("\n"))]
    short = text.replace(body, "    f(0)")
    assert _threaded(short)[0] == "if (v_X == 0):"


def test_a_long_first_branch_under_a_not_equal_test_is_tested_with_equal():
    """The other way round from `!=`: the swapped chain tests `==` (by hand: the ELSE path is
    the one with v_X = 1)."""
    body = "\n".join(f"    f({k})" for k in range(halves.FAR))
    text = f"""
if (v_X != 1):
    v_X = 0
else:
    g()
if (v_X == 0):
{body}
"""
    assert _threaded(text) == ["if (v_X == 1):", "    g()", "else:", "    v_X = 0", *body.split("\n")]


def test_no_threaded_line_is_indented_past_the_deepest_allowed():
    """By hand: the chain's paths end at `margin` + 4 spaces and the next chain's part holds a
    line 4 deeper than its own start, so its deepest threaded line is at `margin` + 8."""
    def chains(margin: int) -> str:
        pad = " " * margin
        return "\n".join(pad + line for line in (
            "if v_A:", "    v_X = 1", "else:", "    v_X = 0", "if (v_X == 1):", "    if v_B:", "        f(0)"))

    at_the_limit = chains(threads.DEEPEST - 8)
    assert _threaded(at_the_limit) == [" " * (threads.DEEPEST - 8) + line for line in (
        "if v_A:", "    v_X = 1", "    if v_B:", "        f(0)", "else:", "    v_X = 0")]
    one_level_past = chains(threads.DEEPEST - 4)
    assert _threaded(one_level_past) == one_level_past.split("\n")


def test_the_wave_state_tests_of_the_axes_jump_near():
    """SP_Controller's first `NewFault` test holds the five other axes' tests: `!= 0` first."""
    from stgen.scenarios.program import controller_sources

    program = api.load_sources(dict(controller_sources(None))).program
    source = compile_program(program, optimise=Optimisations()).python_sources["SP_CONTROLLER"].splitlines()
    start = source.index("        if (v_STATE not in {0, 8, 9, 10}):")
    assert source[start + 1:start + 4] == ["            if (v_NEWFAULT != 0):", "                _spent += 14352",
                                           "            else:"]
    axes = source[start + 4:source.index("        if ((((self.v_MOVEEDGE or self.v_WAVEEDGE) or self.v_PATHEDGE)"
                                         " or self.v_PLAYBACKEDGE) and (not ((_G.v_SPPOWERON & (v_STATE == 3))"
                                         " & (v_NEWFAULT == 0)))):")]
    assert not any("v_NEWFAULT ==" in line or "v_NEWFAULT !=" in line for line in axes)
    assert [line.strip() for line in axes if "_MFAULTLVL.v_ACTIVE:" in line] == \
        [f"if v_MC_AXIS00{k}.v_MFAULTLVL.v_ACTIVE:" for k in range(6)]


def test_the_candidates_are_the_if_lines_testing_a_local_alone():
    """By hand: the first line, an `if` of each shape the `settle` pass reads; not an `elif`,
    not a test of anything else, not a line with more after the colon; a range of lines reads
    only its own."""
    from st_runtime.compiler.optimise.threads import _candidates

    text = ["if v_A:", "    if (v_B == 4):", "    elif (v_B != 0):", "    if (not v_C):", "    if v_D > 2:",
            "    x = 1", "if (v_E != -3):", "if v_F: y", "        if v_G:"]
    assert _candidates(text, 0, len(text)) == [0, 1, 3, 6, 8]
    assert _candidates(text, 1, 7) == [1, 3, 6]
    assert _candidates(text, 2, 3) == []
