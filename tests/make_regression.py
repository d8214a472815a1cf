"""Regression records: every number pavefric gives on its own scenes and on
a set of synthetic cases, kept so that later changes are checked against
them (tests/test_regression.py) within stated tolerances.

    python tests/make_regression.py          # rewrites tests/data/regression/record.json

Regenerate only when the physics changes on purpose, and say in the commit
what changed and by how much (`python tests/make_regression.py --diff`
prints the largest relative change of every variable against the current
record before writing nothing).

Inputs are files in the repository: the scenes of inputs/ and, for the
`simulate` cases, the profiles in tests/data/regression/ (written once from
pavefric.surfaces.spectral_profile and kept, so no record depends on how
NumPy rounds sin, exp or the FFT on the machine at hand). The record names
the commit and the command that made it.

Two records:
- tests/data/regression/record.json: this code (all values, full arrays);
- tests/data/regression_0.1.0.json: pavefric 0.1.0 (values as float.hex,
  large arrays as a SHA-256 and their first four values); kept as a check
  that the paper's model has not drifted since the first release, compared
  with the same tolerances on the values it holds.

How close is close enough (what the tests apply, `tolerance_of`):
- floating-point outputs: relative 1e-9 of each value plus 1e-12 of the
  largest magnitude in the same variable (values that cross zero); the same
  algorithm on another CPU or C library differs by rounding only (even the
  independent NumPy reference, another algorithm, agrees with the core to
  about 1e-15 on mean friction: tests/test_reference.py), a change of the
  model by far more (the dashpot term scaled by 1.001 moves mu by ~4e-8 and
  fails 51 records; docs/numerics.md);
- diagnostics of the numerics, which rounding may move by more than their
  size: `max_balance_residual` (a rounding-level residual of the balance,
  |sum F + Wh - W| / W) must not exceed twice the recorded one or 1e-13;
  `bearing_evaluations` (iterations of the bracketed wet balance) within 2 %;
- counts of discrete events (contacts, clamped facets, statuses, substeps):
  exact.
"""
from __future__ import annotations

import argparse
import datetime
import json
import platform
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "tests" / "data" / "regression"
RECORD = DATA / "record.json"
RECORD_010 = ROOT / "tests" / "data" / "regression_0.1.0.json"
COMMAND = "python tests/make_regression.py"

# the variables every scene output has (attributes are compared separately)
SCENE_VARS = ["speed", "speed_kmh", "mu", "n_clamped", "hydroplaning_fraction", "wet_fraction",
              "max_balance_residual", "mean_hydro_load", "max_compression",
              "bearing_evaluations", "memory_updates", "viscous_memory_ran", "bearing_ran",
              "mpd", "rms_height", "rms_slope", "position", "mu_inst", "hydro_load",
              "penetration", "contact_elements",
              # written since 0.1.0
              "squeeze_film_ran", "mean_local_friction", "mean_film_thickness",
              "film_thickness", "local_friction", "mu_error_estimate", "substeps_used",
              "mu_hysteresis", "mu_adhesion", "mu_extrapolated", "estimate_elements_per_sample"]
BATCH_VARS = ["depth", "speed", "speed_kmh", "mu", "wet_fraction", "hydroplaning_fraction",
              "max_balance_residual", "n_clamped", "mpd", "rms_height", "rms_slope", "status",
              "mu_hysteresis", "mu_adhesion"]
# 0.1.0 computed the paper's scheme on the profile's own spacing, one
# element a sample; the same settings now reproduce it
# (tests/test_regression.py's 0.1.0 comparisons)
PAPER = {"numerics": [("friction_scheme", "'paper'"), ("min_contacts", "0")],
         "pad": [("element_length", "0.0")]}
# ... and the bearing's alpha calibrated then (the default and the scenes'
# value until it was refitted in 2026-11-26 to 12.0, docs/validation.md)
PAPER_ALPHA = "11.8"
NUMERIC_ATTRS = ["pad_elements", "averaged_positions", "spinup_positions", "profile_points",
                 "profile_dx"]

RTOL = 1e-9            # of each value
SCALE_RTOL = 1e-12     # of the largest magnitude of the variable
EVALUATIONS_RTOL = 0.02
RESIDUAL_FLOOR = 1e-13


def read_heights(name: str) -> np.ndarray:
    """A regression input profile (heights in m, one per line, '#' comments,
    one header line), read with Python's correctly rounded float()."""
    lines = (DATA / name).read_text(encoding="utf-8").splitlines()
    return np.array([float(s) for s in lines if s and not s.startswith("#") and s != "height_m"])


def synthetic_cases():
    """(name, heights, dx, speeds, keywords) of the simulate cases."""
    dx = 0.87e-3
    z = read_heights("synthetic_1024.txt")
    z_short = read_heights("synthetic_300.txt")
    speeds = [0.0, 1.0, 3.0, 7.0, 20.0, 21.0, 60.0, 80.0]
    return [
        ("dry", z, dx, speeds, dict(mu_loc=0.6)),
        ("wet", z, dx, speeds, dict(mu_loc=0.6, depth=1e-3)),
        ("wet_alpha1_series", z, dx, [20.0, 60.0], dict(depth=1e-3, alpha=1.0, series=True)),
        ("elastic_dry_series", z, dx, [20.0], dict(viscosity=0.0, series=True)),
        ("viscous", z, dx, [5.0, 40.0], dict(viscosity=3e3, depth=0.5e-3, alpha=1.0)),
        ("substeps4", z, dx, [40.0], dict(viscosity=3e3, substeps=4)),
        ("eps3", z, dx, [40.0], dict(viscosity=3e3, elements_per_sample=3, depth=1e-3)),
        ("stride5", z, dx, [40.0], dict(position_stride=5, depth=1e-3)),
        ("open", z_short, dx, [10.0, 50.0], dict(closed=False, depth=1e-3, series=True)),
        ("rounded", z, dx, [30.0], dict(shape="rounded", radius=0.03, depth=1e-3)),
        ("loose_tolerance", z, dx, [60.0], dict(depth=1e-3, wet_tolerance=1e-6)),
        ("steep", z * 8, dx, [20.0, 60.0], dict(theta_max_deg=60.0, depth=2e-3)),
        # since 0.1.0 (record.json only)
        ("squeeze_series", z, dx, [0.0, 20.0, 80.0],
         dict(depth=1e-3, wet_model="squeeze", series=True)),
        ("maxwell_wet", z, dx, [5.0, 40.0, 80.0],
         dict(rubber_model="maxwell", prony_stiffness=[1e8, 5e7], prony_times=[1e-4, 1e-2],
              temperature=10.0, depth=1e-3)),
        ("tolerance", z, dx, [20.0, 60.0], dict(tolerance=1e-3, depth=1e-3)),
    ]


# --- values in and out of the record -----------------------------------------

def encode(values) -> dict:
    """A variable as the record keeps it: shape and every value (floats as
    JSON numbers, which read back to the same double)."""
    a = np.asarray(values)
    kind = "float" if a.dtype.kind == "f" else "int"
    flat = a.astype(float if kind == "float" else np.int64).ravel().tolist()
    return {"shape": list(a.shape), kind: flat}


def decode(entry: dict):
    """(kind, values or None, shape) of a record entry, either format: this
    record's full values, or 0.1.0's hex / SHA-256 with its first values
    (then only those are compared)."""
    shape = tuple(entry["shape"])
    if "float" in entry:
        return "float", np.array(entry["float"], dtype=float).reshape(shape), shape
    if "int" in entry:
        return "int", np.array(entry["int"], dtype=np.int64).reshape(shape), shape
    if "hex" in entry:
        return "float", np.array([float.fromhex(h) for h in entry["hex"]]).reshape(shape), shape
    first = entry["first"]
    if first and isinstance(first[0], str):
        return "float", np.array([float.fromhex(h) for h in first]), shape
    return "int", np.array(first, dtype=np.int64), shape


def record_dataset(ds, names) -> dict:
    out = {}
    for name in names:
        if name in ds.variables:
            out[name] = encode(ds[name].values)
    for name in NUMERIC_ATTRS:
        if name in ds.attrs:
            out["@" + name] = encode(np.atleast_1d(ds.attrs[name]))
    return out


def mismatch(name: str, got, entry: dict) -> str | None:
    """Why `got` does not agree with the recorded entry, or None if it does
    (the tolerances of the module docstring)."""
    kind, want, shape = decode(entry)
    got = np.asarray(got)
    if tuple(got.shape) != shape:
        return f"shape {got.shape} != recorded {shape}"
    got, want = got.ravel()[: want.size], want.ravel()
    if kind == "int" or got.dtype.kind in "iub":
        if name == "bearing_evaluations":
            bad = np.abs(got - want) > EVALUATIONS_RTOL * np.abs(want)
        else:
            bad = got != want
    elif name == "max_balance_residual":
        bad = ~(got <= np.maximum(2.0 * want, RESIDUAL_FLOOR))
    else:
        # NaN where the record has NaN (a failed profile's row), and only there
        scale = np.nanmax(np.abs(want)) if np.isfinite(want).any() else 0.0
        both_nan = np.isnan(got) & np.isnan(want)
        bad = ~((np.abs(got - want) <= RTOL * np.abs(want) + SCALE_RTOL * scale) | both_nan)
    if not bad.any():
        return None
    k = int(np.argmax(bad))
    return (f"{int(bad.sum())} of {want.size} values differ; first at flat index {k}: "
            f"{got[k]!r} != recorded {want[k]!r}")


def largest_change(got, entry: dict) -> float:
    """max |got - want| / max |want| (for --diff)."""
    _, want, _ = decode(entry)
    want = np.asarray(want, dtype=float).ravel()
    got = np.asarray(got, dtype=float).ravel()
    if got.size != want.size:
        return float("inf")                 # the shape changed
    scale = max(float(np.max(np.abs(want))) if want.size else 0.0, 1e-300)
    return float(np.max(np.abs(got - want))) / scale if want.size else 0.0


# --- making the record --------------------------------------------------------

def scene_paths() -> list[Path]:
    return [p for p in sorted((ROOT / "inputs").glob("*.nml")) +
            sorted((ROOT / "inputs").glob("*/*.nml")) if p.parent.name != "rubber"]


def paper_scene(scene: Path, directory: Path) -> Path:
    """A copy of `scene` in `directory` that runs the paper's discretisation
    (PAPER), its file names made absolute so that it reads the same files."""
    import re

    text = scene.read_text(encoding="utf-8")

    def absolute(m):
        value = m.group(3)
        if value and not Path(value).is_absolute():
            value = str((scene.parent / value).resolve())
        return f"{m.group(1)}{m.group(2)}{value}{m.group(2)}"

    text = re.sub(r"(\b(?:profile_file|profiles|profile_list)\s*=\s*)(['\"])(.*?)\2", absolute,
                  text)
    if re.search(r"^\s*alpha\s*=", text, re.M):
        text = re.sub(r"^(\s*alpha\s*=\s*)[-+0-9.eEdD]+", rf"\g<1>{PAPER_ALPHA}", text,
                      flags=re.M)
    elif re.search(r"^\s*&water\b", text, re.M | re.I):
        text = re.sub(r"^(\s*&water\b[^\n]*)$", rf"\1\n  alpha = {PAPER_ALPHA}", text,
                      count=1, flags=re.M | re.I)
    for group, settings in PAPER.items():
        lines = "".join(f"\n  {name} = {value}" for name, value in settings)
        pattern = re.compile(rf"^(\s*&{group}\b[^\n]*)$", re.M | re.I)
        if pattern.search(text):
            text = pattern.sub(lambda m: f"{m.group(1)}{lines}", text, count=1)
        else:
            text += f"\n&{group}{lines}\n/\n"
    copy = directory / scene.name
    copy.write_text(text, encoding="utf-8")
    return copy


def run_scene(scene: Path, exe: str, paper: bool = False) -> dict:
    """The record of one scene through the program (batch files under
    0.1.0's name of the water depth, `depth`); `paper`: with PAPER's
    settings."""
    import xarray as xr

    with tempfile.TemporaryDirectory() as tmp:
        if paper:
            scene = paper_scene(scene, Path(tmp))
        out = Path(tmp) / (scene.stem + ".nc")
        r = subprocess.run([exe, str(scene), "-o", str(out)], capture_output=True, text=True,
                           cwd=ROOT)
        if r.returncode != 0:
            raise RuntimeError(f"{scene}: {r.stderr}")
        with xr.open_dataset(out) as ds:
            batch = "profile" in ds.dims
            if "water_depth" in ds.variables:
                ds = ds.rename({"water_depth": "depth"})
            return record_dataset(ds, BATCH_VARS if batch else SCENE_VARS)


def run_case(case, paper: bool = False) -> dict:
    """The record of one simulate case (`paper`: with PAPER's settings)."""
    import warnings

    import pavefric

    name, z, dx, speeds, kw = case
    kw = dict(kw)
    if paper:
        kw.update(friction_scheme="paper", element_length=0.0, min_contacts=0)
        if kw.get("depth", 0.0) > 0.0:
            kw.setdefault("alpha", float(PAPER_ALPHA))
    closed = kw.pop("closed", True)
    series = kw.pop("series", False)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", pavefric.PavefricWarning)
        ds = pavefric.simulate(z, dx, speeds, closed=closed, series=series, **kw)
    if series:
        ds = ds.transpose(..., "speed_kmh")   # (position, speed), as the file has it
    return record_dataset(ds, SCENE_VARS)


def program() -> str:
    return str(Path(sys.executable).parent / "pavefric")


def make() -> dict:
    exe = program()
    out: dict = {"scenes": {}, "simulate": {}}
    for scene in scene_paths():
        out["scenes"][str(scene.relative_to(ROOT))] = run_scene(scene, exe)
        print("recorded", scene.relative_to(ROOT), file=sys.stderr)
    for case in synthetic_cases():
        out["simulate"][case[0]] = run_case(case)
        print("recorded simulate", case[0], file=sys.stderr)
    return out


def meta() -> dict:
    import pavefric

    def git(*args):
        r = subprocess.run(["git", *args], capture_output=True, text=True, cwd=ROOT)
        return r.stdout.strip() if r.returncode == 0 else "unknown"

    dirty = git("status", "--porcelain", "--untracked-files=no")
    return {"commit": git("rev-parse", "HEAD") + (" (with uncommitted changes)" if dirty else ""),
            "command": COMMAND, "date": datetime.date.today().isoformat(),
            "pavefric": pavefric.__version__, "machine": platform.machine(),
            "numpy": np.__version__,
            "tolerance": {"rtol": RTOL, "scale_rtol": SCALE_RTOL,
                          "bearing_evaluations_rtol": EVALUATIONS_RTOL,
                          "max_balance_residual": "<= max(2 x recorded, 1e-13)",
                          "counts": "exact"}}


def dumps(record: dict) -> str:
    """The record as JSON, one line per variable (readable diffs)."""
    lines = ["{", f' "meta": {json.dumps(record["meta"], sort_keys=True)},']
    kinds = ["scenes", "simulate"]
    for i, kind in enumerate(kinds):
        lines.append(f" {json.dumps(kind)}: {{")
        cases = sorted(record[kind])
        for j, case in enumerate(cases):
            lines.append(f"  {json.dumps(case)}: {{")
            names = sorted(record[kind][case])
            for k, name in enumerate(names):
                comma = "," if k < len(names) - 1 else ""
                lines.append(f"   {json.dumps(name)}: "
                             f"{json.dumps(record[kind][case][name], sort_keys=True)}{comma}")
            lines.append("  }" + ("," if j < len(cases) - 1 else ""))
        lines.append(" }" + ("," if i < len(kinds) - 1 else ""))
    lines.append("}")
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--diff", action="store_true",
                    help="print the largest relative change of each variable against the "
                         "current record and write nothing")
    ap.add_argument("-o", "--output", default=str(RECORD), help="record to write")
    args = ap.parse_args(argv)
    new = make()
    if args.diff:
        old = json.loads(RECORD.read_text())
        for kind in ("scenes", "simulate"):
            for case, values in new[kind].items():
                for name, entry in values.items():
                    want = old[kind].get(case, {}).get(name)
                    if want is None:
                        print(f"{kind}/{case}/{name}: new")
                        continue
                    ch = largest_change(decode(entry)[1], want)
                    if ch == float("inf"):
                        print(f"{kind}/{case}/{name}: shape changed")
                    elif ch > 0:
                        print(f"{kind}/{case}/{name}: largest change {ch:.3g} of its scale")
        return 0
    record = {"meta": meta(), **new}
    Path(args.output).parent.mkdir(parents=True, exist_ok=True)
    Path(args.output).write_text(dumps(record))
    print("wrote", args.output, file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
