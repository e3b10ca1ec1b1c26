"""Stores into subrange variables (IEC 61131-3 6.4.4.4: a value outside the limits of a
subrange is an error).

Before session 10 a constant outside the limits was stored without a word (`S := 100` into
an INT(1..5) left 100 in S, and so did `A[1] := 100` and a typed `INT#100`), and a REF of an
element or member declared with a subrange was a plain REF_TO INT, through which 100 could be
written.  Expected values: the limits themselves, by hand."""

import pytest

from st_runtime.api import LoadError, load_sources

DECLS = """TYPE S3 : STRUCT M : INT(1..5); N : INT; END_STRUCT END_TYPE
FUNCTION_BLOCK F
VAR_INPUT K : INT(1..5) := 1; END_VAR
END_FUNCTION_BLOCK
PROGRAM Main
VAR S : INT(1..5) := 1; A : ARRAY[1..2] OF INT(1..5) := [1, 1]; St : S3 := (M := 1);
    X : INT; R : REF_TO INT; RS : REF_TO INT(1..5); Fb : F; END_VAR
"""

LINE = DECLS.count("\n") + 1      # the line of the statements under test


def _load(body: str):
    return load_sources({"main.st": DECLS + body + "\nEND_PROGRAM\n"}, dialect="iec")


def _errors(body: str) -> list[tuple[str, int]]:
    with pytest.raises(LoadError) as refused:
        _load(body)
    return [(d.code, d.pos.line) for d in refused.value.diagnostics if d.is_error]


def _after_one_scan(body: str):
    plc = _load(body).controller(period="1ms")
    main = plc.add_program("Main")
    plc.run(1)
    return main, [(f.code, f.line) for f in plc.controller.faults]


@pytest.mark.parametrize("store", ["S := 100;", "A[2] := 0;", "St.M := 6;", "S := 2 + 4;", "Fb.K := 0;",
                                   "Fb(K := 6);"])
def test_a_constant_outside_the_limits_is_refused(store):
    assert _errors(store) == [("E-TYPE-005", LINE)]


@pytest.mark.parametrize("store", ["S := 5;", "A[2] := 1;", "St.M := 2 + 2;", "St.N := 100;"])
def test_a_constant_inside_the_limits_is_stored(store):
    main, faults = _after_one_scan(store)
    assert faults == []
    assert (main["S"], main["A[2]"], main["St.M"], main["St.N"]) == {
        "S := 5;": (5, 1, 1, 0), "A[2] := 1;": (1, 1, 1, 0),
        "St.M := 2 + 2;": (1, 1, 4, 0), "St.N := 100;": (1, 1, 1, 100)}[store]


@pytest.mark.parametrize("store", ["S := INT#100;", "A[1] := INT#0;", "X := 100; S := X;", "X := 0; A[1] := X;"])
def test_a_typed_constant_or_a_variable_outside_faults_and_leaves_the_value(store):
    main, faults = _after_one_scan(store)
    assert faults == [("F-SUBRANGE", LINE)]
    assert (main["S"], main["A[1]"]) == (1, 1)


@pytest.mark.parametrize("place", ["S", "A[1]", "St.M"])
def test_a_reference_to_a_subrange_place_keeps_its_limits(place):
    assert _errors(f"R := REF({place});") == [("E-TYPE-004", LINE)]
    main, faults = _after_one_scan(f"RS := REF({place}); RS^ := 4;")
    assert faults == [] and main[place] == 4
    main, faults = _after_one_scan(f"RS := REF({place}); X := 9; RS^ := X;")
    assert faults == [("F-SUBRANGE", LINE)] and main[place] == 1
    assert _errors(f"RS := REF({place}); RS^ := 9;") == [("E-TYPE-005", LINE)]


def test_a_reference_to_a_plain_member_is_a_plain_reference():
    main, faults = _after_one_scan("R := REF(St.N); R^ := 100;")
    assert faults == [] and main["St.N"] == 100
