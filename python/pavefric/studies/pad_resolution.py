"""The figures of docs/accuracy.md's section "The pad's resolution", printed
as three Markdown tables:

    python -m pavefric.studies.pad_resolution      # about a minute

A stiff rubber stands on few of the pad's elements, and its friction then
depends on how finely the elements resolve the contacts, at any time step.
The first two tables are the paper's discretisation (&numerics
min_contacts = 0, the default until 2026-11-27); the third is the default,
min_contacts = 4.

The first table runs the default scene's profile (inputs/ctm_dry.nml, run
from the repository's root) with the shipped tread compound
(inputs/rubber/tread_compound.nml, mu_loc = 0: the rubber's hysteresis
alone) at 20 km/h and each temperature, and the scene's own rubber, and
prints per row: the elements in contact (averaged over positions), the run's
mu at min_contacts = 0 and its mu_error_estimate (with the
elements_per_sample of the estimate's pass), what a pass at half the step
alone would have estimated (three times its change: the estimate before the
pad's pass), mu with the time step converged at one element per sample
(substeps 64), the resolved mu (substeps 16, elements_per_sample 32) and the
actual error against it, and the wall time of that run with its estimate
against one without (the best of three).

The second table is a test set for the estimate's rule (set on the first
table's profile): the six surfaces of the paper's Table 2
(inputs/surfaces/*.nml, dry) with the compound at 0 and 20 C, mu_loc = 0,
20 km/h: the elements in contact, mu at min_contacts = 0, its estimate,
what one halving of the elements and the step would have estimated (three
times its change: the rule before the levels), the resolved mu and the
actual error. Runs only the core (pavefric); nothing is fitted.

The third table, on the rows of both: the default run, &numerics
min_contacts = 4 (the pad's elements halved at each speed until it stands
on 4, that run reported): its mu, the elements_per_sample it ran at, its
estimate, its actual error against the resolved mu, and its wall time
against the run at min_contacts = 0 (both with their estimates; the best of
three).
"""
from __future__ import annotations

import argparse
import time
import warnings
from pathlib import Path

import pavefric
from ..rubber import compound

SCENE = "inputs/ctm_dry.nml"
COMPOUND = "inputs/rubber/tread_compound.nml"
SPEED = 20.0
TEMPERATURES = (-15.0, 0.0, 20.0, 30.0, 40.0, 60.0, 80.0)
#: The resolved run: time step and elements both refined until mu settles
#: (to about 1e-4 here).
RESOLVED = dict(substeps=16, elements_per_sample=32)
#: The time step alone converged, at the scene's one element per sample.
STEP_CONVERGED = dict(substeps=64)


def _quiet(call, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", pavefric.PavefricWarning)
        warnings.simplefilter("ignore", pavefric.PavefricCostWarning)
        return call(**kw)


def _best(scene, repeats: int = 3, **kw) -> float:
    """The best wall time (s) of `repeats` runs at SPEED."""
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        _quiet(scene.simulate, speeds_kmh=[SPEED], **kw)
        times.append(time.perf_counter() - t0)
    return min(times)


def row(scene, label: str, timing: bool = True, **kw) -> dict:
    """One row of the table for the scene with keywords kw (the columns
    before min_contacts' at the paper's discretisation, min_contacts = 0).
    With timing false the wall times are not measured (their columns are
    NaN): the numbers alone, as the test of the docs' table checks them."""
    paper = dict(kw, min_contacts=0)
    ds = _quiet(scene.simulate, speeds_kmh=[SPEED], **paper)
    t_default = _best(scene, **paper) if timing else float("nan")
    t_run = _best(scene, error_estimate=False, **paper) if timing else float("nan")
    half = _quiet(scene.simulate, speeds_kmh=[SPEED], error_estimate=False, substeps=2,
                  time_scheme="euler", **paper)
    fine = _quiet(scene.simulate, speeds_kmh=[SPEED], error_estimate=False, **RESOLVED,
                  **paper)
    step = _quiet(scene.simulate, speeds_kmh=[SPEED], error_estimate=False, **STEP_CONVERGED,
                  **paper)
    mu = float(ds["mu"][0])
    resolved = float(fine["mu"][0])
    return dict(label=label, contacts=float(ds["contact_fraction"][0]) * ds.attrs["pad_elements"],
                mu=mu, estimate=float(ds["mu_error_estimate"][0]),
                pass_eps=int(ds["estimate_elements_per_sample"][0]),
                step_only=3.0 * abs(float(half["mu"][0]) - mu),
                step_converged=float(step["mu"][0]), resolved=resolved,
                actual=abs(mu - resolved), cost=t_default / t_run,
                **_min_contacts(scene, resolved, t_default, timing, **kw))


#: The knob the third table measures.
MIN_CONTACTS = 4


def _min_contacts(scene, resolved: float, t_default: float, timing: bool = True,
                  **kw) -> dict:
    """The run with min_contacts = MIN_CONTACTS at SPEED against the
    resolved mu and the time `t_default` of the run at min_contacts = 0
    (not measured, NaN, without timing)."""
    ds = _quiet(scene.simulate, speeds_kmh=[SPEED], min_contacts=MIN_CONTACTS, **kw)
    mu = float(ds["mu"][0])
    cost = (_best(scene, min_contacts=MIN_CONTACTS, **kw) / t_default if timing
            else float("nan"))
    return dict(mc_mu=mu, mc_eps=int(ds["elements_per_sample_used"][0]),
                mc_estimate=float(ds["mu_error_estimate"][0]), mc_actual=abs(mu - resolved),
                mc_cost=cost)


#: The first table's last row: the scene's own rubber.
SCENE_RUBBER = "the scene's rubber (paper's Table 1), mu_loc = 0.6"


def table(root: Path = Path("."), temperatures=TEMPERATURES, timing: bool = True) -> list[dict]:
    """The first table: the compound at each of `temperatures`, then the
    scene's own rubber; without timing, no wall times."""
    scene = pavefric.load_scene(root / SCENE)
    rubber = {k: v for k, v in compound(root / COMPOUND).items() if k != "temperature"}
    rows = [row(scene, f"compound, {t:g} C", timing, mu_loc=0.0, temperature=t, **rubber)
            for t in temperatures]
    rows.append(row(scene, SCENE_RUBBER, timing))
    return rows


SURFACES = ("GSP", "GSS", "GSSB", "RSBA", "MCA", "VTAC")
SURFACE_TEMPERATURES = (0.0, 20.0)


def surface_rows(root: Path = Path(".")) -> list[dict]:
    """The test set: each surface of the paper's Table 2, dry, the compound
    at SURFACE_TEMPERATURES, mu_loc = 0, SPEED."""
    rubber = {k: v for k, v in compound(root / COMPOUND).items() if k != "temperature"}
    rows = []
    for name in SURFACES:
        scene = pavefric.load_scene(root / "inputs" / "surfaces" / f"{name}.nml")
        for t in SURFACE_TEMPERATURES:
            kw = dict(speeds_kmh=[SPEED], mu_loc=0.0, depth=0.0, temperature=t, **rubber)
            paper = dict(kw, min_contacts=0)
            ds = _quiet(scene.simulate, **paper)
            one = _quiet(scene.simulate, error_estimate=False, elements_per_sample=2, **paper)
            fine = _quiet(scene.simulate, error_estimate=False, **RESOLVED, **paper)
            mu = float(ds["mu"][0])
            resolved = float(fine["mu"][0])
            kw.pop("speeds_kmh")
            paper.pop("speeds_kmh")
            rows.append(dict(label=f"{name}, {t:g} C",
                             **_min_contacts(scene, resolved, _best(scene, **paper), **kw),
                             contacts=float(ds["contact_fraction"][0]) * ds.attrs["pad_elements"],
                             mu=mu, estimate=float(ds["mu_error_estimate"][0]),
                             pass_eps=int(ds["estimate_elements_per_sample"][0]),
                             one_halving=3.0 * abs(float(one["mu"][0]) - mu),
                             resolved=resolved, actual=abs(mu - resolved)))
    return rows


def _markdown(head: list[str], rows: list[dict], cells) -> list[str]:
    """A Markdown table: the header cells `head`, then per row its cells
    (`cells(row, ratio)`, the ratio estimate / actual given)."""
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for r in rows:
        ratio = r["estimate"] / r["actual"] if r["actual"] > 0 else float("inf")
        lines.append("| " + " | ".join(cells(r, ratio)) + " |")
    return lines


def surface_markdown(rows: list[dict]) -> list[str]:
    return _markdown(
        ["surface, compound", "elements in contact", "mu, min_contacts = 0",
         "its estimate (last pass's elements_per_sample)", "one halving would say",
         "resolved mu", "actual error", "estimate / actual"], rows,
        lambda r, ratio: [r["label"], f"{r['contacts']:.2f}", f"{r['mu']:.4f}",
                          f"{r['estimate']:.4f} ({r['pass_eps']})", f"{r['one_halving']:.4f}",
                          f"{r['resolved']:.4f}", f"{r['actual']:.4f}", f"{ratio:.2f}"])


def min_contacts_markdown(rows: list[dict]) -> list[str]:
    return _markdown(
        ["row", f"mu, min_contacts = {MIN_CONTACTS} (the default)", "elements_per_sample used",
         "its estimate", "actual error", "estimate / actual", "time / min_contacts = 0's"],
        [dict(r, estimate=r["mc_estimate"], actual=r["mc_actual"]) for r in rows],
        lambda r, ratio: [r["label"], f"{r['mc_mu']:.4f}", f"{r['mc_eps']}",
                          f"{r['mc_estimate']:.4f}", f"{r['mc_actual']:.4f}", f"{ratio:.2f}",
                          f"{r['mc_cost']:.2f}x"])


def markdown(rows: list[dict]) -> list[str]:
    return _markdown(
        ["rubber", "elements in contact", "mu, min_contacts = 0",
         "its estimate (last pass's elements_per_sample)", "half step alone would say",
         "time step converged", "resolved mu", "actual error", "estimate / actual",
         "min_contacts = 0 with its estimate / without"], rows,
        lambda r, ratio: [r["label"], f"{r['contacts']:.1f}", f"{r['mu']:.4f}",
                          f"{r['estimate']:.4f} ({r['pass_eps']})", f"{r['step_only']:.4f}",
                          f"{r['step_converged']:.4f}", f"{r['resolved']:.4f}",
                          f"{r['actual']:.4f}", f"{ratio:.2f}", f"{r['cost']:.1f}x"])


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="python -m pavefric.studies.pad_resolution",
                                     description=__doc__.splitlines()[0])
    parser.add_argument("--root", default=".", help="the repository's root (default: .)")
    args = parser.parse_args(argv)
    print(f"{SCENE}, {SPEED:g} km/h; resolved: substeps {RESOLVED['substeps']}, "
          f"elements_per_sample {RESOLVED['elements_per_sample']}")
    print()
    rows = table(Path(args.root))
    surfaces = surface_rows(Path(args.root))
    print("\n".join(markdown(rows)))
    print()
    print("\n".join(surface_markdown(surfaces)))
    print()
    print("\n".join(min_contacts_markdown(rows + surfaces)))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
