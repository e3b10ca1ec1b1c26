"""The first load of a method's prologue is a candidate of `drop_unread` and `store_early`
(optimise/aliases.py) like every later one: `start` is the body's first line, the one after
the `def` (a mutant that read from the line before it survived and showed that both passes
had skipped the first load).  Expected lines by hand from the passes' rules; results, faults
and instance states the same with every pass off."""

from __future__ import annotations

from st_runtime import api

from test_optimiser_equivalence import ON, compiled_lines, run_both

# A, the first variable a cached load is made for, is set before anything reads it: its load
# is left out (drop_unread); B is read before it is set: its load stays.
SET_FIRST = """
FUNCTION_BLOCK First
VAR_OUTPUT Total : LREAL; END_VAR
VAR A, B : LREAL; END_VAR
A := 2.0;
B := A * A + B;
Total := A + B + A * B;
END_FUNCTION_BLOCK
PROGRAM Main
VAR F : First; END_VAR
F();
END_PROGRAM
"""

# Early, declared first, is set once at the top level after a statement that may fault and
# read only after it: stored by its setting line, neither loaded nor stored back (store_early).
STORED_EARLY = """
PROGRAM Main
VAR Early, Scan, Q, Copy : INT; END_VAR
Scan := Scan + 1;
Q := 10 / (Scan - 9);
Early := Scan * 3;
Copy := Early + Early * Early + Scan;
Copy := Copy + Early * Scan - Early;
END_PROGRAM
"""


def test_the_first_load_of_a_variable_set_before_it_is_read_is_left_out():
    program = api.load_text(SET_FIRST).program
    lines = compiled_lines(program, "FIRST", ON)
    assert lines[1] == "v_B = self.v_B" and "v_A = self.v_A" not in lines
    assert "self.v_A = v_A" in lines and "self.v_B = v_B" in lines
    off, on = run_both(program, 3)
    assert off == on


def test_the_first_load_of_a_variable_set_once_is_stored_early():
    program = api.load_text(STORED_EARLY).program
    lines = compiled_lines(program, "MAIN", ON)
    assert "self.v_EARLY = v_EARLY = ((((v_SCAN * 3)) + 32768 & 65535) - 32768)" in lines
    assert "v_EARLY = self.v_EARLY" not in lines and "self.v_EARLY = v_EARLY" not in lines
    off, on = run_both(program, 12)     # Q's division faults at scan 9 (F-DIV-ZERO)
    assert off == on
