"""A batch whose scene text is large (issue 19): a 200 KB scene (long
comments) was stored as an HDF5 attribute, so the run failed at its end and
lost all its work. Texts too long for an attribute are now written as a
variable (the attribute says where; pavefric.open_dataset restores it), and
such a batch, killed at random points five times and resumed each time, ends
with the same output as an uninterrupted run."""
import os
import random
import signal
import subprocess
import time

import pavefric
from conftest import program, run_program
from test_batch import same_contents

COMMENT = "! a long comment, as a survey scene may carry, line after line\n" * 3400


def big_batch(tmp_path, n=2000):
    from pavefric.surfaces import road_profiles

    road_profiles(str(tmp_path / "profiles"), n=n, points=400)
    scene = tmp_path / "survey.nml"
    scene.write_text(COMMENT + "&batch profiles = 'profiles/*.txt', depths = 0.0, 1.0e-3 /\n"
                     "&surface closed = .false., mu_loc = 0.6 /\n"
                     "&operation speeds_kmh = 20, 60 /\n")
    assert scene.stat().st_size > 200_000
    return scene


def journal_lines(journal):
    try:
        return journal.read_bytes().count(b"\nP ")
    except FileNotFoundError:
        return 0


def test_a_200_kb_scene_survives_five_kills_and_resumes_to_the_same_output(tmp_path):
    scene = big_batch(tmp_path)
    env = {**os.environ, "OMP_NUM_THREADS": "1"}
    clean = tmp_path / "clean.nc"
    r = subprocess.run([program(), str(scene), "-o", str(clean)], capture_output=True,
                       text=True, env=env, timeout=600)
    assert r.returncode == 0, r.stderr[-500:]
    ds = pavefric.open_dataset(clean)
    assert ds.attrs["input_namelist"] == scene.read_text()      # the whole scene, restored
    assert "input_namelist" not in ds.variables

    out = tmp_path / "killed.nc"
    journal = tmp_path / "killed.nc.journal"
    rng = random.Random(19)
    kills = 0
    done = 0
    while kills < 5:
        target = done + rng.randint(50, 300)
        proc = subprocess.Popen([program(), str(scene), "-o", str(out)],
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env)
        deadline = time.time() + 300
        while time.time() < deadline and proc.poll() is None and journal_lines(journal) < target:
            time.sleep(0.002)
        if proc.poll() is not None:            # finished before the kill: start again
            break
        proc.send_signal(signal.SIGKILL)
        proc.wait()
        kills += 1
        assert not out.exists(), "a killed run left an output"
        now = journal_lines(journal)
        assert now >= done, "the journal lost lines"
        done = now
    assert kills == 5 and 0 < done < 2000, (kills, done)
    r = run_program(scene, "-o", out)
    assert r.returncode == 0, r.stderr[-500:]
    assert "resuming: " in r.stderr
    assert not journal.exists()
    same_contents(clean, out)
