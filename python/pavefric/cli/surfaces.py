"""``python -m pavefric surfaces``: regenerate the paper's six reference surfaces."""
from __future__ import annotations

import argparse

NAME = "surfaces"
HELP = "(re)generate the six reference surfaces"
DESCRIPTION = ("Write the synthetic stand-ins of the paper's six Table 2 surfaces (profiles "
               "matched to their MPD, and their scenes) into inputs/surfaces (docs/validation.md).")
EXAMPLES = ("python -m pavefric surfaces",
            "python -m pavefric surfaces --outdir /tmp/surfaces --table kane2017_tables.csv")
CHECKOUT = True


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--outdir", default="inputs/surfaces")
    p.add_argument("--table", default=None, help="kane2017_tables.csv")
    p.add_argument("--alpha", type=float, default=None)
    p.add_argument("--beta", type=float, default=1.75)


def needs_checkout(args: argparse.Namespace) -> bool:
    """Only when it writes the checkout's inputs/surfaces or reads its table."""
    return args.outdir == "inputs/surfaces" or args.table is None


def main(args: argparse.Namespace) -> int:
    from ..studies.reference_surfaces import write_surfaces
    from ..studies.validation import CALIBRATED_ALPHA, default_table

    write_surfaces(args.outdir, args.table or default_table(),
                   alpha=CALIBRATED_ALPHA if args.alpha is None else args.alpha, beta=args.beta)
    return 0
