"""PNG of a platform scenario run (docs/mathematics.md sections 6.1, 6.2): the six commanded axis
positions against their limits (stroke, or crank angles), the joint angles of every leg against
theirs (linear legs with joint limits; a crank platform shows the error against the reference
instead), and the set-points' velocity and acceleration against the actuator's limits.

Uses matplotlib's Agg backend (files only, no display needed).
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402  (the backend is chosen first)
import numpy as np  # noqa: E402

from stgen.scenarios.actuators import actuator_limits  # noqa: E402
from stgen.scenarios.setpoint_limits import setpoint_rates  # noqa: E402

LEGEND_OUTSIDE = dict(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8, borderaxespad=0.0)
LIMIT_LINE = dict(color="red", linestyle="--", linewidth=0.8)


def _limit_lines(axes, *values) -> None:
    for value in values:
        axes.axhline(value, **LIMIT_LINE)


def platform_figure(run, path: str | Path) -> None:
    result, config, unit = run.result, run.config, run.unit
    t = result.time_s
    figure, panels = plt.subplots(4, 1, figsize=(10.0, 11.0), sharex=True)
    positions, angles, velocity_panel, acceleration_panel = panels
    name = "crank angle" if config.is_crank else "stroke D"
    for leg in range(6):
        positions.plot(t, result.commanded[:, leg], linewidth=0.9, label=f"{name} {leg + 1}")
    _limit_lines(positions, *actuator_limits(config))
    positions.set_ylabel(f"{name} ({unit})")
    positions.legend(**LEGEND_OUTSIDE)
    joint = run.pose_limits.joint_angles
    if joint:
        for key, label in (("gamma", "max |γi|"), ("psi", "max |ψi|"), ("tilt", "max tilt")):
            angles.plot(t, np.abs(joint[key]).max(axis=1), linewidth=0.9, label=label)
        limits = [v for v in (config.joints.universal_max_deg, config.joints.spherical_tilt_max_deg) if v is not None]
        _limit_lines(angles, *sorted(set(limits)))
        angles.set_ylabel("joint angles (deg)")
    else:
        angles.semilogy(t, np.maximum(result.error.max(axis=1), 1e-16), linewidth=0.9, label="max |q - ref|")
        angles.set_ylabel(f"error vs reference ({unit})")
    angles.legend(**LEGEND_OUTSIDE)
    velocity, acceleration = setpoint_rates(result.setpoint, result.period_s, result.sync)
    for leg in range(6):
        velocity_panel.plot(t, velocity[:, leg], linewidth=0.8, label=f"axis {leg + 1}")
        acceleration_panel.plot(t, acceleration[:, leg], linewidth=0.8, label=f"axis {leg + 1}")
    _limit_lines(velocity_panel, -config.actuator.max_velocity, config.actuator.max_velocity)
    _limit_lines(acceleration_panel, -config.actuator.max_acceleration, config.actuator.max_acceleration)
    velocity_panel.set_ylabel(f"set-point velocity ({unit}/s)")
    acceleration_panel.set_ylabel(f"set-point acceleration ({unit}/s²)")
    # A stream's start step would flatten the panel: scale to the motion, the step is in the table.
    motion = run.motion_limits.max_acceleration.max()
    bound = max(motion, 1.0) * 1.2
    acceleration_panel.set_ylim(-max(bound, 0.0), bound)
    velocity_panel.legend(**LEGEND_OUTSIDE)
    acceleration_panel.legend(**LEGEND_OUTSIDE)
    acceleration_panel.set_xlabel("time (s)")
    verdict = "every limit holds" if run.limits_hold else "a limit is broken"
    positions.set_title(f"{result.scenario.title}\n{result.scans:,} scans, max |error| {result.max_error_mm:.2e} "
                        f"{unit}; {verdict} (dashed: limits)", fontsize=9)
    figure.tight_layout()
    figure.savefig(path, dpi=90)
    plt.close(figure)
