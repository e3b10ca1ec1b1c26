"""A recorded motion for the playback tests and the demo: a JONSWAP sea state sampled at 10 Hz.

JONSWAP spectrum (Hasselmann et al. 1973) in angular frequency ω:
S(ω) = α g² ω⁻⁵ exp(−5/4 (ωp/ω)⁴) γ^r, r = exp(−(ω − ωp)²/(2 σ² ωp²)),
σ = 0.07 below ωp, 0.09 above; component amplitudes A_k = √(2 S(ω_k) Δω),
random phases. The platform rides it scaled down to the platform's range:
heave z = 240 + s·η, surge x and sway y from the orbit, pitch and roll from the slope.
"""

from __future__ import annotations

import numpy as np

G = 9.81


def jonswap_motion(duration_s: float = 20.0, rate_hz: float = 10.0, peak_period_s: float = 8.0,
                   alpha: float = 0.0081, gamma: float = 3.3, components: int = 40, seed: int = 7,
                   scale_mm_per_m: float = 20.0) -> tuple[np.ndarray, np.ndarray]:
    """(t[n], poses[n, 6]) in s, mm and degrees."""
    rng = np.random.default_rng(seed)
    wp = 2 * np.pi / peak_period_s
    w = np.linspace(0.5 * wp, 3.0 * wp, components)
    dw = w[1] - w[0]
    sigma = np.where(w <= wp, 0.07, 0.09)
    r = np.exp(-((w - wp) ** 2) / (2 * sigma**2 * wp**2))
    spectrum = alpha * G**2 * w**-5 * np.exp(-1.25 * (wp / w) ** 4) * gamma**r
    amplitude = np.sqrt(2 * spectrum * dw)                  # m
    k = w**2 / G                                            # deep water, 1/m
    phase = rng.uniform(0, 2 * np.pi, components)
    t = np.arange(0.0, duration_s + 1e-9, 1.0 / rate_hz)
    psi = -w * t[:, None] + phase
    eta = (amplitude * np.cos(psi)).sum(axis=1)
    orbit = (-amplitude * np.sin(psi)).sum(axis=1)
    slope = (-amplitude * k * np.sin(psi)).sum(axis=1)
    poses = np.zeros((len(t), 6))
    poses[:, 0] = scale_mm_per_m * orbit * 0.8
    poses[:, 1] = scale_mm_per_m * orbit * 0.6
    poses[:, 2] = 240.0 + scale_mm_per_m * eta
    poses[:, 4] = -np.degrees(np.arctan(slope * 0.8))
    poses[:, 5] = np.degrees(np.arctan(slope * 0.6))
    # start and end at rest, on the first pose: fade the motion in and out over 2 s
    fade = np.clip(np.minimum(t, t[-1] - t) / 2.0, 0.0, 1.0)
    smooth = fade - np.sin(2 * np.pi * fade) / (2 * np.pi)
    rest = np.array([0.0, 0.0, 240.0, 0.0, 0.0, 0.0])
    return t, rest + (poses - rest) * smooth[:, None]


def write_csv(path, t, poses) -> None:
    rows = ["t,x,y,z,alpha,beta,gamma"] + [",".join(repr(float(v)) for v in (s, *p)) for s, p in zip(t, poses)]
    path.write_text("\n".join(rows) + "\n")
