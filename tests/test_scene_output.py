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
