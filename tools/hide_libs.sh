#!/usr/bin/env bash
# Run a command as on a machine without the system libraries that a normal
# build of pavefric links: each is covered by /dev/null in a private mount
# namespace (root, util-linux unshare), so loading it fails.
#
#   bash tools/hide_libs.sh LIST -- COMMAND ...
#
# LIST: one library path a line (.ci/run makes it from ldd of the program
# and the extension, less glibc, libstdc++, libgcc_s and libz, which a
# manylinux wheel takes from the system, and less the Python interpreter's
# own libraries).
set -euo pipefail
list=${1:?usage: tools/hide_libs.sh LIST -- COMMAND ...}
shift
[ "${1:-}" = "--" ] && shift
exec unshare --mount --propagation private bash -c '
  while read -r lib; do
    [ -n "$lib" ] && mount --bind /dev/null "$(readlink -f "$lib")"
  done < "$0"
  exec "$@"' "$list" "$@"
