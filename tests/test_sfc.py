"""Sequential Function Charts (IEC 61131-3 3rd ed. 6.7, textual form) run scan by scan.

The charts are tests/corpus/accept/sfc_*.st; every expected value below is
traced by hand from the chart and the rules in st_runtime/checker/sfc.py
(transitions on the steps active at the scan's start, then steps, then
actions; an action's body runs while Q and once more when Q falls).
"""

from __future__ import annotations

from pathlib import Path

from st_runtime.api import load

ACCEPT = Path(__file__).parent / "corpus" / "accept"
WATCHED = ("Left", "Right", "Delayed", "Leaving", "Lamp", "Wait.X", "A.X", "Done.X", "A.T")


def start(name: str, program: str):
    plc = load([str(ACCEPT / name)], dialect="iec").controller(period="1ms")
    return plc, plc.add_program(program)


def test_filler_n_p_and_l_actions():
    # Scan 1: Idle -> Fill (NOT Full).  OpenValve (N) sets Valve, Blink (L)
    # inverts it: FALSE.  Tally (P) counts 1; scan 2 is Tally's final scan: 2.
    plc, main = start("sfc_filler.st", "Filler")
    plc.run(1)
    assert (main["Idle.X"], main["Fill.X"], main["Count"], main["Valve"]) == (False, True, 1, False)
    plc.run(2)
    assert (main["Count"], main["Fill.T"]) == (2, "T#2ms")
    # Full: Fill -> Idle needs Fill.T > 1s as well; not before.
    main["Full"] = True
    plc.run(1)
    assert main["Fill.X"] is True
    assert plc.faults == []


def test_sequence_divergence_priority_stored_and_final_scans():
    plc, main = start("sfc_sequence.st", "Seq")
    main["Go"] = True
    rows = []
    for scan in range(1, 9):
        if scan == 7:
            main["Stop"] = True
        plc.run(1)
        rows.append([main[k] for k in WATCHED])
    # Scan 1: Wait -> (A, B) fires first, so Wait -> Done (TRUE, later in the
    # text) does not; A and B count; Lamp is set (S).
    assert rows[0] == [1, 1, 0, 0, True, False, True, False, "T#0s"]
    # Late (D, T#2ms) runs from B's third scan; A.T counts the scans.
    assert rows[2] == [3, 3, 1, 0, True, False, True, False, "T#2ms"]
    assert rows[3] == [4, 4, 2, 0, True, False, True, False, "T#3ms"]
    # Scan 5: A.T >= 3 ms: (A, B) -> Done.  CountLeft, CountRight and Late run
    # their final scan; Lamp is reset (R); A.T keeps its value.
    assert rows[4] == [5, 5, 3, 0, False, False, False, True, "T#3ms"]
    assert rows[5] == rows[4]
    # Scan 7: Stop: Done -> Wait; Leave (P0) pulses on Done's deactivation.
    assert rows[6] == [5, 5, 3, 1, False, True, False, False, "T#3ms"]
    # Scan 8: Go again: Wait -> (A, B); Leave's final scan; A.T restarts.
    assert rows[7] == [6, 6, 3, 2, True, False, True, False, "T#0s"]
    assert plc.faults == []


def test_chart_in_a_function_block():
    # Dark holds for Dark.T >= 2 ms (the value of the scan before): scans 1-3,
    # Bright on scans 4-5 (Bright.T >= 1 ms ends it), Dark 6-8, Bright 9-10,
    # Dark 11-12.  Light follows Bright.X, with Shine's final scan writing
    # FALSE; Count (P1) runs on the activation scan and its final scan: 2 a flash.
    plc, main = start("sfc_in_function_block.st", "Main")
    plc.run(4)
    assert (main["Lit"], main["B.Light"], main["B.Flashes"]) == (1, True, 1)
    plc.run(8)
    assert (main["Lit"], main["B.Light"], main["B.Flashes"]) == (4, False, 4)
    assert (main["B.Dark.X"], main["B.Bright.T"]) == (True, "T#1ms")
