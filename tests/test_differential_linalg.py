"""SP_LeibnizDeterminant (both variants), SP_LuSolve, SP_Jacobian and SP_Atan2 in st_runtime
against NumPy, the reference and hand-calculated cases (issue 4 item 5)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from st_runtime import api
from stgen.config import PlatformConfig
from stgen.reference import jacobian, leibniz_det, residual
from stgen.render import RenderOptions
from stgen.verify import check_linear_algebra, kinematics_sources, load_kinematics, random_poses, sample_matrices

CONFIG = PlatformConfig.default()
MATRICES = 400


@pytest.fixture(scope="module", params=["table", "unrolled"])
def runtime(request):
    return load_kinematics(CONFIG, RenderOptions(request.param), capacity=MATRICES)


def test_sample_matrices_cover_the_four_kinds():
    matrices, _, kinds = sample_matrices(8, 1)
    assert kinds == ["random", "scaled", "near-singular", "singular"] * 2
    conds = [np.linalg.cond(m) for m in matrices]
    assert conds[2] > 1e8 and conds[0] < 1e6
    assert np.linalg.matrix_rank(matrices[3]) < 6 and np.linalg.matrix_rank(matrices[7]) < 6


def test_determinant_and_solve_match_numpy_and_the_reference(runtime):
    det_check, lu_check = check_linear_algebra(runtime, MATRICES, 99, "variant")
    assert det_check.problems == ()
    assert det_check.max_error <= 1e-9
    assert lu_check.problems == ()
    assert lu_check.max_error <= 1e-9


def test_hand_calculated_determinants(runtime):
    diagonal = np.diag([1.0, 2.0, 3.0, 4.0, 5.0, 6.0])  # det = 6! = 720
    swapped = np.eye(6)[[1, 0, 2, 3, 4, 5]]  # one row exchange: det = -1
    cycle = np.eye(6)[[1, 2, 3, 4, 5, 0]]  # a 6-cycle is odd: det = -1
    ones = np.ones((6, 6))  # rank 1: det = 0
    run = runtime.linear_algebra(np.array([diagonal, swapped, cycle, ones]), np.ones((4, 6)))
    assert list(run.determinants) == [720.0, -1.0, -1.0, 0.0]


def test_hand_calculated_solve_and_singular_report(runtime):
    a = 2.0 * np.eye(6)
    a[0, 5] = 1.0  # x6 = b6/2, x1 = (b1 - x6)/2
    b = np.array([5.0, 2.0, 4.0, 6.0, 8.0, 2.0])
    zero_column = np.eye(6)
    zero_column[:, 3] = 0.0
    run = runtime.linear_algebra(np.array([a, zero_column]), np.array([b, b]))
    assert run.solved[0] and list(run.solutions[0]) == [2.0, 1.0, 2.0, 3.0, 4.0, 1.0]
    assert run.lu_determinants[0] == 64.0
    assert not run.solved[1]


def test_pivoting_avoids_a_zero_leading_pivot(runtime):
    a = np.eye(6)[[5, 4, 3, 2, 1, 0]]  # a_11 = 0: fails without row exchanges
    b = np.arange(1.0, 7.0)
    run = runtime.linear_algebra(np.array([a]), np.array([b]))
    assert run.solved[0] and list(run.solutions[0]) == [6.0, 5.0, 4.0, 3.0, 2.0, 1.0]
    assert run.lu_determinants[0] == leibniz_det(a) == run.determinants[0] == -1.0


# --------------------------------------------------------------------------- Jacobian and ATAN2

_JACOBIAN_AND_ATAN2 = """
PROGRAM Probe
VAR
    Pose : ARRAY[1..6] OF LREAL;
    Jacobian : ARRAY[1..6, 1..6] OF LREAL;
    LegLengthSquared : ARRAY[1..6] OF LREAL;
    Block : SP_Jacobian;
    Ys : ARRAY[1..200] OF LREAL;
    Xs : ARRAY[1..200] OF LREAL;
    Angles : ARRAY[1..200] OF LREAL;
    Item : INT;
END_VAR
Block(Pose := Pose, Jacobian := Jacobian, LegLengthSquared := LegLengthSquared);
FOR Item := 1 TO 200 DO
    Angles[Item] := SP_Atan2(Y := Ys[Item], X := Xs[Item]);
END_FOR;
END_PROGRAM
"""


@pytest.fixture(scope="module")
def probe():
    sources = kinematics_sources(CONFIG, RenderOptions("table"), capacity=1)
    sources["Probe.st"] = _JACOBIAN_AND_ATAN2
    plc = api.load_sources(sources).controller(stop_on_fault=True)
    return plc, plc.add_program("Probe")


def test_jacobian_matches_the_reference_and_central_differences(probe):
    plc, program = probe
    for pose_deg in random_poses(CONFIG, 20, 5):
        pose = pose_deg.copy()
        pose[3:] = np.radians(pose[3:])
        program["Pose"] = pose.tolist()
        plc.scan()
        j = np.array(program["Jacobian"])
        assert np.max(np.abs(j - jacobian(CONFIG.geometry, pose))) <= 1e-9 * np.max(np.abs(j))
        positions = np.zeros(6)
        numeric = np.empty((6, 6))
        for k in range(6):
            step = 1e-3 if k < 3 else 1e-6
            delta = np.zeros(6)
            delta[k] = step
            numeric[:, k] = (residual(CONFIG.geometry, pose + delta, positions)
                             - residual(CONFIG.geometry, pose - delta, positions)) / (2 * step)
        assert np.max(np.abs(j - numeric) / np.max(np.abs(j), axis=0)) <= 1e-6
        legs = residual(CONFIG.geometry, pose, np.full(6, -CONFIG.geometry.l0))  # |L_i|^2 - 0
        assert np.max(np.abs(np.array(program["LegLengthSquared"]) - legs)) <= 1e-9 * np.max(legs)


def test_atan2_is_quadrant_correct(probe):
    plc, program = probe
    rng = np.random.default_rng(11)
    axes = [(0.0, 1.0), (1.0, 0.0), (0.0, -1.0), (-1.0, 0.0), (0.0, 0.0), (-0.0, -2.0), (1e-300, -1.0), (5.0, -1e-300)]
    points = axes + [tuple(p) for p in rng.uniform(-100, 100, size=(200 - len(axes), 2))]
    program["Ys"] = [y for y, _ in points]
    program["Xs"] = [x for _, x in points]
    plc.scan()
    angles = program["Angles"]
    for (y, x), angle in zip(points, angles):
        expected = math.atan2(y, x)
        if y == 0.0 and x < 0.0:
            expected = math.pi  # the NJ has no signed zero semantics to honour: (0, -x) -> +pi
        assert angle == pytest.approx(expected, abs=1e-15), (y, x)
        assert -math.pi < angle <= math.pi
