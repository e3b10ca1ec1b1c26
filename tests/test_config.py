"""Platform configuration: defaults, the example file, and every validation rule."""

from __future__ import annotations

import dataclasses
import tomllib
from pathlib import Path

import pytest

from stgen.config import (
    ConfigError,
    GeometryConfig,
    PlatformConfig,
    SolverConfig,
    StrokeConfig,
    config_from_mapping,
    load_config,
    parse_config,
)

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "default_platform.toml"


def test_defaults_are_the_spec_table_1():
    config = PlatformConfig.default()
    geometry = config.geometry
    assert (geometry.rb, geometry.rp, geometry.h0, geometry.l0) == (470.45, 388.95, 1374.0, 1192.63)
    assert (geometry.hb, geometry.hp, geometry.phi_b_deg, geometry.phi_p_deg) == (95.0, -115.0, 24.07, 103.66)
    assert (config.stroke.min, config.stroke.max) == (0.0, 600.0)
    assert config.task.period_s == 0.001
    assert config.solver.tolerance == 0.01
    assert config.solver.start_pose == (60.25, 85.0, 230.7, 0.0, 0.0, 3.75)


def test_load_none_gives_defaults():
    assert load_config(None) == PlatformConfig.default()


def test_example_file_equals_defaults_and_lists_every_key():
    assert load_config(EXAMPLE) == PlatformConfig.default()
    data = tomllib.loads(EXAMPLE.read_text(encoding="utf-8"))
    for section in dataclasses.fields(PlatformConfig):
        assert section.name in data
        section_type = type(getattr(PlatformConfig.default(), section.name))
        optional = {spec.name for spec in dataclasses.fields(section_type) if spec.default is None}  # not writable in TOML
        assert set(data[section.name]) | optional == {spec.name for spec in dataclasses.fields(section_type)}


def test_example_file_comments_every_key():
    for line in EXAMPLE.read_text(encoding="utf-8").splitlines():
        if "=" in line and not line.lstrip().startswith("#"):
            assert "#" in line, f"uncommented key: {line}"


def test_partial_file_keeps_other_defaults_and_accepts_integers_for_reals():
    config = parse_config("[stroke]\nmax = 500\n[geometry]\nrb = 470\n")
    assert config.stroke.max == 500.0 and isinstance(config.stroke.max, float)
    assert config.geometry.rb == 470.0 and isinstance(config.geometry.rb, float)
    assert config.geometry.rp == 388.95
    assert config.solver == SolverConfig()


def test_config_is_frozen():
    config = PlatformConfig.default()
    with pytest.raises(dataclasses.FrozenInstanceError):
        config.geometry.rb = 1.0  # type: ignore[misc]


@pytest.mark.parametrize(
    ("toml", "key", "rule"),
    [
        ("[geometry]\nrb = -1.0", "geometry.rb", "> 0"),
        ("[geometry]\nrp = 0", "geometry.rp", "> 0"),
        ("[geometry]\nl0 = -5", "geometry.l0", "> 0"),
        ("[stroke]\nmin = 600\nmax = 600", "stroke.min", "less than stroke.max"),
        ("[stroke]\nmin = 700", "stroke.min", "less than stroke.max"),
        ("[geometry]\nphi_b_deg = 0", "geometry.phi_b_deg", "coincide"),
        ("[geometry]\nphi_b_deg = 120", "geometry.phi_b_deg", "coincide"),
        ("[geometry]\nphi_p_deg = 0.0", "geometry.phi_p_deg", "coincide"),
        ("[geometry]\nrbb = 1.0", "geometry.rbb", "unknown key"),
        ("[geometrie]\nrb = 1.0", "geometrie", "unknown key"),
        ("geometry = 3", "geometry", "must be a table"),
        ('[geometry]\nrb = "big"', "geometry.rb", "must be a number"),
        ("[geometry]\nrb = true", "geometry.rb", "must be a number"),
        ("[geometry]\nrb = nan", "geometry.rb", "finite"),
        ("[task]\nperiod_s = 0", "task.period_s", "> 0"),
        ("[actuator]\nmax_velocity = -250", "actuator.max_velocity", "> 0"),
        ("[trajectory]\nangular_jerk = 0", "trajectory.angular_jerk", "> 0"),
        ("[solver]\niterations_per_scan = 2.5", "solver.iterations_per_scan", "must be an integer"),
        ("[solver]\nmax_iterations = 0", "solver.max_iterations", ">= 1"),
        ("[solver]\ntolerance = 0", "solver.tolerance", "> 0"),
        ("[solver]\nsingularity_threshold = -1", "solver.singularity_threshold", ">= 0"),
        ("[solver]\nstart_pose = [1, 2, 3]", "solver.start_pose", "array of 6 numbers"),
        ('[solver]\nstart_pose = [1, 2, "z", 0, 0, 0]', "solver.start_pose[2]", "must be a number"),
    ],
)
def test_validation_error_names_key_and_rule(toml, key, rule):
    with pytest.raises(ConfigError) as caught:
        parse_config(toml, source="platform.toml")
    assert caught.value.key == key
    message = str(caught.value)
    # Where the key is written: the line of the table header for a section, else the assignment.
    line = 1 if "." not in key else 2
    assert message.startswith(f"platform.toml:{line}:1: {key}: ")
    assert rule in message


def test_validation_error_points_at_the_line_and_column_of_the_key():
    text = "# platform\n[geometry]\nrb = 470.45\n\n[stroke]\n  min = 600  # too high\nmax = 600\n"
    with pytest.raises(ConfigError) as caught:
        parse_config(text, source="p.toml")
    assert (caught.value.line, caught.value.column) == (6, 3)
    assert str(caught.value).startswith("p.toml:6:3: stroke.min: must be less than stroke.max")


def test_a_rule_broken_by_a_default_has_no_line():
    # stroke.min = 20 puts the home pose (q = 9.9994 mm) outside; the key at fault, geometry, is not written.
    with pytest.raises(ConfigError) as caught:
        parse_config("[stroke]\nmin = 20\n", source="p.toml")
    assert caught.value.line is None and str(caught.value).startswith("p.toml: geometry: ")


def test_home_pose_out_of_stroke_is_rejected():
    # l0 = 1300 mm: the home leg (≈ 1202.63 mm) is shorter than a retracted cylinder, q ≈ −97.37 mm.
    with pytest.raises(ConfigError) as caught:
        parse_config("[geometry]\nl0 = 1300")
    assert caught.value.key == "geometry"
    assert "outside the stroke" in str(caught.value) and "home pose" in str(caught.value)


def test_home_pose_beyond_stroke_max_is_rejected():
    # Home q ≈ 9.9994 mm, so a stroke of 20 .. 600 mm excludes it.
    with pytest.raises(ConfigError, match="outside the stroke"):
        parse_config("[stroke]\nmin = 20")


def test_singular_home_pose_is_rejected():
    # Similar base and platform hexagons (φb = φp) form an architecture singularity: det J = 0
    # everywhere. Their home legs are ≈ −25.8 mm, so the stroke is widened to isolate the rule.
    with pytest.raises(ConfigError) as caught:
        parse_config("[geometry]\nphi_p_deg = 24.07\n[stroke]\nmin = -100")
    assert caught.value.key == "geometry"
    assert "singular" in str(caught.value) and "solver.singularity_threshold" in str(caught.value)


def test_threshold_above_the_home_determinant_is_rejected():
    # |det J| at home is ≈ 8.8e27; a Ktol of 1e30 declares the home pose singular.
    with pytest.raises(ConfigError, match="singular"):
        parse_config("[solver]\nsingularity_threshold = 1e30")


def test_direct_construction_runs_the_same_rules():
    with pytest.raises(ConfigError, match="geometry.rb"):
        GeometryConfig(rb=0.0)
    with pytest.raises(ConfigError, match="stroke.min"):
        StrokeConfig(min=10.0, max=5.0)


def test_mapping_interface():
    config = config_from_mapping({"solver": {"start_pose": [0, 0, 0, 0, 0, 0]}})
    assert config.solver.start_pose == (0.0,) * 6


def test_malformed_toml_reports_file_line_and_column(tmp_path):
    path = tmp_path / "broken.toml"
    path.write_text("[geometry]\nrb = 470.45\nrp 388.95\n", encoding="utf-8")
    with pytest.raises(ConfigError) as caught:
        load_config(path)
    error = caught.value
    assert (error.line, error.column) == (3, 4)
    assert str(error).startswith(f"{path}:3:4: invalid TOML")


def test_missing_file_names_the_file(tmp_path):
    path = tmp_path / "absent.toml"
    with pytest.raises(ConfigError, match="absent.toml"):
        load_config(str(path))


def test_validation_error_from_file_names_the_file(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text("[geometry]\nrb = -3\n", encoding="utf-8")
    with pytest.raises(ConfigError) as caught:
        load_config(path)
    assert str(caught.value).startswith(f"{path}:2:1: geometry.rb: ")
