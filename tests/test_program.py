"""The pavefric program: output contents, CLI, and agreement with Python."""
import shutil
import subprocess

import numpy as np
import pytest
import xarray as xr

import pavefric
from conftest import ROOT, program, run_program, write_scene


def test_default_scenes_run_and_write_cf_netcdf(tmp_path):
    mus = {}
    for name in ("ctm_dry", "ctm_wet"):
        out = tmp_path / f"{name}.nc"
        r = run_program(ROOT / "inputs" / f"{name}.nml", "-o", out)
        assert r.returncode == 0, r.stderr
        ds = xr.open_dataset(out)
        for var in ("speed", "speed_kmh", "mu", "n_clamped", "hydroplaning_fraction",
                    "wet_fraction", "max_balance_residual"):
            assert var in ds.variables, var
        assert ds["speed"].attrs["units"] == "m s-1"
        assert ds["speed_kmh"].attrs["units"] == "km h-1"
        np.testing.assert_allclose(ds["speed"].values * 3.6, ds["speed_kmh"].values)
        assert ds.attrs["Conventions"] == "CF-1.10"
        assert ds.attrs["pavefric_version"] == pavefric.__version__
        assert "pavefric" in ds.attrs["history"]
        text = (ROOT / "inputs" / f"{name}.nml").read_text()
        assert ds.attrs["input_namelist"] == text
        assert np.all((ds["mu"].values > 0.0) & (ds["mu"].values < 1.2))
        wet = name == "ctm_wet"
        assert ("hydrodynamic_bearing" in ds.attrs["effects"]) == wet
        mus[name] = ds["mu"].values
        ds.close()
    # water lowers friction at speed, and more so the faster
    assert np.all(mus["ctm_wet"][3:] < mus["ctm_dry"][3:] - 0.05)
    assert np.all(np.diff(mus["ctm_wet"]) < 0)


def test_ncdump_reads_the_header(tmp_path):
    if shutil.which("ncdump") is None:
        pytest.fail("ncdump (netcdf-bin) should be installed by setup.sh")
    out = tmp_path / "o.nc"
    assert run_program(ROOT / "inputs" / "ctm_wet.nml", "-o", out).returncode == 0
    head = subprocess.run(["ncdump", "-h", str(out)], capture_output=True, text=True).stdout
    assert "double mu(speed_kmh)" in head and ':effects = "' in head


def test_series_variables(tmp_path, profile_m):
    scene = write_scene(tmp_path, profile=profile_m,
                        groups={"water": "depth = 1e-3", "output": "series = .true."})
    out = tmp_path / "s.nc"
    r = run_program(scene, "-o", out)
    assert r.returncode == 0, r.stderr
    ds = xr.open_dataset(out)
    for var in ("mu_inst", "hydro_load", "penetration", "contact_elements"):
        assert ds[var].dims == ("speed_kmh", "position")
    # Eq. 12 holds for the paper's scheme; the energy scheme's mean is the
    # dissipation, which on a wet road differs from the mean of the facets'
    # work per step by the film's work (tests/test_energy.py)
    ds.close()
    paper = write_scene(tmp_path, "paper", profile=profile_m,
                        groups={"water": "depth = 1e-3", "output": "series = .true.",
                                "numerics": "friction_scheme = 'paper'"})
    assert run_program(paper, "-o", tmp_path / "p.nc").returncode == 0
    with xr.open_dataset(tmp_path / "p.nc") as dp:
        np.testing.assert_allclose(dp["mu_inst"].mean("position").values, dp["mu"].values,
                                   rtol=1e-12)
    scene2 = write_scene(tmp_path, "noseries", profile=profile_m)
    out2 = tmp_path / "n.nc"
    assert run_program(scene2, "-o", out2).returncode == 0
    with xr.open_dataset(out2) as d2:
        assert "position" not in d2.dims and "mu_inst" not in d2


@pytest.mark.parametrize("water", ["depth = 0.0", "depth = 1e-3, alpha = 2.0"])
def test_program_and_python_identical(tmp_path, profile_m, water):
    scene = write_scene(tmp_path, profile=profile_m,
                        groups={"water": water, "operation": "speeds_kmh = 0, 5, 20, 60, 90",
                                "rubber": "stiffness = 2e8, viscosity = 500",
                                "output": "series = .true."})
    out = tmp_path / "p.nc"
    assert run_program(scene, "-o", out).returncode == 0
    # the same profile, read by the core's reader, through simulate()
    prof = pavefric.read_profile(tmp_path / "scene_profile.txt")
    params = dict(mu_loc=0.5, stiffness=2e8, viscosity=500.0)
    if "alpha" in water:
        params.update(depth=1e-3, alpha=2.0)
    ds = pavefric.simulate(prof.heights, 0.87e-3, [0, 5, 20, 60, 90], series=True, **params)
    with xr.open_dataset(out) as prog:
        for var in ("mu", "n_clamped", "wet_fraction", "hydroplaning_fraction",
                    "max_balance_residual", "mu_inst", "penetration", "hydro_load",
                    "contact_elements"):
            assert np.array_equal(prog[var].values, ds[var].values), var
        assert prog.attrs["effects"] == ds.attrs["effects"]
    # and pavefric.run writes the same file contents
    out_py = pavefric.run(scene, tmp_path / "py.nc")
    with xr.open_dataset(out_py) as a, xr.open_dataset(out) as b:
        assert np.array_equal(a["mu"].values, b["mu"].values)


def test_output_override_and_default_location(tmp_path, profile_m):
    scene = write_scene(tmp_path / "in", "myscene", profile=profile_m)
    work = tmp_path / "work"
    work.mkdir()
    r = run_program(scene, cwd=work)
    assert r.returncode == 0, r.stderr
    assert (work / "outputs" / "myscene.nc").exists()
    assert "outputs/myscene.nc" in r.stdout


def test_help_and_version():
    r = subprocess.run([program(), "--help"], capture_output=True, text=True)
    assert r.returncode == 0 and "usage: pavefric SCENE.nml" in r.stdout
    r = subprocess.run([program(), "--version"], capture_output=True, text=True)
    assert r.returncode == 0 and r.stdout.strip() == f"pavefric {pavefric.__version__}"
    r = subprocess.run([program()], capture_output=True, text=True)
    assert r.returncode == 2
    r = subprocess.run([program(), "--frobnicate"], capture_output=True, text=True)
    assert r.returncode != 0 and "--frobnicate" in r.stderr


def test_python_cli_run_and_plot(tmp_path):
    import sys

    out = tmp_path / "c.nc"
    png = tmp_path / "c.png"
    r = subprocess.run([sys.executable, "-m", "pavefric", "run", str(ROOT / "inputs" / "ctm_wet.nml"),
                        "-o", str(out), "--plot", str(png)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert png.stat().st_size > 10_000 and png.read_bytes()[:4] == b"\x89PNG"
    ds = pavefric.open(out)
    assert ds.attrs["history"].split(": ", 1)[1].startswith("python -m pavefric run")
    # the friction table, as the program prints it (it printed only 'wrote')
    p = subprocess.run([program(), str(ROOT / "inputs" / "ctm_wet.nml"), "-o",
                        str(tmp_path / "p.nc")], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    table = p.stdout[p.stdout.index("  pad elements"):]
    assert table.count("\n") == 12                     # the run, header and 10 speeds
    assert table in r.stdout, (table, r.stdout)


def test_the_table_keeps_its_columns_for_a_huge_mu(tmp_path):
    """An attack's reproducer: with &numerics theta_max_deg = 89.999999 mu
    reached 4e5 and the printed table ran the speed and mu columns together
    ('1.000408767.51831'); mu is printed in exponent form from 1e4 on, and
    each row keeps one field per column (the values those of the output)."""
    import netCDF4

    z = np.random.default_rng(1).normal(0.0, 0.6e-3, 256)   # a facet near vertical
    prof = tmp_path / "p.txt"
    np.savetxt(prof, z)
    scene = tmp_path / "s.nml"
    scene.write_text(f"&surface profile_file = '{prof}', height_unit = 'm', dx = 0.87e-3, "
                     "closed = .true., mu_loc = 0.6 /\n&operation speeds_kmh = 1, 20, 80 /\n"
                     "&numerics theta_max_deg = 89.999999 /\n")
    out = tmp_path / "r.nc"
    r = run_program(scene, "-o", out)
    assert r.returncode == 0, r.stderr
    lines = r.stdout.splitlines()
    head = next(i for i, ln in enumerate(lines) if ln.strip().startswith("speed_kmh"))
    rows = [ln.split() for ln in lines[head + 1:head + 4]]
    with netCDF4.Dataset(out) as ds:
        mu = ds["mu"][:]
    assert max(abs(mu)) >= 1e4
    for row, m in zip(rows, mu):
        assert len(row) == len(lines[head].split())
        assert float(row[1]) == pytest.approx(float(m), rel=1e-4)
    # python -m pavefric run prints the same text (the review: its own
    # formatting wrote 1.2346e+04 where the program writes 1.2346E+004)
    import sys

    py = subprocess.run([sys.executable, "-m", "pavefric", "run", str(scene), "-o",
                         str(tmp_path / "py.nc")], capture_output=True, text=True)
    assert py.returncode == 0, py.stderr
    assert r.stdout[r.stdout.index("  pad elements"):] in py.stdout, (r.stdout, py.stdout)


def test_python_run_prints_a_long_table_whole(tmp_path):
    """More speeds than the interface's text holds at once (8192 characters,
    read 100 speeds a call): python -m pavefric run prints the program's
    table whole, once its header."""
    import sys

    z = np.random.default_rng(2).normal(0.0, 0.4e-3, 256)
    prof = tmp_path / "p.txt"
    np.savetxt(prof, z)
    speeds = ", ".join(f"{0.5 * k:g}" for k in range(1, 251))
    scene = tmp_path / "s.nml"
    scene.write_text(f"&surface profile_file = '{prof}', height_unit = 'm', dx = 0.87e-3, "
                     f"closed = .true., mu_loc = 0.6 /\n&operation speeds_kmh = {speeds} /\n")
    r = run_program(scene, "-o", tmp_path / "r.nc")
    assert r.returncode == 0, r.stderr
    py = subprocess.run([sys.executable, "-m", "pavefric", "run", str(scene), "-o",
                         str(tmp_path / "py.nc")], capture_output=True, text=True)
    assert py.returncode == 0, py.stderr
    table = r.stdout[r.stdout.index("  pad elements"):]
    assert table.count("\n") == 252 and table in py.stdout
    assert py.stdout.count("speed_kmh") == 1
