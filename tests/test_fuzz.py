"""Fuzzing the program with namelist text and profile text (issue 10): every
outcome is a finite result or a clean error (exit 1 and one stderr line), never
a crash, a hang, another exit status, a non-finite number written or a
temporary file left behind."""
import subprocess

import numpy as np
import pytest
import xarray as xr
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import pavefric
from conftest import program

GROUPS = [g.name for g in pavefric.groups()] + ["surfce", "end", "water"]
NAMES = {g: [p.name for p in pavefric.parameters() if p.group == g] for g in GROUPS}
VALUES = ["0", "1", "-1", "0.5", "1e-3", "1e308", "-1e308", "1e-320", "1.7e308", "2.9",
          "1-3", "2.203-1", "1+2", "nan", "NaN", "inf", "-Infinity", ".5", "5.", "1d-3",
          ".true.", ".false.", "t", "f", "'flat'", "'rounded'", "'squeeze'", "'kane2017'",
          "'mm'", "'um'", "'m'", "'p.txt'", "''", "'it''s'", "\"x\"", "3*20", "0*1", "2*",
          "20, 40", "20 40 60", "1e400", "'a" + "b" * 300 + "'", "\u00b5", "é", "&", "/", ","]
SEPARATORS = [" ", ", ", "\n", "\t", "\u00a0", "\f", " ! comment\n", ""]

profile_line = st.one_of(st.sampled_from(["0.1", "-0.2", "1e-3", "nan", "NaN", "inf", "1-3",
                                          "x", "", "# c", "0.1 0.2", "0.1,0.2", "1.#INF",
                                          "\x00", "\ufeff0.3", "1e300", "-1e300", "0.25 # c"]),
                         st.floats(-5, 5).map(lambda v: f"{v:.6f}"))


@st.composite
def assignments(draw, group):
    names = NAMES.get(group) or ["x"]
    parts = []
    for _ in range(draw(st.integers(0, 4))):
        name = draw(st.sampled_from(names + ["lenght", "speeds_kmh(2)", "depth(0)"]))
        value = draw(st.sampled_from(VALUES))
        parts.append(f"{name} = {value}")
    return draw(st.sampled_from(SEPARATORS)).join(parts)


@st.composite
def scenes(draw):
    groups = {"surface": "profile_file = 'p.txt', closed = .false.", "operation":
              "speeds_kmh = 20, 60", "pad": "", "water": ""}
    for group in draw(st.lists(st.sampled_from(GROUPS), max_size=4)):
        groups[group] = draw(assignments(group))
    blanks = [sep for sep in SEPARATORS if sep]
    text = "".join(f"&{g}{draw(st.sampled_from(blanks))}{body}"
                   f"{draw(st.sampled_from(SEPARATORS))}/\n" for g, body in groups.items())
    prefix = draw(st.sampled_from(["", "\ufeff", "junk\n", "! c\n", "\u00a0"]))
    cut = draw(st.integers(0, 3))
    if cut == 0 and text:                       # sometimes a truncated file
        text = text[:draw(st.integers(0, len(text)))]
    return prefix + text


def check_outcome(tmp_path, scene_text, profile_text):
    (tmp_path / "s.nml").write_text(scene_text, encoding="utf-8")
    (tmp_path / "p.txt").write_text(profile_text, encoding="utf-8")
    out = tmp_path / "o.nc"
    out.unlink(missing_ok=True)
    try:
        r = subprocess.run([program(), "s.nml", "-o", "o.nc"], capture_output=True, text=True,
                           cwd=tmp_path, timeout=60, errors="replace")
    except subprocess.TimeoutExpired:                            # a hang
        pytest.fail(f"hang on scene {scene_text!r} profile {profile_text[:200]!r}")
    assert r.returncode in (0, 1), (r.returncode, scene_text, r.stderr)
    assert not list(tmp_path.glob("o.nc.tmp*")), "temporary file left behind"
    if r.returncode == 1:
        lines = [line for line in r.stderr.splitlines() if line.strip()]
        errors = [line for line in lines if line.startswith("pavefric: error: ")]
        assert len(errors) == 1 and lines[-1] == errors[0], r.stderr
        assert not out.exists()
        return
    with xr.open_dataset(out) as ds:
        for name, var in ds.data_vars.items():
            if var.dtype.kind == "f":
                assert np.all(np.isfinite(var.values)), (name, scene_text)
        assert np.all(ds["mu"].values >= 0)


@settings(max_examples=120, deadline=None, suppress_health_check=list(HealthCheck))
@given(scene=scenes(), profile=st.lists(profile_line, min_size=0, max_size=80))
def test_fuzzed_scenes_end_in_a_result_or_a_clean_error(tmp_path_factory, scene, profile):
    tmp = tmp_path_factory.mktemp("fuzz")
    body = "\n".join(profile)
    if len(profile) > 30:                 # mostly numbers: enough points to reach the model
        body = "\n".join([f"{0.3 * np.sin(0.5 * k):.5f}" for k in range(60)] + profile)
    check_outcome(tmp, scene, body)


@settings(max_examples=60, deadline=None, suppress_health_check=list(HealthCheck))
@given(data=st.binary(max_size=400))
def test_random_bytes_as_a_scene_are_a_clean_error(tmp_path_factory, data):
    tmp = tmp_path_factory.mktemp("bytes")
    (tmp / "s.nml").write_bytes(data)
    (tmp / "p.txt").write_text("\n".join(f"{0.3 * np.sin(k):.4f}" for k in range(60)))
    r = subprocess.run([program(), "s.nml", "-o", "o.nc"], capture_output=True, cwd=tmp,
                       timeout=60)
    assert r.returncode == 1, (data, r.returncode)
    assert r.stderr.startswith(b"pavefric: error: ") and r.stderr.count(b"\n") == 1


@pytest.mark.parametrize("scene", [
    "&surface profile_file = 0*1\x0c",          # found by the fuzzer above (a form feed)
    "&surface profile_file = 'p.txt', mu_loc = 0.\x076 /",     # a bell inside a number
    "&surface mu_loc = 1\x1b[31m /",
])
def test_control_characters_quoted_in_an_error_stay_on_one_line(tmp_path, scene):
    """A message quoting the input writes its control characters as \\xHH:
    a form feed, a vertical tab or an escape sequence would otherwise break
    the one-line message (Python's splitlines) or the user's terminal."""
    check_outcome(tmp_path, scene, "")
    r = subprocess.run([program(), "s.nml", "-o", "o.nc"], capture_output=True, text=True,
                       cwd=tmp_path, timeout=60)
    assert r.returncode == 1 and not any(ord(c) < 32 and c != "\n" for c in r.stderr), r.stderr
    assert "\\x" in r.stderr, r.stderr
