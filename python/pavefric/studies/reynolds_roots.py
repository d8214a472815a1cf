"""The figures of docs/model.md's paragraph "The film's balance has more than
one root" and of "Known limits" (a pad that creeps), printed as text:

    python -m pavefric.studies.reynolds_roots      # under a minute

Issue 21's open defect of the Reynolds film: where a lifted and a seated pad
both balance the load, the penetration jumps between the two roots, the
jumps strike the dashpots, and mu does not converge as the time step
shrinks. This study shows it on the profile the paragraph names, beside the
dry pad and the other two wet models. Runs only the core
(pavefric.simulate, error_estimate off so each row is one pass at the
substeps it names); nothing is fitted here. Each row's seconds are the
wall time of that call on this machine.
"""
from __future__ import annotations

import argparse
import time
import warnings

import numpy as np

import pavefric
from ..surfaces import spectral_profile

DX = 0.87e-3
#: The profile of the paragraph: 256 points at the CTM spacing, RMS 0.5 mm.
PROFILE = dict(n=256, dx=DX, rms=0.5e-3, seed=3)
SPEED = 60.0
DEPTH = 1e-3
#: The models whose jumps the study compares (simulate() keywords).
MODELS = {"dry": {}, "kane2017": dict(wet_model="kane2017", depth=DEPTH),
          "squeeze": dict(wet_model="squeeze", depth=DEPTH),
          "reynolds": dict(wet_model="reynolds", depth=DEPTH)}


def _run(z, speeds, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", pavefric.PavefricWarning)
        warnings.simplefilter("ignore", pavefric.PavefricCostWarning)
        return pavefric.simulate(z, DX, speeds, error_estimate=False, **kw)


def largest_jump(ds) -> float:
    """The largest change of the penetration between two positions (m)."""
    pen = ds["penetration"]
    pen = pen.transpose(*[d for d in pen.dims if d != "speed_kmh"], "speed_kmh").values[:, 0]
    return float(np.abs(np.diff(pen)).max())


def substep_table(z, substeps) -> list[tuple]:
    """mu, film_load_share, the largest jump and film_root_jumps (the averaged
    positions where the root left the range of the clearances' moves) against
    substeps (Reynolds)."""
    rows = []
    for s in substeps:
        t0 = time.perf_counter()
        ds = _run(z, [SPEED], wet_model="reynolds", depth=DEPTH, substeps=s, series=True)
        rows.append((s, float(ds["mu"][0]), float(ds["film_load_share"][0]), largest_jump(ds),
                     int(ds["film_root_jumps"][0]), time.perf_counter() - t0))
    return rows


def model_jumps(z, substeps, models=tuple(MODELS)) -> list[tuple]:
    """The largest jump of the dry pad and of each wet model (`models`, names
    of MODELS)."""
    rows = []
    for s in substeps:
        for name in models:
            ds = _run(z, [SPEED], substeps=s, series=True, **MODELS[name])
            rows.append((s, name, float(ds["mu"][0]), largest_jump(ds)))
    return rows


def depth_rise() -> list[tuple]:
    """mu rising with depth (the attack's profile, seed 11)."""
    z = spectral_profile(512, DX, rms=0.2e-3, seed=11)
    return [(d, float(_run(z, [SPEED], wet_model="reynolds", depth=d)["mu"][0]))
            for d in (0.24e-3, 0.30e-3)]


def creeping_pad(z) -> list[tuple]:
    """A rubber of stiffness 1 N m^-3 (the least allowed) in 1 mm of water: the
    pad sinks and creeps through the whole run (mu_hysteresis < 0, a warning says so)."""
    rows = []
    for model in ("reynolds", "kane2017"):
        ds = _run(z, [20.0], wet_model=model, depth=DEPTH, stiffness=1.0)
        rows.append((model, float(ds["mu"][0]), float(ds["mu_hysteresis"][0])))
    return rows


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(prog="python -m pavefric.studies.reynolds_roots",
                                     description=__doc__.split("\n\n")[0])
    parser.parse_args(argv)
    z = spectral_profile(**PROFILE)
    print(f"spectral_profile({PROFILE['n']}, {DX}, rms={PROFILE['rms']}, "
          f"seed={PROFILE['seed']}), {SPEED:g} km/h, {DEPTH * 1e3:g} mm of water")
    print("Reynolds film against the time step:")
    print("  substeps        mu  film_load_share  largest jump (m)  film_root_jumps  seconds")
    table = substep_table(z, (1, 16, 64, 256, 1024, 4096))
    for s, mu, share, jump, left, sec in table:
        print(f"  {s:8d}  {mu:8.4f}  {share:15.4f}  {jump:16.2e}  {left:15d}  {sec:7.1f}")
    print("Largest jump of the penetration per step, every model:")
    print("  substeps  model          mu  largest jump (m)")
    others = model_jumps(z, (16, 256), models=[m for m in MODELS if m != "reynolds"])
    for s in (16, 256):
        # the Reynolds film's rows are the table's above (not run again)
        rows = [r for r in others if r[0] == s] + [
            (s, "reynolds", mu, jump) for t, mu, _, jump, _, _ in table if t == s]
        for _, name, mu, jump in rows:
            print(f"  {s:8d}  {name:9s}  {mu:8.4f}  {jump:16.2e}")
    print("mu rising with depth, spectral_profile(512, rms=0.2 mm, seed=11), "
          f"{SPEED:g} km/h, Reynolds, default numerics:")
    for d, mu in depth_rise():
        print(f"  depth {d * 1e3:.2f} mm: mu {mu:.4f}")
    print("A pad that creeps (stiffness = 1, 1 mm of water, 20 km/h, the first profile):")
    for model, mu, hyst in creeping_pad(z):
        print(f"  {model:9s} mu {mu:8.3f}  mu_hysteresis {hyst:8.3f}")


if __name__ == "__main__":
    main()
