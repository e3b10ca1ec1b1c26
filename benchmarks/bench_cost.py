"""Benchmark: what charging the NJ501 execution-time estimate costs the simulator.

    python benchmarks/bench_cost.py [--poses N] [--seconds S] [--rounds R]

Every basic block of the ST subtracts its estimated NJ501 time from the
scan's budget (st_runtime/compiler/cost.py); loops also test it.  This
compares the same programs compiled with and without those charges
(`compile_program(charge_costs=False)`), side by side in one run:

1. FK: the stgen.verify harness solves N seeded reachable poses from p_NR
   with the Leibniz-table SP_ForwardKinematics (Tolerance 1e-9, one FB call
   per simulated scan) in one controller scan; time per Newton iteration.
2. Controller: the random-wave scenario (SP_Controller, six simulated axes,
   1 ms scans) for S simulated seconds; wall time per scan.

Best of R rounds (alternating), CPU time of this process.  Target (issue 8):
the charges cost at most 10 % of scan time, i.e. ratio <= 1.10.
"""

from __future__ import annotations

import argparse
import sys
import time
from contextlib import contextmanager
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

import st_runtime.compiler as compiler  # noqa: E402
from stgen.config import PlatformConfig  # noqa: E402
from stgen.render import RenderOptions  # noqa: E402
from stgen.scenarios.definitions import scenario_by_name  # noqa: E402
from stgen.scenarios.runner import run_scenario  # noqa: E402
from stgen.verify import fk_solver, load_kinematics, random_poses  # noqa: E402

TARGET_RATIO = 1.10


@contextmanager
def charges(enabled: bool):
    """Compile every program loaded inside with or without the cost charges."""
    original = compiler.compile_program

    def compile_program(program, guard_statements=True, charge_costs=True):
        return original(program, guard_statements=guard_statements, charge_costs=enabled)

    compiler.compile_program = compile_program
    try:
        yield
    finally:
        compiler.compile_program = original


def fk_seconds_per_iteration(runtime, poses, config) -> float:
    from stgen.reference import inverse_kinematics

    positions = inverse_kinematics(config.geometry, poses, config.stroke).positions
    solver = fk_solver(config, 1e-9)
    started = time.process_time()
    run = runtime.forward_kinematics(positions, config.solver.start_pose, solver)
    return (time.process_time() - started) / int(run.iterations.sum())


def controller_seconds_per_scan(config, seconds: float) -> float:
    scenario = scenario_by_name("random_wave").with_wave_seconds(seconds)
    started = time.process_time()
    result = run_scenario(scenario, config)
    assert result.passed, "the scenario must pass in both builds"
    return (time.process_time() - started) / result.scans


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--poses", type=int, default=100)
    parser.add_argument("--seconds", type=float, default=5.0)
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args(argv)
    config = PlatformConfig.default()
    poses = random_poses(config, args.poses, 11)

    runtimes = {}
    for enabled in (True, False):
        with charges(enabled):
            runtimes[enabled] = load_kinematics(config, RenderOptions("table"), capacity=args.poses)
    fk = {True: [], False: []}
    scans = {True: [], False: []}
    for _ in range(args.rounds):
        for enabled in (True, False):
            fk[enabled].append(fk_seconds_per_iteration(runtimes[enabled], poses, config))
            with charges(enabled):
                scans[enabled].append(controller_seconds_per_scan(config, args.seconds))

    rows = [("FK iteration (Leibniz table)", min(fk[True]), min(fk[False])),
            ("SP_Controller scan (random wave)", min(scans[True]), min(scans[False]))]
    print(f"{'what':34} {'charged':>12} {'uncharged':>12} {'ratio':>7}")
    worst = 0.0
    for name, charged, bare in rows:
        ratio = charged / bare
        worst = max(worst, ratio)
        print(f"{name:34} {charged * 1e6:9.1f} us {bare * 1e6:9.1f} us {ratio:7.3f}")
    print(f"target: ratio <= {TARGET_RATIO:.2f} (charges at most 10 % of scan time): "
          f"{'met' if worst <= TARGET_RATIO else 'NOT met'}")
    return 0 if worst <= TARGET_RATIO else 1


if __name__ == "__main__":
    sys.exit(main())
