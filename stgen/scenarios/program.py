"""The whole controller as ST: the kinematics POUs plus the trajectory FBs and
SP_Controller (:data:`stgen.render.CONTROLLER_TEMPLATES`), rendered for a
platform and loaded into ``st_runtime``.
"""

from __future__ import annotations

from functools import lru_cache

from stgen import render
from stgen.config import PlatformConfig

#: The PROGRAM the primary task runs.
CONTROLLER_PROGRAM = "SP_Controller"

#: The axis variables SP_Controller uses (st_templates/controller/_controller.st.j2): axis i drives cylinder i.
AXIS_NAMES = tuple(f"MC_Axis{index:03d}" for index in range(6))


def render_controller_program(
    config: PlatformConfig | None = None, options: render.RenderOptions | None = None
) -> render.RenderedProgram:
    """Every POU the controller needs, in dependency order: what ``stgen generate`` writes."""
    return render.render_program(config, options)


def iec_sources(program: render.RenderedProgram) -> dict[str, str]:
    """``{"<POU>.st": IEC text}`` for every POU, as ``stgen generate --target iec`` writes them."""
    from stgen.exports.iec import pou_text

    return {f"{pou.name}.st": pou_text(pou) for pou in program.pous}


def codes_of(program: render.RenderedProgram, pou: str) -> dict[str, int]:
    """The integer global constants of a VAR_GLOBAL POU (``16#1201`` -> 0x1201), by name."""
    values = {}
    for variable in program.pou(pou).variables:
        if variable.initial is None or variable.type not in ("INT", "WORD", "DINT", "UINT"):
            continue
        text = variable.initial.strip()
        values[variable.name] = int(text[3:], 16) if text.startswith("16#") else int(text)
    return values


@lru_cache(maxsize=4)
def controller_sources(config: PlatformConfig | None = None) -> tuple[tuple[str, str], ...]:
    """The IEC texts of :func:`render_controller_program` (cached: rendering is pure)."""
    return tuple(iec_sources(render_controller_program(config)).items())


def load_controller(config: PlatformConfig | None = None, playback=None):
    """Parse, check and compile the controller program (the axis variables are
    declared by SP_Axes, named as the simulated axes must be: :data:`AXIS_NAMES`).

    Not cached: the compiled program holds the global variables, so every
    simulation loads its own. ``playback``: a playback table to render with
    (``stgen generate --playback``; its sources are not cached).
    """
    from st_runtime import api

    if playback is not None:
        return api.load_sources(iec_sources(render_controller_program(config, render.RenderOptions(playback=playback))))
    return api.load_sources(dict(controller_sources(config)))
