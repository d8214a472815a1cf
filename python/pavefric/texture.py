"""Texture metrics (computed by the Fortran core) and the International
Friction Index of ASTM E1960 (a two-line formula of the standard, here)."""
from __future__ import annotations

import math

import numpy as np

from . import _core
from .core import _check


def texture(heights_m, dx: float | None = None, *, closed: bool = True,
            segment_length: float = 0.1, slope_suppression: bool = True) -> dict:
    """Mean profile depth (ISO 13473-1 / ASTM E1845), RMS height and RMS slope.

    Parameters
    ----------
    heights_m : array_like or Profile
        Heights (m), or a ``Profile`` from ``read_profile``, whose dropout and
        spike flags then make segments with more than 10 % dropouts or 5 %
        spikes invalid (not averaged), as ISO 13473-1 says.
    dx : float, optional
        The spacing (m); not needed with a ``Profile``.
    closed : bool, optional
        A closed profile (default): segments wrap round.
    segment_length : float, optional
        Segment length (m), 0.1 by the standard.
    slope_suppression : bool, optional
        Remove each segment's linear trend (the standard's slope suppression).

    Returns
    -------
    dict
        ``mpd`` (m), ``n_segments``, ``n_valid``, ``msd`` (m, per segment,
        valid or not), ``rms_height`` (m) and ``rms_slope`` (-).

    Raises
    ------
    PavefricError
        If the profile is shorter than one segment or the spacing is bad.
    """
    use_quality = 0
    if hasattr(heights_m, "dropout_fraction"):
        prof = heights_m
        z = np.ascontiguousarray(prof.heights, dtype=np.float64)
        dx = prof.dx if dx is None else dx
        frac = np.ascontiguousarray(prof.dropout_fraction, dtype=np.float64)
        spike = np.ascontiguousarray(prof.spike, dtype=np.int32)
        use_quality = 1
    else:
        z = np.ascontiguousarray(np.asarray(heights_m, dtype=np.float64).ravel())
        frac = np.zeros(z.size)
        spike = np.zeros(z.size, dtype=np.int32)
    if dx is None:
        raise TypeError("texture: dx is required with an array of heights")
    nseg = max(1, int(z.size // max(1, round(segment_length / dx))))
    (mpd, n_segments, n_valid, rms_h, rms_s, msd, status, message) = _core.pf_texture(
        z, float(dx), int(bool(closed)), float(segment_length), int(bool(slope_suppression)),
        nseg, use_quality, frac, spike)
    _check(status, message)
    return {"mpd": float(mpd), "n_segments": int(n_segments), "n_valid": int(n_valid),
            "msd": msd[:int(n_segments)].copy(), "rms_height": float(rms_h),
            "rms_slope": float(rms_s)}


# ASTM E1960-07 (2015), Sections 6-7: speed constant and F60 for the DFT at 20 km/h
SP_A, SP_B = 14.2, 89.7          # Sp = a + b MPD (MPD in mm, Sp in km/h)
F60_A, F60_B = 0.081, 0.732      # F60 = A + B DFT20 exp(-40/Sp)


def speed_constant(mpd_m: float) -> float:
    """Sp (km/h) of ASTM E1960 from the mean profile depth (m)."""
    return SP_A + SP_B * mpd_m * 1e3


def ifi(dft20: float, mpd_m: float) -> dict:
    """International Friction Index (ASTM E1960) from a DFT value at 20 km/h
    and the mean profile depth.

    Parameters
    ----------
    dft20 : float
        DFT friction at 20 km/h.
    mpd_m : float
        Mean profile depth (m).

    Returns
    -------
    dict
        ``{"F60": ..., "Sp": ...}``: the friction number and the speed
        constant (km/h).
    """
    sp = speed_constant(mpd_m)
    fr60 = dft20 * math.exp((20.0 - 60.0) / sp)
    return {"F60": F60_A + F60_B * fr60, "Sp": sp}
