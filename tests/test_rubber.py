"""The generalised Maxwell rubber and temperature (issue 14), its must-shows:
1. time-temperature superposition holds exactly on dry scenes;
2. the two limits of an arm (relaxation times -> 0: the elastic pad of
   `stiffness`; -> infinity: of `stiffness` plus the arms);
3. on a sinusoid in full contact the friction is the closed form from the
   loss modulus, mu = N l dx k A^2 E''(kV) / (2W), to second order in k dx,
   and the scheme's own discrete form to rounding;
4. extreme relaxation times and stiffnesses give finite results or a clean
   error;
and: program = Python = C API on a Maxwell scene at another temperature, the
cross-checks of the &rubber group, `python -m pavefric prony`. The default
(Kelvin-Voigt at the reference temperature) is the 0.1.0 record bit for bit:
tests/test_regression.py."""
from __future__ import annotations

import os
import subprocess
import sys
import warnings

import numpy as np
import pytest
import xarray as xr

import pavefric
from conftest import DX, ROOT, run_program, write_scene

COMPOUND = ROOT / "inputs" / "rubber" / "tread_compound.nml"
DMA = ROOT / "inputs" / "data" / "tread_compound_dma.csv"
THREE = dict(rubber_model="maxwell", stiffness=1.4e8, prony_stiffness=[1e8, 3e8, 2e8],
             prony_times=[1e-5, 1e-4, 1e-3])


def log10_at(t, tref=20.0, c1=8.86, c2=101.6):
    """WLF, written from MODEL.md section 9 (not the package's function)."""
    return -c1 * (t - tref) / (c2 + t - tref)


def quiet(fn, *args, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", pavefric.PavefricWarning)
        return fn(*args, **kw)


@pytest.fixture(scope="module")
def compound():
    from pavefric.rubber import compound as read

    c = read(COMPOUND)
    c.pop("temperature")
    return c


# --- must-show 1: time-temperature superposition --------------------------------

@pytest.mark.parametrize("surface", ["GSSB", "MCA", "VTAC"])
@pytest.mark.parametrize("law", ["maxwell", "kelvin_voigt"])
def test_time_temperature_superposition_is_exact_on_dry_scenes(surface, law, compound):
    """mu(T, V) = mu(Tref, V a_T): the rubber enters a dry scene only through
    V tau_k(T) = V a_T tau_k (Kelvin-Voigt: C(T) V = a_T C V)."""
    scene = pavefric.load_scene(ROOT / "inputs" / "surfaces" / f"{surface}.nml")
    rubber = compound if law == "maxwell" else dict(viscosity=3e3, rubber_model="kelvin_voigt")
    base = {k: v for k, v in scene.parameters.items() if k not in rubber and k != "temperature"}
    base["depth"] = 0.0
    speeds = np.array([0.0, 1.0, 7.0, 20.0, 45.0, 80.0])
    worst = 0.0
    for t in (0.0, 10.0, 35.0, 60.0):
        a_t = 10.0 ** log10_at(t)
        at_t = quiet(pavefric.simulate, scene.heights, scene.dx, speeds, temperature=t,
                     **base, **rubber)
        at_ref = quiet(pavefric.simulate, scene.heights, scene.dx, speeds * a_t,
                       temperature=20.0, **base, **rubber)
        # not trivially equal: the temperature changes friction
        plain = quiet(pavefric.simulate, scene.heights, scene.dx, speeds, temperature=20.0,
                      **base, **rubber)
        assert np.max(np.abs(plain["mu"].values[1:] - at_t["mu"].values[1:])) > 1e-4
        np.testing.assert_allclose(at_t["mu"].values, at_ref["mu"].values, rtol=1e-12, atol=0)
        np.testing.assert_allclose(at_t["max_compression"].values,
                                   at_ref["max_compression"].values, rtol=1e-11, atol=0)
        worst = max(worst, float(np.max(np.abs(at_t["mu"].values / at_ref["mu"].values - 1))))
    assert worst < 1e-12


def test_superposition_does_not_hold_wet_and_the_docs_say_why(compound):
    """The water's film does not follow the rubber's shift: wet scenes are not
    superposed (docs/rubber.md says which quantities scale)."""
    scene = pavefric.load_scene(ROOT / "inputs" / "surfaces" / "GSSB.nml")
    base = {k: v for k, v in scene.parameters.items() if k not in compound and
            k != "temperature"}
    a_t = 10.0 ** log10_at(0.0)
    at_t = quiet(pavefric.simulate, scene.heights, scene.dx, [40.0], temperature=0.0, **base,
                 **compound)
    at_ref = quiet(pavefric.simulate, scene.heights, scene.dx, [40.0 * a_t], temperature=20.0,
                   **base, **compound)
    assert abs(at_t["mu"].values[0] - at_ref["mu"].values[0]) > 1e-3


def test_at_the_reference_temperature_the_wlf_constants_change_nothing(profile_m):
    """a_T = 1 exactly at T = Tref, whatever Tref, C1 and C2: the default's bits."""
    speeds = [0.0, 3.0, 20.0, 80.0]
    ref = pavefric.simulate(profile_m, DX, speeds, series=True, depth=1e-3)
    other = pavefric.simulate(profile_m, DX, speeds, series=True, depth=1e-3, temperature=-5.0,
                              reference_temperature=-5.0, wlf_c1=30.0, wlf_c2=40.0)
    for name in ("mu", "mu_inst", "penetration", "hydro_load", "max_compression"):
        np.testing.assert_array_equal(ref[name].values, other[name].values, err_msg=name)


def test_temperature_shifts_the_kelvin_voigt_retardation_time(profile_m):
    """Kelvin-Voigt at T = C scaled by a_T at Tref, to the bit (C a_T is the
    same double both ways)."""
    a_t = 10.0 ** log10_at(-10.0)
    c = 2.5e3
    warm = pavefric.simulate(profile_m, DX, [20.0, 60.0], viscosity=c, temperature=-10.0)
    scaled = pavefric.simulate(profile_m, DX, [20.0, 60.0], viscosity=c * a_t)
    np.testing.assert_allclose(warm["mu"].values, scaled["mu"].values, rtol=1e-13)


# --- must-show 2: the two limits of an arm -------------------------------------

@pytest.mark.parametrize("depth", [0.0, 1e-3])
@pytest.mark.parametrize("arms", [[2e8], [1e8, 3e8, 2e8]])
def test_fast_arms_leave_the_elastic_pad_of_stiffness(profile_m, depth, arms):
    """tau -> 0: every arm relaxes within a step (E = G = 0 to rounding)."""
    speeds = [0.0, 1.0, 20.0, 80.0]
    mx = quiet(pavefric.simulate, profile_m, DX, speeds, series=True, depth=depth,
               rubber_model="maxwell", stiffness=1.4e8, prony_stiffness=arms,
               prony_times=[1e-30] * len(arms))
    kv = pavefric.simulate(profile_m, DX, speeds, series=True, depth=depth, stiffness=1.4e8,
                           viscosity=0.0)
    for name in ("mu", "mu_inst", "penetration", "hydro_load", "max_compression"):
        np.testing.assert_allclose(mx[name].values, kv[name].values, rtol=1e-12, atol=1e-18,
                                   err_msg=name)


@pytest.mark.parametrize("depth", [0.0, 1e-3])
@pytest.mark.parametrize("arms", [[2e8], [1e8, 3e8, 2e8]])
def test_slow_arms_give_the_elastic_pad_of_all_springs(profile_m, depth, arms):
    """tau -> infinity: the dashpots never move (E = G = 1), u_free = 0 and
    k_eff = K_inf + sum K_k: the elastic pad of the instantaneous stiffness."""
    speeds = [1.0, 20.0, 80.0]
    mx = quiet(pavefric.simulate, profile_m, DX, speeds, series=True, depth=depth,
               rubber_model="maxwell", stiffness=1.4e8, prony_stiffness=arms,
               prony_times=[1e30] * len(arms))
    kv = pavefric.simulate(profile_m, DX, speeds, series=True, depth=depth,
                           stiffness=1.4e8 + sum(arms), viscosity=0.0)
    for name in ("mu", "mu_inst", "penetration", "hydro_load", "max_compression"):
        np.testing.assert_allclose(mx[name].values, kv[name].values, rtol=1e-12, atol=1e-18,
                                   err_msg=name)
    # and at V = 0 (the static limit) the arms are relaxed whatever tau
    static = quiet(pavefric.simulate, profile_m, DX, [0.0], rubber_model="maxwell",
                   stiffness=1.4e8, prony_stiffness=arms, prony_times=[1e30] * len(arms))
    soft = pavefric.simulate(profile_m, DX, [0.0], stiffness=1.4e8, viscosity=0.0)
    np.testing.assert_array_equal(static["mu"].values, soft["mu"].values)


def test_the_arms_matter_between_the_limits(profile_m):
    """Between the limits the Maxwell pad is neither elastic pad, and it keeps
    memory (its effect is recorded)."""
    mx = pavefric.simulate(profile_m, DX, [20.0, 80.0], **THREE)
    soft = pavefric.simulate(profile_m, DX, [20.0, 80.0], stiffness=1.4e8, viscosity=0.0)
    hard = pavefric.simulate(profile_m, DX, [20.0, 80.0], stiffness=7.4e8, viscosity=0.0)
    assert np.all(np.abs(mx["mu"].values - soft["mu"].values) > 1e-3)
    assert np.all(np.abs(mx["mu"].values - hard["mu"].values) > 1e-3)
    assert "viscous_memory" in mx.attrs["effects"]
    assert list(mx["viscous_memory_ran"].values) == [1, 1]
    assert mx.attrs["param_rubber_model"] == "maxwell"


# --- must-show 3: the closed form on a sinusoid ---------------------------------

def sinusoid_case(per_wave: int, pad_waves: int = 16, waves: int = 64, speed_kmh: float = 20.0,
                  amplitude: float = 1e-4, wavelength: float = 0.0278, scheme: str = "energy"):
    """Every element always in contact: K_inf delta = 8 K_inf A > A |E*|."""
    dx = wavelength / per_wave
    k = 2 * np.pi / wavelength
    z = amplitude * np.sin(k * dx * np.arange(per_wave * waves))
    v = speed_kmh / 3.6
    w = k * v
    arms = np.array([2e7, 3e7, 1e7])
    taus = np.array([0.3, 1.0, 3.0]) / w
    k_inf = 1e7
    width = 0.016
    length = pad_waves * wavelength
    n = int(round(length / dx))
    load = n * width * dx * k_inf * 8 * amplitude
    ds = pavefric.simulate(z, dx, [speed_kmh], series=True, mu_loc=0.0, length=length,
                           width=width, load=load, rubber_model="maxwell", stiffness=k_inf,
                           prony_stiffness=list(arms), prony_times=list(taus),
                           element_length=0.0, friction_scheme=scheme)
    assert ds.attrs["pad_elements"] == n
    # continuous: E''(w) per unit length, mu = N l dx k A^2 E'' / (2W)
    loss = np.sum(arms * w * taus / (1 + (w * taus) ** 2))
    mu_cont = n * width * dx * k * amplitude**2 * loss / (2 * load)
    # the scheme's own: exact step on the sampled (piecewise-linear) sinusoid,
    # u_n = A e^(i theta n): each arm's stretch w = u - v is W u_n with
    # W = G (1 - e^-i theta)/(1 - E e^-i theta), so the step's end pressure is
    # E*_d u, E*_d = K_inf + sum K W. 'paper': Eq. 10 on central slopes,
    # A^2 sin(theta) E''_d / 2 per element. 'energy': the pressure averaged
    # along the step's path, K_inf (u + u')/2 + sum K [H (u' - u) + G w]
    # (H = (1 - G)/r), times u' - u: per element and step on average
    # A^2 sum K [2 H (1 - cos theta) - G^2 Re (1 - e^-i theta)^2/(1 - E e^-i theta)] / 2,
    # the dashpots' dissipation (0 for K_inf: elastic)
    dt = dx / v
    r = dt / taus
    e = np.exp(-r)
    g = -np.expm1(-r) / r
    theta = k * dx
    if scheme == "paper":
        e_d = k_inf + np.sum(arms * g * (1 - np.exp(-1j * theta))
                             / (1 - e * np.exp(-1j * theta)))
        per_element = np.sin(theta) * e_d.imag
    else:
        h = (1 - g) / r
        q = 1 - np.exp(-1j * theta)
        per_element = np.sum(arms * (2 * h * (1 - np.cos(theta))
                                     - g**2 * (q**2 / (1 - e * np.exp(-1j * theta))).real))
    mu_disc = n * width * amplitude**2 * per_element / (2 * load)
    return ds, mu_cont, mu_disc, n


@pytest.mark.parametrize("scheme", ["energy", "paper"])
@pytest.mark.parametrize("per_wave", [8, 32])
def test_sinusoid_friction_is_the_schemes_closed_form_to_rounding(per_wave, scheme):
    """dt/tau spans 0.07-2.6 here: both branches of the arm's weights."""
    ds, _, mu_disc, n = sinusoid_case(per_wave, scheme=scheme)
    assert np.all(ds["contact_elements"].values == n)        # always every element
    mu = float(ds["mu"].values[0])
    assert mu == pytest.approx(mu_disc, rel=1e-12)


def test_sinusoid_friction_converges_to_the_loss_modulus_at_second_order():
    """mu -> N l dx k A^2 E''(kV) / (2W) as O((k dx)^2): the error falls
    fourfold per halving of dx."""
    errors = []
    for per_wave in (16, 32, 64, 128):
        ds, mu_cont, _, n = sinusoid_case(per_wave, pad_waves=8, waves=32)
        assert np.all(ds["contact_elements"].values == n)
        errors.append(float(ds["mu"].values[0]) / mu_cont - 1)
    assert abs(errors[0]) < 0.05 and abs(errors[-1]) < 1e-3
    ratios = [errors[j] / errors[j + 1] for j in range(3)]
    assert all(3.8 < q < 4.2 for q in ratios), (errors, ratios)


# --- must-show 4: extremes --------------------------------------------------------

EXTREMES = [
    dict(prony_stiffness=[1e15], prony_times=[1e-300]),
    dict(prony_stiffness=[1e15], prony_times=[1e30]),
    dict(prony_stiffness=[1e15, 1e15, 1e15], prony_times=[1e-9, 1e-4, 1e1]),
    dict(prony_stiffness=[0.0, 1e8], prony_times=[1e-4, 1e-4]),
    dict(prony_stiffness=[1e8], prony_times=[5e-324 * 1e16]),
    dict(prony_stiffness=[1e-300], prony_times=[1e-4]),
    dict(stiffness=1e15, prony_stiffness=[1e15], prony_times=[1e-4]),
    dict(stiffness=1.0, prony_stiffness=[1e15], prony_times=[1e-4]),    # the least K allowed
    dict(stiffness=1.0, prony_stiffness=[1e-3], prony_times=[1e30]),
    dict(prony_stiffness=[1e8] * 100, prony_times=list(np.logspace(-300, 30, 100))),
    # WLF at the edge of its domain: a_T = 1e+-100 on every arm
    dict(prony_stiffness=[1e9], prony_times=[1e30], temperature=-81.0, wlf_c1=0.5881),
    dict(prony_stiffness=[1e9], prony_times=[1e-300], temperature=1000.0, wlf_c1=110.0),
]


@pytest.mark.parametrize("case", range(len(EXTREMES)))
@pytest.mark.parametrize("depth", [0.0, 1e-3])
def test_extreme_rubbers_give_finite_results(short_profile_m, case, depth):
    kw = {"rubber_model": "maxwell", "stiffness": 1.4e8, **EXTREMES[case]}
    ds = quiet(pavefric.simulate, short_profile_m, DX, [0.0, 1e-6, 20.0, 1e5], series=True,
               depth=depth, **kw)
    for name in ("mu", "max_compression", "max_balance_residual", "mu_inst", "penetration"):
        assert np.all(np.isfinite(ds[name].values)), name
    assert np.all(ds["max_balance_residual"].values < 1e-9)


BAD = [
    (dict(rubber_model="maxwell"), "rubber_model = 'maxwell' (&rubber model): prony_stiffness "
     "and prony_times are empty"),
    (dict(rubber_model="maxwell", prony_stiffness=[1e8, 1e8], prony_times=[1e-4]),
     "&rubber prony_stiffness has 2 values and prony_times 1"),
    (dict(prony_stiffness=[1e8], prony_times=[1e-4, 1e-3]),
     "&rubber prony_stiffness has 1 values and prony_times 2"),
    (dict(rubber_model="maxwell", prony_stiffness=[1e8], prony_times=[0.0]),
     "&rubber prony_times(1) = 0: must be finite and > 0"),
    (dict(rubber_model="maxwell", prony_stiffness=[-1.0], prony_times=[1e-4]),
     "&rubber prony_stiffness(1) = -1: must be finite and >= 0"),
    (dict(rubber_model="maxwell", prony_stiffness=[1e16], prony_times=[1e-4]),
     "&rubber prony_stiffness(1) = 1e16: must be finite and >= 0 and <= 1e15"),
    (dict(rubber_model="maxwell", prony_stiffness=[1e8], prony_times=[1e31]),
     "&rubber prony_times(1) = 1e31: must be finite and > 0 and <= 1e30 s"),
    (dict(rubber_model="maxwell", prony_stiffness=[1e8] * 101, prony_times=[1e-4] * 101),
     "&rubber prony_stiffness: more than 100 values"),
    (dict(rubber_model="prony"), "rubber_model = 'prony' (&rubber model): unknown (expected "
     "'kelvin_voigt' or 'maxwell')"),
    (dict(temperature=-81.6), "&rubber temperature = -81.6: T - reference_temperature = "
     "-101.6 K must be > -wlf_c2 = -101.6 K"),
    (dict(temperature=-100.0), "the WLF equation diverges"),
    (dict(temperature=0.0, reference_temperature=20.0, wlf_c2=10.0), "must be > -wlf_c2 = -10"),
    (dict(temperature=-81.5, wlf_c1=1000.0), "beyond +-100 decades"),
    (dict(temperature=-274.0), "&rubber temperature = -274: must be finite and > -273.15"),
    (dict(wlf_c2=0.0), "&rubber wlf_c2 = 0: must be finite and > 0"),
]


@pytest.mark.parametrize("kw, message", BAD, ids=[m[:40] for _, m in BAD])
def test_bad_rubbers_are_refused_with_a_clear_message(kw, message):
    with pytest.raises(pavefric.PavefricError) as err:
        quiet(pavefric.simulate, np.sin(np.arange(200) * 0.3) * 5e-4, DX, [20.0], **kw)
    assert message in str(err.value)


def test_the_program_names_the_file_and_the_rubber(tmp_path):
    scene = write_scene(tmp_path, groups={"rubber": "model = 'maxwell', prony_stiffness = 1e8, "
                                          "prony_times = 1e-4, 1e-3"})
    r = run_program(scene, "-o", tmp_path / "o.nc")
    assert r.returncode == 1
    assert "&rubber prony_stiffness has 1 values and prony_times 2" in r.stderr


# --- one path across the boundaries ---------------------------------------------

def _compound_scene(tmp_path, temperature=5.0, water="depth = 1.0e-3", series=".true.",
                    speeds="0, 10, 20, 40, 80"):
    text = COMPOUND.read_text().replace("temperature = 20", f"temperature = {temperature}")
    profile = (ROOT / "inputs" / "profiles" / "ctm_medium.txt").resolve()
    text += (f"&surface profile_file = '{profile}', dx = 0.87e-3, mu_loc = 0.6 /\n"
             f"&water {water} /\n&operation speeds_kmh = {speeds} /\n"
             f"&output series = {series} /\n")
    path = tmp_path / "tread.nml"
    path.write_text(text)
    return path


@pytest.mark.parametrize("water", ["depth = 0.0", "depth = 1.0e-3",
                                   "depth = 1.0e-3, wet_model = 'squeeze'"])
def test_program_and_python_agree_on_a_maxwell_scene(tmp_path, water):
    from test_boundaries import assert_same_bits

    scene = _compound_scene(tmp_path, water=water, speeds="0, 10, 20, 40, 80")
    out = tmp_path / "o.nc"
    r = run_program(scene, "-o", out)
    assert r.returncode == 0, r.stderr
    ds = quiet(pavefric.load_scene(scene).simulate)
    with xr.open_dataset(out) as f:
        assert_same_bits(f.load(), ds, water)
        assert f.attrs["param_rubber_model"] == "maxwell"
        assert f.attrs["param_rubber_temperature"] == 5.0
        np.testing.assert_array_equal(np.atleast_1d(f.attrs["param_rubber_prony_times"]),
                                      ds.attrs["param_rubber_prony_times"])


def test_program_python_and_c_agree_on_a_maxwell_scene(tmp_path):
    """The C API (check_api dump, tests/test_api.py) on the compound at 5 C."""
    from pathlib import Path

    from test_api import SCALARS, _run, build, dumped, same_bits

    bindir = Path(sys.executable).parent
    config = bindir / "pavefric-config"
    pcdir = _run([config, "--pkgconfigdir"]).stdout.strip()
    env = dict(os.environ, PKG_CONFIG_PATH=pcdir, PATH=f"{bindir}{os.pathsep}{os.environ['PATH']}")
    scene = _compound_scene(tmp_path)
    out = tmp_path / "program.nc"
    assert run_program(scene, "-o", out).returncode == 0
    ref = pavefric.open_dataset(out)
    exe = build(tmp_path / "c", "check_api.c", env)
    got = dumped(_run([exe, "dump", scene, tmp_path / "c.nc"], cwd=tmp_path).stdout)
    py = quiet(pavefric.load_scene(scene).simulate)
    names = [*ref.coords, *ref.data_vars]
    assert "mu_inst" in names
    for name in names:
        if name in SCALARS:  # texture and IFI: of the file and simulate(), not the C API
            continue
        assert same_bits(got[name], ref[name].values), name
        assert same_bits(py[name].values, ref[name].values), name


# --- python -m pavefric prony -------------------------------------------------------

def _prony_data(tmp_path, e_inf, arms, taus, temps, c1=8.86, c2=101.6, tref=20.0,
                shear=False):
    f = np.logspace(-1, 2, 10)
    rows = ["temperature_c,frequency_hz,storage_mpa,loss_mpa" if not shear
            else "temperature_c,frequency_hz,storage_pa,loss_pa"]
    for t in temps:
        w = 2 * np.pi * f * 10 ** log10_at(t, tref, c1, c2)
        wt = w[:, None] * np.asarray(taus)[None, :]
        s = e_inf + np.sum(np.asarray(arms) * wt**2 / (1 + wt**2), axis=1)
        l = np.sum(np.asarray(arms) * wt / (1 + wt**2), axis=1)
        for fi, si, li in zip(f, s, l):
            if shear:
                rows.append(f"{t},{float(fi)!r},{float(si) / 3!r},{float(li) / 3!r}")
            else:
                rows.append(f"{t},{float(fi)!r},{float(si) / 1e6!r},{float(li) / 1e6!r}")
    path = tmp_path / "dma.csv"
    path.write_text("# a test compound\n" + "\n".join(rows) + "\n")
    return path


def test_prony_recovers_a_known_series_and_writes_a_group_the_core_reads(tmp_path):
    from pavefric.rubber import compound as read, fit_prony, read_dma

    taus = [1e-6, 1e-4, 1e-2, 1.0]
    arms = [4e8, 5e7, 2e7, 5e6]
    path = _prony_data(tmp_path, 3e6, arms, taus, [-10.0, 10.0, 30.0, 50.0])
    data = read_dma(path)
    fit = fit_prony(data, times=[1e-8, 1e-7, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2, 1e-1, 1.0, 10.0])
    # the four arms and nothing else, to rounding
    np.testing.assert_allclose(fit.times, taus)
    np.testing.assert_allclose(fit.e_arms, arms, rtol=1e-9)
    assert fit.e_inf == pytest.approx(3e6, rel=1e-9)
    assert fit.rms_storage < 1e-10 and fit.rms_loss < 1e-10
    # the default candidates (a decade apart, not on these times) fit a
    # discrete spectrum to a few per cent only: real compounds are broad
    w = data.omega[data.temperature == 10.0] * 10 ** log10_at(10.0)
    wt = w[:, None] * np.array(taus)
    want_l = np.sum(np.array(arms) * wt / (1 + wt**2), axis=1)
    np.testing.assert_allclose(fit.moduli(w)[1], want_l, rtol=1e-9)
    coarse = fit_prony(data)
    assert coarse.rms_storage < 0.2 and coarse.rms_loss < 0.3
    fit = coarse                        # what the command writes by default
    out = tmp_path / "c.nml"
    r = subprocess.run([sys.executable, "-m", "pavefric", "prony", str(path), "-o", str(out),
                        "--thickness", "0.004"], capture_output=True, text=True, cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    text = out.read_text()
    assert "K = E / h" in text and "h = 0.004 m" in text and "a test compound" in text
    kw = read(out)
    assert kw["rubber_model"] == "maxwell"
    np.testing.assert_allclose(kw["stiffness"] * 0.004, fit.e_inf, rtol=1e-5)
    np.testing.assert_allclose(np.array(kw["prony_stiffness"]) * 0.004, fit.e_arms, rtol=1e-5)
    np.testing.assert_allclose(kw["prony_times"], fit.times, rtol=1e-5)
    assert kw["wlf_c1"] == 8.86 and kw["wlf_c2"] == 101.6
    # and simulate runs it
    ds = quiet(pavefric.simulate, np.sin(np.arange(300) * 0.3) * 5e-4, DX, [20.0], **kw)
    assert np.isfinite(ds["mu"].values[0])


def test_prony_fits_the_wlf_constants(tmp_path):
    from pavefric.rubber import fit_prony, read_dma

    path = _prony_data(tmp_path, 3e6, [4e8, 5e7, 2e7, 5e6], [1e-6, 1e-4, 1e-2, 1.0],
                       [-10.0, 0.0, 10.0, 20.0, 30.0, 50.0], c1=12.0, c2=140.0)
    fit = fit_prony(read_dma(path), fit_wlf=True, times=[1e-6, 1e-4, 1e-2, 1.0])
    assert fit.c1 == pytest.approx(12.0, rel=1e-3)
    assert fit.c2 == pytest.approx(140.0, rel=1e-3)
    assert fit.rms_loss < 1e-4


def test_prony_fits_a_broad_spectrum_closely(tmp_path):
    """A continuous spectrum (the representative compound's model with other
    constants) at one candidate time a decade: within a few per cent."""
    from pavefric.rubber import DMAData, fit_prony, representative_moduli

    f = np.logspace(-1, 2, 13)
    temps = np.repeat([-20.0, 0.0, 20.0, 40.0, 60.0], f.size)
    freqs = np.tile(f, 5)
    s, l = representative_moduli(2 * np.pi * freqs, temps, e_rubbery=5e6, alpha=0.4)
    fit = fit_prony(DMAData(temps, freqs, s, l))
    assert fit.rms_storage < 0.02 and fit.rms_loss < 0.04
    fine = fit_prony(DMAData(temps, freqs, s, l), per_decade=2)
    assert fine.rms_storage < 0.3 * fit.rms_storage and fine.rms_loss < 0.3 * fit.rms_loss


def test_prony_reads_shear_moduli_as_three_times_young(tmp_path):
    from pavefric.rubber import read_dma

    path = _prony_data(tmp_path, 3e6, [4e8], [1e-4], [20.0], shear=True)
    e = read_dma(path, modulus="shear")
    g = read_dma(path)
    np.testing.assert_allclose(e.storage, 3 * g.storage)
    np.testing.assert_allclose(e.loss, 3 * g.loss)


@pytest.mark.parametrize("text, message", [
    ("frequency_hz,storage_pa\n1,2\n", "no column loss_pa or loss_mpa"),
    ("frequency_hz,storage_pa,loss_pa\n1,2,3\n1,x,3\n", "dma.csv:3: '1,x,3' is not a row"),
    ("frequency_hz,storage_pa,loss_pa\n1,2,3\n1,2\n", "dma.csv:3: 2 values, the header has 3"),
    ("frequency_hz,storage_pa,loss_pa\n1,2,-3\n", "dma.csv:2: the loss modulus must be > 0"),
    # no data rows (issue 19: it wrote an empty group and exited 0)
    ("temperature_c,frequency_hz,storage_mpa,loss_mpa\n", "dma.csv: no data rows"),
    ("temperature_c,frequency_hz,storage_mpa,loss_mpa\n# a comment only\n",
     "dma.csv: no data rows"),
    ("", "dma.csv: no header and no data"),
])
def test_prony_names_the_bad_line(tmp_path, text, message):
    """A bad DMA file fails naming its line, and writes no output."""
    path = tmp_path / "dma.csv"
    path.write_text(text)
    out = tmp_path / "rubber.nml"
    r = subprocess.run([sys.executable, "-m", "pavefric", "prony", str(path), "-o", str(out)],
                       capture_output=True, text=True)
    assert r.returncode == 1
    assert message in r.stderr
    assert not out.exists()


def test_the_shipped_compound_is_the_fit_of_the_shipped_data():
    """inputs/rubber/tread_compound.nml = `prony` on inputs/data/tread_compound_dma.csv,
    and that data set = the representative model it says it is."""
    from pavefric.rubber import (compound as read, fit_prony, read_dma, representative_dma,
                                 THICKNESS)

    data = read_dma(DMA)
    model = representative_dma()
    np.testing.assert_allclose(data.storage, model.storage, rtol=1e-6)
    np.testing.assert_allclose(data.loss, model.loss, rtol=1e-6)
    assert "NOT A MEASUREMENT" in DMA.read_text()
    fit = fit_prony(data)
    assert fit.rms_storage < 0.02 and fit.rms_loss < 0.04
    kw = read(COMPOUND)
    np.testing.assert_allclose(np.array(kw["prony_stiffness"]) * THICKNESS, fit.e_arms,
                               rtol=1e-5)
    np.testing.assert_allclose(kw["prony_times"], fit.times, rtol=1e-5)
    # the indicators the representative compound was built to
    for t, want in ((0.0, 0.50), (60.0, 0.12)):
        s, l = fit.moduli(np.array([2 * np.pi * 10.0]), temperature=t)
        assert l[0] / s[0] == pytest.approx(want, abs=0.02)


def test_the_rubber_report_runs(tmp_path):
    """python -m pavefric rubber-report --quick, from the checkout (the cost
    target is the benchmark's, not a test's)."""
    from pavefric.studies.rubber_report import run_report

    cwd = os.getcwd()
    os.chdir(ROOT)
    try:
        data = run_report(tmp_path / "rubber.md", quick=True, log=lambda *a: None,
                          outdir=tmp_path)
    finally:
        os.chdir(cwd)
    text = (tmp_path / "rubber.md").read_text()
    assert "python -m pavefric rubber-report" in text
    assert (tmp_path / "figures" / "rubber_mu_speed.png").stat().st_size > 10_000
    assert data["superposition"]["worst"] < 1e-12
    assert data["fit"]["same_as_shipped"]
    assert {r["case"] for r in data["cost"]["rows"]} >= {"maxwell, 3 arms"}


@pytest.mark.parametrize("model, given, word", [
    ("maxwell", "viscosity = 50.0", "viscosity"),
    ("kelvin_voigt", "prony_stiffness = 1e7, prony_times = 1e-3", "prony_stiffness"),
])
def test_a_rubber_variable_the_model_does_not_use_is_warned_about(tmp_path, model, given, word):
    arms = "prony_stiffness = 1e7, prony_times = 1e-3, " if model == "maxwell" else ""
    scene = write_scene(tmp_path, groups={
        "rubber": f"model = '{model}', stiffness = 1.4e8, {arms}{given}"})
    out = tmp_path / "o.nc"
    r = run_program(scene, "-o", out)
    assert r.returncode == 0, r.stderr
    assert word in r.stderr and "not used" in r.stderr, r.stderr
    with xr.open_dataset(out) as f:
        assert word in f.attrs["warnings"] and "not used" in f.attrs["warnings"]
    with pytest.warns(pavefric.PavefricWarning, match=f"{word}.*not used"):
        pavefric.load_scene(scene).simulate()


def test_the_default_rubber_gives_no_such_warning(tmp_path):
    r = run_program(write_scene(tmp_path), "-o", tmp_path / "o.nc")
    assert r.returncode == 0 and "not used" not in r.stderr, r.stderr


def test_python_shifts_data_with_the_cores_wlf():
    """One WLF (issue 22): pavefric.rubber.wlf_log10_shift is the core's
    (f2py), equal to the test's own formula to rounding, exactly 0 at Tref,
    and refuses where the equation diverges or runs past 100 decades."""
    from pavefric.rubber import wlf_log10_shift
    t = np.array([-30.0, -10.0, 0.0, 20.0, 45.0, 80.0])
    got = wlf_log10_shift(t, 20.0, 8.86, 101.6)
    np.testing.assert_allclose(got, log10_at(t), rtol=1e-14, atol=0)
    assert got[3] == 0.0 and got.shape == t.shape
    assert isinstance(wlf_log10_shift(0.0), float)
    with pytest.raises(ValueError, match="must be > -C2"):
        wlf_log10_shift([-90.0], 20.0, 8.86, 101.6)
    with pytest.raises(ValueError, match="more than 100 decades"):
        wlf_log10_shift([-81.5], 20.0, 1000.0, 101.6)


def test_prony_replaces_only_its_own_files(tmp_path):
    """`prony -o` and `--write-representative` replace an existing file only
    if this command wrote it (it begins with the command's signature, the
    core's check_text_replaceable): a user's scene or data named by mistake
    is refused with exit status 1, naming it, and stays byte for byte; the
    command's own earlier output and an empty file are replaced."""
    path = _prony_data(tmp_path, 3e6, [4e8, 5e7], [1e-6, 1e-3], [-10.0, 10.0, 30.0])

    def prony(*args):
        return subprocess.run([sys.executable, "-m", "pavefric", "prony", *map(str, args)],
                              capture_output=True, text=True, cwd=tmp_path, timeout=300)

    scene = tmp_path / "scene.nml"
    scene.write_text("&surface profile_file = 'p.txt', dx = 1e-3 /\n&rubber stiffness = 1e8 /\n")
    before = scene.read_bytes()
    r = prony(path, "-o", scene)
    assert r.returncode == 1
    assert f"'{scene}': exists and is not a file this command wrote" in r.stderr
    assert "replaces only its own outputs" in r.stderr
    assert scene.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir() if ".tmp" in p.name) == []
    # its own output, and an empty file, are replaced
    own = tmp_path / "own.nml"
    assert prony(path, "-o", own).returncode == 0
    own.write_text(own.read_text() + "! an edit\n")
    assert prony(path, "-o", own).returncode == 0
    assert "an edit" not in own.read_text()
    empty = tmp_path / "empty.nml"
    empty.touch()
    assert prony(path, "-o", empty).returncode == 0
    assert empty.read_text().startswith("! Prony series fitted by `python -m pavefric prony")
    # the representative data set: a user's DMA file is not replaced, its own is
    dma = tmp_path / "mine.csv"
    dma.write_text("temperature_c,frequency_hz,storage_pa,loss_pa\n20,1,1e7,1e6\n")
    before = dma.read_bytes()
    r = prony("--write-representative", dma)
    assert r.returncode == 1 and "is not a file this command wrote" in r.stderr
    assert dma.read_bytes() == before
    rep = tmp_path / "rep.csv"
    assert prony("--write-representative", rep).returncode == 0
    assert prony("--write-representative", rep).returncode == 0
    assert rep.read_text().startswith("# Representative dynamic mechanical data")


def test_surface_replaces_only_a_profile_it_wrote(tmp_path):
    """`python -m pavefric surface -o` replaces an existing file only if it
    begins as the profiles it writes do ("# pavefric synthetic profile:"): a
    measured profile named by mistake is refused, exit status 1, and stays
    byte for byte; its own earlier profile is replaced."""
    def surface(out, seed):
        return subprocess.run([sys.executable, "-m", "pavefric", "surface", "-o", str(out),
                               "--seed", str(seed), "--points", "256"],
                              capture_output=True, text=True, cwd=tmp_path, timeout=300)

    measured = tmp_path / "measured.txt"
    measured.write_text("height_mm\n0.1\n0.2\n0.15\n")
    before = measured.read_bytes()
    r = surface(measured, 1)
    assert r.returncode == 1
    assert "exists and is not a file this command wrote" in r.stderr
    assert measured.read_bytes() == before
    own = tmp_path / "own.txt"
    assert surface(own, 1).returncode == 0
    first = own.read_text()
    assert surface(own, 2).returncode == 0
    assert own.read_text() != first and "seed=2" in own.read_text()
