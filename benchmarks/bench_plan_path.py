"""Benchmark: how long `stgen plan` takes for a 60 s path, side by side with its parts, in one run.

    python benchmarks/bench_plan_path.py [--seconds 60] [--rounds 3]

1. The whole plan (stgen.reference.paths.plan_path): the shortest-duration scan at T = 1
   (PLAN_SAMPLES points of u) plus the legs at every 1 ms sample of the ``--seconds`` path.
2. The shortest-duration scan alone, and the 1 ms samples alone.
Printed: best of ``--rounds`` wall times and each part's share of the whole, and the
planning speed as path seconds per wall second (a 60 s path at 1 ms is 60001 samples).
"""

from __future__ import annotations

import argparse
import dataclasses
import time

import numpy as np

from stgen.config import PlatformConfig
from stgen.reference.motion_limits import check_motion
from stgen.reference.paths import PLAN_SAMPLES, STUDY_PATHS, STUDY_TILT, plan_path, sample


def best(rounds: int, job) -> float:
    times = []
    for _ in range(rounds):
        start = time.perf_counter()
        job()
        times.append(time.perf_counter() - start)
    return min(times)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=60.0)
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args()
    config = PlatformConfig()
    spec = dataclasses.replace(STUDY_PATHS[0], orientation=STUDY_TILT, duration=args.seconds)
    whole = best(args.rounds, lambda: plan_path(spec, config))
    unit_scan = best(args.rounds, lambda: check_motion(config, *_unit(spec)))
    t = np.arange(int(round(args.seconds / config.task.period_s)) + 1) * config.task.period_s
    samples = best(args.rounds, lambda: check_motion(config, t, *_rest(sample(spec, args.seconds, t))))
    print(f"{spec.family} at roll = pitch = 35 deg, {args.seconds:g} s path, {len(t)} samples at 1 ms, "
          f"{PLAN_SAMPLES} planning points")
    print(f"whole plan            {whole:8.3f} s   ({args.seconds / whole:7.1f} path s per wall s)")
    print(f"  duration scan       {unit_scan:8.3f} s   ({unit_scan / whole:5.2f} of the whole)")
    print(f"  1 ms samples + legs {samples:8.3f} s   ({samples / whole:5.2f} of the whole)")


def _unit(spec):
    path = sample(spec, 1.0, np.linspace(0.0, 1.0, PLAN_SAMPLES))
    return (path.t, *_rest(path))


def _rest(path):
    return path.poses, path.rates, path.accelerations


if __name__ == "__main__":
    main()
