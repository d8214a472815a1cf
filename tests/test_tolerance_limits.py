"""Tolerances double precision cannot meet are refused (issue 19): before,
`tolerance = 1e-400` was read as 0 (accuracy on demand silently off) and
`tolerance = 1e-15` ran on, halving the step to the largest substeps."""
import pytest

from conftest import run_program, write_scene


@pytest.mark.parametrize("value, message", [
    ("1e-400", "&numerics tolerance = 1e-400: too small for double precision (it would be "
               "read as 0;"),
    ("1d-320", "below what double precision can meet"),
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


def test_a_subnormal_value_is_its_value_not_an_error():
    """A subnormal keeps its value (to fewer digits), unlike 1e-400, which
    would be read as 0: the property tests' speeds of 2.2e-313 km/h (the
    static limit, in effect) run, as in 0.1.0."""
    import numpy as np
    import pavefric
    z = np.sin(np.arange(200) * 0.3) * 0.5e-3
    ds = pavefric.simulate(z, 1e-3, [2.2250738585e-313, 20.0], depth=1e-3)
    static = pavefric.simulate(z, 1e-3, [0.0, 20.0], depth=1e-3)
    assert np.all(np.isfinite(ds["mu"].values))
    assert ds["mu"].values[0] == pytest.approx(static["mu"].values[0], rel=1e-9)
    assert ds["speed_kmh"].values[0] == 2.2250738585e-313
