"""The reachable workspace of a platform, offline and vectorised with NumPy (docs/mathematics.md section 6.2 workspace).

Frame (every value in mm and degrees): the upper pose (x, y, z, a1, a2, a3)
of :mod:`stgen.reference.moving_base`, in the world frame with z measured
from the home height h0 and the angles in the order of
``platform.platform_rotation``; the base at its zero pose unless given.

* :func:`coordinate_ranges`: how far each coordinate alone goes from the home
  pose or another centre pose (the others held) before a limit stops it, in both directions, and
  which limit on which leg stops it. Samples the line densely in one
  vectorised call, then bisects the first sign change to :data:`BISECTION_TOLERANCE`.
* :func:`slice_map`: a grid of two coordinates at a fixed rest of the pose
  (fixed orientation), each point feasible or the limit that binds there
  (:attr:`stgen.reference.feasibility.FeasibilityMap.binding`), in one call.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from stgen.config import PlatformConfig
from stgen.reference.feasibility import Limit, feasibility

COORDINATES = ("x", "y", "z", "a1", "a2", "a3")
#: Search extents from home: mm for x, y, z; degrees for the angles.
SEARCH_EXTENT = (2000.0, 2000.0, 2000.0, 180.0, 180.0, 180.0)
#: Line samples per direction before the bisection.
LINE_SAMPLES = 4001
BISECTION_TOLERANCE = 1e-9


def coordinate_index(name: str) -> int:
    if name not in COORDINATES:
        raise ValueError(f"unknown coordinate {name!r}; expected one of {', '.join(COORDINATES)}")
    return COORDINATES.index(name)


def coordinate_unit(index: int) -> str:
    return "mm" if index < 3 else "deg"


@dataclass(frozen=True)
class RangeEnd:
    """One end of a coordinate's range: the last feasible value and what stops it beyond.

    ``limit`` and ``leg`` are :data:`Limit.NONE` and 0 when nothing stops the
    coordinate within :data:`SEARCH_EXTENT` (``value`` is then the extent).
    """

    value: float
    limit: Limit
    leg: int

    def to_json(self) -> dict:
        return {"value": self.value, "limit": self.limit.label if self.limit else None, "leg": self.leg or None}


@dataclass(frozen=True)
class CoordinateRange:
    coordinate: str
    unit: str
    low: RangeEnd
    high: RangeEnd

    def to_json(self) -> dict:
        return {"coordinate": self.coordinate, "unit": self.unit, "min": self.low.to_json(), "max": self.high.to_json()}


def _feasible(config, poses, base):
    return feasibility(config, poses, base).feasible


def _range_end(config, index, sign, base, centre) -> RangeEnd:
    extent = SEARCH_EXTENT[index]
    values = centre[index] + sign * np.linspace(0.0, extent, LINE_SAMPLES)
    poses = np.broadcast_to(centre, (LINE_SAMPLES, 6)).copy()
    poses[:, index] = values
    feasible = _feasible(config, poses, base)
    if not feasible[0]:
        raise ValueError(f"the pose {list(centre)} the ranges start from is not feasible")
    outside = np.flatnonzero(~feasible)
    if outside.size == 0:
        return RangeEnd(float(values[-1]), Limit.NONE, 0)
    inside_value, outside_value = values[outside[0] - 1], values[outside[0]]
    while abs(outside_value - inside_value) > BISECTION_TOLERANCE:
        middle = 0.5 * (inside_value + outside_value)
        pose = centre.copy()
        pose[index] = middle
        if _feasible(config, pose, base):
            inside_value = middle
        else:
            outside_value = middle
    pose = centre.copy()
    pose[index] = outside_value
    limit, leg = feasibility(config, pose, base).binding
    return RangeEnd(float(inside_value), Limit(int(limit)), int(leg))


def coordinate_ranges(config: PlatformConfig, base_pose_deg=None, centre=None) -> list[CoordinateRange]:
    """The range of each coordinate alone from ``centre`` (default home; mm, degrees), the other
    five held at the centre's values, with the limit (and leg) that ends it on each side."""
    centre = np.zeros(6) if centre is None else np.asarray(centre, dtype=float).reshape(6).copy()
    return [
        CoordinateRange(name, coordinate_unit(index), _range_end(config, index, -1.0, base_pose_deg, centre),
                        _range_end(config, index, 1.0, base_pose_deg, centre))
        for index, name in enumerate(COORDINATES)
    ]


@dataclass(frozen=True)
class SliceMap:
    """A slice of the workspace: ``feasible[ny, nx]``, ``limit[ny, nx]`` (:class:`Limit` codes, 0
    where feasible) and ``leg[ny, nx]`` (1..6, 0 where feasible) over the grid ``xs`` × ``ys``."""

    axes: tuple[str, str]
    fixed_pose: tuple[float, ...]
    xs: np.ndarray
    ys: np.ndarray
    feasible: np.ndarray
    limit: np.ndarray
    leg: np.ndarray

    def limit_counts(self) -> dict[str, int]:
        codes, counts = np.unique(self.limit, return_counts=True)
        return {Limit(int(code)).label if code else "feasible": int(count) for code, count in zip(codes, counts)}

    def feasible_extent(self) -> dict[str, list[float] | None]:
        """Smallest and largest feasible value of each axis over the slice (None if none feasible)."""
        if not self.feasible.any():
            return {self.axes[0]: None, self.axes[1]: None}
        rows, columns = np.nonzero(self.feasible)
        return {self.axes[0]: [float(self.xs[columns.min()]), float(self.xs[columns.max()])],
                self.axes[1]: [float(self.ys[rows.min()]), float(self.ys[rows.max()])]}

    def to_json(self, grid: bool = True) -> dict:
        data = {
            "axes": list(self.axes),
            "fixed_pose": list(self.fixed_pose),
            "x": {"axis": self.axes[0], "min": float(self.xs[0]), "max": float(self.xs[-1]), "count": len(self.xs)},
            "y": {"axis": self.axes[1], "min": float(self.ys[0]), "max": float(self.ys[-1]), "count": len(self.ys)},
            "feasible_fraction": float(self.feasible.mean()),
            "feasible_extent": self.feasible_extent(),
            "points_by_limit": self.limit_counts(),
            "limit_codes": {limit.label: int(limit) for limit in Limit},
        }
        if grid:
            data["limit"] = self.limit.tolist()  # rows follow y, columns x; 0 = feasible
            data["leg"] = self.leg.tolist()
        return data


def slice_map(config: PlatformConfig, axes=("x", "y"), bounds=None, resolution: int = 200,
              fixed_pose=None, base_pose_deg=None) -> SliceMap:
    """Feasibility over a ``resolution`` × ``resolution`` grid of two coordinates; the other four
    take ``fixed_pose`` (default home). ``bounds`` = ((x0, x1), (y0, y1)), default from the
    coordinate ranges with a 10 % margin."""
    first, second = (coordinate_index(name) for name in axes)
    if first == second:
        raise ValueError("a slice needs two different coordinates")
    fixed = np.zeros(6) if fixed_pose is None else np.asarray(fixed_pose, dtype=float).reshape(6)
    if bounds is None:
        ranges = coordinate_ranges(config, base_pose_deg, fixed)
        bounds = tuple(_padded(ranges[index]) for index in (first, second))
    xs = np.linspace(bounds[0][0], bounds[0][1], resolution)
    ys = np.linspace(bounds[1][0], bounds[1][1], resolution)
    poses = np.broadcast_to(fixed, (resolution, resolution, 6)).copy()
    poses[..., first] = xs[None, :]
    poses[..., second] = ys[:, None]
    result = feasibility(config, poses, base_pose_deg)
    limit, leg = result.binding
    return SliceMap(tuple(axes), tuple(float(v) for v in fixed), xs, ys, result.feasible, limit, leg)


def _padded(coordinate: CoordinateRange) -> tuple[float, float]:
    low, high = coordinate.low.value, coordinate.high.value
    margin = 0.1 * (high - low)
    return low - margin, high + margin
