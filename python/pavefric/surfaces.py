"""Seeded synthetic texture profiles with a chosen spectrum.

Profile *generation* is pre-processing, not the friction model: it makes
CTM-like closed profiles (1024 points at 0.87 mm, periodic by construction)
for examples, tests and reference surfaces.
"""
from __future__ import annotations

import numpy as np

from .core import CTM_DX  # noqa: F401  (the core's one constant, re-exported)

CTM_POINTS = 1024


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


def write_profile(path: str, heights_m: np.ndarray, header: str = "",
                  signature: str | None = None) -> None:
    """Write heights (m) as a one-column text profile in mm, with a header
    comment. With ``signature`` (what the files of its writer begin with),
    written whole or not at all and replacing an existing file only if it
    begins so (``pavefric.core.atomic_output``): a measured profile named by
    mistake stays."""
    lines = [f"# {line}" for line in header.splitlines()] if header else []
    lines.append("height_mm")
    lines.extend(f"{1e3 * z:.6f}" for z in heights_m)
    text = "\n".join(lines) + "\n"
    if signature is not None:
        from .core import atomic_output

        with atomic_output(path, signature=signature) as tmp:
            tmp.write_text(text, encoding="utf-8")
        return
    with open(path, "w", encoding="utf-8") as fh:
        fh.write(text)


#: What every segment ``road_profiles`` writes begins with.
ROAD_SIGNATURE = "# demo road segment "


def road_profiles(directory: str, n: int = 300, points: int = 512, dx: float = CTM_DX,
                  seed: int = 7) -> list:
    """Write ``n`` seeded profiles of consecutive road segments (texture depth
    drifting along the road, as on a worn wheel path) as ``seg_0001.txt``...
    Used by the demo batch (inputs/batch_demo.nml); returns the paths. Each
    replaces only a segment this function wrote (its files begin "# demo
    road segment"; ``write_text_output``): a file of the user's of that name
    is refused, and none is written then."""
    import os

    from .core import check_output, write_text_output

    os.makedirs(directory, exist_ok=True)
    for k in range(n):
        check_output(os.path.join(directory, f"seg_{k + 1:04d}.txt"),
                     signature=ROAD_SIGNATURE)
    rng = np.random.default_rng(seed)
    rms_along = 0.35e-3 + 0.25e-3 * np.sin(np.linspace(0, 3 * np.pi, n)) ** 2
    paths = []
    for k in range(n):
        z = spectral_profile(points, dx, rms=float(rms_along[k] * rng.uniform(0.85, 1.15)),
                             skew=-0.5, seed=seed * 100000 + k)
        path = os.path.join(directory, f"seg_{k + 1:04d}.txt")
        text = (f"{ROAD_SIGNATURE}{k + 1} of {n} (pavefric.surfaces.road_profiles, seed {seed})"
                "\nheight_mm\n" + "\n".join(f"{1e3 * v:.4f}" for v in z) + "\n")
        write_text_output(path, text, ROAD_SIGNATURE)
        paths.append(path)
    return paths
