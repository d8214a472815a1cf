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
    """meson-python's sdist (meson dist: the committed tree) holds them."""
    r = subprocess.run(
        [sys.executable, "-c", "import sys, mesonpy; print(mesonpy.build_sdist(sys.argv[1], "
         "{'builddir': sys.argv[2]}))", str(tmp_path / "dist"), str(tmp_path / "build")],
        cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stdout[-2000:] + r.stderr[-2000:]
    name = r.stdout.strip().splitlines()[-1]
    with tarfile.open(tmp_path / "dist" / name) as tar:
        names = set(tar.getnames())
        top = f"pavefric-{meson_version()}"
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


def _imported_modules() -> set[str]:
    found = set()
    for path in PACKAGE.glob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Import):
                found |= {a.name.split(".")[0] for a in node.names}
            elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                found.add(node.module.split(".")[0])
    return found


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
