"""The rest of IEC 61131-3 (issue 13): each construct's accept file run scan by scan.

The ST lives in tests/corpus/accept/*.st (the checker and compiler corpora and
the fuzzers read it too); the expected values below are worked out by hand
from the programs' text and the standard.
"""

from __future__ import annotations

from pathlib import Path

from st_runtime.api import load

ACCEPT = Path(__file__).parent / "corpus" / "accept"


def run(name: str, scans: int, program: str = "Main", dialect: str = "iec", sets=None):
    project = load([str(ACCEPT / name)], dialect=dialect)
    plc = project.controller(period="1ms")
    main = plc.add_program(program)
    for path, value in (sets or {}).items():
        main[path] = value
    plc.run(scans)
    return plc, main


def test_pragmas_change_nothing():
    # Count grows by Step = 2 per scan: 2, 4, 6.
    plc, main = run("pragma_anywhere.st", 3)
    assert main["Total"] == 6 and main["C.Count"] == 6
    assert main["Text"] == "{not a pragma}"   # braces inside a string are text
    assert plc.faults == []


def test_edge_inputs_count_edges_and_bool_digits():
    # Signal over scans 1..6 = 0 1 1 0 1 0 (then repeats).  Rising edges on
    # scans 2 and 5; falling edges on scans 4 and 6 (scan 1 is FALSE after
    # FALSE: the memory starts FALSE, so no edge).  After 6 scans: 2 and 2;
    # after 8 (scans 7, 8 = 0, 1): one more rise.
    plc, main = run("edge_inputs_and_bool_digits.st", 6)
    assert (main["Rises"], main["Falls"]) == (2, 2)
    assert main["Counter.SawUp"] is True
    assert main["Counter.Up"] is False            # the caller sees the raw input
    plc.run(2)
    assert (main["Rises"], main["Falls"]) == (3, 2)
    assert main["Pattern"] == [False, True, True, False, True, False]
    assert plc.faults == []


def test_edge_input_on_the_first_call_is_a_rising_edge():
    # R_TRIG's memory starts FALSE: TRUE at the first call is an edge.
    plc, main = run("edge_inputs_and_bool_digits.st", 1, sets={"Pattern[0]": True})
    assert main["Rises"] == 1 and main["Falls"] == 0


def test_operators_in_call_form_and_bcd():
    plc, main = run("operators_in_call_form.st", 1)
    # A = 7, B = 3: by hand.
    assert [main[n] for n in ("Sum", "Diff", "Prod", "Quot", "Rest", "Total")] == [10, 4, 21, 2, 1, 21]
    # GT(10, 7, 3) is 10 > 7 AND 7 > 3; AND(3 <= 7, 7 < 8).
    assert [main[n] for n in ("Bigger", "Chain", "Same", "Differ", "Fits")] == [True] * 5
    assert (main["Both"], main["Either"]) == (0x00F0, 0x0FF0)
    assert [main[n] for n in ("Longer", "Shorter", "Tripled", "Halved")] == \
        ["T#1s500ms", "T#750ms", "T#3s", "T#500ms"]
    assert main["Later"] == "TOD#11:30:00"
    assert main["Gap"] == "T#2d"                 # 2024 is a leap year: Feb 28 -> Mar 1
    assert (main["Decoded"], main["Encoded"]) == (1234, 0x1235)
    assert (main["Decoded3"], main["Encoded3"]) == (99, 0x42)
    assert plc.faults == []


def test_bcd_with_a_nibble_above_nine_is_a_convert_fault():
    plc, main = run("operators_in_call_form.st", 1, sets={"Bcd": 0x12A4})
    assert [f.code for f in plc.faults] == ["F-CONVERT"]
    assert main["Decoded"] == 0                  # the faulting statement is abandoned


def test_en_false_skips_the_callee_and_clears_eno():
    # Scan 1: Enable FALSE -> nothing runs, results are INT's initial 0,
    # the ENOs FALSE; INT_TO_REAL without EN runs (ENO TRUE).
    plc, main = run("en_eno_calls.st", 1)
    assert (main["Doubled"], main["Biggest"], main["Counter.Count"]) == (0, 0, 0)
    assert (main["DoubledOk"], main["MaxOk"], main["TallyOk"]) == (False, False, False)
    assert main["Converted"] is True and main["Real1"] == 1.0
    # Scans 2 and 4 enabled: Tally adds 10 twice; at scan 4 Twice(4) = 8, MAX(4, 3) = 4.
    plc.run(3)
    assert (main["Doubled"], main["Biggest"], main["Counter.Count"]) == (8, 4, 20)
    assert (main["DoubledOk"], main["MaxOk"], main["TallyOk"]) == (True, True, True)
    assert plc.faults == []


def test_subrange_stores_are_checked_and_start_at_the_lower_limit():
    plc, main = run("subrange_types.st", 4)
    # Level: 0 (lower limit) + 30 per scan -> 30, 60, 90; 120 faults, stays 90.
    # Setting: starts at its lower limit 10 -> 14.  Lift: TYPE init 0 -> -1, -2,
    # then -3 faults twice.
    assert (main["Level"], main["Setting"], main["Lift"]) == (90, 14, -2)
    faults = [(f.code, f.line) for f in plc.faults]
    # Lines of the Lift (22) and Level (20) stores; the two expect comments are lines 3-4.
    assert faults == [("F-SUBRANGE", 22), ("F-SUBRANGE", 20), ("F-SUBRANGE", 22)]


def test_subrange_refuses_an_outside_value_from_the_api():
    import pytest

    project = load([str(ACCEPT / "subrange_types.st")])
    main = project.controller().add_program("Main")
    with pytest.raises(ValueError, match="outside the range of INT \\(0..100\\)"):
        main["Level"] = 150
    main["Level"] = 100
    assert main["Level"] == 100


def test_located_variables_share_the_process_image():
    project = load([str(ACCEPT / "located_variables.st")])
    plc = project.controller(period="1ms")
    main = plc.add_program("Main")
    plc.image["%IX0.0"] = True
    plc.image["%IW1"] = 300                      # bytes 2..3 of %I
    plc.run(1)
    assert main["Start"] is True and main["Level"] == 300
    assert plc.image["%QX0.1"] is True           # Lamp := Start
    assert plc.image["%QX1.7"] is True           # the global Alarm: 300 > 100
    assert main["Speed"] == 150.0
    # %QD1 holds REAL 150.0 as IEEE single: 16#43160000.
    assert plc.image["%QD1"] == 0x43160000
    # Word1 := 16#8001 at %MW1 = bytes 2 (16#01), 3 (16#80), little-endian.
    assert (main["Low"], main["High"], main["Bit0"], main["Bit15"]) == (1, 0x80, True, True)
    assert main["Count"] == 0x01 + 0x80
    assert main["Double0"] == 0x80010000         # %MD0 = bytes 0..3
    # A store through one name is seen through the others at once.
    main["Low"] = 0xFE
    assert main["Word1"] == 0x80FE and main["Bit0"] is False
    assert plc.image["%MB2"] == 0xFE
    assert main["Spare"] == 0                    # %M*: an ordinary variable


def test_image_refuses_bad_addresses_and_values():
    import pytest

    plc = load([str(ACCEPT / "located_variables.st")]).controller()
    with pytest.raises(KeyError, match="bit 0..7"):
        plc.image["%IX0.8"] = True
    with pytest.raises(ValueError, match="0..65535"):
        plc.image["%IW0"] = 70000
    with pytest.raises(ValueError, match="true or false"):
        plc.image["%IX0.0"] = 1


def test_in_out_read_from_outside_and_function_without_result():
    # Sum grows by 7 per scan through the in-out; Seen reads it back; Split
    # gives its tens and units: after 3 scans Sum = 21 -> 2 and 1.
    plc, main = run("in_out_read_and_function_without_result.st", 3)
    assert (main["Sum"], main["Seen"], main["T"], main["U"]) == (21, 21, 2, 1)
    assert plc.faults == []


def test_methods_dispatch_on_the_instance():
    # Rect 2 x 3 -> 6; Square 4 x 4: SUPER.Area() (Rect's, 16) + 0.5 = 16.5;
    # through the interface variable the Square's method runs; Describe (in
    # the abstract base) calls THIS.Area(): the Square's, x 10 = 165.
    plc, main = run("oo_methods_interfaces.st", 1)
    assert (main["A1"], main["A2"], main["D2"]) == (6.0, 16.5, 165.0)
    assert main["Sum"] == 6.0 + 16.5              # the array of IShape, one of each
    assert main["S.Calls"] == 1 and main["R.Calls"] == 0
    assert main["Any"] == "Square" and main["Shapes"] == ["Rect", "Square"]
    assert plc.faults == []


def test_a_method_call_through_an_empty_interface_variable_faults():
    plc, main = run("oo_methods_interfaces.st", 1, program="Unbound")
    assert [f.code for f in plc.faults] == ["F-NULL-REF"]
    assert main["Result"] == -1.0 and main["Nobody"] is None


def test_references_read_and_write_what_they_refer_to():
    # Per scan: A := 10 through RA; Bump adds 1 to B and to Arr[2]; Y = P.Y + A
    # = 7 + 10; RA then NULL: Bump skips it, RA^ := 99 faults.  Two scans.
    plc, main = run("references_ref_to.st", 2)
    assert (main["A"], main["B"], main["Arr"], main["Y"]) == (10, 2, [0, 2, 0], 17)
    assert main["P"] == {"X": 0, "Y": 7}
    assert (main["Same"], main["Empty"], main["RA"], main["RP"]) == (True, True, None, "REF")
    assert [f.code for f in plc.faults] == ["F-NULL-REF", "F-NULL-REF"]


def test_codesys_pointers_and_bit_access():
    plc, main = run("codesys_pointers_and_bits.st", 1, dialect="codesys")
    assert main["Value"] == 15                                  # 5 * 3 through the pointer
    assert (main["Bit0"], main["Bit1"], main["Bit2"]) == (True, False, True)   # 16#0005
    assert main["Flags"] == 0x8004 and main["Top"] is True      # bit 15 set, bit 0 cleared
    assert main["Signed"] == 0x7FFF                             # -1 (16#FFFF) without bit 15
    assert (main["Lamp"], main["Alarm"]) == (True, False)       # S= by Bit0, R= by Bit2
    assert plc.faults == []


def test_a_dialect_mismatch_names_the_dialect_that_accepts_it():
    import pytest

    from st_runtime.api import LoadError

    with pytest.raises(LoadError) as refused:
        load([str(ACCEPT / "codesys_pointers_and_bits.st")], dialect="iec")
    text = refused.value.render()
    assert "POINTER TO is not accepted by --dialect iec; --dialect codesys accepts it" in text
    assert "bit access x.3 is not accepted by --dialect iec; --dialect codesys or --dialect nj" in text
    with pytest.raises(LoadError) as refused:
        load([str(ACCEPT / "oo_methods_interfaces.st")], dialect="nj")
    assert "METHOD is not accepted by --dialect nj; --dialect codesys or --dialect iec" \
        in refused.value.render()


def test_partial_access_reads_and_writes_parts_of_a_bit_string():
    plc, main = run("partial_access.st", 1)
    # D = 16#12345678: byte 0 = 16#78, byte 3 = 16#12, word 1 = 16#1234,
    # 16#78 = 2#0111_1000 -> bits 4 and 5 set; then byte 2 := 16#FF.
    assert (main["B0"], main["B3"], main["W1"]) == (0x78, 0x12, 0x1234)
    assert (main["X4"], main["X5"]) == (True, True)
    assert main["D"] == 0x12FF5678
    assert main["L"] == 0xABCD_0000_0000_0001
    assert plc.faults == []


def test_time_to_number_counts_ms_under_codesys_and_ns_under_nj():
    # CODESYS/TwinCAT: a TIME's number is milliseconds; the NJ (and iec here):
    # nanoseconds (W501, TIME; TimeToNanoSec).
    from st_runtime.api import load_text

    source = """
PROGRAM Main
VAR Ms : LINT; Back, Negative : TIME; R : LREAL; END_VAR
Ms := TIME_TO_LINT(T#1s500ms);
Back := DINT_TO_TIME(250);
Negative := DINT_TO_TIME(-3);
R := TIME_TO_LREAL(T#1500us);
END_PROGRAM
"""
    expected = {"codesys": (1500, "T#250ms", "T#-3ms", 1.5),
                "nj": (1_500_000_000, "T#250ns", "T#-3ns", 1_500_000.0),
                "iec": (1_500_000_000, "T#250ns", "T#-3ns", 1_500_000.0)}
    for dialect, values in expected.items():
        plc = load_text(source, dialect=dialect).controller()
        main = plc.add_program("Main")
        plc.run(1)
        assert (main["Ms"], main["Back"], main["Negative"], main["R"]) == values, dialect


def test_codesys_actions_run_on_the_instance():
    # Count: 1, 2, 3 then Reset at scan 3 -> 0; 1, 2 at scans 4, 5.
    plc, main = run("codesys_actions.st", 5, dialect="codesys")
    assert (main["Seen"], main["C.Count"]) == (2, 2)
    assert plc.faults == []


def test_namespaces_qualified_and_short_names():
    # Distance of (3, 4) from the origin = 5 both ways; 2500 mm = 2.5 m.
    plc, main = run("namespaces.st", 1)
    assert (main["D"], main["Short"], main["M"]) == (5.0, 5.0, 2.5)
    assert plc.faults == []


def test_open_arrays_take_the_bounds_of_the_argument():
    # 1 + 2 + 3 = 6; 10 + ... + 50 = 150; the 2 x 2 table times 3.
    plc, main = run("open_arrays.st", 1)
    assert (main["S1"], main["S2"], main["Low"], main["High"]) == (6, 150, -2, 6)
    assert main["Table"] == [[3, 6], [9, 12]]
    assert plc.faults == []


def test_open_array_index_outside_the_arguments_bounds_faults():
    plc, main = run("open_arrays.st", 1, program="Beyond")
    assert [f.code for f in plc.faults] == ["F-INDEX"]
    assert "index 4 of 'Values' out of bounds 1..3" in plc.faults[0].message
    # The faulting statement inside the function is abandoned; the function
    # returns its result's initial value, 0.
    assert main["R"] == 0


def test_codesys_properties_call_their_get_and_set():
    # Speed := 12.5 -> SET stores 125.0 (x 10), counts one write; GET gives 12.5;
    # Running reads THIS.Speed > 0.
    plc, main = run("codesys_properties.st", 1, dialect="codesys")
    assert (main["Read"], main["IsOn"]) == (12.5, True)
    assert (main["M.RawSpeed"], main["M.Writes"]) == (125.0, 1)
    assert plc.faults == []


def test_union_members_share_their_bytes():
    # REAL 1.0 is IEEE 16#3F800000: its low word is 0.  V := U copies the bytes,
    # then V's low word 16#0001 sets bit 0 (Flag) and leaves U alone.
    plc, main = run("codesys_unions.st", 1, dialect="codesys")
    assert (main["Bits"], main["Low"]) == (0x3F80_0000, 0)
    assert (main["U.AsDword"], main["U.Flag"]) == (0x3F80_0000, False)
    assert (main["V.AsDword"], main["V.LowWord"], main["F"]) == (0x3F80_0001, 1, True)
    for dialect in ("codesys", "nj"):
        load([str(ACCEPT / "codesys_unions.st")], dialect=dialect)   # both accept UNION


def test_direct_variables_in_code_use_the_image():
    project = load([str(ACCEPT / "direct_variables.st")])
    plc = project.controller()
    main = plc.add_program("Main")
    plc.image["%IX0.0"] = True
    plc.image["%IW1"] = 300
    plc.run(1)
    assert plc.image["%QX0.1"] is True            # %QX0.1 := %IX0.0
    assert plc.image["%QX0.2"] is True            # AT %QX0.2 : BOOL := 1
    assert main["Copy"] == -5 and main["Seen"] is True
    assert plc.image["%MW2"] == 301               # %IW1 reads as Level's INT
    assert main["Sum"] == 300 - 5
    assert plc.faults == []


def test_codesys_enum_value_with_a_dot():
    # State starts Amber (1): CASE takes Amber -> Next := Red, Code := 2;
    # Next = Red adds 10: 12.  Scan 2: Red -> Green, Code 1.  Scan 3: Green -> Amber, 3.
    plc, main = run("codesys_enum_dot.st", 1, dialect="codesys")
    assert (main["State"], main["Code"]) == ("Red", 12)
    plc.run(1)
    assert (main["State"], main["Code"]) == ("Green", 1)
    plc.run(1)
    assert (main["State"], main["Code"]) == ("Amber", 3)


def test_own_standard_fb_replaces_the_built_in():
    # The project's R_TRIG counts calls and copies CLK: after 3 scans with
    # CLK TRUE, Q is TRUE every scan (3 highs); the built-in would give one edge.
    plc, main = run("own_standard_fb.st", 3)
    assert (main["Highs"], main["Edge.Calls"]) == (3, 3)
    from st_runtime.loader import load_texts
    text = (ACCEPT / "own_standard_fb.st").read_text()
    found = [(d.code, d.pos.line) for d in load_texts({"f.st": text}, "iec").diagnostics]
    assert ("W-DECL-001", 3) in found and not any(c.startswith("E-") for c, _ in found)


def test_codesys_pou_writes_its_inputs():
    # Clamp10(25): X is cut to 10, returns 20; Clamp10(4) = 8; the caller's Big
    # stays 25 (an input is a copy).  Countdown from 10 by 3: 7, 4, 1, -2 (4 steps),
    # and the instance's N keeps -2.  SumTo(2) loops I over its input: 2+3+4 = 9.
    plc, main = run("codesys_input_written.st", 1, dialect="codesys")
    assert [main[n] for n in ("Big", "A", "B", "C")] == [25, 20, 8, 9]
    assert (main["Down.Steps"], main["Down.N"]) == (4, -2)


def test_codesys_super_body_runs_the_base_body():
    # Step 2.  Scan 1: SUPER^() -> Count 2 (Slow).  Scan 2: Count 4 -> Fast,
    # so SUPER^() again -> 6.  Scan 3: 8, then 10.  Mode.Fast names the value
    # although a variable Mode of type Mode is in scope.
    plc, main = run("codesys_super_body.st", 1, dialect="codesys")
    assert (main["T.Count"], main["T.Mode"]) == (2, "Slow")
    plc.run(2)
    assert (main["T.Count"], main["T.Mode"], main["T.Calls"]) == (10, "Fast", 3)


def test_typed_string_literals():
    # STRING#'ABC' is 'ABC'; '$'' is a quote and '$"' a double quote (table 6):
    # Joined = 'ABC' + '-' + "'D'" = ABC-'D' (7 characters).
    plc, main = run("typed_string_literals.st", 1)
    assert (main["Plain"], main["Wide"], main["Joined"]) == ("ABC", 'x"y', "ABC-'D'")
    assert (main["Same"], main["Size"]) == (True, 7)
