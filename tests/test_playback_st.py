"""TRJ_Playback (issue 12): a JONSWAP sea state at 10 Hz rendered by `stgen generate --playback`,
run in st_runtime at 1 ms against stgen.reference.playback (positions 1e-9 mm on every call), the
planning pass's leg extremes against the IK of the reference, refusals with ErrorID and leg, and
the table-size refusal of `stgen generate`."""

from __future__ import annotations

import numpy as np
import pytest

from sea_state import jonswap_motion, write_csv
from st_harness import load_with_harness, scan_while_planning
from stgen.cli import main
from stgen.config import PlatformConfig
from stgen.playback_memory import max_rows
from stgen.reference.kinematics import inverse_kinematics
from stgen.reference.playback import evaluate, make_table, read_playback_csv
from stgen.render import RenderOptions
from stgen.scenarios.program import codes_of, render_controller_program
from stgen.scenarios.setpoint_limits import check_setpoint_limits

PERIOD = 0.001
HARNESS = """
PROGRAM TestPlayback
VAR
    Play : TRJ_Playback;
    Execute : BOOL;
    RunClock : BOOL;
    ActuatorVelocity : LREAL := 250.0;
END_VAR
Play(Execute := Execute, RunClock := RunClock, SamplesPerScan := 500, ActuatorVelocity := ActuatorVelocity);
END_PROGRAM
"""
CONFIG = PlatformConfig()


def _project(table):
    rendered = render_controller_program(CONFIG, RenderOptions(playback=table))
    return load_with_harness(rendered, HARNESS), codes_of(rendered, "TRJ_Constants")


@pytest.fixture(scope="module")
def sea(tmp_path_factory):
    t, poses = jonswap_motion(duration_s=12.0)
    path = tmp_path_factory.mktemp("sea") / "jonswap.csv"
    write_csv(path, t, poses)
    return read_playback_csv(path)


def _plan(program, plc, velocity=250.0):
    program["ActuatorVelocity"] = velocity
    program["Execute"] = True
    return scan_while_planning(plc, program, "Play")


def test_playback_matches_the_reference_on_every_call(sea):
    project, _ = _project(sea)
    plc = project.controller(period="1ms")
    program = plc.add_program("TestPlayback")
    _plan(program, plc)
    assert program["Play.Ready"], program["Play.ErrorID"]
    count = int(np.floor(sea.duration / PERIOD + 1e-9)) + 1
    t = np.arange(count) * PERIOD
    expected, _, _ = evaluate(sea, t)
    q = inverse_kinematics(CONFIG.geometry, expected).positions
    check = check_setpoint_limits(q, PERIOD, CONFIG.actuator.max_velocity, CONFIG.actuator.max_acceleration)
    assert check.passed
    assert np.abs(np.array(program["Play.LegPositionMin"]) - q.min(axis=0)).max() < 1e-9
    assert np.abs(np.array(program["Play.LegPositionMax"]) - q.max(axis=0)).max() < 1e-9
    assert np.abs(np.array(program["Play.LegVelocityMax"]) - check.max_velocity).max() < 1e-6
    assert np.abs(np.array(program["Play.LegAccelerationMax"]) - check.max_acceleration).max() < 1e-3
    program["RunClock"] = True
    poses = []
    for _ in range(count):
        plc.scan()
        poses.append(program["Play.Pose"])
    assert program["Play.Done"]
    assert np.abs(np.array(poses) - expected).max() < 1e-9


def test_playback_out_of_stroke_is_refused_with_the_leg(sea):
    high = make_table(sea.t, sea.poses + np.array([0.0, 0.0, 400.0, 0.0, 0.0, 0.0]), "high.csv")
    q = inverse_kinematics(CONFIG.geometry, evaluate(high, np.arange(0, high.duration, PERIOD))[0]).positions
    legs = [leg + 1 for leg in range(6) if q[:, leg].max() > CONFIG.stroke.max]
    assert legs
    project, codes = _project(high)
    plc = project.controller(period="1ms")
    program = plc.add_program("TestPlayback")
    _plan(program, plc)
    assert program["Play.ErrorID"] == codes["TRJ_ERR_PATH_STROKE"]
    assert program["Play.ErrorLeg"] == min(legs)
    program["RunClock"] = True
    plc.scan()
    assert not program["Play.Busy"]


def test_playback_too_fast_for_the_actuators_is_refused_with_the_leg(sea):
    project, codes = _project(sea)
    plc = project.controller(period="1ms")
    program = plc.add_program("TestPlayback")
    t = np.arange(int(np.floor(sea.duration / PERIOD + 1e-9)) + 1) * PERIOD
    q = inverse_kinematics(CONFIG.geometry, evaluate(sea, t)[0]).positions
    velocity = np.abs(np.diff(q, axis=0)).max(axis=0) / PERIOD
    limit = float(np.sort(velocity)[2])            # some legs under it, some over
    _plan(program, plc, velocity=limit)
    assert program["Play.ErrorID"] == codes["TRJ_ERR_PATH_RATE"]
    assert program["Play.ErrorLeg"] == min(leg + 1 for leg in range(6) if velocity[leg] > limit)


def test_generate_refuses_a_table_too_large_for_the_controller(tmp_path, capsys):
    rows = max_rows() + 1
    t = np.arange(rows) * 0.01
    path = tmp_path / "long.csv"
    write_csv(path, t, np.tile([0.0, 0.0, 240.0, 0.0, 0.0, 0.0], (rows, 1)))
    code = main(["generate", "--target", "iec", "--out", str(tmp_path / "out"), "--playback", str(path)])
    err = capsys.readouterr().err
    assert code == 1
    assert f"{path}:1:1: {rows} rows is too large for the controller: at most {max_rows()} rows" in err
    assert not (tmp_path / "out").exists() or not any((tmp_path / "out").iterdir())


def test_generate_with_a_playback_writes_the_table_and_checks_clean_under_nj(sea, tmp_path, capsys):
    t, poses = jonswap_motion(duration_s=3.0)
    path = tmp_path / "short.csv"
    write_csv(path, t, poses)
    assert main(["generate", "--target", "iec", "--out", str(tmp_path / "out"), "--playback", str(path)]) == 0
    assert (tmp_path / "out" / "TRJ_PlaybackTable.st").exists()
    assert main(["check", "--dialect", "nj", str(tmp_path / "out")]) == 0


def test_the_table_is_sized_by_the_memory_model_of_the_checker():
    # By hand: per knot one LREAL time, six LREAL poses and six LREAL slopes, 8 bytes each
    # (OMRON's allocation table, docs/limits.md): 104 bytes; 2 MiB / 104 = 20164 knots, and
    # 65535 elements per array / 6 = 10922 knots bind first.
    from stgen.playback_memory import max_knots, table_bytes

    assert table_bytes(1) == 104 and table_bytes(10922) == 1_135_888
    assert max_knots() == 10922


def test_the_checker_sizes_the_rendered_table_as_the_planner_counts(sea):
    # The same model: st_runtime's checker, given a 1-byte limit, names each of the rendered
    # table's arrays with its bytes; they add up to what generate --playback counts.
    import re

    from st_runtime.api import LoadError, load_sources
    from stgen.exports.iec import pou_text
    from stgen.playback_memory import table_bytes
    from stgen.render import render_program

    knots = len(sea.t)
    program = render_program(PlatformConfig.default(), RenderOptions(playback=sea))
    sources = {"TRJ_PlaybackTable.st": pou_text(program.pou("TRJ_PlaybackTable"))}
    with pytest.raises(LoadError) as refused:
        load_sources(sources, memory_limit=1)
    sizes = {}
    for line in str(refused.value).splitlines():
        found = re.search(r"E-LIMIT-008\]: global (TRJ_PLAYBACK_(?:TIME|POSE|SLOPE)) needs ([\d,]+) bytes", line)
        if found:
            sizes[found.group(1)] = int(found.group(2).replace(",", ""))
    assert sizes == {"TRJ_PLAYBACK_TIME": knots * 8, "TRJ_PLAYBACK_POSE": knots * 48, "TRJ_PLAYBACK_SLOPE": knots * 48}
    assert sum(sizes.values()) == table_bytes(knots)
