"""Ocean-wave motion by Airy linear theory (docs/mathematics.md section 4, [29–33]).

Component i: ψi = ki·x̃ − ωi·t + φi with ki = 2π/Li, ωi = 2π/Twi.
Surface η = Σ Ai cos ψi; a surface point moves on the orbit
ξ = −Σ Ai sin ψi along the heading θ (x = ξ cos θ, y = ξ sin θ) and
ζ = Σ Ai cos ψi vertically (z). The platform tilts with the surface:
β (about Y) = −atan(∂η/∂x), γ (about X) = atan(∂η/∂y), α (about Z) = 0.

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

METRE_MM = 1000.0


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


def wave_pose(wave: OceanWave, t, centre_pose=None, position_mm: float = 0.0) -> np.ndarray:
    """Platform pose ``[..., 6]`` (mm, degrees) riding ``wave`` at times ``t[...]`` (s) [29–33].

    ``centre_pose`` (default zero) is added to the wave motion;
    ``position_mm`` is x̃, the point's rest position along the heading.
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
    return pose + centre
