"""`stgen run --axes FILE.toml`: the program drives simulated servo axes."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from stgen.cli import main

ROOT = Path(__file__).resolve().parent.parent

RAMP = """
PROGRAM Main
VAR
    Power : MC_Power;
    Sync : MC_SyncMoveAbsolute;
    Target : LREAL;
    Commanded : LREAL;
END_VAR
Power(Axis := Cyl1, Enable := TRUE);
IF Power.Status THEN
    Target := Target + 0.5;
    Sync(Axis := Cyl1, Execute := TRUE, Position := Target, BufferMode := _mcAborting);
END_IF;
Commanded := Cyl1.Cmd.Pos;
END_PROGRAM
"""

AXES = """
[[axis]]
name = "Cyl1"
max_velocity = 1000.0
soft_limit_min = 0.0
soft_limit_max = 600.0
"""


def stgen(capsys, *argv):
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


@pytest.fixture
def ramp(tmp_path):
    (tmp_path / "main.st").write_text(RAMP)
    (tmp_path / "axes.toml").write_text(AXES)
    return tmp_path


def test_program_powers_an_axis_and_moves_it(ramp, capsys):
    # Scan 1 enables the servo (MC_Power.Status is TRUE from scan 2); scans
    # 2..5 command 0.5, 1.0, 1.5, 2.0 mm.  The program reads Cmd.Pos before
    # motion processing, so scan 5 sees scan 4's command, 1.5 mm.
    csv = ramp / "trace.csv"
    code, out, err = stgen(capsys, "run", ramp / "main.st", "--axes", ramp / "axes.toml",
                           "--program", "Main", "--cycles", "5", "--json",
                           "--trace", csv, "--watch", "Cyl1.Cmd.Pos,Cyl1.Status.Discrete")
    assert code == 0, err
    data = json.loads(out)
    assert data["Target"] == 2.0 and data["Commanded"] == 1.5
    assert data["Power"]["Status"] is True and data["Sync"]["Error"] is False
    rows = [line.split(",") for line in csv.read_text().splitlines()]
    # Status.Discrete, not Synchronized: MC_SyncMoveAbsolute keeps the axis in
    # Discrete on the NJ (docs/nj501.md; this test watched Synchronized before issue 8).
    assert rows[0] == ["time_s", "scan", "Cyl1.Cmd.Pos", "Cyl1.Status.Discrete"]
    assert [float(r[2]) for r in rows[1:]] == [0.0, 0.5, 1.0, 1.5, 2.0]
    assert [r[3] for r in rows[1:]] == ["FALSE", "TRUE", "TRUE", "TRUE", "TRUE"]


def test_a_step_above_the_velocity_limit_saturates_at_the_maximum_velocity(ramp, capsys):
    # Changed in issue 8: this test asserted an axis error (ErrorStop) for a
    # step above the maximum velocity; OMRON's MC_SyncMoveAbsolute saturates
    # instead (docs/nj501.md).  Scan 2 asks for 0.5 mm in a 1 ms scan, 500 mm/s, on a
    # 100 mm/s axis: the command moves 0.1 mm per scan, VelLimit TRUE, no error.
    # Targets 0.5, 1.0, 1.5, 2.0 in scans 2..5; commands 0.1, 0.2, 0.3, 0.4.
    (ramp / "slow.toml").write_text(AXES.replace("1000.0", "100.0"))
    csv = ramp / "trace.csv"
    code, out, err = stgen(capsys, "run", ramp / "main.st", "--axes", ramp / "slow.toml",
                           "--program", "Main", "--cycles", "5", "--json", "--trace", csv,
                           "--watch", "Cyl1.Status.ErrorStop,Cyl1.Details.VelLimit,Cyl1.Cmd.Pos")
    assert code == 0, err
    rows = [line.split(",")[2:] for line in csv.read_text().splitlines()[1:]]
    assert [r[:2] for r in rows] == [["FALSE", "FALSE"]] + [["FALSE", "TRUE"]] * 4
    assert [float(r[2]) for r in rows] == pytest.approx([0.0, 0.1, 0.2, 0.3, 0.4])
    data = json.loads(out)
    assert data["Sync"]["CommandAborted"] is False and data["Sync"]["Error"] is False


def test_without_axes_the_axis_is_undeclared(ramp, capsys):
    code, out, err = stgen(capsys, "run", ramp / "main.st", "--program", "Main")
    assert code == 1 and "undeclared name 'Cyl1'" in err


def test_example_axes_file_runs_the_example_program(capsys):
    # 100 scans: the ramp starts on scan 2, so Target1 = 99 * 0.1 = 9.9 mm and
    # scan 100 reads scan 99's command, 9.8 mm; Cyl2 has a 2 ms servo lag,
    # so its actual position trails its command without a following error.
    code, out, err = stgen(capsys, "run", ROOT / "examples" / "axes_demo.st",
                           "--axes", ROOT / "examples" / "axes.toml",
                           "--program", "AxesDemo", "--cycles", "100", "--json")
    assert code == 0, err
    data = json.loads(out)
    assert data["Target1"] == pytest.approx(9.9) and data["Commanded1"] == pytest.approx(9.8)
    assert 0 < data["Target2"] - data["Actual2"] < 5.0
    assert not data["Sync2"]["Error"]


@pytest.mark.parametrize("text, expected", [
    ('[[axis]]\nname = "Cyl1"\nmax_velocity =\n', "not valid TOML: Invalid value (at line 3"),
    ('[[axis]]\nname = "Cyl1"\nmax_velocity = -3\n', "axis 'Cyl1': key 'max_velocity' must be a positive"),
    ('[[axis]]\nname = "Cyl1"\nmax_velocity = 3\nspeed = 2\n', "axis[0]: unknown key 'speed'"),
    ('[[axis]]\nname = "2nd"\nmax_velocity = 3\n', "axis[0]: key 'name' must be an ST identifier"),
    ('[[axis]]\nname = "Cyl1"\nmax_velocity = "fast"\n', "key 'max_velocity' must be a number"),
    ("title = 'no axes'\n", "expected at least one [[axis]] table"),
    ('[[axis]]\nname = "A"\nmax_velocity = 3\n[[axis]]\nname = "a"\nmax_velocity = 3\n',
     "key 'name' duplicates another axis"),
])
def test_bad_axes_file_is_one_line_naming_file_and_key(ramp, capsys, text, expected):
    (ramp / "bad.toml").write_text(text)
    code, out, err = stgen(capsys, "run", ramp / "main.st", "--axes", ramp / "bad.toml", "--program", "Main")
    assert code == 1 and out == ""
    assert err.startswith(f"stgen run: error: {ramp / 'bad.toml'}: ") and expected in err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err


def test_binary_axes_file(ramp, capsys):
    (ramp / "bin.toml").write_bytes(b"\x00\xff\xfe binary")
    code, _, err = stgen(capsys, "run", ramp / "main.st", "--axes", ramp / "bin.toml", "--program", "Main")
    assert code == 1 and "not UTF-8 text" in err and "bin.toml" in err


@pytest.mark.parametrize("which", ["missing.toml", "."])
def test_axes_path_that_is_no_file_is_a_usage_error(ramp, capsys, which):
    code, _, err = stgen(capsys, "run", ramp / "main.st", "--axes", ramp / which, "--program", "Main")
    assert code == 2 and err.startswith("stgen run: error: --axes: ")
