"""The inputs of TRJ_Path for a :class:`~stgen.reference.paths.PathSpec` (family and law numbers
as TRJ_Path's FAMILY_ and LAW_ constants, the closing φ_end computed here)."""

from __future__ import annotations

from stgen.reference.paths import FAMILIES, PathSpec

#: TRJ_Path's Law numbers.
LAW_NUMBERS = {"blend": 1, "cycloidal": 2}


def trj_path_inputs(spec: PathSpec, plan_samples: int, samples_per_scan: int) -> dict[str, object]:
    """``{input name: value}`` for TRJ_Path; Duration is the spec's, 0 for the shortest."""
    return {
        "Family": FAMILIES.index(spec.family) + 1,
        "FixedRadius": float(spec.R),
        "RollingRadius": float(spec.r),
        "PenDistance": float(spec.d),
        "SpiralStart": float(spec.a),
        "SpiralPitch": float(spec.b),
        "ParameterEnd": float(spec.end),
        "Centre": [float(c) for c in spec.centre],
        "Orientation": [float(c) for c in spec.orientation],
        "Law": LAW_NUMBERS[spec.law],
        "BlendFraction": float(spec.blend),
        "Duration": float(spec.duration or 0.0),
        "PlanSamples": int(plan_samples),
        "SamplesPerScan": int(samples_per_scan),
    }
