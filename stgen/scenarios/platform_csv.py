"""A platform scenario run (:mod:`stgen.scenarios.platform_report`) as CSV, one row per scan.

Columns, every unit in the name: ``time_s`` (the simulated clock during the scan,
(k - 1) * period for scan k), ``scan``, ``state``, ``state_name``, ``fault_id``; the set-point
pose ``x_mm .. a3_deg`` (world frame, z from h0, angles in the platform's rotation order)
and the reference ``ref_x_mm ..``; the base pose ``base_x_mm .. base_b3_deg`` (SpBasePose,
zeros on a fixed base); the commanded axis positions ``q1_mm .. q6_mm`` (``theta1_deg ..``
on a crank platform) and the reference ``ref_q1_mm ..``; on linear legs with joint limits the
joint angles of the set-point ``gamma1_deg .. psi1_deg .. tilt1_deg ..``; ``max_error``
(largest |q - ref_q| of the scan, the axes' unit). Floats in shortest round-trip form.
``every`` keeps one scan in N as :func:`stgen.scenarios.csv_trace.kept_rows` says.
"""

from __future__ import annotations

import csv
from pathlib import Path

from stgen.scenarios.csv_trace import kept_rows

POSE = ("x_mm", "y_mm", "z_mm", "a1_deg", "a2_deg", "a3_deg")
BASE = ("base_x_mm", "base_y_mm", "base_z_mm", "base_b1_deg", "base_b2_deg", "base_b3_deg")


def header(run) -> tuple[str, ...]:
    axis = (lambda i: f"theta{i}_deg") if run.config.is_crank else (lambda i: f"q{i}_mm")
    angles = tuple(f"{name}{leg}_deg" for name in run.pose_limits.joint_angles for leg in range(1, 7))
    return (("time_s", "scan", "state", "state_name", "fault_id") + POSE + tuple(f"ref_{c}" for c in POSE) + BASE
            + tuple(axis(i) for i in range(1, 7)) + tuple(f"ref_{axis(i)}" for i in range(1, 7)) + angles
            + ("max_error",))


def write_platform_csv(run, path: str | Path, every: int = 1) -> Path:
    path = Path(path)
    result = run.result
    error = result.error.max(axis=1)
    angles = list(run.pose_limits.joint_angles.values())
    with path.open("w", newline="", encoding="utf-8") as stream:
        writer = csv.writer(stream)
        writer.writerow(header(run))
        for row in kept_rows(result, every):
            writer.writerow(
                [repr(float(result.time_s[row])), row + 1, int(result.state[row]),
                 result.state_names.get(int(result.state[row]), ""), int(result.fault_id[row])]
                + [repr(float(v)) for v in result.setpoint_pose[row]]
                + [repr(float(v)) for v in result.expected_pose[row]]
                + [repr(float(v)) for v in run.base_pose[row]]
                + [repr(float(v)) for v in result.commanded[row]]
                + [repr(float(v)) for v in result.expected[row]]
                + [repr(float(v)) for values in angles for v in values[row]]
                + [repr(float(error[row]))]
            )
    return path
