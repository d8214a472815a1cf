"""A survey at scale, simulated small (issue 23, docs/cluster.md "A survey of a
million profiles"): many small profiles on many ranks (oversubscribed), and a
survey run in parts (job arrays) joined by `python -m pavefric merge`; the
output complete and equal, bit for bit, to one serial run (one machine)."""
import subprocess
import sys

import pytest
import xarray as xr

import pavefric

from conftest import run_program
from test_batch import same_contents
from test_mpi_batch import mpirun

SCENE = ("&batch profiles = '{pattern}', depths = 0.0, 1.0e-3 /\n"
         "&surface closed = .false., mu_loc = 0.6 /\n"
         "&operation speeds_kmh = 20, 60 /\n")


@pytest.fixture(scope="module")
def survey(tmp_path_factory):
    """400 small profiles (96 points), one broken, and the serial run of all."""
    from pavefric.surfaces import road_profiles

    tmp = tmp_path_factory.mktemp("survey")
    road_profiles(str(tmp / "profiles"), n=400, points=96)
    (tmp / "profiles" / "seg_0123.txt").write_text("height_mm\n0.1\nabc\n")
    (tmp / "all.nml").write_text(SCENE.format(pattern="profiles/*.txt"))
    r = run_program(tmp / "all.nml", "-o", tmp / "all.nc")
    assert r.returncode == 4, r.stderr             # done, one profile failed
    return tmp


def test_many_ranks_oversubscribed_equal_the_serial_run(survey, tmp_path):
    r = mpirun(survey / "all.nml", "-o", tmp_path / "mpi.nc", n=8)
    assert r.returncode == 4, r.stderr          # done, one profile failed, on every rank
    same_contents(survey / "all.nc", tmp_path / "mpi.nc")
    with xr.open_dataset(tmp_path / "mpi.nc") as ds:
        assert ds.sizes["profile"] == 400
        assert int((ds["status"] == 1).sum()) == 399 and int((ds["status"] == 2).sum()) == 1
        assert ds.attrs["profiles_computed"] == 399 and ds.attrs["profiles_failed"] == 1


def test_a_survey_in_parts_merges_to_the_whole_run(survey, tmp_path):
    parts = []
    for k, pattern in enumerate(["seg_00*.txt", "seg_01*.txt", "seg_02*.txt", "seg_03*.txt",
                                 "seg_04*.txt"]):
        scene = survey / f"part{k}.nml"
        scene.write_text(SCENE.format(pattern=f"profiles/{pattern}") +
                         "! this part's own comment\n")
        out = tmp_path / f"part{k}.nc"
        r = run_program(scene, "-o", out)
        assert r.returncode in (0, 4), r.stderr
        parts.append(out)
    merged = tmp_path / "merged.nc"
    r = subprocess.run([sys.executable, "-m", "pavefric", "merge", *map(str, parts), "-o",
                        str(merged)], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    # the parts' own scenes, titles and histories are theirs (their profiles:
    # &batch), everything else is equal
    with xr.open_dataset(merged) as ds:
        own = [k for k in ds.attrs if k.startswith(("param_batch_", "param_output_"))]
        assert "param_batch_profiles" in own
    same_contents(survey / "all.nc", merged,
                  ignore_attrs=("history", "title", "input_namelist", "merged_parts",
                                "parameters", *own))
    with xr.open_dataset(merged) as ds:
        assert ds.attrs["profiles_computed"] == 399 and ds.attrs["profiles_failed"] == 1
        assert "part0.nc" in ds.attrs["merged_parts"] and "part4.nc" in ds.attrs["merged_parts"]


def _merge(*args):
    return subprocess.run([sys.executable, "-m", "pavefric", "merge", *map(str, args)],
                          capture_output=True, text=True, timeout=300)


def test_merge_refuses_parts_that_do_not_belong_together(survey, tmp_path):
    def part(name, pattern, extra=""):
        scene = tmp_path / f"{name}.nml"
        scene.write_text(SCENE.format(pattern=str(survey / "profiles" / pattern)) + extra)
        out = tmp_path / f"{name}.nc"
        assert run_program(scene, "-o", out).returncode in (0, 4)
        return out

    a = part("a", "seg_000*.txt")
    b = part("b", "seg_001*.txt")
    overlap = part("overlap", "seg_0019.txt")
    other_mu = part("other_mu", "seg_002*.txt", "&pad length = 0.010 /\n")
    r = _merge(a, overlap, b, "-o", tmp_path / "m.nc")
    assert r.returncode == 1 and "the profile 'seg_0019' is in both" in r.stderr
    r = _merge(a, other_mu, "-o", tmp_path / "m.nc")
    assert r.returncode == 1 and "ran another scene" in r.stderr
    assert "(&pad length: 0.02 against 0.01)" in r.stderr, r.stderr    # what differs
    # the same values written otherwise are the same scene (attack22: refused
    # by the text), and a part whose profiles all failed ran no effects but
    # belongs to the survey (attack22: refused, 'effects' differs)
    (tmp_path / "spelled.nml").write_text(SCENE.format(
        pattern=str(survey / "profiles" / "seg_003*.txt")).replace("mu_loc = 0.6",
                                                                    "mu_loc = 6.0e-1"))
    spelled = tmp_path / "spelled.nc"
    assert run_program(tmp_path / "spelled.nml", "-o", spelled).returncode in (0, 4)
    (tmp_path / "none.txt").write_text("nope_1.txt\nnope_2.txt\n")
    (tmp_path / "failed.nml").write_text(SCENE.format(pattern="x").replace(
        "profiles = 'x'", f"profile_list = '{tmp_path / 'none.txt'}'"))
    failed = tmp_path / "failed.nc"
    assert run_program(tmp_path / "failed.nml", "-o", failed).returncode == 4
    r = _merge(a, spelled, failed, "-o", tmp_path / "m3.nc")
    assert r.returncode == 0, r.stderr
    with xr.open_dataset(tmp_path / "m3.nc") as m, xr.open_dataset(a) as first:
        assert m.sizes["profile"] == 9 + 10 + 2             # seg_0001-9, seg_003x, 2 failed
        assert m.attrs["effects"] == first.attrs["effects"] != ""
    r = _merge(failed, a, "-o", tmp_path / "m4.nc")         # the failed part first
    assert r.returncode == 0, r.stderr
    with xr.open_dataset(tmp_path / "m4.nc") as m, xr.open_dataset(a) as first:
        assert m.attrs["effects"] == first.attrs["effects"]
    # a part written before the parameters were recorded is compared by its
    # scene's text, in either order (the review: refused when it came first,
    # its missing param_* read as a difference)
    import netCDF4

    # (pavefric's files open read-only in netCDF-C: docs/outputs.md; nccopy's
    # copy opens for writing)
    old = tmp_path / "old.nc"
    subprocess.run(["nccopy", str(b), str(old)], check=True)
    with netCDF4.Dataset(old, "a") as nc:
        for name in [k for k in nc.ncattrs() if k == "parameters" or k.startswith("param_")]:
            nc.delncattr(name)
    for order in ((a, old), (old, a)):
        r = _merge(*order, "-o", tmp_path / "m5.nc")
        assert r.returncode == 0, r.stderr
    with netCDF4.Dataset(old, "a") as nc:          # and it still tells other physics
        nc.input_namelist = nc.input_namelist.replace("mu_loc = 0.6", "mu_loc = 0.5")
    r = _merge(old, a, "-o", tmp_path / "m6.nc")
    assert r.returncode == 1 and "their namelists differ" in r.stderr, r.stderr
    before = a.read_bytes()
    r = _merge(a, b, "-o", a)
    assert r.returncode == 1 and "would destroy an input" in r.stderr, r.stderr
    assert a.read_bytes() == before
    r = _merge(a, survey / "all.nml", "-o", tmp_path / "m.nc")
    assert r.returncode == 1 and "cannot read" in r.stderr and "all.nml" in r.stderr
    assert not (tmp_path / "m.nc").exists()
    assert not list(tmp_path.glob("m.nc.*"))          # no temporary left behind


def test_parts_with_a_large_scene_merge_and_keep_it(survey, tmp_path):
    """A scene beyond what an HDF5 attribute holds (a variable in each part)
    stays whole through the merge."""
    comment = "! a survey scene may carry long comments, line after line\n" * 1000
    parts = []
    for k, pattern in enumerate(["seg_000*.txt", "seg_001*.txt"]):
        scene = survey / f"big{k}.nml"
        scene.write_text(comment + SCENE.format(pattern=f"profiles/{pattern}"))
        out = tmp_path / f"big{k}.nc"
        assert run_program(scene, "-o", out).returncode in (0, 4)
        parts.append(out)
    merged = tmp_path / "merged.nc"
    r = _merge(*parts, "-o", merged)
    assert r.returncode == 0, r.stderr
    ds = pavefric.open_dataset(merged)
    assert ds.attrs["input_namelist"] == (survey / "big0.nml").read_text()
    assert ds.sizes["profile"] == 19
