"""Joints [2–4], rotation [6,7] and inverse kinematics [5–12] against hand calculation."""

from __future__ import annotations

import math

import numpy as np
import pytest

from stgen.config import GeometryConfig, StrokeConfig
from stgen.error_codes import ErrorCode
from stgen.reference import base_joints, inverse_kinematics, joint_angles, platform_joints, rotation_matrix

GEOMETRY = GeometryConfig()


def test_joint_angles_of_the_default_platform():
    # Pairs centred on 60°, 180°, 300°, split by φb = 24.07° and φp = 103.66°.
    theta, phi = joint_angles(GEOMETRY)
    assert np.degrees(theta) == pytest.approx([47.965, 72.035, 167.965, 192.035, 287.965, 312.035])
    assert np.degrees(phi) == pytest.approx([8.17, 111.83, 128.17, 231.83, 248.17, 351.83])


def test_joints_lie_on_their_circles_at_their_heights():
    base, platform = base_joints(GEOMETRY), platform_joints(GEOMETRY)
    assert base.shape == platform.shape == (6, 3)
    assert np.hypot(base[:, 0], base[:, 1]) == pytest.approx([470.45] * 6)
    assert np.hypot(platform[:, 0], platform[:, 1]) == pytest.approx([388.95] * 6)
    assert base[:, 2] == pytest.approx([95.0] * 6)
    assert platform[:, 2] == pytest.approx([-115.0] * 6)
    assert base[0, :2] == pytest.approx(
        [470.45 * math.cos(math.radians(47.965)), 470.45 * math.sin(math.radians(47.965))]
    )


def _rz(a):
    return np.array([[math.cos(a), -math.sin(a), 0], [math.sin(a), math.cos(a), 0], [0, 0, 1]])


def _ry(b):
    return np.array([[math.cos(b), 0, math.sin(b)], [0, 1, 0], [-math.sin(b), 0, math.cos(b)]])


def _rx(g):
    return np.array([[1, 0, 0], [0, math.cos(g), -math.sin(g)], [0, math.sin(g), math.cos(g)]])


def test_rotation_is_rz_ry_rx():
    alpha, beta, gamma = 0.3, -0.2, 0.5
    assert rotation_matrix(alpha, beta, gamma) == pytest.approx(_rz(alpha) @ _ry(beta) @ _rx(gamma))


def test_rotation_about_single_axes():
    quarter = math.pi / 2
    assert rotation_matrix(quarter, 0, 0) @ [1, 0, 0] == pytest.approx([0, 1, 0], abs=1e-15)  # α about Z
    assert rotation_matrix(0, quarter, 0) @ [0, 0, 1] == pytest.approx([1, 0, 0], abs=1e-15)  # β about Y
    assert rotation_matrix(0, 0, quarter) @ [0, 1, 0] == pytest.approx([0, 0, 1], abs=1e-15)  # γ about X


def test_rotation_broadcasts():
    angles = np.random.default_rng(3).uniform(-1, 1, (4, 5, 3))
    matrices = rotation_matrix(angles[..., 0], angles[..., 1], angles[..., 2])
    assert matrices.shape == (4, 5, 3, 3)
    assert matrices[2, 3] == pytest.approx(_rz(angles[2, 3, 0]) @ _ry(angles[2, 3, 1]) @ _rx(angles[2, 3, 2]))
    identity = np.einsum("...ji,...jk->...ik", matrices, matrices)
    assert identity == pytest.approx(np.broadcast_to(np.eye(3), identity.shape))


def _home_leg_length(geometry: GeometryConfig) -> float:
    """Law of cosines: the horizontal gap between Pi and Bi spans the angle ϕ1 − θ1 = φb/2 − φp/2."""
    angle = math.radians(geometry.phi_b_deg - geometry.phi_p_deg) / 2
    horizontal_sq = geometry.rb**2 + geometry.rp**2 - 2 * geometry.rb * geometry.rp * math.cos(angle)
    vertical = geometry.h0 + geometry.hp - geometry.hb
    return math.sqrt(horizontal_sq + vertical**2)


def test_home_pose_gives_9_9994_mm_on_every_leg():
    result = inverse_kinematics(GEOMETRY, np.zeros(6))
    assert result.positions == pytest.approx([9.9994] * 6, abs=1e-4)
    assert result.positions == pytest.approx([_home_leg_length(GEOMETRY) - 1192.63] * 6, abs=1e-9)
    assert result.status == ErrorCode.OK and bool(np.all(result.in_stroke))


def test_pure_translation_matches_hand_formula():
    pose = np.array([12.0, -30.0, 150.0, 0.0, 0.0, 0.0])
    result = inverse_kinematics(GEOMETRY, pose)
    base, platform = base_joints(GEOMETRY), platform_joints(GEOMETRY)
    for leg in range(6):
        vector = platform[leg] + [12.0, -30.0, 150.0 + 1374.0] - base[leg]
        expected = math.sqrt(sum(component**2 for component in vector)) - 1192.63
        assert result.positions[leg] == pytest.approx(expected, abs=1e-9)


def test_rotated_pose_uses_degrees_at_the_interface():
    pose_deg = np.array([5.0, 7.0, 100.0, 4.0, -3.0, 2.0])
    rotation = _rz(math.radians(4.0)) @ _ry(math.radians(-3.0)) @ _rx(math.radians(2.0))
    base, platform = base_joints(GEOMETRY), platform_joints(GEOMETRY)
    expected = [
        np.linalg.norm(rotation @ platform[leg] + [5.0, 7.0, 1474.0] - base[leg]) - 1192.63 for leg in range(6)
    ]
    assert inverse_kinematics(GEOMETRY, pose_deg).positions == pytest.approx(expected, abs=1e-9)


def test_vectorised_ik_reports_reach_per_leg_and_per_pose():
    # Straight up and down: all legs equal. z = −50 shortens them below l0, z = 700 beyond the stroke.
    poses = np.zeros((3, 6))
    poses[:, 2] = [-50.0, 300.0, 700.0]
    result = inverse_kinematics(GEOMETRY, poses, StrokeConfig(min=0.0, max=600.0))
    horizontal_sq = _home_leg_length(GEOMETRY) ** 2 - 1164.0**2
    for row, lift in enumerate([-50.0, 300.0, 700.0]):
        expected = math.sqrt(horizontal_sq + (1164.0 + lift) ** 2) - 1192.63
        assert result.positions[row] == pytest.approx([expected] * 6, abs=1e-9)
    assert result.positions[0, 0] < 0.0 and result.positions[2, 0] > 600.0
    assert result.in_stroke.tolist() == [[False] * 6, [True] * 6, [False] * 6]
    assert result.status.tolist() == [ErrorCode.UNREACHABLE, ErrorCode.OK, ErrorCode.UNREACHABLE]
    assert result.reachable.tolist() == [False, True, False]


def test_single_out_of_stroke_leg_is_named():
    # A sideways shift lengthens some legs and shortens others; a stroke around home flags only some.
    pose = np.array([80.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    positions = inverse_kinematics(GEOMETRY, pose).positions
    short = positions < 9.0
    assert 0 < short.sum() < 6
    result = inverse_kinematics(GEOMETRY, pose, StrokeConfig(min=9.0, max=600.0))
    assert result.in_stroke.tolist() == (~short).tolist()
    assert result.status == ErrorCode.UNREACHABLE


def test_non_finite_pose_is_reported():
    result = inverse_kinematics(GEOMETRY, [0.0, np.nan, 0.0, 0.0, 0.0, 0.0])
    assert result.status == ErrorCode.NON_FINITE
    assert not np.any(result.in_stroke)
