"""Benchmark: the compiler's optimisation passes (issue 17), with and without, side by side in one run.

    python benchmarks/bench_optimiser.py [--poses N] [--rounds R] [--seconds S] [--fk-check N]

Each figure is measured twice in the same process, once compiled with every
pass off (`Optimisations.none()`, ST_RUNTIME_OPTIMISE=none) and once with
every pass on, and printed with their ratio (the machine is shared, so only
ratios measured side by side mean much):

1. One Newton-Raphson iteration of SP_ForwardKinematics per determinant
   variant (bench_fk.py's method: N seeded reachable poses solved in one
   scan, time / iterations, best of R, process CPU time), against the
   NJ501's 49.5 us per iteration (docs/mathematics.md section 3; a reference
   line, not a test).
2. The whole controller on the random wave (bench_wave_realtime.py's
   run): real-time factor, best of R.
3. Load time (parse + check + compile) of generated/iec, best of R (at
   least 7), by wall and by CPU time.
4. With --opcodes: the bytecode instructions one FK iteration and one
   controller scan execute (sys.settrace), a count the load does not change,
   and the Python and C function calls of a scan (sys.setprofile).
5. A differential check: `--fk-check` seeded FK solves (default 10,000)
   with both builds; poses, iteration counts and flags must be equal bit for
   bit (the suite runs 1,000: tests/test_optimiser_equivalence.py).

Targets (issue 17): table variant <= 30 us/iteration, controller >= 80x
real time, load time <= 1.5x.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "benchmarks"))

import numpy as np  # noqa: E402

import bench_fk  # noqa: E402
from st_runtime import api  # noqa: E402
from stgen.config import PlatformConfig  # noqa: E402
from stgen.reference import inverse_kinematics  # noqa: E402
from stgen.render import RenderOptions  # noqa: E402
from stgen.scenarios.definitions import RANDOM_WAVE  # noqa: E402
from stgen.scenarios.expected import motion_scans  # noqa: E402
from stgen.scenarios.runner import command_scenario  # noqa: E402
from stgen.scenarios.simulation import ControllerSimulation  # noqa: E402
from stgen.verify import fk_solver, load_kinematics, random_poses  # noqa: E402

NJ501_US = 49.5
BUILDS = ("none", "all")


@contextlib.contextmanager
def build(name: str):
    """Compile with the passes of `name` ("none" or "all") inside the block."""
    saved = os.environ.get("ST_RUNTIME_OPTIMISE")
    os.environ["ST_RUNTIME_OPTIMISE"] = name
    try:
        yield
    finally:
        if saved is None:
            os.environ.pop("ST_RUNTIME_OPTIMISE", None)
        else:
            os.environ["ST_RUNTIME_OPTIMISE"] = saved


def fk_iteration(variant, positions, start, solver, rounds) -> dict:
    times = {}
    for name in BUILDS:
        with build(name):
            times[name] = bench_fk.time_st(variant, positions, start, solver, rounds)[0] * 1e6
    return times


def controller_factor(seconds: float, rounds: int) -> tuple[dict, dict]:
    """Best real-time factor per build: by wall time, and by this process's CPU time (on a
    shared machine the wall clock also counts the time other processes had the core).
    Timed as bench_wave_realtime.controller_run times it: power-on, commands and scans."""
    config = PlatformConfig.default()
    scenario = RANDOM_WAVE.with_wave_seconds(seconds)
    factors = {name: 0.0 for name in BUILDS}
    cpu_factors = {name: 0.0 for name in BUILDS}
    for _ in range(rounds):         # interleaved, so both builds see the same load
        for name in BUILDS:
            with build(name):
                sim = ControllerSimulation(config, scenario.start_pose)
            wall, cpu = time.perf_counter(), time.process_time()
            sim.power_on()
            command_scenario(sim, scenario)
            sim.run(motion_scans(scenario, config))
            wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
            if sim.globals["SpFaultID"] or sim.runtime_faults:
                raise SystemExit(f"the controller faulted ({name}): {sim.runtime_faults[:3]}")
            simulated = sim.scan_count * config.task.period_s
            factors[name] = max(factors[name], simulated / wall)
            cpu_factors[name] = max(cpu_factors[name], simulated / cpu)
    return factors, cpu_factors


def count_opcodes(run) -> int:
    """Bytecode instructions executed by `run()` (sys.settrace with opcode events): a count that
    does not depend on the machine's load, to read beside the times."""
    count = 0

    def local(frame, event, arg):
        nonlocal count
        if event == "opcode":
            count += 1
        return local

    def tracer(frame, event, arg):
        frame.f_trace_opcodes = True
        return local

    sys.settrace(tracer)
    try:
        run()
    finally:
        sys.settrace(None)
    return count


def count_calls(run) -> tuple[int, int]:
    """(Python function calls, calls of C functions) made by `run()` (sys.setprofile): the
    second shows work the bytecode count misses (a builtin such as any() or abs())."""
    calls = {"call": 0, "c_call": 0}

    def profiler(frame, event, arg):
        if event in calls:
            calls[event] += 1

    sys.setprofile(profiler)
    try:
        run()
    finally:
        sys.setprofile(None)
    return calls["call"], calls["c_call"]


def opcodes_per_iteration(variant, positions, start, solver) -> dict:
    counts = {}
    for name in BUILDS:
        with build(name):
            runtime = load_kinematics(bench_fk.CONFIG, RenderOptions(variant), capacity=len(positions))
        runtime.forward_kinematics(positions, start, solver)            # warm
        result = {}
        ops = count_opcodes(lambda: result.setdefault("fk", runtime.forward_kinematics(positions, start, solver)))
        counts[name] = ops / int(result["fk"].iterations.sum())
    return counts


def opcodes_per_scan(scans: int = 200) -> dict:
    config = PlatformConfig.default()
    scenario = RANDOM_WAVE.with_wave_seconds(5.0)
    counts = {}
    for name in BUILDS:
        with build(name):
            sim = ControllerSimulation(config, scenario.start_pose)
        sim.power_on()
        command_scenario(sim, scenario)
        sim.run(2500)                     # into the wave
        counts[name] = count_opcodes(lambda: sim.run(scans)) / scans
        counts[name + " calls"] = [n / scans for n in count_calls(lambda: sim.run(scans))]
    return counts


def load_average() -> str:
    """The 1-minute load average (7 agents share 2 cores: absolute times are inflated)."""
    try:
        return f"load average {os.getloadavg()[0]:.2f}"
    except OSError:
        return "load average unknown"


def load_time(rounds: int) -> tuple[dict, dict]:
    """Best wall and best CPU seconds of loading generated/iec per build (interleaved)."""
    best = {name: float("inf") for name in BUILDS}
    best_cpu = {name: float("inf") for name in BUILDS}
    for _ in range(rounds):
        for name in BUILDS:
            with build(name):
                started, cpu = time.perf_counter(), time.process_time()
                api.load([ROOT / "generated" / "iec"])
                best[name] = min(best[name], time.perf_counter() - started)
                best_cpu[name] = min(best_cpu[name], time.process_time() - cpu)
    return best, best_cpu


def fk_differential(count: int) -> int:
    """Solve `count` seeded poses with both builds; the number of differing solves."""
    config = PlatformConfig.default()
    solver = fk_solver(config)
    poses = random_poses(config, count, seed=2024)
    positions = inverse_kinematics(config.geometry, poses, config.stroke).positions
    start = np.asarray(config.solver.start_pose)
    results = {}
    for name in BUILDS:
        with build(name):
            runtime = load_kinematics(config, RenderOptions("table"), capacity=min(count, 1000))
            runs = [runtime.forward_kinematics(positions[i:i + 1000], start, solver) for i in range(0, count, 1000)]
        results[name] = runs
    differing = 0
    for a, b in zip(results["none"], results["all"]):
        same = (np.array_equal(a.poses.view(np.uint64), b.poses.view(np.uint64))
                and np.array_equal(a.iterations, b.iterations) and np.array_equal(a.done, b.done)
                and np.array_equal(a.error_ids, b.error_ids))
        differing += 0 if same else len(a.iterations)
    return differing


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--poses", type=int, default=200)
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--seconds", type=float, default=20.0, help="seconds of random wave (default 20)")
    parser.add_argument("--fk-check", type=int, default=10_000)
    parser.add_argument("--opcodes", action="store_true",
                        help="also count the bytecode instructions per FK iteration and per controller scan")
    args = parser.parse_args()

    config = PlatformConfig.default()
    bench_fk.CONFIG = config
    solver = fk_solver(config)
    poses = random_poses(config, args.poses, seed=7)
    positions = inverse_kinematics(config.geometry, poses, config.stroke).positions
    start = np.asarray(config.solver.start_pose)

    print(f"FK Newton-Raphson iteration, {args.poses} solves, best of {args.rounds} (us/iteration, CPU time)")
    print(f"  {'variant':<26}{'passes off':>12}{'passes on':>12}{'ratio':>8}{'on / NJ501':>12}")
    for variant in ("table", "unrolled", "lu"):
        t = fk_iteration(variant, positions, start, solver, args.rounds)
        print(f"  {variant:<26}{t['none']:>12.1f}{t['all']:>12.1f}{t['none'] / t['all']:>7.2f}x"
              f"{t['all'] / NJ501_US:>12.2f}   ({load_average()})")
    print(f"  {'NJ501 (docs/mathematics.md section 3, reference)':<26}{NJ501_US:>8.1f}")

    f, cpu = controller_factor(args.seconds, args.rounds)
    print(f"\nWhole controller, random wave ({args.seconds:g} s of wave), x real time, best of {args.rounds}")
    print(f"  by wall time: passes off {f['none']:.1f}x, passes on {f['all']:.1f}x, ratio {f['all'] / f['none']:.2f}x")
    print(f"  by CPU time:  passes off {cpu['none']:.1f}x, passes on {cpu['all']:.1f}x, "
          f"ratio {cpu['all'] / cpu['none']:.2f}x   ({load_average()})")

    load, load_cpu = load_time(max(args.rounds, 7))
    print(f"\nLoad (parse + check + compile) of generated/iec, best of {max(args.rounds, 7)}")
    print(f"  wall: passes off {load['none']:.3f} s, passes on {load['all']:.3f} s, "
          f"ratio {load['all'] / load['none']:.2f}x")
    print(f"  CPU:  passes off {load_cpu['none']:.3f} s, passes on {load_cpu['all']:.3f} s, "
          f"ratio {load_cpu['all'] / load_cpu['none']:.2f}x   ({load_average()})")

    if args.opcodes:
        print("\nBytecode instructions executed (independent of the load), passes off / on")
        for variant in ("table", "lu"):
            c = opcodes_per_iteration(variant, positions[:20], start, solver)
            print(f"  FK iteration, {variant:<9} {c['none']:>9,.0f} / {c['all']:>9,.0f}   ratio {c['none'] / c['all']:.2f}x")
        c = opcodes_per_scan()
        print(f"  controller scan          {c['none']:>9,.0f} / {c['all']:>9,.0f}   ratio {c['none'] / c['all']:.2f}x")
        print("  calls per controller scan, passes off / on: Python {:,.0f} / {:,.0f}, C {:,.0f} / {:,.0f}".format(
            c["none calls"][0], c["all calls"][0], c["none calls"][1], c["all calls"][1]))

    if args.fk_check:
        differing = fk_differential(args.fk_check)
        print(f"\nDifferential: {args.fk_check:,} seeded FK solves (table variant), passes on vs off: "
              f"{'bit-identical' if not differing else f'{differing} solves DIFFER'}")
        return 1 if differing else 0
    return 0


if __name__ == "__main__":
    sys.exit(main())
