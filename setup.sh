#!/usr/bin/env bash
# pavefric set-up: system packages, a Python virtual environment, the build.
#
#   bash setup.sh demo   set up, run the default scene dry and with the three wet models,
#                        write outputs/ctm_dry.nc, outputs/ctm_wet.nc (the paper's
#                        bearing), outputs/ctm_squeeze.nc (drainage),
#                        outputs/ctm_reynolds.nc (the Reynolds film) and
#                        outputs/ctm_mu_speed.png
#   bash setup.sh test   set up and run the whole test suite (on up to 4 processes;
#                        bash setup.sh test tests/test_x.py: that file alone;
#                        bash setup.sh test -n 0: serially)
#   bash setup.sh        set up only
#
# System packages come from apt-get when run as root (or with passwordless
# sudo); otherwise the script names what is missing and stops. Python packages
# go into .venv with pip. PYTHON chooses the interpreter (default python3).
set -euo pipefail
cd "$(dirname "$0")"
PYTHON=${PYTHON:-python3}
VENV=.venv

log() { printf 'setup: %s\n' "$*" >&2; }

missing_system() {
  local miss=()
  command -v gfortran >/dev/null 2>&1 || miss+=(gfortran)
  command -v pkg-config >/dev/null 2>&1 || miss+=(pkg-config)
  if command -v pkg-config >/dev/null 2>&1; then
    pkg-config --exists netcdf-fortran 2>/dev/null || miss+=(libnetcdff-dev)
    pkg-config --exists lapack 2>/dev/null || ls /usr/lib/*/liblapack.so >/dev/null 2>&1 \
      || miss+=(liblapack-dev)
  else
    miss+=(libnetcdff-dev liblapack-dev)
  fi
  command -v ncdump >/dev/null 2>&1 || miss+=(netcdf-bin)
  # MPI for batch runs of the program (mpirun -n P pavefric batch.nml)
  command -v mpifort >/dev/null 2>&1 || miss+=(libopenmpi-dev)
  command -v mpirun >/dev/null 2>&1 || miss+=(openmpi-bin)
  if ! command -v "$PYTHON" >/dev/null 2>&1; then
    miss+=(python3 python3-dev python3-venv)
  else
    "$PYTHON" -c 'import ensurepip, venv' >/dev/null 2>&1 || miss+=(python3-venv)
    "$PYTHON" -c 'import os, sysconfig; assert os.path.exists(os.path.join(sysconfig.get_paths()["include"], "Python.h"))' \
      >/dev/null 2>&1 || miss+=(python3-dev)
  fi
  echo "${miss[@]:-}"
}

install_system() {
  local miss
  miss=$(missing_system)
  [ -z "$miss" ] && return 0
  local sudo=""
  if [ "$(id -u)" -ne 0 ]; then
    if command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then
      sudo="sudo -n"
    else
      log "missing system packages: $miss"
      log "install them (Debian/Ubuntu: sudo apt-get install $miss) and run again"
      exit 1
    fi
  fi
  if ! command -v apt-get >/dev/null 2>&1; then
    log "missing system packages: $miss (no apt-get here: install gfortran, netCDF-Fortran, LAPACK by hand)"
    exit 1
  fi
  log "installing system packages: $miss"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq $miss >/dev/null
  miss=$(missing_system)
  if [ -n "$miss" ]; then
    log "still missing after apt-get: $miss"
    exit 1
  fi
}

install_python() {
  if [ ! -x "$VENV/bin/python" ]; then
    log "creating $VENV"
    # system site packages: reuse what the machine already has (numpy, meson...)
    "$PYTHON" -m venv --system-site-packages "$VENV"
  fi
  log "installing Python packages"
  "$VENV/bin/python" -m pip install -q --disable-pip-version-check \
    "numpy>=1.26" "meson>=1.1" "meson-python>=0.17" ninja \
    "xarray>=2023.1" "netCDF4>=1.6" "matplotlib>=3.6" \
    "pytest>=7" "pytest-xdist>=3" "hypothesis>=6" "pandas>=2.2" scipy "pydantic>=2,<3" psutil click parse unsync \
    compliance-checker pyyaml jsonschema build
  # captif-slp (an established ISO 13473-1 implementation, a test reference)
  # and its reader pyrsona 1.x pin pandas<2.2 and numpy<2, which would break
  # xarray and the extension: install them without their pins (their other
  # requirements are above); they run on the current pandas and numpy.
  "$VENV/bin/python" -m pip install -q --disable-pip-version-check --no-deps \
    "pyrsona>=1.1,<2" "captif-slp>=0.22"
  log "building and installing pavefric (Fortran core, program, Python extension)"
  "$VENV/bin/python" -m pip install -q --disable-pip-version-check --no-build-isolation \
    --force-reinstall --no-deps .
}

install_system
install_python

case "${1:-}" in
  demo)
    mkdir -p outputs
    "$VENV/bin/pavefric" inputs/ctm_dry.nml -o outputs/ctm_dry.nc
    "$VENV/bin/pavefric" inputs/ctm_wet.nml -o outputs/ctm_wet.nc
    "$VENV/bin/pavefric" inputs/ctm_squeeze.nml -o outputs/ctm_squeeze.nc
    "$VENV/bin/pavefric" inputs/ctm_reynolds.nml -o outputs/ctm_reynolds.nc
    "$VENV/bin/python" -m pavefric plot outputs/ctm_dry.nc outputs/ctm_wet.nc \
      outputs/ctm_squeeze.nc outputs/ctm_reynolds.nc -o outputs/ctm_mu_speed.png \
      --title "CTM-like medium texture (MPD 0.74 mm), mu_loc = 0.6, 1 mm water"
    ;;
  test)
    shift
    # the suite on one process per core, at most 4 (pytest-xdist), each test
    # file whole on one of them (its module fixtures computed once); a
    # pytest option given after `test` (-n 0: serially) overrides. Test
    # paths under tests/ given after `test` (tests/test_energy.py,
    # tests/test_x.py::test_y) run alone; without any, the whole suite runs.
    where=tests
    for arg in "$@"; do
      case "$arg" in -*) continue ;; esac
      case "$(realpath -m -- "${arg%%::*}")" in
        "$PWD"/tests|"$PWD"/tests/*) where= ; break ;;
      esac
    done
    "$VENV/bin/python" -m pytest -q -n "$(bash tools/test_workers.sh)" --dist loadfile \
      $where "$@"
    ;;
  "")
    log "ready: $VENV/bin/pavefric and $VENV/bin/python -m pavefric"
    ;;
  *)
    log "unknown command '$1' (expected demo, test or nothing)"
    exit 2
    ;;
esac
