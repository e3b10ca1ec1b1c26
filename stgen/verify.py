"""Hold the generated ST, executed in ``st_runtime``, against the NumPy reference.

The kinematics POUs are rendered for a configuration and loaded together with
small harness PROGRAMs (below) that run many cases in one scan, so ten
thousand IK poses cost one call into the runtime, not ten thousand. The
harness only moves numbers in and out of the POUs under test; every number
compared comes from the POUs themselves.

Public API (used by the differential tests, ``stgen verify`` and the benchmark):

* :func:`load_kinematics` -> :class:`KinematicsRuntime` with
  :meth:`~KinematicsRuntime.inverse_kinematics`, :meth:`~KinematicsRuntime.determinants`,
  :meth:`~KinematicsRuntime.lu_solve` and :meth:`~KinematicsRuntime.forward_kinematics`;
* :func:`random_poses`, :func:`test_matrices`: seeded cases;
* :func:`run_verification` -> rows of (POU, cases, max error, iterations, pass).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from stgen.config import PlatformConfig, SolverConfig
from stgen.error_codes import ErrorCode
from stgen.exports.iec import pou_text
from stgen.reference import forward_kinematics, inverse_kinematics, leibniz_det, lu_doolittle, lu_solve
from stgen.reference.linalg import SingularMatrixError
from stgen.render import KINEMATICS_TEMPLATES, RenderOptions, pou_name, render_program

#: Kinematics POUs (the controller's are not needed here).
KINEMATICS_POUS = tuple(pou_name(template) for template in KINEMATICS_TEMPLATES)

#: Estimated NJ501 time one harness scan may take (ns): a harness scan runs up
#: to `capacity` cases, far more than one PLC scan, so the F-PERIOD limit is
#: lifted to about 11 days; `fk_scan_time` estimates real scans.
HARNESS_TIME_LIMIT_NS = 10**15

# --------------------------------------------------------------------------- harness programs

#: The harness programs, ST files beside this package (their array sizes: the global constant
#: VERIFY_CASES, loaded with them by :func:`harness_sources`).
HARNESS_DIR = Path(__file__).resolve().parent / "harnesses"
HARNESSES = ("VerifyIk", "VerifyLinalg", "VerifyFk")


def cases_constant(capacity: int) -> str:
    """The global constant VERIFY_CASES = ``capacity`` that sizes the harnesses' arrays."""
    return f"VAR_GLOBAL CONSTANT\n    VERIFY_CASES : DINT := {int(capacity)};\nEND_VAR\n"


def harness_sources(capacity: int) -> dict[str, str]:
    """The default platform's harness programs and VERIFY_CASES = ``capacity``."""
    sources = {f"{name}.st": (HARNESS_DIR / f"{name}.st").read_text(encoding="utf-8") for name in HARNESSES}
    sources["VerifyCases.st"] = cases_constant(capacity)
    return sources


# --------------------------------------------------------------------------- results


@dataclass(frozen=True)
class IkRun:
    positions: np.ndarray  # [n, 6] mm
    reachable: np.ndarray  # [n] bool
    error_ids: np.ndarray  # [n] int


@dataclass(frozen=True)
class LinalgRun:
    determinants: np.ndarray  # [n] Leibniz
    lu_determinants: np.ndarray  # [n] from the LU diagonal (valid where solved)
    solutions: np.ndarray  # [n, 6] (valid where solved)
    solved: np.ndarray  # [n] bool


@dataclass(frozen=True)
class FkRun:
    poses: np.ndarray  # [n, 6] mm and degrees (valid where done)
    iterations: np.ndarray  # [n]
    calls: np.ndarray  # [n] FB calls (scans) used
    done: np.ndarray  # [n] bool
    error_ids: np.ndarray  # [n] int


class KinematicsRuntime:
    """The rendered kinematics loaded in ``st_runtime`` with the harness programs."""

    def __init__(self, project, capacity: int) -> None:
        self.project = project
        self.capacity = capacity
        # One harness scan runs many cases: lift the time limit accordingly.
        self._plc = project.controller(period="1ms", time_limit=HARNESS_TIME_LIMIT_NS)
        self._programs = {name: self._plc.add_program(name) for name in ("VerifyIk", "VerifyLinalg", "VerifyFk")}
        self._plc.controller.tasks[0].programs.clear()  # each harness runs only when asked

    def _run(self, name: str, **arrays) -> object:
        program = self._programs[name]
        for key, value in arrays.items():
            program.raw(key)[: len(value)] = value
        controller = self._plc.controller
        controller.tasks[0].programs[:] = [(name, program.obj)]
        faults_before = len(controller.faults)
        controller.run(1)
        if len(controller.faults) > faults_before:
            raise RuntimeError(f"runtime fault in {name}: {controller.faults[faults_before]}")
        return program

    def _batches(self, count: int):
        for start in range(0, count, self.capacity):
            yield start, min(start + self.capacity, count)

    def inverse_kinematics(self, poses_deg) -> IkRun:
        poses = np.asarray(poses_deg, dtype=float).reshape(-1, 6)
        positions, reachable, error_ids = [], [], []
        for start, stop in self._batches(len(poses)):
            chunk = poses[start:stop]
            program = self._programs["VerifyIk"]
            program["CaseCount"] = len(chunk)
            self._run("VerifyIk", Poses=chunk.ravel().tolist())
            positions.append(np.array(program.raw("Positions")[: len(chunk) * 6]).reshape(-1, 6))
            reachable.append(np.array(program.raw("Reachable")[: len(chunk)], dtype=bool))
            error_ids.append(np.array(program.raw("ErrorIDs")[: len(chunk)], dtype=int))
        return IkRun(np.concatenate(positions), np.concatenate(reachable), np.concatenate(error_ids))

    def linear_algebra(self, matrices, rhs) -> LinalgRun:
        """Leibniz det (SP_LeibnizDeterminant) and SP_LuSolve of every matrix [n, 6, 6] with rhs [n, 6]."""
        matrices = np.asarray(matrices, dtype=float).reshape(-1, 6, 6)
        rhs = np.asarray(rhs, dtype=float).reshape(-1, 6)
        parts: dict[str, list] = {"dets": [], "lu": [], "x": [], "ok": []}
        for start, stop in self._batches(len(matrices)):
            n = stop - start
            program = self._programs["VerifyLinalg"]
            program["CaseCount"] = n
            self._run("VerifyLinalg", Matrices=matrices[start:stop].ravel().tolist(), Rhs=rhs[start:stop].ravel().tolist())
            parts["dets"].append(np.array(program.raw("Determinants")[:n]))
            parts["lu"].append(np.array(program.raw("LuDeterminants")[:n]))
            parts["x"].append(np.array(program.raw("Solutions")[: n * 6]).reshape(-1, 6))
            parts["ok"].append(np.array(program.raw("Solved")[:n], dtype=bool))
        return LinalgRun(*(np.concatenate(parts[k]) for k in ("dets", "lu", "x", "ok")))

    def forward_kinematics(self, positions, start_poses_deg, solver: SolverConfig, max_calls: int = 10_000) -> FkRun:
        """SP_ForwardKinematics on every case, one FB call per simulated scan until it ends."""
        targets = np.asarray(positions, dtype=float).reshape(-1, 6)
        starts = np.broadcast_to(np.asarray(start_poses_deg, dtype=float), targets.shape)
        program = self._programs["VerifyFk"]
        program["Tolerance"] = solver.tolerance
        program["IterationsPerScan"] = solver.iterations_per_scan
        program["MaxIterations"] = solver.max_iterations
        program["MaxCalls"] = max_calls
        parts: dict[str, list] = {k: [] for k in ("poses", "iterations", "calls", "done", "ids")}
        for start, stop in self._batches(len(targets)):
            n = stop - start
            program["CaseCount"] = n
            self._run("VerifyFk", Targets=targets[start:stop].ravel().tolist(),
                      Starts=np.ascontiguousarray(starts[start:stop]).ravel().tolist())
            parts["poses"].append(np.array(program.raw("Poses")[: n * 6]).reshape(-1, 6))
            parts["iterations"].append(np.array(program.raw("Iterations")[:n], dtype=int))
            parts["calls"].append(np.array(program.raw("Calls")[:n], dtype=int))
            parts["done"].append(np.array(program.raw("Done")[:n], dtype=bool))
            parts["ids"].append(np.array(program.raw("ErrorIDs")[:n], dtype=int))
        return FkRun(*(np.concatenate(parts[k]) for k in ("poses", "iterations", "calls", "done", "ids")))


@dataclass(frozen=True)
class FkScanTime:
    """Estimated NJ501 time of SP_ForwardKinematics calls, one call per scan.

    `calls`: per-scan times with the configured IterationsPerScan;
    `per_iteration_ns` / `call_overhead_ns`: the worst call is about
    overhead + k * per_iteration; `fitting`: the largest IterationsPerScan
    whose worst call, on its own, stays within OMRON's 80 % of the period.
    """

    calls: object                  # st_runtime.controller.TaskTime
    iterations_per_scan: int
    per_iteration_ns: float
    call_overhead_ns: float
    fitting: int

    def render(self) -> str:
        period = self.calls.period_ns
        return (f"SP_ForwardKinematics on an NJ501 (estimate, FK alone, {period / 1e3:g} us period): "
                f"{self.per_iteration_ns / 1e3:.1f} us per Newton-Raphson iteration; with IterationsPerScan = "
                f"{self.iterations_per_scan}: max {self.calls.max_ns / 1e3:.1f} us, "
                f"p99 {self.calls.p99_ns / 1e3:.1f} us, mean {self.calls.mean_ns / 1e3:.1f} us per scan "
                f"({100 * self.calls.max_ns / period:.0f} % of the period at most); IterationsPerScan <= "
                f"{self.fitting} keeps a call within 80 % of the period")


def fk_scan_time(project, config: PlatformConfig, poses, starts, max_scans: int = 1000) -> FkScanTime:
    """SP_ForwardKinematics on the reference IK's cylinder positions of `poses`,
    called once per scan of the configured period until each solution ends
    (cases in turn), estimated by the NJ501 cost model."""
    from st_runtime.api import Instance
    from st_runtime.controller import LOAD_GUIDELINE, Task, TaskTime

    period_ns = int(round(config.task.period_s * 1e9))

    def scan_times(per_scan: int, cases) -> list[int]:
        plc = project.controller(period=period_ns, time_limit=HARNESS_TIME_LIMIT_NS)
        controller = plc.controller
        fk = project.compiled.new("SP_ForwardKinematics")
        view = Instance(fk)
        view["Tolerance"] = config.solver.tolerance
        view["MaxIterations"] = config.solver.max_iterations
        view["IterationsPerScan"] = per_scan
        controller.tasks[0].programs.append(("SP_ForwardKinematics", fk))
        times: list[int] = []
        for target, start in cases:
            view["CylinderPos"] = list(map(float, target))
            view["StartPose"] = list(map(float, start))
            view["Execute"] = True
            for _ in range(max_scans):
                controller.run(1)
                if not view["Busy"]:
                    break
            times += controller.task_times["Primary"]
            del controller.task_times["Primary"][:]
            view["Execute"] = False
            controller.run(1)
            del controller.task_times["Primary"][:]
        return times

    positions = inverse_kinematics(config.geometry, np.asarray(poses, dtype=float).reshape(-1, 6),
                                   config.stroke).positions
    cases = list(zip(positions, np.broadcast_to(np.asarray(starts, dtype=float), (len(positions), 6))))
    task = Task("Primary", period_ns, 1)
    configured = config.solver.iterations_per_scan
    calls = TaskTime.of(task, scan_times(configured, cases))
    one = max(scan_times(1, cases[:3]))       # the first call: setup and k iterations
    two = max(scan_times(2, cases[:3]))
    per_iteration = (two - one) / 1000
    overhead = one / 1000 - per_iteration
    fitting = max(0, int((LOAD_GUIDELINE * period_ns - overhead) // per_iteration))
    return FkScanTime(calls, configured, per_iteration, overhead, fitting)


def kinematics_sources(config: PlatformConfig | None = None, options: RenderOptions | None = None,
                       capacity: int = 1000) -> dict[str, str]:
    """IEC texts of the kinematics POUs plus the harness programs (``capacity`` cases per scan)."""
    program = render_program(config, options)
    sources = {f"{name}.st": pou_text(program.pou(name)) for name in KINEMATICS_POUS}
    sources.update(harness_sources(capacity))
    return sources


def load_kinematics(config: PlatformConfig | None = None, options: RenderOptions | None = None,
                    capacity: int = 1000) -> KinematicsRuntime:
    """Render, parse, check and compile the kinematics and the harness (raises ``LoadError``)."""
    from st_runtime import api

    return KinematicsRuntime(api.load_sources(kinematics_sources(config, options, capacity)), capacity)


# --------------------------------------------------------------------------- cases


#: Half-widths of the sampling box relative to the vertical stroke span (x, y, z) and in degrees.
BOX_LINEAR_FRACTION = np.array([0.3, 0.3, 0.45])
BOX_ANGLE_DEG = 15.0
#: Batches drawn before giving up on finding enough reachable poses.
MAX_SAMPLING_BATCHES = 50


class SamplingError(ValueError):
    """The configuration's reachable workspace could not be sampled."""


def workspace_box(config: PlatformConfig) -> tuple[np.ndarray, np.ndarray]:
    """(centre, half-widths) of the box the random poses are drawn from (mm, degrees).

    The heights z at which the level platform (x = y = 0, no rotation) is
    reachable span [z_lo, z_hi]; the box is centred at the middle of that span
    with half-widths 0.3, 0.3, 0.45 times the span for x, y, z and 15 degrees
    for the angles, so it covers the reachable workspace of any geometry and
    stroke. (Default platform: z from -10 to 602 mm.)
    """
    g = config.geometry
    # Only heights with the platform joints above the base joints (z + h0 + hp > hb): below
    # that plane lies the mirror image of the workspace, which no real platform reaches.
    lowest = g.hb - g.h0 - g.hp
    heights = lowest + np.arange(1.0, 8000.0, 1.0)
    poses = np.zeros((len(heights), 6))
    poses[:, 2] = heights
    reachable = inverse_kinematics(g, poses, config.stroke).reachable
    if not reachable.any():
        raise SamplingError("no height z makes the level platform reachable: "
                            "check geometry.h0, geometry.l0 and the stroke")
    first = int(np.argmax(reachable))
    run = int(np.argmin(reachable[first:])) if not reachable[first:].all() else len(reachable) - first
    low, high = heights[first], heights[first + run - 1]
    span = max(high - low, 1.0)
    centre = np.array([0.0, 0.0, (low + high) / 2.0, 0.0, 0.0, 0.0])
    half = np.concatenate([BOX_LINEAR_FRACTION * span, np.full(3, BOX_ANGLE_DEG)])
    return centre, half


def random_poses(config: PlatformConfig, count: int, seed: int, reachable: bool = True) -> np.ndarray:
    """``count`` seeded random poses (mm, degrees) drawn uniformly from :func:`workspace_box`.

    With ``reachable`` only poses whose six legs lie inside the stroke (by the
    reference IK) are kept, so they spread over the reachable workspace.
    """
    centre, half = workspace_box(config)
    rng = np.random.default_rng(seed)
    found: list[np.ndarray] = []
    total = 0
    for _ in range(MAX_SAMPLING_BATCHES):
        batch = centre + half * rng.uniform(-1.0, 1.0, size=(4 * count, 6))
        if reachable:
            batch = batch[inverse_kinematics(config.geometry, batch, config.stroke).reachable]
        found.append(batch)
        total += len(batch)
        if total >= count:
            return np.concatenate(found)[:count]
    raise SamplingError(f"found only {total} reachable poses of {count} in the box "
                        f"centre {centre.tolist()}, half-widths {half.tolist()}")


def sample_matrices(count: int, seed: int) -> tuple[np.ndarray, np.ndarray, list[str]]:
    """Seeded 6x6 matrices and right-hand sides, in four kinds (a quarter each):
    ``random`` (standard normal), ``scaled`` (rows and columns scaled by 10^-6 .. 10^6),
    ``near-singular`` (one row a combination of the others plus 1e-10 noise) and
    ``singular`` (two equal rows, or a zero column)."""
    rng = np.random.default_rng(seed)
    matrices, kinds = [], []
    for index in range(count):
        kind = ("random", "scaled", "near-singular", "singular")[index % 4]
        a = rng.standard_normal((6, 6))
        if kind == "scaled":
            a = a * 10.0 ** rng.uniform(-6, 6, size=(6, 1)) * 10.0 ** rng.uniform(-3, 3, size=(1, 6))
        elif kind == "near-singular":
            a[5] = rng.standard_normal(5) @ a[:5] + 1e-10 * rng.standard_normal(6)
        elif kind == "singular":
            if index % 8 == 3:
                a[4] = a[1]
            else:
                a[:, 2] = 0.0
        matrices.append(a)
        kinds.append(kind)
    return np.array(matrices), rng.standard_normal((count, 6)), kinds


# --------------------------------------------------------------------------- the comparison table


@dataclass(frozen=True)
class Check:
    """One row of ``stgen verify``'s table."""

    pou: str
    what: str
    cases: int
    max_error: float | None  # None: a check of outcomes, not of a numeric error
    limit: float
    unit: str
    iterations: str = ""
    problems: tuple[str, ...] = ()

    @property
    def passed(self) -> bool:
        return not self.problems and (self.max_error is None or self.max_error <= self.limit)


def check_inverse_kinematics(runtime: KinematicsRuntime, config: PlatformConfig, poses) -> Check:
    reference = inverse_kinematics(config.geometry, poses, config.stroke)
    run = runtime.inverse_kinematics(poses)
    error = float(np.max(np.abs(run.positions - reference.positions)))
    problems = []
    if not np.array_equal(run.reachable, reference.reachable):
        problems.append(f"Reachable differs on {int(np.sum(run.reachable != reference.reachable))} poses")
    expected_ids = np.array([ErrorCode(int(s)).error_id for s in reference.status])
    if not np.array_equal(run.error_ids, expected_ids):
        problems.append("ErrorID differs from the reference status")
    return Check("SP_InverseKinematics", "q vs reference IK", len(poses), error, 1e-9, "mm", problems=tuple(problems))


def check_linear_algebra(runtime: KinematicsRuntime, count: int, seed: int, variant: str) -> tuple[Check, Check]:
    """SP_LeibnizDeterminant and SP_LuSolve on :func:`sample_matrices`.

    Both must equal the reference bit for bit (same operation order) and report
    the same matrices singular; against ``numpy.linalg`` the relative error must
    be <= 1e-9 where the condition number allows it: determinants of the
    ``random`` and ``scaled`` kinds, solutions with cond(A) < 1e6.
    """
    matrices, rhs, kinds = sample_matrices(count, seed)
    run = runtime.linear_algebra(matrices, rhs)
    det_errors, solve_errors, det_problems, lu_problems = [], [], [], []
    for index, (a, b, kind) in enumerate(zip(matrices, rhs, kinds)):
        if leibniz_det(a) != run.determinants[index]:
            det_problems.append(f"det #{index} ({kind}) differs from the reference")
        if kind in ("random", "scaled"):
            expected = np.linalg.det(a)
            det_errors.append(abs(run.determinants[index] - expected) / abs(expected))
        try:
            lu, perm = lu_doolittle(a)
            expected_x = lu_solve(lu, perm, b)
        except SingularMatrixError:
            if run.solved[index]:
                lu_problems.append(f"#{index} ({kind}): singular, but SP_LuSolve returned TRUE")
            continue
        if not run.solved[index]:
            lu_problems.append(f"#{index} ({kind}): not singular, but SP_LuSolve returned FALSE")
            continue
        if not np.array_equal(run.solutions[index], expected_x):
            lu_problems.append(f"solution #{index} ({kind}) differs from the reference")
        if np.linalg.cond(a) < 1e6:
            exact = np.linalg.solve(a, b)
            solve_errors.append(float(np.max(np.abs(run.solutions[index] - exact)) / np.max(np.abs(exact))))
        if kind in ("random", "scaled"):
            expected = np.linalg.det(a)
            solve_errors.append(abs(run.lu_determinants[index] - expected) / abs(expected))
    if not all(not run.solved[i] for i, k in enumerate(kinds) if k == "singular"):
        lu_problems.append("a singular matrix was reported solved")
    return (
        Check("SP_LeibnizDeterminant", f"det, {variant} (rel. to numpy)", len(matrices),
              max(det_errors, default=0.0), 1e-9, "rel", problems=tuple(det_problems)),
        Check("SP_LuSolve", "x and det (rel. to numpy)", len(matrices),
              max(solve_errors, default=0.0), 1e-9, "rel", problems=tuple(lu_problems)),
    )


def fk_solver(config: PlatformConfig, tolerance: float = 1e-9, **changes) -> SolverConfig:
    """The configuration's solver settings with ``tolerance`` (and any other field) replaced."""
    values = dict(tolerance=tolerance, singularity_threshold=config.solver.singularity_threshold,
                  iterations_per_scan=config.solver.iterations_per_scan,
                  max_iterations=config.solver.max_iterations, start_pose=config.solver.start_pose)
    values.update(changes)
    return SolverConfig(**values)


def check_forward_kinematics(runtime: KinematicsRuntime, config: PlatformConfig, poses, label: str,
                             starts, tolerance: float = 1e-9, iterations_per_scan: int | None = None) -> Check:
    """FK of the reference IK's cylinder positions: the pose within 1e-6 mm / 1e-6 deg of
    the true one (within ``tolerance`` when that is coarser), and the same ErrorID,
    iterations and scans as the reference."""
    solver = fk_solver(config, tolerance, **({} if iterations_per_scan is None else
                                             {"iterations_per_scan": iterations_per_scan}))
    positions = inverse_kinematics(config.geometry, poses, config.stroke).positions
    starts = np.broadcast_to(np.asarray(starts, dtype=float), np.shape(poses))
    run = runtime.forward_kinematics(positions, starts, solver)
    problems = []
    errors = []
    iteration_counts = []
    for index in range(len(poses)):
        ref = forward_kinematics(config.geometry, positions[index], starts[index], solver)
        if int(run.iterations[index]) != ref.iterations:
            problems.append(f"case {index}: {run.iterations[index]} iterations, reference {ref.iterations}")
        if int(run.error_ids[index]) != ref.status.error_id:
            problems.append(f"case {index}: ErrorID {run.error_ids[index]:#06x}, reference {ref.status.name}")
        if int(run.calls[index]) != ref.scans:
            problems.append(f"case {index}: {run.calls[index]} scans, reference {ref.scans}")
        if ref.converged and run.done[index]:
            errors.append(float(np.max(np.abs(run.poses[index] - poses[index]))))
            iteration_counts.append(ref.iterations)
        elif ref.converged:
            problems.append(f"case {index}: reference converged, the FB did not")
    counts = f"{min(iteration_counts)}..{max(iteration_counts)}" if iteration_counts else "-"
    per_scan = "" if iterations_per_scan is None else f", {iterations_per_scan}/scan"
    return Check("SP_ForwardKinematics", f"pose from {label} (Tolerance {tolerance:g}{per_scan})", len(poses),
                 max(errors, default=math.inf), max(1e-6, tolerance), "mm|deg", counts, tuple(problems))


def fk_error_cases(config: PlatformConfig) -> list[tuple[str, np.ndarray, np.ndarray, SolverConfig]]:
    """(name, cylinder positions, start pose, solver) of the FK error paths."""
    g = config.geometry
    solver = fk_solver(config)
    reachable = inverse_kinematics(g, np.array([20.0, -10.0, 150.0, 2.0, -1.0, 3.0]), config.stroke).positions
    lo, hi = config.stroke.min, config.stroke.max
    start = np.asarray(config.solver.start_pose, dtype=float)
    # R = I with the platform joints in the plane of the base joints (z + h0 + hp = hb): all legs
    # horizontal, the z column of J is zero and det J = 0 before the first step.
    flat = np.array([0.0, 0.0, g.hb - g.h0 - g.hp, 0.0, 0.0, 0.0])
    return [
        ("unreachable lengths", np.array([lo, hi, lo, hi, lo, hi]), start, solver),
        ("NaN cylinder position", np.where(np.arange(6) == 2, np.nan, reachable), start, solver),
        ("singular Jacobian at the start", reachable, flat, solver),
        ("iteration limit 2", reachable, start, fk_solver(config, max_iterations=2)),
    ]


def check_fk_error_paths(runtime: KinematicsRuntime, config: PlatformConfig) -> Check:
    """Every error path ends like the reference (same ErrorID and iterations), with a finite Pose."""
    problems = []
    cases = fk_error_cases(config)
    for name, positions, start, solver in cases:
        run = runtime.forward_kinematics(positions[None, :], start[None, :], solver)
        ref = forward_kinematics(config.geometry, positions, start, solver)
        got = (int(run.error_ids[0]), int(run.iterations[0]), bool(run.done[0]))
        want = (ref.status.error_id, ref.iterations, ref.converged)
        if got != want:
            problems.append(f"{name}: (ErrorID, iterations, done) = {got}, reference {want}")
        if ref.converged:
            problems.append(f"{name}: the reference converged; not an error path")
        if not np.all(np.isfinite(run.poses[0])):
            problems.append(f"{name}: a non-finite value reached Pose")
    return Check("SP_ForwardKinematics", "error paths (ErrorID, iterations)", len(cases), None, 0.0, "",
                 problems=tuple(problems))


def run_verification(config: PlatformConfig | None = None, poses: int = 10_000, seed: int = 2024,
                     fk_poses: int = 500, matrices: int = 400, timing: list | None = None) -> list[Check]:
    """Every comparison of ``stgen verify``: ``poses`` IK poses (plus a tenth unreachable
    ones), ``matrices`` 6x6 systems per determinant variant, ``fk_poses`` FK solves from
    p_NR and as many from warm starts.  With a ``timing`` list, the estimated NJ501
    time of the FK calls (`FkScanTime`, up to 50 solves from p_NR) is appended to it."""
    config = config if config is not None else PlatformConfig.default()
    if not config.is_default_kind:  # a crank platform or a moving base (docs/mathematics.md sections 6.1, 6.2)
        from stgen.verify_variants import run_variant_verification

        return run_variant_verification(config, poses=poses, seed=seed, fk_poses=fk_poses)
    reachable = random_poses(config, poses, seed)
    mixed = random_poses(config, max(1, poses // 10), seed + 1, reachable=False)
    table = load_kinematics(config, RenderOptions("table"))
    unrolled = load_kinematics(config, RenderOptions("unrolled"))
    checks = [check_inverse_kinematics(table, config, np.concatenate([reachable, mixed]))]
    det_table, lu = check_linear_algebra(table, matrices, seed + 2, "table")
    det_unrolled, _ = check_linear_algebra(unrolled, matrices, seed + 2, "unrolled")
    checks += [det_table, det_unrolled, lu]
    fk = reachable[:fk_poses]
    checks.append(check_forward_kinematics(table, config, fk, "p_NR", config.solver.start_pose))
    rng = np.random.default_rng(seed + 3)
    warm = fk + rng.uniform(-1.0, 1.0, size=fk.shape) * WARM_START_OFFSET
    checks.append(check_forward_kinematics(table, config, fk, "warm starts", warm))
    checks.append(check_forward_kinematics(table, config, fk[: max(1, len(fk) // 10)], "p_NR", config.solver.start_pose,
                                           iterations_per_scan=1))
    study = check_forward_kinematics(table, config, fk, "p_NR", config.solver.start_pose, tolerance=config.solver.tolerance)
    checks.append(study)  # the study's Klim: it reports 3 to 13 iterations on the NJ501
    if timing is not None:
        timing.append(fk_scan_time(table.project, config, fk[:50], config.solver.start_pose))
    checks.append(check_fk_error_paths(table, config))
    from_lu = load_kinematics(config, RenderOptions("lu"))
    check = check_forward_kinematics(from_lu, config, fk, "p_NR, det J from LU", config.solver.start_pose)
    checks.append(check)
    return checks


#: Largest offset of a warm start from the true pose (mm, degrees).
WARM_START_OFFSET = np.array([2.0, 2.0, 2.0, 0.5, 0.5, 0.5])
