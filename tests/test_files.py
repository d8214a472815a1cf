"""Output safety (issue 10, item 1; temp files on signals): an output path
that is an input or not a regular file is refused before any work, and a
signal during a write leaves neither a temporary file nor a partial output."""
import os
import signal
import socket
import subprocess
import time
from pathlib import Path

import netCDF4
import numpy as np
import pytest

import pavefric
from conftest import program, run_program, write_scene


def snapshot(*paths):
    return {Path(p): Path(p).read_bytes() for p in paths}


def assert_intact(before):
    for path, data in before.items():
        assert path.read_bytes() == data, f"{path} was changed"


def assert_refused(r, *words):
    assert r.returncode == 1, r.stdout + r.stderr
    assert r.stderr.startswith("pavefric: error: "), r.stderr
    for w in words:
        assert w in r.stderr, r.stderr


@pytest.fixture
def scene(tmp_path):
    return write_scene(tmp_path, "s")


# ---- an output that is an input -------------------------------------------------------

def test_output_is_the_scene_file(scene):
    before = snapshot(scene, scene.with_name("s_profile.txt"))
    r = run_program(scene.name, "-o", scene.name, cwd=scene.parent)
    assert_refused(r, "-o 's.nml'", "the scene file 's.nml'", "destroy an input")
    assert_intact(before)
    assert not list(scene.parent.glob("*.tmp*"))


def test_output_is_the_profile(scene):
    profile = scene.with_name("s_profile.txt")
    before = snapshot(scene, profile)
    r = run_program(scene.name, "-o", profile.name, cwd=scene.parent)
    assert_refused(r, "-o 's_profile.txt'", "&surface profile_file", "destroy an input")
    assert_intact(before)


def test_an_output_path_that_cannot_be_inspected_says_why(scene):
    out = "a" * 300 + "/out.nc"                  # a component longer than NAME_MAX
    r = run_program(scene, "-o", out, cwd=scene.parent)
    assert r.returncode == 1
    assert "cannot inspect it (File name too long)" in r.stderr, r.stderr
    assert not list(scene.parent.glob("*.tmp*"))


@pytest.mark.parametrize("trick", ["dotdot", "dot", "absolute", "symlink", "hardlink"])
def test_output_resolving_to_an_input(scene, trick):
    d = scene.parent
    (d / "sub").mkdir()
    before = snapshot(scene, d / "s_profile.txt")
    if trick == "dotdot":
        out = "sub/../s.nml"
    elif trick == "dot":
        out = "./s.nml"
    elif trick == "absolute":
        out = str(scene)
    elif trick == "symlink":
        (d / "sub" / "link.nc").symlink_to(d / "s_profile.txt")
        out = "sub/link.nc"
    else:
        os.link(scene, d / "hard.nc")
        out = "hard.nc"
    r = run_program("s.nml", "-o", out, cwd=d)
    assert_refused(r, f"-o '{out}'", "destroy an input", str(d / ("s_profile.txt" if trick ==
                                                                   "symlink" else "s.nml")))
    assert_intact(before)
    assert not (d / "outputs").exists()


def test_output_file_in_the_namelist_names_an_input(tmp_path):
    scene = write_scene(tmp_path, "s", groups={"output": "file = 's_profile.txt'"})
    before = snapshot(scene, tmp_path / "s_profile.txt")
    r = run_program(scene.name, cwd=tmp_path)
    assert_refused(r, "&output file = 's_profile.txt'", "&surface profile_file")
    assert_intact(before)


def test_python_run_refuses_an_input_as_output(scene):
    before = snapshot(scene)
    with pytest.raises(pavefric.PavefricError, match="the scene file"):
        pavefric.run(scene, output=scene)
    assert_intact(before)


def test_a_good_output_still_written(scene):
    r = run_program(scene.name, "-o", "out.nc", cwd=scene.parent)
    assert r.returncode == 0, r.stderr
    assert (scene.parent / "out.nc").read_bytes()[:4] == b"\x89HDF"
    # an existing regular output is replaced, as before
    r = run_program(scene.name, "-o", "out.nc", cwd=scene.parent)
    assert r.returncode == 0, r.stderr


# ---- an existing file pavefric did not write ------------------------------------------
# (attack, 2026-11-28: `pavefric scene.nml -o notes.txt` replaced the user's notes by a
# NetCDF file without a word)

def test_output_over_a_text_file_is_refused(scene):
    notes = scene.parent / "notes.txt"
    notes.write_text("my field notes\n")
    before = snapshot(notes)
    r = run_program(scene.name, "-o", "notes.txt", cwd=scene.parent)
    assert_refused(r, "-o 'notes.txt'", "not a NetCDF file", "pavefric replaces only its own outputs")
    assert_intact(before)
    assert not list(scene.parent.glob("*.tmp*"))


def test_output_over_another_tools_netcdf_is_refused(scene):
    other = scene.parent / "survey.nc"
    with netCDF4.Dataset(other, "w") as nc:
        nc.createDimension("x", 2)
    before = snapshot(other)
    r = run_program(scene.name, "-o", "survey.nc", cwd=scene.parent)
    assert_refused(r, "-o 'survey.nc'", "NetCDF file pavefric did not write",
                   "no global attribute source")
    assert_intact(before)
    # the namelist's &output file and Python's run are held to the same rule
    with pytest.raises(pavefric.PavefricError, match="pavefric did not write"):
        pavefric.run(scene, output=other)
    assert_intact(before)


def test_output_over_an_empty_file_or_an_earlier_output_is_written(scene):
    d = scene.parent
    (d / "reserved.nc").write_bytes(b"")              # mktemp's empty file holds nothing
    r = run_program(scene.name, "-o", "reserved.nc", cwd=d)
    assert r.returncode == 0, r.stderr
    assert (d / "reserved.nc").read_bytes()[:4] == b"\x89HDF"
    r = run_program(scene.name, "-o", "reserved.nc", cwd=d)    # now pavefric's own
    assert r.returncode == 0, r.stderr


def test_batch_output_over_a_text_file_is_refused(tmp_path):
    scene = make_batch(tmp_path)
    notes = tmp_path / "notes.txt"
    notes.write_text("my field notes\n")
    before = snapshot(notes)
    r = run_program(scene, "-o", "notes.txt", cwd=tmp_path)
    assert_refused(r, "-o 'notes.txt'", "not a NetCDF file")
    assert_intact(before)
    assert not list(tmp_path.rglob("*.journal"))


# ---- an output that is not a regular file ---------------------------------------------

def test_fifo_as_output_is_refused(scene):
    fifo = scene.parent / "fifo"
    os.mkfifo(fifo)
    r = run_program(scene.name, "-o", "fifo", cwd=scene.parent)
    assert_refused(r, "-o 'fifo'", "FIFO", "not a regular file")
    assert fifo.is_fifo()


def test_character_device_as_output_is_refused(scene):
    # through a link, so that a regression replaces the link, never /dev/null
    link = scene.parent / "null.nc"
    link.symlink_to("/dev/null")
    r = run_program(scene.name, "-o", "null.nc", cwd=scene.parent)
    assert_refused(r, "-o 'null.nc'", "character device")
    assert link.is_symlink() and link.is_char_device()


def test_directory_and_socket_as_output_are_refused(scene):
    (scene.parent / "dir.nc").mkdir()
    r = run_program(scene.name, "-o", "dir.nc", cwd=scene.parent)
    assert_refused(r, "-o 'dir.nc'", "a directory")
    sock = socket.socket(socket.AF_UNIX)
    try:
        sock.bind(str(scene.parent / "sock.nc"))
        r = run_program(scene.name, "-o", "sock.nc", cwd=scene.parent)
        assert_refused(r, "-o 'sock.nc'", "a socket")
    finally:
        sock.close()


# ---- batches --------------------------------------------------------------------------

def make_batch(tmp_path, n=4, output=None, list_file=False):
    from pavefric.surfaces import road_profiles

    road_profiles(str(tmp_path / "profiles"), n=n, points=256)
    if list_file:
        names = sorted(p.name for p in (tmp_path / "profiles").iterdir())
        (tmp_path / "list.txt").write_text("".join(f"profiles/{x}\n" for x in names))
        spec = "profile_list = 'list.txt'"
    else:
        spec = "profiles = 'profiles/*.txt'"
    text = (f"&batch {spec}, depths = 0.0 /\n&surface closed = .false., mu_loc = 0.6 /\n"
            "&operation speeds_kmh = 20 /\n")
    if output is not None:
        text += f"&output file = '{output}' /\n"
    scene = tmp_path / "batch.nml"
    scene.write_text(text)
    return scene


def all_inputs(tmp_path):
    return [p for p in tmp_path.rglob("*") if p.is_file()]


def test_batch_output_is_a_profile(tmp_path):
    scene = make_batch(tmp_path)
    before = snapshot(*all_inputs(tmp_path))
    r = run_program(scene, "-o", tmp_path / "profiles" / "seg_0002.txt", cwd=tmp_path)
    assert_refused(r, "-o '", "profile 2 of the batch", "seg_0002.txt")
    assert_intact(before)
    assert not list(tmp_path.rglob("*.journal"))


def test_batch_output_file_is_the_scene_or_list(tmp_path):
    scene = make_batch(tmp_path, output="list.txt", list_file=True)
    before = snapshot(*all_inputs(tmp_path))
    r = run_program(scene, cwd=tmp_path)
    assert_refused(r, "&output file = 'list.txt'", "&batch profile_list")
    r = run_program(scene, "-o", "batch.nml", cwd=tmp_path)
    assert_refused(r, "-o 'batch.nml'", "the scene file")
    assert_intact(before)


def test_batch_journal_is_an_input(tmp_path):
    # the journal of out.nc is profiles/out.nc.journal, which the pattern also matches
    scene = make_batch(tmp_path)
    victim = tmp_path / "profiles" / "out.nc.journal"
    victim.write_text("height_mm\n" + "".join(f"{0.1 * (k % 7):.3f}\n" for k in range(256)))
    scene.write_text(scene.read_text().replace("profiles/*.txt", "profiles/*"))
    before = snapshot(*all_inputs(tmp_path))
    r = run_program(scene, "-o", "profiles/out.nc", cwd=tmp_path)
    assert_refused(r, "the journal of -o 'profiles/out.nc.journal'", "profile 1 of the batch")
    assert_intact(before)


def test_python_batch_refuses_a_profile_as_output(tmp_path):
    scene = make_batch(tmp_path)
    before = snapshot(*all_inputs(tmp_path))
    with pytest.raises(pavefric.PavefricError, match="profile 1 of the batch"):
        pavefric.run(scene, output=tmp_path / "profiles" / "seg_0001.txt", progress=False)
    assert_intact(before)


# ---- signals while an output is written ------------------------------------------------

def wait_stopped(proc, timeout=120.0):
    """Wait until `proc` stops itself (the PAVEFRIC_TEST_PAUSE hook)."""
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        if proc.poll() is not None:
            pytest.fail(f"the program ended (status {proc.returncode}) before the pause point: "
                        + proc.stderr.read())
        state = Path(f"/proc/{proc.pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
        if state == "T":
            return
        time.sleep(0.02)
    proc.kill()
    pytest.fail("the program never reached the pause point")


@pytest.mark.parametrize("point", ["create", "commit"])
@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGINT])
def test_signal_while_writing_leaves_no_temp_file(scene, point, sig):
    d = scene.parent
    out = d / "out.nc"
    r = run_program(scene.name, "-o", "out.nc", cwd=d)   # the previous output
    assert r.returncode == 0, r.stderr
    previous = out.read_bytes()
    env = {**os.environ, "PAVEFRIC_TEST_PAUSE": point}
    # (the signal's default action in the child, whatever the runner's: a
    # shell's background job ignores SIGINT, and the program rightly keeps
    # a signal ignored on entry, which then lets it finish)
    proc = subprocess.Popen([program(), scene.name, "-o", "out.nc"], cwd=d, env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            preexec_fn=lambda: signal.signal(sig, signal.SIG_DFL))
    wait_stopped(proc)
    temps = list(d.glob("out.nc.tmp*"))
    assert len(temps) == 1, temps   # stopped while writing under the temporary name
    proc.send_signal(sig)
    proc.send_signal(signal.SIGCONT)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == -sig, err   # killed by that signal, as without a handler
    assert not list(d.glob("out.nc.tmp*"))
    assert out.read_bytes() == previous


def test_signal_while_writing_a_batch(tmp_path):
    scene = make_batch(tmp_path)
    env = {**os.environ, "PAVEFRIC_TEST_PAUSE": "create"}
    proc = subprocess.Popen([program(), str(scene), "-o", "b.nc"], cwd=tmp_path, env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    wait_stopped(proc)
    assert len(list(tmp_path.glob("b.nc.tmp*"))) == 1
    proc.send_signal(signal.SIGTERM)
    proc.send_signal(signal.SIGCONT)
    proc.communicate(timeout=60)
    assert proc.returncode == -signal.SIGTERM
    assert not list(tmp_path.glob("b.nc.tmp*")) and not (tmp_path / "b.nc").exists()
    # the journal keeps the computed profiles: the run resumes to the end
    assert (tmp_path / "b.nc.journal").exists()
    r = run_program(scene, "-o", "b.nc", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert "resuming: 4 of 4" in r.stderr
    assert (tmp_path / "b.nc").read_bytes()[:4] == b"\x89HDF"


def test_ignored_sigint_stays_ignored(scene):
    # nohup and background jobs ignore signals; the program must not undo that
    env = {**os.environ, "PAVEFRIC_TEST_PAUSE": "commit"}
    proc = subprocess.Popen([program(), scene.name, "-o", "out.nc"], cwd=scene.parent, env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_IGN))
    wait_stopped(proc)
    proc.send_signal(signal.SIGINT)
    proc.send_signal(signal.SIGCONT)
    proc.communicate(timeout=60)
    assert proc.returncode == 0
    assert (scene.parent / "out.nc").read_bytes()[:4] == b"\x89HDF"
    assert not list(scene.parent.glob("out.nc.tmp*"))


# ---- the attack of 2026-12-07: files a batch, merge or write_profiles destroyed ---------

@pytest.mark.parametrize("restart", [".false.", ".true."])
def test_a_journal_path_that_is_a_symlink_is_refused(tmp_path, restart):
    """The journal was written through a symbolic link at `<output>.journal`
    into the file it named (the user's thesis), and the link removed at the
    end."""
    scene = make_batch(tmp_path)
    scene.write_text(scene.read_text().replace("depths = 0.0", f"depths = 0.0, restart = {restart}"))
    thesis = tmp_path / "thesis.txt"
    thesis.write_text("precious user data\n")
    (tmp_path / "out.nc.journal").symlink_to(thesis)
    before = snapshot(thesis, *all_inputs(tmp_path / "profiles"))
    r = run_program(scene, "-o", "out.nc", cwd=tmp_path)
    assert_refused(r, "the journal of -o 'out.nc.journal': is a symbolic link",
                   "pavefric replaces only its own journals")
    assert_intact(before)
    assert (tmp_path / "out.nc.journal").is_symlink()
    assert not (tmp_path / "out.nc").exists()


@pytest.mark.parametrize("restart", [".false.", ".true."])
def test_a_users_file_at_the_journal_path_is_left_alone(tmp_path, restart):
    """A file of the user's named `out.nc.journal` was deleted by a batch with
    restart = .false. (restart = .true. called it another batch's journal and
    advised restart = .false.)."""
    scene = make_batch(tmp_path)
    scene.write_text(scene.read_text().replace("depths = 0.0", f"depths = 0.0, restart = {restart}"))
    notes = tmp_path / "out.nc.journal"
    notes.write_text("my notes, not a journal\n")
    before = snapshot(notes)
    r = run_program(scene, "-o", "out.nc", cwd=tmp_path)
    assert_refused(r, "the journal of -o 'out.nc.journal': exists and is not a pavefric batch "
                   "journal", "remove or rename it")
    assert "another batch" not in r.stderr
    assert_intact(before)
    # a journal of pavefric's own is still taken (an interrupted batch resumes)
    notes.unlink()
    r = run_program(scene, "-o", "out.nc", "--max-profiles", "2", cwd=tmp_path)
    assert r.returncode == 3, r.stderr
    r = run_program(scene, "-o", "out.nc", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    if restart == ".true.":
        assert "2 taken from the journal" in r.stdout + r.stderr


@pytest.mark.parametrize("interrupt", [False, True])
def test_a_batch_over_the_directory_of_its_output_resumes(tmp_path, interrupt):
    """&batch profiles = 'seg' (a directory: all its files) with -o seg/out.nc:
    after an interruption the rerun took the batch's own journal for profile
    1 and refused to resume, and a second run took the output. The batch's
    own output, journal and temporaries are not profiles."""
    from pavefric.surfaces import road_profiles

    road_profiles(str(tmp_path / "seg"), n=5, points=256)
    scene = tmp_path / "b.nml"
    scene.write_text("&batch profiles = 'seg', depths = 0.0 /\n&surface closed = .false. /\n"
                     "&operation speeds_kmh = 20 /\n")
    (tmp_path / "seg" / "out.nc.tmp999999999.pavefric").write_text("a temporary a killed writer left\n")
    if interrupt:
        r = run_program(scene, "-o", "seg/out.nc", "--max-profiles", "2", cwd=tmp_path)
        assert r.returncode == 3, r.stderr
    r = run_program(scene, "-o", "seg/out.nc", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert "5 profiles" in r.stdout + r.stderr, r.stdout + r.stderr
    # and once more over the finished output: the same five profiles
    r = run_program(scene, "-o", "seg/out.nc", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    with netCDF4.Dataset(tmp_path / "seg" / "out.nc") as nc:
        assert nc.dimensions["profile"].size == 5


def survey(path):
    pavefric.write_profiles(path, np.sin(np.arange(3 * 256).reshape(3, 256) * 0.3) * 1e-3,
                            dx=0.87e-3, names=["0+100", "0+200", "0+300"])


def test_an_output_over_a_profile_survey_is_refused(scene):
    """write_profiles gives its surveys source 'pavefric.write_profiles'; the
    program took any source starting 'pavefric' for an output of its own and
    replaced a measured survey with friction results."""
    target = scene.parent / "survey_part2.nc"
    survey(target)
    before = snapshot(target)
    r = run_program(scene.name, "-o", target.name, cwd=scene.parent)
    assert_refused(r, f"-o '{target.name}': exists and is a profile file",
                   "an input, not an output of a run")
    assert_intact(before)
    with pytest.raises(pavefric.PavefricError, match="exists and is a profile file"):
        pavefric.run(scene, output=target)
    assert_intact(before)
    # a survey replaces a survey (written again), never a friction output
    survey(target)
    out = scene.parent / "out.nc"
    assert run_program(scene.name, "-o", out.name, cwd=scene.parent).returncode == 0
    results = snapshot(out)
    with pytest.raises(pavefric.PavefricError, match="is a pavefric results file"):
        survey(out)
    assert_intact(results)


def test_python_writers_replace_only_their_own_kind(scene, tmp_path):
    """merge and write_profiles replaced a text file or another tool's NetCDF
    (the program refused both: the README's rule)."""
    from pavefric.merge import MergeError, merge

    d = tmp_path / "b"
    batch = make_batch(d, n=4)
    parts = []
    for k, pattern in enumerate(["profiles/*_000[12].txt", "profiles/*_000[34].txt"]):
        part = d / f"part_{k}.nml"
        part.write_text(batch.read_text().replace("profiles/*.txt", pattern))
        out = d / f"part_{k}.nc"
        r = run_program(part, "-o", out, cwd=d)
        assert r.returncode == 0, r.stderr
        parts.append(out)
    notes = d / "notes.txt"
    notes.write_text("my field notes\n")
    other = d / "era5.nc"
    with netCDF4.Dataset(other, "w") as nc:
        nc.source = "ERA5 reanalysis"
    before = snapshot(notes, other)
    for target in (notes, other):
        with pytest.raises(MergeError, match="pavefric replaces only its own outputs"):
            merge(parts, target)
        with pytest.raises(pavefric.PavefricError, match="pavefric replaces only its own outputs"):
            survey(target)
    assert_intact(before)
    # each still replaces its own: a merge output, a survey
    merged = d / "merged.nc"
    merge(parts, merged)
    merge(parts, merged)
    survey(d / "s.nc")
    survey(d / "s.nc")
    with pytest.raises(MergeError, match="exists and is a profile file"):
        merge(parts, d / "s.nc")


def test_a_failed_run_leaves_no_outputs_directory(tmp_path):
    """A run refused on its profile left an empty outputs/ behind (the
    default output's directory, made before the checks)."""
    scene = write_scene(tmp_path, "s", profile_text="0.1\n0.2x\n")
    r = run_program(scene.name, cwd=tmp_path)
    assert r.returncode == 1 and "'0.2x' is not a number" in r.stderr, r.stderr
    assert not (tmp_path / "outputs").exists()
    # one that was there stays, and a good run still writes into it
    (tmp_path / "outputs").mkdir()
    r = run_program(scene.name, cwd=tmp_path)
    assert r.returncode == 1 and (tmp_path / "outputs").is_dir()
    good = write_scene(tmp_path / "g", "g")
    r = run_program(good.name, cwd=good.parent)
    assert r.returncode == 0, r.stderr
    assert (good.parent / "outputs" / "g.nc").is_file()


def test_a_profile_list_with_a_byte_order_mark(tmp_path):
    """A profile_list saved with a UTF-8 byte-order mark (an editor's): the
    mark became part of the first path, which then could not be opened."""
    scene = make_batch(tmp_path, n=3, list_file=True)
    listed = tmp_path / "list.txt"
    listed.write_bytes(b"\xef\xbb\xbf" + listed.read_bytes())
    r = run_program(scene, "-o", "out.nc", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    with netCDF4.Dataset(tmp_path / "out.nc") as nc:
        assert nc.dimensions["profile"].size == 3


def test_a_scene_that_is_a_fifo_is_refused_not_waited_for(tmp_path):
    """An attack (2026-12-07): a scene given as a FIFO with no writer blocked
    the program forever, and one read through a pipe (`<(cat s.nml)`) was
    read as empty ("speeds_kmh: not given"). Scenes and profile lists are
    read from regular files only, as profiles are."""
    fifo = tmp_path / "f.nml"
    os.mkfifo(fifo)
    r = subprocess.run([program(), str(fifo), "-o", str(tmp_path / "o.nc")],
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 1, r.stderr
    assert "f.nml': a FIFO (named pipe), not a regular file" in r.stderr, r.stderr
    assert not (tmp_path / "o.nc").exists()
    scene = make_batch(tmp_path / "b", n=2)
    scene.write_text(scene.read_text().replace("profiles = 'profiles/*.txt'",
                                               "profile_list = 'list.fifo'"))
    os.mkfifo(tmp_path / "b" / "list.fifo")
    r = subprocess.run([program(), str(scene), "-o", str(tmp_path / "b.nc")],
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 1 and "list.fifo': a FIFO (named pipe)" in r.stderr, r.stderr
