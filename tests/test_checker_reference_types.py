"""A reference type is one type wherever it is written (IEC 61131-3 3rd ed. 6.4.4.10,
`REF_TO`): a VAR_IN_OUT of REF_TO INT binds a variable of REF_TO INT (passed by reference,
without conversion, 6.5.2.2), and a VAR_EXTERNAL REF_TO INT matches its VAR_GLOBAL.  Before
session 20 both were refused ("expected REF_TO INT, found REF_TO INT"): `same_type` knew no
reference types.  Values by hand in each test."""

from __future__ import annotations

import pytest

from checker_helpers import diagnostics
from st_runtime.api import load_text

REBIND = """
FUNCTION_BLOCK Rebind
VAR_IN_OUT r : REF_TO INT; END_VAR
VAR_INPUT dst : REF_TO INT; END_VAR
r := dst;                 (* the caller's reference now refers to dst's target *)
r^ := r^ + 1;
END_FUNCTION_BLOCK
PROGRAM Main
VAR a, b : INT; ra : REF_TO INT; f : Rebind; END_VAR
ra := REF(a);
f(r := ra, dst := REF(b));
ra^ := ra^ + 10;          (* ra refers to b after the call *)
END_PROGRAM
"""

EXTERNAL = """
VAR_GLOBAL G : REF_TO INT; Target : INT; END_VAR
PROGRAM Main
VAR_EXTERNAL G : REF_TO INT; Target : INT; END_VAR
G := REF(Target);
G^ := 5;
END_PROGRAM
"""


def _run_main(text: str):
    """(Main, the globals) after one scan."""
    plc = load_text(text).controller(period="1ms")
    main = plc.add_program("Main")
    plc.run(1)
    assert plc.faults == []
    return main, plc.globals


def test_an_in_out_reference_is_bound_and_rebinds_the_callers_reference():
    assert diagnostics(REBIND) == []
    main, _ = _run_main(REBIND)
    # a untouched; b: 0 + 1 in the FB through r, then + 10 through ra, which refers to b.
    assert (main["a"], main["b"]) == (0, 11)


def test_an_external_reference_matches_its_global():
    assert diagnostics(EXTERNAL) == []
    assert _run_main(EXTERNAL)[1]["Target"] == 5


@pytest.mark.parametrize("text, expected", [
    (REBIND.replace("ra : REF_TO INT;", "ra : REF_TO DINT;").replace("a, b : INT;", "a, b : DINT;")
           .replace("dst := REF(b)", "dst := NULL"),
     [("E-CALL-011", 11, 8, "VAR_IN_OUT 'r' of Rebind: expected a variable of type REF_TO INT, found "
                            "REF_TO DINT (in-out parameters are passed by reference, without conversion)")]),
    (EXTERNAL.replace("VAR_EXTERNAL G : REF_TO INT;", "VAR_EXTERNAL G : REF_TO DINT;"),
     [("E-DECL-010", 4, 14, "VAR_EXTERNAL 'G': declared REF_TO DINT here, but the VAR_GLOBAL is REF_TO INT")]),
])
def test_a_reference_to_another_type_is_still_refused(text, expected):
    found = [d for d in diagnostics(text) if d[0] in ("E-CALL-011", "E-DECL-010")]
    assert found == expected


def test_a_pointer_and_a_reference_of_one_target_stay_two_types():
    """codesys: POINTER TO INT and REF_TO INT are declared apart (a pointer is dereferenced
    and compared as an address); an in-out of one does not bind the other."""
    text = REBIND.replace("ra : REF_TO INT;", "ra : POINTER TO INT;").replace("ra := REF(a);", "ra := ADR(a);")
    found = [d[:3] for d in diagnostics(text, "codesys") if d[0] == "E-CALL-011"]
    assert found == [("E-CALL-011", 11, 8)]
