"""Benchmark of profile input: ns per number read (text, CSV, NetCDF), and a
10-million-point profile read, and read and run by the program (wall time,
peak memory per point).

Called by ``python -m pavefric bench`` (``bench.run``) or on its own:
``python -c "import pavefric.studies.bench_io as b; b.reading(print)"``. Not a test:
absolute times are noisy on a shared machine.
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

from ..config import program

# The reader before the single-pass parser (commit b82ceed: a formatted read
# per line, a list-directed conversion per token), measured once on the
# 2-core development machine on files written as below: the sources of
# b82ceed (`git archive b82ceed`) compiled with gfortran -O2 -funroll-loops
# and a driver timing one call of read_raw_profile with system_clock; the
# program as `/usr/bin/time -v pavefric big.nml` on the 10-million-point
# scene below. That reader is gone, so these figures cannot be re-measured by
# this module; they are printed beside the new ones.
OLD_FIGURES = {
    "commit": "b82ceed",
    "text_ns_per_number": 837.0,          # 1e6 heights, one column
    "two_column_ns_per_number": 717.0,    # 1e6 (distance, height) lines
    "csv_ns_per_number": 700.0,
    "read_10m_s": 8.19,
    "program_10m_s": 13.88,
    "program_10m_bytes_per_point": 73.4,  # peak RSS 717,196 kB / 1e7
}


def _write_text(path: Path, z_mm: np.ndarray, x_mm: np.ndarray | None = None,
                csv: bool = False) -> None:
    with open(path, "w") as fh:
        if csv:
            fh.write("distance (mm),height (mm)\n")
            np.savetxt(fh, np.c_[x_mm, z_mm], fmt="%.4f,%.6f")
        elif x_mm is not None:
            fh.write("distance_mm height_mm\n")
            np.savetxt(fh, np.c_[x_mm, z_mm], fmt="%.4f %.6f")
        else:
            fh.write("height_mm\n")
            np.savetxt(fh, z_mm, fmt="%.6f")


def _heights_mm(n: int, seed: int = 1) -> np.ndarray:
    rng = np.random.default_rng(seed)
    k = np.arange(n)
    return 0.1 * np.sin(k * 0.37) + 0.2 * np.sin(k * 0.051) + rng.normal(0, 0.02, n)


def read_seconds(path, format: str = "auto", height_unit: str = "mm", profile_name: str = "",
                 repeats: int = 3) -> tuple[float, int, int]:
    """(best seconds, points, numbers) of the core's reader on a file, no
    preprocessing, timed inside Fortran."""
    from .. import _core
    from ..profiles import _b, _check

    n_points, n_numbers, seconds, status, message = _core.pf_profile_read_seconds(
        _b(os.fspath(path)), _b(format), _b(height_unit), _b(profile_name), int(repeats))
    _check(status, message)
    return float(seconds), int(n_points), int(n_numbers)


def _program_run(scene: Path) -> dict:
    """Wall time and peak RSS of the pavefric program on a scene, measured in
    a fresh child (RUSAGE_CHILDREN then holds only the program)."""
    # the executable, not the launcher: no Python start-up in the time or the peak memory
    exe = program()
    code = (
        "import json, resource, subprocess, sys, time\n"
        f"t0 = time.perf_counter()\n"
        f"r = subprocess.run([{str(exe)!r}, {str(scene)!r}, '-o', "
        f"{str(scene.with_suffix('.nc'))!r}], capture_output=True, text=True)\n"
        "t = time.perf_counter() - t0\n"
        "if r.returncode: sys.exit(r.stderr)\n"
        "print(json.dumps({'seconds': t, 'maxrss_kb': "
        "resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss}))\n")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                       timeout=1800)
    if r.returncode != 0:
        raise RuntimeError(r.stderr)
    return json.loads(r.stdout.strip().splitlines()[-1])


def reading(log=print, largest: int = 10_000_000, small: int = 1_000_000,
            directory: str | None = None) -> dict:
    """Reading figures; ``log`` prints each line. Returns them as a dict."""
    from ..profiles import write_profiles

    out: dict = {"old": OLD_FIGURES}
    with tempfile.TemporaryDirectory(dir=directory) as tmp:
        tmp = Path(tmp)
        z = _heights_mm(small)
        x = np.arange(small) * 0.037
        files = {"text, one column": tmp / "z.txt", "text, two columns": tmp / "xz.txt",
                 "CSV, two columns": tmp / "xz.csv"}
        _write_text(files["text, one column"], z)
        _write_text(files["text, two columns"], z, x)
        _write_text(files["CSV, two columns"], z, x, csv=True)
        nc = tmp / "z.nc"
        write_profiles(nc, [np.array([float(f"{v:.6f}") for v in z])], units="mm", dx=0.87e-3)
        files["NetCDF, one profile"] = nc
        old = {"text, one column": OLD_FIGURES["text_ns_per_number"],
               "text, two columns": OLD_FIGURES["two_column_ns_per_number"],
               "CSV, two columns": OLD_FIGURES["csv_ns_per_number"]}
        log(f"\n== Profile reading: {small:,} points, best of 3, timed in the core "
            "(target: text <= 100 ns per number) ==")
        log(f"{'file':22s} {'MB':>7s} {'ns/number':>10s} {'before':>10s}")
        rows = []
        for name, path in files.items():
            seconds, points, numbers = read_seconds(path)
            ns = 1e9 * seconds / numbers
            before = f"{old[name]:10.0f}" if name in old else f"{'-':>10s}"
            log(f"{name:22s} {path.stat().st_size / 1e6:7.1f} {ns:10.1f} {before}")
            rows.append(dict(file=name, ns_per_number=ns, points=points, numbers=numbers,
                             before=old.get(name)))
        out["per_number"] = rows

        # a survey: one file of many short profiles, one read by name
        survey = tmp / "survey.nc"
        n_survey = 10_000
        write_profiles(survey, np.resize(z, (n_survey, 512)) * 1e-3, dx=0.87e-3,
                       names=[f"seg{k:05d}" for k in range(n_survey)])
        seconds, points, _ = read_seconds(survey, profile_name=f"seg{n_survey // 2:05d}")
        log(f"NetCDF survey of {n_survey:,} profiles x 512 points: one profile by name "
            f"{1e3 * seconds:.2f} ms (the file opened and its names read on each call)")
        out["survey_read_ms"] = 1e3 * seconds

        # a long profile: read, and read and run through the program
        big = tmp / "big.txt"
        _write_text(big, _heights_mm(largest, seed=2))
        seconds, points, _ = read_seconds(big, repeats=1)
        scene = tmp / "big.nml"
        scene.write_text(f"&surface\n  profile_file = '{big}', closed = .false., "
                         "mu_loc = 0.5\n/\n&numerics\n  error_estimate = .false.\n/\n"
                         "&operation\n  speeds_kmh = 60\n/\n")
        # best of 3 wall times, as the other figures (the first run also
        # competes with the write-back of the 95 MB just written)
        runs = [_program_run(scene) for _ in range(3)]
        run = dict(seconds=min(r["seconds"] for r in runs),
                   maxrss_kb=max(r["maxrss_kb"] for r in runs))
        per_point = run["maxrss_kb"] * 1024 / largest
        log(f"\n== A {largest:,}-point text profile ({big.stat().st_size / 1e6:.0f} MB; "
            "targets: read and run < 3 s, <= 150 bytes per point; best of 3) ==")
        log(f"  read (core reader):          {seconds:6.2f} s   "
            f"(before: {OLD_FIGURES['read_10m_s']:.2f} s)")
        log(f"  program, read and run dry at 60 km/h: {run['seconds']:6.2f} s, "
            f"{per_point:5.1f} bytes per point (before: {OLD_FIGURES['program_10m_s']:.2f} s, "
            f"{OLD_FIGURES['program_10m_bytes_per_point']:.1f} bytes per point)")
        out["long"] = dict(points=largest, read_s=seconds, program_s=run["seconds"],
                           program_bytes_per_point=per_point)
    return out


if __name__ == "__main__":
    reading()
