"""Hold the platform variants' generated ST against the NumPy reference (docs/mathematics.md sections 6.1, 6.2).

Like :mod:`stgen.verify` for the default platform: the variant's kinematics
are rendered, loaded in ``st_runtime`` with harness PROGRAMs that run many
cases in one scan, and every output is compared with the reference:

* crank platform: SP_InverseKinematics' crank angles, LegInRange and ErrorID
  against :mod:`stgen.reference.crank` and :func:`~stgen.reference.feasibility.error_ids`;
  SP_ForwardKinematics on measured crank angles against
  :func:`~stgen.reference.variant_fk.variant_forward_kinematics` (pose, iterations, ErrorID);
* moving base: SP_InverseKinematics' cylinder positions, universal-joint angles,
  tilt and ErrorID for random upper and base poses; SP_ForwardKinematics on
  cylinder positions with the base pose, like the crank's;
* both: leg (or crank) velocities and accelerations of the reference
  (:mod:`stgen.reference.rates`) against central differences of the IK the ST
  computes, so the rate reference is held against the ST too.
"""

from __future__ import annotations

import math

import numpy as np

from stgen.config import PlatformConfig, SolverConfig
from stgen.exports.iec import pou_text
from stgen.reference.crank import crank_inverse_kinematics
from stgen.reference.feasibility import error_ids, feasibility
from stgen.reference.moving_base import legs, spherical_tilt, universal_joint_angles
from stgen.reference.rates import crank_rates, leg_rates
from stgen.reference.variant_fk import variant_forward_kinematics
from stgen.render import render_program
from stgen.verify import HARNESS_DIR, HARNESS_TIME_LIMIT_NS, Check, KinematicsRuntime, cases_constant

#: The harnesses by platform kind (crank?): IK, then FK.
HARNESSES = {True: ("VerifyVariantIkCrank.st", "VerifyVariantFkCrank.st"),
             False: ("VerifyVariantIkMovingBase.st", "VerifyVariantFkMovingBase.st")}


def variant_harness_sources(config: PlatformConfig, capacity: int) -> dict[str, str]:
    """The IK and FK harnesses of ``config``'s kind and the constant VERIFY_CASES = ``capacity``."""
    ik, fk = HARNESSES[config.is_crank]
    return {
        "VerifyVariantIk.st": (HARNESS_DIR / ik).read_text(encoding="utf-8"),
        "VerifyVariantFk.st": (HARNESS_DIR / fk).read_text(encoding="utf-8"),
        "VerifyCases.st": cases_constant(capacity),
    }


#: Tolerances of the comparisons: mm and degrees.
IK_LIMIT = 1e-9
FK_LIMIT = 1e-9


class VariantRuntime(KinematicsRuntime):
    """A variant's rendered kinematics loaded in ``st_runtime`` with its harness programs
    (the default platform's runtime, with the variant's harnesses and their calls)."""

    def __init__(self, config: PlatformConfig, capacity: int = 1000) -> None:
        from st_runtime import api

        program = render_program(config)
        sources = {f"{pou.name}.st": pou_text(pou) for pou in program.pous}
        sources.update(variant_harness_sources(config, capacity))
        names = ["VerifyVariantIk", "VerifyVariantFk"]
        self.config = config
        self.capacity = capacity
        self.project = api.load_sources(sources)
        self._plc = self.project.controller(period="1ms", time_limit=HARNESS_TIME_LIMIT_NS)
        self._programs = {name: self._plc.add_program(name) for name in names}
        self._plc.controller.tasks[0].programs.clear()

    def _run(self, name: str, count: int, **arrays):
        self._programs[name]["CaseCount"] = count
        return super()._run(name, **arrays)

    def _read(self, program, name: str, count: int, width: int = 6, dtype=float) -> np.ndarray:
        values = np.array(program.raw(name)[: count * width], dtype=dtype)
        return values.reshape(-1, width) if width > 1 else values

    def inverse_kinematics(self, poses, bases=None) -> dict[str, np.ndarray]:
        poses = np.asarray(poses, dtype=float).reshape(-1, 6)
        bases = np.zeros_like(poses) if bases is None else np.asarray(bases, dtype=float).reshape(-1, 6)
        parts: dict[str, list] = {}
        for start, stop in self._batches(len(poses)):
            n = stop - start
            arrays = {"Poses": poses[start:stop].ravel().tolist()}
            if not self.config.is_crank:
                arrays["Bases"] = bases[start:stop].ravel().tolist()
            program = self._run("VerifyVariantIk", n, **arrays)
            names = (("Angles", float), ("InRange", bool)) if self.config.is_crank else (
                ("Positions", float), ("Gammas", float), ("Psis", float), ("Tilts", float))
            for name, dtype in names:
                parts.setdefault(name, []).append(self._read(program, name, n, 6, dtype))
            parts.setdefault("ErrorIDs", []).append(self._read(program, "ErrorIDs", n, 1, int))
            parts.setdefault("ErrorLegs", []).append(self._read(program, "ErrorLegs", n, 1, int))
        return {name: np.concatenate(chunks) for name, chunks in parts.items()}

    def forward_kinematics(self, measured, starts, solver: SolverConfig, bases=None, max_calls: int = 10_000):
        measured = np.asarray(measured, dtype=float).reshape(-1, 6)
        starts = np.broadcast_to(np.asarray(starts, dtype=float), measured.shape)
        bases = np.zeros_like(measured) if bases is None else np.asarray(bases, dtype=float).reshape(-1, 6)
        program = self._programs["VerifyVariantFk"]
        program["Tolerance"] = solver.tolerance
        program["IterationsPerScan"] = solver.iterations_per_scan
        program["MaxIterations"] = solver.max_iterations
        program["MaxCalls"] = max_calls
        parts: dict[str, list] = {}
        for start, stop in self._batches(len(measured)):
            n = stop - start
            arrays = {"Targets": measured[start:stop].ravel().tolist(),
                      "Starts": np.ascontiguousarray(starts[start:stop]).ravel().tolist()}
            if self.config.moving_base:
                arrays["Bases"] = bases[start:stop].ravel().tolist()
            self._run("VerifyVariantFk", n, **arrays)
            for name, width, dtype in (("Poses", 6, float), ("Iterations", 1, int), ("Done", 1, bool),
                                       ("ErrorIDs", 1, int)):
                parts.setdefault(name, []).append(self._read(program, name, n, width, dtype))
        return {name: np.concatenate(chunks) for name, chunks in parts.items()}


# --------------------------------------------------------------------------- cases


def variant_poses(config: PlatformConfig, count: int, seed: int, feasible_share: float = 0.9):
    """(upper poses, base poses) for a variant: mostly feasible ones (by the reference), the rest
    anywhere in the sampling box. Seeded; mm and degrees."""
    rng = np.random.default_rng(seed)
    if config.is_crank:
        centre, half = np.zeros(6), np.array([250.0, 250.0, 200.0, 20.0, 20.0, 20.0])
    else:
        centre, half = np.array([0, 0, 75.0, 0, 0, 0]), np.array([100.0, 100.0, 80.0, 12.0, 12.0, 25.0])
    base_half = np.zeros(6) if not config.moving_base else np.array([30.0, 30.0, 20.0, 8.0, 8.0, 8.0])
    want = max(1, int(round(count * feasible_share)))
    found_upper, found_base, total = [], [], 0
    for _ in range(200):
        upper = centre + half * rng.uniform(-1, 1, (4 * count, 6))
        base = base_half * rng.uniform(-1, 1, (4 * count, 6))
        keep = feasibility(config, upper, base).feasible
        found_upper.append(upper[keep])
        found_base.append(base[keep])
        total += int(keep.sum())
        if total >= want:
            break
    feasible_upper = np.concatenate(found_upper)[:want]
    feasible_base = np.concatenate(found_base)[:want]
    rest = count - len(feasible_upper)
    upper = np.concatenate([feasible_upper, centre + half * rng.uniform(-1, 1, (rest, 6))])
    base = np.concatenate([feasible_base, base_half * rng.uniform(-1, 1, (rest, 6))])
    return upper, base


# --------------------------------------------------------------------------- checks


def check_variant_ik(runtime: VariantRuntime, upper, base) -> list[Check]:
    config = runtime.config
    run = runtime.inverse_kinematics(upper, base)
    ids, leg_named = error_ids(feasibility(config, upper, base))
    problems = []
    if not np.array_equal(run["ErrorIDs"], ids):
        bad = np.flatnonzero(run["ErrorIDs"] != ids)
        problems.append(f"ErrorID differs on {len(bad)} poses, first {upper[bad[0]].tolist()}: "
                        f"{run['ErrorIDs'][bad[0]]:#06x}, reference {ids[bad[0]]:#06x}")
    if not np.array_equal(run["ErrorLegs"], leg_named):
        problems.append(f"ErrorLeg differs on {int(np.sum(run['ErrorLegs'] != leg_named))} poses")
    if config.is_crank:
        reference = crank_inverse_kinematics(config, upper)
        solvable = reference.solvable
        error = float(np.max(np.abs(run["Angles"][solvable] - reference.angles_deg[solvable]), initial=0.0))
        if not np.array_equal(run["InRange"], reference.in_limits):
            problems.append(f"LegInRange differs on {int(np.sum(run['InRange'] != reference.in_limits))} legs")
        return [Check("SP_InverseKinematics", "crank angles vs reference (crank, deg)", len(upper), error,
                      IK_LIMIT, "deg", problems=tuple(problems))]
    state = legs(config, upper, base)
    gamma, psi = (np.degrees(a) for a in universal_joint_angles(config, state))
    tilt = np.degrees(spherical_tilt(state))
    length_error = float(np.max(np.abs(run["Positions"] - state.extensions)))
    angle_error = max(float(np.max(np.abs(run[name] - value)))
                      for name, value in (("Gammas", gamma), ("Psis", psi), ("Tilts", tilt)))
    return [Check("SP_InverseKinematics", "D_i vs reference (moving base)", len(upper), length_error, IK_LIMIT,
                  "mm", problems=tuple(problems)),
            Check("SP_InverseKinematics", "gamma, psi, tilt vs reference", len(upper), angle_error, IK_LIMIT, "deg")]


def check_variant_rates(runtime: VariantRuntime, upper, base, seed: int) -> Check:
    """Reference rates (velocity and acceleration of every leg or crank) against central
    differences of the IK the ST computes, along a straight-line motion through each pose.

    Velocity: step 1e-6 s (truncation O(h²) is negligible even near the crank's reach
    limit, rounding ~1e-12/h); acceleration: step 1e-4 s, held to 1e-3 of its size
    (the difference quotient's truncation grows with the higher derivatives, which are
    large where a crank nears a singular transmission)."""
    config = runtime.config
    rng = np.random.default_rng(seed)
    rate = rng.uniform(-1, 1, upper.shape) * [20, 20, 20, 5, 5, 5]
    base_rate = rng.uniform(-1, 1, upper.shape) * [10, 10, 10, 3, 3, 3] if config.moving_base else np.zeros_like(upper)

    def ik(offset):
        run = runtime.inverse_kinematics(upper + offset * rate, base + offset * base_rate)
        return run["Angles"] if config.is_crank else run["Positions"]

    h_velocity, h_acceleration = 1e-6, 1e-4
    numeric_velocity = (ik(h_velocity) - ik(-h_velocity)) / (2 * h_velocity)
    numeric_acceleration = (ik(h_acceleration) - 2 * ik(0.0) + ik(-h_acceleration)) / h_acceleration**2
    if config.is_crank:
        reference = crank_rates(config, upper, rate, None, base, base_rate, None)
        velocity, acceleration = reference.rates, reference.accelerations
        ok = crank_inverse_kinematics(config, upper).reachable
    else:
        reference = leg_rates(config, upper, rate, None, base, base_rate, None)
        velocity, acceleration = reference.velocities, reference.accelerations
        ok = np.ones(len(upper), dtype=bool)
    velocity_error = float(np.max(np.abs(velocity[ok] - numeric_velocity[ok])))
    relative = np.abs(acceleration[ok] - numeric_acceleration[ok]) / np.maximum(1.0, np.abs(acceleration[ok]))
    acceleration_error = float(np.max(relative))
    problems = () if acceleration_error < 1e-3 else (f"acceleration differs by {acceleration_error:.3g} (relative)",)
    unit = "deg/s" if config.is_crank else "mm/s"
    return Check("reference rates", f"velocity vs central differences of the ST IK (accel rel. {acceleration_error:.1g})",
                 int(ok.sum()), velocity_error, 1e-5, unit, problems=problems)


def check_variant_fk(runtime: VariantRuntime, poses, bases=None, tolerance: float = 1e-9) -> Check:
    """SP_ForwardKinematics from the home pose on the measured values (crank angles, or cylinder
    positions with the base pose) of feasible poses: the reference FK's pose, iterations and
    ErrorID, and the true pose, within ``tolerance``."""
    config = runtime.config
    solver = SolverConfig(tolerance=tolerance, singularity_threshold=config.solver.singularity_threshold,
                          iterations_per_scan=config.solver.iterations_per_scan,
                          max_iterations=config.solver.max_iterations)
    bases = np.zeros_like(poses) if bases is None else np.asarray(bases, dtype=float)
    keep = feasibility(config, poses, bases).feasible
    reachable, bases = poses[keep], bases[keep]
    if config.is_crank:
        measured = crank_inverse_kinematics(config, reachable).angles_deg
    else:
        measured = legs(config, reachable, bases).extensions
    starts = np.zeros(6)
    run = runtime.forward_kinematics(measured, starts, solver, bases)
    problems, errors, counts = [], [], []
    for index in range(len(reachable)):
        ref = variant_forward_kinematics(config, measured[index], starts,
                                         bases[index] if config.moving_base else None, solver=solver)
        if int(run["Iterations"][index]) != ref.iterations:
            problems.append(f"case {index}: {run['Iterations'][index]} iterations, reference {ref.iterations}")
        if int(run["ErrorIDs"][index]) != ref.status.error_id:
            problems.append(f"case {index}: ErrorID {run['ErrorIDs'][index]:#06x}, reference {ref.status.name}")
        if ref.converged and run["Done"][index]:
            errors.append(float(np.max(np.abs(run["Poses"][index] - ref.pose))))
            errors.append(float(np.max(np.abs(run["Poses"][index] - reachable[index]))))
            counts.append(ref.iterations)
        elif ref.converged:
            problems.append(f"case {index}: reference converged, the FB did not")
    span = f"{min(counts)}..{max(counts)}" if counts else "-"
    source = "crank angles" if config.is_crank else "cylinder positions and base pose"
    return Check("SP_ForwardKinematics", f"pose from {source}, start home (Tolerance {tolerance:g})",
                 len(reachable), max(errors, default=math.inf), FK_LIMIT, "mm|deg", span, tuple(problems))


def run_variant_verification(config: PlatformConfig, poses: int = 10_000, seed: int = 2024,
                             fk_poses: int = 500) -> list[Check]:
    """Every comparison of ``stgen verify`` for a variant platform."""
    runtime = VariantRuntime(config)
    upper, base = variant_poses(config, poses, seed)
    checks = check_variant_ik(runtime, upper, base)
    rate_count = max(1, poses // 10)
    checks.append(check_variant_rates(runtime, upper[:rate_count], base[:rate_count], seed + 1))
    checks.append(check_variant_fk(runtime, upper[:fk_poses], base[:fk_poses]))
    return checks
