"""Accuracy on demand (&numerics tolerance, issue 13): the time step is refined
until the estimated error meets the tolerance, and on the reference surfaces
the reported error bounds the actual error (against a much finer step)."""
import numpy as np
import pytest
import xarray as xr

import pavefric
from conftest import ROOT, run_program, write_scene

SURFACES = ["GSP", "GSS", "GSSB", "RSBA", "MCA", "VTAC"]


@pytest.mark.parametrize("name", SURFACES)
@pytest.mark.parametrize("depth", [0.0, 1e-3])
def test_reported_error_bounds_the_actual_error(name, depth):
    scene = pavefric.load_scene(ROOT / "inputs" / "surfaces" / f"{name}.nml")
    speeds = [20.0, 60.0]
    reference = scene.simulate(speeds_kmh=speeds, depth=depth, substeps=1024)["mu"].values
    for tol in (1e-2, 1e-3):
        ds = scene.simulate(speeds_kmh=speeds, depth=depth, tolerance=tol)
        estimate = ds["mu_error_estimate"].values
        actual = np.abs(ds["mu"].values - reference)
        assert np.all(estimate <= tol), (tol, estimate)
        assert np.all(actual <= estimate), (name, depth, tol, actual, estimate)
        used = ds["substeps_used"].values
        # the result is the run at the substeps reported
        again = scene.simulate(speeds_kmh=speeds, depth=depth, substeps=int(used.max()))
        j = int(np.argmax(used))
        assert ds["mu"].values[j] == again["mu"].values[j]


def test_a_tighter_tolerance_costs_more_and_errs_less(profile_m):
    loose = pavefric.simulate(profile_m, 0.87e-3, [40.0], viscosity=3e3, tolerance=1e-2)
    tight = pavefric.simulate(profile_m, 0.87e-3, [40.0], viscosity=3e3, tolerance=1e-4)
    assert tight["substeps_used"].values[0] > loose["substeps_used"].values[0]
    assert tight["mu_error_estimate"].values[0] < loose["mu_error_estimate"].values[0]


def test_no_tolerance_no_estimate(profile_m):
    ds = pavefric.simulate(profile_m, 0.87e-3, [40.0])
    assert "mu_error_estimate" not in ds and "substeps_used" not in ds


def test_program_records_the_estimate_and_series_share_positions(tmp_path, profile_m):
    scene = write_scene(tmp_path, profile=profile_m, groups={
        "numerics": "tolerance = 1e-3", "output": "series = .true.",
        "operation": "speeds_kmh = 10, 60"})
    out = tmp_path / "o.nc"
    r = run_program(scene, "-o", out)
    assert r.returncode == 0, r.stderr
    with xr.open_dataset(out) as ds:
        assert np.all(ds["mu_error_estimate"].values <= 1e-3)
        assert ds["substeps_used"].values[0] == ds["substeps_used"].values[1]   # series: together
        assert ds["mu_inst"].shape == (2, ds.sizes["position"])
        np.testing.assert_allclose(ds["mu_inst"].mean("position").values, ds["mu"].values,
                                   rtol=1e-12)
        assert ds.attrs["param_numerics_tolerance"] == 1e-3
        # Python sizes its series before the run, for the scene's substeps: a
        # tolerance run with more positions still returns them, the same
        from test_boundaries import assert_same_bits
        assert_same_bits(ds.load(), pavefric.load_scene(scene).simulate(), "tolerance series")


def test_an_unreachable_tolerance_warns(profile_m):
    with pytest.warns(pavefric.PavefricWarning, match="tolerance = 1e-12: not met"):
        ds = pavefric.simulate(profile_m[:300], 0.87e-3, [40.0], viscosity=3e3, tolerance=1e-12,
                               closed=False)
    assert ds["substeps_used"].values[0] == 4096
