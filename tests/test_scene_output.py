"""Scene files follow their conventions (issue 10 item 10): zero messages
from the IOOS compliance checker's CF 1.10 suite at its strictest, the speed
in km/h usable with sel, the speed in m/s an auxiliary coordinate (not an
axis), and the plot command works on them."""
import numpy as np
import pytest
import xarray as xr

from conftest import ROOT, run_program, write_scene
from test_batch_output import cf_check


@pytest.fixture(scope="module", params=["ctm_wet", "ctm_squeeze", "series"])
def scene_file(request, tmp_path_factory, profile_m):
    tmp = tmp_path_factory.mktemp("scene")
    if request.param == "series":
        scene = write_scene(tmp, profile=profile_m, groups={
            "water": "depth = 1e-3, wet_model = 'squeeze'", "output": "series = .true."})
    else:
        scene = ROOT / "inputs" / f"{request.param}.nml"
    out = tmp / "o.nc"
    r = run_program(scene, "-o", out)
    assert r.returncode == 0, r.stderr
    return out


def test_scene_file_passes_the_cf_1_10_checker(scene_file, tmp_path):
    scored, possible, msgs = cf_check(scene_file, tmp_path)
    assert msgs == [] and scored == possible, msgs


def test_sel_by_speed_kmh(scene_file):
    with xr.open_dataset(scene_file) as ds:
        assert "speed_kmh" in ds.indexes
        mu = ds["mu"].sel(speed_kmh=ds["speed_kmh"].values[1])
        assert float(mu) == float(ds["mu"].values[1])
        assert "speed" in ds.coords and "axis" not in ds["speed"].attrs
        np.testing.assert_array_equal(ds["speed"].values, ds["speed_kmh"].values * (1 / 3.6))


def test_plot_of_a_scene_file(scene_file, tmp_path):
    import subprocess
    import sys

    png = tmp_path / "p.png"
    r = subprocess.run([sys.executable, "-m", "pavefric", "plot", str(scene_file), "-o", str(png)],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert png.stat().st_size > 5000


def test_a_sweep_of_scene_files_sorts_by_its_typed_parameters(tmp_path, profile_m):
    """Issue 24 asked whether the per-parameter attributes (param_<group>_<name>)
    are needed beside the one namelist text (`parameters`). They are: a
    study over many scene files selects and sorts them by the values they
    ran with, as numbers and strings, and Python has no Fortran-namelist
    reader (pavefric depends on none); the text alone would need one."""
    files = []
    for k, (depth, model) in enumerate([(1e-3, "squeeze"), (0.0, "kane2017"),
                                         (0.5e-3, "kane2017")]):
        scene = write_scene(tmp_path / f"s{k}", profile=profile_m, groups={
            "water": f"depth = {depth}, wet_model = '{model}'"})
        out = tmp_path / f"s{k}.nc"
        assert run_program(scene, "-o", out).returncode == 0
        files.append(out)
    runs = []
    for f in files:
        with xr.open_dataset(f) as ds:
            runs.append((ds.attrs["param_water_depth"], ds.attrs["param_water_wet_model"],
                         float(ds["mu"].values[0]), ds.attrs["parameters"]))
    # typed: a float and a string, as given, with no parsing
    assert [type(r[0]) for r in runs] == [np.float64] * 3
    ordered = sorted(runs)
    assert [r[0] for r in ordered] == [0.0, 0.5e-3, 1e-3]
    assert [r[1] for r in ordered] == ["kane2017", "kane2017", "squeeze"]
    # the same values are in the namelist text, but only as text
    assert all("depth = " in r[3] for r in runs)
    # dry friction above wet, read off the sorted runs
    assert ordered[0][2] > ordered[1][2]


def test_a_copy_of_a_scene_file_opens_for_writing(scene_file, tmp_path):
    """docs/outputs.md: netCDF-C 4.9 opens pavefric's files (built in memory
    by nc_create_mem, whose root group has no link creation order) for
    reading only; a copy written by xarray opens for writing, with every
    value and attribute kept. Should netCDF-C lift the limit, the first
    assertion fails and the docs' paragraph goes."""
    import netCDF4

    with pytest.raises(OSError, match="Can't write file"):
        netCDF4.Dataset(scene_file, "a").close()
    copy = tmp_path / "annotated.nc"
    with xr.open_dataset(scene_file) as ds:
        ds.to_netcdf(copy)
    with netCDF4.Dataset(copy, "a") as nc:
        nc.setncattr("site", "A1 northbound, km 12.4")
    with xr.open_dataset(scene_file) as a, xr.open_dataset(copy) as b:
        assert b.attrs["site"] == "A1 northbound, km 12.4"
        assert {k: v for k, v in b.attrs.items() if k != "site"}.keys() == a.attrs.keys()
        for name in a.variables:
            np.testing.assert_array_equal(a[name].values, b[name].values)


def test_the_typed_parameters_are_those_of_the_parameters_text(scene_file):
    """param_<group>_<name> holds the groups `parameters` holds: a scene's
    file leaves &batch out of both (it listed param_batch_* defaults beside
    a text without &batch), and every variable of the text has its typed
    attribute (lists too, as Python's dataset has them)."""
    import re

    with xr.open_dataset(scene_file) as ds:
        text = ds.attrs["parameters"]
        groups = set(re.findall(r"^&(\w+)$", text, flags=re.M))
        typed = [k for k in ds.attrs if k.startswith("param_")]
    assert "batch" not in groups and "rubber" in groups
    assert {k.split("_")[1] for k in typed} == groups
    current = None
    names = set()
    for line in text.splitlines():
        if line.startswith("&"):
            current = line[1:]
        elif " = " in line and current:
            names.add(f"param_{current}_{line.split(' = ')[0].strip()}")
    assert names == set(typed)
