"""``python -m pavefric speed-gradient``: the wet models against PIARC's speed gradient."""
from __future__ import annotations

import argparse

NAME = "speed-gradient"
HELP = "the wet models' speed gradient against PIARC (docs/speed_gradient.md)"
EXAMPLES = ("python -m pavefric speed-gradient",
            "python -m pavefric speed-gradient --quick --report /tmp/speed_gradient.md")
CHECKOUT = True


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--report", default="docs/speed_gradient.md")
    p.add_argument("--quick", action="store_true", help="three MPD levels only")


def main(args: argparse.Namespace) -> int:
    from ..studies.speed_gradient import run_study

    run_study(args.report, quick=args.quick)
    return 0
