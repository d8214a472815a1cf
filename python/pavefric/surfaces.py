"""Seeded synthetic texture profiles with a chosen spectrum.

Profile *generation* is pre-processing, not the friction model: it makes
CTM-like closed profiles (1024 points at 0.87 mm, periodic by construction)
for examples, tests and reference surfaces.
"""
from __future__ import annotations

import numpy as np

CTM_POINTS = 1024
CTM_DX = 0.87e-3


def spectral_profile(n: int = CTM_POINTS, dx: float = CTM_DX, *, rms: float = 0.5e-3,
                     exponent: float = 2.0, wavelength_min: float = 2.0e-3,
                     wavelength_max: float = 50.0e-3, skew: float = 0.0,
                     seed: int = 0) -> np.ndarray:
    """A periodic random profile of ``n`` heights (m) at spacing ``dx`` (m).

    Amplitude spectrum ``|Z(k)| ~ k**(-exponent/2)`` (power ~ k**-exponent)
    between the two wavelengths, random phases from ``numpy.random.default_rng(seed)``,
    scaled to RMS height ``rms`` (m). ``skew`` < 0 gives flat tops and deep
    narrow valleys (a "negative" texture, like an asphalt), > 0 sharp peaks,
    through the monotone map ``z -> (exp(skew z/s) - 1)/skew`` (s the RMS)
    applied before rescaling.
    """
    if n < 4 or dx <= 0 or rms < 0 or wavelength_min <= 0 or wavelength_max <= wavelength_min:
        raise ValueError("spectral_profile: n >= 4, dx > 0, rms >= 0 and "
                         "0 < wavelength_min < wavelength_max are required")
    rng = np.random.default_rng(seed)
    k = np.fft.rfftfreq(n, d=dx)                 # cycles per metre
    amp = np.zeros_like(k)
    band = (k >= 1.0 / wavelength_max) & (k <= 1.0 / wavelength_min)
    if not band.any():
        raise ValueError("spectral_profile: no Fourier mode between the wavelengths")
    amp[band] = k[band] ** (-exponent / 2.0)
    phases = rng.uniform(0.0, 2.0 * np.pi, size=k.size)
    z = np.fft.irfft(amp * np.exp(1j * phases), n=n)
    z -= z.mean()
    s = z.std()
    if s > 0 and skew != 0.0:
        z = np.expm1(skew * z / s) / skew
        z -= z.mean()
        s = z.std()
    if s > 0:
        z *= rms / s
    return z


def write_profile(path: str, heights_m: np.ndarray, header: str = "") -> None:
    """Write heights (m) as a one-column text profile in mm, with a header comment."""
    lines = [f"# {line}" for line in header.splitlines()] if header else []
    lines.append("height_mm")
    lines.extend(f"{1e3 * z:.6f}" for z in heights_m)
    with open(path, "w", encoding="utf-8") as fh:
        fh.write("\n".join(lines) + "\n")
