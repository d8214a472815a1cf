"""``python -m pavefric calibrate``: fit model parameters to measured friction."""
from __future__ import annotations

import argparse

NAME = "calibrate"
HELP = "fit model parameters to measured friction (CSV)"
DESCRIPTION = ("Least-squares fit (scipy least_squares, parameters fitted as log p) of model "
               "parameters to measured friction; every evaluation runs the core. See "
               "docs/calibration.md.")
EXAMPLES = ("python -m pavefric calibrate measured.csv --fit alpha --speeds 20",
            "python -m pavefric calibrate measured.csv --fit alpha beta --profile beta "
            "-o fit.json")


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("data", help="CSV with columns surface,speed_kmh,mu")
    p.add_argument("--scenes", default="inputs/surfaces",
                   help="directory of <surface>.nml scenes")
    p.add_argument("--fit", nargs="+", default=["alpha"],
                   help="parameters: alpha beta viscosity ... or mu_loc:<SURFACE>")
    p.add_argument("--speeds", type=float, nargs="+", default=None,
                   help="use only these speeds (km/h)")
    p.add_argument("--source", default=None,
                   help="use only rows whose 'source' column is this (e.g. dft)")
    p.add_argument("--start", nargs="+", default=None,
                   help="start values, NAME=VALUE (default: the scenes' values)")
    p.add_argument("--bounds", nargs="+", default=None,
                   help="search bounds, NAME=LO:HI (default: wide physical ranges)")
    p.add_argument("--level", type=float, default=0.95,
                   help="confidence level of the intervals (default 0.95)")
    p.add_argument("--profile", nargs="+", default=None, metavar="NAME",
                   help="also a profile-likelihood interval for these parameters")
    p.add_argument("--max-evaluations", type=int, default=None,
                   help="limit of least_squares evaluations (default 100 per parameter)")
    p.add_argument("-o", "--output", default=None, help="write the fit as JSON")


def main(args: argparse.Namespace) -> int:
    from ..calibrate import main_calibrate

    return main_calibrate(args)
