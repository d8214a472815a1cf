"""Results on stdout, progress on stderr, and --quiet/-q dropping the
progress only (the cost estimate, a batch's progress lines and MPI lines),
never a warning or an error; `python -m pavefric run -q` likewise."""
import os
import pty
import shutil
import subprocess
import sys

import numpy as np
import pytest
import xarray as xr

from conftest import program, write_scene
from test_batch import make_batch, same_contents


def progress_lines(text: str) -> list[str]:
    return [line for line in text.splitlines()
            if line.startswith(("pavefric: estimate", "pavefric batch"))]


def run(*args, cwd=None, env=None):
    return subprocess.run([program(), *map(str, args)], capture_output=True, text=True,
                          cwd=cwd, timeout=600, env={**os.environ, **(env or {})})


def test_quiet_scene_drops_the_estimate_keeps_warnings_and_results(tmp_path, profile_m):
    """A run long enough to be announced, with a warning (microtexture_rms
    is the drainage model's, given to the paper's bearing): without -q the
    estimate is on stderr; with -q it is gone, the warning stays, stdout is
    the same."""
    scene = write_scene(tmp_path, profile=profile_m,
                        groups={"surface": "profile_file = 'scene_profile.txt', mu_loc = 0.5, "
                                           "microtexture_rms = 1e-5",
                                "water": "depth = 1e-3",
                                "numerics": "substeps = 1024",
                                "operation": "speeds_kmh = 20, 40, 60"})
    env = {"OMP_NUM_THREADS": "1"}
    loud = run(scene, "-o", tmp_path / "loud.nc", env=env)
    assert loud.returncode == 0, loud.stderr
    assert any(line.startswith("pavefric: estimate: ") for line in loud.stderr.splitlines())
    warnings = [line for line in loud.stderr.splitlines() if line.startswith("pavefric: warning:")]
    assert warnings and any("microtexture_rms" in w for w in warnings), loud.stderr
    assert not progress_lines(loud.stdout)            # progress never on stdout
    for flag in ("-q", "--quiet"):
        quiet = run(scene, flag, "-o", tmp_path / f"quiet{flag}.nc", env=env)
        assert quiet.returncode == 0, quiet.stderr
        assert not progress_lines(quiet.stdout) and not progress_lines(quiet.stderr), \
            quiet.stderr
        assert quiet.stderr.splitlines() == warnings          # the warnings, nothing else
        # the same results, on stdout, with the output's name changed
        assert quiet.stdout == loud.stdout.replace("loud.nc", f"quiet{flag}.nc")
    with xr.open_dataset(tmp_path / "loud.nc") as a, xr.open_dataset(tmp_path / "quiet-q.nc") as b:
        assert np.array_equal(a["mu"].values, b["mu"].values)


def test_quiet_keeps_errors(tmp_path):
    r = run(tmp_path / "missing.nml", "-q")
    assert r.returncode == 1 and r.stderr.startswith("pavefric: error: "), r.stderr
    assert len(r.stderr.splitlines()) == 1 and r.stdout == ""


def test_batch_progress_on_stderr_and_quiet(tmp_path):
    """A batch with a broken profile: progress lines on stderr (stdout: the
    summary only); with -q none, the failed profile still on stderr, the
    output the same."""
    scene = make_batch(tmp_path, n=6, broken=True)
    loud = run(scene, "-o", tmp_path / "loud.nc")
    assert loud.returncode == 4, loud.stderr
    assert any("6/6 profiles" in line for line in progress_lines(loud.stderr)), loud.stderr
    assert len(loud.stdout.splitlines()) == 1 and ": batch " in loud.stdout
    quiet = run(scene, "-q", "-o", tmp_path / "quiet.nc")
    assert quiet.returncode == 4, quiet.stderr
    assert not progress_lines(quiet.stderr) and not progress_lines(quiet.stdout), quiet.stderr
    assert "pavefric: profile seg_0005: " in quiet.stderr
    assert "1 of 6 profiles failed" in quiet.stderr
    assert quiet.stdout == loud.stdout.replace("loud.nc", "quiet.nc")
    same_contents(tmp_path / "loud.nc", tmp_path / "quiet.nc")


def test_quiet_resume_still_warns_of_a_damaged_journal(tmp_path):
    scene = make_batch(tmp_path, n=8, depths="0.0")      # dry: no profile warnings
    out = tmp_path / "o.nc"
    r = run(scene, "-q", "-o", out, "--max-profiles", "4")
    assert r.returncode == 3 and not progress_lines(r.stderr), r.stderr
    assert "batch stopped before the end" in r.stderr          # a notice, not progress
    journal = tmp_path / "o.nc.journal"
    journal.write_text(journal.read_text()[:-20])     # the last line cut short (a kill)...
    r = run(scene, "-q", "-o", out, "--max-profiles", "1")
    assert r.returncode == 3 and not progress_lines(r.stderr), r.stderr
    r = run(scene, "-q", "-o", out)                     # ...is a damaged line once followed
    assert r.returncode == 0, r.stderr
    assert not progress_lines(r.stderr) and "resuming" not in r.stderr, r.stderr
    assert r.stderr.splitlines() == [
        "pavefric: warning: 1 damaged journal line(s) ignored (their profiles are recomputed)"]


def test_quiet_under_mpi(tmp_path):
    mpirun = shutil.which("mpirun")
    if mpirun is None:
        pytest.fail("mpirun not found: setup.sh installs Open MPI (openmpi-bin)")
    scene = make_batch(tmp_path, n=6)
    env = {**os.environ, "OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
           "OMP_NUM_THREADS": "1"}
    runs = {}
    for name, flags in (("loud", []), ("quiet", ["-q"])):
        runs[name] = subprocess.run([mpirun, "--oversubscribe", "-n", "2", program(), str(scene),
                                     *flags, "-o", str(tmp_path / f"{name}.nc")],
                                    capture_output=True, text=True, env=env, timeout=600)
        assert runs[name].returncode == 0, runs[name].stderr
    assert "6 profiles on 2 MPI ranks" in runs["loud"].stderr
    assert "CPU seconds per rank" in runs["loud"].stderr
    assert not progress_lines(runs["loud"].stdout)
    assert not progress_lines(runs["quiet"].stderr) and not progress_lines(runs["quiet"].stdout)
    assert len(runs["quiet"].stdout.splitlines()) == 1 and ": batch " in runs["quiet"].stdout
    same_contents(tmp_path / "loud.nc", tmp_path / "quiet.nc")


def _python_run_on_a_terminal(args, cwd) -> tuple[int, str]:
    """python -m pavefric run with stderr on a terminal (where its progress
    bar shows by default); what the terminal received."""
    master, slave = pty.openpty()
    proc = subprocess.Popen([sys.executable, "-m", "pavefric", "run", *map(str, args)],
                            cwd=cwd, stdout=subprocess.DEVNULL, stderr=slave)
    os.close(slave)
    chunks = []
    while True:
        try:
            data = os.read(master, 4096)
        except OSError:                  # EIO: the child closed the terminal
            break
        if not data:
            break
        chunks.append(data)
    os.close(master)
    return proc.wait(timeout=600), b"".join(chunks).decode(errors="replace")


def test_python_run_quiet_drops_the_progress_bar(tmp_path):
    scene = make_batch(tmp_path, n=4)
    code, terminal = _python_run_on_a_terminal([scene, "-o", tmp_path / "bar.nc"], tmp_path)
    assert code == 0 and "pavefric batch" in terminal, terminal
    code, terminal = _python_run_on_a_terminal([scene, "-q", "-o", tmp_path / "q.nc"], tmp_path)
    assert code == 0, terminal
    assert "pavefric batch" not in terminal and "Traceback" not in terminal, terminal
    same_contents(tmp_path / "bar.nc", tmp_path / "q.nc")
