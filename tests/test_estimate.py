"""The cost of a run, estimated before it starts (issues 19 and 23): element-
steps exactly, memory checked before allocating, seconds at calibrated rates
(compared with measured times in the benchmark, not here: timings are for
the benchmark). Recorded in every output; printed by the program before a
run estimated at a second or more, and by Python (PavefricCostWarning) before
one estimated at ANNOUNCE_SECONDS or more."""
import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import pavefric
from conftest import DX, program, write_scene

VISCOUS = dict(viscosity=3e3)


@pytest.mark.parametrize("knobs", [
    {}, {"substeps": 4}, {"elements_per_sample": 3}, {"position_stride": 5},
    {"closed": False}, {"closed": False, "substeps": 3, "elements_per_sample": 2},
    {"depth": 1e-3}, {"depth": 1e-3, "wet_model": "squeeze"},
    {"rubber_model": "maxwell", "prony_stiffness": [1e8, 5e7], "prony_times": [1e-4, 1e-2]},
])
def test_estimated_element_steps_are_the_steps_the_run_made(profile_m, knobs):
    """memory_updates counts every element update of a rubber with memory:
    the estimate, made from the scene alone, is that count exactly."""
    kw = dict(knobs)
    closed = kw.pop("closed", True)
    if "rubber_model" not in kw:
        kw |= VISCOUS
    ds = pavefric.simulate(profile_m, DX, [5.0, 20.0, 60.0], closed=closed, **kw)
    assert ds.attrs["estimated_element_steps"] == float(ds["memory_updates"].values.sum())
    # each speed spins up at least a pad length, the longest spinup_positions
    pad_spin = ds.attrs["pad_elements"] * kw.get("substeps", 1) if closed else 0
    pad_spin = -(-pad_spin // kw.get("position_stride", 1))
    per_speed = ds.attrs["pad_elements"] * (ds.attrs["averaged_positions"] + pad_spin)
    assert 3 * per_speed <= ds.attrs["estimated_element_steps"] <= 3 * ds.attrs[
        "pad_elements"] * (ds.attrs["averaged_positions"] + ds.attrs["spinup_positions"])
    assert 0 < ds.attrs["estimated_memory_bytes"] < 1e9
    assert ds.attrs["estimated_seconds"] > 0


def test_the_estimate_grows_as_the_knobs_say(profile_m):
    """Linear in substeps, quadratic in elements_per_sample (more elements,
    each over a finer profile), wet dearer than dry: what a user must see
    before choosing a knob. (Wet against dry here, 2026-11-29: estimated
    1.96x, measured 1.89-1.91x, best of 7; 2x and more before the paper's
    balance took its pieces' roots without a checking pass.)"""
    def est(**kw):
        a = pavefric.simulate(profile_m, DX, [20.0], **kw).attrs
        return a["estimated_element_steps"], a["estimated_seconds"]

    base, _ = est()
    sub, dry = est(substeps=8)
    eps, _ = est(elements_per_sample=4)
    _, wet = est(substeps=8, depth=1e-3)
    assert sub / base == pytest.approx(8, rel=0.02)
    assert eps / base == pytest.approx(16, rel=0.02)
    assert wet > 1.5 * dry


def test_the_program_announces_a_long_run_and_records_every_estimate(tmp_path, profile_m):
    long_scene = write_scene(tmp_path / "long", profile=profile_m,
                             groups={"water": "depth = 1e-3", "numerics": "substeps = 1024",
                                     "operation": "speeds_kmh = 20, 40, 60"})
    out = tmp_path / "long.nc"
    r = subprocess.run([program(), str(long_scene), "-o", str(out)], capture_output=True,
                       text=True, env={**os.environ, "OMP_NUM_THREADS": "1"}, timeout=600)
    assert r.returncode == 0, r.stderr
    with xr.open_dataset(out) as ds:
        steps = int(ds.attrs["estimated_element_steps"])
        assert ds.attrs["estimated_seconds"] >= 1.0
    line = [x for x in r.stderr.splitlines() if x.startswith("pavefric: estimate: ")]
    assert len(line) == 1 and f"{steps} element-steps" in line[0] and "MiB" in line[0], r.stderr
    short_scene = write_scene(tmp_path / "short", profile=profile_m)
    r = subprocess.run([program(), str(short_scene), "-o", str(tmp_path / "s.nc")],
                       capture_output=True, text=True, timeout=600)
    assert r.returncode == 0 and "estimate" not in r.stderr        # short runs stay quiet
    with xr.open_dataset(tmp_path / "s.nc") as ds:
        assert ds.attrs["estimated_element_steps"] > 0


def test_each_wet_model_is_costed_as_itself(profile_m):
    """The Reynolds film was costed as the paper's bearing (found 2026-11-27:
    estimated 0.04 s, measured 1.06 s, 25 times too cheap); each wet model
    now has its own rate, and the Reynolds film's per element-step is many
    times the bearing's (docs/performance.md measures it: at most 22 times
    after its balance got faster on 2026-11-28, 25.5 after the bearing's
    did; here its estimate is 9.3 times the bearing's)."""
    est = {}
    for model in ("kane2017", "squeeze", "reynolds"):
        ds = pavefric.simulate(profile_m, DX, [20.0, 60.0], depth=1e-3, wet_model=model,
                               **VISCOUS)
        est[model] = ds.attrs["estimated_seconds"]
    dry = pavefric.simulate(profile_m, DX, [20.0, 60.0], **VISCOUS).attrs["estimated_seconds"]
    assert est["reynolds"] > 5 * est["kane2017"] > 5 * dry
    assert est["squeeze"] > dry


def _cost_warnings(record):
    return [str(w.message) for w in record if issubclass(w.category, pavefric.PavefricCostWarning)]


def test_the_estimate_foresees_the_pad_refined_under_a_film(monkeypatch):
    """The bench of 2026-11-28 measured runs 6-7 times their estimate where a
    water film lifted the pad onto a few asperities: the default then halves
    the elements there (min_contacts, the error estimate), each level about 4
    times the cost of the one before, which the estimate did not count. A
    probe (the run on every n-th position) now finds those speeds before the
    run; the estimate costs their levels and names them."""
    import warnings

    import pavefric.core
    from pavefric.surfaces import spectral_profile

    z = spectral_profile(4096, DX, rms=0.2e-3, skew=-0.3, seed=7)     # fine, 1 mm of water
    monkeypatch.setattr(pavefric.core, "ANNOUNCE_SECONDS", 0.0)      # every run says it

    def run(speeds, **kw):
        with warnings.catch_warnings(record=True) as record:
            warnings.simplefilter("always")
            ds = pavefric.simulate(z, DX, speeds, closed=False, **kw)
        said = [str(w.message) for w in record
                if issubclass(w.category, pavefric.PavefricCostWarning)]
        assert len(said) == 1, said
        return ds, said[0]

    slow, _ = run([20.0], depth=1e-3)
    fast, _ = run([80.0], depth=1e-3)
    both, line = run([20.0, 80.0], depth=1e-3)
    # 80 km/h: the pad refined (the run's own record), and costed as such
    assert list(both["elements_per_sample_used"].values) == [1, 2]
    assert "of it refining the pad at 80 km/h, where a probe found it on fewer than 4" in line
    assert fast.attrs["estimated_seconds"] > 2 * slow.attrs["estimated_seconds"]
    # the element-steps stay the reported pass's; a dry run refines nothing
    assert both.attrs["estimated_element_steps"] == (slow.attrs["estimated_element_steps"]
                                                     + fast.attrs["estimated_element_steps"])
    dry, line = run([20.0, 80.0])
    assert "refining" not in line and dry.attrs["estimated_seconds"] < slow.attrs[
        "estimated_seconds"]
    # many speeds refined: the list is shortened (the line must fit the
    # interface's 1024 characters; the review of 2026-12-07)
    from pavefric import _core
    from pavefric.core import _format, _spec, _typed

    speeds = [80.0 + 5.0 * k for k in range(13)]
    settings = {("surface", "dx"): _format(_spec("surface", "dx"), DX, "dx"),
                ("surface", "closed"): _format(_spec("surface", "closed"), False, "closed"),
                ("operation", "speeds_kmh"): _format(_spec("operation", "speeds_kmh"), speeds,
                                                     "speeds_kmh"),
                ("water", "depth"): _format(_spec("water", "depth"), 1e-3, "depth")}
    _, text, status, message = _core.pf_estimate(z, *_typed(settings))
    assert status == 0, message
    assert ("refining the pad at 80, 85, 90, 95, 100, 105, ... and 140 (13 speeds) km/h, "
            "where a probe") in pavefric.core._text(text)
    # without the passes that refine, no probe and no refinement costed
    plain, line = run([20.0, 80.0], depth=1e-3, min_contacts=0, error_estimate=False)
    assert "refining" not in line
    assert plain.attrs["estimated_seconds"] < 0.5 * both.attrs["estimated_seconds"]


# an attack's 13-arm compound (the shipped tread compound's Prony series near
# 20 C), as it gave them
ATTACK_ARMS = dict(
    rubber_model="maxwell", stiffness=5.16678e8,
    prony_stiffness=[4.30519e10, 2.95458e10, 2.01065e10, 1.1136e10, 5.85204e9, 2.92091e9,
                     1.45041e9, 7.04164e8, 3.43986e8, 1.66489e8, 8.09505e7, 3.91319e7,
                     2.0888e7],
    prony_times=[2.48563e-9, 2.19937e-8, 1.94608e-7, 1.72196e-6, 1.52365e-5, 0.000134818,
                 0.00119291, 0.0105553, 0.0933972, 0.826411, 7.31237, 64.7024, 572.51])


def _estimate(z, speeds, **kw):
    """pf_estimate of simulate(z, DX, speeds, **kw): what simulate() weighs
    before a run (element-steps, bytes, seconds, seconds refining), and its
    words, without making the run."""
    from pavefric import _core
    from pavefric.core import _format, _parameters, _spec, _typed

    settings = {**_parameters(kw),
                ("surface", "dx"): _format(_spec("surface", "dx"), DX, "dx"),
                ("operation", "speeds_kmh"): _format(_spec("operation", "speeds_kmh"),
                                                     speeds, "speeds_kmh")}
    estimate, text, status, message = _core.pf_estimate(z, *_typed(settings))
    assert status == 0, message
    return estimate, pavefric.core._text(text)


def test_a_tolerance_on_a_short_stiff_profile_is_announced():
    """An attack's reproducer (2026-12-07): a 128-point profile of a 13-arm
    compound at 300 km/h with tolerance = 1e-9 ran 104 s without a
    PavefricCostWarning: the estimate (0.001 s a pass) did not probe so short
    a profile for the pad's refinement (min_contacts: elements 8 times finer
    here, each level about 4 times the one before, each running the
    tolerance's passes), and the probe was skipped with any tolerance. A
    short run is now probed where all its levels and passes could reach a
    second, and the tolerance's guess multiplies the levels' passes too (19 s
    guessed for that run, 96 s measured on this host: announced)."""
    z = np.random.default_rng(0).normal(0, 5e-4, 128)
    kw = dict(mu_loc=0.0, **ATTACK_ARMS)
    slow, text = _estimate(z, [300.0], tolerance=1e-9, **kw)
    assert slow[2] >= pavefric.ANNOUNCE_SECONDS, text
    assert "tolerance = 1e-9 may need substeps 4096" in text
    assert slow[3] > 0.0                          # the probe found levels to refine
    # the same without refining the pad: its passes alone, about half a second
    plain, _ = _estimate(z, [300.0], tolerance=1e-9, min_contacts=0, **kw)
    assert plain[3] == 0.0 and plain[2] < 0.5 * slow[2]
    # at tolerance = 0 so short a run is not worth a probe (every level and
    # the estimate's pass stay under a second): nothing refined is costed
    quick, _ = _estimate(z, [300.0], **kw)
    assert quick[3] == 0.0 and quick[2] < 0.01


def test_the_probe_runs_once_a_run(tmp_path):
    """The probe behind the refinement's cost ran twice a run (for the
    estimate printed before it, then again for the one recorded): up to a
    third of a run of 2048 positions. The run now records the up-front
    estimate's refinement seconds as given (the program, simulate() and
    run() hand them on), and probes itself only when given none (< 0): a
    forecast handed on is what the output records, and without one the run
    records what the up-front estimate said."""
    from pavefric import _core
    from pavefric.core import _format, _spec, _tables, _typed
    from pavefric.surfaces import spectral_profile

    z = spectral_profile(4096, DX, rms=0.2e-3, skew=-0.3, seed=7)
    settings = {("surface", "dx"): _format(_spec("surface", "dx"), DX, "dx"),
                ("surface", "closed"): _format(_spec("surface", "closed"), False, "closed"),
                ("water", "depth"): _format(_spec("water", "depth"), 1e-3, "depth"),
                ("operation", "speeds_kmh"): _format(_spec("operation", "speeds_kmh"),
                                                     [20.0, 80.0], "speeds_kmh")}
    typed = _typed(settings)
    estimate, _, status, message = _core.pf_estimate(z, *typed)
    assert status == 0, message
    assert estimate[3] > 0.1 * estimate[2]        # 80 km/h refined: a probe found it

    def recorded(forecast):
        out = _core.pf_simulate(z, *typed, 2, 1, len(_tables()[2]), 1, 8192, forecast)
        assert out[-2] == 0, out[-1]
        return out[8][2]                          # estimated seconds, as recorded

    probed = recorded(-1.0)
    assert probed == pytest.approx(estimate[2], rel=1e-12)
    assert recorded(estimate[3]) == pytest.approx(estimate[2], rel=1e-12)
    # a forecast handed on is recorded as it is: the run did not probe again
    assert recorded(100.0) == pytest.approx(estimate[2] - estimate[3] + 100.0, rel=1e-12)
    # run(): the output records what the up-front estimate said
    scene = write_scene(tmp_path / "s", profile=z,
                        groups={"water": "depth = 1e-3", "operation": "speeds_kmh = 20, 80",
                                "surface": "profile_file = 'scene_profile.txt', closed = .false."})
    before, _, status, message = _core.pf_scene_estimate(str(scene).encode())
    assert status == 0, message
    assert before[3] > 0.1 * before[2]
    with xr.open_dataset(pavefric.run(scene, output=tmp_path / "s.nc")) as ds:
        assert ds.attrs["estimated_seconds"] == pytest.approx(before[2], rel=1e-12)


def test_python_warns_before_a_long_run(monkeypatch, profile_m, tmp_path):
    """The attack of 2026-11-27: Python ran for as long as a run takes without
    a word (the program announces from 1 s). simulate() and run() now warn,
    before the run, when the estimate reaches ANNOUNCE_SECONDS, with the
    numbers the output records; a shorter run stays quiet."""
    import warnings

    import pavefric.core

    assert pavefric.ANNOUNCE_SECONDS == pavefric.core.ANNOUNCE_SECONDS == 10.0
    kw = dict(depth=1e-3, substeps=8)
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        ds = pavefric.simulate(profile_m, DX, [20.0, 60.0], **kw)
    assert ds.attrs["estimated_seconds"] < pavefric.ANNOUNCE_SECONDS
    assert _cost_warnings(record) == []                    # short: quiet
    monkeypatch.setattr(pavefric.core, "ANNOUNCE_SECONDS", 0.5 * ds.attrs["estimated_seconds"])
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        ds2 = pavefric.simulate(profile_m, DX, [20.0, 60.0], **kw)
    said = _cost_warnings(record)
    steps = int(ds2.attrs["estimated_element_steps"])
    assert len(said) == 1 and f"estimate: {steps} element-steps" in said[0], said
    assert "MiB" in said[0] and "s on one thread" in said[0]
    # warned first: before the run's own warnings (none here but the cost's)
    assert issubclass(record[0].category, pavefric.PavefricCostWarning)
    assert not issubclass(pavefric.PavefricCostWarning, pavefric.PavefricWarning)
    # a scene file, as run() does it: the same estimate as its output records
    scene = write_scene(tmp_path / "s", profile=profile_m,
                        groups={"water": "depth = 1e-3", "numerics": "substeps = 8"})
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        out = pavefric.run(scene, output=tmp_path / "s.nc")
    with xr.open_dataset(out) as ds3:
        steps = int(ds3.attrs["estimated_element_steps"])
    said = _cost_warnings(record)
    assert len(said) == 1 and f"estimate: {steps} element-steps" in said[0], said
    # a scene that cannot be read: the run's own error, not the estimate's
    bad = write_scene(tmp_path / "b", groups={"numerics": "substeps = 0"})
    with pytest.raises(pavefric.PavefricError, match="substeps"):
        pavefric.run(bad, output=tmp_path / "b.nc")
    assert not (tmp_path / "b.nc").exists()


def test_a_run_that_cannot_fit_is_refused_before_allocating(profile_m):
    """Series of 4096 elements per sample at 60 speeds: terabytes. Refused
    with the estimate and the knobs to change; the Python process lives on."""
    with pytest.raises(pavefric.PavefricMemoryError,
                       match=r"needs about \d+ MiB.*elements_per_sample"):
        pavefric.simulate(profile_m, DX, list(np.linspace(1, 120, 60)), series=True,
                          elements_per_sample=4096)


def test_memory_errors_are_pavefric_errors(profile_m):
    """An element_length of 1e-300 (in range) asks for more points than can
    be held: a PavefricError (attack20: a bare MemoryError escaped `except
    pavefric.PavefricError`), still a MemoryError."""
    with pytest.raises(pavefric.PavefricMemoryError, match=r"&pad element_length = 1e-300"):
        pavefric.simulate(profile_m, DX, [20.0], element_length=1e-300)
    assert issubclass(pavefric.PavefricMemoryError, pavefric.PavefricError)
    assert issubclass(pavefric.PavefricMemoryError, MemoryError)


def test_a_pad_of_millions_of_elements_is_announced_at_once(tmp_path):
    """&pad element_length = 1e-9 m on a short profile: a pad of 20,000,000
    elements. The probe that foresees min_contacts' refinement ran on it
    before the estimate was printed or the memory checked (attack20: no
    output in 120 s and 6.9 GB resident; 79 s of silence at 1e-8). The
    probe's cost is now bounded: the estimate (or, where the machine is
    smaller, the refusal for memory) is the first thing said, at once. (The
    60 s below only tells a hang from an answer.)"""
    import select

    scene = write_scene(tmp_path, profile=np.sin(np.arange(128) * 0.3) * 0.5e-3,
                        groups={"pad": "element_length = 1e-9",
                                "operation": "speeds_kmh = 20"})
    proc = subprocess.Popen([str(program()), str(scene), "-o", str(tmp_path / "o.nc")],
                            stderr=subprocess.PIPE, text=True, cwd=tmp_path)
    try:
        ready, _, _ = select.select([proc.stderr], [], [], 60.0)
        assert ready, "nothing said in 60 s"
        line = proc.stderr.readline()
        assert ("estimate:" in line and "element-steps" in line) or \
            ("needs about" in line and "element_length" in line), line
    finally:
        proc.kill()
        proc.wait(timeout=60)
    assert not (tmp_path / "o.nc").exists()
    # the library: the cost warning (or the refusal) before the run, as soon
    code = ("import warnings, numpy as np, pavefric\n"
            "warnings.simplefilter('error', pavefric.PavefricCostWarning)\n"
            "try:\n"
            "    pavefric.simulate(np.sin(np.arange(128) * 0.3) * 0.5e-3, 0.87e-3, [20.0],\n"
            "                      element_length=1e-9)\n"
            "except (pavefric.PavefricCostWarning, pavefric.PavefricMemoryError) as w:\n"
            "    print('announced:', w)\n")
    proc = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True)
    try:
        ready, _, _ = select.select([proc.stdout], [], [], 60.0)
        assert ready, "nothing said in 60 s"
        assert proc.stdout.readline().startswith("announced:")
    finally:
        proc.kill()
        proc.wait(timeout=60)


def test_the_run_command_warns_of_the_cost_before_the_run(tmp_path):
    """`python -m pavefric run` recorded every warning and replayed them when
    the run had finished, so its cost warning ('... s on one thread', said so
    that an expensive run can be stopped) came after the run (attack20). It
    comes while the run is still going."""
    import select

    scene = write_scene(tmp_path, groups={
        "numerics": "elements_per_sample = 4096, min_contacts = 0, error_estimate = .false."})
    proc = subprocess.Popen([sys.executable, "-m", "pavefric", "run", str(scene), "-o",
                             str(tmp_path / "o.nc"), "-q"], stderr=subprocess.PIPE, text=True,
                            cwd=tmp_path)
    try:
        said = ""
        while "on one thread" not in said:
            ready, _, _ = select.select([proc.stderr], [], [], 120.0)
            assert ready, said
            line = proc.stderr.readline()
            assert line, said                       # the run ended without the warning
            said += line
        assert proc.poll() is None, said              # the run is still going
        # one line, as the program says it (not the source line that warned)
        assert said.startswith("pavefric: warning: "), said
        assert "warnings.warn" not in said and ".py:" not in said, said
    finally:
        proc.kill()
        proc.wait(timeout=60)
    assert not (tmp_path / "o.nc").exists()


def _limited(megabytes):
    import resource

    def apply():
        resource.setrlimit(resource.RLIMIT_AS, (megabytes << 20, megabytes << 20))
    return apply


def test_a_memory_limit_is_honoured_with_a_clear_refusal(tmp_path, profile_m):
    """substeps = 2048 with series under a 400 MB address-space limit (ulimit
    -v, as a job may have): the program ended in a segmentation fault inside
    HDF5; it now refuses before the run, one line naming the estimate, the
    limit and the knobs, and writes nothing. With room, the same scene runs."""
    scene = write_scene(tmp_path, profile=profile_m,
                        groups={"water": "depth = 1e-3", "numerics": "substeps = 2048",
                                "operation": "speeds_kmh = 20, 40, 60",
                                "output": "series = .true."})
    out = tmp_path / "o.nc"
    r = subprocess.run([program(), str(scene), "-o", str(out)], capture_output=True, text=True,
                       preexec_fn=_limited(400), timeout=600)
    assert r.returncode == 1, (r.returncode, r.stderr[-500:])
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and "needs about" in lines[0] and "may use" in lines[0], r.stderr
    assert "substeps" in lines[0] and not out.exists()
    # the library alike: a MemoryError, and the Python process lives on
    code = ("import sys; sys.path.insert(0, %r)\n"
            "import pavefric\n"
            "from make_regression import read_heights\n"
            "z = read_heights('synthetic_1024.txt')\n"
            "try:\n"
            "    pavefric.simulate(z, 0.87e-3, [20, 40, 60], depth=1e-3, substeps=2048, "
            "series=True)\n"
            "except MemoryError as e:\n"
            "    print('MemoryError:', e)\n" % str(Path(__file__).parent))
    env = {**os.environ, "OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1"}
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env,
                       preexec_fn=_limited(1000), timeout=600)
    assert r.returncode == 0 and "MemoryError: the run needs about" in r.stdout, \
        (r.returncode, r.stdout[-300:], r.stderr[-500:])


def test_a_tolerance_run_is_announced_by_its_refinements_guess():
    """From an attack (2026-12-06): a CAPTIF profile at tolerance = 1e-12 ran
    114 s with no warning: the estimate (0.029 s) was its first pass, and the
    refinement doubles the step up to substeps 4096. The estimate now adds a
    guess of the substeps the tolerance needs (tolerance_guess: the
    Richardson value's error about 0.25 / s**2, backward Euler's 0.03 / s,
    the exact integrator's met in two halvings; at least two halvings, at
    most 4096) and of all the passes to there, each twice the one before;
    the announcement (the program's from 1 s, Python's from
    ANNOUNCE_SECONDS) weighs that guess where it is more. What the output
    records as estimated_seconds stays the first pass's."""
    from pavefric import _core
    from pavefric.core import _format, _spec, _typed
    from pavefric.surfaces import spectral_profile

    z = spectral_profile(2048, DX, rms=0.5e-3, seed=7)

    def estimate(**numerics):
        settings = {("surface", "dx"): _format(_spec("surface", "dx"), DX, "dx"),
                    ("operation", "speeds_kmh"): _format(_spec("operation", "speeds_kmh"),
                                                         [20.0, 80.0], "speeds_kmh")}
        for name, value in numerics.items():
            settings["numerics", name] = _format(_spec("numerics", name), value, name)
        out, text, status, message = _core.pf_estimate(z, *_typed(settings))
        assert status == 0, message
        return float(out[2]), pavefric.core._text(text)

    tight, said = estimate(tolerance=1e-12)
    assert "tolerance = 1e-12 may need substeps 4096" in said, said
    loose, said = estimate(tolerance=1e-3)
    assert "may need substeps 16," in said, said        # sqrt(0.25 / 1e-3) = 15.8
    # the same first pass, guessed to 4096 (8191 passes' worth) and to 16 (31)
    assert tight / loose == pytest.approx(8191 / 31, rel=1e-12)
    euler, said = estimate(tolerance=1e-3, time_scheme="euler")
    assert "may need substeps 32," in said and euler / loose == pytest.approx(63 / 31, rel=1e-12)
    _, said = estimate(tolerance=1e-3, time_scheme="exact")     # (its own rate a pass)
    assert "may need substeps 4," in said
    _, said = estimate()
    assert "may need" not in said
    # the Reynolds film's mu need not converge in the step: the ladder's top
    # (attack21: announced substeps 16, ran to 4096 and 60 times as long)
    settings = {("surface", "dx"): _format(_spec("surface", "dx"), DX, "dx"),
                ("operation", "speeds_kmh"): _format(_spec("operation", "speeds_kmh"),
                                                     [20.0, 80.0], "speeds_kmh"),
                ("numerics", "tolerance"): _format(_spec("numerics", "tolerance"), 1e-3,
                                                   "tolerance"),
                ("water", "depth"): _format(_spec("water", "depth"), 1e-3, "depth"),
                ("water", "wet_model"): _format(_spec("water", "wet_model"), "reynolds",
                                                "wet_model")}
    out, text, status, message = _core.pf_estimate(z, *_typed(settings))
    assert status == 0, message
    assert "tolerance = 0.001 may need substeps 4096" in pavefric.core._text(text)
    # the refinement's own ladder from substeps = 3: 12, 24, ..., 3072 (6144
    # would pass 4096)
    _, said = estimate(tolerance=1e-12, substeps=3)
    assert "may need substeps 3072," in said, said
    # its memory: the last pass's, the first's times the substeps' ratio (the
    # refined profile and the series grow with them; attack21: 1 MiB
    # announced where the series of the passes took 2.3 GB)
    for series in (False, True):
        settings = {("surface", "dx"): _format(_spec("surface", "dx"), DX, "dx"),
                    ("operation", "speeds_kmh"): _format(_spec("operation", "speeds_kmh"),
                                                         [20.0, 80.0], "speeds_kmh"),
                    ("numerics", "tolerance"): _format(_spec("numerics", "tolerance"), 1e-12,
                                                       "tolerance"),
                    ("output", "series"): _format(_spec("output", "series"), series, "series")}
        out, text, status, message = _core.pf_estimate(z, *_typed(settings))
        assert status == 0, message
        said = pavefric.core._text(text)
        last = re.search(r"about (\d+) MiB at the last pass", said)
        assert last, said
        assert int(last.group(1)) == max(1, round(float(out[1]) * 4096 / 2**20)), said
