"""The ``pavefric`` command: replaces itself with the Fortran program.

pip installs the program inside the package (``pavefric/bin/pavefric``,
src/meson.build) and this console script on PATH, because an editable
install (``pip install --no-build-isolation -e .``) takes a project's
console scripts but not the executables of a wheel's scripts directory; so
``pavefric`` is there after either install.

The launcher is a top-level module, not part of the ``pavefric`` package,
so that it does not import the package (NumPy, 0.2-0.4 s) before every run
of the program. It ``exec``s the program: the process id, signals, the exit
status, stdin/stdout/stderr and an MPI rank's environment are the program's
own, so ``mpirun -n 4 pavefric batch.nml`` and a ``kill`` of a run work as
with the bare executable. In an editable install, finding the package
rebuilds what changed first (meson-python), as ``import pavefric`` does.
"""
from __future__ import annotations

import importlib.util
import os
import sys
from pathlib import Path

#: The program's path inside the package.
RELATIVE_PATH = ("bin", "pavefric")


def program_path() -> Path:
    """The Fortran program shipped in the installed ``pavefric`` package
    (the build directory's, in an editable install).

    Returns
    -------
    pathlib.Path
        The executable (it may be missing if the install is broken).

    Raises
    ------
    FileNotFoundError
        No ``pavefric`` package can be found by this interpreter.
    """
    spec = importlib.util.find_spec("pavefric")   # no import of the package itself
    if spec is None:
        raise FileNotFoundError(f"no pavefric package for {sys.executable}")
    if spec.origin:
        here = Path(spec.origin).parent.joinpath(*RELATIVE_PATH)
        if here.exists():
            return here
    # an editable install: meson-python's loader maps the package's installed
    # files to the build directory
    reader = getattr(spec.loader, "get_resource_reader", None)
    files = getattr(reader(spec.name), "files", None) if reader else None
    if files is not None:
        found = files().joinpath(*RELATIVE_PATH)
        if isinstance(found, Path):
            return found
    return Path(spec.origin or "pavefric").parent.joinpath(*RELATIVE_PATH)


def main() -> int:
    try:
        exe = program_path()
    except FileNotFoundError as exc:
        print(f"pavefric: error: {exc}", file=sys.stderr)
        return 1
    if not os.access(exe, os.X_OK):
        print(f"pavefric: error: the program {exe} is missing or not executable: reinstall "
              "pavefric", file=sys.stderr)
        return 1
    sys.stdout.flush()
    sys.stderr.flush()
    os.execv(exe, [sys.argv[0], *sys.argv[1:]])
    return 1  # not reached


if __name__ == "__main__":
    sys.exit(main())
