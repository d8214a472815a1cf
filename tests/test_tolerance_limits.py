"""Tolerances double precision cannot meet are refused (issue 19): before,
`tolerance = 1e-400` was read as 0 (accuracy on demand silently off) and
`tolerance = 1e-15` ran on, halving the step to the largest substeps."""
import pytest

from conftest import run_program, write_scene


@pytest.mark.parametrize("value, message", [
    ("1e-400", "&numerics tolerance = 1e-400: too small for double precision (it would be "
               "read as 0;"),
    ("1d-320", "&numerics tolerance = 1d-320: too small for double precision (it would be "
               "read as 1e-320;"),
    ("1e-15", "&numerics tolerance = 1e-15: below what double precision can meet"),
])
def test_tolerance_below_double_precision_is_an_error(tmp_path, value, message):
    scene = write_scene(tmp_path, groups={"numerics": f"tolerance = {value}"})
    out = tmp_path / "o.nc"
    r = run_program(scene, "-o", out)
    assert r.returncode == 1
    assert message in r.stderr
    assert ("write 0 or a larger value" in r.stderr or
            "use 0 (off) or a tolerance >= 1e-14" in r.stderr)
    assert not out.exists()


def test_a_zero_written_small_and_an_underflowing_other_knob(tmp_path):
    scene = write_scene(tmp_path, groups={"numerics": "tolerance = 0.0e-400"})
    assert run_program(scene, "-o", tmp_path / "o.nc").returncode == 0
    scene = write_scene(tmp_path, groups={"surface": "profile_file = 'scene_profile.txt', "
                                                     "mu_loc = 1e-999"})
    r = run_program(scene, "-o", tmp_path / "p.nc")
    assert r.returncode == 1 and "&surface mu_loc = 1e-999: too small for double" in r.stderr
