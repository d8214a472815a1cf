"""The observed order of backward Euler's time step on a scene.

    python -m pavefric.studies.step_orders [scene.nml] [--speeds 20,60] [--levels 10]
                                           [--scheme euler|exact]

runs the scene (default ``inputs/ctm_wet.nml``, at 20 and 60 km/h) with
``time_scheme = 'euler'`` (or the one given), one pass per ``substeps`` = 1, 2, 4, ... (no
error estimate, no refinement of the pad: ``min_contacts = 0``) and prints,
per speed, mu, its change from the pass before, the ratio of two successive
changes (2 for an error falling as the step, 4 as its square) and the
observed order log2 of that ratio. ``simulate_to_tolerance``'s Richardson
value assumes first order (it extrapolates only where that ratio lies in
1.5-3); docs/numerics.md ("Known gaps") quotes this table for the paper's
wet scene, whose passes fall at second order from 2 to 64 substeps.
"""
from __future__ import annotations

import math
import sys
import warnings

import numpy as np

import pavefric

from .energy_report import _repo_file


def sequence(scene, speeds, levels: int, scheme: str = "euler") -> list[tuple[int, np.ndarray]]:
    """(substeps, mu per speed) for substeps = 1, 2, ..., 2**(levels - 1)."""
    kw = dict(scene.parameters)
    kw.update(time_scheme=scheme, min_contacts=0, error_estimate=False, tolerance=0.0)
    rows = []
    for level in range(levels):
        kw["substeps"] = 2 ** level
        ds = pavefric.simulate(scene.heights, scene.dx, speeds, closed=scene.closed, **kw)
        rows.append((2 ** level, ds["mu"].values.copy()))
    return rows


def ratios(rows: list[tuple[int, np.ndarray]]) -> list[tuple[int, np.ndarray, np.ndarray,
                                                                np.ndarray]]:
    """Per pass from the third: (substeps, change, ratio of the change before
    to this one, observed order log2(ratio)); the order is NaN where the two
    changes differ in sign or one is zero."""
    out = []
    for k in range(2, len(rows)):
        d1 = rows[k - 1][1] - rows[k - 2][1]
        d2 = rows[k][1] - rows[k - 1][1]
        with np.errstate(divide="ignore", invalid="ignore"):
            r = d1 / d2
            order = np.where(r > 0, np.log2(np.abs(r)), np.nan)
        out.append((rows[k][0], d2, r, order))
    return out


def main(argv: list[str] | None = None) -> None:
    args = list(sys.argv[1:] if argv is None else argv)
    speeds, levels, scheme = [20.0, 60.0], 10, "euler"
    if "--scheme" in args:
        i = args.index("--scheme")
        scheme = args[i + 1]
        del args[i:i + 2]
    if "--speeds" in args:
        i = args.index("--speeds")
        speeds = [float(v) for v in args[i + 1].split(",")]
        del args[i:i + 2]
    if "--levels" in args:
        i = args.index("--levels")
        levels = int(args[i + 1])
        del args[i:i + 2]
    path = args[0] if args else _repo_file("inputs", "ctm_wet.nml")
    warnings.simplefilter("ignore", pavefric.PavefricWarning)
    scene = pavefric.load_scene(path)
    rows = sequence(scene, speeds, levels, scheme)
    print(f"time_scheme = '{scheme}' on {path}: mu per substeps (min_contacts = 0, no error "
          "estimate)")
    print("substeps  " + "  ".join(f"{'mu at ' + format(v, 'g') + ' km/h':>16s}"
                                   f"{'change':>11s}{'ratio':>7s}{'order':>6s}" for v in speeds))
    table = {s: (d, r, o) for s, d, r, o in ratios(rows)}
    for k, (s, mu) in enumerate(rows):
        cells = []
        for j in range(len(speeds)):
            d, r, o = ("", "", "")
            if k >= 1:
                d = f"{mu[j] - rows[k - 1][1][j]:.2e}"
            if s in table:
                r = f"{table[s][1][j]:.2f}"
                o = "-" if math.isnan(table[s][2][j]) else f"{table[s][2][j]:.2f}"
            cells.append(f"{mu[j]:16.8f}{d:>11s}{r:>7s}{o:>6s}")
        print(f"{s:8d}  " + "  ".join(cells))


if __name__ == "__main__":
    main()
