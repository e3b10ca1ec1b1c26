"""The `wraps` pass (st_runtime/compiler/optimise/wraps.py): a store of MIN or MAX of integers
is not wrapped when their range lies inside the target's type (`SyncCalls := MIN(SyncCalls
+ 1, 2)`: at most 2).  The wrap left out would have given its operand back, so every stored
value, fault, instance state and the NJ time are equal bit for bit with the pass on and off,
under IEC's exact expressions and under the NJ's wrap inside expressions; a store whose range
may leave the type keeps its wrap.
"""

from __future__ import annotations

from dataclasses import replace

import pytest

from st_runtime import api
from st_runtime.compiler import Optimisations, compile_program
from st_runtime.controller import Controller
from test_optimiser_equivalence import compiled_lines, run_both, stopped_runs

ON = Optimisations()
WITHOUT = replace(ON, wraps=False)

SELECTIONS = """
PROGRAM Main
VAR
    Calls : INT := 32767; Low : INT := -32760; Big : DINT := 2000000000; Small : SINT := 100;
    A, B, D, G : INT; C : DINT; F : SINT; Q : INT; K : INT;
END_VAR
Calls := MIN(Calls + 1, 2);                 (* at most 2: no wrap *)
Low := MAX(Low - 1, -5);                    (* at least -5 *)
A := MIN(Calls + 1, 2, 7);
B := MAX(Small + 1, 0);                     (* SINT + 1 into INT: [0, 128] *)
C := MIN(Big + Big, 10);                    (* may be below DINT: wrapped *)
D := MIN(Calls + 32767, 32000);             (* [-1, 32000] *)
G := MAX(Calls + 32767, 0);                 (* may be above INT: wrapped *)
F := MAX(Small + 100, 0);                   (* may be above SINT: wrapped *)
Q := 7 / K;                                 (* F-DIV-ZERO every scan *)
END_PROGRAM
"""


def _program(dialect="iec"):
    return api.load_text(SELECTIONS, dialect=dialect).program


def test_only_the_stores_that_fit_lose_their_wrap():
    lines = compiled_lines(_program(), "MAIN", ON)
    plain = compiled_lines(_program(), "MAIN", WITHOUT)
    assert "v_CALLS = (2 if (_t1 := (v_CALLS + 1)) > 2 else _t1)" in lines         # calls.py: MIN of two
    assert "self.v_D = (32000 if (_t1 := (v_CALLS + 32767)) > 32000 else _t1)" in lines
    assert sum("32768 & 65535" in line for line in plain) == 7          # Q := 7 / K too
    assert [line.split(" = ")[0] for line in lines if " & " in line] == ["self.v_C", "self.v_G", "self.v_F", "self.v_Q"]


@pytest.mark.parametrize("dialect, first, second", [
    # By hand, IEC: exact expressions, the store wraps; the NJ wraps each input first
    # (Calls + 1 = 32768 is INT -32768 there, Big + Big DINT -294967296, Small + 100 -56).
    ("iec", dict(CALLS=2, LOW=-5, A=2, B=101, C=10, D=32000, G=-32767, F=-56),
     dict(CALLS=2, LOW=-5, A=2, B=101, C=10, D=32000, G=-32767, F=-56)),
    ("nj", dict(CALLS=-32768, LOW=-5, A=-32767, B=101, C=-294967296, D=-1, G=0, F=0),
     dict(CALLS=-32767, LOW=-5, A=-32766, B=101, C=-294967296, D=0, G=0, F=0)),
])
def test_the_values_are_those_worked_by_hand(dialect, first, second):
    for optimise in (ON, WITHOUT):
        controller = Controller(compile_program(_program(dialect), optimise=optimise))
        main = controller.add_program("Main")
        for want in (first, second):
            controller.run(1)
            assert {name: getattr(main, "v_" + name) for name in want} == want, (dialect, optimise.wraps)


@pytest.mark.parametrize("dialect", ["iec", "nj"])
@pytest.mark.parametrize("budget_ns", [20, 60, 500_000])
def test_the_scans_see_the_same_with_and_without_the_pass(dialect, budget_ns):
    off, alone = run_both(_program(dialect), 4, budget_ns, optimise=Optimisations.only("wraps"))
    assert alone == off
    off, every = run_both(_program(dialect), 4, budget_ns, optimise=ON)
    assert every == off


def test_the_time_charged_and_a_stopping_fault_are_the_same():
    outcomes = stopped_runs(_program(), 3, WITHOUT, ON)
    assert outcomes[0] == outcomes[1]
    assert [(code, scan) for code, _, scan in outcomes[1][0]] == [("F-DIV-ZERO", 1)]


WIDE = """
PROGRAM Main
VAR
    L : LINT := 9223372036854775806; N : LINT := -9223372036854775807; U : UDINT := 4294967294;
    D : DINT := 2147483646; UL : ULINT := 18446744073709551614; I : INT := 32766; K, Z : LINT;
END_VAR
L := L + 1;
N := N - 1;
U := U + 1;
D := D + 1;
UL := UL + 1;
I := I + 1;
K := L / Z;                                 (* F-DIV-ZERO every scan, inside the tested store *)
END_PROGRAM
"""


def test_a_wide_store_tests_its_range_before_it_wraps():
    """`tested`: a store into DINT, UDINT, LINT or ULINT wraps only a value outside the type;
    the values by hand (two's complement, IEC 61131-3 2.3.1's ranges): each variable reaches
    its type's last value in the first scan and wraps round to the first in the second."""
    lines = compiled_lines(api.load_text(WIDE).program, "MAIN", ON)
    assert "self.v_L = (_t1 if -9223372036854775808 <= (_t1 := (self.v_L + 1)) <= 9223372036854775807 else " \
        "(((_t1) + 9223372036854775808 & 18446744073709551615) - 9223372036854775808))" in lines
    assert "self.v_U = (_t1 if 0 <= (_t1 := (self.v_U + 1)) <= 4294967295 else ((_t1) & 4294967295))" in lines
    assert "self.v_I = ((((self.v_I + 1)) + 32768 & 65535) - 32768)" in lines          # below 32 bits: as before
    wanted = [dict(L=9223372036854775807, N=-9223372036854775808, U=4294967295, D=2147483647,
                   UL=18446744073709551615, I=32767),
              dict(L=-9223372036854775808, N=9223372036854775807, U=0, D=-2147483648, UL=0, I=-32768)]
    for optimise in (ON, WITHOUT):
        controller = Controller(compile_program(api.load_text(WIDE).program, optimise=optimise))
        main = controller.add_program("Main")
        for want in wanted:
            controller.run(1)
            got = {name: getattr(main, "v_" + name) for name in want}
            assert got == want and all(type(value) is int for value in got.values()), optimise.wraps
        assert [(f.code, f.line, f.scan) for f in controller.faults] == [("F-DIV-ZERO", 13, 1), ("F-DIV-ZERO", 13, 2)]

