"""The command line, ``python -m pavefric COMMAND ...``: one module of this
package per command (``pavefric.cli.run``, ``pavefric.cli.bench``, ...),
each declaring its name, its one-line help, its examples, its arguments and
what it does. This module only gathers them into an argparse parser with
subcommands and turns the library's errors into one line on stderr.

A command module defines:

- ``NAME``: the command's name on the command line;
- ``HELP``: one line for ``python -m pavefric --help``;
- ``DESCRIPTION`` (optional): a paragraph for the command's own ``--help``;
- ``EXAMPLES``: command lines shown at the end of the command's ``--help``;
- ``CHECKOUT`` (optional, default False): a maintainers' command that reads
  or writes the checkout's inputs/ and docs/ and refuses elsewhere;
- ``add_arguments(parser)``, ``main(args) -> int`` (the exit status), and
  optionally ``needs_checkout(args) -> bool``.

Adding a command is a new module here and its name in ``COMMANDS``.
"""
from __future__ import annotations

import argparse
import importlib
import sys
import warnings
from pathlib import Path
from types import ModuleType

#: The command modules, in the order ``--help`` lists them.
COMMANDS = ("run", "plot", "surface", "accuracy", "bench", "calibrate", "surfaces", "validate",
            "profile", "docs", "speed_gradient", "prony", "rubber_report", "merge", "example")


def commands() -> dict[str, ModuleType]:
    """Every command module, by its command-line name."""
    mods = [importlib.import_module(f"{__name__}.{name}") for name in COMMANDS]
    return {m.NAME: m for m in mods}


def checkout_commands() -> tuple[str, ...]:
    """The maintainers' commands, which need a checkout as the current directory."""
    return tuple(name for name, m in commands().items() if getattr(m, "CHECKOUT", False))


def in_checkout(directory: Path | None = None) -> bool:
    """Whether ``directory`` (default: the current one) is the root of a
    pavefric checkout: its meson.build, src/ and inputs/ are there."""
    root = Path.cwd() if directory is None else directory
    return ((root / "meson.build").is_file() and (root / "src").is_dir()
            and (root / "inputs").is_dir())


def build_parser() -> tuple[argparse.ArgumentParser, dict[str, ModuleType]]:
    """The parser of every command, and the command modules by name."""
    from .. import __version__

    parser = argparse.ArgumentParser(
        prog="python -m pavefric",
        description="pavefric: pavement friction (Kane et al. 2017). Each command has its "
                    "own --help with examples.")
    parser.add_argument("--version", action="version", version=f"pavefric {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    mods = commands()
    for name, mod in mods.items():
        examples = "examples:\n" + "\n".join(f"  {line}" for line in mod.EXAMPLES)
        p = sub.add_parser(name, help=mod.HELP,
                           description=getattr(mod, "DESCRIPTION", None) or mod.HELP,
                           epilog=examples, formatter_class=argparse.RawDescriptionHelpFormatter)
        mod.add_arguments(p)
    return parser, mods


def _one_line(message, category, filename, lineno, line=None) -> str:
    """warnings.formatwarning for the commands: 'pavefric: warning: ...'."""
    sys.stdout.flush()
    return f"pavefric: warning: {message}\n"


def main(argv: list[str] | None = None) -> int:
    """Run one command; return its exit status (0 done, 1 an error named in
    one line on stderr, 2 a maintainers' command outside a checkout, 4 a
    batch in which some profiles failed)."""
    parser, mods = build_parser()
    args = parser.parse_args(argv)
    mod = mods[args.command]
    if getattr(mod, "CHECKOUT", False):
        needed = mod.needs_checkout(args) if hasattr(mod, "needs_checkout") else True
        if needed and not in_checkout():
            print(f"pavefric: error: 'python -m pavefric {args.command}' is a maintainer "
                  "command and needs a pavefric checkout (meson.build, src/ and inputs/ in the "
                  f"current directory, {Path.cwd()}): run it from the repository's root",
                  file=sys.stderr)
            return 2
    from ..core import PavefricError
    from ..merge import MergeError

    # a warning is one line, as the program prints it (not the source line
    # that raised it), after what the command has printed so far (stdout
    # flushed first: redirected to a file, its buffer put each run's
    # warnings above that run's own table)
    formatted = warnings.formatwarning
    warnings.formatwarning = _one_line
    try:
        return int(mod.main(args) or 0)
    except (PavefricError, MergeError) as exc:
        print(f"pavefric: error: {exc}", file=sys.stderr)
        return 1
    finally:
        warnings.formatwarning = formatted
