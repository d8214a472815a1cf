"""Calibration: least-squares fit of model parameters to measured friction.

Measured data is a CSV with columns ``surface,speed_kmh,mu`` (other columns
and ``#`` comments are ignored). Each surface has a scene namelist
``<scenes>/<surface>.nml`` (profile, mu_loc, water...). Every evaluation runs
the Fortran core. Parameters are fitted in log space (they are positive) by
Levenberg-Marquardt with a forward-difference Jacobian; uncertainties come
from the covariance s^2 (J^T J)^-1 at the optimum.

Parameter names: any ``simulate`` keyword shared by all surfaces (``alpha``,
``beta``, ``viscosity``, ``stiffness``, ``depth``...), or ``mu_loc:<SURFACE>``
for one surface's local friction.
"""
from __future__ import annotations

import csv
import json
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Sequence

import numpy as np


def read_measurements(path: str | os.PathLike, source: str | None = None) -> list[dict]:
    """Rows (surface, speed_kmh, mu) of a CSV; with ``source``, only rows whose
    ``source`` column equals it (as in data/kane2017_tables.csv)."""
    with open(path, encoding="utf-8") as fh:
        lines = [line for line in fh if not line.lstrip().startswith("#") and line.strip()]
    rows = []
    for r in csv.DictReader(lines):
        if source is not None and r.get("source") != source:
            continue
        if r.get("mu", "") == "":
            continue
        rows.append({"surface": r["surface"], "speed_kmh": float(r["speed_kmh"]),
                     "mu": float(r["mu"])})
    if not rows:
        raise ValueError(f"calibrate: no measurements in {path}"
                         + (f" with source = {source}" if source else ""))
    return rows


@dataclass
class Model:
    """The model over several surfaces, with a run counter."""

    scenes_dir: Path
    overrides: dict = field(default_factory=dict)
    runs: int = 0
    _scenes: dict = field(default_factory=dict)

    def scene(self, surface):
        from .core import load_scene

        if surface not in self._scenes:
            path = self.scenes_dir / f"{surface}.nml"
            if not path.exists():
                raise FileNotFoundError(f"calibrate: no scene {path} for surface {surface}")
            self._scenes[surface] = load_scene(path)
        return self._scenes[surface]

    def predict(self, rows: Sequence[dict], params: dict) -> np.ndarray:
        out = np.empty(len(rows))
        by_surface: dict[str, list[int]] = {}
        for i, r in enumerate(rows):
            by_surface.setdefault(r["surface"], []).append(i)
        for surface, idx in by_surface.items():
            kw = dict(self.overrides)
            for name, value in params.items():
                if ":" in name:
                    pname, target = name.split(":", 1)
                    if target == surface:
                        kw[pname] = value
                else:
                    kw[name] = value
            speeds = [rows[i]["speed_kmh"] for i in idx]
            ds = self.scene(surface).simulate(speeds_kmh=speeds, series=False, **kw)
            self.runs += 1
            out[idx] = ds["mu"].values
        return out


@dataclass
class Fit:
    names: list
    values: dict
    std: dict
    residuals: np.ndarray
    rmse: float
    runs: int
    iterations: int
    converged: bool

    def as_dict(self):
        return {"parameters": self.values, "std": self.std, "rmse": self.rmse,
                "model_runs": self.runs, "iterations": self.iterations,
                "converged": self.converged, "residuals": self.residuals.tolist()}


def fit(rows: Sequence[dict], scenes_dir: str | os.PathLike, names: Sequence[str],
        start: dict | None = None, overrides: dict | None = None, max_iter: int = 50,
        tol: float = 1e-10) -> Fit:
    """Fit parameters ``names`` to ``rows`` by Levenberg-Marquardt in log space."""
    model = Model(Path(scenes_dir), dict(overrides or {}))
    measured = np.array([r["mu"] for r in rows])
    start = dict(start or {})
    p0 = []
    for name in names:
        if name in start:
            p0.append(start[name])
        elif ":" in name:
            p0.append(model.scene(name.split(":", 1)[1]).parameters[name.split(":")[0]])
        else:
            p0.append(model.scene(rows[0]["surface"]).parameters[name])
    theta = np.log(np.maximum(np.array(p0, dtype=float), 1e-300))

    def residual(th):
        return model.predict(rows, dict(zip(names, np.exp(th)))) - measured

    r = residual(theta)
    cost = float(r @ r)
    lam = 1e-3
    converged = False
    it = 0
    jac = None
    for it in range(1, max_iter + 1):
        jac = np.empty((len(rows), len(names)))
        for k in range(len(names)):
            h = 1e-6 * max(1.0, abs(theta[k]))
            t2 = theta.copy()
            t2[k] += h
            jac[:, k] = (residual(t2) - r) / h
        g = jac.T @ r
        a = jac.T @ jac
        improved = False
        while lam < 1e12:
            step = np.linalg.solve(a + lam * np.diag(np.diag(a) + 1e-12), -g)
            r_new = residual(theta + step)
            cost_new = float(r_new @ r_new)
            if cost_new < cost:
                theta, r = theta + step, r_new
                rel = (cost - cost_new) / max(cost, 1e-300)
                cost = cost_new
                lam = max(lam / 10, 1e-12)
                improved = True
                break
            lam *= 10
        if not improved or rel < tol or np.max(np.abs(step)) < 1e-10:
            converged = True
            break
    dof = max(1, len(rows) - len(names))
    s2 = cost / dof
    try:
        cov = s2 * np.linalg.inv(jac.T @ jac)
        rel_std = np.sqrt(np.maximum(np.diag(cov), 0.0))   # std of log(p) = relative std
    except np.linalg.LinAlgError:
        rel_std = np.full(len(names), np.inf)
    values = {n: float(np.exp(t)) for n, t in zip(names, theta)}
    std = {n: float(values[n] * s) for n, s in zip(names, rel_std)}
    return Fit(list(names), values, std, r, float(np.sqrt(cost / len(rows))), model.runs, it,
               converged)


def report_text(result: Fit, rows: Sequence[dict]) -> str:
    lines = [f"fitted in {result.iterations} iterations, {result.runs} model runs "
             f"({'converged' if result.converged else 'NOT converged'}); "
             f"RMSE {result.rmse:.4f}"]
    for n in result.names:
        lines.append(f"  {n:16s} = {result.values[n]:.6g} +/- {result.std[n]:.2g}")
    lines.append("  surface  speed_kmh  measured  model  residual")
    for r, res in zip(rows, result.residuals):
        lines.append(f"  {r['surface']:7s} {r['speed_kmh']:9.1f} {r['mu']:9.3f} "
                     f"{r['mu'] + res:6.3f} {res:+9.4f}")
    return "\n".join(lines)


def main_calibrate(args) -> int:
    rows = read_measurements(args.data, source=args.source)
    if args.speeds:
        rows = [r for r in rows if r["speed_kmh"] in set(args.speeds)]
    start = {}
    for item in args.start or []:
        k, v = item.split("=", 1)
        start[k] = float(v)
    result = fit(rows, args.scenes, args.fit, start=start)
    print(report_text(result, rows))
    if args.output:
        Path(args.output).write_text(json.dumps(result.as_dict(), indent=2))
        print(f"wrote {args.output}")
    return 0
