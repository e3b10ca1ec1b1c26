"""FK residual [13–18] and the analytic Jacobian [36] against central differences and hand values."""

from __future__ import annotations

import math

import numpy as np
import pytest

from stgen.config import GeometryConfig
from stgen.reference import inverse_kinematics, jacobian, joint_angles, pose_to_radians, residual

GEOMETRY = GeometryConfig()


def _random_poses_rad(count: int, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    poses = rng.uniform(-1.0, 1.0, (count, 6)) * [150.0, 150.0, 150.0, 0.3, 0.3, 0.3]
    poses[:, 2] += 250.0
    return poses


def test_residual_vanishes_at_the_ik_solution():
    poses_rad = _random_poses_rad(50, seed=11)
    poses_deg = np.concatenate((poses_rad[:, :3], np.degrees(poses_rad[:, 3:])), axis=1)
    positions = inverse_kinematics(GEOMETRY, poses_deg).positions
    # |Li|² is ≈ 1.5e6 mm², so rounding leaves ≈ 1e-9 of it.
    assert np.abs(residual(GEOMETRY, poses_rad, positions)) == pytest.approx(np.zeros((50, 6)), abs=1e-6)


def test_residual_is_difference_of_squares():
    # At home with qi = 0 every leg is Lhome and fi = Lhome² − l0².
    home_sq = (9.9994017 + 1192.63) ** 2
    values = residual(GEOMETRY, np.zeros(6), np.zeros(6))
    assert values == pytest.approx([home_sq - 1192.63**2] * 6, rel=1e-7)


def test_jacobian_matches_central_differences():
    poses = _random_poses_rad(40, seed=5)
    positions = np.full(6, 100.0)
    analytic = jacobian(GEOMETRY, poses)
    steps = [1e-3, 1e-3, 1e-3, 1e-6, 1e-6, 1e-6]  # mm, rad
    for column, step in enumerate(steps):
        offset = np.zeros(6)
        offset[column] = step
        numeric = (residual(GEOMETRY, poses + offset, positions) - residual(GEOMETRY, poses - offset, positions)) / (
            2 * step
        )
        scale = np.abs(analytic[..., column]).max()
        assert np.abs(analytic[..., column] - numeric).max() <= 1e-6 * scale, f"column {column}"


def test_jacobian_at_home_by_hand():
    matrix = jacobian(GEOMETRY, np.zeros(6))
    theta, phi = joint_angles(GEOMETRY)
    # z column: 2(z̄ + w) = 2(h0 − hb + hp) = 2·1164.
    assert matrix[:, 2] == pytest.approx([2328.0] * 6)
    # x column: 2(Pix − Bix); α column: 2(Bix·Piy − Biy·Pix) = 2·rb·rp·sin(ϕi − θi).
    assert matrix[:, 0] == pytest.approx(2 * (388.95 * np.cos(phi) - 470.45 * np.cos(theta)))
    assert matrix[:, 3] == pytest.approx(2 * 470.45 * 388.95 * np.sin(phi - theta))
    # β column with R = I: 2[(x̄)·hp − Pix·z̄] with x̄ = −Bix, z̄ = h0 − hb.
    expected_beta = 2 * (-470.45 * np.cos(theta) * -115.0 - 388.95 * np.cos(phi) * 1279.0)
    assert matrix[:, 4] == pytest.approx(expected_beta)
    # γ column with R = I: 2[z̄·Piy − ȳ·Piz] with ȳ = −Biy.
    expected_gamma = 2 * (1279.0 * 388.95 * np.sin(phi) - (-470.45 * np.sin(theta)) * -115.0)
    assert matrix[:, 5] == pytest.approx(expected_gamma)


def test_jacobian_shape_follows_the_poses():
    assert jacobian(GEOMETRY, np.zeros(6)).shape == (6, 6)
    assert jacobian(GEOMETRY, np.zeros((3, 4, 6))).shape == (3, 4, 6, 6)


def test_pose_conversion_touches_only_angles():
    converted = pose_to_radians([1.0, 2.0, 3.0, 180.0, 90.0, -45.0])
    assert converted == pytest.approx([1.0, 2.0, 3.0, math.pi, math.pi / 2, -math.pi / 4])
