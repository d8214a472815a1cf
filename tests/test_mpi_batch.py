"""MPI batches: rank 0 alone decides the work; the result equals the serial
run bit for bit whatever the mix of good, empty and broken profiles, and
whatever the profiles' sizes (dynamic scheduling); an error on any rank ends
every rank, with the message, never a hang (issue 10 item 2, issue 13).

Every mpirun has a timeout, so a hang fails the test instead of CI."""
import os
import shutil
import subprocess

import numpy as np
import pytest
import xarray as xr

from conftest import program, run_program
from test_batch import same_contents

TIMEOUT = 180


def mpirun(*args, n=2, wrap_exit=False, env_extra=None):
    """`mpirun -n N pavefric ARGS`; with `wrap_exit`, each rank runs under a
    shell that prints its own exit status ("rank R exit S") and exits 0, so
    that every rank's status can be checked."""
    exe = shutil.which("mpirun")
    if exe is None:
        pytest.fail("mpirun not found: setup.sh installs Open MPI (openmpi-bin)")
    env = {**os.environ, "OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
           "OMP_NUM_THREADS": "1", **(env_extra or {})}
    cmd = [exe, "--oversubscribe", "-n", str(n)]
    if os.geteuid() == 0:
        cmd.append("--allow-run-as-root")
    for k in (env_extra or {}):
        cmd += ["-x", k]
    prog = [program(), *map(str, args)]
    if wrap_exit:
        prog = ["sh", "-c", '"$@"; echo "rank $OMPI_COMM_WORLD_RANK exit $?"; exit 0', "sh", *prog]
    return subprocess.run(cmd + prog, capture_output=True, text=True, env=env, timeout=TIMEOUT)


def rank_exits(r):
    return sorted(line.split(" exit ")[1] for line in r.stdout.splitlines()
                  if line.startswith("rank ") and " exit " in line)


def tiny_batch(tmp_path, n=301, empty=(150,), broken=(7,)):
    """n tiny profiles (64 points, one speed: start-up and messages dominate,
    where the old code's ranks raced on the journal), some empty, some with
    text where a height should be."""
    from pavefric.surfaces import road_profiles

    road_profiles(str(tmp_path / "profiles"), n=n, points=64)
    for k in empty:
        (tmp_path / "profiles" / f"seg_{k:04d}.txt").write_text("")
    for k in broken:
        (tmp_path / "profiles" / f"seg_{k:04d}.txt").write_text("height_mm\n0.1\n1-3\n0.2\n")
    scene = tmp_path / "batch.nml"
    scene.write_text("&batch profiles = 'profiles/*.txt' /\n"
                     "&surface closed = .false., mu_loc = 0.6 /\n"
                     "&operation speeds_kmh = 20 /\n")
    return scene


def test_mixed_tiny_batch_equals_serial_every_time(tmp_path):
    # 301 tiny profiles with an empty one: the old code ended with a bogus
    # "--max-profiles" stop (150 duplicates, every even index missing), or hung
    scene = tiny_batch(tmp_path)
    serial = tmp_path / "serial.nc"
    r = run_program(scene, "-o", serial)
    assert r.returncode == 4, r.stderr
    for k in range(3):
        out = tmp_path / f"mpi{k}.nc"
        r = mpirun(scene, "-o", out)
        assert r.returncode == 4, r.stdout[-2000:] + r.stderr[-2000:]
        assert "--max-profiles" not in r.stderr
        assert "301 profiles: 301 done in this run (failed included), 0 taken from the journal, 2 failed" \
            in r.stdout
        same_contents(serial, out)
    with xr.open_dataset(serial) as ds:
        status = ds["status"].values
        assert np.flatnonzero(status == 2).tolist() == [6, 149]
        assert "seg_0150.txt" in str(ds["error_message"].values[149])


def test_one_more_file_and_three_ranks(tmp_path):
    # 302 files (the old code hung here), and three ranks on two cores
    scene = tiny_batch(tmp_path, n=302, empty=(1, 150, 302), broken=(2, 301))
    serial = tmp_path / "serial.nc"
    assert run_program(scene, "-o", serial).returncode == 4
    for n in (2, 3):
        out = tmp_path / f"mpi{n}.nc"
        r = mpirun(scene, "-o", out, n=n)
        assert r.returncode == 4, r.stdout[-2000:] + r.stderr[-2000:]
        same_contents(serial, out)


def test_uneven_batch_dynamic_scheduling_equals_serial(tmp_path):
    # a few long profiles among many short ones, where round-robin would give
    # them all to one rank (odd positions with 2 ranks)
    from pavefric.surfaces import spectral_profile, write_profile

    d = tmp_path / "profiles"
    d.mkdir()
    for k in range(1, 61):
        n = 4096 if k in (1, 3, 5, 7) else 256
        write_profile(str(d / f"p{k:03d}.txt"), spectral_profile(n, 0.87e-3, rms=0.4e-3, seed=k))
    scene = tmp_path / "uneven.nml"
    scene.write_text("&batch profiles = 'profiles/*.txt', depths = 0.0, 1e-3 /\n"
                     "&surface closed = .false., mu_loc = 0.6 /\n"
                     "&operation speeds_kmh = 20, 60, 90 /\n")
    serial = tmp_path / "serial.nc"
    assert run_program(scene, "-o", serial).returncode == 0
    for n in (2, 3):
        out = tmp_path / f"mpi{n}.nc"
        r = mpirun(scene, "-o", out, n=n)
        assert r.returncode == 0, r.stdout[-2000:] + r.stderr[-2000:]
        assert f"60 profiles on {n} MPI ranks" in r.stderr
        same_contents(serial, out)


def test_unwritable_output_ends_every_rank(tmp_path):
    # the old code: rank 0 exited, rank 1 waited forever
    scene = tiny_batch(tmp_path, n=20, empty=(), broken=())
    r = mpirun(scene, "-o", tmp_path / "no-such-dir" / "o.nc", wrap_exit=True)
    assert rank_exits(r) == ["1", "1"], r.stdout + r.stderr
    assert r.stderr.count("pavefric: error: &output file = ") == 1       # rank 0 says it once
    assert "cannot write the journal" in r.stderr


def test_every_rank_exits_alike(tmp_path):
    # 4 (finished with failures) and 3 (stopped early) on every rank, then a
    # resume under MPI equals the serial run
    scene = tiny_batch(tmp_path, n=40, empty=(3,), broken=())
    serial = tmp_path / "serial.nc"
    assert run_program(scene, "-o", serial).returncode == 4
    out = tmp_path / "mpi.nc"
    r = mpirun(scene, "-o", out, "--max-profiles", "15", wrap_exit=True)
    assert rank_exits(r) == ["3", "3"], r.stdout + r.stderr
    assert "15 done in this run (failed included)" in r.stdout and "25 left" in r.stdout
    journal = (tmp_path / "mpi.nc.journal").read_text()
    assert journal.count("\nP ") == 15
    r = mpirun(scene, "-o", out, wrap_exit=True)
    assert rank_exits(r) == ["4", "4"], r.stdout + r.stderr
    assert "resuming: 15 of 40 profiles already done" in r.stderr
    assert "40 profiles: 25 done in this run (failed included), 15 taken from the journal, 1 failed" in r.stdout
    same_contents(serial, out)


def test_bad_scene_ends_every_rank(tmp_path):
    scene = tmp_path / "bad.nml"
    scene.write_text("&batch profiles = 'nothing/*.txt' /\n&operation speeds_kmh = 20 /\n")
    r = mpirun(scene, "-o", tmp_path / "o.nc", wrap_exit=True)
    assert rank_exits(r) == ["1", "1"], r.stdout + r.stderr
    assert r.stderr.count("matches no file") == 1
