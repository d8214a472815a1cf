"""NetCDF profile input honours CF packing and missing data for every
numeric type, reads sizes in 64 bits, and refuses ragged counts that do not
fit (issue 19). Before: int16/int32 heights at the netCDF default fill, a
missing_value's second value and values outside valid_min/valid_max were
read as heights; a dimension of 2^32 + 2000 was read as 2000; counts whose
sum wraps past 2^63 were accepted."""
import netCDF4
import numpy as np
import pytest

import pavefric

TYPES = ["i1", "u1", "i2", "u2", "i4", "u4", "i8", "u8", "f4", "f8"]


def packed_file(path, dtype, n=400):
    """One profile of `n` points in `dtype`, packed with scale_factor and
    add_offset (integers), with a _FillValue point, two missing_value
    points (a vector) and one point above valid_max; the expected heights
    (m), NaN where missing."""
    rng = np.random.default_rng(3)
    stored = rng.integers(10, 100, size=n).astype(dtype)
    scale, offset = (0.01, 0.5) if np.dtype(dtype).kind in "iu" else (1.0, 0.0)
    fill, miss, _ = np.array([3, 4, 5], dtype=dtype)
    stored[[11, 12, 13, 14]] = [fill, miss, 5, 120]        # 120 > valid_max
    with netCDF4.Dataset(path, "w") as nc:
        nc.createDimension("point", n)
        h = nc.createVariable("height", dtype, ("point",), fill_value=fill)
        h.set_auto_maskandscale(False)
        h.units = "mm"
        if np.dtype(dtype).kind in "iu":
            h.scale_factor = 0.01
            h.add_offset = 0.5
        h.missing_value = np.array([miss, 5], dtype=dtype)
        h.valid_max = np.array(110, dtype=dtype)
        h[:] = stored
    expected = (stored.astype(np.float64) * scale + offset) * 1e-3
    expected[[11, 12, 13, 14]] = np.nan
    return expected


@pytest.mark.parametrize("dtype", TYPES)
def test_packing_fill_missing_and_valid_range_for_every_type(tmp_path, dtype):
    path = tmp_path / f"{dtype}.nc"
    expected = packed_file(path, dtype)
    p = pavefric.read_profile(path, trim_plates=False, dropouts="interpolate")
    assert p.report["dropouts"] == 4
    np.testing.assert_array_equal(np.isnan(p.raw_heights), np.isnan(expected))
    ok = ~np.isnan(expected)
    np.testing.assert_allclose(p.raw_heights[ok], expected[ok], rtol=1e-12, atol=0)
    # a dropout under dropouts = 'error' names the file, profile and point
    with pytest.raises(pavefric.PavefricError, match=rf"{dtype}.nc, profile '1', point 12: "
                                                     "dropout"):
        pavefric.read_profile(path, trim_plates=False)


def test_valid_range_and_integer_default_fill(tmp_path):
    path = tmp_path / "range.nc"
    with netCDF4.Dataset(path, "w") as nc:
        nc.createDimension("point", 300)
        h = nc.createVariable("height", "i4", ("point",))    # no _FillValue attribute
        h.set_auto_maskandscale(False)
        h.units = "um"
        h.valid_range = np.array([-1000, 1000], dtype="i4")
        values = (np.arange(300) % 50 - 25).astype("i4")
        values[40] = 5000                                   # outside valid_range
        h[:] = values
        h[100] = netCDF4.default_fillvals["i4"]             # the default fill: missing
    p = pavefric.read_profile(path, trim_plates=False, dropouts="interpolate")
    assert np.flatnonzero(np.isnan(p.raw_heights)).tolist() == [40, 100]
    assert p.raw_heights[0] == pytest.approx(-25e-6, rel=1e-12)
    with netCDF4.Dataset(path, "a") as nc:
        nc["height"].valid_range = np.array([1000, -1000], dtype="i4")
    with pytest.raises(pavefric.PavefricError, match=r"range.nc': variable 'height': valid "
                                                     r"minimum 1000 above valid maximum -1000"):
        pavefric.read_profile(path)


def test_a_dimension_past_2_to_the_32_is_not_read_short(tmp_path):
    path = tmp_path / "huge.nc"
    with netCDF4.Dataset(path, "w") as nc:         # sparse: 4 MB on disk
        nc.createDimension("point", None)
        h = nc.createVariable("height", "f4", ("point",), chunksizes=(1 << 20,))
        h.units = "mm"
        h[2**32 + 1999] = 1.0
    with pytest.raises(pavefric.PavefricError, match=r"huge.nc, profile '1': holds 4294969296 "
                                                     r"points, more than 2147483647"):
        pavefric.read_profile(path)


def ragged(path, counts, n_obs, dtype="i8"):
    with netCDF4.Dataset(path, "w") as nc:
        nc.createDimension("station", len(counts))
        nc.createDimension("obs", n_obs)
        rs = nc.createVariable("rowSize", dtype, ("station",))
        rs.sample_dimension = "obs"
        rs[:] = np.array(counts, dtype=dtype)
        nc.createVariable("height", "f8", ("obs",))[:] = np.linspace(0, 1e-3, n_obs)


def test_ragged_counts_that_overflow_or_overlap_are_refused(tmp_path):
    path = tmp_path / "wrap.nc"
    # 2^62 + 2^62 + 2^63 - ... wraps to the 10 points a 64-bit sum would see
    big = 2**62
    ragged(path, [big, big, big, big + 10 - 0], 10)
    with pytest.raises(pavefric.PavefricError, match=r"wrap.nc': variable 'rowSize' \(the "
                                                     r"ragged counts\): profile 1 has count "
                                                     r"4611686018427387904, but only 10 of the 10"):
        pavefric.list_profiles(path)
    path = tmp_path / "overlap.nc"
    ragged(path, [6, 6], 10, dtype="i4")
    with pytest.raises(pavefric.PavefricError, match=r"overlap.nc': variable 'rowSize' \(the "
                                                     r"ragged counts\): profile 2 has count 6, "
                                                     r"but only 4 of the 10 points"):
        pavefric.list_profiles(path)


def test_65537_profiles_with_their_names(tmp_path):
    n = 65537
    path = tmp_path / "many.nc"
    with netCDF4.Dataset(path, "w") as nc:
        nc.createDimension("profile", n)
        nc.createDimension("point", 3)
        nc.createDimension("name_strlen", 12)
        names = nc.createVariable("profile_name", "S1", ("profile", "name_strlen"))
        names.cf_role = "profile_id"
        names[:] = netCDF4.stringtochar(np.array([f"p{k:06d}" for k in range(n)], dtype="S12"))
        nc.createVariable("height", "f4", ("profile", "point"))[:] = np.zeros((n, 3), "f4")
    entries = pavefric.list_profiles(path)
    assert len(entries) == n and entries[-1].name == "p065536"
