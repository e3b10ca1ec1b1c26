"""The unguard pass (optimise/unguard.py): which statements lose their `try`, and that
the ones that keep it fault at the same line, scan after scan, with the pass on and off."""

from __future__ import annotations

from st_runtime import loader
from st_runtime.compiler import Optimisations, compile_program

from test_optimiser_equivalence import run_both

SOURCE = """\
PROGRAM MAIN
VAR
    T : LINT;
    A : DINT := 7;
    B : DINT;
    F : BOOL;
    R : LREAL := 1.5;
    Q AT %QW0 : INT;
    ARR : ARRAY[0..3] OF DINT;
    I : DINT := 5;
    N : DINT;
END_VAR
T := 93784005006007;
B := -A;
F := A > 3 AND NOT (R < 0.5) OR FALSE;
R := R * 2.0 - R;
N := A / B;
ARR[I] := 1;
Q := 3;
B := 0;
N := N + A / B;
I := I + 1;
G := 1;
END_PROGRAM
VAR_GLOBAL
    G : DINT;
END_VAR
"""
FAULT_FREE = ["self.v_T = 93784005006007", "v_B = (_t1 if -2147483648 <= (_t1 := (-v_A))", "self.v_F = (((",
              "v_R = ((v_R * 2.0) - v_R)", "v_B = 0", "self.v_I = (_t1 if -2147483648 <= (_t1 := (self.v_I + 1))"]
MAY_FAULT = ["_idiv(", "_index_fault(", "self.v_Q = 3", "v_G = 1"]


def _program(tmp_path):
    path = tmp_path / "main.st"
    path.write_text(SOURCE)
    result = loader.load([str(path)])
    assert result.program is not None
    return result.program


def _guarded(source: str, fragment: str) -> bool:
    """Whether the line holding `fragment` sits in a `try:` whose handler is `except _FAULTS`."""
    lines = source.splitlines()
    index = next(i for i, line in enumerate(lines) if fragment in line)
    indent = _depth(lines[index])
    opener = next(i for i in range(index - 1, -1, -1) if _depth(lines[i]) < indent)
    if lines[opener].strip() != "try:":
        return False
    after = next(line for line in lines[index:] if _depth(line) <= _depth(lines[opener]))
    return after.strip().startswith("except _FAULTS")


def _depth(line: str) -> int:
    return len(line) - len(line.lstrip())


def test_fault_free_stores_lose_their_try_and_the_rest_keep_it(tmp_path):
    source = compile_program(_program(tmp_path), optimise=Optimisations()).python_sources["MAIN"]
    for fragment in FAULT_FREE:
        assert not _guarded(source, fragment), fragment
    for fragment in MAY_FAULT:            # division, index check, process image, global
        assert _guarded(source, fragment), fragment
    without = compile_program(_program(tmp_path), optimise=Optimisations.none()).python_sources["MAIN"]
    for fragment in ("self.v_T = 93784005006007", "v_B = 0"):
        assert _guarded(without, fragment), fragment


def test_guarded_statements_fault_at_the_same_line_and_the_scan_goes_on(tmp_path):
    off, on = run_both(_program(tmp_path), 2, budget_ns=10_000_000)
    assert on == off
    faults = [(code, line, scan) for code, _, line, _, scan in on[0]]
    # Line 17: 7 / -7 is fine; line 18: ARR[5] is out of 0..3; line 21: N + 7 / 0.
    # I goes 5 -> 6, so scan 2 indexes out of range again.
    assert [(code, line) for code, line, _ in faults] == [("F-INDEX", 18), ("F-DIV-ZERO", 21)] * 2
    assert [scan for *_, scan in faults] == [faults[0][2]] * 2 + [faults[0][2] + 1] * 2


LONG_CHAIN = """\
FUNCTION F : LREAL
VAR_INPUT X : LREAL; END_VAR
VAR A : LINT := 9223372036854775807; R : LREAL; END_VAR
R := {chain} * X;
F := 2.5;
END_FUNCTION
PROGRAM MAIN
VAR Y : LREAL; END_VAR
Y := F(1.0);
END_PROGRAM
"""


def test_a_long_integer_product_meeting_a_real_keeps_its_guard(tmp_path):
    # (2**63 - 1)**20 is about 2**1260: beyond 2**1024, Python cannot convert it to a
    # float (OverflowError, F-MATH).  With the guard the fault lands on line 4 in F and
    # F goes on (F := 2.5, so Y = 2.5); without it, it would land on the call, line 9.
    path = tmp_path / "main.st"
    path.write_text(LONG_CHAIN.format(chain=" * ".join(["A"] * 20)))
    result = loader.load([str(path)])
    off, on = run_both(result.program, 1)
    assert on == off
    assert [(code, line) for code, _, line, _, _ in on[0]] == [("F-MATH", 4)]
    main = dict(on[1][0][1])["MAIN"]              # (class name, (slot, value), ...)
    assert dict(main[1:])["v_Y"] == ("f", (2.5).hex())


ELEMENTS = """\
FUNCTION_BLOCK Store
VAR_IN_OUT Shared : ARRAY[1..3] OF LREAL; END_VAR
VAR
    Own : ARRAY[1..3] OF LREAL;
    Counts : ARRAY[0..2] OF INT;
    Scaled : ARRAY[1..2] OF REAL;
    X : LREAL := 2.5;
    N : INT := 7;
    Y : REAL := 1.5;
END_VAR
Own[2] := X * X - 1.0;
Counts[1] := N + 1;
Shared[1] := X;
Own[3] := Shared[2];
Scaled[1] := Y * Y;
Own[1] := X / 2.0;
END_FUNCTION_BLOCK
"""


def test_element_stores_at_literal_indices_of_owned_arrays_lose_their_try():
    """`Own[2] := X * X - 1.0` and `Counts[1] := N + 1` (the INT wrap is arithmetic) store
    into the FB's own lists at indices in range: no `try`.  An in-out (a NullRef when
    unconnected), a read of one, a REAL store (a call rounds it) and a division keep it."""
    from st_runtime.api import load_text

    program = load_text(ELEMENTS, "elements.st").program
    source = compile_program(program, optimise=Optimisations()).python_sources["STORE"]
    for fragment in ("v_OWN[1] = ", "v_COUNTS[1] = "):
        assert not _guarded(source, fragment), fragment
    for fragment in ("v_SHARED[0] = ", "v_OWN[2] = ", "v_SCALED[0] = ", "v_OWN[0] = "):
        assert _guarded(source, fragment), fragment
    without = compile_program(program, optimise=Optimisations.none()).python_sources["STORE"]
    assert _guarded(without, "v_OWN[1] = ")
    from test_optimiser_equivalence import _Context

    outcomes = []
    for optimise in (Optimisations.none(), Optimisations()):
        compiled = compile_program(program, optimise=optimise)
        fb, context = compiled.new("Store"), _Context()
        type(fb).execute(fb, context)          # Shared unconnected: its store and read fault
        outcomes.append((context.faults, fb.v_OWN, fb.v_COUNTS, fb.v_SCALED))
    assert outcomes[0] == outcomes[1]
    assert [f[1] for f in outcomes[0][0]] == ["F-NULL-REF", "F-NULL-REF"]
    assert outcomes[0][1:3] == ([1.25, 5.25, 0.0], [0, 8, 0])     # 2.5 * 2.5 - 1.0; 7 + 1


INSTANCE_COPIES = """
FUNCTION_BLOCK Source
VAR_INPUT Scale : LREAL; END_VAR
VAR_OUTPUT Out : ARRAY[1..3] OF LREAL; Flags : ARRAY[1..3] OF BOOL; END_VAR
Out[1] := Scale; Out[2] := Scale * 2.0; Out[3] := Scale * 3.0;
Flags[2] := Scale > 1.0;
END_FUNCTION_BLOCK
FUNCTION_BLOCK Copier
VAR_IN_OUT Lent : Source; END_VAR
VAR Own : Source; Values : ARRAY[1..3] OF LREAL; Kept : ARRAY[1..3] OF BOOL; Borrowed : ARRAY[1..3] OF LREAL;
    Ref : REF_TO Source; Via : ARRAY[1..3] OF LREAL; END_VAR
Own(Scale := 1.5);
Values := Own.Out;          (* the own instance's output arrays: no guard *)
Kept := Own.Flags;
Borrowed := Lent.Out;       (* an in-out instance, unconnected: F-NULL-REF *)
Via := Ref^.Out;            (* through a NULL reference: F-NULL-REF *)
END_FUNCTION_BLOCK
"""


def test_copies_of_an_own_instances_arrays_lose_their_try():
    """`Values := Own.Out` copies a list of the FB's own instance into its own list: no `try`.
    The same copy from an in-out instance (a NullRef when unconnected) or through a
    reference keeps it, and faults at its line with the passes on and off."""
    from st_runtime.api import load_text
    from test_optimiser_equivalence import _Context

    program = load_text(INSTANCE_COPIES, "copies.st").program
    source = compile_program(program, optimise=Optimisations()).python_sources["COPIER"]
    for fragment in ("v_VALUES[_WHOLE] = v_OWN.v_OUT", "v_KEPT[_WHOLE] = v_OWN.v_FLAGS"):
        assert not _guarded(source, fragment), fragment
    for fragment in ("v_BORROWED[_WHOLE] = ", "v_VIA[_WHOLE] = "):
        assert _guarded(source, fragment), fragment
    outcomes = []
    for optimise in (Optimisations.none(), Optimisations()):
        fb, context = compile_program(program, optimise=optimise).new("Copier"), _Context()
        type(fb).execute(fb, context)
        outcomes.append((context.faults, context.budget, fb.v_VALUES, fb.v_KEPT, fb.v_BORROWED, fb.v_VIA))
    assert outcomes[0] == outcomes[1]
    assert [(code, where[2]) for _, code, where in outcomes[0][0]] == [("F-NULL-REF", 15), ("F-NULL-REF", 16)]
    assert outcomes[0][2:] == ([1.5, 3.0, 4.5], [False, True, False], [0.0] * 3, [0.0] * 3)  # 1.5 x 1, 2, 3
