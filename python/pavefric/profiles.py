"""Profile files: reading any format the core reads (plain text, CSV, laser
profiler export, NetCDF), listing and writing NetCDF files of many profiles.

Reading goes through the Fortran core (the same reader as the program), so a
profile read here gives the program's numbers bit for bit. Writing NetCDF is
pre-processing and uses netCDF4 directly; the layout and attributes are
those docs/profiles.md describes and the core reads.
"""
from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Sequence

import numpy as np

from . import _core
from .core import (PavefricError, PavefricKeywordError, Profile, _check, _format, _typed,
                   _spec, _text, parameters)

__all__ = ["read_profile", "list_profiles", "write_profiles", "ProfileEntry", "element_profile"]


def element_profile(heights, dx: float, element_length: float = 0.87e-3, *,
                    closed: bool = True, phase: float = 0.0) -> tuple[np.ndarray, float]:
    """The profile the pad's elements see (``&pad element_length``).

    The core's own box filter and resampling; ``simulate`` runs four phases
    of this and averages them (docs/model.md).

    Parameters
    ----------
    heights : array_like
        Heights (m).
    dx : float
        Their spacing (m).
    element_length : float, optional
        The pad's element length (m), default the CTM's 0.87 mm.
    closed : bool, optional
        A closed profile (default) or an open one.
    phase : float, optional
        Where the element grid starts, as a fraction of an element in [0, 1).

    Returns
    -------
    tuple of (numpy.ndarray, float)
        The heights (m) at the elements, and their spacing (m); a closed
        profile's spacing is adjusted to a whole number of elements round it.

    Raises
    ------
    PavefricError
        If an argument is out of range.
    """
    z = np.ascontiguousarray(heights, dtype=float).ravel()
    if z.size < 1 or not np.all(np.isfinite(z)):
        raise PavefricError("element_profile: heights must be finite and not empty")
    if not (dx > 0 and element_length > 0 and 0.0 <= phase < 1.0):
        raise PavefricError(f"element_profile: dx = {dx!r}, element_length = "
                            f"{element_length!r} must be > 0, phase = {phase!r} in [0, 1)")
    m = int(_core.pf_resampled_points(z.size, float(dx), int(bool(closed)),
                                      float(element_length), float(phase)))
    if m < 1:
        raise PavefricError(f"element_profile: no element of {element_length} m fits the "
                            f"profile at phase {phase}")
    zr, dxr, status = _core.pf_resample_to_length(z, float(dx), int(bool(closed)),
                                                  float(element_length), float(phase), m)
    if status != 0:
        raise PavefricError("element_profile: not enough memory")
    return np.asarray(zr), float(dxr)

def _b(text: str | os.PathLike) -> bytes:
    """Text for a Fortran character argument (f2py takes UTF-8 bytes; a
    non-ASCII str is refused)."""
    if isinstance(text, bytes):
        return text
    if isinstance(text, os.PathLike):
        return os.fsencode(text)
    return str(text).encode("utf-8")


def read_profile(path: str | os.PathLike, height_unit: str | None = None, *,
                 format: str | None = None, x_column: str | None = None,
                 z_column: str | None = None, dx: float | None = None,
                 profile_name: str | None = None, **preprocess) -> Profile:
    """Read a profile file and make it fit for analysis with the core's ISO
    13473-1 preprocessing, exactly as a scene reads its profile.

    The arguments go to the core as &surface and &preprocess namelist text,
    read and checked by the same code as a scene file's (defaults from its
    declarations).

    Parameters
    ----------
    path : str or os.PathLike
        The profile file: plain text, CSV, a laser profiler's export, or
        NetCDF (one or many profiles).
    height_unit : str, optional
        The file's height unit (``'m'``, ``'mm'``, ``'um'``) when it does not
        say.
    format : str, optional
        ``'auto'`` (default: detected), or the format by name.
    x_column : str, optional
        The column of distances (CSV).
    z_column : str, optional
        The column of heights (CSV).
    dx : float, optional
        ``&surface dx`` (m): the spacing when the file gives neither distances
        nor a spacing (default: the CTM's 0.87 mm), else it must agree with
        the file's.
    profile_name : str, optional
        Which profile of a NetCDF file (empty: the file's only one).
    **preprocess
        Keywords of ``&preprocess``: dropouts, trim_plates, plate_threshold,
        plate_min_length, plate_buffer, spike_slope, resample_dx,
        lowpass_wavelength.

    Returns
    -------
    Profile
        Heights (m), spacing, the raw points and the preprocessing report
        (``report['chainage']``: a NetCDF profile's chainage, m).

    Raises
    ------
    PavefricError
        If the file is missing or bad, or a keyword is unknown or out of range.
    """
    known = {p.name for p in parameters() if p.group == "preprocess"}
    unknown = sorted(set(preprocess) - known)
    if unknown:
        raise PavefricKeywordError(f"unknown preprocessing option(s) {', '.join(unknown)}; "
                                   f"known: {', '.join(sorted(known))}")
    settings = {("surface", "profile_file"): _format(_spec("surface", "profile_file"),
                                                     os.fspath(path), "path")}
    for name, value in (("height_unit", height_unit), ("format", format),
                        ("x_column", x_column), ("z_column", z_column),
                        ("profile_name", profile_name), ("dx", dx)):
        if value is not None:
            settings[("surface", name)] = _format(_spec("surface", name), value, name)
    for name, value in preprocess.items():
        settings[("preprocess", name)] = _format(_spec("preprocess", name), value, name)
    typed = _typed(settings)
    n_raw, n_out, dx_out, has_x, status, message = _core.pf_profile_read_info(*typed)
    _check(status, message)
    (x_raw, z_raw, valid, z, frac, spike, counts, fmt, chainage, has_chainage, status,
     message) = _core.pf_profile_read_data(*typed, int(n_raw), int(n_out))
    _check(status, message)
    keys = ["points_read", "trimmed_start", "trimmed_end", "dropouts", "spikes", "points_out",
            "resampled", "filtered"]
    report: dict[str, Any] = {k: int(v) for k, v in zip(keys, counts)}
    report["resampled"] = bool(report["resampled"])
    report["filtered"] = bool(report["filtered"])
    report["format"] = _text(fmt)
    report["dx"] = float(dx_out)
    report["has_distances"] = bool(has_x)
    if profile_name:
        report["profile_name"] = str(profile_name)
    if has_chainage:
        report["chainage"] = float(chainage)
    raw_h = np.where(valid.astype(bool), z_raw, np.nan)
    return Profile(heights=z.copy(), dx=float(dx_out), path=str(path), report=report,
                   raw_x=x_raw.copy(), raw_heights=raw_h, dropout_fraction=frac.copy(),
                   spike=spike.astype(bool))


@dataclass(frozen=True)
class ProfileEntry:
    """One profile of a NetCDF profile file.

    Parameters
    ----------
    name : str
        The profile's name.
    chainage : float or None
        Its distance along the road (m; None when the file gives none).
    """

    name: str
    chainage: float | None


def list_profiles(path: str | os.PathLike) -> list[ProfileEntry]:
    """The profiles of a NetCDF profile file, in file order, as the core
    reads them.

    Parameters
    ----------
    path : str or os.PathLike
        A NetCDF profile file (``write_profiles``).

    Returns
    -------
    list of ProfileEntry
        Each profile's name and chainage.

    Raises
    ------
    PavefricError
        If the file is missing or not a profile file.
    """
    n, nchars, has_chainage, status, message = _core.pf_profile_list_info(_b(os.fspath(path)))
    _check(status, message)
    codes, ends, chainage, status, message = _core.pf_profile_list(_b(os.fspath(path)), int(n),
                                                                   max(int(nchars), 1))
    _check(status, message)
    data = (np.asarray(codes[:int(nchars)]) & 0xFF).astype(np.uint8).tobytes()
    out = []
    start = 0
    for k in range(int(n)):
        end = int(ends[k])
        out.append(ProfileEntry(data[start:end].decode("utf-8", "replace"),
                                float(chainage[k]) if has_chainage else None))
        start = end
    return out


_UNITS = {"m": 1.0, "mm": 1e-3, "um": 1e-6}


def write_profiles(path: str | os.PathLike, heights, dx=None, *,
                   names: Sequence[str] | None = None,
                   chainage: Sequence[float] | None = None,
                   units: str = "m", title: str = "pavefric texture profiles",
                   compress: bool = False) -> Path:
    """Write profiles to one NetCDF file that ``read_profile``, scenes
    (``&surface profile_file``) and batches read.

    The file is never written over a file the profiles came from, nor onto a
    FIFO, a device or a directory (the rule of every pavefric writer); it is
    written to a temporary name and renamed, so a failed write leaves no
    partial file.

    Parameters
    ----------
    path : str or os.PathLike
        The file to write.
    heights : array_like, list of array_like or Profile
        A 2-D array (profiles x points), or a list of 1-D arrays (any lengths:
        the CF contiguous ragged layout); a 1-D array is one profile; a
        ``Profile`` stands for its heights. NaN marks a dropout.
    dx : float or sequence of float, optional
        The spacing (m), one number or one per profile (None: the reader's
        default or the scene's dx).
    names : sequence of str, optional
        One name per profile (default '1', '2', ...).
    chainage : sequence of float, optional
        Distance along the road (m) of each profile.
    units : str, optional
        The heights' unit: 'm' (default), 'mm' or 'um'.
    title : str, optional
        The file's title attribute.
    compress : bool, optional
        Compress the heights (zlib).

    Returns
    -------
    pathlib.Path
        The file written.

    Raises
    ------
    PavefricError
        If the path may not be written or the arguments disagree. An existing
        file at ``path`` is replaced only if it is a survey ``write_profiles``
        wrote (or is empty): never a friction output, another tool's NetCDF
        or a file that is not NetCDF (the program's rule, ``check_output``).
    """
    import netCDF4

    from .core import atomic_output, check_output

    # never over a file the profiles came from, never onto a FIFO or device
    sources = [getattr(h, "path", None) for h in
               (heights if isinstance(heights, (list, tuple)) else [heights])]
    check_output(path, sources, replaces="profiles")
    heights = ([getattr(h, "heights", h) for h in heights] if isinstance(heights, (list, tuple))
               else getattr(heights, "heights", heights))
    if units not in _UNITS:
        raise PavefricError(f"write_profiles units = {units!r}: expected 'm', 'mm' or 'um'")
    ragged = isinstance(heights, (list, tuple))
    if ragged:
        profiles = [np.asarray(h, dtype=np.float64) for h in heights]
        if any(h.ndim != 1 for h in profiles):
            raise PavefricError("write_profiles heights: a list of 1-D arrays is expected")
    else:
        arr = np.asarray(heights, dtype=np.float64)
        if arr.ndim == 1:
            arr = arr[np.newaxis, :]
        if arr.ndim != 2:
            raise PavefricError(f"write_profiles heights: {arr.ndim} dimensions (expected a "
                                "2-D array, profiles x points, or a list of 1-D arrays)")
        profiles = list(arr)
    n = len(profiles)
    if n == 0 or any(h.size == 0 for h in profiles):
        raise PavefricError("write_profiles heights: no profiles, or an empty one")
    if any(np.isinf(h).any() for h in profiles):
        raise PavefricError("write_profiles heights: Inf is not a height (NaN marks a dropout)")
    if names is None:
        names = [str(k + 1) for k in range(n)]
    names = [str(s) for s in names]
    if len(names) != n:
        raise PavefricError(f"write_profiles names: {len(names)} names for {n} profiles")
    if len(set(names)) != n:
        raise PavefricError("write_profiles names: the names must differ")
    dx_values = None
    if dx is not None:
        dx_values = np.atleast_1d(np.asarray(dx, dtype=np.float64))
        if dx_values.size not in (1, n):
            raise PavefricError(f"write_profiles dx: {dx_values.size} values for {n} profiles")
        if not np.all(np.isfinite(dx_values) & (dx_values > 0)):
            raise PavefricError("write_profiles dx: must be finite and > 0")
    if chainage is not None:
        chainage = np.asarray(chainage, dtype=np.float64)
        if chainage.shape != (n,) or not np.all(np.isfinite(chainage)):
            raise PavefricError(f"write_profiles chainage: {n} finite values expected")

    path = Path(path)
    with atomic_output(path, sources, replaces="profiles") as tmp:
        with netCDF4.Dataset(tmp, "w", format="NETCDF4") as nc:
            nc.Conventions = "CF-1.10"
            nc.title = title
            nc.source = "pavefric.write_profiles"
            nc.pavefric_profile_layout = "ragged" if ragged else "dense"
            nc.createDimension("profile", n)
            strlen = max(1, max(len(s.encode("utf-8")) for s in names))
            nc.createDimension("name_strlen", strlen)
            kw = dict(zlib=True, complevel=1) if compress else dict(contiguous=True)
            if ragged:
                total = sum(h.size for h in profiles)
                nc.createDimension("obs", total)
                count = nc.createVariable("profile_count", "i8", ("profile",))
                count.long_name = "number of points of each profile"
                count.sample_dimension = "obs"
                count[:] = [h.size for h in profiles]
                height = nc.createVariable("height", "f8", ("obs",), **kw)
                height[:] = np.concatenate(profiles)
            else:
                nc.createDimension("point", profiles[0].size)
                height = nc.createVariable("height", "f8", ("profile", "point"), **kw)
                height[:, :] = np.vstack(profiles)
            height.units = units
            height.long_name = "texture profile height, positive up"
            height.coordinates = "profile_name"
            name = nc.createVariable("profile_name", "S1", ("profile", "name_strlen"))
            name.cf_role = "profile_id"
            name.long_name = "profile name"
            name._Encoding = "utf-8"
            name.set_auto_chartostring(False)
            encoded = np.array([s.encode("utf-8") for s in names], dtype=f"S{strlen}")
            name[:] = encoded.view("S1").reshape(n, strlen)
            if dx_values is not None:
                if dx_values.size == 1:
                    var = nc.createVariable("dx", "f8", ())
                    var[...] = dx_values[0]
                else:
                    var = nc.createVariable("dx", "f8", ("profile",))
                    var[:] = dx_values
                var.units = "m"
                var.long_name = "spacing of the profile's points"
            if chainage is not None:
                var = nc.createVariable("chainage", "f8", ("profile",))
                var.units = "m"
                var.long_name = "distance along the road of the profile (chainage)"
                var[:] = chainage
    return path
