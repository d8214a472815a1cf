"""Issue 22: the Fortran core's layers run one way (docs/architecture.md).

src/ holds one directory per layer; a module may use modules of its own
layer and of the layers below it, never one above:

    base < physics < model < io < run < api < app

The test reads every `use` statement of the sources (the f2py wrapper
counts as api) and checks each edge against that order, so a module that
reaches upwards (physics reading a file, a writer calling the driver) fails
here with the file, the line and the module it reached.
"""
from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import pavefric

from conftest import ROOT

LAYERS = ["base", "physics", "model", "io", "run", "api", "app"]
SRC = ROOT / "src"

MODULE = re.compile(r"^\s*module\s+(?!procedure\b)(\w+)\s*(?:!.*)?$", re.I | re.M)
USE = re.compile(r"^\s*use\s*(?:,\s*(\w+)\s*)?(?:::)?\s*(\w+)", re.I)


def layer_of(path: Path, src: Path = SRC) -> str:
    return path.relative_to(src).parts[0]


def sources() -> list[Path]:
    return sorted(p for p in SRC.rglob("*") if p.suffix in (".f90", ".F90"))


def modules_by_name(paths) -> dict[str, Path]:
    found = {}
    for p in paths:
        for name in MODULE.findall(p.read_text(encoding="utf-8")):
            found[name.lower()] = p
    return found


def uses(text: str):
    """(line number, module) of every non-intrinsic `use` statement."""
    for k, line in enumerate(text.splitlines(), start=1):
        m = USE.match(line.split("!")[0])
        if m and (m.group(1) or "").lower() != "intrinsic":
            yield k, m.group(2).lower()


def violations(paths, modules, src: Path = SRC) -> list[str]:
    """Every use of a module of a higher layer, as 'file:line: layer uses module (layer)'."""
    bad = []
    for p in paths:
        mine = LAYERS.index(layer_of(p, src))
        for k, used in uses(p.read_text(encoding="utf-8")):
            if used not in modules:
                continue                  # netcdf, mpi, omp_lib: not ours
            theirs = LAYERS.index(layer_of(modules[used], src))
            if theirs > mine:
                bad.append(f"src/{p.relative_to(src)}:{k}: {layer_of(p, src)} uses {used} "
                           f"({layer_of(modules[used], src)})")
    return bad


def test_every_source_lies_in_a_layer():
    paths = sources()
    assert len(paths) > 40
    outside = [str(p.relative_to(ROOT)) for p in paths if layer_of(p) not in LAYERS]
    assert not outside


def test_module_names_are_file_names():
    """One module per file, named as the file (the .mod files installed for
    `use pavefric` are found by that name)."""
    for p in sources():
        names = [n.lower() for n in MODULE.findall(p.read_text(encoding="utf-8"))]
        if p.parent.name == "f2py" or p.stem == "main":
            assert names == [], p          # plain procedures, a program
        elif p.stem == "batch_mpi":
            assert names == ["pavefric_batch_mpi"]
        else:
            assert names == [p.stem.lower()], p


def test_uses_run_down_the_layers_only():
    paths = sources()
    modules = modules_by_name(paths)
    assert violations(paths, modules) == []
    # the edges the issue named as running backwards are gone
    text = {p.stem: p.read_text(encoding="utf-8").lower() for p in paths}
    assert "use pavefric_simulate" not in text["pavefric_outputs"]
    assert "use pavefric_simulate" not in text["pavefric_netcdf"]
    assert "use pavefric_profile," not in text["pavefric_preprocess"]
    assert "subroutine make_components" not in text["pavefric_simulate"]
    # the physics and the model read and write no files
    for p in paths:
        if layer_of(p) in ("physics", "model"):
            code = "\n".join(ln.split("!")[0] for ln in p.read_text(encoding="utf-8").splitlines())
            assert not re.search(r"\b(open|read|write|inquire|close)\s*\(\s*(unit|newunit|\d|\*)",
                                 code, re.I), p


@pytest.mark.parametrize("layer, used_layer, ok", [
    ("physics", "base", True), ("physics", "physics", True), ("model", "physics", True),
    ("physics", "io", False), ("io", "run", False), ("model", "io", False), ("api", "app", False)])
def test_the_check_sees_an_edge_against_the_order(tmp_path, layer, used_layer, ok):
    """The checker itself, on two made-up modules: an upward use is reported."""
    for d in {layer, used_layer}:
        (tmp_path / d).mkdir()
    low = tmp_path / used_layer / "pf_low.f90"
    low.write_text("module pf_low\nend module pf_low\n")
    high = tmp_path / layer / "pf_high.f90"
    high.write_text("module pf_high\n   use, intrinsic :: iso_c_binding\n   use pf_low, only: x\n"
                    "end module pf_high\n")
    paths = [low, high]
    found = violations(paths, modules_by_name(paths), src=tmp_path)
    if ok:
        assert found == []
    else:
        assert len(found) == 1 and ":3:" in found[0] and "uses pf_low" in found[0]


def test_the_worked_example_component_compiles_and_runs(tmp_path):
    """docs/architecture.md's film component, built outside the tree against
    the installed modules (pkg-config's flags) and run: its load and
    stiffness are its closed form."""
    from test_api import _run, pkg_config

    bin_dir = Path(sys.executable).parent       # pavefric-config, as a user's build
    pcdir = _run([bin_dir / "pavefric-config", "--pkgconfigdir"]).stdout.strip()
    env = dict(os.environ, PKG_CONFIG_PATH=pcdir, PATH=f"{bin_dir}{os.pathsep}{os.environ['PATH']}")
    doc = (ROOT / "docs" / "architecture.md").read_text(encoding="utf-8")
    blocks = re.findall(r"```fortran\n(.*?)```", doc, re.S)
    assert len(blocks) == 1
    src = tmp_path / "cushion_example.f90"
    src.write_text(blocks[0])
    exe = tmp_path / "cushion_example"
    flags = pkg_config(env, "--cflags") + pkg_config(env, "--libs")
    _run(["gfortran", "-Wall", "-o", exe, src, *flags], env=env, cwd=tmp_path)
    out = _run([exe], env=dict(env, LD_LIBRARY_PATH=""), cwd=tmp_path).stdout.split()
    assert out[0] == "water_cushion" and out[3] == "T"
    assert out[4] == "cushion:cushion_thickness,cushion_stiffness"
    assert float(out[1]) == pytest.approx(1.0e3 * (2.0e-4 - 1.5e-4), rel=1e-12)
    assert float(out[2]) == pytest.approx(750.0, rel=1e-15)


# --- Python: the library apart from the studies -------------------------------

PY = ROOT / "python" / "pavefric"
STUDIES = ["accuracy", "bench", "bench_io", "bench_mpi", "docs", "energy_report", "reports",
           "reference_surfaces", "rubber_report", "speed_gradient", "validation"]


def test_the_library_never_imports_the_studies():
    """pavefric's library modules (all of python/pavefric/ but the studies,
    the deprecated aliases of their old names and the command line) import
    no study: a study may use the library, not the other way round."""
    import ast

    library = [p for p in PY.glob("*.py") if p.stem not in STUDIES and p.stem != "__main__"]
    assert {"core", "profiles", "calibrate", "rubber"} <= {p.stem for p in library}
    for p in library:
        for node in ast.walk(ast.parse(p.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ImportFrom):
                names = [node.module or ""] + [a.name for a in node.names]
                assert not any(n == "studies" or n.startswith("studies.") or
                               "pavefric.studies" in n for n in names), (p.name, node.lineno)
            elif isinstance(node, ast.Import):
                assert not any("pavefric.studies" in a.name for a in node.names), (p.name, node.lineno)


@pytest.mark.parametrize("name", STUDIES)
def test_a_study_s_old_name_warns_and_is_the_moved_module(name):
    import importlib
    import sys as _sys

    moved = importlib.import_module(f"pavefric.studies.{name}")
    _sys.modules.pop(f"pavefric.{name}", None)
    with pytest.warns(DeprecationWarning, match=f"pavefric.{name} is now pavefric.studies.{name}"):
        old = importlib.import_module(f"pavefric.{name}")
    assert old is moved


def test_a_wet_model_is_one_module_and_its_registry_lines(tmp_path):
    """Issue 22: docs/architecture.md's cushion film, added to a copy of the
    source as one new module plus its lines in the registry
    (model/pavefric_wet_models.f90) and in src/meson.build, builds into a
    program where &water wet_model = 'cushion' runs it: its variables are
    read, checked by name and echoed, its effect is reported, and its load
    lowers the friction. In the same copy a variable added to the
    Kelvin-Voigt law in its module alone (physics/pavefric_rubber.f90) is
    read, echoed and used, and warned about when given for another law."""
    tree = tmp_path / "tree"
    for name in ("meson.build", "meson.options", "LICENSE"):
        (tree / name).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(ROOT / name, tree / name)
    for name in ("src", "python"):
        shutil.copytree(ROOT / name, tree / name, ignore=shutil.ignore_patterns("__pycache__"))
    for name in ("ctm_dry.nml", "ctm_wet.nml", "ctm_squeeze.nml", "ctm_reynolds.nml",
                 "profiles/ctm_medium.txt"):
        (tree / "inputs" / name).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(ROOT / "inputs" / name, tree / "inputs" / name)
    doc = (ROOT / "docs" / "architecture.md").read_text(encoding="utf-8")
    block = re.findall(r"```fortran\n(.*?)```", doc, re.S)[0]
    module = block[:block.index("program cushion_example")].replace("cushion_film_mod",
                                                                    "pavefric_cushion")
    (tree / "src" / "physics" / "pavefric_cushion.f90").write_text(module)
    registry = tree / "src" / "model" / "pavefric_wet_models.f90"
    text = registry.read_text()
    for old, new in [
            ("   use pavefric_reynolds, only: reynolds_entry, reynolds_n_parameters\n",
             "   use pavefric_reynolds, only: reynolds_entry, reynolds_n_parameters\n"
             "   use pavefric_cushion, only: cushion_entry, cushion_n_parameters\n"),
            ("& + reynolds_n_parameters",
             "& + reynolds_n_parameters + cushion_n_parameters"),
            ("      allocate(e(3))\n", "      allocate(e(4))\n"),
            ("      e(3) = reynolds_entry()\n",
             "      e(3) = reynolds_entry()\n      e(4) = cushion_entry()\n")]:
        assert text.count(old) == 1, old
        text = text.replace(old, new)
    registry.write_text(text)
    # a variable added to a rubber law, in that law's module only
    law = tree / "src" / "physics" / "pavefric_rubber.f90"
    text = law.read_text()
    for old, new in [
            ("integer, parameter :: kelvin_voigt_n_parameters = 1\n",
             "integer, parameter :: kelvin_voigt_n_parameters = 2\n"),
            ("      e%build => kelvin_voigt_build\n",
             "      e%parameters(2) = real_param(\"rubber\", \"viscosity_scale\", \"1\", \"1\", &\n"
             "         & \"model\", \"a factor on C (a test's)\", lower=0.0_wp, upper=1.0_wp)\n"
             "      e%build => kelvin_voigt_build\n"),
            ('real_value(specs, values, "rubber", "viscosity")))',
             'real_value(specs, values, "rubber", "viscosity") * &\n'
             '         & real_value(specs, values, "rubber", "viscosity_scale")))')]:
        assert text.count(old) == 1, old
        text = text.replace(old, new)
    law.write_text(text)
    build_file = tree / "src" / "meson.build"
    text = build_file.read_text()
    old = "  'physics/pavefric_squeeze.f90',\n"
    assert text.count(old) == 1
    build_file.write_text(text.replace(old, old + "  'physics/pavefric_cushion.f90',\n"))

    env = dict(os.environ, PATH=f"{Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}")
    meson = [sys.executable, "-m", "mesonbuild.mesonmain"]
    build = tmp_path / "build"
    for cmd in ([*meson, "setup", build, tree, "-Dmpi=disabled", "-Dopenmp=disabled"],
                [*meson, "compile", "-C", build, "-j", "2", "src/pavefric:executable"]):
        proc = subprocess.run([str(c) for c in cmd], capture_output=True, text=True, env=env,
                              cwd=tmp_path, timeout=1800)
        assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]
    program = build / "src" / "pavefric"

    scene_text = (ROOT / "inputs" / "ctm_dry.nml").read_text().replace(
        "'profiles/ctm_medium.txt'", f"'{ROOT / 'inputs' / 'profiles' / 'ctm_medium.txt'}'")
    runs = {}
    for name, water in [("dry", ""),
                        ("cushion", "&water depth = 1e-3, wet_model = 'cushion', "
                                    "cushion_thickness = 1e-3, cushion_stiffness = 5e3 /\n"),
                        ("bad", "&water depth = 1e-3, wet_model = 'cushion', "
                                "cushion_stiffness = -1 /\n"),
                        ("scaled", "&rubber viscosity = 3e4, viscosity_scale = 0 /\n"),
                        ("elastic", "&rubber viscosity = 0 /\n"),
                        ("viscous", "&rubber viscosity = 3e4 /\n"),
                        ("maxwell", "&rubber model = 'maxwell', prony_stiffness = 1e8, "
                                    "prony_times = 1e-4, viscosity_scale = 0.5 /\n")]:
        scene = tmp_path / f"{name}.nml"
        if name in ("scaled", "elastic", "viscous", "maxwell"):
            scene.write_text(re.sub(r"(?ms)^&rubber\b.*?^/\n", water, scene_text))
        else:
            scene.write_text(re.sub(r"(?ms)^&water\b.*?^/\n", water, scene_text) if water
                             else scene_text)
        proc = subprocess.run([str(program), str(scene), "-o", str(tmp_path / f"{name}.nc")],
                              capture_output=True, text=True, cwd=tmp_path, timeout=600)
        runs[name] = proc
    assert runs["bad"].returncode != 0
    assert "&water cushion_stiffness = -1: must be finite and >= 0" in runs["bad"].stderr
    assert not (tmp_path / "bad.nc").exists()
    assert runs["dry"].returncode == 0 and runs["cushion"].returncode == 0, runs["cushion"].stderr
    dry = pavefric.open_dataset(tmp_path / "dry.nc")
    wet = pavefric.open_dataset(tmp_path / "cushion.nc")
    assert "water_cushion" in wet.attrs["effects"]
    assert wet.attrs["param_water_cushion_thickness"] == 1e-3
    assert wet.attrs["param_water_cushion_stiffness"] == 5e3
    assert "cushion_thickness = 0.001" in wet.attrs["parameters"]
    # the rubber law's new variable is read, echoed and used (scale 0: no dashpot)
    for name in ("scaled", "elastic", "viscous", "maxwell"):
        assert runs[name].returncode == 0, runs[name].stderr
    scaled = pavefric.open_dataset(tmp_path / "scaled.nc")
    assert scaled.attrs["param_rubber_viscosity_scale"] == 0.0
    np.testing.assert_array_equal(scaled["mu"].values,
                                  pavefric.open_dataset(tmp_path / "elastic.nc")["mu"].values)
    assert not np.array_equal(scaled["mu"].values,
                              pavefric.open_dataset(tmp_path / "viscous.nc")["mu"].values)
    # given for another law: a warning names it
    assert "viscosity_scale" in runs["maxwell"].stderr and "not used" in runs["maxwell"].stderr
    moving = wet["speed_kmh"].values > 0
    assert np.all(wet["wet_fraction"].values[moving] > 0)
    assert np.all(wet["mu"].values[moving] < dry["mu"].values[moving])


def test_the_deprecated_ids_of_the_bearing_s_variables_still_name_them():
    """p_alpha and p_beta (public before the bearing declared its own
    variables) index &water alpha and beta in the table."""
    text = (SRC / "model" / "pavefric_model.f90").read_text(encoding="utf-8")
    assert re.search(r"public :: p_alpha = n_scene_parameters \+ 1, p_beta = n_scene_parameters \+ 2",
                     text)
    names = [(p.group, p.name) for p in pavefric.parameters()]
    n_scene = next(k for k, p in enumerate(names) if p == ("water", "alpha"))
    assert n_scene == len(names) - 4 - 26       # the wet models' four follow the scene's
    assert names[n_scene:n_scene + 2] == [("water", "alpha"), ("water", "beta")]
    assert all(g != "water" or n in ("alpha", "beta", "squeeze_inlet_fraction", "density")
               for g, n in names[n_scene:])


def test_the_deprecated_ids_of_the_components_variables_still_name_them():
    """p_stiffness, p_viscosity, p_dropouts, p_length, p_mu_loc, ... (the
    scene's ids before the rubber laws, preprocessing, the pad and the
    facets declared their own variables) index them in the table: each
    component's block after the wet models', in the order of the model's
    `*_first` constants."""
    text = (SRC / "model" / "pavefric_model.f90").read_text(encoding="utf-8")
    flat = re.sub(r"&\s*\n\s*&", "", text)
    names = [(p.group, p.name) for p in pavefric.parameters()]
    first = next(k for k, p in enumerate(names) if p == ("water", "alpha")) + 4 + 1
    blocks = {"rubber": ["model", "stiffness", "temperature", "reference_temperature",
                         "wlf_c1", "wlf_c2", "viscosity", "prony_stiffness", "prony_times"],
              "preprocess": ["dropouts", "trim_plates", "plate_threshold", "plate_min_length",
                             "plate_buffer", "spike_slope", "resample_dx",
                             "lowpass_wavelength"],
              "pad": ["length", "width", "thickness", "load", "shape", "radius",
                      "element_length"]}
    expected = [("rubber", n) for n in blocks["rubber"]] + \
        [("preprocess", n) for n in blocks["preprocess"]] + \
        [("pad", n) for n in blocks["pad"]] + [("surface", "mu_loc"), ("numerics", "theta_max_deg")]
    assert names[first - 1:] == expected
    # the Fortran ids (1-based), evaluated from their definitions
    env = {"rubber_first": first, "preprocess_first": first + 9, "pad_first": first + 17,
           "facet_first": first + 24, "n_rubber_shared_parameters": 6,
           "kelvin_voigt_n_parameters": 1}
    defs = re.findall(r"\b(p_\w+) = ((?:rubber|preprocess|pad|facet)_first(?: \+ \w+)?|"
                      r"p_\w+ \+ \w+)", flat)
    assert len(defs) == 9 + 8 + 7 + 2
    for pid, expr in defs:
        env[pid] = eval(expr, {}, env)
        group, name = names[env[pid] - 1]
        assert name == pid[2:].replace("rubber_model", "model"), (pid, expr, name)


def test_nothing_under_python_uses_the_tests():
    """Issue 22: the package neither imports the tests' modules nor reads
    their files (the benchmark's plain loop lives with the studies; the NumPy
    reference is timed only when the user names it with --reference). A path
    literal is a string without spaces; messages may name tests/ files."""
    import ast
    import re

    sources = sorted((ROOT / "python").rglob("*.py"))
    assert len(sources) > 30
    for p in sources:
        for node in ast.walk(ast.parse(p.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom):
                names = [node.module or ""]
            else:
                names = []
            assert not any(n.split(".")[0] in ("tests", "reference", "conftest",
                                               "make_regression") for n in names), (p, names)
            if isinstance(node, ast.Constant) and isinstance(node.value, str):
                assert not re.fullmatch(r"\.?/?tests(/[\w.\-]+)*/?", node.value), \
                    (p, node.lineno, node.value)


def test_the_check_of_the_tests_paths_would_fire():
    """The literal check above sees the old benchmark's way in."""
    import re

    for literal in ("tests", "tests/reference.py", "tests/plain_loop.f90"):
        assert re.fullmatch(r"\.?/?tests(/[\w.\-]+)*/?", literal)
    assert not re.fullmatch(r"\.?/?tests(/[\w.\-]+)*/?", "the NumPy reference, tests/reference.py")


def test_the_command_line_is_one_module_per_command():
    """Issue 22: every command is a module of pavefric.cli declaring its name,
    help, examples, arguments and action; __main__ builds no parser itself;
    every example parses with the command's own parser."""
    import argparse
    import shlex

    from pavefric import cli

    parser, mods = cli.build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    assert set(sub.choices) == set(mods) and len(mods) == len(cli.COMMANDS) >= 15
    assert "add_parser" not in (PY / "__main__.py").read_text(encoding="utf-8")
    for name, mod in mods.items():
        assert mod.__file__.endswith(f"{name.replace('-', '_')}.py"), name
        assert callable(mod.add_arguments) and callable(mod.main), name
        assert mod.HELP and mod.EXAMPLES, name
        helptext = sub.choices[name].format_help()
        assert "examples:" in helptext, name
        for example in mod.EXAMPLES:
            assert example in helptext, (name, example)
            words = shlex.split(example.split("&&")[0])
            assert words[:3] == ["python", "-m", "pavefric"] and words[3] == name, example
            parser.parse_args(words[3:])            # exits (SystemExit) if it does not parse


def test_each_output_is_declared_by_its_component():
    """Issue 22: every result variable is declared next to the code that
    produces it (pad and numerics in the outputs table, facets, rubber, any
    load-carrying film, each wet model's own in its entry), once, and the
    table keeps the file's order (the C API's indices) as before."""
    from pavefric.core import _tables

    outs = _tables()[2]
    names = [o[0] for o in outs]
    assert names == [
        "mu", "n_clamped", "hydroplaning_fraction", "wet_fraction", "max_balance_residual",
        "mean_hydro_load", "max_compression", "bearing_evaluations", "memory_updates",
        "viscous_memory_ran", "bearing_ran", "squeeze_film_ran", "mean_local_friction",
        "mean_film_thickness", "mu_inst", "hydro_load", "penetration", "contact_elements",
        "film_thickness", "local_friction", "mu_error_estimate", "substeps_used",
        "mu_hysteresis", "mu_adhesion", "mu_extrapolated", "exact_integrator_ran",
        # issue 21's, appended (the indices before them unchanged)
        "contact_fraction", "film_load_share", "mean_water_thickness", "film_unsettled",
        "film_pressure_max", "water_thickness",
        # appended with the error estimate's pad pass
        "estimate_elements_per_sample",
        # appended with &numerics min_contacts
        "elements_per_sample_used",
        # appended with the Reynolds film's root jumps
        "film_root_jumps"]
    modules = {"pad": "model/pavefric_outputs.f90", "numerics": "model/pavefric_outputs.f90",
               "facets": "physics/pavefric_facet.f90", "rubber": "physics/pavefric_rubber.f90",
               "film": "physics/pavefric_film.f90", "squeeze": "physics/pavefric_squeeze.f90",
               "reynolds": "physics/pavefric_reynolds.f90"}
    owners = {o[0]: o[6] for o in outs}
    assert set(owners.values()) == set(modules)
    for name, owner in owners.items():
        text = re.sub(r"\s+", " ", (SRC / modules[owner]).read_text(encoding="utf-8"))
        assert re.search(rf'output_var\("{owner}", "{name}"', text), (name, owner)
    assert owners["film_thickness"] == "squeeze" and owners["mu_hysteresis"] == "rubber"


def test_python_sets_parameters_as_typed_values():
    """Issue 22: Python's keywords cross into the core as typed items
    (variable id, kind, numbers, text), checked by the same declarations as
    the C API's typed setters, not as namelist text written and re-parsed."""
    import numpy as np

    from pavefric import _core
    from pavefric.core import _typed, _format, _spec

    for name in ("pf_layout", "pf_simulate", "pf_profile_read_info", "pf_profile_read_data"):
        doc = getattr(_core, name).__doc__
        assert "t_ids" in doc and "t_reals" in doc and "settings" not in doc.split("\n")[0], name
    core_text = (PY / "core.py").read_text(encoding="utf-8")
    assert "_settings_text" not in core_text
    # a value of each kind, and what the core makes of it
    items = {("surface", "mu_loc"): _format(_spec("surface", "mu_loc"), 0.1 + 2.0**-55, "mu_loc"),
             ("numerics", "substeps"): _format(_spec("numerics", "substeps"), 3, "substeps"),
             ("surface", "closed"): _format(_spec("surface", "closed"), False, "closed"),
             ("pad", "shape"): _format(_spec("pad", "shape"), "rounded", "shape"),
             ("operation", "speeds_kmh"): _format(_spec("operation", "speeds_kmh"),
                                                  [20.0, 60.0], "speeds_kmh"),
             ("surface", "dx"): _format(_spec("surface", "dx"), 0.87e-3, "dx")}
    n_el, n_pos, n_series, status, message = _core.pf_layout(*_typed(items), 200)
    assert status == 0, message
    assert n_el == 23 and n_series == 4
    # open, one speed step a third of the spacing: (200 - 23) x 3 + 1 positions
    assert n_pos == (200 - 23) * 3 + 1 == pavefric.layout(200, 0.87e-3, closed=False,
                                                          substeps=3)[1]
    z = np.sin(np.arange(200) * 0.3) * 5e-4
    ds = pavefric.simulate(z, 0.87e-3, [20.0, 60.0], mu_loc=0.1 + 2.0**-55, substeps=3,
                           closed=False, shape="rounded")
    assert ds.attrs["param_surface_mu_loc"] == 0.1 + 2.0**-55
    assert ds.attrs["param_numerics_substeps"] == 3 and ds.attrs["param_pad_shape"] == "rounded"
    # the declarations' checks and words
    ids, kinds, counts, lengths, reals, text = _typed(items)
    bad = [(np.array([0], np.int32), "internal: typed item 1 is malformed"),
           (np.array([len(pavefric.parameters()) + 1], np.int32), "is malformed")]
    for bad_ids, words in bad:
        out = _core.pf_layout(bad_ids, kinds[:1], counts[:1], lengths[:1], reals[:1], text, 200)
        assert out[3] != 0 and words in pavefric.core._text(out[4])
    wrong = {("surface", "mu_loc"): (4, [], b"high")}      # a text for a real
    out = _core.pf_layout(*_typed(wrong), 200)
    assert out[3] != 0 and "&surface mu_loc: a real number is expected, not a text" in \
        pavefric.core._text(out[4])
    with pytest.raises(pavefric.PavefricError,
                       match=r"&numerics substeps = 2.9: must be a whole number in \[1, 4096\]"):
        pavefric.simulate(z, 0.87e-3, [20.0], substeps=2.9)


def test_reading_a_profile_takes_only_its_groups_typed_values(tmp_path):
    """The typed path of read_profile (scene_from_typed with profile_only)
    refuses a variable of another group, naming it, as the namelist path
    refuses another group."""
    from pavefric import _core
    from pavefric.core import _format, _spec, _typed

    path = tmp_path / "p.txt"
    path.write_text("height_mm\n" + "\n".join(str(0.1 * (k % 7)) for k in range(200)) + "\n")
    items = {("surface", "profile_file"): _format(_spec("surface", "profile_file"), str(path),
                                                  "path"),
             ("pad", "load"): _format(_spec("pad", "load"), 20.0, "load")}
    out = _core.pf_profile_read_info(*_typed(items))
    assert out[-2] != 0
    assert "&pad load: reading a profile takes only &surface and &preprocess variables" in \
        pavefric.core._text(out[-1])
    del items[("pad", "load")]
    out = _core.pf_profile_read_info(*_typed(items))
    assert out[-2] == 0 and out[0] == 200, pavefric.core._text(out[-1])
