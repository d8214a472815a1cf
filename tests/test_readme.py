"""Every example of README.md runs, as written, in a scratch copy of the
repository's inputs (a fresh clone's view: nothing beside it).

The blocks are taken from the README itself, so an example that stops working
(or a README edited into one that does not) fails here. Three substitutions
only: `.venv/bin/` is this interpreter's directory; `mpirun` may oversubscribe
the machine's cores (and run as root in a container); the report commands
(`validate`, `speed-gradient`, `bench`, `accuracy`) run their quick variants
(`--quick`, or one repeat), which execute the same code. `bash setup.sh ...`
is what CI itself runs and is not run again here.
"""
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import ROOT

BIN = Path(sys.executable).parent
README = (ROOT / "README.md").read_text(encoding="utf-8")
BLOCKS = re.findall(r"```(\w+)\n(.*?)```", README, re.S)


def _blocks(language: str) -> list[str]:
    return [body for lang, body in BLOCKS if lang == language]


# the bash blocks with something to run besides CI's own `bash setup.sh`
RUNNABLE = [b for b in _blocks("bash")
            if any(line.strip() and not line.strip().startswith("bash setup.sh")
                   for line in b.splitlines())]


def _shell(body: str) -> str:
    """The block as a bash script with the substitutions above."""
    lines = []
    for line in body.replace("\\\n", " ").splitlines():
        if not line.strip() or line.strip().startswith("bash setup.sh"):
            continue
        line = line.replace(".venv/bin/", f"{BIN}/")
        if line.lstrip().startswith("mpirun"):
            extra = " --allow-run-as-root" if os.geteuid() == 0 else ""
            line = line.replace("mpirun", f"mpirun --oversubscribe{extra}", 1)
        code = line.split("#", 1)[0] if " #" in line else line
        for report in ("validate", "speed-gradient", "bench"):
            if re.search(rf"-m pavefric {report}\b", code):
                code = code.rstrip() + " --quick"
        if re.search(r"-m pavefric accuracy\b", code):
            code = code.rstrip() + " --repeats 1"
        lines.append(code)
    return "set -e\n" + "\n".join(lines) + "\n"


@pytest.fixture(scope="module")
def scratch(tmp_path_factory) -> Path:
    """What a user's checkout holds that the examples use."""
    d = tmp_path_factory.mktemp("readme")
    shutil.copytree(ROOT / "inputs", d / "inputs")
    (d / "tests").mkdir()
    shutil.copytree(ROOT / "tests" / "api", d / "tests" / "api")
    shutil.copytree(ROOT / "examples", d / "examples")
    shutil.copy(ROOT / "meson.build", d / "meson.build")
    (d / "src").mkdir()
    (d / "outputs").mkdir()
    (d / "docs" / "figures").mkdir(parents=True)
    return d


def _run(script: str, cwd: Path, timeout: int = 3600) -> subprocess.CompletedProcess:
    env = {**os.environ, "OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
           "MPLBACKEND": "Agg", "PATH": f"{BIN}{os.pathsep}{os.environ['PATH']}"}
    return subprocess.run(["bash", "-c", script], cwd=cwd, capture_output=True, text=True,
                          env=env, timeout=timeout)


def test_the_readme_has_the_examples_this_test_runs():
    assert len(RUNNABLE) >= 2 and _blocks("python") and _blocks("sh")
    assert _blocks("fortran")
    assert "bash setup.sh demo" in README and "bash setup.sh test" in README


@pytest.mark.parametrize("index", range(len(RUNNABLE)))
def test_bash_block_runs(scratch, index):
    script = _shell(RUNNABLE[index])
    r = _run(script, scratch)
    assert r.returncode == 0, f"README block {index}:\n{script}\n{r.stdout[-3000:]}\n" \
                              f"{r.stderr[-3000:]}"


def test_c_block_runs(scratch):
    r = _run(_shell(_blocks("sh")[0]), scratch)
    assert r.returncode == 0, r.stdout + r.stderr
    assert re.search(r"km/h: mu = ", r.stdout), r.stdout


def test_scene_block_runs(scratch):
    """The namelist shown in the README, as a scene beside inputs/profiles."""
    scene = scratch / "inputs" / "readme_scene.nml"
    scene.write_text(_blocks("fortran")[0])
    r = _run(f"{BIN}/pavefric {scene} -o readme_scene.nc", scratch)
    assert r.returncode == 0, r.stderr
    assert (scratch / "readme_scene.nc").exists()


def test_python_block_runs(scratch):
    r = subprocess.run([sys.executable, "-c", _blocks("python")[0]], cwd=scratch,
                       capture_output=True, text=True, timeout=600,
                       env={**os.environ, "MPLBACKEND": "Agg"})
    assert r.returncode == 0, r.stderr
    assert "elastic_contact" in r.stdout
    assert (scratch / "mu.png").exists()
