"""Reference details that mutation testing found unchecked, seed 21 (issue 16, docs/mutation.md).

Written from the survivors of the fresh seed-21 sample of stgen/reference/.
Expected values are worked out by hand (unit conversions, the Leibniz table's
size, knot times, the planner's rounding rule) or follow from the docstrings'
contracts (a copy in degrees, thirds of a two-row table, the margin on the
shortest duration).
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from stgen.config import PlatformConfig, load_config

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def test_pose_to_degrees_of_integer_radians_keeps_the_fraction():
    from stgen.reference.geometry import pose_to_degrees

    # 1 rad = 180/pi deg = 57.29577951308232...: a copy in floats, not truncated to the integers given.
    poses = pose_to_degrees([[10, 20, 30, 1, 2, 0]])
    assert poses.tolist() == [[10.0, 20.0, 30.0, 180.0 / math.pi, 360.0 / math.pi, 0.0]]


def test_the_leibniz_table_is_six_by_six_by_default():
    from stgen.reference.linalg import permutation_table

    # 6! = 720 permutations of the six legs, half of them odd.
    perms, signs = permutation_table()
    assert perms.shape == (720, 6) and signs.shape == (720,)
    assert int((signs > 0).sum()) == 360
    assert perms[0].tolist() == [0, 1, 2, 3, 4, 5] and perms[-1].tolist() == [5, 4, 3, 2, 1, 0]


def test_check_motion_keeps_the_sample_times():
    from stgen.reference.motion_limits import check_motion

    poses = np.array([[0.0, 0.0, 20.0, 0.0, 0.0, 0.0]] * 2)
    check = check_motion(PlatformConfig(), [0, 0.25], poses, np.zeros((2, 6)), np.zeros((2, 6)))
    assert check.t.tolist() == [0.0, 0.25]


def test_universal_joint_gamma_of_a_direction_rounded_past_one_is_a_right_angle():
    from stgen.reference.geometry import joint_angles
    from stgen.reference.moving_base import universal_joint_angles

    # Each leg pointing straight out along its base joint's polar direction (c, s, 0): γ = asin(c² + s²)
    # = 90°. A unit vector that rounding left a hair longer than 1 must still give 90°, not asin(> 1) = NaN.
    config = PlatformConfig()
    polar, _ = joint_angles(config.geometry)
    directions = np.stack((np.cos(polar), np.sin(polar), np.zeros(6)), axis=-1) * (1.0 + 1e-12)
    state = SimpleNamespace(joints=SimpleNamespace(base_rotation=np.eye(3)), directions=directions)
    gamma, _ = universal_joint_angles(config, state)
    assert gamma.tolist() == [math.pi / 2] * 6


def test_a_crank_at_full_stretch_is_solvable():
    from stgen.reference.crank import crank_inverse_kinematics

    # z = 177.51044601235492 mm (found by bisection on z) puts leg 6's joint where H / (2 a rho) is exactly 1:
    # rod and crank in one line (docs/mathematics.md section 6.1), acos(1) = 0, theta = atan2(dz, M).
    crank = load_config(EXAMPLES / "crank_platform.toml")
    solution = crank_inverse_kinematics(crank, np.array([0.0, 0.0, 177.51044601235492, 0.0, 0.0, 0.0]))
    assert solution.cosine[5] == 1.0
    assert bool(solution.solvable[5]) and math.isfinite(solution.angles_deg[5])
    # one float step higher the rod no longer reaches
    above = crank_inverse_kinematics(crank, np.array([0.0, 0.0, 177.51044601235495, 0.0, 0.0, 0.0]))
    assert above.cosine[5] > 1.0 and not bool(above.solvable[5])


def test_the_shortest_duration_keeps_its_margin_just_under_a_whole_number_of_periods():
    from stgen.reference.paths import PLAN_MARGIN, PathSpec, _scale_duration, plan_path

    # T* (the limits' shortest T) is rounded up to whole periods *after* the margin: with a period p
    # such that T* / p = N / (1 + 1e-7), just under N, T*(1 + 1e-6) / p is just over N, so the plan
    # takes N + 1 periods, never N periods (which would be less than T*(1 + PLAN_MARGIN)).
    spec = PathSpec("epitrochoid")
    base = PlatformConfig()
    limit_t, _ = _scale_duration(spec, base, 2001)
    n = math.ceil(limit_t / 0.001)
    period = limit_t / n * (1.0 + 1e-7)
    config = dataclasses.replace(base, task=dataclasses.replace(base.task, period_s=period))
    plan = plan_path(spec, config, samples=3, plan_samples=2001)
    assert plan.shortest >= limit_t * (1.0 + PLAN_MARGIN)
    assert plan.shortest == pytest.approx((n + 1) * period, rel=1e-12)


def test_a_spiral_needs_no_circles():
    from stgen.reference.paths import PathSpec

    # R and r are the trochoids' circles; a spiral rho = a + b phi does not read them.
    spiral = PathSpec("spiral", R=0.0, r=-1.0, a=10.0, b=5.0)
    assert spiral.end == pytest.approx(6.0 * math.pi)


def test_a_two_row_table_gets_knots_at_its_thirds():
    from stgen.reference.playback import make_table

    # Two rows 2 s apart: the inserted knots at 2/3 s and 4/3 s (module docstring: thirds of a two-row table).
    table = make_table([0.0, 2.0], [[0.0] * 6, [6.0, 0.0, 0.0, 0.0, 0.0, 0.0]])
    assert table.t == pytest.approx([0.0, 2.0 / 3.0, 4.0 / 3.0, 2.0], rel=1e-15)


def test_a_wave_shorter_than_one_unit_is_a_wave():
    from stgen.reference.wave import OceanWave, WaveComponent

    # 0.5 m: any wavelength > 0 is valid; k = 2 pi / 500 mm.
    wave = OceanWave((WaveComponent(3.0, 10.0, 0.5, 0.0),))
    assert wave.wavenumbers_per_mm.tolist() == pytest.approx([2.0 * math.pi / 500.0], rel=1e-15)


def test_the_variant_model_needs_six_measured_values():
    from stgen.reference.variant_fk import VariantModel

    with pytest.raises(ValueError):
        VariantModel(PlatformConfig(), np.zeros(5))
