#!/usr/bin/env bash
# CI: the README's test command, nothing cheaper; then the package as users
# get it, in fresh virtual environments; then the suite again, from the
# unpacked sdist against the wheel built from it, with NumPy restricted to
# its baseline instruction set, so a test that depends on the last bits of
# one SIMD path (NumPy's sin, exp, FFT round differently on CPUs with other
# vector units) fails here, on the developers' machine, before it fails on a
# user's (docs/numerics.md, "What is promised bit for bit"). A skipped test
# counts as a failure (PAVEFRIC_NO_SKIP, tests/conftest.py).
#
# Steps (each prints "ci: ..." and its time on stderr):
#   1. bash setup.sh test                       the README's command (.venv)
#   2. python -m build: the sdist, and the wheel built from the sdist
#   3. editable install in a fresh venv (docs/install.md's commands):
#      import pavefric from the checkout, the pavefric program, the example
#   4. a fresh venv with only the wheel and its [test] extra: the README's
#      first commands from an empty directory
#   5. the whole suite from the unpacked sdist in that venv (step 4's), with
#      NPY_DISABLE_CPU_FEATURES
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
export PAVEFRIC_NO_SKIP=1
PYTHON=${PYTHON:-python3}
t0=$SECONDS
step_start=$SECONDS
step() {
  echo "ci: [$((SECONDS - step_start)) s, $((SECONDS - t0)) s in all] done; next: $*" >&2
  step_start=$SECONDS
}

echo "ci: 1. bash setup.sh test" >&2
: skip

work=$(mktemp -d "${TMPDIR:-/tmp}/pavefric-ci.XXXXXX")
: keep
version=$(.venv/bin/python -c 'import pavefric; print(pavefric.__version__)')

step "2. the sdist (meson dist: the committed tree) and the wheel built from it"
.venv/bin/python -m build --no-isolation --skip-dependency-check --outdir "$work/dist" . >"$work/build.log" 2>&1 ||
  { tail -40 "$work/build.log"; exit 1; }
sdist="$work/dist/pavefric-$version.tar.gz"
wheel=$(ls "$work/dist"/pavefric-"$version"-*.whl)
tar -xzf "$sdist" -C "$work"
src="$work/pavefric-$version"
[ -f "$src/pyproject.toml" ] && [ -f "$src/PKG-INFO" ] && [ -d "$src/tests" ]

step "3. editable install in a fresh venv: build dependencies, then pip install -e"
# docs/install.md's commands, as written there (a venv of its own, no system
# site packages: everything comes from the build requirements and the
# [test] extra)
"$PYTHON" -m venv "$work/venv-editable"
"$work/venv-editable/bin/python" -m pip install -q "meson-python>=0.17" "meson>=1.1" ninja \
  "numpy>=1.26"
"$work/venv-editable/bin/python" -m pip install -q --no-build-isolation -e ".[test]" \
  >"$work/editable.log" 2>&1 || { tail -40 "$work/editable.log"; exit 1; }
(
  cd "$work"
  export PATH="$work/venv-editable/bin:$PATH"
  # the package is the checkout's source, and the program is there
  python -c "import pavefric, sys; from pathlib import Path; \
f = Path(pavefric.__file__).resolve(); \
sys.exit(0 if f == Path('$root/python/pavefric/__init__.py').resolve() else f'imported {f}')"
  [ "$(command -v pavefric)" = "$work/venv-editable/bin/pavefric" ]
  [ "$(pavefric --version)" = "pavefric $version" ]
  python -m pavefric example editable-run && cd editable-run && pavefric -q ctm_dry.nml
  python -c "import pavefric; ds = pavefric.open_dataset('outputs/ctm_dry.nc'); \
assert ds['mu'].size == 10 and (ds['mu'] > 0).all()"
)
# the launcher and the example tests, against the editable install
(cd "$root" && "$work/venv-editable/bin/python" -m pytest -q tests/test_program_launcher.py \
  tests/test_example.py)

step "4. a fresh venv with the wheel and its [test] extra; the README's first commands"
"$PYTHON" -m venv "$work/venv-wheel"
"$work/venv-wheel/bin/python" -m pip install -q "$wheel[test]"
# captif-slp (a test reference) and its reader pyrsona pin pandas<2.2 and
# numpy<2: their other requirements, then they without their pins (as
# setup.sh does; tests that need them skip, which PAVEFRIC_NO_SKIP fails)
"$work/venv-wheel/bin/python" -m pip install -q "pandas>=2.2" "pydantic>=2,<3" psutil click \
  parse unsync
"$work/venv-wheel/bin/python" -m pip install -q --no-deps "pyrsona>=1.1,<2" "captif-slp>=0.22"
mkdir "$work/empty"
(
  cd "$work/empty"
  export PATH="$work/venv-wheel/bin:$PATH"
  python -m pavefric example my-run && cd my-run && pavefric ctm_dry.nml
  [ -s outputs/ctm_dry.nc ]
)

# the dispatched features NumPy may use beyond its baseline (NumPy 2.x:
# __cpu_dispatch__; naming one this CPU lacks is allowed)
py="$work/venv-wheel/bin/python"
features=$("$py" -c 'from numpy._core import _multiarray_umath as m; print(" ".join(m.__cpu_dispatch__))')
step "5. the suite from the unpacked sdist ($src) against the wheel, NPY_DISABLE_CPU_FEATURES='$features'"
cd "$src"
# the tests import the installed wheel, not the sdist's python/ tree
"$py" -c "import pavefric, sys; sys.exit(0 if '$work/venv-wheel/' in pavefric.__file__ else \
f'pavefric imported from {pavefric.__file__}')"
if [ -n "$features" ]; then
  export NPY_DISABLE_CPU_FEATURES="$features"
  "$py" -c 'from numpy._core import _multiarray_umath as m; import sys; on = [f for f in m.__cpu_dispatch__ if m.__cpu_features__.get(f)]; sys.exit(f"ci: still dispatched: {on}" if on else 0)'
fi
"$py" -m pytest -q tests/test_package.py tests/test_program_launcher.py tests/test_example.py
step "end"
