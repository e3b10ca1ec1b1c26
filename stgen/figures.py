"""PNG figures of a scenario run, laid out like the NJ501 study's (docs/mathematics.md,
Sources; the scenarios are its trajectories of docs/mathematics.md section 4): the platform pose
over time (positions relative to the start pose, then angles) and the six cylinder positions over time,
with the error against the NumPy reference underneath; then the cylinder set-points' velocity and
acceleration against the actuator's limits (issue 8) and the following error (commanded minus
actual position of every axis). A run of several
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
from stgen.scenarios.setpoint_limits import setpoint_rates  # noqa: E402

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


def window_max(values: np.ndarray, window: int) -> np.ndarray:
    """Largest value of each run of ``window`` rows (NaN ignored, 0 for an all-NaN window)."""
    usable = len(values) // window * window
    shaped = np.nan_to_num(values[:usable], nan=0.0).reshape((-1, window) + values.shape[1:])
    return shaped.max(axis=1)


def _rate_panels(result: ScenarioResult, axes, shown: slice, time: np.ndarray, window: int) -> None:
    """|v| and |a| of the set-points handed to MC_SyncMoveAbsolute (window maxima) against the limits."""
    velocity, acceleration = setpoint_rates(result.setpoint, result.period_s, result.sync)
    limits = result.limits
    for axis, values, limit, unit, name in (
        (axes[0], np.abs(velocity[shown]), limits.velocity_limit, "mm/s", "velocity"),
        (axes[1], np.abs(acceleration[shown]), limits.acceleration_limit, "mm/s²", "acceleration"),
    ):
        peaks = window_max(values, window)
        for leg in range(6):
            axis.plot(time[:len(peaks) * window:window], peaks[:, leg], label=f"q{leg + 1}", linewidth=0.8)
        axis.axhline(limit, color="red", linestyle="--", linewidth=0.8, label=f"limit {limit:g} {unit}")
        largest = float(np.nanmax(values)) if np.isfinite(values).any() else 0.0
        axis.set_ylabel(f"|{name}| ({unit})")
        axis.set_title(f"Cylinder set-point {name} (finite differences at {result.period_s * 1000:g} ms; "
                       f"max {largest:.3g} {unit} of {limit:g})")
        axis.set_yscale("symlog", linthresh=1.0)
        axis.legend(**LEGEND_OUTSIDE)


def _following_error_panel(result: ScenarioResult, axis, shown: slice, time: np.ndarray, window: int) -> None:
    error = result.following_error[shown]
    peaks = window_max(np.abs(error), window)
    for leg in range(6):
        axis.plot(time[:len(peaks) * window:window], peaks[:, leg], label=f"axis {leg + 1}", linewidth=0.8)
    axis.set_ylabel("|Cmd.Pos − Act.Pos| (mm)")
    axis.set_title(f"Following error, commanded minus actual (max {np.abs(error).max():.3g} mm)")
    axis.legend(**LEGEND_OUTSIDE)


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
    figure, axes = plt.subplots(7, 1, figsize=(10, 20), sharex=True, constrained_layout=True)
    figure.suptitle(
        f"{result.scenario.title}\n{result.duration_s:.3f} s simulated, {result.scans:,} scans of "
        f"{result.period_s * 1000:g} ms, SP_Controller in st_runtime with six simulated axes"
        + (f" (servo lag {result.servo_lag_s * 1000:g} ms)" if result.servo_lag_s > 0 else " (ideal servos)"),
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
    axes[3].legend(**LEGEND_OUTSIDE)

    if result.setpoint is not None:
        _rate_panels(result, axes[4:6], shown, time, window)
    _following_error_panel(result, axes[6], shown, time, window)
    axes[6].set_xlabel("time (s)")

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
