"""Faults end in clean errors (issue 10, item 5): a full disk while the
output is written, in the program and in Python, and out of memory in
Python. A full disk is simulated without root: RLIMIT_FSIZE (ulimit -f)
makes every write past the limit fail with EFBIG, as ENOSPC would."""
import resource
import signal
import subprocess
import sys
import textwrap

import pytest

from conftest import program, write_scene
from pavefric.core import PavefricError, _check


def file_size_limit(nbytes):
    def limit():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (nbytes, nbytes))
    return limit


def run_limited(args, nbytes, cwd):
    return subprocess.run([str(a) for a in args], capture_output=True, text=True, cwd=cwd,
                          preexec_fn=file_size_limit(nbytes), timeout=600)


@pytest.fixture(scope="module")
def full_size(tmp_path_factory):
    """The size of the scene's output when the disk has room."""
    d = tmp_path_factory.mktemp("room")
    scene = write_scene(d, "s", groups={"output": "series = .true."})
    r = subprocess.run([program(), scene.name, "-o", "out.nc"], cwd=d, capture_output=True,
                       text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    return (d / "out.nc").stat().st_size


@pytest.mark.parametrize("fraction", [0.0, 0.1, 0.5, 0.9, 0.999])
def test_full_disk_in_the_program(tmp_path, full_size, fraction):
    scene = write_scene(tmp_path, "s", groups={"output": "series = .true."})
    old = tmp_path / "out.nc"
    # the previous output: a run of another scene (pavefric replaces only its own outputs)
    prev = write_scene(tmp_path / "prev", "p")
    r = subprocess.run([program(), str(prev), "-o", str(old)], capture_output=True, text=True,
                       timeout=600)
    assert r.returncode == 0, r.stderr
    previous = old.read_bytes()
    r = run_limited([program(), scene.name, "-o", "out.nc"], int(fraction * full_size),
                    tmp_path)
    # a clean error, not SIGSEGV (139) or SIGXFSZ; the line reaches a pipe
    assert r.returncode == 1, (r.returncode, r.stderr)
    assert r.stderr.startswith("pavefric: error: &output file: writing 'out.nc' failed"), r.stderr
    assert "File too large" in r.stderr
    assert "Backtrace" not in r.stderr
    assert not list(tmp_path.glob("out.nc.tmp*"))
    assert old.read_bytes() == previous


def test_full_disk_leaves_a_batch_resumable(tmp_path):
    from pavefric.surfaces import road_profiles

    road_profiles(str(tmp_path / "profiles"), n=3, points=256)
    scene = tmp_path / "b.nml"
    scene.write_text("&batch profiles = 'profiles/*.txt', depths = 0.0 /\n"
                     "&surface closed = .false., mu_loc = 0.6 /\n"
                     "&operation speeds_kmh = 20, 60 /\n")
    # room for the journal (well under 4 kB), not for the NetCDF file
    r = run_limited([program(), scene, "-o", "b.nc"], 4096, tmp_path)
    assert r.returncode == 1, (r.returncode, r.stderr)
    assert "pavefric: error: &output file: writing 'b.nc' failed" in r.stderr
    assert not list(tmp_path.glob("b.nc.tmp*")) and not (tmp_path / "b.nc").exists()
    assert (tmp_path / "b.nc.journal").exists()
    r = subprocess.run([program(), str(scene), "-o", "b.nc"], cwd=tmp_path, capture_output=True,
                       text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    assert "resuming: 3 of 3" in r.stderr


PY_RUN = textwrap.dedent("""
    import sys
    import pavefric
    try:
        pavefric.run(sys.argv[1], output=sys.argv[2], progress=False)
    except pavefric.PavefricError as e:
        print("PavefricError:", e)
    else:
        print("written")
""")


@pytest.mark.parametrize("fraction", [0.0, 0.5, 0.999])
def test_full_disk_in_python_then_a_clean_exit(tmp_path, full_size, fraction):
    # was: PavefricError, then a segfault at interpreter exit (HDF5 closing a
    # file netCDF had left open)
    scene = write_scene(tmp_path, "s", groups={"output": "series = .true."})
    r = run_limited([sys.executable, "-c", PY_RUN, scene.name, "out.nc"],
                    int(fraction * full_size), tmp_path)
    assert r.returncode == 0, (r.returncode, r.stdout, r.stderr)
    assert r.stdout.startswith("PavefricError: &output file: writing 'out.nc' failed"), r.stdout
    assert not list(tmp_path.glob("out.nc.tmp*")) and not (tmp_path / "out.nc").exists()


def test_full_disk_in_a_python_batch_then_a_clean_exit(tmp_path):
    from pavefric.surfaces import road_profiles

    road_profiles(str(tmp_path / "profiles"), n=3, points=256)
    scene = tmp_path / "b.nml"
    scene.write_text("&batch profiles = 'profiles/*.txt', depths = 0.0 /\n"
                     "&surface closed = .false., mu_loc = 0.6 /\n"
                     "&operation speeds_kmh = 20 /\n")
    r = run_limited([sys.executable, "-c", PY_RUN, scene.name, "b.nc"], 4096, tmp_path)
    assert r.returncode == 0, (r.returncode, r.stdout, r.stderr)
    assert r.stdout.startswith("PavefricError: &output file: writing 'b.nc' failed"), r.stdout
    assert not list(tmp_path.glob("b.nc.tmp*"))


def test_status_kinds_map_to_exceptions():
    with pytest.raises(MemoryError, match="not enough memory"):
        _check(3, b"simulate: not enough memory for the series")
    for status in (1, 2, 4):
        with pytest.raises(PavefricError, match="bad"):
            _check(status, "bad")
    _check(0, "")


PY_MEMORY = textwrap.dedent("""
    import resource, sys, traceback
    import numpy as np
    import xarray  # imported before the limit: simulate imports it
    import pavefric
    n, ns = 40000, 200
    z = 0.5e-3 * np.sin(np.arange(n) * 0.3)
    speeds = np.linspace(5.0, 100.0, ns)
    n_el, npos = pavefric.layout(n, 0.87e-3)
    series = npos * ns * (3 * 8 + 4)          # mu_inst, hydro_load, penetration, contacts
    vm = [int(l.split()[1]) * 1024 for l in open("/proc/self/status") if l.startswith("VmSize")][0]
    # room for the series Python allocates for the results, not for a second copy in the core
    resource.setrlimit(resource.RLIMIT_AS, (vm + int(1.3 * series) + (64 << 20),) * 2)
    try:
        pavefric.simulate(z, 0.87e-3, speeds, series=True)
    except MemoryError as e:
        where = traceback.extract_tb(e.__traceback__)[-1].name
        print("MemoryError from", where, ":", e)
    else:
        print("no error")
""")


def test_out_of_memory_in_simulate_is_a_memory_error(tmp_path):
    r = subprocess.run([sys.executable, "-c", PY_MEMORY], capture_output=True, text=True,
                       cwd=tmp_path, timeout=600)
    # was: the Fortran runtime's "Allocation would exceed memory limit" ended the interpreter
    assert r.returncode == 0, (r.returncode, r.stdout, r.stderr[-2000:])
    assert r.stdout.startswith("MemoryError from _check :"), r.stdout
