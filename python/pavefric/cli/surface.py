"""``python -m pavefric surface``: a seeded CTM-like synthetic profile."""
from __future__ import annotations

import argparse

NAME = "surface"
HELP = "write a seeded CTM-like profile (mm, one column)"
DESCRIPTION = ("Write a synthetic texture profile with a power-law spectrum between two "
               "wavelengths, of a given RMS and skewness, reproducible from its seed "
               "(pavefric.surfaces.spectral_profile), as one column of heights in mm.")
EXAMPLES = ("python -m pavefric surface -o rough.txt --rms-mm 1.0 --skew -0.6 --seed 3",
            "python -m pavefric surface -o fine.txt --points 4096 --dx-mm 0.25")


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("-o", "--output", required=True, help="the profile file to write")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--rms-mm", type=float, default=0.5)
    p.add_argument("--exponent", type=float, default=2.0)
    p.add_argument("--wavelength-min-mm", type=float, default=2.0)
    p.add_argument("--wavelength-max-mm", type=float, default=50.0)
    p.add_argument("--skew", type=float, default=0.0)
    p.add_argument("--points", type=int, default=1024)
    p.add_argument("--dx-mm", type=float, default=0.87)


def main(args: argparse.Namespace) -> int:
    from ..core import PavefricError
    from ..surfaces import spectral_profile, write_profile

    for opt, value, ok, rule in (
            ("--points", args.points, args.points >= 4, "must be >= 4"),
            ("--dx-mm", args.dx_mm, args.dx_mm > 0, "must be > 0"),
            ("--rms-mm", args.rms_mm, args.rms_mm >= 0, "must be >= 0"),
            ("--wavelength-min-mm", args.wavelength_min_mm,
             0 < args.wavelength_min_mm < args.wavelength_max_mm,
             f"must be > 0 and < --wavelength-max-mm {args.wavelength_max_mm:g}")):
        if not ok:
            raise PavefricError(f"surface {opt} {value:g}: {rule}")
    try:
        z = spectral_profile(args.points, args.dx_mm * 1e-3, rms=args.rms_mm * 1e-3,
                             exponent=args.exponent,
                             wavelength_min=args.wavelength_min_mm * 1e-3,
                             wavelength_max=args.wavelength_max_mm * 1e-3, skew=args.skew,
                             seed=args.seed)
    except ValueError as exc:
        raise PavefricError(f"surface: {exc} (--points {args.points}, --dx-mm "
                            f"{args.dx_mm:g}, --wavelength-min-mm "
                            f"{args.wavelength_min_mm:g}, --wavelength-max-mm "
                            f"{args.wavelength_max_mm:g}); widen the band of wavelengths "
                            "or give more --points") from None
    header = (f"pavefric synthetic profile: spectral_profile(n={args.points}, "
              f"dx={args.dx_mm} mm, rms={args.rms_mm} mm, exponent={args.exponent}, "
              f"wavelengths {args.wavelength_min_mm}-{args.wavelength_max_mm} mm, "
              f"skew={args.skew}, seed={args.seed})")
    # replaces only a profile this command wrote (never a measured one)
    write_profile(args.output, z, header, signature="# pavefric synthetic profile:")
    print(f"wrote {args.output}")
    return 0
