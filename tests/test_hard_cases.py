"""Hard cases: each runs, and its result is finite and behaves as
docs/numerics.md says (or a clear error is raised)."""
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import pavefric
from conftest import run_program, write_scene

DX = 0.87e-3
SPEEDS = [0.0, 1e-6, 20.0, 60.0, 1000.0]


@pytest.fixture(scope="module")
def z():
    from pavefric.surfaces import spectral_profile

    return spectral_profile(1024, DX, rms=0.5e-3, seed=3)


def finite(ds):
    for name in ("mu", "max_balance_residual", "mean_hydro_load", "max_compression",
                 "wet_fraction", "hydroplaning_fraction"):
        assert np.all(np.isfinite(ds[name].values)), name
    assert np.all(ds["mu"].values >= 0)
    assert np.all(ds["max_balance_residual"].values <= 1e-12)


@pytest.mark.parametrize("depth", [0.0, 1e-3])
def test_facets_steeper_than_theta_max(depth):
    ramp = np.tan(np.radians(70)) * DX * np.arange(10)
    saw = np.tile(np.concatenate([ramp, ramp[::-1]]), 30)
    ds = pavefric.simulate(saw, DX, SPEEDS, mu_loc=0.5, depth=depth)
    finite(ds)
    assert ds["n_clamped"].values[0] > 0
    # a clamped facet pushes with tan(85 deg) at most
    assert np.all(ds["mu"].values <= np.tan(np.radians(85)))


@pytest.mark.parametrize("depth", [0.0, 1e-3])
def test_vertical_step(z, depth):
    step = z.copy()
    step[512:] += 5e-3                       # a 5 mm cliff (and its wrap-around)
    ds = pavefric.simulate(step, DX, SPEEDS, depth=depth)
    finite(ds)
    assert ds["n_clamped"].values[0] > 0
    assert ds["max_compression"].values[0] > 4e-3   # the pad climbs onto the step


@pytest.mark.parametrize("depth", [0.0, 1e-3])
def test_isolated_spike(z, depth):
    spike = z.copy()
    spike[300] += 100 * z.std()
    finite(pavefric.simulate(spike, DX, SPEEDS, depth=depth, series=True))
    # while the spike is under the pad, the whole load rests on it: one
    # contact (at one element per sample: min_contacts = 0; the default
    # refines the pad where it stood on fewer than 4 on average, and the
    # spike, interpolated linearly, then spans more than one element)
    ds = pavefric.simulate(spike, DX, SPEEDS, depth=depth, series=True, min_contacts=0)
    finite(ds)
    assert ds["contact_elements"].values[0].min() == 1


def test_perfectly_flat_profile():
    ds = pavefric.simulate(np.zeros(500), DX, SPEEDS, mu_loc=0.4)
    finite(ds)
    np.testing.assert_allclose(ds["mu"].values, 0.4, rtol=1e-14)
    # wet: no valley holds the water, the film closes, the bearing carries
    # the whole load at any speed > 0 (Wh -> infinity as Hout -> 0)
    wet = pavefric.simulate(np.zeros(500), DX, SPEEDS, mu_loc=0.4, depth=1e-3)
    finite(wet)
    assert wet["mu"].values[0] == pytest.approx(0.4, rel=1e-14)
    # at 1e-6 km/h the film that carries W is thinner than any double: the
    # pad rests on it with a penetration of order 1e-61 m
    assert wet["mu"].values[1] < 1e-12
    assert np.all(wet["mu"].values[2:] == 0.0)
    assert np.all(wet["hydroplaning_fraction"].values[2:] == 1.0)


def test_one_element_pad(z):
    ds = pavefric.simulate(z, DX, SPEEDS, length=DX)
    finite(ds)
    assert ds.attrs["pad_elements"] == 1
    # one element carries W on each facet: mu is the mean of tan(theta)
    flat = pavefric.simulate(np.zeros(50), DX, SPEEDS, length=DX, mu_loc=0.3)
    np.testing.assert_allclose(flat["mu"].values, 0.3, rtol=1e-14)


def test_load_compressing_past_the_thickness(tmp_path, z):
    ds = pavefric.simulate(z, DX, SPEEDS, load=1e5)
    finite(ds)
    assert np.all(ds["max_compression"].values > 0.006)
    scene = write_scene(tmp_path, profile=z, groups={"pad": "load = 1e5"})
    r = run_program(scene, "-o", tmp_path / "o.nc")
    assert r.returncode == 0
    assert "warning" in r.stderr and "&pad thickness = 0.006" in r.stderr


@pytest.mark.parametrize("depth", [0.0, 1e-3])
def test_tiny_load(z, depth):
    ds = pavefric.simulate(z, DX, SPEEDS, load=1e-9, depth=depth)
    finite(ds)
    assert ds["max_compression"].values[0] < 1e-9


@pytest.mark.parametrize("depth", [0.0, 1e-3])
def test_extreme_speeds(z, depth):
    ds = pavefric.simulate(z, DX, [0.0, 1e-6, 1000.0], depth=depth)
    finite(ds)
    assert ds["mu"].values[1] == pytest.approx(ds["mu"].values[0], abs=1e-9)
    if depth > 0:
        assert ds["hydroplaning_fraction"].values[2] > 0.5     # 1000 km/h floats
        assert ds["bearing_evaluations"].values[0] == 0


@pytest.mark.parametrize("viscosity", [0.0, 1e12])
@pytest.mark.parametrize("depth", [0.0, 1e-3])
def test_extreme_viscosity(z, viscosity, depth):
    ds = pavefric.simulate(z, DX, SPEEDS, viscosity=viscosity, depth=depth)
    finite(ds)


@pytest.mark.parametrize("stiffness", [1e4, 1e14])
@pytest.mark.parametrize("depth", [0.0, 1e-3])
def test_extreme_stiffness(z, stiffness, depth):
    ds = pavefric.simulate(z, DX, SPEEDS, stiffness=stiffness, depth=depth)
    finite(ds)


def test_bearing_near_a_equal_one_and_huge_a():
    from pavefric.core import hydro_load

    h_in = 1e-3
    wh, dwh = hydro_load([h_in / (1 + 1e-12), h_in / 1e12], h_in, prefactor=2.0)
    assert np.all(np.isfinite(wh)) and np.all(np.isfinite(dwh))
    # a = 1 + e: Wh ~ P e / (12 Hin^2);  a = 1e12: Wh ~ P (ln a - 2) / Hin^2
    e = (h_in - h_in / (1 + 1e-12)) / (h_in / (1 + 1e-12))
    assert wh[0] == pytest.approx(2.0 * e / 12 / h_in**2, rel=1e-9)
    assert wh[1] == pytest.approx(2.0 * (np.log(1e12) - 2) / h_in**2, rel=1e-9)


def test_complete_hydroplaning(z):
    # deep water (valleys under the pad all flooded) and a strong bearing
    ds = pavefric.simulate(z, DX, [20.0, 60.0], depth=5e-3, alpha=1e6, series=True)
    finite(ds)
    assert np.all(ds["mu"].values == 0.0)                 # exactly 0, no NaN
    assert np.all(ds["hydroplaning_fraction"].values == 1.0)
    assert np.all(ds["contact_elements"].values == 0)
    np.testing.assert_allclose(ds["hydro_load"].values, 11.8, rtol=1e-12)


@pytest.mark.parametrize("series", [False])
def test_ten_million_points_memory_scales_with_profile(series):
    """Peak memory of a 10-million-point profile is proportional to the
    profile, not to profile x pad: a 4 times longer pad costs almost nothing."""
    script = textwrap.dedent("""
        import resource, sys, numpy as np, pavefric
        n = 10_000_000
        z = 1e-4 * np.sin(np.arange(n) * 0.37) + 2e-4 * np.sin(np.arange(n) * 0.051)
        base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
        ds = pavefric.simulate(z, 0.87e-3, [60.0], closed=False, length=float(sys.argv[1]))
        assert np.isfinite(ds["mu"].values).all()
        peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
        print((peak - base) * 1024 / n)
    """)
    per_point = {}
    for length in (0.02, 0.08):
        r = subprocess.run([sys.executable, "-c", script, str(length)], capture_output=True,
                           text=True, timeout=600)
        assert r.returncode == 0, r.stderr
        per_point[length] = float(r.stdout.strip())
    # the core holds heights, facet tangents and clamp flags, a few copies:
    # tens of bytes per point; profile x pad would be 8 x 92 = 736 bytes
    assert per_point[0.08] < 100
    assert per_point[0.08] - per_point[0.02] < 8


def _bearing_g_decimal(h_in: float, h_out: float):
    """g(a) = a^2 B(a) and dg/da of Eq. 15 in 60-digit decimal arithmetic:
    an independent reference where doubles overflow (a^2 beyond 1e308)."""
    from decimal import Decimal, getcontext

    getcontext().prec = 60
    a = Decimal(h_in) / Decimal(h_out)
    e = a - 1
    p = a.ln() - 2 * e / (a + 1)
    b = p / e**2
    db = 1 / (a * (a + 1) ** 2) - 2 * p / e**3
    return a, a * a * b, 2 * a * b + a * a * db


def test_bearing_for_films_thinner_than_1e_100_of_the_water():
    # Reproducer: on a flat wet profile at 1e-6 km/h the pad sinks onto a
    # film of ~1e-61 m; the warm-started wet balance (issue 23) probes films
    # of 1e-160 m on the way, where a^2 and e^2 overflowed and Eq. 15 gave
    # Inf x 0 = NaN (the half-step estimate pass then failed). Wh and its
    # derivative must be finite, agree with a 60-digit reference, and keep
    # rising as the film thins, across the scaled branch (e > 1e100).
    from pavefric.core import hydro_load

    h_in, prefactor = 1e-3, 2.0
    h = h_in * np.logspace(-20, -240, 45)
    h = np.sort(np.concatenate([h, [h_in / (1 + 1e100) * (1 + 1e-15), h_in / (1 + 1e100)]]))
    wh, dwh = hydro_load(h, h_in, prefactor=prefactor)
    assert np.all(np.isfinite(wh)) and np.all(np.isfinite(dwh))
    # thinner film, more load (the two films either side of the scaled
    # branch's threshold, 1e-15 apart, give the same load to rounding:
    # measured 1.3e-16 relative)
    assert np.all(np.diff(wh) <= 1e-15 * wh[1:]) and np.all(dwh < 0)
    assert np.count_nonzero(np.diff(wh) > 0) <= 1
    assert np.all(np.diff(wh[h < 1e-104]) < 0) and np.all(np.diff(wh[h > 1e-102]) < 0)
    for hout, w, dw in zip(h, wh, dwh):
        a, g, dg = _bearing_g_decimal(h_in, hout)
        assert w == pytest.approx(prefactor / h_in**2 * float(g), rel=1e-12), hout
        expect = -(prefactor / h_in**3) * float(dg * a) * float(a)
        assert dw == pytest.approx(max(expect, -np.finfo(float).max), rel=1e-9), hout


def test_flat_wet_profile_at_a_crawl_estimates_its_error():
    # the same scene through the default run: its half-step pass must run
    # (it failed with a NaN bearing load), both passes finite
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error", pavefric.PavefricWarning)
        warnings.filterwarnings("ignore", message=".*RMS height is 0 m.*")
        # (the film keeps the whole load at this crawl: said, and meant here)
        warnings.filterwarnings("ignore", message=".*carries 100 % of the load at this "
                                "creeping speed.*")
        ds = pavefric.simulate(np.zeros(500), DX, [1e-6], mu_loc=0.4, depth=1e-3)
    finite(ds)
    assert np.isfinite(ds["mu_error_estimate"].values[0])
    assert ds["mu"].values[0] < 1e-12
    for substeps in (2, 4):
        finite(pavefric.simulate(np.zeros(500), DX, [1e-6], mu_loc=0.4, depth=1e-3,
                                 substeps=substeps, error_estimate=False))


@pytest.mark.parametrize("closed", [False, True])
def test_a_long_memory_under_a_tiny_load_balances_to_rounding(closed):
    """An attack's reproducer (2026-12-06): a Kelvin-Voigt pad of very long
    memory (viscosity 1e10 against stiffness 1.4e8) under a load of 1e-5 N
    keeps many clearances within 1e-20 m of the root. The dry balance's
    first Newton step, taken from the guess's sums and not confirmed (its
    terms far above the root), had its set compared with the guess's, not
    with its own, and rounding had moved it past such clearances: the
    balance missed by up to 5e-6 of the load. Every root is now taken from
    the set of a point a pass has seen: the residual is rounding, at every
    speed, whichever speeds share the call."""
    import warnings

    z = np.zeros(40)
    z[[3, 11, 15, 31]] = [1e-4, 4e-4, 2e-4, 2e-4]
    speeds = [40.0, 60.0, 100.0, 120.0, 200.0, 300.0]
    kw = dict(closed=closed, length=0.005, load=1e-5, stiffness=1.4e8, viscosity=1e10,
              mu_loc=0.0, time_scheme="euler", error_estimate=False, min_contacts=0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")      # (a memory that outlasts the spin-up says so)
        ds = pavefric.simulate(z, 0.87e-3, speeds, **kw)
        alone = pavefric.simulate(z, 0.87e-3, [100.0], **kw)
    assert np.all(ds["max_balance_residual"].values <= 1e-12), ds["max_balance_residual"].values
    assert alone["max_balance_residual"].values[0] <= 1e-12


@pytest.mark.parametrize("name, value, bound", [("load", 1e-320, "1e-12"), ("load", 1e-300, "1e-12"),
                                                ("width", 1e-305, "1e-6"), ("width", 1e-315, "1e-6")])
def test_a_load_or_width_beyond_double_precision_is_refused(z, name, value, bound):
    """An attack (2026-12-07): &pad load = 1e-320 N (within its range then)
    made the pushes subnormal and the friction 0/0 (the core's own 'please
    report this scene'), 1e-322 read mu = 0 with hydroplaning on a dry road;
    width = 1e-305 m wrote mu = -7.6e270, 1e-315 stopped on an internal
    error. The ranges now start where the arithmetic holds: a clear error
    naming the variable, its value and the bound."""
    with pytest.raises(pavefric.PavefricError) as info:
        pavefric.simulate(z, DX, [20.0], **{name: value})
    assert f"&pad {name} = {value!r}: must be finite and >= {bound}" in str(info.value)
    # the bound itself runs, finite
    finite(pavefric.simulate(z, DX, [20.0], **{name: float(bound)}))
