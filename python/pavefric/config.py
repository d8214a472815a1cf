"""``pavefric-config``: where a pip-installed pavefric keeps its library.

As numpy's ``numpy-config``: other builds find libpavefric, ``pavefric.h``
and the Fortran ``.mod`` files through ``pavefric.pc``::

    PKG_CONFIG_PATH=$(pavefric-config --pkgconfigdir) pkg-config --cflags --libs pavefric

Everything lives inside the package (``pavefric/lib``, ``pavefric/include``);
the ``.pc`` file's paths are relative to itself, so they hold wherever pip
put the package. docs/api.md shows the C and Fortran use.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

_PACKAGE = Path(__file__).resolve().parent


def pkgconfigdir() -> Path:
    """Directory of ``pavefric.pc``."""
    return _PACKAGE / "lib" / "pkgconfig"


def libdir() -> Path:
    """Directory of ``libpavefric.so`` and ``libpavefric.a``."""
    return _PACKAGE / "lib"


def includedir() -> Path:
    """Directory of ``pavefric.h`` (the ``.mod`` files are in ``pavefric/<compiler>``)."""
    return _PACKAGE / "include"


def program() -> Path:
    """The Fortran program ``pavefric`` shipped inside the package (what the
    ``pavefric`` command on PATH executes; in an editable install, the build
    directory's)."""
    from _pavefric_program import program_path

    return program_path()


def main(argv: list[str] | None = None) -> int:
    from . import __version__

    parser = argparse.ArgumentParser(
        prog="pavefric-config",
        description="Where pavefric's C/Fortran library, header, .mod files and pavefric.pc "
                    "are installed (use with pkg-config).")
    parser.add_argument("--pkgconfigdir", action="store_true",
                        help="directory of pavefric.pc: PKG_CONFIG_PATH=$(pavefric-config "
                             "--pkgconfigdir) pkg-config --cflags --libs pavefric")
    parser.add_argument("--libdir", action="store_true", help="directory of libpavefric")
    parser.add_argument("--includedir", action="store_true", help="directory of pavefric.h")
    parser.add_argument("--program", action="store_true",
                        help="the Fortran program that the pavefric command runs")
    parser.add_argument("--version", action="store_true", help="pavefric's version")
    args = parser.parse_args(argv)
    lines = []
    if args.program:
        lines.append(str(program()))
    if args.pkgconfigdir:
        lines.append(str(pkgconfigdir()))
    if args.libdir:
        lines.append(str(libdir()))
    if args.includedir:
        lines.append(str(includedir()))
    if args.version:
        lines.append(__version__)
    if not lines:
        parser.print_help()
        return 2
    wants_library = args.pkgconfigdir or args.libdir or args.includedir
    if wants_library and not (pkgconfigdir() / "pavefric.pc").is_file():
        print(f"pavefric-config: {pkgconfigdir() / 'pavefric.pc'} is missing (the library is "
              "installed with 'pip install .', not with an editable install)", file=sys.stderr)
        return 1
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main())
