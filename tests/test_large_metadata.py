"""Metadata of any size (issue 19): a scene with 200 KB of comments is kept
whole in the output. HDF5 keeps attributes in a 64 KiB object header; a
longer scene text stored as an attribute failed the batch at its very end,
losing all its work, and every resume failed the same way."""
import subprocess
import sys

import pavefric
from conftest import ROOT, run_program
from test_batch import make_batch, same_contents

COMMENTS = "".join(f"! survey note {i:05d}: " + "x" * 80 + "\n" for i in range(2000))


def long_scene(path):
    """`path` (a scene) with 200 KB of comments before its groups."""
    path.write_text(COMMENTS + path.read_text())
    assert path.stat().st_size > 200_000
    return path.read_text()


def test_batch_with_a_200kb_scene_completes_and_resumes(tmp_path):
    scene = make_batch(tmp_path, n=8)
    text = long_scene(scene)
    whole = tmp_path / "whole.nc"
    r = run_program(scene, "-o", whole)
    assert r.returncode == 0, r.stderr
    ds = pavefric.open_dataset(whole)
    assert ds.attrs["input_namelist"] == text
    assert "input_namelist" not in ds.variables
    assert int((ds["status"] == 1).sum()) == 8
    # stopped after 3 profiles, then resumed from the journal
    out = tmp_path / "resumed.nc"
    r = run_program(scene, "-o", out, "--max-profiles", "3")
    assert r.returncode == 3, r.stderr
    r = run_program(scene, "-o", out)
    assert r.returncode == 0, r.stderr
    assert "resuming: 3 of 8" in r.stderr
    same_contents(whole, out)
    assert pavefric.open_dataset(out).attrs["input_namelist"] == text


def test_scene_with_a_200kb_text_writes_its_output(tmp_path):
    scene = tmp_path / "dry.nml"
    scene.write_text((ROOT / "inputs" / "ctm_dry.nml").read_text().replace(
        "'profiles/", f"'{ROOT / 'inputs' / 'profiles'}/"))
    text = long_scene(scene)
    out = tmp_path / "dry.nc"
    r = run_program(scene, "-o", out)
    assert r.returncode == 0, r.stderr
    ds = pavefric.open_dataset(out)
    assert ds.attrs["input_namelist"] == text
    assert ds["mu"].size > 0


def test_parts_with_200kb_scenes_merge(tmp_path):
    parts = []
    for k in range(2):
        d = tmp_path / f"p{k}"
        d.mkdir()
        scene = make_batch(d, n=3)
        # other profile names in each part
        for f in sorted((d / "profiles").iterdir()):
            f.rename(f.with_name(f"part{k}_" + f.name))
        long_scene(scene)
        out = tmp_path / f"part{k}.nc"
        r = run_program(scene, "-o", out, cwd=d)
        assert r.returncode == 0, r.stderr
        parts.append(out)
    merged = tmp_path / "merged.nc"
    r = subprocess.run([sys.executable, "-m", "pavefric", "merge", *map(str, parts), "-o",
                        str(merged)], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    ds = pavefric.open_dataset(merged)
    assert ds.sizes["profile"] == 6
    assert ds.attrs["input_namelist"] == pavefric.open_dataset(parts[0]).attrs["input_namelist"]
    assert ds.attrs["profiles_with_warnings"] == sum(
        int(pavefric.open_dataset(p).attrs["profiles_with_warnings"]) for p in parts)
