"""Two passes that leave out repeated or useless work around variables, and nothing a program
can see changes (results, faults with code, file, line, column and scan, instance states,
F-PERIOD), with each on and off:

* `offsets`: `A[i]` of an ARRAY[1..n] in a FOR over i: `i - 1` once per iteration;
* `unused`: a load of a local nothing names (a constant table every read of which was folded),
  or of a variable the body sets before it reads it and before anything can raise.
"""

from __future__ import annotations

from dataclasses import replace

import pytest

from st_runtime import api
from st_runtime.compiler import Optimisations, compile_program
from test_optimiser_equivalence import _Context, compiled_lines, run_both, same_alone_and_with_all, snapshot

ON = Optimisations()

SUMS = """
VAR_GLOBAL CONSTANT Weights : ARRAY[1..3] OF LREAL := [0.5, 0.25, 2.0]; END_VAR
FUNCTION_BLOCK Summer
VAR_INPUT Count : INT; END_VAR
VAR_OUTPUT Sum : LREAL; Weighted : LREAL; END_VAR
VAR
    A : ARRAY[1..8] OF LREAL := [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0];
    B : ARRAY[2..9] OF LREAL := [0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5];
    I : INT;
END_VAR
Sum := 0.0;
FOR I := 1 TO Count DO                           (* Count 9: A[9] is out of range *)
    Sum := Sum + A[I] * B[I + 1] + A[I] * A[I];
    A[I] := A[I] + 0.125;
END_FOR;
Weighted := Weights[1] * Sum + Weights[3];       (* Weights: folded, no load *)
END_FUNCTION_BLOCK
PROGRAM Main
VAR S : Summer; N : INT; END_VAR
N := N + 1;
S(Count := 5 + N MOD 5);
END_PROGRAM
"""


def _program():
    return api.load_text(SUMS).program


def _source(optimise):
    return compile_program(_program(), optimise=optimise).python_sources["SUMMER"]


def test_the_index_is_computed_once_an_iteration():
    lines = [line.strip() for line in _source(ON).splitlines()]
    plain = _source(replace(ON, offsets=False))
    temps = [line for line in lines if line.endswith(" = v_I - 1")]
    assert temps and all(line.startswith("_t") for line in temps)
    assert "v_A[v_I - 1]" in plain and "v_A[v_I - 1]" not in "\n".join(lines)
    assert len(temps) == 2          # the loop without index checks and the loop with them
    checked = temps[1].split(" = ")[0]
    assert f"v_A[({checked}) if 1 <= v_I <= 8 else _index_fault(v_I, 1, 8, 'A', " in "\n".join(lines)


def test_a_load_nothing_names_is_left_out():
    lines = [line.strip() for line in _source(ON).splitlines()]
    plain = [line.strip() for line in _source(replace(ON, unused=False)).splitlines()]
    assert "v_WEIGHTS = _G.v_WEIGHTS" in plain and "v_WEIGHTS = _G.v_WEIGHTS" not in lines
    assert "v_A = self.v_A" in lines


def test_only_whole_load_lines_of_names_nothing_else_names_are_left_out():
    """`aliases.drop_unused` from line `start` on: a whole line `v_X = self.v_X` or `_G.v_X`
    whose local no other line names goes (the first and last line of the text among them);
    a load whose local is read, a line that only holds a load's text, a load of another
    name, one before `start`, and the only line of its block stay (worked out by its rules)."""
    from st_runtime.compiler.optimise.aliases import drop_unused

    lines = ["    v_K = self.v_K",              # before start: never read
             "    v_A = self.v_A",              # unused: goes
             "    v_B = _G.v_B",                # read below: stays
             "    v_C = self.v_D",              # another name's: no load of its own name
             "    x = 1; v_E = self.v_E",       # not a whole line
             "    v_H = self.v_H.v_I",          # nor this
             "    if x:",
             "        v_F = self.v_F",          # the only line of its block: stays
             "    y = v_B + 1",
             "    v_G = _G.v_G"]                # the last line, unused: goes
    drop_unused(lines, 1)
    assert lines == ["    v_K = self.v_K", "    v_B = _G.v_B", "    v_C = self.v_D", "    x = 1; v_E = self.v_E",
                     "    v_H = self.v_H.v_I", "    if x:", "        v_F = self.v_F", "    y = v_B + 1"]


@pytest.mark.parametrize("name", ["offsets", "unused"])
def test_the_scans_see_the_same_with_and_without_the_pass(name):
    faults = same_alone_and_with_all(_program, 12, name)[0]
    assert {code for code, *_ in faults} == {"F-INDEX"}          # Count 9: A[9]


@pytest.mark.parametrize("budget_ns", [500, 2_000, 5_000])
def test_f_period_lands_on_the_same_statement_with_the_passes(budget_ns):
    off, on = run_both(_program(), 6, budget_ns, optimise=Optimisations.only("offsets", "unused"))
    assert on == off


ROTATION = """
FUNCTION_BLOCK Rotate
VAR_INPUT Angle : LREAL; Divisor : INT; END_VAR
VAR_OUTPUT X : LREAL; Y : LREAL; END_VAR
VAR C : LREAL; S : LREAL; Q : LREAL; N : INT; K : INT; END_VAR
C := COS(Angle);                           (* set before anything can raise: no load *)
S := SIN(Angle);
N := N + 1;                                (* read first: loaded *)
Q := INT_TO_LREAL(10 / Divisor);           (* F-DIV-ZERO when Divisor is 0 *)
K := N * 2;
X := C * 2.0 + Q;                          (* set after what can raise: loaded *)
Y := S * 2.0 + Q + INT_TO_LREAL(K);
X := X + C; Y := Y + S + INT_TO_LREAL(K) + INT_TO_LREAL(N); C := C + X; S := S + Y;
END_FUNCTION_BLOCK
PROGRAM Main
VAR R : Rotate; I : INT; END_VAR
I := I + 1;
R(Angle := INT_TO_LREAL(I) * 0.3, Divisor := I MOD 3);
END_PROGRAM
"""


def test_a_variable_set_before_it_is_read_is_not_loaded():
    program = api.load_text(ROTATION).program
    lines = compiled_lines(program, "ROTATE", ON)
    prologue = lines[1:lines.index("_spent = 0")]
    assert "v_C = self.v_C" not in prologue and "v_S = self.v_S" not in prologue
    assert {"v_N = self.v_N", "v_X = self.v_X"} <= set(prologue)     # X: set after what can raise
    assert {"self.v_C = v_C", "self.v_S = v_S"} <= set(lines[lines.index("_ctx.budget -= _spent"):])
    off, on = run_both(program, 7, optimise=Optimisations.only("unused"))
    assert on == off and {code for code, *_ in on[0]} == {"F-DIV-ZERO"}


COPIES = """
VAR_GLOBAL Shared : ARRAY[1..3] OF LREAL := [1.0, 2.0, 3.0]; END_VAR
FUNCTION_BLOCK Keeper
VAR_IN_OUT Outside : ARRAY[1..3] OF LREAL; END_VAR
VAR Last, Before : ARRAY[1..3] OF LREAL; Fresh : INT; Seen : INT; END_VAR
Before := Last;                 (* own arrays: no guard *)
Last := Shared;                 (* from a global: no guard *)
Fresh := 7;                     (* set before anything can raise: no load *)
Outside := Last;                (* into an in-out: guarded (unconnected: F-NULL-REF) *)
Seen := Seen + Fresh * Fresh + Fresh;           (* Fresh read often: a cached local *)
END_FUNCTION_BLOCK
PROGRAM Main
VAR K : Keeper; Mine : ARRAY[1..3] OF LREAL; N : INT; END_VAR
N := N + 1;
Shared[1] := Shared[1] + 0.5;
K(Outside := Mine);
END_PROGRAM
"""


def test_array_copies_between_owned_lists_need_no_guard():
    program = api.load_text(COPIES).program
    lines = compiled_lines(program, "KEEPER", ON)
    at = {line: i for i, line in enumerate(lines)}
    assert lines[at["v_BEFORE[_WHOLE] = v_LAST"] - 1] != "try:" and lines[at["v_LAST[_WHOLE] = v_SHARED"] - 1] != "try:"
    assert lines[at["v_OUTSIDE[_WHOLE] = v_LAST"] - 1] == "try:"
    assert "v_FRESH = self.v_FRESH" not in lines and "self.v_FRESH = v_FRESH" in lines
    alone = same_alone_and_with_all(lambda: api.load_text(COPIES).program, 5, "unguard")
    assert alone[0] == []
    outcomes = []
    for optimise in (Optimisations.none(), ON):        # unconnected in-out: the same fault
        instance, context = compile_program(program, optimise=optimise).new("Keeper"), _Context()
        type(instance).execute(instance, context)
        outcomes.append((context.faults, context.budget, snapshot(instance)))
    assert outcomes[0] == outcomes[1]
    assert [code for _, code, _ in outcomes[1][0]] == ["F-NULL-REF"]
