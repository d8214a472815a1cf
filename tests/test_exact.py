"""The exact Kelvin-Voigt integrator (&numerics time_scheme = 'exact', issue
23): the pad stepped from contact event to event. Its answer is the limit
backward Euler converges to as the time step shrinks; the test's reference
is that limit, estimated independently from two very fine Euler passes
(Richardson of substeps 512 and 1024, itself within ~3e-7 of the limit on
these scenes: docs/accuracy.md)."""
import os
import subprocess
import warnings

import numpy as np
import pytest
import xarray as xr

import pavefric
from conftest import ROOT, program, write_scene

SPEEDS = [20.0, 60.0]


def euler_limit(scene, **kw):
    fine = [scene.simulate(speeds_kmh=SPEEDS, substeps=s, tolerance=0.0, time_scheme="euler",
                           **kw) for s in (512, 1024)]
    return {v: 2.0 * fine[1][v].values - fine[0][v].values
            for v in ("mu", "mu_hysteresis", "mu_adhesion")}


@pytest.mark.parametrize("name,viscosity", [("GSP", 100.0), ("GSS", 100.0), ("VTAC", 100.0),
                                            ("RSBA", 1.0e4)])
def test_exact_is_the_limit_of_backward_euler(name, viscosity):
    scene = pavefric.load_scene(ROOT / "inputs" / "surfaces" / f"{name}.nml")
    kw = dict(depth=0.0, viscosity=viscosity)
    limit = euler_limit(scene, **kw)
    exact = scene.simulate(speeds_kmh=SPEEDS, time_scheme="exact", tolerance=0.0, **kw)
    one = scene.simulate(speeds_kmh=SPEEDS, time_scheme="euler", tolerance=0.0, **kw)
    assert exact["exact_integrator_ran"].values.tolist() == [1, 1]
    for v in ("mu", "mu_hysteresis", "mu_adhesion"):
        np.testing.assert_allclose(exact[v].values, limit[v], rtol=0, atol=2e-6, err_msg=v)
    # and the paper's single step is far from it (the point of the scheme)
    if name != "RSBA":
        assert np.abs(one["mu"].values - limit["mu"]).max() > 1e-2
    np.testing.assert_allclose(exact["mu_hysteresis"].values + exact["mu_adhesion"].values,
                               exact["mu"].values, rtol=0, atol=1e-15)
    assert np.all(exact["max_balance_residual"].values < 1e-12)


def test_exact_needs_no_refinement():
    """The exact answer does not depend on the grid's substeps (the road is
    the same piecewise-linear line), and a tolerance run stops after one
    doubling with an estimate at rounding level."""
    scene = pavefric.load_scene(ROOT / "inputs" / "ctm_dry.nml")
    one = scene.simulate(time_scheme="exact", tolerance=0.0)
    four = scene.simulate(time_scheme="exact", tolerance=0.0, substeps=4)
    np.testing.assert_allclose(one["mu"].values, four["mu"].values, rtol=0, atol=1e-12)
    tol = scene.simulate(time_scheme="exact", tolerance=1e-9)
    assert np.all(tol["substeps_used"].values == 2)
    assert np.all(tol["mu_error_estimate"].values <= 1e-12)


@pytest.fixture(scope="module")
def gsp():
    return pavefric.load_scene(ROOT / "inputs" / "surfaces" / "GSP.nml")


def test_a_vertical_shift_changes_nothing(gsp):
    kw = dict(speeds_kmh=SPEEDS, depth=0.0, time_scheme="exact", tolerance=0.0)
    base = pavefric.simulate(gsp.heights, gsp.dx, **kw)
    up = pavefric.simulate(gsp.heights + 0.37e-3, gsp.dx, **kw)
    np.testing.assert_allclose(up["mu"].values, base["mu"].values, rtol=1e-9)


def test_series_are_the_steps_of_the_mean(gsp):
    ds = gsp.simulate(speeds_kmh=SPEEDS, depth=0.0, time_scheme="exact", tolerance=0.0,
                      series=True)
    np.testing.assert_allclose(ds["mu_inst"].mean("position").values, ds["mu"].values,
                               rtol=1e-12)
    assert np.all(ds["contact_elements"].values >= 1)
    assert np.all(np.isfinite(ds["penetration"].values))


@pytest.mark.parametrize("closed", [True, False])
def test_open_profiles_and_a_rounded_pad(gsp, closed):
    """Open profiles and a rounded pad: the same limit as backward Euler
    (open: the means differ by the first position's weight, O(1 / positions):
    3e-5 measured)."""
    z = gsp.heights[:600]
    kw = dict(depth=0.0, closed=closed, shape="rounded", radius=0.05)
    exact = pavefric.simulate(z, gsp.dx, SPEEDS, time_scheme="exact", tolerance=0.0, **kw)
    fine = [pavefric.simulate(z, gsp.dx, SPEEDS, substeps=s, tolerance=0.0,
                              time_scheme="euler", **kw)["mu"].values for s in (256, 512)]
    limit = 2.0 * fine[1] - fine[0]
    atol = 1e-5 if closed else 2e-4
    np.testing.assert_allclose(exact["mu"].values, limit, rtol=0, atol=atol)
    assert np.all(exact["max_balance_residual"].values < 1e-12)


def test_other_rubbers_and_films_run_euler_and_say_so(gsp):
    # the drainage film (the paper's is integrated: the tests below)
    with pytest.warns(pavefric.PavefricWarning, match="time_scheme = 'exact'.*backward Euler"):
        wet = gsp.simulate(speeds_kmh=SPEEDS, time_scheme="exact", tolerance=0.0,
                           wet_model="squeeze")                                    # 1 mm water
    assert wet["exact_integrator_ran"].values.tolist() == [0, 0]
    euler = gsp.simulate(speeds_kmh=SPEEDS, time_scheme="euler", tolerance=0.0,
                         wet_model="squeeze")
    assert np.array_equal(wet["mu"].values, euler["mu"].values)
    # no memory (speed 0): nothing to integrate, no warning (the error
    # estimate's pass is off: its own warning, of the pad's sampling of this
    # rough road, is tests/test_error_estimate.py's)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        still = gsp.simulate(speeds_kmh=[0.0], depth=0.0, time_scheme="exact", tolerance=0.0,
                             error_estimate=False)
    assert still["exact_integrator_ran"].values.tolist() == [0]


@pytest.mark.parametrize("setting,words", [
    ("position_stride = 2", "position_stride = 2: the exact integrator"),
    ("friction_scheme = 'paper'", "friction_scheme = 'paper': the exact integrator")])
def test_settings_it_cannot_honour_are_errors(tmp_path, profile_m, setting, words):
    scene = write_scene(tmp_path, profile=profile_m,
                        groups={"numerics": f"time_scheme = 'exact', {setting}"})
    r = subprocess.run([program(), str(scene), "-o", str(tmp_path / "o.nc")],
                       capture_output=True, text=True)
    assert r.returncode != 0
    assert "&numerics time_scheme = 'exact'" in r.stderr and words in r.stderr
    assert not (tmp_path / "o.nc").exists()


def test_slow_memory_and_an_open_start_follow_euler():
    """A slowly relaxing pad on an open profile (memory of ~60 steps, no
    spin-up): the start matters, and the exact scheme starts as backward
    Euler's limit does (relaxed elements, the pad landing on the highest);
    found by a random search: it started from the elastic balance, 0.05 off.
    Both at the elements given (min_contacts = 0: the pad stands on few at
    100 km/h, and the comparison is of the time schemes)."""
    z = pavefric.load_scene(ROOT / "inputs" / "surfaces" / "GSS.nml").heights[:300]
    kw = dict(depth=0.0, closed=False, viscosity=321.0, stiffness=1.72e5, load=0.095,
              min_contacts=0)
    exact = pavefric.simulate(z, 0.87e-3, [40.0, 100.0], time_scheme="exact", tolerance=0.0,
                              **kw)
    fine = [pavefric.simulate(z, 0.87e-3, [40.0, 100.0], substeps=s, tolerance=0.0,
                              time_scheme="euler", **kw)["mu"].values for s in (256, 512)]
    np.testing.assert_allclose(exact["mu"].values, 2.0 * fine[1] - fine[0], rtol=0, atol=2e-4)
    assert np.all(exact["max_balance_residual"].values < 1e-12)


def test_threads_change_no_bit(tmp_path, profile_m):
    scene = write_scene(tmp_path, profile=profile_m, groups={
        "numerics": "time_scheme = 'exact'", "operation": "speeds_kmh = 5, 20, 40, 60, 80",
        "output": "series = .true."})
    out = {}
    for n in ("1", "2"):
        path = tmp_path / f"t{n}.nc"
        r = subprocess.run([program(), str(scene), "-o", str(path)], capture_output=True,
                           text=True, env={**os.environ, "OMP_NUM_THREADS": n})
        assert r.returncode == 0, r.stderr
        out[n] = xr.open_dataset(path).load()
    assert out["1"]["exact_integrator_ran"].values.all()
    for var in ("mu", "mu_hysteresis", "mu_inst", "penetration", "max_balance_residual"):
        assert np.array_equal(out["1"][var].values, out["2"][var].values), var


def test_auto_runs_the_exact_integrator_where_it_applies(profile_m):
    """time_scheme = 'auto': on a dry Kelvin-Voigt road, and under the paper's
    film, it is 'exact' bit for bit; where the exact integrator does not
    apply (the drainage film, the Maxwell
    compound, position_stride > 1, the paper's friction scheme) it is
    'extrapolated' bit for bit, with no warning of the fallback (and no
    refusal where 'exact' refuses)."""
    kw = dict(viscosity=3e3)
    auto = pavefric.simulate(profile_m, 0.87e-3, SPEEDS, time_scheme="auto", **kw)
    exact = pavefric.simulate(profile_m, 0.87e-3, SPEEDS, time_scheme="exact", **kw)
    assert auto["exact_integrator_ran"].values.tolist() == [1, 1]
    np.testing.assert_array_equal(auto["mu"].values, exact["mu"].values)
    # under the paper's film it is 'exact' too (second order in the step)
    wet = dict(depth=1e-3, **kw)
    auto = pavefric.simulate(profile_m, 0.87e-3, SPEEDS, time_scheme="auto", **wet)
    exact = pavefric.simulate(profile_m, 0.87e-3, SPEEDS, time_scheme="exact", **wet)
    assert auto["exact_integrator_ran"].values.tolist() == [1, 1]
    np.testing.assert_array_equal(auto["mu"].values, exact["mu"].values)
    maxwell = dict(rubber_model="maxwell", prony_stiffness=[1e8], prony_times=[1e-4])
    for other in (dict(depth=1e-3, wet_model="squeeze", **kw), dict(maxwell),
                  dict(position_stride=2, **kw), dict(friction_scheme="paper", **kw)):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", pavefric.PavefricWarning)
            euler = pavefric.simulate(profile_m, 0.87e-3, SPEEDS, time_scheme="extrapolated",
                                      **other)
            auto = pavefric.simulate(profile_m, 0.87e-3, SPEEDS, time_scheme="auto", **other)
        assert auto["exact_integrator_ran"].values.tolist() == [0, 0], other
        np.testing.assert_array_equal(auto["mu"].values, euler["mu"].values)
        assert "time_scheme = 'exact' integrates" not in auto.attrs["warnings"], other


def test_the_open_profiles_first_position_has_no_step():
    """docs/model.md, "the open profile's first position": an open profile's
    M positions bound M - 1 steps, and the rubber's part (the steps' work)
    is their mean; it was the mean over M, which halved it on a profile one
    sample longer than the pad (an attack's reproducer, 24 random heights:
    backward Euler 0.021 against the exact integrator's 0.044)."""
    z = np.random.default_rng(1).normal(0.0, 0.6e-3, 1024)
    kw = dict(error_estimate=False, min_contacts=0, element_length=0.0)

    def hyst(n, scheme, closed=False, substeps=1):
        ds = pavefric.simulate(z[:n], 0.87e-3, [20.0], closed=closed, time_scheme=scheme,
                               substeps=substeps, **kw)
        return float(ds["mu_hysteresis"][0])

    # (0.0440 and 0.043 before 2026-12-07, when an open profile's mean was
    # the facets' work: on this one-step stretch that was nearly all the
    # energy stored at its ends; it is now the rubber's dissipation)
    exact = hyst(24, "exact")
    assert round(exact, 4) == 0.0034
    assert abs(hyst(24, "euler", substeps=64) - exact) < 0.01 * exact
    # a longer open stretch of the same heights: near the same heights closed
    closed_100 = hyst(100, "exact", closed=True)
    assert abs(hyst(100, "exact") - closed_100) < 0.1 * closed_100
    # closed, the same heights converge to the exact integrator's
    closed = hyst(100, "exact", closed=True)
    assert abs(hyst(100, "euler", closed=True, substeps=4096) - closed) < 1e-6


@pytest.mark.parametrize("n", [24, 100])
@pytest.mark.parametrize("viscosity", [1e2, 1e3, 1e4])
def test_backward_euler_converges_to_the_exact_integrator_on_open_profiles(n, viscosity):
    """docs/model.md, "The landing": a lane's first step lands the pad on
    relaxed elements over the time the road takes to move one element
    length, whatever the substeps, in both integrators. It was one step of
    the run's own length, so a finer step resolved a different (and ever
    faster) landing: backward Euler's rubber part on a short open profile
    left the exact one past a few hundred substeps (24 samples, C = 100:
    0.0409 at 256 and 0.0272 at 4096 against 0.0439; 100 samples: 0.00552
    and 0.00535 against 0.00557). Now it converges to it, first order:
    each error below the one at 16 times fewer substeps, and within 1.2e-4
    of the exact value (relative) at 4096 (measured: 1.3e-5 to 1.16e-4); the
    figures the page quotes for 24 samples at C = 100."""
    z = np.random.default_rng(1).normal(0.0, 0.6e-3, n)
    kw = dict(error_estimate=False, min_contacts=0, element_length=0.0, closed=False,
              viscosity=viscosity)

    def hyst(scheme, substeps=1):
        ds = pavefric.simulate(z, 0.87e-3, [20.0], time_scheme=scheme, substeps=substeps, **kw)
        return float(ds["mu_hysteresis"][0])

    exact = hyst("exact")
    euler = {s: hyst("euler", s) for s in (1, 16, 256, 4096)}
    errors = [abs(euler[s] - exact) for s in (16, 256, 4096)]
    assert errors[0] > errors[1] > errors[2], (exact, euler)
    assert errors[2] < 1.2e-4 * abs(exact), (exact, euler)
    if n == 24 and viscosity == 1e2:
        assert [round(euler[s], 5) for s in (1, 16, 256)] == [0.00245, 0.00337, 0.00341]
        assert round(euler[4096], 6) == round(exact, 6) == 0.00341


# backward Euler's limit on inputs/ctm_wet.nml at 20 and 60 km/h: Richardson
# of substeps 1024 and 2048 (the passes' changes 3.2e-8 and 4.0e-8 there, so
# within about 5e-8 of the limit); python -m pavefric.studies.step_orders
# --levels 12 prints those passes
CTM_WET_LIMIT = np.array([0.3884238, 0.1181223])


def test_under_the_papers_film_the_exact_integrator_falls_at_second_order():
    """docs/numerics.md ("An integrator exact in time under the paper's
    film"): the film's load linearised in the mean gap over each part of a
    step; on inputs/ctm_wet.nml its error at one step per sample is 1.2e-4
    and 3.5e-5 (backward Euler's 8.0e-3 and 4.7e-3), falls towards second
    order as the step shrinks, and the load balance holds to rounding."""
    scene = pavefric.load_scene(ROOT / "inputs" / "ctm_wet.nml")
    errors = []
    for substeps in (1, 4, 16, 64):
        ds = scene.simulate(speeds_kmh=SPEEDS, time_scheme="exact", substeps=substeps,
                            tolerance=0.0, error_estimate=False, min_contacts=0)
        assert ds["exact_integrator_ran"].values.tolist() == [1, 1]
        assert ds["bearing_ran"].values.all()
        assert ds["max_balance_residual"].values.max() < 1e-12
        errors.append(np.abs(ds["mu"].values - CTM_WET_LIMIT))
        if substeps == 1:
            share = ds["film_load_share"].values
    errors = np.array(errors)
    assert np.all(errors[0] < 1.5e-4) and np.all(errors[0] > 2e-5), errors[0]
    assert np.all(errors[-1] < 5e-7), errors[-1]
    ratios = errors[:-1] / errors[1:]                 # per factor 4 in the step
    assert np.all(ratios[-1] > 10.0), ratios           # near 16 at second order
    euler = scene.simulate(speeds_kmh=SPEEDS, time_scheme="euler", tolerance=0.0,
                           error_estimate=False, min_contacts=0)
    assert np.all(np.abs(euler["mu"].values - CTM_WET_LIMIT) > 4e-3)
    np.testing.assert_allclose(share, euler["film_load_share"].values, atol=0.02)


def test_under_the_papers_film_the_default_estimate_and_tolerance_hold():
    """With time_scheme = 'exact' on a wet scene the error estimate (one pass
    at half the step, three times its change) bounds the error, and
    tolerance = 1e-6 is met (the passes' own order read from two successive
    ratios of their changes: simulate_to_tolerance)."""
    scene = pavefric.load_scene(ROOT / "inputs" / "ctm_wet.nml")
    one = scene.simulate(speeds_kmh=SPEEDS, time_scheme="exact", min_contacts=0)
    actual = np.abs(one["mu"].values - CTM_WET_LIMIT)
    estimate = one["mu_error_estimate"].values
    assert np.all(estimate >= actual) and np.all(estimate <= 3.0 * actual), (estimate, actual)
    tol = scene.simulate(speeds_kmh=SPEEDS, time_scheme="exact", tolerance=1e-6)
    assert np.all(tol["mu_error_estimate"].values <= 1e-6)
    np.testing.assert_allclose(tol["mu"].values, CTM_WET_LIMIT, rtol=0, atol=1e-6)
    assert tol["exact_integrator_ran"].values.tolist() == [1, 1]


def test_a_film_that_lifts_the_pad_only_all_but_closed_is_left_to_backward_euler():
    """A fuzz's reproducer: a 100 N pad on flat-topped texture in 3 mm of
    water. At 1 and 20 km/h the film carries it only at a mean gap of 1e-60
    and 2e-6 of the depth, where the film's load changes by its own size as
    an element passes (the linearised film was 2 orders of magnitude off at
    20 km/h, and its events ran away at 1 km/h). The exact integrator
    declines such a film (floating gap below 1e-3 of the depth): backward
    Euler runs those speeds, bit for bit as time_scheme = 'extrapolated',
    and the warning for speeds the exact integrator did not run says so."""
    x = np.arange(210)
    z = 1e-3 * np.sign(np.sin(2 * np.pi * (x + 0.5) / 20))
    kw = dict(depth=3e-3, alpha=105.0, viscosity=10.0, stiffness=3e7, load=100.0, mu_loc=0.0,
              closed=False, min_contacts=0, error_estimate=False)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        exact = pavefric.simulate(z, 0.25e-3, [1.0, 20.0], time_scheme="exact", **kw)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", pavefric.PavefricWarning)
        euler = pavefric.simulate(z, 0.25e-3, [1.0, 20.0], time_scheme="extrapolated", **kw)
    assert exact["exact_integrator_ran"].values.tolist() == [0, 0]
    for v in ("mu", "mu_hysteresis", "max_compression", "film_load_share"):
        np.testing.assert_array_equal(exact[v].values, euler[v].values, err_msg=v)
    assert any("km/h backward Euler ran at substeps = 1" in str(w.message) for w in caught)
    assert np.all(exact["max_compression"].values < 3e-3)


def test_a_flat_road_in_deep_water_floats_alike_in_both_integrators():
    """A flat closed road, 5 mm of water, 80 km/h: the film carries the pad
    alone at every position (hydroplaning_fraction 1, mu 0) in the exact
    integrator as in backward Euler."""
    z = np.zeros(256)
    kw = dict(depth=5e-3, alpha=12.0, closed=True, min_contacts=0, error_estimate=False)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", pavefric.PavefricWarning)
        exact = pavefric.simulate(z, 0.87e-3, [80.0], time_scheme="exact", **kw)
        euler = pavefric.simulate(z, 0.87e-3, [80.0], time_scheme="euler", **kw)
    assert exact["exact_integrator_ran"].values.tolist() == [1]
    for ds in (exact, euler):
        assert ds["hydroplaning_fraction"].values[0] == 1.0
        assert abs(ds["mu"].values[0]) < 1e-12
        assert ds["film_load_share"].values[0] == pytest.approx(1.0, abs=1e-12)
