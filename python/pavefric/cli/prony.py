"""``python -m pavefric prony``: a Prony series (&rubber) from dynamic mechanical data."""
from __future__ import annotations

import argparse
import sys

NAME = "prony"
HELP = "fit a Prony series to dynamic mechanical data and write the &rubber group"
DESCRIPTION = ("Fit a generalised Maxwell (Prony) series to DMA data (CSV with a header: "
               "temperature_c (optional), frequency_hz or omega_rad_s, storage_pa or "
               "storage_mpa, loss_pa or loss_mpa; '#' comments), shifted to a master curve by "
               "the WLF equation, by non-negative least squares; write the &rubber group "
               "(moduli divided by the rubber thickness). See docs/rubber.md.")
EXAMPLES = ("python -m pavefric prony dma.csv -o compound.nml --plot master.png",
            "python -m pavefric prony dma.csv --fit-wlf --modulus shear --thickness 0.008",
            "python -m pavefric prony --write-representative tread_dma.csv")


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("data", nargs="?", help="DMA CSV file")
    p.add_argument("-o", "--output", default=None,
                   help="namelist fragment to write (default: print it)")
    p.add_argument("--reference-temperature", type=float, default=20.0,
                   help="Tref of the master curve, degC (default 20)")
    p.add_argument("--c1", type=float, default=8.86, help="WLF C1 (default 8.86)")
    p.add_argument("--c2", type=float, default=101.6, help="WLF C2, K (default 101.6)")
    p.add_argument("--fit-wlf", action="store_true",
                   help="also fit C1 and C2 (data at several temperatures)")
    p.add_argument("--thickness", type=float, default=0.006,
                   help="rubber thickness h (m): K = E / h (default 0.006, the DFT pad)")
    p.add_argument("--modulus", choices=["tensile", "shear"], default="tensile",
                   help="the data's moduli: Young's (E', E'') or shear (G', G''; E = 3G)")
    p.add_argument("--per-decade", type=float, default=1.0,
                   help="relaxation times per decade of the candidate set (default 1)")
    p.add_argument("--plot", default=None, help="PNG of the master curve and the fit")
    p.add_argument("--write-representative", default=None, metavar="CSV",
                   help="write the representative tread compound's data set here")


def main(args: argparse.Namespace) -> int:
    from ..rubber import main_prony

    try:
        return main_prony(args)
    except ValueError as exc:
        print(f"pavefric: error: {exc}", file=sys.stderr)
        return 1
