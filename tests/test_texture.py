"""Texture metrics (core) against hand-worked cases and captif-slp, and the
ASTM E1960 International Friction Index."""
import numpy as np
import pytest

import pavefric
from conftest import CAPTIF, ROOT, import_captif_slp

DX = 0.5e-3


def test_msd_by_hand_no_slope():
    # one 100 mm segment at 0.5 mm: flat at 0 with a 2 mm peak in the first
    # half and a 1 mm peak in the second: MSD = (2 + 1)/2 - mean
    z = np.zeros(200)
    z[30] = 2e-3
    z[150] = 1e-3
    t = pavefric.texture(z, DX, closed=False, slope_suppression=False)
    assert t["n_segments"] == 1
    assert t["mpd"] == pytest.approx(1.5e-3 - 3e-3 / 200, rel=1e-12)


def test_slope_suppression_removes_a_tilt_exactly():
    rng = np.random.default_rng(4)
    z = rng.normal(0, 0.4e-3, 600)
    x = np.arange(600) * DX
    tilted = z + 0.05 * x + 3.0
    a = pavefric.texture(z, DX, closed=False)
    b = pavefric.texture(tilted, DX, closed=False)
    assert a["n_segments"] == 3
    np.testing.assert_allclose(b["msd"], a["msd"], rtol=1e-9)
    # by hand: per segment, remove the least-squares line, then the two peaks
    for k in range(3):
        seg = z[200 * k: 200 * (k + 1)]
        xs = np.arange(200) * DX
        coef = np.polyfit(xs, seg, 1)
        r = seg - np.polyval(coef, xs)
        assert a["msd"][k] == pytest.approx(0.5 * (r[:100].max() + r[100:].max()) - r.mean(),
                                            rel=1e-9)


def test_rms_height_and_slope_by_hand():
    k = np.arange(1000)
    z = 1e-3 * np.sin(2 * np.pi * k / 100)            # 10 whole periods, closed
    t = pavefric.texture(z, DX, closed=True)
    assert t["rms_height"] == pytest.approx(1e-3 / np.sqrt(2), rel=1e-12)
    # discrete slope of a sine: amplitude 2 A sin(pi/100)/dx, RMS over periods
    expect = 2e-3 * np.sin(np.pi / 100) / DX / np.sqrt(2)
    assert t["rms_slope"] == pytest.approx(expect, rel=1e-12)


def test_texture_errors():
    with pytest.raises(pavefric.PavefricError, match="shorter than one segment"):
        pavefric.texture(np.zeros(50), DX)


@pytest.mark.parametrize("name", ["20211011_aylesbury_dec_station_0.dat",
                                  "20211011_aylesbury_dec_station_1.dat"])
def test_msd_matches_captif_slp_on_real_profiles(name):
    captif_slp = import_captif_slp()   # setup.sh and CI install it; CI never skips
    path = CAPTIF / name
    reading = captif_slp.Reading.from_file(path, detect_plates=True,
                                           target_sample_spacing_mm=0.5)
    ours, theirs, valid = [], [], []
    for seg in reading.segments:
        h = seg.resampled_trace["relative_height_mm"].values * 1e-3
        if h.size < 8 or np.isnan(h).any():
            continue
        t = pavefric.texture(h, DX, closed=False, segment_length=h.size * DX,
                             slope_suppression=False)
        ours.append(t["mpd"] * 1e3)
        theirs.append(seg.msd)
        valid.append(seg.is_valid)
    assert len(ours) >= 10
    np.testing.assert_allclose(ours, theirs, rtol=1e-9)
    mpd = reading.mpd()["mpd"]
    assert np.mean(np.array(ours)[np.array(valid)]) == pytest.approx(mpd, rel=1e-9)


def test_ifi_by_hand():
    # ASTM E1960: Sp = 14.2 + 89.7 MPD(mm); F60 = 0.081 + 0.732 DFT20 exp(-40/Sp)
    r = pavefric.ifi(0.60, 0.8e-3)
    sp = 14.2 + 89.7 * 0.8
    assert r["Sp"] == pytest.approx(sp)
    assert r["F60"] == pytest.approx(0.081 + 0.732 * 0.60 * np.exp(-40 / sp))


def test_program_writes_texture(tmp_path):
    import xarray as xr
    from conftest import run_program

    out = tmp_path / "t.nc"
    assert run_program(ROOT / "inputs" / "ctm_dry.nml", "-o", out).returncode == 0
    prof = pavefric.read_profile(ROOT / "inputs" / "profiles" / "ctm_medium.txt")
    t = pavefric.texture(prof.heights, 0.87e-3)
    with xr.open_dataset(out) as ds:
        assert float(ds["mpd"]) == t["mpd"]
        assert float(ds["rms_slope"]) == t["rms_slope"]
        assert ds["mpd"].attrs["units"] == "m"
