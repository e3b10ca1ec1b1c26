"""Figures of planned paths and playbacks: the six actuator velocities along the motion, the
curve in the x-y plane beside them, the parameters in the title (the study gives none: they are ours).

Matplotlib's Agg backend (files only).
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402  (the backend is chosen first)

from stgen.config import PlatformConfig  # noqa: E402
from stgen.reference.motion_limits import MotionCheck  # noqa: E402


def draw_actuator_velocities(rows: list[tuple[str, MotionCheck]], config: PlatformConfig, title: str,
                             out: Path) -> Path:
    """One row per (label, motion): x-y trace of the centre, and the six leg velocities against ±v_max."""
    fig, axes = plt.subplots(len(rows), 2, figsize=(13, 3.6 * len(rows)), squeeze=False,
                             gridspec_kw={"width_ratios": [1, 3]})
    limit = config.actuator.max_velocity
    for (label, check), (curve_ax, rate_ax) in zip(rows, axes):
        curve_ax.plot(check.poses[:, 0], check.poses[:, 1], lw=0.8)
        curve_ax.set_aspect("equal", adjustable="datalim")
        curve_ax.set_xlabel("x, mm")
        curve_ax.set_ylabel("y, mm")
        curve_ax.set_title("centre in the x-y plane", fontsize=8)
        for leg in range(6):
            rate_ax.plot(check.t, check.legs.velocities[:, leg], lw=0.8, label=f"leg {leg + 1}")
        peak = abs(check.legs.velocities).max()
        if peak > 0.5 * limit:
            for sign in (1, -1):
                rate_ax.axhline(sign * limit, color="red", lw=0.8, ls="--")
        rate_ax.set_xlabel("t, s")
        rate_ax.set_ylabel("actuator velocity, mm/s")
        rate_ax.set_title(f"{label}\nmax |v| {peak:.1f} mm/s of {limit:g}"
                          f" (limit {'dashed' if peak > 0.5 * limit else 'off scale'})", fontsize=8)
        rate_ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=7)
        rate_ax.grid(alpha=0.3)
    fig.suptitle(title, fontsize=9)
    fig.tight_layout()
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=110)
    plt.close(fig)
    return out
