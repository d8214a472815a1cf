"""Only the effects a scene calls for run; skipping one gives the same
numbers as running it with its neutral value, and does no work (counted)."""
import numpy as np
import pytest
import xarray as xr

import pavefric
from conftest import run_program, write_scene

DX = 0.87e-3
SPEEDS = [0.0, 10.0, 40.0, 80.0]


def test_dry_scene_never_evaluates_the_bearing(profile_m):
    dry = pavefric.simulate(profile_m, DX, SPEEDS)
    assert np.all(dry["bearing_evaluations"].values == 0)
    assert not dry["bearing_ran"].values.any()
    assert "hydrodynamic_bearing" not in dry.attrs["effects"]
    # the same scene with the bearing running at its neutral value (alpha = 0
    # makes Eq. 15 carry nothing): the same numbers, but real work done (the
    # wet balance starts from the dry root, where f = 0, at every position:
    # it is warm-started only after a position where the film carried load).
    # To rounding, not to the bit: a dry pad's balance may take its first
    # Newton step as the root without the pass that confirms it (where no
    # element lies between the guess and the step), the dry root under a
    # film always takes that pass, and the two formulas round differently.
    neutral = pavefric.simulate(profile_m, DX, SPEEDS, depth=1e-3, alpha=0.0)
    np.testing.assert_allclose(neutral["mu"].values, dry["mu"].values, rtol=1e-14, atol=0)
    assert np.all(neutral["mean_hydro_load"].values == 0.0)
    assert np.all(neutral["bearing_evaluations"].values[1:] > 0)
    assert "hydrodynamic_bearing" in neutral.attrs["effects"]


def test_elastic_scene_keeps_no_viscous_memory(profile_m):
    elastic = pavefric.simulate(profile_m, DX, SPEEDS, viscosity=0.0)
    assert np.all(elastic["memory_updates"].values == 0)
    assert "viscous_memory" not in elastic.attrs["effects"]
    # memory running with a neutral viscosity (relaxes to nothing in a step)
    neutral = pavefric.simulate(profile_m, DX, SPEEDS, viscosity=1e-300)
    # the same adhesion bit for bit; the rubber's part is exactly 0 for the
    # elastic scene (nothing dissipates) and the rounding of the facets' work
    # round the circle (~1e-19) for the one that keeps memory
    assert np.array_equal(neutral["mu_adhesion"].values, elastic["mu_adhesion"].values)
    assert np.all(elastic["mu_hysteresis"].values == 0.0)
    np.testing.assert_allclose(neutral["mu"].values, elastic["mu"].values, rtol=0, atol=1e-15)
    assert np.all(neutral["memory_updates"].values[1:] > 0)
    assert neutral["memory_updates"].values[0] == 0            # V = 0: no memory
    assert "viscous_memory" in neutral.attrs["effects"]


def test_no_series_no_per_position_output(tmp_path, profile_m):
    ds = pavefric.simulate(profile_m, DX, SPEEDS)
    assert "position" not in ds.dims
    scene = write_scene(tmp_path, profile=profile_m)
    out = tmp_path / "o.nc"
    assert run_program(scene, "-o", out).returncode == 0
    with xr.open_dataset(out) as f:
        assert "position" not in f.dims
        assert not any(v in f for v in ("mu_inst", "hydro_load", "penetration"))


def test_series_does_not_change_the_mean(profile_m):
    a = pavefric.simulate(profile_m, DX, SPEEDS, depth=1e-3)
    b = pavefric.simulate(profile_m, DX, SPEEDS, depth=1e-3, series=True)
    assert np.array_equal(a["mu"].values, b["mu"].values)


@pytest.mark.parametrize("threads", ["1", "2"])
def test_thread_count_changes_no_bit(tmp_path, profile_m, threads):
    import os

    scene = write_scene(tmp_path, profile=profile_m,
                        groups={"water": "depth = 1e-3",
                                "operation": "speeds_kmh = 5, 10, 20, 30, 40, 60, 80, 100",
                                "output": "series = .true."})
    env_out = {}
    for n in ("1", threads):
        out = tmp_path / f"t{n}.nc"
        import subprocess
        from conftest import program
        r = subprocess.run([program(), str(scene), "-o", str(out)], capture_output=True,
                           text=True, env={**os.environ, "OMP_NUM_THREADS": n})
        assert r.returncode == 0, r.stderr
        env_out[n] = xr.open_dataset(out).load()
    for var in ("mu", "mu_inst", "penetration", "hydro_load", "max_balance_residual"):
        assert np.array_equal(env_out["1"][var].values, env_out[threads][var].values)


@pytest.mark.parametrize("speeds", ["20", "10, 30, 50", "5, 10, 20, 30, 40, 60, 80",
                                    "1, 5, 10, 15, 20, 25, 30, 40, 50, 60, 70, 80, 90"])
def test_chunking_of_the_speeds_changes_no_bit(tmp_path, profile_m, speeds):
    """Speeds advance in chunks whose width depends on the speed and thread
    counts; each speed's result is the same alone and in any chunk, dry and
    wet, with 1, 2 or 3 threads."""
    import os
    import subprocess

    from conftest import program

    listed = [float(v) for v in speeds.split(",")]
    for depth in ("0.0", "1e-3"):
        scene = write_scene(tmp_path, profile=profile_m,
                            groups={"water": f"depth = {depth}",
                                    "operation": f"speeds_kmh = {speeds}",
                                    "output": "series = .true."})
        results = []
        for n in ("1", "2", "3"):
            out = tmp_path / f"c{n}.nc"
            r = subprocess.run([program(), str(scene), "-o", str(out)], capture_output=True,
                               text=True, env={**os.environ, "OMP_NUM_THREADS": n})
            assert r.returncode == 0, r.stderr
            results.append(xr.open_dataset(out).load())
        single = write_scene(tmp_path, name="single", profile=profile_m,
                             groups={"water": f"depth = {depth}",
                                     "operation": f"speeds_kmh = {listed[-1]}",
                                     "output": "series = .true."})
        alone = pavefric.load_scene(single).simulate()
        for ds in results[1:]:
            for var in ("mu", "mu_inst", "penetration", "hydro_load", "contact_elements"):
                assert np.array_equal(results[0][var].values, ds[var].values), (var, depth)
        last = results[0].isel(speed_kmh=-1)
        assert last["mu"].values == alone["mu"].values[0]
        assert np.array_equal(last["mu_inst"].values, alone["mu_inst"].isel(speed_kmh=0).values)


@pytest.mark.parametrize("scheme", ["euler", "exact"])
def test_contact_fraction_is_the_share_of_elements_touching(scheme):
    """Issue 21: contact_fraction, every run's, is the mean over positions of
    the share of the pad's elements touching: all of them on a flat road
    (the pad sinks into it evenly), fewer on a texture, the same figure
    from both time schemes on a dry road to within the schemes' difference,
    and exactly the series' contact_elements over the pad's elements."""
    from pavefric.surfaces import spectral_profile

    flat = pavefric.simulate(np.zeros(256), 0.87e-3, [20.0, 60.0], time_scheme=scheme,
                             error_estimate=False)
    assert np.all(flat["contact_fraction"].values == 1.0)
    z = spectral_profile(512, 0.87e-3, rms=0.5e-3, seed=5)
    r = pavefric.simulate(z, 0.87e-3, [20.0, 60.0], time_scheme=scheme, series=True,
                          error_estimate=False)
    frac = r["contact_fraction"].values
    assert np.all((0.2 < frac) & (frac < 0.95)), frac
    ce = r["contact_elements"]
    per_speed = ce.mean(dim=[d for d in ce.dims if d not in r["mu"].dims]).values
    np.testing.assert_allclose(frac, per_speed / r.attrs["pad_elements"], rtol=1e-12)
    other = pavefric.simulate(z, 0.87e-3, [20.0, 60.0], error_estimate=False,
                              time_scheme="exact" if scheme == "euler" else "euler")
    assert np.all(np.abs(other["contact_fraction"].values - frac) < 0.05)
