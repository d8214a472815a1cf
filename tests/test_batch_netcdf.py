"""A batch over one NetCDF file of many profiles (issue 13): the same numbers
as the same profiles given as text files, bit for bit; names and chainage
come from the file; a resume trusts the journal only while the file is
unchanged; MPI gives the same file."""
import shutil
import subprocess

import numpy as np
import pytest
import xarray as xr

import pavefric
from conftest import run_program

DX = 0.87e-3


@pytest.fixture()
def survey(tmp_path):
    from pavefric.surfaces import spectral_profile

    profiles = [spectral_profile(n, DX, rms=0.4e-3, skew=-0.3, seed=k)
                for k, n in enumerate([300, 512, 700, 256])]
    names = ["km0.1", "km0.2", "km0.3", "km0.4"]
    pavefric.write_profiles(tmp_path / "survey.nc", profiles, DX, names=names,
                            chainage=[100.0, 200.0, 300.0, 400.0])
    text_dir = tmp_path / "text"
    text_dir.mkdir()
    for name, z in zip(names, profiles):
        (text_dir / f"{name}.txt").write_text("\n".join(repr(float(v)) for v in z) + "\n")
    common = ("&surface height_unit = 'm', dx = 0.87e-3, closed = .false., mu_loc = 0.6 /\n"
              "&operation speeds_kmh = 20, 60 /\n")
    (tmp_path / "nc.nml").write_text("&batch profiles = 'survey.nc', depths = 0, 1e-3 /\n"
                                     + common)
    (tmp_path / "txt.nml").write_text("&batch profiles = 'text', depths = 0, 1e-3 /\n" + common)
    return tmp_path, names


def test_netcdf_survey_equals_text_profiles(survey):
    tmp, names = survey
    assert run_program(tmp / "nc.nml", "-o", tmp / "nc.nc").returncode == 0
    assert run_program(tmp / "txt.nml", "-o", tmp / "txt.nc").returncode == 0
    with xr.open_dataset(tmp / "nc.nc") as a, xr.open_dataset(tmp / "txt.nc") as b:
        assert list(a["profile_name"].values) == names
        assert a["profile"].values.tolist() == [1, 2, 3, 4]
        # the directory lists them sorted: select b's by name (the label as an index)
        b = b.set_xindex("profile_name").sel(profile_name=names)
        for var in ("mu", "wet_fraction", "max_balance_residual", "mpd", "rms_height"):
            np.testing.assert_array_equal(a[var].values, b[var].values, err_msg=var)
        np.testing.assert_array_equal(a["chainage"].values, [100.0, 200.0, 300.0, 400.0])
        assert int(a.attrs["profiles_failed"]) == 0


def test_resume_trusts_the_journal_only_while_the_file_is_unchanged(survey):
    tmp, _ = survey
    r = run_program(tmp / "nc.nml", "-o", tmp / "o.nc", "--max-profiles", "2")
    assert r.returncode == 3
    r = run_program(tmp / "nc.nml", "-o", tmp / "o.nc")
    assert r.returncode == 0 and "2 taken from the journal" in r.stdout
    first = xr.load_dataset(tmp / "o.nc")
    # a clean run gives the same file's numbers
    r = run_program(tmp / "nc.nml", "-o", tmp / "clean.nc")
    with xr.open_dataset(tmp / "clean.nc") as clean:
        np.testing.assert_array_equal(first["mu"].values, clean["mu"].values)
    # stop again, then change the survey file: nothing is taken from the journal
    (tmp / "o.nc").unlink()
    assert run_program(tmp / "nc.nml", "-o", tmp / "o.nc", "--max-profiles", "2").returncode == 3
    from pavefric.surfaces import spectral_profile
    pavefric.write_profiles(tmp / "survey.nc", [spectral_profile(400, DX, rms=0.5e-3, seed=9)
                                                for _ in range(4)], DX,
                            names=["km0.1", "km0.2", "km0.3", "km0.4"],
                            chainage=[100.0, 200.0, 300.0, 400.0])
    r = run_program(tmp / "nc.nml", "-o", tmp / "o.nc")
    assert r.returncode == 0 and "taken from the journal" in r.stdout
    assert "0 taken from the journal" in r.stdout


def test_mpi_equals_serial_on_a_netcdf_survey(survey):
    tmp, _ = survey
    mpirun = shutil.which("mpirun")
    assert mpirun, "Open MPI should be installed by setup.sh"
    assert run_program(tmp / "nc.nml", "-o", tmp / "serial.nc").returncode == 0
    import os
    cmd = [mpirun, "-n", "2", "--oversubscribe"]
    if os.geteuid() == 0:
        cmd.append("--allow-run-as-root")
    from conftest import program
    r = subprocess.run(cmd + [program(), str(tmp / "nc.nml"), "-o", str(tmp / "mpi.nc")],
                       capture_output=True, text=True, timeout=180, cwd=tmp)
    assert r.returncode == 0, r.stderr
    with xr.open_dataset(tmp / "serial.nc") as a, xr.open_dataset(tmp / "mpi.nc") as b:
        np.testing.assert_array_equal(a["mu"].values, b["mu"].values)


@pytest.mark.parametrize("wet_model, effect", [("kane2017", "hydrodynamic_bearing"),
                                               ("squeeze", "squeeze_film"),
                                               ("reynolds", "reynolds_film")])
def test_batch_effects_name_the_film_that_ran(survey, wet_model, effect):
    """The batch file's `effects` names the scene's own film where it ran, as
    a single scene's output does (it had said hydrodynamic_bearing for any
    load-carrying film and nothing for the drainage model); a dry batch names
    none."""
    tmp, _ = survey
    common = ("&surface height_unit = 'm', dx = 0.87e-3, closed = .false., mu_loc = 0.6 /\n"
              "&operation speeds_kmh = 20, 60 /\n")
    (tmp / "w.nml").write_text("&batch profiles = 'survey.nc', depths = 0, 1e-3 /\n"
                               f"&water wet_model = '{wet_model}' /\n" + common)
    (tmp / "d.nml").write_text("&batch profiles = 'survey.nc', depths = 0 /\n"
                               f"&water wet_model = '{wet_model}' /\n" + common)
    assert run_program(tmp / "w.nml", "-q", "-o", tmp / "w.nc").returncode == 0
    assert run_program(tmp / "d.nml", "-q", "-o", tmp / "d.nc").returncode == 0
    with xr.open_dataset(tmp / "w.nc") as w, xr.open_dataset(tmp / "d.nc") as d:
        films = {"hydrodynamic_bearing", "squeeze_film", "reynolds_film"}
        assert set(w.attrs["effects"].split(",")) & films == {effect}
        assert not set(d.attrs["effects"].split(",")) & films
