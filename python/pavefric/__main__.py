"""Command line of the Python layer: ``python -m pavefric COMMAND ...``.

Commands:
  run SCENE.nml [-o OUT.nc] [--plot PNG] [-q]  run a scene (same core as the program)
  plot OUT.nc [OUT.nc ...] -o PNG           friction against speed
  surface -o FILE [--seed N --rms-mm R ...] write a seeded CTM-like profile
  accuracy SCENE.nml [...] [--report docs/accuracy.md] [-q]  accuracy-cost study
  bench [--report docs/performance.md] [-q] benchmark against the NumPy reference
  calibrate DATA.csv --fit alpha ...        least-squares calibration (core runs)
  surfaces [--outdir inputs/surfaces]       regenerate the six reference surfaces
  validate [--report docs/validation.md] [-q]  calibrate at 20 km/h, compare, report
  profile FILE [--dropouts interpolate ...] read, preprocess, report, plot a profile
  docs [--inputs docs/inputs.md] [--outputs docs/outputs.md]  regenerate the references
  speed-gradient [--report docs/speed_gradient.md]  wet models against the PIARC speed gradient
  prony DATA.csv [-o compound.nml] [--thickness H] ...  Prony series from DMA data (&rubber)
  rubber-report [--report docs/rubber.md]  Maxwell rubber: friction against speed and
                                           temperature, cost against Kelvin-Voigt
  merge PART.nc [PART.nc ...] -o SURVEY.nc  join batch outputs of one survey run in parts
  example [DIR] [--force]                   write the default scenes into DIR (any directory)

The report commands (bench, validate, docs, speed-gradient, rubber-report,
surfaces) are the maintainers': they read and write the checkout's tests/,
inputs/ and docs/, and refuse in one line (exit status 2) elsewhere.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

#: The maintainers' commands, which need a checkout as the current directory.
CHECKOUT_COMMANDS = ("bench", "validate", "docs", "speed-gradient", "rubber-report", "surfaces")


def in_checkout(directory: Path | None = None) -> bool:
    """Whether ``directory`` (default: the current one) is a pavefric
    checkout: the NumPy reference tests/reference.py and inputs/ are there."""
    root = Path.cwd() if directory is None else directory
    return (root / "tests" / "reference.py").is_file() and (root / "inputs").is_dir()


def needs_checkout(args: argparse.Namespace) -> bool:
    """Whether this maintainer command reads or writes the checkout: always,
    except docs and surfaces told where to read and write everything."""
    if args.command == "docs":
        return args.inputs == "docs/inputs.md" or args.outputs == "docs/outputs.md"
    if args.command == "surfaces":
        return args.outdir == "inputs/surfaces" or args.table is None
    return args.command in CHECKOUT_COMMANDS


def main(argv: list[str] | None = None) -> int:
    from . import __version__

    parser = argparse.ArgumentParser(prog="python -m pavefric",
                                     description="pavefric: pavement friction (Kane et al. 2017)")
    parser.add_argument("--version", action="version", version=f"pavefric {__version__}")
    sub = parser.add_subparsers(dest="command", required=True)

    p_run = sub.add_parser("run", help="run a scene namelist and write NetCDF")
    p_run.add_argument("scene")
    p_run.add_argument("-o", "--output", default=None, help="NetCDF output path")
    p_run.add_argument("--plot", default=None, help="also write a PNG of mu against speed")
    p_run.add_argument("-q", "--quiet", action="store_true",
                       help="no progress bar for a batch (warnings and errors still on stderr)")

    p_plot = sub.add_parser("plot", help="plot mu against speed from NetCDF outputs")
    p_plot.add_argument("files", nargs="+")
    p_plot.add_argument("-o", "--output", required=True, help="PNG path")
    p_plot.add_argument("--title", default=None)

    p_surf = sub.add_parser("surface", help="write a seeded CTM-like profile (mm, one column)")
    p_surf.add_argument("-o", "--output", required=True)
    p_surf.add_argument("--seed", type=int, default=0)
    p_surf.add_argument("--rms-mm", type=float, default=0.5)
    p_surf.add_argument("--exponent", type=float, default=2.0)
    p_surf.add_argument("--wavelength-min-mm", type=float, default=2.0)
    p_surf.add_argument("--wavelength-max-mm", type=float, default=50.0)
    p_surf.add_argument("--skew", type=float, default=0.0)
    p_surf.add_argument("--points", type=int, default=1024)
    p_surf.add_argument("--dx-mm", type=float, default=0.87)

    p_acc = sub.add_parser("accuracy", help="accuracy-cost study of the numerical knobs")
    p_acc.add_argument("scenes", nargs="+", help="scene namelists")
    p_acc.add_argument("--speeds", type=float, nargs="+", default=None,
                       help="speeds in km/h (default: each scene's)")
    p_acc.add_argument("--outdir", default="outputs/accuracy")
    p_acc.add_argument("--repeats", type=int, default=3)
    p_acc.add_argument("--also-dry", action="store_true",
                       help="also study each scene with its water removed")
    p_acc.add_argument("--report", default=None,
                       help="also write a Markdown report here (e.g. docs/accuracy.md)")
    p_acc.add_argument("-q", "--quiet", action="store_true",
                       help="no progress on stderr (runs done, elapsed, left)")

    p_bench = sub.add_parser("bench", help="benchmark the core against the NumPy reference")
    p_bench.add_argument("--report", default=None, help="write docs/performance.md here")
    p_bench.add_argument("--quick", action="store_true",
                         help="small sizes, one repeat: check that it runs (not a measurement)")
    p_bench.add_argument("--largest", type=int, default=10_000_000,
                         help="largest profile of the length scaling (points)")
    p_bench.add_argument("-q", "--quiet", action="store_true",
                         help="no progress on stderr (sections done, elapsed, left)")

    p_cal = sub.add_parser("calibrate", help="fit model parameters to measured friction (CSV)",
                           description="Least-squares fit (scipy least_squares, parameters "
                           "fitted as log p) of model parameters to measured friction; every "
                           "evaluation runs the core. See docs/calibration.md.")
    p_cal.add_argument("data", help="CSV with columns surface,speed_kmh,mu")
    p_cal.add_argument("--scenes", default="inputs/surfaces",
                       help="directory of <surface>.nml scenes")
    p_cal.add_argument("--fit", nargs="+", default=["alpha"],
                       help="parameters: alpha beta viscosity ... or mu_loc:<SURFACE>")
    p_cal.add_argument("--speeds", type=float, nargs="+", default=None,
                       help="use only these speeds (km/h)")
    p_cal.add_argument("--source", default=None,
                       help="use only rows whose 'source' column is this (e.g. dft)")
    p_cal.add_argument("--start", nargs="+", default=None,
                       help="start values, NAME=VALUE (default: the scenes' values)")
    p_cal.add_argument("--bounds", nargs="+", default=None,
                       help="search bounds, NAME=LO:HI (default: wide physical ranges)")
    p_cal.add_argument("--level", type=float, default=0.95,
                       help="confidence level of the intervals (default 0.95)")
    p_cal.add_argument("--profile", nargs="+", default=None, metavar="NAME",
                       help="also a profile-likelihood interval for these parameters")
    p_cal.add_argument("--max-evaluations", type=int, default=None,
                       help="limit of least_squares evaluations (default 100 per parameter)")
    p_cal.add_argument("-o", "--output", default=None, help="write the fit as JSON")

    p_sur = sub.add_parser("surfaces", help="(re)generate the six reference surfaces")
    p_sur.add_argument("--outdir", default="inputs/surfaces")
    p_sur.add_argument("--table", default=None, help="kane2017_tables.csv")
    p_sur.add_argument("--alpha", type=float, default=None)
    p_sur.add_argument("--beta", type=float, default=1.75)

    p_val = sub.add_parser("validate", help="calibrate on 20 km/h and regenerate docs/validation.md")
    p_val.add_argument("--table", default=None, help="kane2017_tables.csv")
    p_val.add_argument("--report", default="docs/validation.md")
    p_val.add_argument("--outdir", default="outputs/validation")
    p_val.add_argument("--quick", action="store_true", help="fewer speeds in the curves")
    p_val.add_argument("-q", "--quiet", action="store_true",
                       help="no progress on stderr (sections done, elapsed, left)")

    p_prof = sub.add_parser("profile", help="read and preprocess a profile file; report and plot")
    p_prof.add_argument("file")
    p_prof.add_argument("--format", default="auto")
    p_prof.add_argument("--height-unit", default="mm")
    p_prof.add_argument("--dropouts", default="error", choices=["error", "interpolate"])
    p_prof.add_argument("--no-trim-plates", action="store_true")
    p_prof.add_argument("--spike-slope", type=float, default=0.0)
    p_prof.add_argument("--resample-mm", type=float, default=0.0)
    p_prof.add_argument("--lowpass-mm", type=float, default=0.0)
    p_prof.add_argument("--plot", default=None, help="PNG of raw against cleaned profile")
    p_prof.add_argument("--export", default=None,
                        help="write the cleaned profile as two columns (distance, height; mm)")

    p_docs = sub.add_parser("docs", help="regenerate reference documents from the core's "
                            "declarations")
    p_docs.add_argument("--inputs", default="docs/inputs.md",
                        help="where to write the namelist reference")
    p_docs.add_argument("--outputs", default="docs/outputs.md",
                        help="where to write the NetCDF output reference")

    p_sg = sub.add_parser("speed-gradient", help="the wet models' speed gradient against PIARC "
                          "(docs/speed_gradient.md)")
    p_sg.add_argument("--report", default="docs/speed_gradient.md")
    p_sg.add_argument("--quick", action="store_true", help="three MPD levels only")

    p_prony = sub.add_parser("prony", help="fit a Prony series to dynamic mechanical data and "
                             "write the &rubber group", description="Fit a generalised "
                             "Maxwell (Prony) series to DMA data (CSV with a header: "
                             "temperature_c (optional), frequency_hz or omega_rad_s, storage_pa "
                             "or storage_mpa, loss_pa or loss_mpa; '#' comments), shifted to a "
                             "master curve by "
                             "the WLF equation, by non-negative least squares; write the "
                             "&rubber group (moduli divided by the rubber thickness). See "
                             "docs/rubber.md.")
    p_prony.add_argument("data", nargs="?", help="DMA CSV file")
    p_prony.add_argument("-o", "--output", default=None,
                         help="namelist fragment to write (default: print it)")
    p_prony.add_argument("--reference-temperature", type=float, default=20.0,
                         help="Tref of the master curve, degC (default 20)")
    p_prony.add_argument("--c1", type=float, default=8.86, help="WLF C1 (default 8.86)")
    p_prony.add_argument("--c2", type=float, default=101.6, help="WLF C2, K (default 101.6)")
    p_prony.add_argument("--fit-wlf", action="store_true",
                         help="also fit C1 and C2 (data at several temperatures)")
    p_prony.add_argument("--thickness", type=float, default=0.006,
                         help="rubber thickness h (m): K = E / h (default 0.006, the DFT pad)")
    p_prony.add_argument("--modulus", choices=["tensile", "shear"], default="tensile",
                         help="the data's moduli: Young's (E', E'') or shear (G', G''; E = 3G)")
    p_prony.add_argument("--per-decade", type=float, default=1.0,
                         help="relaxation times per decade of the candidate set (default 1)")
    p_prony.add_argument("--plot", default=None, help="PNG of the master curve and the fit")
    p_prony.add_argument("--write-representative", default=None, metavar="CSV",
                         help="write the representative tread compound's data set here")

    p_rr = sub.add_parser("rubber-report", help="the Maxwell rubber's friction against speed "
                          "and temperature, and its cost (docs/rubber.md)")
    p_rr.add_argument("--report", default="docs/rubber.md")
    p_rr.add_argument("--compound", default="inputs/rubber/tread_compound.nml")
    p_rr.add_argument("--quick", action="store_true", help="fewer speeds and temperatures")

    p_merge = sub.add_parser(
        "merge", help="join batch outputs of one survey run in parts (job arrays)",
        description="Join the batch outputs of one survey run in parts (each part a batch "
        "over its own profiles, with the same physics, depths and speeds) into one file, "
        "along 'profile', in the order given. Refuses parts that ran other physics, depths "
        "or speeds, or that share a profile. docs/cluster.md.",
        epilog="example: python -m pavefric merge part_*.nc -o survey_results.nc")
    p_merge.add_argument("parts", nargs="+", help="batch outputs (NetCDF)")
    p_merge.add_argument("-o", "--output", required=True, help="the merged file")

    p_ex = sub.add_parser(
        "example", help="write the default scenes and their profile into a directory",
        description="Write the default scenes (ctm_dry.nml, ctm_wet.nml, ctm_squeeze.nml) "
        "and the profile they read (profiles/ctm_medium.txt), shipped in the package, into "
        "DIR, and print the commands to run next. Existing files are left alone unless "
        "--force.",
        epilog="example: python -m pavefric example my-run && cd my-run && pavefric ctm_dry.nml")
    p_ex.add_argument("directory", nargs="?", default="pavefric-example",
                      help="where to write (default ./pavefric-example; made if missing)")
    p_ex.add_argument("--force", action="store_true", help="overwrite files already there")

    args = parser.parse_args(argv)
    if args.command in CHECKOUT_COMMANDS and needs_checkout(args) and not in_checkout():
        print(f"pavefric: error: 'python -m pavefric {args.command}' is a maintainer command "
              "and needs a pavefric checkout (tests/reference.py and inputs/ in the current "
              f"directory, {Path.cwd()}): run it from the repository's root", file=sys.stderr)
        return 2
    from .core import PavefricError
    from .merge import MergeError

    try:
        if args.command == "run":
            import warnings

            from .core import ProfilesFailedWarning, run
            from .plot import plot_mu_speed

            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always", ProfilesFailedWarning)
                out = run(args.scene, args.output, progress=False if args.quiet else None)
            failed = [w for w in caught if issubclass(w.category, ProfilesFailedWarning)]
            for w in caught:
                if w not in failed:
                    warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
            print(f"wrote {out}")
            if args.plot:
                print(f"wrote {plot_mu_speed([out], args.plot)}")
            if failed:
                # as the program: the batch finished, some profiles failed
                print(f"pavefric: {failed[0].message}", file=sys.stderr)
                return 4
        elif args.command == "plot":
            from .plot import plot_mu_speed

            for f in args.files:
                if not Path(f).is_file():
                    raise PavefricError(f"plot: '{f}': no such file (give NetCDF outputs of "
                                        "pavefric runs)")
            try:
                print(f"wrote {plot_mu_speed(args.files, args.output, title=args.title)}")
            except OSError as exc:
                raise PavefricError(f"plot: cannot read {args.files} as pavefric outputs "
                                    f"({exc}); give NetCDF outputs of pavefric runs") from None
        elif args.command == "accuracy":
            from .studies.reports import accuracy_report

            accuracy_report(args.scenes, args.outdir, speeds=args.speeds, repeats=args.repeats,
                            report=args.report, also_dry=args.also_dry, quiet=args.quiet)
        elif args.command == "bench":
            from .studies.bench import run as bench_run

            bench_run(args.report, args.largest, quick=args.quick, quiet=args.quiet)
        elif args.command == "calibrate":
            from .calibrate import main_calibrate

            return main_calibrate(args)
        elif args.command == "surfaces":
            from .studies.reference_surfaces import write_surfaces
            from .studies.validation import CALIBRATED_ALPHA, default_table

            write_surfaces(args.outdir, args.table or default_table(),
                           alpha=CALIBRATED_ALPHA if args.alpha is None else args.alpha,
                           beta=args.beta)
        elif args.command == "validate":
            from .studies.validation import validate

            validate(table=args.table, report=args.report, outdir=args.outdir, quick=args.quick,
                     quiet=args.quiet)
        elif args.command == "speed-gradient":
            from .studies.speed_gradient import run_study

            run_study(args.report, quick=args.quick)
        elif args.command == "prony":
            from .rubber import main_prony

            try:
                return main_prony(args)
            except ValueError as exc:
                print(f"pavefric: error: {exc}", file=sys.stderr)
                return 1
        elif args.command == "rubber-report":
            from .studies.rubber_report import run_report

            run_report(args.report, compound=args.compound, quick=args.quick)
        elif args.command == "docs":
            from .studies.docs import write_inputs, write_outputs

            print(f"wrote {write_inputs(args.inputs)}")
            print(f"wrote {write_outputs(args.outputs)}")
        elif args.command == "profile":
            from .profiles import read_profile
            from .plot import plot_profile
            from .texture import texture

            prof = read_profile(args.file, args.height_unit, format=args.format,
                                dropouts=args.dropouts, trim_plates=not args.no_trim_plates,
                                spike_slope=args.spike_slope,
                                resample_dx=args.resample_mm * 1e-3,
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
                np.savetxt(args.export, np.column_stack([x * 1e3, prof.heights * 1e3]),
                           fmt="%.17g", header=f"cleaned from {args.file}\ndistance_mm height_mm")
                print(f"wrote {args.export}")
        elif args.command == "surface":
            from .surfaces import spectral_profile, write_profile

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
            write_profile(args.output, z, header)
            print(f"wrote {args.output}")
        elif args.command == "merge":
            from .merge import merge

            print(f"wrote {merge(args.parts, args.output)}")
        elif args.command == "example":
            from .example import next_steps, write_example

            try:
                written = write_example(args.directory, force=args.force)
            except FileExistsError as exc:
                print(f"pavefric: error: {exc}", file=sys.stderr)
                return 1
            for path in written:
                print(f"wrote {path}")
            print(next_steps(args.directory))
    except (PavefricError, MergeError) as exc:
        print(f"pavefric: error: {exc}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
