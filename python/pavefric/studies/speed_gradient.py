"""The speed-gradient study: how wet friction falls with speed, against the
PIARC international experiment (ASTM E1960): F(S) = F(60) exp((60 - S)/Sp)
with Sp = 14.2 + 89.7 MPD (km/h, MPD in mm).

``python -m pavefric speed-gradient`` regenerates ``docs/speed_gradient.md``
and its figure from scratch. Every friction value comes from the Fortran
core (``pavefric.simulate``); this module makes profiles, fits one constant
per wet model, and writes the report.

- Profiles: synthetic CTM-like closed profiles (1024 points at 0.87 mm, the
  macrotexture band 2-50 mm of ``spectral_profile``) of three kinds - a
  Gaussian texture and textures of skewness -1 (negative: flat tops, narrow
  valleys, as porous or worn asphalt) and +1 (positive: protruding chips) -
  two seeds each, scaled to MPD 0.3, 0.5, 0.75, 1, 1.5, 2, 2.5 and 3 mm;
  and the two real CAPTIF laser profiles, read and resampled as a Circular
  Track Meter would see them (0.87 mm bins, ISO 13473-1 dropouts and spikes).
- The model's speed constant from its friction at 20 and 60 km/h (the DFT
  speeds the IFI uses): Sp = 40 / ln(mu20 / mu60). Water 1 mm, mu_loc 0.6,
  the paper's rubber.
- Each wet model at its best single constant (kane2017: alpha; squeeze and
  reynolds: microtexture_rms), the one minimising the RMS of
  ln(Sp / Sp_PIARC) over the training profiles; the test profiles (another
  seed, other shapes, the real profiles) are predictions.
- The paper's Table 2 with the three models: the constant fitted on the six
  20 km/h DFT points only (``pavefric.calibrate``), 40 and 60 km/h predicted.
"""
from __future__ import annotations

import json
import math
import time
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..surfaces import CTM_DX, spectral_profile

SP_A, SP_B = 14.2, 89.7              # ASTM E1960 / PIARC: Sp = a + b MPD (mm), km/h
MPD_MM = [0.3, 0.5, 0.75, 1.0, 1.5, 2.0, 2.5, 3.0]
KINDS = {"Gaussian": 0.0, "negative (Rsk -1)": -1.0, "positive (Rsk +1)": 1.0}
# The declared split: each model's one constant is fitted on the training
# profiles only (seed 11 of the three kinds); the test profiles never take
# part in a fit: the same kinds with another seed, textures of other shapes
# (other spectral slopes, shorter and longer plateaus, stronger skewness)
# and the two real CAPTIF profiles.
SEEDS = {"training": [11], "test": [12]}
OTHER_SHAPES = {
    "rougher spectrum (k^-1.2)": dict(exponent=1.2),
    "smoother spectrum (k^-3)": dict(exponent=3.0),
    "short plateaus (2-15 mm)": dict(wavelength_max=15e-3),
    "long plateaus (8-50 mm)": dict(wavelength_min=8e-3),
    "negative (skew parameter -2)": dict(skew=-2.0),
    "positive (skew parameter +2)": dict(skew=2.0),
}
OTHER_MPD_MM = [0.5, 1.0, 2.0]
OTHER_SEED = 21
SPEEDS = (20.0, 60.0)
DEPTH = 1.0e-3
MU_LOC = 0.6
CAPTIF = ["20211011_aylesbury_dec_station_0.dat", "20211011_aylesbury_dec_station_1.dat"]
MODELS = {"kane2017": "alpha", "squeeze": "microtexture_rms", "reynolds": "microtexture_rms"}
LABELS = {"kane2017": "kane2017 (paper)", "squeeze": "squeeze (drainage)",
          "reynolds": "reynolds (film)"}
SEARCH = {"alpha": (1e-2, 1e5), "microtexture_rms": (2e-6, 5e-4)}


@dataclass
class StudyProfile:
    kind: str
    label: str
    mpd_mm: float
    heights: np.ndarray
    dx: float
    closed: bool
    real: bool
    split: str = "test"         # "training" (fitted on) or "test" (never fitted on)

    @property
    def sp_piarc(self) -> float:
        return SP_A + SP_B * self.mpd_mm


def skewness(z: np.ndarray) -> float:
    z = z - z.mean()
    return float(np.mean(z**3) / np.mean(z**2) ** 1.5)


def skewed_profile(target: float, seed: int) -> np.ndarray:
    """A unit-RMS macrotexture profile whose sample skewness is `target`
    (the skew parameter of spectral_profile found by bisection)."""
    if target == 0.0:
        return spectral_profile(1024, CTM_DX, rms=1.0, seed=seed)
    # the sample skewness grows monotonically with the skew parameter
    lo, hi = -2.0, 2.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if skewness(spectral_profile(1024, CTM_DX, rms=1.0, seed=seed, skew=mid)) < target:
            lo = mid
        else:
            hi = mid
    return spectral_profile(1024, CTM_DX, rms=1.0, seed=seed, skew=0.5 * (lo + hi))


def data_dir() -> Path:
    for base in (Path.cwd(), Path(__file__).resolve().parents[3]):
        p = base / "inputs" / "data"
        if (p / "captif" / CAPTIF[0]).exists():
            return p
    raise FileNotFoundError("inputs/data/captif not found: run from the pavefric checkout")


def study_profiles() -> list[StudyProfile]:
    """The synthetic profiles (scaled to each MPD) and the real ones."""
    from ..profiles import read_profile
    from ..texture import texture

    out = []
    for split, seeds in SEEDS.items():
        for kind, rsk in KINDS.items():
            for seed in seeds:
                base = skewed_profile(rsk, seed)
                unit_mpd = texture(base, CTM_DX)["mpd"]
                for mpd in MPD_MM:
                    z = base * (mpd * 1e-3 / unit_mpd)
                    out.append(StudyProfile(kind, f"{kind}, seed {seed}", mpd, z, CTM_DX, True,
                                            False, split))
    for kind, kw in OTHER_SHAPES.items():
        base = spectral_profile(1024, CTM_DX, rms=1.0, seed=OTHER_SEED, **kw)
        unit_mpd = texture(base, CTM_DX)["mpd"]
        for mpd in OTHER_MPD_MM:
            out.append(StudyProfile(kind, f"{kind}, seed {OTHER_SEED}", mpd,
                                    base * (mpd * 1e-3 / unit_mpd), CTM_DX, True, False, "test"))
    captif = data_dir() / "captif"
    for name in CAPTIF:
        prof = read_profile(captif / name, dropouts="interpolate", resample_dx=CTM_DX,
                            spike_slope=3.0)
        mpd = texture(prof, closed=False)["mpd"] * 1e3
        out.append(StudyProfile("CAPTIF laser profile", name.split("_", 2)[-1].replace(".dat", ""),
                                mpd, prof.heights, prof.dx, False, True, "test"))
    return out


def speed_constant(mu20: float, mu60: float) -> float:
    """Sp (km/h) from friction at 20 and 60 km/h; infinite when friction does
    not fall."""
    if not (mu20 > 0 and mu60 > 0) or mu60 >= mu20:
        return math.inf
    return (SPEEDS[1] - SPEEDS[0]) / math.log(mu20 / mu60)


class Runner:
    """Friction at the study's speeds, through the core, counted."""

    def __init__(self, profiles):
        self.profiles = profiles
        self.runs = 0
        #: per wet model: positions where the film's solution did not settle
        #: (film_unsettled), summed over every run and speed
        self.unsettled: dict = {}

    def mu(self, p: StudyProfile, model: str, constant: float | None) -> np.ndarray:
        from ..core import PavefricWarning, simulate

        kw = dict(mu_loc=MU_LOC, depth=DEPTH, wet_model=model)
        if constant is not None:
            kw[MODELS[model]] = constant
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", PavefricWarning)
            ds = simulate(p.heights, p.dx, list(SPEEDS), closed=p.closed, **kw)
        self.runs += 1
        self.unsettled[model] = self.unsettled.get(model, 0) + int(ds["film_unsettled"].sum())
        return ds["mu"].values

    def sp(self, model: str, constant: float) -> np.ndarray:
        return np.array([speed_constant(*self.mu(p, model, constant)) for p in self.profiles])


def log_error(sp: np.ndarray, piarc: np.ndarray) -> np.ndarray:
    """ln(Sp / Sp_PIARC), with a model that does not lose friction counted
    at Sp = 10^4 km/h (its error is then large but finite)."""
    return np.log(np.minimum(sp, 1e4) / piarc)


def best_constant(runner: Runner, model: str, log=print, points: int = 19
                  ) -> tuple[float, float]:
    """The single constant minimising the RMS of ln(Sp/Sp_PIARC) over the
    training profiles only: a grid in log space, then Brent's method."""
    from scipy.optimize import minimize_scalar

    synthetic = [p for p in runner.profiles if p.split == "training"]
    piarc = np.array([p.sp_piarc for p in synthetic])
    sub = Runner(synthetic)

    def rms(log_c):
        e = log_error(sub.sp(model, 10.0 ** log_c), piarc)
        return float(np.sqrt(np.mean(e**2)))

    lo, hi = (math.log10(v) for v in SEARCH[MODELS[model]])
    grid = np.linspace(lo, hi, points)
    values = [rms(g) for g in grid]
    k = int(np.argmin(values))
    a, b = grid[max(k - 1, 0)], grid[min(k + 1, len(grid) - 1)]
    res = minimize_scalar(rms, bounds=(a, b), method="bounded", options={"xatol": 1e-3})
    best = 10.0 ** res.x
    runner.runs += sub.runs
    for name, count in sub.unsettled.items():
        runner.unsettled[name] = runner.unsettled.get(name, 0) + count
    log(f"speed-gradient: {model}: best {MODELS[model]} = {best:.4g}, RMS ln(Sp/Sp_PIARC) "
        f"= {res.fun:.3f} ({sub.runs} core runs)")
    return best, float(res.fun)


#: The Reynolds film's floor on microtexture_rms (m; sigma_floor in
#: src/physics/pavefric_reynolds.f90).
REYNOLDS_SIGMA_FLOOR = 1e-6


def table2(model: str, log=print, table: str | Path | None = None,
           surfaces: str | Path | None = None) -> dict:
    """The paper's Table 2: the constant fitted on the 20 km/h DFT points only,
    40 and 60 km/h predicted, with the reference surfaces (`surfaces`,
    default the checkout's inputs/surfaces) and the paper's measurements
    (`table`, default the shipped kane2017_tables.csv)."""
    from .. import calibrate as cal
    from .validation import default_table, statistics

    table = table or default_table()
    if surfaces is None:
        surfaces = Path.cwd() / "inputs" / "surfaces"
        if not surfaces.exists():
            surfaces = Path(__file__).resolve().parents[3] / "inputs" / "surfaces"
    surfaces = Path(surfaces)
    rows = cal.read_measurements(table, source="dft")
    fit_rows = [r for r in rows if r["speed_kmh"] == 20.0]
    name = MODELS[model]
    overrides = {"depth": DEPTH, "wet_model": model}
    start = {"alpha": 1.0, "microtexture_rms": 40e-6}[name]
    # the Reynolds film takes max(microtexture_rms, 1 um) (sigma_floor in
    # src/physics/pavefric_reynolds.f90): below it the constant does nothing,
    # and a fit the 20 km/h points hardly constrain would wander there
    bounds = {name: (REYNOLDS_SIGMA_FLOOR, 1e-2)} if model == "reynolds" else None
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        result = cal.fit(fit_rows, surfaces, [name], start={name: start}, overrides=overrides,
                         bounds=bounds)
        value = result.values[name]
        pred = cal.Model(surfaces, overrides).predict(rows, {name: value})
    meas = np.array([r["mu"] for r in rows])
    speeds = np.array([r["speed_kmh"] for r in rows])
    surf = [r["surface"] for r in rows]
    ratios = {}
    for s in dict.fromkeys(surf):
        idx = {sp: i for i, (ss, sp) in enumerate(zip(surf, speeds)) if ss == s}
        ratios[s] = {"measured": meas[idx[60.0]] / meas[idx[20.0]],
                     "model": pred[idx[60.0]] / pred[idx[20.0]]}
    out = {"parameter": name, "value": value,
           "at_floor": bool(model == "reynolds" and value <= REYNOLDS_SIGMA_FLOOR * 1.001),
           "interval": (None if result.interval.get(name) is None
                        else [float(v) for v in result.interval[name]]),
           "all": statistics(meas, pred),
           "predicted": statistics(meas[speeds != 20.0], pred[speeds != 20.0]),
           "ratios": ratios, "rows": [(s, float(v), float(m), float(p)) for s, v, m, p in
                                      zip(surf, speeds, meas, pred)]}
    log(f"speed-gradient: Table 2, {model}: {name} = {value:.4g} (20 km/h), R2 all "
        f"{out['all']['R2']:.3f}, predicted 40/60 {out['predicted']['R2']:.3f}")
    return out


def run_study(report: str | Path = "docs/speed_gradient.md", quick: bool = False,
              log=print, outdir: str | Path = "outputs") -> dict:
    """Run the whole study and write the report, its figure and a JSON of
    the numbers (`outdir`/speed_gradient.json)."""
    t0 = time.perf_counter()
    profiles = study_profiles()
    if quick:
        profiles = [p for p in profiles if p.real or p.mpd_mm in (0.3, 1.0, 3.0)]
    runner = Runner(profiles)
    piarc = np.array([p.sp_piarc for p in profiles])
    real = np.array([p.real for p in profiles])
    train = np.array([p.split == "training" for p in profiles])

    def scores(err):
        rms = lambda m: float(np.sqrt(np.mean(err[m] ** 2))) if m.any() else float("nan")  # noqa: E731
        return {"rms_training": rms(train), "rms_test": rms(~train),
                "rms_test_synthetic": rms(~train & ~real), "real_ratio": np.exp(err[real]).tolist()}

    results = {}
    for model in MODELS:
        best, _ = best_constant(runner, model, log, points=9 if quick else 19)
        sp = runner.sp(model, best)
        err = log_error(sp, piarc)
        results[model] = {"constant": best, "sp": sp.tolist(), "ratio": np.exp(err).tolist(),
                          **scores(err)}
        log(f"speed-gradient: {model}: out of sample (test) RMS {results[model]['rms_test']:.3f}")
    # the default constant of the scenes, for comparison
    defaults = {}
    from ..core import defaults as core_defaults

    d = core_defaults()
    for model, name in MODELS.items():
        err = log_error(runner.sp(model, d[name]), piarc)
        defaults[model] = {"constant": d[name], **scores(err)}
    t2 = {model: table2(model, log) for model in MODELS}
    seconds = time.perf_counter() - t0
    data = {"profiles": [{"kind": p.kind, "label": p.label, "mpd_mm": p.mpd_mm,
                          "sp_piarc": p.sp_piarc, "real": p.real, "split": p.split}
                         for p in profiles],
            "models": results, "defaults": defaults, "table2": t2, "core_runs": runner.runs,
            "unsettled": runner.unsettled,
            "seconds": seconds, "quick": quick}
    report = Path(report)
    fig = _figure(report.parent / "figures" / "speed_gradient.png", profiles, results)
    out = Path(outdir)
    out.mkdir(parents=True, exist_ok=True)
    (out / "speed_gradient.json").write_text(json.dumps(data, indent=1, default=float))
    _write_report(report, profiles, data, fig)
    log(f"speed-gradient: wrote {report}, {fig} ({seconds:.0f} s, {runner.runs} core runs)")
    return data


def _figure(path: Path, profiles, results) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    path.parent.mkdir(parents=True, exist_ok=True)
    fig, axes = plt.subplots(1, len(results), figsize=(5.5 * len(results), 4.6), dpi=110,
                             sharey=True)
    m = np.linspace(0.2, 3.6, 50)
    markers = {"Gaussian": "o", "negative (Rsk -1)": "v", "positive (Rsk +1)": "^",
               **{kind: "s" for kind in OTHER_SHAPES}, "CAPTIF laser profile": "*"}
    for ax, (model, res) in zip(axes, results.items()):
        ax.plot(m, SP_A + SP_B * m, "k-", lw=1.5, label="PIARC / ASTM E1960")
        ax.fill_between(m, (SP_A + SP_B * m) / 1.5, (SP_A + SP_B * m) * 1.5, color="0.9",
                        label="factor 1.5")
        for kind, marker in markers.items():
            idx = [i for i, p in enumerate(profiles) if p.kind == kind]
            if not idx:
                continue
            ax.plot([profiles[i].mpd_mm for i in idx],
                    [min(res["sp"][i], 1e4) for i in idx], marker, ls="none", ms=9 if
                    marker == "*" else 5, label=kind, mfc="none" if marker != "*" else None)
        name = MODELS[model]
        const = res["constant"]
        shown = f"{const * 1e6:.3g} µm" if name == "microtexture_rms" else f"{const:.3g}"
        ax.set_title(f"{model}: {name} = {shown}, RMS ln(Sp/Sp_PIARC): training "
                     f"{res['rms_training']:.2f}, test {res['rms_test']:.2f}", fontsize=9)
        ax.set_xlabel("MPD (mm)")
        ax.set_yscale("log")
        ax.set_ylim(5, 3e3)
        ax.grid(alpha=0.3, which="both")
    axes[0].set_ylabel("speed constant Sp (km/h)")
    axes[0].legend(fontsize=7, loc="upper left")
    fig.suptitle("Speed gradient of wet friction (1 mm water, 20 and 60 km/h) against PIARC",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)
    return path


def _write_report(path: Path, profiles, data, fig: Path) -> None:
    from .reports import machine_description

    res = data["models"]
    k17, sq = res["kane2017"], res["squeeze"]
    lines = [
        "# Speed gradient of wet friction against PIARC",
        "",
        f"Generated by `python -m pavefric speed-gradient`{' --quick' if data['quick'] else ''} "
        f"on {machine_description()}, {time.strftime('%Y-%m-%d')} ({data['seconds']:.0f} s, "
        f"{data['core_runs']} runs of the core). Numbers also in `outputs/speed_gradient.json`.",
        "",
        "The PIARC international experiment (1995) behind ASTM E1960 gives the speed gradient "
        "of wet friction from macrotexture: F(S) = F(60) exp((60 − S)/Sp), Sp = 14.2 + 89.7 MPD "
        "(km/h, MPD in mm); the IFI uses it to carry DFT friction at 20 km/h to 60 km/h. "
        "Here each wet model's Sp is measured as a pavement engineer would: from its friction at "
        "20 and 60 km/h, Sp = 40 / ln(μ20/μ60), with 1 mm of water, μ_loc = 0.6 and the paper's "
        "rubber (K = 1.4e8 N m⁻³, C = 100 N s m⁻³).",
        "",
        "## Method",
        "",
        "- **Synthetic profiles**: CTM-like closed profiles (1024 points at 0.87 mm, "
        "macrotexture band 2–50 mm, power ∝ k⁻², `pavefric.surfaces.spectral_profile`) of three "
        "kinds: Gaussian, skewness −1 (negative texture: flat tops, narrow valleys) and +1 "
        "(positive: protruding chips), scaled to MPD "
        + ", ".join(f"{m:g}" for m in MPD_MM) + " mm (MPD per ISO 13473-1 in the core); and "
        "textures of other shapes: " + ", ".join(OTHER_SHAPES) + ", scaled to MPD "
        + ", ".join(f"{m:g}" for m in OTHER_MPD_MM) + " mm.",
        "- **Real profiles**: the two CAPTIF laser profiles (`inputs/data/captif`), dropouts "
        "interpolated, resampled into 0.87 mm bins as a Circular Track Meter would see them, "
        "spikes removed (ISO 13473-1), open profiles.",
        "- **The split, declared before any fit**: the *training* set is seed "
        + ", ".join(map(str, SEEDS["training"])) + " of the three kinds ("
        + str(sum(p.split == "training" for p in profiles)) + " profiles); the *test* set, "
        "which takes part in no fit, is seed " + ", ".join(map(str, SEEDS["test"]))
        + " of the three kinds, every profile of another shape and the two real profiles ("
        + str(sum(p.split == "test" for p in profiles)) + " profiles).",
        "- **One constant per model**, the one minimising the RMS of ln(Sp/Sp_PIARC) over the "
        "training set (a grid in log space, then Brent's method): `alpha` for the paper's "
        "bearing (`kane2017`), `microtexture_rms` for the drainage model (`squeeze`) and for "
        "the Reynolds film (`reynolds`: the roughness of its flow factors; its other "
        "constants, the water's density and viscosity and the pad's size, are physics). "
        "Every test figure is a prediction.",
        "",
        "## Result",
        "",
        "| model | constant (fitted on training) | RMS ln(Sp/Sp_PIARC), training (in sample) | "
        "RMS, test (out of sample) | RMS, synthetic test | Sp/Sp_PIARC, CAPTIF 0 | "
        "Sp/Sp_PIARC, CAPTIF 1 |",
        "|---|---|---|---|---|---|---|",
    ]
    for model, r in res.items():
        lines.append(f"| {LABELS[model]} | {constant_text(MODELS[model], r['constant'])} | "
                     f"{r['rms_training']:.2f} | {r['rms_test']:.2f} | "
                     f"{r['rms_test_synthetic']:.2f} | {r['real_ratio'][0]:.2f} | "
                     f"{r['real_ratio'][1]:.2f} |")
    lines.append("")
    ok_rms = sq["rms_test"] <= 0.3
    ok_real = all(1 / 1.5 <= r <= 1.5 for r in sq["real_ratio"])
    lines += [
        f"**Targets (drainage model), judged on the test set: RMS ≤ 0.3 — "
        f"{'met' if ok_rms else 'NOT met'} ({sq['rms_test']:.2f} out of sample, "
        f"{sq['rms_training']:.2f} in sample); Sp of the real profiles within a factor 1.5 of "
        f"PIARC — {'met' if ok_real else 'NOT met'}.** The paper's bearing at its best alpha: "
        f"{k17['rms_test']:.2f} out of sample. (Earlier versions of this report gave 0.18 for "
        "the drainage model: that was its RMS on the very profiles its constant was fitted "
        "on.)",
        "",
    ]
    rey, rey_default = res["reynolds"], data["defaults"]["reynolds"]
    lines += [
        f"**Target (Reynolds film, issue 21), judged on the test set at its defaults: RMS ≤ 0.3 "
        f"— {'met' if rey_default['rms_test'] <= 0.3 else 'NOT met'} "
        f"({rey_default['rms_test']:.2f} out of sample, {rey_default['rms_training']:.2f} in "
        f"sample); at its fitted constant {rey['rms_test']:.2f} out of sample.**",
        "",
        "With the defaults shipped (`&water alpha = "
        f"{data['defaults']['kane2017']['constant']:g}`, `&surface microtexture_rms = "
        f"{data['defaults']['squeeze']['constant'] * 1e6:g} µm`), out of sample: RMS "
        f"{data['defaults']['kane2017']['rms_test']:.2f} (kane2017), "
        f"{data['defaults']['squeeze']['rms_test']:.2f} (squeeze) and "
        f"{rey_default['rms_test']:.2f} (reynolds).",
        "",
        "Convergence: the Reynolds film's solution "
        + ("settled at every position of every run of the study"
           if data["unsettled"].get("reynolds", 0) == 0 else
           f"did not settle at {data['unsettled']['reynolds']} positions over the study's runs")
        + " (`film_unsettled`, summed over the runs of the fits and of the report; the "
        "paper's bearing and the drainage film always settle).",
        "",
        f"![Sp against MPD]({fig.relative_to(path.parent).as_posix()})",
        "",
        "## Every profile",
        "",
        "| set | kind | profile | MPD (mm) | Sp PIARC | "
        + " | ".join(f"Sp {model} | ratio" for model in res) + " |",
        "|---|---|---|---|---|" + "---|---|" * len(res),
    ]
    for i, p in enumerate(profiles):
        lines.append(f"| {p.split} | {p.kind} | {p.label} | {p.mpd_mm:.2f} | {p.sp_piarc:.0f} | "
                     + " | ".join(f"{_sp(r['sp'][i])} | {r['ratio'][i]:.2f}"
                                  for r in res.values()) + " |")
    kinds = list(dict.fromkeys(p.kind for p in profiles))
    lines += ["", "## By kind of texture", "",
              "Sp/Sp_PIARC per kind, the geometric mean over its profiles (training and test "
              "together; 1 is PIARC's law):", "",
              "| kind | profiles | " + " | ".join(res) + " |",
              "|---|---|" + "---|" * len(res)]
    for kind in kinds:
        idx = [i for i, p in enumerate(profiles) if p.kind == kind]
        lines.append(f"| {kind} | {len(idx)} | " + " | ".join(
            f"{float(np.exp(np.mean(np.log([r['ratio'][i] for i in idx])))):.2f}"
            for r in res.values()) + " |")
    lines += ["", "## The paper's Table 2 with the three models", "",
              "The constant fitted on the six 20 km/h DFT measurements only (reference surfaces "
              "of `inputs/surfaces`, 1 mm water, `pavefric.calibrate`), 40 and 60 km/h "
              "predicted. R² = 1 − SS_res/SS_tot.", "",
              "| model | constant (fitted at 20 km/h) | 95 % interval (linearised) | R² all 18 "
              "points | R² predicted 40/60 | RMSE all |",
              "|---|---|---|---|---|---|"]
    for model, t in data["table2"].items():
        lines.append(f"| {model} | {constant_text(t['parameter'], t['value'])} | "
                     f"{interval_text(t['parameter'], t['interval'], t.get('at_floor', False))} | "
                     f"{t['all']['R2']:.3f} | {t['predicted']['R2']:.3f} | "
                     f"{t['all']['rmse']:.3f} |")
    t2 = data["table2"]
    lines += ["", "μ60/μ20 per surface, measured (DFT) and predicted:", "",
              "| surface | measured | " + " | ".join(t2) + " |", "|---|---|" + "---|" * len(t2)]
    for s in t2["kane2017"]["ratios"]:
        lines.append(f"| {s} | {t2['kane2017']['ratios'][s]['measured']:.2f} | "
                     + " | ".join(f"{t['ratios'][s]['model']:.2f}" for t in t2.values()) + " |")
    def mean_ratio(model, lo, hi):
        r = [res[model]["ratio"][i] for i, p in enumerate(profiles)
             if not p.real and p.kind in KINDS and lo <= p.mpd_mm <= hi]
        return float(np.exp(np.mean(np.log(r))))

    k_fine, k_coarse = mean_ratio("kane2017", 0, 0.5), mean_ratio("kane2017", 2.5, 9)
    s_fine, s_coarse = mean_ratio("squeeze", 0, 0.5), mean_ratio("squeeze", 2.5, 9)
    r_fine, r_coarse = mean_ratio("reynolds", 0, 0.5), mean_ratio("reynolds", 2.5, 9)
    by_kind = {}
    for kind in kinds:
        r = [res["reynolds"]["ratio"][i] for i, p in enumerate(profiles) if p.kind == kind]
        by_kind[kind] = float(np.exp(np.mean(np.log(r))))
    r_low = min(by_kind.items(), key=lambda kv: kv[1])
    r_high = max(by_kind.items(), key=lambda kv: kv[1])
    lines += ["", "## Reading it", "",
              f"- The paper's bearing, even at its best alpha, does not follow MPD: on fine "
              f"textures (MPD ≤ 0.5 mm) its Sp is {k_fine:.2f} of PIARC's (friction falls too "
              f"fast), on coarse ones (MPD ≥ 2.5 mm) {k_coarse:.2f} of it (too flat). Its "
              "effect comes from the empirical α V^β factor of Eq. 15 and a yes/no wetting "
              "test of the mean gap (docs/model.md), not from how water leaves the contacts.",
              f"- The drainage model gives {s_fine:.2f} and {s_coarse:.2f} of PIARC's Sp on the "
              "same two groups: its Sp grows with MPD because coarse textures touch the pad on "
              "short plateaus, which drain fast (the film left is ∝ b), while on fine textures "
              "the pad wraps the texture into one long plateau (b capped at the pad width) "
              "whose film survives at speed. At equal MPD the texture's shape still moves Sp "
              "(negative textures lose less friction than positive ones on fine textures), which "
              "PIARC's MPD-only law averages out.",
              f"- The Reynolds film at its fitted constant gives {r_fine:.2f} and "
              f"{r_coarse:.2f} of PIARC's Sp on the same two groups, but by kind of texture "
              f"from {r_low[1]:.2f} ({r_low[0]}) to {r_high[1]:.2f} ({r_high[0]}). Its speed "
              "dependence is the inertia of the water stopped at the pad's leading edge (the "
              "viscous film alone carries a few per cent of the load, tests/test_reynolds.py); "
              "how far that pressure reaches under the pad is set by the runs of open elements "
              "the water drains through, so Sp follows the texture's horizontal scale and shape "
              "(short plateaus and a rough spectrum drain it, a flat plain between protruding "
              "chips lets it spread) more than MPD. That is our reading of the table above, "
              "not yet a tested statement; what the film lacks is listed in docs/model.md.",
              "- mu_loc, the water depth and the rubber are fixed here. The reference surfaces "
              "of Table 2 were tuned to the paper's dry model values with MPDs of 1.45–2.6 mm "
              "(docs/validation.md), far coarser than polished granite: the drainage model "
              "sees them as coarse textures, which is why it keeps the granites' friction at "
              "speed where the DFT lost 40 %.",
              ""]
    path.write_text("\n".join(lines), encoding="utf-8")


def interval_text(name: str, interval, at_floor: bool = False) -> str:
    """A fit's 95 % interval (linearised) as the reports show it: "not
    identified" when it spans more than six decades (the 20 km/h points do
    not fix the constant); none where the fit stopped at the Reynolds film's
    floor on microtexture_rms (`at_floor`, table2's "at_floor")."""
    if at_floor:
        return ("none: the fit stops at the film's floor, 1 µm (the search's lower bound; "
                "the 20 km/h points ask for less microtexture than the film takes)")
    if not interval or not all(np.isfinite(interval)) or interval[0] <= 0:
        return "not available"
    lo, hi = interval
    if hi / lo > 1e6:
        return "not identified (the fit stays near its start)"
    scale, unit = (1e6, " µm") if name == "microtexture_rms" else (1.0, "")
    return f"[{lo * scale:.3g}, {hi * scale:.3g}]{unit}"


def constant_text(name: str, value: float) -> str:
    """A fitted constant as the reports show it: "name = value" (µm for
    microtexture_rms)."""
    shown = f"{value * 1e6:.3g} µm" if name == "microtexture_rms" else f"{value:.3g}"
    return f"{name} = {shown}"


def _sp(v: float) -> str:
    return "∞" if not np.isfinite(v) or v >= 1e4 else f"{v:.0f}"
