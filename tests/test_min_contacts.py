"""&numerics min_contacts (issues 20 and 23): a pad that stands on one or two
of its elements gives a friction set by the elements' size, not the road's
(docs/accuracy.md, "The pad's resolution"); with min_contacts = n each speed
where it stood on fewer than n elements in contact is rerun with the
elements halved until it stands on n (at most 4 times), and that run is
reported, its elements_per_sample in elements_per_sample_used. 4 is the
default; 0 is the paper's discretisation."""
import warnings

import numpy as np
import pytest
import xarray as xr

import pavefric
from conftest import ROOT, cold_compound_batch, run_cold_batch, run_program, write_scene

SPEEDS = [5.0, 20.0, 80.0]


def _compound():
    from pavefric.rubber import compound
    return {k: v for k, v in compound(ROOT / "inputs" / "rubber" / "tread_compound.nml").items()
            if k != "temperature"}


def _quiet(*args, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", pavefric.PavefricWarning)
        return pavefric.simulate(*args, **kw)


def _contacts(ds, k):
    """Elements in contact at speed k of a run made at one elements_per_sample."""
    return float(ds["contact_fraction"].values[k]) * ds.attrs["pad_elements"]


@pytest.fixture(scope="module")
def cold(profile_m):
    """The shipped compound at 0 C, mu_loc = 0: the pad on 1.2 to 1.5 of
    its 23 elements (the issue-20 reproducer's regime)."""
    return dict(mu_loc=0.0, temperature=0.0, **_compound())


def test_each_speed_is_the_run_at_the_elements_it_names(profile_m, cold):
    """Every per-speed output at speed j is the one of a plain run at
    elements_per_sample_used[j]; there the pad stands on at least 4
    elements, at half of it on fewer (so no more refinement than needed)."""
    ds = _quiet(profile_m, 0.87e-3, SPEEDS, min_contacts=4, **cold)
    used = ds["elements_per_sample_used"].values
    assert used.dtype.kind == "i"
    assert np.all(used >= 2) and np.all(used <= 16)
    for k, speed in enumerate(SPEEDS):
        own = _quiet(profile_m, 0.87e-3, [speed], elements_per_sample=int(used[k]),
                     error_estimate=False, min_contacts=0, **cold)
        half = _quiet(profile_m, 0.87e-3, [speed], elements_per_sample=int(used[k]) // 2,
                      error_estimate=False, min_contacts=0, **cold)
        for name in ("mu", "mu_hysteresis", "mu_adhesion", "contact_fraction",
                     "max_compression", "max_balance_residual", "memory_updates"):
            assert ds[name].values[k] == own[name].values[0], (name, speed)
        assert _contacts(own, 0) >= 4.0 > _contacts(half, 0), speed
    # the parts still add up, and mu_loc = 0 leaves no adhesion
    assert np.allclose(ds["mu_hysteresis"] + ds["mu_adhesion"], ds["mu"], rtol=0, atol=1e-12)
    assert np.all(ds["mu_adhesion"].values == 0.0)


def test_the_refined_pad_is_the_default(profile_m, cold):
    """min_contacts = 4 is the default: the same numbers as naming it.
    min_contacts = 0 runs the elements as given (the paper's
    discretisation): elements_per_sample_used the value given, and a
    friction far below the refined one on this pad (the reason for the
    default: 0.011 against 0.043 at 20 km/h)."""
    default = _quiet(profile_m, 0.87e-3, SPEEDS, **cold)
    named = _quiet(profile_m, 0.87e-3, SPEEDS, min_contacts=4, **cold)
    paper = _quiet(profile_m, 0.87e-3, SPEEDS, min_contacts=0, **cold)
    xr.testing.assert_identical(default.drop_attrs(), named.drop_attrs())
    assert np.all(paper["elements_per_sample_used"].values == 1)
    assert np.all(paper["mu"].values < 0.5 * default["mu"].values)
    assert np.all(default["elements_per_sample_used"].values >= 2)
    # the default costs no more passes: its levels are the ones the
    # estimate at min_contacts = 0 runs (the same elements_per_sample at last)
    assert np.all(paper["estimate_elements_per_sample"].values
                  >= default["elements_per_sample_used"].values)


def test_speeds_on_enough_elements_are_left_alone(profile_m):
    """The paper's rubber stands on 4 to 15 elements: min_contacts = 4
    changes nothing there, not a bit."""
    plain = _quiet(profile_m, 0.87e-3, SPEEDS, min_contacts=0)
    asked = _quiet(profile_m, 0.87e-3, SPEEDS, min_contacts=4)
    assert all(_contacts(plain, k) >= 4.0 for k in range(len(SPEEDS)))
    for name in ("mu", "mu_hysteresis", "mu_error_estimate", "estimate_elements_per_sample"):
        np.testing.assert_array_equal(plain[name].values, asked[name].values)
    assert np.all(asked["elements_per_sample_used"].values == 1)


def test_the_estimate_is_the_refined_runs_own(profile_m, cold):
    """mu_error_estimate is the error of the reported (refined) mu: on 4
    contacts or more, three times its change at half the step; it is no
    larger than the unrefined run's estimate, which carried the elements'
    error; and the refined mu is the one the warning of a run at
    min_contacts = 0 named."""
    with pytest.warns(pavefric.PavefricWarning, match=r"gave mu = (\d\.\d+)") as said:
        default = pavefric.simulate(profile_m, 0.87e-3, [20.0], min_contacts=0, **cold)
    named = [w for w in said if "gave mu" in str(w.message)][0]
    ds = _quiet(profile_m, 0.87e-3, [20.0], min_contacts=4, **cold)
    used = int(ds["elements_per_sample_used"].values[0])
    half_step = _quiet(profile_m, 0.87e-3, [20.0], elements_per_sample=used, substeps=2,
                       time_scheme="euler", error_estimate=False, min_contacts=0, **cold)
    mu = ds["mu"].values[0]
    assert ds["mu_error_estimate"].values[0] == pytest.approx(
        3.0 * abs(mu - half_step["mu"].values[0]), rel=1e-12, abs=1e-15)
    assert int(ds["estimate_elements_per_sample"].values[0]) == used
    assert ds["mu_error_estimate"].values[0] < default["mu_error_estimate"].values[0]
    assert f"gave mu = {mu:.4g}" in str(named.message)
    assert f"elements_per_sample = {used}" in str(named.message)
    assert "min_contacts" in str(named.message)      # the warning names the knob


def test_series_are_each_speeds_own_held_on_the_finest_positions(profile_m, cold):
    """With series each speed's means are its own run's, as without (asking
    for series changes no mean), and its series are its own run's, each
    value held over the positions of the finest run (closed profile: 2^k of
    them), so their mean is its own run's too."""
    speeds = [5.0, 20.0, 80.0]
    plain = _quiet(profile_m, 0.87e-3, speeds, temperature=30.0,
                   **{k: v for k, v in cold.items() if k != "temperature"})
    ds = _quiet(profile_m, 0.87e-3, speeds, series=True, temperature=30.0,
                **{k: v for k, v in cold.items() if k != "temperature"})
    used = ds["elements_per_sample_used"].values
    assert used.min() < used.max()                    # levels differ between speeds
    np.testing.assert_array_equal(ds["mu"].values, plain["mu"].values)
    np.testing.assert_array_equal(used, plain["elements_per_sample_used"].values)
    n_fine = ds.sizes["position"]
    for k, speed in enumerate(speeds):
        own = _quiet(profile_m, 0.87e-3, [speed], elements_per_sample=int(used[k]),
                     series=True, error_estimate=False, min_contacts=0, temperature=30.0,
                     **{q: v for q, v in cold.items() if q != "temperature"})
        factor = n_fine // own.sizes["position"]
        assert factor * own.sizes["position"] == n_fine and factor == used.max() // used[k]
        for name in ("mu_inst", "hydro_load", "penetration", "contact_elements"):
            held = ds[name].isel(speed_kmh=k).values.reshape(-1, factor)
            assert np.all(held == held[:, :1]), name
            np.testing.assert_array_equal(held[:, 0], own[name].isel(speed_kmh=0).values)
        np.testing.assert_allclose(ds["mu_inst"].isel(speed_kmh=k).values.mean(),
                                   ds["mu"].values[k], rtol=1e-12)
    finest = _quiet(profile_m, 0.87e-3, [5.0], elements_per_sample=int(used.max()),
                    series=True, error_estimate=False, min_contacts=0, **cold)
    np.testing.assert_array_equal(ds["position"].values, finest["position"].values)
    assert ds.attrs["pad_elements"] == finest.attrs["pad_elements"]


def test_a_target_out_of_reach_says_so(profile_m, cold):
    """A pad of 23 elements cannot stand on 1000: the elements are refined
    4 times (elements_per_sample 16), the results are that run's, finite,
    and a warning names the speed, what was reached and what to change."""
    with pytest.warns(pavefric.PavefricWarning,
                      match=r"min_contacts = 1000 not reached at 20 km/h.*elements_per_sample "
                            r"= 16.*stood on"):
        ds = pavefric.simulate(profile_m, 0.87e-3, [20.0], min_contacts=1000,
                               error_estimate=False, **cold)
    assert int(ds["elements_per_sample_used"].values[0]) == 16
    assert np.isfinite(ds["mu"].values[0])
    assert "min_contacts = 1000 not reached" in ds.attrs["warnings"]


def test_a_profile_too_short_to_refine_keeps_its_elements_and_says_so(profile_m, cold):
    """An open profile with no room for twice the elements (a pad of 22.4
    samples: 22 elements, 45 at elements_per_sample = 2, which stand on 23
    open points at one position, refused): the default's refinement cannot
    be made, the results are those of the elements given (bit for bit the
    run at min_contacts = 0), and a warning names min_contacts, the speed
    and the input check that refused it."""
    kw = dict(closed=False, error_estimate=False, length=22.4 * 0.87e-3, **cold)
    with pytest.warns(pavefric.PavefricWarning,
                      match=r"&numerics min_contacts = 4: the pad's elements could not be "
                            r"refined beyond elements_per_sample = 1 at 20 km/h.*its check said"):
        ds = pavefric.simulate(profile_m[:23], 0.87e-3, [20.0], **kw)
    paper = _quiet(profile_m[:23], 0.87e-3, [20.0], min_contacts=0, **kw)
    assert int(ds["elements_per_sample_used"].values[0]) == 1
    assert ds["mu"].values[0] == paper["mu"].values[0]
    assert "min_contacts = 4" in ds.attrs["warnings"]


def test_with_a_tolerance_the_refined_pad_is_converged_in_time(profile_m, cold):
    """min_contacts and tolerance together: the pad refined, then the step
    halved at that pad until the tolerance is met; the tolerance's warning
    that it does not cover a pad on few elements is gone."""
    with warnings.catch_warnings(record=True) as said:
        warnings.simplefilter("always", pavefric.PavefricWarning)
        ds = pavefric.simulate(profile_m, 0.87e-3, [20.0], min_contacts=4, tolerance=1e-3,
                               **cold)
    assert not any("bounds the error from the time step only" in str(w.message) for w in said)
    used = int(ds["elements_per_sample_used"].values[0])
    own = _quiet(profile_m, 0.87e-3, [20.0], elements_per_sample=used, tolerance=1e-3,
                 min_contacts=0, **cold)
    assert ds["mu"].values[0] == own["mu"].values[0]
    assert ds["mu_error_estimate"].values[0] <= 1e-3
    assert ds["substeps_used"].values[0] == own["substeps_used"].values[0]


@pytest.mark.parametrize("value", ["-1", "1001", "2.5", "'four'"])
def test_a_bad_value_names_the_variable(tmp_path, value):
    """Bad input: a clear error naming the group, the variable and the value,
    no output written."""
    path = write_scene(tmp_path, groups={"numerics": f"min_contacts = {value}"})
    proc = run_program(path, "-o", tmp_path / "out.nc")
    assert proc.returncode != 0
    assert "&numerics" in proc.stderr and "min_contacts" in proc.stderr, proc.stderr
    assert not list(tmp_path.glob("*.nc"))


def test_the_program_and_the_batch_record_it(tmp_path, profile_m):
    """The program's output and a batch's carry elements_per_sample_used
    per speed (per depth and profile in a batch), equal to the single runs';
    a batch at min_contacts = 0 records the value given."""
    rubber = cold_compound_batch(tmp_path, profile_m)
    d = tmp_path / "p"
    for label, numerics in (("resolved", ""), ("paper", "&numerics min_contacts = 0 /\n")):
        with xr.open_dataset(run_cold_batch(tmp_path, label, numerics + rubber)) as ds:
            used = ds["elements_per_sample_used"].transpose(
                "profile", "water_depth", "speed_kmh").values
            mu = ds["mu"].transpose("profile", "water_depth", "speed_kmh").values
            names = [str(n) for n in ds["profile_name"].values]
        if label == "paper":
            assert np.all(used == 1)
            continue
        assert np.all(used >= 2), used
        for i, name in enumerate(names):
            one = pavefric.read_profile(d / f"{name.split('/')[-1]}.txt")
            single = _quiet(one.heights, one.dx, [20.0, 60.0], mu_loc=0.0, temperature=0.0,
                            min_contacts=4, **_compound())
            np.testing.assert_array_equal(used[i, 0], single["elements_per_sample_used"].values)
            np.testing.assert_array_equal(mu[i, 0], single["mu"].values)


def test_the_program_writes_it(tmp_path):
    """A scene's NetCDF output has elements_per_sample_used, with its
    meaning, on the speed dimension."""
    path = write_scene(tmp_path, groups={"numerics": "min_contacts = 4"})
    r = run_program(path, "-o", tmp_path / "out.nc")
    assert r.returncode == 0, r.stderr
    with xr.open_dataset(tmp_path / "out.nc") as ds:
        var = ds["elements_per_sample_used"]
        assert var.dims == ds["mu"].dims
        assert "min_contacts" in var.attrs["comment"]
        assert var.attrs["long_name"] == "elements_per_sample of the run each speed's results come from"
        assert np.all(var.values >= 1)


@pytest.mark.parametrize("surface", ["GSP", "GSS", "GSSB", "RSBA", "MCA", "VTAC"])
def test_on_the_paper_surfaces_the_refined_pad_is_closer_and_bounded(surface):
    """The test set of docs/accuracy.md's third table ("The pad's
    resolution"): the shipped compound at 0 C on the paper's surfaces stands
    on 1.1 to 1.3 elements; with min_contacts = 4 (the default) its mu is at
    least 3 times closer to the resolved one than at min_contacts = 0 (4.7
    to 10.6 times in the table), and its estimate bounds its error."""
    scene = pavefric.load_scene(ROOT / "inputs" / "surfaces" / f"{surface}.nml")
    kw = dict(speeds_kmh=[20.0], mu_loc=0.0, temperature=0.0, depth=0.0, **_compound())
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", pavefric.PavefricWarning)
        default = scene.simulate(min_contacts=0, **kw)
        ds = scene.simulate(**kw)
        resolved = scene.simulate(substeps=8, elements_per_sample=16, error_estimate=False,
                                  **kw)["mu"].values[0]
    actual = abs(ds["mu"].values[0] - resolved)
    assert int(ds["elements_per_sample_used"].values[0]) >= 4
    assert 3.0 * actual < abs(default["mu"].values[0] - resolved), (surface, actual)
    assert actual <= ds["mu_error_estimate"].values[0] <= 3.0 * actual + 1e-3, surface
