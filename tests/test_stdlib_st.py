"""The standard library called from ST, end to end through the Python API.

Expected values are the same hand calculations as in the direct tests; here
they prove that the checker, the compiler and the library agree on names,
argument order, bit widths and faults.
"""

import math

import numpy as np
import pytest

from st_runtime.api import load_text
from st_runtime.trace import read_csv


def run(source: str, scans: int = 1, program: str = "Main"):
    project = load_text(source)
    plc = project.controller(period="1ms")
    main = plc.add_program(program)
    plc.run(scans)
    return plc, main


def test_ton_from_st_on_the_simulated_clock():
    # Same reasoning as the direct test: IN TRUE from scan 1, PT = 5 ms,
    # 1 ms scans -> ET = 0..5 ms on scans 1..6 and Q from scan 6.
    project = load_text("""
PROGRAM Main
VAR
    Delay : TON;
    Done : BOOL;
    Elapsed : TIME;
END_VAR
Delay(IN := TRUE, PT := T#5ms, Q => Done, ET => Elapsed);
END_PROGRAM
""")
    plc = project.controller(period="1ms")
    main = plc.add_program("Main")
    seen = []
    for _ in range(7):
        plc.run(1)
        seen.append((main["Done"], main["Elapsed"]))
    assert seen == [(False, "T#0s"), (False, "T#1ms"), (False, "T#2ms"), (False, "T#3ms"),
                    (False, "T#4ms"), (True, "T#5ms"), (True, "T#5ms")]
    assert main["Delay.Q"] is True
    assert plc.faults == []


def test_conversions_and_functions_from_st():
    plc, main = run("""
PROGRAM Main
VAR
    Tie1, Tie2, Tie3 : INT;
    Near : DINT;
    Low : SINT;
    Bits : WORD;
    Shl1, Rol1, Inv : BYTE;
    Lim : INT;
    Pick : LREAL;
    Which : INT;
    Big : LREAL;
    Cut : DINT;
    Text : STRING[40];
    Count : INT;
    Period : STRING[20];
    Root : LREAL;
    Angle : LREAL;
END_VAR
Tie1 := REAL_TO_INT(REAL#2.5);          (* ties to even: 2 *)
Tie2 := REAL_TO_INT(REAL#-2.5);         (* -2 *)
Tie3 := LREAL_TO_INT(3.5);              (* 4 *)
Near := LREAL_TO_DINT(-1.51);           (* -2 *)
Low := INT_TO_SINT(4223);               (* 16#107F -> 16#7F = 127 *)
Bits := LREAL_TO_WORD(-1.6);            (* 16#FFFE *)
Shl1 := SHL(BYTE#16#81, 1);             (* 16#02 *)
Rol1 := ROL(BYTE#16#81, 1);             (* 16#03 *)
Inv := NOT BYTE#16#0F;                  (* 16#F0 *)
Lim := LIMIT(0, 15, 10);                (* 10 *)
Pick := SEL(TRUE, 1.0, 2.0);            (* 2.0 *)
Which := MUX(2, 10, 20, 30);            (* 30 *)
Big := MAX(1.5, 7.25, -3.0);            (* 7.25 *)
Cut := TRUNC(-3.55);                    (* -3 *)
Text := CONCAT(LEFT('ABCDE', 2), MID('ABCDE', 2, 3), RIGHT('ABCDE', 1));  (* 'AB' 'CD' 'E' *)
Count := LEN(Text);
Period := TIME_TO_STRING(T#1s500ms);
Root := SQRT(2.0);
Angle := ATAN(1.0) * 4.0;
END_PROGRAM
""")
    assert plc.faults == []
    got = {k: main[k] for k in ("Tie1", "Tie2", "Tie3", "Near", "Low", "Bits", "Shl1", "Rol1",
                                "Inv", "Lim", "Pick", "Which", "Big", "Cut", "Text", "Count",
                                "Period")}
    assert got == {"Tie1": 2, "Tie2": -2, "Tie3": 4, "Near": -2, "Low": 127, "Bits": 0xFFFE,
                   "Shl1": 0x02, "Rol1": 0x03, "Inv": 0xF0, "Lim": 10, "Pick": 2.0, "Which": 30,
                   "Big": 7.25, "Cut": -3, "Text": "ABCDE", "Count": 5, "Period": "T#1s500ms"}
    assert main["Root"] == np.sqrt(2.0)
    assert main["Angle"] == np.arctan(1.0) * 4.0


def test_nj_math_gives_nan_and_library_faults_are_recorded():
    plc, main = run("""
PROGRAM Main
VAR
    Bad : LREAL;
    Logz : LREAL;
    Which : INT := 7;
    Part : STRING[10] := 'keep';
    Big : INT := 5;
    After : BOOL;
END_VAR
Bad := SQRT(-1.0);                 (* NJ: nonnumeric data, no error *)
Logz := LN(0.0);                   (* -inf *)
Which := MUX(3, 10, 20, 30);       (* K out of range: fault, statement abandoned *)
Part := MID('ABC', 1, 9);          (* P out of range: fault *)
Big := LREAL_TO_INT(1.0E10);       (* outside INT: fault *)
After := TRUE;                     (* execution goes on after each fault *)
END_PROGRAM
""")
    assert math.isnan(main["Bad"])
    assert main["Logz"] == -math.inf
    assert main["Which"] == 7 and main["Part"] == "keep" and main["Big"] == 5
    assert main["After"] is True
    assert [f.code for f in plc.faults] == ["F-INDEX", "F-STRING", "F-CONVERT"]
    # the text starts with a newline: PROGRAM is line 2, the MUX line 13
    assert [f.line for f in plc.faults] == [13, 14, 15]


def test_counters_edges_and_bistables_from_st():
    # Every scan Toggle flips, so CTU sees a rising edge every second scan:
    # scans 1, 3, 5, 7 -> CV = 4 after 8 scans, Q (CV >= 3) from scan 5.
    # R_TRIG counts the same edges; SR is set by Q and stays set.
    plc, main = run("""
PROGRAM Main
VAR
    Toggle : BOOL;
    Counter : CTU;
    Edge : R_TRIG;
    Edges : INT;
    Latch : SR;
    Veto : RS;
    Fall : F_TRIG;
    Falls : INT;
    Quiet : F_TRIG;
    Spurious : INT;
END_VAR
Toggle := NOT Toggle;
Counter(CU := Toggle, R := FALSE, PV := 3);
Edge(CLK := Toggle);
IF Edge.Q THEN
    Edges := Edges + 1;
END_IF;
Latch(S1 := Counter.Q, R := TRUE);
Veto(S := TRUE, R1 := TRUE);
Fall(CLK := Toggle);
IF Fall.Q THEN
    Falls := Falls + 1;
END_IF;
Quiet(CLK := FALSE);
IF Quiet.Q THEN
    Spurious := Spurious + 1;
END_IF;
END_PROGRAM
""", scans=8)
    assert main["Counter.CV"] == 4 and main["Counter.Q"] is True
    assert main["Edges"] == 4
    assert main["Latch.Q1"] is True         # set dominates
    assert main["Veto.Q1"] is False         # reset dominates
    # Toggle is TRUE on odd scans: falling edges on scans 2, 4, 6, 8.  F_TRIG's
    # memory M starts FALSE (IEC 61131-3 tables 35/44 give it no initial
    # value), so Quiet, whose CLK is FALSE from the first call, pulses once
    # on scan 1 and never again.
    assert main["Falls"] == 4
    assert main["Spurious"] == 1


def test_call_ton_until_q():
    # `stgen call --pou TON --set IN=true --set PT="T#3ms" --until Q`: ET
    # reaches 3 ms on the 4th scan.
    project = load_text("PROGRAM Main\nEND_PROGRAM\n")
    result = project.call("TON", {"IN": True, "PT": "T#3ms"}, until="Q")
    assert result["outputs"]["Q"] is True
    assert result["outputs"]["ET"] == "T#3ms"
    assert result["outputs"]["cycles"] == 4


def test_trace_of_an_fb_instance_through_the_api(tmp_path):
    project = load_text("""
PROGRAM Main
VAR
    Pulse : TP;
    Start : BOOL;
    Pose : ARRAY[1..2] OF LREAL;
END_VAR
Start := TRUE;
Pulse(IN := Start, PT := T#2ms);
Pose[1] := Pose[1] + 0.5;
END_PROGRAM
""")
    plc = project.controller(period="1ms")
    plc.add_program("Main")
    trace = plc.trace(["Pulse.Q", "Pulse.ET", "Pose"], program="Main")
    plc.run(4)
    assert trace.column_names == ["Pulse.Q", "Pulse.ET", "Pose[1]", "Pose[2]"]
    path = tmp_path / "t.csv"
    trace.write_csv(path)
    data = read_csv(path)
    np.testing.assert_array_equal(data["scan"], [1, 2, 3, 4])
    np.testing.assert_array_equal(data["Pulse.Q"], [True, True, False, False])
    np.testing.assert_array_equal(data["Pulse.ET"], [0, 1_000_000, 2_000_000, 2_000_000])
    np.testing.assert_array_equal(data["Pose[1]"], [0.5, 1.0, 1.5, 2.0])


@pytest.mark.parametrize("expr, expected", [
    ("INT_TO_STRING(-42)", "-42"),
    ("STRING_TO_INT('16#7F')", 127),
    ("BOOL_TO_INT(TRUE)", 1),
    ("DINT_TO_REAL(16777217)", 16777216.0),
    ("TIME_TO_LINT(T#1ms)", 1_000_000),
    ("DT_TO_DATE(DT#2024-01-02-12:30:00)", "D#2024-01-02"),
])
def test_conversion_calls_from_st(expr, expected):
    types = {str: "STRING[30]", int: "LINT", float: "LREAL"}
    result_type = "DATE" if expr.startswith("DT_TO_DATE") else types[type(expected)]
    plc, main = run(f"""
PROGRAM Main
VAR
    R : {result_type};
END_VAR
R := {expr};
END_PROGRAM
""")
    assert plc.faults == []
    assert main["R"] == expected


def test_tof_ctd_ctud_from_st_on_the_simulated_clock():
    # 1 ms scans, scan k runs at (k - 1) ms.  Toggle is TRUE on odd scans.
    # TOF: IN TRUE on scans 1-2, falls at scan 3 (2 ms): ET 0, 1, 2, 3 ms on
    #   scans 3..6; Q stays TRUE until ET reaches PT = 3 ms on scan 6.
    # CTD (IEC body: LD wins over the edge of the same call): loaded to 2 on
    #   scan 1; rising edges of CD on scans 3, 5, 7 -> CV 1, 0, -1; Q once CV <= 0.
    # CTUD: CU edges on scans 1, 3, 5, CD's one edge on scan 3 (both edges in
    #   one call: no count) -> CV 1, 1, 2; QU once CV >= PV = 2.
    project = load_text("""
PROGRAM Main
VAR
    Scan : INT;
    Toggle : BOOL;
    OffDelay : TOF;
    Down : CTD;
    UpDown : CTUD;
END_VAR
Scan := Scan + 1;
Toggle := NOT Toggle;
OffDelay(IN := Scan <= 2, PT := T#3ms);
Down(CD := Toggle, LD := Scan = 1, PV := 2);
UpDown(CU := Toggle, CD := Scan = 3 OR Scan = 4, R := FALSE, LD := FALSE, PV := 2);
END_PROGRAM
""")
    plc = project.controller(period="1ms")
    main = plc.add_program("Main")
    seen = []
    for _ in range(8):
        plc.run(1)
        seen.append((main["OffDelay.Q"], main["OffDelay.ET"], main["Down.CV"], main["Down.Q"],
                     main["UpDown.CV"], main["UpDown.QU"], main["UpDown.QD"]))
    assert seen == [
        (True, "T#0s", 2, False, 1, False, False),
        (True, "T#0s", 2, False, 1, False, False),
        (True, "T#0s", 1, False, 1, False, False),
        (True, "T#1ms", 1, False, 1, False, False),
        (True, "T#2ms", 0, True, 2, True, False),
        (False, "T#3ms", 0, True, 2, True, False),
        (False, "T#3ms", -1, True, 3, True, False),
        (False, "T#3ms", -1, True, 3, True, False),
    ]
    assert plc.faults == []


def test_the_rest_of_the_function_list_from_st():
    plc, main = run("""
PROGRAM Main
VAR
    AbsR : LREAL; AbsI : INT; Ln1 : LREAL; Log1 : LREAL; Exp1 : LREAL; Expt1 : LREAL;
    Sin1 : LREAL; Cos1 : LREAL; Tan1 : LREAL; Asin1 : LREAL; Acos1 : LREAL;
    Min1 : DINT; Move1 : INT; Shr1 : WORD; Ror1 : BYTE; And1 : WORD; Or1 : WORD; Xor1 : WORD;
END_VAR
AbsR := ABS(-2.5);
AbsI := ABS(INT#-7);
Ln1 := LN(10.0);
Log1 := LOG(1000.0);
Exp1 := EXP(0.5);
Expt1 := EXPT(2.0, 10);
Sin1 := SIN(0.5);
Cos1 := COS(0.5);
Tan1 := TAN(0.5);
Asin1 := ASIN(0.5);
Acos1 := ACOS(0.5);
Min1 := MIN(DINT#3, -4, 7);
Move1 := MOVE(INT#42);
Shr1 := SHR(WORD#16#8001, 4);
Ror1 := ROR(BYTE#16#81, 1);
And1 := WORD#16#F0F0 AND WORD#16#FF00;
Or1 := WORD#16#F0F0 OR WORD#16#FF00;
Xor1 := WORD#16#F0F0 XOR WORD#16#FF00;
END_PROGRAM
""")
    assert plc.faults == []
    assert (main["AbsR"], main["AbsI"], main["Min1"], main["Move1"]) == (2.5, 7, -4, 42)
    assert main["Ln1"] == np.log(10.0) and main["Log1"] == np.log10(1000.0)
    assert main["Exp1"] == np.exp(0.5) and main["Expt1"] == 1024.0
    # the library calls Python's libm, NumPy its own: they may differ in the last bit
    for name, ref in (("Sin1", np.sin), ("Cos1", np.cos), ("Tan1", np.tan),
                      ("Asin1", np.arcsin), ("Acos1", np.arccos)):
        assert abs(main[name] - ref(0.5)) <= np.spacing(ref(0.5)), name
    # 16#8001 >> 4 = 16#0800; ROR of 1000_0001 by 1 = 1100_0000
    assert (main["Shr1"], main["Ror1"]) == (0x0800, 0xC0)
    assert (main["And1"], main["Or1"], main["Xor1"]) == (0xF000, 0xFFF0, 0x0FF0)
