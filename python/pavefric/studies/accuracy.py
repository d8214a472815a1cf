"""Accuracy-cost study: what each numerical knob buys, and what it costs.

For a scene, each knob of ``&numerics`` is varied over a range with the others
at the scene's values; for each setting the friction is computed (by the
Fortran core), its largest difference over the speeds from the finest
setting of that knob is recorded, and the wall time is measured (best of a
few repeats; absolute times are noisy, ratios less so).
"""
from __future__ import annotations

import os
import time
import warnings
from pathlib import Path
from typing import Callable, Sequence

import numpy as np

# knob -> settings, coarsest (cheapest) first; the last is the reference
KNOBS: dict[str, list] = {
    "substeps": [1, 2, 4, 8, 16, 32, 64],
    "elements_per_sample": [1, 2, 4, 8, 16, 32, 64],
    "position_stride": [32, 16, 8, 4, 2, 1],
    "wet_tolerance": [1e-2, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12, 1e-14],
}

BUDGETS = {  # name -> largest cost, as wall time relative to the default settings
    "quick look": 1.0,
    "network survey": 4.0,
    "research": 64.0,
}


def _timed(scene, speeds, repeats, **knob):
    # the knob's own pass, not the default run's error-estimate pass on top
    knob.setdefault("error_estimate", False)
    best = np.inf
    ds = None
    for _ in range(max(1, repeats)):
        t0 = time.perf_counter()
        ds = scene.simulate(speeds_kmh=speeds, series=False, **knob)
        best = min(best, time.perf_counter() - t0)
    return ds, best


def study(scene_path: str | os.PathLike, speeds_kmh: Sequence[float] | None = None,
          knobs: dict[str, list] | None = None, repeats: int = 3,
          overrides: dict | None = None, label: str | None = None,
          on_step: Callable[[str], None] | None = None):
    """Run the study on one scene; return an ``xarray.Dataset`` with one row
    per (knob, setting): ``mu`` per speed, ``error`` (largest |mu - mu_finest|
    over the speeds), ``time_s``, ``element_steps``."""
    import xarray as xr

    from ..core import layout, load_scene

    scene = load_scene(scene_path)
    scene.parameters.update(overrides or {})
    speeds = np.asarray(scene.speeds_kmh if speeds_kmh is None else speeds_kmh, dtype=float)
    knobs = dict(KNOBS if knobs is None else knobs)
    wet = scene.parameters["depth"] > 0
    if not wet:
        knobs.pop("wet_tolerance", None)   # a dry scene never solves the wet balance
    rows = []
    for knob, values in knobs.items():
        results = []
        for value in values:
            ds, seconds = _timed(scene, speeds, repeats, **{knob: value})
            p = {**scene.parameters, knob: value}
            n_el, n_pos = layout(scene.heights.size, scene.dx, scene.closed, **{
                k: p[k] for k in ("length", "elements_per_sample", "substeps",
                                  "position_stride")})
            results.append((value, ds["mu"].values.copy(), seconds,
                            n_el * (n_pos + ds.attrs["spinup_positions"]) * speeds.size))
            if on_step:
                on_step(f"{knob} = {value:g}")
        finest = results[-1][1]
        for value, mu, seconds, steps in results:
            rows.append((knob, float(value), mu, float(np.max(np.abs(mu - finest))), seconds,
                         steps))
    # The converged limit, estimated by Richardson extrapolation of the finest
    # time refinements, with the order of convergence estimated from the
    # three finest (kept within [0.5, 4]).
    sub = [r for r in rows if r[0] == "substeps"]
    if len(sub) >= 3 and sub[-1][1] == 2 * sub[-2][1] == 4 * sub[-3][1]:
        d1 = np.abs(sub[-2][2] - sub[-3][2]).max()
        d2 = np.abs(sub[-1][2] - sub[-2][2]).max()
        order = float(np.clip(np.log2(d1 / d2), 0.5, 4.0)) if d2 > 0 and d1 > 0 else 1.0
        limit = sub[-1][2] + (sub[-1][2] - sub[-2][2]) / (2.0**order - 1.0)
        limit_note = (f"Richardson extrapolation of substeps = {sub[-2][1]:g}, {sub[-1][1]:g} "
                      f"with the observed order {order:.2f}")
    else:
        limit = rows[-1][2]
        limit_note = "the last setting"
    n = len(rows)
    return xr.Dataset(
        {
            "knob": ("setting", np.array([r[0] for r in rows], dtype=object)),
            "value": ("setting", np.array([r[1] for r in rows])),
            "mu": (("setting", "speed_kmh"), np.array([r[2] for r in rows])),
            "error": ("setting", np.array([float(np.max(np.abs(r[2] - limit))) for r in rows]),
                      {"long_name": "largest |mu - mu(continuum limit)| over speeds"}),
            "convergence": ("setting", np.array([r[3] for r in rows]),
                            {"long_name": "largest |mu - mu(finest setting of this knob)| "
                                          "over speeds"}),
            "mu_limit": ("speed_kmh", np.asarray(limit)),
            "time_s": ("setting", np.array([r[4] for r in rows]),
                       {"units": "s", "long_name": "wall time, best of repeats (noisy)"}),
            "element_steps": ("setting", np.array([r[5] for r in rows], dtype=np.int64)),
        },
        coords={"setting": np.arange(n), "speed_kmh": speeds},
        attrs={"scene": str(scene_path), "label": label or Path(scene_path).stem,
               "wet": int(wet), "repeats": repeats,
               "limit": limit_note,
               "speeds_kmh": " ".join(f"{s:g}" for s in speeds)},
    )


TOLERANCES = [1e-2, 3e-3, 1e-3, 3e-4, 1e-4]

# substeps of the order study, coarsest first; the reference is the
# Richardson value of the two finest
ORDER_SUBSTEPS = [1, 2, 4, 8, 16, 32, 64, 128, 256, 512]


def fitted_order(dt, err, floor: float) -> float:
    """Least-squares slope of log(err) against log(dt) over the points whose
    error is above ``floor`` (the reference's own uncertainty) and whose time
    step is at most a quarter of the coarsest (the asymptotic range); NaN
    with fewer than three such points."""
    dt = np.asarray(dt, dtype=float)
    err = np.asarray(err, dtype=float)
    keep = (err > floor) & (dt <= dt.max() / 4.0)
    if keep.sum() < 3:
        return float("nan")
    return float(np.polyfit(np.log(dt[keep]), np.log(err[keep]), 1)[0])


def order_study(scene_path: str | os.PathLike, speeds_kmh: Sequence[float],
                substeps: Sequence[int] | None = None, overrides: dict | None = None,
                label: str | None = None,
                on_step: Callable[[str], None] | None = None) -> dict:
    """The time integrator's order on one scene: mu at each ``substeps`` (one
    backward-Euler pass each, ``tolerance = 0``), the Richardson value
    2 mu(s) - mu(s/2) of each pair, and the largest error of either over the
    speeds against the reference (the Richardson value of the two finest
    passes; its own uncertainty, taken as the change of the extrapolated
    value between the two finest pairs, is the floor below which no error is
    fitted). The fitted slopes of log error against log dt are the orders."""
    from ..core import load_scene

    scene = load_scene(scene_path)
    scene.parameters.update(overrides or {})
    speeds = np.asarray(speeds_kmh, dtype=float)
    s = np.asarray(ORDER_SUBSTEPS if substeps is None else substeps, dtype=int)
    mu = []
    for k in s:
        ds = scene.simulate(speeds_kmh=speeds, series=False, substeps=int(k), tolerance=0.0,
                            error_estimate=False, time_scheme="euler")
        mu.append(ds["mu"].values.copy())
        if on_step:
            on_step(f"order, substeps = {k}")
    mu = np.array(mu)
    rich = 2.0 * mu[1:] - mu[:-1]
    ref = rich[-1]
    floor = float(np.max(np.abs(rich[-1] - rich[-2])))
    err_e = np.max(np.abs(mu - ref), axis=1)
    err_r = np.max(np.abs(rich - ref), axis=1)
    dt = 1.0 / s          # in units of dx / V
    # the exact integrator where the scene allows it (a Kelvin-Voigt rubber
    # on a road without a film), its error and its cost against one pass
    _, t_one = _timed(scene, speeds, 3, substeps=int(s[0]), tolerance=0.0, time_scheme="euler")
    with warnings.catch_warnings():
        # a scene the exact scheme does not cover says so; here it is expected
        warnings.simplefilter("ignore")
        ex, t_exact = _timed(scene, speeds, 3, substeps=int(s[0]), tolerance=0.0,
                             time_scheme="exact")
    if on_step:
        on_step("order, exact")
    exact_ran = bool(np.all(ex["exact_integrator_ran"].values))
    # the default run (one pass and its error estimate, &numerics
    # error_estimate): what it says of its error against what it is
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")       # a large estimate warns; expected here
        dflt = scene.simulate(speeds_kmh=speeds, series=False, tolerance=0.0,
                              time_scheme="euler")
    if on_step:
        on_step("order, default estimate")
    return {"exact_ran": exact_ran,
            "default_estimate": dflt["mu_error_estimate"].values.tolist(),
            "default_error": np.abs(dflt["mu"].values - ref).tolist(),
            "exact_error": float(np.max(np.abs(ex["mu"].values - ref))) if exact_ran else None,
            "exact_cost": t_exact / t_one,
            "one_pass_s": t_one,
            "label": label or Path(scene_path).stem,
            "wet_model": (str(scene.parameters.get("wet_model", "kane2017"))
                          if scene.parameters["depth"] > 0 else "dry"),
            "substeps": s.tolist(), "dt": dt.tolist(),
            "euler_error": err_e.tolist(), "extrapolated_error": [np.nan] + err_r.tolist(),
            "floor": floor,
            "euler_order": fitted_order(dt[:-1], err_e[:-1], floor),
            "extrapolated_order": fitted_order(dt[1:-1], err_r[:-1], floor)}


# the order plot's line style per model
STYLES = {"dry": "--", "kane2017": "-", "squeeze": "-.", "reynolds": (0, (4, 1, 1, 1, 1, 1))}


def plot_order(rows: Sequence[dict], path: str | os.PathLike) -> str:
    """Log-log error against the time step, backward Euler and extrapolated,
    one colour per surface and one line style per model, with the fitted
    slopes (Euler, extrapolated) in the legend."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ..plot import save_figure

    legend_in = 0.12 * (-(-len(rows) // 3)) + 0.2     # the legend's height (inches)
    height = 4.2 + legend_in
    fig, axes = plt.subplots(1, 2, figsize=(11, height), dpi=110, sharey=True)
    colours: dict[str, str] = {}          # one colour per surface, one line style per model
    for r in rows:
        dt = np.asarray(r["dt"])
        for ax, key in ((axes[0], "euler_error"), (axes[1], "extrapolated_error")):
            err = np.asarray(r[key], dtype=float)
            keep = np.isfinite(err) & (err > 0)
            ax.loglog(dt[keep], err[keep], marker="o", ms=3, lw=1,
                      color=colours.setdefault(r["label"].split("_")[0], f"C{len(colours) % 10}"),
                      ls=STYLES.get(r["wet_model"], "-"),
                      label=(f"{r['label']} ({r['wet_model']}): slopes {r['euler_order']:.2f}, "
                             f"{r['extrapolated_order']:.2f}"))
    for ax, title in zip(axes, ("backward Euler, one pass", "extrapolated, 2 mu(s) - mu(s/2)")):
        x = np.array([1.0 / 512, 1.0])
        ax.loglog(x, 1e-2 * x, color="0.6", lw=0.8, ls=":")
        ax.loglog(x, 1e-2 * x**2, color="0.3", lw=0.8, ls=":")
        ax.set_title(title + " (dotted: slopes 1 and 2)", fontsize=9)
        ax.set_xlabel("time step (dx / V; 1 = the paper's)", fontsize=8)
        ax.grid(alpha=0.3, which="both")
    handles, labels = axes[1].get_legend_handles_labels()
    fig.legend(handles, labels, fontsize=6, loc="lower center", ncol=3, frameon=False)
    axes[0].set_ylabel("largest |mu - mu(limit)| over the speeds", fontsize=8)
    fig.tight_layout(rect=(0, legend_in / height, 1, 1))
    try:
        return save_figure(fig, path)
    finally:
        plt.close(fig)


def tolerance_study(scene_path: str | os.PathLike, mu_limit, speeds_kmh: Sequence[float],
                    tolerances: Sequence[float] = TOLERANCES, repeats: int = 3,
                    overrides: dict | None = None,
                    on_step: Callable[[str], None] | None = None) -> list[dict]:
    """The cost of each ``&numerics tolerance`` on one scene: for each
    tolerance, the error the run reports (``mu_error_estimate``), its actual
    error against ``mu_limit`` (the converged limit from :func:`study`), the
    substeps it chose, and its wall time against the default settings."""
    from ..core import load_scene

    scene = load_scene(scene_path)
    scene.parameters.update(overrides or {})
    speeds = np.asarray(speeds_kmh, dtype=float)
    _, t_default = _timed(scene, speeds, repeats)
    if on_step:
        on_step("default settings")
    rows = []
    for scheme in ("euler", "extrapolated"):
        for tol in tolerances:
            ds, seconds = _timed(scene, speeds, repeats, tolerance=float(tol),
                                 time_scheme=scheme)
            if on_step:
                on_step(f"tolerance = {tol:g} ({scheme})")
            rows.append({
                "scheme": scheme,
                "tolerance": float(tol),
                "estimate": float(np.max(ds["mu_error_estimate"].values)),
                "actual": float(np.max(np.abs(ds["mu"].values - np.asarray(mu_limit)))),
                "substeps": int(np.max(ds["substeps_used"].values)),
                "time_s": seconds,
                "cost": seconds / t_default,
                "met": bool(np.all(ds["mu_error_estimate"].values <= tol)),
            })
    return rows


#: The column line every accuracy CSV begins with (the replace rule's
#: signature: a file at the path that does not begin so is refused).
CSV_SIGNATURE = "scene,knob,value,error,convergence,time_s,element_steps,"


def to_csv(table, path: str | os.PathLike) -> None:
    """One row per setting: knob, value, error, time, element-steps, mu per
    speed (``write_text_output``'s rule: replaces only such a CSV)."""
    from ..core import write_text_output

    speeds = table["speed_kmh"].values
    rows = [CSV_SIGNATURE + ",".join(f"mu_{s:g}kmh" for s in speeds)]
    for i in range(table.sizes["setting"]):
        mu = ",".join(f"{m:.12g}" for m in table["mu"].values[i])
        rows.append(f"{table.attrs['label']},{table['knob'].values[i]},"
                    f"{table['value'].values[i]:g},{table['error'].values[i]:.6g},"
                    f"{table['convergence'].values[i]:.6g},"
                    f"{table['time_s'].values[i]:.6g},{table['element_steps'].values[i]},{mu}")
    write_text_output(path, "\n".join(rows) + "\n", CSV_SIGNATURE)


def to_netcdf(table, path: str | os.PathLike) -> None:
    """The table as NetCDF (source 'pavefric <version> ...': replaces only a
    pavefric results file, ``atomic_output``'s 'results' rule)."""
    from .. import __version__
    from ..core import atomic_output

    out = table.copy()
    out["knob"] = out["knob"].astype(str)
    out.attrs["source"] = f"pavefric {__version__} (accuracy study)"
    with atomic_output(path, replaces="results") as tmp:
        out.to_netcdf(tmp, format="NETCDF4")


def plot(tables: Sequence, path: str | os.PathLike, title: str | None = None) -> str:
    """Log-log error against time: one panel per knob, one line per scene
    (colour by surface, dashed when dry)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ..plot import save_figure

    knobs = list(dict.fromkeys(k for t in tables for k in t["knob"].values))
    ncols = 2
    nrows = (len(knobs) + 1) // 2
    fig, axes = plt.subplots(nrows, ncols, figsize=(10, 3.4 * nrows), dpi=110, squeeze=False)
    surfaces = list(dict.fromkeys(str(t.attrs["label"]).removesuffix("_dry") for t in tables))
    colours = {name: f"C{i % 10}" for i, name in enumerate(surfaces)}
    for ax, knob in zip(axes.flat, knobs):
        for table in tables:
            label = str(table.attrs["label"])
            surface = label.removesuffix("_dry")
            sel = table["knob"].values == knob
            if not sel.any():
                continue
            err = table["convergence"].values[sel]
            t = table["time_s"].values[sel]
            keep = err > 0                                 # the finest setting is 0
            if keep.any():
                ax.loglog(t[keep], err[keep], marker="o", ms=3, lw=1,
                          color=colours[surface], ls="--" if table.attrs["wet"] == 0 else "-")
        ax.set_title(knob, fontsize=10)
        ax.grid(alpha=0.3, which="both")
        ax.set_xlabel("wall time (s, best of repeats)", fontsize=8)
        ax.set_ylabel("|mu - mu(finest)|", fontsize=8)
    for ax in list(axes.flat)[len(knobs):]:
        ax.axis("off")
    handles = [plt.Line2D([], [], color=colours[s], label=s) for s in surfaces]
    handles += [plt.Line2D([], [], color="0.3", ls="-", label="wet"),
                plt.Line2D([], [], color="0.3", ls="--", label="dry")]
    fig.legend(handles=handles, loc="lower center", ncol=min(8, len(handles)), fontsize=8)
    fig.suptitle(title or "error against cost, per knob (each knob's own finest setting as "
                 "reference)", fontsize=10)
    fig.tight_layout(rect=(0, 0.06, 1, 0.97))
    try:
        return save_figure(fig, path)
    finally:
        plt.close(fig)


def recommend(tables: Sequence) -> dict[str, dict]:
    """For each budget (a cost limit relative to the default settings), the
    single-knob setting with the smallest worst-case error over the scenes
    among those whose worst-case cost stays within the limit."""
    out = {}
    candidates: dict[tuple, list] = {}
    for table in tables:
        knobs = table["knob"].values
        values = table["value"].values
        default = [i for i in range(table.sizes["setting"])
                   if knobs[i] == "substeps" and values[i] == 1.0]
        t_default = float(table["time_s"].values[default[0]]) if default else np.nan
        for i in range(table.sizes["setting"]):
            key = (str(knobs[i]), float(values[i]))
            candidates.setdefault(key, []).append(
                (float(table["error"].values[i]), float(table["time_s"].values[i]),
                 float(table["time_s"].values[i]) / t_default))
    for budget, limit in BUDGETS.items():
        best = None
        for (knob, value), res in candidates.items():
            if len(res) < len(tables):
                continue                       # not measured on every scene (dry-only knob)
            err = max(r[0] for r in res)
            t = max(r[1] for r in res)
            cost = max(r[2] for r in res)
            # the default itself (cost 1 by definition) is always allowed
            if (cost <= limit or (knob, value) == ("substeps", 1.0)) and \
                    (best is None or err < best[2]):
                best = (knob, value, err, t, cost)
        if best:
            out[budget] = {"knob": best[0], "value": best[1], "error": best[2],
                           "time_s": best[3], "cost": best[4], "limit": limit}
    return out
