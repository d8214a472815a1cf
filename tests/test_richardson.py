"""&numerics time_scheme = 'richardson': at tolerance = 0 the run reports the
Richardson value 2 mu(2s) - mu(s) of its own backward-Euler pass and its
error estimate's pass at half the step (no pass more than the default runs),
its parts alike, and twice their difference as mu_error_estimate."""
import warnings

import numpy as np
import pytest

import pavefric
from conftest import DX


def quiet(*args, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", pavefric.PavefricWarning)
        return pavefric.simulate(*args, **kw)


def euler_passes(z, speeds, **kw):
    """The two passes written out: the run's own (substeps s) and one at half
    the step, each one backward-Euler pass at the pad the run used."""
    return [quiet(z, DX, speeds, time_scheme="euler", substeps=s, min_contacts=0,
                  error_estimate=False, **kw) for s in (1, 2)]


@pytest.mark.parametrize("kw", [
    pytest.param(dict(), id="dry"),
    pytest.param(dict(viscosity=3e4, mu_loc=0.3), id="dry-viscous"),
    pytest.param(dict(depth=1e-3), id="wet-kane2017"),
    pytest.param(dict(depth=1e-3, wet_model="squeeze"), id="wet-squeeze"),
])
def test_it_is_the_two_passes_extrapolated(short_profile_m, kw):
    speeds = [1.0, 20.0, 60.0]
    ds = quiet(short_profile_m, DX, speeds, time_scheme="richardson", min_contacts=0, **kw)
    one, two = euler_passes(short_profile_m, speeds, **kw)
    assert np.all(ds["mu_extrapolated"].values == 1)
    for name in ("mu", "mu_hysteresis", "mu_adhesion"):
        want = 2.0 * two[name].values - one[name].values
        np.testing.assert_allclose(ds[name].values, want, rtol=0, atol=1e-15)
    np.testing.assert_allclose(ds["mu_hysteresis"].values + ds["mu_adhesion"].values,
                               ds["mu"].values, rtol=0, atol=1e-15)
    np.testing.assert_allclose(ds["mu_error_estimate"].values,
                               2.0 * np.abs(two["mu"].values - one["mu"].values),
                               rtol=1e-12, atol=0)
    # the default ('extrapolated') reports the run's own pass, bit for bit
    default = quiet(short_profile_m, DX, speeds, min_contacts=0, **kw)
    np.testing.assert_array_equal(default["mu"].values, one["mu"].values)
    assert not default["mu_extrapolated"].values.any()


def test_at_the_pad_min_contacts_chose():
    """The shipped compound at 0 C stands on too few elements: the default
    refines the pad (elements_per_sample 4 here) and the two passes are made
    on that pad."""
    from pavefric.studies.energy_report import DX as CTM_DX, compound, medium_profile

    z, rubber = medium_profile(), compound()
    kw = dict(mu_loc=0.0, temperature=0.0, **rubber)
    ds = quiet(z, CTM_DX, [20.0], time_scheme="richardson", **kw)
    eps = int(ds["elements_per_sample_used"].values[0])
    assert eps == 4
    one, two = (quiet(z, CTM_DX, [20.0], time_scheme="euler", substeps=s, elements_per_sample=eps,
                      min_contacts=0, error_estimate=False, **kw)["mu"].values[0] for s in (1, 2))
    assert ds["mu"].values[0] == pytest.approx(2.0 * two - one, abs=1e-15)
    assert ds["mu_extrapolated"].values[0] == 1


def test_no_local_friction_stays_non_negative(profile_m):
    """mu_loc = 0: every part of mu is >= 0 whatever the rubber, the
    temperature and the speed (a Richardson value that would make one
    negative is not reported: the run's own pass is)."""
    from test_energy import compound

    rubber = compound()
    for t in (-40.0, -20.0, 0.0, 40.0, 120.0):
        ds = quiet(profile_m, DX, [0.5, 20.0, 200.0], mu_loc=0.0, temperature=t,
                   time_scheme="richardson", **rubber)
        assert np.all(ds["mu"].values >= 0.0), (t, ds["mu"].values)
        assert np.all(ds["mu_adhesion"].values == 0.0)
        np.testing.assert_array_equal(ds["mu_hysteresis"].values, ds["mu"].values)


def test_elastic_pad_has_no_friction(profile_m):
    ds = quiet(profile_m, DX, [1.0, 20.0, 80.0], viscosity=0.0, mu_loc=0.0,
               time_scheme="richardson")
    assert np.all(np.abs(ds["mu"].values) <= 1e-9)


def test_flat_profile_gives_mu_loc_to_rounding():
    ds = quiet(np.zeros(256), DX, [1.0, 60.0], mu_loc=0.3, time_scheme="richardson")
    np.testing.assert_allclose(ds["mu"].values, 0.3, rtol=1e-13)


def test_without_the_estimates_pass_it_is_refused(short_profile_m):
    with pytest.raises(pavefric.PavefricError, match=r"time_scheme = 'richardson' with "
                       r"error_estimate = \.false\."):
        pavefric.simulate(short_profile_m, DX, [20.0], time_scheme="richardson",
                          error_estimate=False)
    # with a tolerance it is 'extrapolated' (the estimate is the tolerance's)
    a = quiet(short_profile_m, DX, [20.0], time_scheme="richardson", tolerance=1e-3,
              error_estimate=False)
    b = quiet(short_profile_m, DX, [20.0], time_scheme="extrapolated", tolerance=1e-3)
    np.testing.assert_array_equal(a["mu"].values, b["mu"].values)


def test_the_shipped_compound_is_one_bell_at_the_default_numerics():
    """docs/model.md ("Temperature, with the energy scheme"): with the default
    numerics and time_scheme = 'richardson', on inputs/profiles/ctm_medium.txt
    at 20 km/h, mu against temperature has one maximum, at 30 C, and falls
    from there to 60 C, within 0.004 of the resolved curve."""
    from pavefric.studies.energy_report import DX as CTM_DX, compound, medium_profile

    z, rubber = medium_profile(), compound()
    temps = (-20.0, 0.0, 10.0, 20.0, 30.0, 40.0, 50.0, 60.0, 80.0)
    mu = np.array([quiet(z, CTM_DX, [20.0], mu_loc=0.0, temperature=t, time_scheme="richardson",
                         **rubber)["mu"].values[0] for t in temps])
    peak = int(np.argmax(mu))
    assert temps[peak] == 30.0, mu
    assert np.all(np.diff(mu[:peak + 1]) > 0), mu
    assert np.all(np.diff(mu[peak:]) < 0), mu
    resolved = np.array([quiet(z, CTM_DX, [20.0], mu_loc=0.0, temperature=t, substeps=16,
                               elements_per_sample=4, min_contacts=0, error_estimate=False,
                               **rubber)["mu"].values[0] for t in temps[1:-1]])
    assert np.max(np.abs(mu[1:-1] - resolved)) < 0.004


def test_output_descriptions_are_whole(tmp_path):
    """The descriptions Python reads from the core (the xarray long_name,
    docs/outputs.md) are the ones the program writes to NetCDF, not cut at
    the interface's buffer (they were cut at 256 characters: mu_error_estimate's
    ended mid-sentence)."""
    import netCDF4

    from conftest import run_program, write_scene

    scene = write_scene(tmp_path, groups={"water": "depth = 1e-3"})
    out = tmp_path / "out.nc"
    proc = run_program(scene, "-o", out, cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    ds = quiet(np.sin(np.arange(256) * 0.3) * 0.5e-3, DX, [20.0], depth=1e-3)
    with netCDF4.Dataset(out) as nc:
        compared = 0
        for name, var in nc.variables.items():
            if name not in ds.variables or "long_name" not in var.ncattrs():
                continue
            assert ds[name].attrs["long_name"] == var.long_name, name
            assert ds[name].attrs.get("comment") == getattr(var, "comment", None), name
            # long_name a few words (xarray's axis label), the rest in comment
            assert len(var.long_name) <= 80, name
            if "comment" in var.ncattrs():
                assert var.comment != var.long_name, name
            compared += 1
    assert compared > 20
    assert ds["mu_error_estimate"].attrs["long_name"] == "estimated error of mu"
    assert len(ds["mu_error_estimate"].attrs["comment"]) > 300
    # and nothing the tables hold reaches the interface's buffers (4096
    # characters; a text that long would be cut without a word)
    import pavefric.core as core

    params, groups, outputs = core._tables()
    assert max(len(p.meaning) for p in params) < 4000
    assert max(len(o[7]) for o in outputs) < 4000
    assert any(len(p.meaning) > 1000 for p in params)     # the old 1024 was near


def test_series_are_the_runs_own_pass(short_profile_m):
    """With series, mu is the Richardson value but mu_inst is the run's own
    pass (as the parameter's description says): its mean is that pass's mu."""
    ds = quiet(short_profile_m, DX, [20.0], time_scheme="richardson", min_contacts=0,
               series=True)
    one, _ = euler_passes(short_profile_m, [20.0], series=True)
    np.testing.assert_array_equal(ds["mu_inst"].values, one["mu_inst"].values)
    # (the mean of a repeating lane's series exceeds its mu by the path's
    # imbalance, which the mean counts out: docs/model.md)
    np.testing.assert_allclose(ds["mu_inst"].values.mean(axis=1), one["mu"].values,
                               rtol=1e-5)
    assert ds["mu_extrapolated"].values[0] == 1
    assert abs(ds["mu"].values[0] - one["mu"].values[0]) > 1e-6


GUARD_CHECK = """
program check
   use pavefric_simulate, only: richardson
   implicit none
   double precision :: r, rh, ra
   logical :: ok
   ! a plain pair: extrapolated, parts alike
   call richardson(0.5d0, 0.3d0, 0.2d0, 0.6d0, 0.35d0, 0.25d0, r, rh, ra, ok)
   print *, r, rh, ra, merge(1, 0, ok)
   ! hysteresis 0.3 then 0.1: 2 b - a = -0.1 < 0 where both are >= 0
   call richardson(0.3d0, 0.3d0, 0.0d0, 0.1d0, 0.1d0, 0.0d0, r, rh, ra, ok)
   print *, merge(1, 0, ok)
   ! adhesion 0.4 then 0.15, hysteresis fine
   call richardson(0.6d0, 0.2d0, 0.4d0, 0.4d0, 0.25d0, 0.15d0, r, rh, ra, ok)
   print *, merge(1, 0, ok)
   ! a part already negative in a pass (the paper's scheme can give one):
   ! the guard is not its business
   call richardson(0.1d0, -0.2d0, 0.3d0, 0.1d0, -0.05d0, 0.15d0, r, rh, ra, ok)
   print *, merge(1, 0, ok)
end program check
"""


def test_the_guard_keeps_a_non_negative_part_so(tmp_path):
    """The Richardson value and its guard, shared by time_scheme =
    'richardson' (tolerance = 0) and the tolerance's 'extrapolated': not
    usable where a part both passes have >= 0 would turn negative. (No
    scene found in a search of dry, wet and compound runs makes the passes
    fall that fast, so the guard is checked on the routine itself.)"""
    from test_reynolds import _compile_and_run

    out = [float(v) for v in _compile_and_run(tmp_path, GUARD_CHECK)]
    np.testing.assert_allclose(out[:3], [0.7, 0.4, 0.3], rtol=0, atol=1e-15)
    assert out[3:] == [1.0, 0.0, 0.0, 1.0]
