"""Silent nonsense made loud (issue 19): knobs the chosen wet model ignores
are warned about; an accuracy request that cannot estimate its error is
refused (it wrote mu_error_estimate = 1.797e308); NetCDF surveys with empty
or duplicate profile names or a non-finite chainage are refused; temporaries left by a SIGKILL are removed
by the next run that writes the same output."""
import os
import signal
import subprocess
import sys

import netCDF4
import numpy as np
import pytest
import xarray as xr

import pavefric
from conftest import DX, run_program, write_scene
from test_files import program, wait_stopped

WAVE = np.sin(np.arange(300) * 0.3) * 0.5


# ---- knobs the chosen components do not use ----------------------------------------

@pytest.mark.parametrize("water, surface, message", [
    ("depth = 1e-3, wet_model = 'squeeze', alpha = 5.0", None,
     "&water alpha = 5 is not used with &water wet_model = 'squeeze'"),
    ("depth = 1e-3, wet_model = 'squeeze', beta = 2.0", None,
     "&water beta = 2 is not used with &water wet_model = 'squeeze'"),
    ("depth = 1e-3, wet_model = 'kane2017'",
     "profile_file = 'scene_profile.txt', mu_loc = 0.5, microtexture_rms = 1e-5",
     "&surface microtexture_rms = 0.00001 is not used with &water wet_model = 'kane2017'"),
])
def test_a_wet_knob_the_model_does_not_use_is_warned_about(tmp_path, water, surface, message):
    groups = {"water": water}
    if surface:
        groups["surface"] = surface
    scene = write_scene(tmp_path, groups=groups)
    out = tmp_path / "o.nc"
    r = run_program(scene, "-o", out)
    assert r.returncode == 0, r.stderr
    assert message in r.stderr
    with xr.open_dataset(out) as ds:                    # recorded in the output too
        assert message in ds.attrs["warnings"]


def test_the_used_knobs_give_no_such_warning(tmp_path):
    scene = write_scene(tmp_path, groups={"water": "depth = 1e-3, wet_model = 'squeeze'",
                                          "surface": "profile_file = 'scene_profile.txt', "
                                                     "mu_loc = 0.5, microtexture_rms = 1e-5"})
    r = run_program(scene, "-o", tmp_path / "o.nc")
    assert r.returncode == 0 and "is not used" not in r.stderr, r.stderr


def test_python_warns_about_alpha_with_squeeze():
    with pytest.warns(pavefric.PavefricWarning, match="alpha = 5 is not used"):
        pavefric.simulate(WAVE * 1e-3, 1e-3, [20.0], depth=1e-3, wet_model="squeeze", alpha=5.0)


# ---- accuracy on demand needs room for two halvings ---------------------------------

def test_tolerance_with_substeps_too_large_for_an_estimate_is_an_error(tmp_path):
    scene = write_scene(tmp_path, groups={"numerics": "tolerance = 1e-6, substeps = 2048"})
    out = tmp_path / "o.nc"
    r = run_program(scene, "-o", out)
    assert r.returncode == 1
    assert "&numerics substeps = 2048 with tolerance = 1e-6" in r.stderr
    assert "give substeps <= 1024" in r.stderr
    assert not out.exists()


def test_the_largest_start_that_can_estimate_writes_a_finite_estimate():
    ds = pavefric.simulate(WAVE[:120] * 1e-3, 1e-3, [20.0], tolerance=1e-12, substeps=1024)
    est = ds["mu_error_estimate"].values
    assert np.all(np.isfinite(est)) and np.all(est < 1.0), est
    assert ds["substeps_used"].values[0] == 4096


# ---- NetCDF surveys: names and chainage ----------------------------------------------

def _survey(path, names=("a", "b", "c"), chainage=(0.0, 10.0, 20.0)):
    pavefric.write_profiles(path, [WAVE] * 3, dx=1e-3, names=["a", "b", "c"], units="mm",
                            chainage=[0.0, 10.0, 20.0])
    with netCDF4.Dataset(path, "a") as f:
        width = f.dimensions["name_strlen"].size
        for k, name in enumerate(names):
            f["profile_name"][k] = netCDF4.stringtochar(np.array([name.ljust(width)], f"S{width}"))[0]
        f["chainage"][:] = np.asarray(chainage, float)
    return path


@pytest.mark.parametrize("names, chainage, message", [
    (("a", "b", "a"), (0.0, 10.0, 20.0), "profiles 1 and 3 are both named 'a'"),
    (("a", "", "c"), (0.0, 10.0, 20.0), "profile 2 of 3 has an empty name"),
    (("a", "b", "c"), (0.0, np.nan, 20.0), "profile 2 ('b') has chainage NaN"),
    (("a", "b", "c"), (0.0, 10.0, np.inf), "profile 3 ('c') has chainage Infinity"),
    (("a", "b", "c"), (0.0, 9.969209968386869e36, 20.0), "farther than any road"),
])
def test_a_survey_with_bad_names_or_chainage_is_refused(tmp_path, names, chainage, message):
    nc = _survey(tmp_path / "survey.nc", names, chainage)
    # as one profile of a scene
    scene = write_scene(tmp_path, groups={"surface": f"profile_file = '{nc}', mu_loc = 0.5, "
                                                     "profile_name = 'c'"})
    r = run_program(scene, "-o", tmp_path / "one.nc")
    assert r.returncode == 1 and message in r.stderr, r.stderr
    assert f"&surface profile_file = '{nc}'" in r.stderr
    # as a batch
    batch = tmp_path / "batch.nml"
    batch.write_text(scene.read_text().replace(f"profile_file = '{nc}', ", "")
                     .replace(", profile_name = 'c'", "")
                     + f"&batch\n  profiles = '{nc}'\n/\n")
    out = tmp_path / "b.nc"
    r = run_program(batch, "-o", out)
    assert r.returncode == 1 and message in r.stderr, r.stderr
    assert not out.exists()
    # from Python
    with pytest.raises(pavefric.PavefricError, match=message.split("(")[0].strip()):
        pavefric.list_profiles(nc)


def test_a_good_survey_still_reads(tmp_path):
    nc = _survey(tmp_path / "survey.nc")
    assert [e.name for e in pavefric.list_profiles(nc)] == ["a", "b", "c"]


# ---- temporaries of a killed run ----------------------------------------------------

def _dead_pid() -> int:
    p = subprocess.Popen(["true"])
    p.wait()
    return p.pid


def test_sigkill_while_writing_then_a_rerun_leaves_no_temporary(tmp_path):
    scene = write_scene(tmp_path)
    env = {**os.environ, "PAVEFRIC_TEST_PAUSE": "commit"}
    proc = subprocess.Popen([program(), scene.name, "-o", "out.nc"], cwd=tmp_path, env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    wait_stopped(proc)
    temps = list(tmp_path.glob("out.nc.tmp*"))
    assert temps == [tmp_path / f"out.nc.tmp{proc.pid}.pavefric"]
    proc.send_signal(signal.SIGKILL)                   # no handler runs
    proc.communicate(timeout=60)
    assert temps[0].exists()                           # what a SIGKILL leaves
    # another process's live temporary and look-alikes of the user's stay:
    # a file of the user's named <output>.tmp<a dead PID> (without the
    # temporaries' suffix) was deleted by the sweep until 2026-12-07
    # (attack19 F8)
    alive = tmp_path / f"out.nc.tmp{os.getpid()}.pavefric"
    alive.write_bytes(b"being written")
    mine = tmp_path / "out.nc.tmpfile"
    mine.write_bytes(b"the user's")
    users = [tmp_path / f"out.nc.tmp{_dead_pid()}", tmp_path / f"out.nc.tmp{_dead_pid()}.bak",
             tmp_path / f"out.nc.tmp{_dead_pid()}.pavefricx"]
    for k, f in enumerate(users):
        f.write_bytes(b"the user's %d" % k)
    dead_other = tmp_path / f"other.nc.tmp{_dead_pid()}.pavefric"
    dead_other.write_bytes(b"not this output's")
    r = run_program(scene, "-o", "out.nc", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert not temps[0].exists()
    assert alive.read_bytes() == b"being written"
    assert mine.read_bytes() == b"the user's"
    assert dead_other.exists()
    for k, f in enumerate(users):
        assert f.read_bytes() == b"the user's %d" % k
    assert sorted(p.name for p in tmp_path.glob("out.nc*")) == sorted(
        ["out.nc", alive.name, mine.name] + [f.name for f in users])


def test_a_dead_writers_temporary_of_a_batch_is_removed(tmp_path):
    from test_batch import make_batch
    scene = make_batch(tmp_path)
    stale = tmp_path / f"b.nc.tmp{_dead_pid()}.pavefric"
    stale.write_bytes(b"half a file")
    r = run_program(scene, "-o", "b.nc", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert not stale.exists()


@pytest.mark.parametrize("bad", ["nan", "inf", "-Infinity"])
def test_a_profile_list_with_a_non_finite_chainage_is_refused(tmp_path, bad):
    from test_batch_output import list_batch
    scene = list_batch(tmp_path, n=3, broken=0)
    lines = (tmp_path / "list.txt").read_text().splitlines()
    lines[2] = lines[2].split()[0] + "  " + bad           # the second profile
    (tmp_path / "list.txt").write_text("\n".join(lines) + "\n")
    out = tmp_path / "b.nc"
    r = run_program(scene, "-o", out)
    assert r.returncode == 1
    assert f"list.txt:3: chainage '{bad}' is not a finite number (m)" in r.stderr, r.stderr
    assert not out.exists()


def test_a_default_given_again_is_no_reason_to_warn(tmp_path):
    """Python passes every variable of a scene, defaults included: the value
    decides, so the program and Python record the same warnings."""
    scene = write_scene(tmp_path, groups={"water": "depth = 1e-3, wet_model = 'squeeze', "
                                                   "alpha = 12.0, beta = 1.75"})
    out = tmp_path / "o.nc"
    r = run_program(scene, "-o", out)
    assert r.returncode == 0 and "is not used" not in r.stderr, r.stderr
    ds = pavefric.load_scene(scene).simulate()
    with xr.open_dataset(out) as f:
        assert f.attrs.get("warnings", "") == ds.attrs.get("warnings", "")


def test_python_writers_share_the_programs_temporaries(tmp_path, profile_m):
    """Issue 19: one implementation of 'a temporary beside the output, then a
    rename' for every writer. A Python writer killed outright (SIGKILL) leaves
    path.tmpPID.pavefric, as the program would; the next writer of that path, from any
    interface, removes it; a live process's temporary stays."""
    out = tmp_path / "p.nc"
    code = ("import os, signal, numpy as np, pavefric\n"
            "from pavefric.core import atomic_output\n"
            f"with atomic_output({str(out)!r}) as tmp:\n"
            "    tmp.write_bytes(b'half a file')\n"
            "    os.kill(os.getpid(), signal.SIGKILL)\n")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, timeout=120)
    assert proc.returncode == -signal.SIGKILL
    left = list(tmp_path.glob("p.nc.tmp*"))
    assert len(left) == 1 and left[0].read_bytes() == b"half a file"
    alive = tmp_path / f"p.nc.tmp{os.getppid()}.pavefric"    # a live process, not this one
    alive.write_bytes(b"being written")
    pavefric.write_profiles(out, [profile_m, profile_m[:500]], names=["a", "b"], dx=DX)
    assert not left[0].exists() and alive.exists()
    assert [e.name for e in pavefric.list_profiles(out)] == ["a", "b"]
    # the merge and the example write through the same helper
    stale = tmp_path / "ex" / f"ctm_dry.nml.tmp{_dead_pid()}.pavefric"
    stale.parent.mkdir()
    stale.write_bytes(b"stale")
    from pavefric.example import write_example
    write_example(tmp_path / "ex")
    assert not stale.exists() and (tmp_path / "ex" / "ctm_dry.nml").is_file()
    assert not list((tmp_path / "ex").glob("*.tmp*"))
