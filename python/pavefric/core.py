"""Thin wrappers over the Fortran core (the f2py extension ``_core``).

Nothing here computes friction: every number comes from the Fortran core, so
``simulate`` gives the same numbers as the ``pavefric`` program, bit for bit.
This module only converts arguments, sizes output arrays, and turns the
core's status and message into a Python exception.
"""
from __future__ import annotations

import functools
import os
import shlex
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Iterable

import numpy as np

from . import _core

__all__ = [
    "PavefricError",
    "defaults",
    "simulate",
    "run",
    "open_dataset",
    "read_profile",
    "Profile",
    "layout",
    "hydro_load",
    "load_scene",
    "Scene",
    "ProfilesFailedWarning",
]


class PavefricError(ValueError):
    """Bad input or a failed run; the message names the group, variable and value."""


class ProfilesFailedWarning(UserWarning):
    """A batch finished but some of its profiles failed (the program's exit
    status 4): the output is written, its ``status`` (2) and ``error_message``
    variables say which and why. ``path`` is the output file, ``failed`` maps
    each failed profile's name to its message. Make it an error with
    ``warnings.simplefilter("error", pavefric.ProfilesFailedWarning)``."""

    def __init__(self, message: str, path: Path | None = None,
                 failed: dict[str, str] | None = None):
        super().__init__(message)
        self.path = path
        self.failed = dict(failed or {})


def _text(raw: Any) -> str:
    if isinstance(raw, bytes):
        raw = raw.decode("utf-8", "replace")
    elif isinstance(raw, np.ndarray):
        raw = raw.tobytes().decode("utf-8", "replace")
    return str(raw).rstrip("\x00 ").strip()


def _check(status: int, message: Any) -> None:
    if int(status) != 0:
        raise PavefricError(_text(message))


# The model's parameters: Python keyword -> namelist group and variable.
PARAMETERS: dict[str, tuple[str, str]] = {
    "mu_loc": ("surface", "mu_loc"),
    "length": ("pad", "length"),
    "width": ("pad", "width"),
    "thickness": ("pad", "thickness"),
    "load": ("pad", "load"),
    "shape": ("pad", "shape"),
    "radius": ("pad", "radius"),
    "stiffness": ("rubber", "stiffness"),
    "viscosity": ("rubber", "viscosity"),
    "depth": ("water", "depth"),
    "water_viscosity": ("water", "viscosity"),
    "alpha": ("water", "alpha"),
    "beta": ("water", "beta"),
    "theta_max_deg": ("numerics", "theta_max_deg"),
    "substeps": ("numerics", "substeps"),
    "elements_per_sample": ("numerics", "elements_per_sample"),
    "position_stride": ("numerics", "position_stride"),
    "wet_tolerance": ("numerics", "wet_tolerance"),
}


@functools.lru_cache(maxsize=1)
def _core_defaults() -> dict[str, Any]:
    out = _core.pf_defaults()
    names = ["mu_loc", "length", "width", "thickness", "load", "radius", "stiffness",
             "viscosity", "depth", "water_viscosity", "alpha", "beta", "theta_max_deg",
             "substeps", "elements_per_sample", "position_stride", "wet_tolerance",
             "ctm_dx", "version"]
    values = dict(zip(names, out))
    values["version"] = _text(values["version"])
    for key in ("substeps", "elements_per_sample", "position_stride"):
        values[key] = int(values[key])
    for key in names:
        if key not in ("version", "substeps", "elements_per_sample", "position_stride"):
            values[key] = float(values[key])
    values["shape"] = "flat"
    return values


def defaults() -> dict[str, Any]:
    """The model's default parameters, read from the Fortran core (SI units)."""
    values = dict(_core_defaults())
    values.pop("version")
    values.pop("ctm_dx")
    return values


def layout(n_points: int, dx: float, closed: bool = True, **parameters: Any) -> tuple[int, int]:
    """(pad elements, averaged positions) of a profile; 0 positions if the pad does not fit."""
    p = _parameters(parameters)
    n_el, n_pos = _core.pf_layout(int(n_points), float(dx), int(bool(closed)), p["length"],
                                  p["elements_per_sample"], p["substeps"], p["position_stride"])
    return int(n_el), int(n_pos)


def _parameters(given: dict[str, Any]) -> dict[str, Any]:
    unknown = sorted(set(given) - set(PARAMETERS))
    if unknown:
        raise TypeError(f"unknown parameter(s) {', '.join(unknown)}; known: "
                        f"{', '.join(PARAMETERS)}")
    p = defaults()
    p.update(given)
    return p


def simulate(heights_m: Iterable[float], dx: float, speeds_kmh: Iterable[float] | float, *,
             closed: bool = True, series: bool = False, **parameters: Any):
    """Run the friction model on a profile and return an ``xarray.Dataset``.

    Parameters
    ----------
    heights_m : profile heights in metres, at uniform spacing ``dx`` (m).
    speeds_kmh : sliding speeds in km/h.
    closed : a closed Circular Track Meter circle (True) or an open profile.
    series : also return per-position ``mu_inst``, ``hydro_load``,
        ``penetration`` and ``contact_elements``.
    **parameters : the namelist's variables (SI units); ``viscosity`` is the
        rubber's C, ``water_viscosity`` the water's eta. See ``defaults()``
        and docs/inputs.md.

    The variables and attributes are those of the program's NetCDF output.
    """
    import xarray as xr

    p = _parameters(parameters)
    z = np.ascontiguousarray(np.asarray(heights_m, dtype=np.float64).ravel())
    speeds = np.ascontiguousarray(np.atleast_1d(np.asarray(speeds_kmh, dtype=np.float64)).ravel())
    if z.size == 0:
        raise PavefricError("&surface profile_file: the profile holds no heights")
    npos = 1
    if series:
        _, npos = layout(z.size, dx, closed, **{k: p[k] for k in
                         ("length", "elements_per_sample", "substeps", "position_stride")})
        npos = max(npos, 1)
    out = _core.pf_simulate(
        z, float(dx), int(bool(closed)), speeds,
        float(p["mu_loc"]), float(p["length"]), float(p["width"]), float(p["thickness"]),
        float(p["load"]), str(p["shape"]), float(p["radius"]), float(p["stiffness"]),
        float(p["viscosity"]), float(p["depth"]), float(p["water_viscosity"]),
        float(p["alpha"]), float(p["beta"]), float(p["theta_max_deg"]), int(p["substeps"]),
        int(p["elements_per_sample"]), int(p["position_stride"]), float(p["wet_tolerance"]),
        int(bool(series)), npos)
    (mu, hyd, wet, resid, mwh, comp, ncl, nbe, nmem, vis, bea, position, mu_inst, hload, pen, ce,
     n_el, n_pos, n_spin, effects, status, message) = out
    _check(status, message)
    coords = {"speed": ("speed", speeds / 3.6, {"units": "m s-1",
                                                "long_name": "sliding speed of the pad"}),
              "speed_kmh": ("speed", speeds, {"units": "km h-1",
                                              "long_name": "sliding speed of the pad"})}
    data = {
        "mu": ("speed", mu.copy()),
        "n_clamped": ("speed", ncl.copy()),
        "hydroplaning_fraction": ("speed", hyd.copy()),
        "wet_fraction": ("speed", wet.copy()),
        "max_balance_residual": ("speed", resid.copy()),
        "mean_hydro_load": ("speed", mwh.copy()),
        "max_compression": ("speed", comp.copy()),
        "bearing_evaluations": ("speed", nbe.copy()),
        "memory_updates": ("speed", nmem.copy()),
        "viscous_memory_ran": ("speed", vis.astype(np.int8)),
        "bearing_ran": ("speed", bea.astype(np.int8)),
    }
    if series:
        coords["position"] = ("position", position.copy(), {"units": "m"})
        for name, arr in (("mu_inst", mu_inst), ("hydro_load", hload), ("penetration", pen),
                          ("contact_elements", ce)):
            data[name] = (("speed", "position"), np.ascontiguousarray(arr.T))
    attrs = {
        "effects": _text(effects),
        "pavefric_version": _core_defaults()["version"],
        "pad_elements": int(n_el),
        "averaged_positions": int(n_pos),
        "spinup_positions": int(n_spin),
        "profile_points": int(z.size),
        "profile_dx": float(dx),
        "profile_closed": int(bool(closed)),
    }
    return xr.Dataset(data, coords=coords, attrs=attrs)


def hydro_load(h_out, h_in: float, prefactor: float = 1.0):
    """Bearing load Wh (N) of Eq. 15 for outlet films ``h_out`` (m), inlet film
    ``h_in`` (m) and prefactor alpha 6 eta V**beta l L**2; returns (Wh, dWh/dHout)."""
    h = np.ascontiguousarray(np.atleast_1d(np.asarray(h_out, dtype=np.float64)))
    wh, dwh = _core.pf_hydro_load(float(prefactor), float(h_in), h)
    return wh, dwh


def run(path: str | os.PathLike, output: str | os.PathLike | None = None,
        progress: bool | None = None) -> Path:
    """Run the scene namelist at ``path`` as the program does; return the output path.

    A batch scene (with a ``&batch`` group) is computed profile by profile
    through the core, with a progress bar (``progress``: default when
    stderr is a terminal), resuming from the journal of an interrupted run.
    """
    command = "pavefric.run(" + shlex.quote(str(path)) + (
        f", output={shlex.quote(str(output))})" if output else ")")
    if Path(sys.argv[0]).name == "__main__.py":
        command = "python -m pavefric " + " ".join(shlex.quote(a) for a in sys.argv[1:])
    is_batch, status, message = _core.pf_scene_is_batch(str(path))
    _check(status, message)
    if is_batch:
        return _run_batch(str(path), str(output or ""), command, progress)
    out_path, status, message = _core.pf_run_scene(str(path), str(output or ""), command)
    _check(status, message)
    return Path(_text(out_path))


def _run_batch(path: str, output: str, command: str, progress: bool | None) -> Path:
    """The batch through the core in calls of a few profiles each (a progress
    bar between calls). Each call re-reads the journal and checks the
    profiles in it (a cost that grows with the profiles done, about 0.5 % of
    computing them, docs/cluster.md), so a call computes at least an eighth
    of the profiles done, and about half a second of work."""
    import time

    if progress is None:
        progress = sys.stderr.isatty()
    bar = _ProgressBar(progress)
    chunk = 1
    while True:
        t0 = time.perf_counter()
        (out_path, computed, finished, total, done, status, message) = _core.pf_batch_run(
            path, output, command, chunk)
        _check(status, message)
        dt = time.perf_counter() - t0
        bar.update(int(done), int(total))
        if finished:
            bar.close()
            out = Path(_text(out_path))
            _warn_failed_profiles(path, out)
            return out
        if computed == 0:
            raise PavefricError(f"batch {path}: no progress (max_profiles reached?)")
        timed = int(chunk * max(0.5, min(4.0, 0.5 / max(dt, 1e-6))))
        chunk = max(1, min(int(total), max(timed, int(done) // 8)))


def _warn_failed_profiles(path: str, out: Path) -> None:
    """A ProfilesFailedWarning naming the failed profiles, if any."""
    import warnings

    import xarray as xr

    with xr.open_dataset(out, engine="netcdf4") as ds:
        if int(ds.attrs.get("profiles_failed", 0)) == 0:
            return
        bad = np.flatnonzero(ds["status"].values == 2)
        names = [str(v) for v in ds["profile"].values[bad]]
        messages = [str(v) for v in ds["error_message"].values[bad]]
        total = ds.sizes["profile"]
    failed = dict(zip(names, messages))
    shown = "; ".join(f"{n}: {m}" for n, m in list(failed.items())[:5])
    more = f"; ... {len(failed) - 5} more" if len(failed) > 5 else ""
    warnings.warn(ProfilesFailedWarning(
        f"batch {path}: {len(failed)} of {total} profiles failed (status = 2 and "
        f"error_message in {out}): {shown}{more}", out, failed), stacklevel=4)


class _ProgressBar:
    """tqdm when installed, else a one-line text bar on stderr."""

    def __init__(self, enabled: bool):
        self.enabled = enabled
        self._tqdm = None
        self._done = 0
        if enabled:
            try:
                from tqdm import tqdm
                self._tqdm = tqdm(unit="profile", desc="pavefric batch")
            except ImportError:
                self._tqdm = None

    def update(self, done: int, total: int) -> None:
        if not self.enabled:
            return
        if self._tqdm is not None:
            self._tqdm.total = total
            self._tqdm.update(done - self._done)
        else:
            width = 30
            fill = int(width * done / max(total, 1))
            sys.stderr.write(f"\rpavefric batch [{'#' * fill}{'.' * (width - fill)}] "
                             f"{done}/{total}")
            sys.stderr.flush()
        self._done = done

    def close(self) -> None:
        if not self.enabled:
            return
        if self._tqdm is not None:
            self._tqdm.close()
        else:
            sys.stderr.write("\n")


def open_dataset(path: str | os.PathLike):
    """Read a pavefric NetCDF output into memory as an ``xarray.Dataset``."""
    import xarray as xr

    with xr.open_dataset(path, engine="netcdf4") as ds:
        return ds.load()


@dataclass
class Scene:
    """A scene namelist as the core reads it: the profile (heights in m,
    spacing dx in m), the speeds, and the model parameters as ``simulate``
    keywords."""

    name: str
    heights: np.ndarray
    dx: float
    closed: bool
    speeds_kmh: np.ndarray
    parameters: dict
    series: bool
    profile_file: str
    output_file: str

    def simulate(self, speeds_kmh=None, series=None, **overrides):
        """Run this scene through ``simulate`` (parameters may be overridden)."""
        params = {**self.parameters, **overrides}
        return simulate(self.heights, self.dx,
                        self.speeds_kmh if speeds_kmh is None else speeds_kmh,
                        closed=self.closed, series=self.series if series is None else series,
                        **params)


def load_scene(path: str | os.PathLike) -> Scene:
    """Read a scene namelist and its profile with the core's readers."""
    out = _core.pf_scene_info(str(path))
    (np_, ns, dx, closed, series, mu_loc, length, width, thickness, load, shape, radius,
     stiffness, viscosity, depth, water_viscosity, alpha, beta, theta_max_deg, substeps,
     elements_per_sample, position_stride, wet_tolerance, profile_file, output_file,
     status, message) = out
    _check(status, message)
    z, speeds, status, message = _core.pf_scene_arrays(str(path), int(np_), int(ns))
    _check(status, message)
    params = dict(mu_loc=float(mu_loc), length=float(length), width=float(width),
                  thickness=float(thickness), load=float(load), shape=_text(shape),
                  radius=float(radius), stiffness=float(stiffness), viscosity=float(viscosity),
                  depth=float(depth), water_viscosity=float(water_viscosity),
                  alpha=float(alpha), beta=float(beta), theta_max_deg=float(theta_max_deg),
                  substeps=int(substeps), elements_per_sample=int(elements_per_sample),
                  position_stride=int(position_stride), wet_tolerance=float(wet_tolerance))
    return Scene(name=Path(path).stem, heights=z.copy(), dx=float(dx), closed=bool(closed),
                 speeds_kmh=speeds.copy(), parameters=params, series=bool(series),
                 profile_file=_text(profile_file), output_file=_text(output_file))


@dataclass
class Profile:
    """A profile as the core reads and preprocesses it.

    ``heights`` (m) at spacing ``dx`` (m) are fit for analysis; ``report``
    says what preprocessing did; ``raw_x``, ``raw_heights`` (m, NaN at
    dropouts) are the file's points for checking; ``dropout_fraction`` and
    ``spike`` are per-sample quality flags (used for texture validity)."""

    heights: np.ndarray
    dx: float
    path: str
    report: dict
    raw_x: np.ndarray
    raw_heights: np.ndarray
    dropout_fraction: np.ndarray
    spike: np.ndarray


PREPROCESS_DEFAULTS = dict(dropouts="error", trim_plates=True, plate_threshold=0.010,
                           plate_min_length=0.005, plate_buffer=0.002, spike_slope=0.0,
                           resample_dx=0.0, lowpass_wavelength=0.0)


def read_profile(path: str | os.PathLike, height_unit: str = "mm", *, format: str = "auto",
                 x_column: str = "", z_column: str = "", dx: float | None = None,
                 **preprocess) -> Profile:
    """Read a profile file (plain text, laser profiler export, CSV) and make
    it fit for analysis with the core's ISO 13473-1 preprocessing (keywords
    of ``&preprocess``: dropouts, trim_plates, plate_threshold,
    plate_min_length, plate_buffer, spike_slope, resample_dx,
    lowpass_wavelength). ``dx`` (m) is used when the file has no distances
    (default: the CTM's 0.87 mm)."""
    unknown = sorted(set(preprocess) - set(PREPROCESS_DEFAULTS))
    if unknown:
        raise TypeError(f"unknown preprocessing option(s) {', '.join(unknown)}; known: "
                        f"{', '.join(PREPROCESS_DEFAULTS)}")
    p = {**PREPROCESS_DEFAULTS, **preprocess}
    dx_default = float(dx) if dx else float(_core_defaults()["ctm_dx"])
    args = (str(path), format, height_unit, x_column, z_column, dx_default, str(p["dropouts"]),
            int(bool(p["trim_plates"])), float(p["plate_threshold"]),
            float(p["plate_min_length"]), float(p["plate_buffer"]), float(p["spike_slope"]),
            float(p["resample_dx"]), float(p["lowpass_wavelength"]))
    n_raw, n_out, dx_out, has_x, status, message = _core.pf_profile_info(*args)
    _check(status, message)
    (x_raw, z_raw, valid, z, frac, spike, counts, fmt, status, message) = \
        _core.pf_read_profile(*args, int(n_raw), int(n_out))
    _check(status, message)
    keys = ["points_read", "trimmed_start", "trimmed_end", "dropouts", "spikes", "points_out",
            "resampled", "filtered"]
    report = {k: int(v) for k, v in zip(keys, counts)}
    report["resampled"] = bool(report["resampled"])
    report["filtered"] = bool(report["filtered"])
    report["format"] = _text(fmt)
    report["dx"] = float(dx_out)
    report["has_distances"] = bool(has_x)
    raw_h = np.where(valid.astype(bool), z_raw, np.nan)
    return Profile(heights=z.copy(), dx=float(dx_out), path=str(path), report=report,
                   raw_x=x_raw.copy(), raw_heights=raw_h, dropout_fraction=frac.copy(),
                   spike=spike.astype(bool))
