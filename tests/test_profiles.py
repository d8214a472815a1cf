"""Real instrument profiles: readers, dropouts, plates, spikes, resampling."""
import subprocess
import sys

import numpy as np
import pytest
import xarray as xr

import pavefric
from conftest import CAPTIF, ROOT, import_captif_slp, run_program, write_scene

STATIONS = ["20211011_aylesbury_dec_station_0.dat", "20211011_aylesbury_dec_station_1.dat"]


def captif(name):
    path = CAPTIF / name
    return path


@pytest.mark.parametrize("station", [0, 1])
@pytest.mark.parametrize("variant", ["", "_ctm"])
def test_real_profiles_run_through_the_program(tmp_path, station, variant):
    captif(STATIONS[station])
    scene = ROOT / "inputs" / "captif" / f"station{station}{variant}.nml"
    out = tmp_path / "o.nc"
    r = run_program(scene, "-o", out)
    assert r.returncode == 0, r.stderr
    with xr.open_dataset(out) as ds:
        assert np.all(np.isfinite(ds["mu"].values)) and np.all(ds["mu"].values > 0)
        assert "hydrodynamic_bearing" in ds.attrs["effects"]
        assert ds.attrs["preprocess_format"] == "captif"
        assert ds.attrs["preprocess_dropouts"] > 1000            # ~5 % of the points
        assert ds.attrs["preprocess_trimmed_start"] > 0 and ds.attrs["preprocess_trimmed_end"] > 0
        assert "dropouts interpolated" in ds.attrs["preprocessing"]
        # the pad's own 0.87 mm elements whatever the spacing (&pad element_length)
        assert ds.attrs["pad_elements"] == 23
        assert float(ds["mpd"]) > 1e-3
        # dry at the same profile: water lowers friction
    dry = tmp_path / "dry.nml"
    dry.write_text(scene.read_text().replace("depth = 1.0e-3", "depth = 0.0")
                   .replace("'../data/", f"'{ROOT}/inputs/data/"))
    r = run_program(dry, "-o", tmp_path / "dry.nc")
    assert r.returncode == 0, r.stderr
    with xr.open_dataset(out) as wet, xr.open_dataset(tmp_path / "dry.nc") as d:
        assert np.all(wet["mu"].values < d["mu"].values)
        assert "hydrodynamic_bearing" not in d.attrs["effects"]


@pytest.mark.parametrize("name", STATIONS)
def test_read_profile_reports_what_it_did(name):
    p = pavefric.read_profile(captif(name), dropouts="interpolate")
    r = p.report
    assert r["format"] == "captif" and r["has_distances"]
    assert r["points_read"] > 50_000
    assert r["points_out"] == r["points_read"] - r["trimmed_start"] - r["trimmed_end"]
    assert p.dx == pytest.approx(0.0375e-3, rel=0.01)
    assert np.all(np.isfinite(p.heights))
    assert np.abs(p.heights).max() < 0.015                     # no plate left (+47 mm)
    assert np.isnan(p.raw_heights).sum() > 1000                 # the raw dropouts, kept


@pytest.mark.parametrize("name", STATIONS)
@pytest.mark.parametrize("spacing_mm", [0.5, 1.0])
def test_mpd_within_one_percent_of_captif_slp(name, spacing_mm):
    captif_slp = import_captif_slp()   # setup.sh and CI install it; CI never skips
    path = captif(name)
    p = pavefric.read_profile(path, dropouts="interpolate", resample_dx=spacing_mm * 1e-3,
                              spike_slope=3.0, lowpass_wavelength=2.4e-3)
    ours = pavefric.texture(p, closed=False)
    theirs = captif_slp.Reading.from_file(path, detect_plates=True,
                                          target_sample_spacing_mm=spacing_mm).mpd()
    assert ours["mpd"] * 1e3 == pytest.approx(theirs["mpd"], rel=0.01)
    assert ours["n_valid"] == theirs["valid_segments"]


def test_instrument_file_and_clean_export_give_the_same_friction(tmp_path):
    path = captif(STATIONS[0])
    export = tmp_path / "clean.txt"
    r = subprocess.run([sys.executable, "-m", "pavefric", "profile", str(path), "--dropouts",
                        "interpolate", "--resample-mm", "0.87", "--export", str(export)],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    opts = "&preprocess dropouts = 'interpolate', resample_dx = 0.87e-3 /\n"
    common = "&water depth = 1e-3 /\n&operation speeds_kmh = 20, 60 /\n"
    a = tmp_path / "instrument.nml"
    a.write_text(f"&surface profile_file = '{path}', closed = .false., mu_loc = 0.6 /\n"
                 + opts + common)
    b = tmp_path / "export.nml"
    b.write_text(f"&surface profile_file = '{export}', closed = .false., mu_loc = 0.6 /\n"
                 + common)
    for scene in (a, b):
        assert run_program(scene, "-o", scene.with_suffix(".nc")).returncode == 0
    with xr.open_dataset(a.with_suffix(".nc")) as da, xr.open_dataset(b.with_suffix(".nc")) as db:
        np.testing.assert_allclose(db["mu"].values, da["mu"].values, rtol=1e-9)
        assert db.attrs["preprocess_format"] == "plain"


def test_dropout_under_the_strict_default_names_file_and_line(tmp_path):
    path = captif(STATIONS[0])
    scene = tmp_path / "s.nml"
    scene.write_text(f"&surface profile_file = '{path}', closed = .false. /\n"
                     "&operation speeds_kmh = 20 /\n")
    out = tmp_path / "o.nc"
    r = run_program(scene, "-o", out)
    assert r.returncode != 0
    lines = [l for l in r.stderr.splitlines() if l.strip()]
    assert len(lines) == 1
    assert f"{path}:" in lines[0] and "dropout" in lines[0]
    assert "dropouts = 'interpolate'" in lines[0]
    line_no = int(lines[0].split(f"{path}:")[1].split(":")[0])
    text = path.read_text().splitlines()[line_no - 1].rstrip("\r").split("\t")
    assert len(text) < 3 or text[2] in ("", "NaN")            # that line is a dropout
    assert not out.exists()
    scene.write_text(scene.read_text() + "&preprocess dropouts = 'interpolate' /\n")
    assert run_program(scene, "-o", out).returncode == 0


def test_plain_file_with_a_nan_is_a_dropout(tmp_path):
    z = np.sin(np.arange(300) * 0.3) * 0.5
    text = "height_mm\n" + "\n".join(f"{v:.6f}" for v in z[:100]) + "\nnan\n" + \
        "\n".join(f"{v:.6f}" for v in z[101:]) + "\n"
    strict = write_scene(tmp_path, "strict", profile_text=text)
    r = run_program(strict, "-o", tmp_path / "s.nc")
    assert r.returncode != 0 and "strict_profile.txt:102" in r.stderr
    scene = write_scene(tmp_path, "interp", profile_text=text,
                        groups={"preprocess": "dropouts = 'interpolate'"})
    assert run_program(scene, "-o", tmp_path / "i.nc").returncode == 0


def test_csv_with_named_columns(tmp_path):
    x = np.arange(400) * 0.5
    z = np.sin(x / 3.0)
    csv = tmp_path / "road.csv"
    csv.write_text("segment,distance (mm),height (mm),quality\n" +
                   "\n".join(f"A,{a},{b:.6f},ok" for a, b in zip(x, z)) + "\n")
    p = pavefric.read_profile(csv)
    assert p.report["format"] == "csv" and p.dx == pytest.approx(0.5e-3)
    np.testing.assert_allclose(p.heights, z * 1e-3, atol=1e-9)
    q = pavefric.read_profile(csv, x_column="distance (mm)", z_column="height (mm)")
    np.testing.assert_array_equal(q.heights, p.heights)
    with pytest.raises(pavefric.PavefricError, match="z_column = 'elevation'"):
        pavefric.read_profile(csv, z_column="elevation")


def test_plates_are_trimmed_but_a_spike_is_not(tmp_path):
    z = np.sin(np.arange(2000) * 0.2) * 0.5
    z[:100] = 45.0                      # a 10 mm plate at 0.1 mm spacing
    z[1900:] = 45.0
    z[1000] = 60.0                      # one spike, not a plate
    f = tmp_path / "p.txt"
    f.write_text("\n".join(f"{i * 0.1:.3f} {v:.6f}" for i, v in enumerate(z)) + "\n")
    p = pavefric.read_profile(f)
    assert p.report["trimmed_start"] == 100 + 20    # plate + 2 mm buffer
    assert p.report["trimmed_end"] == 100 + 20
    assert p.heights.max() == pytest.approx(0.060)  # the spike stays (no spike removal)
    q = pavefric.read_profile(f, spike_slope=3.0)
    # a one-point spike makes two jumps; each flags both its points: 3 replaced
    assert q.report["spikes"] == 3 and q.heights.max() < 0.001


def test_lowpass_matches_scipy(tmp_path):
    import scipy.signal as signal  # a declared dependency: fail, never skip
    rng = np.random.default_rng(2)
    z = rng.normal(0, 1e-3, 500)
    path = tmp_path / "p.txt"
    path.write_text("\n".join(f"{v * 1e3:.17g}" for v in z) + "\n")
    p = pavefric.read_profile(path, dx=0.5e-3, trim_plates=False, lowpass_wavelength=2.4e-3)
    # 2nd-order Butterworth, cut-off 1/2.4 mm-1 at 0.5 mm spacing, forward and back
    sos = signal.butter(2, (1 / 2.4) / (0.5 * 1 / 0.5), output="sos")
    np.testing.assert_allclose(p.heights, signal.sosfiltfilt(sos, z), atol=1e-12)


def test_preprocess_bad_input(tmp_path):
    scene = write_scene(tmp_path, groups={"preprocess": "dropouts = 'guess'"})
    r = run_program(scene, "-o", tmp_path / "o.nc")
    assert r.returncode != 0 and "&preprocess dropouts = 'guess'" in r.stderr
    scene = write_scene(tmp_path, groups={"preprocess": "resample_dx = -1"})
    r = run_program(scene, "-o", tmp_path / "o.nc")
    assert r.returncode != 0 and "&preprocess resample_dx = -1" in r.stderr
    scene = write_scene(tmp_path, groups={"surface": "profile_file = 'scene_profile.txt', "
                                                     "format = 'xml'"})
    r = run_program(scene, "-o", tmp_path / "o.nc")
    assert r.returncode != 0 and "&surface format = 'xml'" in r.stderr


def test_native_spacing_pad_has_hundreds_of_elements():
    p = pavefric.read_profile(captif(STATIONS[1]), dropouts="interpolate")
    ds = pavefric.simulate(p.heights, p.dx, [60.0], closed=False, depth=1e-3,
                           element_length=0.0)
    assert ds.attrs["pad_elements"] == 533
    assert np.isfinite(ds["mu"].values[0])
    assert ds["max_balance_residual"].values[0] <= 1e-12


def test_lines_longer_than_the_read_buffer(tmp_path):
    f = tmp_path / "long.txt"
    f.write_text("height_mm\n0." + "1" * 600 + "   # a 600-character number\n" +
                 "\n".join(["0.2"] * 60) + "\n")
    p = pavefric.read_profile(f)
    assert p.report["points_read"] == 61
    assert p.heights[0] == pytest.approx(0.1111111111111111e-3, rel=1e-15)


@pytest.mark.parametrize("body,needle", [
    ("plate_threshold = 0", "&preprocess plate_threshold = 0"),
    ("plate_min_length = -1e-3", "&preprocess plate_min_length = -0.001"),
    ("plate_buffer = -1e-3", "&preprocess plate_buffer = -0.001"),
    ("spike_slope = -3", "&preprocess spike_slope = -3"),
    ("lowpass_wavelength = -2.4e-3", "&preprocess lowpass_wavelength = -0.0024"),
    ("lowpass_wavelength = 1e-3", "&preprocess lowpass_wavelength = 0.001"),   # < 2 samples
])
def test_preprocess_bounds(tmp_path, body, needle):
    scene = write_scene(tmp_path, groups={"preprocess": body})
    r = run_program(scene, "-o", tmp_path / "o.nc")
    assert r.returncode == 1 and needle in r.stderr, r.stderr
    assert not (tmp_path / "o.nc").exists()


def test_csv_named_x_column_missing(tmp_path):
    csv = tmp_path / "road.csv"
    csv.write_text("distance (mm),height (mm)\n0,0.1\n0.5,0.2\n1.0,0.1\n")
    with pytest.raises(pavefric.PavefricError, match="x_column = 'chainage'"):
        pavefric.read_profile(csv, x_column="chainage")
