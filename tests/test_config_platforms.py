"""The platform-kind sections (docs/mathematics.md section 6): [platform], [crank], [joints] and the two example files."""

from __future__ import annotations

from pathlib import Path

import pytest

from stgen.config import ConfigError, PlatformConfig, load_config, parse_config

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def test_default_is_the_nj_study_kind():
    config = PlatformConfig.default()
    assert config.is_default_kind
    assert (config.platform.actuator, config.platform.base) == ("linear", "fixed")
    assert (config.platform.base_rotation, config.platform.platform_rotation) == ("ZYX", "ZYX")
    assert config.joints.universal_max_deg is None and config.joints.spherical_tilt_max_deg is None


def test_moving_base_example_has_the_spec_parameters():
    config = load_config(EXAMPLES / "moving_base_platform.toml")
    assert config.moving_base and not config.is_crank
    assert (config.platform.base_rotation, config.platform.platform_rotation) == ("ZYX", "XYZ")
    geometry = config.geometry
    assert (geometry.rb, geometry.rp, geometry.h0, geometry.hb, geometry.hp) == (184.0, 184.0, 415.706, 0.0, 0.0)
    assert (config.stroke.min, config.stroke.max) == (0.0, 150.0)
    assert (config.joints.universal_max_deg, config.joints.spherical_tilt_max_deg) == (24.25, 24.25)


def test_moving_base_example_joint_layout_is_the_studys():
    import numpy as np

    from stgen.reference.geometry import joint_angles

    config = load_config(EXAMPLES / "moving_base_platform.toml")
    base, upper = (np.degrees(a) for a in joint_angles(config.geometry))
    assert base == pytest.approx([45, 75, 165, 195, 285, 315])
    assert upper == pytest.approx([15, 105, 135, 225, 255, 345])


def test_crank_example_has_the_studys_mechanism():
    config = load_config(EXAMPLES / "crank_platform.toml")
    assert config.is_crank and not config.moving_base
    crank = config.crank
    assert (crank.crank_length, crank.rod_length, crank.gear_ratio) == (250.0, 940.0, 32.41)
    assert (crank.angle_min_deg, crank.angle_max_deg) == (50.0, 230.0)
    assert "ASSUMPTIONS" in (EXAMPLES / "crank_platform.toml").read_text(encoding="utf-8")


@pytest.mark.parametrize(
    "text, key, rule",
    [
        ('[platform]\nactuator = "hydraulic"\n', "platform.actuator", "must be one of 'linear', 'crank'"),
        ('[platform]\nbase = 1\n', "platform.base", "must be one of"),
        ('[platform]\nplatform_rotation = "XXZ"\n', "platform.platform_rotation", "must be one of"),
        ('[crank]\nbranch = [1, 1, 0, 1, 1, 1]\n', "crank.branch[2]", "must be +1 or -1"),
        ('[crank]\nplane_angle_deg = [1, 2, 3]\n', "crank.plane_angle_deg", "array of 6 numbers"),
        ('[crank]\nangle_min_deg = 240.0\n', "crank.angle_min_deg", "must be less than"),
        ('[joints]\nuniversal_max_deg = -3.0\n', "joints.universal_max_deg", "must be > 0"),
    ],
)
def test_bad_values_name_file_line_key_and_rule(text, key, rule):
    with pytest.raises(ConfigError) as caught:
        parse_config(text, source="p.toml")
    message = str(caught.value)
    assert message.startswith("p.toml:2:1: " + key + ": "), message
    assert rule in message


def test_joint_limits_with_a_crank_are_refused():
    with pytest.raises(ConfigError, match="joints: joint limits are checked for linear legs only"):
        parse_config('[platform]\nactuator = "crank"\n[geometry]\nh0 = 1180.0\n[joints]\nuniversal_max_deg = 20.0\n')


def test_a_crank_platform_whose_home_is_out_of_reach_is_refused():
    # With the default h0 = 1374 mm the rods (940 mm) cannot reach the platform joints.
    with pytest.raises(ConfigError, match="home pose is not feasible: leg 1: crank_no_solution"):
        parse_config('[platform]\nactuator = "crank"\n')


def test_joint_limits_that_exclude_home_are_refused():
    # The moving-base example's home tilt is 12.9 degrees on every leg.
    text = (EXAMPLES / "moving_base_platform.toml").read_text(encoding="utf-8")
    text = text.replace("spherical_tilt_max_deg = 24.25", "spherical_tilt_max_deg = 10.0")
    with pytest.raises(ConfigError, match="spherical_tilt exceeded"):
        parse_config(text)
