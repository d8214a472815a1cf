"""Every report, study and side file a pavefric command writes follows the
writers' rule (an attack of 2026-12-07, attack19, F1-F11: until then they
wrote with write_text, open('w'), savefig, copyfile and to_netcdf straight
onto their paths): a user's file at the path is refused and left byte for
byte, a command's own input is never written over, a FIFO or a directory is
refused, and the refusal comes before the work. Each test is one of the
attack's reproducers."""
from __future__ import annotations

import os
import subprocess
import sys

import pytest

from conftest import write_scene

ROOT = __import__("pathlib").Path(__file__).resolve().parents[1]
NOTES = "the user's own notes, named by mistake\n"


def cli(*args, cwd, timeout=300):
    return subprocess.run([sys.executable, "-m", "pavefric", *map(str, args)],
                          capture_output=True, text=True, cwd=cwd, timeout=timeout)


def refused(r, path, what="is not a file this command wrote"):
    assert r.returncode != 0, r.stdout + r.stderr
    assert f"'{path}'" in r.stderr and what in r.stderr, r.stderr
    assert "Traceback" not in r.stderr, r.stderr


def test_docs_pages_replace_only_themselves(tmp_path):
    notes = tmp_path / "notes.txt"
    notes.write_text(NOTES)
    r = cli("docs", "--inputs", notes, "--outputs", tmp_path / "o.md", cwd=tmp_path)
    refused(r, notes)
    assert notes.read_text() == NOTES and not (tmp_path / "o.md").exists()
    # through a symbolic link to the user's file: the same
    (tmp_path / "link.md").symlink_to(notes.name)
    r = cli("docs", "--inputs", tmp_path / "i.md", "--outputs", tmp_path / "link.md",
            cwd=tmp_path)
    assert r.returncode != 0 and notes.read_text() == NOTES
    assert not (tmp_path / "i.md").exists()                  # checked before either
    # a FIFO is refused at once (it blocked the writer), a missing directory named
    os.mkfifo(tmp_path / "fifo")
    r = cli("docs", "--inputs", tmp_path / "fifo", "--outputs", tmp_path / "o.md",
            cwd=tmp_path, timeout=120)
    refused(r, tmp_path / "fifo", "not a regular file")
    r = cli("docs", "--inputs", tmp_path / "nodir" / "i.md", "--outputs", tmp_path / "o.md",
            cwd=tmp_path)
    refused(r, tmp_path / "nodir" / "i.md", "cannot write in directory")
    # its own pages are replaced
    for _ in range(2):
        r = cli("docs", "--inputs", tmp_path / "i.md", "--outputs", tmp_path / "o.md",
                cwd=tmp_path)
        assert r.returncode == 0, r.stderr
    assert (tmp_path / "i.md").read_text().startswith("# Scene namelist reference")
    assert not [p for p in tmp_path.iterdir() if ".tmp" in p.name]
    # one path given to both pages, however spelled, whether or not it exists
    # yet: refused before either is written (it would hold only the second)
    for page in ("new.md", "i.md"):
        before = (tmp_path / page).read_bytes() if (tmp_path / page).exists() else None
        r = cli("docs", "--inputs", page, "--outputs", f"./{page}", cwd=tmp_path)
        assert r.returncode != 0 and "Traceback" not in r.stderr, r.stderr
        # (a page not yet written is the other by its path; one written, by the core's
        # test of the file's identity)
        said = "another file this command reads or writes" if page == "new.md" else \
            "would destroy an input"
        assert f"'{page}'" in r.stderr and said in r.stderr, r.stderr
        after = (tmp_path / page).read_bytes() if (tmp_path / page).exists() else None
        assert after == before


def test_accuracy_refuses_before_its_runs(tmp_path):
    scene = write_scene(tmp_path)
    notes = tmp_path / "notes.md"
    notes.write_text(NOTES)
    before = scene.read_bytes()
    for report in (notes, scene):                            # a user's file; its own scene
        r = cli("accuracy", scene, "--speeds", "20", "--repeats", "1", "--outdir",
                tmp_path / "acc", "--report", report, "-q", cwd=tmp_path, timeout=120)
        assert r.returncode != 0 and "Traceback" not in r.stderr, r.stderr
        assert "accuracy: scene" not in r.stdout                # no study was run
    assert notes.read_text() == NOTES and scene.read_bytes() == before
    assert not list((tmp_path / "acc").glob("accuracy_*"))
    # a user's file among the outdir's
    (tmp_path / "acc" / "tolerance_scene.csv").write_text(NOTES)
    r = cli("accuracy", scene, "--speeds", "20", "--repeats", "1", "--outdir", tmp_path / "acc",
            "-q", cwd=tmp_path, timeout=120)
    refused(r, tmp_path / "acc" / "tolerance_scene.csv")
    assert (tmp_path / "acc" / "tolerance_scene.csv").read_text() == NOTES


def test_surfaces_refuse_a_users_profile_before_tuning(tmp_path):
    out = tmp_path / "surf"
    out.mkdir()
    (out / "GSP.txt").write_text("0.1\n0.2\n0.3\n")
    r = cli("surfaces", "--outdir", out, "--table", ROOT / "inputs/data/kane2017_tables.csv",
            cwd=tmp_path, timeout=120)
    refused(r, out / "GSP.txt")
    assert (out / "GSP.txt").read_text() == "0.1\n0.2\n0.3\n"
    assert sorted(p.name for p in out.iterdir()) == ["GSP.txt"]


@pytest.mark.parametrize("command", [["validate"], ["speed-gradient"], ["rubber-report"],
                                     ["bench", "--quick"]])
def test_maintainers_reports_refuse_a_users_file_before_the_work(tmp_path, command):
    notes = tmp_path / "notes.md"
    notes.write_text(NOTES)
    r = cli(*command, "--report", notes, cwd=ROOT, timeout=120)
    refused(r, notes)
    assert notes.read_text() == NOTES
    assert not [p for p in tmp_path.iterdir() if p.name != "notes.md"]


@pytest.mark.parametrize("side", ["comparison.csv", "validation.json"])
def test_validate_refuses_a_users_side_file_before_the_work(tmp_path, side):
    out = tmp_path / "out"
    out.mkdir()
    (out / side).write_text(NOTES)
    r = cli("validate", "--report", tmp_path / "v.md", "--outdir", out, cwd=ROOT, timeout=120)
    refused(r, out / side)
    assert (out / side).read_text() == NOTES
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]
    assert [p.name for p in out.iterdir()] == [side]


def test_rubber_report_never_writes_over_its_compound(tmp_path):
    compound = tmp_path / "c.nml"
    compound.write_text((ROOT / "inputs/rubber/tread_compound.nml").read_text())
    before = compound.read_bytes()
    r = cli("rubber-report", "--report", compound, "--compound", compound, cwd=ROOT,
            timeout=120)
    assert r.returncode != 0 and "Traceback" not in r.stderr, r.stderr
    assert compound.read_bytes() == before


def test_prony_representative_never_writes_over_the_data_it_fits(tmp_path):
    data = tmp_path / "dma.csv"
    assert cli("prony", "--write-representative", data, cwd=tmp_path).returncode == 0
    data.write_text(data.read_text() + "# the user's edit\n")
    before = data.read_bytes()
    r = cli("prony", data, "--write-representative", data, cwd=tmp_path)
    refused(r, data, "is an input")
    assert data.read_bytes() == before


def test_two_outputs_at_one_path_are_refused_before_the_work(tmp_path):
    scene = write_scene(tmp_path)
    r = cli("run", scene, "-o", "r.png", "--plot", "r.png", cwd=tmp_path)
    refused(r, "r.png", "is also")
    assert not (tmp_path / "r.png").exists()                 # no run was made
    profile = tmp_path / "scene_profile.txt"
    r = cli("profile", profile, "--plot", "e.png", "--export", "e.png", cwd=tmp_path)
    refused(r, "e.png", "is also")
    assert not (tmp_path / "e.png").exists()


@pytest.mark.parametrize("args, path", [
    (["profile", "scene_profile.txt", "--export", "nodir/e.txt"], "nodir/e.txt"),
    (["profile", "scene_profile.txt", "--plot", "nodir/p.png"], "nodir/p.png"),
    (["surface", "-o", "nodir/s.txt"], "nodir/s.txt"),
], ids=["export", "profile-plot", "surface"])
def test_a_missing_directory_is_a_named_error(tmp_path, args, path):
    write_scene(tmp_path)
    r = cli(*args, cwd=tmp_path)
    refused(r, path, "cannot write in directory")


def test_an_empty_output_path_is_a_named_error(tmp_path):
    r = cli("surface", "-o", "", cwd=tmp_path)
    assert r.returncode != 0 and "the output path is empty" in r.stderr, r.stderr
    assert "Traceback" not in r.stderr


def test_a_read_only_output_is_refused_and_a_private_one_stays_private(tmp_path):
    """attack19 F9: a rename replaces a file whatever its mode, and the new
    file took the umask's 0644: a results file made read-only was replaced,
    and a private 0600 one became world-readable."""
    import stat

    from conftest import run_program

    scene = write_scene(tmp_path)
    out = tmp_path / "out.nc"
    assert run_program(scene, "-o", out, cwd=tmp_path).returncode == 0
    out.chmod(0o600)
    assert run_program(scene, "-o", out, cwd=tmp_path).returncode == 0
    assert stat.S_IMODE(out.stat().st_mode) == 0o600
    out.chmod(0o444)
    before = out.read_bytes()
    r = run_program(scene, "-o", out, cwd=tmp_path)
    assert r.returncode != 0 and "is read-only" in r.stderr, r.stderr
    assert out.read_bytes() == before and stat.S_IMODE(out.stat().st_mode) == 0o444
    # the Python writers alike
    png = tmp_path / "mu.png"
    assert cli("plot", out, "-o", png, cwd=tmp_path).returncode == 0
    png.chmod(0o640)
    assert cli("plot", out, "-o", png, "--title", "again", cwd=tmp_path).returncode == 0
    assert stat.S_IMODE(png.stat().st_mode) == 0o640
    png.chmod(0o444)
    before = png.read_bytes()
    refused(cli("plot", out, "-o", png, cwd=tmp_path), png, "is read-only")
    assert png.read_bytes() == before


def test_road_profiles_replace_only_their_own_segments(tmp_path):
    from pavefric.surfaces import road_profiles

    road = tmp_path / "road"
    road.mkdir()
    (road / "seg_0002.txt").write_text("my measured segment\n")
    with pytest.raises(__import__("pavefric").PavefricError, match="is not a file this command"):
        road_profiles(str(road), n=3, points=64)
    assert sorted(p.name for p in road.iterdir()) == ["seg_0002.txt"]    # none written
    assert (road / "seg_0002.txt").read_text() == "my measured segment\n"
    (road / "seg_0002.txt").unlink()
    first = road_profiles(str(road), n=3, points=64)
    again = road_profiles(str(road), n=3, points=64)                   # its own: replaced
    assert first == again and all(open(p).read().startswith("# demo road segment ")
                                  for p in again)
