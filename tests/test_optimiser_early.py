"""The early pass (optimise/aliases.py `store_early`): a method's cached variable set once at
the top level before any line names it is stored into its slot by that line, not loaded at the
start and stored back at the end; the slot holds the same value whether a fault stops the body
before that line or after it."""

from __future__ import annotations

import pytest

from st_runtime import api
from st_runtime.compiler import Optimisations

from test_optimiser_equivalence import OFF, ON, compiled_lines, run_both, stopped_runs

# Early: set once, after a statement that may fault, read after.  ReadFirst: read before it is
# set, UsedFirst read by another statement first.  Twice: set twice.  Branch: set in a branch.  Only Early's load goes.
TEXT = """
PROGRAM Main
VAR Scan, Q, Early, Twice, Branch, ReadFirst, UsedFirst, Copy : INT; END_VAR
Scan := Scan + 1;
Copy := UsedFirst;
UsedFirst := Scan * 2;
Q := 10 / (Scan - {before});
ReadFirst := ReadFirst + 1;
Early := Scan * 3;
Q := 10 / (Scan - {after});
Twice := Scan;
Twice := Twice + 1;
IF Scan > 1 THEN Branch := Scan; END_IF;
Copy := Early + Twice + Branch + ReadFirst + Early + UsedFirst * UsedFirst;
Copy := Copy + Early * ReadFirst - Early + ReadFirst + Branch + Branch;
END_PROGRAM
"""


def _program(before: int = 9, after: int = 9):
    return api.load_text(TEXT.format(before=before, after=after)).program


def test_only_a_variable_set_once_before_any_use_is_stored_early():
    lines = compiled_lines(_program(), "MAIN", ON)
    assert "self.v_EARLY = v_EARLY = ((((v_SCAN * 3)) + 32768 & 65535) - 32768)" in lines
    assert "v_EARLY = self.v_EARLY" not in lines and "self.v_EARLY = v_EARLY" not in lines
    for kept in ("READFIRST", "USEDFIRST", "TWICE", "SCAN"):
        assert f"v_{kept} = self.v_{kept}" in lines and f"self.v_{kept} = v_{kept}" in lines
    plain = compiled_lines(_program(), "MAIN", Optimisations(early=False))
    assert "v_EARLY = self.v_EARLY" in plain and "self.v_EARLY = v_EARLY" in plain


@pytest.mark.parametrize("before, after, early", [(2, 9, 3), (9, 2, 6)])
def test_a_fault_before_or_after_the_store_leaves_the_same_slot(before, after, early):
    """Stopped by F-DIV-ZERO at scan 2: before Early's line it holds scan 1's 1 * 3, after it
    scan 2's 2 * 3."""
    off, on = stopped_runs(_program(before, after), 3, OFF, ON)
    assert on == off
    faults, state, _ = on
    assert faults == [("F-DIV-ZERO", 7 if before == 2 else 10, 2)]
    assert dict(state[1:])["v_EARLY"] == early


def test_every_scan_ends_the_same():
    off, on = run_both(_program(3, 5), 6)
    assert on == off
    assert [(code, line, scan) for code, _, line, _, scan in on[0]] == [("F-DIV-ZERO", 7, 3), ("F-DIV-ZERO", 10, 5)]
