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
-32768; SINT 127 + 127 to -2; INT -32768 / -1 to -32768 (the same rule
applied to a quotient: W501 shows it for a sum only).

The same expressions with CONSTANT operands, which the checker folds, must
give the same values as with variables, under each dialect.
"""

from __future__ import annotations

import pytest

from st_runtime.api import load_text
from test_semantics_random_mixed import run_once

OPERANDS = "D1 : DINT := 2147483647; D2 : DINT := 1; I : INT := 16384; B : SINT := 127; I2 : INT := -32768;"
DECLS = """X : LREAL := 0.5; A : ARRAY[-2..254] OF INT;
L1, L2 : LINT; C : BOOL; R : LREAL; K : DINT; M : LINT; E : BOOL; S : DINT; N : LINT;
P, Q : LINT; W : INT; G : INT; V : DINT;"""
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
P := DINT_TO_LINT(D1 + D2);   (* a conversion's argument *)
Q := MAX(D1 + D2, 0);         (* a standard function's argument *)
CASE D1 + D2 OF               (* a CASE selector *)
    -2147483648: W := 1;
ELSE
    W := 2;
END_CASE;
A[-2] := 5; A[254] := 7;
G := A[B + B];                (* an index: SINT 127 + 127 *)
V := I2 / -1;                 (* a quotient *)
"""
NJ = {"L1": -1073741824, "L2": -2147483648, "C": False, "R": -1073741824.0, "K": -32768, "M": -2,
      "E": True, "S": 2147483647, "N": -2147483648, "P": -2147483648, "Q": 0, "W": 1, "G": 5, "V": -32768}
EXACT = {"L1": 1073741824, "L2": 2147483648, "C": True, "R": 1073741824.0, "K": 32768, "M": 2,
         "E": False, "S": 2147483647, "N": -2147483648, "P": 2147483648, "Q": 2147483648, "W": 2, "G": 7,
         "V": 32768}


def run(dialect: str, optimise: str, monkeypatch, operands: str = "VAR"):
    """Run BODY once; `operands` is the block the operands are declared in."""
    monkeypatch.setenv("ST_RUNTIME_OPTIMISE", optimise)
    src = f"PROGRAM Main\nVAR\n{DECLS}\nEND_VAR\n{operands}\n{OPERANDS}\nEND_VAR\n{BODY}\nEND_PROGRAM\n"
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


@pytest.mark.parametrize("dialect, expected", [("nj", NJ), ("iec", EXACT), ("codesys", EXACT)])
def test_constant_operands_fold_to_the_values_variables_give(dialect, expected, monkeypatch):
    """Folded by the checker (`(C + 1) / 2` with C a CONSTANT) or computed at
    run time, an expression has one value; under `iec` the fold of `C + 1`
    used to wrap where the run time keeps the exact sum."""
    assert run(dialect, "all", monkeypatch, operands="VAR CONSTANT") == expected


# OMRON's data type ranking (W501 6-5-3, p. 6-106): an integer operation takes
# the type of its higher-ranked operand, and of a signed and an unsigned one
# of the same rank, the unsigned type.  Hand values below.
RANKED_OPERANDS = """U : UDINT := 16#FFFFFFFF; D : DINT := 1; M1 : DINT := -1; UZ : UDINT := 10;
I : INT := -1; W : UINT := 3; S : SINT := -2;"""
RANKED_BODY = """
R1 := (U + D) / DINT#2;   (* OMRON's own example: UDINT, overflows to 0, 0 / 2 = 0 *)
R2 := UZ / M1;            (* UDINT / DINT is UDINT: 10 / 4294967295 = 0 *)
R3 := W + I;              (* UINT + INT is UINT: 3 + 65535 wraps to 2 *)
R4 := I * W;              (* UINT: -3 is 65533 *)
R5 := S + W;              (* UINT (rank 2 over rank 1): 1 *)
R6 := UZ MOD M1;          (* UDINT: 10 MOD 4294967295 = 10 *)
R7 := M1 - UZ;            (* UDINT: -11 is 4294967285 *)
"""
RANKED_NJ = {"R1": 0, "R2": 0, "R3": 2, "R4": 65533, "R5": 1, "R6": 10, "R7": 4294967285}
# IEC 61131-3: the narrowest type both widen to (UDINT and DINT: LINT; UINT and INT: DINT).
RANKED_IEC = {"R1": 2147483648, "R2": -10, "R3": 2, "R4": -3, "R5": 1, "R6": 0, "R7": -11}


@pytest.mark.parametrize("dialect, expected", [("nj", RANKED_NJ), ("iec", RANKED_IEC)])
@pytest.mark.parametrize("operands", ["VAR", "VAR CONSTANT"])
def test_mixed_signed_and_unsigned_integers_take_the_dialects_type(dialect, expected, operands, monkeypatch):
    src = (f"PROGRAM Main\nVAR R1, R2, R3, R4, R5, R6, R7 : LINT; END_VAR\n{operands}\n{RANKED_OPERANDS}\n"
           f"END_VAR\n{RANKED_BODY}\nEND_PROGRAM\n")
    main = run_once(src, dialect)
    assert {name: main[name] for name in expected} == expected


def test_ulint_and_lint_meet_in_ulint_on_the_nj_only():
    src = "PROGRAM Main\nVAR UL : ULINT := 5; L : LINT := -1; R : ULINT; END_VAR\nR := UL + L;\nEND_PROGRAM\n"
    plc = load_text(src, "main.st", dialect="nj").controller()
    main = plc.add_program("Main")
    plc.run(1)
    assert main["R"] == 4
    with pytest.raises(Exception, match="E-TYPE-002"):
        load_text(src, "main.st", dialect="iec")
