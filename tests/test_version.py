"""One version: meson.build's project(version:) is its only source; the
program, the Python package, its metadata and every output file say the same."""
import re
import subprocess
import sys
from importlib import metadata

import pavefric
from conftest import ROOT, program


def meson_version() -> str:
    text = (ROOT / "meson.build").read_text(encoding="utf-8")
    project = re.search(r"project\((.*?)\n\)", text, re.S).group(1)
    return re.search(r"version:\s*'([^']+)'", project).group(1)


def test_program_python_and_meson_build_agree():
    version = meson_version()
    assert re.fullmatch(r"\d+\.\d+\.\d+", version), version
    r = subprocess.run([program(), "--version"], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == f"pavefric {version}"
    assert pavefric.__version__ == version
    assert metadata.version("pavefric") == version
    r = subprocess.run([sys.executable, "-m", "pavefric", "--version"], capture_output=True,
                       text=True, timeout=60)
    assert r.stdout.strip() == f"pavefric {version}", r.stdout + r.stderr


def test_the_version_is_written_nowhere_else():
    """The Fortran and Python sources take it from meson.build at build time;
    pyproject.toml declares it dynamic (meson-python reads meson.build)."""
    kinds = (ROOT / "src" / "base" / "pavefric_kinds.f90").read_text(encoding="utf-8")
    assert 'include "pavefric_version.inc"' in kinds
    assert not re.search(r"pavefric_version\s*=", kinds)
    init = (ROOT / "python" / "pavefric" / "__init__.py").read_text(encoding="utf-8")
    assert not re.search(r"__version__\s*=", init)
    pyproject = (ROOT / "pyproject.toml").read_text(encoding="utf-8")
    assert re.search(r'^dynamic = \[[^]]*"version"', pyproject, re.M)
    assert not re.search(r"^version\s*=", pyproject, re.M)


def test_outputs_record_the_version(tmp_path):
    ds = pavefric.simulate([0.0, 1e-4, 0.0, -1e-4] * 64, 0.87e-3, [20.0])
    assert ds.attrs["pavefric_version"] == meson_version()


def test_changelog_names_this_version():
    """CHANGELOG.md's newest entry is the version being built."""
    text = (ROOT / "CHANGELOG.md").read_text(encoding="utf-8")
    entries = re.findall(r"^## \[([^]]+)\]", text, re.M)
    assert entries and entries[0] == meson_version(), entries
