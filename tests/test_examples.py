"""Every script of examples/ runs, as a user runs it, in an empty directory
with the installed pavefric (its environment's bin/ on PATH), and gives
what it says it gives."""
from __future__ import annotations

import csv
import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np

import pavefric
from conftest import ROOT, run_program

EXAMPLES = ROOT / "examples"
BIN = Path(sys.executable).parent
SCRIPTS = ["survey.py", "calibration.py", "api/build.sh"]


def run(args, cwd) -> subprocess.CompletedProcess:
    env = {**os.environ, "PATH": f"{BIN}{os.pathsep}{os.environ['PATH']}", "MPLBACKEND": "Agg"}
    r = subprocess.run([str(a) for a in args], cwd=cwd, capture_output=True, text=True,
                       env=env, timeout=900)
    assert r.returncode == 0, f"{args}\n{r.stdout[-3000:]}\n{r.stderr[-3000:]}"
    return r


def test_every_example_is_tested_and_described():
    found = sorted(str(p.relative_to(EXAMPLES)) for p in EXAMPLES.rglob("*")
                   if p.suffix in (".py", ".sh"))
    assert found == sorted(SCRIPTS)
    readme = (EXAMPLES / "README.md").read_text(encoding="utf-8")
    for name in SCRIPTS + ["api/example.c", "api/example.f90"]:
        assert f"`{name}`" in readme, name


def test_survey(tmp_path):
    r = run([sys.executable, EXAMPLES / "survey.py", "my-survey"], tmp_path)
    out = tmp_path / "my-survey"
    assert "12 profiles: 12 done in this run (failed included)" in r.stdout
    with pavefric.open_dataset(out / "survey.nc") as ds:
        assert dict(ds["mu"].sizes) == {"profile": 12, "water_depth": 2, "speed_kmh": 3}
        mu = ds["mu"].values
        wet60 = ds["mu"].sel(water_depth=1e-3, speed_kmh=60.0).values
    assert np.all(np.isfinite(mu)) and np.all(mu > 0)
    # the dry friction exceeds the wet one on every segment and speed
    assert np.all(mu[:, 0, :] > mu[:, 1, :])
    worst = re.search(r"least wet friction at 60 km/h: \S+ \(mu = ([\d.]+); road mean ([\d.]+)\)",
                      r.stdout)
    assert worst and float(worst[1]) == round(float(wet60.min()), 3)
    assert float(worst[2]) == round(float(wet60.mean()), 3)
    with open(out / "survey_mu.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    assert len(rows) == 72 and set(rows[0]) == {"profile", "water_depth", "speed_kmh", "mu"}
    assert sorted(float(r["mu"]) for r in rows) == sorted(mu.ravel().tolist())


def test_calibration(tmp_path):
    r = run([sys.executable, EXAMPLES / "calibration.py"], tmp_path)
    out = tmp_path / "calibration-example"
    m = re.search(r"alpha = ([\d.]+) \(95 % interval ([\d.]+) to ([\d.]+)\); made with 8$",
                  r.stdout, re.M)
    assert m, r.stdout
    alpha, low, high = map(float, m.groups())
    assert low < 8 < high and low < alpha < high and high / low < 1.5
    with open(out / "measured.csv", newline="") as fh:
        assert len(list(csv.DictReader(fh))) == 6


def test_c_and_fortran_examples_build_and_give_the_programs_numbers(tmp_path):
    r = run(["bash", EXAMPLES / "api" / "build.sh"], tmp_path)
    assert (tmp_path / "example_c").is_file() and (tmp_path / "example_f").is_file()
    scene = tmp_path / "api-scenes" / "ctm_wet.nml"
    ran = run_program(scene, "-o", tmp_path / "program.nc")
    assert ran.returncode == 0, ran.stderr
    with pavefric.open_dataset(tmp_path / "program.nc") as ds:
        want = ds["mu"].values
    c_part, f_part = r.stdout.split("\nC:\n")[1].split("\nFortran:\n")
    for part in (c_part, f_part):
        got = [float(v) for v in re.findall(r"km/h: mu =\s*(\S+)", part)]
        assert np.array(got).tobytes() == want.tobytes(), (got, want)
