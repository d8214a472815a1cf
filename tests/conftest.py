"""Shared fixtures: profiles, scene files, and the installed program."""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(HERE))  # the NumPy reference lives beside the tests

DX = 0.87e-3

# The property and fuzz tests (hypothesis) draw the same examples on every
# run and machine: a suite that passes must pass again. Set
# PAVEFRIC_EXPLORE=1 to draw new ones (a search for bugs, not a check).
try:
    from hypothesis import settings as _hyp_settings

    _hyp_settings.register_profile("pavefric", derandomize=True, database=None)
    _hyp_settings.register_profile("explore", derandomize=False)
    _hyp_settings.load_profile("explore" if os.environ.get("PAVEFRIC_EXPLORE") else "pavefric")
except ImportError:                      # hypothesis is a test requirement (setup.sh)
    pass
# Data shipped in the repository (inputs/data): a fresh clone needs nothing beside it.
DATA = ROOT / "inputs" / "data"
CAPTIF = DATA / "captif"
TABLE = DATA / "kane2017_tables.csv"


def import_captif_slp():
    """captif-slp, the independent ISO 13473-1 implementation the texture
    tests compare with. It and its reader pyrsona pin pandas<2.2 and numpy<2,
    so they are not in the [test] extra: setup.sh and .ci/run install them
    with --no-deps. Without them these tests skip, saying so, and CI
    (PAVEFRIC_NO_SKIP) counts that skip as a failure."""
    return pytest.importorskip(
        "captif_slp", reason="captif-slp is not installed: pip install --no-deps "
        "'pyrsona>=1.1,<2' 'captif-slp>=0.22' (they pin pandas<2.2 and numpy<2; their other "
        "requirements: pandas pydantic psutil click parse unsync; setup.sh does this)")


def program() -> str:
    exe = Path(sys.executable).parent / "pavefric"
    if not exe.exists():
        pytest.fail(f"the pavefric program is not installed beside {sys.executable}")
    return str(exe)


def run_program(*args: str, cwd: str | os.PathLike | None = None) -> subprocess.CompletedProcess:
    return subprocess.run([program(), *map(str, args)], capture_output=True, text=True,
                          cwd=cwd, timeout=600)


# Profiles the tests share are files (tests/data/regression/), written once
# from pavefric.surfaces.spectral_profile: NumPy's sin, exp and FFT round
# differently on other CPUs, and a test must not depend on those last bits.
@pytest.fixture(scope="session")
def profile_m() -> np.ndarray:
    """A CTM-like closed profile (m): 1024 points at 0.87 mm."""
    from make_regression import read_heights

    return read_heights("synthetic_1024.txt")


@pytest.fixture(scope="session")
def short_profile_m() -> np.ndarray:
    """A short profile for the slow reference (200 points)."""
    from make_regression import read_heights

    return read_heights("synthetic_200.txt")


def cold_compound_batch(tmp_path: Path, profile_m: np.ndarray) -> str:
    """Two profiles for a batch (tmp_path/p/a.txt, b.txt: the halves of
    `profile_m`) and the shipped tread compound's &rubber group at 0 C (the
    text returned): a pad that stands on one or two of its elements."""
    import re

    from pavefric.surfaces import write_profile

    d = tmp_path / "p"
    d.mkdir()
    write_profile(str(d / "a.txt"), profile_m[:512])
    write_profile(str(d / "b.txt"), profile_m[512:])
    rubber = (ROOT / "inputs" / "rubber" / "tread_compound.nml").read_text()
    rubber = re.sub(r"^(\s*)temperature = 20\b", r"\1temperature = 0", rubber, flags=re.M)
    assert "reference_temperature = 20" in rubber and "  temperature = 0" in rubber
    return rubber


def run_cold_batch(tmp_path: Path, label: str, groups: str) -> Path:
    """The program's batch over cold_compound_batch's profiles (tmp_path/p),
    dry, mu_loc = 0, at 20 and 60 km/h, with the namelist groups `groups`
    added; checks it succeeded and returns its output (tmp_path/label.nc)."""
    scene = tmp_path / f"{label}.nml"
    scene.write_text("&batch profiles = 'p/*.txt', depths = 0.0 /\n"
                     "&surface height_unit = 'mm', mu_loc = 0.0 /\n"
                     "&operation speeds_kmh = 20, 60 /\n" + groups)
    out = tmp_path / f"{label}.nc"
    r = run_program(str(scene), "-o", str(out))
    assert r.returncode == 0, r.stderr
    return out


def write_scene(directory: Path, name: str = "scene", *, profile: np.ndarray | None = None,
                groups: dict[str, str] | None = None, profile_text: str | None = None) -> Path:
    """A scene file in `directory`; `groups` maps group name -> body text,
    replacing the default body of that group."""
    directory.mkdir(parents=True, exist_ok=True)
    prof = directory / f"{name}_profile.txt"
    if profile_text is not None:
        prof.write_text(profile_text)
    else:
        z = profile if profile is not None else np.sin(np.arange(256) * 0.3) * 0.5e-3
        prof.write_text("height_mm\n" + "\n".join(f"{1e3 * v:.9f}" for v in z) + "\n")
    body = {
        "surface": f"profile_file = '{prof.name}', mu_loc = 0.5",
        "pad": "length = 0.020",
        "rubber": "stiffness = 1.4e8, viscosity = 100.0",
        "water": "depth = 0.0",
        "operation": "speeds_kmh = 20, 60",
        "output": "series = .false.",
    }
    body.update(groups or {})
    text = "\n".join(f"&{g}\n  {b}\n/" for g, b in body.items() if b is not None) + "\n"
    path = directory / f"{name}.nml"
    path.write_text(text)
    return path


def pytest_sessionfinish(session, exitstatus):
    """With PAVEFRIC_NO_SKIP set (CI sets it), a skipped test fails the run:
    the suite must pass whole on a fresh clone."""
    if not os.environ.get("PAVEFRIC_NO_SKIP"):
        return
    reporter = session.config.pluginmanager.get_plugin("terminalreporter")
    skipped = len(reporter.stats.get("skipped", [])) if reporter else 0
    if skipped and exitstatus == 0:
        reporter.ensure_newline()
        reporter.write_line(f"PAVEFRIC_NO_SKIP: {skipped} test(s) skipped; the suite must "
                            "run whole", red=True)
        session.exitstatus = 1
