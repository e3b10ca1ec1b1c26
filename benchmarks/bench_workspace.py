"""Benchmark: workspace feasibility, vectorised NumPy against the per-pose Python loop (issue 11).

    python benchmarks/bench_workspace.py [--config FILE] [--resolution N] [--loop-points M]

Times one `slice_map` of N x N points (the whole grid in one vectorised
call) and `check_pose` called pose by pose on the first M points of the same
grid, in the same run, best of 3 rounds each (time.perf_counter), and prints
points per second of both and their ratio. Target (issue 11): a 200 x 200
slice in under 2 s on this machine.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402

from stgen.config import load_config  # noqa: E402
from stgen.reference.feasibility import check_pose  # noqa: E402
from stgen.workspace import slice_map  # noqa: E402


def best_of(rounds: int, job) -> float:
    times = []
    for _ in range(rounds):
        started = time.perf_counter()
        job()
        times.append(time.perf_counter() - started)
    return min(times)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--config", default=str(ROOT / "examples" / "moving_base_platform.toml"))
    parser.add_argument("--resolution", type=int, default=200)
    parser.add_argument("--loop-points", type=int, default=2000)
    args = parser.parse_args()
    config = load_config(args.config)
    centre = [0.0, 0.0, 75.0, 0.0, 0.0, 0.0] if config.moving_base else [0.0] * 6
    bounds = ((-200.0, 200.0), (-200.0, 200.0))
    n = args.resolution
    vectorised = best_of(3, lambda: slice_map(config, ("x", "y"), bounds, n, centre))
    xs = np.linspace(*bounds[0], n)
    ys = np.linspace(*bounds[1], n)
    poses = [np.array([x, y, *centre[2:]]) for y in ys for x in xs][: args.loop_points]
    looped = best_of(3, lambda: [check_pose(config, pose) for pose in poses])
    grid_rate = n * n / vectorised
    loop_rate = len(poses) / looped
    print(f"config {args.config}")
    print(f"vectorised slice {n}x{n}: {vectorised:.3f} s, {grid_rate:,.0f} points/s")
    print(f"per-pose loop, {len(poses)} points: {looped:.3f} s, {loop_rate:,.0f} points/s")
    print(f"ratio vectorised / loop: {grid_rate / loop_rate:.0f}x")
    return 0


if __name__ == "__main__":
    sys.exit(main())
