"""The International Friction Index (ASTM E1960) of a computed speed sweep
(issue 21): F60 from the friction at 20 km/h and Sp from the texture's MPD,
and the model's own speed constant, in every scene output and simulate()."""
import numpy as np
import pytest

import pavefric
from conftest import ROOT, run_program


@pytest.fixture(scope="module")
def medium():
    return pavefric.read_profile(ROOT / "inputs" / "profiles" / "ctm_medium.txt", "mm").heights


def test_f60_is_the_standards_formula_on_the_computed_friction(medium):
    ds = pavefric.simulate(medium, 0.87e-3, [20.0, 40.0, 60.0], mu_loc=0.6, depth=1e-3,
                           wet_model="squeeze")
    mu20, mpd = float(ds["mu"].sel(speed_kmh=20.0)), float(ds["mpd"])
    want = pavefric.ifi(mu20, mpd)
    assert float(ds["ifi_f60"]) == pytest.approx(want["F60"], rel=1e-12)
    assert float(ds["ifi_sp"]) == pytest.approx(want["Sp"], rel=1e-12)
    assert float(ds["ifi_sp"]) == pytest.approx(14.2 + 89.7 * mpd * 1e3, rel=1e-12)


def test_the_models_speed_constant_is_the_least_squares_slope(medium):
    speeds = [10.0, 20.0, 40.0, 60.0, 80.0]
    ds = pavefric.simulate(medium, 0.87e-3, speeds, mu_loc=0.6, depth=1e-3, wet_model="squeeze")
    slope = np.polyfit(speeds, np.log(ds["mu"].values), 1)[0]
    assert slope < 0
    assert float(ds["speed_constant"]) == pytest.approx(-1.0 / slope, rel=1e-10)


def test_without_20_kmh_f60_uses_the_fitted_line(medium):
    speeds = [30.0, 50.0, 70.0]
    ds = pavefric.simulate(medium, 0.87e-3, speeds, mu_loc=0.6, depth=1e-3, wet_model="squeeze")
    b, a = np.polyfit(speeds, np.log(ds["mu"].values), 1)
    want = pavefric.ifi(float(np.exp(a + 20.0 * b)), float(ds["mpd"]))
    assert float(ds["ifi_f60"]) == pytest.approx(want["F60"], rel=1e-10)


def test_undefined_cases_write_nothing_rather_than_a_guess(medium):
    dry = pavefric.simulate(medium, 0.87e-3, [20.0, 60.0], mu_loc=0.6)        # flat in speed?
    one = pavefric.simulate(medium, 0.87e-3, [60.0], mu_loc=0.6, depth=1e-3)
    assert "speed_constant" not in one and "ifi_f60" not in one            # no 20, no line
    # Sp needs only the texture and water (attack22: it went with F60)
    assert float(one["ifi_sp"]) == pytest.approx(14.2 + 89.7 * float(one["mpd"]) * 1e3,
                                                 rel=1e-12)
    # F60 from a line far from 20 km/h would be a guess (attack22: F60 0.0997
    # from 99,999 and 100,000 km/h): the line reaches at most 20 km/h beyond
    far = pavefric.simulate(medium, 0.87e-3, [45.0, 80.0], mu_loc=0.6, depth=1e-3,
                            wet_model="squeeze")
    assert "ifi_f60" not in far and "ifi_sp" in far and "speed_constant" in far
    near = pavefric.simulate(medium, 0.87e-3, [40.0, 80.0], mu_loc=0.6, depth=1e-3,
                             wet_model="squeeze")
    assert "ifi_f60" in near
    if float(dry["mu"][1]) >= float(dry["mu"][0]):
        assert "speed_constant" not in dry                                 # friction not falling
    # the IFI indexes wet friction: a dry run's friction is not a DFT's
    assert "mpd" in dry and "ifi_f60" not in dry and "ifi_sp" not in dry
    short = pavefric.simulate(medium[:60], 0.87e-3, [20.0, 60.0], mu_loc=0.6, closed=False)
    assert "ifi_f60" not in short                                          # no MPD (< 100 mm)


def test_the_program_writes_the_same_index(tmp_path):
    out = tmp_path / "o.nc"
    assert run_program(ROOT / "inputs" / "ctm_squeeze.nml", "-o", out).returncode == 0
    ds = pavefric.open_dataset(out)
    assert np.isfinite(float(ds["ifi_f60"])) and float(ds["ifi_f60"]) > 0.081
    assert ds["ifi_sp"].attrs["units"] == "km h-1"
