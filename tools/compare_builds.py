"""Two builds of pavefric timed side by side on the benchmark's rubber and wet runs.

    python tools/compare_builds.py SITE_A SITE_B [--rounds 3] [--repeats 7]
                                   [--runs NAME ...]

SITE_A and SITE_B are directories holding a `pavefric` package each (an
installed site-packages, or a copy with another build's `_core` module).
Each round runs every build in its own process, one after the other (so the
host's load falls on both alike); each process times the paper's rubber,
the elastic pad (viscosity 0), a 3-arm Maxwell rubber (the benchmark's
Prony series), and the paper's rubber under 1 mm of water with the paper's
bearing (`paper_wet`) and with the Reynolds film (`reynolds_wet`), on the
benchmark's medium surface tiled to 65,536 points, 4 speeds, one thread, no
error estimate and no refinement of the pad, and keeps the best of
`repeats` runs of each; and the paper's rubber at one speed (60 km/h,
`kelvin_voigt_one_speed`: the single-lane path a batch of one speed or a
long profile takes). The table is the best over the rounds, in seconds per
run. --runs keeps the runs named (default: all).
"""
import argparse
import json
import os
import subprocess
import sys

CHILD = r"""
import json, sys, time, warnings
import numpy as np
import pavefric
from pavefric.surfaces import spectral_profile
warnings.simplefilter("ignore")
repeats = int(sys.argv[1])
z = np.tile(spectral_profile(1024, 0.87e-3, rms=0.5e-3, skew=-0.6, seed=23), 64)
speeds = [20.0, 40.0, 60.0, 80.0]
runs = {"kelvin_voigt": {}, "elastic": {"viscosity": 0.0},
        "maxwell_3_arms": {"rubber_model": "maxwell", "prony_stiffness": [1e8, 5e7, 2e7],
                           "prony_times": [1e-4, 1e-3, 1e-2]},
        "paper_wet": {"depth": 1e-3},
        "reynolds_wet": {"depth": 1e-3, "wet_model": "reynolds"},
        "kelvin_voigt_one_speed": {"speeds": [60.0]}}
keep = json.loads(sys.argv[2])
best = {}
for name, kw in runs.items():
    if keep and name not in keep:
        continue
    best[name] = float("inf")
    kw = dict(kw)
    these = kw.pop("speeds", speeds)
    for _ in range(repeats):
        t0 = time.perf_counter()
        pavefric.simulate(z, 0.87e-3, these, error_estimate=False, min_contacts=0, **kw)
        best[name] = min(best[name], time.perf_counter() - t0)
print(json.dumps(best))
"""


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("sites", nargs=2, help="two directories each holding a pavefric package")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--repeats", type=int, default=7)
    parser.add_argument("--runs", nargs="*", default=[],
                        help="kelvin_voigt, elastic, maxwell_3_arms, paper_wet, reynolds_wet, "
                        "kelvin_voigt_one_speed")
    args = parser.parse_args()
    best = {site: {} for site in args.sites}
    for _ in range(args.rounds):
        for site in args.sites:
            env = dict(os.environ, PYTHONPATH=site, OMP_NUM_THREADS="1")
            out = subprocess.run([sys.executable, "-c", CHILD, str(args.repeats),
                                  json.dumps(args.runs)], env=env,
                                 check=True, capture_output=True, text=True).stdout
            for name, seconds in json.loads(out.splitlines()[-1]).items():
                best[site][name] = min(best[site].get(name, float("inf")), seconds)
    names = list(best[args.sites[0]])
    width = {n: max(16, len(n) + 2) for n in names}
    print("build".ljust(40) + "".join(n.rjust(width[n]) for n in names))
    for site in args.sites:
        print(site[-40:].ljust(40) + "".join(f"{best[site][n]:{width[n]}.4f}" for n in names))


if __name__ == "__main__":
    main()
