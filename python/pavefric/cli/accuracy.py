"""``python -m pavefric accuracy``: what each numerical knob buys and costs."""
from __future__ import annotations

import argparse

NAME = "accuracy"
HELP = "accuracy-cost study of the numerical knobs"
DESCRIPTION = ("Run scenes at refined numerics (substeps, elements_per_sample, tolerance, "
               "the time schemes) and report each result's error against its cost "
               "(docs/accuracy.md).")
EXAMPLES = ("python -m pavefric accuracy inputs/ctm_dry.nml --speeds 20 60",
            "python -m pavefric accuracy inputs/surfaces/{GSP,GSS,GSSB,RSBA,MCA,VTAC}.nml "
            "--also-dry --wet-models squeeze reynolds --speeds 20 60 --report docs/accuracy.md")


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("scenes", nargs="+", help="scene namelists")
    p.add_argument("--speeds", type=float, nargs="+", default=None,
                   help="speeds in km/h (default: each scene's)")
    p.add_argument("--outdir", default="outputs/accuracy")
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--also-dry", action="store_true",
                   help="also study each scene with its water removed")
    p.add_argument("--wet-models", nargs="+", default=(), metavar="MODEL",
                   choices=("kane2017", "squeeze", "reynolds"),
                   help="also measure the time integrator's order (backward Euler, "
                        "extrapolated, exact) and the default run's error estimate on each "
                        "wet scene under these wet models (&water wet_model): the order "
                        "study only, not the knobs' and tolerances' tables")
    p.add_argument("--report", default=None,
                   help="also write a Markdown report here (e.g. docs/accuracy.md)")
    p.add_argument("-q", "--quiet", action="store_true",
                   help="no progress on stderr (runs done, elapsed, left)")


def main(args: argparse.Namespace) -> int:
    from ..studies.reports import accuracy_report

    accuracy_report(args.scenes, args.outdir, speeds=args.speeds, repeats=args.repeats,
                    report=args.report, also_dry=args.also_dry,
                    wet_models=tuple(args.wet_models), quiet=args.quiet)
    return 0
