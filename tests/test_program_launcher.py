"""The `pavefric` command is a console script that replaces itself with the
Fortran program installed inside the package (pavefric/bin/pavefric), so
that an editable install provides it too (.ci/run step 3 runs this file
against one). It must behave as the bare executable: the same output and
exit status, and the same process (exec, not a child), so signals, MPI and
the temporaries' owner-PID rule see the program."""
from __future__ import annotations

import os
import signal
import subprocess
import sys
from pathlib import Path

import pavefric
from conftest import ROOT, program, write_scene
from pavefric.config import program as shipped_program


def test_the_command_is_the_launcher_and_the_program_is_in_the_package():
    launcher = Path(program())
    assert launcher.read_bytes().startswith(b"#!"), "pavefric on PATH is the console script"
    assert b"_pavefric_program" in launcher.read_bytes()
    exe = shipped_program()
    assert exe.read_bytes()[:4] == b"\x7fELF", exe
    package = Path(pavefric.__file__).resolve().parent
    if exe.resolve().is_relative_to(package):     # pip install .: inside the package
        assert exe.resolve() == package / "bin" / "pavefric"
    else:                                         # pip install -e .: the build directory's
        assert (ROOT / "build").resolve() in exe.resolve().parents, exe
    r = subprocess.run([sys.executable, "-m", "pavefric.config", "--program"],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0 and Path(r.stdout.strip()) == exe, r.stdout + r.stderr


def test_same_output_and_status_as_the_executable(tmp_path):
    exe = str(shipped_program())
    for args in (["--version"], ["--help"], ["no-such-scene.nml"], ["--no-such-option"]):
        via_launcher = subprocess.run([program(), *args], capture_output=True, text=True,
                                      cwd=tmp_path, timeout=120)
        direct = subprocess.run([exe, *args], capture_output=True, text=True, cwd=tmp_path,
                                timeout=120)
        assert (via_launcher.returncode, via_launcher.stdout, via_launcher.stderr) == \
            (direct.returncode, direct.stdout, direct.stderr), args
    assert subprocess.run([program(), "no-such-scene.nml"], capture_output=True,
                          cwd=tmp_path, timeout=120).returncode == 1
    # a scene runs and writes its file
    scene = write_scene(tmp_path)
    r = subprocess.run([program(), "-q", str(scene), "-o", str(tmp_path / "out.nc")],
                       capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    assert r.stderr == ""
    with pavefric.open_dataset(tmp_path / "out.nc") as ds:
        assert ds["mu"].size == 2


def test_the_launcher_becomes_the_program(tmp_path):
    """The process the launcher started turns into the executable (exec):
    /proc/PID/exe is the program while it runs, and SIGKILL to that PID
    ends the run itself, with no Python parent left to report otherwise."""
    exe = shipped_program().resolve()
    scene = tmp_path / "batch.nml"
    scene.write_text(
        f"&batch profiles = '{ROOT / 'inputs' / 'batch_demo'}/*.txt', "
        "depths = 0.0, 0.5e-3, 1.0e-3 /\n"
        "&surface height_unit = 'mm', dx = 0.87e-3, closed = .false., mu_loc = 0.6 /\n"
        "&operation speeds_kmh = 20, 40, 60, 80 /\n"
        f"&output file = '{tmp_path / 'batch.nc'}' /\n")
    proc = subprocess.Popen([program(), str(scene)], stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, text=True,
                            env={**os.environ, "OMP_NUM_THREADS": "1"})
    seen = set()
    try:
        # the batch's first progress line comes from the program itself
        line = proc.stderr.readline()
        assert line, "the run ended without a line on stderr"
        seen.add(Path(os.readlink(f"/proc/{proc.pid}/exe")).resolve())
    finally:
        proc.send_signal(signal.SIGKILL)
        proc.wait(timeout=120)
        proc.stderr.close()
    assert seen == {exe}, seen
    assert proc.returncode == -signal.SIGKILL


def test_a_missing_program_is_one_line(tmp_path):
    code = ("import sys, _pavefric_program as p; p.RELATIVE_PATH = ('bin', 'no-such-program'); "
            "sys.exit(p.main())")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                       cwd=tmp_path, timeout=120)
    assert r.returncode == 1 and r.stdout == ""
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and "no-such-program" in lines[0] and "reinstall" in lines[0], r.stderr
