"""``python -m pavefric rubber-report``: the Maxwell rubber's report (docs/rubber.md)."""
from __future__ import annotations

import argparse

NAME = "rubber-report"
HELP = "the Maxwell rubber's friction against speed and temperature, and its cost (docs/rubber.md)"
EXAMPLES = ("python -m pavefric rubber-report",
            "python -m pavefric rubber-report --quick --report /tmp/rubber.md")
CHECKOUT = True


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--report", default="docs/rubber.md")
    p.add_argument("--compound", default="inputs/rubber/tread_compound.nml")
    p.add_argument("--quick", action="store_true", help="fewer speeds and temperatures")


def main(args: argparse.Namespace) -> int:
    from ..studies.rubber_report import run_report

    run_report(args.report, compound=args.compound, quick=args.quick)
    return 0
