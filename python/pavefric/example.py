"""The default scenes, shipped in the package: ``python -m pavefric example DIR``.

The wheel carries a copy of the checkout's ``inputs/ctm_dry.nml``,
``inputs/ctm_wet.nml``, ``inputs/ctm_squeeze.nml``, ``inputs/ctm_reynolds.nml`` and
the profile they read
(``inputs/profiles/ctm_medium.txt``) in ``pavefric/example/`` (installed by
python/meson.build), so that an installed pavefric runs its default scene from
any directory::

    python -m pavefric example my-run && cd my-run && pavefric ctm_dry.nml

The scenes are written as they are in the checkout, except that the "Run:"
line of their header names the scene as it now lies (``pavefric
ctm_dry.nml``, not ``pavefric inputs/ctm_dry.nml``).
"""
from __future__ import annotations

import os
import shutil
import sys
from importlib import resources
from pathlib import Path

#: What ``example`` writes, relative to its directory (and to ``inputs/`` of
#: a checkout, where the originals are).
FILES = ("ctm_dry.nml", "ctm_wet.nml", "ctm_squeeze.nml", "ctm_reynolds.nml",
         "profiles/ctm_medium.txt")

#: The directory written when none is given.
DEFAULT_DIRECTORY = "pavefric-example"


def shipped(name: str) -> bytes:
    """The packaged copy of ``inputs/<name>`` (one of FILES)."""
    data = (resources.files("pavefric") / "example" / name).read_bytes()
    if name.endswith(".nml"):
        data = data.replace(b"Run:  pavefric inputs/", b"Run:  pavefric ")
    return data


def write_example(directory: str | os.PathLike = DEFAULT_DIRECTORY, force: bool = False
                  ) -> list[Path]:
    """Write the default scenes and their profile into ``directory`` (made if
    missing); return the paths written.

    Raises FileExistsError naming the files that are there already unless
    ``force`` (nothing is written then), and PavefricError when a path may
    not be written (a directory, a FIFO, a device: pavefric's writer rule)
    or when a directory below ``directory`` is a symbolic link (``--force``
    would otherwise replace files in a directory the user did not name).
    """
    from .core import PavefricError, atomic_output, check_output

    root = Path(directory)
    targets = [root / name for name in FILES]
    for sub in sorted({t.parent for t in targets if t.parent != root}):
        if sub.is_symlink():
            raise PavefricError(f"'{sub}': is a symbolic link (to '{os.readlink(sub)}'); "
                                f"example writes only inside '{root}': remove the link or "
                                "choose another directory")
    present = [t for t in targets if os.path.lexists(t)]
    if present and not force:
        raise FileExistsError(f"{', '.join(map(str, present))}: already there (--force "
                              "overwrites)")
    for target in targets:
        check_output(target)
    for name, target in zip(FILES, targets):
        target.parent.mkdir(parents=True, exist_ok=True)
        with atomic_output(target) as tmp:
            tmp.write_bytes(shipped(name))
    return targets


def _command(name: str) -> str:
    """How to call ``name`` (the program or python) from the shell: its
    bare name when PATH finds this environment's, else its full path."""
    here = Path(sys.executable).parent / name
    found = shutil.which(name)
    if found and here.exists() and Path(found).resolve() == here.resolve():
        return name
    if name == "python":
        return sys.executable
    return str(here) if here.exists() else name


def next_steps(directory: str | os.PathLike) -> str:
    """The commands to run in ``directory`` after writing it."""
    program, python = _command("pavefric"), _command("python")
    return "\n".join([
        "next:",
        f"  cd {directory}",
        f"  {program} ctm_dry.nml        # dry -> outputs/ctm_dry.nc",
        f"  {program} ctm_wet.nml        # 1 mm of water, the paper's wet model",
        f"  {program} ctm_squeeze.nml    # 1 mm of water, the drainage model",
        f"  {program} ctm_reynolds.nml   # 1 mm of water, the Reynolds film",
        f"  {python} -m pavefric plot outputs/ctm_dry.nc outputs/ctm_wet.nc "
        "outputs/ctm_squeeze.nc outputs/ctm_reynolds.nc -o mu_speed.png",
    ])


__all__ = ["FILES", "DEFAULT_DIRECTORY", "shipped", "write_example", "next_steps"]
