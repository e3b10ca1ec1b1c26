"""Ocean-wave motion by Airy linear theory (docs/mathematics.md section 4, [29–33]).

Component i: ψi = ki·x̃ − ωi·t + φi with ki = 2π/Li, ωi = 2π/Twi.
Surface η = Σ Ai cos ψi; a surface point moves on the orbit
ξ = −Σ Ai sin ψi along the heading θ (x = ξ cos θ, y = ξ sin θ) and
ζ = Σ Ai cos ψi vertically (z). The platform tilts with the surface:
β (about Y) = −atan(∂η/∂x), γ (about X) = atan(∂η/∂y), α (about Z) = 0.
The tilt about X is the study's atan(∂η/∂y), not the exact
atan(cos β · ∂η/∂y) that aligns the platform normal with the surface normal
(docs/mathematics.md section 4): they differ by less than 1e-6° for the study's presets, and the ST
(TRJ_OceanWave) computes the same.

Fade-in (docs/mathematics.md section 4, issue 8): the wave clock starts at rest at the centre pose
and the wave's offset w(t) from the centre is faded in,
p(t) = centre + s(t/T_F)·w(t), with s = σ the cycloidal fraction
(s(0) = 0, s(1) = 1, s' and s'' zero at both ends). Position, velocity and
acceleration are continuous at t = 0 (rest at the centre) and at t = T_F
(the wave itself). T_F (:func:`fade_in_duration`) is the shortest duration
for which a bound of the faded motion's velocity, acceleration and jerk stays
inside the trajectory limits in every coordinate.

Units of the wavelength. The study prints L without a clear unit (docs/mathematics.md section 4);
here a wavelength is a number times ``OceanWave.wavelength_unit_mm``:
the default 1000.0 reads L in metres, so L = 100 gives
k = 2π/(100·1000 mm) ≈ 6.28e-5 per mm. Set ``wavelength_unit_mm=1.0`` to read
L in millimetres. Amplitudes are mm, periods s, phases and heading degrees,
x̃ mm.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from stgen.config import TrajectoryConfig
from stgen.reference.cycloidal import cycloidal_fraction

METRE_MM = 1000.0

#: max |d²/du² atan u| = 3√3/8 (at u = 1/√3) and max |d³/du³ atan u| = 2 (at u = 0).
ATAN_SECOND_DERIVATIVE_MAX = 3.0 * np.sqrt(3.0) / 8.0
ATAN_THIRD_DERIVATIVE_MAX = 2.0


@dataclass(frozen=True)
class WaveComponent:
    """One Airy component: amplitude A (mm), period Tw (s), wavelength L (in the wave's unit), phase φ (degrees)."""

    amplitude_mm: float
    period_s: float
    wavelength: float
    phase_deg: float


@dataclass(frozen=True)
class OceanWave:
    """A sum of components travelling along ``heading_deg`` (θ, from +x towards +y).

    ``wavelength_unit_mm``: millimetres per unit of ``WaveComponent.wavelength``
    (1000.0: metres).
    """

    components: tuple[WaveComponent, ...]
    heading_deg: float = 0.0
    wavelength_unit_mm: float = METRE_MM

    def __post_init__(self) -> None:
        for component in self.components:
            if not (component.period_s > 0.0 and component.wavelength > 0.0):
                raise ValueError(f"period and wavelength must be > 0: {component}")
        if not self.wavelength_unit_mm > 0.0:
            raise ValueError(f"wavelength_unit_mm must be > 0, got {self.wavelength_unit_mm}")

    def _column(self, name: str) -> np.ndarray:
        return np.array([getattr(component, name) for component in self.components], dtype=float)

    @property
    def amplitudes_mm(self) -> np.ndarray:
        """Ai, mm."""
        return self._column("amplitude_mm")

    @property
    def phases_rad(self) -> np.ndarray:
        """φi, rad."""
        return np.radians(self._column("phase_deg"))

    @property
    def wavenumbers_per_mm(self) -> np.ndarray:
        """ki = 2π / (Li · wavelength_unit_mm), rad/mm."""
        return 2.0 * np.pi / (self._column("wavelength") * self.wavelength_unit_mm)

    @property
    def angular_frequencies(self) -> np.ndarray:
        """ωi = 2π / Twi, rad/s."""
        return 2.0 * np.pi / self._column("period_s")


#: The study's regular (Airy) wave: A = 3 mm, φ = 10°, Tw = 10 s, L = 100 m.
AIRY = OceanWave((WaveComponent(3.0, 10.0, 100.0, 10.0),))

#: The study's random wave of five components (L as printed, read in metres).
RANDOM_5 = OceanWave(
    tuple(
        WaveComponent(amplitude, period, wavelength, phase)
        for amplitude, period, wavelength, phase in zip(
            (3.0, 2.3, -3.5, 0.7, 5.4),
            (10.0, 5.0, 3.0, 7.0, 3.0),
            (60.0, 85.0, 75.0, 70.0, 100.0),
            (-10.0, 15.0, 0.0, 20.0, -45.0),
        )
    )
)


def wave_pose(wave: OceanWave, t, centre_pose=None, position_mm: float = 0.0, fade_s: float = 0.0) -> np.ndarray:
    """Platform pose ``[..., 6]`` (mm, degrees) riding ``wave`` at times ``t[...]`` (s) [29–33].

    ``centre_pose`` (default zero) is added to the wave motion;
    ``position_mm`` is x̃, the point's rest position along the heading;
    ``fade_s`` is T_F: the wave's offset from the centre is multiplied by
    σ(t/T_F), 1 from t = T_F on (0: no fade, the study's wave).
    """
    t = np.asarray(t, dtype=float)
    amplitude = wave.amplitudes_mm
    wavenumber = wave.wavenumbers_per_mm
    phase = (
        wavenumber * position_mm
        - wave.angular_frequencies * t[..., None]
        + wave.phases_rad
    )
    horizontal = -np.sum(amplitude * np.sin(phase), axis=-1)
    vertical = np.sum(amplitude * np.cos(phase), axis=-1)
    slope_along = -np.sum(amplitude * wavenumber * np.sin(phase), axis=-1)  # ∂η/∂x̃
    heading = np.radians(wave.heading_deg)
    slope_x, slope_y = slope_along * np.cos(heading), slope_along * np.sin(heading)
    pose = np.stack(
        (
            horizontal * np.cos(heading),
            horizontal * np.sin(heading),
            vertical,
            np.zeros_like(vertical),
            -np.degrees(np.arctan(slope_x)),
            np.degrees(np.arctan(slope_y)),
        ),
        axis=-1,
    )
    centre = np.zeros(6) if centre_pose is None else np.asarray(centre_pose, dtype=float)
    if fade_s > 0.0:
        fade = np.where(t >= fade_s, 1.0, cycloidal_fraction(t / fade_s))
        pose = fade[..., None] * pose
    return pose + centre


def wave_derivative_bounds(wave: OceanWave) -> np.ndarray:
    """``D[n, coordinate]``: bounds of |dⁿ/dtⁿ| (n = 0..3) of each coordinate of the unfaded wave offset.

    Linear (mm): z has Σ|Ai|·ωiⁿ, x and y that times |cos θ| and |sin θ|.
    Tilts (degrees): u = ∂η/∂x or ∂η/∂y has Kn = |cos θ| or |sin θ| times
    Σ|Ai·ki|·ωiⁿ; for atan(u) the chain rule with |atan′| <= 1,
    |atan″| <= 3√3/8 and |atan‴| <= 2 gives D0 = atan K0, D1 = K1,
    D2 = K2 + 3√3/8·K1², D3 = K3 + 3·(3√3/8)·K1·K2 + 2·K1³. α stays 0.
    """
    amplitude = np.abs(wave.amplitudes_mm)
    omega = wave.angular_frequencies
    slope = amplitude * wave.wavenumbers_per_mm
    powers = np.arange(4)[:, None]
    orbit = np.sum(amplitude * omega**powers, axis=-1)  # Σ|A|ωⁿ, n = 0..3
    tilt = np.sum(slope * omega**powers, axis=-1)       # Σ|A k|ωⁿ
    heading = np.radians(wave.heading_deg)
    along = (abs(np.cos(heading)), abs(np.sin(heading)))
    c2, c3 = ATAN_SECOND_DERIVATIVE_MAX, ATAN_THIRD_DERIVATIVE_MAX
    bounds = np.zeros((4, 6))
    bounds[:, 0] = orbit * along[0]
    bounds[:, 1] = orbit * along[1]
    bounds[:, 2] = orbit
    for column, factor in ((4, along[0]), (5, along[1])):
        k0, k1, k2, k3 = tilt * factor
        bounds[:, column] = np.degrees((np.arctan(k0), k1, k2 + c2 * k1**2, k3 + 3.0 * c2 * k1 * k2 + c3 * k1**3))
    return bounds


def fade_in_duration(wave: OceanWave, limits: TrajectoryConfig) -> float:
    """T_F: the wave's fade-in duration under the trajectory limits (linear for x, y, z; angular for the tilts).

    With r = 1/T_F and s = σ (|s′| <= 2r, |s″| <= 2π·r², |s‴| <= 4π²·r³), the
    faded offset s·w of a coordinate with bounds D0..D3 (:func:`wave_derivative_bounds`) has
      |v| <= 2·D0·r + D1,
      |a| <= 2π·D0·r² + 4·D1·r + D2,
      |j| <= 4π²·D0·r³ + 6π·D1·r² + 6·D2·r + D3   (Leibniz rule).
    What the wave leaves of a limit (limit − Dn) is shared equally by the
    terms in r, each giving a largest r in closed form; T_F is 1 over the
    smallest r of all coordinates (0 for a wave that does not move).
    ValueError when the wave alone (D1, D2 or D3) reaches a limit.
    """
    bounds = wave_derivative_bounds(wave)
    linear = (limits.linear_velocity, limits.linear_acceleration, limits.linear_jerk)
    angular = (limits.angular_velocity, limits.angular_acceleration, limits.angular_jerk)
    duration = 0.0
    for coordinate in range(6):
        d0, d1, d2, d3 = bounds[:, coordinate]
        if d0 <= 0.0:
            continue
        velocity, acceleration, jerk = linear if coordinate < 3 else angular
        spare_v, spare_a, spare_j = velocity - d1, acceleration - d2, jerk - d3
        if min(spare_v, spare_a, spare_j) <= 0.0:
            raise ValueError(f"the wave alone reaches the limits in pose coordinate {coordinate + 1}")
        rates = [
            spare_v / (2.0 * d0),
            np.sqrt(spare_a / 2.0 / (2.0 * np.pi * d0)),
            np.cbrt(spare_j / 3.0 / (4.0 * np.pi**2 * d0)),
        ]
        if d1 > 0.0:
            rates += [spare_a / 2.0 / (4.0 * d1), np.sqrt(spare_j / 3.0 / (6.0 * np.pi * d1))]
        if d2 > 0.0:
            rates.append(spare_j / 3.0 / (6.0 * d2))
        duration = max(duration, 1.0 / min(rates))
    return float(duration)
