"""The figures of docs/model.md's "Friction", "The pad's own scale" and
"Temperature" paragraphs (issue 20), and its "Known limits" figures of an
open profile's settling, printed as text:

    python -m pavefric.studies.energy_report
    python -m pavefric.studies.energy_report --open-settling   # that section alone

Runs only the core (pavefric.simulate); nothing is fitted here.
"""
from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np

import pavefric

ROOT = Path(__file__).resolve().parents[3]
DX = 0.87e-3


def _repo_file(*parts: str) -> Path:
    """A file of the checkout: from the working directory, else beside the
    package's source tree."""
    for base in (Path.cwd(), ROOT):
        path = base.joinpath(*parts)
        if path.exists():
            return path
    print(f"pavefric.studies.energy_report: {Path(*parts)} not found: run it in a checkout")
    raise SystemExit(2)


def compound() -> dict:
    """The shipped tread compound's &rubber values as simulate() keywords
    (read by the core), its temperature left to the caller."""
    from ..rubber import compound as read_compound

    rubber = read_compound(_repo_file("inputs", "rubber", "tread_compound.nml"))
    return {k: v for k, v in rubber.items() if k != "temperature"}


def medium_profile() -> np.ndarray:
    lines = _repo_file("inputs", "profiles", "ctm_medium.txt").read_text().splitlines()
    return np.array([float(v) for v in lines if v and not v.startswith(("#", "h"))]) * 1e-3


def default_passes(z, rubber: dict, temperatures, speed: float = 20.0) -> list[tuple]:
    """Per temperature, mu_loc = 0, dry: the pad's elements_per_sample the
    default (min_contacts = 4) chose, and mu of the default's two passes at
    that pad, substeps 1 (the one reported) and 2 (the error estimate's)."""
    rows = []
    for t in temperatures:
        kw = dict(mu_loc=0.0, temperature=float(t), error_estimate=False, **rubber)
        level = int(pavefric.simulate(z, DX, [speed], **kw)
                    ["elements_per_sample_used"].values[0])
        one, two = (pavefric.simulate(z, DX, [speed], substeps=s, elements_per_sample=level,
                                      min_contacts=0, **kw)["mu"].values[0] for s in (1, 2))
        rows.append((t, level, one, two))
    return rows


def synthetic_profile() -> np.ndarray:
    """The tests' synthetic closed profile (inputs/profiles/synthetic_1024.txt, a
    copy of tests/data/regression/synthetic_1024.txt: spectral, RMS 0.5 mm,
    skew -0.3, 1024 points at 0.87 mm)."""
    lines = _repo_file("inputs", "profiles", "synthetic_1024.txt").read_text().splitlines()
    return np.array([float(v) for v in lines if v and not v.startswith("#") and v != "height_m"])


def at_tolerance(z, rubber: dict, temperatures, tolerance: float = 1e-3,
                 speed: float = 20.0) -> tuple[list[tuple], float]:
    """Per temperature, mu_loc = 0, dry, the default numerics but for
    &numerics tolerance: mu, elements_per_sample_used and mu_error_estimate;
    and the sweep's time over the same sweep at the defaults (each the best
    of two)."""
    import time

    def sweep(**kw):
        best, rows = np.inf, []
        for _ in range(2):
            t0 = time.perf_counter()
            rows = []
            for t in temperatures:
                ds = pavefric.simulate(z, DX, [speed], mu_loc=0.0, temperature=float(t),
                                       **rubber, **kw)
                rows.append((t, float(ds["mu"].values[0]),
                             int(ds["elements_per_sample_used"].values[0]),
                             float(ds["mu_error_estimate"].values[0])))
            best = min(best, time.perf_counter() - t0)
        return rows, best

    _, default_seconds = sweep()
    rows, seconds = sweep(tolerance=tolerance)
    return rows, seconds / default_seconds


def open_settling(z, rubber: dict, loads=(11.8, 1000.0), lengths=(60, 115, 230, 460, 1024),
                  speeds=(1.0, 20.0, 80.0)) -> list[tuple]:
    """docs/model.md, Known limits: an open profile's mu_hysteresis on the
    first n points against the whole profile closed, the compound at 20 C,
    mu_loc = 0, dry, per load: (load, [open rows a length], closed row)."""
    rows = []
    for load in loads:
        kw = dict(load=load, mu_loc=0.0, temperature=20.0, **rubber)
        opened = [pavefric.simulate(z[:n], DX, list(speeds), closed=False, **kw)
                  ["mu_hysteresis"].values for n in lengths]
        closed = pavefric.simulate(z, DX, list(speeds), closed=True, **kw)["mu_hysteresis"].values
        rows.append((load, opened, closed))
    return rows


def print_open_settling(z, rubber: dict) -> None:
    lengths = (60, 115, 230, 460, 1024)
    print("An open profile's settling: the compound at 20 C, mu_loc = 0, dry, mu_hysteresis "
          "at 1, 20 and 80 km/h on the first n points (open) against the whole profile "
          "closed")
    for load, opened, closed in open_settling(z, rubber, lengths=lengths):
        print(f"  load {load} N: " + "; ".join(
            f"n = {n} {np.round(v, 4).tolist()}" for n, v in zip(lengths, opened)) +
            f"; closed {np.round(closed, 4).tolist()}")


def main() -> None:
    import sys

    warnings.simplefilter("ignore", pavefric.PavefricWarning)
    z = medium_profile()
    if "--open-settling" in sys.argv[1:]:       # that section alone
        print_open_settling(z, compound())
        return
    print("Friction schemes, inputs/profiles/ctm_medium.txt, paper rubber, dry")
    for kw in (dict(mu_loc=0.5), dict(mu_loc=0.0, viscosity=0.0)):
        for scheme in ("energy", "paper"):
            ds = pavefric.simulate(z, DX, [20.0, 80.0], friction_scheme=scheme, **kw)
            print(f"  {kw} {scheme}: mu {ds['mu'].values}, mu_hysteresis "
                  f"{ds['mu_hysteresis'].values}")
    print("The paper's Table 2 surfaces (inputs/surfaces/*.nml, their mu_loc; wet: their "
          "1 mm): mu at 20 and 60 km/h, energy against paper")
    from ..core import load_scene
    for name in ("GSP", "GSS", "GSSB", "RSBA", "MCA", "VTAC"):
        scene = load_scene(_repo_file("inputs", "surfaces", f"{name}.nml"))
        row = []
        for water in ("dry", "wet"):
            kw = dict(scene.parameters)
            if water == "dry":
                kw["depth"] = 0.0
            mus = {}
            for scheme in ("energy", "paper"):
                kw["friction_scheme"] = scheme
                mus[scheme] = pavefric.simulate(scene.heights, scene.dx, [20.0, 60.0],
                                                closed=scene.closed, **kw)["mu"].values
            change = 100 * (mus["energy"] / mus["paper"] - 1)
            row.append(f"{water} {np.round(mus['energy'], 3)} vs {np.round(mus['paper'], 3)} "
                       f"({change[0]:+.2f} %, {change[1]:+.2f} %)")
        print(f"  {name}: " + "; ".join(row))
    print("Temperature, shipped compound, mu_loc = 0, dry (mu at 20 and 60 km/h): the "
          "default (min_contacts = 4; elements_per_sample_used; mu_error_estimate), and "
          "min_contacts = 0 (one element per sample)")
    rubber = compound()
    for t in (-20, 0, 10, 20, 30, 40, 50, 60):
        ds = pavefric.simulate(z, DX, [20.0, 60.0], mu_loc=0.0, temperature=float(t), **rubber)
        paper = pavefric.simulate(z, DX, [20.0, 60.0], mu_loc=0.0, temperature=float(t),
                                  min_contacts=0, **rubber)
        print(f"  {t:4d} C: {np.round(ds['mu'].values, 4)} "
              f"({ds['elements_per_sample_used'].values}; "
              f"{np.round(ds['mu_error_estimate'].values, 3)}); "
              f"min_contacts = 0: {np.round(paper['mu'].values, 4)}")
    ds = pavefric.simulate(z, DX, [1.0], mu_loc=0.0, temperature=200.0, **rubber)
    print(f"   200 C, 1 km/h: {ds['mu'].values[0]:.4f}")
    print("The default's two passes (substeps 1, and 2 for its error estimate, at the pad "
          "min_contacts = 4 chose), 20 km/h: the first (reported), the second, and "
          "2 mu(2) - mu(1) (Richardson, not what the default reports: what "
          "time_scheme = 'richardson' reports, its run's mu_extrapolated and "
          "mu_error_estimate after it)")
    for t, level, one, two in default_passes(z, rubber, (0, 10, 20, 30, 40, 50, 60)):
        rich = pavefric.simulate(z, DX, [20.0], mu_loc=0.0, temperature=float(t),
                                 time_scheme="richardson", **rubber)
        print(f"  {t:4d} C (elements_per_sample {level}): {one:.4f}, {two:.4f}, "
              f"{2 * two - one:.4f} (richardson: {rich['mu'].values[0]:.4f}, "
              f"{int(rich['mu_extrapolated'].values[0])}, "
              f"{rich['mu_error_estimate'].values[0]:.4f})")
    print("The same at substeps 16, elements_per_sample 4, min_contacts = 0 (the tests' "
          "numerics for the bell; mu at 20 and 60 km/h)")
    for t in (0, 10, 20, 30, 40, 50, 60):
        ds = pavefric.simulate(z, DX, [20.0, 60.0], mu_loc=0.0, temperature=float(t),
                               substeps=16, elements_per_sample=4, min_contacts=0,
                               error_estimate=False, **rubber)
        print(f"  {t:4d} C: {np.round(ds['mu'].values, 4)}")
    print("At a stated accuracy, &numerics tolerance = 1e-3 (the other numerics the "
          "defaults), 20 km/h, 0-60 C: mu, elements_per_sample_used, mu_error_estimate; "
          "the sweep's time over the defaults' (best of two each)")
    for name, zt in (("ctm_medium", z), ("tests' synthetic_1024", synthetic_profile())):
        rows, ratio = at_tolerance(zt, rubber, (0, 10, 20, 30, 40, 50, 60))
        print(f"  {name} ({ratio:.1f} times the defaults' time): " + ", ".join(
            f"{t} C {mu:.4f} ({eps}; {err:.4f})" for t, mu, eps, err in rows))
    print("Time step, shipped compound, mu_loc = 0, dry, 20 km/h, 20/30/40 C "
          "(one element per sample; substeps 64 is converged in time)")
    for substeps in (1, 4, 64):
        mus = [pavefric.simulate(z, DX, [20.0], mu_loc=0.0, temperature=t, substeps=substeps,
                                 error_estimate=False, min_contacts=0, **rubber)["mu"].values[0]
               for t in (20.0, 30.0, 40.0)]
        print(f"  substeps {substeps:2d}: " + ", ".join(f"{v:.4f}" for v in mus))
    print("Peaks of tan delta and of the loss compliance E''/|E*|^2 (shipped compound)")
    k_inf = rubber["stiffness"]
    arms = np.array(rubber["prony_stiffness"])
    times = np.array(rubber["prony_times"])
    temps = np.arange(-40.0, 121.0, 1.0)
    for f in (10.0, 600.0, 3000.0):
        w = 2 * np.pi * f
        tand, comp = [], []
        for t in temps:
            shift = 10 ** (-rubber["wlf_c1"] * (t - 20) / (rubber["wlf_c2"] + t - 20))
            wt = w * times * shift
            e = k_inf + np.sum(arms * 1j * wt / (1 + 1j * wt))
            tand.append(e.imag / e.real)
            comp.append(e.imag / abs(e) ** 2)
        print(f"  {f:6.0f} Hz: tan delta peaks at {temps[np.argmax(tand)]:.0f} C, "
              f"loss compliance at {temps[np.argmax(comp)]:.0f} C")
    print_open_settling(z, rubber)
    for station in (0, 1):
        profile = pavefric.read_profile(
            _repo_file("inputs", "data", "captif",
                       f"20211011_aylesbury_dec_station_{station}.dat"),
            dropouts="interpolate", trim_plates=True, spike_slope=0.0)
        zc, dxc = np.asarray(profile.heights), profile.dx
        one = [pavefric.simulate(*pavefric.element_profile(zc, dxc, closed=False, phase=ph),
                                 [20.0], closed=False, mu_loc=0.3,
                                 element_length=0.0)["mu"].values[0]
               for ph in (0.0, 0.25, 0.5, 0.75)]
        print(f"Instrument spacing, CAPTIF station {station} (dry, 20 km/h); one phase of the "
              f"grid at a time (mu_loc = 0.3): " + ", ".join(f"{v:.3f}" for v in one))
        for mu_loc in (0.3, 0.6):
            for length in (0.87e-3, 0.0):
                row = {"raw": pavefric.simulate(zc, dxc, [20.0], closed=False, mu_loc=mu_loc,
                                                element_length=length)["mu"].values[0]}
                spread = {"dec": [row["raw"]], "bin": [row["raw"]]}
                for target in (1e-4, 2.5e-4, 5e-4, 1.5e-3):
                    k = int(round(target / dxc))
                    m = zc.size // k
                    for how, zk in (("dec", zc[::k]),
                                    ("bin", zc[:m * k].reshape(m, k).mean(axis=1))):
                        v = pavefric.simulate(zk, k * dxc, [20.0], closed=False, mu_loc=mu_loc,
                                              element_length=length)["mu"].values[0]
                        row[f"{how} {target * 1e3:g} mm"] = v
                        if target < 1e-3:
                            spread[how].append(v)
                print(f"  mu_loc {mu_loc}, element_length = {length}: " +
                      ", ".join(f"{k} {v:.3f}" for k, v in row.items()) +
                      "; spread to 0.5 mm: " + ", ".join(
                          f"{h} {100 * (max(v) / min(v) - 1):.2f} %" for h, v in spread.items()))


if __name__ == "__main__":
    main()
