"""``stgen demo`` runs the platform variants' scenarios too (issue 11): progress, a table row each,
a CSV trace and a PNG each; exit 1 when one fails."""

from __future__ import annotations

import csv

import pytest

from stgen import cli
from stgen.commands import demo, demo_platforms
from stgen.scenarios import definitions, platform_report, platforms

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


@pytest.fixture()
def two_short_platform_runs(monkeypatch):
    monkeypatch.setattr(definitions, "SCENARIOS", ())  # tests/test_scenarios_demo.py runs the study's
    monkeypatch.setattr(platforms, "PLATFORM_SCENARIOS", tuple(
        platforms.platform_scenario(name) for name in ("moving_base_motion", "crank_surge")))
    monkeypatch.setattr(demo_platforms, "QUICK_STREAM_SECONDS", 0.3)
    monkeypatch.setattr(demo, "_path_scenarios", lambda quick, scratch: [])  # tests/test_scenarios_paths.py


def test_demo_runs_the_platform_scenarios(tmp_path, two_short_platform_runs, capsys):
    assert cli.main(["demo", "--quick", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "Platform variants" in out and "γ/ψ/tilt°" in out and "start|a|" in out
    rows = [line for line in out.splitlines()
            if line.strip().startswith(("moving_base_motion ", "crank_surge ")) and "━" not in line]
    assert len(rows) == 2 and all("hold" in row and "pass" in row for row in rows)
    for name, axis in (("moving_base_motion", "q1_mm"), ("crank_surge", "theta1_deg")):
        assert (tmp_path / f"{name}.png").read_bytes()[:8] == PNG_SIGNATURE
        with (tmp_path / f"{name}.csv").open() as stream:
            table = list(csv.reader(stream))
        header = table[0]
        assert axis in header and "base_z_mm" in header and header[-1] == "max_error"
        assert ("gamma1_deg" in header) == (name == "moving_base_motion")
        assert table[1][0] == "0.0" and table[1][1] == "1"
        assert max(float(row[-1]) for row in table[1:]) <= platform_report.PLATFORM_MAX_ERROR
        # 0.3 s streamed at 1 ms: 301 set-points after power-on and the hold. --quick keeps one scan
        # in ten and the first and last scan of each state: the stretch's ends are in the CSV.
        track = [int(row[1]) for row in table[1:] if row[3] == "SP_STATE_TRACK"]
        assert track[-1] - track[0] + 1 == 301 and 30 <= len(track) <= 33
    assert out.count("estimated NJ501 time per scan") == 2
    assert "All scenarios passed" in out


def test_demo_exits_1_when_a_platform_scenario_fails(tmp_path, two_short_platform_runs, monkeypatch, capsys):
    monkeypatch.setattr(platform_report, "PLATFORM_MAX_ERROR", -1.0)  # no error is below zero
    assert cli.main(["demo", "--quick", "--out", str(tmp_path)]) == 1
    assert "FAILED: moving_base_motion, crank_surge" in capsys.readouterr().out
