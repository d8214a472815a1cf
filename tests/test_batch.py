"""Batch runs: one NetCDF over many profiles, MPI, restart, broken profiles."""
import os
import shutil
import signal
import subprocess
import time

import numpy as np
import pytest
import xarray as xr

import pavefric
from conftest import ROOT, program, run_program

DEMO = ROOT / "inputs" / "batch_demo.nml"
VARS = ("mu", "mu_hysteresis", "mu_adhesion", "wet_fraction", "hydroplaning_fraction", "max_balance_residual", "n_clamped",
        "mpd", "rms_height", "rms_slope", "status", "profile", "error_message")


def same_contents(a, b, ignore_attrs=("history",)):
    """Every variable (coordinates included) equal bit for bit, and the
    attributes but `ignore_attrs`."""
    with xr.open_dataset(a) as x, xr.open_dataset(b) as y:
        assert set(x.variables) == set(y.variables)
        assert set(VARS) <= set(x.variables)
        for v in x.variables:
            xv, yv = x[v].values, y[v].values
            assert xv.dtype == yv.dtype, v
            if xv.dtype.kind == "f":
                assert np.array_equal(xv, yv, equal_nan=True), v
            else:
                assert np.array_equal(xv, yv), v
        for k in set(x.attrs) | set(y.attrs):
            if k not in ignore_attrs:
                assert np.array_equal(np.asarray(x.attrs[k]), np.asarray(y.attrs[k])), k


def make_batch(tmp_path, n=24, broken=False, speeds="20, 60", depths="0.0, 1.0e-3"):
    from pavefric.surfaces import road_profiles

    road_profiles(str(tmp_path / "profiles"), n=n, points=256)
    if broken:
        (tmp_path / "profiles" / "seg_0005.txt").write_text("height_mm\n0.1\nabc\n0.2\n")
    scene = tmp_path / "batch.nml"
    scene.write_text(f"&batch profiles = 'profiles/*.txt', depths = {depths} /\n"
                     "&surface closed = .false., mu_loc = 0.6 /\n"
                     f"&operation speeds_kmh = {speeds} /\n")
    return scene


@pytest.fixture(scope="module")
def serial_demo(tmp_path_factory):
    out = tmp_path_factory.mktemp("serial") / "demo.nc"
    r = run_program(DEMO, "-o", out)
    assert r.returncode == 0, r.stderr
    return out


def test_demo_batch_output(serial_demo):
    with xr.open_dataset(serial_demo) as ds:
        assert dict(ds.sizes) == {"profile": 300, "water_depth": 3, "speed_kmh": 4}
        assert ds["mu"].dims == ("profile", "water_depth", "speed_kmh")
        assert ds["profile"].values.tolist() == list(range(1, 301))
        assert ds["profile_name"].values[0] == "seg_0001"
        assert np.all(ds["status"].values == 1)
        # no profile failed, so no integer can be missing: integers stay integers
        for v in ("preprocess_points_read", "preprocess_spikes", "preprocess_resampled",
                  "n_clamped", "n_warnings"):
            assert ds[v].dtype.kind == "i" and "_FillValue" not in ds[v].encoding, v
        assert np.all(np.isfinite(ds["mu"].values))
        assert np.all(ds["max_balance_residual"].values <= 1e-12)
        # dry (depth 0) is above wet at speed, texture beside friction
        assert np.all(ds["mu"].sel(water_depth=0.0).values[:, -1] >
                      ds["mu"].isel(water_depth=2).values[:, -1])
        assert np.all(ds["mpd"].values > 0) and ds["mpd"].attrs["units"] == "m"
        assert ds.attrs["profiles_failed"] == 0


def test_batch_splits_mu_as_a_single_scene_does(tmp_path):
    """Issue 20: mu_hysteresis and mu_adhesion per profile, depth and speed,
    adding up to mu, and equal to a single scene's of the same profile; a
    failed profile has neither."""
    scene = make_batch(tmp_path, n=4, broken=True)
    out = tmp_path / "b.nc"
    r = run_program(scene, "-o", out)
    assert r.returncode == 4, r.stderr
    with xr.open_dataset(out) as ds:
        ok = ds["status"].values == 1
        mu, hyst, adh = (ds[v].values for v in ("mu", "mu_hysteresis", "mu_adhesion"))
        assert ds["mu_hysteresis"].dims == ("profile", "water_depth", "speed_kmh")
        np.testing.assert_allclose((hyst + adh)[ok], mu[ok], rtol=1e-14, atol=1e-15)
        assert np.all(adh[ok] > 0) and np.all(np.isnan(hyst[~ok])) and np.all(np.isnan(adh[~ok]))
        # a failed profile's integers are missing: they have a _FillValue
        for v in ("preprocess_points_read", "preprocess_spikes", "preprocess_filtered",
                  "n_clamped"):
            assert ds[v].encoding.get("_FillValue") is not None, v
            assert np.all(np.isnan(ds[v].values[~ok])) and np.all(np.isfinite(ds[v].values[ok]))
        name = str(ds["profile_name"].values[0])
        z = pavefric.read_profile(tmp_path / "profiles" / f"{name}.txt").heights
        for d, depth in enumerate(ds["water_depth"].values):
            one = pavefric.simulate(z, 0.87e-3, [20.0, 60.0], closed=False, mu_loc=0.6,
                                    depth=float(depth))
            for v in ("mu", "mu_hysteresis", "mu_adhesion"):
                np.testing.assert_allclose(ds[v].values[0, d], one[v].values, rtol=1e-13)


def test_mpi_two_ranks_same_as_serial(tmp_path, serial_demo):
    mpirun = shutil.which("mpirun")
    if mpirun is None:
        pytest.fail("mpirun not found: setup.sh installs Open MPI (openmpi-bin)")
    out = tmp_path / "mpi.nc"
    env = {**os.environ, "OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
           "OMP_NUM_THREADS": "1"}
    r = subprocess.run([mpirun, "--oversubscribe", "-n", "2", program(), str(DEMO), "-o",
                        str(out)], capture_output=True, text=True, env=env, timeout=600)
    assert r.returncode == 0, r.stderr + r.stdout
    assert "on 2 MPI ranks" in r.stderr
    same_contents(serial_demo, out)


def test_killed_batch_resumes_without_recomputing(tmp_path):
    scene = make_batch(tmp_path, n=400, speeds="10, 20, 30, 40, 50, 60, 70, 80")
    clean = tmp_path / "clean.nc"
    assert run_program(scene, "-o", clean).returncode == 0
    out = tmp_path / "killed.nc"
    journal = tmp_path / "killed.nc.journal"
    proc = subprocess.Popen([program(), str(scene), "-o", str(out)], stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)
    deadline = time.time() + 120
    while time.time() < deadline:
        if journal.exists() and journal.read_text().count("\nP ") >= 30:
            break
        time.sleep(0.005)
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    assert not out.exists()
    done = journal.read_text().count("\nP ")
    assert 30 <= done < 400, done
    r = run_program(scene, "-o", out)
    assert r.returncode == 0, r.stderr
    resumed = int(r.stderr.split("resuming: ")[1].split(" of ")[0])
    assert resumed >= done - 1          # a line cut by the kill is recomputed, nothing else
    assert not journal.exists()
    same_contents(clean, out)


def test_stopped_batch_recomputes_no_finished_profile(tmp_path):
    scene = make_batch(tmp_path, n=30)
    clean = tmp_path / "clean.nc"
    assert run_program(scene, "-o", clean).returncode == 0
    out = tmp_path / "part.nc"
    r = run_program(scene, "-o", out, "--max-profiles", "12")
    assert r.returncode == 3 and "resume" in r.stderr
    assert not out.exists()
    # the rest through the core, counting what it computes
    from pavefric import _core
    (path, computed, finished, total, done, status, message) = _core.pf_batch_run(
        str(scene), str(out), "test", 0)
    assert status == 0 and finished == 1
    assert (computed, total, done) == (18, 30, 30)
    same_contents(clean, out)


def test_broken_profile_is_reported_and_the_rest_computed(tmp_path):
    scene = make_batch(tmp_path, n=10, broken=True)
    out = tmp_path / "b.nc"
    r = run_program(scene, "-o", out)
    assert r.returncode == 4, r.stderr          # finished, with a failed profile
    with xr.open_dataset(out) as ds:
        status = ds["status"].values
        assert status[4] == 2 and np.all(np.delete(status, 4) == 1)
        msg = str(ds["error_message"].values[4])
        assert "seg_0005.txt:3" in msg and "abc" in msg
        assert np.isnan(ds["mu"].values[4]).all()          # fill value, masked
        assert np.all(np.isfinite(np.delete(ds["mu"].values, 4, axis=0)))
        assert ds.attrs["profiles_failed"] == 1


def test_python_run_of_a_batch_matches_the_program(tmp_path):
    scene = make_batch(tmp_path, n=15)
    a = tmp_path / "prog.nc"
    assert run_program(scene, "-o", a).returncode == 0
    b = pavefric.run(scene, tmp_path / "py.nc", progress=False)
    same_contents(a, b)


def test_journal_of_another_batch_is_refused(tmp_path):
    scene = make_batch(tmp_path, n=10)
    out = tmp_path / "o.nc"
    assert run_program(scene, "-o", out, "--max-profiles", "3").returncode == 3
    scene.write_text(scene.read_text().replace("speeds_kmh = 20, 60", "speeds_kmh = 20, 80"))
    r = run_program(scene, "-o", out)
    assert r.returncode == 1 and "belongs to another batch" in r.stderr


def test_progress_lines(tmp_path):
    scene = make_batch(tmp_path, n=20)
    r = run_program(scene, "-o", tmp_path / "o.nc")
    # progress on stderr; stdout holds the results only (the summary line)
    lines = [l for l in r.stderr.splitlines() if l.startswith("pavefric batch: ")]
    assert len(lines) >= 2 and "20/20 profiles (100.0 %)" in lines[-1]
    assert "profiles/s" in lines[-1] and "s left" in lines[-1]
    results = r.stdout.splitlines()
    assert len(results) == 1 and ": batch " in results[0], r.stdout
    assert "20 profiles: 20 done in this run (failed included)" in results[0]


def test_batch_bad_input(tmp_path):
    scene = tmp_path / "b.nml"
    scene.write_text("&batch profiles = 'nothing/*.txt' /\n&operation speeds_kmh = 20 /\n")
    r = run_program(scene, "-o", tmp_path / "o.nc")
    assert r.returncode == 1 and "&batch profiles = " in r.stderr and "matches no file" in r.stderr
    scene.write_text("&batch depths = -1 /\n&operation speeds_kmh = 20 /\n")
    r = run_program(scene, "-o", tmp_path / "o.nc")
    assert r.returncode == 1 and "&batch" in r.stderr


def test_mpi_broken_profile_same_as_serial(tmp_path):
    mpirun = shutil.which("mpirun")
    if mpirun is None:
        pytest.fail("mpirun not found: setup.sh installs Open MPI (openmpi-bin)")
    scene = make_batch(tmp_path, n=12, broken=True)
    serial = tmp_path / "serial.nc"
    assert run_program(scene, "-o", serial).returncode == 4
    out = tmp_path / "mpi.nc"
    env = {**os.environ, "OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
           "OMP_NUM_THREADS": "1"}
    r = subprocess.run([mpirun, "--oversubscribe", "-n", "2", program(), str(scene), "-o",
                        str(out)], capture_output=True, text=True, env=env, timeout=600)
    assert r.returncode == 4, r.stderr + r.stdout
    same_contents(serial, out)       # the failed profile's message crossed MPI intact


def test_profile_list_restart_off_and_progress_every(tmp_path):
    scene = make_batch(tmp_path, n=8)
    names = sorted((tmp_path / "profiles").glob("*.txt"))[::2]        # every other one
    (tmp_path / "list.txt").write_text("# chosen segments\n" +
                                        "\n".join(f"profiles/{p.name}" for p in names) + "\n")
    scene.write_text(scene.read_text().replace(
        "profiles = 'profiles/*.txt'", "profile_list = 'list.txt', progress_every = 1"))
    out = tmp_path / "l.nc"
    r = run_program(scene, "-o", out)
    assert r.returncode == 0, r.stderr
    assert len([l for l in r.stderr.splitlines() if "profiles/s" in l]) == 4   # one a profile
    with xr.open_dataset(out) as ds:
        assert list(ds["profile_name"].values) == [p.stem for p in names]
    # restart = .false.: an old journal is ignored and overwritten
    assert run_program(scene, "-o", out, "--max-profiles", "2").returncode == 3
    scene.write_text(scene.read_text().replace("progress_every = 1",
                                               "progress_every = 1, restart = .false."))
    r = run_program(scene, "-o", out)
    assert r.returncode == 0 and "resuming" not in r.stderr + r.stdout
    assert len([l for l in r.stderr.splitlines() if "profiles/s" in l]) == 4   # all four again


def test_batch_unwritable_output_and_bad_max_profiles(tmp_path):
    scene = make_batch(tmp_path, n=3)
    r = run_program(scene, "-o", "/nonexistent-dir/b.nc")
    assert r.returncode == 1 and "&output file = '/nonexistent-dir/b.nc'" in r.stderr
    r = run_program(scene, "-o", tmp_path / "o.nc", "--max-profiles", "many")
    assert r.returncode == 2 and "--max-profiles 'many'" in r.stderr     # bad usage


def test_a_batch_output_plots_directly(tmp_path):
    """Issue 24: `b.mu.sel(speed_kmh=60).plot()` on a batch of a glob (names,
    no chainage), read by plain xarray and by pavefric.open_dataset: the
    dimension's coordinate `profile` numbers the profiles 1..N; the names
    are the label `profile_name`, which indexes in pavefric.open_dataset."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import xarray as xr

    scene = make_batch(tmp_path, n=4)
    out = tmp_path / "b.nc"
    assert run_program(scene, "-o", out).returncode == 0
    with xr.open_dataset(out) as plain:
        assert plain["profile"].dtype.kind == "i"
        assert plain["profile"].values.tolist() == [1, 2, 3, 4]
        mesh = plain.mu.sel(speed_kmh=60).plot()         # profile x water depth
        assert mesh.get_array().size == 4 * 2
        plt.close("all")
    b = pavefric.open_dataset(out)
    assert b["profile_name"].dtype.kind == "U"
    mesh = b.mu.sel(speed_kmh=60).plot()
    assert mesh.get_array().size == 4 * 2
    line, = b.mu.sel(speed_kmh=60, water_depth=0.0).plot()
    np.testing.assert_array_equal(line.get_xdata(), [1, 2, 3, 4])
    np.testing.assert_array_equal(line.get_ydata(), b.mu.sel(speed_kmh=60, water_depth=0.0))
    plt.close("all")
    assert b.mu.sel(profile_name="seg_0002", speed_kmh=20, water_depth=0.0) == b.mu.values[1, 0, 0]
    assert b.mu.sel(profile=2, speed_kmh=20, water_depth=0.0) == b.mu.values[1, 0, 0]
