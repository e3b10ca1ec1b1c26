"""PNG figures of a scenario run, laid out like the NJ501 study's (docs/mathematics.md,
Sources; the scenarios are its trajectories of docs/mathematics.md section 4): the platform pose
over time (positions relative to the start pose, then angles) and the six cylinder positions over time,
with the error against the NumPy reference underneath. A run of several
moves has each excursion (out and back to the start pose) shaded and named
above the top panel ("x +100 mm", ...).

Uses matplotlib's Agg backend (files only, no display needed).
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402  (the backend is chosen first)
import numpy as np  # noqa: E402

from stgen.scenarios.definitions import PointToPointMotion, describe_move  # noqa: E402
from stgen.scenarios.runner import ScenarioResult  # noqa: E402

POSITION_LABELS = ("x", "y", "z")
ANGLE_LABELS = ("α (about Z)", "β (about Y)", "γ (about X)")
#: Errors below this (exact agreement included) are drawn at it on the log scale, mm.
ERROR_FLOOR_MM = 1e-16
#: Legends right of the panels, so they never hide a curve.
LEGEND_OUTSIDE = dict(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8, borderaxespad=0.0)
EXCURSION_SHADE = dict(color="0.5", alpha=0.08, linewidth=0)


def excursions(result: ScenarioResult) -> list[tuple[float, float, str]]:
    """(start time, end time, label) of every excursion of a run of several moves: the moves from
    the start pose up to the one that returns to it. Empty for a single move or a wave."""
    motion = result.scenario.motion
    if not isinstance(motion, PointToPointMotion) or len(motion.targets) < 2:
        return []
    home = tuple(result.scenario.start_pose)
    period = result.period_s
    edges = list(result.command_scans) + [result.scans + 1]
    spans, first = [], 0
    for index, target in enumerate(motion.targets):
        if tuple(target) == home or index == len(motion.targets) - 1:
            start = edges[first] - 1  # the edge scan starts at (edge - 1) * period
            label = describe_move(home, motion.targets[first])
            spans.append((start * period, (edges[index + 1] - 1) * period, label))
            first = index + 1
    return spans


def scenario_figure(result: ScenarioResult, path: str | Path, dpi: int = 110) -> Path:
    """Write ``path`` (PNG): pose positions, pose angles, cylinder positions, error; returns the path."""
    path = Path(path)
    # From the scan before the command: power-on and locating set no pose yet.
    shown = slice(max(result.command_scan - 2, 0), None)
    time = result.time_s[shown]
    pose = result.setpoint_pose[shown]
    start = result.scenario.start_pose[:3]
    commanded = result.commanded[shown]
    error = result.error[shown].max(axis=1)
    figure, axes = plt.subplots(4, 1, figsize=(10, 12), sharex=True, constrained_layout=True)
    figure.suptitle(
        f"{result.scenario.title}\n{result.duration_s:.3f} s simulated, {result.scans:,} scans of "
        f"{result.period_s * 1000:g} ms, SP_Controller in st_runtime with six simulated axes",
        fontsize=11,
    )

    for index, label in enumerate(POSITION_LABELS):
        # Relative to the start: a wave's 3 mm would be lost on an axis that also spans z = 150 mm.
        axes[0].plot(time, pose[:, index] - start[index], label=label)
    axes[0].set_ylabel("position − start (mm)")
    axes[0].set_title(f"Platform pose set-point: position relative to the start (x, y, z) = ({', '.join(f'{v:g}' for v in start)}) mm")
    axes[0].legend(**LEGEND_OUTSIDE)

    for index, label in enumerate(ANGLE_LABELS):
        axes[1].plot(time, pose[:, 3 + index], label=label)
    axes[1].set_ylabel("angle (deg)")
    axes[1].set_title("Platform pose set-point: orientation")
    axes[1].legend(**LEGEND_OUTSIDE)

    for leg in range(6):
        axes[2].plot(time, commanded[:, leg], label=f"q{leg + 1}")
    axes[2].set_ylabel("cylinder position (mm)")
    axes[2].set_title("Cylinder positions commanded through MC_SyncMoveAbsolute")
    axes[2].legend(**LEGEND_OUTSIDE)

    # The largest error of each window of scans (about 1000 windows): readable at any length.
    window = max(1, len(error) // 1000)
    usable = len(error) // window * window
    window_max = error[:usable].reshape(-1, window).max(axis=1)
    axes[3].semilogy(time[:usable:window], np.maximum(window_max, ERROR_FLOOR_MM), color="black", linewidth=0.8)
    axes[3].axhline(1e-6, color="red", linestyle="--", linewidth=0.8, label="limit 1e-6 mm")
    axes[3].set_ylabel("|ST - reference| (mm)")
    axes[3].set_title(f"Largest cylinder error per scan (max {result.max_error_mm:.2e} mm; below 1e-16 drawn at 1e-16)")
    axes[3].set_xlabel("time (s)")
    axes[3].legend(**LEGEND_OUTSIDE)

    for axis in axes:
        axis.grid(True, linewidth=0.3)
    spans = excursions(result)
    for number, (begin, end, _) in enumerate(spans):
        if number % 2 == 0:
            for axis in axes:
                axis.axvspan(begin, end, **EXCURSION_SHADE)
    if spans:
        names = axes[0].secondary_xaxis("top")
        names.set_xticks([(begin + end) / 2 for begin, end, _ in spans], [label for _, _, label in spans])
        names.tick_params(length=0, labelsize=9)
    path.parent.mkdir(parents=True, exist_ok=True)
    figure.savefig(path, dpi=dpi)
    plt.close(figure)
    return path
