"""``python -m pavefric validate``: the paper's Table 2 (docs/validation.md)."""
from __future__ import annotations

import argparse

NAME = "validate"
HELP = "calibrate on 20 km/h and regenerate docs/validation.md"
DESCRIPTION = ("Calibrate the wet model's constant on the paper's 20 km/h points, predict 40 "
               "and 60 km/h, and regenerate docs/validation.md and outputs/validation/.")
EXAMPLES = ("python -m pavefric validate",
            "python -m pavefric validate --quick --report /tmp/validation.md --outdir /tmp/v")
CHECKOUT = True


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--table", default=None, help="kane2017_tables.csv")
    p.add_argument("--report", default="docs/validation.md")
    p.add_argument("--outdir", default="outputs/validation")
    p.add_argument("--quick", action="store_true", help="fewer speeds in the curves")
    p.add_argument("-q", "--quiet", action="store_true",
                   help="no progress on stderr (sections done, elapsed, left)")


def main(args: argparse.Namespace) -> int:
    from ..studies.validation import validate

    validate(table=args.table, report=args.report, outdir=args.outdir, quick=args.quick,
             quiet=args.quiet)
    return 0
