"""The drainage film (&water wet_model = 'squeeze'): its closed forms and the
invariants docs/model.md states, on synthetic and real laser profiles."""
import numpy as np
import pytest
from scipy.special import erfc

import pavefric
from conftest import CAPTIF, ROOT

DX = 0.87e-3


def real_profile():
    p = pavefric.read_profile(CAPTIF / "20211011_aylesbury_dec_station_0.dat",
                              dropouts="interpolate", resample_dx=DX, spike_slope=3.0)
    return p.heights[:700], p.dx, False


def synthetic(skew):
    from pavefric.surfaces import spectral_profile

    return spectral_profile(1024, DX, rms=0.5e-3, skew=skew, seed=31), DX, True


PROFILES = {"real CAPTIF": real_profile, "Gaussian": lambda: synthetic(0.0),
            "negative": lambda: synthetic(-0.4), "positive": lambda: synthetic(0.3)}


@pytest.fixture(scope="module", params=list(PROFILES))
def profile(request):
    return PROFILES[request.param]()


def run(profile, speeds, **kw):
    z, dx, closed = profile
    kw.setdefault("mu_loc", 0.6)
    return pavefric.simulate(z, dx, speeds, closed=closed, **kw)


def squeeze(profile, speeds, **kw):
    kw.setdefault("depth", 1e-3)
    return run(profile, speeds, wet_model="squeeze", **kw)


def test_zero_depth_is_exactly_dry(profile):
    dry = run(profile, [20.0, 60.0])
    wet = squeeze(profile, [20.0, 60.0], depth=0.0)
    np.testing.assert_array_equal(wet["mu"].values, dry["mu"].values)
    assert "squeeze_film" not in wet.attrs["effects"]


def test_speed_to_zero_gives_the_dry_result(profile):
    dry = run(profile, [0.0])["mu"].values[0]
    assert squeeze(profile, [0.0])["mu"].values[0] == dry        # no motion, no film
    speeds = [1e-1, 1e-2, 1e-3, 1e-4, 1e-6, 1e-8]
    gaps = np.abs(squeeze(profile, speeds)["mu"].values - run(profile, speeds)["mu"].values)
    assert np.all(np.diff(gaps) < 0)                   # closer and closer to dry
    # a film squeezed for a time ~ 1/V is ~ sqrt(V) thin: the gap closes like sqrt(V)
    assert gaps[-1] < 2e-3 * gaps[0] and gaps[-1] < 2e-5 * dry


@pytest.mark.parametrize("viscosity", [0.0, 100.0])
def test_friction_never_rises_with_speed(profile, viscosity):
    speeds = [1.0, 5.0, 10.0, 20.0, 30.0, 40.0, 60.0, 80.0, 120.0]
    mu = squeeze(profile, speeds, viscosity=viscosity)["mu"].values
    assert np.all(np.diff(mu) <= 0), mu
    assert mu[-1] < mu[0]


def test_friction_never_rises_with_water_depth(profile):
    mus = [squeeze(profile, [20.0, 60.0], depth=d)["mu"].values
           for d in (1e-6, 1e-5, 1e-4, 3e-4, 1e-3, 3e-3, 1e-2)]
    dry = run(profile, [20.0, 60.0])["mu"].values
    mus = np.array([dry] + mus)
    assert np.all(np.diff(mus, axis=0) <= 0), mus


def test_more_microtexture_never_lowers_friction(profile):
    mus = np.array([squeeze(profile, [20.0, 60.0], microtexture_rms=s)["mu"].values
                    for s in (0.0, 5e-6, 20e-6, 40e-6, 100e-6, 1e-3)])
    assert np.all(np.diff(mus, axis=0) >= 0), mus
    dry = run(profile, [20.0, 60.0])["mu"].values
    assert np.all(mus[-1] <= dry)


def test_outputs_say_which_model_ran(profile):
    ds = squeeze(profile, [20.0], series=True)
    assert ds.attrs["effects"].endswith(",squeeze_film")
    assert "hydrodynamic_bearing" not in ds.attrs["effects"]
    assert ds["squeeze_film_ran"].values[0] == 1 and ds["bearing_ran"].values[0] == 0
    assert ds["mean_hydro_load"].values[0] == 0 and ds["wet_fraction"].values[0] == 0
    h = ds["film_thickness"].values[0]
    assert np.all((h > 0) & (h <= 1e-3))                 # thinned from the 1 mm depth
    mu_eff = ds["local_friction"].values[0]
    assert np.all((mu_eff >= 0) & (mu_eff <= 0.6))
    assert 0 < ds["mean_local_friction"].values[0] < 0.6
    # the dry contact carries the whole load: the film lifts nothing
    assert ds["max_balance_residual"].values[0] < 1e-12


def test_no_microtexture_leaves_only_hysteresis():
    # sigma = 0: nothing pierces any film, so mu_loc acts nowhere: the friction
    # is the facets' hysteresis alone, mu = sum F tan(alpha) / W (mu_loc = 0)
    z, dx, closed = synthetic(0.0)
    wet = pavefric.simulate(z, dx, [20.0], mu_loc=0.6, depth=1e-3, wet_model="squeeze",
                            microtexture_rms=0.0, viscosity=0.0)
    bare = pavefric.simulate(z, dx, [20.0], mu_loc=0.0, viscosity=0.0)
    assert wet["mu"].values[0] == pytest.approx(bare["mu"].values[0], rel=1e-12, abs=1e-15)


def test_squeeze_closed_form_on_a_flat_profile():
    # A flat road: every element touches, one plateau of the pad's length
    # capped at its width l, pressure W / (l L) everywhere. A sample under
    # the pad for time t has h**-2 = H**-2 + 2 p t / (eta b**2); the element
    # at distance s behind the leading edge has been over it for t = s / V.
    n = 400
    z = np.zeros(n)
    V, H, eta, sigma, l, L, W, mu_loc = 20 / 3.6, 1e-3, 1e-3, 40e-6, 0.016, 0.020, 11.8, 0.6
    ds = pavefric.simulate(z, DX, [20.0], closed=True, mu_loc=mu_loc, depth=H,
                           wet_model="squeeze", microtexture_rms=sigma, viscosity=0.0,
                           series=True)
    N = ds.attrs["pad_elements"]
    assert abs(N * DX - L) <= DX                       # the pad: N elements over L
    p = W / (l * N * DX)
    b = min(N * DX, l)
    dt = DX / V
    # element i (1 = trailing) has squeezed its sample for N - i + 1 steps
    steps = np.arange(N, 0, -1)
    h = (H**-2 + 2 * p * dt * steps / (eta * b**2)) ** -0.5
    share = erfc(h / (np.sqrt(2) * sigma))
    mu = np.sum((W / N) * share * mu_loc) / W          # flat: tan(0 + atan(mu)) = mu
    np.testing.assert_allclose(ds["mu"].values[0], mu, rtol=1e-12)
    np.testing.assert_allclose(ds["film_thickness"].values[0], h.mean(), rtol=1e-12)


def test_program_runs_the_squeeze_scene(tmp_path):
    from conftest import run_program
    import xarray as xr

    out = tmp_path / "sq.nc"
    r = run_program(ROOT / "inputs" / "ctm_squeeze.nml", "-o", out)
    assert r.returncode == 0, r.stderr
    with xr.open_dataset(out) as ds:
        assert "squeeze_film" in ds.attrs["effects"]
        assert ds.attrs["param_water_wet_model"] == "squeeze"
        mu = ds["mu"].values
        assert np.all(np.diff(mu) <= 0) and mu[-1] < mu[0]


def test_a_speed_without_film_reports_no_film_and_the_full_mu_loc(tmp_path):
    """At 0 km/h the drainage film is off (no motion): its series and means
    say so (film 0, local friction mu_loc where in contact), identically in
    the program and Python (they were uninitialised memory)."""
    from conftest import run_program, write_scene
    from test_boundaries import assert_same_bits
    import xarray as xr

    scene = write_scene(tmp_path, groups={"water": "depth = 1e-3, wet_model = 'squeeze'",
                                          "operation": "speeds_kmh = 0, 20, 0",
                                          "output": "series = .true."})
    out = tmp_path / "o.nc"
    r = run_program(scene, "-o", out)
    assert r.returncode == 0, r.stderr
    ds = pavefric.load_scene(scene).simulate()
    with xr.open_dataset(out) as f:
        assert_same_bits(f.load(), ds, "squeeze at 0 km/h")
    for j in (0, 2):
        still = ds.isel(speed_kmh=j)
        assert int(still["squeeze_film_ran"]) == 0
        assert np.all(still["film_thickness"].values == 0.0)
        contact = still["contact_elements"].values > 0
        assert contact.any()
        np.testing.assert_array_equal(still["local_friction"].values[contact], 0.5)
        assert float(still["mean_local_friction"]) == 0.5
        assert float(still["mean_film_thickness"]) == 0.0
    moving = ds.isel(speed_kmh=1)
    assert int(moving["squeeze_film_ran"]) == 1
    assert float(moving["mean_film_thickness"]) > 0.0


# --- &water squeeze_inlet_fraction: a variable the squeeze film declares itself

def test_an_inlet_fraction_is_the_film_of_that_share_of_the_depth(profile):
    """The entering film is squeeze_inlet_fraction x depth: half the water
    entering is, bit for bit, the film of half the depth (the squeeze film
    takes depth nowhere else), and less water never lowers friction."""
    half = squeeze(profile, [20.0, 60.0], depth=1e-3, squeeze_inlet_fraction=0.5)
    shallow = squeeze(profile, [20.0, 60.0], depth=0.5e-3)
    assert np.array_equal(half["mu"].values, shallow["mu"].values)
    full = squeeze(profile, [20.0, 60.0], depth=1e-3)
    assert np.all(half["mu"].values >= full["mu"].values)
    default = squeeze(profile, [20.0, 60.0], depth=1e-3, squeeze_inlet_fraction=1.0)
    assert np.array_equal(default["mu"].values, full["mu"].values)
    assert half.attrs["param_water_squeeze_inlet_fraction"] == 0.5


@pytest.mark.parametrize("value", [0.0, -0.1, 1.5, float("nan")])
def test_an_inlet_fraction_out_of_range_is_refused_by_name(value):
    z, dx, closed = synthetic(0.0)
    with pytest.raises(pavefric.PavefricError, match=r"&water squeeze_inlet_fraction = "):
        pavefric.simulate(z, dx, [20.0], depth=1e-3, wet_model="squeeze",
                          squeeze_inlet_fraction=value)


def test_an_inlet_fraction_given_to_the_bearing_is_warned_of():
    z, dx, closed = synthetic(0.0)
    with pytest.warns(pavefric.PavefricWarning,
                      match=r"&water squeeze_inlet_fraction = 0.5 is not used with &water "
                            r"wet_model = 'kane2017' \(a variable of wet_model = 'squeeze'"):
        pavefric.simulate(z, dx, [20.0], depth=1e-3, squeeze_inlet_fraction=0.5)


def test_the_film_thickness_is_the_contacts(profile):
    """Issue 21: mean_film_thickness is the film left between the rubber and
    the road where they touch, not an average with the elements out of
    contact (the water on the road under them): the mean over positions of
    the series' film_thickness, which is at most the water depth, positive
    on average, and 0 at a position where nothing touches."""
    r = squeeze(profile, [20.0, 80.0], series=True, error_estimate=False)
    ft = r["film_thickness"]
    per_speed = ft.mean(dim=[d for d in ft.dims if d not in r["mu"].dims]).values
    np.testing.assert_allclose(r["mean_film_thickness"].values, per_speed, rtol=1e-12)
    assert np.all(r["mean_film_thickness"].values > 0.0)
    assert np.all(ft.values <= 1e-3 * (1 + 1e-12)) and np.all(ft.values >= 0.0)
    # where no element touches, the series says 0 (no film between them)
    ce = r["contact_elements"].values
    assert np.all(ft.values[ce == 0] == 0.0)
