"""Platform configuration: a TOML file read into frozen, validated dataclasses.

Every section and key, with its default (docs/mathematics.md section 1, table for the geometry)::

    [geometry]   rb, rp, h0, l0, hb, hp (mm), phi_b_deg, phi_p_deg (degrees)
    [stroke]     min, max (mm)
    [actuator]   max_velocity (mm/s), max_acceleration (mm/s²)
    [trajectory] linear_velocity, linear_acceleration, linear_jerk (mm/s, mm/s², mm/s³)
                 angular_velocity, angular_acceleration, angular_jerk (deg/s, deg/s², deg/s³)
    [task]       period_s (s)
    [solver]     tolerance (Klim), singularity_threshold (Ktol), iterations_per_scan,
                 max_iterations, start_pose (p_NR: mm and degrees)

``examples/default_platform.toml`` lists them all with comments. Every
missing key takes its default; an unknown key, a wrong type or a broken rule
raises :class:`ConfigError`, whose message names the file, the line and
column where the key is written, the dotted key (``geometry.rb``) and the
rule: ``platform.toml:7:1: geometry.rb: must be > 0, got -1.0``. Constructing the dataclasses directly runs the
same checks.
"""

from __future__ import annotations

import math
import re
import tomllib
from dataclasses import dataclass, field, fields
from pathlib import Path
from typing import Any, ClassVar, Mapping

#: Two joints closer than this (mm) count as coincident.
MIN_JOINT_SEPARATION_MM = 1e-3


class ConfigError(ValueError):
    """A configuration that cannot be used.

    ``key`` is the dotted key at fault (``None`` for a syntax error),
    ``source`` the file (``None`` when not read from a file), ``line`` and
    ``column`` the position of a TOML syntax error.
    """

    def __init__(
        self,
        message: str,
        *,
        key: str | None = None,
        source: str | None = None,
        line: int | None = None,
        column: int | None = None,
    ) -> None:
        self.message = message
        self.key = key
        self.source = source
        self.line = line
        self.column = column
        super().__init__(self._render())

    def _render(self) -> str:
        where = ""
        if self.source is not None:
            where = self.source
            if self.line is not None:
                where += f":{self.line}:{self.column}"
            where += ": "
        what = f"{self.key}: " if self.key else ""
        return f"{where}{what}{self.message}"

    def with_source(self, source: str, position: tuple[int, int] | None = None) -> "ConfigError":
        """The same error, attributed to ``source`` (at ``position`` = (line, column) when given)."""
        line, column = position if position is not None else (self.line, self.column)
        return ConfigError(self.message, key=self.key, source=source, line=line, column=column)


# --------------------------------------------------------------------------- field rules

_POSITIVE = "positive"
_NON_NEGATIVE = "non-negative"
_FINITE = "finite"
_COUNT = "count"  # an integer >= 1
_POSE = "pose"  # six finite numbers


def _spec(default: Any, rule: str, doc: str) -> Any:
    """A dataclass field with its validation rule and a one-line description."""
    return field(default=default, metadata={"rule": rule, "doc": doc})


def _is_number(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _check_real(key: str, value: Any, rule: str) -> float:
    if not _is_number(value):
        raise ConfigError(f"must be a number, got {type(value).__name__} {value!r}", key=key)
    number = float(value)
    if not math.isfinite(number):
        raise ConfigError(f"must be finite, got {number}", key=key)
    if rule == _POSITIVE and not number > 0.0:
        raise ConfigError(f"must be > 0, got {number}", key=key)
    if rule == _NON_NEGATIVE and not number >= 0.0:
        raise ConfigError(f"must be >= 0, got {number}", key=key)
    return number


def _check_count(key: str, value: Any) -> int:
    if not isinstance(value, int) or isinstance(value, bool):
        raise ConfigError(f"must be an integer, got {type(value).__name__} {value!r}", key=key)
    if value < 1:
        raise ConfigError(f"must be >= 1, got {value}", key=key)
    return value


def _check_pose(key: str, value: Any) -> tuple[float, ...]:
    if not isinstance(value, (list, tuple)) or len(value) != 6:
        raise ConfigError(f"must be an array of 6 numbers (x, y, z, alpha, beta, gamma), got {value!r}", key=key)
    return tuple(_check_real(f"{key}[{index}]", item, _FINITE) for index, item in enumerate(value))


def _validate_fields(section: Any) -> None:
    """Check and normalise (int → float, list → tuple) every field of a section dataclass."""
    for spec in fields(section):
        key = f"{section.SECTION}.{spec.name}"
        value = getattr(section, spec.name)
        rule = spec.metadata["rule"]
        if rule == _COUNT:
            checked: Any = _check_count(key, value)
        elif rule == _POSE:
            checked = _check_pose(key, value)
        else:
            checked = _check_real(key, value, rule)
        object.__setattr__(section, spec.name, checked)


# --------------------------------------------------------------------------- sections


class _Section:
    """Mixin for the section dataclasses: field rules first, then the section's own rules."""

    SECTION: ClassVar[str]

    def __post_init__(self) -> None:
        _validate_fields(self)
        self._check_rules()

    def _check_rules(self) -> None:
        """Rules across the section's fields; none by default."""


@dataclass(frozen=True)
class GeometryConfig(_Section):
    """6-6 UPS geometry, docs/mathematics.md section 1 and table 1 (mm, degrees)."""

    SECTION: ClassVar[str] = "geometry"

    rb: float = _spec(470.45, _POSITIVE, "rb: radius of the base joint circle, mm")
    rp: float = _spec(388.95, _POSITIVE, "rp: radius of the platform joint circle, mm")
    h0: float = _spec(1374.0, _POSITIVE, "h0: centre-to-centre height at the home pose, mm")
    l0: float = _spec(1192.63, _POSITIVE, "l0: length of a fully retracted cylinder, mm")
    hb: float = _spec(95.0, _FINITE, "hb: height of the universal-joint centres above the base, mm")
    hp: float = _spec(-115.0, _FINITE, "hp: height of the spherical-joint centres in the platform frame, mm")
    phi_b_deg: float = _spec(24.07, _FINITE, "φb: angle between the two joints of a base pair, degrees")
    phi_p_deg: float = _spec(103.66, _FINITE, "φp: angle between the two joints of a platform pair, degrees")

    def _check_rules(self) -> None:
        # Imported here: the reference depends on this module for its data types.
        from stgen.reference.geometry import base_joints, platform_joints

        for name, joints in (("phi_b_deg", base_joints(self)), ("phi_p_deg", platform_joints(self))):
            pair = _closest_pair(joints)
            if pair is not None:
                first, second = pair
                raise ConfigError(
                    f"joints {first + 1} and {second + 1} coincide (closer than "
                    f"{MIN_JOINT_SEPARATION_MM} mm); the pair angle must lie strictly between "
                    f"0 and 120 degrees (modulo 360), got {getattr(self, name)}",
                    key=f"{self.SECTION}.{name}",
                )


def _closest_pair(joints) -> tuple[int, int] | None:
    """The first pair of joints closer than :data:`MIN_JOINT_SEPARATION_MM`, if any."""
    for first in range(len(joints)):
        for second in range(first + 1, len(joints)):
            gap = math.dist(joints[first], joints[second])
            if gap < MIN_JOINT_SEPARATION_MM:
                return first, second
    return None


@dataclass(frozen=True)
class StrokeConfig(_Section):
    """Usable cylinder travel qi, mm (docs/mathematics.md section 1, table: 0 .. 600)."""

    SECTION: ClassVar[str] = "stroke"

    min: float = _spec(0.0, _FINITE, "lower end of the usable cylinder travel, mm")
    max: float = _spec(600.0, _FINITE, "upper end of the usable cylinder travel, mm")

    def _check_rules(self) -> None:
        if not self.min < self.max:
            raise ConfigError(
                f"must be less than stroke.max, got min = {self.min} >= max = {self.max}",
                key=f"{self.SECTION}.min",
            )


@dataclass(frozen=True)
class ActuatorConfig(_Section):
    """Limits of one electric cylinder.

    Defaults (not in the study; a typical ball-screw cylinder of this size):
    250 mm/s and 2500 mm/s². At the 1 ms default period a cylinder may then
    move at most 0.25 mm per scan.
    """

    SECTION: ClassVar[str] = "actuator"

    max_velocity: float = _spec(250.0, _POSITIVE, "largest cylinder speed, mm/s")
    max_acceleration: float = _spec(2500.0, _POSITIVE, "largest cylinder acceleration, mm/s²")


@dataclass(frozen=True)
class TrajectoryConfig(_Section):
    """Limits for planned motion of the platform pose (docs/mathematics.md section 4, cycloidal duration).

    Linear limits apply to x, y, z; angular limits to α, β, γ. Defaults (chosen
    to keep the legs well inside :class:`ActuatorConfig`): 100 mm/s,
    500 mm/s², 5000 mm/s³ and 10 °/s, 50 °/s², 500 °/s³.
    """

    SECTION: ClassVar[str] = "trajectory"

    linear_velocity: float = _spec(100.0, _POSITIVE, "largest speed of x, y, z, mm/s")
    linear_acceleration: float = _spec(500.0, _POSITIVE, "largest acceleration of x, y, z, mm/s²")
    linear_jerk: float = _spec(5000.0, _POSITIVE, "largest jerk of x, y, z, mm/s³")
    angular_velocity: float = _spec(10.0, _POSITIVE, "largest rate of α, β, γ, deg/s")
    angular_acceleration: float = _spec(50.0, _POSITIVE, "largest angular acceleration, deg/s²")
    angular_jerk: float = _spec(500.0, _POSITIVE, "largest angular jerk, deg/s³")


@dataclass(frozen=True)
class TaskConfig(_Section):
    """The PLC primary task (docs/mathematics.md section 5): period in seconds, default 1 ms."""

    SECTION: ClassVar[str] = "task"

    period_s: float = _spec(0.001, _POSITIVE, "primary task period, s")


#: p_NR, the study's Newton–Raphson start pose (mm and degrees), docs/mathematics.md section 3.
STUDY_START_POSE = (60.25, 85.0, 230.7, 0.0, 0.0, 3.75)


@dataclass(frozen=True)
class SolverConfig(_Section):
    """Newton–Raphson forward kinematics, docs/mathematics.md section 3.

    ``tolerance`` is Klim (mm and rad: converged when every |Δk| < Klim).  It
    drives the NumPy reference and `stgen verify`'s check at the study's Klim;
    the generated `SP_ForwardKinematics.Tolerance` keeps the study's 0.01 as
    its interface default (issue 4 fixes it), callers pass another bound.
    ``singularity_threshold`` is Ktol: |det J| <= Ktol is "singular". det J
    is not scale-free (J rows are 2·Li ≈ 2300 mm for x, y, z and ≈ 1e6 mm²
    for the angles): with the default geometry |det J| is ≈ 8.8e27 at the home
    pose and 1e28 nearby, and the rounding error of its 720 products is ≈ 5e12.
    The default Ktol = 1e21, about a millionth of the home value, lies far
    above the rounding noise.
    ``iterations_per_scan`` bounds one FB call (≈ 49.5 µs per iteration on the
    NJ501, so 4 keep one call near 0.2 ms); ``max_iterations`` ends in
    "not converged". ``start_pose`` is p_NR.
    """

    SECTION: ClassVar[str] = "solver"

    tolerance: float = _spec(0.01, _POSITIVE, "Klim: convergence bound on every |Δk|, mm and rad")
    singularity_threshold: float = _spec(1e21, _NON_NEGATIVE, "Ktol: |det J| at or below this is singular")
    iterations_per_scan: int = _spec(4, _COUNT, "Newton-Raphson iterations in one FB call")
    max_iterations: int = _spec(50, _COUNT, "total iterations before 'not converged'")
    start_pose: tuple[float, ...] = _spec(STUDY_START_POSE, _POSE, "p_NR: start pose, mm and degrees")


# --------------------------------------------------------------------------- the whole platform

_SECTIONS: dict[str, type] = {
    "geometry": GeometryConfig,
    "stroke": StrokeConfig,
    "actuator": ActuatorConfig,
    "trajectory": TrajectoryConfig,
    "task": TaskConfig,
    "solver": SolverConfig,
}


@dataclass(frozen=True)
class PlatformConfig:
    """Everything ``stgen`` needs to know about one platform."""

    geometry: GeometryConfig = field(default_factory=GeometryConfig)
    stroke: StrokeConfig = field(default_factory=StrokeConfig)
    actuator: ActuatorConfig = field(default_factory=ActuatorConfig)
    trajectory: TrajectoryConfig = field(default_factory=TrajectoryConfig)
    task: TaskConfig = field(default_factory=TaskConfig)
    solver: SolverConfig = field(default_factory=SolverConfig)

    def __post_init__(self) -> None:
        for name, cls in _SECTIONS.items():
            if not isinstance(getattr(self, name), cls):
                raise ConfigError(f"must be a {cls.__name__}", key=name)
        _check_home_pose(self)

    @classmethod
    def default(cls) -> "PlatformConfig":
        """The study's platform (docs/mathematics.md section 1, table) with the documented default limits."""
        return cls()


def _check_home_pose(config: PlatformConfig) -> None:
    """The home pose a = 0 must be reachable (docs/mathematics.md section 2) and not singular (docs/mathematics.md section 3)."""
    import numpy as np

    from stgen.reference.kinematics import inverse_kinematics, jacobian
    from stgen.reference.linalg import leibniz_det

    home = np.zeros(6)
    ik = inverse_kinematics(config.geometry, home, config.stroke)
    outside = [leg + 1 for leg in range(6) if not ik.in_stroke[leg]]
    if outside:
        legs = ", ".join(f"q{leg} = {ik.positions[leg - 1]:.4f} mm" for leg in outside)
        raise ConfigError(
            f"the home pose puts {legs} outside the stroke "
            f"[{config.stroke.min}, {config.stroke.max}] mm (check geometry.h0, geometry.l0 and stroke)",
            key="geometry",
        )
    determinant = abs(float(leibniz_det(jacobian(config.geometry, home))))
    if not determinant > config.solver.singularity_threshold:
        raise ConfigError(
            f"the home pose is singular: |det J| = {determinant:.6g} <= "
            f"solver.singularity_threshold = {config.solver.singularity_threshold:.6g}",
            key="geometry",
        )


# --------------------------------------------------------------------------- reading


def config_from_mapping(data: Mapping[str, Any]) -> PlatformConfig:
    """Build a :class:`PlatformConfig` from parsed TOML (a dict of section tables)."""
    sections: dict[str, Any] = {}
    for name, table in data.items():
        cls = _SECTIONS.get(name)
        if cls is None:
            raise ConfigError(f"unknown key; expected one of {', '.join(_SECTIONS)}", key=name)
        if not isinstance(table, Mapping):
            raise ConfigError(f"must be a table [{name}], got {type(table).__name__}", key=name)
        known = {spec.name for spec in fields(cls)}
        for key in table:
            if key not in known:
                raise ConfigError(
                    f"unknown key; expected one of {', '.join(sorted(known))}", key=f"{name}.{key}"
                )
        sections[name] = cls(**table)
    return PlatformConfig(**sections)


_TOML_POSITION = re.compile(r"\s*\(at line (\d+), column (\d+)\)\s*$")


def parse_config(text: str, source: str = "<string>") -> PlatformConfig:
    """Parse TOML text; errors name ``source`` (and line and column for syntax errors)."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        message = str(error)
        match = _TOML_POSITION.search(message)
        if match is None:
            raise ConfigError(f"invalid TOML: {message}", source=source) from error
        raise ConfigError(
            f"invalid TOML: {message[: match.start()]}",
            source=source,
            line=int(match.group(1)),
            column=int(match.group(2)),
        ) from error
    try:
        return config_from_mapping(data)
    except ConfigError as error:
        position = key_position(text, error.key) if error.key else None
        raise error.with_source(source, position) from None


_TABLE_HEADER = re.compile(r"^\s*\[\s*([A-Za-z0-9_-]+)\s*\]\s*(?:#.*)?$")
_KEY_LINE = re.compile(r"^(\s*)([A-Za-z0-9_-]+)\s*=")


def key_position(text: str, key: str) -> tuple[int, int] | None:
    """(line, column), 1-based, where ``key`` is written in the TOML ``text``.

    ``key`` is a dotted key as :class:`ConfigError` names it: ``section`` (the
    ``[section]`` header), ``section.name`` or ``section.name[index]`` (the
    line that assigns ``name`` inside ``[section]``). ``None`` when the key is
    not written in that plain form (a default that broke a rule, say).
    """
    section, _, name = key.partition(".")
    name = name.split("[", 1)[0]
    current = None
    for number, line in enumerate(text.splitlines(), 1):
        header = _TABLE_HEADER.match(line)
        if header:
            current = header.group(1)
            if current == section and not name:
                return number, line.index("[") + 1
            continue
        assignment = _KEY_LINE.match(line)
        if assignment is None:
            continue
        if (name and current == section and assignment.group(2) == name) or (
            not name and current is None and assignment.group(2) == section
        ):
            return number, len(assignment.group(1)) + 1
    return None


def load_config(path: str | Path | None = None) -> PlatformConfig:
    """Read a platform TOML file; ``None`` gives :meth:`PlatformConfig.default`."""
    if path is None:
        return PlatformConfig.default()
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as error:
        raise ConfigError(f"cannot read: {error.strerror}", source=str(path)) from error
    return parse_config(text, source=str(path))
