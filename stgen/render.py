"""Render the platform's POUs from the Jinja2 templates in ``st_templates/``.

Each POU template (``st_templates/<POU>.st.j2``) is one POU. Rendered as a
Jinja2 *module*, it exports

* ``kind``: ``FUNCTION``, ``FUNCTION_BLOCK`` or ``VAR_GLOBAL`` (a global list);
* ``return_type``: the FUNCTION's result type (``none`` otherwise);
* ``header``: the POU's header comment, a complete ST ``(* ... *)`` block;
* ``variables``: its declarations, built with the ``input()``, ``output()``,
  ``in_out()``, ``internal()``, ``constant()``, ``external()`` and
  ``global_constant()`` helpers below;

and its rendered text is the POU body (ST statements only). Keeping the
declarations as data lets every export lay them out its own way: IEC
``VAR_INPUT`` blocks for CODESYS/TwinCAT, a variable table for Sysmac Studio.

Numbers reach the ST only through :func:`lreal_literal` (``repr`` of the
float, so the ST holds exactly the configuration's double) and comments only
through :func:`comment_text` (which refuses text that could close a comment).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import jinja2

from stgen.config import PlatformConfig
from stgen.error_codes import ErrorCode
from stgen.reference.geometry import LEG_COUNT, base_joints, platform_joints
from stgen.reference.linalg import permutation_table

TEMPLATE_DIR = Path(__file__).resolve().parent.parent / "st_templates"

#: Templates of the kinematics POUs (docs/mathematics.md sections 1-3), in dependency order.
KINEMATICS_TEMPLATES = (
    "SP_Constants",
    "SP_Atan2",
    "SP_LuSolve",
    "SP_LeibnizDeterminant",
    "SP_Jacobian",
    "SP_InverseKinematics",
    "SP_ForwardKinematics",
)

#: Templates of the trajectory FBs (docs/mathematics.md section 4) and the controller program (docs/mathematics.md section 5), in dependency order.
CONTROLLER_TEMPLATES = (
    "trajectory/TRJ_Constants",
    "trajectory/TRJ_Cycloidal",
    "trajectory/TRJ_OceanWave",
    "trajectory/TRJ_Brake",
    "trajectory/TRJ_Path",
    "controller/SP_ControllerConstants",
    "controller/SP_ControllerGlobals",
    "controller/SP_Axes",
    "controller/SP_Controller",
)

#: Every POU template (paths below ``st_templates/`` without ``.st.j2``), in
#: dependency order: a POU only calls POUs listed before it. The POU's name is
#: the last path component.
POU_TEMPLATES = KINEMATICS_TEMPLATES + CONTROLLER_TEMPLATES

#: Rendered only with a playback table (``stgen generate --playback FILE.csv``).
PLAYBACK_TEMPLATES = ("trajectory/TRJ_PlaybackTable", "trajectory/TRJ_Playback")
#: The first template rendered after the playback's (SP_Controller plays the table).
PLAYBACK_CALLER = "controller/SP_ControllerConstants"


#: The test benches (``stgen generate --tests``): their results, then one
#: PROGRAM per bench; vectors from :mod:`stgen.benches`.
TEST_BENCH_TEMPLATES = (
    "tests/TB_Globals",
    "tests/TB_InverseKinematics",
    "tests/TB_ForwardKinematics",
    "tests/TB_Determinant",
    "tests/TB_LuSolve",
)
#: The TEST file of the benches (a whole file, not a POU module).
BENCH_TEST_TEMPLATE = "tests/test_benches"
BENCH_TEST_FILE = "test_benches.st"


#: Templates of the platform variants (docs/mathematics.md sections 6.1, 6.2): the variant's own
#: kinematics POUs (in a folder named after the variant), then the trajectories and SP_Controller,
#: whose variant conditionals read crank angles (crank) or take the base pose (moving base).
CRANK_TEMPLATES = (
    "SP_Constants",
    "SP_Atan2",
    "SP_LuSolve",
    "SP_LeibnizDeterminant",
    "SP_Jacobian",
    "crank/SP_InverseKinematics",
    "SP_ForwardKinematics",
) + CONTROLLER_TEMPLATES
MOVING_BASE_TEMPLATES = (
    "SP_Constants",
    "SP_Atan2",
    "SP_LuSolve",
    "SP_LeibnizDeterminant",
    "moving_base/SP_Jacobian",
    "moving_base/SP_InverseKinematics",
    "SP_ForwardKinematics",
) + CONTROLLER_TEMPLATES


def program_templates(config: PlatformConfig) -> tuple[str, ...]:
    """The templates ``config``'s kind renders (raises :class:`RenderError` for a kind not rendered)."""
    kind = config.platform
    if config.is_default_kind:
        return POU_TEMPLATES
    if config.is_crank and not config.moving_base and kind.platform_rotation == "ZYX":
        return CRANK_TEMPLATES
    if not config.is_crank and config.moving_base:
        return MOVING_BASE_TEMPLATES
    raise RenderError(
        f"the ST for this platform kind (actuator {kind.actuator!r}, base {kind.base!r}, rotations "
        f"{kind.base_rotation}/{kind.platform_rotation}) is not rendered; rendered are the default "
        "kind, a crank platform on a fixed base with ZYX, and linear legs on a moving base")


def pou_name(template: str) -> str:
    """The POU a template renders: the last component of its path."""
    return template.rsplit("/", 1)[-1]


#: How the FK obtains det J (docs/mathematics.md section 3, step 1), a generator option.
DETERMINANT_METHODS = ("table", "unrolled", "lu")

# Variable usages, named as in Sysmac Studio's variable tables.
INPUT, OUTPUT, IN_OUT, INTERNAL, EXTERNAL, GLOBAL = "Input", "Output", "InOut", "Internal", "External", "Global"


class RenderError(ValueError):
    """A template or a value that cannot become valid ST."""


@dataclass(frozen=True)
class Variable:
    """One declaration: ``Name : Type := Initial; (* comment *)``.

    ``initial`` is ST text (may span lines; exports that need one line
    collapse its whitespace) or ``None``.
    """

    usage: str
    name: str
    type: str
    initial: str | None = None
    comment: str = ""
    constant: bool = False
    retain: bool = False


@dataclass(frozen=True)
class Pou:
    """A rendered POU (or a global variable list when ``kind`` is ``VAR_GLOBAL``)."""

    name: str
    kind: str
    return_type: str | None
    header: str
    variables: tuple[Variable, ...]
    body: str

    def variables_of(self, usage: str, constant: bool | None = None) -> list[Variable]:
        return [
            v for v in self.variables if v.usage == usage and (constant is None or v.constant == constant)
        ]


@dataclass(frozen=True)
class RenderOptions:
    """Generator options.

    ``determinant``: ``table`` (Leibniz with a constant permutation/sign table
    and a loop), ``unrolled`` (Leibniz written out term by term) or ``lu``
    (the FK takes det J from the LU diagonal; the Leibniz POU is still
    rendered, as a table).
    """

    determinant: str = "table"
    tests: bool = False          # also render the test benches (TEST_BENCH_TEMPLATES)
    #: A :class:`~stgen.reference.playback.PlaybackTable`: also render TRJ_PlaybackTable and TRJ_Playback.
    playback: Any = field(default=None, compare=False)

    def __post_init__(self) -> None:
        if self.determinant not in DETERMINANT_METHODS:
            raise RenderError(
                f"determinant must be one of {', '.join(DETERMINANT_METHODS)}, got {self.determinant!r}"
            )


@dataclass(frozen=True)
class RenderedProgram:
    """Everything ``stgen generate`` writes: the global constants first, then the POUs."""

    pous: tuple[Pou, ...] = field(default_factory=tuple)
    #: ``stgen generate --tests``: the TEST file that runs the bench PROGRAMs under
    #: ``stgen test`` (st_templates/tests/test_benches.st.j2); "" otherwise.
    bench_tests: str = ""

    def pou(self, name: str) -> Pou:
        for pou in self.pous:
            if pou.name == name:
                return pou
        raise KeyError(name)


# --------------------------------------------------------------------------- literals and comments


def lreal_literal(value: float) -> str:
    """An IEC LREAL literal holding exactly ``value`` (``repr`` digits, always with a decimal point)."""
    number = float(value)
    if not math.isfinite(number):
        raise RenderError(f"cannot render the non-finite value {number!r} as an LREAL literal")
    text = repr(number)
    mantissa, _, exponent = text.partition("e")
    if "." not in mantissa:
        mantissa += ".0"
    return f"{mantissa}E{int(exponent)}" if exponent else mantissa


def word_literal(value: int) -> str:
    if not 0 <= value <= 0xFFFF:
        raise RenderError(f"{value} does not fit a WORD")
    return f"16#{value:04X}"


def comment_text(text: Any) -> str:
    """Text safe inside an ST ``(* ... *)`` comment (no nested comment delimiters)."""
    text = str(text)
    if "(*" in text or "*)" in text:
        raise RenderError(f"comment text must not contain '(*' or '*)': {text!r}")
    return text


def array_initializer(values, per_line: int, indent: str = "    ", separator: str = ", ") -> str:
    """``[a, b, ...]`` with ``per_line`` items a line (continuation lines indented).

    ``separator`` goes between the items of a line (a wider one sets groups apart).
    """
    items = [str(v) for v in values]
    lines = [separator.join(items[start : start + per_line]) for start in range(0, len(items), per_line)]
    return "[" + (",\n" + indent).join(lines) + "]"


# --------------------------------------------------------------------------- declaration helpers


def _declare(usage: str, constant: bool = False):
    def helper(name: str, type_: str, comment: str = "", initial: Any = None) -> Variable:
        return Variable(
            usage=usage,
            name=name,
            type=type_,
            initial=None if initial is None else str(initial),
            comment=comment_text(comment),
            constant=constant,
        )

    return helper


_DECLARATION_HELPERS = {
    "input": _declare(INPUT),
    "output": _declare(OUTPUT),
    "in_out": _declare(IN_OUT),
    "internal": _declare(INTERNAL),
    "constant": _declare(INTERNAL, constant=True),
    "external": _declare(EXTERNAL, constant=True),
    "global_constant": _declare(GLOBAL, constant=True),
    "global_variable": _declare(GLOBAL),
    "external_variable": _declare(EXTERNAL),
}


# --------------------------------------------------------------------------- rendering


def make_environment() -> jinja2.Environment:
    env = jinja2.Environment(
        loader=jinja2.FileSystemLoader(str(TEMPLATE_DIR)),
        undefined=jinja2.StrictUndefined,
        trim_blocks=True,
        lstrip_blocks=True,
        keep_trailing_newline=True,
        autoescape=False,
    )
    env.filters["lreal"] = lreal_literal
    env.filters["word"] = word_literal
    env.filters["comment"] = comment_text
    env.globals.update(_DECLARATION_HELPERS)
    env.globals["array_initializer"] = array_initializer
    return env


def template_context(config: PlatformConfig, options: RenderOptions) -> dict[str, Any]:
    """What the templates may use: the configuration and values derived from it."""
    perms, signs = permutation_table(LEG_COUNT)
    return {
        "config": config,
        "geometry": config.geometry,
        "solver": config.solver,
        "stroke": config.stroke,
        "options": options,
        "leg_count": LEG_COUNT,
        "base_joints": base_joints(config.geometry).tolist(),
        "platform_joints": platform_joints(config.geometry).tolist(),
        "error_codes": list(ErrorCode),
        # Leibniz table, 1-based column indices, same rows in the same order as the reference.
        "permutations": [[int(c) + 1 for c in row] for row in perms],
        "permutation_signs": [int(s) for s in signs],
        "rad_per_deg": math.pi / 180.0,
        "deg_per_rad": 180.0 / math.pi,
        "lreal_max": 1.7976931348623157e308,
        "pi": math.pi,
        **variant_context(config),
        "playback": _playback_context(options.playback),
    }


def variant_context(config: PlatformConfig) -> dict[str, Any]:
    """Values only the variants' templates use (docs/mathematics.md sections 6.1, 6.2)."""
    from stgen.error_codes import LegLimitError
    from stgen.reference.geometry import joint_angles

    planes = [math.radians(angle) for angle in config.crank.plane_angle_deg]
    centre = 0.5 * (config.crank.angle_min_deg + config.crank.angle_max_deg)
    polar, _ = joint_angles(config.geometry)
    return {
        "is_crank": config.is_crank,
        "moving_base": config.moving_base,
        "variant": not config.is_default_kind,
        "leg_limit_errors": list(LegLimitError),
        "crank_plane_cos": [math.cos(angle) for angle in planes],
        "crank_plane_sin": [math.sin(angle) for angle in planes],
        "crank_wrap_low_deg": centre - 180.0,
        "base_polar_cos": [math.cos(angle) for angle in polar],
        "base_polar_sin": [math.sin(angle) for angle in polar],
        "base_rotation_entries": rotation_entries(config.platform.base_rotation, "B"),
        "platform_rotation_entries": rotation_entries(config.platform.platform_rotation, "U"),
        "platform_rotation_partials": [rotation_entries(config.platform.platform_rotation, "U", k) for k in (1, 2, 3)],
    }


def rotation_entries(order: str, suffix: str, derivative: int = 0) -> list[list[str]]:
    """ST expressions of the nine entries of R = R1(a1)·R2(a2)·R3(a3) for ``order`` ("ZYX", ...),
    in the cosines and sines ``C1{suffix}``, ``S1{suffix}``, ... of the three angles; products
    written out symbolically so any rotation order renders without matrix code in the ST.
    ``derivative`` = k (1..3) gives ∂R/∂ak instead (the FK Jacobian's angle columns)."""
    def elementary(axis: str, k: int) -> list[list[list[tuple[int, tuple[str, ...]]]]]:
        c, s = f"C{k}{suffix}", f"S{k}{suffix}"
        one = [(1, ())]
        zero: list = []
        if k == derivative:  # d/da of cos a = -sin a, of sin a = cos a, of 1 = 0
            table = {
                "X": [[zero, zero, zero], [zero, [(-1, (s,))], [(-1, (c,))]], [zero, [(1, (c,))], [(-1, (s,))]]],
                "Y": [[[(-1, (s,))], zero, [(1, (c,))]], [zero, zero, zero], [[(-1, (c,))], zero, [(-1, (s,))]]],
                "Z": [[[(-1, (s,))], [(-1, (c,))], zero], [[(1, (c,))], [(-1, (s,))], zero], [zero, zero, zero]],
            }
            return table[axis]
        table = {
            "X": [[one, zero, zero], [zero, [(1, (c,))], [(-1, (s,))]], [zero, [(1, (s,))], [(1, (c,))]]],
            "Y": [[[(1, (c,))], zero, [(1, (s,))]], [zero, one, zero], [[(-1, (s,))], zero, [(1, (c,))]]],
            "Z": [[[(1, (c,))], [(-1, (s,))], zero], [[(1, (s,))], [(1, (c,))], zero], [zero, zero, one]],
        }
        return table[axis]

    def multiply(left, right):
        return [[[(a * b, fa + fb) for i in range(3) for a, fa in left[r][i] for b, fb in right[i][c]]
                 for c in range(3)] for r in range(3)]

    product = elementary(order[0], 1)
    for k, axis in enumerate(order[1:], start=2):
        product = multiply(product, elementary(axis, k))

    def text(terms) -> str:
        if not terms:
            return "0.0"
        parts = []
        for index, (sign, factors) in enumerate(terms):
            body = " * ".join(factors) if factors else "1.0"
            parts.append(("-" if sign < 0 else "") + body if index == 0 else (" - " if sign < 0 else " + ") + body)
        return "".join(parts)

    return [[text(product[r][c]) for c in range(3)] for r in range(3)]


def _playback_context(table) -> dict[str, Any] | None:
    """The playback table as plain lists for TRJ_PlaybackTable (file name only, comment-safe)."""
    if table is None:
        return None
    name = str(table.source).replace("\\", "/").rsplit("/", 1)[-1].replace("(*", "( *").replace("*)", "* )")
    return {"knots": len(table.t), "t": [float(v) for v in table.t], "file": name,
            "poses": [float(v) for v in table.poses.ravel()], "slopes": [float(v) for v in table.slopes.ravel()]}


def render_pou(env: jinja2.Environment, template: str, context: dict[str, Any]) -> Pou:
    """Render ``st_templates/<template>.st.j2``; the POU is named after the template's file name."""
    name = pou_name(template)
    try:
        module = env.get_template(f"{template}.st.j2").make_module(context)
    except jinja2.TemplateError as error:
        raise RenderError(f"{template}.st.j2: {error}") from error
    exported = module.__dict__
    for key in ("kind", "header", "variables"):
        if key not in exported:
            raise RenderError(f"{template}.st.j2 does not set '{key}'")
    body = str(module).strip("\n")
    return Pou(
        name=name,
        kind=exported["kind"],
        return_type=exported.get("return_type"),
        header=str(exported["header"]).strip("\n"),
        variables=tuple(exported["variables"]),
        body=body + "\n" if body else "",
    )


def render_program(config: PlatformConfig | None = None, options: RenderOptions | None = None) -> RenderedProgram:
    """Render every POU of :data:`POU_TEMPLATES` for ``config`` (default: the study's platform)."""
    config = config if config is not None else PlatformConfig.default()
    options = options if options is not None else RenderOptions()
    templates = program_templates(config)
    env = make_environment()
    context = template_context(config, options)
    if options.playback is not None:
        # Before the controller, which plays the table (dependency order).
        at = templates.index(PLAYBACK_CALLER) if PLAYBACK_CALLER in templates else len(templates)
        templates = templates[:at] + PLAYBACK_TEMPLATES + templates[at:]
    if options.tests:
        from stgen.benches import bench_vectors

        context["bench"] = bench_vectors(config)
        templates += TEST_BENCH_TEMPLATES
    pous = tuple(render_pou(env, template, context) for template in templates)
    if not options.tests:
        return RenderedProgram(pous)
    return RenderedProgram(pous, env.get_template(f"{BENCH_TEST_TEMPLATE}.st.j2").render(context))
