#!/usr/bin/env bash
# Where the core's time goes, as docs/performance.md ("Where the time goes")
# reports it.
#
#   tools/profile_kernel.sh [python]              # perf: shares of the samples
#   tools/profile_kernel.sh --callgrind [python]  # valgrind: instruction counts
#
# python defaults to .venv/bin/python, else python3. To profile another
# build: PYTHONPATH=<its site-packages> tools/profile_kernel.sh.
#
# perf workloads (one thread, no error-estimate pass and no refinement of the
# pad, min_contacts = 0, as the benchmark's sweep):
#   dry    the benchmark's coarse surface (rms 1 mm, 65,536 points, closed),
#          6 speeds 10-80 km/h, 20 runs;
#   wet    the same at 1 mm of water (the paper's bearing), 10 runs;
#   squeeze  the same with the drainage film (wet_model = 'squeeze'), 10
#          runs (with --callgrind only);
#   calls  500 runs on a 64-point profile (the fixed cost of one call:
#          reading the scene, echoing it, building the outputs).
# --callgrind counts instructions instead (slow, but the counts do not move
# with the load of a shared host as times do): one dry, one wet and one
# squeeze run on 16,384 points of the same surface; the instructions in the
# core (and libm's logarithm and erfc) per function and in total.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
mode=perf
if [ "${1:-}" = "--callgrind" ]; then mode=callgrind; shift; fi
py="${1:-}"
if [ -z "$py" ]; then
    if [ -x "$here/.venv/bin/python" ]; then py="$here/.venv/bin/python"; else py=python3; fi
fi
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cat > "$work/load.py" <<'PYEOF'
import sys, time, warnings
import numpy as np
import pavefric
from pavefric.surfaces import spectral_profile

warnings.simplefilter("ignore")
kind = sys.argv[1]
z0 = spectral_profile(1024, 0.87e-3, rms=1.0e-3, skew=-0.6, seed=23)
speeds = [10.0, 20.0, 30.0, 40.0, 60.0, 80.0]
z, kw, runs = np.tile(z0, 64), {}, 20
if kind == "calls":
    z, runs = z0[:64], 500
elif kind == "wet":
    kw, runs = {"depth": 1e-3}, 10
elif kind == "squeeze":
    kw, runs = {"depth": 1e-3, "wet_model": "squeeze"}, 10
if len(sys.argv) > 2:                      # --callgrind: one run, 16,384 points
    z, runs = np.tile(z0, 16), 1
best = float("inf")
for _ in range(runs):
    t0 = time.perf_counter()
    pavefric.simulate(z, 0.87e-3, speeds, error_estimate=False, min_contacts=0, **kw)
    best = min(best, time.perf_counter() - t0)
print(f"-- one run: {best * 1e3:.2f} ms (best of {runs}, under the profiler)")
PYEOF

if [ "$mode" = callgrind ]; then
    command -v valgrind >/dev/null || { echo "profile_kernel.sh: valgrind not found" >&2; exit 2; }
    for kind in dry wet squeeze; do
        OMP_NUM_THREADS=1 valgrind -q --tool=callgrind --callgrind-out-file="$work/$kind.cg" \
            "$py" "$work/load.py" "$kind" once >/dev/null 2>&1
        echo "== $kind: instructions (one run, 16,384 points, 6 speeds) =="
        callgrind_annotate "$work/$kind.cg" 2>/dev/null | grep -E '_core\.|e_log|s_erf' \
            | sed -e 's/ *\[.*//' -e 's/???://' -e 's/[^ ]*e_log\.c://' -e 's/[^ ]*s_erf\.c://' \
            > "$work/$kind.rows" || true
        awk '{gsub(",", "", $1); s += $1} END {printf "-- the core and libm: %.0f M\n", s / 1e6}' \
            "$work/$kind.rows"
        head -8 "$work/$kind.rows"
        echo
    done
    exit 0
fi

command -v perf >/dev/null || { echo "profile_kernel.sh: perf not found (install linux-tools)" >&2; exit 2; }
for kind in dry wet calls; do
    echo "== $kind: share of the samples (self time) =="
    OMP_NUM_THREADS=1 perf record -q -o "$work/$kind.data" "$py" "$work/load.py" "$kind" \
        2>/dev/null
    echo "-- by library (the Python interpreter's share includes importing pavefric once)"
    perf report -q -i "$work/$kind.data" --no-children --sort dso --stdio 2>/dev/null \
        | sed -e 's/ \+$//' -e '/^$/d' | head -6
    echo "-- the core's functions (inlined routines count in their caller)"
    perf report -q -i "$work/$kind.data" --no-children --sort sym --stdio 2>/dev/null \
        | grep -E 'pavefric|f2py' | sed -e 's/ \+$//' | head -8
    echo
done
