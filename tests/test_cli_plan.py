"""`stgen plan` (issue 12): extremes against an independent IK sampling, refusals with the leg, errors."""

from __future__ import annotations

import json

import numpy as np
import pytest

from stgen.cli import main
from stgen.config import PlatformConfig
from stgen.path_spec import parse_path_spec
from stgen.reference.kinematics import inverse_kinematics
from stgen.reference.paths import sample

CONFIG = PlatformConfig()


def run_plan(capsys, *args):
    code = main(["plan", *map(str, args)])
    out = capsys.readouterr()
    return code, out.out, out.err


def test_plan_json_extremes_match_the_ik_sampled_at_the_task_period(capsys):
    text = "hypocycloid:R=100,r=25,roll=35,pitch=35"
    code, out, _ = run_plan(capsys, "--path", text, "--json")
    assert code == 0
    plan = json.loads(out)["motions"][0]
    duration = plan["duration_s"]
    t = np.arange(int(round(duration / CONFIG.task.period_s)) + 1) * CONFIG.task.period_s
    q = inverse_kinematics(CONFIG.geometry, sample(parse_path_spec(text), duration, t).poses).positions
    assert np.abs(np.array(plan["position_min"]) - q.min(axis=0)).max() < 1e-6
    assert np.abs(np.array(plan["position_max"]) - q.max(axis=0)).max() < 1e-6
    # velocity by differences of the sampled positions: within O(dt²·jerk) of the analytic one
    v = np.abs(np.diff(q, axis=0) / CONFIG.task.period_s).max(axis=0)
    assert np.abs(np.array(plan["velocity_max"]) - v).max() < 1e-2
    assert max(plan["velocity_max"]) <= CONFIG.actuator.max_velocity


def test_plan_refuses_a_path_out_of_stroke_and_names_the_leg(capsys):
    code, out, _ = run_plan(capsys, "--path", "epitrochoid:z=300,roll=35,pitch=35")
    assert code == 1
    refused = [line for line in out.splitlines() if line.startswith("REFUSED")]
    assert refused and all("stroke max" in line for line in refused)
    # which legs: the IK of the same samples says
    spec = parse_path_spec("epitrochoid:z=300,roll=35,pitch=35")
    q = inverse_kinematics(CONFIG.geometry, sample(spec, 13.963, np.linspace(0, 13.963, 5001)).poses).positions
    legs = {int(line.split()[2]) for line in refused}
    assert legs == {leg + 1 for leg in range(6) if q[:, leg].max() > CONFIG.stroke.max}


def test_plan_refuses_a_requested_duration_that_breaks_a_rate(tmp_path, capsys):
    slow = tmp_path / "slow.toml"
    slow.write_text("[actuator]\nmax_velocity = 10.0\nmax_acceleration = 2500.0\n")
    code, out, _ = run_plan(capsys, "--config", slow, "--path", "epicycloid:duration=12")
    assert code == 1
    assert "REFUSED: leg" in out and "velocity" in out
    code, out, _ = run_plan(capsys, "--path", "epicycloid:duration=2")
    assert code == 1 and "REFUSED: duration 2 s is shorter than the shortest 11.171 s (x/y velocity)" in out


def test_plan_of_a_playback_csv(tmp_path, capsys):
    t = np.arange(0.0, 10.0001, 0.1)
    rows = ["t,x,y,z,alpha,beta,gamma"] + [f"{s:.1f},{10 * np.sin(s):.6f},0,240,0,{2 * np.sin(0.5 * s):.6f},0"
                                             for s in t]
    path = tmp_path / "sea.csv"
    path.write_text("\n".join(rows) + "\n")
    code, out, _ = run_plan(capsys, "--playback", path, "--figures", tmp_path / "fig")
    assert code == 0
    assert "101 rows, 103 knots" in out and "within every limit" in out
    assert (tmp_path / "fig" / "plan.png").stat().st_size > 10_000


@pytest.mark.parametrize("spec, message", [
    ("circle", "--path: family"),
    ("spiral:b=x", "--path: column 8: b: expected a number"),
])
def test_bad_path_spec_is_one_line_without_traceback(capsys, spec, message):
    code, _, err = run_plan(capsys, "--path", spec)
    assert code == 1
    assert message in err and "Traceback" not in err


def test_bad_playback_names_file_line_and_column(tmp_path, capsys):
    path = tmp_path / "bad.csv"
    path.write_text("t,x,y,z,alpha,beta,gamma\n0,0,0,0,0,0,0\n0.1,0,0,nan,0,0,0\n")
    code, _, err = run_plan(capsys, "--playback", path)
    assert code == 1
    assert f"{path}:3:9: expected a finite number" in err


@pytest.mark.parametrize("example", ["crank_platform.toml", "moving_base_platform.toml"])
def test_plan_refuses_a_platform_it_does_not_plan_for(capsys, example):
    # The planner's legs are linear on a fixed base; it used to print a crank platform's
    # "stroke" as if its legs were cylinders.
    from pathlib import Path

    config = Path(__file__).resolve().parent.parent / "examples" / example
    code, out, err = run_plan(capsys, "--config", config, "--path", "epitrochoid:R=60,r=20,d=30,z=240")
    assert code == 1 and out == ""
    assert "not planned" in err and err.count("\n") == 1
