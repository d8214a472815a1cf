"""``python -m pavefric bench``: the performance figures (docs/performance.md)."""
from __future__ import annotations

import argparse

NAME = "bench"
HELP = "benchmark the core against the plain loop (and a NumPy reference, if given)"
DESCRIPTION = ("Throughput, scaling, memory, threads, MPI and the cost of accuracy, each "
               "measured beside the plain loop (MODEL.md written the obvious way in Fortran, "
               "shipped with the studies) in the same run; with --reference, also beside the "
               "independent NumPy reference (the tests' oracle, tests/reference.py in a "
               "checkout). A maintainers' command: run it from the checkout's root.")
EXAMPLES = ("python -m pavefric bench --quick",
            "python -m pavefric bench --report docs/performance.md --reference tests/reference.py")
CHECKOUT = True


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--report", default=None, help="write docs/performance.md here")
    p.add_argument("--reference", default=None, metavar="PY",
                   help="a Python file with the model's simulate() to time beside the core "
                        "(the NumPy reference: tests/reference.py); without it, no NumPy "
                        "figures")
    p.add_argument("--quick", action="store_true",
                   help="small sizes, one repeat: check that it runs (not a measurement)")
    p.add_argument("--largest", type=int, default=10_000_000,
                   help="largest profile of the length scaling (points)")
    p.add_argument("-q", "--quiet", action="store_true",
                   help="no progress on stderr (sections done, elapsed, left)")


def main(args: argparse.Namespace) -> int:
    from ..studies.bench import run as bench_run

    bench_run(args.report, args.largest, quick=args.quick, quiet=args.quiet,
              reference=args.reference)
    return 0
