"""``stgen demo``: generated code, summary table, CSV traces and PNG figures, exit status.

The waves, paths and the sea state are shortened here (the full runs are in test_scenarios.py and
test_scenarios_paths.py)."""

from __future__ import annotations

import csv

import pytest

from stgen import cli
from stgen.commands import demo
from stgen.scenarios import definitions, platforms, runner
from stgen.scenarios.csv_trace import HEADER

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


@pytest.fixture()
def short_waves(monkeypatch):
    monkeypatch.setattr(demo, "QUICK_WAVE_SECONDS", 0.3)
    monkeypatch.setattr(platforms, "PLATFORM_SCENARIOS", ())  # tests/test_platform_demo.py runs those
    monkeypatch.setattr(demo, "QUICK_PATH_FRACTION", 0.02)
    monkeypatch.setattr(demo, "QUICK_SEA_STATE_SECONDS", 1.0)


@pytest.fixture()
def no_paths(monkeypatch):
    """No path or playback scenario (one short run is enough)."""
    monkeypatch.setattr(demo, "_path_scenarios", lambda quick, scratch: [])


def test_demo_writes_code_traces_figures_and_passes(tmp_path, short_waves, capsys):
    assert cli.main(["demo", "--quick", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    # The summary table has the columns the issue asks for.
    for column in ("scenario", "duration", "scans", "max error", "faults", "max |v|", "max |a|"):
        assert column in out
    # Issue 8: the set-points' velocity and acceleration per cylinder against the actuator's limits.
    assert "limit 250 mm/s" in out and "limit 2500 mm/s²" in out and "Cmd.Pos" in out
    # Two rows (|v|, |a|) per scenario in the limits table, each within its limit.
    limit_rows = [line for line in out.splitlines() if "mm/s" in line and ("within" in line or "ABOVE" in line)]
    assert len(limit_rows) == 16 and all("within" in line for line in limit_rows)
    # Issue 8 section 4: one estimated NJ501 time line per scenario, against the 80 % rule.
    assert out.count("estimated NJ501 time per scan") == 8
    # Issue 12: the four path families and the playback of the recorded sea state, written beside the traces.
    assert (tmp_path / "sea_state_10hz.csv").read_text().startswith("t,x,y,z,alpha,beta,gamma\n")
    for name in ("point_to_point", "airy_wave", "random_wave", "path_epitrochoid", "path_epicycloid",
                 "path_hypocycloid", "path_spiral", "playback"):
        assert name in out
        assert (tmp_path / f"{name}.png").read_bytes()[:8] == PNG_SIGNATURE
        with (tmp_path / f"{name}.csv").open() as stream:
            rows = list(csv.reader(stream))
        assert tuple(rows[0]) == HEADER
        # --quick keeps one scan in ten, with the ends of each state's stretch: no gap wider than ten.
        scans = [int(row[1]) for row in rows[1:]]
        assert scans[0] == 1 and all(0 < b - a <= 10 for a, b in zip(scans, scans[1:]))
        assert set(range(1, scans[-1], 10)) <= set(scans)
        # The time base of stgen run --trace: scan k at (k - 1) * 1 ms.
        assert rows[1][0] == "0.0"
        assert all(float(row[0]) == pytest.approx((int(row[1]) - 1) * 1e-3, abs=1e-12) for row in rows[1:])
        assert rows[1][3] == "SP_STATE_POWERING"
        errors = [float(row[-1]) for row in rows[1:]]
        assert max(errors) <= 1e-6
    assert "All scenarios passed" in out
    # --quick moves a tenth of each displacement at the study's limits: 2h/v = 2*10/20 = 1 s for
    # 10 mm at 20 mm/s and for 1 deg at 2 deg/s, 0.6 s for 0.6 deg.
    assert "12 moves planned by SP_Controller (SpMoveDuration): " + ", ".join(
        ["1.000"] * 6 + ["0.600"] * 4 + ["1.000"] * 2) + " s" in out
    # The controller code was generated for both targets.
    assert (tmp_path / "generated" / "iec" / "SP_Controller.st").is_file()
    assert (tmp_path / "generated" / "nj501" / "SP_Controller.variables.tsv").is_file()
    # --quick shortens the point-to-point moves too (8 of 1 s, 4 of 0.6 s, 0.1 s standstill after
    # each): 8*1,001 + 4*601 + 12*100 = 11,612 scans after the first command, not 110,012; the CSV
    # keeps about one in ten of them.
    with (tmp_path / "point_to_point.csv").open() as stream:
        rows = list(csv.reader(stream))[1:]
    assert 11_612 < int(rows[-1][1]) < 12_000
    assert 1_161 < len(rows) < 1_400


def test_demo_csv_headers_carry_units():
    for column in ("time_s", "x_mm", "alpha_deg", "gamma_deg", "ref_z_mm", "q1_mm", "ref_q6_mm", "max_error_mm"):
        assert column in HEADER
    assert not {"x", "alpha", "q1", "time"} & set(HEADER)


def test_demo_exits_1_when_a_scenario_fails(tmp_path, short_waves, no_paths, monkeypatch, capsys):
    monkeypatch.setattr(runner, "MAX_ERROR_MM", 0.0)  # nothing can pass an error limit of zero
    monkeypatch.setattr(definitions, "SCENARIOS", (definitions.AIRY_WAVE,))  # one short run is enough
    assert cli.main(["demo", "--quick", "--out", str(tmp_path)]) == 1
    assert "FAILED" in capsys.readouterr().out


def test_demo_reports_a_bad_config(tmp_path, capsys):
    bad = tmp_path / "bad.toml"
    bad.write_text("[geometry]\nrb = -1.0\n")
    assert cli.main(["demo", "--config", str(bad), "--out", str(tmp_path / "o")]) == 1
    assert "geometry.rb" in capsys.readouterr().err


def test_demo_fails_a_scenario_whose_setpoints_exceed_the_actuator_acceleration(tmp_path, short_waves, no_paths,
                                                                                 monkeypatch, capsys):
    # The Airy wave's fade-in accelerates the cylinders at about 110 mm/s^2 (planned within the pose limits,
    # 500 mm/s^2): an actuator limited to 50 mm/s^2 must fail the scenario, whatever the position error.
    config = tmp_path / "slow.toml"
    config.write_text("[actuator]\nmax_acceleration = 50.0\n")
    monkeypatch.setattr(definitions, "SCENARIOS", (definitions.AIRY_WAVE,))
    assert cli.main(["demo", "--quick", "--config", str(config), "--out", str(tmp_path / "o")]) == 1
    out = capsys.readouterr().out
    assert "ABOVE" in out and "FAILED" in out


def test_a_thinned_trace_keeps_one_scan_in_n_and_both_ends_of_each_state():
    from types import SimpleNamespace

    import numpy as np

    from stgen.scenarios.csv_trace import kept_rows

    # 25 scans: state 1 for scans 1-4, state 2 for 5-20, a fault on scans 13-14, state 3 for 21-25.
    state = np.array([1] * 4 + [2] * 16 + [3] * 5)
    fault = np.zeros(25, dtype=int)
    fault[12:14] = 7
    result = SimpleNamespace(scans=25, state=state, fault_id=fault)
    # rows (scan - 1): every tenth 0, 10, 20; state ends 3, 4, 19, 20; fault ends 11, 12, 13, 14; the last 24.
    assert kept_rows(result, 10) == [0, 3, 4, 10, 11, 12, 13, 14, 19, 20, 24]
    assert kept_rows(result, 1) == list(range(25))
