#!/usr/bin/env bash
# ThreadSanitizer check of the C API (issue 19): build the library with
# -fsanitize=thread (OpenMP off: libgomp is not instrumented, and its
# barriers look like races to TSan; MPI off), build tests/api/check_api.c
# against it with -fsanitize=thread, run its "stress" mode (scenes from
# namelist text on several threads at once, set_parameter/get_parameter/
# run/results/warnings interleaved, every fifth job also reading a scene
# file and writing NetCDF under the files lock), and fail on any
# ThreadSanitizer report whose stack passes through pavefric's code.
#
#   tests/tsan/run_tsan.sh [BUILD_DIR [THREADS JOBS]]
#
# BUILD_DIR defaults to build-tsan in the source tree (kept: a second run
# only rebuilds what changed). Needs the venv's meson/ninja on PATH (setup.sh).
# Exit 0: no report in pavefric code; 1: reports (printed); 2: build failed.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build-tsan}
threads=${2:-4}
jobs=${3:-16}
if [ ! -f "$build/build.ninja" ]; then
    meson setup "$build" "$root" -Dopenmp=disabled -Dmpi=disabled \
        -Dbuildtype=debugoptimized -Db_sanitize=thread >"$build.setup.log" 2>&1 ||
        { cat "$build.setup.log"; exit 2; }
fi
meson compile -C "$build" pavefric:shared_library >"$build.build.log" 2>&1 ||
    { tail -40 "$build.build.log"; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
gcc -g -O1 -fsanitize=thread -I"$root/src/api" -o "$work/check_api" "$root/tests/api/check_api.c" \
    -L"$build/src" -Wl,-rpath,"$build/src" -lpavefric -lm -pthread ||
    exit 2
log="$work/tsan.log"
status=0
TSAN_OPTIONS="halt_on_error=0 exitcode=0 history_size=4 second_deadlock_stack=1 log_path=$work/tsan" \
    "$work/check_api" stress "$threads" "$jobs" "$root/inputs/ctm_wet.nml" "$work" ||
    status=$?
cat "$work"/tsan.* >"$log" 2>/dev/null || true
reports=$(grep -c '^WARNING: ThreadSanitizer' "$log" || true)
# A report counts when one of its frames is pavefric's (a symbol or a source
# file) -- except a lock-order inversion between libgfortran's own mutexes
# (every mutex in the cycle taken inside libgfortran: its global unit-table
# lock and the per-unit locks, internal units for to_str's writes against
# file units at a close; the per-unit mutexes live on the heap, and TSan
# sees two units at one reused address as one mutex). Those are counted
# and printed apart.
read -r ours runtime < <(awk '
    function finish() { if (inrep) { if (hit && !(inversion && only_runtime)) n++;
                                      else if (inversion && only_runtime) r++ } inrep = 0 }
    /^WARNING: ThreadSanitizer/ { finish(); inrep = 1; hit = 0;
        inversion = /lock-order-inversion/; only_runtime = 1; want = 0; next }
    !inrep { next }
    /acquired here while holding/ { want = 1; next }
    want && /#0 pthread_mutex_lock/ { next }
    want && /#1 / { if ($0 !~ /libgfortran/) only_runtime = 0; want = 0 }
    /pavefric/ { hit = 1 }
    /^SUMMARY: ThreadSanitizer/ { finish() }
    END { finish(); print n + 0, r + 0 }' "$log")
echo "run_tsan: check_api stress exit $status; ThreadSanitizer reports: $reports, in pavefric code: $ours (lock-order inversions inside libgfortran: $runtime)"
if [ "$ours" -gt 0 ] || [ "$status" -ne 0 ]; then
    cat "$log"
    exit 1
fi
exit 0
