"""The installed library (issue 11): C and Fortran programs built outside the
source tree with the pkg-config flags of the pip install (the .venv of
setup.sh), bad input through the C API, program = Python = C API on every
output variable, and a `meson install --prefix` that puts the library,
header, .mod files and .pc file where pkg-config says."""
from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import pavefric
from conftest import ROOT, run_program

API = ROOT / "tests" / "api"
# the users' examples (examples/api/, with their build script); check_api.c stays here
EXAMPLES = ROOT / "examples" / "api"
BIN = Path(sys.executable).parent
WET = ROOT / "inputs" / "ctm_wet.nml"
CAPTIF = ROOT / "inputs" / "captif" / "station0.nml"
# the texture metrics: Python's simulate computes them without the
# instrument's quality flags (not part of the output table)
TEXTURE = {"mpd", "rms_height", "rms_slope"}
# the file's scalars, derived from the results and the texture (ASTM E1960):
# results of the C API too (since 2026-12-07)
SCALARS = TEXTURE | {"ifi_f60", "ifi_sp", "speed_constant"}


def _run(cmd, env=None, cwd=None, timeout=900) -> subprocess.CompletedProcess:
    proc = subprocess.run([str(c) for c in cmd], capture_output=True, text=True, env=env,
                          cwd=cwd, timeout=timeout)
    assert proc.returncode == 0, f"{' '.join(map(str, cmd))}\n{proc.stdout}\n{proc.stderr}"
    return proc


@pytest.fixture(scope="module")
def pc_env() -> dict:
    """The environment a user gets from `pavefric-config --pkgconfigdir`."""
    config = BIN / "pavefric-config"
    assert config.exists(), f"pavefric-config is not installed beside {sys.executable}"
    pcdir = _run([config, "--pkgconfigdir"]).stdout.strip()
    return dict(os.environ, PKG_CONFIG_PATH=pcdir, PATH=f"{BIN}{os.pathsep}{os.environ['PATH']}")


def pkg_config(env: dict, *args: str) -> list[str]:
    return _run(["pkg-config", *args, "pavefric"], env=env).stdout.split()


def build(tmp: Path, source: str, env: dict, *, static: bool = False) -> Path:
    """Copy examples/api/<source> (or tests/api/<source>) to tmp and build it
    there with pkg-config's flags."""
    tmp.mkdir(parents=True, exist_ok=True)
    src = tmp / source
    shutil.copy(EXAMPLES / source if (EXAMPLES / source).is_file() else API / source, src)
    exe = tmp / (src.stem + ("_static" if static else ""))
    flags = pkg_config(env, "--cflags") + pkg_config(env, *(["--static"] if static else []),
                                                     "--libs")
    if static:  # the archive, and its dependencies from Libs.private
        flags = ["-l:libpavefric.a" if f == "-lpavefric" else f for f in flags]
    compiler = "gfortran" if source.endswith(".f90") else "cc"
    extra = ["-lm", "-pthread"] if source == "check_api.c" else []
    _run([compiler, "-Wall", "-o", exe, src, *flags, *extra], env=env, cwd=tmp)
    return exe


def program_output(scene: Path, out: Path) -> xr.Dataset:
    proc = run_program(scene, "-o", out)
    assert proc.returncode == 0, proc.stderr
    return pavefric.open_dataset(out)


def printed_mu(stdout: str) -> tuple[list[float], list[float]]:
    """(speeds, mu) from the examples' 'S km/h: mu = M' lines."""
    rows = re.findall(r"^\s*(\S+) km/h: mu =\s*(\S+)\s*$", stdout, re.M)
    return [float(s) for s, _ in rows], [float(m) for _, m in rows]


def dumped(stdout: str) -> dict[str, np.ndarray]:
    """check_api dump's 'name n hex...' lines."""
    out = {}
    for line in stdout.splitlines():
        name, n, *values = line.split()
        assert len(values) == int(n), line
        out[name] = np.array([float.fromhex(v) for v in values])
    return out


def same_bits(a, b) -> bool:
    a = np.asarray(a, dtype=np.float64).ravel()
    b = np.asarray(b, dtype=np.float64).ravel()
    return a.shape == b.shape and a.tobytes() == b.tobytes()


# --- what pip installs, where pkg-config says -----------------------------------

def test_pavefric_config_points_at_the_installed_library(pc_env):
    pcdir = Path(pc_env["PKG_CONFIG_PATH"])
    assert (pcdir / "pavefric.pc").is_file()
    assert pcdir.is_relative_to(Path(pavefric.__file__).parent)   # inside the package
    assert pkg_config(pc_env, "--modversion") == [pavefric.__version__]
    libdir = Path(pkg_config(pc_env, "--variable=libdir")[0]).resolve()
    includedir = Path(pkg_config(pc_env, "--variable=includedir")[0]).resolve()
    moddir = Path(pkg_config(pc_env, "--variable=moddir")[0]).resolve()
    assert (libdir / "libpavefric.so").is_file() and (libdir / "libpavefric.a").is_file()
    assert (includedir / "pavefric.h").is_file()
    for module in ("pavefric", "pavefric_api", "pavefric_session", "pavefric_scene",
                   "pavefric_run", "pavefric_outputs", "pavefric_error", "pavefric_kinds"):
        assert (moddir / f"{module}.mod").is_file(), module
    cflags = pkg_config(pc_env, "--cflags")
    assert f"-I{includedir}" in [f"-I{Path(f[2:]).resolve()}" for f in cflags]
    assert f"-I{moddir}" in [f"-I{Path(f[2:]).resolve()}" for f in cflags]
    # the same answers from pavefric-config itself
    for option, path in (("--libdir", libdir), ("--includedir", includedir)):
        assert Path(_run([BIN / "pavefric-config", option]).stdout.strip()).resolve() == path
    assert _run([BIN / "pavefric-config", "--version"]).stdout.strip() == pavefric.__version__
    # the shared library carries its dependencies (a user links -lpavefric only)
    needed = _run(["readelf", "-d", libdir / "libpavefric.so"]).stdout
    for lib in ("libnetcdff", "liblapack", "libgfortran"):
        assert lib in needed, lib


def _stack_flags(path: Path) -> int | None:
    """The flags of an ELF file's PT_GNU_STACK program header (None if it
    has none: the stack is then executable on most targets)."""
    import struct

    data = path.read_bytes()
    assert data[:4] == b"\x7fELF", path
    wide, order = data[4] == 2, "<" if data[5] == 1 else ">"
    if wide:
        phoff, = struct.unpack_from(order + "Q", data, 0x20)
        phentsize, phnum = struct.unpack_from(order + "HH", data, 0x36)
    else:
        phoff, = struct.unpack_from(order + "I", data, 0x1C)
        phentsize, phnum = struct.unpack_from(order + "HH", data, 0x2A)
    for k in range(phnum):
        at = phoff + k * phentsize
        p_type, = struct.unpack_from(order + "I", data, at)
        if p_type == 0x6474E551:                      # PT_GNU_STACK
            return struct.unpack_from(order + "I", data, at + (4 if wide else 24))[0]
    return None


def test_nothing_installed_needs_an_executable_stack(pc_env):
    """The extension, the library and the program ask for a stack that is not
    executable. An internal procedure passed as an argument that reads its
    host's variables needs a trampoline, which marks the object as needing
    an executable stack; glibc 2.41 and later then refuse to load the
    library ("cannot enable executable stack"), so `import pavefric` failed
    on newer distributions (0.1.x: pavefric_simulate's error-estimate runner
    and the program's announce callback). The build now stops at one
    (-Werror=trampolines)."""
    libdir = Path(pkg_config(pc_env, "--variable=libdir")[0]).resolve()
    from pavefric import _core
    program = Path(pavefric.__file__).parent / "bin" / "pavefric"
    for path in (Path(_core.__file__), libdir / "libpavefric.so", program):
        flags = _stack_flags(path.resolve())
        assert flags is not None, f"{path}: no PT_GNU_STACK header"
        assert not flags & 0x1, f"{path}: needs an executable stack (flags {flags:#x})"


# --- must-show 2: C and Fortran outside the tree reproduce the program ----------

@pytest.mark.parametrize("scene", [WET, CAPTIF], ids=["ctm_wet", "captif_station0"])
def test_c_and_fortran_examples_reproduce_the_program(tmp_path, pc_env, scene):
    ref = program_output(scene, tmp_path / "program.nc")
    speeds, mu = ref["speed_kmh"].values, ref["mu"].values
    for source in ("example.c", "example.f90"):
        exe = build(tmp_path / source.replace(".", "_"), source, pc_env)
        proc = _run([exe, scene], cwd=tmp_path)
        got_speeds, got_mu = printed_mu(proc.stdout)
        assert got_speeds == list(speeds), source
        assert same_bits(got_mu, mu), (source, got_mu, list(mu))


def test_fortran_write_results_after_a_failed_run_is_an_error(tmp_path, pc_env):
    """An attack's reproducer (2026-12-07): write_results on the empty result
    of a run_profile that failed killed the host with SIGSEGV; it is an
    error naming the output, and nothing is written."""
    exe = build(tmp_path, "write_after_failed_run.f90", pc_env)
    (tmp_path / "short.txt").write_text("0.1\n0.2\n0.3\n")
    (tmp_path / "s.nml").write_text("&surface profile_file = 'short.txt' /\n"
                                    "&operation speeds_kmh = 20 /\n")
    proc = subprocess.run([exe], cwd=tmp_path, capture_output=True, text=True, timeout=60)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    lines = proc.stdout.splitlines()
    assert lines[0].startswith("run_profile error: &surface profile_file = 'short.txt'"), lines
    assert lines[1] == ("write_results error: &output file = 'out.nc': no results to write "
                        "(run first; the last run failed)"), lines
    assert not list(tmp_path.glob("out.nc*"))


def test_c_example_statically_linked(tmp_path, pc_env):
    """libpavefric.a with pkg-config --static: Libs.private is complete."""
    exe = build(tmp_path, "example.c", pc_env, static=True)
    assert "libpavefric" not in _run(["ldd", exe]).stdout
    ref = program_output(WET, tmp_path / "program.nc")
    _, mu = printed_mu(_run([exe, WET], cwd=tmp_path).stdout)
    assert same_bits(mu, ref["mu"].values)


def test_c_set_parameter_gives_the_programs_numbers(tmp_path, pc_env):
    """pavefric_set_parameter('water', 'depth', ...) = the program on a scene
    file saying that depth, bit for bit."""
    text = WET.read_text().replace("depth = 1.0e-3", "depth = 0.4e-3")
    text = text.replace("'profiles/ctm_medium.txt'", f"'{WET.parent / 'profiles/ctm_medium.txt'}'")
    scene = tmp_path / "wet_04.nml"
    scene.write_text(text)
    ref = program_output(scene, tmp_path / "program.nc")
    exe = build(tmp_path / "c", "example.c", pc_env)
    _, mu = printed_mu(_run([exe, WET, "0.4e-3", tmp_path / "c.nc"], cwd=tmp_path).stdout)
    assert same_bits(mu, ref["mu"].values)
    assert not same_bits(mu, program_output(WET, tmp_path / "wet.nc")["mu"].values)
    written = pavefric.open_dataset(tmp_path / "c.nc")
    assert written.attrs["param_water_depth"] == 0.4e-3
    assert "set through the API: &water depth = 0.4e-3 /" in written.attrs["input_namelist"]
    for name in ref.data_vars:
        assert same_bits(written[name].values, ref[name].values), name
    # one handle, many depths in turn: the last run is the program's at the
    # last depth, and the input echo keeps one line for the variable
    exe = build(tmp_path / "check", "check_api.c", pc_env)
    depths = ["0.1e-3", "0.2e-3", "1.5e-3", "0.4e-3"]
    out = _run([exe, "repeat", WET, tmp_path / "repeat.nc", *depths], cwd=tmp_path).stdout
    assert same_bits(dumped(out)["mu"], ref["mu"].values)
    echo = pavefric.open_dataset(tmp_path / "repeat.nc").attrs["input_namelist"]
    assert echo.count("set through the API") == 1
    assert echo.endswith("! set through the API: &water depth = 0.4e-3 /\n")


def test_c_typed_setters_give_the_programs_numbers(tmp_path, pc_env):
    """Issue 22: the typed setters (pavefric_set_parameter_double, _int,
    _bool, _text, _doubles) check a value against its declaration without
    namelist text and give the bits of the text setter and of the program on
    a scene file saying the same values; a bad value is an error naming the
    variable and leaves the scene as it was."""
    text = WET.read_text()
    for old, new in [("'profiles/ctm_medium.txt'", f"'{WET.parent / 'profiles/ctm_medium.txt'}'"),
                     ("mu_loc       = 0.6", "mu_loc = 0.45"), ("load = 11.8", "load = 40"),
                     ("depth = 1.0e-3", "depth = 2e-4, wet_model = 'squeeze'"),
                     ("speeds_kmh = 1, 5, 10, 20, 30, 40, 50, 60, 70, 80", "speeds_kmh = 10, 35.5, 70"),
                     ("series = .false.\n/", "series = .false.\n/\n&numerics substeps = 2, "
                                             "error_estimate = .false. /")]:
        assert old in text, old
        text = text.replace(old, new)
    scene = tmp_path / "changed.nml"
    scene.write_text(text)
    exe = build(tmp_path / "check", "check_api.c", pc_env)
    out = _run([exe, "typed", WET], cwd=tmp_path).stdout
    mus = {m.group(1): [float.fromhex(v) for v in m.group(2).split()]
           for m in re.finditer(r"^(text|typed|after) mu 3 (.*)$", out, re.M)}
    assert set(mus) == {"text", "typed", "after"}, out
    assert mus["typed"] == mus["text"] == mus["after"]
    for line in re.findall(r"^get .*$", out, re.M):
        a, b = re.match(r"get \S+ \S+: text=(.*) typed=(.*)$", line).groups()
        assert a == b, line
    errors = dict(re.findall(r"^case (\S+): check=1 status=\d+ length=\d+ message=(.*)$", out, re.M))
    expected = {
        "negative_depth": "&water depth = -1: must be finite and >= 0",
        "nan_depth": "&water depth = NaN: must be finite",
        "infinite_depth": "&water depth = Infinity: must be finite",
        "zero_substeps": "&numerics substeps = 0: must lie in [1, 4096]",
        "real_for_integer": "&numerics substeps: a whole number is expected, not a real number",
        "unknown_choice": "&water wet_model = 'reynolds2': unknown (expected 'kane2017', 'squeeze' or 'reynolds')",
        "text_for_real": "&water depth: a real number is expected, not a text",
        "bool_two": "&numerics error_estimate = 2: must be 1 (.true.) or 0 (.false.)",
        "negative_speed": "&operation speeds_kmh(2) = -5: must be finite and >= 0",
        "negative_count": "pavefric_set_parameter_doubles: n = -1: must be >= 0",
        # attack 2026-11-28: an emptied list was "not given in 'scene.nml'", and a
        # scene given as text without speeds named a file ''
        "empty_speeds": "&operation speeds_kmh: an empty list (0 values), but the variable is "
                        "required",
        "text_without_speeds": "&operation speeds_kmh: not given in the scene text",
        "unknown_variable": "&water no_such: unknown variable",
        "null_group": "pavefric_set_parameter_double: the group is NULL",
        "across_variables": "&numerics substeps = 4096 with tolerance = 0.001",
    }
    assert set(errors) == set(expected), out
    for case, fragment in expected.items():
        assert fragment in errors[case], (case, errors[case])
    # the same values from a scene file, through the program
    ref = program_output(scene, tmp_path / "program.nc")
    assert same_bits(mus["typed"], ref["mu"].values)


# --- bad input through the C API: the error is set, the process goes on ---------

def test_c_api_bad_input_sets_the_error_and_goes_on(tmp_path, pc_env):
    exe = build(tmp_path, "check_api.c", pc_env)
    proc = _run([exe, "bad", WET], cwd=tmp_path)
    cases = {}
    for m in re.finditer(r"^case (\w+): check=(\d) status=(-?\d) length=(\d+) message=(.*)$",
                         proc.stdout, re.M):
        name, check, status, length, message = m.groups()
        cases[name] = (int(check), int(status), int(length), message)
    failing = {k: v for k, v in cases.items() if k not in ("good_load", "good_run")}
    for name, (check, status, length, message) in failing.items():
        # bad input is stat_input (1); a file that cannot be written is stat_io (4)
        expected = 4 if name == "unwritable_output" else 1
        assert check == 1 and status == expected and length == len(message) > 0, name
    assert cases["good_load"][0] == 0 and cases["good_run"][0] == 0
    msg = {k: v[3] for k, v in cases.items()}
    assert msg["nan_height"] == "profile height 3 = NaN: heights must be finite numbers (m)"
    assert "'no/such/dir/missing.nml'" in msg["missing_scene"]
    assert msg["missing_scene"].startswith("scene file: cannot open")
    assert "missing_scene_handle_null: 1" in proc.stdout
    # the program's reader and its messages
    assert msg["negative_depth"] == "&water depth = -0.001: must be finite and >= 0 and <= 100 m"
    assert msg["unknown_variable"].startswith("&water deep = 1e-3: unknown variable (known: wet_model depth")
    assert msg["unknown_group"].startswith("&sea: unknown namelist group")
    assert "one variable" in msg["two_assignments"]
    assert msg["not_a_number"].startswith("&rubber stiffness = 1.4e8x: not a number (write one "
                                          "such as 0.5, 1e-3 or 2.5d3); must be finite and >= 1")
    assert msg["radius_too_small"] == "&pad radius = 0.001: must exceed half the pad length (0.01 m)"
    assert msg["infinite_dx"].startswith("&surface dx = Infinity: must be finite and > 0")
    assert "depth_unchanged: 0.001" in proc.stdout          # a failed set changes nothing
    assert "NULL handle" in msg["null_scene"] and "NULL" in msg["null_path"]
    assert "null_error_handle: check=2 load=1" in proc.stdout
    assert "run first" in msg["result_before_run"] and "run first" in msg["write_before_run"]
    assert "unknown_result_size: -1" in proc.stdout and "no such variable" in msg["unknown_result"]
    assert "blank_result_size: -1" in proc.stdout
    assert "the name 'mpd ' begins or ends with a blank" in msg["blank_result"]
    assert "the name 'depth ' begins or ends with a blank" in msg["blank_parameter"]
    assert msg["small_array"] == "result 'mu': 10 values, room for 1 given"
    assert "'no/such/dir/out.nc' failed (No such file or directory)" in msg["unwritable_output"]
    # a too small buffer: 7 bytes and the NUL; the length says how much room
    assert f"small_buffer: '&water ' nul=1 length={len(msg['negative_depth'])}" in proc.stdout
    # and the process went on to the program's numbers
    ref = program_output(WET, tmp_path / "program.nc")
    mu0 = re.search(r"^continued: speeds=10 mu0=(\S+)$", proc.stdout, re.M).group(1)
    assert float.fromhex(mu0) == ref["mu"].values[0]
    assert "version: 100" in proc.stdout                     # 0.1.0


def test_c_api_handles_are_independent_across_threads(tmp_path, pc_env):
    exe = build(tmp_path, "check_api.c", pc_env)
    depths = ["0.0", "0.2e-3", "0.5e-3", "1.0e-3"]
    out = _run([exe, "threads", WET, *depths], cwd=tmp_path).stdout
    assert out.count(": same ") == len(depths), out
    ref = program_output(WET, tmp_path / "program.nc")
    last = re.search(r"^depth 1.0e-3: same mu0=(\S+)$", out, re.M).group(1)
    assert float.fromhex(last) == ref["mu"].values[0]


# --- must-show 3: program = Python = C API on every output variable -------------

def _series_scene(tmp_path: Path) -> Path:
    text = WET.read_text().replace("series = .false.", "series = .true.")
    text = text.replace("'profiles/ctm_medium.txt'", f"'{WET.parent / 'profiles/ctm_medium.txt'}'")
    scene = tmp_path / "ctm_wet_series.nml"
    scene.write_text(text)
    return scene


@pytest.mark.parametrize("which", ["ctm_wet_series", "captif_station0"])
def test_program_python_and_c_agree_on_every_output_variable(tmp_path, pc_env, which):
    scene = _series_scene(tmp_path) if which == "ctm_wet_series" else CAPTIF
    ref = program_output(scene, tmp_path / "program.nc")
    names = [*ref.coords, *ref.data_vars]
    assert {"speed", "speed_kmh", "mu", "wet_fraction"} <= set(names)
    if which == "ctm_wet_series":
        assert {"position", "mu_inst", "hydro_load", "penetration",
                "contact_elements"} <= set(names)

    # Python: the scene through the core's readers, and simulate on its arrays
    sc = pavefric.load_scene(scene)
    from_scene = sc.simulate()
    from_arrays = pavefric.simulate(sc.heights, sc.dx, sc.speeds_kmh, closed=sc.closed,
                                    series=sc.series, **sc.parameters)
    # C: the scene's profile file read by the library, and the same heights given
    exe = build(tmp_path, "check_api.c", pc_env)
    lazy = dumped(_run([exe, "dump", scene, tmp_path / "c_file.nc"], cwd=tmp_path).stdout)
    heights = tmp_path / "heights.bin"
    np.asarray(sc.heights, dtype="<f8").tofile(heights)
    given = dumped(_run([exe, "dump", scene, tmp_path / "c_arrays.nc", heights, repr(sc.dx),
                         int(sc.closed)], cwd=tmp_path).stdout)
    c_file = pavefric.open_dataset(tmp_path / "c_file.nc")
    c_arrays = pavefric.open_dataset(tmp_path / "c_arrays.nc")

    for name in names:
        want = ref[name].values
        assert same_bits(c_file[name].values, want), name
        # the profile file read by the library: every variable, the
        # scalars included, the program's bits
        assert same_bits(lazy[name], want), name
        if name in SCALARS:
            continue
        assert same_bits(from_scene[name].values, want), name
        assert same_bits(from_arrays[name].values, want), name
        assert same_bits(given[name], want), name
        assert same_bits(c_arrays[name].values, want), name
    assert same_bits(lazy["mu_from_run"], ref["mu"].values)
    # the C API's names are the output's, no more, no fewer
    assert set(lazy) - {"mu_from_run"} == set(names)
    assert SCALARS <= set(names)
    # the file the C API writes is the program's (but for its history)
    for key, value in ref.attrs.items():
        if key != "history":
            assert np.array_equal(c_file.attrs[key], value), key
    # heights given: their spacing becomes &surface dx (the program's may
    # come from the file's distances, unset in the namelist)
    def without_dx(text):
        return [line for line in text.splitlines() if not line.strip().startswith("dx =")]
    assert without_dx(c_arrays.attrs["parameters"]) == without_dx(ref.attrs["parameters"])
    assert c_arrays.attrs["param_surface_dx"] == sc.dx == ref.attrs["profile_dx"]
    assert c_arrays.attrs["profile_file"] == ""


def test_c_scene_from_text_agrees_with_python_simulate(tmp_path, pc_env, profile_m):
    """pavefric_new_scene (namelist text, no file) + pavefric_set_profile =
    pavefric.simulate on the same arrays and keywords, on every variable."""
    exe = build(tmp_path, "check_api.c", pc_env)
    heights = tmp_path / "heights.bin"
    np.asarray(profile_m, dtype="<f8").tofile(heights)
    text = ("text:&surface dx = 1e-3, mu_loc = 0.55 / &water depth = 0.8e-3 / "
            "&operation speeds_kmh = 15, 45, 75 / &output series = .true. /")
    # the heights' own spacing and closure replace the text's dx
    got = dumped(_run([exe, "dump", text, tmp_path / "c.nc", heights, "0.87e-3", "0"],
                      cwd=tmp_path).stdout)
    ds = pavefric.simulate(profile_m, 0.87e-3, [15, 45, 75], closed=False, series=True,
                           mu_loc=0.55, depth=0.8e-3)
    names = [*ds.coords, *ds.data_vars]
    assert SCALARS <= set(names)
    assert set(got) - {"mu_from_run"} == set(names)
    for name in names:
        assert same_bits(got[name], ds[name].values), name
    written = pavefric.open_dataset(tmp_path / "c.nc")
    assert written.attrs["param_surface_dx"] == 0.87e-3 and written.attrs["profile_closed"] == 0
    for name in ds.data_vars:
        assert same_bits(written[name].values, ds[name].values), name
    # Sp without F60 (speeds far from 20 km/h): the C API has the one, not
    # the other, as the file and Python
    far = text.replace("15, 45, 75", "45, 75")
    got = dumped(_run([exe, "dump", far, tmp_path / "far.nc", heights, "0.87e-3", "0"],
                      cwd=tmp_path).stdout)
    ds = pavefric.simulate(profile_m, 0.87e-3, [45, 75], closed=False, series=True,
                           mu_loc=0.55, depth=0.8e-3)
    assert "ifi_sp" in got and "ifi_f60" not in got and "ifi_f60" not in ds
    assert same_bits(got["ifi_sp"], ds["ifi_sp"].values)
    assert "ifi_f60" not in pavefric.open_dataset(tmp_path / "far.nc")
    # without heights there is nothing to run, and the error says so
    proc = subprocess.run([str(exe), "dump", text, "-"], capture_output=True, text=True)
    assert proc.returncode == 1
    assert "profile: not set" in proc.stdout


def test_c_scene_with_its_profile_elsewhere(tmp_path, pc_env):
    """A scene whose profile file is not there loads (the file is read at
    the run); with the heights given it runs, without them the error names
    the file."""
    text = WET.read_text().replace("'profiles/ctm_medium.txt'", "'elsewhere/ctm_medium.txt'")
    scene = tmp_path / "moved.nml"
    scene.write_text(text)
    exe = build(tmp_path, "check_api.c", pc_env)
    proc = subprocess.run([str(exe), "dump", scene, "-"], capture_output=True, text=True)
    assert proc.returncode == 1
    assert "case run: check=1 status=1" in proc.stdout
    assert str(tmp_path / "elsewhere" / "ctm_medium.txt") in proc.stdout
    sc = pavefric.load_scene(WET)
    heights = tmp_path / "heights.bin"
    np.asarray(sc.heights, dtype="<f8").tofile(heights)
    got = dumped(_run([exe, "dump", scene, "-", heights, repr(sc.dx), "1"]).stdout)
    assert same_bits(got["mu"], program_output(WET, tmp_path / "program.nc")["mu"].values)


# --- meson install into a prefix -------------------------------------------------

def test_meson_install_puts_everything_where_pkg_config_says(tmp_path):
    """`meson install` into a prefix: libpavefric (shared, static), pavefric.h,
    the .mod files and pavefric.pc, found through pkg-config; the C and
    Fortran examples build against them and reproduce the program."""
    prefix, builddir = tmp_path / "prefix", tmp_path / "build"
    env = dict(os.environ, PATH=f"{BIN}{os.pathsep}{os.environ['PATH']}")
    meson = [sys.executable, "-m", "mesonbuild.mesonmain"]
    _run([*meson, "setup", builddir, ROOT, f"--prefix={prefix}", "-Dmpi=disabled"], env=env)
    _run([*meson, "compile", "-C", builddir, "-j", "2"], env=env, timeout=1800)
    _run([*meson, "install", "-C", builddir, "--quiet"], env=env)
    pcs = list(prefix.rglob("pavefric.pc"))
    assert len(pcs) == 1
    env["PKG_CONFIG_PATH"] = str(pcs[0].parent)
    libdir = Path(pkg_config(env, "--variable=libdir")[0])
    includedir = Path(pkg_config(env, "--variable=includedir")[0])
    assert pcs[0].parent == libdir / "pkgconfig"
    assert libdir.is_relative_to(prefix) and includedir.is_relative_to(prefix)
    assert (libdir / "libpavefric.a").is_file()
    assert (libdir / f"libpavefric.so.{pavefric.__version__}").is_file()
    assert (libdir / "libpavefric.so").resolve() == (libdir / f"libpavefric.so.{pavefric.__version__}")
    assert (includedir / "pavefric.h").read_text() == (ROOT / "src" / "api" / "pavefric.h").read_text()
    mod_dirs = [Path(f[2:]) for f in pkg_config(env, "--cflags-only-I")
                if (Path(f[2:]) / "pavefric.mod").is_file()]
    assert len(mod_dirs) == 1 and mod_dirs[0].is_relative_to(includedir)
    modules = {p.stem for p in mod_dirs[0].glob("*.mod")}
    sources = {p.stem for p in (ROOT / "src").rglob("pavefric*.f90") if "f2py" not in p.parts}
    assert len(sources) >= 40 and sources <= modules
    # a user's build against the prefix (no rpath there: LD_LIBRARY_PATH)
    env["LD_LIBRARY_PATH"] = str(libdir)
    ref = program_output(WET, tmp_path / "program.nc")
    for source in ("example.c", "example.f90"):
        exe = build(tmp_path / source.replace(".", "_"), source, env)
        _, mu = printed_mu(_run([exe, WET], env=env, cwd=tmp_path).stdout)
        assert same_bits(mu, ref["mu"].values), source
