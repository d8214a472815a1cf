"""One rule for every writer, in every interface (issue 19): never write over
a file the run read, never open a FIFO, a device or a directory for writing;
write a temporary in the same directory and rename it. The program obeyed
it; the C API's pavefric_write_output, the Fortran session's write (and
write_results itself) and Python's write_profiles overwrote the run's own
inputs and replaced FIFOs and device nodes. One implementation (the core's
write_results / pavefric_fsys, reached from Python by pavefric.check_output)
now serves them all."""
from __future__ import annotations

import os
import subprocess
import textwrap

import netCDF4
import numpy as np
import pytest

import pavefric
from conftest import write_scene
from test_api import build, pc_env  # noqa: F401  (the fixture)

TIMEOUT = 120        # a writer that opened a FIFO would block: fail instead of hanging


@pytest.fixture()
def scene(tmp_path, profile_m):
    return write_scene(tmp_path / "run", profile=profile_m)


def targets(scene):
    """(name, path to write, what must stay as it was) for every forbidden target."""
    d = scene.parent
    profile = d / "scene_profile.txt"
    (d / "link_to_scene.nml").symlink_to(scene.name)
    os.link(profile, d / "hard_link_to_profile.txt")
    os.mkfifo(d / "fifo")
    (d / "a_directory").mkdir()
    (d / "notes.txt").write_text("the user's own notes, named as the output by mistake\n")
    with netCDF4.Dataset(d / "other.nc", "w") as nc:    # another tool's NetCDF
        nc.source = "a survey vehicle's export"
        nc.createDimension("x", 3)
    return [("the scene file", scene), ("the profile file", profile),
            ("a text file", d / "notes.txt"), ("another tool's NetCDF", d / "other.nc"),
            ("a symbolic link to the scene", d / "link_to_scene.nml"),
            ("a hard link to the profile", d / "hard_link_to_profile.txt"),
            ("a FIFO", d / "fifo"), ("a directory", d / "a_directory"),
            ("a character device", "/dev/null")]


def snapshot(path):
    st = os.lstat(path)
    data = open(path, "rb").read() if os.path.isfile(path) and not os.path.islink(path) else b""
    return st.st_mode, st.st_ino, data


@pytest.fixture(scope="module")
def check_api(tmp_path_factory, pc_env):  # noqa: F811
    return build(tmp_path_factory.mktemp("capi"), "check_api.c", pc_env)


def test_c_api_write_output_refuses_inputs_fifos_devices(scene, check_api):
    for name, target in targets(scene):
        before = snapshot(target)
        r = subprocess.run([str(check_api), "dump", str(scene), str(target)],
                           capture_output=True, text=True, timeout=TIMEOUT)
        assert r.returncode == 1, (name, r.stdout[-500:], r.stderr)
        line = [x for x in r.stdout.splitlines() if x.startswith("case write:")]
        assert line and "status=1" in line[0], (name, r.stdout[-500:])
        assert ("would destroy an input" in line[0] or "not a regular file" in line[0]
                or "pavefric replaces only its own outputs" in line[0]), line
        assert snapshot(target) == before, name
    assert not list(scene.parent.glob("*.tmp*")), "a temporary was left behind"


FORTRAN = """
program write_over
   use pavefric, only: error_type, session_type, load_session, session_run, session_write
   implicit none
   type(session_type) :: s
   type(error_type), allocatable :: error
   character(len=4096) :: scene, target
   call get_command_argument(1, scene)
   call get_command_argument(2, target)
   call load_session(trim(scene), s, error)
   if (.not. allocated(error)) call session_run(s, error)
   if (allocated(error)) then
      write(*, '(a)') "run failed: " // error%message
      stop 2
   end if
   call session_write(s, trim(target), error)
   if (allocated(error)) then
      write(*, '(a)') "refused: " // error%message
      stop 1
   end if
   write(*, '(a)') "written"
end program write_over
"""


def test_fortran_session_write_refuses_inputs_fifos_devices(scene, tmp_path, pc_env):  # noqa: F811
    src = tmp_path / "write_over.f90"
    src.write_text(textwrap.dedent(FORTRAN))
    flags = subprocess.run(["pkg-config", "--cflags", "--libs", "pavefric"], env=pc_env,
                           capture_output=True, text=True, check=True).stdout.split()
    exe = tmp_path / "write_over"
    subprocess.run(["gfortran", "-o", str(exe), str(src), *flags], env=pc_env, check=True,
                   capture_output=True, timeout=300)
    for name, target in targets(scene):
        before = snapshot(target)
        r = subprocess.run([str(exe), str(scene), str(target)], capture_output=True, text=True,
                           timeout=TIMEOUT)
        assert r.returncode == 1 and r.stdout.startswith("refused: "), (name, r.stdout)
        assert snapshot(target) == before, name
    r = subprocess.run([str(exe), str(scene), str(tmp_path / "fresh.nc")], capture_output=True,
                       text=True, timeout=TIMEOUT)
    assert r.returncode == 0 and (tmp_path / "fresh.nc").is_file(), r.stdout


def test_python_write_profiles_refuses_its_source_fifos_devices(tmp_path):
    z = 1e-4 * np.sin(np.arange(400) * 0.2)
    survey = pavefric.write_profiles(tmp_path / "survey.nc", [z, 2 * z])
    prof = pavefric.read_profile(survey, profile_name="1")
    before = snapshot(survey)
    with pytest.raises(pavefric.PavefricError, match="would destroy an input"):
        pavefric.write_profiles(survey, [prof])                      # over its own source
    (tmp_path / "link.nc").symlink_to("survey.nc")
    with pytest.raises(pavefric.PavefricError, match="would destroy an input"):
        pavefric.write_profiles(tmp_path / "link.nc", prof)
    assert snapshot(survey) == before
    os.mkfifo(tmp_path / "fifo")
    for target in (tmp_path / "fifo", "/dev/null", tmp_path):
        with pytest.raises(pavefric.PavefricError, match="not a regular file"):
            pavefric.write_profiles(target, z)
    assert os.path.exists(tmp_path / "fifo") and not os.path.isfile(tmp_path / "fifo")
    # a profile read elsewhere is written fine, and reads back the same
    out = pavefric.write_profiles(tmp_path / "copy.nc", [prof])
    back = pavefric.read_profile(out)
    np.testing.assert_array_equal(back.heights, prof.heights)
    assert not list(tmp_path.glob(".*tmp*"))


def test_the_shared_check_is_public(tmp_path):
    (tmp_path / "in.txt").write_text("x")
    pavefric.check_output(tmp_path / "out.nc", [tmp_path / "in.txt"])     # fine
    with pytest.raises(pavefric.PavefricError, match="would destroy an input"):
        pavefric.check_output(tmp_path / "in.txt", [tmp_path / "in.txt"])
    # inputs given as an iterator are read once, whole: the output among the
    # later ones (existing or not yet written) is still found; None names nothing
    with pytest.raises(pavefric.PavefricError, match="would destroy an input"):
        pavefric.check_output(tmp_path / "in.txt",
                              iter([None, tmp_path / "new.md", tmp_path / "in.txt"]))
    with pytest.raises(pavefric.PavefricError, match="is also"):
        pavefric.check_output(tmp_path / "new.md",
                              (p for p in [None, "", tmp_path / "in.txt", tmp_path / "new.md"]))


def test_a_text_writer_writes_only_text_with_its_signature(tmp_path):
    """write_text_output refuses text that does not begin with its signature
    (a file it could never replace again), writing nothing; with it, it
    replaces its own file and refuses a user's."""
    from pavefric.core import write_text_output

    out = tmp_path / "r.md"
    with pytest.raises(ValueError, match="does not begin with '# pavefric test'"):
        write_text_output(out, "# something else\n", "# pavefric test")
    assert list(tmp_path.iterdir()) == []
    for text in ("# pavefric test: one\n", "# pavefric test: two\n"):
        assert write_text_output(out, text, "# pavefric test") == out
        assert out.read_text() == text
    out.write_text("the user's\n")
    with pytest.raises(pavefric.PavefricError, match="not a file this command wrote"):
        write_text_output(out, "# pavefric test: three\n", "# pavefric test")
    assert out.read_text() == "the user's\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.md"]
