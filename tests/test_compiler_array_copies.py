"""`A := B` of arrays of elementary elements: a copy in place through the namespace's one
slice (`target[_WHOLE] = source`, calls.copy_statement), not a slice built at every copy.

The values are IEC 61131-3's (an assignment of an array copies its elements: a later change
of the source leaves the target as it was), worked out by hand below."""

from __future__ import annotations

import dis

import pytest

from optimiser_helpers import run_main
from st_runtime import api
from st_runtime.compiler import Optimisations, compile_program

COPIES = """
VAR_GLOBAL G : ARRAY[1..3] OF LREAL := [1.5, 2.5, 3.5]; END_VAR
FUNCTION_BLOCK Mirror
VAR_INPUT In : ARRAY[0..2] OF DINT; END_VAR
VAR_OUTPUT Out : ARRAY[0..2] OF DINT; END_VAR
VAR_IN_OUT Io : ARRAY[1..3] OF LREAL; END_VAR
Out := In;                      (* an FB's own arrays *)
Io := G;                        (* a global into an in-out *)
END_FUNCTION_BLOCK
PROGRAM Main
VAR
  A, B, Z : ARRAY[1..3] OF LREAL; X, Y : ARRAY[0..2] OF DINT; M : Mirror;
  B1, B2, B3, Z1, Z2, Z3 : LREAL; Y0, Y1, Y2, In1 : DINT;
END_VAR
A[1] := 1.0; A[2] := 2.0; A[3] := 3.0;
B := A;
A[2] := 20.0;                   (* B keeps 2.0: B holds a copy *)
X[0] := 7; X[1] := 8; X[2] := 9;
M(In := X, Io := Z, Out => Y);  (* the input, the in-out and the output copied *)
X[1] := 80;                     (* M.In and Y keep 8 *)
B1 := B[1]; B2 := B[2]; B3 := B[3];
Z1 := Z[1]; Z2 := Z[2]; Z3 := Z[3];
Y0 := Y[0]; Y1 := Y[1]; Y2 := Y[2]; In1 := M.In[1];
END_PROGRAM
"""

OUTPUTS = ("B1", "B2", "B3", "Z1", "Z2", "Z3", "Y0", "Y1", "Y2", "In1")
BY_HAND = (1.0, 2.0, 3.0, 1.5, 2.5, 3.5, 7, 8, 9, 8)


@pytest.mark.parametrize("optimise", [Optimisations.none(), Optimisations()], ids=["none", "all"])
def test_array_copies_copy_every_element_and_only_then(optimise):
    values, faults, _ = run_main(COPIES, optimise, {}, OUTPUTS)
    assert faults == []
    assert values == BY_HAND
    assert [type(v) for v in values] == [float] * 6 + [int] * 4


@pytest.mark.parametrize("optimise", [Optimisations.none(), Optimisations()], ids=["none", "all"])
def test_no_array_copy_builds_a_slice(optimise):
    sources = compile_program(api.load_text(COPIES).program, optimise=optimise).python_sources
    built = []
    for pou in ("MAIN", "MIRROR"):
        assert "[_WHOLE] = " in sources[pou] and "[:]" not in sources[pou]
        stack = [compile(sources[pou], pou, "exec")]
        while stack:
            code = stack.pop()
            built += [pou for op in dis.get_instructions(code) if op.opname == "BUILD_SLICE"]
            stack += [const for const in code.co_consts if hasattr(const, "co_code")]
    assert built == []


# Session 21 (h-mut-s21): an array of aggregates is copied element by element
# (`_assign_list`), not by the slice store, which would share the elements (kills
# calls.copy_statement_3).
NESTED = """
TYPE Pair : STRUCT X, Y : DINT; END_STRUCT; END_TYPE
PROGRAM Main
VAR
  A, B : ARRAY[1..2] OF Pair; M, N : ARRAY[1..2] OF ARRAY[0..1] OF DINT;
  BX, B2Y, AX, N0 : DINT;
END_VAR
A[1].X := 1; A[1].Y := 2; A[2].X := 3; A[2].Y := 4;
M[1][0] := 5; M[1][1] := 6;
B := A; N := M;
A[1].X := 10;                   (* B[1].X keeps 1: B holds copies of the elements *)
M[1][0] := 50;                  (* N[1][0] keeps 5 *)
BX := B[1].X; B2Y := B[2].Y; AX := A[1].X; N0 := N[1][0];
END_PROGRAM
"""


@pytest.mark.parametrize("optimise", [Optimisations.none(), Optimisations()], ids=["none", "all"])
def test_an_array_of_aggregates_copies_its_elements(optimise):
    values, faults, _ = run_main(NESTED, optimise, {}, ("BX", "B2Y", "AX", "N0"))
    assert faults == []
    assert values == (1, 4, 10, 5)
