"""Bad input: a non-zero exit, one line naming the group, variable and value
(or file and line), and no output file left behind."""
import math

import numpy as np
import pytest

import pavefric
from conftest import run_program, write_scene


def assert_rejected(tmp_path, scene, *needles):
    out = tmp_path / "out" / "result.nc"
    out.parent.mkdir(exist_ok=True)
    r = run_program(scene, "-o", out)
    assert r.returncode != 0
    lines = [line for line in r.stderr.splitlines() if line.strip()]
    assert len(lines) == 1, r.stderr
    for needle in needles:
        assert needle in lines[0], (needle, lines[0])
    assert list(out.parent.iterdir()) == []          # nothing written, no temp file
    return lines[0]


@pytest.mark.parametrize("group,body,needles", [
    ("pad", "lenght = 0.02", ["&pad lenght = 0.02", "unknown variable"]),
    ("rubber", "stiffness = 1.4e8, visc = 3", ["&rubber visc = 3", "unknown variable"]),
    ("pad", "load = heavy", ["&pad load = heavy", "not a number (write one such as",
                             "must be finite and >= 1e-12"]),
    ("rubber", "stiffness = 0.0", ["&rubber stiffness = 0", ">= 1"]),
    # an attack found 1e-305 taken, then failing as an internal error at 0 km/h
    ("rubber", "stiffness = 1e-305", ["&rubber stiffness = 1e-305", ">= 1"]),
    ("rubber", "stiffness = -1e8", ["&rubber stiffness = -1e8"]),
    ("pad", "load = 0", ["&pad load = 0"]),
    ("pad", "load = -11.8", ["&pad load = -11.8"]),
    ("pad", "length = 0", ["&pad length = 0"]),
    ("pad", "length = -0.02", ["&pad length = -0.02"]),
    ("pad", "width = 0", ["&pad width = 0"]),
    ("pad", "width = -1", ["&pad width = -1"]),
    ("pad", "thickness = 0", ["&pad thickness = 0"]),
    ("pad", "thickness = -0.006", ["&pad thickness = -0.006"]),
    ("pad", "shape = 'square'", ["&pad shape = 'square'"]),
    ("surface", "profile_file = '{prof}', dx = 0", ["&surface dx = 0"]),
    ("surface", "profile_file = '{prof}', dx = -8.7e-4", ["&surface dx = -0.00087"]),
    ("surface", "profile_file = '{prof}', mu_loc = -0.1", ["&surface mu_loc = -0.1"]),
    ("surface", "profile_file = '{prof}', height_unit = 'inch'", ["&surface height_unit = 'inch'"]),
    ("rubber", "viscosity = -1", ["&rubber viscosity = -1"]),
    ("water", "depth = -1e-3", ["&water depth = -0.001"]),
    ("water", "viscosity = 0", ["&water viscosity = 0"]),
    ("operation", "speeds_kmh = 20, -5", ["&operation speeds_kmh(2) = -5"]),
    ("numerics", "theta_max_deg = 0", ["&numerics theta_max_deg = 0"]),
    ("numerics", "theta_max_deg = 90", ["&numerics theta_max_deg = 90"]),
    ("numerics", "theta_max_deg = -10", ["&numerics theta_max_deg = -10"]),
    ("numerics", "theta_max_deg = 120", ["&numerics theta_max_deg = 120"]),
    ("pad", "shape = 'rounded', radius = 0.005", ["&pad radius = 0.005", "half the pad length"]),
    ("numerics", "substeps = 0", ["&numerics substeps = 0"]),
    ("numerics", "elements_per_sample = -2", ["&numerics elements_per_sample = -2"]),
    ("numerics", "position_stride = 0", ["&numerics position_stride = 0"]),
    ("numerics", "wet_tolerance = 2", ["&numerics wet_tolerance = 2"]),
    ("water", "alpha = -1", ["&water alpha = -1"]),
    ("water", "beta = -0.5", ["&water beta = -0.5"]),
    ("operation", "speeds_kmh = 20, 1e400", ["&operation speeds_kmh"]),
])
def test_bad_variable(tmp_path, group, body, needles):
    scene = write_scene(tmp_path)
    body = body.format(prof="scene_profile.txt")
    scene = write_scene(tmp_path, groups={group: body})
    assert_rejected(tmp_path, scene, *needles)


def test_misspelt_group(tmp_path):
    scene = write_scene(tmp_path)
    scene.write_text(scene.read_text().replace("&rubber", "&rubbr"))
    assert_rejected(tmp_path, scene, "&rubbr", "unknown namelist group", ":7")


def test_missing_profile_file(tmp_path):
    scene = write_scene(tmp_path, groups={"surface": "profile_file = 'nowhere.txt'"})
    assert_rejected(tmp_path, scene, "&surface profile_file", "nowhere.txt")


def test_one_point_profile_names_the_pad_not_the_plates(tmp_path):
    """An attack found a one-point profile blamed on trimming reference
    plates, which trimmed nothing; with trim_plates off it was (and is) the
    pad's message."""
    (tmp_path / "one.txt").write_text("0.0\n")
    for preprocess in ("trim_plates = .true.", "trim_plates = .false."):
        scene = write_scene(tmp_path, groups={"surface": "profile_file = 'one.txt'",
                                              "preprocess": preprocess})
        line = assert_rejected(tmp_path, scene, "&surface profile_file", "has 1 points",
                               "fewer than the pad's")
        assert "plates" not in line


def test_empty_profile_file(tmp_path):
    scene = write_scene(tmp_path, profile_text="")
    assert_rejected(tmp_path, scene, "&surface profile_file", "holds no heights",
                    "the file is empty (0 bytes")


def test_a_kernel_file_is_named_empty(tmp_path):
    """A file of /proc reports a size of 0 and read as empty: the message said it
    held 'only comments or blank lines' (it has text: no profile's)."""
    scene = write_scene(tmp_path, groups={"surface": "profile_file = '/proc/self/stat'"})
    line = assert_rejected(tmp_path, scene, "&surface profile_file = '/proc/self/stat'",
                           "the file is empty (0 bytes; a file of /proc or /sys")
    assert "only comments" not in line


def test_unreadable_profile_file(tmp_path):
    # a directory where the file should be: unreadable even for root
    (tmp_path / "adir").mkdir()
    scene = write_scene(tmp_path, groups={"surface": "profile_file = 'adir'"})
    assert_rejected(tmp_path, scene, "&surface profile_file", "adir")


@pytest.mark.parametrize("bad", ["NaN", "nan", "Inf", "-Infinity"])
def test_non_finite_height(tmp_path, bad):
    text = "height_mm\n0.1\n0.2\n" + bad + "\n" + "\n".join(["0.1"] * 50) + "\n"
    scene = write_scene(tmp_path, profile_text=text)
    # NaN is a dropout (refused under the strict default), Inf is not a height
    why = "dropout" if bad.lower() == "nan" else "not finite"
    assert_rejected(tmp_path, scene, "scene_profile.txt:4", why)


def test_non_numeric_text(tmp_path):
    text = "height_mm\n0.1\n0.2\nabc\n" + "\n".join(["0.1"] * 50) + "\n"
    scene = write_scene(tmp_path, profile_text=text)
    assert_rejected(tmp_path, scene, "scene_profile.txt:4", "'abc' is not a number")


def test_decimal_commas_are_named_where_distances_stop_increasing(tmp_path):
    # attack, 2026-11-28: '0,0993' reads as a distance 0 and a height 993; the
    # message said only that the distances do not increase
    text = "".join(f"0,{k:04d}\n" for k in range(0, 5000, 97))
    scene = write_scene(tmp_path, profile_text=text)
    assert_rejected(tmp_path, scene, "scene_profile.txt:2: distances do not increase",
                    "decimals with a comma", "write decimal points")
    # real distances that repeat: no such hint
    text = "".join(f"{0.5 * k:.1f} 0.1\n" for k in range(60)) + "29.5 0.2\n"
    scene = write_scene(tmp_path / "b", profile_text=text)
    r = run_program(scene, "-o", tmp_path / "b.nc")
    assert r.returncode == 1 and "distances do not increase" in r.stderr, r.stderr
    assert "decimals with a comma" not in r.stderr


def test_fewer_points_than_elements(tmp_path):
    scene = write_scene(tmp_path, profile=np.zeros(10))
    assert_rejected(tmp_path, scene, "&surface profile_file", "10 points", "23 elements")


def test_unwritable_output_directory(tmp_path):
    scene = write_scene(tmp_path)
    r = run_program(scene, "-o", "/nonexistent-dir/sub/out.nc")
    assert r.returncode != 0
    # the path came from -o: the message says -o, not &output file, and not
    # the temporary's name; it says what to do
    assert ("-o '/nonexistent-dir/sub/out.nc': cannot write in directory '/nonexistent-dir/sub' "
            "(No such file or directory); create the directory or give another path") in r.stderr
    assert ".tmp" not in r.stderr
    scene = write_scene(tmp_path, groups={"output": "file = '/nonexistent-dir/out.nc'"})
    r = run_program(scene)
    assert r.returncode != 0 and "/nonexistent-dir" in r.stderr


def test_existing_output_survives_a_failed_run(tmp_path):
    good = write_scene(tmp_path, "good")
    out = tmp_path / "keep.nc"
    assert run_program(good, "-o", out).returncode == 0
    before = out.read_bytes()
    bad = write_scene(tmp_path, "bad", groups={"pad": "load = -1"})
    assert run_program(bad, "-o", out).returncode != 0
    assert out.read_bytes() == before


def test_python_raises_the_same_message(tmp_path):
    with pytest.raises(pavefric.PavefricError, match=r"&rubber stiffness = -1e8"):
        pavefric.simulate(np.zeros(100), 0.87e-3, [20], stiffness=-1e8)
    with pytest.raises(pavefric.PavefricError, match=r"profile height 3 = NaN"):
        pavefric.simulate([0.0, 0.0, math.nan] + [0.0] * 50, 0.87e-3, [20])
    with pytest.raises(TypeError, match="lenght"):
        pavefric.simulate(np.zeros(100), 0.87e-3, [20], lenght=0.02)
    scene = write_scene(tmp_path, groups={"pad": "load = -2"})
    with pytest.raises(pavefric.PavefricError, match=r"&pad load = -2"):
        pavefric.run(scene, tmp_path / "x.nc")
    assert not (tmp_path / "x.nc").exists()
