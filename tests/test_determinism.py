"""Determinism on one machine, bit for bit (docs/numerics.md, "What is
promised bit for bit"): the same scene gives the same bits run twice, on 1
or N threads, from a fresh process; the other parts of the promise (MPI
ranks, program = Python = C API, restart) are tested where those interfaces
are (the table in docs/numerics.md names each test).

Across machines the promise is a tolerance, not bits (tests/test_regression.py).
"""
import os
import subprocess
import sys

import numpy as np
import pytest
import xarray as xr

import pavefric
from conftest import program, write_scene

# every model path: the paper's bearing, the drainage film, a Maxwell rubber
# with temperature, a viscous pad on substeps, the tolerance loop
SCENES = {
    "kane2017_series": {"water": "depth = 1e-3, alpha = 1.0",
                        "operation": "speeds_kmh = 5, 20, 40, 60, 80",
                        "output": "series = .true."},
    "squeeze": {"water": "depth = 1e-3, wet_model = 'squeeze'",
                "operation": "speeds_kmh = 10, 30, 60, 90", "output": "series = .true."},
    "maxwell": {"rubber": "model = 'maxwell', stiffness = 1.4e8, "
                          "prony_stiffness = 1e8, 5e7, prony_times = 1e-4, 1e-2, "
                          "temperature = 10.0",
                "water": "depth = 1e-3, alpha = 1.0",
                "operation": "speeds_kmh = 5, 40, 80"},
    "tolerance": {"rubber": "stiffness = 1.4e8, viscosity = 3e3",
                  "water": "depth = 1e-3",
                  "numerics": "tolerance = 1e-3",
                  "operation": "speeds_kmh = 20, 60"},
}


def numeric_variables(ds: xr.Dataset) -> dict:
    return {name: ds[name].values for name in ds.variables if ds[name].dtype.kind in "fiu"}


def assert_same_bits(a: dict, b: dict, where: str):
    assert set(a) == set(b), where
    for name in a:
        x, y = np.ascontiguousarray(a[name]), np.ascontiguousarray(b[name])
        assert x.shape == y.shape and x.tobytes() == y.tobytes(), f"{where}: {name} differs"


def run(scene, out, threads="1"):
    r = subprocess.run([program(), str(scene), "-o", str(out)], capture_output=True, text=True,
                       env={**os.environ, "OMP_NUM_THREADS": threads}, timeout=600)
    assert r.returncode == 0, r.stderr
    with xr.open_dataset(out) as ds:
        return numeric_variables(ds.load())


@pytest.mark.parametrize("name", sorted(SCENES))
def test_program_twice_and_on_two_threads_gives_the_same_bits(tmp_path, profile_m, name):
    scene = write_scene(tmp_path, profile=profile_m, groups=SCENES[name])
    first = run(scene, tmp_path / "a.nc")
    assert_same_bits(first, run(scene, tmp_path / "b.nc"), f"{name}: run twice")
    assert_same_bits(first, run(scene, tmp_path / "c.nc", threads="2"), f"{name}: 2 threads")


def test_python_twice_and_in_a_fresh_process_gives_the_same_bits(tmp_path, profile_m):
    kw = dict(depth=1e-3, alpha=1.0, series=True)
    a = numeric_variables(pavefric.simulate(profile_m, 0.87e-3, [10.0, 60.0], **kw))
    b = numeric_variables(pavefric.simulate(profile_m, 0.87e-3, [10.0, 60.0], **kw))
    assert_same_bits(a, b, "simulate twice")
    # a fresh interpreter (nothing cached, another heap layout)
    np.save(tmp_path / "z.npy", profile_m)
    code = ("import numpy as np, pavefric, sys\n"
            f"z = np.load({str(tmp_path / 'z.npy')!r})\n"
            "ds = pavefric.simulate(z, 0.87e-3, [10.0, 60.0], depth=1e-3, alpha=1.0, "
            "series=True)\n"
            f"ds.to_netcdf({str(tmp_path / 'fresh.nc')!r})\n")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    with xr.open_dataset(tmp_path / "fresh.nc") as ds:
        c = numeric_variables(ds.load())
    assert_same_bits({k: a[k] for k in c}, c, "fresh process")


def test_the_bitwise_check_sees_one_changed_bit():
    x = {"mu": np.array([0.5, 0.25])}
    y = {"mu": np.array([0.5, np.nextafter(0.25, 1.0)])}
    assert_same_bits(x, {"mu": x["mu"].copy()}, "same")
    with pytest.raises(AssertionError, match="mu differs"):
        assert_same_bits(x, y, "one bit")
