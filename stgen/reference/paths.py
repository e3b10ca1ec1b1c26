"""Parametric paths (docs/mathematics.md section 6.3): four planar curves, a time law, and the shortest duration.

The platform centre follows (xc + x(φ), yc + y(φ), z0) at a fixed orientation
(α, β, γ) of docs/mathematics.md section 1 (α about Z, β about Y, γ about X; the study's roll about
X is γ here, its pitch about Y is β). Curves, written as z(φ) = x + i·y:

    epitrochoid  z = (R + r)·e^{iφ} − d·e^{i k φ},   k = (R + r)/r
    epicycloid   the epitrochoid with d = r
    hypocycloid  z = (R − r)·e^{iφ} + r·e^{−i m φ},  m = (R − r)/r
    spiral       z = (a + bφ)·e^{iφ}                 (Archimedean, ρ = a + bφ)

so the n-th derivative in φ is analytic: (i)^n and (ik)^n, (−im)^n factors;
for the spiral z' = (b + iρ)e^{iφ}, z'' = (2ib − ρ)e^{iφ}, z''' = (−3b − iρ)e^{iφ}.

Time law φ(t) = φ_end·f(t/T), u = t/T in [0, 1]:

* ``blend`` (default): φ̇ rises from rest over the first fraction b of T by a
  cycloidal ramp f'(u) = Ω·(τ − sin 2πτ/2π), τ = u/b, runs uniform at
  Ω = 1/(1 − b), and falls back the same way: φ, φ̇ and φ̈ continuous, φ̈ = 0
  at both ends (the study's uniform law has a velocity step at both ends).
* ``cycloidal``: f(u) = u − sin(2πu)/(2π) (docs/mathematics.md section 4's profile in φ).

With the shape f fixed, pose and leg velocities scale with 1/T,
accelerations with 1/T² and pose jerks with 1/T³, so the shortest T keeping
docs/mathematics.md section 4's pose limits and the actuator limits is the largest of
V₁/v_max, √(A₁/a_max), ∛(J₁/j_max) over those quantities at T = 1, taken on
a dense sample of u (``PLAN_SAMPLES``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction

import numpy as np

from stgen.config import PlatformConfig
from stgen.reference.actuator_rates import ActuatorRates, actuator_rates
from stgen.reference.motion_limits import MotionCheck, check_motion

FAMILIES = ("epitrochoid", "epicycloid", "hypocycloid", "spiral")
LAWS = ("blend", "cycloidal")
TWO_PI = 2.0 * math.pi
#: Samples of u in [0, 1] on which the planner takes the extremes at T = 1 (end points included).
PLAN_SAMPLES = 20_001
#: Relative margin on the shortest T: a peak between two of those samples is higher than both by
#: about (π·n·Δu)²/8 for n oscillations over u (3e-7 for n = 10), so the samples at the task
#: period never see more than the limit.
PLAN_MARGIN = 1e-6


class PathError(ValueError):
    """A path specification that cannot be planned (message says which parameter and why)."""


@dataclass(frozen=True)
class PathSpec:
    """A curve with its placement, orientation and time law.

    ``R, r, d``: circles and pen distance (mm) of the trochoids; ``a, b``: spiral
    ρ = a + bφ (mm, mm/rad); ``phi_end``: last parameter value (rad; None closes a
    trochoid: 2π·q for R/r = p/q, and gives a spiral 3 turns); ``centre``
    (xc, yc, z0) in mm; ``orientation`` (α, β, γ) in degrees; ``law`` and
    ``blend`` (fraction of T per blend, 0 < b <= 0.5); ``duration``: None for the
    shortest, or a longer T in s.
    """

    family: str
    R: float = 60.0
    r: float = 20.0
    d: float = 30.0
    a: float = 0.0
    b: float = 5.0
    phi_end: float | None = None
    centre: tuple[float, float, float] = (0.0, 0.0, 240.0)
    orientation: tuple[float, float, float] = (0.0, 0.0, 0.0)
    law: str = "blend"
    blend: float = 0.1
    duration: float | None = None

    def __post_init__(self):
        if self.family not in FAMILIES:
            raise PathError(f"family: must be one of {', '.join(FAMILIES)}, got {self.family!r}")
        if self.law not in LAWS:
            raise PathError(f"law: must be one of {', '.join(LAWS)}, got {self.law!r}")
        if not 0.0 < self.blend <= 0.5:
            raise PathError(f"blend: must be in (0, 0.5], got {self.blend!r}")
        numbers = (self.R, self.r, self.d, self.a, self.b, *self.centre, *self.orientation)
        if not all(math.isfinite(v) for v in numbers):
            raise PathError("every parameter must be a finite number")
        if self.family != "spiral" and (self.R <= 0.0 or self.r <= 0.0):
            raise PathError(f"R and r: must be > 0, got R={self.R!r}, r={self.r!r}")
        if self.family == "hypocycloid" and self.r >= self.R:
            raise PathError(f"r: must be less than R for a hypocycloid, got r={self.r!r}, R={self.R!r}")
        if self.phi_end is not None and not (math.isfinite(self.phi_end) and self.phi_end > 0.0):
            raise PathError(f"phi_end: must be a finite number > 0, got {self.phi_end!r}")
        if self.duration is not None and not (math.isfinite(self.duration) and self.duration > 0.0):
            raise PathError(f"duration: must be a finite number > 0 s, got {self.duration!r}")

    @property
    def end(self) -> float:
        """φ_end in rad: given, or the closing value of a trochoid (2π·q for R/r = p/q), 3 turns of a spiral."""
        if self.phi_end is not None:
            return float(self.phi_end)
        if self.family == "spiral":
            return 3.0 * TWO_PI
        ratio = Fraction(self.R / self.r).limit_denominator(1000)
        return TWO_PI * ratio.denominator

    @property
    def pen(self) -> float:
        """Pen distance d: the epicycloid has d = r."""
        return self.r if self.family == "epicycloid" else self.d


def curve_derivatives(spec: PathSpec, phi, order: int) -> np.ndarray:
    """The ``order``-th derivative (0..3) of z(φ) = x + i·y in φ, complex array of φ's shape, mm/radⁿ."""
    phi = np.asarray(phi, dtype=float)
    if spec.family == "spiral":
        rho = spec.a + spec.b * phi
        factor = (rho + 0j, spec.b + 1j * rho, 2j * spec.b - rho, -3.0 * spec.b - 1j * rho)[order]
        return factor * np.exp(1j * phi)
    if spec.family == "hypocycloid":
        m = (spec.R - spec.r) / spec.r
        return (spec.R - spec.r) * 1j**order * np.exp(1j * phi) + spec.r * (-1j * m) ** order * np.exp(-1j * m * phi)
    k = (spec.R + spec.r) / spec.r
    return (spec.R + spec.r) * 1j**order * np.exp(1j * phi) - spec.pen * (1j * k) ** order * np.exp(1j * k * phi)


def time_law(spec: PathSpec, u) -> tuple[np.ndarray, ...]:
    """(f, f', f'', f''') of u = t/T clipped to [0, 1]; f(0) = 0, f(1) = 1."""
    u = np.clip(np.asarray(u, dtype=float), 0.0, 1.0)
    if spec.law == "cycloidal":
        s, c = np.sin(TWO_PI * u), np.cos(TWO_PI * u)
        return u - s / TWO_PI, 1.0 - c, TWO_PI * s, TWO_PI**2 * c
    b = spec.blend
    omega = 1.0 / (1.0 - b)
    mirrored = u > 0.5
    v = np.where(mirrored, 1.0 - u, u)                 # the end blend is the start blend mirrored
    tau = np.minimum(v / b, 1.0)
    s, c = np.sin(TWO_PI * tau), np.cos(TWO_PI * tau)
    in_blend = v < b
    f = np.where(in_blend, omega * b * (tau**2 / 2.0 + (c - 1.0) / TWO_PI**2), omega * (v - b / 2.0))
    f1 = np.where(in_blend, omega * (tau - s / TWO_PI), omega)
    f2 = np.where(in_blend, omega / b * (1.0 - c), 0.0)
    f3 = np.where(in_blend, omega / b**2 * TWO_PI * s, 0.0)
    sign = np.where(mirrored, -1.0, 1.0)
    return np.where(mirrored, 1.0 - f, f), f1, sign * f2, f3


@dataclass(frozen=True)
class PathSamples:
    """Poses and their derivatives at times ``t`` (``[n]``): ``poses, rates, accelerations, jerks`` ``[n, 6]``."""

    t: np.ndarray
    phi: np.ndarray
    poses: np.ndarray
    rates: np.ndarray
    accelerations: np.ndarray
    jerks: np.ndarray


def sample(spec: PathSpec, duration: float, t) -> PathSamples:
    """The path's pose (mm, deg) and its time derivatives at times ``t`` (s) for total time ``duration``."""
    t = np.asarray(t, dtype=float)
    f0, f1, f2, f3 = time_law(spec, t / duration)
    end = spec.end
    phi, dphi, ddphi, dddphi = end * f0, end * f1 / duration, end * f2 / duration**2, end * f3 / duration**3
    z0, z1, z2, z3 = (curve_derivatives(spec, phi, n) for n in range(4))
    velocity = z1 * dphi
    acceleration = z2 * dphi**2 + z1 * ddphi
    jerk = z3 * dphi**3 + 3.0 * z2 * dphi * ddphi + z1 * dddphi
    shape = t.shape + (6,)
    poses = np.zeros(shape)
    poses[..., 0] = spec.centre[0] + z0.real
    poses[..., 1] = spec.centre[1] + z0.imag
    poses[..., 2] = spec.centre[2]
    poses[..., 3:] = spec.orientation
    rates, accelerations, jerks = np.zeros(shape), np.zeros(shape), np.zeros(shape)
    for out, value in ((rates, velocity), (accelerations, acceleration), (jerks, jerk)):
        out[..., 0], out[..., 1] = value.real, value.imag
    return PathSamples(t, phi, poses, rates, accelerations, jerks)


@dataclass(frozen=True)
class PathPlan:
    """A planned path: its duration, the shortest one and the limit that sets it, the samples and their legs."""

    spec: PathSpec
    duration: float
    shortest: float
    binding: str
    samples: PathSamples = field(repr=False)
    check: MotionCheck = field(repr=False)

    @property
    def legs(self) -> ActuatorRates:
        return self.check.legs

    @property
    def positions(self) -> np.ndarray:
        return self.check.positions

    def extremes(self) -> dict[str, np.ndarray]:
        return self.check.extremes()

    @property
    def too_short(self) -> bool:
        """The requested duration is shorter than the shortest within every limit."""
        return self.duration < self.shortest - 1e-12


def _scale_duration(spec: PathSpec, config: PlatformConfig, plan_samples: int) -> tuple[float, str]:
    """Shortest T and the name of the limit that sets it, from the extremes at T = 1."""
    unit = sample(spec, 1.0, np.linspace(0.0, 1.0, plan_samples))
    legs = actuator_rates(config.geometry, unit.poses, unit.rates, unit.accelerations)
    limits = config.trajectory
    act = config.actuator
    candidates = {
        "x/y velocity": np.abs(unit.rates[:, :2]).max() / limits.linear_velocity,
        "x/y acceleration": math.sqrt(np.abs(unit.accelerations[:, :2]).max() / limits.linear_acceleration),
        "x/y jerk": math.pow(np.abs(unit.jerks[:, :2]).max() / limits.linear_jerk, 1.0 / 3.0),
        "actuator velocity": np.abs(legs.velocities).max() / act.max_velocity,
        "actuator acceleration": math.sqrt(np.abs(legs.accelerations).max() / act.max_acceleration),
    }
    binding = max(candidates, key=candidates.get)
    return float(candidates[binding]), binding


def plan_path(spec: PathSpec, config: PlatformConfig, samples: int | None = None,
              plan_samples: int = PLAN_SAMPLES) -> PathPlan:
    """Plan ``spec`` on ``config``: the shortest duration (or the requested longer one), then the
    samples at the task period (or ``samples`` evenly spaced points) with leg positions and rates.
    ``plan_samples``: points of u in [0, 1] for the extremes at T = 1 (TRJ_Path's PlanSamples).

    The shortest T is rounded up to a whole number of task periods, since the
    controller runs whole scans. A requested duration shorter than the shortest
    is planned as asked (:attr:`PathPlan.too_short`; the legs' breaches say which
    actuator limit it breaks).
    """
    shortest, binding = _scale_duration(spec, config, plan_samples)
    period = config.task.period_s
    shortest = math.ceil(shortest * (1.0 + PLAN_MARGIN) / period - 1e-9) * period
    duration = spec.duration if spec.duration is not None else shortest
    count = samples if samples is not None else int(round(duration / period)) + 1
    path = sample(spec, duration, np.linspace(0.0, duration, count))
    check = check_motion(config, path.t, path.poses, path.rates, path.accelerations)
    return PathPlan(spec, duration, shortest, binding, path, check)


#: The curve parameters of the figures (the study gives none): mm, centre (0, 0, 240) mm.
STUDY_PATHS = (
    PathSpec("epitrochoid", R=60.0, r=20.0, d=30.0),
    PathSpec("epicycloid", R=60.0, r=20.0),
    PathSpec("hypocycloid", R=100.0, r=25.0),
    PathSpec("spiral", a=10.0, b=5.0),
)
#: The study's tilt: roll (about X, γ here) = pitch (about Y, β here) = 35°.
STUDY_TILT = (0.0, 35.0, 35.0)


def describe(spec: PathSpec) -> str:
    """One line naming the curve, its parameters, placement, orientation and time law."""
    if spec.family == "spiral":
        shape = f"a={spec.a:g} mm b={spec.b:g} mm/rad"
    elif spec.family == "epitrochoid":
        shape = f"R={spec.R:g} r={spec.r:g} d={spec.d:g} mm"
    else:
        shape = f"R={spec.R:g} r={spec.r:g} mm"
    alpha, beta, gamma = spec.orientation
    law = f"blend {spec.blend:g}" if spec.law == "blend" else "cycloidal"
    return (f"{spec.family} {shape}, φ_end={spec.end:.4g} rad, centre ({', '.join(f'{c:g}' for c in spec.centre)}) mm, "
            f"roll γ={gamma:g} pitch β={beta:g} yaw α={alpha:g} deg, law {law}")
