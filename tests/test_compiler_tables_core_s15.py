"""More rows of the core files' tables (issue 16, session 15): the leftovers of session 14 and
the survivors of the fresh seed-360 sample in st_runtime/compiler/ outside optimise/
(docs/mutation.md, "Session 15, the core files").

As in tests/test_compiler_tables_core.py: one row per behaviour, checked in full with `==`;
expected values from IEC 61131-3, OMRON's manuals as docs/nj501.md cites them and hand
calculation, never from running the code under test; every row with every optimisation pass
and with none.
"""

from __future__ import annotations

import pytest

from test_compiler_tables_core import PS_PER_UNIT, program, scan_times
from test_compiler_tables_core_s14 import PASSES, run      # (Main after its scans, and its faults)


# ============================ calls.py, initial.py: a FUNCTION not called (EN FALSE) of a derived type

NOT_CALLED = """TYPE Speed : INT := 5; END_TYPE
TYPE Color : (Red, Green, Blue) := Green; END_TYPE
TYPE Triple : ARRAY[1..3] OF INT := [1, 2, 3]; END_TYPE
TYPE Pt : STRUCT a : INT := 4; b : INT; END_STRUCT; END_TYPE
FUNCTION FSpeed : Speed
VAR_INPUT x : INT; END_VAR
FSpeed := x;
END_FUNCTION
FUNCTION FColor : Color
VAR_INPUT x : INT; END_VAR
FColor := Blue;
END_FUNCTION
FUNCTION FTriple : Triple
VAR_INPUT x : INT; END_VAR
FTriple[1] := x;
END_FUNCTION
FUNCTION FPt : Pt
VAR_INPUT x : INT; END_VAR
FPt.b := x;
END_FUNCTION
PROGRAM Main
VAR en : BOOL; s : INT := -1; c : Color := Blue; t : Triple; p : Pt;
    ok1, ok2, ok3, ok4 : BOOL := TRUE; END_VAR
s := FSpeed(EN := en, x := 9, ENO => ok1);
c := FColor(EN := en, x := 9, ENO => ok2);
t := FTriple(EN := en, x := 9, ENO => ok3);
p := FPt(EN := en, x := 9, ENO => ok4);
END_PROGRAM
"""


@PASSES
@pytest.mark.parametrize("en", [False, True], ids=["EN FALSE", "EN TRUE"])
def test_a_function_not_called_gives_its_derived_result_types_initial_value(en: bool, optimise):
    # IEC 61131-3 6.6.1.2 as calls.enabled_call_expr reads it: with EN FALSE the FUNCTION is not
    # called, its value is its result type's initial value and ENO is FALSE; a derived type's
    # initial value is that of every variable of the type (IEC 61131-3:2013 table 11): Speed 5,
    # Color Green (1), Triple [1, 2, 3], Pt (a 4, b 0). EN TRUE: the values the bodies set.
    _, main, faults = run(NOT_CALLED, optimise, inputs={"en": en})
    got = (main.v_S, main.v_C, list(main.v_T), (main.v_P.v_A, main.v_P.v_B),
           (main.v_OK1, main.v_OK2, main.v_OK3, main.v_OK4), faults)
    assert got == ((9, 2, [9, 2, 3], (4, 9), (True,) * 4, []) if en else
                   (5, 1, [1, 2, 3], (4, 0), (False,) * 4, []))


# ============================ initial.py: a type derived from a derived type without an initial value

DERIVED_TWICE = """TYPE Color : (Red, Green, Blue) := Green; END_TYPE
TYPE Shade : Color; END_TYPE
TYPE Pt : STRUCT a : Shade; b : INT; END_STRUCT; END_TYPE
FUNCTION Set : Shade
VAR_INPUT x : INT; END_VAR
Set := Blue;
END_FUNCTION
FUNCTION Unset : Shade
VAR_INPUT x : INT; END_VAR
END_FUNCTION
FUNCTION_BLOCK Holder
VAR_OUTPUT q : Shade; END_VAR
END_FUNCTION_BLOCK
PROGRAM Main
VAR en : BOOL; v : Shade; a : ARRAY[1..2] OF Shade; p : Pt; fb : Holder;
    skipped : Shade := Blue; blank : Shade := Blue; END_VAR
skipped := Set(EN := en, x := 1);
blank := Unset(x := 1);
END_PROGRAM
"""


@PASSES
def test_a_type_derived_from_an_enumeration_with_an_initial_value_keeps_it(optimise):
    # Shade is Color under another name and declares no initial value of its own: its variables
    # start at Color's, Green (1), as Color's do (IEC 61131-3:2013 table 11) - a variable, array
    # elements, a structure member, an FB output, a FUNCTION's unset result, a FUNCTION not
    # called (EN FALSE).
    _, main, faults = run(DERIVED_TWICE, optimise)
    assert (main.v_V, list(main.v_A), main.v_P.v_A, main.v_FB.v_Q, main.v_SKIPPED, main.v_BLANK,
            faults) == (1, [1, 1], 1, 1, 1, 1, [])


SPEED_TWICE = """TYPE Speed : INT := 5; END_TYPE
TYPE Pace : Speed; END_TYPE
PROGRAM Main
VAR v : Pace; a : ARRAY[1..2] OF Pace; END_VAR
END_PROGRAM
"""


@PASSES
def test_a_type_derived_from_a_derived_elementary_type_keeps_its_initial_value(optimise):
    # as the enumeration above: Pace is Speed under another name, so it starts at 5
    _, main, faults = run(SPEED_TWICE, optimise)
    assert (main.v_V, list(main.v_A), faults) == (5, [5, 5], [])


# ================================================ calls.py: a negated ENO (NOT ENO => x)

NEGATED_ENO = """FUNCTION Twice : INT
VAR_INPUT a : INT; END_VAR
Twice := a * 2;
END_FUNCTION
PROGRAM Main
VAR en : BOOL; y1, y2 : INT := -1; bad1, bad2, bad3 : BOOL; END_VAR
y1 := Twice(EN := en, a := 3, NOT ENO => bad1);
Twice(EN := en, a := 4, NOT ENO => bad2);
y2 := Twice(a := 5, NOT ENO => bad3);
END_PROGRAM
"""


@PASSES
@pytest.mark.parametrize("en", [False, True], ids=["EN FALSE", "EN TRUE"])
def test_a_negated_eno_stores_the_negation(en: bool, optimise):
    # IEC 61131-3 6.6.1.2: ENO is FALSE when EN is FALSE (the FUNCTION not called, its value its
    # type's initial value 0), TRUE when it runs; `NOT ENO => x` stores the negation (a negated
    # output), in an expression, in a call statement and without EN.
    _, main, faults = run(NEGATED_ENO, optimise, inputs={"en": en})
    assert (main.v_Y1, main.v_Y2, main.v_BAD1, main.v_BAD2, main.v_BAD3, faults) == \
        ((6, 10, False, False, False, []) if en else (0, 10, True, True, False, []))


# =============================== statements.py: a FOR whose end is an element of a CONSTANT array

CONSTANT_END = """PROGRAM Main
VAR CONSTANT lims : ARRAY[1..3] OF INT := [2, 4, 12]; END_VAR
VAR a : ARRAY[1..10] OF INT; k : INT; s : INT; i : INT; after : INT; END_VAR
FOR i := 1 TO lims[k] DO a[i] := i; s := s + a[i]; END_FOR;
after := 1;
END_PROGRAM
"""


@PASSES
@pytest.mark.parametrize("k, filled, s, faults", [(1, 2, 3, []), (2, 4, 10, []),
                                                  (3, 10, 55, [("F-INDEX", 4, 1)] * 4)])
def test_a_for_up_to_an_element_of_a_constant_array(k: int, filled: int, s: int, faults: list, optimise):
    # The end lims[k] lies in 2..12, known before the run (the loop in two versions, checked
    # and not, optimise/ranges.py); a[1..10]. With lims[3] = 12 the sum of 1..10 is 55, and
    # i = 11 and 12 each fault in both statements of the body (README: a runtime fault abandons
    # the faulting statement): four F-INDEX on line 4, the statement after the FOR runs.
    _, main, got = run(CONSTANT_END, optimise, inputs={"k": k})
    assert (main.v_S, list(main.v_A), main.v_AFTER, got) == \
        (s, [n if n <= filled else 0 for n in range(1, 11)], 1, faults)


# ================ statements.py: what a FOR body assigns is not known after the FOR (it may not run)

MAYBE_NEVER = """PROGRAM Main
VAR a : ARRAY[1..5] OF INT := [1, 2, 3, 4, 5]; j, k, n, i : INT; y1, y2 : INT := -1; END_VAR
j := 0;
FOR i := 1 TO n DO j := 2; END_FOR;
y1 := a[j];
k := 0;
FOR i := 1 TO n DO k := 3; IF i > 100 THEN EXIT; END_IF; END_FOR;
y2 := a[k];
END_PROGRAM
"""


@PASSES
@pytest.mark.parametrize("n, y1, y2, faults", [(0, -1, -1, [("F-INDEX", 5, 1), ("F-INDEX", 8, 1)]),
                                               (2, 2, 3, [])])
def test_a_variable_a_for_body_assigns_may_keep_its_value_from_before(n: int, y1: int, y2: int,
                                                                      faults: list, optimise):
    # With n = 0 neither FOR runs its body: j and k stay 0, and a[0] lies outside 1..5 (F-INDEX,
    # the store abandoned); with n = 2 they are 2 and 3. (A pass that took the body's j := 2 as
    # j's value after the loop read a[0] as Python's a[-1], 5.)
    _, main, got = run(MAYBE_NEVER, optimise, inputs={"n": n})
    assert (main.v_Y1, main.v_Y2, got) == (y1, y2, faults)


# ============================ exprs.py: a folded constant stored into a subrange is checked

FOLDED_INTO_SUBRANGE = """PROGRAM Main
VAR CONSTANT C : INT := 4; END_VAR
VAR s : INT(1..5) := 2; y : INT := 1; END_VAR
s := {value};
y := 2;
END_PROGRAM
"""


@PASSES
@pytest.mark.parametrize("dialect", ["iec", "nj"])
@pytest.mark.parametrize("value, s, faults", [("C - 1", 3, []), ("C + 1", 5, []), ("C + 3", 2, [("F-SUBRANGE", 4, 1)]),
                                              ("C - 4", 2, [("F-SUBRANGE", 4, 1)])])
def test_a_folded_constant_outside_a_subrange_faults_when_stored(value: str, s: int, faults: list, dialect: str,
                                                                 optimise):
    # The checker folds C + 3 to 7 (a literal 7 it refuses, E-TYPE-005); stored into INT(1..5)
    # it lies outside 1..5: F-SUBRANGE, the store abandoned (s keeps 2), the next statement runs.
    # 3 and 5 lie inside and are stored.
    _, main, got = run(FOLDED_INTO_SUBRANGE.format(value=value), optimise, dialect=dialect)
    assert (main.v_S, main.v_Y, got) == (s, 2, faults)


# ======================== cost.py: an assignment of an array of aggregates moves every element

NESTED_COPIES = {  # body: units by hand (docs/nj501.md "What a scan costs": element moved 2)
    "array of structures": ("ps := qs;", 2 * 2 * (1 + 3)),        # 2 Pairs of an LREAL and 3 INTs
    "array of arrays": ("n1 := n2;", 2 * 2 * 3),                   # 2 arrays of 3 INTs
}


@pytest.mark.parametrize("row", NESTED_COPIES.values(), ids=NESTED_COPIES.keys())
def test_an_array_of_aggregates_is_charged_per_elementary_value(row):
    body, units = row
    src = ("TYPE Pair : STRUCT x : LREAL; y : ARRAY[1..3] OF INT; END_STRUCT; END_TYPE\n"
           + program("ps, qs : ARRAY[1..2] OF Pair; n1, n2 : ARRAY[1..2] OF ARRAY[1..3] OF INT;", body))
    expected = ([], [units * PS_PER_UNIT])
    assert scan_times(src, {}) == {"every pass": expected, "no pass": expected}


CHAIN_OF_DERIVED = """TYPE A : INT := 7; END_TYPE
TYPE B : A; END_TYPE
TYPE C : B; END_TYPE
TYPE D : C := 2; END_TYPE
TYPE E : D; END_TYPE
FUNCTION Unset : C
VAR_INPUT x : INT; END_VAR
END_FUNCTION
PROGRAM Main
VAR c : C; e : E; r : INT; arr : ARRAY[0..1] OF E; END_VAR
r := Unset(x := 1);
END_PROGRAM
"""


@PASSES
def test_a_chain_of_derived_types_starts_at_the_nearest_initial_value(optimise):
    # C is B is A (:= 7), none giving its own: C starts at 7; E is D, which gives 2: E starts
    # at 2, not A's 7 (the nearest declared value down the chain, IEC 61131-3:2013 table 11);
    # a FUNCTION's unset result of type C gives 7.
    _, main, faults = run(CHAIN_OF_DERIVED, optimise)
    assert (main.v_C, main.v_E, main.v_R, list(main.v_ARR), faults) == (7, 2, 7, [2, 2], [])
