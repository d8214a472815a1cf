"""Strict profile reading (issue 10): every token is a number or an error
naming file and line, units stated in CSV headers are read exactly, only
regular text files are read, reading is linear, and preprocessing bounds its
memory before allocating. Each reproducer of the issue is a test here."""
import math
import os
import random
import resource
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import pavefric
from conftest import CAPTIF, program, run_program, write_scene

BODY = [f"{0.5 * math.sin(0.3 * k):.6f}" for k in range(60)]      # mm


def plain(tmp_path, lines, name="p.txt", header="height_mm"):
    path = tmp_path / name
    path.write_text(((header + "\n") if header else "") + "\n".join(lines) + "\n")
    return path


def csv(tmp_path, header, rows, name="p.csv"):
    path = tmp_path / name
    path.write_text(header + "\n" + "\n".join(rows) + "\n", encoding="utf-8")
    return path


def captif_file(tmp_path, depths, name="p.dat"):
    """A laser profiler export in the shape of inputs/data/captif (CRLF, tabs)."""
    head = ["Road Name\tCAPTIF\t", "Ref Station\t0\t", "*****DATA*****\t\t",
            "Data Point No:\tDistance (mm)\tDepth (mm)"]
    rows = [f"{k + 1}.000\t{k * 0.5:.3f}\t{d}" for k, d in enumerate(depths)]
    path = tmp_path / name
    path.write_bytes(("\r\n".join(head + rows) + "\r\n").encode())
    return path


def rejected(path, *needles, **kw):
    with pytest.raises(pavefric.PavefricError) as info:
        pavefric.read_profile(path, trim_plates=False, **kw)
    message = str(info.value)
    for needle in needles:
        assert needle in message, (needle, message)
    return message


# -- 1. one strict number grammar for every format ---------------------------

REPRODUCERS = ["1-3", "2.203-1", "1+2", "1.#INF", "1.#QNAN", "0x1p3", "1e", "--1", "1..2",
               "1,5e", "1.5.", "12#"]


@pytest.mark.parametrize("token", REPRODUCERS)
def test_plain_token_that_is_not_a_number_names_file_and_line(tmp_path, token):
    path = plain(tmp_path, BODY[:3] + [token] + BODY[3:])
    bad = token.split(",")[0] if token == "1,5e" else token     # ',' separates plain columns
    if token == "1,5e":
        rejected(path, "p.txt:5")
    else:
        rejected(path, "p.txt:5: '" + bad + "' is not a number")


@pytest.mark.parametrize("token", ["1-3", "2.203-1", "1+2", "1.#INF", "1.#QNAN"])
def test_program_refuses_the_issue_tokens(tmp_path, token):
    text = "height_mm\n" + "\n".join(BODY[:10] + [token] + BODY[10:]) + "\n"
    scene = write_scene(tmp_path, profile_text=text)
    r = run_program(scene, "-o", tmp_path / "o.nc")
    assert r.returncode == 1, r.stderr
    assert f"scene_profile.txt:12: '{token}' is not a number" in r.stderr
    assert not (tmp_path / "o.nc").exists()


@pytest.mark.parametrize("token", ["1-3", "2.203-1", "1+2", "1.#INF", "1.#QNAN", "1.5 mm"])
def test_csv_height_that_is_not_a_number(tmp_path, token):
    rows = [f"{0.5 * k},{v}" for k, v in enumerate(BODY)]
    rows[7] = f"3.5,{token}"
    path = csv(tmp_path, "distance (mm),height (mm)", rows)
    rejected(path, f"p.csv:9: height '{token}' is not a number")


@pytest.mark.parametrize("token", ["1-3", "1.#INF", "1+2"])
def test_csv_distance_that_is_not_a_number(tmp_path, token):
    rows = [f"{0.5 * k},{v}" for k, v in enumerate(BODY)]
    rows[4] = f"{token},0.1"
    path = csv(tmp_path, "distance (mm),height (mm)", rows)
    rejected(path, f"p.csv:6: distance '{token}' is not a number")


@pytest.mark.parametrize("token", ["1-3", "2.203-1", "1+2", "1.#INF", "1.#QNAN"])
def test_laser_export_depth_that_is_not_a_number(tmp_path, token):
    depths = BODY[:5] + [token] + BODY[5:]
    path = captif_file(tmp_path, depths)
    rejected(path, f"p.dat:10: height '{token}' is not a number")


def test_laser_export_checks_every_field(tmp_path):
    path = captif_file(tmp_path, BODY)
    text = path.read_bytes().replace(b"3.000\t", b"3x000\t")
    path.write_bytes(text)
    rejected(path, "p.dat:7: point number '3x000' is not a number")
    path = captif_file(tmp_path, BODY)
    lines = path.read_bytes().split(b"\r\n")
    lines[8] += b"\t7"
    path.write_bytes(b"\r\n".join(lines))
    rejected(path, "p.dat:9: '7' beyond the three columns")
    lines[8] = lines[8][:-2] + b"\t\t"                 # empty trailing fields are fine
    path.write_bytes(b"\r\n".join(lines))
    assert pavefric.read_profile(path, trim_plates=False).report["points_read"] == len(BODY)


@pytest.mark.parametrize("token", ["inf", "-Infinity", "+INF", "1e999", "-2.5e400"])
@pytest.mark.parametrize("fmt", ["plain", "csv", "captif"])
def test_infinity_is_an_error_in_every_format(tmp_path, token, fmt):
    if fmt == "plain":
        path = plain(tmp_path, BODY[:3] + [token] + BODY[3:])
        where = "p.txt:5: "
    elif fmt == "csv":
        path = csv(tmp_path, "x_mm,z_mm", [f"{0.5 * k},{v}" for k, v in
                                            enumerate(BODY[:3] + [token] + BODY[3:])])
        where = "p.csv:5: height "
    else:
        path = captif_file(tmp_path, BODY[:3] + [token] + BODY[3:])
        where = "p.dat:8: height "
    rejected(path, where + f"'{token}' is not finite")


@pytest.mark.parametrize("token", ["nan", "NaN", "-nan", "NAN"])
@pytest.mark.parametrize("fmt", ["plain", "csv", "captif"])
def test_nan_stays_a_dropout_in_every_format(tmp_path, token, fmt):
    values = BODY[:3] + [token] + BODY[4:]
    if fmt == "plain":
        path = plain(tmp_path, values)
        line = 5
    elif fmt == "csv":
        path = csv(tmp_path, "distance,height", [f"{0.5 * k},{v}" for k, v in enumerate(values)])
        line = 5
    else:
        path = captif_file(tmp_path, values)
        line = 8
    rejected(path, f"{path.name}:{line}: dropout")
    p = pavefric.read_profile(path, trim_plates=False, dropouts="interpolate")
    assert p.report["dropouts"] == 1 and np.isnan(p.raw_heights[3])
    assert p.heights[3] == pytest.approx(0.5 * (p.heights[2] + p.heights[4]), abs=1e-9)


def test_numbers_are_the_correctly_rounded_doubles(tmp_path):
    """The fast conversion path and strtod give the bits of the correctly
    rounded value (Python's float) for every form the grammar allows."""
    rng = random.Random(13)
    tokens = ["0", "-0", "+0.0", "1", "-1.", ".5", "-.5", "0.1", "0.3", "1e0", "1E+3", "2.5d-3",
              "-7.25D2", "123456789012345678", "1234567890123456789012345", "9007199254740993",
              "0.000000000000000000000000000001", "4.9e-324", "2.2250738585072011e-308",
              "1.7976931348623157e308", "1e-400", "8.98846567431158e307", "1e22", "1e23",
              "0.1e-22", "12345678901234567890e-30", "0." + "1" * 600,
              "2.675", "1.0000000000000002", "0.30000000000000004", "5e-324"]
    for _ in range(3000):
        mant = "".join(rng.choice("0123456789") for _ in range(rng.randint(1, 21)))
        point = rng.randint(0, len(mant))
        tok = mant[:point] + "." + mant[point:] if rng.random() < 0.8 else mant
        if rng.random() < 0.5:
            tok += rng.choice("eEdD") + rng.choice(["", "+", "-"]) + str(rng.randint(0, 40))
        tokens.append(rng.choice(["", "-", "+"]) + tok)
    path = plain(tmp_path, tokens, header="")
    p = pavefric.read_profile(path, "m", trim_plates=False)
    expected = np.array([float(t.replace("d", "e").replace("D", "e")) for t in tokens])
    assert p.raw_heights.view(np.int64).tolist() == expected.view(np.int64).tolist()


def test_laser_export_values_are_the_correctly_rounded_doubles():
    path = CAPTIF / "20211011_aylesbury_dec_station_0.dat"
    p = pavefric.read_profile(path, trim_plates=False, dropouts="interpolate")
    rows = [line.split("\t") for line in path.read_text().splitlines()]
    start = next(k for k, r in enumerate(rows) if r[0].startswith("*****DATA*****")) + 2
    x = np.array([float(r[1]) * 1e-3 for r in rows[start:]])
    z = np.array([float(r[2]) * 1e-3 if r[2] not in ("", "NaN") else np.nan
                  for r in rows[start:]])
    assert np.array_equal(p.raw_x, x)
    assert np.array_equal(p.raw_heights, z, equal_nan=True)


# -- comments and headers ----------------------------------------------------

def test_comment_rule_plain(tmp_path):
    path = plain(tmp_path, ["# a comment line", "  # an indented one", "0.1 # after a blank",
                            "0.2\t# after a tab", "0.3,# after a comma", "0.4;#semicolon",
                            "#0.9 commented out"] + BODY[:20])
    p = pavefric.read_profile(path, trim_plates=False)
    np.testing.assert_array_equal(p.raw_heights[:4], np.array([0.1, 0.2, 0.3, 0.4]) * 1e-3)
    assert p.report["points_read"] == 24
    rejected(plain(tmp_path, BODY[:3] + ["0.5#glued"] + BODY[3:], "g.txt"),
             "g.txt:5: '0.5#glued' is not a number")


def test_comment_rule_csv_is_whole_lines(tmp_path):
    rows = ["# a comment", "0,0.1", "  # indented comment", "0.5,0.2,# a third field is text",
            "1.0,0.3 # not a comment"]
    path = csv(tmp_path, "distance,height", rows)
    rejected(path, "p.csv:6: height '0.3 # not a comment' is not a number")


@pytest.mark.parametrize("first", ["0.1x", "12..5", "1.0.0", "-.5e", ".", "+", "1O.5", "0.5."])
def test_a_typo_in_the_first_data_line_is_an_error_not_a_header(tmp_path, first):
    path = plain(tmp_path, [first] + BODY, header="")
    message = rejected(path, "p.txt:1: '")
    assert "is not a number" in message


def test_headers_that_are_names_are_skipped(tmp_path):
    for header in ["height_mm", "distance height", "x (mm)\tz (mm)", "Height", "z"]:
        cols = 2 if header in ("distance height", "x (mm)\tz (mm)") else 1
        lines = [f"{0.5 * k} {v}" if cols == 2 else v for k, v in enumerate(BODY)]
        path = plain(tmp_path, lines, header=header)
        p = pavefric.read_profile(path, trim_plates=False)
        assert p.report["points_read"] == len(BODY)
    # only the first non-comment line can be a header
    path = plain(tmp_path, ["# comment", "height_mm", "depth_mm"] + BODY, header="")
    rejected(path, "p.txt:3: 'depth_mm' is not a number")


def test_byte_order_mark_is_not_a_header(tmp_path):
    path = tmp_path / "bom.txt"
    path.write_text("\ufeff" + "\n".join(BODY) + "\n", encoding="utf-8")
    p = pavefric.read_profile(path, trim_plates=False)
    assert p.report["points_read"] == len(BODY)
    assert p.raw_heights[0] == float(BODY[0]) * 1e-3


# -- 2. CSV units --------------------------------------------------------------

def test_one_letter_height_column_is_in_height_unit(tmp_path):
    """Issue 10: header 'n,z' with data in mm was read in metres."""
    rows = [f"{k},{v}" for k, v in enumerate(BODY)]
    path = csv(tmp_path, "n,z", rows)
    p = pavefric.read_profile(path, "mm", trim_plates=False)
    assert np.array_equal(p.raw_heights, np.array([float(v) * 1e-3 for v in BODY]))


def test_one_letter_column_gives_the_friction_of_the_plain_file(tmp_path):
    z = np.sin(np.arange(256) * 0.3) * 0.5
    (tmp_path / "a.csv").write_text("n,z\n" + "\n".join(f"{k},{v:.6f}" for k, v in
                                                         enumerate(z)) + "\n")
    (tmp_path / "b.txt").write_text("height_mm\n" + "\n".join(f"{v:.6f}" for v in z) + "\n")
    mus = []
    for name in ("a.csv", "b.txt"):
        scene = write_scene(tmp_path, name.split(".")[0],
                            groups={"surface": f"profile_file = '{name}', mu_loc = 0.5, "
                                               "height_unit = 'mm'"})
        r = run_program(scene, "-o", tmp_path / (name + ".nc"))
        assert r.returncode == 0, r.stderr
        import xarray as xr
        with xr.open_dataset(tmp_path / (name + ".nc")) as ds:
            mus.append(ds["mu"].values.copy())
    assert np.array_equal(mus[0], mus[1])
    assert 0.3 < mus[0][0] < 1.5


@pytest.mark.parametrize("header,factor", [
    ("n,Height (\u00b5m)", 1e-6),      # micro sign, UTF-8
    ("n,Height (\u03bcm)", 1e-6),      # Greek mu, UTF-8
    ("n,height [um]", 1e-6),
    ("n,height_um", 1e-6),
    ("n,Height (mm)", 1e-3),
    ("n,height[MM]", 1e-3),
    ("n,z_mm", 1e-3),
    ("n,Height (m)", 1.0),
    ("n,height_m", 1.0),
    ("n,z", 1e-3),                     # no unit: height_unit ('mm')
    ("n,height_left", 1e-3),           # a suffix that is not a unit: no unit
    ("n,Height ( micrometres )", 1e-6),
])
def test_units_in_csv_headers(tmp_path, header, factor):
    path = csv(tmp_path, header, [f"{k},{v}" for k, v in enumerate(BODY)])
    p = pavefric.read_profile(path, "mm", trim_plates=False)
    assert np.array_equal(p.raw_heights, np.array([float(v) * factor for v in BODY]))


@pytest.mark.parametrize("header,bad", [
    ("n,Height (inches)", "inches"),
    ("n,Height (left wheel path)", "left wheel path"),
    ("distance (ft),height (mm)", "ft"),
    ("n,height [mm", "[mm"),
])
def test_unknown_unit_in_brackets_is_an_error(tmp_path, header, bad):
    path = csv(tmp_path, header, [f"{k},{v}" for k, v in enumerate(BODY)])
    message = rejected(path, "p.csv:1: column '", f"unknown unit '{bad}'")
    assert "expected m, mm, um" in message


def test_unused_columns_may_have_any_name(tmp_path):
    path = csv(tmp_path, "quality (%),distance (mm),height (mm)",
               [f"ok,{0.5 * k},{v}" for k, v in enumerate(BODY)])
    p = pavefric.read_profile(path, trim_plates=False)
    assert p.report["points_read"] == len(BODY) and p.dx == pytest.approx(0.5e-3)


# -- 3. hangs, binary content, linear reading ------------------------------------

def run_python(code, timeout=60, limit_bytes=None):
    def limit():
        if limit_bytes:
            resource.setrlimit(resource.RLIMIT_AS, (limit_bytes, limit_bytes))
    return subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True,
                          text=True, timeout=timeout, preexec_fn=limit)


@pytest.mark.parametrize("device", ["/dev/zero", "/dev/urandom", "/dev/null"])
def test_devices_are_refused(tmp_path, device):
    scene = write_scene(tmp_path, groups={"surface": f"profile_file = '{device}'"})
    r = subprocess.run([program(), str(scene), "-o", str(tmp_path / "o.nc")],
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 1
    assert f"&surface profile_file = '{device}': a character device, not a regular file" \
        in r.stderr
    r = run_python(f"import pavefric\ntry:\n    pavefric.read_profile({device!r})\n"
                   "except pavefric.PavefricError as e:\n    print(e)\n")
    assert "not a regular file" in r.stdout, r.stderr


def test_fifo_and_directory_are_refused(tmp_path):
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    (tmp_path / "adir").mkdir()
    for target, what in ((fifo, "a FIFO"), (tmp_path / "adir", "a directory")):
        scene = write_scene(tmp_path, groups={"surface": f"profile_file = '{target.name}'"})
        r = subprocess.run([program(), str(scene), "-o", str(tmp_path / "o.nc")],
                           capture_output=True, text=True, timeout=60)
        assert r.returncode == 1
        assert f"'{target}': {what}" in r.stderr and "not a regular file" in r.stderr


def test_binary_content_names_file_and_line(tmp_path):
    path = tmp_path / "bin.txt"
    path.write_bytes(("\n".join(BODY[:6]) + "\n").encode() + b"0.1\x00\x07\xff\n" +
                     ("\n".join(BODY) + "\n").encode())
    rejected(path, "bin.txt:7: binary content (a NUL byte)")
    path.write_bytes(b"height_mm\n0.1\n0.2 # \x00 in a comment\n0.3\n")
    rejected(path, "bin.txt:3: binary content")
    path.write_bytes(os.urandom(4096).replace(b"\x00", b"\x01") + b"\x00")
    with pytest.raises(pavefric.PavefricError):
        pavefric.read_profile(path)


def test_one_line_of_sixteen_megabytes_is_read_in_one_pass(tmp_path):
    """Issue 10: a 4 MB line took 31 s (quadratic). A guard against a hang,
    not a timing assertion: the read takes well under a second; the old
    reader needed minutes for this line."""
    path = tmp_path / "long.txt"
    path.write_text("0.25" + " " * 16_000_000 + "0.5\n0.75 1.0\n")
    r = run_python(f"""
        import pavefric
        p = pavefric.read_profile({str(path)!r}, trim_plates=False)
        print(p.report["points_read"], p.raw_x[0], p.raw_heights[1])
    """, timeout=120)
    assert r.returncode == 0, r.stderr
    assert r.stdout.split() == ["2", "0.00025", "0.001"]


# -- 4. bounded memory -------------------------------------------------------------

def test_resampling_finer_than_the_data_fails_before_allocating(tmp_path):
    """Issue 10: resample_dx = 1e-9 allocated 3 x 8.9e8 elements before any
    check. Under a 2 GB address-space limit the program now fails cleanly."""
    scene = write_scene(tmp_path, groups={"preprocess": "resample_dx = 1e-9"})
    two_gb = 2 * 1024 ** 3

    def limit():
        resource.setrlimit(resource.RLIMIT_AS, (two_gb, two_gb))
    r = subprocess.run([program(), str(scene), "-o", str(tmp_path / "o.nc")], capture_output=True,
                       text=True, timeout=120, preexec_fn=limit)
    assert r.returncode == 1, r.stderr
    assert "&preprocess resample_dx = 1e-9: finer than the data's spacing" in r.stderr
    with pytest.raises(pavefric.PavefricError, match="resample_dx = 1e-9"):
        pavefric.read_profile(tmp_path / "scene_profile.txt", resample_dx=1e-9)


def test_out_of_memory_while_reading_is_a_memory_error(tmp_path):
    """An allocation that fails while reading is an error with the memory
    status (MemoryError in Python, exit 1 with the message from the
    program), never an abort of the process."""
    path = tmp_path / "big.txt"
    with open(path, "w") as fh:
        fh.write("height_mm\n")
        fh.write("0.125\n" * 8_000_000)                       # 48 MB, 8e6 points
    code = f"""
        import resource, pavefric
        with open("/proc/self/status") as fh:
            vm = [int(l.split()[1]) * 1024 for l in fh if l.startswith("VmSize")][0]
        limit = vm + 100 * 1024 ** 2       # the 48 MB file fits, its 8e6 points do not
        resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
        try:
            pavefric.read_profile({str(path)!r}, trim_plates=False)
            print("read")
        except MemoryError as e:
            print("MemoryError:", e)
    """
    r = run_python(code, timeout=300)
    assert r.returncode == 0, r.stderr
    assert r.stdout.startswith("MemoryError:") and "not enough memory" in r.stdout, r.stdout


# -- 5. a fuzz over profile text ------------------------------------------------------

def test_fuzz_profile_text_is_a_result_or_a_clean_error(tmp_path):
    """Any text: a finite profile or a PavefricError, never a crash, a hang
    or a non-finite height."""
    from hypothesis import HealthCheck, given, settings
    from hypothesis import strategies as st

    pieces = st.sampled_from(["0.1", "-2.5e-1", "nan", "inf", "1-3", "#", " ", "\t", ",", ";",
                              "\n", "\r\n", "x", "height_mm", "1.#INF", "\x00", "\ufeff", "e",
                              ".", "+", "3d2", "(mm)", "distance (mm)", "*****DATA*****",
                              "\u00b5m", "1e400", "0" * 30])
    counter = iter(range(10 ** 9))

    @settings(max_examples=300, deadline=None, suppress_health_check=list(HealthCheck))
    @given(st.lists(pieces, max_size=60), st.sampled_from(["auto", "plain", "csv", "captif"]))
    def check(parts, fmt):
        path = tmp_path / f"f{next(counter)}.txt"
        path.write_bytes("".join(parts).encode("utf-8"))
        try:
            p = pavefric.read_profile(path, format=fmt, trim_plates=False,
                                      dropouts="interpolate")
        except pavefric.PavefricError as e:
            assert str(e).strip()
            return
        assert np.all(np.isfinite(p.heights)) and p.heights.size > 0

    check()
