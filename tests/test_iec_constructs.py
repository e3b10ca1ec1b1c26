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
