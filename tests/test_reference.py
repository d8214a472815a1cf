"""The core against an independent slow NumPy implementation of MODEL.md."""
import numpy as np
import pytest

import pavefric
import reference

CASES = [
    pytest.param(dict(), id="dry"),
    pytest.param(dict(viscosity=0.0), id="dry-elastic"),
    pytest.param(dict(viscosity=3e4), id="dry-viscous"),
    pytest.param(dict(depth=1e-3), id="wet"),
    pytest.param(dict(depth=1e-3, alpha=11.8), id="wet-default-alpha"),
    pytest.param(dict(depth=1e-3, viscosity=3e4, alpha=3.0), id="wet-viscous"),
    pytest.param(dict(depth=0.2e-3, mu_loc=0.3, load=5.0), id="wet-thin-film"),
    pytest.param(dict(theta_max_deg=30.0, mu_loc=0.8), id="clamped"),
]


@pytest.mark.parametrize("params", CASES)
@pytest.mark.parametrize("closed", [True, False], ids=["closed", "open"])
def test_mean_friction_matches_reference(short_profile_m, params, closed):
    speeds = [0.0, 1.0, 20.0, 60.0, 80.0]
    params = {"alpha": 1.0, **params}
    ref = reference.simulate(short_profile_m, 0.87e-3, speeds, closed=closed, **params)
    # the reference is MODEL.md's discretisation, one element per sample:
    # min_contacts = 0
    ds = pavefric.simulate(short_profile_m, 0.87e-3, speeds, closed=closed, min_contacts=0,
                           **params)
    np.testing.assert_allclose(ds["mu"].values, ref, rtol=0, atol=1e-10)
    assert np.all(ds["max_balance_residual"].values <= 1e-12)
    # the default is that run wherever it did not refine the pad (a film
    # that leaves the pad on fewer than 4 elements: the thin film at speed)
    default = pavefric.simulate(short_profile_m, 0.87e-3, speeds, closed=closed, **params)
    same = default["elements_per_sample_used"].values == 1
    assert same.sum() >= 4
    np.testing.assert_array_equal(default["mu"].values[same], ds["mu"].values[same])


def test_series_match_reference(short_profile_m):
    mu, series = reference.simulate(short_profile_m, 0.87e-3, [40.0], depth=1e-3, alpha=3.0,
                                   series=True)
    ds = pavefric.simulate(short_profile_m, 0.87e-3, [40.0], depth=1e-3, alpha=3.0, series=True)
    ref_mu, ref_delta, ref_wh = series[0]
    np.testing.assert_allclose(ds["mu_inst"].values[0], ref_mu, atol=1e-10)
    np.testing.assert_allclose(ds["penetration"].values[0], ref_delta, atol=1e-12)
    np.testing.assert_allclose(ds["hydro_load"].values[0], ref_wh, rtol=1e-8, atol=1e-10)
    assert ds["wet_fraction"].values[0] > 0.5      # the case really is wet


def test_rounded_pad_matches_reference(short_profile_m):
    n = 23
    x = (np.arange(1, n + 1) - 0.5 - n / 2) * 0.87e-3
    radius = 0.03
    h = radius - np.sqrt(radius**2 - x**2)
    ref = reference.simulate(short_profile_m, 0.87e-3, [20.0, 60.0], h=h, depth=1e-3, alpha=11.8)
    ds = pavefric.simulate(short_profile_m, 0.87e-3, [20.0, 60.0], shape="rounded",
                           radius=radius, depth=1e-3, alpha=11.8)
    np.testing.assert_allclose(ds["mu"].values, ref, atol=1e-10)
