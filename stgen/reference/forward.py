"""Forward kinematics by Newton–Raphson, step for step as the ST FB does it (docs/mathematics.md section 3, [13–18, 34–36]).

Per iteration, at the current estimate a (mm and radians):

1. F = f(a) (:func:`residual`) and J = ∂f/∂a (:func:`jacobian`);
   any non-finite entry → :attr:`ErrorCode.NON_FINITE`;
2. |det J| by the Leibniz formula <= Ktol → :attr:`ErrorCode.SINGULAR_JACOBIAN`
   (a non-finite det → NON_FINITE);
3. solve J·Δ = F by Doolittle LU with partial pivoting (a zero pivot →
   SINGULAR_JACOBIAN);
4. a ← a − Δ, iterations += 1; a non-finite a → NON_FINITE;
5. converged (:attr:`ErrorCode.OK`) when |Δk| < Klim for every k; otherwise,
   if iterations has reached ``max_iterations`` → NOT_CONVERGED.

One call of :meth:`NewtonRaphsonSolver.scan` does at most
``iterations_per_scan`` iterations and keeps its state for the next scan, like
one call of the FB in one PLC scan. The measured positions are not checked
against the stroke: they are what the cylinders report.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from stgen.config import GeometryConfig, SolverConfig
from stgen.error_codes import ErrorCode
from stgen.reference.geometry import pose_to_degrees, pose_to_radians
from stgen.reference.kinematics import jacobian, residual
from stgen.reference.linalg import SingularMatrixError, leibniz_det, lu_doolittle, lu_solve


@dataclass(frozen=True)
class ForwardKinematicsResult:
    """Outcome of one FK solve.

    ``pose``: last estimate (x, y, z in mm, α, β, γ in degrees), also on error;
    ``iterations``: Newton steps taken; ``scans``: FB calls used;
    ``status``: :class:`ErrorCode`.
    """

    pose: np.ndarray
    iterations: int
    scans: int
    status: ErrorCode

    @property
    def converged(self) -> bool:
        return self.status == ErrorCode.OK


class NewtonRaphsonSolver:
    """The FK function block's state machine: :meth:`start`, then :meth:`scan` until :attr:`done`."""

    def __init__(self, geometry: GeometryConfig, solver: SolverConfig | None = None) -> None:
        self.geometry = geometry
        self.settings = solver if solver is not None else SolverConfig()
        self._estimate = np.zeros(6)
        self._positions = np.zeros(6)
        self.iterations = 0
        self.scans = 0
        self.done = True
        self.status = ErrorCode.OK

    def start(self, positions, start_pose_deg=None) -> None:
        """Begin a solve for cylinder positions ``q[6]`` (mm) from ``start_pose_deg`` (default p_NR)."""
        start = self.settings.start_pose if start_pose_deg is None else start_pose_deg
        self._estimate = pose_to_radians(np.asarray(start, dtype=float).reshape(6))
        self._positions = np.asarray(positions, dtype=float).reshape(6).copy()
        self.iterations = 0
        self.scans = 0
        self.done = False
        self.status = ErrorCode.OK

    @property
    def pose_deg(self) -> np.ndarray:
        """The current estimate, mm and degrees."""
        return pose_to_degrees(self._estimate)

    def scan(self) -> bool:
        """One FB call: up to ``iterations_per_scan`` iterations. Returns :attr:`done`."""
        if self.done:
            return True
        self.scans += 1
        for _ in range(self.settings.iterations_per_scan):
            if self.step():
                break
        return self.done

    def step(self) -> bool:
        """One Newton–Raphson iteration (steps 1–5 of the module docstring). Returns :attr:`done`."""
        if self.done:
            return True
        with np.errstate(invalid="ignore", over="ignore"):  # non-finite values are reported, not warned
            values = residual(self.geometry, self._estimate, self._positions)
            matrix = jacobian(self.geometry, self._estimate)
        if not (np.all(np.isfinite(values)) and np.all(np.isfinite(matrix))):
            return self._finish(ErrorCode.NON_FINITE)
        determinant = leibniz_det(matrix)
        if not np.isfinite(determinant):
            return self._finish(ErrorCode.NON_FINITE)
        if abs(determinant) <= self.settings.singularity_threshold:
            return self._finish(ErrorCode.SINGULAR_JACOBIAN)
        try:
            lu, perm = lu_doolittle(matrix)
        except SingularMatrixError:
            return self._finish(ErrorCode.SINGULAR_JACOBIAN)
        delta = lu_solve(lu, perm, values)
        self._estimate = self._estimate - delta
        self.iterations += 1
        if not np.all(np.isfinite(self._estimate)):
            return self._finish(ErrorCode.NON_FINITE)
        if np.all(np.abs(delta) < self.settings.tolerance):
            return self._finish(ErrorCode.OK)
        if self.iterations >= self.settings.max_iterations:
            return self._finish(ErrorCode.NOT_CONVERGED)
        return False

    def result(self) -> ForwardKinematicsResult:
        return ForwardKinematicsResult(self.pose_deg, self.iterations, self.scans, self.status)

    def _finish(self, status: ErrorCode) -> bool:
        self.status = status
        self.done = True
        return True


def forward_kinematics(
    geometry: GeometryConfig,
    positions,
    start_pose_deg=None,
    solver: SolverConfig | None = None,
) -> ForwardKinematicsResult:
    """Pose (mm, degrees) whose IK gives ``positions[6]``, by Newton–Raphson from ``start_pose_deg``.

    ``solver`` defaults to :class:`SolverConfig` (Klim 0.01, start p_NR).
    Runs scans until the solver is done; never raises for a numerical failure,
    the ``status`` says what happened.
    """
    machine = NewtonRaphsonSolver(geometry, solver)
    machine.start(positions, start_pose_deg)
    while not machine.scan():
        pass
    return machine.result()
