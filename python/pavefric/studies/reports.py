"""Reports that regenerate documentation pages from measurements."""
from __future__ import annotations

import os
import platform
import shutil
import sys
import time
from pathlib import Path
from typing import Sequence


def machine_description() -> str:
    cpu = platform.processor() or "unknown CPU"
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as fh:
            for line in fh:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return (f"{cpu}, {os.cpu_count()} logical cores, {platform.system()} "
            f"{platform.release()}, Python {platform.python_version()}")


def accuracy_report(scenes: Sequence[str], outdir: str, *, speeds=None, repeats: int = 3,
                    report: str | None = None, also_dry: bool = False,
                    wet_models: Sequence[str] = (), quiet: bool = False) -> list:
    """Run the accuracy-cost study on each scene; write CSV, NetCDF and a plot
    under ``outdir``; with ``report``, a Markdown page and its figure.
    ``wet_models``: on each wet scene, the order study (and the default run's
    estimate) under each of these wet models too, where the scene's own is
    another. Progress (runs done, elapsed, left) on stderr unless ``quiet``."""
    from . import accuracy
    from ..core import load_scene
    from ..progress import Progress

    out = Path(outdir)
    out.mkdir(parents=True, exist_ok=True)
    tables = []
    runs = []
    for scene in scenes:
        runs.append((scene, None, Path(scene).stem))
        if also_dry:
            runs.append((scene, {"depth": 0.0}, Path(scene).stem + "_dry"))
    # the runs to make: each knob's settings (a dry scene has no wet
    # tolerance), the default settings and each tolerance
    steps = 0
    for scene, overrides, _ in runs:
        depth = (overrides or {}).get("depth", load_scene(scene).parameters["depth"])
        steps += sum(len(v) for k, v in accuracy.KNOBS.items()
                     if depth > 0 or k != "wet_tolerance")
        steps += 1 + 2 * len(accuracy.TOLERANCES) + len(accuracy.ORDER_SUBSTEPS) + 1
    # the order study alone under other wet models (wet scenes only)
    extra = []
    for scene in scenes:
        parameters = load_scene(scene).parameters
        if parameters["depth"] <= 0:
            continue
        own = str(parameters.get("wet_model", "kane2017"))
        for model in wet_models:
            if model != own:
                extra.append((scene, {"wet_model": model}, f"{Path(scene).stem}_{model}"))
    steps += len(extra) * (len(accuracy.ORDER_SUBSTEPS) + 2)
    progress = Progress("accuracy", steps, "runs", quiet=quiet)
    for scene, overrides, stem in runs:
        t0 = time.perf_counter()
        table = accuracy.study(scene, speeds_kmh=speeds, repeats=repeats, overrides=overrides,
                               label=stem,
                               on_step=lambda what: progress.advance(what=f"{stem}, {what}"))
        accuracy.to_csv(table, out / f"accuracy_{stem}.csv")
        accuracy.to_netcdf(table, out / f"accuracy_{stem}.nc")
        progress.clear()
        print(f"accuracy: {stem}: {table.sizes['setting']} settings in "
              f"{time.perf_counter() - t0:.1f} s -> {out}/accuracy_{stem}.csv")
        tables.append(table)
        t0 = time.perf_counter()
        table.attrs["tolerance_rows"] = accuracy.tolerance_study(
            scene, table["mu_limit"].values, table["speed_kmh"].values, repeats=repeats,
            overrides=overrides,
            on_step=lambda what: progress.advance(what=f"{stem}, {what}"))
        progress.clear()
        with open(out / f"tolerance_{stem}.csv", "w", encoding="utf-8") as fh:
            fh.write("scheme,tolerance,estimate,actual,substeps,time_s,cost,met\n")
            for r in table.attrs["tolerance_rows"]:
                fh.write(f"{r['scheme']},{r['tolerance']:g},{r['estimate']:.6g},{r['actual']:.6g},"
                         f"{r['substeps']},{r['time_s']:.6g},{r['cost']:.4g},{int(r['met'])}\n")
        print(f"accuracy: {stem}: tolerances in {time.perf_counter() - t0:.1f} s "
              f"-> {out}/tolerance_{stem}.csv")
        t0 = time.perf_counter()
        table.attrs["order"] = accuracy.order_study(
            scene, table["speed_kmh"].values, overrides=overrides, label=stem,
            on_step=lambda what: progress.advance(what=f"{stem}, {what}"))
        progress.clear()
        o = table.attrs["order"]
        print(f"accuracy: {stem}: order {o['euler_order']:.2f} (Euler), "
              f"{o['extrapolated_order']:.2f} (extrapolated) in "
              f"{time.perf_counter() - t0:.1f} s")
    extra_orders = []
    for scene, overrides, stem in extra:
        t0 = time.perf_counter()
        o = accuracy.order_study(scene, speeds if speeds else load_scene(scene).speeds_kmh,
                                 overrides=overrides, label=stem,
                                 on_step=lambda what: progress.advance(what=f"{stem}, {what}"))
        progress.clear()
        print(f"accuracy: {stem}: order {o['euler_order']:.2f} (Euler), "
              f"{o['extrapolated_order']:.2f} (extrapolated) in "
              f"{time.perf_counter() - t0:.1f} s")
        extra_orders.append(o)
    progress.close()
    orders = [t.attrs["order"] for t in tables] + extra_orders
    order_png = accuracy.plot_order(orders, out / "accuracy_order.png")
    print(f"accuracy: wrote {order_png}")
    png = accuracy.plot(tables, out / "accuracy.png", title="error against cost, per knob")
    print(f"accuracy: wrote {png}")
    rec = accuracy.recommend(tables)
    if report:
        _write_accuracy_markdown(Path(report), tables, rec, Path(png), scenes, speeds, repeats,
                                 also_dry, Path(order_png), orders, tuple(wet_models))
        print(f"accuracy: wrote {report}")
    return tables


def _order_cell(order: float) -> str:
    """An order of the table: '—' where too few errors lie above the
    reference's uncertainty to fit one."""
    import math

    return f"{order:.2f}" if math.isfinite(order) else "—"


def _order_summary(orders: Sequence[dict]) -> list[str]:
    """One line per model of the order table: the range of its fitted orders
    and of its reference's uncertainty over the scenes, from the rows."""
    import numpy as np

    models = []
    for o in orders:
        if o["wet_model"] not in models:
            models.append(o["wet_model"])
    lines = ["Per model, over the scenes above (the range of each column):", ""]
    for model in models:
        rows = [o for o in orders if o["wet_model"] == model]

        def span(key, fmt, rows=rows):
            v = np.array([r[key] for r in rows], dtype=float)
            v = v[np.isfinite(v)]
            if v.size == 0:
                return "not defined (too few errors above the reference's uncertainty)"
            return f"{fmt(v.min())} to {fmt(v.max())}"

        lines.append(f"- `{model}` ({len(rows)} scene{'s' if len(rows) > 1 else ''}): Euler order "
                     f"{span('euler_order', lambda x: f'{x:.2f}')}, extrapolated order "
                     f"{span('extrapolated_order', lambda x: f'{x:.2f}')}, reference "
                     f"uncertainty {span('floor', lambda x: f'{x:.1g}')}.")
    return lines


def _write_accuracy_markdown(report: Path, tables, rec, png: Path, scenes, speeds, repeats,
                             also_dry=False, order_png: Path | None = None,
                             orders: Sequence[dict] | None = None,
                             wet_models: Sequence[str] = ()):
    import numpy as np

    from . import accuracy

    figdir = report.parent / "figures"
    figdir.mkdir(parents=True, exist_ok=True)
    shutil.copyfile(png, figdir / "accuracy.png")
    if order_png is not None:
        shutil.copyfile(order_png, figdir / "accuracy_order.png")
    cmd = "python -m pavefric accuracy " + " ".join(scenes)
    if speeds:
        cmd += " --speeds " + " ".join(f"{s:g}" for s in speeds)
    cmd += f" --repeats {repeats}" + (" --also-dry" if also_dry else "")
    if wet_models:
        cmd += " --wet-models " + " ".join(wet_models)
    cmd += f" --report {report}"
    if orders is None:
        orders = [t.attrs["order"] for t in tables if t.attrs.get("order")]
    lines = [
        "# Accuracy and cost of the numerical knobs",
        "",
        "Generated by",
        "",
        f"    {cmd}",
        "",
        f"on {machine_description()}, {time.strftime('%Y-%m-%d')}. "
        "Wall times are the best of the repeats and are noisy; compare them "
        "within a table, not across machines. Each knob is varied with the others "
        "at the scene's values. `error` is the largest difference of the mean "
        "friction over the speeds from the converged limit, estimated per scene by "
        "Richardson extrapolation of the finest `substeps` settings with the order "
        "of convergence observed on the three finest; `convergence` is the "
        "difference from the knob's own finest setting.",
        "",
        "## Recommended settings",
        "",
        "For each budget (a wall-time limit relative to the default settings), the "
        "single-knob setting with the smallest worst-case error over the scenes "
        "below; error, time and cost are the worst over the scenes (time per scene for "
        "the speeds studied, on a 1024-point CTM profile):",
        "",
        "| budget | cost limit | setting | error | time (s) | cost vs default |",
        "|---|---|---|---|---|---|",
    ]
    for budget, r in rec.items():
        setting = f"`{r['knob']} = {r['value']:g}`"
        if (r["knob"], r["value"]) == ("substeps", 1.0):
            setting = "the defaults"
        lines.append(f"| {budget} | {r['limit']:g}x | {setting} | {r['error']:.2g} | "
                     f"{r['time_s']:.3g} | {r['cost']:.2g}x |")
    lines += [
        "",
        "What the knobs do (docs/inputs.md): `substeps` refines the Kelvin–Voigt "
        "time step (the profile is interpolated between samples); "
        "`elements_per_sample` refines the pad; `position_stride` averages every "
        "k-th position with a k times longer time step; `wet_tolerance` stops the "
        "wet load balance earlier.",
        "",
        "![error against time](figures/accuracy.png)",
        "",
        "## The order of the time integrator",
        "",
        "Each element's Kelvin–Voigt (or Maxwell) law is integrated by backward "
        "Euler, one pass per `substeps`; `time_scheme = 'extrapolated'` combines two "
        "passes as 2 mu(s) - mu(s/2) (Richardson), which removes the first-order "
        "term. The error of each against the time step (in units of the paper's "
        "dx / V), against a reference that is the extrapolated value of the two "
        "finest passes (substeps "
        f"{accuracy.ORDER_SUBSTEPS[-2]} and {accuracy.ORDER_SUBSTEPS[-1]}); the "
        "slope is a least-squares fit of log error on log dt over the steps of at "
        "most a quarter of the paper's, above the reference's own uncertainty:",
        "",
        "![error against time step](figures/accuracy_order.png)",
        "",
        "Every row's time is its passes': one backward-Euler pass at `substeps = s` costs "
        "about s times the pass at 1 (column `one pass`, the best of three runs of the "
        "speeds above), and the extrapolated value at s costs the passes at s and s/2. "
        "`reference uncertainty` is the change of the extrapolated value between the "
        "two finest pairs: no error below it is fitted, and where it is large the scheme "
        "has not converged in the time step at all (the order is then not defined).",
        "",
        "| scene | model | Euler order | extrapolated order | Euler error at dt = 1, 1/8 | "
        "extrapolated error at dt = 1/2, 1/8 | reference uncertainty | one pass (s) | "
        "exact: error, cost vs one Euler pass |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for o in orders:
        at8 = list(o["substeps"]).index(8)
        e, r = o["euler_error"], o["extrapolated_error"]
        lines.append(f"| {o['label']} | {o['wet_model']} | {_order_cell(o['euler_order'])} | "
                     f"{_order_cell(o['extrapolated_order'])} | {e[0]:.2g}, {e[at8]:.2g} | "
                     f"{r[1]:.2g}, {r[at8]:.2g} | {o['floor']:.1g} | "
                     f"{o.get('one_pass_s', float('nan')):.3g} | "
                     + (f"{o['exact_error']:.1g}, {o['exact_cost']:.2g}x |" if o["exact_ran"]
                        else "(backward Euler: a film or a Maxwell rubber) |"))
    lines += ["", *_order_summary(orders)]
    if any(o["wet_model"] == "reynolds" for o in orders):
        lines += [
            "",
            "The Reynolds film's rows are not a rate: its load balance has more than one "
            "root, and the root a pass takes depends on where its iteration starts, so its "
            "friction drifts as the step shrinks instead of converging (docs/model.md, "
            "\"The film's balance has more than one root\"; the figures there come from "
            "`python -m pavefric.studies.reynolds_roots`). Where its fitted orders are near 0 "
            "or its reference uncertainty is of the size of its errors, refining the step "
            "does not bring it to a limit on that scene, and the errors in its rows are "
            "changes against the finest passes, not distances to a converged value; "
            "extrapolation and the default run's estimate (the table below) then rest on "
            "a convergence that is not there. A run says so where its balance's root left "
            "the range of the clearances' moves in any of its passes (`film_root_jumps`, "
            "docs/model.md): one warning, and no advice to set a tolerance.",
        ]
    exact = [o for o in orders if o["exact_ran"]]
    exact_note = ""
    if exact:
        exact_note = (f" ({min(o['exact_error'] for o in exact):.1g} to "
                      f"{max(o['exact_error'] for o in exact):.1g} here; "
                      "tests/test_exact.py compares it with a finer one, to 2e-6), at "
                      f"{min(o['exact_cost'] for o in exact):.2g} to "
                      f"{max(o['exact_cost'] for o in exact):.2g} times the cost of one "
                      "Euler pass")
    lines += [
        "",
        "`time_scheme = 'exact'` (last column) integrates the Kelvin–Voigt pad on a "
        "road without a film exactly, from contact event to event (docs/model.md, "
        "\"Exact time integration\"): its error is the reference's own uncertainty"
        f"{exact_note}. Wet scenes (the "
        "paper's bearing, the drainage film, the Reynolds film) and the Maxwell compound "
        "still run backward Euler under it, and say so (`exact_integrator_ran`).",
        "",
        "Why not a higher order for backward Euler: the friction is the rubber's dissipation, and most "
        "of it happens where an element meets a rising facet. The contact starts "
        "inside a time step, and the dashpot's force there jumps (a Kelvin–Voigt "
        "element struck at speed); a fixed-step scheme, whatever its order on smooth "
        "motion, places that event to within a step, so the error of each contact "
        "is of the order of one step's dissipation. Extrapolation removes the "
        "first-order term of that error once the steps are fine enough for it to "
        "dominate (from about substeps 4–8); below that, the passes are not in their "
        "asymptotic range and `time_scheme = 'extrapolated'` reports the finest pass "
        "instead (the ratio test below). `time_scheme = 'richardson'` reports the "
        "default's own pair extrapolated (substeps 1 and 2: the run and its error "
        "estimate's pass, no pass more): the column \"extrapolated error at dt = 1/2\" "
        "is its error on these scenes. Resolving each contact event within the "
        "step, as `time_scheme = 'exact'` does, removes that error altogether.",
        "",
        "## What a default run says of its accuracy",
        "",
        "A run at `tolerance = 0` (the default) estimates its own error from the time "
        "step (`&numerics error_estimate = .true.`, the default): one more backward-Euler "
        "pass at half the step (`substeps` doubled), and three times the change of mu as "
        "`mu_error_estimate`, with a warning where it exceeds 5 % of mu (and 0.001); the reported mu is the "
        "run's own. The pass costs about twice the run (`error_estimate = .false.` skips "
        "it; speeds the exact integrator ran have no error from the step, and their pass halves the elements instead: below). A coarse pass "
        "(`position_stride = 2`, half the cost) was tried first and rejected: it keeps the "
        "pad stepping from sample to sample, where most of the error of one step per "
        "sample lies on a wet road: on `inputs/ctm_wet.nml` at 20 km/h its change was 2.3e-4 "
        "where the error was 7.8e-3, 34 times as much (tests/test_error_estimate.py, "
        "test_a_coarse_pass_would_miss_the_wet_error, measures it). Where the pad stood on "
        "fewer than 4 elements in contact on average, the default run refines the pad itself "
        "(`&numerics min_contacts = 4`) and the estimate is the refined run's; with "
        "`min_contacts = 0` the elements are halved in the estimate's passes instead, until "
        "it stands on 4, and the estimate adds the change that made "
        "(`estimate_elements_per_sample` records the finest pass's elements): see \"The "
        "pad's resolution\" below. "
        "Each scene's default run (one step per "
        "sample, Euler) against the reference limit above, per speed (`ratio` is estimate / "
        "actual error, below 1 an underestimate):",
        "",
        "| scene | model | largest actual error | its estimate | smallest ratio over the speeds |",
        "|---|---|---|---|---|",
    ]
    for o in orders:
        if "default_estimate" not in o:
            continue
        est = np.asarray(o["default_estimate"], dtype=float)
        err = np.asarray(o["default_error"], dtype=float)
        w = int(np.argmax(err))
        ratio = est / np.maximum(err, 1e-300)
        lines.append(f"| {o['label']} | {o['wet_model']} | {err[w]:.2g} | {est[w]:.2g} | "
                     f"{np.min(ratio):.2g} |")
    lines += ["", *_pad_resolution_section()]
    lines += [
        "",
        "## Accuracy on demand: the cost of each `&numerics tolerance`",
        "",
        "With `tolerance > 0` the time step is halved (`substeps` doubled from the "
        "scene's value) until each speed's estimated error is within the tolerance. "
        "`time_scheme = 'euler'` reports the finest pass, with the estimate twice the "
        "larger of its last two changes (first-order convergence leaves an error "
        "equal to the last change; the doubling and the larger of two guard the "
        "coarse steps, where the sequence is not yet monotone). "
        "`time_scheme = 'extrapolated'` (the default) reports 2 mu(s) - mu(s/2) "
        "where the last two changes d1, d2 have one sign with d1/d2 in [1.5, 3] (the "
        "first-order range), with the estimate max(|2 d2 - d1|, |d2|) when that is the "
        "smaller (`mu_extrapolated` = 1 says where). The estimate is written as "
        "`mu_error_estimate`, the substeps chosen as `substeps_used`. The step is refined "
        "at the pad `min_contacts` chose (the default 4: \"The pad's resolution\" above); "
        "at `min_contacts = 0` the pad (`elements_per_sample`) is not refined, and where it "
        "stood on fewer than 4 elements in contact a warning says that the tolerance does "
        "not cover its resolution. `actual` is the largest "
        "|mu - converged limit| over the speeds; `cost` is the wall time against the "
        "default settings (every refinement level run counts). Worst over the scenes:",
        "",
        "| scheme | tolerance | largest estimate | largest actual error | substeps chosen | "
        "cost vs default | met everywhere |",
        "|---|---|---|---|---|---|---|",
    ]
    n_rows = len(tables[0].attrs.get("tolerance_rows", []))
    for i in range(n_rows):
        rows = [t.attrs["tolerance_rows"][i] for t in tables]
        lines.append(
            f"| {rows[0]['scheme']} | {rows[0]['tolerance']:g} | "
            f"{max(r['estimate'] for r in rows):.2g} | "
            f"{max(r['actual'] for r in rows):.2g} | "
            f"{min(r['substeps'] for r in rows)}–{max(r['substeps'] for r in rows)} | "
            f"{min(r['cost'] for r in rows):.2g}–{max(r['cost'] for r in rows):.2g}x | "
            f"{'yes' if all(r['met'] for r in rows) else 'no'} |")
    heads = [f"{r['tolerance']:g} {r['scheme'][:5]}"
             for r in tables[0].attrs.get("tolerance_rows", [])]
    lines += [
        "",
        "Per scene (tolerance and scheme: actual error / estimate, substeps, cost):",
        "",
        "| scene | " + " | ".join(heads) + " |",
        "|---|" + "---|" * len(heads),
    ]
    for t in tables:
        cells = [f"{r['actual']:.1g} / {r['estimate']:.1g}, {r['substeps']}, {r['cost']:.2g}x"
                 for r in t.attrs.get("tolerance_rows", [])]
        lines.append(f"| {t.attrs['label']} | " + " | ".join(cells) + " |")
    lines += [""]
    for table in tables:
        name = table.attrs["label"]
        kind = "wet" if table.attrs["wet"] else "dry"
        lines += [f"## {name} ({kind}, speeds {table.attrs['speeds_kmh']} km/h)", "",
                  "| knob | setting | error | convergence | time (s) | element-steps | cost vs default |",
                  "|---|---|---|---|---|---|---|"]
        default_t = None
        for i in range(table.sizes["setting"]):
            if (str(table["knob"].values[i]) == "substeps"
                    and float(table["value"].values[i]) == 1.0):
                default_t = float(table["time_s"].values[i])
        for i in range(table.sizes["setting"]):
            t = float(table["time_s"].values[i])
            ratio = f"{t / default_t:.2g}x" if default_t else ""
            lines.append(f"| {table['knob'].values[i]} | {table['value'].values[i]:g} | "
                         f"{table['error'].values[i]:.3g} | "
                         f"{table['convergence'].values[i]:.3g} | {t:.3g} | "
                         f"{table['element_steps'].values[i]:,} | {ratio} |")
        lines.append("")
    lines += [
        "## Reading the tables",
        "",
        "- `substeps` and `elements_per_sample` converge (each doubling buys "
        "accuracy for double or more the cost). Their default error is MODEL.md's "
        "discretisation error on a CTM profile.",
        "- Refinement places elements between the CTM's samples, where heights and "
        "facet tangents are interpolated linearly (facets stay those of MODEL.md's "
        "central differences at the samples). On textures with much of their "
        "content at 3–5 samples per wavelength (the reference granites and VTAC, "
        "RMS slope near 1) the refined answer is up to ~0.08 higher; on the asphalt "
        "MCA (RMS slope 0.25) it moves by less than 1e-4. What lies between a CTM's "
        "samples is unknown, so on such textures the default's error is as much a "
        "property of the measurement as of the numerics.",
        "- `position_stride` divides the cost by the stride; for an elastic dry "
        "scene it only subsamples positions, otherwise it also lengthens the time "
        "step. The two errors partly cancel, so its error is not monotone at small "
        "strides; it is the cheap knob for a quick look at long profiles.",
        "- `wet_tolerance` costs little either way: the safeguarded Newton "
        "iteration converges quadratically, so the default (1e-14) is nearly free.",
        "",
    ]
    report.write_text("\n".join(lines), encoding="utf-8")


def _pad_resolution_section() -> list[str]:
    """docs/accuracy.md's "The pad's resolution": the rule, and the table of
    python -m pavefric.studies.pad_resolution when run from the repository's
    root (where its scene and compound are)."""
    from . import pad_resolution

    lines = [
        "## The pad's resolution",
        "",
        "The time step is not the only discretisation: the pad is a row of elements, one per "
        "sample by default (23 on the 20 mm pad). A rubber as soft as the paper's stands on "
        "about 15 of them and the elements' resolution moves its mu by a tenth of the time "
        "step's error (the `elements_per_sample` rows of the scenes below). A stiff rubber "
        "stands on a few: the shipped tread compound below 40 °C on one to four. At one "
        "element per sample (`min_contacts = 0`) its mu is then a fifth to three fifths of the resolved value, and part of that error is the "
        "elements' at any time step (the column \"time step converged\" below, substeps 64 "
        "at one element per sample), because a contact patch narrower than an element "
        "is one element's indentation or nothing. A pass at half the step alone never sees that error (the "
        "column \"half step alone\" below: less than half the actual error at 0 °C). Nor does "
        "one halving of the elements: as they shrink, friction rises along an S (the pad rests "
        "on one asperity's top until its elements are fine enough to wrap it), and on the "
        "paper's surfaces, where the compound at 0 °C stands on 1.1 to 1.3 elements, one "
        "halving's change (three times it, the column \"one halving would say\" of the second "
        "table) was a fifth of the actual error (GSP: 0.08 where mu is 0.42 off). So where "
        "the pad stood on fewer than 4 elements in contact, averaged over the positions "
        "where any touched (the film may carry it alone at the others), the estimate halves "
        "the elements (`elements_per_sample` doubled; the step along the road halves with "
        "them) until the pad stands on 4, at most 4 times (16 times finer; the levels cost up "
        "to 340 times the run), then makes one more pass (half the elements again where it "
        "still stands on fewer, else half the step), and reports the change the refinement made "
        "plus three times that pass's change. Its warning gives the refined pad's mu and the "
        "`elements_per_sample` to set. That is the estimate at `&numerics min_contacts = 0`, "
        "the paper's discretisation, which the first two tables measure; the default, "
        "`min_contacts = 4`, reports the refined pad itself (below). At `min_contacts = 0` "
        "a run with `&numerics tolerance` (which refines the time step only) warns that its "
        "tolerance does not cover the pad there. Speeds the exact integrator ran (a dry Kelvin–Voigt "
        "pad, `time_scheme = 'auto'` or `'exact'`) have no error from the step but one from "
        "the elements at any number of contacts (a pad of 1e9 N m⁻³ on 5 to 6.4 elements was "
        "9–13 % off with an estimate of 0): their passes halve the elements, exact too. The "
        "rule was set on the first table's profile; the second table, the paper's six "
        "surfaces with the compound, is its test set: estimate / actual 1.03–1.22 there.",
        "",
        f"Generated by `python -m pavefric.studies.pad_resolution` ({pad_resolution.SCENE}, "
        f"{pad_resolution.SPEED:g} km/h; resolved: substeps "
        f"{pad_resolution.RESOLVED['substeps']}, elements_per_sample "
        f"{pad_resolution.RESOLVED['elements_per_sample']}; time step converged: substeps "
        f"{pad_resolution.STEP_CONVERGED['substeps']}):",
        "",
    ]
    if not (Path(pad_resolution.SCENE).exists() and Path(pad_resolution.COMPOUND).exists()):
        return lines + ["(run the command from the repository's root for the table)", ""]
    rows = pad_resolution.table()
    surfaces = pad_resolution.surface_rows()
    return (lines + pad_resolution.markdown(rows) + [
        "",
        f"The test set: the paper's surfaces (`inputs/surfaces/*.nml`, dry), the compound at "
        f"{' and '.join(f'{t:g}' for t in pad_resolution.SURFACE_TEMPERATURES)} °C, mu_loc = 0, "
        f"{pad_resolution.SPEED:g} km/h, resolved as above:",
        "",
        *pad_resolution.surface_markdown(surfaces), "",
        f"### `&numerics min_contacts = {pad_resolution.MIN_CONTACTS}` (the default): the "
        "resolved pad reported",
        "",
        "The default since 2026-11-27. `min_contacts = 0` reports the paper's "
        "discretisation, one element per sample, and says how far off it is (the tables "
        "above). `&numerics min_contacts = n` reports the refined pad instead: at "
        "each speed where the pad stood on fewer than n elements in contact, the elements are "
        "halved until it stands on n (at most 4 times; `elements_per_sample_used` records "
        "where each speed ended), and that run's mu, its parts and every per-speed output "
        "are reported, with an estimate of its own error (three times the change at half the "
        "step, or at half the elements where it still stands on fewer). The levels are the "
        "ones the estimate at `min_contacts = 0` runs anyway, so with the estimate on it costs "
        "about what that run costs. A pad on enough elements is not touched (the paper's rubber "
        "row: the same bits). On the test set, the six surfaces, its actual error was 2.2 "
        "to 10.6 times smaller than at `min_contacts = 0` (0.007–0.091 against 0.026–0.48), "
        "its estimate 1.11–1.80 times its actual error, its time 0.97–1.01 times that "
        "run's. What is left (up to a third of mu: VTAC at 20 °C) is the refined pad's own "
        "error, from its time step and from what its elements still miss; its estimate "
        "bounds it on every row, and `tolerance` refines the step. On the rows of both "
        "tables above (time: the best of three, both with their estimates):",
        "",
        *pad_resolution.min_contacts_markdown(rows + surfaces), ""])


def _span(values, scale=1e-6, fmt="{:.0f}") -> str:
    lo, hi = min(values) * scale, max(values) * scale
    return fmt.format(lo) if fmt.format(lo) == fmt.format(hi) else \
        f"{fmt.format(lo)}–{fmt.format(hi)}"


def _numpy_cell(rows, digits: str) -> str:
    """The NumPy reference's rate and the core's ratio to it, or why not
    (the benchmark times the reference only when given --reference)."""
    rates = [r.get("numpy", float("nan")) for r in rows]
    if not rates or any(v != v for v in rates):
        return "not measured (bench --reference tests/reference.py)"
    return (f"{_span(rates, 1e-6, digits)} M "
            f"(core {_span([r['core'] / r['numpy'] for r in rows], 1, '{:.0f}')}x)")


def _has_numpy(rows) -> bool:
    return all(r.get("numpy", float("nan")) == r.get("numpy", float("nan")) for r in rows)


def _met(ok: bool) -> str:
    return "met" if ok else "**not met**"


def _targets_now(results: dict) -> list[str]:
    """Issue 13's targets (and the cost targets of issues 12 and 14), each
    with the figure measured in this run beside the plain loop and the NumPy
    reference."""
    sw = results["sweep"]
    dry = [r for r in sw if r["scene"] == "dry"]
    wet = [r for r in sw if r["scene"] == "wet"]
    sq = [r for r in sw if r["scene"] == "wet, squeeze"]
    rey = [r for r in sw if r["scene"] == "wet, reynolds"]
    prog = results["program"]
    rd = results["reading"]
    text = [r for r in rd["per_number"] if r["file"].startswith("text")]
    long = rd["long"]
    mpi = results.get("batch", {}).get("mpi_uneven") or {}
    rub = results.get("rubber") or {}
    squeeze_ratio = max(k["core"] / q["core"] for k, q in zip(wet, sq))
    rows = [
        "| target | measured | plain loop | NumPy reference | |",
        "|---|---|---|---|---|",
        f"| whole program, 400,000-point dry text profile, 10 speeds: ≥ 1.5x the plain "
        f"loop's compute | {prog['plain'] / prog['1']:.2f}x on one thread "
        f"({prog['1']:.2f} s for reading, running and writing; {prog['plain'] / prog['2']:.2f}x "
        f"on two) | {prog['plain']:.2f} s compute | — | {_met(prog['plain'] / prog['1'] >= 1.5)} |",
        f"| text profile reading ≤ 100 ns per number | "
        f"{_span([r['ns_per_number'] for r in text], 1, '{:.0f}')} ns "
        f"(before: {_span([r['before'] for r in text if r['before']], 1, '{:.0f}')} ns) | — | — "
        f"| {_met(max(r['ns_per_number'] for r in text) <= 100)} |",
        f"| a 10,000,000-point profile read and run in < 3 s and ≤ 150 bytes a point | "
        f"{long['program_s']:.2f} s, {long['program_bytes_per_point']:.0f} bytes a point "
        f"(before: {rd['old']['program_10m_s']:.1f} s) | — | — | "
        f"{_met(long['program_s'] < 3 and long['program_bytes_per_point'] <= 150)} |",
        f"| dry, N = 23, 6-speed sweep: ≥ 300 M element-steps/s per core | "
        f"{_span([r['core'] for r in dry])} M | {_span([r['plain'] for r in dry])} M "
        f"(core {_span([r['core'] / r['plain'] for r in dry], 1, '{:.2f}')}x) | "
        f"{_numpy_cell(dry, '{:.2f}')} | "
        f"{_met(min(r['core'] for r in dry) >= 300e6)} |",
        f"| wet, N = 23, 6-speed sweep: ≥ 60 M element-steps/s per core | "
        f"{_span([r['core'] for r in wet])} M | {_span([r['plain'] for r in wet], 1e-6, '{:.1f}')}"
        f" M (core {_span([r['core'] / r['plain'] for r in wet], 1, '{:.1f}')}x) | "
        f"{_numpy_cell(wet, '{:.3f}')} | "
        f"{_met(min(r['core'] for r in wet) >= 60e6)} |",
    ]
    if mpi:
        rows.append(
            f"| 2 MPI ranks ≥ 1.7x one rank on an uneven batch, wall time with start-up | "
            f"{mpi['ratio']:.2f}x (6 long profiles among 240 short; outputs identical: "
            f"{mpi['identical']}) | — | — | {_met(mpi['ratio'] >= 1.7)} |")
    else:
        rows.append("| 2 MPI ranks ≥ 1.7x one rank on an uneven batch | not measured "
                    "(no mpirun) | — | — | |")
    rows.append(
        f"| issue 12: the drainage film ≤ 2x the paper's wet model per element-step | "
        f"{squeeze_ratio:.2f}x (at most; {_span([r['core'] for r in sq])} M element-steps/s) "
        f"| — | — | {_met(squeeze_ratio <= 2)} |")
    if rub:
        rows.append(
            f"| issue 14: a Maxwell rubber of 3 arms ≤ 1.5x Kelvin–Voigt per element-step | "
            f"{rub['three_arms_ratio']:.2f}x | — | — | {_met(rub['three_arms_ratio'] <= 1.5)} |")
    est = [r for r in results.get("estimate") or [] if r["set"] == "test"]
    fit = [r for r in results.get("estimate") or [] if r["set"] == "training"]
    if est:
        worst = max(max(r["ratio"], 1 / r["ratio"]) for r in est)
        rows.append(
            f"| issue 23: estimated vs measured time within a factor 2 over the benchmark "
            f"scenes | estimated / measured {_span([r['ratio'] for r in est], 1, '{:.2f}')} "
            f"on the {len(est)} test scenes the rates were not fitted on "
            f"({_span([r['ratio'] for r in fit], 1, '{:.2f}')} on the {len(fit)} training "
            f"scenes; the program, one thread) | — | — | {_met(worst <= 2)} |")
    el = results.get("elements") or []
    if dry and wet and el:
        big = el[-1]
        rows += [
            f"| issue 23: dry, N = 23, ≥ 2.5x the plain loop | core "
            f"{_span([r['core'] / r['plain'] for r in dry], 1, '{:.2f}')}x the plain loop | "
            f"{_span([r['plain'] for r in dry])} M | — | "
            f"{_met(min(r['core'] / r['plain'] for r in dry) >= 2.5)} |",
            f"| issue 23: wet (`kane2017`), N = 23, ≥ 8x the plain loop | core "
            f"{_span([r['core'] / r['plain'] for r in wet], 1, '{:.1f}')}x the plain loop | "
            f"{_span([r['plain'] for r in wet], 1e-6, '{:.1f}')} M | — | "
            f"{_met(min(r['core'] / r['plain'] for r in wet) >= 8)} |",
            f"| issue 23: N = {big['N']} per element-step no worse than 2x N = 23 | dry "
            f"{el[0]['dry'] / big['dry']:.2f}x, wet {el[0]['wet'] / big['wet']:.2f}x | — | — | "
            f"{_met(max(el[0]['dry'] / big['dry'], el[0]['wet'] / big['wet']) <= 2)} |",
        ]
    acc = results.get("accuracy") or []
    for r in acc:
        rows.append(
            f"| issue 23: the default scene `{r['scene']}` to tolerance = {r['tolerance']:g} "
            f"≤ 10x its default run | {r['ratio']:.1f}x with `time_scheme = '{r['scheme']}'` "
            f"(substeps {r['substeps']}, estimate {r['estimate']:.1e}"
            + ("" if r["met"] else ", tolerance not met") + ") | — | — | "
            f"{_met(r['ratio'] <= 10 and r['met'])} |")
    if rey:
        reynolds_ratio = max(k["core"] / q["core"] for k, q in zip(wet, rey))
        rows.append(
            f"| issue 21: the Reynolds film ≤ 3x `kane2017` per element-step | "
            f"{reynolds_ratio:.2f}x (at most; {_span([r['core'] for r in rey])} M "
            f"element-steps/s) | — | — | {_met(reynolds_ratio <= 3)} |")
    else:
        rows.append("| issue 21: the Reynolds film ≤ 3x `kane2017` per element-step | not "
                    "measured in this report | — | — | |")
    api = results.get("api_threads")
    if api:
        rows.append(
            f"| issue 19: two scenes on two threads through the C API ≤ 0.7x the time of one "
            f"after the other (2 cores) | {api['ratio']:.2f}x ({api['parallel']:.2f} s against "
            f"{api['serial']:.2f} s; results identical: {api['same']}; the runs' CPU time "
            f"{api.get('cpu_ratio', float('nan')):.2f}x the serial runs) | — | — | "
            f"{_met(api['ratio'] <= 0.7 and api['same'])} |")
    rows += [
        "",
        "The plain loop is python/pavefric/studies/plain_loop.f90: MODEL.md written the obvious way in "
        "Fortran (one speed, one position at a time, the dry balance by insertion sort "
        "and scan, the wet one by bisection), compiled by the benchmark with the core's "
        "`-O3 -funroll-loops`; its compute is timed inside it, its reading excluded. It "
        "sums the paper's facet forces (Eq. 10); the core's default measures the energy "
        "the rubber and the facets dissipate (`friction_scheme`, docs/model.md), which "
        "differs from it by the `|mu - plain|` column below (the same model, not the "
        "same discretisation of its friction). In the kernel rows the core does the plain "
        "loop's work: one Euler step per sample (`time_scheme = 'euler'`), no error estimate "
        "and no refinement of the pad (`min_contacts = 0`); the default's further passes "
        "(its error estimate, the pad halved where it stands on few elements) are costed "
        "in the section 'Cost estimate'. The NumPy reference is the tests' oracle, "
        "tests/reference.py, timed only when the command names it (`--reference`).",
    ]
    return rows


def performance_report(report: Path, results: dict, lines: list[str]) -> None:
    """docs/performance.md: the benchmark's tables and a log-log plot."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figdir = report.parent / "figures"
    figdir.mkdir(parents=True, exist_ok=True)
    el = results["elements"]
    length_rows, six = results["length"]
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4.2), dpi=120)
    n = [r["N"] for r in el]
    a.loglog(n, [1e9 / r["dry"] for r in el], "o-", label="core, dry")
    a.loglog(n, [1e9 / r["wet"] for r in el], "s-", label="core, wet")
    if _has_numpy(el):
        a.loglog(n, [1e9 / r["numpy"] for r in el], "^--", label="NumPy reference, dry")
    a.set_xlabel("pad elements N")
    a.set_ylabel("ns per element-step")
    a.grid(alpha=0.3, which="both")
    a.legend(fontsize=8)
    pts = [r["n"] for r in length_rows]
    b.loglog(pts, [r["seconds"] for r in length_rows], "o-", label="time (s)")
    b.loglog(pts, [max(r["extra_bytes"], 1) / 2**20 for r in length_rows], "s-",
             label="peak extra memory (MB)")
    b.set_xlabel("profile points (open, dry, N = 23)")
    b.grid(alpha=0.3, which="both")
    b.legend(fontsize=8)
    fig.suptitle("cost against pad elements and profile length (noisy absolute times)")
    fig.tight_layout()
    fig.savefig(figdir / "performance.png")
    plt.close(fig)

    tp = results["throughput"]
    dry = [r for r in tp if r["scene"] == "dry"]
    wet = [r for r in tp if r["scene"] == "wet"]
    th = results["threads"]
    out = [
        "# Performance",
        "",
        "Generated by `python -m pavefric bench --report docs/performance.md"
        f"{' --reference tests/reference.py' if _has_numpy(tp) else ''}` "
        f"on {machine_description()}, {time.strftime('%Y-%m-%d')}. "
        "Absolute times are noisy (shared machine, one run); the ratios measured side by "
        "side in the same run are the figures to read. An element-step is one pad "
        "element at one position (and sub-step).",
        "",
        "## Against the targets",
        "",
        *_targets_now(results),
        "",
        "### The first version's targets",
        "",
        "| target | measured |",
        "|---|---|",
        f"| dry, N = 23: ≥ 100 M element-steps/s per core | "
        f"{min(r['core'] for r in dry) / 1e6:.0f}–{max(r['core'] for r in dry) / 1e6:.0f} M |",
        f"| wet, N = 23: ≥ 20 M element-steps/s per core | "
        f"{min(r['core'] for r in wet) / 1e6:.0f}–{max(r['core'] for r in wet) / 1e6:.0f} M |",
        f"| N = 2000 per element no worse than N = 23 by 3x | dry "
        f"{el[0]['dry'] / el[-1]['dry']:.2f}x, wet {el[0]['wet'] / el[-1]['wet']:.2f}x "
        f"(N = {el[-1]['N']}) |",
        (f"| ≥ 300x the NumPy reference | dry {min(r['ratio'] for r in dry):.0f}–"
         f"{max(r['ratio'] for r in dry):.0f}x, wet {min(r['ratio'] for r in wet):.0f}–"
         f"{max(r['ratio'] for r in wet):.0f}x at N = 23; dry "
         f"{el[-1]['dry'] / el[-1]['numpy']:.0f}x at N = {el[-1]['N']} |"
         if _has_numpy(tp) and _has_numpy(el) else
         "| ≥ 300x the NumPy reference | not measured (bench --reference tests/reference.py) |"),
        f"| memory ∝ profile + pad, independent of speeds | "
        f"{length_rows[-1]['extra_bytes'] / length_rows[-1]['n']:.0f} bytes/point at "
        f"{length_rows[-1]['n']:,} points; 6 speeds {six['extra_bytes'] / 2**20:.0f} MB vs "
        f"1 speed {[r for r in length_rows if r['n'] == six['n']][0]['extra_bytes'] / 2**20:.0f}"
        " MB |",
        f"| 2 threads ≥ 1.8x one thread on 6 speeds | dry {th[0]['one'] / th[0]['two']:.2f}x, "
        f"wet {th[1]['one'] / th[1]['two']:.2f}x; identical results: "
        f"{all(r['same'] for r in th)} |",
        (f"| demo batch: 2 MPI ranks ≥ 1.8x one rank | throughput "
         f"{results['mpi']['rate_two'] / results['mpi']['rate_one']:.2f}x; wall time with "
         f"mpirun start-up {results['mpi']['one'] / results['mpi']['two']:.2f}x "
         f"({results['mpi']['profiles']} profiles, 3 depths, 8 speeds, one thread a rank) |"
         if results.get("mpi") else "| demo batch: 2 MPI ranks ≥ 1.8x one rank | not measured (no mpirun) |"),
        "",
        "![cost against N and profile length](figures/performance.png)",
        "",
        "## Full output",
        "",
        "```",
        *lines,
        "```",
        "",
        "## How the core gets there",
        "",
        "- Speeds in lanes: the speeds of a scene advance together, up to 8 at a "
        "time (as many chunks as threads when there are speeds enough), the element "
        "loops running over the lanes innermost in small kernels on explicit run-time "
        "shapes, which GCC turns into vector loops with blends. Each speed's "
        "arithmetic is the scalar algorithm's, sums in element order, so neither the "
        "chunking nor the thread count changes a bit (tests/test_effects.py).",
        "- Dry balance: Newton's method on the convex piecewise-linear load "
        "function, warm-started from the previous position's dry root (extrapolated "
        "linearly from the two before where there are two); it "
        "stops when its active set repeats, which gives the exact closed-form "
        "root in 2–4 passes over the elements (no sort; LAPACK `dlasrt` only as "
        "a fallback).",
        "- Wet balance: safeguarded Newton with the analytic derivative of Eq. 15, "
        "warm-started from the previous position's wet root (from the dry root at the "
        "first position, or when the guess leaves the bracket), the evaluations of all "
        "the lanes still iterating in one pass; `bearing_evaluations` counts them. The "
        "warm start (used where the film carried load at the previous position; elsewhere "
        "the dry root, exact when the film carries nothing) took 11–37 % fewer evaluations "
        "on the scenes of the regression record, 45–52 % on its tolerance cases and 2 % "
        "more on one steep profile (the record's `bearing_evaluations` before and after, "
        "2026-11-26), for the same roots to the balance's tolerance (mu moved by 1e-16). "
        "Since 2026-11-28 the Newton steps run on the formula of the piece the iterate "
        "lies on (the contacts fixed: the pad's push and the gaps' sum linear in the "
        "penetration, one logarithm per step and no pass over the elements), and a pass "
        "checks the piece's root: `bearing_evaluations` counts the passes, 3.7–4.5 a "
        "position before and 2.1–2.3 after on the wet run of `tools/profile_kernel.sh "
        "--callgrind`, for the same roots to the tolerance (mu moved by at most 1e-15 on "
        "the regression record's scenes; tests/test_wet_balance.py). The dry balance "
        "under a film starts from the previous position's dry root, no longer from its "
        "wet one (the same roots to the bit, a third fewer of its passes: callgrind, "
        "93 M instructions of `dry_roots` before and 59 M after in that run). Since "
        "2026-11-29 a root of the piece's formula with no element's height between the "
        "pass's point and it (ends included) is taken without the checking pass: one "
        "cheaper pass counts those heights for all such lanes at once. The formula and a "
        "pass give the same f rounded differently (by about 1e-15 W), so such a root may "
        "miss the tolerance by that much when f is summed element by element "
        "(tests/test_wet_balance.py). The bearing's load now takes its scales P / H_in² "
        "and P / H_in³ from the speed's step and runs in line for all the lanes in one "
        "call (the same numbers to the bit). On the wet run of `tools/profile_kernel.sh "
        "--callgrind`: 2.06–2.25 passes with the film's load a speed and position before, "
        "1.10–1.19 after; "
        "533 M instructions before, 497 M after; mu moved by at most 6e-16 of its scale "
        "(its rubber part 6e-15) on the regression record (tests/data/regression/"
        "record.json before and after, 2026-11-29). Whether the film engages at the dry "
        "root, and the wet bracket's lower end, come from the lanes' sums in one vector "
        "pass (the film's `engages_of_sums` and `lower_bound_of_sum`), no longer from "
        "each lane's gap field copied out row by row: the same numbers to the bit, "
        "497 M instructions before and 479 M after on that run "
        "(tests/test_wet_balance.py, test_the_lanes_engage_as_each_field_does). Where "
        "every speed's film carried load at the previous position, the dry roots are not "
        "computed: the film engages iff the pad's push at its engage level is below the "
        "load (two vector passes where the dry roots took about four), and the wet "
        "bracket's upper end is the dry balance's Newton step from that level "
        "(docs/model.md): 479 M instructions before and 434 M after on that run; "
        "`bearing_evaluations` 0–2.3 % higher on the regression record's scenes (8.9 % "
        "on its steep profile), mu moved by at most 2.2e-16 of its scale.",
        "- Facet tangents computed once per profile sample, not per position; a closed "
        "profile is unrolled once so no element index needs a modulo; no allocation "
        "inside the position loop. That last was not so until 2026-12-07: gfortran "
        "allocated heap temporaries there, at every position: the mask of a WHERE on "
        "sections of the lanes (`(1:nl)`), a mask expression passed to the wet balance, "
        "and contiguous copies of the profile's strided sections where `substeps` or "
        "`elements_per_sample` exceeds 1 (the default's error estimate runs at "
        "`substeps = 2`); the dummies now take those sections as they are, and the "
        "masks are loops or lanes-sized arrays. Found with `perf record --call-graph "
        "dwarf` and confirmed with a breakpoint on malloc after the first positions "
        "(gdb, on the program built with `-g`): none now on the dry, wet, Maxwell and "
        "Reynolds paths; malloc and free had taken about 5 % of a 1,000,000-point dry "
        "run at 60 km/h with the default error estimate, whose user time fell from 1.01 "
        "s to 0.89 s (best of 4, the two builds alternated; results identical to the "
        "bit; perf, gdb and `/usr/bin/time` run by hand on the program, a record, not a "
        "command of the repository). The same change stopped storing each step's pushes twice in the "
        "Kelvin–Voigt step.",
        "- Profile reading: a single-pass parser over the file's bytes "
        "(docs/profiles.md); NetCDF surveys read one profile by index.",
        "",
        "## Why 300 M (dry) and 60 M (wet) are not reached",
        "",
        "The per-position work is a handful of passes over the pad (for the dry "
        "Kelvin-Voigt pad two or three: the clearances with the balance's first "
        "Newton pass, a confirming pass where the first step cannot be taken as it "
        "stands, and the step), each a short loop: with "
        "six speeds a pass is three SSE2 vectors per element, so loop control and the "
        "serial sum chains, not arithmetic, set the pace. A build with "
        "`-Dnative=true` (AVX-512 on this machine) measured slower, not faster, at "
        "six lanes. Reaching 300 M would need the elements, not the speeds, in the "
        "vectors, with sums in another order: results would then differ from 0.1.0's "
        "in the last bits, which the regression record forbids for dry scenes. The "
        "wet balance needed 4–8 bearing evaluations a position (each a logarithm per "
        "speed); warm-started, 4–5; with Newton on the pieces' formula, about 2 passes, "
        "and about 1.1 since the piece's root is taken without a check where no height "
        "lies between (the line under the sweep table). The demand that "
        "results stay bit for bit with 0.1.0 is withdrawn (issue 23), so the elements-in-"
        "vectors design is open; it has not been built.",
        "",
        "Two ratios moved on 2026-11-26 because their denominators got faster, not "
        "because their numerators got slower: the drainage film against the paper's wet "
        "model (issue 12) crossed 2x as the paper's wet balance took fewer evaluations "
        "(the drainage film's own rate, 15–20 M element-steps/s, is what it was: it runs "
        "no wet balance), and the tolerance rows' default runs lost about 8 ms of fixed "
        "cost per call (the echo of the scene's numbers), which raised every `ratio to "
        "its default run` on these small scenes (ctm_dry's default run 13.7 ms before, "
        "5.4 ms after).",
        "",
        "On 2026-11-28 (the run after 18f76b4) three rows moved again without their "
        "numerators slowing: the drainage film against the paper's wet model (2.14x to "
        "2.29x) and the Maxwell rubber of 3 arms against Kelvin-Voigt (1.50x to 1.62x), "
        "because the Kelvin-Voigt pad's step was fused into fewer passes (dry and under the "
        "paper's bearing) while the drainage film and the Maxwell rubber keep the general "
        "passes (their own rates the same within the host's noise: 8.6-12.5 M element-steps/s "
        "and 21.9-22.6 ns); and the tolerance rows' runs to 1e-6, 1.48 s and 3.51 s against "
        "1.02 s and 2.60 s the run before, with the same default runs. The build of the "
        "run before (45f5dd1) took as long on this host that hour (the program on "
        "`ctm_dry` to 1e-6: 1.43-1.74 s, today's build 1.38-1.44 s; `ctm_wet`: 5.1 s and "
        "4.8-5.0 s): the host, not the code.",
        "",
        "Later on 2026-11-28 two numerators got faster. The Reynolds film: its wet "
        "balance splits the bracket at the touching points, where the film's load jumps "
        "(a root there took about 50 evaluations, halving the bracket to adjacent "
        "doubles), and the load's derivative is the settled system differentiated "
        "instead of a second solve with every cell term evaluated again: 13.8 "
        "evaluations per position at 80 km/h became 5.9 on the medium surface, and "
        "perf counted 13,517 samples of a Reynolds sweep against 24,128 "
        "(the evaluations: `bearing_evaluations` over the positions of the scene of "
        "tests/test_reynolds.py, \"a root at the film's jump\", which bounds them at 7; "
        "the perf samples by hand, `perf record` on the bench's Reynolds sweep child with "
        "each build; its roots moved where the balance has several, docs/model.md). The "
        "drainage film: the Kelvin-Voigt pad's fused step now runs under it too (its "
        "facets after), and the film's thickness under each element comes out of its "
        "step instead of a call per element; callgrind by hand, `valgrind "
        "--tool=callgrind` on the program's run of 16,384 points at 6 speeds in 1 mm of "
        "water (`min_contacts = 0`, no error estimate): 930 M instructions before, 866 M "
        "after, every number the same to the bit.",
        "",
        "Later still on 2026-11-28 (after 0c0b275), the paper's wet balance took Newton's "
        "steps on the formula of the contacts' piece with a pass over the elements to "
        "check each piece's root (above, \"Wet balance\"), the dry balance under a film "
        "started from the previous dry root, and the Kelvin-Voigt pad's fused step lost "
        "a copy of the state, a sum the energy scheme does not use and the compiler's "
        "aliasing checks; the runs of `tools/profile_kernel.sh --callgrind` (under "
        "valgrind, whose logarithm differs in the last bits from the host's): dry 226 M "
        "instructions before, 208 M after, every number the same to the bit; wet 594 M "
        "before, 527 M after. From the same run on, the sweep times the core and the plain "
        "loop in three alternating rounds and keeps the best of each: before, each was "
        "timed once in a row, and on this shared host the ratio of two times taken a "
        "minute apart could measure the host's drift (the coarse surface's wet ratio "
        "4.61x in the run before, where its wet time equalled the other surfaces' within "
        "5 % when timed by hand)."
        " The Maxwell rubber of 3 arms against Kelvin-Voigt (issue 14) read 1.87x in "
        "this run, 1.32x in the one before: the Kelvin-Voigt pad got faster (its fused "
        "step, above) while the Maxwell rubber runs the general passes, and the host was "
        "slower during this section than during the sweep (Kelvin-Voigt 12.2 ns an "
        "element-step here, 8.2 ns the run before). Timed by hand "
        "(`pavefric.studies.rubber_report.cost` with five repeats, the build of 0c0b275 "
        "twice and of 3b4a5af five times, in turn): Kelvin-Voigt 9.7-15.5 ns before and "
        "8.6-9.7 ns after, the 3 arms 15.2-25.1 ns before and 14.9-16.2 ns after, "
        "1.56-1.62x before and 1.61-1.74x after: on this host that hour the build before "
        "did not meet the target either, and the 1.32x of the run before was a quieter "
        "moment.",
        "",
        "On 2026-11-29 the paper's wet balance took its pieces' roots without a checking "
        "pass where no element's height lies between (above, \"Wet balance\"). Two runs "
        "of this benchmark with that build, an hour apart on this shared host: wet "
        "(`kane2017`) 8.0-9.4x the plain loop and 6.7-8.5x, dry 2.27-2.60x and 2.57-2.81x "
        "(the dry kernel unchanged), the fine surface's wet rate 51.8 and 30.0 M "
        "element-steps/s, the 2 MPI ranks 1.73x and 1.61x, the Maxwell rubber's 3 arms "
        "1.73x and 2.03x, the drainage film 2.26x and 1.85x the paper's bearing. A row that "
        "moves across its target between two runs of the same build measures the host. "
        "The cost model's rates for the paper's bearing were refitted between the two runs "
        "(src/run/pavefric_simulate.f90): estimated / measured on the test scenes 1.00-2.04 "
        "in the first, 0.83-1.52 in the second.",
        "",
        "Later on 2026-11-29 the paper's wet balance took whether its film engages and "
        "its lower bracket from the lanes' sums, and skipped the dry roots where every "
        "speed's film carried load at the previous position (above, \"Wet balance\"): the "
        "wet run of `tools/profile_kernel.sh --callgrind` 497 M instructions before, 434 M "
        "after. The drainage film's step lost an inner loop and the elements out of "
        "contact (the same numbers to the bit; its squeeze run "
        "(`wet_model = 'squeeze'`) 712 M before, 630 M after). From then on the sweep times the core and the plain "
        "loop in five alternating rounds, not three: the same build's fine-surface wet "
        "rate read 52.8 and 30.7 M element-steps/s in two sweeps minutes apart (timed by hand). The run "
        "with the wet balance's changes and not yet the drainage film's: wet (`kane2017`) "
        "8.8-10.5x the plain loop, dry 2.17-2.43x (the dry kernel unchanged, 213 M "
        "instructions), the drainage film 3.05x the paper's bearing, its own rate 14-27 M "
        "element-steps/s as before and its denominator faster. The drainage film's time "
        "over the bearing's, timed by hand side by side in one process (best of five), on the "
        "fine, medium and coarse surfaces: 2.27, 2.02 and 1.91 before its change, 2.32, "
        "1.93 and 1.59 after; on the fine surface `erfc` takes a fifth of its time (perf).",
        "",
        "In the session after (2026-11-29, tenth) the dry kernel lost two costs, each "
        "keeping every number's bits (hashes of 12 dry, 12 wet and 24 squeeze scenes): "
        "the contacts on clamped facets are counted in a pass over the few elements on "
        "one, not summed over every element and lane inside the step's pass, and the "
        "dry balance's warm start is extrapolated from the two previous positions' "
        "roots (most positions already took two passes: the first and the one that "
        "finds its active set repeated). "
        "`tools/profile_kernel.sh --callgrind`: dry 214 M instructions before, 200 M "
        "after; wet 434 M and 422 M; squeeze 630 M and 617 M (the table above is the "
        "run after them). Two more tries were dropped: the dry root's sums two lanes at "
        "a time with the elements inner (fewer instructions, but slower on the medium "
        "and coarse surfaces, timed by hand), and an integrator exact in time under the "
        "paper's film (its load taken linear in time over each part of a step and "
        "solved for at the part's end; the contact events found as on a dry road). On "
        "the default wet scene it came far closer to the converged friction than "
        "backward Euler at one step per sample, but the events it decides from the "
        "interpolated load disagree near a grazing contact (a contact's force and the "
        "same element's gap, each from its own interpolation), and on random scenes it "
        "ran away or settled far from backward Euler's limit; it is not in the code "
        "(its branch was never pushed and is not in this repository: its figures are "
        "a record, not regenerable from it; docs/numerics.md, \"Tried and not kept\", "
        "states its design and what a consistent version needs). In the run above the drainage film "
        "read 3.33x the paper's bearing and the 3-arm Maxwell rubber 2.39x Kelvin-Voigt "
        "(2.29x and 1.76x the run before): timed side by side (`python "
        "tools/compare_builds.py <the build before> <this build>`, best of three rounds "
        "of seven runs; 65,536 points, 4 speeds), this build ran the paper's rubber, the "
        "elastic pad and the 3-arm Maxwell rubber in 0.060, 0.060 and 0.110 s, the "
        "build of 08ab7fc in 0.063, 0.069 and 0.115 s: those rows moved with the "
        "host's load.",
        "",
        "In the session of 2026-12-06 the Reynolds film's tridiagonal systems moved from "
        "LAPACK's `dgtsv` to an elimination of our own that keeps its factors "
        "(`src/base/pavefric_tridiagonal.f90`): the load's derivative is one more solve "
        "with them, where it re-assembled and re-factored the system. Side by side with "
        "the build before (`python tools/compare_builds.py <before> <after> --runs "
        "reynolds_wet paper_wet kelvin_voigt`, best of three rounds of three runs): the "
        "Reynolds film 2.015 s and 1.686 s a run, the paper's wet model 0.073 and 0.074 "
        "s, the dry pad 0.035 s both. What is left of the Reynolds film's time is its "
        "3-6 balance evaluations a position, each at least one factorisation and the "
        "cell terms' transcendental functions; a Newton step that takes the pad's push "
        "whole and one on the logarithm of the film's load were tried: the first saved "
        "about 3 % of the evaluations and the second cost more, and both moved mu by up "
        "to 1 %, because where the film's balance has several roots (docs/model.md) the "
        "root a position takes depends on the iteration's path (measured once with "
        "builds changed so, not a command of the repository). The drainage film's cost "
        "per element-step no longer grows with `substeps` (an attack found a 256-point "
        "profile at substeps 1024 taking 12-26 s, estimated 0.45 s): the film updates a "
        "plateau's road samples as vector runs from each element's first sample, where "
        "the driver rebuilt an index of every sample under the pad each step; the cost "
        "estimate counts that update per sample (`sec_squeeze_sample`). This session's "
        "first run of the benchmark was on an Intel Xeon host that ran the cost "
        "section's scenes in about half their estimate (estimated / measured 1.50-2.73; "
        "the AMD host the rates were fitted on read 0.73-1.65 in its last run): the "
        "estimate is now scaled by 0.71, the middle of the two hosts "
        "(`hosts_scale`, src/run/pavefric_simulate.f90), and the table above is the run "
        "after. A host more than about 1.4 times faster or slower than both reads "
        "outside the factor 2.",
        "",
        "Later the same day (a second session) the Reynolds film's report at each "
        "position's root reads the solution of the balance's last load, kept in the "
        "lane's workspace with its gap field, where it solved the film once more: the "
        "same numbers to the bit, a Reynolds run 2.54 s and 2.23 s side by side with "
        "the build before (`python tools/compare_builds.py <before> <after> --runs "
        "reynolds_wet`, while the test suite ran beside it). A dry balance started from "
        "the previous position's contacts moved with the road was tried and not kept: "
        "slower (docs/numerics.md, \"Tried and not kept\"). With a tolerance, the cost "
        "estimate now guesses the substeps the refinement will reach and the seconds of "
        "all its passes, which the announcement before a run weighs; the rows above "
        "are of runs without a tolerance, whose estimate did not change.",
        "",
        "In the session after (2026-12-06, thirteenth) a dry pad's balance lost two of "
        "its passes over the pad: its first Newton pass is taken in the pass that forms "
        "the clearances (`lane_free_gaps_from`, `lane_gaps_from`: their count and sum "
        "below the extrapolated penetration), which no longer shifts them by their least "
        "value; the balance's later passes and the contacts' pass subtract it as they "
        "read them (`dry_roots_of_c`), the same subtraction, and the root comes from the "
        "confirming pass's sums, so every number of the regression record keeps its "
        "bits. Passes a position for the Kelvin-Voigt pad: 3.18 (the clearances, 1.18 "
        "confirming, the step) where they were 5.18 (the clearances, their shift, 2.18 "
        "of the balance, the step), counted with callgrind on a `-g` build (a command of "
        "this session, not of the repository). Side by side (`python "
        "tools/compare_builds.py <before> <after>`, best of three rounds of seven runs): "
        "the paper's rubber 0.0349 s and 0.0317 s a run, the elastic pad 0.0359 and "
        "0.0331 s, the 3-arm Maxwell rubber 0.0627 and 0.0582 s, the paper's wet model "
        "unchanged (0.074 s). Then the first Newton step is taken as the root without "
        "its confirming pass where no element lies between the guess and it (the first "
        "pass also takes the largest clearance below the guess and the least above) and "
        "its terms are within four times the root, which keeps a tiny compression's "
        "digits: the paper's rubber 0.0332 and 0.0322 s a run, 0.0329 and 0.0312 s in "
        "a second comparison; dry numbers move by rounding (the regression record "
        "regenerated: mu by at most 1.2e-15 of its scale). A variant that measured the "
        "clearances from the previous penetration lost the root's digits at tiny "
        "compressions (docs/numerics.md, \"Tried and not kept\").",
        "",
        "In the session of 2026-12-07 (eighteenth) the Reynolds film's tridiagonal "
        "systems are eliminated without pivoting (they are column diagonally dominant: "
        "partial pivoting swapped no row; tests/test_reynolds.py), its conductances "
        "and side leakage are computed once per evaluation instead of once per "
        "active-set iteration, and its cell terms take one exponential fewer: the "
        "Reynolds film 2.136 s and 1.656 s a run side by side with the build before, "
        "the paper's wet model 0.098 and 0.099 s, the dry pad 0.041 s both (`python "
        "tools/compare_builds.py <before> <after> --runs reynolds_wet paper_wet "
        "kelvin_voigt`). This run of the benchmark is the first on an AMD EPYC host "
        "since 2026-12-06: there the plain loop, a branchy insertion sort and scan, ran "
        "148-169 M element-steps/s where the Intel Xeon host of the run before gave it "
        "88-89 M, while the core ran 170-174 M against 210-221 M, so the dry core's "
        "ratio to it fell from 2.35-2.51x to 1.00-1.18x with no change to either "
        "(the dry kernel's code did not change this session): the dry kernel target is "
        "a ratio to a loop whose speed depends on the host's branch prediction more "
        "than the core's does.",
        "",
        "## Where the time goes",
        "",
        "`tools/profile_kernel.sh` profiles three workloads with `perf` (one thread, no "
        "error-estimate pass, and since 2026-11-28 no refinement of the pad, "
        "`min_contacts = 0`, as the sweep): the benchmark's coarse surface dry and wet (65,536 points, 6 "
        "speeds) and 500 calls on a 64-point profile (the fixed cost of a call); "
        "`tools/profile_kernel.sh --callgrind` counts the instructions of one dry and one "
        "wet run (16,384 points), which the load of a shared host does not move. Measured "
        "on 2026-11-26 before (0fe4299) and after the changes of that day "
        "(`PYTHONPATH=<the other build> tools/profile_kernel.sh` profiles another build). "
        "Shares are of the samples, self time; inlined routines count in their caller.",
        "",
        "| workload | before | after |",
        "|---|---|---|",
        "| dry sweep | 93 ms a run; the core 54 % of the samples: `slide` (gaps, contacts, "
        "the facets' work, inlined) 37 %, the dry Newton passes 13 %, the rubber's memory 3 "
        "%; Python 29 % (importing pavefric once, building the Dataset); 226 M instructions "
        "| 90 ms; the same shares and 226 M instructions (the dry kernel was not changed) |",
        "| wet sweep | 413 ms a run; the core 72 %: the wet balance (contact sums, the "
        "bearing's gap sums, Eq. 15 and its logarithm) 36 %, `slide` 18 %, the dry root 8 %; "
        "714 M instructions, 411 M of them the wet balance | 355 ms; the wet balance 28 %, "
        "`slide` 20 %, the dry root 9 %; 579 M instructions (-19 %), 274 M the wet balance "
        "(-33 %: a quarter fewer evaluations, and the bearing's sums taken in the balance's "
        "own pass) |",
        "| one call, 64 points | 7.9 ms: 63 % in libgfortran and libc formatting numbers "
        "(each echoed parameter written and read back up to 17 times to find its shortest "
        "text, and that 8 times over by length-then-text functions; a range check "
        "formatted its message before knowing of an error) | 2.1 ms: a bisection over the "
        "digits, each text built once, messages only on error; now 59 % Python (the xarray "
        "Dataset) |",
        "",
        "On 2026-11-28 (18f76b4) the Kelvin-Voigt pad's step lost three of its passes: the "
        "rubber's free compression is taken in the gaps' pass (`lane_free_gaps`), and the "
        "contacts, the energy scheme's work and the rubber's update in one pass after the "
        "balance (`lane_step_kv`), dry and under films that carry load; each value by the "
        "same operations, so every number keeps its bits. `valgrind --tool=callgrind` on "
        "the program (one dry run of 16,384 points, 6 speeds, one thread, `min_contacts = "
        "0`, no error estimate, a `-g` build): the core's kernel 235 M instructions before "
        "(`slide` 115 M, the dry Newton passes 58 M, the energy step 50 M, the rubber 11 M), "
        "213 M after (`slide` 155 M with all of them inlined but the Newton passes, 58 M). "
        "The time fell more than the instructions (the sweep's dry rate 59-61 M "
        "element-steps/s before, 69-70 M after, measured with the benchmark's sweep child): "
        "the pass over each array's 138 values is the cost, more than its arithmetic. A "
        "shortcut of the dry root's first pass (stop where no element lies between the "
        "guess and the Newton step) saved no pass often enough to pay for its two extra "
        "reductions: 5 % slower, not kept.",
        "",
        "## What the cost estimate foresees with a probe",
        "",
        "The estimate printed before a run (and recorded as `estimated_seconds`) counts "
        "the passes the scene's numerics fix: the run, and the error estimate's pass at "
        "half the step. Other passes depend on what the run finds: where the pad stands "
        "on fewer than 4 elements in contact on average, the default (`min_contacts = "
        "4`) reruns that speed with the elements halved, up to 4 times, each level "
        "costing about 4 times the one before (twice the elements at twice the "
        "positions), and the error estimate halves them again from there. A water film "
        "that lifts the pad onto a few asperities triggers exactly this. In the first "
        "run of 2026-11-28, before the probe, the cost-estimate section's test scene "
        "\"wet kane2017, fine texture (rms 0.2 mm), 3 speeds\" (20, 50, 80 km/h at 1 mm) "
        "took 4.6 s against 0.62 s estimated (0.14), and \"wet kane2017, 10 speeds, a 40 "
        "mm pad\" at 2 mm 15.2 s against 2.6 s (0.17); the estimate had been within a "
        "factor 2 on every scene of the run of 2026-11-27, made before `min_contacts` "
        "defaulted to 4.",
        "",
        "Since then a probe runs before the estimate (`add_refinement_cost`, "
        "src/run/pavefric_simulate.f90): each speed on every n-th of about 1024 "
        "positions of the profile's first 65,536 samples, one step a position, no "
        "estimate, no refinement. The speeds where it finds the pad on fewer than 4 "
        "elements in contact get their levels costed (assuming the contacts double with "
        "each halving), and the program's estimate line names them (\"4.06 s of it "
        "refining the pad at 50 and 80 km/h\"). In the second run of 2026-11-28 the two "
        "scenes came to 1.06 (4.68 s estimated, 4.43 s measured) and 0.98 (12.05 s, "
        "12.30 s), every test scene within 0.53–1.06 (these two figures are that run's; "
        "the table above is the latest run's). Runs of fewer than 2048 positions are "
        "not probed (the probe would cost more than half a pass) unless all their "
        "levels and the error estimate's pass, or with `&numerics tolerance` all its "
        "passes at every level up to `substeps = 4096`, could take a second or more (the "
        "program announces a run from 1 s); with a tolerance the probe runs too, since "
        "each level `min_contacts` takes runs the tolerance's passes, and the guess of "
        "the tolerance's passes multiplies the levels' first passes. An attack of "
        "2026-12-07 ran a 128-point profile of a 13-arm compound at 300 km/h with "
        "`tolerance = 1e-9` for 104 s without a warning: its estimate was 0.001 s (no "
        "probe: the pad's three levels of refinement unseen), and the tolerance's guess "
        "9 s; it is now guessed at 19.2 s and announced (96 s measured on this host "
        "by running the test's scene by hand, a record, not a command of the "
        "repository; the guess is the estimate `pf_estimate` prints; "
        "tests/test_estimate.py, `test_a_tolerance_on_a_short_stiff_profile_is_announced`). "
        "A first version "
        "probed 256 positions: at 80 km/h the film carried the pad at all but 2 of "
        "them, too few to count its contacts, and it missed that speed. Command: "
        "`python -m pavefric bench --report docs/performance.md --reference "
        "tests/reference.py` (the section \"Cost estimate against the measured time\").",
        "",
        "## Why the NumPy ratio is lower when dry",
        "",
        "The reference (tests/reference.py) is vectorised over the pad's elements and "
        "loops over positions in Python: ~15 µs of interpreter and call overhead "
        "per position whatever N is. At N = 23 it reaches ~1.5 M element-steps/s "
        "dry, so 300x would need ~450 M element-steps/s from one core (about two "
        "CPU cycles per element-step for five passes over the elements); the core "
        "is bound by the serial add chains of its reductions. The wet reference "
        "bisects in Python and the ratio there is well above 300x.",
        "",
    ]
    report.write_text("\n".join(out), encoding="utf-8")
