"""PNG figures of a scenario run, laid out like the study's: the platform pose
over time (positions, then angles) and the six cylinder positions over time,
with the error against the NumPy reference underneath.

Uses matplotlib's Agg backend (files only, no display needed).
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402  (the backend is chosen first)
import numpy as np  # noqa: E402

from stgen.scenarios.runner import ScenarioResult  # noqa: E402

POSITION_LABELS = ("x", "y", "z")
ANGLE_LABELS = ("α (about Z)", "β (about Y)", "γ (about X)")
#: Errors below this (exact agreement included) are drawn at it on the log scale, mm.
ERROR_FLOOR_MM = 1e-16


def scenario_figure(result: ScenarioResult, path: str | Path, dpi: int = 110) -> Path:
    """Write ``path`` (PNG): pose positions, pose angles, cylinder positions, error; returns the path."""
    path = Path(path)
    # From the scan before the command: power-on and locating set no pose yet.
    shown = slice(max(result.command_scan - 2, 0), None)
    time = result.time_s[shown]
    pose = result.setpoint_pose[shown]
    commanded = result.commanded[shown]
    error = result.error[shown].max(axis=1)
    figure, axes = plt.subplots(4, 1, figsize=(10, 12), sharex=True, constrained_layout=True)
    figure.suptitle(
        f"{result.scenario.title}\n{result.duration_s:.3f} s simulated, {result.scans:,} scans of "
        f"{result.period_s * 1000:g} ms, SP_Controller in st_runtime with six simulated axes",
        fontsize=11,
    )

    for index, label in enumerate(POSITION_LABELS):
        axes[0].plot(time, pose[:, index], label=label)
    axes[0].set_ylabel("position (mm)")
    axes[0].set_title("Platform pose set-point: position")
    axes[0].legend(loc="upper right", fontsize=8)

    for index, label in enumerate(ANGLE_LABELS):
        axes[1].plot(time, pose[:, 3 + index], label=label)
    axes[1].set_ylabel("angle (deg)")
    axes[1].set_title("Platform pose set-point: orientation")
    axes[1].legend(loc="upper right", fontsize=8)

    for leg in range(6):
        axes[2].plot(time, commanded[:, leg], label=f"q{leg + 1}")
    axes[2].set_ylabel("cylinder position (mm)")
    axes[2].set_title("Cylinder positions commanded through MC_SyncMoveAbsolute")
    axes[2].legend(loc="upper right", fontsize=8, ncol=3)

    # The largest error of each window of scans (about 1000 windows): readable at any length.
    window = max(1, len(error) // 1000)
    usable = len(error) // window * window
    window_max = error[:usable].reshape(-1, window).max(axis=1)
    axes[3].semilogy(time[:usable:window], np.maximum(window_max, ERROR_FLOOR_MM), color="black", linewidth=0.8)
    axes[3].axhline(1e-6, color="red", linestyle="--", linewidth=0.8, label="limit 1e-6 mm")
    axes[3].set_ylabel("|ST - reference| (mm)")
    axes[3].set_title(f"Largest cylinder error per scan (max {result.max_error_mm:.2e} mm; below 1e-16 drawn at 1e-16)")
    axes[3].set_xlabel("time (s)")
    axes[3].legend(loc="upper right", fontsize=8)

    for axis in axes:
        axis.grid(True, linewidth=0.3)
    path.parent.mkdir(parents=True, exist_ok=True)
    figure.savefig(path, dpi=dpi)
    plt.close(figure)
    return path
