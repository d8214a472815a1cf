"""Command line of the Python layer: ``python -m pavefric COMMAND ...``.

Each command is a module of ``pavefric.cli`` with its own ``--help`` and
examples (``python -m pavefric COMMAND --help``); ``python -m pavefric
--help`` lists them. The report commands (bench, validate, docs,
speed-gradient, rubber-report, surfaces) are the maintainers': they read and
write the checkout's inputs/ and docs/, and refuse in one line (exit status
2) elsewhere.
"""
from __future__ import annotations

import sys

from .cli import checkout_commands, in_checkout, main

#: The maintainers' commands, which need a checkout as the current directory.
CHECKOUT_COMMANDS = checkout_commands()

__all__ = ["CHECKOUT_COMMANDS", "in_checkout", "main"]

if __name__ == "__main__":
    sys.exit(main())
