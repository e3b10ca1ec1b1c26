"""``stgen demo``: generated code, summary table, CSV traces and PNG figures, exit status.

The waves are shortened here (the full 60 s runs are in test_scenarios.py)."""

from __future__ import annotations

import csv

import pytest

from stgen import cli
from stgen.commands import demo
from stgen.scenarios import runner
from stgen.scenarios.csv_trace import HEADER

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


@pytest.fixture()
def short_waves(monkeypatch):
    monkeypatch.setattr(demo, "QUICK_WAVE_SECONDS", 0.3)


def test_demo_writes_code_traces_figures_and_passes(tmp_path, short_waves, capsys):
    assert cli.main(["demo", "--quick", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    # The summary table has the columns the issue asks for.
    for column in ("scenario", "duration", "scans", "max error", "faults"):
        assert column in out
    for name in ("point_to_point", "airy_wave", "random_wave"):
        assert name in out
        assert (tmp_path / f"{name}.png").read_bytes()[:8] == PNG_SIGNATURE
        with (tmp_path / f"{name}.csv").open() as stream:
            rows = list(csv.reader(stream))
        assert tuple(rows[0]) == HEADER
        assert [int(row[1]) for row in rows[1:4]] == [1, 2, 3]
        errors = [float(row[-1]) for row in rows[1:]]
        assert max(errors) <= 1e-6
    assert "All scenarios passed" in out
    # The controller code was generated for both targets.
    assert (tmp_path / "generated" / "iec" / "SP_Controller.st").is_file()
    assert (tmp_path / "generated" / "nj501" / "SP_Controller.variables.tsv").is_file()
    # The point-to-point move is 10 s + 0.5 s settling after power-on: more than 10,500 rows.
    with (tmp_path / "point_to_point.csv").open() as stream:
        assert sum(1 for _ in stream) - 1 > 10_500


def test_demo_exits_1_when_a_scenario_fails(tmp_path, short_waves, monkeypatch, capsys):
    monkeypatch.setattr(runner, "MAX_ERROR_MM", 0.0)  # nothing can pass an error limit of zero
    assert cli.main(["demo", "--quick", "--out", str(tmp_path)]) == 1
    assert "FAILED" in capsys.readouterr().out


def test_demo_reports_a_bad_config(tmp_path, capsys):
    bad = tmp_path / "bad.toml"
    bad.write_text("[geometry]\nrb = -1.0\n")
    assert cli.main(["demo", "--config", str(bad), "--out", str(tmp_path / "o")]) == 1
    assert "geometry.rb" in capsys.readouterr().err
