"""Benchmark: one Newton-Raphson iteration of the FK, rendered ST in st_runtime vs the NumPy reference.

    python benchmarks/bench_fk.py [--poses N] [--rounds R]

For each variant of the rendered SP_ForwardKinematics -- the Leibniz
determinant as a permutation-table loop (the default), fully unrolled, and
det J taken from the LU diagonal -- the kinematics are loaded in st_runtime
with the stgen.verify harness, which solves N seeded random reachable poses
from p_NR (Tolerance 1e-9, one FB call per simulated scan) in one controller
scan. Time per iteration = time of that scan / total Newton iterations, so it
includes everything an iteration does (residual, Jacobian, determinant, LU
solve, update, checks) and the small per-solve overhead spread over the
iterations. The reference is timed the same way: NewtonRaphsonSolver over the
same cases, time / iterations. Best of R rounds, CPU time of this process
(time.process_time), all in the same run; the rounds are interleaved (each
round times every variant and the reference in turn), so a slow stretch of a
shared machine reaches every figure alike instead of all the rounds of one.
(Timed one variant after the other, five rounds fill 0.15 s: on a machine with
load 13 the table variant read 45.7 us timed first after the reference and
30.7 us timed again later in the same process.)

The study's NJ501 takes about 49.5 us per iteration (docs/mathematics.md section 3).
Target (issue 4): the table variant at most 0.5 ms per iteration here.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402

from stgen.config import PlatformConfig  # noqa: E402
from stgen.reference import NewtonRaphsonSolver, inverse_kinematics  # noqa: E402
from stgen.render import RenderOptions  # noqa: E402
from stgen.verify import fk_solver, load_kinematics, random_poses  # noqa: E402

NJ501_US_PER_ITERATION = 49.5
TARGET_MS = 0.5


def time_st(variant: str, positions, start, solver, rounds: int) -> tuple[float, int]:
    """(best CPU seconds per iteration, iterations) of `rounds` runs of one variant in a row."""
    runtime = load_kinematics(CONFIG, RenderOptions(variant), capacity=len(positions))
    best = float("inf")
    for _ in range(rounds):
        seconds, iterations = _solve_st(runtime, positions, start, solver)
        best = min(best, seconds)
    return best / iterations, iterations


def _solve_st(runtime, positions, start, solver) -> tuple[float, int]:
    """(CPU seconds, Newton iterations) of one run of every case in `runtime`."""
    started = time.process_time()
    fk = runtime.forward_kinematics(positions, start, solver)
    seconds = time.process_time() - started
    assert fk.done.all(), "not every solve converged"
    return seconds, int(fk.iterations.sum())


def _solve_reference(positions, start, solver) -> tuple[float, int]:
    """(CPU seconds, Newton iterations) of the NumPy reference solving every case."""
    started = time.process_time()
    iterations = 0
    for target in positions:
        machine = NewtonRaphsonSolver(CONFIG.geometry, solver)
        machine.start(target, start)
        while not machine.done:
            machine.step()
        iterations += machine.iterations
    return time.process_time() - started, iterations


CONFIG = PlatformConfig.default()


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--poses", type=int, default=200, help="FK solves per round (default 200)")
    parser.add_argument("--rounds", type=int, default=3, help="rounds, best taken (default 3)")
    args = parser.parse_args()

    solver = fk_solver(CONFIG)  # Tolerance 1e-9, the configured Ktol and limits
    poses = random_poses(CONFIG, args.poses, seed=7)
    positions = inverse_kinematics(CONFIG.geometry, poses, CONFIG.stroke).positions
    start = np.asarray(CONFIG.solver.start_pose)

    variants = (("table", "ST, Leibniz table"), ("unrolled", "ST, Leibniz unrolled"),
                ("lu", "ST, det from LU diagonal"))
    best = {name: float("inf") for name, _ in variants + (("reference", ""),)}
    iterations = {}
    runtimes = {name: load_kinematics(CONFIG, RenderOptions(name), capacity=len(positions)) for name, _ in variants}
    for _ in range(args.rounds):            # interleaved: every figure sees the same stretch of time
        for name, _ in variants:
            seconds, iterations[name] = _solve_st(runtimes[name], positions, start, solver)
            best[name] = min(best[name], seconds)
        seconds, iterations["reference"] = _solve_reference(positions, start, solver)
        best["reference"] = min(best["reference"], seconds)
    ref_iterations = iterations["reference"]
    ref_seconds = best["reference"] / ref_iterations
    rows = []
    for name, label in variants:
        assert iterations[name] == ref_iterations, f"{name}: {iterations[name]} iterations, reference {ref_iterations}"
        rows.append((label, best[name] / ref_iterations))
    rows.append(("NumPy reference", ref_seconds))

    print(f"FK Newton-Raphson, {args.poses} solves from p_NR, {ref_iterations} iterations "
          f"(Tolerance 1e-9), best of {args.rounds}")
    print(f"{'variant':<28}{'us/iteration':>14}{'x reference':>13}{'x NJ501':>9}")
    for label, seconds in rows:
        us = seconds * 1e6
        print(f"{label:<28}{us:>14.1f}{seconds / ref_seconds:>13.2f}{us / NJ501_US_PER_ITERATION:>9.2f}")
    table_ms = rows[0][1] * 1e3
    verdict = "meets" if table_ms <= TARGET_MS else "MISSES"
    print(f"\ntable variant: {table_ms:.3f} ms/iteration, {verdict} the target of {TARGET_MS} ms")
    return 0


if __name__ == "__main__":
    sys.exit(main())
