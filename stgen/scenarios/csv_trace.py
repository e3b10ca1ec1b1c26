"""A scenario run as CSV: one row per scan, what was commanded next to the reference.

Columns: ``time_s`` (end of the scan), ``scan``, ``state`` (SpState),
``fault_id`` (SpFaultID), the pose set-point ``x, y, z, alpha, beta, gamma``
(mm, deg), the reference pose ``ref_x .. ref_gamma``, the commanded cylinder
positions ``q1 .. q6`` (mm, the axes' Cmd.Pos), the reference IK
``ref_q1 .. ref_q6``, the set-points SP_Controller handed to
MC_SyncMoveAbsolute ``sp_q1 .. sp_q6`` (mm; equal to q unless an axis
saturated them) and ``max_error_mm`` (largest |q - ref_q| of the scan). Floats in shortest
round-trip form (``repr``), so the file holds exactly the simulated values.
"""

from __future__ import annotations

import csv
from pathlib import Path

from stgen.scenarios.runner import ScenarioResult

POSE_NAMES = ("x", "y", "z", "alpha", "beta", "gamma")
HEADER = (
    ("time_s", "scan", "state", "fault_id")
    + POSE_NAMES
    + tuple(f"ref_{name}" for name in POSE_NAMES)
    + tuple(f"q{leg}" for leg in range(1, 7))
    + tuple(f"ref_q{leg}" for leg in range(1, 7))
    + tuple(f"sp_q{leg}" for leg in range(1, 7))
    + ("max_error_mm",)
)


def write_trace_csv(result: ScenarioResult, path: str | Path) -> Path:
    """Write the run to ``path``; returns the path."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    error = result.error.max(axis=1)
    time = result.time_s
    with path.open("w", newline="", encoding="utf-8") as stream:
        writer = csv.writer(stream)
        writer.writerow(HEADER)
        for row in range(result.scans):
            writer.writerow(
                [repr(float(time[row])), row + 1, int(result.state[row]), int(result.fault_id[row])]
                + [repr(float(v)) for v in result.setpoint_pose[row]]
                + [repr(float(v)) for v in result.expected_pose[row]]
                + [repr(float(v)) for v in result.commanded[row]]
                + [repr(float(v)) for v in result.expected[row]]
                + [repr(float(v)) for v in result.setpoint[row]]
                + [repr(float(error[row]))]
            )
    return path
