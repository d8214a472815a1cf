"""NetCDF profile input (issue 13): one file of many profiles, dense or CF
ragged, written by ``pavefric.write_profiles`` or by other tools; it reads
the same profiles as text files, bit for bit, and gives the same friction."""
import subprocess

import netCDF4
import numpy as np
import pytest
import xarray as xr

import pavefric
from conftest import run_program, write_scene
from pavefric.surfaces import spectral_profile

DX = 0.87e-3


@pytest.fixture(scope="module")
def texts(tmp_path_factory):
    """Three profiles as the text files a user has: mm with 6 decimals."""
    d = tmp_path_factory.mktemp("texts")
    paths = []
    for k, n in enumerate((700, 1024, 900)):
        z = spectral_profile(n, DX, rms=0.5e-3, skew=-0.3, seed=40 + k)
        path = d / f"seg{k}.txt"
        path.write_text("height_mm\n" + "\n".join(f"{1e3 * v:.6f}" for v in z) + "\n")
        paths.append(path)
    return paths


def mm_values(path):
    """The text file's numbers as Python reads them (correctly rounded, as the core)."""
    return np.array([float(t) for t in path.read_text().split()[1:]])


@pytest.mark.parametrize("layout", ["ragged", "dense"])
def test_netcdf_input_equals_text_input_bit_for_bit(tmp_path, texts, layout):
    """Issue 13 must-show: the same profiles from NetCDF and from text give
    the same heights and the same friction, bit for bit."""
    values = [mm_values(p) for p in texts]
    names = ["seg0", "seg1", "seg2"]
    nc = tmp_path / "survey.nc"
    if layout == "ragged":
        pavefric.write_profiles(nc, values, dx=DX, names=names, units="mm",
                                chainage=[0.0, 10.0, 20.0])
    else:
        n = min(v.size for v in values)
        values = [v[:n] for v in values]
        for p, v in zip(texts, values):
            p.with_suffix(".cut").write_text("height_mm\n" + "\n".join(
                p.read_text().split()[1:n + 1]) + "\n")
        texts = [p.with_suffix(".cut") for p in texts]
        pavefric.write_profiles(nc, np.vstack(values), dx=DX, names=names, units="mm")
    for name, text in zip(names, texts):
        a = pavefric.read_profile(text, dx=DX)
        b = pavefric.read_profile(nc, profile_name=name)
        assert b.report["format"] == "netcdf" and a.report["format"] == "plain"
        assert a.dx == b.dx
        assert a.heights.tobytes() == b.heights.tobytes()
        assert np.array_equal(a.raw_heights, b.raw_heights)
        mu_a = pavefric.simulate(a.heights, a.dx, [20, 60], closed=False, depth=1e-3)["mu"]
        mu_b = pavefric.simulate(b.heights, b.dx, [20, 60], closed=False, depth=1e-3)["mu"]
        assert mu_a.values.tobytes() == mu_b.values.tobytes()
    if layout == "ragged":
        assert [e.chainage for e in pavefric.list_profiles(nc)] == [0.0, 10.0, 20.0]


def test_program_reads_a_netcdf_profile_as_it_reads_text(tmp_path, texts):
    """A scene's profile_file may be a NetCDF file (detected by its magic
    bytes, whatever its name); the output equals the text scene's."""
    nc = tmp_path / "one_profile.dat"                 # not named .nc: magic bytes decide
    pavefric.write_profiles(nc, [mm_values(texts[1])], dx=DX, names=["only"], units="mm")
    outs = []
    for k, prof in enumerate((texts[1], nc)):
        scene = write_scene(tmp_path, f"s{k}", groups={
            "surface": f"profile_file = '{prof}', mu_loc = 0.5, dx = {DX}",
            "water": "depth = 1e-3"})
        r = run_program(scene, "-o", tmp_path / f"o{k}.nc")
        assert r.returncode == 0, r.stderr
        outs.append(xr.open_dataset(tmp_path / f"o{k}.nc").load())
    a, b = outs
    for var in ("mu", "wet_fraction", "hydroplaning_fraction", "max_balance_residual"):
        assert a[var].values.tobytes() == b[var].values.tobytes(), var
    assert b.attrs["preprocess_format"] == "netcdf"
    # format = 'netcdf' given explicitly
    scene = write_scene(tmp_path, "s3", groups={
        "surface": f"profile_file = '{nc}', format = 'netcdf', mu_loc = 0.5"})
    assert run_program(scene, "-o", tmp_path / "o3.nc").returncode == 0


def test_which_profile_errors_name_the_file(tmp_path, texts):
    nc = tmp_path / "survey.nc"
    pavefric.write_profiles(nc, [mm_values(p) for p in texts], names=["A", "B", "C"], units="mm")
    with pytest.raises(pavefric.PavefricError,
                       match=r"profile_name: not given, and '.*survey.nc' holds 3 profiles "
                             r"\('A', 'B', 'C'\): name one"):
        pavefric.read_profile(nc)
    with pytest.raises(pavefric.PavefricError, match=r"profile_name = 'D': no such profile"):
        pavefric.read_profile(nc, profile_name="D")
    with pytest.raises(pavefric.PavefricError, match=r"profile_name = 'A': .*seg0.txt' is a "
                                                     r"plain file of one profile"):
        pavefric.read_profile(texts[0], profile_name="A")
    with pytest.raises(pavefric.PavefricError, match=r"cannot open as NetCDF"):
        pavefric.read_profile(texts[0], format="netcdf")
    # the program: a multi-profile file without a name
    scene = write_scene(tmp_path, groups={"surface": f"profile_file = '{nc}'"})
    r = run_program(scene, "-o", tmp_path / "o.nc")
    assert r.returncode == 1 and "holds 3 profiles" in r.stderr


def test_profile_ids_strings_distance_and_packing_from_other_tools(tmp_path):
    """A CF ragged file as another tool writes it: NC_STRING ids with
    cf_role, a count variable named otherwise, distances in mm over obs,
    int16 heights packed with scale_factor and add_offset, a _FillValue
    dropout, chainage in km."""
    rng = np.random.default_rng(5)
    counts = [120, 80]
    packed = rng.integers(-3000, 3000, size=sum(counts)).astype(np.int16)
    packed[7] = -32767                                # a dropout
    dist = np.concatenate([np.arange(c) * 0.5 for c in counts])
    path = tmp_path / "other.nc"
    with netCDF4.Dataset(path, "w") as nc:
        nc.createDimension("station", 2)
        nc.createDimension("obs", sum(counts))
        ids = nc.createVariable("station_id", str, ("station",))
        ids.cf_role = "profile_id"
        ids[0] = "lane 1, 0+100"
        ids[1] = "lane 1, 0+200"
        rs = nc.createVariable("rowSize", "i4", ("station",))
        rs.sample_dimension = "obs"
        rs[:] = counts
        h = nc.createVariable("height", "i2", ("obs",), fill_value=np.int16(-32767))
        h.set_auto_maskandscale(False)
        h.scale_factor = 0.001
        h.add_offset = 0.25
        h.units = "mm"
        h[:] = packed
        d = nc.createVariable("distance", "f8", ("obs",))
        d.units = "millimetre"
        d[:] = dist
        c = nc.createVariable("chainage", "f4", ("station",))
        c.units = "km"
        c[:] = [0.1, 0.2]
    entries = pavefric.list_profiles(path)
    assert [e.name for e in entries] == ["lane 1, 0+100", "lane 1, 0+200"]
    assert entries[1].chainage == pytest.approx(200.0)
    p = pavefric.read_profile(path, profile_name="lane 1, 0+100", trim_plates=False,
                              dropouts="interpolate")
    expected = (packed[:120].astype(np.float64) * 0.001 + 0.25) * 1e-3
    assert np.isnan(p.raw_heights[7]) and p.report["dropouts"] == 1
    keep = np.arange(120) != 7
    assert np.array_equal(p.raw_heights[keep], expected[keep])
    assert p.report["has_distances"] and p.dx == pytest.approx(0.5e-3)
    np.testing.assert_array_equal(p.raw_x, dist[:120] * 1e-3)
    with pytest.raises(pavefric.PavefricError, match=r"other.nc, profile 'lane 1, 0\+100', "
                                                     r"point 8: dropout"):
        pavefric.read_profile(path, profile_name="lane 1, 0+100", trim_plates=False)
    q = pavefric.read_profile(path, profile_name="lane 1, 0+200", trim_plates=False)
    assert q.report["points_read"] == 80 and q.raw_x[0] == 0.0


def test_xarray_written_dense_file_with_shared_distance(tmp_path):
    z = np.vstack([spectral_profile(512, DX, seed=s) for s in (1, 2)])
    ds = xr.Dataset({"height": (("profile", "point"), z * 1e6, {"units": "um"}),
                     "distance": (("point",), np.arange(512) * 0.87, {"units": "mm"})},
                    coords={"profile_name": (("profile",), ["left", "right"],
                                             {"cf_role": "profile_id"})})
    path = tmp_path / "xr.nc"
    ds.to_netcdf(path)
    p = pavefric.read_profile(path, profile_name="right", trim_plates=False)
    np.testing.assert_array_equal(p.raw_heights, z[1] * 1e6 * 1e-6)
    assert p.dx == pytest.approx(DX)


def test_netcdf_values_are_checked(tmp_path):
    path = tmp_path / "bad.nc"
    z = np.zeros((2, 300))
    z[1, 17] = np.inf
    with netCDF4.Dataset(path, "w") as nc:
        nc.createDimension("profile", 2)
        nc.createDimension("point", 300)
        h = nc.createVariable("height", "f8", ("profile", "point"))
        h.units = "furlong"
        h[:] = z
    with pytest.raises(pavefric.PavefricError, match=r"bad.nc': variable 'height': units = "
                                                     r"'furlong' is not a length unit"):
        pavefric.read_profile(path, profile_name="1")
    with netCDF4.Dataset(path, "a") as nc:
        nc["height"].units = "m"
    with pytest.raises(pavefric.PavefricError, match=r"bad.nc, profile '2', point 18: height "
                                                     r"Infinity is not finite"):
        pavefric.read_profile(path, profile_name="2")
    with netCDF4.Dataset(path, "w") as nc:
        nc.createDimension("obs", 10)
        nc.createVariable("heights", "f8", ("obs",))
    with pytest.raises(pavefric.PavefricError, match=r"no variable 'height'"):
        pavefric.read_profile(path)
    with netCDF4.Dataset(path, "w") as nc:
        nc.createDimension("profile", 2)
        nc.createDimension("obs", 10)
        c = nc.createVariable("count", "i4", ("profile",))
        c.sample_dimension = "obs"
        c[:] = [4, 5]
        nc.createVariable("height", "f8", ("obs",))[:] = np.zeros(10)
    with pytest.raises(pavefric.PavefricError, match=r"the counts add up to 9 points but "
                                                     r"'height' has 10"):
        pavefric.read_profile(path, profile_name="1")


def test_write_profiles_checks_its_arguments(tmp_path):
    with pytest.raises(pavefric.PavefricError, match="names: 1 names for 2 profiles"):
        pavefric.write_profiles(tmp_path / "a.nc", np.zeros((2, 10)), names=["x"])
    with pytest.raises(pavefric.PavefricError, match="Inf is not a height"):
        pavefric.write_profiles(tmp_path / "a.nc", [np.array([0.0, np.inf])])
    with pytest.raises(pavefric.PavefricError, match="dx: must be finite and > 0"):
        pavefric.write_profiles(tmp_path / "a.nc", np.zeros((2, 10)), dx=-1.0)
    with pytest.raises(pavefric.PavefricError, match="names: the names must differ"):
        pavefric.write_profiles(tmp_path / "a.nc", np.zeros((2, 10)), names=["x", "x"])
    assert list(tmp_path.iterdir()) == []            # no file, no temporary left


def test_write_profiles_round_trip_and_cf_attributes(tmp_path):
    rng = np.random.default_rng(3)
    profiles = [rng.normal(0, 5e-4, n) for n in (50, 333, 1)]
    profiles[1][10] = np.nan
    path = pavefric.write_profiles(tmp_path / "r.nc", profiles, dx=[1e-3, 0.5e-3, 2e-3],
                                   names=["a", "\u00e9t\u00e9", "c"], chainage=[1.5, 2.5, 3.5])
    entries = pavefric.list_profiles(path)
    assert [e.name for e in entries] == ["a", "\u00e9t\u00e9", "c"]
    p = pavefric.read_profile(path, profile_name="\u00e9t\u00e9", trim_plates=False,
                              dropouts="interpolate")
    assert p.dx == 0.5e-3 and p.report["chainage"] == 2.5 and p.report["dropouts"] == 1
    np.testing.assert_array_equal(np.isnan(p.raw_heights), np.isnan(profiles[1]))
    assert np.array_equal(p.raw_heights, profiles[1], equal_nan=True)
    r = subprocess.run(["ncdump", "-h", str(path)], capture_output=True, text=True)
    assert 'profile_count:sample_dimension = "obs"' in r.stdout
    assert 'profile_name:cf_role = "profile_id"' in r.stdout
    assert 'height:units = "m"' in r.stdout and 'chainage:units = "m"' in r.stdout
    assert ':Conventions = "CF-1.10"' in r.stdout
