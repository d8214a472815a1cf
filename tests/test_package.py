"""The package as Python users expect it: a licence in the repository, the
wheel and the sdist; a valid CITATION.cff citing the software and the paper;
py.typed; and no dependency that nothing imports."""
import ast
import json
import re
import subprocess
import sys
import tarfile
from importlib import metadata
from pathlib import Path

import jsonschema
import yaml

from conftest import HERE, ROOT
from test_version import meson_version

PACKAGE = ROOT / "python" / "pavefric"


def test_licence_is_the_declared_one():
    """LICENSE is MIT, as meson.build's project(license:) says; pyproject.toml
    takes the licence and its file from meson.build."""
    text = (ROOT / "LICENSE").read_text(encoding="utf-8")
    assert text.startswith("MIT License\n")
    assert "Permission is hereby granted, free of charge" in text
    meson = (ROOT / "meson.build").read_text(encoding="utf-8")
    assert "license: 'MIT'" in meson and "license_files: ['LICENSE']" in meson
    pyproject = (ROOT / "pyproject.toml").read_text(encoding="utf-8")
    assert re.search(r'^dynamic = \[.*"license", "license-files"\]', pyproject, re.M)


def test_installed_distribution_has_licence_and_py_typed():
    """What pip installed from the wheel: the licence file (as in the
    repository), License-Expression MIT, py.typed in the package."""
    dist = metadata.distribution("pavefric")
    assert dist.metadata["License-Expression"] == "MIT"
    files = {str(f): f for f in dist.files}
    licence = [f for name, f in files.items() if name.endswith("dist-info/licenses/LICENSE")]
    assert licence, sorted(files)
    assert licence[0].read_text(encoding="utf-8") == (ROOT / "LICENSE").read_text(
        encoding="utf-8")
    assert "pavefric/py.typed" in files
    assert files["pavefric/py.typed"].locate().is_file()


def test_sdist_holds_licence_citation_and_changelog(tmp_path):
    """meson-python's sdist (meson dist: the committed tree) holds them. Run
    from an unpacked sdist (.ci/run's second pass), which has no git history
    to make one from, the same is checked on that sdist itself."""
    top = f"pavefric-{meson_version()}"
    if not (ROOT / ".git").exists() and (ROOT / "PKG-INFO").is_file():
        assert ROOT.name == top
        for f in ("LICENSE", "CITATION.cff", "CHANGELOG.md", "python/pavefric/py.typed"):
            assert (ROOT / f).is_file(), f
        pkg_info = (ROOT / "PKG-INFO").read_text(encoding="utf-8")
        assert "License-Expression: MIT" in pkg_info
        assert f"Version: {meson_version()}" in pkg_info
        return
    r = subprocess.run(
        [sys.executable, "-c", "import sys, mesonpy; print(mesonpy.build_sdist(sys.argv[1], "
         "{'builddir': sys.argv[2]}))", str(tmp_path / "dist"), str(tmp_path / "build")],
        cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stdout[-2000:] + r.stderr[-2000:]
    name = r.stdout.strip().splitlines()[-1]
    with tarfile.open(tmp_path / "dist" / name) as tar:
        names = set(tar.getnames())
        for f in ("LICENSE", "CITATION.cff", "CHANGELOG.md", "python/pavefric/py.typed"):
            assert f"{top}/{f}" in names, f
        pkg_info = tar.extractfile(f"{top}/PKG-INFO").read().decode()
    assert "License-Expression: MIT" in pkg_info
    assert f"Version: {meson_version()}" in pkg_info


def test_citation_cff_is_valid_and_cites_software_and_paper():
    cff = yaml.safe_load((ROOT / "CITATION.cff").read_text(encoding="utf-8"))
    schema = json.loads((HERE / "data" / "citation_cff_1.2.0.schema.json").read_text())
    jsonschema.validate(cff, schema,
                        format_checker=jsonschema.Draft7Validator.FORMAT_CHECKER)
    assert cff["cff-version"] == "1.2.0" and cff["type"] == "software"
    assert str(cff["version"]) == meson_version()
    assert cff["license"] == "MIT"
    paper = [ref for ref in cff["references"] if ref["type"] == "article"]
    assert len(paper) == 1
    paper = paper[0]
    assert [a["family-names"] for a in paper["authors"]] == [
        "Kane", "Do", "Cerezo", "Rado", "Khelifi"]
    assert paper["title"] == ("Contribution to pavement friction modelling: an introduction "
                              "of the wetting effect")
    assert paper["journal"] == "International Journal of Pavement Engineering"
    assert paper["year"] == 2017
    # the DOI the README (and the paper's own first page) gives
    assert f"doi:{paper['doi']}" in (ROOT / "README.md").read_text(encoding="utf-8")


def test_a_broken_citation_fails_the_schema():
    """The schema check above can fail: a citation without authors does."""
    cff = yaml.safe_load((ROOT / "CITATION.cff").read_text(encoding="utf-8"))
    del cff["authors"]
    schema = json.loads((HERE / "data" / "citation_cff_1.2.0.schema.json").read_text())
    try:
        jsonschema.validate(cff, schema)
    except jsonschema.ValidationError as exc:
        assert "authors" in exc.message
    else:
        raise AssertionError("CITATION.cff without authors passed the schema")


def _top_level_imports(directory: Path) -> set[str]:
    """The top-level modules the .py files of `directory` import (absolute imports)."""
    found = set()
    for path in directory.glob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Import):
                found |= {a.name.split(".")[0] for a in node.names}
            elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                found.add(node.module.split(".")[0])
    return found


def _imported_modules() -> set[str]:
    return _top_level_imports(PACKAGE)


def test_every_runtime_dependency_is_imported():
    """A declared dependency that nothing imports (f90nml was one) is dead
    weight for every user's install."""
    requires = metadata.requires("pavefric")
    runtime = [re.match(r"[A-Za-z0-9_.-]+", r).group(0) for r in requires if "extra ==" not in r]
    assert runtime
    imported = _imported_modules()
    assert "numpy" in imported
    for name in runtime:
        assert name in imported, f"{name} is a dependency but python/pavefric never imports it"


def test_the_tested_package_is_the_installed_one():
    """The suite imports pavefric as installed (a wheel's files, or an
    editable install's loader), never the python/ tree of the directory it
    runs from by accident: an sdist unpacked for testing holds python/
    too."""
    import pavefric

    dist = metadata.distribution("pavefric")
    here = Path(pavefric.__file__).resolve()
    direct_url = dist.read_text("direct_url.json")
    editable = bool(direct_url) and json.loads(direct_url).get("dir_info", {}).get("editable")
    if editable:
        # meson-python's editable loader maps the package to the source tree
        # the install was made from, and builds the extension elsewhere
        source = Path(json.loads(direct_url)["url"].removeprefix("file://")).resolve()
        assert here == source / "python" / "pavefric" / "__init__.py"
        assert not Path(pavefric._core.__file__).resolve().is_relative_to(source / "python")
    else:
        assert here == Path(dist.locate_file("pavefric/__init__.py")).resolve()
        assert not here.is_relative_to((ROOT / "python").resolve())
        assert Path(pavefric._core.__file__).resolve().parent == here.parent


# What the tests run besides imports: meson and ninja (test_api's meson
# install, tests/tsan/run_tsan.sh). captif-slp and pyrsona pin pandas<2.2 and
# numpy<2, which would break xarray and the extension: they are installed
# with --no-deps (setup.sh, .ci/run), and the tests that use them say so.
RUN_BY_TESTS = {"meson", "ninja"}
NO_DEPS_INSTALLS = {"captif-slp"}


def _test_imports() -> set[str]:
    found = _top_level_imports(HERE)
    local = {p.stem for p in HERE.glob("*.py")}
    return {m for m in found - local if m not in sys.stdlib_module_names and m != "pavefric"}


def _normal(name: str) -> str:
    return re.sub(r"[-_.]+", "-", name).lower()


def test_test_extra_holds_what_the_tests_import():
    """pip install pavefric[test] gives what the suite imports and runs
    (with pavefric's own dependencies), except the two --no-deps packages."""
    requires = metadata.requires("pavefric")
    declared = {_normal(re.match(r"[A-Za-z0-9_.-]+", r).group(0)) for r in requires
                if "extra ==" not in r or 'extra == "test"' in r}
    by_module = metadata.packages_distributions()
    imported = _test_imports()
    assert {"numpy", "xarray", "hypothesis", "yaml", "jsonschema"} <= imported
    for module in sorted(imported):
        dists = {_normal(d) for d in by_module.get(module, [module])}
        assert dists & (declared | NO_DEPS_INSTALLS), \
            f"the tests import {module} ({', '.join(sorted(dists))}): not in the test extra"
    assert RUN_BY_TESTS <= declared
