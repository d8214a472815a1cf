"""``python -m pavefric merge``: join a survey's batch outputs run in parts."""
from __future__ import annotations

import argparse

NAME = "merge"
HELP = "join batch outputs of one survey run in parts (job arrays)"
DESCRIPTION = ("Join the batch outputs of one survey run in parts (each part a batch over its "
               "own profiles, with the same physics, depths and speeds) into one file, along "
               "'profile', in the order given. Refuses parts that ran other physics, depths or "
               "speeds, or that share a profile. docs/cluster.md.")
EXAMPLES = ("python -m pavefric merge part_*.nc -o survey_results.nc",)


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("parts", nargs="+", help="batch outputs (NetCDF)")
    p.add_argument("-o", "--output", required=True, help="the merged file")


def main(args: argparse.Namespace) -> int:
    from ..merge import merge

    print(f"wrote {merge(args.parts, args.output)}")
    return 0
