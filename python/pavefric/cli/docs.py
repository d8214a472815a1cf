"""``python -m pavefric docs``: the reference documents, from the core's declarations."""
from __future__ import annotations

import argparse

NAME = "docs"
HELP = "regenerate reference documents from the core's declarations"
DESCRIPTION = ("Write the namelist reference (docs/inputs.md) and the NetCDF output "
               "reference (docs/outputs.md) from the tables the core declares.")
EXAMPLES = ("python -m pavefric docs",
            "python -m pavefric docs --inputs /tmp/inputs.md --outputs /tmp/outputs.md")
CHECKOUT = True


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--inputs", default="docs/inputs.md",
                   help="where to write the namelist reference")
    p.add_argument("--outputs", default="docs/outputs.md",
                   help="where to write the NetCDF output reference")


def needs_checkout(args: argparse.Namespace) -> bool:
    """Only when it writes the checkout's docs/."""
    return args.inputs == "docs/inputs.md" or args.outputs == "docs/outputs.md"


def main(args: argparse.Namespace) -> int:
    from ..core import check_output
    from ..studies.docs import INPUTS_SIGNATURE, OUTPUTS_SIGNATURE, write_inputs, write_outputs

    # both pages checked before either is written (one path given to both,
    # however spelled, is check_output's "is also" error)
    check_output(args.inputs, [args.outputs], signature=INPUTS_SIGNATURE, writable=True)
    check_output(args.outputs, signature=OUTPUTS_SIGNATURE, writable=True)
    print(f"wrote {write_inputs(args.inputs)}")
    print(f"wrote {write_outputs(args.outputs)}")
    return 0
