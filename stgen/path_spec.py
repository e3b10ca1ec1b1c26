"""The ``--path CURVE`` text of ``stgen plan``: ``FAMILY[:KEY=VALUE,...]``.

Keys: ``R``, ``r``, ``d`` (trochoids, mm), ``a`` (mm), ``b`` (mm/rad) of the
spiral, ``phi_end`` (rad) or ``turns`` (φ_end = 2π·turns), ``x``, ``y``, ``z``
(centre, mm), ``roll`` (about X: γ of docs/mathematics.md section 1), ``pitch`` (about Y: β), ``yaw``
(about Z: α), degrees; ``law`` (blend or cycloidal), ``blend`` (fraction of
the duration per blend), ``duration`` (s). Example:
``epitrochoid:R=60,r=20,d=30,z=240,roll=35,pitch=35``.
"""

from __future__ import annotations

import dataclasses
import math

from stgen.reference.paths import PathError, PathSpec

_NUMBER_KEYS = {"R", "r", "d", "a", "b", "phi_end", "turns", "x", "y", "z", "roll", "pitch", "yaw", "blend",
                "duration"}


def parse_path_spec(text: str) -> PathSpec:
    """A :class:`PathSpec` from ``text``; :class:`PathError` names the column and the key on bad input."""
    family, _, rest = text.partition(":")
    values: dict[str, float | str] = {}
    column = len(family) + 2
    for item in rest.split(",") if rest else []:
        key, sep, value = (part.strip() for part in item.partition("="))
        if not sep:
            raise PathError(f"column {column}: expected KEY=VALUE, got {item!r}")
        if key == "law":
            values[key] = value
        elif key in _NUMBER_KEYS:
            try:
                values[key] = float(value)
            except ValueError:
                raise PathError(f"column {column}: {key}: expected a number, got {value!r}") from None
        else:
            raise PathError(f"column {column}: unknown key {key!r} (keys: {', '.join(sorted(_NUMBER_KEYS))}, law)")
        column += len(item) + 1
    fields = {k: values[k] for k in ("R", "r", "d", "a", "b", "phi_end", "law", "blend", "duration") if k in values}
    if "turns" in values:
        fields["phi_end"] = 2.0 * math.pi * values["turns"]
    default = {f.name: f.default for f in dataclasses.fields(PathSpec)}
    centre = tuple(values.get(k, c) for k, c in zip(("x", "y", "z"), default["centre"]))
    orientation = (values.get("yaw", 0.0), values.get("pitch", 0.0), values.get("roll", 0.0))
    return PathSpec(family.strip(), centre=centre, orientation=orientation, **fields)
