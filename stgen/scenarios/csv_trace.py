"""A scenario run as CSV: one row per scan, what was commanded next to the reference.

Every column that has a unit says it in its name. Columns: ``time_s`` (the
simulated clock during the scan, (k - 1) * period for scan k, as ``stgen run
--trace`` writes it), ``scan``, ``state`` (SpState) and ``state_name``
(``SP_STATE_MOVING``, ...), ``fault_id`` (SpFaultID), the pose set-point
``x_mm, y_mm, z_mm, alpha_deg, beta_deg, gamma_deg``, the reference pose
``ref_x_mm .. ref_gamma_deg``, the commanded cylinder positions ``q1_mm ..
q6_mm`` (the axes' Cmd.Pos), the reference IK ``ref_q1_mm .. ref_q6_mm``, the
set-points SP_Controller handed to MC_SyncMoveAbsolute ``sp_q1_mm ..
sp_q6_mm`` (equal to q unless an axis saturated them) and ``max_error_mm``
(largest |q - ref_q| of the scan). Floats in shortest round-trip form
(``repr``), so the file holds exactly the simulated values.

``every=N`` (``stgen demo --quick`` writes N = 10) keeps one scan in N: scans 1,
N + 1, 2N + 1, ..., the first and the last scan of every stretch of one state and
fault, and the last scan. The rows kept are whole; ``scan`` says which they are.
"""

from __future__ import annotations

import csv
from pathlib import Path

from stgen.scenarios.runner import ScenarioResult

POSE_COLUMNS = ("x_mm", "y_mm", "z_mm", "alpha_deg", "beta_deg", "gamma_deg")
HEADER = (
    ("time_s", "scan", "state", "state_name", "fault_id")
    + POSE_COLUMNS
    + tuple(f"ref_{name}" for name in POSE_COLUMNS)
    + tuple(f"q{leg}_mm" for leg in range(1, 7))
    + tuple(f"ref_q{leg}_mm" for leg in range(1, 7))
    + tuple(f"sp_q{leg}_mm" for leg in range(1, 7))
    + ("max_error_mm",)
)


def kept_rows(result, every: int = 1) -> list[int]:
    """The rows (scan - 1) a trace keeps when it keeps one scan in ``every`` (module docstring)."""
    scans = result.scans
    if every <= 1:
        return list(range(scans))
    state, fault = result.state, result.fault_id

    def changes(row: int, other: int) -> bool:
        return state[row] != state[other] or fault[row] != fault[other]

    return [row for row in range(scans)
            if row % every == 0 or row == scans - 1 or changes(row, row - 1) or changes(row, row + 1)]


def write_trace_csv(result: ScenarioResult, path: str | Path, every: int = 1) -> Path:
    """Write the run to ``path`` (one scan in ``every``, module docstring); returns the path."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    error = result.error.max(axis=1)
    time = result.time_s
    with path.open("w", newline="", encoding="utf-8") as stream:
        writer = csv.writer(stream)
        writer.writerow(HEADER)
        for row in kept_rows(result, every):
            writer.writerow(
                [repr(float(time[row])), row + 1, int(result.state[row]),
                 result.state_names.get(int(result.state[row]), ""), int(result.fault_id[row])]
                + [repr(float(v)) for v in result.setpoint_pose[row]]
                + [repr(float(v)) for v in result.expected_pose[row]]
                + [repr(float(v)) for v in result.commanded[row]]
                + [repr(float(v)) for v in result.expected[row]]
                + [repr(float(v)) for v in result.setpoint[row]]
                + [repr(float(error[row]))]
            )
    return path
