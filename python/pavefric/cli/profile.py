"""``python -m pavefric profile``: read and clean a profile; report and plot it."""
from __future__ import annotations

import argparse

NAME = "profile"
HELP = "read and preprocess a profile file; report and plot"
DESCRIPTION = ("Read a profile file (plain, CSV, laser profiler export or NetCDF), run the "
               "preprocessing steps asked for (docs/profiles.md), print what they did and its "
               "MPD, and optionally plot or export the cleaned profile.")
EXAMPLES = ("python -m pavefric profile inputs/profiles/ctm_medium.txt",
            "python -m pavefric profile scan.dat --dropouts interpolate --spike-slope 3 "
            "--plot scan.png --export scan_clean.txt")


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("file", help="the profile file")
    p.add_argument("--format", default="auto")
    p.add_argument("--height-unit", default="mm")
    p.add_argument("--dropouts", default="error", choices=["error", "interpolate"])
    p.add_argument("--no-trim-plates", action="store_true")
    p.add_argument("--spike-slope", type=float, default=0.0)
    p.add_argument("--resample-mm", type=float, default=0.0)
    p.add_argument("--lowpass-mm", type=float, default=0.0)
    p.add_argument("--plot", default=None, help="PNG of raw against cleaned profile")
    p.add_argument("--export", default=None,
                   help="write the cleaned profile as two columns (distance, height; mm)")


#: The first characters of every file ``--export`` writes: an existing file
#: at its path is replaced only if it begins so (``check_output``'s
#: ``signature``), so a measured profile named by mistake stays as it is.
EXPORT_SIGNATURE = "# pavefric profile: cleaned from "


def main(args: argparse.Namespace) -> int:
    from ..core import PavefricError, atomic_output, check_output
    from ..plot import _checked, plot_profile
    from ..profiles import read_profile
    from ..texture import texture

    # the outputs checked before any work (the profile's own file and a
    # file pavefric did not write are never replaced)
    if args.plot:
        _checked(args.plot, [args.file])
    if args.export:
        check_output(args.export, [args.file, args.plot], signature=EXPORT_SIGNATURE,
                     writable=True)
    prof = read_profile(args.file, args.height_unit, format=args.format,
                        dropouts=args.dropouts, trim_plates=not args.no_trim_plates,
                        spike_slope=args.spike_slope, resample_dx=args.resample_mm * 1e-3,
                        lowpass_wavelength=args.lowpass_mm * 1e-3)
    for key, value in prof.report.items():
        print(f"{key:16s} {value}")
    try:
        t = texture(prof, closed=False)
        print(f"{'mpd_mm':16s} {t['mpd'] * 1e3:.4f} ({t['n_valid']} of "
              f"{t['n_segments']} segments valid)")
    except PavefricError as exc:
        print(f"{'mpd_mm':16s} - ({exc})")
    if args.plot:
        print(f"wrote {plot_profile(prof, args.plot)}")
    if args.export:
        import numpy as np

        x = np.arange(prof.heights.size) * prof.dx
        with atomic_output(args.export, [args.file, args.plot],
                           signature=EXPORT_SIGNATURE) as tmp:
            np.savetxt(tmp, np.column_stack([x * 1e3, prof.heights * 1e3]), fmt="%.17g",
                       header=f"{EXPORT_SIGNATURE[2:]}{args.file}\ndistance_mm height_mm")
        print(f"wrote {args.export}")
    return 0
