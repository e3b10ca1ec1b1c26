"""PNG of a workspace slice: feasible points light, each binding limit its own colour (docs/mathematics.md section 6.2).

Uses matplotlib's Agg backend (files only, no display needed).
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402  (the backend is chosen first)
import numpy as np  # noqa: E402
from matplotlib.colors import ListedColormap  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402

from stgen.reference.feasibility import Limit  # noqa: E402
from stgen.workspace import COORDINATES, SliceMap, coordinate_unit  # noqa: E402

#: One colour per :class:`Limit` code, feasible (0) first.
LIMIT_COLOURS = ("#f2f2f2", "#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                 "#8c564b", "#e377c2", "#7f7f7f", "#000000")


def draw_slice(item: SliceMap, path: str | Path) -> None:
    figure, axes = plt.subplots(figsize=(7.0, 6.0))
    codes = np.asarray(item.limit)
    axes.imshow(codes, origin="lower", interpolation="nearest", aspect="auto",
                cmap=ListedColormap(LIMIT_COLOURS), vmin=-0.5, vmax=len(LIMIT_COLOURS) - 0.5,
                extent=(item.xs[0], item.xs[-1], item.ys[0], item.ys[-1]))
    present = sorted(int(code) for code in np.unique(codes))
    axes.legend(handles=[Patch(color=LIMIT_COLOURS[code], label="feasible" if code == 0 else Limit(code).label)
                         for code in present], loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8)
    first, second = (COORDINATES.index(name) for name in item.axes)
    axes.set_xlabel(f"{item.axes[0]} ({coordinate_unit(first)})")
    axes.set_ylabel(f"{item.axes[1]} ({coordinate_unit(second)})")
    axes.set_title(f"workspace slice {item.axes[0]},{item.axes[1]} at {list(item.fixed_pose)}\n"
                   "colour: feasible, or the limit broken the most", fontsize=9)
    figure.tight_layout()
    figure.savefig(path, dpi=100)
    plt.close(figure)
