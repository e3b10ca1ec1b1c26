"""The elements pass (optimise/elements.py): an IF chain's conditions read an array element
once where its first read always runs, and as written where it may be left out or where the
chain calls code that may store into the array."""

from __future__ import annotations

import re
from dataclasses import replace

from st_runtime import api
from st_runtime.compiler import Optimisations

from test_optimiser_equivalence import compiled_lines, run_both, same_alone_and_with_all

CHAINS = """
FUNCTION_BLOCK Unit
VAR_INPUT Level : INT; END_VAR
VAR_OUTPUT Error, Busy, Done : BOOL; END_VAR
Error := Level = 1; Busy := Level = 2; Done := Level >= 3;
END_FUNCTION_BLOCK
FUNCTION Bump : BOOL
VAR_IN_OUT A : ARRAY[1..2] OF INT; END_VAR
A[1] := A[1] + 1;
Bump := FALSE;
END_FUNCTION
PROGRAM Main
VAR Units : ARRAY[1..2] OF Unit; Scan : INT; Flag : BOOL; P, Q : ARRAY[1..2] OF INT;
    Counts : ARRAY[1..2] OF INT; Taken : ARRAY[1..4] OF INT; END_VAR
Scan := Scan + 1;
P[1] := Scan * 2 - 5;
Q[1] := 5 - Scan;
Units[2](Level := Scan MOD 4);
IF Units[2].Error THEN Taken[1] := 1;                   (* Units[2] read once *)
ELSIF Units[2].Busy THEN Taken[1] := 2;
ELSIF NOT Units[2].Done THEN Taken[1] := 3;
ELSE Taken[1] := 4;
END_IF;
Flag := Scan MOD 2 = 0;
IF Flag AND P[1] > 0 THEN Taken[2] := 1;              (* its first read may be left out *)
ELSIF P[1] < 0 THEN Taken[2] := 2;
ELSE Taken[2] := 3;
END_IF;
IF ABS(P[1] - Q[1]) > 2 THEN Taken[3] := 1;           (* read inside a walrus: once *)
ELSIF P[1] > Q[1] THEN Taken[3] := 2;
ELSE Taken[3] := 3;
END_IF;
Counts[1] := 3;
IF Counts[1] > 5 THEN Taken[4] := 1;                    (* Bump stores into Counts between *)
ELSIF Bump(Counts) THEN Taken[4] := 2;
ELSIF Counts[1] > 3 THEN Taken[4] := 3;
ELSE Taken[4] := 4;
END_IF;
END_PROGRAM
"""


def _tests(lines: list[str], element: str) -> list[str]:
    return [line for line in lines if line.startswith(("if ", "elif ")) and element in line]


def test_an_element_read_by_three_conditions_is_read_once():
    """(`reuse` off: it reads P[1] and Q[1] into names before the chains itself.)"""
    lines = compiled_lines(api.load_text(CHAINS).program, "MAIN", replace(Optimisations(), reuse=False))
    units = [line for line in lines if line.startswith(("if ", "elif ")) and ".v_BUSY" in line
             or ".v_ERROR" in line and line.startswith("if ") or ".v_DONE" in line and line.startswith("elif ")]
    assert len(units) == 3 and sum(line.count("v_UNITS[1]") for line in units) == 1
    assert "(_t" in units[0] and "v_UNITS[1]" not in units[1] + units[2]
    assert {"if (self.v_FLAG and (v_P[0] > 0)):", "elif (v_P[0] < 0):"} <= set(lines)    # as written
    walrus = _tests(lines, "v_Q[0]")
    assert len(walrus) == 1 and re.fullmatch(r"if \(\(_t(\d+) := \(\(_t(\d+) := v_P\[0\]\) - \(_t(\d+) := v_Q\[0\]\)\)\)"
                                             r" > 2 or _t\1 < -2\):", walrus[0])
    after = lines[lines.index(walrus[0]) + 1:]
    assert next(line for line in after if line.startswith("elif ")) == "elif (_t{} > _t{}):".format(
        *re.findall(r"_t(\d+) := v_[PQ]", walrus[0]))
    assert sum(line.count("v_COUNTS[0]") for line in lines if "v_COUNTS[0] >" in line) == 2     # guarded chain


def test_the_branches_taken_are_the_same_with_and_without_the_pass():
    """Scan s: Units[2].Level = s MOD 4 (1 Error, 2 Busy, 3 Done, 0 none); P[1] = 2s - 5 and
    Flag = s even (s 4 alone takes branch 1); Q[1] = 5 - s, |P[1] - Q[1]| = |3s - 10| > 2 for
    s 1 and 2, P[1] > Q[1] for s 4; Counts[1] = 3, 4 after Bump: branch 3 every scan."""
    alone = same_alone_and_with_all(lambda: api.load_text(CHAINS).program, 4, "elements")
    off, shared = run_both(api.load_text(CHAINS).program, 4, optimise=replace(Optimisations(), reuse=False))
    assert shared == off == alone        # (`shortcut` on, `reuse` off: the chains above)
    faults, states = alone
    assert faults == []
    taken = [_taken(state) for state in states]
    assert taken == [(1, 2, 1, 3), (2, 2, 1, 3), (4, 3, 3, 3), (3, 1, 2, 3)]


def _taken(state) -> tuple:
    """Main's Taken array from a snapshot of the program's state (run_both's states)."""
    found = []

    def walk(value):
        if isinstance(value, tuple):
            if len(value) == 2 and value[0] == "v_TAKEN":
                found.append(value[1])
            for item in value:
                walk(item)
    walk(state)
    assert len(found) == 1, found
    return found[0]
