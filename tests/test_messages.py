"""Error messages say what was wrong and what to change (issue 19: an attack
run found messages that did not). Each case is a reproducer from the audit of
every message (program, Python library, Python commands): the one line names
the group and variable (or the file and line, or the option) and gives the
remedy."""
import math
import subprocess
import warnings
import sys

import numpy as np
import pytest

import pavefric
from conftest import DX, run_program

HEIGHTS = [f"{math.sin(i) * 0.5:.3f}" for i in range(100)]


def profile_file(tmp_path, name, lines):
    path = tmp_path / "p" / name
    path.parent.mkdir(exist_ok=True)
    path.write_text("\n".join(lines) + "\n")
    return path


def scene_text(tmp_path, text, name="s.nml"):
    path = tmp_path / name
    path.write_text(text)
    return path


def one_error(tmp_path, scene, *args, status=1):
    """Run the program; the one stderr line (no output written)."""
    out = tmp_path / "out" / "r.nc"
    out.parent.mkdir(exist_ok=True)
    r = run_program(scene, "-q", "-o", out, *args)
    assert r.returncode == status, r.stdout + r.stderr
    lines = [ln for ln in r.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1, r.stderr
    assert not out.exists()
    return lines[0]


def with_profile(tmp_path, lines, extra="", name="x.txt"):
    p = profile_file(tmp_path, name, lines)
    return scene_text(tmp_path, f"&surface profile_file = 'p/{p.name}' /\n"
                                f"&operation speeds_kmh = 10 /\n{extra}")


BASE = "&surface profile_file = 'p/ok.txt' /\n&operation speeds_kmh = 10 /\n"


@pytest.fixture
def base(tmp_path):
    profile_file(tmp_path, "ok.txt", HEIGHTS)
    return tmp_path


def test_no_profile_file(tmp_path):
    line = one_error(tmp_path, scene_text(tmp_path, "&operation speeds_kmh = 10 /\n"))
    assert "&surface profile_file: not given in" in line
    assert "relative to the scene's directory" in line and "&batch" in line


@pytest.mark.parametrize("extra,needles", [
    ("&water depth = 1-3 /", ["&water depth = 1-3: not a number (write one such as 0.5, 1e-3",
                              "must be finite and >= 0 and <= 100 m", "s.nml:3"]),
    # a NaN or an Infinity written out is a number, out of range: the range alone
    ("&rubber stiffness = nan /", ["&rubber stiffness = nan: must be finite and >= 1"]),
    ("&rubber stiffness = -Infinity /", ["&rubber stiffness = -Infinity: must be finite"]),
    # an overflow is named as such, with the value as written
    ("&rubber stiffness = 1e400 /", ["&rubber stiffness = 1e400: too large for double precision",
                                     "(it would be read as Infinity)", "must be finite and >= 1"]),
    ("&numerics substeps = 2.5 /", ["&numerics substeps = 2.5: must be a whole number from 1 to"]),
    ("&operation speeds_kmh(1) = 10, speeds_kmh(3) = 20 /",
     ["&operation speeds_kmh: element 2 is not given", "give speeds_kmh(2) too",
      "number the elements from 1 without gaps"]),
    ("&pad length = /", ["&pad length = : no value given; give one, or remove the assignment "
                         "to keep the default"]),
    ("&rubber temperature = -80 /", ["&rubber temperature = -80", "log10 a_T = 553.8,",
                                     "give a temperature nearer reference_temperature"]),
    ("&preprocess resample_dx = 0.0001 /",
     ["&preprocess resample_dx = 0.0001: finer than the data's spacing",
      "give resample_dx >= the data's spacing, or 0 to keep it"]),
    ("&pad element_length = 1e-13 /", ["&pad element_length = 1e-13", "give a larger "
                                       "element_length (default 0.87e-3 m) or 0"]),
])
def test_scene_values(base, extra, needles):
    text = BASE.replace("&operation speeds_kmh = 10 /\n", "") if "speeds_kmh(" in extra else BASE
    line = one_error(base, scene_text(base, text + extra + "\n"))
    for needle in needles:
        assert needle in line, (needle, line)


def test_more_than_one_scene_file(base):
    scene = scene_text(base, BASE)
    r = run_program(scene, scene.parent / "out.nc")
    assert r.returncode == 2
    assert "more than one scene file given" in r.stderr
    assert f"name the output with -o (pavefric {scene} -o out.nc)" in r.stderr


def test_max_profiles_not_a_count(base):
    line = one_error(base, scene_text(base, BASE), "--max-profiles", "x", status=2)
    assert "--max-profiles 'x': must be a whole number >= 0" in line and "0: no limit" in line


@pytest.mark.parametrize("bad,needles", [
    ("n/a", ["p/x.txt:11: 'n/a' is not a number", "mark a dropout as NaN",
             "&preprocess dropouts = 'interpolate'"]),
    ("0,5", ["p/x.txt:11: 2 columns where earlier lines have 1",
             "a height, or a distance and a height (a decimal comma? write 0.5)"]),
    ("2e9", ["p/x.txt:11: height 2e6 m", "are the heights in the unit declared (&surface "
                                            "height_unit"]),
])
def test_profile_lines(tmp_path, bad, needles):
    line = one_error(tmp_path, with_profile(tmp_path, HEIGHTS[:10] + [bad] + HEIGHTS[10:]))
    for needle in needles:
        assert needle in line, (needle, line)


def test_profile_shorter_than_the_pad(tmp_path):
    line = one_error(tmp_path, with_profile(tmp_path, HEIGHTS[:8]))
    assert line.startswith("pavefric: error: &surface profile_file = '") and "p/x.txt'" in line
    assert "8 points (0.00696 m), fewer than the pad's 23 elements" in line
    assert "give a profile of at least 23 points, or &pad length <= 0.00696 m" in line


@pytest.mark.parametrize("closed", [True, False])
@pytest.mark.parametrize("element_length", [0.87e-3, 0.0])
@pytest.mark.parametrize("dx", [1e-20, 1e-300, 1e-12, 1e-7])
def test_a_spacing_far_below_the_pad_is_bad_input_not_memory(dx, element_length, closed):
    """An attack's reproducer: pavefric.simulate(z, 1e-20, [20.0]) raised a
    bare MemoryError blaming &numerics elements_per_sample and substeps
    (the pad would have had more than 2e9 elements at that spacing); a
    profile a thousand times shorter than the pad is the spacing's fault.
    At 1e-7 m (a pad of 200,000 elements that fits) the pad's own spacing
    (element_length = 0) ran a closed profile of 6.4 um under a pad of
    20 mm, wrapped round it 3,000 times: refused the same way since
    2026-12-07, as the resampled pad already was."""
    z = np.sin(np.arange(64)) * 1e-3
    with pytest.raises(pavefric.PavefricError) as info:
        pavefric.simulate(z, dx, [20.0], closed=closed, element_length=element_length)
    assert not isinstance(info.value, MemoryError)
    text = str(info.value)
    shown = {1e-7: "1e-7"}.get(dx, f"{dx:g}")          # (the core writes no exponent's 0)
    assert text.startswith(f"&surface dx = {shown} m: the profile of 64 points is "), text
    assert "far shorter than the pad (&pad length = 0.02 m); give dx in metres" in text
    assert "elements_per_sample" not in text


def test_the_program_says_so_of_a_spacing_far_below_the_pad(tmp_path):
    p = profile_file(tmp_path, "x.txt", HEIGHTS)
    line = one_error(tmp_path, scene_text(tmp_path, f"&surface profile_file = 'p/{p.name}', "
                                                    "dx = 1e-20 /\n&operation speeds_kmh = 10 /\n"))
    assert "&surface dx = 1e-20 m: the profile of 100 points is 1e-18 m long, far shorter " \
        "than the pad" in line, line


def open_profile(tmp_path, lines, extra=""):
    p = profile_file(tmp_path, "x.txt", lines)
    return scene_text(tmp_path, f"&surface profile_file = 'p/{p.name}', closed = .false. /\n"
                                f"&operation speeds_kmh = 10 /\n{extra}")


@pytest.mark.parametrize("scheme", ["euler", "extrapolated", "exact", "auto"])
def test_an_open_profile_one_pad_long_is_refused(tmp_path, scheme):
    """An attack's reproducer: an open profile exactly as long as the pad
    (23 points, 23 elements) has one position, where the pad lands and never
    slides; time_scheme = 'exact' reported mu = 0 with mu_inst 3.7, backward
    Euler a mu that grew with substeps (1.19 at 1, 3.42 at 4096). Friction
    is the work done over the distance slid: it is refused, naming the
    remedy; one more point runs, and so does the same profile closed."""
    line = one_error(tmp_path, open_profile(tmp_path, HEIGHTS[:23],
                                            f"&numerics time_scheme = '{scheme}' /\n"))
    assert "the profile has 23 points (0.02001 m): the pad's 23 elements (&pad length = " \
        "0.02 m at dx = 0.00087 m) stand on it at one averaged position only" in line
    assert "give a profile of at least 24 points, or &pad length <= 0.0191 m" in line
    z = np.array([float(h) for h in HEIGHTS[:24]]) * 1e-3
    for n, closed in ((24, False), (23, True)):
        ds = pavefric.simulate(z[:n], DX, [20.0], closed=closed, time_scheme=scheme,
                               error_estimate=False, min_contacts=0)
        assert 0.1 < float(ds["mu"][0]) < 2.0


def test_the_short_profile_message_names_the_knobs_that_made_the_pad(tmp_path):
    """An attack's reproducers: a pad of 1471 elements was blamed on &pad
    length alone (elements_per_sample = 64 made it), and a profile resampled
    to &pad element_length was said to have 22 points where the file had
    23 (the resampled count, the variable unnamed)."""
    line = one_error(tmp_path, open_profile(tmp_path, HEIGHTS[:23],
                                            "&numerics elements_per_sample = 64 /\n"))
    assert "fewer than the pad's 1471 elements (&pad length = 0.02 m at dx = 0.00087 m / " \
        "&numerics elements_per_sample = 64); give a profile of at least 24 points" in line
    line = one_error(tmp_path, open_profile(tmp_path, HEIGHTS[:23],
                                            "&pad element_length = 0.5e-3 /\n"))
    assert "the profile resampled to &pad element_length = 0.0005 m has 39 points " \
        "(0.0195 m), fewer than the pad's 40 elements" in line
    assert "give a profile of at least 41 points at that spacing (0.0205 m), or &pad " \
        "length <= 0.019 m" in line
    # the lengths it names fit: the longest pad runs on the profile as given
    z = np.array([float(h) for h in HEIGHTS[:23]]) * 1e-3
    ds = pavefric.simulate(z, DX, [20.0], closed=False, element_length=0.5e-3, length=0.019,
                           error_estimate=False, min_contacts=0)
    assert int(ds.attrs["averaged_positions"]) >= 2


def test_one_averaged_position_of_a_long_stride_is_refused(tmp_path):
    """position_stride can leave an open profile one averaged position:
    refused too, naming it."""
    line = one_error(tmp_path, open_profile(tmp_path, HEIGHTS[:46],
                                            "&numerics position_stride = 40 /\n"))
    assert "stand on it at one averaged position only (&numerics position_stride = 40)" in line
    assert "give a profile of at least 63 points" in line and "a smaller position_stride" in line


def test_empty_and_all_dropout_profiles(tmp_path):
    line = one_error(tmp_path, with_profile(tmp_path, ["# nothing"]))
    assert "holds no heights (only comments or blank lines); give one height a line" in line
    line = one_error(tmp_path, with_profile(tmp_path, ["nan"] * 50,
                                            "&preprocess dropouts = 'interpolate' /\n"))
    assert "every height is a dropout" in line and "check the height column" in line


def test_uneven_plain_distances_can_be_resampled(tmp_path):
    """A two-column plain file's uneven step is preprocessing's to judge (as a
    table's), so the remedy the message gives, resample_dx, works."""
    rows, x = ["# distance_mm height_mm"], 0.0
    for i in range(200):
        x += 0.87 if i != 50 else 1.5
        rows.append(f"{x:.3f} {math.sin(i) * 0.5:.3f}")
    line = one_error(tmp_path, with_profile(tmp_path, rows))
    assert "p/x.txt:52: spacing 0.0015 m against the mean 0.0008732 m (more than 5 % off)" in line
    assert "resample it (&preprocess resample_dx)" in line
    scene = with_profile(tmp_path, rows, "&preprocess resample_dx = 0.001 /\n", name="y.txt")
    r = run_program(scene, "-q", "-o", tmp_path / "ok.nc")
    assert r.returncode == 0, r.stderr


def test_dx_against_the_file(tmp_path):
    rows = [f"{i * 0.87:.2f} {math.sin(i) * 0.5:.3f}" for i in range(200)]
    p = profile_file(tmp_path, "withx.txt", rows)
    scene = scene_text(tmp_path, f"&surface profile_file = 'p/{p.name}', dx = 1e-3 /\n"
                                 "&operation speeds_kmh = 10 /\n")
    line = one_error(tmp_path, scene)
    assert "&surface dx = 0.001: disagrees (by more than 1 %) with the spacing" in line
    assert "remove dx to take the file's spacing, or correct it" in line


@pytest.mark.parametrize("fmt,needles", [
    ("captif", ["no '*****DATA*****' line, so not a laser profiler export",
                "set &surface format = 'auto'"]),
    ("netcdf", ["cannot open as NetCDF", "a text profile? set &surface format = 'auto'"]),
])
def test_format_mismatch(tmp_path, fmt, needles):
    p = profile_file(tmp_path, "t.txt", HEIGHTS)
    scene = scene_text(tmp_path, f"&surface profile_file = 'p/{p.name}', format = '{fmt}' /\n"
                                 "&operation speeds_kmh = 10 /\n")
    line = one_error(tmp_path, scene)
    for needle in needles:
        assert needle in line, (needle, line)


def test_batch_pattern_that_matches_nothing(tmp_path):
    scene = scene_text(tmp_path, "&batch profiles = 'nomatch/*.txt' /\n"
                                 "&operation speeds_kmh = 10 /\n")
    line = one_error(tmp_path, scene)
    # the pattern as the program read it: relative to the scene's directory
    assert f"&batch profiles = '{tmp_path}/nomatch/*.txt': matches no file; check the " \
           "pattern, or give a directory or &batch profile_list" in line


def test_short_profile_under_the_low_pass_filter(tmp_path):
    line = one_error(tmp_path, with_profile(tmp_path, HEIGHTS[:8],
                                            "&preprocess lowpass_wavelength = 0.0024 /\n"))
    assert "&preprocess lowpass_wavelength: the low-pass filter needs more than" in line
    assert "give a longer profile, or lowpass_wavelength = 0 (off)" in line


# --- Python -----------------------------------------------------------------

def test_python_names_the_keyword_it_was_given(profile_m):
    with pytest.raises(pavefric.PavefricError) as e:
        pavefric.simulate(profile_m, DX, [10.0], water_viscosity=0.0)
    assert str(e.value).startswith("water_viscosity = 0 (&water viscosity): must be finite")
    with pytest.raises(pavefric.PavefricError) as e:
        pavefric.simulate(profile_m, DX, [10.0], rubber_model="prony")
    assert str(e.value).startswith("rubber_model = 'prony' (&rubber model): unknown")
    # a keyword that is its namelist name keeps the namelist's words
    with pytest.raises(pavefric.PavefricError) as e:
        pavefric.simulate(profile_m, DX, [10.0], depth=-1.0)
    assert str(e.value).startswith("&water depth = -1: must be finite and >= 0")


def test_python_empty_inputs(profile_m):
    with pytest.raises(pavefric.PavefricError, match=r"^heights: an empty array; give the "):
        pavefric.simulate([], DX, [10.0])
    with pytest.raises(pavefric.PavefricError, match=r"^speeds_kmh = \[\]: give at least one"):
        pavefric.simulate(profile_m, DX, [])
    z = np.array(profile_m, dtype=float)
    z[5] = np.nan
    with pytest.raises(pavefric.PavefricError, match=r"profile height 6 = NaN: heights must "
                                                      r"be finite; fill or remove the dropouts"):
        pavefric.simulate(z, DX, [10.0])


def command(*args, cwd=None):
    return subprocess.run([sys.executable, "-m", "pavefric", *map(str, args)],
                          capture_output=True, text=True, timeout=300, cwd=cwd)


@pytest.mark.parametrize("args,needles", [
    (["plot", "nothere.nc", "-o", "x.png"], ["plot: 'nothere.nc': no such file (give NetCDF "
                                             "outputs of pavefric runs)"]),
    (["plot", "s.nml", "-o", "x.png"], ["plot: cannot read", "give NetCDF outputs"]),
    (["prony", "nothere.csv"], ["nothere.csv: no such DMA CSV file", "--write-representative"]),
    (["surface", "-o", "s.txt", "--points", "2"], ["surface --points 2: must be >= 4"]),
    (["surface", "-o", "s.txt", "--points", "16", "--wavelength-min-mm", "1.8",
      "--wavelength-max-mm", "1.9"], ["no Fourier mode", "--points 16",
                                      "widen the band of wavelengths or give more --points"]),
])
def test_python_commands_give_one_line_not_a_traceback(tmp_path, args, needles):
    (tmp_path / "s.nml").write_text(BASE)
    r = command(*args, cwd=tmp_path)
    assert r.returncode == 1, r.stderr
    assert "Traceback" not in r.stderr
    line = r.stderr.strip()
    assert line.startswith("pavefric: error: ") and len(line.splitlines()) == 1, r.stderr
    for needle in needles:
        assert needle in line, (needle, line)


def test_prony_messages_name_the_line_and_the_options(tmp_path):
    from conftest import ROOT

    rows = [ln for ln in (ROOT / "inputs" / "data" / "tread_compound_dma.csv").read_text()
            .splitlines() if not ln.startswith("#")]
    cells = rows[3].split(",")
    header = [h.strip() for h in rows[0].split(",")]
    cells[header.index("storage_pa")] = "nan"
    bad = tmp_path / "dma_nan.csv"
    bad.write_text("\n".join(rows[:3] + [",".join(cells)] + rows[4:]) + "\n")
    r = command("prony", bad)
    assert r.returncode == 1 and "Traceback" not in r.stderr
    assert f"{bad}:4: storage_pa = 'nan' is not finite; give finite numbers" in r.stderr
    good = tmp_path / "dma.csv"
    good.write_text("\n".join(rows) + "\n")
    r = command("prony", good, "--c2", "5")
    assert r.returncode == 1 and "Traceback" not in r.stderr
    assert "where the WLF equation with C2 = 5 K diverges" in r.stderr
    assert "(prony --c2) or a lower reference temperature (--reference-temperature)" in r.stderr
    r = command("prony", good, "--per-decade", "0")
    assert "per_decade = 0 (prony --per-decade): must be > 0" in r.stderr


def test_calibration_with_more_parameters_than_data(tmp_path):
    from conftest import ROOT

    data = tmp_path / "meas.csv"
    data.write_text("surface,speed_kmh,mu\nGSSB,20,0.5\nGSSB,40,0.45\n")
    r = command("calibrate", data, "--scenes", ROOT / "inputs" / "surfaces", "--fit", "alpha",
                "beta", "viscosity")
    assert r.returncode != 0 and "Traceback" not in r.stderr
    assert "--fit gives 3 parameters (alpha, beta, viscosity) but the data hold 2 " \
           "measurement(s): fit at most 2, or add measurements" in r.stderr


# From an attack on 2026-12-06 (its reproducers, each a test)

def test_a_pad_shorter_than_half_its_element_length_is_named(tmp_path):
    """&pad element_length more than twice &pad length gave a pad of 0
    elements and the short-profile message ("fewer than the pad's 0
    elements ... give a profile of at least 0 points"). Now the message
    names the pad's length and what set the element's."""
    profile_file(tmp_path, "ok.txt", HEIGHTS)
    line = one_error(tmp_path, scene_text(
        tmp_path, BASE + "&pad length = 0.02, element_length = 0.041 /\n"))
    assert "&pad length = 0.02 m is less than half an element" in line, line
    assert "&pad element_length = 0.041 m" in line and "no element" in line, line
    assert "0 points" not in line and "0 elements" not in line, line
    # no resampling: the profile's own spacing made the element
    line = one_error(tmp_path, scene_text(
        tmp_path, "&surface profile_file = 'p/ok.txt', dx = 0.05 /\n&operation speeds_kmh = 10 /\n"
        "&pad length = 0.02, element_length = 0 /\n", name="t.nml"))
    assert "&pad length = 0.02 m is less than half an element" in line, line
    assert "the profile's spacing dx = 0.05 m" in line, line


def test_an_element_longer_than_the_pad_warns(profile_m):
    """element_length between &pad length and twice it made a pad of one
    element longer than the pad given, with no word of it."""
    with pytest.warns(pavefric.PavefricWarning, match="element_length = 0.03 m is longer than "
                      "&pad length = 0.02 m: the pad is one element"):
        ds = pavefric.simulate(profile_m, 0.87e-3, [20.0], element_length=0.03,
                               error_estimate=False)
    assert int(ds.attrs["pad_elements"]) == 1


def test_a_needlessly_fine_element_length_warns_and_its_memory_refusal_names_it(tmp_path):
    """element_length = 1e-9 m (inside its range, no warning) was refused
    for memory with a message naming elements_per_sample, substeps and
    series (all at their defaults); 1e-6 m ran a 1448 s estimate with no
    warning. Below 1e-5 m (finer than profilometers sample) it warns, and
    the refusal names &pad element_length."""
    profile_file(tmp_path, "ok.txt", [f"{math.sin(i) * 0.5:.3f}" for i in range(1024)])
    # (ten speeds with series: beyond any machine's memory)
    line = one_error(tmp_path, scene_text(
        tmp_path, "&surface profile_file = 'p/ok.txt' /\n&operation speeds_kmh = 10, 20, 30, "
        "40, 50, 60, 70, 80, 90, 100 /\n&output series = .true. /\n"
        "&pad element_length = 1e-9 /\n"))
    assert "a longer &pad element_length (now 1e-9 m)" in line, line
    assert "&output series = .false." in line, line
    assert "elements_per_sample" not in line and "substeps" not in line, line
    z = np.sin(np.arange(32) * 0.7) * 0.5e-3
    with pytest.warns(pavefric.PavefricWarning, match=r"element_length = 5e-6 m: finer than "
                      r"0.00001 m.*the pad has 4000 elements"):
        pavefric.simulate(z, 0.87e-3, [20.0], element_length=5e-6, error_estimate=False,
                          min_contacts=0)


def test_a_height_beyond_any_road_names_its_file_and_line(tmp_path):
    """A height of 1e300 mm was refused as "profile height 499 = 1e297 m"
    (an index, not the line, and no file); every other error in a profile's
    contents names file:line."""
    line = one_error(tmp_path, with_profile(tmp_path, ["height_mm"] + HEIGHTS[:98] + ["1e300"]
                                            + HEIGHTS[:10]))
    assert "x.txt:100: height 1e297 m: beyond +-1e6 m, not a texture" in line, line
    # read_profile shows what the file holds: the run refuses it
    p = pavefric.read_profile(tmp_path / "p" / "x.txt", trim_plates=False)
    assert p.raw_heights[98] == 1e297


def test_a_stride_that_does_not_close_the_lap_is_named():
    """A closed profile's positions at a position_stride that does not
    divide its points do not close the lap: with mu_loc = 0 mu came out
    negative (-4.8e-5) with only the generic negative-hysteresis warning."""
    z = np.random.default_rng(5).normal(0, 3e-4, 512)
    with pytest.warns(pavefric.PavefricWarning, match=r"position_stride = 7 does not divide "
                      r"the 512 points.*74 positions do not close the lap \(they run 6 points"):
        ds = pavefric.simulate(z, 0.87e-3, [0.01], closed=True, mu_loc=0.0, position_stride=7)
    assert ds["mu"].values[0] < 0
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ds = pavefric.simulate(z, 0.87e-3, [0.01], closed=True, mu_loc=0.0, position_stride=8)
    assert ds["mu"].values[0] >= 0
