"""`python -m pavefric example DIR` writes the default scenes from the
installed package, anywhere, and the program runs them there; the
maintainers' commands refuse cleanly outside a checkout."""
import subprocess
import sys

import numpy as np
import pytest

import pavefric
from conftest import ROOT, program, run_program


def cli(*args, cwd):
    return subprocess.run([sys.executable, "-m", "pavefric", *map(str, args)], cwd=cwd,
                          capture_output=True, text=True, timeout=600)


def test_example_runs_from_any_directory(tmp_path):
    r = cli("example", "my-run", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    run_dir = tmp_path / "my-run"
    for name in ("ctm_dry.nml", "ctm_wet.nml", "ctm_squeeze.nml", "ctm_reynolds.nml",
                 "profiles/ctm_medium.txt"):
        assert (run_dir / name).is_file(), name
        assert f"wrote my-run/{name}" in r.stdout
    # the commands to run next, with this environment's program
    assert "cd my-run" in r.stdout
    assert f"{program()} ctm_dry.nml" in r.stdout or "\n  pavefric ctm_dry.nml" in r.stdout

    ran = run_program("ctm_dry.nml", cwd=run_dir)
    assert ran.returncode == 0, ran.stderr
    out = run_dir / "outputs" / "ctm_dry.nc"
    with pavefric.open_dataset(out) as ds:
        mu = ds["mu"].values
        assert mu.size == 10 and np.all(np.isfinite(mu)) and np.all(mu > 0)
    # the same numbers as the checkout's own default scene
    reference = run_program(ROOT / "inputs" / "ctm_dry.nml", "-o", tmp_path / "ref.nc")
    assert reference.returncode == 0, reference.stderr
    with pavefric.open_dataset(tmp_path / "ref.nc") as ref:
        assert np.array_equal(mu, ref["mu"].values)


def test_example_files_are_the_checkouts(tmp_path):
    """What the wheel ships is inputs/ as committed; only the header's Run:
    line names the scene where it now lies."""
    assert cli("example", tmp_path / "ex", cwd=tmp_path).returncode == 0
    for name in ("ctm_dry.nml", "ctm_wet.nml", "ctm_squeeze.nml", "ctm_reynolds.nml",
                 "profiles/ctm_medium.txt"):
        original = (ROOT / "inputs" / name).read_text(encoding="utf-8")
        if name.endswith(".nml"):
            assert f"Run:  pavefric inputs/{name}" in original
            original = original.replace(f"pavefric inputs/{name}", f"pavefric {name}")
        assert (tmp_path / "ex" / name).read_text(encoding="utf-8") == original, name


def test_example_default_directory_and_no_overwrite(tmp_path):
    r = cli("example", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    scene = tmp_path / "pavefric-example" / "ctm_wet.nml"
    assert scene.is_file()
    scene.write_text("! my edits\n")
    r = cli("example", cwd=tmp_path)
    assert r.returncode == 1 and "Traceback" not in r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and "already there" in lines[0] and "--force" in lines[0], r.stderr
    assert scene.read_text() == "! my edits\n"           # nothing written
    r = cli("example", "--force", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert scene.read_text() == (ROOT / "inputs" / "ctm_wet.nml").read_text().replace(
        "pavefric inputs/ctm_wet.nml", "pavefric ctm_wet.nml")


def test_example_refuses_a_directory_in_the_way(tmp_path):
    (tmp_path / "ex" / "ctm_dry.nml").mkdir(parents=True)
    r = cli("example", "ex", "--force", cwd=tmp_path)
    assert r.returncode == 1 and "Traceback" not in r.stderr, r.stderr
    assert "ctm_dry.nml" in r.stderr and len(r.stderr.strip().splitlines()) == 1
    assert not (tmp_path / "ex" / "ctm_wet.nml").exists()    # nothing written


def test_example_force_never_writes_through_a_linked_directory(tmp_path):
    """attack19 F12: with DIR/profiles a symbolic link to another directory,
    `example DIR --force` replaced the file of that name there."""
    (tmp_path / "mydata").mkdir()
    (tmp_path / "mydata" / "ctm_medium.txt").write_text("measured\n")
    (tmp_path / "e").mkdir()
    (tmp_path / "e" / "profiles").symlink_to("../mydata")
    r = cli("example", "e", "--force", cwd=tmp_path)
    assert r.returncode == 1 and "Traceback" not in r.stderr, r.stderr
    assert "'e/profiles': is a symbolic link" in r.stderr, r.stderr
    assert (tmp_path / "mydata" / "ctm_medium.txt").read_text() == "measured\n"
    assert sorted(p.name for p in (tmp_path / "e").iterdir()) == ["profiles"]


@pytest.mark.parametrize("command", ["bench", "validate", "docs", "speed-gradient",
                                     "rubber-report", "surfaces"])
def test_maintainer_commands_need_a_checkout(tmp_path, command):
    """Outside a checkout (no meson.build, src/ and inputs/): one line,
    exit status 2, nothing written."""
    r = cli(command, cwd=tmp_path)
    assert r.returncode == 2, r.stdout + r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in r.stderr, r.stderr
    assert f"'python -m pavefric {command}'" in lines[0] and "needs a pavefric checkout" \
        in lines[0]
    assert list(tmp_path.iterdir()) == []


def test_docs_told_where_to_write_runs_anywhere(tmp_path):
    r = cli("docs", "--inputs", "in.md", "--outputs", "out.md", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert (tmp_path / "in.md").read_text(encoding="utf-8") == \
        (ROOT / "docs" / "inputs.md").read_text(encoding="utf-8")


def test_the_checkout_is_recognised():
    from pavefric.__main__ import in_checkout

    assert in_checkout(ROOT)
    assert not in_checkout(ROOT / "docs")


def test_bench_refuses_a_missing_reference_in_one_line(tmp_path):
    """bench --reference names a file that is not there: one line naming it,
    exit status 1, before any measurement (nothing written)."""
    report = tmp_path / "performance.md"
    r = cli("bench", "--quick", "-q", "--reference", str(tmp_path / "nope.py"), "--report",
            str(report), cwd=ROOT)
    assert r.returncode == 1, r.stdout + r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in r.stderr
    assert "bench --reference" in lines[0] and "nope.py: no such file" in lines[0]
    assert not report.exists()


def test_default_scenes_run_each_wet_model_beside_dry(tmp_path):
    """Issue 21, must-show 3: the default scene comes dry and with each of the
    three wet models (what `bash setup.sh demo` runs and plots), each output
    says which ran, the plot labels each curve by it, and on the same
    surface at 1 mm of water every wet model loses friction against dry at
    80 km/h."""
    from pavefric.plot import plot_mu_speed, water_label

    expected = {"ctm_dry": "dry", "ctm_wet": "wet: paper's bearing",
                "ctm_squeeze": "wet: drainage model", "ctm_reynolds": "wet: Reynolds film"}
    mu80 = {}
    outs = []
    for scene, label in expected.items():
        out = tmp_path / f"{scene}.nc"
        r = run_program(ROOT / "inputs" / f"{scene}.nml", "-q", "-o", out)
        assert r.returncode == 0, r.stderr
        with pavefric.open_dataset(out) as ds:
            assert water_label(ds) == label
            speeds = list(ds["speed_kmh"].values)
            mu80[scene] = float(ds["mu"].values[speeds.index(80.0)])
        outs.append(out)
    for scene in ("ctm_wet", "ctm_squeeze", "ctm_reynolds"):
        assert mu80[scene] < mu80["ctm_dry"], (scene, mu80)
    png = plot_mu_speed(outs, tmp_path / "mu.png")
    assert (tmp_path / "mu.png").stat().st_size > 10_000 and png.endswith("mu.png")
