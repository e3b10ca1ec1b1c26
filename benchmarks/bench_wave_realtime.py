"""Benchmark: real-time factor of the 60 s random-wave scenario, side by side
with the bare NumPy reference for the same trajectory, in one run.

    python benchmarks/bench_wave_realtime.py [--seconds 60] [--rounds 3] [--profile] [--opcodes]

1. Controller: SP_Controller (rendered ST, compiled by st_runtime) with six
   simulated axes at 1 ms: power on, locate, the random wave's lead-in, then
   ``--seconds`` of wave. Timed: the scans only (loading, i.e. parse + check +
   compile, is reported apart). Real-time factor = simulated s / wall s.
   Best of ``--rounds``.
2. NumPy reference, the same scans: (a) per scan, as a controller would
   compute it: ``wave_pose`` of one time and ``inverse_kinematics`` of one
   pose each scan; (b) vectorised, the whole trajectory at once.
3. ``--profile``: cProfile of one controller run, the top entries by own
   time, to show where a scan's time goes.
4. ``--opcodes``: bytecode instructions, Python calls and C calls per scan
   in the wave (bench_optimiser's counters), per function: figures the
   machine's load does not change, to read beside the times.

The real-time factor is given by wall time and by this process's CPU time
(on a shared machine the wall clock also counts other processes' turns).

Targets: >= 20x real time (issue 5), >= 80x (issue 17).
"""

from __future__ import annotations

import argparse
import cProfile
import io
import pstats
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "benchmarks"))


from stgen.config import PlatformConfig  # noqa: E402
from stgen.reference.kinematics import inverse_kinematics  # noqa: E402
from stgen.reference.wave import wave_pose  # noqa: E402
from stgen.scenarios.definitions import RANDOM_WAVE  # noqa: E402
from stgen.scenarios.expected import expected_cylinders, expected_poses, motion_scans, wave_fade_duration  # noqa: E402
from stgen.scenarios.runner import command_scenario  # noqa: E402
from stgen.scenarios.simulation import ControllerSimulation  # noqa: E402

TARGET_FACTOR = 20.0
ISSUE_17_FACTOR = 80.0


def controller_run(scenario, config) -> tuple[float, int, float, ControllerSimulation, float]:
    """(wall s of the scans, scans, load s, simulation, CPU s of the scans) of one whole scenario."""
    started = time.perf_counter()
    sim = ControllerSimulation(config, scenario.start_pose)
    loaded = time.perf_counter() - started
    started, cpu = time.perf_counter(), time.process_time()
    sim.power_on()
    command_scenario(sim, scenario)
    sim.run(motion_scans(scenario, config))
    wall, cpu = time.perf_counter() - started, time.process_time() - cpu
    if sim.globals["SpFaultID"] or sim.runtime_faults or any(axis.fault_active for axis in sim.axes):
        raise SystemExit(f"the controller faulted: SpFaultID {sim.globals['SpFaultID']:#06x}, {sim.runtime_faults[:3]}")
    return wall, sim.scan_count, loaded, sim, cpu


def reference_per_scan(scenario, config, scans: int) -> float:
    """Wall s of the reference computed one scan at a time (wave pose + IK of one pose)."""
    motion = scenario.motion
    geometry, stroke, period = config.geometry, config.stroke, config.task.period_s
    fade = wave_fade_duration(scenario, config)  # the wave fades in, as SP_Controller runs it
    started = time.perf_counter()
    for scan in range(scans):
        pose = wave_pose(motion.wave, scan * period, motion.centre_pose, fade_s=fade)
        inverse_kinematics(geometry, pose, stroke)
    return time.perf_counter() - started


def reference_vectorised(scenario, config, scans: int) -> float:
    started = time.perf_counter()
    expected_cylinders(expected_poses(scenario, config, 5, scans), config)
    return time.perf_counter() - started


def profile(scenario, config, top: int = 25) -> str:
    sim = ControllerSimulation(config, scenario.start_pose)
    sim.power_on()
    command_scenario(sim, scenario)
    scans = motion_scans(scenario, config)
    profiler = cProfile.Profile()
    profiler.enable()
    sim.run(scans)
    profiler.disable()
    stream = io.StringIO()
    pstats.Stats(profiler, stream=stream).sort_stats("tottime").print_stats(top)
    return stream.getvalue()


class _OpcodeTally:
    """A trace function counting the bytecode instructions run, per code object."""

    def __init__(self):
        from collections import Counter

        self.counts = Counter()

    def __call__(self, frame, event, arg):
        frame.f_trace_opcodes = True
        if event == "opcode":
            self.counts[frame.f_code] += 1
        return self


def opcodes(config, scans: int = 200, top: int = 12) -> str:
    """Instructions and calls per scan in the wave, in total and by function."""
    from bench_optimiser import count_calls

    scenario = RANDOM_WAVE.with_wave_seconds(5.0)
    sim = ControllerSimulation(config, scenario.start_pose)
    sim.power_on()
    command_scenario(sim, scenario)
    sim.run(2500)                         # into the wave
    python_calls, c_calls = (n / scans for n in count_calls(lambda: sim.run(scans)))
    tally = _OpcodeTally()
    sys.settrace(tally)
    try:
        sim.run(scans)
    finally:
        sys.settrace(None)
    total = sum(tally.counts.values()) / scans
    lines = [f"Per scan in the wave: {total:,.0f} bytecode instructions, {python_calls:,.0f} Python calls, "
             f"{c_calls:,.0f} C calls; instructions by function:"]
    lines += [f"  {count / scans:8,.0f}  {code.co_name} ({Path(code.co_filename).name})"
              for code, count in tally.counts.most_common(top)]
    return "\n".join(lines)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=60.0, help="seconds of wave (default 60)")
    parser.add_argument("--rounds", type=int, default=3, help="controller runs, best is reported (default 3)")
    parser.add_argument("--profile", action="store_true", help="print a cProfile of one controller run")
    parser.add_argument("--opcodes", action="store_true",
                        help="count bytecode instructions and calls per scan (independent of the load)")
    args = parser.parse_args(argv)

    config = PlatformConfig.default()
    scenario = RANDOM_WAVE.with_wave_seconds(args.seconds)
    runs = [controller_run(scenario, config) for _ in range(max(1, args.rounds))]
    wall, scans, loaded, _, _ = min(runs, key=lambda run: run[0])
    cpu = min(run[4] for run in runs)
    simulated = scans * config.task.period_s
    factor = simulated / wall
    per_scan_ref = reference_per_scan(scenario, config, scans)
    vectorised_ref = reference_vectorised(scenario, config, scans)

    print(f"Random wave, {args.seconds:g} s of wave + power-on and lead-in: {scans:,} scans of "
          f"{config.task.period_s * 1000:g} ms = {simulated:.3f} s simulated")
    print(f"  load (parse + check + compile the controller): {loaded:.2f} s")
    rows = [
        ("controller in st_runtime (6 axes)", wall),
        ("NumPy reference, one scan at a time", per_scan_ref),
        ("NumPy reference, vectorised", vectorised_ref),
    ]
    print(f"  {'':40s} {'wall s':>9s} {'us/scan':>9s} {'x real time':>12s}")
    for name, seconds in rows:
        print(f"  {name:40s} {seconds:9.3f} {seconds / scans * 1e6:9.1f} {simulated / seconds:12.1f}")
    print(f"  controller / per-scan NumPy: {wall / per_scan_ref:.2f}x the time")
    verdict = "meets" if factor >= TARGET_FACTOR else "MISSES"
    print(f"  real-time factor {factor:.1f}x: {verdict} the target of {TARGET_FACTOR:g}x")
    print(f"  by CPU time: {cpu / scans * 1e6:.1f} us/scan, {simulated / cpu:.1f}x real time "
          f"(issue 17's target: {ISSUE_17_FACTOR:g}x)")
    if args.profile:
        print(profile(scenario, config))
    if args.opcodes:
        print(opcodes(config))
    return 0


if __name__ == "__main__":
    sys.exit(main())
