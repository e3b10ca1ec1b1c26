"""`stgen workspace` and :mod:`stgen.workspace`: boundaries checked by the per-pose test."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from stgen.cli import main
from stgen.config import PlatformConfig, load_config
from stgen.reference.feasibility import Limit, check_pose
from stgen.workspace import coordinate_ranges, slice_map

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
CONFIGS = {
    "default": (PlatformConfig.default(), [0.0] * 6),
    "crank": (load_config(EXAMPLES / "crank_platform.toml"), [0.0] * 6),
    "moving_base": (load_config(EXAMPLES / "moving_base_platform.toml"), [0.0, 0.0, 75.0, 0.0, 0.0, 0.0]),
}


@pytest.mark.parametrize("name", sorted(CONFIGS))
def test_each_side_of_every_reported_range_end(name):
    config, centre = CONFIGS[name]
    for index, item in enumerate(coordinate_ranges(config, centre=centre)):
        for end, sign in ((item.low, -1.0), (item.high, 1.0)):
            assert end.limit != Limit.NONE, f"{item.coordinate}: nothing stops it"
            inside, outside = np.array(centre), np.array(centre)
            inside[index] = end.value - sign * 1e-6
            outside[index] = end.value + sign * 1e-6
            assert check_pose(config, inside).feasible, (item.coordinate, end)
            report = check_pose(config, outside)
            assert not report.feasible, (item.coordinate, end)
            assert (end.leg, end.limit) in {(v.leg, v.limit) for v in report.violations}


def test_moving_base_vertical_range_is_the_stroke_seen_through_the_inclined_legs():
    # Straight up from home every leg grows from Di = 0 to 150 mm: by hand, with the leg's
    # horizontal part h fixed, z_max solves sqrt(h² + (h0 + z)²) = l0 + 150.
    config, _ = CONFIGS["moving_base"]
    z_range = coordinate_ranges(config, centre=[0, 0, 75, 0, 0, 0])[2]
    o = 184.0 * np.array([np.cos(np.radians(45)), np.sin(np.radians(45))])
    p = 184.0 * np.array([np.cos(np.radians(15)), np.sin(np.radians(15))])
    horizontal = np.linalg.norm(p - o)
    top = np.sqrt((426.4776 + 150.0) ** 2 - horizontal**2) - 415.706
    bottom = np.sqrt(426.4776**2 - horizontal**2) - 415.706
    assert z_range.high.value == pytest.approx(top, abs=1e-6)
    assert z_range.low.value == pytest.approx(bottom, abs=1e-6)
    assert (z_range.high.limit, z_range.low.limit) == (Limit.STROKE_MAX, Limit.STROKE_MIN)


def test_slice_points_agree_with_the_per_pose_test():
    config, centre = CONFIGS["moving_base"]
    item = slice_map(config, ("x", "z"), bounds=((-160, 190), (-10, 170)), resolution=40, fixed_pose=centre)
    rng = np.random.default_rng(3)
    for row, column in rng.integers(0, 40, (60, 2)):
        pose = np.array(centre)
        pose[0], pose[2] = item.xs[column], item.ys[row]
        report = check_pose(config, pose)
        assert report.feasible == bool(item.feasible[row, column])
        if not report.feasible:
            assert (int(item.leg[row, column]), Limit(int(item.limit[row, column]))) in {
                (v.leg, v.limit) for v in report.violations}
    assert set(item.limit_counts()) == {"feasible", "stroke_min", "stroke_max", "spherical_tilt"}


def test_cli_json_and_png(tmp_path, capsys):
    code = main(["workspace", "--config", str(EXAMPLES / "crank_platform.toml"), "--json",
                 "--resolution", "20", "--slice", "x,y", "--png", str(tmp_path)])
    assert code == 0
    data = json.loads(capsys.readouterr().out)
    assert [r["coordinate"] for r in data["ranges"]] == ["x", "y", "z", "a1", "a2", "a3"]
    assert data["slices"][0]["axes"] == ["x", "y"] and len(data["slices"][0]["limit"]) == 20
    assert (tmp_path / "workspace_x_y.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_cli_table_names_the_limits(capsys):
    assert main(["workspace", "--config", str(EXAMPLES / "moving_base_platform.toml"),
                 "--centre", "0,0,75,0,0,0", "--resolution", "10"]) == 0
    out = capsys.readouterr().out
    assert "stroke_max, leg 1" in out and "spherical_tilt" in out


@pytest.mark.parametrize("argv, message", [
    (["--slice", "x,x"], "two different coordinates"),
    (["--centre", "1,2,3"], "six"),
    (["--resolution", "1"], "2..2000"),
])
def test_cli_usage_errors(argv, message, capsys):
    with pytest.raises(SystemExit) as caught:
        main(["workspace", *argv])
    assert caught.value.code == 2
    assert message in capsys.readouterr().err


def test_cli_infeasible_centre_is_an_error(capsys):
    assert main(["workspace", "--centre", "0,0,900,0,0,0", "--resolution", "5"]) == 1
    assert "is not feasible" in capsys.readouterr().err
