"""Integer overflow inside an expression under `--dialect nj`.

OMRON's "NJ-series CPU Unit Software User's Manual" (W501), 6-5-3 Structured
Text, "Implicit Casts": the right-hand side is evaluated in the data type of
its highest-ranked operand, and a result outside that type's range overflows
before it is cast to the variable ("the result of the addition ... exceeds
the range of 32-bit data. An overflow will result").  Under `iec` (overflow
left to the implementation) and `codesys` (32-bit or wider registers) the
runtime keeps intermediate results exact and wraps them when stored.

Expected values by hand: DINT 2147483647 + 1 overflows to -2147483648; half
of it, truncated toward zero, is -1073741824; INT 16384 * 2 overflows to
-32768.
"""

from __future__ import annotations

import pytest

from st_runtime.api import load_text

DECLS = """D1 : DINT := 2147483647; D2 : DINT := 1; I : INT := 16384; X : LREAL := 0.5;
L1, L2 : LINT; C : BOOL; R : LREAL; K : DINT; M : LINT; E : BOOL; S : DINT; N : LINT;"""
BODY = """
L1 := (D1 + D2) / DINT#2;     (* the sum overflows DINT before the division *)
L2 := D1 + D2;                (* cast to LINT after the DINT overflow *)
C := D1 + D2 > 0;             (* compared after the overflow *)
R := (D1 + D2) * X;           (* converted to LREAL after the overflow *)
K := I * 2;                   (* INT side: overflows INT, then cast to DINT *)
M := (D1 + D2) MOD 3;         (* -2147483648 MOD 3 = -2 (sign of the dividend) *)
E := I * 2 = -32768;
S := D1 + D2 - 1;             (* a chain stored into its own type: wraps as before *)
N := -(D1 + D2);              (* -(-2147483648) overflows DINT again *)
"""
NJ = {"L1": -1073741824, "L2": -2147483648, "C": False, "R": -1073741824.0, "K": -32768, "M": -2,
      "E": True, "S": 2147483647, "N": -2147483648}
EXACT = {"L1": 1073741824, "L2": 2147483648, "C": True, "R": 1073741824.0, "K": 32768, "M": 2,
         "E": False, "S": 2147483647, "N": -2147483648}


def run(dialect: str, optimise: str, monkeypatch):
    monkeypatch.setenv("ST_RUNTIME_OPTIMISE", optimise)
    src = f"PROGRAM Main\nVAR\n{DECLS}\nEND_VAR\n{BODY}\nEND_PROGRAM\n"
    plc = load_text(src, "main.st", dialect=dialect).controller()
    main = plc.add_program("Main")
    plc.run(1)
    assert not plc.faults
    return {name: main[name] for name in NJ}


@pytest.mark.parametrize("optimise", ["none", "all"])
def test_nj_overflows_in_the_type_of_the_right_hand_side(optimise, monkeypatch):
    assert run("nj", optimise, monkeypatch) == NJ


@pytest.mark.parametrize("dialect", ["iec", "codesys"])
def test_other_dialects_keep_intermediate_results_exact(dialect, monkeypatch):
    assert run(dialect, "all", monkeypatch) == EXACT
