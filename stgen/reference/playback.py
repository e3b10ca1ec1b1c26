"""Playback of a recorded motion: a table of poses (t, x, y, z, α, β, γ) interpolated to the task period.

Interpolation: the cubic spline through the knots, clamped (velocity zero at
the first and last knot, so playback starts and ends at rest), C2 inside:
position, velocity and acceleration are continuous at every knot. The spline
is kept in Hermite form, one slope mᵢ per knot and coordinate, found here by
the tridiagonal system of the C2 conditions (de Boor, "A Practical Guide to
Splines", ch. IV):

    h_k·m_{k−1} + 2(h_{k−1} + h_k)·m_k + h_{k−1}·m_{k+1} = 3(h_k·δ_{k−1} + h_{k−1}·δ_k),
    h_k = t_{k+1} − t_k,  δ_k = (y_{k+1} − y_k)/h_k,  m_0 = m_N = 0.

On segment k with s = (t − t_k)/h_k the pose is
    y = (2s³ − 3s² + 1)·y_k + (s³ − 2s² + s)·h_k·m_k + (−2s³ + 3s²)·y_{k+1} + (s³ − s²)·h_k·m_{k+1},
the form TRJ_Playback evaluates with the slopes rendered into its table.

Rest at both ends: a clamped spline fixes only the slope, so its acceleration
at the first and last knot is generally not zero (a step from rest). The table
therefore gets one knot more inside the first and inside the last segment
(their midpoints; thirds of a two-row table), whose values are chosen so that
the acceleration is zero at both ends: s''(t_0) = (6(y_1 − y_0) − 2h·m_1)/h² is
affine in the two inserted values, so three spline solves and a 2×2 system per
coordinate give them. The spline still passes through every recorded row.

CSV: a header row ``t,x,y,z,alpha,beta,gamma`` (s, mm, degrees), then one row
per knot, times strictly increasing, at least two rows. Errors are
:class:`PlaybackError` naming file, line and column.
"""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

COLUMNS = ("t", "x", "y", "z", "alpha", "beta", "gamma")


class PlaybackError(ValueError):
    """A playback table that cannot be read or played (message: ``file:line:col: rule``)."""


@dataclass(frozen=True)
class PlaybackTable:
    """Knot times ``t[n]`` (s, from 0), poses ``poses[n, 6]`` and spline slopes ``slopes[n, 6]`` per s."""

    t: np.ndarray
    poses: np.ndarray
    slopes: np.ndarray
    source: str = "<table>"

    @property
    def duration(self) -> float:
        return float(self.t[-1])


def read_playback_csv(path) -> PlaybackTable:
    """Read and check a playback CSV; times are shifted so the first knot is at t = 0."""
    name = str(path)
    try:
        text = Path(path).read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as error:
        raise PlaybackError(f"{name}: cannot read: {error}") from None
    rows = list(csv.reader(text.splitlines()))
    if not rows or [c.strip().lower() for c in rows[0]] != list(COLUMNS):
        raise PlaybackError(f"{name}:1:1: the header must be {','.join(COLUMNS)}")
    values = []
    for line, row in enumerate(rows[1:], start=2):
        if not row or all(not cell.strip() for cell in row):
            continue
        if len(row) != len(COLUMNS):
            raise PlaybackError(f"{name}:{line}:1: expected {len(COLUMNS)} columns, got {len(row)}")
        numbers = []
        column = 1
        for cell in row:
            try:
                number = float(cell)
            except ValueError:
                number = math.nan
            if not math.isfinite(number):
                raise PlaybackError(f"{name}:{line}:{column}: expected a finite number, got {cell.strip()!r}")
            numbers.append(number)
            column += len(cell) + 1
        if values and numbers[0] <= values[-1][0]:
            raise PlaybackError(f"{name}:{line}:1: times must increase strictly ({numbers[0]!r} after {values[-1][0]!r})")
        values.append(numbers)
    if len(values) < 2:
        raise PlaybackError(f"{name}:1:1: a playback table needs at least two rows, got {len(values)}")
    data = np.array(values)
    return make_table(data[:, 0] - data[0, 0], data[:, 1:], name)


#: Knots the table gets beyond the recorded rows (one in the first, one in the last segment).
ADDED_KNOTS = 2


def make_table(t, poses, source: str = "<table>") -> PlaybackTable:
    """A :class:`PlaybackTable` through the rows ``t[n]`` (increasing), ``poses[n, 6]`` that starts and
    ends at rest in velocity and acceleration (:data:`ADDED_KNOTS` knots inserted, see the module)."""
    t = np.asarray(t, dtype=float)
    poses = np.asarray(poses, dtype=float)
    if len(t) == 2:
        first, last = t[0] + (t[1] - t[0]) / 3.0, t[0] + 2.0 * (t[1] - t[0]) / 3.0
    else:
        first, last = (t[0] + t[1]) / 2.0, (t[-2] + t[-1]) / 2.0
    knots = np.concatenate(([t[0], first], t[1:-1], [last, t[-1]]))

    def end_accelerations(inserted_first, inserted_last):
        values = np.concatenate(([poses[0], inserted_first], poses[1:-1], [inserted_last, poses[-1]]))
        slopes = clamped_spline_slopes(knots, values)
        h0, h1 = knots[1] - knots[0], knots[-1] - knots[-2]
        start = (6.0 * (values[1] - values[0]) - 2.0 * h0 * slopes[1]) / h0**2
        end = (6.0 * (values[-2] - values[-1]) + 2.0 * h1 * slopes[-2]) / h1**2
        return np.stack((start, end), axis=-1), values

    zero, one = np.zeros(poses.shape[1]), np.ones(poses.shape[1])
    base, _ = end_accelerations(zero, zero)
    by_first = end_accelerations(one, zero)[0] - base
    by_last = end_accelerations(zero, one)[0] - base
    matrix = np.stack((by_first, by_last), axis=-1)               # [6, 2 conditions, 2 unknowns]
    inserted = np.linalg.solve(matrix, -base[..., None])[..., 0]  # [6, 2]
    _, values = end_accelerations(inserted[:, 0], inserted[:, 1])
    return PlaybackTable(knots, values, clamped_spline_slopes(knots, values), source)


def clamped_spline_slopes(t, y) -> np.ndarray:
    """Knot slopes m[n, k] of the C2 cubic spline with m_0 = m_N = 0 (Thomas algorithm)."""
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    n = len(t)
    slopes = np.zeros_like(y)
    if n < 3:
        return slopes
    h = np.diff(t)
    delta = np.diff(y, axis=0) / h[:, None]
    # unknowns m_1 .. m_{n-2}; row j (knot k = j + 1): h_k m_{k-1} + 2(h_{k-1} + h_k) m_k + h_{k-1} m_{k+1}
    lower = h[2:]                    # coefficient of m_{k-1} = h_k (k = 2 .. n-2)
    diag = 2.0 * (h[:-1] + h[1:])
    upper = h[:-2]                   # coefficient of m_{k+1} = h_{k-1} (k = 1 .. n-3)
    rhs = 3.0 * (h[1:, None] * delta[:-1] + h[:-1, None] * delta[1:])
    size = n - 2
    c = np.zeros(size)
    d = np.zeros_like(rhs)
    c[0] = upper[0] / diag[0] if size > 1 else 0.0
    d[0] = rhs[0] / diag[0]
    for j in range(1, size):
        denom = diag[j] - lower[j - 1] * c[j - 1]
        c[j] = upper[j] / denom if j < size - 1 else 0.0
        d[j] = (rhs[j] - lower[j - 1] * d[j - 1]) / denom
    for j in range(size - 2, -1, -1):
        d[j] -= c[j] * d[j + 1]
    slopes[1:-1] = d
    return slopes


def evaluate(table: PlaybackTable, t) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(poses, rates, accelerations) ``[..., 6]`` at times ``t`` (clipped to the table: rest outside)."""
    t = np.asarray(t, dtype=float)
    knots = table.t
    clipped = np.clip(t, knots[0], knots[-1])
    k = np.clip(np.searchsorted(knots, clipped, side="right") - 1, 0, len(knots) - 2)
    h = (knots[k + 1] - knots[k])[..., None]
    s = ((clipped - knots[k]) / (knots[k + 1] - knots[k]))[..., None]
    y0, y1 = table.poses[k], table.poses[k + 1]
    m0, m1 = table.slopes[k] * h, table.slopes[k + 1] * h
    s2, s3 = s * s, s * s * s
    pose = (2 * s3 - 3 * s2 + 1) * y0 + (s3 - 2 * s2 + s) * m0 + (-2 * s3 + 3 * s2) * y1 + (s3 - s2) * m1
    rate = ((6 * s2 - 6 * s) * y0 + (3 * s2 - 4 * s + 1) * m0 + (-6 * s2 + 6 * s) * y1 + (3 * s2 - 2 * s) * m1) / h
    acc = ((12 * s - 6) * y0 + (6 * s - 4) * m0 + (-12 * s + 6) * y1 + (6 * s - 2) * m1) / (h * h)
    outside = ((t < knots[0]) | (t > knots[-1]))[..., None]
    return pose, np.where(outside, 0.0, rate), np.where(outside, 0.0, acc)
