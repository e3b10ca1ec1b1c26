"""Test vectors for the generated test benches (`stgen generate --tests`).

The NumPy reference computes every expected value; the templates in
``st_templates/tests/`` hold them in constant arrays of one PROGRAM per bench
(for the real controller) and of a TEST file (for `stgen test`).  Seeds are
fixed, so the same configuration always renders the same benches.

* IK: seeded random poses, reachable and a few outside the stroke ->
  cylinder positions and ErrorID (:func:`inverse_kinematics`);
* FK: the IK's cylinder positions of seeded poses, solved from p_NR ->
  pose, iterations and ErrorID (:func:`forward_kinematics`, the FB's own
  state machine);
* determinant and LU: seeded 6x6 matrices of the four kinds of
  ``stgen verify`` -> det (Leibniz, same product order as the ST), solution,
  solved flag and det from the LU diagonal (Doolittle with partial pivoting).
  A determinant is compared relative to Hadamard's bound prod_i |row_i|
  (>= |det A|, the size of its rounding error), so near-singular matrices
  do not demand digits no computation has.

Cases per scan keep one scan of a bench inside the task period: the FK bench
runs one FB call a scan (``iterations_per_scan`` Newton steps, about 49.5 us
each on an NJ501-1300 by the study's measurement, docs/nj501.md), the others a few
cases of a single 720-term determinant or 6x6 LU each.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from stgen.config import PlatformConfig
from stgen.error_codes import ErrorCode
from stgen.reference.forward import forward_kinematics
from stgen.reference.kinematics import inverse_kinematics
from stgen.reference.linalg import SingularMatrixError, leibniz_det, lu_doolittle, lu_solve

SEED = 20261123
IK_REACHABLE, IK_UNREACHABLE, IK_PER_SCAN = 24, 8, 8
FK_CASES = 8
DET_CASES, DET_PER_SCAN = 8, 1
LU_CASES, LU_PER_SCAN = 8, 2
#: Accepted differences from the reference: the ST does the reference's
#: operations in the reference's order, so these only absorb a different
#: rounding of the controller's maths library.
IK_TOLERANCE_MM = 1e-9
FK_TOLERANCE = 1e-6          # mm and degrees
#: Klim of the FK bench (stgen verify's): tight enough that a solve takes
#: more Newton steps than one call makes, so cases span scans.
FK_KLIM = 1e-9
RELATIVE_TOLERANCE = 1e-9    # determinant and LU solution, relative


@dataclass(frozen=True)
class BenchVectors:
    ik_poses: list
    ik_positions: list
    ik_error_ids: list
    fk_positions: list
    fk_starts: list
    fk_poses: list
    fk_iterations: list
    fk_scans: list          # FB calls of each solve (the bench: one a scan)
    fk_error_ids: list
    fk_solver_tolerance: float
    matrices: list          # DET_CASES + LU_CASES matrices, each 6 rows of 6
    determinants: list      # Leibniz det of the first DET_CASES matrices
    lu_rhs: list
    lu_solutions: list      # zeros where singular
    lu_solved: list
    lu_determinants: list   # 0.0 where singular
    ik_per_scan: int = IK_PER_SCAN
    det_per_scan: int = DET_PER_SCAN
    lu_per_scan: int = LU_PER_SCAN
    ik_tolerance: float = IK_TOLERANCE_MM
    fk_tolerance: float = FK_TOLERANCE
    relative_tolerance: float = RELATIVE_TOLERANCE


def bench_vectors(config: PlatformConfig) -> BenchVectors:
    from stgen.verify import fk_solver, random_poses, sample_matrices

    reachable = random_poses(config, IK_REACHABLE, SEED)
    drawn = random_poses(config, 50 * IK_UNREACHABLE, SEED + 1, reachable=False)
    far = drawn[~inverse_kinematics(config.geometry, drawn, config.stroke).reachable]
    poses = np.concatenate([reachable, far[:IK_UNREACHABLE]])
    ik = inverse_kinematics(config.geometry, poses, config.stroke)

    solver = fk_solver(config, FK_KLIM)
    fk_targets = random_poses(config, FK_CASES, SEED + 2)
    fk_positions = inverse_kinematics(config.geometry, fk_targets, config.stroke).positions
    start = np.asarray(config.solver.start_pose, dtype=float)
    fk = [forward_kinematics(config.geometry, q, start, solver) for q in fk_positions]

    matrices, rhs, _kinds = sample_matrices(DET_CASES + LU_CASES, SEED + 3)
    determinants = [float(leibniz_det(a)) for a in matrices[:DET_CASES]]
    solutions, solved, lu_dets = [], [], []
    for a, b in zip(matrices[DET_CASES:], rhs[DET_CASES:]):
        try:
            lu, perm = lu_doolittle(a)
        except SingularMatrixError:
            solutions.append([0.0] * 6)
            solved.append(False)
            lu_dets.append(0.0)
            continue
        solutions.append(lu_solve(lu, perm, b).tolist())
        solved.append(True)
        lu_dets.append(_lu_determinant(lu, perm))
    return BenchVectors(
        ik_poses=poses.tolist(), ik_positions=ik.positions.tolist(),
        ik_error_ids=[ErrorCode(int(s)).error_id for s in ik.status],
        fk_positions=fk_positions.tolist(), fk_starts=[start.tolist()] * FK_CASES,
        fk_poses=[r.pose.tolist() for r in fk], fk_iterations=[r.iterations for r in fk],
        fk_scans=[r.scans for r in fk],
        fk_error_ids=[r.status.error_id for r in fk], fk_solver_tolerance=solver.tolerance,
        matrices=[m.tolist() for m in matrices], determinants=determinants,
        lu_rhs=rhs[DET_CASES:].tolist(), lu_solutions=solutions, lu_solved=solved,
        lu_determinants=lu_dets,
    )


def _lu_determinant(lu: np.ndarray, perm: np.ndarray) -> float:
    """det A = (-1)^swaps * prod(U_kk), in SP_LuSolve's order (k = 1..6)."""
    sign = 1.0
    seen = list(range(len(perm)))
    for k in range(len(perm)):            # count the transpositions of the row exchanges
        while seen[k] != int(perm[k]):
            j = seen.index(int(perm[k]))
            seen[k], seen[j] = seen[j], seen[k]
            sign = -sign
    det = sign
    for k in range(len(perm)):
        det *= float(lu[k, k])
    return det
