#!/usr/bin/env bash
# Build the C and Fortran examples against the installed libpavefric, with
# the flags pkg-config reads from pavefric.pc (which pavefric-config finds
# inside the pip-installed package), then run both on a scene.
#
#   bash build.sh [SCENE.nml]     # default: python -m pavefric example's ctm_wet.nml
#
# Needs pavefric-config on PATH (an activated environment with pavefric),
# pkg-config, cc and gfortran (the one that built pavefric: .mod files are
# compiler-specific).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
PKG_CONFIG_PATH=$(pavefric-config --pkgconfigdir)
export PKG_CONFIG_PATH
cc "$here/example.c" $(pkg-config --cflags --libs pavefric) -o example_c
gfortran "$here/example.f90" $(pkg-config --cflags --libs pavefric) -o example_f
echo "built ./example_c and ./example_f against pavefric $(pkg-config --modversion pavefric)"
scene=${1:-}
if [ -z "$scene" ]; then
  python -m pavefric example api-scenes >/dev/null
  scene=api-scenes/ctm_wet.nml
fi
echo "C:"
./example_c "$scene"
echo "Fortran:"
./example_f "$scene"
