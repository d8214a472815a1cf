"""A batch records every warning (issue 19): a survey read in the wrong unit
gave mu per profile and exit 0 with no word, where the same profile alone
warns. Each profile's warnings are in the output (n_warnings,
warning_message), counted in the summary line, and survive a resume and MPI."""
import os
import shutil
import subprocess
import warnings

import numpy as np
import pytest

import pavefric
from conftest import program, run_program
from test_batch import make_batch, same_contents


def unit_batch(tmp_path, unit, n=4, depths="0.0, 1.0e-3"):
    """A batch of millimetre profiles declared in `unit`."""
    scene = make_batch(tmp_path, n=n, depths=depths)
    scene.write_text(scene.read_text().replace("mu_loc = 0.6", f"mu_loc = 0.6, height_unit = "
                                               f"'{unit}'"))
    return scene


def single_scene_warnings(tmp_path, profile, unit):
    scene = tmp_path / "one.nml"
    scene.write_text(f"&surface profile_file = '{profile}', closed = .false., mu_loc = 0.6, "
                     f"height_unit = '{unit}' /\n&operation speeds_kmh = 20, 60 /\n")
    out = tmp_path / "one.nc"
    r = run_program(scene, "-o", out)
    assert r.returncode == 0, r.stderr
    return pavefric.open_dataset(out).attrs["warnings"].splitlines()


def test_micrometres_on_millimetre_data_warn_per_profile(tmp_path):
    scene = unit_batch(tmp_path, "um")
    out = tmp_path / "um.nc"
    r = run_program(scene, "-o", out)
    assert r.returncode == 0, r.stderr                 # warnings keep the exit status
    assert "0 failed, 4 with warnings" in r.stdout
    assert r.stderr.count("pavefric: warning: profile seg_") == 4
    assert "4 of 4 profiles have warnings" in r.stderr
    ds = pavefric.open_dataset(out)
    assert ds.attrs["profiles_with_warnings"] == 4
    # the texture's warning, and at 1 mm of water the wet model's regime (MPD ~ 0)
    assert list(ds["n_warnings"].values) == [2, 2, 2, 2]
    # the very line the profile alone records
    alone = single_scene_warnings(tmp_path, tmp_path / "profiles" / "seg_0002.txt", "um")
    assert len(alone) == 1 and "RMS height" in alone[0]
    lines = str(ds["warning_message"].sel(profile_name="seg_0002").values).splitlines()
    assert lines[0] == alone[0]
    assert lines[1].startswith("&water depth = 0.001 m is more than 2 x the texture depth")


def test_metres_on_millimetre_data_warn_at_each_depth_and_speed(tmp_path):
    scene = unit_batch(tmp_path, "m", n=3)
    out = tmp_path / "m.nc"
    r = run_program(scene, "-o", out)
    assert r.returncode in (0, 4), r.stderr
    ds = pavefric.open_dataset(out)
    ok = ds["status"].values == 1
    assert ok.any()
    n = ds["n_warnings"].values
    assert np.all(n[ok] >= 1) and np.all(n[~ok] == 0)
    mu = ds["mu"].values
    for i in np.flatnonzero(ok):
        text = str(ds["warning_message"].values[i])
        lines = text.splitlines()
        assert "RMS height" in lines[0]
        if (mu[i] > 2.0).any():
            assert "above what any road gives" in text and "water depth" in text
        # at most five lines of text, all counted
        if n[i] > 5:
            assert len(lines) == 6 and lines[-1].startswith(f"... {n[i] - 5} more warnings")
        else:
            assert len(lines) == n[i]
    assert ds.attrs["profiles_with_warnings"] == int((n > 0).sum())
    assert f"{int((n > 0).sum())} with warnings" in r.stdout


def test_warnings_and_messages_survive_a_resume(tmp_path):
    scene = unit_batch(tmp_path, "m", n=6)
    # a failed profile whose message holds a backslash (escaped in the journal)
    (tmp_path / "profiles" / "seg_0004.txt").write_text("height_mm\n0.1\na\\b\n0.2\n")
    whole = tmp_path / "whole.nc"
    r = run_program(scene, "-o", whole)
    assert r.returncode == 4, r.stderr
    part = tmp_path / "part.nc"
    assert run_program(scene, "-o", part, "--max-profiles", "4").returncode == 3
    r = run_program(scene, "-o", part)
    assert r.returncode == 4 and "resuming: 4 of 6" in r.stderr, r.stdout + r.stderr
    same_contents(whole, part)
    ds = pavefric.open_dataset(part)
    assert "a\\b" in str(ds["error_message"].sel(profile_name="seg_0004").values)
    assert int(ds["n_warnings"].sum()) > 0


def test_mpi_batch_records_the_same_warnings(tmp_path):
    mpirun = shutil.which("mpirun")
    if mpirun is None:
        pytest.fail("mpirun not found: setup.sh installs Open MPI (openmpi-bin)")
    scene = unit_batch(tmp_path, "m", n=5)
    serial = tmp_path / "serial.nc"
    assert run_program(scene, "-o", serial).returncode in (0, 4)
    out = tmp_path / "mpi.nc"
    env = {**os.environ, "OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
           "OMP_NUM_THREADS": "1"}
    r = subprocess.run([mpirun, "--oversubscribe", "-n", "2", program(), str(scene), "-o",
                        str(out)], capture_output=True, text=True, env=env, timeout=600)
    assert r.returncode in (0, 4), r.stderr + r.stdout
    same_contents(serial, out)
    assert int(pavefric.open_dataset(out)["n_warnings"].sum()) > 0


def test_python_batch_run_warns(tmp_path):
    scene = unit_batch(tmp_path, "um", n=2)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        pavefric.run(str(scene), output=str(tmp_path / "py.nc"), progress=False)
    texts = [str(w.message) for w in caught if issubclass(w.category, pavefric.PavefricWarning)]
    assert any("2 of 2 profiles have warnings" in t and "RMS height" in t for t in texts)


def test_scene_warnings_of_a_batch_are_recorded(tmp_path):
    scene = make_batch(tmp_path, n=2)
    # an implausible parameter: a single scene warns about it, so does a batch
    scene.write_text(scene.read_text().replace("mu_loc = 0.6", "mu_loc = 2.5"))
    out = tmp_path / "b.nc"
    r = run_program(scene, "-o", out)
    assert r.returncode == 0, r.stderr
    ds = pavefric.open_dataset(out)
    assert "mu_loc" in ds.attrs["warnings"]
    assert "mu_loc" in r.stderr
