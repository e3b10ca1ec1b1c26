"""Assignment casts of the NJ beyond IEC's widening (W501 6-5-3, p. 6-107).

"SINT->USINT->UINT->UDINT->ULINT are all connected, so you can write an
assignment such as ULINT:=SINT", and "intVar := -1; uintVar := intVar;
(* uintVar := 16#FFFF *)": a signed integer goes into an unsigned one of the
same or a larger size with its bits kept (two's complement).  IEC 61131-3
has no such implicit conversion: under `iec` each is E-TYPE-004.  Expected
values by hand: -1 in 16 bits is 16#FFFF = 65535; SINT -2 in ULINT,
sign-extended as SINT_TO_ULINT does, is 2**64 - 2.
"""

from __future__ import annotations

import pytest

from st_runtime.api import LoadError, load_text

SOURCE = """PROGRAM Main
VAR I : INT := -1; S : SINT := -2; D : DINT := -3; L : LINT := -4;
    U : UINT; US : USINT; UL : ULINT; UD : UDINT; ULL : ULINT; END_VAR
U := I;
US := S;
UL := S;
UD := D;
ULL := L;
END_PROGRAM
"""


def test_signed_into_unsigned_keeps_the_bits_on_the_nj():
    plc = load_text(SOURCE, "main.st", dialect="nj").controller()
    main = plc.add_program("Main")
    plc.run(1)
    assert (main["U"], main["US"], main["UL"], main["UD"], main["ULL"]) == \
        (0xFFFF, 0xFE, 2**64 - 2, 2**32 - 3, 2**64 - 4)


def test_iec_needs_an_explicit_conversion():
    with pytest.raises(LoadError) as caught:
        load_text(SOURCE, "main.st", dialect="iec")
    codes = [d.code for d in caught.value.diagnostics]
    assert codes.count("E-TYPE-004") == 5


@pytest.mark.parametrize("assignment", ["I := U;", "S := I;", "US := I;", "D := UL;"])
def test_the_nj_still_refuses_what_the_text_does_not_show(assignment):
    # unsigned into signed and narrowing: not among the casts the manual's text shows
    src = SOURCE.replace("U := I;", assignment)
    with pytest.raises(LoadError) as caught:
        load_text(src, "main.st", dialect="nj")
    assert [d.code for d in caught.value.diagnostics] == ["E-TYPE-004"]
