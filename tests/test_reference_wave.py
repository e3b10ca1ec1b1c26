"""Ocean wave (docs/mathematics.md section 4, [29–33]) at phases where the pose is known by hand."""

from __future__ import annotations

import math

import numpy as np
import pytest

from stgen.reference import AIRY, RANDOM_5, OceanWave, WaveComponent, wave_pose

K_100_M = 2 * math.pi / 100_000.0  # rad/mm for L = 100 m


def _single(phase_deg=0.0, heading_deg=0.0, unit_mm=1000.0) -> OceanWave:
    return OceanWave((WaveComponent(3.0, 10.0, 100.0, phase_deg),), heading_deg, unit_mm)


def test_crest_at_t0_with_zero_phase():
    # ψ = 0: ξ = 0, ζ = A, slope −A k sin ψ = 0.
    assert wave_pose(_single(), 0.0) == pytest.approx([0.0, 0.0, 3.0, 0.0, 0.0, 0.0], abs=1e-12)


def test_quarter_period_later_the_point_is_ahead_and_tilted():
    # t = Tw/4: ψ = −π/2, so ξ = A, ζ = 0, ∂η/∂x = A k, β = −atan(A k).
    pose = wave_pose(_single(), 2.5)
    expected_beta = -math.degrees(math.atan(3.0 * K_100_M))
    assert pose == pytest.approx([3.0, 0.0, 0.0, 0.0, expected_beta, 0.0], abs=1e-12)


def test_phase_of_90_degrees_at_t0():
    # ψ = π/2: ξ = −A, ζ = 0, ∂η/∂x = −A k, β = +atan(A k).
    pose = wave_pose(_single(phase_deg=90.0), 0.0)
    assert pose == pytest.approx([-3.0, 0.0, 0.0, 0.0, math.degrees(math.atan(3.0 * K_100_M)), 0.0], abs=1e-12)


def test_heading_90_degrees_moves_along_y_and_tilts_about_x():
    # ψ = −π/2 at t = Tw/4: ξ = A along +y; ∂η/∂y = A k, γ = atan(A k).
    pose = wave_pose(_single(heading_deg=90.0), 2.5)
    assert pose == pytest.approx([0.0, 3.0, 0.0, 0.0, 0.0, math.degrees(math.atan(3.0 * K_100_M))], abs=1e-12)


def test_heading_45_degrees_splits_the_motion():
    pose = wave_pose(_single(heading_deg=45.0), 2.5)
    half = 3.0 / math.sqrt(2)
    slope = 3.0 * K_100_M / math.sqrt(2)
    expected = [half, half, 0.0, 0.0, -math.degrees(math.atan(slope)), math.degrees(math.atan(slope))]
    assert pose == pytest.approx(expected, abs=1e-12)


def test_wavelength_unit_is_a_parameter():
    # L = 100 mm: k = 2π/100 per mm, so A k = 0.1885 and the tilt is ≈ 10.68°.
    pose = wave_pose(_single(unit_mm=1.0), 2.5)
    assert pose[4] == pytest.approx(-math.degrees(math.atan(3.0 * 2 * math.pi / 100.0)))
    assert pose[4] == pytest.approx(-10.675, abs=1e-3)


def test_airy_preset_at_t0():
    # A = 3 mm, φ = 10°: ψ = 10°, ∂η/∂x = −A k sin ψ < 0, so β = −atan(∂η/∂x) > 0.
    pose = wave_pose(AIRY, 0.0)
    psi = math.radians(10.0)
    expected_beta = math.degrees(math.atan(3.0 * K_100_M * math.sin(psi)))
    assert pose == pytest.approx([-3.0 * math.sin(psi), 0.0, 3.0 * math.cos(psi), 0.0, expected_beta, 0.0])


def test_random_preset_holds_the_study_values():
    assert [c.amplitude_mm for c in RANDOM_5.components] == [3.0, 2.3, -3.5, 0.7, 5.4]
    assert [c.period_s for c in RANDOM_5.components] == [10.0, 5.0, 3.0, 7.0, 3.0]
    assert [c.wavelength for c in RANDOM_5.components] == [60.0, 85.0, 75.0, 70.0, 100.0]
    assert [c.phase_deg for c in RANDOM_5.components] == [-10.0, 15.0, 0.0, 20.0, -45.0]
    assert RANDOM_5.wavelength_unit_mm == 1000.0


def test_random_preset_at_t0_sums_the_components():
    phases = np.radians([-10.0, 15.0, 0.0, 20.0, -45.0])
    amplitudes = np.array([3.0, 2.3, -3.5, 0.7, 5.4])
    pose = wave_pose(RANDOM_5, 0.0)
    assert pose[0] == pytest.approx(-np.sum(amplitudes * np.sin(phases)))
    assert pose[2] == pytest.approx(np.sum(amplitudes * np.cos(phases)))


def test_opposite_components_cancel():
    wave = OceanWave((WaveComponent(2.0, 6.0, 50.0, 0.0), WaveComponent(2.0, 6.0, 50.0, 180.0)))
    assert wave_pose(wave, np.linspace(0, 6, 7)) == pytest.approx(np.zeros((7, 6)), abs=1e-12)


def test_centre_pose_is_added_and_time_vectorises():
    centre = np.array([10.0, 20.0, 300.0, 1.0, 2.0, 3.0])
    times = np.array([0.0, 2.5, 10.0, 12.5])
    poses = wave_pose(_single(), times, centre)
    assert poses.shape == (4, 6)
    assert poses[0] == pytest.approx(centre + [0, 0, 3.0, 0, 0, 0])
    assert poses[2] == pytest.approx(poses[0])  # one period later
    assert poses[3] == pytest.approx(poses[1])


def test_rest_position_along_the_heading_shifts_the_phase():
    # x̃ = L/4 = 25 000 mm adds π/2 to ψ: the same as φ = 90°.
    assert wave_pose(_single(), 0.0, position_mm=25_000.0) == pytest.approx(
        wave_pose(_single(phase_deg=90.0), 0.0), abs=1e-12
    )


def test_invalid_components_are_rejected():
    with pytest.raises(ValueError):
        OceanWave((WaveComponent(3.0, 0.0, 100.0, 0.0),))
    with pytest.raises(ValueError):
        OceanWave((WaveComponent(3.0, 10.0, 100.0, 0.0),), wavelength_unit_mm=0.0)


# Fade-in (issue 8, docs/mathematics.md section 4): continuity of position, velocity and acceleration.


def test_fade_in_duration_of_the_airy_preset_by_hand():
    from stgen.config import TrajectoryConfig
    from stgen.reference.wave import fade_in_duration

    # z binds: D0 = A = 3 mm, D3 = A w^3 with w = 2 pi / 10 s. The jerk term 4 pi^2 D0 r^3 gets a third of
    # (5000 - D3): r = ((5000 - D3) / 3 / (4 pi^2 * 3))^(1/3); every other term allows a larger r (worked out in
    # the reference's docstring: velocity r <= 16.4, acceleration r <= 3.6).
    w = 2 * math.pi / 10.0
    rate = ((5000.0 - 3.0 * w**3) / 3.0 / (4 * math.pi**2 * 3.0)) ** (1.0 / 3.0)
    assert fade_in_duration(AIRY, TrajectoryConfig()) == pytest.approx(1.0 / rate, rel=1e-12)
    assert 1.0 / rate == pytest.approx(0.4142, abs=1e-4)


def test_fade_in_is_continuous_and_inside_the_limits():
    from stgen.config import TrajectoryConfig
    from stgen.reference.wave import fade_in_duration

    limits = TrajectoryConfig()
    fade = fade_in_duration(RANDOM_5, limits)
    dt = 1e-4
    t = np.arange(0, int(2 * fade / dt)) * dt
    pose = wave_pose(RANDOM_5, t, fade_s=fade)
    velocity = np.diff(pose, axis=0) / dt
    acceleration = np.diff(velocity, axis=0) / dt
    assert pose[0] == pytest.approx(np.zeros(6), abs=1e-15)           # at rest at the centre
    assert np.abs(velocity[0]).max() < 1e-3 and np.abs(acceleration[0]).max() < 1.0
    assert np.abs(velocity[:, :3]).max() <= limits.linear_velocity
    assert np.abs(acceleration[:, :3]).max() <= limits.linear_acceleration
    # From T_F on, the wave itself, exactly.
    after = t >= fade
    assert np.array_equal(pose[after], wave_pose(RANDOM_5, t[after]))
    # No velocity step at T_F: around it, velocity changes at the wave's own acceleration, |a| <= Σ|A|w^2 = 44.4 mm/s^2.
    at = int(np.argmax(after))
    assert np.abs(acceleration[at - 3:at + 3, 2]).max() <= 44.5
