"""``python -m pavefric run``: run a scene namelist (one profile or a batch)."""
from __future__ import annotations

import argparse
import sys
import warnings

NAME = "run"
HELP = "run a scene namelist and write NetCDF"
DESCRIPTION = ("Run a scene namelist with the same core as the program: one profile, or a "
               "&batch of many, into NetCDF (docs/inputs.md, docs/outputs.md). Exit status 4 "
               "when a batch finished but some profiles failed.")
EXAMPLES = ("python -m pavefric run inputs/ctm_dry.nml --plot outputs/ctm_dry.png",
            "python -m pavefric run inputs/batch_demo.nml -o outputs/batch.nc -q")


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("scene", help="the scene namelist")
    p.add_argument("-o", "--output", default=None, help="NetCDF output path")
    p.add_argument("--plot", default=None, help="also write a PNG of mu against speed")
    p.add_argument("-q", "--quiet", action="store_true",
                   help="no progress bar for a batch (warnings and errors still on stderr)")


def main(args: argparse.Namespace) -> int:
    from ..core import ProfilesFailedWarning, run
    from ..plot import _checked, plot_mu_speed

    if args.plot:
        # checked before the run: a refused figure path costs no run
        _checked(args.plot, [args.scene, args.output])
    # every warning is shown as it comes (the cost warning is said before the
    # run, so that an expensive run can be stopped: recorded and replayed, it
    # came only once the run had finished, attack20); a batch's failed
    # profiles are kept for the exit status
    failed = []
    with warnings.catch_warnings():
        warnings.simplefilter("always", ProfilesFailedWarning)
        shown = warnings.showwarning

        def show(message, category, filename, lineno, file=None, line=None):
            if issubclass(category, ProfilesFailedWarning):
                failed.append(message)
            else:
                shown(message, category, filename, lineno, file, line)

        warnings.showwarning = show
        out = run(args.scene, args.output, progress=False if args.quiet else None)
    print(f"wrote {out}")
    _print_table(out)
    if args.plot:
        print(f"wrote {plot_mu_speed([out], args.plot, inputs=[args.scene])}")
    if failed:
        # as the program: the batch finished, some profiles failed
        print(f"pavefric: {failed[0]}", file=sys.stderr)
        return 4
    return 0


def _print_table(path) -> None:
    """A single scene's friction against speed, as the program prints it
    (the core's text: pf_friction_table); a batch's file is a cube, which
    `python -m pavefric plot` shows."""
    from .. import _core
    from ..core import open_dataset

    with open_dataset(path) as ds:
        if "profile" in ds.dims or "mu" not in ds:
            return
        has_err = "mu_error_estimate" in ds
        columns = [ds[v].values.astype(float) for v in ("speed_kmh", "mu", "wet_fraction",
                                                         "hydroplaning_fraction")]
        err = ds["mu_error_estimate"].values.astype(float) if has_err else 0.0 * columns[0]
        head = (int(ds.attrs["pad_elements"]), int(ds.attrs["averaged_positions"]),
                str(ds.attrs.get("effects", "")))
    lines = []
    for start in range(0, columns[0].size, 100):      # (the interface's text holds 8192)
        part = slice(start, start + 100)
        text, length = _core.pf_friction_table(*head, *(c[part] for c in columns), err[part],
                                               int(has_err))
        raw = text.tobytes() if hasattr(text, "tobytes") else text
        raw = raw if isinstance(raw, bytes) else str(raw).encode("utf-8")
        chunk = raw[:int(length)].decode("utf-8", "replace").splitlines()
        lines += chunk if start == 0 else chunk[2:]
    print("\n".join(lines))
