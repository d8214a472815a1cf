"""Calibration: a least-squares fit of model parameters to measured friction.

Measured data is a CSV with columns ``surface,speed_kmh,mu`` (other columns,
blank lines and ``#`` comment lines are ignored; an empty ``mu`` means "not
measured" and the row is skipped). Each surface has a scene namelist
``<scenes>/<surface>.nml`` (profile, mu_loc, water...). Every evaluation of
the model runs the Fortran core (``Scene.simulate``); nothing here computes
friction.

The fit is ``scipy.optimize.least_squares`` (trust-region reflective, with
bounds). Every fittable parameter is a positive physical quantity that may
span decades (``alpha`` from 1e-2 to 1e3, ``viscosity`` from 1 to 1e4), so
each is fitted as theta = log(p): a step of 1 in theta is a factor e in p
whatever the units (``x_scale = 1``), the bounds in p become bounds in theta,
and p = exp(theta) stays positive. The Jacobian is a forward difference with
a fixed step of 1e-6 in theta (a relative change of 1e-6 in p), every column
a run of the core.

Uncertainty (see docs/calibration.md): the linearised covariance of theta,
s^2 (J^T J)^-1 with s^2 = SSR/(n - p), gives a Student-t interval
theta +/- t(level, n - p) se(theta), mapped back to p as
[exp(theta - t se), exp(theta + t se)]: positive and asymmetric around p.
Optionally a profile-likelihood interval for one parameter: the values whose
profiled SSR (the other parameters refitted) stays below
SSR_min (1 + t^2 / (n - p)), the F-test form of the likelihood ratio.

Parameter names: any of ``FITTABLE`` shared by all surfaces, or
``NAME:SURFACE`` for one surface's own value (``mu_loc:GSP``).
"""
from __future__ import annotations

import csv
import difflib
import json
import math
import os
import re
import warnings
from collections import OrderedDict
from dataclasses import dataclass, field
from pathlib import Path
from typing import Sequence

import numpy as np

from .core import PavefricError, PavefricWarning

__all__ = ["CalibrationError", "FITTABLE", "Model", "Fit", "read_measurements", "fit",
           "profile_interval", "report_text", "main_calibrate"]


class CalibrationError(PavefricError):
    """Bad calibration input (data, parameter names, start values, bounds); a
    one-line message naming the file and line or the option and value."""


@dataclass(frozen=True)
class ParameterSpec:
    """A parameter that can be fitted: units and the default search bounds.

    The bounds keep the search where the core accepts the value and where
    exp(theta) is finite; they are wide on purpose (override with
    ``--bounds NAME=LO:HI``)."""

    units: str
    lower: float
    upper: float
    doc: str


# Every fittable parameter is positive: all are fitted in log space.
FITTABLE: dict[str, ParameterSpec] = {
    "mu_loc": ParameterSpec("1", 1e-3, 5.0, "local (micro-texture) friction, &surface mu_loc"),
    "alpha": ParameterSpec("1", 1e-6, 1e8, "bearing coefficient of Eq. 15, &water alpha"),
    "beta": ParameterSpec("1", 1e-3, 10.0, "speed exponent of Eq. 15, &water beta"),
    "viscosity": ParameterSpec("N s m-3", 1e-6, 1e10, "rubber damping C, &rubber viscosity"),
    "stiffness": ParameterSpec("N m-3", 1e3, 1e14, "rubber stiffness K, &rubber stiffness"),
    "depth": ParameterSpec("m", 1e-8, 0.1, "water depth, &water depth"),
    "water_viscosity": ParameterSpec("Pa s", 1e-7, 10.0, "water viscosity eta, &water viscosity"),
    "load": ParameterSpec("N", 1e-4, 1e5, "pad load, &pad load"),
    "length": ParameterSpec("m", 1e-4, 1.0, "pad length, &pad length"),
    "width": ParameterSpec("m", 1e-4, 1.0, "pad width, &pad width"),
    "thickness": ParameterSpec("m", 1e-5, 1.0, "pad thickness, &pad thickness"),
    "radius": ParameterSpec("m", 1e-4, 10.0, "rounded pad radius, &pad radius"),
    "microtexture_rms": ParameterSpec("m", 1e-7, 1e-2, "microtexture RMS height of the "
                                      "squeeze film model, &surface microtexture_rms"),
}

LEVEL = 0.95            # default confidence level
JAC_STEP = 1e-6         # forward-difference step in theta = log p
RANK_RTOL = 1e-5        # singular values below RANK_RTOL * largest count as zero: the
#                         forward-difference Jacobian is accurate to ~1e-6 of its size
CORRELATION_WARN = 0.99

_NUMBER = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?")
_REQUIRED = ("surface", "speed_kmh", "mu")


def _known_names() -> str:
    return ", ".join(FITTABLE) + " (or NAME:SURFACE for one surface, e.g. mu_loc:GSP)"


def _number(text: str, where: str, column: str) -> float:
    """A strict decimal number (no 'nan', 'inf', '1_000', hex): value or error."""
    t = text.strip()
    if not _NUMBER.fullmatch(t):
        raise CalibrationError(f"{where}: {column} = '{text}' is not a number")
    v = float(t)
    if not math.isfinite(v):
        raise CalibrationError(f"{where}: {column} = '{text}' is not finite")
    return v


def read_measurements(path: str | os.PathLike, source: str | None = None,
                      speeds: Sequence[float] | None = None) -> list[dict]:
    """Rows ``{surface, speed_kmh, mu, line}`` of a measurement CSV.

    ``source``: only rows whose ``source`` column equals it (as in
    inputs/data/kane2017_tables.csv); ``speeds``: only rows at these speeds
    (km/h). Every row is checked (numbers, columns) whether selected or not;
    the message names the file and line."""
    path = Path(path)
    try:
        with open(path, encoding="utf-8", newline="") as fh:
            lines = fh.read().splitlines()
    except FileNotFoundError:
        raise CalibrationError(f"{path}: no such measurement file") from None
    except IsADirectoryError:
        raise CalibrationError(f"{path}: is a directory, not a measurement CSV") from None
    except UnicodeDecodeError as exc:
        raise CalibrationError(f"{path}: not UTF-8 text (byte {exc.start})") from None
    except OSError as exc:
        raise CalibrationError(f"{path}: cannot be read ({exc.strerror})") from None
    if lines and lines[0].startswith("\ufeff"):
        lines[0] = lines[0][1:]
    header = None
    all_rows = []
    for number, line in enumerate(lines, start=1):
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        where = f"{path}:{number}"
        fields = [f.strip() for f in next(csv.reader([line]))]
        if header is None:
            header = fields
            dup = sorted({h for h in header if header.count(h) > 1})
            if dup:
                raise CalibrationError(f"{where}: column {dup[0]} given twice in the header")
            need = list(_REQUIRED) + (["source"] if source is not None else [])
            missing = [c for c in need if c not in header]
            if missing:
                raise CalibrationError(
                    f"{where}: the header ({','.join(header)}) lacks the column(s) "
                    f"{', '.join(missing)}; needed: {', '.join(need)}")
            continue
        if len(fields) != len(header):
            raise CalibrationError(f"{where}: {len(fields)} fields, the header has "
                                   f"{len(header)}")
        rec = dict(zip(header, fields))
        if not rec["surface"]:
            raise CalibrationError(f"{where}: empty surface name")
        if "/" in rec["surface"] or "\\" in rec["surface"] or rec["surface"] in (".", ".."):
            raise CalibrationError(f"{where}: surface = '{rec['surface']}' is not a name "
                                   "(it names the scene <scenes>/<surface>.nml)")
        speed = _number(rec["speed_kmh"], where, "speed_kmh")
        if speed < 0:
            raise CalibrationError(f"{where}: speed_kmh = {rec['speed_kmh']}: must be >= 0")
        if rec["mu"] == "":
            continue  # not measured
        mu = _number(rec["mu"], where, "mu")
        if mu < 0:
            raise CalibrationError(f"{where}: mu = {rec['mu']}: must be >= 0")
        all_rows.append({"surface": rec["surface"], "speed_kmh": speed, "mu": mu,
                         "line": number, "source": rec.get("source")})
    if header is None:
        raise CalibrationError(f"{path}: no header line (needed: {', '.join(_REQUIRED)})")
    rows = all_rows
    if source is not None:
        rows = [r for r in rows if r["source"] == source]
        if not rows:
            have = sorted({r["source"] for r in all_rows})
            raise CalibrationError(f"{path}: no measurements with source = '{source}' "
                                   f"(sources: {', '.join(have) or 'none'})")
    if speeds is not None:
        want = np.asarray(list(speeds), float)
        before = rows
        rows = [r for r in rows if np.any(np.isclose(r["speed_kmh"], want, rtol=0, atol=1e-9))]
        if not rows:
            have = sorted({r["speed_kmh"] for r in before})
            raise CalibrationError(
                f"{path}: no measurements at {', '.join(f'{s:g}' for s in want)} km/h"
                + (f" with source = '{source}'" if source is not None else "")
                + f" (speeds present: {', '.join(f'{s:g}' for s in have) or 'none'})")
    if not rows:
        raise CalibrationError(f"{path}: no measurements (every mu is empty)")
    for r in rows:
        r.pop("source")
    return rows


@dataclass(frozen=True)
class _Target:
    """One fitted parameter: ``base`` applies to ``surface`` (None: to all)."""

    name: str
    base: str
    surface: str | None


def _targets(names: Sequence[str], surfaces: Sequence[str]) -> list[_Target]:
    out = []
    if not names:
        raise CalibrationError("no parameter to fit (--fit NAME ...); known: " + _known_names())
    for name in names:
        base, sep, surface = name.partition(":")
        if base not in FITTABLE:
            close = difflib.get_close_matches(base, list(FITTABLE), n=1)
            hint = f" (did you mean {close[0]}?)" if close else ""
            raise CalibrationError(f"unknown parameter '{name}' to fit{hint}; known: "
                                   + _known_names())
        if sep and not surface:
            raise CalibrationError(f"parameter '{name}': no surface after ':' "
                                   f"(e.g. {base}:{surfaces[0]})")
        if surface and surface not in surfaces:
            raise CalibrationError(f"parameter '{name}': no measurement of surface "
                                   f"'{surface}' in the selected data (surfaces: "
                                   f"{', '.join(surfaces)})")
        out.append(_Target(name, base, surface or None))
    seen = set()
    for t in out:
        if t.name in seen:
            raise CalibrationError(f"parameter '{t.name}' is given twice")
        seen.add(t.name)
    for t in out:
        if t.surface and t.base in seen:
            raise CalibrationError(f"parameters '{t.base}' and '{t.name}' both set "
                                   f"{t.base} on {t.surface}: fit one or the other")
    return out


@dataclass
class Model:
    """The model over several surfaces, through the core, with run counters.

    ``runs`` counts runs of the core (one ``Scene.simulate`` of one surface at
    all its speeds); ``evaluations`` counts evaluations of all surfaces."""

    scenes_dir: Path
    overrides: dict = field(default_factory=dict)
    runs: int = 0
    evaluations: int = 0
    _scenes: dict = field(default_factory=dict)

    def __post_init__(self):
        self.scenes_dir = Path(self.scenes_dir)
        from .core import PARAMETERS

        unknown = sorted(set(self.overrides) - set(PARAMETERS))
        if unknown:
            raise CalibrationError(f"unknown fixed parameter(s) {', '.join(unknown)}; known: "
                                   f"{', '.join(PARAMETERS)}")

    def scene(self, surface: str, where: str = ""):
        """The scene of ``surface`` (read once); ``where`` names the data line."""
        from .core import load_scene

        if surface not in self._scenes:
            path = self.scenes_dir / f"{surface}.nml"
            if not self.scenes_dir.is_dir():
                raise CalibrationError(f"scene directory {self.scenes_dir} does not exist "
                                       "or is not a directory (--scenes)")
            if not path.is_file():
                raise CalibrationError(f"no scene file {path} for surface {surface}"
                                       + (f" ({where})" if where else ""))
            try:
                self._scenes[surface] = load_scene(path)
            except PavefricError as exc:
                raise CalibrationError(f"scene {path}: {exc}") from None
        return self._scenes[surface]

    def surface_parameters(self, surface: str, params: dict) -> dict:
        """The keywords of ``simulate`` for ``surface``: overrides, then fitted values
        (``NAME`` for every surface, ``NAME:SURFACE`` for that one)."""
        kw = dict(self.overrides)
        for name, value in params.items():
            base, _, target = name.partition(":")
            if not target or target == surface:
                kw[base] = float(value)
        return kw

    def predict(self, rows: Sequence[dict], params: dict) -> np.ndarray:
        """The model's friction at every row: one core run per surface."""
        out = np.empty(len(rows))
        by_surface: dict[str, list[int]] = {}
        for i, r in enumerate(rows):
            by_surface.setdefault(r["surface"], []).append(i)
        for surface, idx in by_surface.items():
            speeds = np.array([rows[i]["speed_kmh"] for i in idx])
            unique, inverse = np.unique(speeds, return_inverse=True)
            kw = self.surface_parameters(surface, params)
            try:
                # the run's warnings name the surface they are about
                with warnings.catch_warnings(record=True) as caught:
                    warnings.simplefilter("always")
                    ds = self.scene(surface).simulate(speeds_kmh=unique, series=False, **kw)
                for w in caught:
                    text = str(w.message)
                    if issubclass(w.category, PavefricWarning):
                        text = f"{surface}: {text}"
                    warnings.warn(text, w.category, stacklevel=2)
            except PavefricError as exc:
                shown = ", ".join(f"{k} = {v:.6g}" for k, v in params.items())
                raise CalibrationError(f"the core failed on {surface} with {shown}: "
                                       f"{exc}") from None
            self.runs += 1
            mu = ds["mu"].values[inverse]
            if not np.all(np.isfinite(mu)):
                raise CalibrationError(f"the core returned a non-finite friction on {surface} "
                                       "with " + ", ".join(f"{k} = {v:.6g}"
                                                           for k, v in params.items()))
            out[idx] = mu
        self.evaluations += 1
        return out


@dataclass
class Fit:
    """A calibration: values, intervals, residuals, diagnostics."""

    names: list
    values: dict
    start: dict
    bounds: dict
    level: float
    t_quantile: float | None
    se_log: dict                 # standard error of log p (None when not available)
    interval: dict               # name -> [lo, hi] (linearised, parameter space) or None
    profile: dict                # name -> {"interval": [lo, hi], ...} (profile likelihood)
    rows: list                   # the measurements
    model_values: np.ndarray
    residuals: np.ndarray        # measured - model
    ssr: float
    n: int
    dof: int
    s: float | None              # residual standard error sqrt(SSR / dof)
    runs: int
    evaluations: int
    nfev: int
    njev: int
    status: int
    message: str
    converged: bool
    at_bound: dict
    singular_values: list
    correlation: list | None
    warnings: list
    overrides: dict = field(default_factory=dict)
    inputs: dict = field(default_factory=dict)
    profile_runs: int = 0        # of ``runs``, those for the profile intervals

    @property
    def rmse(self) -> float:
        return math.sqrt(self.ssr / self.n)

    def as_dict(self) -> dict:
        params = {}
        for n in self.names:
            params[n] = {
                "value": self.values[n], "start": self.start[n], "bounds": self.bounds[n],
                "fitted_as": "log", "se_log": self.se_log[n],
                "interval": self.interval[n], "at_bound": self.at_bound[n],
            }
            if n in self.profile:
                params[n]["profile"] = self.profile[n]
        return {
            "inputs": self.inputs,
            "fixed": self.overrides,
            "parameters": params,
            "confidence": {
                "level": self.level,
                "method": "linearised covariance s^2 (J^T J)^-1 of log p, Student t; "
                          "interval [exp(log p - t se), exp(log p + t se)]",
                "t_quantile": self.t_quantile, "dof": self.dof,
            },
            "n_measurements": self.n, "n_parameters": len(self.names), "dof": self.dof,
            "ssr": self.ssr, "rmse": self.rmse, "residual_std": self.s,
            "model_runs": self.runs, "model_runs_profile": self.profile_runs,
            "evaluations": self.evaluations,
            "least_squares": {"status": self.status, "message": self.message,
                              "success": self.converged, "nfev": self.nfev,
                              "njev": self.njev, "method": "trf",
                              "jacobian": f"forward difference, step {JAC_STEP:g} in log p"},
            "jacobian_singular_values": self.singular_values,
            "correlation": self.correlation,
            "warnings": self.warnings,
            "residuals": [{"surface": r["surface"], "speed_kmh": r["speed_kmh"],
                           "measured": r["mu"], "model": float(m), "residual": float(e),
                           "line": r.get("line")}
                          for r, m, e in zip(self.rows, self.model_values, self.residuals)],
        }


class _Problem:
    """Residuals measured - model as a function of theta = log p, with a cache
    (least_squares evaluates the Jacobian at the point it has just evaluated)."""

    def __init__(self, model: Model, rows, targets, lower, upper):
        self.model = model
        self.rows = rows
        self.names = [t.name for t in targets]
        self.measured = np.array([r["mu"] for r in rows])
        self.lower = np.asarray(lower, float)
        self.upper = np.asarray(upper, float)
        self._cache: OrderedDict[bytes, np.ndarray] = OrderedDict()

    def params(self, theta) -> dict:
        return dict(zip(self.names, np.exp(theta)))

    def residual(self, theta) -> np.ndarray:
        theta = np.asarray(theta, float)
        key = theta.tobytes()
        if key in self._cache:
            self._cache.move_to_end(key)
        else:
            self._cache[key] = self.measured - self.model.predict(self.rows, self.params(theta))
            if len(self._cache) > 256:
                self._cache.popitem(last=False)
        return self._cache[key]

    def jacobian(self, theta, columns: Sequence[int] | None = None) -> np.ndarray:
        """d residual / d theta (only ``columns`` if given) by forward differences
        with a step of JAC_STEP in log p (backward where the forward step would
        leave the bounds)."""
        theta = np.asarray(theta, float)
        columns = range(theta.size) if columns is None else list(columns)
        r0 = self.residual(theta)
        jac = np.empty((r0.size, len(columns)))
        for j, k in enumerate(columns):
            h = JAC_STEP if theta[k] + JAC_STEP <= self.upper[k] else -JAC_STEP
            t = theta.copy()
            t[k] += h
            jac[:, j] = (self.residual(t) - r0) / h
        return jac


def _start_values(model: Model, rows, targets, start: dict) -> dict:
    unknown = sorted(set(start) - {t.name for t in targets})
    if unknown:
        raise CalibrationError(f"--start {unknown[0]}: not a fitted parameter (fitted: "
                               f"{', '.join(t.name for t in targets)})")
    out = {}
    for t in targets:
        if t.name in start:
            out[t.name] = float(start[t.name])
            continue
        if t.base in model.overrides:
            out[t.name] = float(model.overrides[t.base])
            continue
        surfaces = [t.surface] if t.surface else sorted({r["surface"] for r in rows})
        vals = [float(model.scene(s).parameters[t.base]) for s in surfaces]
        if min(vals) <= 0:
            raise CalibrationError(f"start value of {t.name}: the scenes give {min(vals):g}; "
                                   f"a fitted parameter must be > 0: give --start "
                                   f"{t.name}=VALUE")
        out[t.name] = float(np.exp(np.mean(np.log(vals))))  # geometric mean over surfaces
    return out


def _bounds(targets, bounds: dict | None) -> dict:
    bounds = dict(bounds or {})
    names = {t.name for t in targets} | {t.base for t in targets}
    unknown = sorted(set(bounds) - names)
    if unknown:
        raise CalibrationError(f"--bounds {unknown[0]}: not a fitted parameter (fitted: "
                               f"{', '.join(t.name for t in targets)})")
    out = {}
    for t in targets:
        spec = FITTABLE[t.base]
        lo, hi = bounds.get(t.name, bounds.get(t.base, (spec.lower, spec.upper)))
        lo, hi = float(lo), float(hi)
        if not (math.isfinite(lo) and math.isfinite(hi) and 0 < lo < hi):
            raise CalibrationError(f"--bounds {t.name}={lo:g}:{hi:g}: need 0 < LO < HI, "
                                   "both finite (the parameter is fitted as log p)")
        out[t.name] = [lo, hi]
    return out


def null_direction(v: np.ndarray) -> np.ndarray:
    """A null-space direction scaled to its largest component, +1.

    An SVD's singular vectors are defined up to sign (LAPACK returns either,
    by machine and library): reporting the direction with its largest
    component positive (the first of equal ones) makes the report the same
    everywhere.
    """
    v = np.asarray(v, dtype=float)
    k = int(np.argmax(np.abs(v) > (1 - 1e-9) * np.max(np.abs(v))))
    return v / v[k]


def fit(rows: Sequence[dict], scenes_dir: str | os.PathLike, names: Sequence[str],
        start: dict | None = None, overrides: dict | None = None,
        bounds: dict | None = None, level: float = LEVEL, profile: Sequence[str] = (),
        max_evaluations: int | None = None, inputs: dict | None = None) -> Fit:
    """Fit parameters ``names`` to ``rows`` (from ``read_measurements``).

    ``start``: start values (default: the scenes' values, geometric mean over
    surfaces for a shared parameter); ``overrides``: fixed ``simulate``
    keywords for every surface; ``bounds``: name -> (lo, hi) in parameter
    units; ``level``: confidence level of the intervals; ``profile``:
    parameters that also get a profile-likelihood interval."""
    from scipy.optimize import least_squares
    from scipy.stats import t as student_t

    if not rows:
        raise CalibrationError("no measurements to fit")
    if not (0.0 < level < 1.0):
        raise CalibrationError(f"--level {level:g}: must lie in (0, 1), e.g. 0.95")
    model = Model(Path(scenes_dir), dict(overrides or {}))
    surfaces = list(dict.fromkeys(r["surface"] for r in rows))
    targets = _targets(list(names), surfaces)
    for r in rows:  # every scene exists and reads, before any fitting
        model.scene(r["surface"], where=f"line {r['line']}" if r.get("line") else "")
    n, p = len(rows), len(targets)
    if n < p:
        raise CalibrationError(f"--fit gives {p} parameters ({', '.join(t.name for t in targets)}) "
                               f"but the data hold {n} measurement(s): fit at most {n}, or add "
                               "measurements")
    if max_evaluations is not None and not (int(max_evaluations) >= 1):
        raise CalibrationError(f"--max-evaluations {max_evaluations}: must be >= 1")
    for name in profile:
        if name not in {t.name for t in targets}:
            raise CalibrationError(f"--profile {name}: not a fitted parameter (fitted: "
                                   f"{', '.join(t.name for t in targets)})")
    bnd = _bounds(targets, bounds)
    p0 = _start_values(model, rows, targets, dict(start or {}))
    for t in targets:
        lo, hi = bnd[t.name]
        if not (math.isfinite(p0[t.name]) and lo <= p0[t.name] <= hi):
            given = ("--start" if t.name in (start or {}) else
                     "fixed value" if t.base in model.overrides else "the scenes' value")
            raise CalibrationError(f"start value {t.name} = {p0[t.name]:g} ({given}) lies "
                                   f"outside its bounds [{lo:g}, {hi:g}]")
    lower = np.log([bnd[t.name][0] for t in targets])
    upper = np.log([bnd[t.name][1] for t in targets])
    prob = _Problem(model, rows, targets, lower, upper)
    theta0 = np.log([p0[t.name] for t in targets])
    res = least_squares(prob.residual, theta0, jac=prob.jacobian, bounds=(lower, upper),
                        method="trf", x_scale=1.0, ftol=1e-10, xtol=1e-10, gtol=1e-10,
                        max_nfev=max_evaluations)
    theta = res.x
    r = prob.residual(theta)
    jac = prob.jacobian(theta)  # cached runs when least_squares ended on this point
    ssr = float(r @ r)
    dof = n - p
    names = [t.name for t in targets]
    warnings: list[str] = []
    if not res.success:
        warnings.append(f"least_squares did not converge: {res.message}")

    # parameters at a bound (active_mask, or within the Jacobian step of one)
    at_bound = {}
    for k, name in enumerate(names):
        side = None
        if res.active_mask[k] < 0 or theta[k] - lower[k] < 10 * JAC_STEP:
            side = "lower"
        elif res.active_mask[k] > 0 or upper[k] - theta[k] < 10 * JAC_STEP:
            side = "upper"
        at_bound[name] = side
        if side:
            warnings.append(f"{name} = {math.exp(theta[k]):.6g} is at its {side} bound "
                            f"{bnd[name][0 if side == 'lower' else 1]:g}: not identifiable "
                            "within the bounds; its interval is not given")

    sv = np.linalg.svd(jac, compute_uv=False) if jac.size else np.zeros(0)
    rank = int(np.sum(sv > RANK_RTOL * sv[0])) if sv.size and sv[0] > 0 else 0
    se = {name: None for name in names}
    interval = {name: None for name in names}
    correlation = None
    t_q = float(student_t.ppf(0.5 + level / 2, dof)) if dof > 0 else None
    s = math.sqrt(ssr / dof) if dof > 0 else None
    if rank < p:
        # the null space of J says which combination the data cannot fix
        _, _, vt = np.linalg.svd(jac)
        null = null_direction(vt[-1])
        combo = ", ".join(f"{c:+.2f} log {nm}" for c, nm in zip(null, names) if abs(c) > 0.05)
        warnings.append(f"not identifiable: the Jacobian has rank {rank} < {p} parameters "
                        f"(singular values {', '.join(f'{v:.3g}' for v in sv)}); no residual "
                        f"changes along the direction ({combo}): the data do not determine "
                        "it; no intervals are given")
    elif dof == 0:
        warnings.append(f"{n} measurement(s) for {p} parameter(s): no degrees of freedom "
                        "left, no intervals are given")
    else:
        cov = s * s * np.linalg.inv(jac.T @ jac)
        sd = np.sqrt(np.diag(cov))
        corr = cov / np.outer(sd, sd)
        correlation = corr.tolist()
        for k, name in enumerate(names):
            se[name] = float(sd[k])
            if at_bound[name] is None:
                interval[name] = [float(np.exp(theta[k] - t_q * sd[k])),
                                  float(np.exp(theta[k] + t_q * sd[k]))]
        for i in range(p):
            for j in range(i + 1, p):
                if abs(corr[i, j]) > CORRELATION_WARN:
                    warnings.append(f"{names[i]} and {names[j]} are correlated (r = "
                                    f"{corr[i, j]:+.4f}): the data fix a combination of "
                                    "them better than either")
    result = Fit(
        names=names, values={nm: float(np.exp(th)) for nm, th in zip(names, theta)},
        start=p0, bounds=bnd, level=level, t_quantile=t_q, se_log=se, interval=interval,
        profile={}, rows=list(rows), model_values=prob.measured - r, residuals=r.copy(),
        ssr=ssr, n=n, dof=dof, s=s, runs=0, evaluations=0, nfev=int(res.nfev),
        njev=int(res.njev or 0), status=int(res.status), message=str(res.message),
        converged=bool(res.success), at_bound=at_bound, singular_values=sv.tolist(),
        correlation=correlation, warnings=warnings, overrides=dict(model.overrides),
        inputs=dict(inputs or {}))
    fit_runs = model.runs
    for name in profile:
        result.profile[name] = profile_interval(prob, result, name)
    result.runs = model.runs
    result.profile_runs = model.runs - fit_runs
    result.evaluations = model.evaluations
    return result


def profile_interval(prob: _Problem, result: Fit, name: str) -> dict:
    """Profile-likelihood interval of one parameter: with log p fixed at each
    trial value and the other parameters refitted, the interval holds the
    values whose SSR stays below SSR_min (1 + t^2 / dof), t the Student-t
    quantile of ``result.level`` (the F(1, dof) test of the likelihood ratio)."""
    from scipy.optimize import brentq, least_squares

    if result.dof <= 0:
        return {"interval": None, "note": "no degrees of freedom"}
    names = result.names
    k = names.index(name)
    others = [i for i in range(len(names)) if i != k]
    theta_hat = np.log([result.values[nm] for nm in names])
    threshold = result.ssr * (1.0 + result.t_quantile ** 2 / result.dof)
    state = {"theta": theta_hat.copy()}

    def profiled_ssr(tk: float) -> float:
        th = state["theta"].copy()
        th[k] = tk
        if others:
            def sub(x):
                full = th.copy()
                full[others] = x
                return prob.residual(full)

            def sub_jac(x):
                full = th.copy()
                full[others] = x
                return prob.jacobian(full, others)

            x0 = np.clip(th[others], prob.lower[others], prob.upper[others])
            res = least_squares(sub, x0, jac=sub_jac,
                                bounds=(prob.lower[others], prob.upper[others]),
                                method="trf", x_scale=1.0, ftol=1e-9, xtol=1e-9,
                                gtol=1e-9)
            th[others] = res.x
            state["theta"] = th  # warm start for the next trial value
        r = prob.residual(th)
        return float(r @ r)

    out = {"level": result.level, "threshold_ssr": threshold,
           "method": "profile likelihood: SSR(p) <= SSR_min (1 + t^2/dof)"}
    ends = []
    scale = result.se_log[name] * result.t_quantile if result.se_log[name] else 0.1
    scale = max(scale, 1e-3)
    for direction, bound in ((-1, prob.lower[k]), (1, prob.upper[k])):
        state["theta"] = theta_hat.copy()
        inner = theta_hat[k]
        step = scale
        end = None
        for _ in range(40):
            trial = theta_hat[k] + direction * step
            if (trial - bound) * direction >= 0:  # the bound is inside the interval
                if profiled_ssr(bound) <= threshold:
                    end = ("bound", bound)
                    break
                trial = bound
            if profiled_ssr(trial) > threshold:
                lo, hi = sorted((inner, trial))
                root = brentq(lambda x: profiled_ssr(x) - threshold, lo, hi, xtol=1e-5)
                end = ("root", root)
                break
            inner = trial
            step *= 2.0
        ends.append(end)
    notes = []
    out["reaches_bound"] = []
    for end, side in zip(ends, ("lower", "upper")):
        if end is None:
            notes.append(f"has no {side} end within 2^40 interval widths")
        elif end[0] == "bound":
            notes.append(f"reaches the {side} bound")
            out["reaches_bound"].append(side)
    # an end at a search bound is reported as the bound itself
    out["interval"] = ([result.bounds[name][i] if e[0] == "bound" else float(np.exp(e[1]))
                        for i, e in enumerate(ends)] if all(ends) else None)
    if notes:
        out["note"] = "; ".join(notes)
        result.warnings.append(f"the profile interval of {name} {' and '.join(notes)}: "
                               "the data do not bound it there")
    return out


def _fmt(v: float | None, digits: int = 4) -> str:
    return "-" if v is None else f"{v:.{digits}g}"


def report_text(result: Fit) -> str:
    """The fit as text: header, parameters with intervals, residuals, warnings."""
    inp = result.inputs
    sel = []
    if inp.get("source") is not None:
        sel.append(f"source {inp['source']}")
    if inp.get("speeds"):
        sel.append(f"speeds {', '.join(f'{s:g}' for s in inp['speeds'])} km/h")
    surfaces = list(dict.fromkeys(r["surface"] for r in result.rows))
    lines = [
        f"calibration of {', '.join(result.names)}: {result.n} measurements"
        + (f" from {inp['data']}" if inp.get("data") else "")
        + (f" ({'; '.join(sel)})" if sel else "")
        + f" on {len(surfaces)} surfaces; {result.dof} degrees of freedom",
        f"least_squares (trust-region reflective, log-parameters): "
        f"{'converged' if result.converged else 'NOT converged'}, status {result.status}: "
        f"{result.message}",
        f"  {result.runs} model runs = {result.evaluations} evaluations x {len(surfaces)} "
        f"surfaces (least_squares: {result.nfev} residual and {result.njev} Jacobian "
        f"evaluations" + (f"; profile intervals: {result.profile_runs} runs)"
                          if result.profile else ")"),
        f"  SSR {result.ssr:.6g}, RMSE {result.rmse:.4g}, residual standard error "
        + (f"{result.s:.4g}" if result.s is not None else "-"),
    ]
    if result.overrides:
        lines.append("  fixed: " + ", ".join(f"{k} = {v:g}" for k, v in result.overrides.items()))
    lines.append("")
    pct = f"{100 * result.level:g}%"
    lines.append(f"parameters (fitted as log p; {pct} interval = exp(log p +/- t se), "
                 + (f"t = {result.t_quantile:.4g} with {result.dof} dof)"
                    if result.t_quantile else "not available)"))
    w = max(9, max(len(nm) for nm in result.names))
    lines.append(f"  {'parameter':{w}s} {'start':>10s} {'fitted':>10s} {'se(log p)':>9s}  "
                 f"{pct + ' interval':24s} profile interval")
    for nm in result.names:
        iv = result.interval[nm]
        iv_text = f"[{_fmt(iv[0])}, {_fmt(iv[1])}]" if iv else (
            f"at {result.at_bound[nm]} bound" if result.at_bound[nm] else "-")
        prof = result.profile.get(nm, {})
        pr = prof.get("interval")
        open_ends = prof.get("reaches_bound", [])
        pr_text = (f"[{_fmt(pr[0])}{' (bound)' if 'lower' in open_ends else ''}, "
                   f"{_fmt(pr[1])}{' (bound)' if 'upper' in open_ends else ''}]") if pr else "-"
        lines.append(f"  {nm:{w}s} {_fmt(result.start[nm]):>10s} {_fmt(result.values[nm]):>10s} "
                     f"{_fmt(result.se_log[nm], 3):>9s}  {iv_text:24s} {pr_text}".rstrip())
    if result.correlation is not None and len(result.names) > 1:
        lines.append("  correlation of log p: " + "; ".join(
            f"{result.names[i]}~{result.names[j]} {result.correlation[i][j]:+.3f}"
            for i in range(len(result.names)) for j in range(i + 1, len(result.names))))
    lines += ["", "residuals (residual = measured - model)",
              f"  {'surface':8s} {'speed_kmh':>9s} {'measured':>9s} {'model':>9s} "
              f"{'residual':>9s}"]
    for r, m, e in zip(result.rows, result.model_values, result.residuals):
        lines.append(f"  {r['surface']:8s} {r['speed_kmh']:9g} {r['mu']:9.4f} {m:9.4f} "
                     f"{e:+9.4f}")
    if result.warnings:
        lines += ["", "warnings:"] + [f"  - {w_}" for w_ in result.warnings]
    return "\n".join(lines)


def _parse_assignments(items, option: str) -> dict:
    out = {}
    for item in items or []:
        name, eq, value = item.partition("=")
        name = name.strip()
        if not eq or not name:
            raise CalibrationError(f"{option} '{item}': expected NAME=VALUE")
        if name in out:
            raise CalibrationError(f"{option} {name} given twice")
        out[name] = value.strip()
    return out


def _start_option(items) -> dict:
    out = {}
    for name, value in _parse_assignments(items, "--start").items():
        if not _NUMBER.fullmatch(value):
            raise CalibrationError(f"--start {name}={value}: '{value}' is not a number")
        out[name] = float(value)
        if not (math.isfinite(out[name]) and out[name] > 0):
            raise CalibrationError(f"--start {name}={value}: must be finite and > 0 "
                                   "(fitted as log p)")
    return out


def _bounds_option(items) -> dict:
    out = {}
    for name, value in _parse_assignments(items, "--bounds").items():
        lo, colon, hi = value.partition(":")
        if not colon or not _NUMBER.fullmatch(lo.strip()) or not _NUMBER.fullmatch(hi.strip()):
            raise CalibrationError(f"--bounds {name}={value}: expected NAME=LO:HI "
                                   "(numbers, e.g. alpha=0.1:1000)")
        out[name] = (float(lo), float(hi))
    return out


def _check_output(path: Path, inputs: Sequence[Path]) -> None:
    """-o must not name an input (the data or a scene) or a non-regular file."""
    target = path.resolve()
    for p in inputs:
        if p.exists() and p.resolve() == target:
            raise CalibrationError(f"-o {path}: is an input ({p}); choose another name")
    if path.exists() and not path.is_file():
        raise CalibrationError(f"-o {path}: exists and is not a regular file")
    # before the fit, not after it: a file this command did not write stays
    from .core import PavefricError, check_output

    try:
        check_output(path, signature=JSON_SIGNATURE)
    except PavefricError as exc:
        raise CalibrationError(f"-o {path}: {exc}") from None


#: What every JSON file ``calibrate -o`` writes begins with (its first
#: member, ``written_by``): an existing file at ``-o`` is replaced only if it
#: begins so (a user's file named by mistake stays; the core's rule,
#: ``check_output``'s ``signature``).
JSON_SIGNATURE = '{\n  "written_by": "pavefric calibrate'


def _write_json(path: Path, data: dict) -> None:
    """Write beside the final name, then rename: no partial file under the name;
    ``written_by`` first, the signature of the files this command writes."""
    from . import __version__
    from .core import PavefricError, atomic_output

    data = {"written_by": f"pavefric calibrate {__version__}", **data}
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        with atomic_output(path, signature=JSON_SIGNATURE) as tmp:
            tmp.write_text(json.dumps(data, indent=2) + "\n", encoding="utf-8")
    except OSError as exc:
        raise CalibrationError(f"-o {path}: cannot write ({exc.strerror})") from None
    except PavefricError as exc:
        raise CalibrationError(f"-o {path}: {exc}") from None


def main_calibrate(args) -> int:
    """``python -m pavefric calibrate``: 0 on a converged fit, 1 otherwise (the
    report and the JSON are still written)."""
    import sys

    start = _start_option(args.start)
    bounds = _bounds_option(args.bounds)
    rows = read_measurements(args.data, source=args.source, speeds=args.speeds)
    if args.output:
        scenes = Path(args.scenes)
        _check_output(Path(args.output), [Path(args.data)] + [
            scenes / f"{s}.nml" for s in {r["surface"] for r in rows}])
    inputs = {"data": str(args.data), "source": args.source, "speeds": args.speeds,
              "scenes": str(args.scenes), "fit": list(args.fit)}
    result = fit(rows, args.scenes, args.fit, start=start, bounds=bounds, level=args.level,
                 profile=args.profile or (), max_evaluations=args.max_evaluations,
                 inputs=inputs)
    print(report_text(result))
    if args.output:
        _write_json(Path(args.output), result.as_dict())
        print(f"wrote {args.output}")
    sys.stdout.flush()
    for w in result.warnings:
        print(f"pavefric: warning: {w}", file=sys.stderr)
    if not result.converged:
        raise CalibrationError(f"the fit did not converge (status {result.status}: "
                               f"{result.message}); raise --max-evaluations, or give --start "
                               "values nearer the solution; the report above is of the last "
                               "point")
    return 0
