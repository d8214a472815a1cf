"""Closed-form cases and invariants of the model."""
import numpy as np
import pytest

import pavefric

DX = 0.87e-3
SPEEDS = [0.0, 1.0, 20.0, 40.0, 60.0, 80.0]


@pytest.mark.parametrize("mu_loc", [0.0, 0.3, 0.75])
@pytest.mark.parametrize("viscosity", [0.0, 100.0, 1e5])
def test_flat_profile_gives_mu_loc(mu_loc, viscosity):
    # all elements tie, alpha = 0 everywhere: mu = tan(atan(mu_loc)) = mu_loc
    z = np.full(300, 1.234e-3)
    ds = pavefric.simulate(z, DX, SPEEDS, mu_loc=mu_loc, viscosity=viscosity)
    np.testing.assert_allclose(ds["mu"].values, mu_loc, rtol=1e-14, atol=1e-15)
    assert np.all(ds["max_balance_residual"].values <= 1e-14)


def test_elastic_scene_is_independent_of_speed(profile_m):
    ds = pavefric.simulate(profile_m, DX, SPEEDS, viscosity=0.0, mu_loc=0.6)
    assert np.all(ds["mu"].values == ds["mu"].values[0])       # bit for bit
    assert not ds["viscous_memory_ran"].values.any()
    # and viscosity does change it, so the test can fail
    dv = pavefric.simulate(profile_m, DX, [1.0, 80.0], viscosity=1e4, mu_loc=0.6)
    assert abs(dv["mu"].values[1] - dv["mu"].values[0]) > 1e-3


def test_wet_at_zero_speed_or_depth_is_exactly_dry(profile_m):
    dry = pavefric.simulate(profile_m, DX, SPEEDS, mu_loc=0.6)
    no_water = pavefric.simulate(profile_m, DX, SPEEDS, mu_loc=0.6, depth=0.0, alpha=50.0)
    wet = pavefric.simulate(profile_m, DX, SPEEDS, mu_loc=0.6, depth=1e-3, alpha=1.0)
    assert np.array_equal(no_water["mu"].values, dry["mu"].values)
    assert wet["mu"].values[0] == dry["mu"].values[0]            # V = 0: no bearing
    assert wet["bearing_evaluations"].values[0] == 0
    assert np.all(wet["mu"].values[2:] < dry["mu"].values[2:])   # water does act
    assert dry["bearing_evaluations"].values.sum() == 0


@pytest.mark.parametrize("shift", [-0.05, 1e-3, 7.0])
@pytest.mark.parametrize("depth", [0.0, 1e-3])
def test_vertical_shift_changes_nothing(profile_m, shift, depth):
    a = pavefric.simulate(profile_m, DX, SPEEDS, depth=depth, series=True)
    b = pavefric.simulate(profile_m + shift, DX, SPEEDS, depth=depth, series=True)
    np.testing.assert_allclose(b["mu"].values, a["mu"].values, rtol=0, atol=1e-12)
    np.testing.assert_allclose(b["penetration"].values, a["penetration"].values - shift,
                               rtol=0, atol=1e-12 * max(1.0, abs(shift)))


@pytest.mark.parametrize("depth", [0.0, 0.3e-3, 1e-3, 5e-3])
@pytest.mark.parametrize("closed", [True, False])
def test_load_balance_at_every_position(profile_m, depth, closed):
    ds = pavefric.simulate(profile_m, DX, SPEEDS, depth=depth, closed=closed, alpha=2.0)
    assert np.all(ds["max_balance_residual"].values <= 1e-12)


def test_bearing_series_continuous_with_closed_form():
    from pavefric.core import hydro_load

    h_in = 1e-3
    # the series is used for e = Hin/Hout - 1 < 0.25: compare both sides of it
    e = 0.25
    h_switch = h_in / (1 + e)
    h = h_switch * (1 + np.array([-1e-12, 0.0, 1e-12]))
    wh, dwh = hydro_load(h, h_in)
    np.testing.assert_allclose(wh, wh[1], rtol=1e-11)
    np.testing.assert_allclose(dwh, dwh[1], rtol=1e-10)
    # against the closed form in extended precision, across the switch
    ee = np.array([1e-12, 1e-8, 1e-4, 0.1, 0.2499, 0.2501, 0.5, 3.0, 1e6])
    hout = h_in / (1 + ee)
    wh, _ = hydro_load(hout, h_in)
    # e as the core forms it from the rounded Hout: (Hin - Hout) / Hout
    e_ld = (np.longdouble(h_in) - hout.astype(np.longdouble)) / hout.astype(np.longdouble)
    a = 1 + e_ld
    exact_small = e_ld / 12 - e_ld**2 / 8 + 11 * e_ld**3 / 80 - 13 * e_ld**4 / 96 \
        + 57 * e_ld**5 / 448
    exact_big = (np.log(a) - 2 * (a - 1) / (a + 1)) / (a - 1) ** 2
    bracket = np.where(ee < 1e-3, exact_small, exact_big)
    expect = (1 / hout.astype(np.longdouble) ** 2 * bracket).astype(float)
    np.testing.assert_allclose(wh, expect, rtol=1e-12)


def test_bearing_limits():
    from pavefric.core import hydro_load

    wh, _ = hydro_load([1e-3, 2e-3, 0.0, 1e-300], 1e-3)
    assert wh[0] == 0.0 and wh[1] == 0.0            # no wedge: no load
    assert np.isfinite(wh[2]) and wh[2] > 1e300     # a film cannot close
    assert np.isfinite(wh[3]) and wh[3] > 1e300


def test_friction_falls_with_water_on_a_fine_texture(profile_m):
    # Not a monotonicity test (MODEL.md section 7: Eq. 15 is not monotone in
    # depth): from dry to a thin film, friction must fall at speed.
    dry = pavefric.simulate(profile_m, DX, [60.0])["mu"].values[0]
    wet = pavefric.simulate(profile_m, DX, [60.0], depth=0.5e-3)["mu"].values[0]
    assert wet < dry - 0.01


def test_wet_friction_falls_with_speed(profile_m):
    ds = pavefric.simulate(profile_m, DX, [1, 10, 20, 40, 60, 80], depth=1e-3, viscosity=0.0)
    assert np.all(np.diff(ds["mu"].values) < 0)


def test_effects_say_what_ran(profile_m):
    assert pavefric.simulate(profile_m, DX, [20], viscosity=0.0).attrs["effects"] == \
        "elastic_contact,facet_friction"
    assert pavefric.simulate(profile_m, DX, [20]).attrs["effects"] == \
        "elastic_contact,facet_friction,viscous_memory"
    ds = pavefric.simulate(profile_m, DX, [0, 20], depth=1e-3)
    assert ds.attrs["effects"].endswith("hydrodynamic_bearing")
    assert list(ds["bearing_ran"].values) == [0, 1]
    assert list(ds["viscous_memory_ran"].values) == [0, 1]


def test_clamped_facets_are_counted():
    # a saw-tooth with 60 degree flanks: with mu_loc = 0.5 the rising flank's
    # theta is 60 + 26.6 = 86.6 degrees, beyond 85 (clamped), within 89.9
    dx = DX
    ramp = np.tan(np.radians(60)) * dx * np.arange(8)
    z = np.tile(np.concatenate([ramp, ramp[::-1]]), 20)
    ds = pavefric.simulate(z, dx, [20.0], mu_loc=0.5)
    assert ds["n_clamped"].values[0] > 0
    assert np.isfinite(ds["mu"].values[0])
    loose = pavefric.simulate(z, dx, [20.0], mu_loc=0.5, theta_max_deg=89.9)
    assert loose["n_clamped"].values[0] == 0
    assert loose["mu"].values[0] > ds["mu"].values[0]


def test_open_profile_positions():
    z = np.sin(np.arange(100) * 0.4) * 1e-4
    ds = pavefric.simulate(z, DX, [20.0], closed=False, series=True)
    assert ds.attrs["pad_elements"] == 23
    assert ds.sizes["position"] == 100 - 23 + 1
    assert ds.attrs["spinup_positions"] == 0
    dc = pavefric.simulate(z, DX, [20.0], closed=True, series=True)
    assert dc.sizes["position"] == 100 and dc.attrs["spinup_positions"] == 23
