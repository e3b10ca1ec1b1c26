"""More rows of the core files' tables (issue 16, session 14): the behaviours session 13's
leftovers and the coverage of the compiler's mutation test selection showed unchecked in
st_runtime/compiler/ outside optimise/ (docs/mutation.md, "Session 14, the core files").

As in tests/test_compiler_tables_core.py: one row per behaviour, checked in full with `==`;
expected values from IEC 61131-3, OMRON's manuals as docs/nj501.md cites them, IEEE 754 bit
patterns and Python's exact integers by hand, never from running the code under test; every
row with every optimisation pass and with none.
"""

from __future__ import annotations

import struct

import pytest

from st_runtime import loader
from st_runtime.compiler import Optimisations, compile_program
from st_runtime.controller import Controller
from st_runtime.process_image import ImageView

EVERY, NONE = Optimisations(), Optimisations.none()
PASSES = pytest.mark.parametrize("optimise", [EVERY, NONE], ids=["every pass", "no pass"])


def checked(src: str, dialect: str = "iec"):
    result = loader.load_texts({"m.st": src}, dialect, None)
    errors = [d.header() for d in result.diagnostics if d.is_error]
    assert result.program is not None and not errors, errors
    return result.program


def run(src: str, optimise: Optimisations = EVERY, scans: int = 1, inputs: dict | None = None,
        dialect: str = "iec"):
    """Main of `src` after `scans` scans: (controller, instance, [(code, line, scan)])."""
    controller = Controller(compile_program(checked(src, dialect), optimise=optimise))
    main = controller.add_program("Main")
    for name, value in (inputs or {}).items():
        setattr(main, "v_" + name.upper(), value)
    controller.run(scans)
    return controller, main, [(f.code, f.line, f.scan) for f in controller.faults]


# ============================================ calls.py: every kind of call whose value is dropped

DROPPED = """FUNCTION Twice : INT
VAR_INPUT a : INT; END_VAR
Twice := a * 2;
END_FUNCTION
PROGRAM Main
VAR x : REAL := 2.0; a : ARRAY[1..3] OF INT; i : INT := 4; y : INT; END_VAR
{call}
y := i + 1;
END_PROGRAM
"""


@PASSES
@pytest.mark.parametrize("call", ["SIN(x);", "MAX(i, 7);", "SHL(WORD#1, i);", "REAL_TO_INT(x);",
                                  "LOWER_BOUND(a, 1);", "REF(x);", "Twice(i);", "Twice(a := i);"])
def test_a_call_whose_value_is_dropped_is_a_statement(call: str, optimise):
    # IEC 61131-3 7.3.3.1: a function called as a statement; its value goes nowhere, the
    # statements around it run.
    _, main, faults = run(DROPPED.format(call=call), optimise)
    assert (main.v_Y, main.v_I, faults) == (5, 4, [])


# ========================================= __init__.py: what an instance and the image hold

LOCATED = """PROGRAM Main
VAR AT %MD4 : REAL := 1.5; END_VAR
VAR AT %ML8 : LREAL := -2.0; END_VAR
VAR AT %MW20 : INT := -2; END_VAR
VAR AT %MB22 : USINT := 200; END_VAR
VAR AT %MX30.3 : BOOL := TRUE; END_VAR
VAR y : INT; END_VAR
y := 1;
END_PROGRAM
"""


@PASSES
def test_an_unnamed_located_variable_puts_its_initial_value_in_the_image(optimise):
    # `AT %MD4 : REAL := 1.5;` names no variable: the image holds the value's bits (a REAL as
    # its IEEE 754 single, an LREAL as its double, integers in two's complement, little-endian).
    controller, main, faults = run(LOCATED, optimise)
    image = ImageView(controller.compiled.image)
    assert image["%MD4"] == 0x3FC0_0000                      # 1.5 = 1.1b x 2^0
    assert image["%ML8"] == 0xC000_0000_0000_0000            # -2.0 = -1.0b x 2^1
    assert image["%MD4"] == struct.unpack("<I", struct.pack("<f", 1.5))[0]
    assert (image["%MW20"], image["%MB22"], image["%MX30.3"], image["%MX30.2"]) == (0xFFFE, 200, True, False)
    assert (main.v_Y, faults) == (1, [])


GLOBAL_IN_PROGRAM = """PROGRAM Main
VAR_GLOBAL g : INT := 3; END_VAR
VAR y : INT; END_VAR
g := g + 1;
y := g;
END_PROGRAM
"""


@PASSES
def test_a_var_global_of_a_program_is_a_global_not_an_instance_variable(optimise):
    # The global lives once, in the configuration's globals; the instance keeps no copy of it.
    controller, main, faults = run(GLOBAL_IN_PROGRAM, optimise, scans=2)
    assert (main.v_Y, controller.globals.v_G, faults) == (5, 5, [])
    assert not hasattr(main, "v_G")
    pou = controller.compiled.pou("main")           # a POU by its name in any case
    assert (pou.name, pou.kind, list(pou.variables)) == ("Main", "PROGRAM", ["Y"])


# ================================= calls.py / exprs.py: ENO stored from inside an expression

ENO_PLACES = """FUNCTION FI : INT
VAR_INPUT a : INT; END_VAR
FI := a;
END_FUNCTION
FUNCTION G : INT
VAR_INPUT en : BOOL; END_VAR
VAR ok : BOOL; END_VAR
G := FI(EN := en, a := 10, ENO => ok) + BOOL_TO_INT(ok);
END_FUNCTION
FUNCTION H : INT
VAR_INPUT en : BOOL; END_VAR
VAR_IN_OUT flag : BOOL; END_VAR
H := FI(EN := en, a := 20, ENO => flag);
END_FUNCTION
PROGRAM Main
VAR w : WORD; arr : ARRAY[1..3] OF BOOL; i : INT := 2; en : BOOL; y1, y2, y3, y4, y5 : INT;
    r : REF_TO BOOL; b, f : BOOL; END_VAR
r := REF(b);
y1 := FI(EN := en, a := 3, ENO => w.3);
y2 := FI(EN := en, a := 4, ENO => arr[i]);
y3 := FI(EN := en, a := 5, ENO => r^);
y4 := G(en := en);
y5 := H(en := en, flag := f);
END_PROGRAM
"""


@PASSES
@pytest.mark.parametrize("en", [True, False])
def test_eno_is_stored_from_an_expression_into_every_kind_of_place(en: bool, optimise):
    # IEC 61131-3 6.6.1.2: ENO follows EN; with EN FALSE the function's value is 0 (INT's
    # initial value).  ENO goes into a bit of a WORD (bit 3: 8), an element, a dereferenced
    # reference, a FUNCTION's local (read in the same expression: 10 + 1) and an in-out.
    _, main, faults = run(ENO_PLACES, optimise, dialect="codesys",
                          inputs={"en": en, "w": 0x0100 if en else 0x0108, "arr": [True, not en, True],
                                  "b": not en, "f": not en})
    assert (main.v_W, list(main.v_ARR), main.v_B, main.v_F) == \
        ((0x0108 if en else 0x0100), [True, en, True], en, en)
    assert (main.v_Y1, main.v_Y2, main.v_Y3, main.v_Y4, main.v_Y5) == ((3, 4, 5, 11, 20) if en else (0, 0, 0, 0, 0))
    assert faults == []


# ===================================================== statements.py: empty statements and bodies

EMPTY = """PROGRAM Main
VAR i, k, n, y : INT; b : BOOL; END_VAR
;
IF b THEN ; ELSE y := y + 1; END_IF;
IF NOT b THEN ; END_IF;
CASE k OF 1: ; ELSE ; END_CASE;
FOR i := 1 TO 3 DO ; END_FOR;
WHILE n < 2 DO n := n + 1; ; END_WHILE;
REPEAT ; UNTIL TRUE END_REPEAT;
y := y + 10;
END_PROGRAM
"""


@PASSES
def test_empty_statements_and_bodies_do_nothing(optimise):
    _, main, faults = run(EMPTY, optimise, scans=2)
    assert (main.v_I, main.v_K, main.v_N, main.v_Y, faults) == (4, 0, 2, 22, [])


# ======================== calls.py: defaults made per call, outputs in expressions, generics

CALL_KINDS = """TYPE Pt : STRUCT c : INT := 11; d : INT; END_STRUCT; END_TYPE
FUNCTION FArr : INT
VAR_INPUT a : ARRAY[1..2] OF INT := [5, 6]; p : Pt; k : INT; END_VAR
FArr := a[1] + a[2] + p.c + k;
a[1] := 100;
p.c := 100;
END_FUNCTION
FUNCTION FOut : INT
VAR_INPUT a : INT; END_VAR
VAR_OUTPUT q : BOOL; END_VAR
q := a > 0;
FOut := a * 2;
END_FUNCTION
FUNCTION NoResult : INT
VAR_INPUT a : INT; END_VAR
END_FUNCTION
FUNCTION RefIn : INT
VAR_INPUT a : INT; END_VAR
VAR r : REF_TO INT; END_VAR
r := REF(a);
r^ := r^ + 1;
RefIn := a;
END_FUNCTION
FUNCTION_BLOCK Keep
VAR_INPUT pts : ARRAY[1..2] OF Pt; END_VAR
VAR_OUTPUT s : INT; END_VAR
s := pts[1].c + pts[2].d;
END_FUNCTION_BLOCK
PROGRAM Main
VAR y1, y2, y3, y4, y5, y6, i, s1, s2 : INT; b, b2 : BOOL; m1, m2, m3, x : REAL; d : DINT;
    pts : ARRAY[1..2] OF Pt; k : Keep; END_VAR
y1 := FArr(k := 1);
y2 := FArr(k := 2) + FOut(a := i, NOT q => b);
y3 := FOut(a := -i, q => b2);
y4 := NoResult(a := 7);
y5 := RefIn(a := i);
m1 := MAX(x, i);
m2 := MOVE(x);
m3 := LIMIT(0.0, i, x);
y6 := DINT_TO_INT(d + 1);
pts[1].c := 7;
pts[2].d := 9;
k(pts := pts);
s1 := k.s;
pts[1].c := 70;
k();
s2 := k.s;
END_PROGRAM
"""


@PASSES
@pytest.mark.parametrize("i, x, d", [(3, 2.5, 40000), (-4, -0.5, -40002)])
def test_defaults_outputs_in_expressions_and_generic_arguments(i: int, x: float, d: int, optimise):
    # An input left out has its declared initial value at every call (the array [5, 6] and
    # the structure's c = 11 again at the second call, though the first wrote 100 to both);
    # `NOT q => b` inside an expression stores the negated output; a FUNCTION that never
    # assigns its name returns INT's initial value 0; REF of a FUNCTION's input reaches it;
    # MAX / LIMIT of a REAL and an INT compare in REAL (IEC 61131-3 generic ANY_NUM); MOVE
    # copies; DINT_TO_INT keeps the low 16 bits (two's complement); an FB's array of
    # structures input is a copy made at the call (the later store to pts is not seen).
    _, main, faults = run(CALL_KINDS, optimise, dialect="codesys", inputs={"i": i, "x": x, "d": d})
    assert (main.v_Y1, main.v_Y2, main.v_Y3, main.v_Y4, main.v_Y5) == \
        (23, 24 + 2 * i, -2 * i, 0, i + 1)
    assert (main.v_B, main.v_B2) == (not i > 0, -i > 0)
    assert (main.v_M1, main.v_M2, main.v_M3) == (max(x, float(i)), x, min(max(0.0, float(i)), x))
    assert all(isinstance(v, float) for v in (main.v_M1, main.v_M2, main.v_M3))
    low = (d + 1) & 0xFFFF
    assert main.v_Y6 == (low - 0x10000 if low >= 0x8000 else low)
    assert (main.v_S1, main.v_S2, faults) == (16, 16, [])


# ================================================ exprs.py: strings stored, cut to their length

STRINGS = """PROGRAM Main
VAR s4 : STRING[4]; s8 : STRING[8]; t4, t8 : STRING[4]; u : STRING[8] := 'abcdefgh'; n : INT; END_VAR
s4 := 'abcd';
s8 := 'abc';
t4 := u;
t8 := CONCAT(s8, 'xy');
n := LEN(s4);
END_PROGRAM
"""


@PASSES
@pytest.mark.parametrize("dialect", ["iec", "nj"])
def test_strings_are_stored_whole_or_cut_to_the_targets_length(dialect: str, optimise):
    # A constant that fits is stored as it is; a longer STRING[8] or a CONCAT result keeps its
    # first 4 characters in a STRING[4] (IEC 61131-3 6.4.2: the declared length is the most).
    _, main, faults = run(STRINGS, optimise, dialect=dialect)
    assert (main.v_S4, main.v_S8, main.v_T4, main.v_T8, main.v_N, faults) == ("abcd", "abc", "abcd", "abcx", 4, [])


UNSET_OUTPUTS = """FUNCTION F : INT
VAR_INPUT a : INT; END_VAR
VAR_OUTPUT q : INT := 7; r : BOOL; END_VAR
F := a + 1;
END_FUNCTION
PROGRAM Main
VAR y, z, y2, z2 : INT := -1; b : BOOL := TRUE; END_VAR
y := F(a := 4, q => z, r => b);
F(a := 5, q => z2);
END_PROGRAM
"""


@PASSES
def test_outputs_a_function_never_sets_give_their_initial_values(optimise):
    # IEC 61131-3 6.6.1.2: a FUNCTION's outputs start at their initial values at every call.
    _, main, faults = run(UNSET_OUTPUTS, optimise)
    assert (main.v_Y, main.v_Z, main.v_B, main.v_Z2, main.v_Y2, faults) == (5, 7, False, 7, -1, [])


# ========================================= exprs.py: a PROPERTY written runs its SET accessor

PROPERTY_SET = """FUNCTION_BLOCK Tank
VAR lvl : INT; writes : INT; END_VAR
PROPERTY Level : INT
GET
Level := lvl;
END_GET
SET
lvl := LIMIT(0, Level, 100);
writes := writes + 1;
END_SET
END_PROPERTY
METHOD Fill
VAR_INPUT n : INT; END_VAR
THIS.Level := THIS.Level + n;
END_METHOD
END_FUNCTION_BLOCK
PROGRAM Main
VAR t : Tank; a, b, c : INT; END_VAR
t.Level := 150;
a := t.Level;
t.Level := -3;
b := t.Level;
t.Fill(n := 40);
c := t.Level;
END_PROGRAM
"""


@PASSES
def test_a_property_written_from_outside_and_from_a_method_runs_its_set(optimise):
    # Each write calls SET (IEC 61131-3 3rd ed. 6.6.5.11), which clamps to 0..100 and counts:
    # 150 -> 100, -3 -> 0, 0 + 40 -> 40, three writes.
    _, main, faults = run(PROPERTY_SET, optimise, dialect="codesys")
    assert (main.v_A, main.v_B, main.v_C, main.v_T.v_WRITES, main.v_T.v_LVL, faults) == (100, 0, 40, 3, 40, [])


# =================================== __init__.py: standard FBs before their first call

STANDARD_FBS = {  # IEC 61131-3 6.6.3.5: each standard FB and its variables (every initial value FALSE / 0 / T#0s)
    "TON": ("IN", "PT", "Q", "ET"), "TOF": ("IN", "PT", "Q", "ET"), "TP": ("IN", "PT", "Q", "ET"),
    "R_TRIG": ("CLK", "Q"), "F_TRIG": ("CLK", "Q"), "CTU": ("CU", "R", "PV", "Q", "CV"),
    "CTD": ("CD", "LD", "PV", "Q", "CV"), "CTUD": ("CU", "CD", "R", "LD", "PV", "QU", "QD", "CV"),
    "SR": ("S1", "R", "Q1"), "RS": ("S", "R1", "Q1")}


@PASSES
def test_a_standard_fb_holds_its_initial_values_before_its_first_call(optimise):
    names = list(STANDARD_FBS)
    src = ("PROGRAM Main\nVAR " + "".join(f"f{i} : {name}; " for i, name in enumerate(names))
           + "y : INT; END_VAR\ny := 1;\nEND_PROGRAM\n")
    _, main, faults = run(src, optimise)
    for i, name in enumerate(names):
        fb = getattr(main, f"v_F{i}")
        got = [getattr(fb, "v_" + v) for v in STANDARD_FBS[name]]
        expected = [0 if v in ("PT", "ET", "PV", "CV") else False for v in STANDARD_FBS[name]]   # TIME, INT, BOOL
        assert (got, [type(v) for v in got]) == (expected, [type(v) for v in expected]), name
    assert (main.v_Y, faults) == (1, [])


# ===================== statements.py: a FOR variable of a subrange type (found, not fixed)

SUBRANGE_FOR = """PROGRAM Main
VAR i : INT(1..5); s : INT; n : INT := 10; y : INT; END_VAR
{loop}
y := 7;
END_PROGRAM
"""

# IEC 61131-3 (FOR): the variable takes the start, and after each iteration variable + step,
# tested against the end; this runtime's rule for a subrange: a store outside the limits is
# F-SUBRANGE in the statement that makes it, which is abandoned (README, "subranges").  So a
# FOR past 5 runs i = 1..5 (s = 15 by hand) and faults at the store of 6 - also a FOR to 5,
# whose last increment stores 6 - and the scan goes on (y := 7), i never outside 1..5.
SUBRANGE_LOOPS = {  # loop: (s, i, faults)
    "to a variable past the limit": ("FOR i := 1 TO n DO s := s + i; END_FOR;", 15, 5, [("F-SUBRANGE", 3)]),
    "to the limit": ("FOR i := 1 TO 5 DO s := s + i; END_FOR;", 15, 5, [("F-SUBRANGE", 3)]),
    "to below the limit": ("FOR i := 1 TO 4 DO s := s + i; END_FOR;", 10, 5, []),
    "by 2 past the limit": ("FOR i := 1 TO n - 1 BY 2 DO s := s + i; END_FOR;", 9, 5, [("F-SUBRANGE", 3)]),
    "CONTINUE past the limit": ("FOR i := 1 TO n DO IF i = 2 THEN CONTINUE; END_IF; s := s + i; END_FOR;",
                                13, 5, [("F-SUBRANGE", 3)]),
    "a start outside (1 the initial value)": ("FOR i := n - 10 TO 3 DO s := s + 1; END_FOR;", 0, 1,
                                              [("F-SUBRANGE", 3)]),
}


@PASSES
@pytest.mark.parametrize("row", SUBRANGE_LOOPS.values(), ids=SUBRANGE_LOOPS.keys())
def test_a_for_variable_of_a_subrange_type_faults_in_its_statement(row, optimise):
    loop, s, i, faults = row
    _, main, got = run(SUBRANGE_FOR.format(loop=loop), optimise)
    assert ([(code, line) for code, line, _ in got], main.v_S, main.v_I, main.v_Y) == (faults, s, i, 7)


WRITE_ONLY = """FUNCTION_BLOCK Tank
VAR lvl : INT; END_VAR
PROPERTY Target : INT
SET
lvl := Target * 2;
END_SET
END_PROPERTY
END_FUNCTION_BLOCK
PROGRAM Main
VAR t : Tank; END_VAR
t.Target := 21;
END_PROGRAM
"""


@PASSES
def test_a_property_with_only_set_can_be_written(optimise):
    _, main, faults = run(WRITE_ONLY, optimise, dialect="codesys")
    assert (main.v_T.v_LVL, faults) == (42, [])


# =========================== exprs.py: arrays and structures stored and read through references

DEREFERENCED = """TYPE Pt : STRUCT x : INT; y : ARRAY[1..2] OF INT; END_STRUCT; END_TYPE
FUNCTION Fill : INT
VAR_IN_OUT a : ARRAY[1..3] OF INT; END_VAR
a[3] := 30;
Fill := 1;
END_FUNCTION
PROGRAM Main
VAR arr, arr2 : ARRAY[1..3] OF INT; p, p2 : Pt; ra : REF_TO ARRAY[1..3] OF INT; rp : REF_TO Pt; k, m : INT;
    copy : ARRAY[1..3] OF INT; q : Pt; END_VAR
arr2[1] := 7;
arr2[2] := 8;
p2.x := 5;
p2.y[2] := 6;
ra := REF(arr);
rp := REF(p);
ra^ := arr2;
rp^ := p2;
k := Fill(a := ra^);
copy := ra^;
q := rp^;
m := ra^[2] + rp^.y[2];
arr2[1] := -1;
p2.y[2] := -1;
END_PROGRAM
"""


@PASSES
def test_aggregates_are_copied_into_and_out_of_a_dereference(optimise):
    # `ra^ := arr2` copies the array into arr (later stores to arr2 not seen); an in-out bound
    # to ra^ is arr itself (a[3] := 30 lands in arr); copies out of ra^ and rp^ are values.
    _, main, faults = run(DEREFERENCED, optimise)
    assert (list(main.v_ARR), main.v_P.v_X, list(main.v_P.v_Y)) == ([7, 8, 30], 5, [0, 6])
    assert (list(main.v_COPY), main.v_Q.v_X, list(main.v_Q.v_Y), main.v_M, main.v_K, faults) == \
        ([7, 8, 30], 5, [0, 6], 14, 1, [])


# ================ __init__.py: what an instance's class tells the API (kinds, constants)

SEEN = """FUNCTION_BLOCK Box
VAR_INPUT a : INT; END_VAR
VAR_IN_OUT io : INT; END_VAR
VAR_OUTPUT b : INT; END_VAR
VAR CONSTANT K : INT := 4; END_VAR
VAR n : INT; END_VAR
b := a + io + K;
n := n + 1;
END_FUNCTION_BLOCK
PROGRAM Main
VAR CONSTANT C : INT := 3; END_VAR
VAR x : INT := 1; box : Box; v : INT := 10; END_VAR
box(a := x, io := v);
x := x + C;
END_PROGRAM
"""


@PASSES
def test_an_instance_shows_its_own_variables_and_refuses_writes_to_constants(optimise):
    # The JSON view of an FB instance leaves out its in-out (a reference, not its own value);
    # writing a CONSTANT through the API is refused, a plain variable is written.
    from st_runtime import api
    from st_runtime.values import object_to_json

    _, main, faults = run(SEEN, optimise)
    assert object_to_json(main.v_BOX) == {"a": 1, "b": 15, "K": 4, "n": 1}      # 1 + 10 + 4
    assert object_to_json(main) == {"C": 3, "x": 4, "box": {"a": 1, "b": 15, "K": 4, "n": 1}, "v": 10}
    with pytest.raises(KeyError):
        api.Instance(main)["C"] = 5
    with pytest.raises(KeyError):
        api.Instance(main.v_BOX)["K"] = 5
    api.Instance(main)["x"] = 7
    assert (main.v_X, main.v_C, main.v_BOX.v_K, faults) == (7, 3, 4, [])


SIGNED_SUMS = """PROGRAM Main
VAR i : INT; s : SINT; d : DINT; u : UINT; us : USINT; ud : UDINT; ul : ULINT; END_VAR
u := i + 1;
us := s * 2;
ud := d - 1;
ul := s + 1;
END_PROGRAM
"""


@PASSES
@pytest.mark.parametrize("i, s, d", [(-5, -2, -3), (7, 60, 9), (-32768, -128, -2147483647)])
def test_nj_stores_a_signed_sum_into_an_unsigned_type_with_its_bits(i: int, s: int, d: int, optimise):
    # W501 6-5-3 as docs/nj501.md cites it: a signed integer goes into an unsigned one of the
    # same or a larger size with its bits kept (two's complement), here the value of a sum,
    # product or difference in its own type (the expression overflows in INT, SINT, DINT).
    def bits(value: int, width: int, signed_width: int) -> int:
        low = value & ((1 << signed_width) - 1)         # the expression's own type ...
        if low >= 1 << (signed_width - 1):
            low -= 1 << signed_width
        return low & ((1 << width) - 1)                 # ... its bits in the wider unsigned one
    _, main, faults = run(SIGNED_SUMS, optimise, dialect="nj", inputs={"i": i, "s": s, "d": d})
    assert (main.v_U, main.v_US, main.v_UD, main.v_UL, faults) == \
        (bits(i + 1, 16, 16), bits(s * 2, 8, 8), bits(d - 1, 32, 32), bits(s + 1, 64, 8), [])


DERIVED_RESULT = """TYPE Speed : INT := 5; END_TYPE
FUNCTION F : Speed
VAR_INPUT a : INT; END_VAR
IF a > 0 THEN F := a; END_IF;
END_FUNCTION
PROGRAM Main
VAR y1, y2 : INT; v : Speed; END_VAR
y1 := F(a := 0);
y2 := F(a := 3);
END_PROGRAM
"""


@PASSES
def test_a_function_result_of_a_derived_type_starts_at_the_types_initial_value(optimise):
    _, main, faults = run(DERIVED_RESULT, optimise)
    assert (main.v_Y1, main.v_Y2, main.v_V, faults) == (5, 3, 5, [])


DERIVED_METHOD_RESULT = """TYPE Speed : INT := 5; END_TYPE
FUNCTION_BLOCK Drive
METHOD Pick : Speed
VAR_INPUT a : INT; END_VAR
IF a > 0 THEN Pick := a; END_IF;
END_METHOD
END_FUNCTION_BLOCK
PROGRAM Main
VAR d : Drive; y1, y2 : INT; END_VAR
y1 := d.Pick(a := 0);
y2 := d.Pick(a := 4);
END_PROGRAM
"""


@PASSES
def test_a_method_result_of_a_derived_type_starts_at_the_types_initial_value(optimise):
    # IEC 61131-3:2013 table 11: a derived type's initial value is every variable's of that
    # type; a METHOD's result is one (5 when the METHOD does not set it, by hand).
    _, main, faults = run(DERIVED_METHOD_RESULT, optimise, dialect="codesys")
    assert (main.v_Y1, main.v_Y2, faults) == (5, 4, [])
