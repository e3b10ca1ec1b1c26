"""The `charges` pass (st_runtime/compiler/optimise/charges.py): charges of one block level
with nothing between them that can raise, check the budget or leave are one, and nothing a
program can see changes: results, faults (code, file, line, column, scan), instance states and
the time charged are equal with the pass on and off, also when F-PERIOD cuts the scan at many
budgets or a fault stops the run between two charges.  The `settle` pass (the same module):
a charge where `_spent`'s value is known is a store of the sum, with the same outcomes.
"""

from __future__ import annotations

from dataclasses import replace

import pytest

from st_runtime import api
from st_runtime.compiler import Optimisations, compile_program
from st_runtime.controller import Controller
from test_optimiser_equivalence import run_both, same_alone_and_with_all, snapshot, stopped_runs

ON = replace(Optimisations(), settle=False)   # (`settle` makes the first charges stores: its tests below)

LEGS = """
FUNCTION_BLOCK Legs
VAR_INPUT X : LREAL; Divisor : INT; END_VAR
VAR_OUTPUT Total : LREAL; Bad : INT; END_VAR
VAR Leg : INT; A : LREAL; B : LREAL; Q : INT; END_VAR
Total := 0.0;
FOR Leg := 1 TO 4 DO                        (* unrolled: a charge a copy, IFs between them *)
    A := X * INT_TO_LREAL(Leg);
    IF A > 2.0 THEN Bad := Bad + 1; END_IF;
    B := A * A;
    Total := Total + B;
END_FOR;
Q := 10 / Divisor;                          (* a guard between two charges: not joined *)
IF Q > 3 THEN Total := Total + 1.0; END_IF;
Total := Total * 2.0;
END_FUNCTION_BLOCK
PROGRAM Main
VAR L : Legs; N : INT; END_VAR
N := N + 1;
L(X := INT_TO_LREAL(N) * 0.25, Divisor := N MOD 3);
END_PROGRAM
"""


def _program():
    return api.load_text(LEGS).program


def _charges(optimise) -> list[int]:
    source = compile_program(_program(), optimise=optimise).python_sources["LEGS"]
    return [int(line.split("+=")[1]) for line in source.splitlines() if line.strip().startswith("_spent += ")
            and line.split("+=")[1].strip().isdigit()]


def test_charges_of_a_straight_run_are_one_and_add_up_the_same():
    joined, plain = _charges(ON), _charges(replace(ON, charges=False))
    assert len(joined) < len(plain)
    guarded = compile_program(_program(), optimise=ON).python_sources["LEGS"]
    assert "_idiv(10" in guarded and sum(joined) == sum(plain)


def test_the_scans_see_the_same_with_and_without_the_pass():
    faults = same_alone_and_with_all(_program, 9, "charges")[0]
    assert {code for code, *_ in faults} == {"F-DIV-ZERO"}


@pytest.mark.parametrize("budget_ns", [300, 600, 1_000, 1_500, 2_000, 3_000, 5_000])
def test_f_period_lands_on_the_same_statement_with_the_pass(budget_ns):
    off, on = run_both(_program(), 4, budget_ns, optimise=Optimisations.only("charges"))
    assert on == off


def test_a_fault_that_stops_the_run_leaves_the_same_time_charged():
    outcomes = []
    for optimise in (replace(ON, charges=False), ON):
        controller = Controller(compile_program(_program(), optimise=optimise), stop_on_fault=True)
        main = controller.add_program("Main")
        controller.run(5)
        outcomes.append(([(f.code, f.line, f.scan) for f in controller.faults], snapshot(main),
                         controller.ctx.budget))
    assert outcomes[0] == outcomes[1]
    assert outcomes[1][0] == [("F-DIV-ZERO", 13, 3)]


# A charge before an IF chain goes into its branches (a chain without ELSE gets one), and on
# into the chains those open: the same time on every path.
CHAINS = """
PROGRAM Main
VAR N, K, Z, Y : INT; X : LREAL; END_VAR
N := N + 1;
K := K + 1;
IF K > 3 THEN K := 0; END_IF;               (* no ELSE *)
IF K = 0 THEN
    Y := 1;
ELSIF K = 1 THEN
    Y := 2;
    IF N > 5 THEN Y := 3; ELSE Y := 4; END_IF;
ELSE
    Y := 5;
END_IF;
X := X + 1.0;
IF N > 4 THEN                               (* no ELSE, a guard in the branch *)
    X := X * 2.0;
    Z := 10 / (N - 6);
END_IF;
Y := Y + 1;
END_PROGRAM
"""


def test_a_charge_sinks_into_the_branches_of_the_chain_after_it():
    sunk = compile_program(api.load_text(CHAINS).program, optimise=ON).python_sources["MAIN"]
    plain = compile_program(api.load_text(CHAINS).program, optimise=replace(ON, charges=False)).python_sources["MAIN"]
    assert sunk.count("else:") == plain.count("else:") + 1       # the first chain got one
    lines = [line.strip() for line in sunk.splitlines()]
    for head in ("if (v_K > 3):",):
        assert not lines[lines.index(head) - 1].startswith("_spent += ")
        assert lines[lines.index(head) + 1].startswith("_spent += ")


@pytest.mark.parametrize("budget_ns", [200, 400, 600, 800, 1_000, 2_000, 500_000])
def test_sunk_charges_cut_the_scan_where_they_did(budget_ns):
    for optimise in (Optimisations.only("charges"), ON):
        off, on = run_both(api.load_text(CHAINS).program, 12, budget_ns, optimise=optimise)
        assert on == off


def test_sunk_charges_leave_the_same_time_charged():
    outcomes = stopped_runs(api.load_text(CHAINS).program, 8, replace(ON, charges=False),
                            Optimisations.only("charges"), ON)
    assert outcomes[0] == outcomes[1] == outcomes[2]
    assert outcomes[0][0] == [("F-DIV-ZERO", 18, 6)]          # Z := 10 / (N - 6), N = 6


# `settle`: the walk by hand.  The value is known from `_spent = 0` on, through a `try` that
# charges nothing, into every branch of the first chain and on after it (its three paths end
# at 103), past a budget check (it reads); not on after an ELSE-less chain (its paths end at
# 118 and 113); a handler is read knowing nothing (its take-back stays an addition).
_WALKED = """def f(self, _ctx):
    _spent = 0
    try:
        _spent += 100
        try:
            a = 1
        except _FAULTS as _e:
            _ctx.fault(_e, 1)
        if a:
            _spent += 3
        elif b:
            _spent += 1
            _spent += 2
        else:
            _spent += 3
        if _ctx.budget < _spent: _overrun(1)
        _spent += 10
        if c:
            _spent += 5
        _spent += 1
        try:
            _spent += 4
            d = 1
        except _FAULTS as _e:
            _spent -= 4
            _ctx.fault(_e, 2)
            _spent += 4
        _spent += 6
    finally:
        _ctx.budget -= _spent"""

# The lines `settled` changes, by hand: line number -> the store it writes there.
_SETTLED = {3: "_spent = 100", 9: "_spent = 103", 11: "_spent = 101", 12: "_spent = 103", 14: "_spent = 103",
            16: "_spent = 113", 18: "_spent = 118"}


def test_settled_stores_the_known_values_by_hand():
    from st_runtime.compiler.optimise.charges import settled

    walked = _WALKED.split("\n")
    expected = [line[:len(line) - len(line.lstrip())] + _SETTLED[n] if n in _SETTLED else line
                for n, line in enumerate(walked)]
    assert settled(walked) == expected


def test_settled_follows_no_value_into_a_loop():
    from st_runtime.compiler.optimise.charges import settled

    looped = ["    _spent = 0", "    _spent += 7", "    for i in r:", "        _spent += 2",
              "    _spent += 1", "    while x:", "        y = 1", "    _spent += 1"]
    assert settled(looped) == ["    _spent = 0", "    _spent = 7", "    for i in r:", "        _spent += 2",
                               "    _spent += 1", "    while x:", "        y = 1", "    _spent += 1"]




# Where the walk goes once nothing is known (session 18: it jumps, or stops, instead of
# stepping over each statement): to a `_spent = 0` of the same block, which makes the value
# known again (0, then 5); not to one in a handler, which the walk never reads (the
# loop left the body's value unknown, and no line of the block is one); an empty line
# inside a loop is part of the loop (more indented than any line), so the walk goes on
# after the loop, which charges nothing, with the value it had (7, then 8).
def test_settled_knows_the_value_again_after_a_zero_of_the_same_block():
    from st_runtime.compiler.optimise.charges import settled

    again = ["    _spent = 0", "    for i in r:", "        _spent += 2", "    _spent += 1",
             "    _spent = 0", "    _spent += 5"]
    assert settled(again) == again[:5] + ["    _spent = 5"]


def test_settled_reads_no_handler_after_nothing_is_known():
    from st_runtime.compiler.optimise.charges import settled

    handled = ["def f(self, _ctx):", "    _spent = 0", "    try:", "        for i in r:",
               "            _spent += 2", "        _spent += 1", "    finally:", "        _spent = 0",
               "        _spent += 9"]
    assert settled(handled) == handled


def test_settled_steps_over_a_loop_with_an_empty_line():
    from st_runtime.compiler.optimise.charges import settled

    spaced = ["    _spent = 0", "    _spent += 7", "    while x:", "", "        y = 1", "    _spent += 1"]
    assert settled(spaced) == ["    _spent = 0", "    _spent = 7", "    while x:", "", "        y = 1",
                               "    _spent = 8"]
SETTLE_ON = Optimisations()


def test_settle_makes_the_first_charge_a_store_of_its_amount():
    settled_source = compile_program(_program(), optimise=SETTLE_ON).python_sources["LEGS"]
    joined = _charges(ON)                           # the same code, its charges as additions
    first = next(line.strip() for line in settled_source.splitlines() if line.strip().startswith("_spent = ")
                 and line.strip() != "_spent = 0")
    assert first == f"_spent = {joined[0]}"


def test_the_scans_see_the_same_with_and_without_settle():
    same_alone_and_with_all(_program, 9, "settle")
    same_alone_and_with_all(lambda: api.load_text(CHAINS).program, 12, "settle")


@pytest.mark.parametrize("budget_ns", [200, 300, 600, 1_000, 1_500, 3_000])
def test_f_period_lands_on_the_same_statement_with_settle(budget_ns):
    for program in (_program, lambda: api.load_text(CHAINS).program):
        for optimise in (Optimisations.only("settle"), Optimisations.only("charges", "settle"), SETTLE_ON):
            off, on = run_both(program(), 6, budget_ns, optimise=optimise)
            assert on == off


def test_settle_leaves_the_same_time_charged_scan_by_scan():
    outcomes = stopped_runs(api.load_text(CHAINS).program, 8, replace(SETTLE_ON, settle=False), SETTLE_ON,
                            Optimisations.none())
    assert outcomes[0] == outcomes[1] == outcomes[2]


# `settle` along paths (session 19): where paths join with different totals, each keeps its
# own with the locals it set to a literal, and a test of such a local takes into a branch only
# the paths that reach it.  By hand (lines from 0): F is 0 (line 3), so the first test's ELSE
# (line 14) is reached by no path and stays as it is; after the first chain the paths are
# (11, F=4), (12, F=5), (13, F=0), and only the last takes the second `F == 0` (lines 17 and
# 20); then (17, F=6), (18, F=0), (11, F=4), (12, F=5): `F != 0` is three totals (line 22
# stays), its ELSE one (line 24).
_CODES = """    _spent = 0
    try:
        _spent += 10
        v_F = 0
        if (v_F == 0):
            if a:
                _spent += 1
                v_F = 4
            elif b:
                _spent += 2
                v_F = 5
            else:
                _spent += 3
        else:
            _spent += 7
        if (v_F == 0):
            if c:
                _spent += 4
                v_F = 6
            else:
                _spent += 5
        if (v_F != 0):
            _spent += 1
        else:
            _spent += 2
    finally:
        _ctx.budget -= _spent"""
_CODES_SETTLED = {2: "_spent = 10", 6: "_spent = 11", 9: "_spent = 12", 12: "_spent = 13",
                  17: "_spent = 17", 20: "_spent = 18", 24: "_spent = 20"}

# A BOOL's truth: B is TRUE unless `d` (which charges 1 more); `if v_B:` is one total (13),
# `if (not v_B):` after it too (6 + 9).  What the walk forgets: a local set other than to a
# literal (`v_C = x`, `v_C += 1`, in a tuple, by `:=` in a test, as a loop's variable, inside a
# `try`) is not known after, so the totals that its tests would tell apart stay apart.
_TRUTH = """    _spent = 0
    _spent += 5
    v_B = True
    if d:
        _spent += 1
        v_B = False
    if v_B:
        _spent += 8
    if (not v_B):
        _spent += 9"""
_TRUTH_SETTLED = {1: "_spent = 5", 4: "_spent = 6", 7: "_spent = 13", 9: "_spent = 15"}

_FORGETTING = ["v_C = x", "v_C += 1", "v_C, v_D = p", "if (v_C := g()):\n        pass",
               "for v_C in r:\n        pass", "try:\n        v_C = g()\n    except _FAULTS as _e:\n        pass"]


def _expected(lines: list[str], stores: dict[int, str]) -> list[str]:
    return [line[:len(line) - len(line.lstrip())] + stores[n] if n in stores else line
            for n, line in enumerate(lines)]


def test_settled_follows_each_path_with_the_literals_its_locals_hold_by_hand():
    from st_runtime.compiler.optimise.charges import settled

    codes = _CODES.split("\n")
    assert settled(codes) == _expected(codes, _CODES_SETTLED)
    truth = _TRUTH.split("\n")
    assert settled(truth) == _expected(truth, _TRUTH_SETTLED)


@pytest.mark.parametrize("setting", _FORGETTING)
def test_settled_forgets_a_local_set_other_than_to_a_literal(setting):
    from st_runtime.compiler.optimise.charges import settled

    # Without the setting the ELSE-less `v_C == 0` is taken by the path of total 1 only (2).
    lines = ["    _spent = 0", "    v_C = 0", "    if a:", "        _spent += 1", "    else:",
             "        _spent += 2", "        v_C = 3", "    " + setting, "    if (v_C == 0):",
             "        _spent += 4"]
    text = "\n".join(lines).split("\n")
    assert settled(text)[-1] == "        _spent += 4"
    plain = lines[:7] + ["    y = v_C"] + lines[8:]
    assert settled(plain)[-1] == "        _spent = 5"


def test_may_set_tells_a_read_from_a_store_of_a_local():
    from st_runtime.compiler.optimise.charges import may_set

    for line in ("v_C = 1", "v_C += 2", "v_C //= 2", "v_C, v_D = p", "(v_C := 4)", "for v_C in r:",
                 "with f() as v_C:", "except _FAULTS as v_C:", "del v_C", "v_D = v_C = 1"):
        assert may_set("v_C", line), line
    for line in ("v_D = v_C", "self.v_C = 1", "v_CX = 1", "if (v_C == 0):", "v_D = (v_C >= 2)",
                 "v_D = (v_C <= 2)", "v_D = (v_C != 2)", "x.v_C = 1", "v_D = f(v_C)"):
        assert not may_set("v_C", line), line


# The same in a program: Code is 0, the first axis-like chain sets it in every branch but
# its ELSE, the second runs `IF Code = 0`; Ok likewise.  Faults at scans 9 (Code <> 0) and 15
# (NOT Ok) on the paths the settled charges are on.
CODES = """
PROGRAM Main
VAR N, K, M, Code, Detail, Z : INT; Ok : BOOL; X : LREAL; END_VAR
N := N + 1;
K := N MOD 4;
M := N MOD 3;
Code := 0;
Ok := TRUE;
X := X + 1.0;
IF Code = 0 THEN
    IF K = 1 THEN Code := 11; Detail := N;
    ELSIF K = 2 THEN Code := 12; X := X * 2.0;
    ELSE Detail := 0;
    END_IF;
END_IF;
IF Code = 0 THEN
    IF M = 0 THEN Code := 21; Ok := FALSE;
    ELSE Detail := Detail + 1;
    END_IF;
END_IF;
IF Code <> 0 THEN Z := 100 / (N - 9); END_IF;
IF Ok THEN Detail := Detail + 2; ELSE Detail := Detail - 2; END_IF;
IF NOT Ok THEN Z := 10 / (N - 15); END_IF;
X := X - 0.5;
END_PROGRAM
"""


def _codes():
    return api.load_text(CODES).program


def test_settle_knows_the_total_of_the_paths_a_test_of_a_local_lets_through():
    """(`threads` off: it leaves the second `Code = 0` test out, each path then runs the second
    chain's branch it takes; test_optimiser_threads.py.)"""
    lines = [line.strip() for line in
             compile_program(_codes(), optimise=replace(SETTLE_ON, threads=False)).python_sources["MAIN"].splitlines()]
    second = lines.index("if (v_CODE == 0):", lines.index("if (v_CODE == 0):") + 1)
    assert lines[second + 2].startswith("_spent = ") and lines[second + 6].startswith("_spent = ")
    after = lines.index("if (not v_OK):")
    assert lines[after + 1].startswith("_spent = ")


def test_the_scans_see_the_same_with_and_without_settle_along_paths():
    alone = same_alone_and_with_all(_codes, 16, "settle")
    assert [fault[0] for fault in alone[0]] == ["F-DIV-ZERO", "F-DIV-ZERO"]
    assert [fault[4] for fault in alone[0]] == [9, 15]
    outcomes = stopped_runs(_codes(), 16, replace(SETTLE_ON, settle=False), SETTLE_ON, Optimisations.none())
    assert outcomes[0] == outcomes[1] == outcomes[2]


@pytest.mark.parametrize("budget_ns", [300, 1_000, 3_000])
def test_f_period_lands_on_the_same_statement_with_settle_along_paths(budget_ns):
    for optimise in (Optimisations.only("settle"), SETTLE_ON):
        off, on = run_both(_codes(), 16, budget_ns, optimise=optimise)
        assert on == off


# `_lifted` (with `charges`): the ELSE charge of a chain that follows another chain goes into
# that chain's branches, taken from its own other branches.  By hand:
_TWO_CHAINS = """    _spent += 5
    if a:
        _spent += 1
    else:
        _spent += 2
    x = 1
    if b:
        if c:
            _spent += 7
        else:
            _spent += 3
    else:
        _spent += 4"""

# The lines `_lifted` changes, by hand (line number -> what it writes; None: dropped): the
# first chain's charges take the 4, the second chain's other branches give it back.
_TWO_LIFTED = {2: "_spent += 5", 4: "_spent += 6", 8: "_spent += 3", 10: "_spent -= 1", 11: None, 12: None}


def test_lifted_moves_an_else_charge_into_the_chain_before_by_hand():
    from st_runtime.compiler.optimise.charges import _lifted

    chains = _TWO_CHAINS.split("\n")
    expected = [line[:len(line) - len(line.lstrip())] + _TWO_LIFTED[n] if n in _TWO_LIFTED else line
                for n, line in enumerate(chains) if _TWO_LIFTED.get(n, "") is not None]
    assert _lifted(chains) == expected
    guarded = _TWO_CHAINS.replace("    x = 1", "    try:\n        x = 1\n    except _FAULTS as _e:\n"
                                  "        _ctx.fault(_e, 1)").split("\n")
    assert _lifted(guarded) == guarded                  # a handler between the chains: no move
    open_a = _TWO_CHAINS.replace("    else:\n        _spent += 2\n", "").split("\n")
    assert _lifted(open_a) == open_a                    # the first chain has no ELSE: no move


# SP_Controller's legs in small: a FOR unrolled into chains whose ELSE charges the tests.
LEGS_CHAINS = """
PROGRAM Main
VAR N, Fault, K, Z : INT; P, S : ARRAY[1..4] OF LREAL; Ok : ARRAY[1..4] OF BOOL; END_VAR
N := N + 1;
FOR K := 1 TO 4 DO
    P[K] := INT_TO_LREAL(N * K) * 0.1;
    Ok[K] := P[K] < 3.0;
END_FOR;
FOR K := 1 TO 4 DO
    IF NOT Ok[K] THEN
        IF Fault = 0 THEN Fault := K; ELSE Fault := Fault + 10; END_IF;
    ELSIF ABS(P[K] - S[K]) > 0.25 THEN
        IF Fault = 0 THEN Fault := 100 + K; ELSE Fault := Fault + 1; END_IF;
    END_IF;
END_FOR;
S := P;
Z := 10 / (N - 9);                          (* F-DIV-ZERO in scan 9 *)
IF N MOD 5 = 0 THEN Fault := 0; END_IF;
END_PROGRAM
"""


def _legs():
    return api.load_text(LEGS_CHAINS).program


def test_a_run_of_chains_charges_its_else_path_once():
    lifted = compile_program(_legs(), optimise=ON).python_sources["MAIN"].splitlines()
    plain = compile_program(_legs(), optimise=replace(ON, charges=False)).python_sources["MAIN"].splitlines()
    heads = [n for n, line in enumerate(lifted) if line.strip().startswith("if (not v_OK[")]
    assert len(heads) == 4
    # the first chain's ELSE charges, the three after it have no ELSE left
    else_charges = [n for n in range(heads[0], len(lifted)) if lifted[n].strip() == "else:"
                    and lifted[n + 1].strip().startswith("_spent += ")
                    and lifted[n].index("e") == lifted[heads[0]].index("i")]      # (the chains' level)
    assert len(else_charges) == 1 and heads[0] < else_charges[0] < heads[1]
    assert any(line.strip().startswith("_spent -= ") for line in lifted)
    assert not any(line.strip().startswith("_spent -= ") for line in plain)


@pytest.mark.parametrize("budget_ns", [300, 700, 1_000, 1_200, 1_400, 2_000, 500_000])
def test_lifted_charges_cut_the_scan_where_they_did(budget_ns):
    for optimise in (Optimisations.only("charges"), ON, SETTLE_ON):
        off, on = run_both(_legs(), 14, budget_ns, optimise=optimise)
        assert on == off


def test_lifted_charges_leave_the_same_time_charged_scan_by_scan():
    outcomes = stopped_runs(_legs(), 12, Optimisations.none(), Optimisations.only("charges"), SETTLE_ON)
    assert outcomes[0] == outcomes[1] == outcomes[2]
    assert outcomes[0][0] == [("F-DIV-ZERO", 17, 9)]


def test_indentation_counts_leading_spaces_only_when_a_line_holds_other_white_space():
    """`_indents` reads a line's leading spaces with `str.lstrip()` when no line holds other
    white space; a tab (or a form feed) after the spaces is then not indentation."""
    from st_runtime.compiler.optimise.charges import _indents

    assert _indents(["def f():", "    x = 1", "", "        y"]) == [0, 4, 1 << 20, 8]
    assert _indents(["  \tx = 1", "    y = 2"]) == [2, 4]
    assert _indents(["    \x0cz", "\u3000w"]) == [4, 0]


def test_a_word_across_two_lines_is_on_neither():
    """`_lines_holding` finds a word in the lines joined without a break: a place that
    starts in one line and ends in the next is no line's."""
    from itertools import accumulate

    from st_runtime.compiler.optimise.charges import _lines_holding

    text = ["    x = v_A", "B", "    v_AB = 1", "", "v_AB v_AB"]
    flat = "".join(text)
    ends = list(accumulate(map(len, text)))
    assert _lines_holding(flat, ends, "v_AB") == [2, 4]
    assert _lines_holding(flat, ends, "v_A") == [0, 2, 4]
    assert _lines_holding(flat, ends, "Bv") == []



# Session 21 (h-mut-s21): a clause taken on `v_K == 2` tells a path that did not know v_K
# that it is 2 there, so a nested test of v_K == 2 is known to hold: its ELSE is reached by
# no path (left as written) and the value after the nested IF is one, 5 + 1 + 2 = 8, by hand
# (kills _Paths.taking_7, which told nothing and left 6 or 8).
def test_settled_knows_a_local_inside_the_clause_that_tested_it():
    from st_runtime.compiler.optimise.charges import settled

    nested = ["    _spent = 0", "    if v_K == 2:", "        _spent += 5", "        if v_K == 2:",
              "            _spent += 1", "        else:", "            _spent += 3", "        _spent += 2"]
    assert settled(nested) == ["    _spent = 0", "    if v_K == 2:", "        _spent = 5", "        if v_K == 2:",
                               "            _spent = 6", "        else:", "            _spent += 3",
                               "        _spent = 8"]


# The same past a test of `!=`: the paths going on past `if v_K != 2` learn v_K is 2, so the
# ELIF on v_K == 2 takes them all and the ELSE is reached by none (left as written); both
# clauses charge 4, so the value after the chain is 4 + 1 = 5, by hand (kills _taken_66,
# which told them nothing: the ELSE's 9 reached, 4 or 9 after).
def test_settled_knows_a_local_past_a_test_of_not_equal():
    from st_runtime.compiler.optimise.charges import settled

    chain = ["    _spent = 0", "    if v_K != 2:", "        _spent += 4", "    elif v_K == 2:", "        _spent += 4",
             "    else:", "        _spent += 9", "    _spent += 1"]
    assert settled(chain) == ["    _spent = 0", "    if v_K != 2:", "        _spent = 4", "    elif v_K == 2:",
                              "        _spent = 4", "    else:", "        _spent += 9", "    _spent = 5"]


# Beyond `_PATH_CAP` (64) paths the walk keeps one path of the total they share: seven IFs
# on an unknown v_Q, each setting its own tested local (v_A ... v_G), make 2 ** 7 = 128 paths,
# every one with _spent 0, so the charge after them is 1 on every path, by hand (kills
# _kept_24, which dropped what was known where a total was shared).
def test_settled_keeps_the_shared_total_beyond_the_path_cap():
    from st_runtime.compiler.optimise.charges import settled

    names = "ABCDEFG"
    ifs = [line for name in names for line in ("    if v_Q:", f"        v_{name} = 1")]
    tests = [line for name in names for line in (f"    if v_{name}:", "        v_Z = 0")]
    lines = ["    _spent = 0", *ifs, "    _spent += 1", *tests]
    assert settled(lines) == ["    _spent = 0", *ifs, "    _spent = 1", *tests]


# `settled`'s one look at a straight body (`_straight`): a body whose charges all stand at the
# top level of its `try`.  Each expected text is the walk's, worked out by hand: a charge the
# value of `_spent` is known at becomes the store of the running total.
_HEAD = ["def f(self, _ctx):", "    v_A = self.v_A", "    _spent = 0", "    try:", "        _spent += 5",
         "        if v_A:"]
_TAIL = ["        _spent += 7", "    finally:", "        _ctx.budget -= _spent"]


def _settled(middle: list[str]) -> list[str]:
    from st_runtime.compiler.optimise.charges import settled
    return settled(_HEAD + middle + _TAIL)


@pytest.mark.parametrize("head", [0, 1])
def test_a_straight_body_charges_its_running_total(head):
    """Charges of the `try`'s top level around a branch that charges nothing: 5, then 5 + 7;
    with the `def` line or, as the compiler hands it over, from the line after it."""
    from st_runtime.compiler.optimise.charges import settled
    out = settled((_HEAD + ["            v_A = 1"] + _TAIL)[head:])
    assert out[4 - head] == "        _spent = 5" and out[7 - head] == "        _spent = 12"


def test_a_charge_inside_a_branch_is_left_to_the_walk():
    """The branch's charge is 5 + 3; after the IF the paths hold 8 and 5 (v_A not known on
    either), so the charge after it stays an addition.  A one-look settle that took every
    charge as straight would write 8 and 15 (or 12)."""
    out = _settled(["            _spent += 3", "            v_A = 1"])
    assert out[4:9] == ["        _spent = 5", "        if v_A:", "            _spent = 8", "            v_A = 1",
                        "        _spent += 7"]


def test_a_zero_between_the_charges_starts_the_total_again():
    """`_spent = 0` of the `try`'s level: the next charge is 7, not 12."""
    out = _settled(["            v_A = 1", "        _spent = 0"])
    assert out[-3] == "        _spent = 7"


@pytest.mark.parametrize("middle", [
    ["            v_A = 1", "                v_B = 2"],            # deeper after a simple line
    ["                v_A = 1", "            v_B = 2"],            # back to no open block's level
    ["            v_A = 1", ""],                                    # an empty line (more indented than any)
])
def test_a_shape_the_walk_does_not_read_is_left_as_it_was(middle):
    """The walk stops at a line more indented than its block's statements (`_Unread`) and
    changes nothing; the one look must not replace the charges of such a body either."""
    text = _HEAD + middle + _TAIL
    from st_runtime.compiler.optimise.charges import settled
    assert settled(text) == text


def test_a_line_holding_a_barrier_word_is_a_barrier_and_a_name_holding_its_letters_is_not():
    """`_is_barrier` of lines neither a block's head nor a loop's: each holding one word of a
    line that can raise, check the budget or leave its level (the handler's `_ctx`, a `try:`,
    `except`, `finally:`, the overrun test, `return`, `break`, `continue`, an FB's
    `.execute(`, a FUNCTION's `_fn_`) is one; names that hold such letters are not."""
    from st_runtime.compiler.optimise.charges import _is_barrier

    barriers = ["        _ctx.budget -= _spent", "        try: v_X = 1", "        except _FAULTS: v_X = 0",
                "        finally: v_X = 0", "        _overrun(7)", "        return v_X", "        break",
                "        continue", "        v_T.execute(None)", "        v_Y = _fn_F(1)"]
    assert [line for line in barriers if not _is_barrier(line)] == []
    plain = ["        v_returned = v_breaks + 1", "        v_X = v_continued - v_trying", "        _spent += 12"]
    assert [line for line in plain if _is_barrier(line)] == []


def test_charges_opening_a_try_go_before_it_one_after_another():
    """`_out_of_try`: a charge that opens a `try` body with more lines after it goes before the
    `try`, and then the next one that opens it; not in the body's own `try` (after
    `_spent = 0`), nor where the charge is all the body holds (worked out by its rules)."""
    from st_runtime.compiler.optimise.charges import _out_of_try

    handler = ["        except _FAULTS as _e:", "            pass"]
    text = ["    _spent = 0", "    try:", "        _spent += 2", "        x = 1",
            "        try:", "            _spent += 5", "            _spent += 7", "            y = 2", *handler,
            "        try:", "            _spent += 4", *handler]
    _out_of_try(text)
    assert text == ["    _spent = 0", "    try:", "        _spent += 2", "        x = 1",
                    "        _spent += 5", "        _spent += 7", "        try:", "            y = 2", *handler,
                    "        try:", "            _spent += 4", *handler]


def test_the_nearest_line_not_more_indented_each_way():
    """By hand, indentations 0 4 8 8 4 8 0: from line 0 the later one is line 6, none earlier
    (-1); from line 1 (4) line 4 later (2 and 3 are deeper), line 0 earlier; from line 2 (8)
    line 3 (as deep) later, line 1 earlier; from line 4 (4) line 6 later, line 1 earlier; from
    line 6 none later (7), line 0 earlier."""
    from st_runtime.compiler.optimise.charges import _Nearest

    indents = [0, 4, 8, 8, 4, 8, 0]
    after, before = _Nearest(indents, 1), _Nearest(indents, -1)
    assert [after[n] for n in range(7)] == [6, 4, 3, 4, 6, 6, 7]
    assert [before[n] for n in range(7)] == [-1, 0, 1, 2, 1, 4, 0]


@pytest.mark.parametrize("line, barrier", [
    # by hand, a keyword stands as a word: nothing of a name before it, nor after one ending
    # with a letter (`try:` and `finally:` end with their colon)
    ("        x.return_value = 1", False), ("        y = v_A.break", True), ("        (continue)", True),
    ("        v_retry: int = 1", False), ("        _return = 1", False), ("        exceptional = 1", False),
    ("        except: pass", True), ("        x = 1; try:", True), ("        v_breaké = 2", False),
    ("        d = {v_finally: 1}", False), ("        v_X = 1 # finally: done", True),
    # a part of a name anywhere (the sure side: `v_fn_X` is no FUNCTION's, but a barrier)
    ("        v_X = self._ctxs", True), ("        v_fn_X = 1", True), ("        v_fnX = v_ct + 1", False),
])
def test_a_keyword_is_a_barrier_only_as_a_word(line, barrier):
    from st_runtime.compiler.optimise.charges import _is_barrier
    assert _is_barrier(line) is barrier
