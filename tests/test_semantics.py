"""IEC 61131-3 semantics of the compiled code, one behaviour per test.

Expected values are worked out by hand (or by NumPy's float32 for REAL).
"""

from __future__ import annotations

import numpy as np
import pytest

from st_runtime.api import load_text


def run(body: str, decls: str, cycles: int = 1, extra: str = ""):
    """Run `PROGRAM Main` with the given declarations and body; (instance, plc)."""
    src = f"{extra}\nPROGRAM Main\nVAR\n{decls}\nEND_VAR\n{body}\nEND_PROGRAM\n"
    plc = load_text(src, "main.st").controller()
    main = plc.add_program("Main")
    plc.run(cycles)
    return main, plc


def faults(plc):
    return [(f.code, f.line) for f in plc.faults]


# ------------------------------------------------------------------ integers


@pytest.mark.parametrize("decl, expr, expected", [
    ("x : INT := 32767;", "x := x + 1;", -32768),
    ("x : INT := -32768;", "x := x - 1;", 32767),
    ("x : SINT := 100;", "x := x * 2;", -56),          # 200 - 256
    ("x : USINT := 250;", "x := x + 10;", 4),           # 260 mod 256
    ("x : UINT := 0;", "x := x - 1;", 65535),
    ("x : DINT := 2147483647;", "x := x + 2;", -2147483647),
    ("x : UDINT := 4294967295;", "x := x + 1;", 0),
    ("x : LINT := 9223372036854775807;", "x := x + 1;", -9223372036854775808),
    ("x : WORD := 16#00F0;", "x := NOT x;", 0xFF0F),
])
def test_integers_wrap_on_every_store(decl, expr, expected):
    main, _ = run(expr, decl)
    assert main["x"] == expected


def test_intermediate_results_are_not_wrapped():
    # (30000 + 30000) / 2 = 30000: the sum is not wrapped before the division.
    main, _ = run("x := (a + a) / 2;", "a : INT := 30000; x : INT;")
    assert main["x"] == 30000


@pytest.mark.parametrize("a, b, quotient, remainder", [
    (7, 2, 3, 1), (-7, 2, -3, -1), (7, -2, -3, 1), (-7, -2, 3, -1), (6, 3, 2, 0), (-1, 5, 0, -1),
])
def test_division_truncates_toward_zero_and_mod_takes_sign_of_dividend(a, b, quotient, remainder):
    main, _ = run("q := a / b; r := a MOD b;", f"a : DINT := {a}; b : DINT := {b}; q, r : DINT;")
    assert (main["q"], main["r"]) == (quotient, remainder)
    assert quotient * b + remainder == a


def test_integer_division_by_zero_is_a_fault_and_the_statement_is_abandoned():
    main, plc = run("q := 5;\nq := a / b;\nr := a MOD b;\ndone := TRUE;",
                    "a : INT := 7; b : INT; q, r : INT; done : BOOL;")
    assert faults(plc) == [("F-DIV-ZERO", 7), ("F-DIV-ZERO", 8)]
    assert main["q"] == 5          # the faulting store did not happen
    assert main["done"] is True    # the statements after it ran
    assert plc.faults[0].pou == "Main" and plc.faults[0].file == "main.st" and plc.faults[0].scan == 1


def test_shift_and_bit_operations_use_the_width():
    main, _ = run("a := SHL(a, 4); b := ROL(b, 1); c := c AND BYTE#16#0F; d := d XOR c; e := NOT e;",
                  "a : BYTE := 16#F1; b : BYTE := 16#81; c : BYTE := 16#FF; d : BYTE := 16#F0; e : BOOL;")
    assert main["a"] == 0x10          # high bits shifted out of the byte
    assert main["b"] == 0x03          # the top bit comes round
    assert main["c"] == 0x0F and main["d"] == 0xFF and main["e"] is True


# ----------------------------------------------------------------------- reals


def test_real_is_float32_rounded_on_every_store():
    main, _ = run("FOR i := 1 TO 10 DO x := x + 0.1; END_FOR; y := 16777216.0; y := y + 1.0;",
                  "x : REAL; y : REAL; i : INT;")
    acc = np.float32(0.0)
    for _ in range(10):
        acc = np.float32(acc + np.float32(0.1))
    assert main.raw("x") == float(acc)
    assert main["y"] == 16777216.0      # 2**24 + 1 is not a float32


def test_integer_constants_stored_in_reals_are_rounded():
    main, _ = run("x := 16777217; y := 16777217; z := 3;", "x : REAL; y : LREAL; z : LREAL;")
    assert main.raw("x") == 16777216.0           # float32 has 24 bits of mantissa
    assert main.raw("y") == 16777217.0 and isinstance(main.raw("z"), float)


def test_lreal_is_float64():
    main, _ = run("FOR i := 1 TO 10 DO x := x + 0.1; END_FOR;", "x : LREAL; i : INT;")
    acc = 0.0
    for _ in range(10):
        acc += 0.1
    assert main["x"] == acc


def test_integer_to_lreal_store_is_a_float():
    main, _ = run("x := i; y := i / 2;", "x, y : LREAL; i : INT := 7;")
    assert main["x"] == 7.0 and isinstance(main.raw("x"), float)
    assert main["y"] == 3.0          # INT / INT truncates, then converts


def test_real_division_by_zero_follows_ieee():
    main, plc = run("a := 1.0 / z; b := -1.0 / z; c := z / z;", "a, b, c, z : LREAL;")
    assert main.raw("a") == float("inf") and main.raw("b") == float("-inf")
    assert main.raw("c") != main.raw("c")     # NaN
    assert plc.faults == []


def test_real_overflow_to_float32_gives_infinity():
    main, _ = run("x := LREAL_TO_REAL(y * y); z := z * z;", "x : REAL; y : LREAL := 1.0E30; z : REAL := 1.0E30;")
    assert main.raw("z") == float("inf")
    assert main.raw("x") == float("inf")


def test_power_operator_follows_ieee_like_expt():
    main, plc = run("a := 2.0 ** 10.0; b := (-8.0) ** 0.5; c := 0.0 ** -1.0; d := EXPT(2.0, 3);",
                    "a, b, c, d : LREAL;")
    assert main.raw("a") == 1024.0 and main.raw("d") == 8.0
    assert main.raw("b") != main.raw("b") and main.raw("c") == float("inf")
    assert plc.faults == []


def test_power_of_constants_folds_as_expt_at_run_time():
    # C99 Annex F pow(): 0 ** -1 = +inf, (-0) ** -1 = -inf (odd exponent),
    # (-8) ** 0.5 = NaN; the folded constants equal what EXPT gives the same
    # values held in variables, and nothing faults.  A REAL context gives
    # the base its type (2.0 ** 3 into a REAL is no LREAL narrowing).
    main, plc = run(
        "v1 := a ** b; v2 := EXPT(a, b); f1 := Pole; f2 := 0.0 ** -1.0; f3 := (-8.0) ** 0.5;"
        " r := 2.0 ** 3; n := NegPole;",
        "a : LREAL := 0.0; b : LREAL := -1.0; v1, v2, f1, f2, f3, n : LREAL; r : REAL;\n"
        "END_VAR\nVAR CONSTANT Pole : LREAL := 0.0 ** -1.0; NegPole : LREAL := (-0.0) ** -1.0;"
        " Half : REAL := 0.25 ** 0.5;")
    inf = float("inf")
    assert [main.raw(n) for n in ("v1", "v2", "f1", "f2", "Pole")] == [inf] * 5
    assert main.raw("n") == -inf
    assert main.raw("f3") != main.raw("f3")
    assert main.raw("r") == 8.0 and main.raw("Half") == 0.5
    assert plc.faults == []


# ------------------------------------------------------------------------ time


def test_time_arithmetic_in_nanoseconds():
    main, _ = run("t := T#1s500ms + T#250ms; u := t * 2; v := t / 4; w := T#1s - T#3s;",
                  "t, u, v, w : TIME;")
    assert main.raw("t") == 1_750_000_000
    assert main["t"] == "T#1s750ms"
    assert main.raw("u") == 3_500_000_000
    assert main.raw("v") == 437_500_000
    assert main.raw("w") == -2_000_000_000


def test_time_times_real_rounds_to_the_nearest_nanosecond():
    main, plc = run("a := T#1s * 0.3; b := T#10ns * 0.25; c := T#1s / 3.0; d := T#1s / z;",
                    "a, b, c, d : TIME; z : LREAL;")
    assert main.raw("a") == 300_000_000
    assert main.raw("b") == 2                 # 2.5 ns: ties to even
    assert main.raw("c") == 333_333_333
    assert [f.code for f in plc.faults] == ["F-DIV-ZERO"]


# ---------------------------------------------------------------------- arrays


def test_arrays_with_any_lower_bounds():
    main, _ = run("a[-2] := 1; a[0] := 3; a[2] := 5; m[0, 10] := 7; m[1, 11] := 9;",
                  "a : ARRAY[-2..2] OF INT; m : ARRAY[0..1, 10..11] OF INT;")
    assert main["a"] == [1, 0, 3, 0, 5]
    assert main["m"] == [[7, 0], [0, 9]]


def test_index_out_of_bounds_is_a_fault_naming_index_and_bounds():
    main, plc = run("i := 6;\na[i] := 1;\nx := a[i - 10];\nm[1, i] := 2;\nok := TRUE;",
                    "a : ARRAY[1..5] OF INT; m : ARRAY[1..2, 1..3] OF INT; i : INT; x : INT; ok : BOOL;")
    assert [f.code for f in plc.faults] == ["F-INDEX"] * 3
    assert [f.line for f in plc.faults] == [7, 8, 9]
    assert "index 6" in plc.faults[0].message and "1..5" in plc.faults[0].message
    assert "'a'" in plc.faults[0].message
    assert "index -4" in plc.faults[1].message
    assert "index 6" in plc.faults[2].message and "1..3" in plc.faults[2].message
    assert main["a"] == [0] * 5 and main["ok"] is True


def test_array_assignment_copies():
    main, _ = run("b := a; b[1] := 99;", "a : ARRAY[1..3] OF INT := [1, 2, 3]; b : ARRAY[1..3] OF INT;")
    assert main["a"] == [1, 2, 3] and main["b"] == [99, 2, 3]


def test_array_initializer_with_repetition():
    main, _ = run("", "a : ARRAY[1..6] OF INT := [1, 2(5), 2(7)];")
    assert main["a"] == [1, 5, 5, 7, 7, 0]


# --------------------------------------------------------------------- structs

POINT = "TYPE Point : STRUCT x : LREAL := 1.5; y : INT; END_STRUCT; END_TYPE"


def test_struct_assignment_copies_and_initial_values():
    main, _ = run("q := p; q.y := 5; r[2] := q;", "p, q : Point; r : ARRAY[1..2] OF Point;", extra=POINT)
    assert main["p"] == {"x": 1.5, "y": 0}
    assert main["q"] == {"x": 1.5, "y": 5}
    assert main["r"] == [{"x": 1.5, "y": 0}, {"x": 1.5, "y": 5}]


# ---------------------------------------------------------------- VAR_IN_OUT

INOUT = """
TYPE Point : STRUCT x : LREAL; y : INT; END_STRUCT; END_TYPE
FUNCTION Bump : BOOL
VAR_IN_OUT v : INT; END_VAR
v := v + 1; Bump := TRUE;
END_FUNCTION
FUNCTION Fill : BOOL
VAR_IN_OUT a : ARRAY[1..3] OF INT; p : Point; END_VAR
a[2] := 42; p.y := 7; Fill := TRUE;
END_FUNCTION
FUNCTION_BLOCK Counter
VAR_OUTPUT n : INT; END_VAR
n := n + 1;
END_FUNCTION_BLOCK
FUNCTION_BLOCK Driver
VAR_IN_OUT c : Counter; END_VAR
c();
END_FUNCTION_BLOCK
"""


def test_var_in_out_is_by_reference():
    main, _ = run("Bump(x); Bump(a[3]); Bump(p.y); Fill(a, p); d(c := cnt); d(c := cnt);",
                  "x : INT; a : ARRAY[1..3] OF INT; p : Point; cnt : Counter; d : Driver;",
                  extra=INOUT)
    assert main["x"] == 1
    assert main["a"] == [0, 42, 1]
    assert main["p"] == {"x": 0.0, "y": 7}
    assert main["cnt"] == {"n": 2}


def test_var_in_out_of_a_function_local_and_of_an_fb_variable():
    src = INOUT + """
    FUNCTION Twice : INT
    VAR k : INT := 3; END_VAR
    Bump(k); Bump(k); Twice := k;
    END_FUNCTION
    FUNCTION_BLOCK Holder
    VAR_OUTPUT h : INT; END_VAR
    Bump(h);
    END_FUNCTION_BLOCK
    """
    main, _ = run("y := Twice(); hold(); hold();", "y : INT; hold : Holder;", cycles=2, extra=src)
    assert main["y"] == 5
    assert main["hold"] == {"h": 4}


# ------------------------------------------------------------- persistence


def test_fb_instances_keep_every_variable_and_program_variables_persist():
    src = """
    FUNCTION_BLOCK Acc
    VAR_INPUT inc : INT; END_VAR
    VAR_OUTPUT total : INT; END_VAR
    VAR calls : INT; END_VAR
    VAR_TEMP t : INT; END_VAR
    t := t + 1; calls := calls + t; total := total + inc;
    END_FUNCTION_BLOCK
    """
    main, _ = run("a(inc := 2); IF first THEN b(inc := 5); first := FALSE; END_IF; b(); n := n + 1;",
                  "a, b : Acc; n : INT := 10; first : BOOL := TRUE;", cycles=3, extra=src)
    assert main["a"] == {"inc": 2, "total": 6, "calls": 3}     # VAR_TEMP restarts at 0: t = 1 each call
    assert main["b"] == {"inc": 5, "total": 20, "calls": 4}    # inputs not given keep their value
    assert main["n"] == 13                                     # initial value applied once


def test_var_temp_of_a_program_is_reset_every_scan():
    src = "PROGRAM Main\nVAR n : INT; END_VAR\nVAR_TEMP t : INT := 4; END_VAR\nt := t + 1; n := n + t;\nEND_PROGRAM\n"
    plc = load_text(src).controller()
    main = plc.add_program("Main")
    plc.run(3)
    assert main["n"] == 15


def test_function_variables_start_fresh_every_call():
    src = """
    FUNCTION Inc : INT
    VAR k : INT := 10; END_VAR
    k := k + 1; Inc := k;
    END_FUNCTION
    """
    main, _ = run("a := Inc(); b := Inc();", "a, b : INT;", extra=src)
    assert (main["a"], main["b"]) == (11, 11)


def test_function_with_var_output():
    src = """
    FUNCTION DivMod : DINT
    VAR_INPUT n, d : DINT; END_VAR
    VAR_OUTPUT r : DINT; neg : BOOL; END_VAR
    DivMod := n / d; r := n MOD d; neg := n < 0;
    END_FUNCTION
    """
    main, _ = run("q := DivMod(-17, 5, r => r, neg => s);\nDivMod(n := 9, d := 4, r => r2);",
                  "q, r, r2 : DINT; s : BOOL;", extra=src)
    assert (main["q"], main["r"], main["s"], main["r2"]) == (-3, -2, True, 1)


# ---------------------------------------------------------------- loops


def test_for_evaluates_bounds_once_and_leaves_the_variable_past_the_end():
    main, _ = run("n := 3; FOR i := 1 TO n DO n := n + 1; count := count + 1; END_FOR;",
                  "i, n, count : INT;")
    assert main["count"] == 3 and main["n"] == 6 and main["i"] == 4


def test_for_with_negative_step_and_empty_ranges():
    main, _ = run("FOR i := 10 TO 1 BY -3 DO s := s * 10 + i; END_FOR;\n"
                  "FOR j := 5 TO 4 DO e := e + 1; END_FOR;\n"
                  "FOR k := 1 TO 0 BY 1 DO e := e + 1; END_FOR;\n"
                  "FOR m := 0 TO 10 BY step DO c := c + 1; END_FOR;",
                  "i, j, k, m, e, c : INT; s : DINT; step : INT := 4;")
    assert main["s"] == 10741          # 10, 7, 4, 1
    assert main["i"] == -2
    assert main["e"] == 0 and main["j"] == 5 and main["k"] == 1
    assert main["c"] == 3 and main["m"] == 12     # 0, 4, 8


def test_exit_and_continue_act_on_the_innermost_loop():
    main, _ = run("""
    FOR i := 1 TO 3 DO
      FOR j := 1 TO 10 DO
        IF j = 3 THEN EXIT; END_IF;
        IF j = 1 THEN CONTINUE; END_IF;
        n := n + 1;
      END_FOR;
      outer := outer + 1;
    END_FOR;
    k := 0;
    WHILE k < 10 DO k := k + 1; IF k MOD 2 = 0 THEN CONTINUE; END_IF; odd := odd + 1; END_WHILE;
    REPEAT r := r + 1; IF r < 4 THEN CONTINUE; END_IF; EXIT; UNTIL FALSE END_REPEAT;
    """, "i, j, n, outer, k, odd, r : INT;")
    assert main["n"] == 3 and main["outer"] == 3 and main["j"] == 3
    assert main["odd"] == 5
    assert main["r"] == 4


def test_repeat_runs_at_least_once_and_while_may_not_run():
    main, _ = run("REPEAT a := a + 1; UNTIL TRUE END_REPEAT; WHILE FALSE DO b := 1; END_WHILE;",
                  "a, b : INT;")
    assert (main["a"], main["b"]) == (1, 0)


def test_return_leaves_the_pou():
    src = """
    FUNCTION Sign : INT
    VAR_INPUT x : INT; END_VAR
    Sign := 0;
    IF x > 0 THEN Sign := 1; RETURN; END_IF;
    IF x < 0 THEN Sign := -1; RETURN; END_IF;
    Sign := 100;
    END_FUNCTION
    FUNCTION_BLOCK Early
    VAR_OUTPUT a, b : INT; END_VAR
    a := a + 1;
    FOR a := a TO 100 DO IF a > 2 THEN RETURN; END_IF; END_FOR;
    b := 1;
    END_FUNCTION_BLOCK
    """
    main, _ = run("p := Sign(5); m := Sign(-5); z := Sign(0); e(); n := n + 1;",
                  "p, m, z, n : INT; e : Early;", extra=src)
    assert (main["p"], main["m"], main["z"], main["n"]) == (1, -1, 100, 1)
    assert main["e"] == {"a": 3, "b": 0}


def test_case_with_values_lists_ranges_and_else():
    main, _ = run("""
    FOR i := 0 TO 9 DO
      CASE i OF
        1, 3: out := out + 1;
        5..7: out := out + 10;
      ELSE
        out := out + 100;
      END_CASE;
    END_FOR;""", "i, out : INT;")
    assert main["out"] == 2 * 1 + 3 * 10 + 5 * 100


def test_enumerations():
    src = "TYPE Mode : (Idle, Run := 5, Stop); END_TYPE"
    main, _ = run("IF m = Idle THEN m := Mode#Run; END_IF; CASE m OF Run: x := 1; Stop: x := 2; END_CASE;",
                  "m : Mode; x : INT;", extra=src)
    assert main["x"] == 1
    assert main.raw("m") == 5


def test_strings_truncate_to_their_length():
    main, _ = run("s := CONCAT(s, 'defgh'); t := 'it$'s $N';", "s : STRING[5] := 'abc'; t : STRING;")
    assert main["s"] == "abcde"
    assert main["t"] == "it's \n"


def test_standard_fbs_run_on_the_simulated_clock():
    main, _ = run("t(IN := TRUE, PT := T#5ms); q := t.Q; IF q AND at = 0 THEN at := n; END_IF; n := n + 1;",
                  "t : TON; q : BOOL; n, at : INT;", cycles=10)
    # Scan k runs at (k-1) ms: ET reaches 5 ms in scan 6 (n = 5 before its increment).
    assert main["at"] == 5


def test_standard_functions_with_formal_and_extensible_arguments():
    main, _ = run("a := LIMIT(MX := 10, IN := 42, MN := 0);\n"
                  "b := MUX(K := 2, IN0 := 5, IN1 := 6, IN2 := 7, IN3 := 8);\n"
                  "c := SEL(G := TRUE, IN0 := 1, IN1 := 2);\n"
                  "d := MAX(3, 9, -4, 7);\n"
                  "e := MIN(IN1 := 2.5, IN2 := -1.5);\n"
                  "s := MID(IN := 'abcdef', L := 3, P := 2);\n"
                  "n := LEN(CONCAT('ab', 'cd', 'e'));",
                  "a, b, c, d, n : INT; e : LREAL; s : STRING;")
    assert (main["a"], main["b"], main["c"], main["d"], main["n"]) == (10, 7, 2, 9, 5)
    assert main["e"] == -1.5 and main["s"] == "bcd"


def test_string_functions_insert_delete_replace_find():
    # IEC 61131-3 string functions (1-based positions): INSERT puts IN2 after
    # the P-th character of IN1; DELETE removes L characters from P; REPLACE
    # puts IN2 in place of L characters from P; FIND is the position of the
    # first IN2 in IN1, 0 when absent.
    main, plc = run(
        "a := INSERT('ABC', 'XY', 2); b := DELETE(IN := 'ABXYC', L := 2, P := 3);"
        " c := REPLACE('ABCDE', 'X', 2, 3); f := FIND('ABCBC', 'BC'); g := FIND('ABC', 'Z');",
        "a, b, c : STRING; f, g : INT;")
    assert (main["a"], main["b"], main["c"]) == ("ABXYC", "ABC", "ABXE")
    assert (main["f"], main["g"]) == (2, 0)
    assert plc.faults == []


def test_time_times_real_constants_fold_to_whole_nanoseconds():
    # TIME * real rounds the exact product to the nearest ns, ties to even
    # (values.time_mul, the NJ's MULTIME): 10 ns * 0.25 = 2.5 -> 2 ns,
    # 10 ns * 0.75 = 7.5 -> 8 ns, 0.5 * 1 s = 500 ms, 1 s / 8.0 = 125 ms.
    # Folded constants (a CONSTANT initial value, a constant right-hand
    # side) equal the run-time products of the same values in variables.
    main, plc = run(
        "a := T#10ns * 0.25; b := T#10ns * 0.75; c := 0.5 * T#1s; d := T#1s / 8.0;"
        " va := t10 * q; vb := t10 * tq;",
        "a, b, c, d, va, vb : TIME; t10 : TIME := T#10ns; q : LREAL := 0.25; tq : LREAL := 0.75;\n"
        "END_VAR\nVAR CONSTANT Quarter : TIME := T#10ns * 0.25; Eighth : TIME := T#1s / 8.0;")
    assert [main.raw(n) for n in ("a", "b", "c", "d")] == [2, 8, 500_000_000, 125_000_000]
    assert (main.raw("va"), main.raw("vb")) == (2, 8)
    assert (main["Quarter"], main["Eighth"]) == ("T#2ns", "T#125ms")
    assert plc.faults == []


def test_real_division_by_zero_folds_as_it_runs():
    # IEEE 754, no fault (NJ): 1/0 = +inf, -1/0 = -inf, 0/0 = NaN; a
    # CONSTANT initial value folds to the same as the division at run time.
    main, plc = run(
        "p := one / zero; n := -one / zero; z := zero / zero; fp := Pos; fz := 0.0 / 0.0;",
        "one : LREAL := 1.0; zero : LREAL; p, n, z, fp, fz : LREAL;\n"
        "END_VAR\nVAR CONSTANT Pos : LREAL := 1.0 / 0.0; Neg : REAL := -1.0 / 0.0;")
    inf = float("inf")
    assert (main.raw("p"), main.raw("n"), main.raw("fp")) == (inf, -inf, inf)
    assert main.raw("Neg") == -inf
    assert main.raw("z") != main.raw("z") and main.raw("fz") != main.raw("fz")
    assert plc.faults == []


# ------------------------------------------------------------- precedence


@pytest.mark.parametrize("decl, expr, expected", [
    # IEC 61131-3 3rd ed. table 71: ** above unary minus, equal levels left to right
    ("x : LREAL;", "x := 2.0 ** 3.0 ** 2.0;", 64.0),       # (2**3)**2, not 2**9 = 512
    ("x : LREAL;", "x := -2.0 ** 2.0;", -4.0),             # -(2**2), not (-2)**2 = 4
    ("x : LREAL;", "x := 2.0 ** -1.0;", 0.5),              # a signed exponent
    ("x : LREAL;", "x := 2.0 * 3.0 ** 2.0;", 18.0),        # ** above *
    ("x : DINT;", "x := 7 - 2 - 1;", 4),                   # left to right, not 7 - (2 - 1)
    ("x : DINT;", "x := 100 / 10 / 5;", 2),                # (100/10)/5, not 100/(10/5) = 50
    ("x : DINT;", "x := 1 + 3 * 4 MOD 5;", 3),             # 1 + ((3*4) MOD 5)
    ("x : DINT;", "x := -7 MOD 3 * 2;", -2),               # ((-7) MOD 3) * 2
    ("x : BOOL;", "x := 1 + 1 > 1;", True),                # + above >
    ("x : BOOL;", "x := 1 < 2 = 3 < 4;", True),            # < above =
    ("x : BOOL;", "x := TRUE OR TRUE XOR TRUE;", True),    # XOR above OR
    ("x : BOOL;", "x := TRUE XOR TRUE AND FALSE;", True),  # AND above XOR
    ("x : BOOL;", "x := TRUE XOR TRUE & FALSE;", True),    # & is AND
    ("x : BOOL;", "x := NOT FALSE AND FALSE;", False),     # NOT above AND
    ("x : BOOL;", "x := 2 = 2 AND 3 = 3;", True),          # = above AND
])
def test_the_precedence_table_at_run_time(decl, expr, expected):
    main, plc = run(expr, decl)
    assert plc.faults == [] and main["x"] == expected
