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
    [platform]   actuator ("linear" | "crank"), base ("fixed" | "moving"),
                 base_rotation, platform_rotation (rotation order, "ZYX" | "XYZ" | ...)
    [crank]      crank_length, rod_length (mm), gear_ratio, plane_angle_deg[6],
                 branch[6] (+1 | -1), angle_min_deg, angle_max_deg (docs/mathematics.md section 6.1)
    [joints]     universal_max_deg, spherical_tilt_max_deg (docs/mathematics.md section 6.2; absent: not checked)

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
_LEGS = "legs"  # six finite numbers, one per leg
_BRANCHES = "branches"  # six values, each +1 or -1
_OPTIONAL_POSITIVE = "optional-positive"  # absent (None) or > 0


def _spec(default: Any, rule: str, doc: str, within: tuple[float, float, str] | None = None) -> Any:
    """A dataclass field with its validation rule, a one-line description and its allowed range.

    ``within`` = (low, high, unit), both ends included: a value that is a
    valid number but absurd for the job (a 1 µs task period that would make
    the demo allocate gigabytes, an iteration count the generated INT cannot
    hold) is refused with the range in the message.
    """
    return field(default=default, metadata={"rule": rule, "doc": doc, "within": within})


def _check_within(key: str, number: float, within: tuple[float, float, str] | None) -> None:
    if within is None:
        return
    low, high, unit = within
    if not low <= number <= high:
        unit = f" {unit}" if unit else ""
        raise ConfigError(f"must lie in [{low:g}, {high:g}]{unit}, got {number:g}", key=key)


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


def _check_legs(key: str, value: Any) -> tuple[float, ...]:
    if not isinstance(value, (list, tuple)) or len(value) != 6:
        raise ConfigError(f"must be an array of 6 numbers (one per leg), got {value!r}", key=key)
    return tuple(_check_real(f"{key}[{index}]", item, _FINITE) for index, item in enumerate(value))


def _check_branches(key: str, value: Any) -> tuple[int, ...]:
    if not isinstance(value, (list, tuple)) or len(value) != 6:
        raise ConfigError(f"must be an array of 6 values +1 or -1 (one per leg), got {value!r}", key=key)
    for index, item in enumerate(value):
        if isinstance(item, bool) or item not in (1, -1):
            raise ConfigError(f"must be +1 or -1, got {item!r}", key=f"{key}[{index}]")
    return tuple(int(item) for item in value)


def _check_choice(key: str, value: Any, choices: tuple[str, ...]) -> str:
    if not isinstance(value, str) or value not in choices:
        raise ConfigError(f"must be one of {', '.join(repr(c) for c in choices)}, got {value!r}", key=key)
    return value


def _validate_fields(section: Any) -> None:
    """Check and normalise (int → float, list → tuple) every field of a section dataclass."""
    for spec in fields(section):
        key = f"{section.SECTION}.{spec.name}"
        value = getattr(section, spec.name)
        rule = spec.metadata["rule"]
        within = spec.metadata.get("within")
        if isinstance(rule, tuple):  # a choice among strings
            checked: Any = _check_choice(key, value, rule)
        elif rule == _LEGS:
            checked = _check_legs(key, value)
        elif rule == _BRANCHES:
            checked = _check_branches(key, value)
        elif rule == _OPTIONAL_POSITIVE:
            checked = None if value is None else _check_real(key, value, _POSITIVE)
            if checked is not None:
                _check_within(key, checked, within)
        elif rule == _COUNT:
            checked = _check_count(key, value)
            _check_within(key, checked, within)
        elif rule == _POSE:
            checked = _check_pose(key, value)
            for index, number in enumerate(checked):
                _check_within(f"{key}[{index}]", number, within)
        else:
            checked = _check_real(key, value, rule)
            _check_within(key, checked, within)
        object.__setattr__(section, spec.name, checked)


#: Ranges shared by several keys: lengths of the mechanism, offsets and positions, angles.
_MM_SIZE = (1.0, 1e5, "mm")
_MM_OFFSET = (-1e5, 1e5, "mm")
_DEGREES = (-360.0, 360.0, "degrees")

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

    rb: float = _spec(470.45, _POSITIVE, "rb: radius of the base joint circle, mm", _MM_SIZE)
    rp: float = _spec(388.95, _POSITIVE, "rp: radius of the platform joint circle, mm", _MM_SIZE)
    h0: float = _spec(1374.0, _POSITIVE, "h0: centre-to-centre height at the home pose, mm", _MM_SIZE)
    l0: float = _spec(1192.63, _POSITIVE, "l0: length of a fully retracted cylinder, mm", _MM_SIZE)
    hb: float = _spec(95.0, _FINITE, "hb: height of the universal-joint centres above the base, mm", _MM_OFFSET)
    hp: float = _spec(-115.0, _FINITE, "hp: height of the spherical-joint centres in the platform frame, mm",
                      _MM_OFFSET)
    phi_b_deg: float = _spec(24.07, _FINITE, "φb: angle between the two joints of a base pair, degrees", _DEGREES)
    phi_p_deg: float = _spec(103.66, _FINITE, "φp: angle between the two joints of a platform pair, degrees", _DEGREES)

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

    min: float = _spec(0.0, _FINITE, "lower end of the usable cylinder travel, mm", _MM_OFFSET)
    max: float = _spec(600.0, _FINITE, "upper end of the usable cylinder travel, mm", _MM_OFFSET)

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
    move at most 0.25 mm per scan. On a crank platform (docs/mathematics.md section 6.1) the
    actuator is the crank: the same keys in degrees/s and degrees/s².
    """

    SECTION: ClassVar[str] = "actuator"

    max_velocity: float = _spec(250.0, _POSITIVE, "largest cylinder speed, mm/s", (0.1, 1e5, "mm/s"))
    max_acceleration: float = _spec(2500.0, _POSITIVE, "largest cylinder acceleration, mm/s²", (1.0, 1e7, "mm/s²"))


@dataclass(frozen=True)
class TrajectoryConfig(_Section):
    """Limits for planned motion of the platform pose (docs/mathematics.md section 4, cycloidal duration).

    Linear limits apply to x, y, z; angular limits to α, β, γ. Defaults (chosen
    to keep the legs well inside :class:`ActuatorConfig`): 100 mm/s,
    500 mm/s², 5000 mm/s³ and 10 °/s, 50 °/s², 500 °/s³.
    """

    SECTION: ClassVar[str] = "trajectory"

    linear_velocity: float = _spec(100.0, _POSITIVE, "largest speed of x, y, z, mm/s", (5.0, 1e4, "mm/s"))
    linear_acceleration: float = _spec(500.0, _POSITIVE, "largest acceleration of x, y, z, mm/s²", (5.0, 1e6, "mm/s²"))
    linear_jerk: float = _spec(5000.0, _POSITIVE, "largest jerk of x, y, z, mm/s³", (5.0, 1e8, "mm/s³"))
    angular_velocity: float = _spec(10.0, _POSITIVE, "largest rate of α, β, γ, deg/s", (0.5, 1e3, "deg/s"))
    angular_acceleration: float = _spec(50.0, _POSITIVE, "largest angular acceleration, deg/s²",
                                        (0.5, 1e5, "deg/s²"))
    angular_jerk: float = _spec(500.0, _POSITIVE, "largest angular jerk, deg/s³", (0.5, 1e7, "deg/s³"))


@dataclass(frozen=True)
class TaskConfig(_Section):
    """The PLC primary task (docs/mathematics.md section 5): period in seconds, default 1 ms.

    Allowed 0.5 ms to 100 ms: 500 µs is the shortest primary period OMRON
    names for the NJ series (myOMRON knowledge base article 1415, "NJ-series
    task execution", https://www.myomron.com/index.php?action=kb&article=1415;
    the list of settable periods is in W501, not at hand); 100 ms is a bound
    of ours, far above any motion task, that keeps the demo's arrays small.
    """

    SECTION: ClassVar[str] = "task"

    period_s: float = _spec(0.001, _POSITIVE, "primary task period, s", (0.0005, 0.1, "s"))


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
    NJ501, so 4 keep one call near 0.2 ms; at most 100, ≈ 5 ms, already more
    than a primary period); ``max_iterations`` ends in "not converged" (at
    most 32767: the generated FB holds it in an INT). ``start_pose`` is p_NR.
    """

    SECTION: ClassVar[str] = "solver"

    tolerance: float = _spec(0.01, _POSITIVE, "Klim: convergence bound on every |Δk|, mm and rad",
                             (1e-12, 10.0, "mm and rad"))
    singularity_threshold: float = _spec(1e21, _NON_NEGATIVE, "Ktol: |det J| at or below this is singular")
    iterations_per_scan: int = _spec(4, _COUNT, "Newton-Raphson iterations in one FB call", (1, 100, ""))
    max_iterations: int = _spec(50, _COUNT, "total iterations before 'not converged'", (1, 32767, ""))
    start_pose: tuple[float, ...] = _spec(STUDY_START_POSE, _POSE, "p_NR: start pose, mm and degrees", _MM_OFFSET)


#: Tait-Bryan rotation orders: "ZYX" is R = Rz(a4)·Ry(a5)·Rx(a6), the pose's
#: three angles taken in the order of the factors (docs/mathematics.md section 1: α about Z, β about Y, γ about X).
ROTATION_ORDERS = ("ZYX", "XYZ", "XZY", "YXZ", "YZX", "ZXY")
ACTUATOR_KINDS = ("linear", "crank")
BASE_KINDS = ("fixed", "moving")


@dataclass(frozen=True)
class PlatformKindConfig(_Section):
    """Which platform: actuator kind, fixed or moving base, rotation order of each platform (docs/mathematics.md section 6).

    ``actuator``: ``linear`` (six cylinders, docs/mathematics.md sections 1-3) or ``crank`` (six
    rotary cranks with rods, docs/mathematics.md section 6.1, parameters in ``[crank]``).
    ``base``: ``fixed``, or ``moving`` (docs/mathematics.md section 6.2: the base pose is an input,
    the upper pose is held in the world frame).
    ``base_rotation`` / ``platform_rotation``: the order of the factors of RB
    and RU; the three angles of a pose are taken in that order, so the
    default ``ZYX`` is docs/mathematics.md section 1's R = Rz(α)·Ry(β)·Rx(γ).
    """

    SECTION: ClassVar[str] = "platform"

    actuator: str = _spec("linear", ACTUATOR_KINDS, "actuator kind: linear or crank")
    base: str = _spec("fixed", BASE_KINDS, "base: fixed or moving")
    base_rotation: str = _spec("ZYX", ROTATION_ORDERS, "rotation order of the base RB")
    platform_rotation: str = _spec("ZYX", ROTATION_ORDERS, "rotation order of the upper platform RU")


@dataclass(frozen=True)
class CrankConfig(_Section):
    """Rotary crank actuators, docs/mathematics.md section 6.1 (used when ``platform.actuator = "crank"``).

    Leg i: the motor shaft sits at the base joint Bi of ``[geometry]``; its
    crank of length ``crank_length`` turns in the vertical plane through Bi
    with horizontal direction (cos φi, sin φi, 0), φi = ``plane_angle_deg[i]``
    (from the base x axis); the crank angle θi is measured from that horizontal
    direction towards +z, so the tip is Ai = Bi + a·(cos θi cos φi,
    cos θi sin φi, sin θi). A rod of length ``rod_length`` joins Ai to the
    platform joint Pi. ``branch[i]`` = σi = ±1 picks the IK solution
    θi = atan2(Δz, M) + σi·acos(H/(2aρ)).

    Crank-angle limits: one convention for all legs, the one above. The study's
    odd/even legs (its eqs 4-9) describe the same crank with φ + 180° and
    θ → 180° − θ, so its 50..230° on a leg written in the other parity is
    −50..130° in that leg's φ; configure each leg's ``plane_angle_deg`` in the
    parity where its range reads ``angle_min_deg..angle_max_deg``.

    Defaults: the study's mechanism (crank 250 mm, rod 105 + 835 = 940 mm,
    gearbox 32.41, limits 50..230°); the plane angles and branches are an
    assumption (the study does not give the joint layout), see
    ``examples/crank_platform.toml``.
    """

    SECTION: ClassVar[str] = "crank"

    crank_length: float = _spec(250.0, _POSITIVE, "a: crank length, mm")
    rod_length: float = _spec(940.0, _POSITIVE, "s: rod length, mm")
    gear_ratio: float = _spec(32.41, _POSITIVE, "gearbox ratio, motor turns per crank turn")
    plane_angle_deg: tuple[float, ...] = _spec(
        (317.965, 162.035, 77.965, 282.035, 197.965, 42.035), _LEGS, "φi: horizontal direction of each crank plane, degrees"
    )
    branch: tuple[int, ...] = _spec((1, 1, 1, 1, 1, 1), _BRANCHES, "σi: IK branch of each leg, +1 or -1")
    angle_min_deg: float = _spec(50.0, _FINITE, "lowest crank angle θi, degrees")
    angle_max_deg: float = _spec(230.0, _FINITE, "highest crank angle θi, degrees")

    def _check_rules(self) -> None:
        if not self.angle_min_deg < self.angle_max_deg:
            raise ConfigError(
                f"must be less than crank.angle_max_deg, got {self.angle_min_deg} >= {self.angle_max_deg}",
                key=f"{self.SECTION}.angle_min_deg",
            )


@dataclass(frozen=True)
class JointLimitsConfig(_Section):
    """Joint-angle limits, docs/mathematics.md section 6.2; a key left out is not checked (the default platform checks none).

    ``universal_max_deg`` bounds |γi| and |ψi|, the two universal-joint angles
    at the base; ``spherical_tilt_max_deg`` bounds the angle between a leg and
    the upper platform's normal.
    """

    SECTION: ClassVar[str] = "joints"

    universal_max_deg: float | None = _spec(None, _OPTIONAL_POSITIVE, "bound on |γi| and |ψi|, degrees")
    spherical_tilt_max_deg: float | None = _spec(None, _OPTIONAL_POSITIVE, "bound on the spherical tilt, degrees")

    @property
    def any(self) -> bool:
        """Whether any joint limit is checked."""
        return self.universal_max_deg is not None or self.spherical_tilt_max_deg is not None


# --------------------------------------------------------------------------- the whole platform

_SECTIONS: dict[str, type] = {
    "geometry": GeometryConfig,
    "stroke": StrokeConfig,
    "actuator": ActuatorConfig,
    "trajectory": TrajectoryConfig,
    "task": TaskConfig,
    "solver": SolverConfig,
    "platform": PlatformKindConfig,
    "crank": CrankConfig,
    "joints": JointLimitsConfig,
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
    platform: PlatformKindConfig = field(default_factory=PlatformKindConfig)
    crank: CrankConfig = field(default_factory=CrankConfig)
    joints: JointLimitsConfig = field(default_factory=JointLimitsConfig)

    @property
    def is_crank(self) -> bool:
        return self.platform.actuator == "crank"

    @property
    def moving_base(self) -> bool:
        return self.platform.base == "moving"

    @property
    def is_default_kind(self) -> bool:
        """Linear actuators, fixed base, docs/mathematics.md section 1's rotation, no joint limits: the NJ study's kind."""
        return (
            self.platform == PlatformKindConfig() and not self.joints.any
        )

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
    """The home pose a = 0 must be reachable (docs/mathematics.md sections 2, 6.1, 6.2) and not singular (docs/mathematics.md section 3)."""
    import numpy as np

    from stgen.reference.linalg import leibniz_det

    if config.is_crank and config.joints.any:
        raise ConfigError("joint limits are checked for linear legs only; remove [joints] "
                          "or set platform.actuator = \"linear\"", key="joints")
    home = np.zeros(6)
    if config.is_default_kind:
        from stgen.reference.kinematics import inverse_kinematics, jacobian

        ik = inverse_kinematics(config.geometry, home, config.stroke)
        outside = [leg + 1 for leg in range(6) if not ik.in_stroke[leg]]
        if outside:
            legs = ", ".join(f"q{leg} = {ik.positions[leg - 1]:.4f} mm" for leg in outside)
            raise ConfigError(
                f"the home pose puts {legs} outside the stroke "
                f"[{config.stroke.min}, {config.stroke.max}] mm (check geometry.h0, geometry.l0 and stroke)",
                key="geometry",
            )
        matrix = jacobian(config.geometry, home)
    else:
        from stgen.reference.crank import crank_inverse_kinematics
        from stgen.reference.feasibility import check_pose
        from stgen.reference.variant_fk import VariantModel

        report = check_pose(config, home)
        if not report.feasible:
            raise ConfigError("the home pose is not feasible: "
                              + "; ".join(str(v) for v in report.violations), key="geometry")
        measured = (crank_inverse_kinematics(config, home).angles_deg if config.is_crank
                    else np.zeros(6))
        model = VariantModel(config, measured)
        matrix = model.jacobian(home)
    determinant = abs(float(leibniz_det(matrix)))
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
    except RecursionError:  # tomllib recurses once per level of nested arrays or inline tables
        raise ConfigError("invalid TOML: arrays or inline tables nested too deeply", source=source) from None
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
    from st_runtime.input_files import MAX_TOML_BYTES, InputFileError, read_bounded

    try:
        data = read_bounded(path, MAX_TOML_BYTES)  # a regular file only: a FIFO or /dev/zero never hangs
    except InputFileError as error:
        raise ConfigError(error.reason, source=str(path)) from None
    return parse_config(decode_utf8(data, str(path)), source=str(path))


def decode_utf8(data: bytes, source: str) -> str:
    """The text of a TOML file (TOML is UTF-8); a bad byte is a ConfigError at its line and column."""
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as error:
        line = data.count(b"\n", 0, error.start) + 1
        column = error.start - (data.rfind(b"\n", 0, error.start) + 1) + 1
        raise ConfigError(f"not UTF-8 text: byte 0x{data[error.start]:02X} cannot be decoded (TOML is UTF-8)",
                          source=source, line=line, column=column) from None
