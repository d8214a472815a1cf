"""The generalised Maxwell rubber's report: ``python -m pavefric rubber-report``
regenerates ``docs/rubber.md`` and its figures from scratch.

- The element, its exact step, the contact test and the free recovery, the
  WLF shift and why time-temperature superposition is exact on a dry scene,
  the closed form of a sinusoid's hysteresis friction (the tests' must-shows).
- The example compound (``inputs/rubber/tread_compound.nml``) against the
  DMA data it was fitted to (``inputs/data/tread_compound_dma.csv``).
- Friction against speed at several temperatures on the six reference
  surfaces (``inputs/surfaces/*.nml``), dry and with their 1 mm of water,
  beside the paper's Kelvin-Voigt rubber; time-temperature superposition
  measured on the dry runs.
- What the Prony element costs per element-step against Kelvin-Voigt,
  measured in the same run (``cost``, also called by ``python -m pavefric
  bench``).

Every friction value comes from the Fortran core (``pavefric.simulate``).
"""
from __future__ import annotations

import json
import time
import warnings
from pathlib import Path

import numpy as np

from ..rubber import (REPRESENTATIVE, THICKNESS, compound, fit_prony, plot_fit, read_dma,
                     wlf_log10_shift)

SURFACES = ["GSP", "GSS", "GSSB", "RSBA", "MCA", "VTAC"]
TEMPERATURES = [-10.0, 0.0, 10.0, 20.0, 30.0, 40.0]
SPEEDS = [1.0, 5.0, 10.0, 20.0, 30.0, 40.0, 50.0, 60.0, 70.0, 80.0]
DATA = "inputs/data/tread_compound_dma.csv"
#: The numerics of the report's curves: the stiff compound needs finer steps
#: than the paper's rubber (the resolution table of the report measures it).
NUMERICS = dict(substeps=16, elements_per_sample=4)
#: The settings of the resolution table (substeps, elements_per_sample).
RESOLUTIONS = [(1, 1), (4, 1), (16, 1), (16, 4), (16, 8)]
#: The three-arm element of the cost target (issue 14: at most 1.5x
#: Kelvin-Voigt per element-step).
THREE_ARMS = dict(rubber_model="maxwell", prony_stiffness=[1e8, 2e8, 1e8],
                  prony_times=[1e-5, 1e-4, 1e-3])


def cost(log=print, compound_file: str | Path | None = "inputs/rubber/tread_compound.nml",
         repeats: int = 7) -> dict:
    """ns per element-step of the rubber components on a dry 65,536-point
    profile at four speeds (one chunk of lanes), best of ``repeats`` runs
    taken in turn (so load on the machine hits every case alike)."""
    from ..core import simulate
    from ..surfaces import spectral_profile

    z = np.tile(spectral_profile(1024, 0.87e-3, rms=0.5e-3, skew=-0.3, seed=22), 64)
    speeds = [20.0, 40.0, 60.0, 80.0]
    cases = {"kelvin_voigt (paper, C = 100)": {},
             "kelvin_voigt elastic (C = 0, no memory)": {"viscosity": 0.0},
             "maxwell, 1 arm": dict(THREE_ARMS, prony_stiffness=[1e8], prony_times=[1e-4]),
             "maxwell, 3 arms": dict(THREE_ARMS)}
    if compound_file is not None and Path(compound_file).exists():
        c = compound(compound_file)
        cases[f"maxwell, the example compound ({len(c['prony_times'])} arms)"] = c
    best = {k: np.inf for k in cases}
    steps = 0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for kw in cases.values():                       # warm up
            simulate(z[:2048], 0.87e-3, speeds, mu_loc=0.6, error_estimate=False,
                     min_contacts=0, **kw)
        for _ in range(repeats):
            for name, kw in cases.items():
                t0 = time.perf_counter()
                # one pass at the elements given: the error estimate's passes
                # and min_contacts' refinement would count several times
                ds = simulate(z, 0.87e-3, speeds, mu_loc=0.6, error_estimate=False,
                              min_contacts=0, **kw)
                best[name] = min(best[name], time.perf_counter() - t0)
                steps = ds.attrs["pad_elements"] * (ds.attrs["averaged_positions"] +
                                                    ds.attrs["spinup_positions"]) * len(speeds)
    base = best["kelvin_voigt (paper, C = 100)"]
    rows = [dict(case=k, ns=1e9 * v / steps, ratio=v / base) for k, v in best.items()]
    log("\n== Rubber components: cost per element-step (dry, 65,536 points, N = 23, "
        "4 speeds, best of %d) ==" % repeats)
    for r in rows:
        log(f"{r['case']:48s} {r['ns']:7.2f} ns  {r['ratio']:5.2f}x Kelvin-Voigt")
    three = next(r for r in rows if r["case"] == "maxwell, 3 arms")
    log(f"target: 3 arms at most 1.5x Kelvin-Voigt: {three['ratio']:.2f}x "
        f"({'met' if three['ratio'] <= 1.5 else 'NOT met'})")
    return {"rows": rows, "steps": steps, "three_arms_ratio": three["ratio"]}


def _scene_parameters(name: str):
    from ..core import load_scene

    scene = load_scene(Path("inputs/surfaces") / f"{name}.nml")
    return scene


def _base(scene, rubber: dict, numerics: dict) -> dict:
    """The scene's keywords without the rubber's, with ``numerics`` as given:
    the pad not refined beyond them (&numerics min_contacts = 0), so that each
    row is the resolution it names."""
    base = {k: v for k, v in scene.parameters.items() if k not in rubber and k != "temperature"}
    base.update(numerics)
    base.setdefault("min_contacts", 0)
    # the report shows mu, not its estimate: no estimate passes (they do
    # not change mu, and cost up to hundreds of runs on a stiff pad)
    base.setdefault("error_estimate", False)
    return base


def friction_curves(rubber: dict, temperatures=TEMPERATURES, speeds=SPEEDS,
                    surfaces=SURFACES, numerics=NUMERICS) -> dict:
    """mu[surface][water][temperature] against speed, and the paper's rubber."""
    from ..core import simulate

    out = {}
    rubber = {k: v for k, v in rubber.items() if k != "temperature"}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for name in surfaces:
            scene = _scene_parameters(name)
            base = _base(scene, rubber, numerics)
            depth = base.get("depth", 0.0)
            out[name] = {"depth": depth, "mu_loc": base["mu_loc"]}
            for water, d in (("dry", 0.0), ("wet", depth)):
                p = dict(base, depth=d)
                curves = {"kelvin_voigt": simulate(scene.heights, scene.dx, speeds,
                                                   closed=scene.closed, **p)["mu"].values.tolist()}
                for t in temperatures:
                    ds = simulate(scene.heights, scene.dx, speeds, closed=scene.closed,
                                  temperature=t, **p, **rubber)
                    curves[t] = ds["mu"].values.tolist()
                out[name][water] = curves
    return out


def hysteresis_table(rubber: dict, temperatures=TEMPERATURES, surfaces=SURFACES,
                     speed: float = 20.0, numerics=NUMERICS) -> dict:
    """mu at ``speed`` on the dry surfaces with mu_loc = 0 (no local friction):
    elastic pads (viscosity 0) of the paper's K and of 1e10 N m-3, and the
    compound at each temperature."""
    from ..core import simulate

    rubber = {k: v for k, v in rubber.items() if k != "temperature"}
    out = {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for name in surfaces:
            scene = _scene_parameters(name)
            base = _base(scene, rubber, numerics)
            base.update(depth=0.0, mu_loc=0.0)
            row = {}
            for k in (1.4e8, 1e10):
                p = dict(base, stiffness=k, viscosity=0.0)
                row[f"elastic {k:.2g}"] = float(simulate(scene.heights, scene.dx, [speed],
                                                         closed=scene.closed, **p)["mu"][0])
            p = dict(base, stiffness=1e10, viscosity=0.0, substeps=1, elements_per_sample=1)
            row["elastic 1e+10, default numerics"] = float(simulate(
                scene.heights, scene.dx, [speed], closed=scene.closed, **p)["mu"][0])
            # the paper's discretisation of the same elastic pads (Eq. 10 on
            # central differences): friction where nothing dissipates
            for key, q in (("paper elastic 1e+10", dict(base, stiffness=1e10, viscosity=0.0)),
                           ("paper elastic 1e+10, default numerics", p)):
                q = dict(q, friction_scheme="paper", element_length=0.0)
                row[key] = float(simulate(scene.heights, scene.dx, [speed], closed=scene.closed,
                                          **q)["mu"][0])
            for t in temperatures:
                row[t] = float(simulate(scene.heights, scene.dx, [speed], closed=scene.closed,
                                        temperature=t, **base, **rubber)["mu"][0])
            out[name] = row
    return out


def resolution_table(rubber: dict, surfaces=SURFACES, speed: float = 20.0,
                     resolutions=RESOLUTIONS) -> dict:
    """mu at ``speed`` on the dry surfaces at each (substeps, elements_per_sample):
    the paper's rubber and the compound at its reference temperature."""
    from ..core import simulate

    rubber = {k: v for k, v in rubber.items() if k != "temperature"}
    out = {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for name in surfaces:
            scene = _scene_parameters(name)
            rows = {}
            for ss, eps in resolutions:
                base = _base(scene, rubber, dict(substeps=ss, elements_per_sample=eps))
                base["depth"] = 0.0
                kv = float(simulate(scene.heights, scene.dx, [speed], closed=scene.closed,
                                    **base)["mu"][0])
                mx = float(simulate(scene.heights, scene.dx, [speed], closed=scene.closed,
                                    **base, **rubber)["mu"][0])
                rows[f"{ss},{eps}"] = (kv, mx)
            out[name] = rows
    return out


TEMPERATURE_SWEEP = [-20.0, -10.0, 0.0, 10.0, 20.0, 30.0, 40.0, 50.0, 60.0, 70.0, 80.0]


def temperature_sweep(rubber: dict, surfaces=("GSSB", "MCA"), speeds=(20.0, 60.0),
                      temperatures=TEMPERATURE_SWEEP, numerics=NUMERICS) -> dict:
    """mu_hysteresis and mu_adhesion against temperature, dry, each surface's
    mu_loc, at ``speeds`` (the energy scheme's split of mu)."""
    from ..core import simulate

    rubber = {k: v for k, v in rubber.items() if k != "temperature"}
    out = {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for name in surfaces:
            scene = _scene_parameters(name)
            base = dict(_base(scene, rubber, numerics), depth=0.0)
            rows = {"hysteresis": [], "adhesion": []}
            for t in temperatures:
                ds = simulate(scene.heights, scene.dx, list(speeds), closed=scene.closed,
                              temperature=t, **base, **rubber)
                rows["hysteresis"].append(ds["mu_hysteresis"].values.tolist())
                rows["adhesion"].append(ds["mu_adhesion"].values.tolist())
            out[name] = {"mu_loc": base["mu_loc"], **rows}
    return {"speeds": list(speeds), "temperatures": list(temperatures), "surfaces": out}


def _figure_temperature(path: Path, sweep: dict) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    names = list(sweep["surfaces"])
    temps = sweep["temperatures"]
    fig, axes = plt.subplots(2, len(names), figsize=(3.6 * len(names), 6.0), dpi=110,
                             sharex=True)
    axes = np.atleast_2d(axes).reshape(2, len(names))
    for col, name in enumerate(names):
        d = sweep["surfaces"][name]
        for j, v in enumerate(sweep["speeds"]):
            style = "-" if j == 0 else "--"
            h = [r[j] for r in d["hysteresis"]]
            a = [r[j] for r in d["adhesion"]]
            axes[0, col].plot(temps, h, "C3" + style, label=f"hysteresis, {v:g} km/h")
            axes[0, col].plot(temps, a, "C0" + style, label=f"adhesion, {v:g} km/h")
            axes[1, col].plot(temps, np.add(h, a), "k" + style, label=f"μ, {v:g} km/h")
        axes[0, col].set_title(f"{name}, dry, μ_loc = {d['mu_loc']:g}", fontsize=9)
        axes[1, col].set_xlabel("rubber temperature (°C)")
        for ax in axes[:, col]:
            ax.grid(alpha=0.3)
    axes[0, 0].set_ylabel("μ_hysteresis, μ_adhesion")
    axes[1, 0].set_ylabel("μ")
    axes[0, 0].legend(fontsize=7)
    axes[1, 0].legend(fontsize=7)
    fig.suptitle("The example compound against temperature: the rubber's dissipation and "
                 "the local friction's work (energy scheme)", fontsize=10)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path)
    plt.close(fig)
    return path


def superposition(rubber: dict, surface: str = "GSSB", temperatures=(0.0, 10.0, 30.0, 40.0),
                  speeds=SPEEDS) -> dict:
    """Largest |mu(T, V) / mu(Tref, V a_T) - 1| on the dry surface."""
    from ..core import simulate

    scene = _scene_parameters(surface)
    rubber = {k: v for k, v in rubber.items() if k != "temperature"}
    base = {k: v for k, v in scene.parameters.items() if k not in rubber and k != "temperature"}
    base["depth"] = 0.0
    base["error_estimate"] = False          # mu only (the estimate would not change it)
    tref = rubber["reference_temperature"]
    worst = 0.0
    rows = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for t in temperatures:
            a_t = 10.0 ** float(wlf_log10_shift(t, tref, rubber["wlf_c1"], rubber["wlf_c2"]))
            v = np.asarray(speeds)
            mu_t = simulate(scene.heights, scene.dx, v, temperature=t, **base, **rubber)["mu"].values
            mu_r = simulate(scene.heights, scene.dx, v * a_t, temperature=tref, **base,
                            **rubber)["mu"].values
            dev = float(np.max(np.abs(mu_t / mu_r - 1)))
            worst = max(worst, dev)
            rows.append(dict(temperature=t, a_t=a_t, deviation=dev))
    return {"surface": surface, "rows": rows, "worst": worst}


def _figure_curves(path: Path, curves: dict, temperatures) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    path.parent.mkdir(parents=True, exist_ok=True)
    names = list(curves)
    fig, axes = plt.subplots(2, len(names), figsize=(3.0 * len(names), 6.4), dpi=110,
                             sharex=True, sharey="row")
    cmap = plt.get_cmap("coolwarm")
    for col, name in enumerate(names):
        for row, water in enumerate(("dry", "wet")):
            ax = axes[row, col]
            c = curves[name][water]
            ax.plot(SPEEDS, c["kelvin_voigt"], "k--", lw=1.2, label="paper's Kelvin–Voigt")
            for k, t in enumerate(temperatures):
                ax.plot(SPEEDS, c[t], "-", color=cmap(k / max(1, len(temperatures) - 1)),
                        lw=1.4, label=f"{t:g} °C")
            title = f"{name}, dry" if water == "dry" else \
                f"{name}, {1e3 * curves[name]['depth']:g} mm water"
            ax.set_title(title, fontsize=9)
            ax.grid(alpha=0.3)
            if row == 1:
                ax.set_xlabel("speed (km/h)")
            if col == 0:
                ax.set_ylabel("μ")
    axes[0, 0].legend(fontsize=7, loc="upper left", ncol=2)
    fig.suptitle("Friction against speed: the example tread compound at six temperatures "
                 "(Maxwell element) and the paper's rubber", fontsize=10)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)
    return path


def run_report(report: str | Path = "docs/rubber.md",
               compound: str | Path = "inputs/rubber/tread_compound.nml", quick: bool = False,
               log=print, outdir: str | Path = "outputs") -> dict:
    """Run everything and write the report, its figures and a JSON of the numbers."""
    from .. import rubber as rubber_mod

    t0 = time.perf_counter()
    report = Path(report)
    figdir = report.parent / "figures"
    rubber = rubber_mod.compound(compound)
    temperatures = [0.0, 20.0, 40.0] if quick else TEMPERATURES
    surfaces = ["GSSB", "MCA"] if quick else SURFACES
    data = read_dma(DATA)
    fit = fit_prony(data, reference=rubber["reference_temperature"], c1=rubber["wlf_c1"],
                    c2=rubber["wlf_c2"])
    shipped = np.array(rubber["prony_stiffness"]) * THICKNESS
    same_fit = (shipped.size == fit.e_arms.size and
                np.allclose(shipped, fit.e_arms, rtol=1e-5) and
                np.allclose(rubber["prony_times"], fit.times, rtol=1e-5))
    fig_fit = plot_fit(fit, data, figdir / "rubber_compound.png", inputs=[DATA],
                       title="The example tread compound: DMA data shifted to 20 °C and its "
                       "Prony series")
    log("rubber-report: friction curves ...")
    curves = friction_curves(rubber, temperatures, SPEEDS, surfaces)
    fig_mu = _figure_curves(figdir / "rubber_mu_speed.png", curves, temperatures)
    hysteresis = hysteresis_table(rubber, temperatures, surfaces)
    log("rubber-report: temperature sweep ...")
    sweep = temperature_sweep(rubber, temperatures=[0.0, 20.0, 40.0] if quick
                              else TEMPERATURE_SWEEP)
    fig_t = _figure_temperature(figdir / "rubber_mu_temperature.png", sweep)
    log("rubber-report: resolution ...")
    resolution = resolution_table(rubber, surfaces)
    log("rubber-report: time-temperature superposition ...")
    tts = superposition(rubber)
    log("rubber-report: cost ...")
    # quick: one repeat (the report runs, the cost is not measured to any precision)
    costs = cost(log, compound, repeats=1 if quick else 7)
    seconds = time.perf_counter() - t0
    numbers = {"curves": {s: {w: {str(k): v for k, v in c.items()} if isinstance(c, dict) else c
                              for w, c in d.items()} for s, d in curves.items()},
               "superposition": tts, "cost": costs,
               "hysteresis": {n: {str(k): v for k, v in r.items()} for n, r in hysteresis.items()},
               "resolution": resolution, "numerics": NUMERICS, "temperature_sweep": sweep,
               "fit": {
                   "arms": int(fit.e_arms.size), "rms_storage": fit.rms_storage,
                   "rms_loss": fit.rms_loss, "same_as_shipped": bool(same_fit)},
               "seconds": seconds, "quick": quick}
    out = Path(outdir)
    out.mkdir(parents=True, exist_ok=True)
    (out / "rubber.json").write_text(json.dumps(numbers, indent=1, default=float))
    _write_report(report, rubber, fit, same_fit, curves, temperatures, tts, costs, fig_fit,
                  fig_mu, seconds, quick, Path(compound), hysteresis, resolution, sweep, fig_t)
    log(f"rubber-report: wrote {report}, {fig_fit}, {fig_mu} ({seconds:.0f} s)")
    return numbers


def _fmt_list(values, fmt="{:.3g}") -> str:
    return ", ".join(fmt.format(v) for v in values)


def _write_report(path: Path, rubber, fit, same_fit, curves, temperatures, tts, costs,
                  fig_fit: Path, fig_mu: Path, seconds: float, quick: bool,
                  compound_path: Path, hysteresis: dict, resolution: dict, sweep: dict,
                  fig_t: Path) -> None:
    from .reports import machine_description

    rel = lambda p: Path(p).relative_to(path.parent).as_posix()  # noqa: E731
    tref = rubber["reference_temperature"]
    n_arms = len(rubber["prony_times"])
    three = costs["three_arms_ratio"]
    rep = REPRESENTATIVE
    s_lo, _ = fit.moduli(np.array([1e3, 1e5]))
    stiff_lo, stiff_hi = s_lo / fit.e_inf
    fine = fit_prony(read_dma(DATA), reference=fit.reference_temperature, c1=fit.c1, c2=fit.c2,
                     per_decade=2.0)
    lines = [
        "# Rubber that behaves like rubber: the generalised Maxwell element and temperature",
        "",
        f"Generated by `python -m pavefric rubber-report`{' --quick' if quick else ''} on "
        f"{machine_description()}, {time.strftime('%Y-%m-%d')} ({seconds:.0f} s). Numbers also "
        "in `outputs/rubber.json`. MODEL.md §9; issue 14.",
        "",
        "The paper's Kelvin–Voigt rubber (K = 1.4e8 N m⁻³, C = 100 N s m⁻³) has a retardation "
        "time C/K = 0.7 µs, far below the 39 µs or more an element spends over a sample at up to "
        "80 km/h: it is effectively elastic, its dry friction flat in speed, and it has no "
        "temperature. `&rubber model = 'maxwell'` replaces it by a generalised Maxwell (Prony) "
        "element whose relaxation times follow the temperature through the WLF equation. The "
        "default (`model = 'kelvin_voigt'`, `temperature = reference_temperature`) with the "
        "paper's discretisation (`friction_scheme = 'paper'`, `element_length = 0`, "
        "`min_contacts = 0`) gives the paper's model as 0.1.0 computed it: dry bit for bit, "
        "wet to rounding (tests/test_regression.py).",
        "",
        "## The element",
        "",
        "Per unit length of pad, like K: an equilibrium spring K∞ (`stiffness`) in parallel "
        "with arms k = 1…n, each a spring K_k (`prony_stiffness`) in series with a dashpot of "
        "relaxation time τ_k (`prony_times`). With v_k the dashpot's displacement (the arm's "
        "relaxed compression) and u the element's compression,",
        "",
        "    p = K∞ u + Σ_k K_k (u − v_k),    τ_k dv_k/dt = u − v_k,",
        "",
        "so the arm's stress s_k = K_k (u − v_k) obeys ds_k/dt = K_k du/dt − s_k/τ_k. Its "
        "complex modulus is E*(ω) = K∞ + Σ K_k iωτ_k/(1 + iωτ_k): storage "
        "E' = K∞ + Σ K_k ω²τ_k²/(1 + ω²τ_k²), loss E'' = Σ K_k ωτ_k/(1 + ω²τ_k²) "
        "(per unit length, N m⁻³).",
        "",
        "**One step, exactly.** The pad advances one (refined) sample per step, "
        "Δt = advance/V, and the element's compression between two steps is linear in time "
        "(the profile is linear between its samples). Over a step in which u goes linearly "
        "from u0 to u1, the arm equation integrates exactly; with r = Δt/τ, E = e^(−r), "
        "G = (1 − E)/r,",
        "",
        "    v_k(1) = E v_k(0) + (1/τ)∫₀^Δt e^(−(Δt−s)/τ) u(s) ds = (1 − G) u1 + (G − E) u0 + E v_k(0),",
        "",
        "(the integral of e^(−σ/τ) times the linear u, σ = Δt − s), i.e. for the arm's stress "
        "s_k(1) = E s_k(0) + K_k (u1 − u0)(τ/Δt)(1 − e^(−Δt/τ)). The three weights 1 − G, "
        "G − E and E are ≥ 0 and sum to 1 (e^r − 1 ≥ r gives G ≥ E), so v_k stays between the "
        "compressions the element has had: it cannot drift or overflow.",
        "",
        "**The contact form.** The pressure at the step's end is linear in u1:",
        "",
        "    p = k_eff (u1 − u_free),   k_eff = K∞ + Σ_k K_k G_k,",
        "    u_free = Σ_k K_k [(G_k − E_k) u0 + E_k v_k(0)] / k_eff,",
        "",
        "the form every rubber component gives the driver (`pavefric_rubber`). k_eff is the "
        "same for every element at a speed; u_free, the compression at which the element "
        "would end the step carrying nothing, comes from its own history and is ≥ 0 (u0, v_k ≥ 0 "
        "and all weights ≥ 0). As for Kelvin–Voigt (MODEL.md §3):",
        "",
        "- **Contact test**: the element touches iff its geometric compression g = δ − h_i + z_k "
        "exceeds u_free. Then u1 = g and p = k_eff (g − u_free) > 0. Pressing it to g when "
        "g ≤ u_free would need p ≤ 0, a pull the road cannot exert, so \"negative pressure "
        "set to zero\" and \"the recovering rubber is above the road\" are the same condition "
        "and the test is exact for the discrete scheme.",
        "- **Free recovery**: out of contact the element ends the step at u1 = u_free, where "
        "its pressure is zero; every arm then updates with u1 = u_free. The pressure is zero "
        "at the step's end, not all through it: the true free path (p ≡ 0, a sum of "
        "exponentials) is replaced by its linear interpolation between steps, a difference "
        "of O(Δt²) per step, as for the piecewise-linear profile.",
        "- The new state is u1 = u_free + push, push = max(0, g − u_free) (never negative), "
        "then each v_k as above; the driver and the load balance see only k_eff and u_free.",
        "",
        "**Limits.** V = 0 (Δt → ∞) and τ_k → 0 give E = G = 0: the arms relax within a step, "
        "k_eff = K∞, u_free = 0 — the elastic pad of `stiffness` alone (no memory is kept at "
        "V = 0). τ_k → ∞ gives E = G = 1: v_k never moves from 0, u_free = 0 exactly and "
        "k_eff = K∞ + Σ K_k — the elastic pad of the instantaneous stiffness. Both are tested "
        "against `model = 'kelvin_voigt'`, `viscosity = 0` with those stiffnesses.",
        "",
        "**Numerics** [`pavefric_maxwell`]. r = advance/(V τ) ranges over hundreds of decades "
        "(τ from 1e-300 to 1e30 s, a_T up to 1e±100), so the weights avoid cancellation: for "
        "r < 1, 1 − G = Σ_{n≥1} (−1)^(n+1) rⁿ/(n+1)! (18 terms, Horner), G = 1 − (1 − G), "
        "G − E = rG − (1 − G); for r ≥ 1, G = (1 − e^(−r))/r, 1 − G and G − E directly "
        "(e^(−r) ≤ 0.37 there, no cancellation); r > 1e300 (or V = 0) is the relaxed limit, "
        "exp is not called below its underflow. The state per element is u and the v_k "
        "(`state_size` = 1 + n); per element-step, u_free costs n + 1 multiplications and "
        "the update 3n; the lane loops run on explicit shapes, four lanes a vector.",
        "",
        "Kelvin–Voigt (backward Euler, first order in Δt) stays the default; the Maxwell step "
        "is exact for the piecewise-linear compression, so what remains of the time "
        "discretisation is the profile's sampling and the contact's timing (an element "
        "gains or loses contact at a step's end only; see Resolution below).",
        "",
        "## Temperature: the WLF shift",
        "",
        "Every relaxation time is multiplied by a_T, log10 a_T = −C1 (T − Tref)/(C2 + T − Tref) "
        "(Williams, Landel & Ferry 1955): `temperature`, `reference_temperature` (°C), "
        "`wlf_c1`, `wlf_c2` (K). At T = Tref a_T is exactly 1 (the default: 20 °C both), so "
        "the default scene is unchanged. T − Tref ≤ −C2 (where the equation diverges) and "
        "shifts beyond 10^±100 are refused with a message naming the values. For "
        "`model = 'kelvin_voigt'` the retardation time C/K is shifted likewise (C → a_T C). "
        "The defaults C1 = 8.86, C2 = 101.6 K are WLF's for a reference temperature about "
        "50 K above the glass transition.",
        "",
        "**Time–temperature superposition is exact on a dry scene.** In a dry scene the rubber "
        "enters the computation only through its stiffnesses and r_k = Δt/τ_k(T) = "
        "advance/(V a_T τ_k) (Kelvin–Voigt: through C(T) V = a_T C V); the profile, the pad, "
        "the facets and μ_loc do not depend on V or T. So every number computed at (T, V) is "
        "computed at (Tref, V a_T) from the same r_k, and μ(T, V) = μ(Tref, V a_T) up to the "
        "rounding of the products V a_T τ_k taken in another order. Measured on "
        f"{tts['surface']} (dry, the example compound): largest |μ(T, V)/μ(Tref, V a_T) − 1| "
        f"= {tts['worst']:.1e} over T = "
        f"{_fmt_list([r['temperature'] for r in tts['rows']], '{:g}')} °C and "
        f"{len(SPEEDS)} speeds (tests/test_rubber.py asserts it to 1e-12). Scaled: the "
        "relaxation times only. Not scaled: the moduli (no vertical shift b_T = ρT/ρ0T0, a "
        "few per cent over 40 K; it would change k_eff and break exact superposition), the "
        "water's viscosity (set `&water viscosity` for the water's own temperature), the "
        "bearing's V^β and the squeeze film's flow — so on a wet scene superposition does "
        "not hold, and should not: water does not follow the rubber's shift — and μ_loc "
        "(adhesion has its own temperature dependence; set it).",
        "",
        "## The closed form on a sinusoid (test 3)",
        "",
        "Profile z = A sin(kx) and a pad of whole periods, loaded so that every element is "
        "always in contact, μ_loc = 0. Then tan θ_k is the facet slope s_k itself, and "
        "μ = Σ_i F_i s_i / W with F_i = l dx p_i (Eqs. 2, 10, 11). In steady state element i "
        "sees u = δ + A sin φ, φ = k(x_i + Vt), a sinusoid of angular frequency ω = kV, so "
        "p = K∞ δ + A (E' sin φ + E'' cos φ) while s = A k cos φ; the time average of p s is "
        "A² k E''(ω)/2 (the δ and E' terms average out: sin φ cos φ and, over whole periods "
        "of the pad, Σ s_i = 0). Summing over the N elements:",
        "",
        "    μ = N l dx k A² E''(kV) / (2W),   E''(ω) = Σ_k K_k ωτ_k / (1 + ω²τ_k²)   (per unit length).",
        "",
        "The model samples the profile at dx: the element sees the piecewise-linear "
        "interpolant, to which the exact step answers with the discrete modulus "
        "E*_d(θ) = K∞ + Σ K_k G_k (1 − e^(−iθ))/(1 − E_k e^(−iθ)), θ = k dx, and the central "
        "difference slope has amplitude A sin(k dx)/dx; so the model gives "
        "μ_d = N l dx (sin(k dx)/dx) A² Im E*_d(θ)/(2W) to rounding (once the start-up "
        "transient, which decays as E_k per step, has died out), and μ_d = μ (1 + O((k dx)²)). "
        "tests/test_rubber.py checks both: μ against μ_d to 1e-12, and μ against the "
        "continuous μ at 16, 32, 64, 128 samples a wavelength with the error falling fourfold "
        "per halving of dx (second order; −3.8 % at 16, −0.06 % at 128 samples).",
        "",
        "## The example compound",
        "",
        f"`{compound_path.as_posix()}` holds a {n_arms}-arm Prony series written by",
        "",
        f"    python -m pavefric prony {DATA} -o {compound_path.as_posix()}",
        "",
        f"from `{DATA}`, which is **not a measurement**: it is a representative tread compound, "
        "written by `python -m pavefric prony --write-representative "
        f"{DATA}` from a stated model (its header and inputs/data/README.md say so): a "
        "Havriliak–Negami glass transition E*(ω) = E_g − (E_g − E_r)/(1 + (iωa_Tτ)^α)^β "
        "(Havriliak & Negami 1966, J. Polym. Sci. C 14, 99) with "
        f"E_r = {rep['e_rubbery'] / 1e6:g} MPa (a passenger-car tread's low-frequency Young's "
        f"modulus), E_g = {rep['e_glassy'] / 1e9:g} GPa (glassy "
        f"elastomers: 1–3 GPa), β = {rep['beta']:g}, and τ = {rep['tau']:g} s, "
        f"α = {rep['alpha']:g} set so that tan δ at 10 Hz is 0.50 at 0 °C and 0.12 at 60 °C "
        "(typical values of the wet-grip and rolling-resistance indicators of passenger-car "
        "tread compounds), "
        "shifted by WLF's C1 = 8.86, C2 = 101.6 K about Tref = 20 °C (taken 50 K above a glass "
        "transition of −30 °C); frequency sweeps 0.1–100 Hz at −20 to 60 °C. Replace it with "
        "your compound's DMA data: the CSV format is in `python -m pavefric prony --help` and "
        "pavefric/rubber.py.",
        "",
        f"The fit: non-negative least squares (`scipy.optimize.nnls`) over one relaxation time "
        f"a decade, a decade beyond the data's reduced frequencies on either side, relative "
        f"errors: {fit.e_arms.size} arms, RMS error {100 * fit.rms_storage:.2f} % in E' and "
        f"{100 * fit.rms_loss:.2f} % in E'' (two times a decade: {100 * fine.rms_storage:.2f} % "
        f"and {100 * fine.rms_loss:.2f} % with {fine.e_arms.size} arms, at a higher cost). "
        + ("The shipped file is this fit." if same_fit else
           "**The shipped file differs from this fit: regenerate it.**"),
        "",
        f"![The compound's master curve and its Prony series]({rel(fig_fit)})",
        "",
        "**From moduli to stiffness per unit length.** The element works with N m⁻³ like the "
        "paper's K: a modulus becomes one by dividing by a length. A thin layer of "
        "thickness h pressed between plates carries p = E u/h, so `prony` writes K = E/h "
        f"with h = `--thickness` (default {THICKNESS * 1e3:g} mm, the DFT pad's rubber); shear "
        "data are converted by E = 3G (`--modulus shear`). This is an assumption of the "
        "element model, not a property of the compound: a pad indented by texture of "
        "wavelength λ responds more like a half-space, p/u ≈ E k/(2(1 − ν²)) = 2πE/(1.5λ), "
        "which is E/h with h ≈ λ/4 (h = 6 mm for λ ≈ 25 mm). Note what it means: the "
        "compound's "
        f"K∞ = {rubber['stiffness']:.3g} N m⁻³ is {rubber['stiffness'] / 1.4e8:.1f}x the "
        "paper's K, and at texture frequencies (10³–10⁵ rad/s at 20 °C) the compound's "
        f"storage modulus is {stiff_lo:.0f}–{stiff_hi:.0f} times its equilibrium one; the "
        "paper's K = 1.4e8 corresponds to E = 0.84 MPa by K = E/h, softer than a tread "
        "compound.",
        "",
        "## Friction against speed and temperature",
        "",
        f"The reference surfaces (`inputs/surfaces/*.nml`: each scene's profile, μ_loc and "
        "water, 1 mm with the paper's bearing at the calibrated α), dry and wet, with the "
        f"example compound at {_fmt_list(temperatures, '{:g}')} °C, beside the paper's "
        "Kelvin–Voigt rubber (dashed), all at `&numerics substeps = "
        f"{NUMERICS['substeps']}, elements_per_sample = {NUMERICS['elements_per_sample']}, "
        "min_contacts = 0` (below: why).",
        "",
        "**Resolution.** The compound is far stiffer than the paper's rubber at texture "
        "frequencies, and a stiff element that gains or loses contact within a step is "
        "placed by the step's end only: at the paper's numerics (one step and one element "
        "per sample, `min_contacts = 0`) the compound's friction is far from converged, while the paper's rubber "
        "is within a few hundredths (docs/accuracy.md). μ at 20 km/h, dry, the compound at "
        f"{tref:g} °C (the paper's rubber in brackets), against `(substeps, "
        "elements_per_sample)`:",
        "",
        "| surface | " + " | ".join(f"({k})" for k in next(iter(resolution.values()))) + " |",
        "|---|" + "---|" * len(next(iter(resolution.values()))),
        *[f"| {n} | " + " | ".join(f"{mx:.3f} ({kv:.3f})" for kv, mx in rows.values()) + " |"
          for n, rows in resolution.items()],
        "",
        "The Maxwell step is exact for a compression linear in time, so what converges here "
        "is the contact's timing and the pad's discretisation, not the rubber's integration. "
        "The rows are at the `(substeps, elements_per_sample)` they name, `min_contacts = 0`; "
        "the default `min_contacts = 4` refines the elements where the pad stands on fewer "
        "than 4 (docs/accuracy.md, \"The pad's resolution\"). "
        "Use `substeps` ≥ 16 and `elements_per_sample` ≥ 4 with a compound of this "
        "stiffness, and check the convergence on your own profiles (`python -m pavefric "
        "accuracy`). At the default cost, `&numerics time_scheme = 'richardson'` removes "
        "most of the step's share for a curve against temperature (on "
        "inputs/profiles/ctm_medium.txt, mu_loc = 0: within 0.004 of the resolved curve "
        "where the default's own pass is up to 0.020 off; docs/model.md, \"Temperature, "
        "with the energy scheme\"); the elements' share it leaves.",
        "",
        f"![mu against speed at several temperatures]({rel(fig_mu)})",
        "",
        "| surface | water | rubber | " + " | ".join(f"{v:g} km/h" for v in (20, 40, 60, 80))
        + " |",
        "|---|---|---|" + "---|" * 4,
    ]
    idx = [SPEEDS.index(v) for v in (20.0, 40.0, 60.0, 80.0)]
    for name, d in curves.items():
        for water in ("dry", "wet"):
            c = d[water]
            lines.append(f"| {name} | {water} | Kelvin–Voigt (paper) | " +
                         " | ".join(f"{c['kelvin_voigt'][i]:.3f}" for i in idx) + " |")
            for t in temperatures:
                lines.append(f"| {name} | {water} | compound, {t:g} °C | " +
                             " | ".join(f"{c[t][i]:.3f}" for i in idx) + " |")
    dry_spread = {n: max(max(d["dry"][t]) for t in temperatures) -
                  min(min(d["dry"][t]) for t in temperatures) for n, d in curves.items()}
    i20 = SPEEDS.index(20.0)
    i80 = SPEEDS.index(80.0)
    cold, warm = temperatures[0], temperatures[-1]
    colder_more = [n for n, d in curves.items() if d["dry"][cold][i20] > d["dry"][warm][i20]]
    colder_less = [n for n in curves if n not in colder_more]
    tref_ = rubber["reference_temperature"]
    tan_d = {}
    for t in temperatures:
        sto, los = fit.moduli(np.array([1e4]), temperature=t)
        tan_d[t] = float(los[0] / sto[0])
    wet_kv = {n: d["wet"]["kelvin_voigt"][i80] / d["dry"]["kelvin_voigt"][i80]
              for n, d in curves.items()}
    wet_mx = {n: d["wet"][tref_][i80] / d["dry"][tref_][i80] for n, d in curves.items()}
    lines += [
        "",
        "What the curves say, and what they do not:",
        "",
        "- The compound makes dry friction depend on speed and temperature, which the paper's "
        "rubber does not: across temperatures and speeds μ spans "
        + ", ".join(f"{n} {v:.2f}" for n, v in dry_spread.items()) + ". "
        "Lower temperature and higher speed are equivalent (superposition): each family of "
        "dry curves is one master curve in V a_T.",
        f"- At 20 km/h dry the rubber at {cold:g} °C grips "
        + (f"less than at {warm:g} °C on every surface" if not colder_more else
           f"more than at {warm:g} °C on every surface" if not colder_less else
           f"more than at {warm:g} °C on {', '.join(colder_more)} and less on "
           f"{', '.join(colder_less)}") + ". "
        "In this element model friction is the rubber's dissipation (μ_hysteresis) plus "
        "μ_loc's work on the facets (μ_adhesion, which grows with the slopes of the facets "
        "that carry the load): the rubber acts through which facets carry the load (its "
        "stiffness) as well as through its loss. "
        "Colder, the compound is stiffer at texture frequencies (a stiffer pad under the "
        "same load deforms less and rides on the tops); its tan δ at 10⁴ rad/s is "
        + ", ".join(f"{tan_d[t]:.2f} at {t:g} °C" for t in temperatures) + ".",
        "- Without local friction (μ_loc = 0, dry, 20 km/h, the same numerics) what remains "
        "is the part of μ "
        "that comes from the rubber's deformation alone:",
        "",
        "| surface | elastic pad K = 1.4e8 | elastic pad K = 1e10 | "
        + " | ".join(f"compound {t:g} °C" for t in temperatures) + " |",
        "|---|---|---|" + "---|" * len(temperatures),
        *[f"| {n} | {r['elastic 1.4e+08']:.3f} | {r['elastic 1e+10']:.3f} | "
          + " | ".join(f"{r[t]:.3f}" for t in temperatures) + " |"
          for n, r in hysteresis.items()],
        "",
        "  An elastic pad dissipates nothing, and with the energy scheme (`&numerics "
        "friction_scheme = 'energy'`, docs/model.md) its friction is "
        f"{max(abs(r['elastic 1e+10']) for r in hysteresis.values()):.1g} on every surface "
        "(the elastic columns): what the compound's columns show is its dissipation. The "
        "paper's scheme (Eq. 10 on central-difference slopes) gave the stiff elastic pad "
        "(K = 1e10 N m⁻³, about the compound's k_eff at 20 °C) up to "
        f"{max(abs(r['paper elastic 1e+10']) for r in hysteresis.values()):.2f} (at one "
        "step and one element per sample up to "
        f"{max(abs(r['paper elastic 1e+10, default numerics']) for r in hysteresis.values()):.2f}"
        "): its facet forces do not do the work the elements store.",
        "",
        "**Against temperature** (dry, each surface's μ_loc, the same numerics; "
        "`temperature_sweep` in `pavefric.studies.rubber_report`):",
        "",
        f"![mu_hysteresis and mu_adhesion against temperature]({rel(fig_t)})",
        "",
        "| surface | part | " + " | ".join(f"{t:g} °C" for t in sweep["temperatures"]) + " |",
        "|---|---|" + "---|" * len(sweep["temperatures"]),
        *[f"| {n} | {part} at {v:g} km/h | "
          + " | ".join(f"{row[j]:.3f}" for row in d[part]) + " |"
          for n, d in sweep["surfaces"].items() for part in ("hysteresis", "adhesion")
          for j, v in enumerate(sweep["speeds"])],
        "",
        "  The hysteresis rises from the glassy side to one maximum and falls beyond it, "
        "as Grosch (1963) measured for rubber on rough tracks, but its maximum lies hotter "
        "than the tan δ peak at the texture's frequencies: the pad carries a fixed load, so "
        "its dissipation per unit load follows the loss compliance E''/|E*|², which peaks "
        "40–70 °C hotter than tan δ for this compound (`python -m pavefric.studies.energy_report`). "
        "Softer rubber sinks deeper and is deformed more by the same load. The adhesion "
        "moves with temperature only through which facets carry the load, since μ_loc is "
        "a constant: the fall of skid resistance with temperature seen in the field "
        "(Bazlamit & Reza 2005) comes largely from the adhesion and the flash temperature, "
        "which this model does not carry (docs/model.md, \"Temperature\").",
        "- Wet (1 mm, the paper's bearing): μ at 80 km/h keeps "
        + ", ".join(f"{n} {100 * wet_mx[n]:.0f} %" for n in curves)
        + f" of its dry value with the compound at {tref_:g} °C, against "
        + ", ".join(f"{n} {100 * wet_kv[n]:.0f} %" for n in curves)
        + " with the paper's rubber. The bearing's α was calibrated with the paper's rubber; "
        "with another rubber it should be recalibrated (`python -m pavefric calibrate`).",
        "- The levels are the model's, for a representative compound; no measured DFT data "
        "at several temperatures are available here to validate them.",
        "",
        "## Cost",
        "",
        "Measured in the same run (`pavefric.studies.rubber_report.cost`, also in `python -m pavefric "
        "bench`): a dry 65,536-point CTM-like profile, N = 23, four speeds (one chunk of "
        "lanes), best of several runs taken in turn. An element-step is one element at one "
        "position and speed.",
        "",
        "| rubber | ns per element-step | against Kelvin–Voigt |",
        "|---|---|---|",
        *[f"| {r['case']} | {r['ns']:.2f} | {r['ratio']:.2f}x |" for r in costs["rows"]],
        "",
        f"**Target: three arms at most 1.5x Kelvin–Voigt — {three:.2f}x, "
        f"{'met' if three <= 1.5 else 'not met'}.** The Maxwell kernels cost about one "
        "multiplication and addition per arm for u_free and three per arm for the update, "
        "on whole four-lane vectors; the rest of an element-step (the geometry, the load "
        "balance, the friction sums) is the driver's and the same for every rubber.",
        "",
        "## Not modelled",
        "",
        "- No vertical shift of the moduli with temperature (see above), no flash temperature "
        "(the rubber's temperature rises in sliding contact; set `temperature` to the "
        "rubber's, not the air's), no strain dependence (the Payne effect of filled "
        "compounds), no heat balance.",
        "- The element is one-dimensional per unit length (the paper's); K = E/h is the "
        "thin-layer conversion, stated in every file `prony` writes.",
        "- `&rubber viscosity` is Kelvin–Voigt's only; with `model = 'maxwell'` it is not used.",
        "",
        "## Regenerate",
        "",
        "    python -m pavefric prony --write-representative inputs/data/tread_compound_dma.csv",
        "    python -m pavefric prony inputs/data/tread_compound_dma.csv -o inputs/rubber/tread_compound.nml",
        "    python -m pavefric rubber-report --report docs/rubber.md",
        "",
    ]
    path.write_text("\n".join(lines), encoding="utf-8")
