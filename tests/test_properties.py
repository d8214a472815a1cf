"""Property-based tests over random scenes (hypothesis)."""
import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import pavefric
from pavefric.surfaces import spectral_profile

scenes = st.fixed_dictionaries({
    "n": st.integers(60, 400),
    "seed": st.integers(0, 2**31 - 1),
    "rms": st.floats(1e-6, 3e-3),
    "skew": st.floats(-1.5, 1.5),
    "closed": st.booleans(),
    "mu_loc": st.floats(0.0, 1.2),
    "stiffness": st.floats(1e5, 1e11),
    "viscosity": st.one_of(st.just(0.0), st.floats(1e-3, 1e7)),
    "load": st.floats(1e-3, 1e3),
    "depth": st.one_of(st.just(0.0), st.floats(1e-6, 1e-2)),
    "alpha": st.floats(0.0, 1e3),
    "speed": st.floats(0.0, 300.0),
    "length": st.floats(2e-3, 4e-2),
})


def run(s, shift=0.0, series=True, **kw):
    z = spectral_profile(s["n"], 0.87e-3, rms=s["rms"], skew=s["skew"], seed=s["seed"]) + shift
    settings = dict(closed=s["closed"], mu_loc=s["mu_loc"], stiffness=s["stiffness"],
                    viscosity=s["viscosity"], load=s["load"], depth=s["depth"],
                    alpha=s["alpha"], length=s["length"], series=series)
    settings.update(kw)
    return pavefric.simulate(z, 0.87e-3, [s["speed"], 0.5 * s["speed"]], **settings)


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(scenes)
def test_random_scenes_are_finite_and_balanced(s):
    ds = run(s)
    assert np.all(np.isfinite(ds["mu"].values))
    # (mu may be negative: with a small mu_loc, facets falling on average
    # under the pad push it forward; so no sign is asserted)
    assert np.all(ds["max_balance_residual"].values <= 1e-12)
    # friction exactly 0 wherever no element touches, at this position and
    # the one before (the energy scheme's step friction is the facets' work
    # from the one to the other)
    touching = ds["contact_elements"].values
    no_contact = touching == 0
    no_contact[..., 1:] &= touching[..., :-1] == 0
    if not s["closed"]:
        no_contact[..., 0] = touching[..., 0] == 0
    else:
        no_contact[..., 0] = False         # the step before is the spin-up's
    assert np.all(ds["mu_inst"].values[no_contact] == 0.0)
    # the paper's scheme: at every position without contact
    paper = run(s, friction_scheme="paper")
    assert np.all(paper["mu_inst"].values[paper["contact_elements"].values == 0] == 0.0)


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(scenes)
def test_dry_closed_friction_without_local_friction_is_dissipation(s):
    """Issue 20: with mu_loc = 0 on a dry closed profile, friction is the
    rubber's dissipation: never negative, all of it hysteresis."""
    ds = run(s, series=False, closed=True, mu_loc=0.0, depth=0.0)
    mu = ds["mu"].values
    assert np.all(mu >= -1e-15 * (1 + np.abs(mu)))
    assert np.all(ds["mu_adhesion"].values == 0.0)
    np.testing.assert_allclose(ds["mu_hysteresis"].values, mu, rtol=1e-14, atol=1e-18)
    if s["viscosity"] == 0.0:
        assert np.all(mu == 0.0)


@settings(max_examples=60, deadline=None)
@given(scenes, st.floats(-0.1, 0.1))
def test_vertical_shift_invariance(s, shift):
    """A vertical shift changes nothing, dry or wet. (Wet, it held only to
    3e-6 of mu where a film held the pad at an element's clearance, before
    the energy scheme's contact ramp: tests/test_energy.py,
    test_the_contact_ramp_keeps_friction_continuous_in_the_pushes.)"""
    a = run(s, series=False)
    b = run(s, shift, series=False)
    np.testing.assert_allclose(b["mu"].values, a["mu"].values, rtol=1e-9, atol=1e-12)
