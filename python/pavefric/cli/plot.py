"""``python -m pavefric plot``: friction against speed from NetCDF outputs."""
from __future__ import annotations

import argparse
from pathlib import Path

NAME = "plot"
HELP = "plot mu against speed from NetCDF outputs"
EXAMPLES = ("python -m pavefric plot outputs/ctm_dry.nc outputs/ctm_wet.nc -o outputs/mu.png",)


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("files", nargs="+", help="NetCDF outputs of pavefric runs")
    p.add_argument("-o", "--output", required=True, help="PNG path")
    p.add_argument("--title", default=None)


def main(args: argparse.Namespace) -> int:
    from ..core import PavefricError
    from ..plot import plot_mu_speed

    for f in args.files:
        if not Path(f).is_file():
            raise PavefricError(f"plot: '{f}': no such file (give NetCDF outputs of "
                                "pavefric runs)")
    try:
        print(f"wrote {plot_mu_speed(args.files, args.output, title=args.title)}")
    except OSError as exc:
        raise PavefricError(f"plot: cannot read {args.files} as pavefric outputs "
                            f"({exc}); give NetCDF outputs of pavefric runs") from None
    return 0
