"""Batch output conventions (issue 10 item 10), exit codes and the summary
(item 7), the profile list (items 8 and 10), plots of batch files."""
import json
import os
import subprocess
import sys
import warnings

import numpy as np
import pytest
import xarray as xr

import pavefric
from conftest import program, run_program
from test_batch import make_batch

KMH_TO_MS = 1.0 / 3.6          # pavefric_kinds: speed = speed_kmh * kmh_to_ms


def list_batch(tmp_path, n=8, broken=3, chainage=True, speeds="21, 42", depths="0.0, 1.0e-3"):
    """A batch over a profile list with a chainage column (m) and one broken
    profile (text where a height should be)."""
    from pavefric.surfaces import road_profiles

    road_profiles(str(tmp_path / "profiles"), n=n, points=300)
    if broken:
        (tmp_path / "profiles" / f"seg_{broken:04d}.txt").write_text("height_mm\n0.1\nx\n")
    rows = [f"profiles/seg_{k:04d}.txt" + (f"  {1000.0 + 0.5 * (k - 1):.1f}" if chainage else "")
            for k in range(1, n + 1)]
    (tmp_path / "list.txt").write_text("# segment  chainage_m\n" + "\n".join(rows) + "\n")
    scene = tmp_path / "batch.nml"
    scene.write_text(f"&batch profile_list = 'list.txt', depths = {depths} /\n"
                     "&surface closed = .false., mu_loc = 0.6 /\n"
                     f"&operation speeds_kmh = {speeds} /\n")
    return scene


@pytest.fixture(scope="module")
def batch_file(tmp_path_factory):
    d = tmp_path_factory.mktemp("out")
    scene = list_batch(d)
    out = d / "b.nc"
    r = run_program(scene, "-o", out)
    assert r.returncode == 4, r.stderr
    return out


def cf_check(path, tmp_path):
    """The IOOS compliance checker's CF 1.10 suite at its strictest: the
    points scored and possible, and every message it reports."""
    from compliance_checker.runner import CheckSuite, ComplianceChecker

    CheckSuite.load_all_available_checkers()
    report = tmp_path / "cf.json"
    ComplianceChecker.run_checker(str(path), ["cf:1.10"], 0, "strict",
                                  output_filename=str(report), output_format="json")
    r = json.loads(report.read_text())["cf:1.10"]
    msgs = [m for level in ("high_priorities", "medium_priorities", "low_priorities")
            for item in r[level] for m in item["msgs"]]
    return r["scored_points"], r["possible_points"], msgs


def test_batch_file_passes_the_cf_1_10_checker(batch_file, tmp_path):
    scored, possible, msgs = cf_check(batch_file, tmp_path)
    assert msgs == [] and scored == possible, msgs


def test_batch_file_without_failures_passes_the_cf_1_10_checker(tmp_path):
    """No profile failed and no chainage: integers without _FillValue, the
    profile numbers and names alone as coordinates; still clean CF 1.10."""
    scene = list_batch(tmp_path, n=3, broken=0, chainage=False)
    out = tmp_path / "b.nc"
    r = run_program(scene, "-o", out)
    assert r.returncode == 0, r.stderr
    with xr.open_dataset(out) as ds:
        assert ds["preprocess_points_read"].dtype.kind == "i" and "chainage" not in ds
        assert set(ds["mu"].coords) == {"profile", "profile_name", "water_depth", "speed_kmh",
                                        "speed"}
    scored, possible, msgs = cf_check(out, tmp_path)
    assert msgs == [] and scored == possible, msgs


def test_sel_by_speed_kmh_and_profile_name(batch_file):
    with xr.open_dataset(batch_file) as ds:
        assert set(ds.indexes) == {"profile", "water_depth", "speed_kmh"}
        mu = ds["mu"].set_xindex("profile_name").sel(speed_kmh=42, profile_name="seg_0005",
                                                       water_depth=1.0e-3)
        assert float(mu) == float(ds["mu"].sel(speed_kmh=42, profile=5, water_depth=1.0e-3))
        assert float(mu) == float(ds["mu"].values[4, 1, 1]) and 0 < float(mu) < 1
        assert ds["mu"].sel(speed_kmh=21).dims == ("profile", "water_depth")
        # speed (m/s) is an auxiliary coordinate, not an axis (not a longitude)
        assert "speed" in ds.coords and "axis" not in ds["speed"].attrs
        assert ds["speed"].attrs["units"] == "m s-1"
        # the one conversion: speed_kmh * kmh_to_ms (21 / 3.6 is another number)
        assert np.array_equal(ds["speed"].values, ds["speed_kmh"].values * KMH_TO_MS)
        assert ds["speed"].values[0] != 21 / 3.6
        assert "standard_name" not in ds["water_depth"].attrs
        assert "water film" in ds["water_depth"].attrs["long_name"]


def test_chainage_from_the_profile_list(batch_file):
    with xr.open_dataset(batch_file) as ds:
        assert ds["chainage"].attrs["units"] == "m"
        assert np.array_equal(ds["chainage"].values, 1000.0 + 0.5 * np.arange(8))
        assert "chainage" in ds["mu"].coords and "chainage" in ds["mpd"].coords
        # along the road by chainage
        assert float(ds["mu"].swap_dims(profile="chainage").sel(
            chainage=1001.5, speed_kmh=21, water_depth=0.0)) == float(ds["mu"].values[3, 0, 0])


def test_preprocessing_record_per_profile(batch_file):
    with xr.open_dataset(batch_file) as ds:
        ok = ds["status"].values == 1
        assert np.array_equal(ds["preprocess_points_read"].values[ok], np.full(7, 300.0))
        assert np.array_equal(ds["preprocess_points_out"].values[ok], np.full(7, 300.0))
        assert np.all(ds["preprocess_dropouts"].values[ok] == 0)
        assert np.all(ds["preprocess_resampled"].values[ok] == 0)
        assert np.all(ds["profile_dx"].values[ok] == 0.87e-3)
        assert ds["profile_dx"].attrs["units"] == "m"
        # the broken profile was never read: fill values
        assert np.isnan(ds["preprocess_points_read"].values[2])
        assert np.isnan(ds["profile_dx"].values[2])


def test_preprocessing_record_counts_dropouts_and_resampling(tmp_path):
    from pavefric.surfaces import spectral_profile

    z = spectral_profile(400, 0.87e-3, rms=0.4e-3, seed=2) * 1e3
    rows = [f"{v:.6f}" for v in z]
    rows[100] = rows[200] = rows[201] = "nan"
    (tmp_path / "p.txt").write_text("height_mm\n" + "\n".join(rows) + "\n")
    (tmp_path / "list.txt").write_text("p.txt\n")
    scene = tmp_path / "s.nml"
    scene.write_text("&batch profile_list = 'list.txt' /\n&surface closed = .false. /\n"
                     "&preprocess dropouts = 'interpolate', resample_dx = 1.0e-3 /\n"
                     "&operation speeds_kmh = 20 /\n")
    r = run_program(scene, "-o", tmp_path / "o.nc")
    assert r.returncode == 0, r.stderr
    with xr.open_dataset(tmp_path / "o.nc") as ds:
        assert int(ds["preprocess_points_read"].values[0]) == 400
        assert int(ds["preprocess_dropouts"].values[0]) == 3
        assert int(ds["preprocess_resampled"].values[0]) == 1
        assert float(ds["preprocess_dx_in"].values[0]) == pytest.approx(0.87e-3)
        assert float(ds["profile_dx"].values[0]) == pytest.approx(1.0e-3)


def test_profile_list_format_errors_and_quoted_paths(tmp_path):
    scene = list_batch(tmp_path, n=4, broken=0)
    lst = tmp_path / "list.txt"
    # mixed: chainage on some lines only
    lst.write_text("profiles/seg_0001.txt 10\nprofiles/seg_0002.txt\n")
    r = run_program(scene, "-o", tmp_path / "o.nc")
    assert r.returncode == 1 and "list.txt:2: no chainage, but line 1 gives one" in r.stderr
    lst.write_text("profiles/seg_0001.txt 10\nprofiles/seg_0002.txt 1-3\n")
    r = run_program(scene, "-o", tmp_path / "o.nc")
    assert r.returncode == 1 and "list.txt:2: chainage '1-3' is not a finite number (m)" in r.stderr
    lst.write_text("profiles/seg_0001.txt 10 20\n")
    r = run_program(scene, "-o", tmp_path / "o.nc")
    assert r.returncode == 1 and "list.txt:1: '20' after the chainage" in r.stderr
    lst.write_text("profiles/seg_0001.txt\nprofiles/seg_0002.txt\nprofiles/seg_0001.txt\n")
    r = run_program(scene, "-o", tmp_path / "o.nc")
    assert r.returncode == 1 and "is given twice (entries 1 and 3)" in r.stderr
    # the same file by another spelling of its path (attack17 V8: it ran twice)
    lst.write_text("profiles/seg_0001.txt\nprofiles/seg_0002.txt\n./profiles//./seg_0001.txt\n")
    r = run_program(scene, "-o", tmp_path / "o.nc")
    assert r.returncode == 1, r.stderr
    assert ("is given twice (entries 1 and 3), as 'profiles/seg_0001.txt' and "
            "'./profiles//./seg_0001.txt'") in r.stderr.replace(str(tmp_path) + "/", ""), r.stderr
    # one file by two names (a symbolic link, a hard link: it ran twice)
    links = tmp_path / "links"
    links.mkdir()
    (links / "soft.txt").symlink_to(tmp_path / "profiles" / "seg_0001.txt")
    os.link(tmp_path / "profiles" / "seg_0002.txt", links / "hard.txt")
    for twin, entries in (("soft.txt", "1 and 2"), ("hard.txt", "2 and 3")):
        lst.write_text("profiles/seg_0001.txt\nprofiles/seg_0002.txt\nlinks/" + twin + "\n"
                       if twin == "hard.txt" else
                       "profiles/seg_0001.txt\nlinks/soft.txt\nprofiles/seg_0002.txt\n")
        r = run_program(scene, "-o", tmp_path / "o.nc")
        assert r.returncode == 1, r.stderr
        assert f"is given twice (entries {entries})" in r.stderr and "(one file)" in r.stderr \
            and f"'links/{twin}'" in r.stderr.replace(str(tmp_path) + "/", ""), r.stderr
        assert not (tmp_path / "o.nc").exists()
    # a path with blanks, quoted; '#' comments; two files of the same name
    (tmp_path / "my dir").mkdir()
    (tmp_path / "other").mkdir()
    (tmp_path / "profiles" / "seg_0001.txt").rename(tmp_path / "my dir" / "seg.txt")
    (tmp_path / "profiles" / "seg_0002.txt").rename(tmp_path / "other" / "seg.txt")
    lst.write_text("'my dir/seg.txt' 5.0  # first\n\n# a comment line\nother/seg.txt 7.5\n")
    r = run_program(scene, "-o", tmp_path / "o.nc")
    assert r.returncode == 0, r.stderr
    with xr.open_dataset(tmp_path / "o.nc") as ds:
        assert list(ds["profile_name"].values) == ["my dir/seg", "other/seg"]
        assert list(ds["chainage"].values) == [5.0, 7.5]


def test_long_profile_list(tmp_path):
    # 40,000 entries (the old reader grew its array by concatenation: 23 s on
    # every restart; the figure is in docs/cluster.md, from the benchmark)
    d = tmp_path / "p"
    d.mkdir()
    body = "height_mm\n" + "\n".join("0.1" if k % 2 else "-0.1" for k in range(64)) + "\n"
    names = []
    for k in range(40_000):
        (d / f"{k:05d}.txt").write_text(body)
        names.append(f"p/{k:05d}.txt {0.25 * k}")
    (tmp_path / "list.txt").write_text("\n".join(names) + "\n")
    scene = tmp_path / "s.nml"
    scene.write_text("&batch profile_list = 'list.txt' /\n&surface closed = .false. /\n"
                     "&operation speeds_kmh = 20 /\n")
    r = run_program(scene, "-o", tmp_path / "o.nc", "--max-profiles", "2")
    assert r.returncode == 3, r.stderr
    assert "40000 profiles: 2 done in this run (failed included)" in r.stdout and "39998 left" in r.stdout
    r = run_program(scene, "-o", tmp_path / "o.nc", "--max-profiles", "1")
    assert r.returncode == 3 and "resuming: 2 of 40000 profiles already done" in r.stderr


def test_failed_batch_does_not_look_like_success(tmp_path):
    # every profile failing: exit 4 (the old code: 0 and "100 %")
    scene = make_batch(tmp_path, n=5)
    for p in (tmp_path / "profiles").glob("*.txt"):
        p.write_text("height_mm\nabc\n")
    out = tmp_path / "o.nc"
    r = run_program(scene, "-o", out)
    assert r.returncode == 4, r.stdout + r.stderr
    assert "5/5 profiles (100.0 %, 5 failed)" in r.stderr
    assert f"-> {out}: 5 profiles: 5 done in this run (failed included), 0 taken from the journal, " \
           "5 failed" in r.stdout
    assert "pavefric: profile seg_0001: " in r.stderr and "'abc'" in r.stderr
    assert "5 of 5 profiles failed" in r.stderr
    with xr.open_dataset(out) as ds:
        assert ds.attrs["profiles_failed"] == 5 and ds.attrs["profiles_computed"] == 0


def test_python_run_warns_naming_the_failed_profiles(tmp_path):
    scene = make_batch(tmp_path, n=6, broken=True)
    with pytest.warns(pavefric.ProfilesFailedWarning) as caught:
        out = pavefric.run(scene, tmp_path / "o.nc", progress=False)
    assert out == tmp_path / "o.nc" and out.exists()
    w = caught[0].message
    assert w.path == out and list(w.failed) == ["seg_0005"]
    assert "seg_0005.txt:3" in w.failed["seg_0005"]
    assert "1 of 6 profiles failed" in str(w)
    # a batch without failures: no ProfilesFailedWarning (its profiles' own
    # warnings, here 1 mm of water over shallow texture, are PavefricWarnings)
    scene = make_batch(tmp_path / "good", n=3)
    with warnings.catch_warnings():
        warnings.simplefilter("error", pavefric.ProfilesFailedWarning)
        pavefric.run(scene, tmp_path / "good.nc", progress=False)


def test_python_m_pavefric_run_exits_4_as_the_program_does(tmp_path):
    import sys

    scene = make_batch(tmp_path, n=6, broken=True)
    r = subprocess.run([sys.executable, "-m", "pavefric", "run", str(scene), "-o",
                        str(tmp_path / "o.nc")], capture_output=True, text=True, timeout=600)
    assert r.returncode == 4, r.stdout + r.stderr
    assert "1 of 6 profiles failed" in r.stderr and "seg_0005" in r.stderr
    assert (tmp_path / "o.nc").exists()
    good = make_batch(tmp_path / "good", n=3)
    r = subprocess.run([sys.executable, "-m", "pavefric", "run", str(good), "-o",
                        str(tmp_path / "good.nc")], capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr


def test_help_documents_exit_codes():
    r = subprocess.run([program(), "--help"], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0
    for code, words in (("0", "success"), ("1", "error"), ("2", "bad usage"),
                        ("3", "stopped early"), ("4", "some profiles failed")):
        assert any(line.strip().startswith(code + " ") and words in line
                   for line in r.stdout.splitlines()), (code, words)
    r = subprocess.run([program(), "--frobnicate"], capture_output=True, text=True, timeout=60)
    assert r.returncode == 2


def test_plot_a_batch_file(batch_file, tmp_path):
    png = tmp_path / "road.png"
    r = subprocess.run([sys.executable, "-m", "pavefric", "plot", str(batch_file), "-o", str(png)],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    import matplotlib.image

    img = matplotlib.image.imread(png)
    assert img.ndim == 3 and img.shape[0] > 300 and img.shape[1] > 500
    from pavefric.plot import batch_curves

    with xr.open_dataset(batch_file) as ds:
        x, xlabel, curves = batch_curves(ds)
        assert xlabel == "chainage (m)" and np.array_equal(x, ds["chainage"].values)
        assert set(curves) == {(0.0, 21.0), (0.0, 42.0), (1e-3, 21.0), (1e-3, 42.0)}
        assert np.array_equal(curves[(1e-3, 42.0)], ds["mu"].values[:, 1, 1], equal_nan=True)
        assert np.isnan(curves[(0.0, 21.0)][2])           # the failed profile is a gap



def test_a_batch_file_records_the_parameters_used(tmp_path):
    """A batch file carries, as a scene's file does, every variable used
    (`parameters`, defaults included) and each one typed (`param_*`): run as
    a batch scene again, `parameters` gives the same numbers bit for bit."""
    scene = list_batch(tmp_path, n=3, broken=0, chainage=False, speeds="30, 70")
    out = tmp_path / "b.nc"
    r = run_program(scene, "-o", out)
    assert r.returncode == 0, r.stderr
    with pavefric.open_dataset(out) as ds:
        text = ds.attrs["parameters"]
        assert ds.attrs["param_surface_mu_loc"] == 0.6
        assert ds.attrs["param_surface_closed"] == 0
        assert ds.attrs["param_batch_profile_list"] == "list.txt"
        np.testing.assert_array_equal(np.atleast_1d(ds.attrs["param_batch_depths"]), [0.0, 1.0e-3])
        np.testing.assert_array_equal(np.atleast_1d(ds.attrs["param_operation_speeds_kmh"]),
                                      [30.0, 70.0])
        # defaults the scene did not set are there too
        assert ds.attrs["param_rubber_stiffness"] == 1.4e8
        assert "&rubber" in text and "&batch" in text and "profile_list = 'list.txt'" in text
        mu = ds["mu"].values.copy()
    again = tmp_path / "again.nml"
    again.write_text(text)
    r = run_program(again, "-o", tmp_path / "again.nc")
    assert r.returncode == 0, r.stderr
    with pavefric.open_dataset(tmp_path / "again.nc") as ds:
        np.testing.assert_array_equal(ds["mu"].values, mu)
        assert ds.attrs["parameters"] == text


def test_a_batch_names_its_variables_as_a_scene_does(batch_file, profile_m):
    """The variables a batch's file shares with a scene's carry the same
    long_name (the review: 'mpd' read "mean profile depth" in a batch and
    "mean profile depth (ISO 13473-1 / ASTM E1845)" in a scene); the batch's
    own description is whole in comment where it says more."""
    scene = pavefric.simulate(profile_m, 0.87e-3, [20.0, 60.0], depth=1e-3)
    with xr.open_dataset(batch_file) as ds:
        shared = [v for v in ds.variables if v in scene.variables and v not in
                  ("speed", "speed_kmh")]
        assert {"mu", "mu_hysteresis", "mu_error_estimate", "elements_per_sample_used",
                "mpd", "rms_slope", "wet_fraction"} <= set(shared)
        for v in shared:
            assert ds[v].attrs["long_name"] == scene[v].attrs["long_name"], v
            assert len(ds[v].attrs["long_name"]) <= 80, v
            if "comment" in ds[v].attrs:
                assert ds[v].attrs["comment"] != ds[v].attrs["long_name"], v
