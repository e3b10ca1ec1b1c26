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
