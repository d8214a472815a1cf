"""Record every number pavefric gives on its own scenes and on a set of
synthetic cases, bit for bit, so later changes can be checked against them
(tests/test_regression.py).

    python tests/make_regression.py tests/data/regression_record.json

Two records:
- tests/data/regression_0.1.0.json: pavefric 0.1.0, recorded once on the code
  before the components/parameters refactor (issue 11) and the wet models
  (issue 12). Every output still equals it bit for bit, dry and wet.
- tests/data/regression_record.json: this code, on every scene in inputs/
  (the new models' too), bit for bit.
Not to be regenerated casually: a changed number is a changed model. Values
are stored as float.hex() (exact); large arrays as the SHA-256 of their
little-endian float64 bytes plus a few values for diagnosis.
"""
from __future__ import annotations

import hashlib
import json
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]

# the variables every scene output has (attributes are compared separately)
SCENE_VARS = ["speed", "speed_kmh", "mu", "n_clamped", "hydroplaning_fraction", "wet_fraction",
              "max_balance_residual", "mean_hydro_load", "max_compression",
              "bearing_evaluations", "memory_updates", "viscous_memory_ran", "bearing_ran",
              "mpd", "rms_height", "rms_slope", "position", "mu_inst", "hydro_load",
              "penetration", "contact_elements",
              # written since 0.1.0
              "squeeze_film_ran", "mean_local_friction", "mean_film_thickness",
              "film_thickness", "local_friction", "mu_error_estimate", "substeps_used"]
BATCH_VARS = ["depth", "speed", "speed_kmh", "mu", "wet_fraction", "hydroplaning_fraction",
              "max_balance_residual", "n_clamped", "mpd", "rms_height", "rms_slope", "status"]
NUMERIC_ATTRS = ["pad_elements", "averaged_positions", "spinup_positions", "profile_points",
                 "profile_dx"]


def encode(values) -> dict:
    a = np.asarray(values)
    if a.dtype.kind == "f":
        a64 = np.ascontiguousarray(a, dtype="<f8")
        if a64.size <= 64:
            return {"hex": [float(v).hex() for v in a64.ravel()], "shape": list(a.shape)}
        return {"sha256": hashlib.sha256(a64.tobytes()).hexdigest(), "shape": list(a.shape),
                "first": [float(v).hex() for v in a64.ravel()[:4]]}
    a64 = np.ascontiguousarray(a, dtype="<i8")
    if a64.size <= 64:
        return {"int": [int(v) for v in a64.ravel()], "shape": list(a.shape)}
    return {"sha256": hashlib.sha256(a64.tobytes()).hexdigest(), "shape": list(a.shape),
            "first": [int(v) for v in a64.ravel()[:4]]}


def record_dataset(ds, names) -> dict:
    out = {}
    for name in names:
        if name in ds.variables:
            out[name] = encode(ds[name].values)
    for name in NUMERIC_ATTRS:
        if name in ds.attrs:
            out["@" + name] = encode(np.atleast_1d(ds.attrs[name]))
    return out


def synthetic_cases():
    """(name, heights, dx, speeds, keywords) of the simulate cases."""
    from pavefric.surfaces import spectral_profile

    dx = 0.87e-3
    z = spectral_profile(1024, dx, rms=0.5e-3, skew=-0.3, seed=7)
    z_short = spectral_profile(300, dx, rms=0.6e-3, seed=11)
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
        # since 0.1.0 (regression_record.json only)
        ("squeeze_series", z, dx, [0.0, 20.0, 80.0],
         dict(depth=1e-3, wet_model="squeeze", series=True)),
        ("maxwell_wet", z, dx, [5.0, 40.0, 80.0],
         dict(rubber_model="maxwell", prony_stiffness=[1e8, 5e7], prony_times=[1e-4, 1e-2],
              temperature=10.0, depth=1e-3)),
        ("tolerance", z, dx, [20.0, 60.0], dict(tolerance=1e-3, depth=1e-3)),
    ]


def main(path: str) -> None:
    import xarray as xr

    import pavefric

    exe = Path(sys.executable).parent / "pavefric"
    record: dict = {"version": pavefric.__version__, "scenes": {}, "simulate": {}}
    scenes = sorted((ROOT / "inputs").glob("*.nml")) + sorted((ROOT / "inputs").glob("*/*.nml"))
    with tempfile.TemporaryDirectory() as tmp:
        for scene in scenes:
            if scene.parent.name == "rubber":
                continue                  # &rubber groups to include, not scenes
            rel = str(scene.relative_to(ROOT))
            out = Path(tmp) / (scene.stem + ".nc")
            r = subprocess.run([str(exe), str(scene), "-o", str(out)], capture_output=True,
                               text=True, cwd=ROOT)
            if r.returncode != 0:
                raise SystemExit(f"{rel}: {r.stderr}")
            with xr.open_dataset(out) as ds:
                batch = "profile" in ds.dims
                if "water_depth" in ds.variables:     # recorded under 0.1.0's name
                    ds = ds.rename({"water_depth": "depth"})
                record["scenes"][rel] = record_dataset(ds, BATCH_VARS if batch else SCENE_VARS)
            print("recorded", rel)
    for name, z, dx, speeds, kw in synthetic_cases():
        kw = dict(kw)
        closed = kw.pop("closed", True)
        series = kw.pop("series", False)
        ds = pavefric.simulate(z, dx, speeds, closed=closed, series=series, **kw)
        if series:
            ds = ds.transpose(..., "speed_kmh")   # (position, speed), as the file has it
        record["simulate"][name] = record_dataset(ds, SCENE_VARS)
        print("recorded simulate", name)
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    Path(path).write_text(json.dumps(record, indent=1, sort_keys=True) + "\n")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else
         str(ROOT / "tests" / "data" / "regression_record.json"))
