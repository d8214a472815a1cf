"""``python -m pavefric example``: the default scenes, written where the user works."""
from __future__ import annotations

import argparse
import sys

NAME = "example"
HELP = "write the default scenes and their profile into a directory"
DESCRIPTION = ("Write the default scenes (ctm_dry.nml, ctm_wet.nml, ctm_squeeze.nml, ctm_reynolds.nml) and the "
               "profile they read (profiles/ctm_medium.txt), shipped in the package, into DIR, "
               "and print the commands to run next. Existing files are left alone unless "
               "--force.")
EXAMPLES = ("python -m pavefric example my-run && cd my-run && pavefric ctm_dry.nml",)


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("directory", nargs="?", default="pavefric-example",
                   help="where to write (default ./pavefric-example; made if missing)")
    p.add_argument("--force", action="store_true", help="overwrite files already there")


def main(args: argparse.Namespace) -> int:
    from ..example import next_steps, write_example

    try:
        written = write_example(args.directory, force=args.force)
    except FileExistsError as exc:
        print(f"pavefric: error: {exc}", file=sys.stderr)
        return 1
    for path in written:
        print(f"wrote {path}")
    print(next_steps(args.directory))
    return 0
