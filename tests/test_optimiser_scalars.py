"""`scalars` (st_runtime/compiler/optimise/scalars.py): a fast FUNCTION's in-out elements in locals.

Each program runs with the pass on and off: the same results, faults (code, POU, line, column,
scan), arrays and NJ time per scan, and the values by hand.  The cases a wrong rewrite gets
wrong: an in-out passed twice (a store through one name read through the other), a read and a
store at a data index between literal ones, a fault (F-DIV-ZERO, F-INDEX) after elements
were stored (the scan stops there with stop_on_fault: the caller's array must hold what the
exact code stored), a row exchange at a data index inside an IF.
"""

from __future__ import annotations

from dataclasses import replace

import pytest

from st_runtime.api import load_text
from st_runtime.compiler import Optimisations, compile_program
from st_runtime.compiler.optimise import scalars

from optimiser_helpers import run_main

ON = Optimisations()
OFF = replace(ON, scalars=False)

# Mix adds B (which may be A: Main passes X twice when Alias) into A at literal indices, then
# divides an integer by Den (F-DIV-ZERO at line 14 when 0) and reads and stores A at the data
# index I (F-INDEX at lines 15, 16 and 17 when I = 7).
MIX = """
FUNCTION Mix : DINT
VAR_INPUT I, Den : DINT; END_VAR
VAR_IN_OUT A : ARRAY[1..4] OF LREAL; B : ARRAY[1..4] OF LREAL; END_VAR
VAR K, J : INT; T : LREAL; N : DINT := 12; END_VAR
FOR K := 1 TO 4 DO
    A[K] := A[K] + 10.0;
END_FOR;
FOR K := 1 TO 4 DO
    FOR J := 1 TO 4 DO
        A[K] := A[K] + B[J];
    END_FOR;
END_FOR;
N := N / Den;
T := A[I];
A[I] := A[1] * 2.0;
A[2] := A[2] + A[I];
A[4] := A[4] + T;
FOR K := 1 TO 3 DO
    A[K] := A[K] - A[K + 1];
END_FOR;
Mix := N;
END_FUNCTION

PROGRAM Main
VAR
    X : ARRAY[1..4] OF LREAL := [1.0, 2.0, 3.0, 4.0];
    Y : ARRAY[1..4] OF LREAL := [1.0, 1.0, 1.0, 1.0];
    I : DINT := 2;
    Den : DINT := 1;
    Alias : BOOL;
    R : DINT;
END_VAR
IF Alias THEN
    R := Mix(I := I, Den := Den, A := X, B := X);
ELSE
    R := Mix(I := I, Den := Den, A := X, B := Y);
END_IF;
END_PROGRAM
"""

# Swap doubles row 1, exchanges rows 1 and P inside an IF (P = 3 is out of range: F-INDEX
# at lines 10 and 11 for each column), takes row 2 from row 1, adds 1 and halves.
SWAP = """
FUNCTION Swap : BOOL
VAR_INPUT P : INT; END_VAR
VAR_IN_OUT M : ARRAY[1..2, 1..4] OF LREAL; END_VAR
VAR R, C : INT; H : LREAL; END_VAR
FOR C := 1 TO 4 DO M[1, C] := M[1, C] * 2.0; END_FOR;
IF P <> 1 THEN
    FOR C := 1 TO 4 DO
        H := M[1, C];
        M[1, C] := M[P, C];
        M[P, C] := H;
    END_FOR;
END_IF;
FOR C := 1 TO 4 DO M[1, C] := M[1, C] - M[2, C]; END_FOR;
FOR R := 1 TO 2 DO
    FOR C := 1 TO 4 DO M[R, C] := M[R, C] + 1.0; END_FOR;
END_FOR;
FOR R := 1 TO 2 DO
    FOR C := 1 TO 4 DO M[R, C] := M[R, C] * 0.5; END_FOR;
END_FOR;
Swap := TRUE;
END_FUNCTION

PROGRAM Main
VAR
    X : ARRAY[1..2, 1..4] OF LREAL := [1.0, 2.0, 3.0, 4.0, 10.0, 20.0, 30.0, 40.0];
    P : INT := 2;
    R : BOOL;
END_VAR
R := Swap(P := P, M := X);
END_PROGRAM
"""


def _run(source: str, optimise: Optimisations, inputs: dict, stop: bool = False, dialect: str = "iec"):
    (x, r), faults, times = run_main(source, optimise, inputs, ("X", "R"), stop, dialect)
    return x, r, faults, times


def _same(source: str, inputs: dict, stop: bool = False, dialect: str = "iec"):
    on, off = _run(source, ON, inputs, stop, dialect), _run(source, OFF, inputs, stop, dialect)
    assert on == off
    return on


@pytest.mark.parametrize("name, source, local", [("MIX", MIX, "v_A_e0"), ("SWAP", SWAP, "v_M_e0")])
def test_the_fast_copy_keeps_the_in_out_in_locals(name, source, local):
    """The pass applies to both (what the other tests run is the rewritten code); off, no local."""
    program = load_text(source, "t.st").program
    fast = compile_program(program, optimise=ON).python_sources[name].split("\n        else:\n", 1)[0]
    assert local in fast and "_type(" in fast
    assert local not in compile_program(program, optimise=OFF).python_sources[name]


def test_an_in_out_passed_once():
    # by hand: X + 10 = [11, 12, 13, 14], + 4 (Y's sum) each = [15, 16, 17, 18]; T = 16;
    # A[2] := 30, then 30 + 30; A[4] := 18 + 16; then A[K] - A[K + 1] for K = 1..3
    x, r, faults, _ = _same(MIX, {})
    assert (x, r, faults) == ([-45.0, 43.0, -17.0, 34.0], 12, [])


def test_an_in_out_passed_twice_is_read_through_the_other_name():
    # by hand, B is A: after + 10, A[1] = 11 + 11 + 12 + 13 + 14 = 61; A[2] = 12 + 61 + 73
    # + 13 + 14 = 173; A[3] = 13 + 61 + 173 + 247 + 14 = 508; A[4] = 14 + 61 + 173 + 508 + 756
    # = 1512; T = 173; A[2] := 122, then 244; A[4] := 1685; then the differences
    x, r, faults, _ = _same(MIX, {"Alias": True})
    assert (x, r, faults) == ([-183.0, -264.0, -1177.0, 1685.0], 12, [])


def test_faults_at_a_data_index_land_on_their_statements():
    # I = 7: lines 15, 16 and 17 fault and store nothing (T stays 0.0)
    x, r, faults, _ = _same(MIX, {"I": 7})
    assert x == [-1.0, -1.0, -1.0, 18.0] and r == 12
    assert [(f[0], f[2]) for f in faults] == [("F-INDEX", 15), ("F-INDEX", 16), ("F-INDEX", 17)]


@pytest.mark.parametrize("inputs, line", [({"Den": 0}, 14), ({"I": 7}, 15)])
def test_a_fault_that_ends_the_scan_sees_every_element_stored_before_it(inputs, line):
    # the scan stops at the fault: X holds what lines 6-13 stored, [15, 16, 17, 18]
    x, r, faults, _ = _same(MIX, inputs, stop=True)
    assert x == [15.0, 16.0, 17.0, 18.0] and r == 0
    assert [(f[1], f[2]) for f in faults] == [("Mix", line)]


@pytest.mark.parametrize("p, x", [
    # rows exchanged: [8, 16, 24, 32] and [2, 4, 6, 8] after row 1 - row 2; (x + 1) / 2
    (2, [[4.5, 8.5, 12.5, 16.5], [1.5, 2.5, 3.5, 4.5]]),
    # no exchange: [-8, -16, -24, -32] and [10, 20, 30, 40]; (x + 1) / 2
    (1, [[-3.5, -7.5, -11.5, -15.5], [5.5, 10.5, 15.5, 20.5]]),
])
def test_a_row_exchange_at_a_data_index(p, x):
    assert _same(SWAP, {"P": p})[:3] == (x, True, [])


def test_a_row_exchange_out_of_range_faults_at_each_column():
    # P = 3: M[1, C] := M[3, C] (line 10) and M[3, C] := H (line 11) fault for each C; row 1
    # stays doubled: as P = 1
    x, r, faults, _ = _same(SWAP, {"P": 3})
    assert x == [[-3.5, -7.5, -11.5, -15.5], [5.5, 10.5, 15.5, 20.5]]
    assert [(f[0], f[2]) for f in faults] == [("F-INDEX", 10), ("F-INDEX", 11)] * 4


# The rewrite on lines written by hand (the compiler's shapes): what it must and must not do.

def _rewrite(lines: list[str], others=()) -> list[str]:
    return scalars._Rewrite("v_A", 2, tuple(others)).whole(lines)


def test_a_branch_that_stores_at_a_data_index_leaves_the_locals_stale():
    lines = ["v_A[0] = (v_A[0] + 1.0)",
             "if (v_P != 1):",
             "    v_A[v_P - 1] = v_A[1]",
             "v_A[1] = (v_A[1] * 2.0)"]
    assert _rewrite(lines) == [
        "v_A_e0, v_A_e1 = v_A",
        "v_A_e0 = (v_A_e0 + 1.0)",
        "if (v_P != 1):",
        "    v_A[0] = v_A_e0",          # written back before the store at a data index
        "    v_A[v_P - 1] = v_A_e1",
        "    v_A_e0, v_A_e1 = v_A",     # held on the other path: loaded again on this one
        "v_A_e1 = (v_A_e1 * 2.0)",
        "v_A[0] = v_A_e0",              # the end: both written back
        "v_A[1] = v_A_e1"]


def test_a_fault_handler_writes_back_before_the_fault_is_recorded():
    lines = ["v_A[0] = (v_A[0] + 1.0)",
             "try:",
             "    v_A[1] = (v_A[1] / _t1 if (_t1 := v_D) else _rdiv(v_A[1], _t1))",
             "except _FAULTS as _e:",
             "    _ctx.fault(_e, ('F', 'f.st', 3, 1))",
             "return (v_F, v_A[1])"]
    out = _rewrite(lines)
    handler = out.index("except _FAULTS as _e:")
    assert out[handler + 1] == "    v_A[0] = v_A_e0"
    assert out[handler + 2].strip().startswith("_ctx.fault(")
    assert out[-3:] == ["v_A[0] = v_A_e0", "v_A[1] = v_A_e1", "return (v_F, v_A_e1)"]


def test_a_list_that_may_be_the_same_is_read_after_a_write_back():
    lines = ["v_A[0] = 1.0", "v_A[1] = 2.0", "v_X = v_B[0]"]
    assert _rewrite(lines, others=["v_B"]) == [
        "v_A_e0 = 1.0", "v_A_e1 = 2.0", "v_A[0] = v_A_e0", "v_A[1] = v_A_e1", "v_X = v_B[0]"]


def test_an_else_of_a_loop_leaves_the_lines_as_they_were():
    lines = ["v_A[0] = 1.0", "for v_I in range(2):", "    v_X = v_A[v_I]", "else:", "    v_X = 0.0"]
    with pytest.raises(scalars._Unknown):
        _rewrite(lines)


def test_a_body_that_calls_st_code_keeps_its_lists():
    """A callee could reach the caller's list through a global: no element in a local."""
    source = MIX.replace("N := N / Den;", "N := Half(N);") + """
FUNCTION Half : DINT
VAR_INPUT N : DINT; END_VAR
Half := N / 2;
END_FUNCTION
"""
    fast = compile_program(load_text(source, "t.st").program, optimise=ON).python_sources["MIX"]
    assert "_type(v_A) is _list" in fast and "v_A_e0" not in fast
    x, r, faults, _ = _same(source, {})
    assert (x, r, faults) == ([-45.0, 43.0, -17.0, 34.0], 6, [])


def test_a_list_named_in_a_string_is_left_as_it_is():
    lines = ["v_A[0] = 1.0"] * 20 + ["v_S = 'v_A[0]'"]
    kept = list(lines)
    scalars.replace(lines, 0, {"v_A": (2, ())})
    assert lines == kept
    plain = lines[:20]
    scalars.replace(plain, 0, {"v_A": (2, ())})
    assert plain == ["v_A_e0 = 1.0"] * 20 + ["v_A[0] = v_A_e0"]


def test_a_line_that_hands_on_the_context_sees_the_list_written_back():
    """Code given `_ctx` may record a fault that ends the scan: the list is up to date first;
    and it may reach the list (a global the caller passed): it is loaded again after."""
    lines = ["v_A[0] = 1.0", "v_X = _std(_ctx, v_Y)", "v_A[1] = v_A[0]"]
    assert _rewrite(lines) == ["v_A_e0 = 1.0", "v_A[0] = v_A_e0", "v_X = _std(_ctx, v_Y)",
                               "v_A_e0, v_A_e1 = v_A", "v_A_e1 = v_A_e0", "v_A[1] = v_A_e1"]


def test_a_loop_inside_a_try_is_not_followed():
    """A fault inside the loop (after it stored v_A[0]) must not see v_A_e0 written back over
    that store: the handler cannot know which, so the lines stay as they were."""
    lines = ["v_A[0] = 1.0",
             "try:",
             "    for v_I in range(2):",
             "        v_A[v_I] = 2.0",
             "except _FAULTS as _e:",
             "    _ctx.fault(_e, ('F', 'f.st', 3, 1))",
             "v_X = v_A[0]"]
    with pytest.raises(scalars._Unknown):
        _rewrite(lines)


# Session 19: rows for the survivors of a sample of the pass's mutants (docs/mutation.md).

def _executed(lines: list[str], v_A: list, **names) -> dict:
    """Run `lines` as Python with the list `v_A` (a copy) and `names`: every variable after."""
    env = dict(names, v_A=list(v_A))
    exec("\n".join(lines), {}, env)
    return {k: v for k, v in env.items() if not k.startswith("v_A_e")}


def test_a_list_of_one_element_is_unpacked_as_one():
    """`v_A_e0, = v_A` (a one-element unpack), not `v_A_e0 = v_A` (the list itself)."""
    lines = ["v_A[0] = (v_A[0] + 1.0)"] * 3 + ["v_X = v_A[0]"]
    out = scalars._Rewrite("v_A", 1, ()).whole(lines)
    assert out[0] == "v_A_e0, = v_A"
    assert _executed(out, [2.0]) == _executed(lines, [2.0]) == {"v_A": [5.0], "v_X": 5.0}


def test_a_read_after_a_store_at_a_data_index_in_a_branch_reads_the_list():
    lines = ["v_A[0] = 1.0", "if (v_P != 1):", "    v_A[v_P - 1] = 3.0", "    v_X = v_A[1]",
             "v_Y = v_A[0]"]
    out = _rewrite(lines)
    assert "    v_X = v_A[1]" in out
    for p, x in ((2, 3.0), (1, 0.0)):
        # by hand: P = 2 stores 3.0 into A[1], which X reads; P = 1 leaves X as it was (0.0)
        assert _executed(out, [0.0, 0.0], v_P=p, v_X=0.0) == _executed(lines, [0.0, 0.0], v_P=p, v_X=0.0)
        assert _executed(out, [0.0, 0.0], v_P=p, v_X=0.0)["v_X"] == x


def test_a_loop_keeps_its_text_with_the_elements_written_back_before_and_loaded_after():
    lines = ["v_A[0] = 1.0", "for v_I in range(2):", "    v_X = v_A[v_I]", "v_A[1] = v_A[0]"]
    assert _rewrite(lines) == [
        "v_A_e0 = 1.0", "v_A[0] = v_A_e0",                   # written back before the loop
        "for v_I in range(2):", "    v_X = v_A[v_I]",
        "v_A_e0, v_A_e1 = v_A",                               # stale after it: loaded again
        "v_A_e1 = v_A_e0", "v_A[1] = v_A_e1"]


@pytest.mark.parametrize("p", [1, 2])
def test_an_if_with_an_else_is_followed_clause_by_clause(p):
    lines = ["v_A[0] = 1.0", "if (v_P != 1):", "    v_A[1] = 2.0", "else:", "    v_A[1] = 3.0",
             "v_X = v_A[1]"]
    out = _rewrite(lines)                   # (a chain cut at its `else:` is not followed)
    assert out[0] == "v_A_e0 = 1.0" and "else:" in out
    expected = {"v_A": [1.0, 3.0 if p == 1 else 2.0], "v_X": 3.0 if p == 1 else 2.0, "v_P": p}
    assert _executed(out, [0.0, 0.0], v_P=p) == _executed(lines, [0.0, 0.0], v_P=p) == expected


@pytest.mark.parametrize("accesses, kept_in_locals", [(scalars.MIN_ACCESSES, True),
                                                      (scalars.MIN_ACCESSES - 1, False)])
def test_a_list_needs_min_accesses_literal_accesses(accesses, kept_in_locals):
    lines = ["v_A[0] = 1.0"] * accesses
    scalars.replace(lines, 0, {"v_A": (2, ())})
    assert (lines[0] == "v_A_e0 = 1.0") is kept_in_locals


def test_a_body_that_dereferences_a_pointer_keeps_its_lists():
    """A pointer may reach the in-out (`P := ADR(A)`): a store through it must be seen by
    the next read of A, so no element is kept in a local (CODESYS: POINTER TO)."""
    source = MIX.replace("VAR K, J : INT;", "VAR P : POINTER TO ARRAY[1..4] OF LREAL; K, J : INT;").replace(
        "N := N / Den;", "N := N / Den; P := ADR(A); P^[1] := 100.0;")
    program = load_text(source, "t.st", dialect="codesys").program
    fast = compile_program(program, optimise=ON).python_sources["MIX"]
    assert "_type(v_A) is _list" in fast and "v_A_e0" not in fast
    # by hand: A = [15, 16, 17, 18] after line 13, A[1] := 100; T = A[2] = 16; A[2] := 200,
    # then 400; A[4] := 34; then A[K] - A[K + 1]: [100 - 400, 400 - 17, 17 - 34, 34]
    x, r, faults, _ = _same(source, {}, dialect="codesys")
    assert (x, r, faults) == ([-300.0, 383.0, -17.0, 34.0], 12, [])


def test_a_branch_that_does_not_touch_the_list_adds_no_line():
    """The element stays dirty in its local through both clauses: nothing is written back
    at their ends, only at the end of the copy."""
    lines = ["v_A[0] = 1.0", "if (v_P != 1):", "    v_X = 1.0", "else:", "    v_X = 2.0", "v_Y = v_A[0]"]
    assert _rewrite(lines) == ["v_A_e0 = 1.0", "if (v_P != 1):", "    v_X = 1.0", "else:", "    v_X = 2.0",
                               "v_Y = v_A_e0", "v_A[0] = v_A_e0"]


@pytest.mark.parametrize("lines", [
    pytest.param(["v_A[0] = 1.0", "v_X = _f(1.0,", "         v_A[1])"], id="a_statement_on_two_lines"),
    pytest.param(["v_A[0] = 1.0", "finally:"], id="a_clause_without_its_statement"),
])
def test_lines_the_pass_does_not_know_are_left_as_they_were(lines):
    with pytest.raises(scalars._Unknown):
        _rewrite(lines)
