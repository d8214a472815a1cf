"""The namelist reader: groups wherever the standard allows them, nothing
silently ignored or misread (issue 10 item 3), every value checked against
its one declaration, plausible-but-suspicious values warned about."""
import math
import warnings

import numpy as np
import pytest
import xarray as xr

import pavefric
from conftest import run_program, write_scene

DX = 0.87e-3


def mu_of(tmp_path, scene):
    out = tmp_path / (scene.stem + ".nc")
    r = run_program(scene, "-o", out)
    assert r.returncode == 0, r.stderr
    with xr.open_dataset(out) as ds:
        return ds["mu"].values.copy(), ds.attrs["effects"], r


@pytest.fixture()
def wet_reference(tmp_path, profile_m):
    scene = write_scene(tmp_path / "ref", profile=profile_m, groups={"water": "depth = 1e-3"})
    mu, effects, _ = mu_of(tmp_path, scene)
    assert "hydrodynamic_bearing" in effects
    return mu


@pytest.mark.parametrize("prefix", [
    "\ufeff",            # a byte-order mark at the start of the file
    "\u00a0",            # a no-break space
    "\f",                # a form feed
    "\t  ",
])
def test_a_group_after_unusual_blanks_is_read(tmp_path, profile_m, wet_reference, prefix):
    scene = write_scene(tmp_path, profile=profile_m, groups={"water": None})
    scene.write_text(scene.read_text() + prefix + "&water depth = 1e-3 /\n", encoding="utf-8")
    mu, effects, _ = mu_of(tmp_path, scene)
    assert "hydrodynamic_bearing" in effects
    np.testing.assert_array_equal(mu, wet_reference)


def test_a_bom_at_the_start_of_the_file(tmp_path, profile_m, wet_reference):
    scene = write_scene(tmp_path, profile=profile_m, groups={"water": "depth = 1e-3"})
    scene.write_bytes(b"\xef\xbb\xbf" + scene.read_bytes())
    mu, _, _ = mu_of(tmp_path, scene)
    np.testing.assert_array_equal(mu, wet_reference)


def test_two_groups_on_one_line(tmp_path, profile_m, wet_reference):
    scene = write_scene(tmp_path, profile=profile_m, groups={"water": None, "pad": None})
    scene.write_text(scene.read_text() + "&pad length = 0.020 / &water depth = 1e-3 /\n")
    mu, _, _ = mu_of(tmp_path, scene)
    np.testing.assert_array_equal(mu, wet_reference)


def test_a_group_given_twice_is_an_error(tmp_path):
    scene = write_scene(tmp_path)
    scene.write_text(scene.read_text() + "&water\n  depth = 1e-3\n/\n")
    r = run_program(scene, "-o", tmp_path / "o.nc")
    assert r.returncode == 1
    assert "&water: given twice" in r.stderr and "merge the two groups" in r.stderr
    assert not (tmp_path / "o.nc").exists()


@pytest.mark.parametrize("body,needles", [
    ("depth = 1e-3, depth = 2e-3", ["&water depth", "given twice"]),
    ("depth = 1-3", ["&water depth = 1-3", "not a number (write one such as 0.5, 1e-3",
                     "must be finite and >= 0 and <= 100 m"]),
    ("depth = 1e-3 viscosity = '1e-3'", ["&water viscosity", "not a number (write one"]),
    ("depth = 1e-3,, alpha = 1", ["&water depth", "empty value"]),
    ("depth = 1e-3 &end junk", ["junk", "outside a namelist group"]),
])
def test_malformed_assignments(tmp_path, body, needles):
    scene = write_scene(tmp_path, groups={"water": body})
    r = run_program(scene, "-o", tmp_path / "o.nc")
    assert r.returncode == 1
    line = r.stderr.strip()
    assert len(line.splitlines()) == 1, r.stderr
    for needle in needles:
        assert needle in line, (needle, line)


def test_text_outside_groups_is_an_error_not_ignored(tmp_path):
    scene = write_scene(tmp_path, groups={"water": None})
    scene.write_text(scene.read_text() + "depth = 1e-3\n")    # forgot the group
    r = run_program(scene, "-o", tmp_path / "o.nc")
    assert r.returncode == 1
    assert "'depth = 1e-3' outside a namelist group" in r.stderr


def test_an_unterminated_group_is_an_error(tmp_path):
    scene = write_scene(tmp_path, groups={"water": None})
    scene.write_text(scene.read_text() + "&water depth = 1e-3\n")
    r = run_program(scene, "-o", tmp_path / "o.nc")
    assert r.returncode == 1 and "&water is not terminated" in r.stderr


def test_dx_minus_one_is_refused_not_taken_as_unset(tmp_path):
    scene = write_scene(tmp_path, groups={"surface": "profile_file = 'scene_profile.txt', "
                                                     "dx = -1"})
    r = run_program(scene, "-o", tmp_path / "o.nc")
    assert r.returncode == 1 and "&surface dx = -1" in r.stderr


def test_a_huge_negative_speed_is_refused(tmp_path):
    scene = write_scene(tmp_path, groups={"operation": "speeds_kmh = 20, -1e300"})
    r = run_program(scene, "-o", tmp_path / "o.nc")
    assert r.returncode == 1 and "&operation speeds_kmh(2) = -1e300" in r.stderr


@pytest.mark.parametrize("group,body,needle", [
    # old reader: fixed-length strings truncated, then the truncation was accepted
    ("pad", "shape = 'flat" + " " * 40 + "x'", "&pad shape = 'flat"),
    ("surface", "profile_file = 'scene_profile.txt" + " " * 5000 + "x'",
     "&surface profile_file"),
    ("surface", "profile_file = 'scene_profile.txt', height_unit = 'mm" + " " * 30 + "zz'",
     "&surface height_unit"),
])
def test_over_long_strings_are_not_truncated(tmp_path, group, body, needle):
    scene = write_scene(tmp_path, groups={group: body})
    r = run_program(scene, "-o", tmp_path / "o.nc")
    assert r.returncode == 1, r.stdout
    assert needle in r.stderr


def test_an_integer_written_as_a_real_is_refused(tmp_path):
    scene = write_scene(tmp_path, groups={"numerics": "substeps = 2.9"})
    r = run_program(scene, "-o", tmp_path / "o.nc")
    assert r.returncode == 1 and "&numerics substeps = 2.9" in r.stderr
    assert "whole number" in r.stderr


def test_list_syntax(tmp_path, profile_m):
    a = write_scene(tmp_path / "a", profile=profile_m,
                    groups={"operation": "speeds_kmh = 20, 20, 60"})
    b = write_scene(tmp_path / "b", profile=profile_m,
                    groups={"operation": "speeds_kmh = 2*20 60"})
    c = write_scene(tmp_path / "c", profile=profile_m,
                    groups={"operation": "speeds_kmh(3) = 60, speeds_kmh(1) = 2*20"})
    mus_r = [mu_of(tmp_path, s) for s in (a, b, c)]
    mus = [m[0] for m in mus_r]
    mus_r = [m[2] for m in mus_r]
    np.testing.assert_array_equal(mus[0], mus[1])
    np.testing.assert_array_equal(mus[0], mus[2])
    # a speed given twice runs (the list syntax allows it) but is named
    # (attack, 2026-11-28: the output's speed_kmh coordinate repeated 20 without a word)
    for r in (mus_r[0], mus_r[1]):
        assert ("pavefric: warning: &operation speeds_kmh(2) = 20 repeats speeds_kmh(1): "
                "each is computed again") in r.stderr, r.stderr
    assert "speeds_kmh(2) = 20 repeats speeds_kmh(1)" in mus_r[2].stderr
    many = write_scene(tmp_path / "e", profile=profile_m,
                       groups={"operation": "speeds_kmh = 60, 40, 3*20, 40"})
    _, _, r = mu_of(tmp_path, many)
    assert ("&operation speeds_kmh(4) = 20 repeats speeds_kmh(3) (3 repeated values in all)"
            in r.stderr), r.stderr
    with xr.open_dataset(tmp_path / "scene.nc") as ds:   # mu_of writes <stem>.nc
        assert "speeds_kmh(4) = 20 repeats" in ds.attrs["warnings"]
    once = write_scene(tmp_path / "f", profile=profile_m, groups={"operation": "speeds_kmh = 20, 60"})
    assert "repeats" not in mu_of(tmp_path, once)[2].stderr
    gap = write_scene(tmp_path / "d", groups={"operation": "speeds_kmh(1) = 20, "
                                                           "speeds_kmh(3) = 60"})
    r = run_program(gap, "-o", tmp_path / "o.nc")
    assert r.returncode == 1 and "element 2 is not given" in r.stderr


# --- plausibility warnings -----------------------------------------------------

def test_water_depth_in_mm_by_mistake_warns(tmp_path, profile_m):
    scene = write_scene(tmp_path, profile=profile_m, groups={"water": "depth = 1.0"})
    mu, _, r = mu_of(tmp_path, scene)
    assert "pavefric: warning: &water depth = 1 m: outside the plausible range" in r.stderr
    with xr.open_dataset(tmp_path / "scene.nc") as ds:
        assert "&water depth = 1 m" in ds.attrs["warnings"]


def test_a_loose_wet_balance_and_an_unused_radius_warn(tmp_path, profile_m):
    """attack21 and the fresh-user audit (2026-12-07): wet_tolerance = 0.5 (in its
    range) left the balance off by half the load, and &pad radius on a flat
    pad was ignored, both silently."""
    scene = write_scene(tmp_path, profile=profile_m,
                        groups={"water": "depth = 1e-3",
                                "numerics": "wet_tolerance = 0.5",
                                "pad": "radius = 0.005"})
    mu, _, r = mu_of(tmp_path, scene)
    assert "pavefric: warning: &numerics wet_tolerance = 0.5: outside the plausible range" \
        in r.stderr, r.stderr
    assert ("pavefric: warning: &pad radius = 0.005 is not used with &pad shape = 'flat'"
            in r.stderr), r.stderr
    rounded = write_scene(tmp_path / "r", profile=profile_m,
                          groups={"pad": "shape = 'rounded', radius = 0.05"})
    assert "radius" not in mu_of(tmp_path / "r", rounded)[2].stderr


def test_a_check_across_variables_names_the_line(tmp_path):
    """The checks across variables (here the WLF equation's range) named the
    variable but not where the file gave it, as the checks of single values
    do."""
    scene = write_scene(tmp_path, groups={"rubber": "temperature = -90"})
    r = run_program(scene, "-o", tmp_path / "o.nc")
    assert r.returncode == 1
    line = next(i for i, text in enumerate(scene.read_text().splitlines(), 1)
                if "temperature = -90" in text)
    assert r.stderr.startswith("pavefric: error: &rubber temperature = -90: ")
    assert r.stderr.rstrip().endswith(f" at {scene.name}:{line}") or \
        r.stderr.rstrip().endswith(f" at {scene}:{line}"), r.stderr
    assert not (tmp_path / "o.nc").exists()


def test_heights_in_metres_declared_as_mm_warns(tmp_path, profile_m):
    # heights written in metres, declared as mm: a micrometre texture
    prof = tmp_path / "m.txt"
    prof.write_text("\n".join(f"{v:.9e}" for v in profile_m) + "\n")
    scene = write_scene(tmp_path, groups={"surface": "profile_file = 'm.txt', "
                                                     "height_unit = 'mm'"})
    mu, _, r = mu_of(tmp_path, scene)
    assert "RMS height" in r.stderr and "height_unit" in r.stderr
    with xr.open_dataset(tmp_path / "scene.nc") as ds:
        assert "RMS height" in ds.attrs["warnings"]


def test_no_warning_on_a_plausible_scene(tmp_path, profile_m):
    """Plausible inputs, run to a stated accuracy: nothing to say (at the
    default single step the error estimate would warn at 60 km/h, 12 % of mu:
    test_error_estimate.py)."""
    scene = write_scene(tmp_path, profile=profile_m, groups={"water": "depth = 1e-3",
                                                              "numerics": "tolerance = 1e-3"})
    mu, _, r = mu_of(tmp_path, scene)
    assert r.stderr == ""
    with xr.open_dataset(tmp_path / "scene.nc") as ds:
        assert ds.attrs["warnings"] == ""


def test_python_raises_the_warnings_too(profile_m):
    with pytest.warns(pavefric.PavefricWarning, match=r"&water depth = 0.5 m"):
        ds = pavefric.simulate(profile_m, DX, [20.0], depth=0.5)
    assert "&water depth = 0.5 m" in ds.attrs["warnings"]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ds = pavefric.simulate(profile_m, DX, [20.0], depth=1e-3)
    assert ds.attrs["warnings"] == ""


# --- values that overflowed inside the model (issue 10 item 4) --------------------

@pytest.mark.parametrize("group,body,needle", [
    ("rubber", "viscosity = 1e306", "&rubber viscosity = 1e306"),
    ("water", "depth = 1e-3, viscosity = 1e306", "&water viscosity = 1e306"),
    ("pad", "load = 1.7e308", "&pad load = 1.7e308"),
    ("pad", "shape = 'rounded', radius = 1e300", "&pad radius = 1e300"),
    ("water", "depth = 1e-3, beta = 300", "&water beta = 300"),
])
def test_overflowing_values_are_refused_with_a_clear_error(tmp_path, group, body, needle):
    scene = write_scene(tmp_path, groups={group: body})
    r = run_program(scene, "-o", tmp_path / "o.nc")
    assert r.returncode == 1
    assert needle in r.stderr and "must be finite" in r.stderr
    assert not (tmp_path / "o.nc").exists()


def test_the_largest_values_allowed_give_finite_results(profile_m):
    for kw in (dict(viscosity=1e12), dict(load=1e9), dict(stiffness=1e15),
               dict(depth=1e-3, water_viscosity=1e6, alpha=1e12, beta=10.0),
               dict(shape="rounded", radius=1e12)):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", pavefric.PavefricWarning)
            ds = pavefric.simulate(profile_m, DX, [0.0, 20.0, 1e5], **kw)
        for name in ("mu", "max_balance_residual", "mean_hydro_load", "max_compression"):
            assert np.all(np.isfinite(ds[name].values)), (kw, name)


def test_a_huge_rounded_pad_is_flat_not_hydroplaning(profile_m):
    flat = pavefric.simulate(profile_m, DX, [20.0, 60.0])
    huge = pavefric.simulate(profile_m, DX, [20.0, 60.0], shape="rounded", radius=1e12)
    assert np.all(huge["hydroplaning_fraction"].values == 0)
    np.testing.assert_array_equal(huge["mu"].values, flat["mu"].values)


def test_heights_beyond_any_texture_are_refused():
    with pytest.raises(pavefric.PavefricError, match=r"profile height 3 = 1e\+?200 m"):
        pavefric.simulate([0.0, 0.0, 1e200] + [0.0] * 60, DX, [20.0])


def test_huge_but_finite_heights_give_finite_texture_metrics(tmp_path):
    z = np.sin(np.arange(300) * 0.3) * 1e5           # absurd but finite: warned, metrics finite
    with pytest.warns(pavefric.PavefricWarning, match="RMS height"):
        ds = pavefric.simulate(z, 0.5e-3, [20.0], closed=False)
    assert np.isfinite(float(ds["rms_height"])) and np.isfinite(float(ds["rms_slope"]))


# --- Python: bad calls end in PavefricError, never a bare traceback ------------------

BAD_CALLS = [
    lambda z: pavefric.simulate(np.vstack([z, z]), DX, [20.0]),          # 2-D heights
    lambda z: pavefric.simulate(np.ma.masked_array(z, mask=z > 0), DX, [20.0]),
    lambda z: pavefric.simulate(z, DX, [20.0], substeps=2.9),
    lambda z: pavefric.simulate(z, DX, [20.0], closed="False"),
    lambda z: pavefric.simulate(z, DX, [20.0], series="yes"),
    lambda z: pavefric.simulate(None, DX, [20.0]),
    lambda z: pavefric.simulate(z + 1e-4j, DX, [20.0]),                  # complex heights
    lambda z: pavefric.simulate([str(v) for v in z], DX, [20.0]),        # strings
    lambda z: pavefric.simulate(z > 0, DX, [20.0]),                      # booleans
    lambda z: pavefric.simulate("abc", DX, [20.0]),
    lambda z: pavefric.simulate(z, "0.87e-3", [20.0]),
    lambda z: pavefric.simulate(z, None, [20.0]),
    lambda z: pavefric.simulate(z, DX, "fast"),
    lambda z: pavefric.simulate(z, DX, [[20.0, 40.0]]),
    lambda z: pavefric.simulate(z, DX, []),
    lambda z: pavefric.simulate(z, DX, [20.0], mu_loc="high"),
    lambda z: pavefric.simulate(z, DX, [20.0], shape=3),
    lambda z: pavefric.simulate(z, DX, [20.0], depth=None),
    lambda z: pavefric.simulate(z, DX, [20.0], substeps=True),
    lambda z: pavefric.simulate(z, DX, [20.0], load=np.array([1.0, 2.0])),
    lambda z: pavefric.simulate(z, DX, [20.0], depth=math.nan),
    lambda z: pavefric.simulate(z, DX, [20.0], shape="flat\nrounded"),
    lambda z: pavefric.simulate(z, -DX, [20.0]),
    lambda z: pavefric.layout(100, DX, closed="no"),
]


@pytest.mark.parametrize("call", BAD_CALLS, ids=range(len(BAD_CALLS)))
def test_bad_python_calls_raise_pavefric_error(profile_m, call):
    with pytest.raises(pavefric.PavefricError) as info:
        call(profile_m)
    assert str(info.value).strip() and "\n" not in str(info.value).strip()


def test_an_unknown_keyword_is_a_type_error_and_a_pavefric_error(profile_m):
    with pytest.raises(TypeError, match="lenght"):
        pavefric.simulate(profile_m, DX, [20.0], lenght=0.02)
    with pytest.raises(pavefric.PavefricError, match="lenght"):
        pavefric.simulate(profile_m, DX, [20.0], lenght=0.02)


def test_integral_keywords_accept_numpy_integers(profile_m):
    a = pavefric.simulate(profile_m, DX, [40.0], substeps=2)
    b = pavefric.simulate(profile_m, DX, [40.0], substeps=np.int64(2))
    np.testing.assert_array_equal(a["mu"].values, b["mu"].values)


# Issue 19: a 10 MB namelist value ended the program (and a Python or C host)
# with a segmentation fault: a stack buffer as long as the value.
HUGE = 10_000_000


HUGE_BODIES = {
    "title": ("output", lambda: f"title = '{'x' * HUGE}'",
              "&output title: a value of 10000000 characters"),
    "path": ("surface", lambda: f"profile_file = '{'p' * HUGE}'",
             "&surface profile_file: a value of 10000000 characters"),
    "number": ("surface", lambda: f"profile_file = 'scene_profile.txt', mu_loc = 0.{'6' * HUGE}",
               "&surface mu_loc: a value of 10000002 characters"),
}


@pytest.mark.parametrize("which", sorted(HUGE_BODIES))
def test_a_ten_megabyte_value_is_a_clear_error(tmp_path, which):
    group, body, needle = HUGE_BODIES[which]
    scene = write_scene(tmp_path, groups={group: body()})
    r = run_program(scene, "-o", tmp_path / "o.nc")
    assert r.returncode == 1, r.stderr[-300:]
    assert needle in r.stderr and "more than the 65536 allowed" in r.stderr, r.stderr[-300:]
    assert not (tmp_path / "o.nc").exists()


def test_a_ten_megabyte_name_is_a_clear_error(tmp_path):
    scene = write_scene(tmp_path, groups={"operation": "speeds_kmh = 20, " + "a" * HUGE + " = 1"})
    r = run_program(scene, "-o", tmp_path / "o.nc")
    assert r.returncode == 1 and "&operation speeds_kmh: a value of 10000000 characters" \
        in r.stderr, r.stderr[-300:]


def test_a_ten_megabyte_value_through_python_raises(tmp_path):
    """The library too: a PavefricError, and the Python process lives on
    (run in a child so an old library's crash fails this test, not pytest)."""
    import subprocess
    import sys

    scene = write_scene(tmp_path, groups={"output": f"title = '{'x' * HUGE}'"})
    code = ("import pavefric\n"
            "try:\n"
            f"    pavefric.run({str(scene)!r}, {str(tmp_path / 'o.nc')!r})\n"
            "except pavefric.PavefricError as e:\n"
            "    print('raised:', str(e)[:200])\n")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr[-500:]
    assert "raised:" in r.stdout and "a value of 10000000 characters" in r.stdout


def test_two_million_values_end_in_a_clear_error(tmp_path):
    scene = write_scene(tmp_path, groups={"operation": "speeds_kmh = " +
                                          ", ".join(["20"] * 2_000_000)})
    r = run_program(scene, "-o", tmp_path / "o.nc")
    assert r.returncode == 1 and "&operation speeds_kmh: more than 100000 values" in r.stderr


def test_a_ten_megabyte_comment_runs_and_the_scene_is_kept_whole(tmp_path, profile_m):
    """A scene text beyond what an HDF5 attribute holds is written as a
    variable; pavefric.open_dataset gives it back as the attribute."""
    scene = write_scene(tmp_path, profile=profile_m)
    scene.write_text("! " + "c" * HUGE + "\n" + scene.read_text())
    r = run_program(scene, "-o", tmp_path / "o.nc")
    assert r.returncode == 0, r.stderr[-300:]
    ds = pavefric.open_dataset(tmp_path / "o.nc")
    assert ds.attrs["input_namelist"] == scene.read_text()
    with xr.open_dataset(tmp_path / "o.nc") as raw:
        assert raw.attrs["input_namelist"].startswith("in the variable of this name: ")


def _significant_digits(text: str) -> str:
    mantissa = text.lower().lstrip("-").split("e")[0].replace(".", "")
    return mantissa.strip("0") or "0"


def test_the_echo_writes_each_number_in_its_fewest_digits():
    # The output's `parameters` echo writes every real in the fewest
    # significant digits that read back to the same double (the core finds
    # them by bisection over 1..17 digits). Python's repr is an independent
    # shortest round-trip (David Gay's algorithm): same value, same digits.
    rng = np.random.default_rng(7)
    values = [float(v) for v in rng.uniform(0.1, 300.0, 40)]          # 15-17 digits
    values += [round(float(v), int(k)) or 1.0
               for v, k in zip(rng.uniform(0.1, 300.0, 40), rng.integers(0, 14, 40))]
    values += [0.1, 0.3, 1.0, 2.5, 100.0, 120.0, 1 / 3, 2 / 3, 299.99999999999994, 1e-3]
    z = np.sin(np.arange(64) * 0.7) * 3e-4
    ds = pavefric.simulate(z, 0.87e-3, values, error_estimate=False)
    line = [ln for ln in ds.attrs["parameters"].splitlines()
            if ln.strip().startswith("speeds_kmh")][0]
    written = [t.strip() for t in line.split("=", 1)[1].split(",")]
    assert len(written) == len(values)
    for text, value in zip(written, values):
        assert float(text) == value, (text, value)
        assert _significant_digits(text) == _significant_digits(repr(value)), (text, repr(value))


@pytest.mark.parametrize("count", ["99999999999", "1000000000"])
def test_a_huge_repeat_count_is_named_as_too_large(tmp_path, count):
    """An attack found `speeds_kmh = 99999999999*20` told that a repeat count
    needs a whole number >= 1, which it is: it is too large."""
    scene = write_scene(tmp_path, groups={"operation": f"speeds_kmh = {count}*20"})
    r = run_program(scene, "-o", tmp_path / "o.nc")
    assert r.returncode == 1
    assert "&operation speeds_kmh" in r.stderr and "more than 9 digits" in r.stderr
    assert "more values than any list holds" in r.stderr and not (tmp_path / "o.nc").exists()
