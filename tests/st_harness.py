"""Helpers of the ST tests of paths and playback: a rendered program with a test harness, and
scanning until a planning pass ends."""

from __future__ import annotations

from st_runtime import api
from stgen.scenarios.program import iec_sources


def load_with_harness(rendered, harness: str):
    """The rendered POUs (IEC text) plus ``harness`` (ST source of the test programs), loaded."""
    sources = iec_sources(rendered)
    sources["harness.st"] = harness
    return api.load_sources(sources)


def scan_while_planning(plc, program, instance: str) -> int:
    """Scan until ``instance.Planning`` is FALSE after a scan; the number of scans."""
    scans = 0
    while True:
        plc.scan()
        scans += 1
        if not program[f"{instance}.Planning"]:
            return scans
