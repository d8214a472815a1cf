"""Benchmark of batch runs: MPI on an uneven batch, reading a long profile
list, and the cost of checking the journal on a resume.

Run from a checkout: ``python -m pavefric.bench_mpi`` (also part of
``python -m pavefric bench``). Not a test: times are wall-clock and noisy on
a shared machine; each figure is the best of a few runs.
"""
from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

DX = 0.87e-3


def _program() -> str | None:
    return shutil.which("pavefric", path=str(Path(sys.executable).parent))


def _env() -> dict:
    return {**os.environ, "OMP_NUM_THREADS": "1", "OMPI_ALLOW_RUN_AS_ROOT": "1",
            "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1"}


def uneven_batch(directory: Path, n_short: int = 240, n_long: int = 6,
                 short_points: int = 2048, long_points: int = 100_000) -> Path:
    """A batch of `n_short` short profiles and `n_long` long ones, the long
    ones first at odd positions (1, 3, 5...): where a round-robin deal over
    two ranks gives every long profile to rank 0. Returns the scene path."""
    from .surfaces import spectral_profile, write_profile

    d = directory / "profiles"
    d.mkdir(parents=True, exist_ok=True)
    long_at = {2 * k + 1 for k in range(n_long)}
    for k in range(1, n_short + n_long + 1):
        n = long_points if k in long_at else short_points
        write_profile(str(d / f"p{k:04d}.txt"),
                      spectral_profile(n, DX, rms=0.45e-3, skew=-0.4, seed=k))
    scene = directory / "uneven.nml"
    scene.write_text("&batch profiles = 'profiles/*.txt', depths = 0.0, 1.0e-3 /\n"
                     "&surface closed = .false., mu_loc = 0.6 /\n"
                     "&operation speeds_kmh = 20, 40, 60, 80 /\n")
    return scene


def mpi_uneven(log=print, repeats: int = 3, n_short: int = 240,
               long_points: int = 100_000) -> dict:
    """Wall time (including mpirun's start-up) of 1 and 2 MPI ranks on the
    uneven batch; the two outputs must be equal bit for bit."""
    import xarray as xr

    log(f"\n== MPI batch, uneven: 6 long profiles ({long_points:,} points) among {n_short} "
        "short ones (2048), placed where round-robin would give all to rank 0 ==")
    mpirun, exe = shutil.which("mpirun"), _program()
    if mpirun is None or exe is None:
        log("not run: needs mpirun and the pavefric program")
        return {}
    cmd0 = [mpirun, "--oversubscribe"] + (["--allow-run-as-root"] if os.geteuid() == 0 else [])
    with tempfile.TemporaryDirectory() as tmp:
        scene = uneven_batch(Path(tmp), n_short=n_short, long_points=long_points)
        times = {1: np.inf, 2: np.inf}
        cpu = []
        for rep in range(repeats):             # interleaved: a load change hits both
            for ranks in (1, 2):
                out = Path(tmp) / f"o{ranks}_{rep}.nc"
                t0 = time.perf_counter()
                r = subprocess.run(cmd0 + ["-n", str(ranks), exe, str(scene), "-o", str(out)],
                                   capture_output=True, text=True, env=_env(), timeout=3600)
                times[ranks] = min(times[ranks], time.perf_counter() - t0)
                if r.returncode != 0:
                    raise RuntimeError(r.stdout[-2000:] + r.stderr[-2000:])
                if ranks == 2:
                    line = [x for x in r.stdout.splitlines() if "CPU seconds per rank" in x][0]
                    cpu.append([float(v) for v in line.split(":")[-1].split()])
        with xr.open_dataset(Path(tmp) / "o1_0.nc") as a, \
                xr.open_dataset(Path(tmp) / "o2_0.nc") as b:
            same = all(np.array_equal(a[v].values, b[v].values,
                                      equal_nan=a[v].dtype.kind == "f") for v in a.variables)
    ratio = times[1] / times[2]
    # the balance from CPU time, which other jobs on the machine do not change
    balance = min(max(c) / np.mean(c) for c in cpu)
    bound = 2.0 / balance
    log(f"  command: mpirun -n R pavefric uneven.nml (OMP_NUM_THREADS=1), best of {repeats}, "
        "interleaved")
    log(f"  wall time including start-up: 1 rank {times[1]:.2f} s, 2 ranks {times[2]:.2f} s: "
        f"{ratio:.2f}x (target 1.7x); outputs identical: {same}")
    log(f"  CPU time per rank (2 ranks): the busiest {balance:.3f}x the mean; work shared "
        f"as {bound:.2f}x over 2 ranks (2.00 is perfect)")
    return {"one": times[1], "two": times[2], "ratio": ratio, "identical": same,
            "balance": balance}


def profile_list_reading(log=print, n: int = 40_000) -> dict:
    """Start-up of a batch over an `n`-entry profile_list (one profile
    computed, `--max-profiles 1`): reading the list, checking names."""
    log(f"\n== A {n:,}-entry profile_list: pavefric s.nml --max-profiles 1 ==")
    exe = _program()
    if exe is None:
        log("not run: needs the pavefric program")
        return {}
    with tempfile.TemporaryDirectory() as tmp:
        d = Path(tmp)
        (d / "p").mkdir()
        (d / "p" / "00000.txt").write_text(
            "height_mm\n" + "\n".join("0.1" if k % 2 else "-0.1" for k in range(64)) + "\n")
        (d / "list.txt").write_text("\n".join(f"p/{k:05d}.txt {0.5 * k}" for k in range(n)) + "\n")
        (d / "s.nml").write_text("&batch profile_list = 'list.txt' /\n"
                                 "&surface closed = .false. /\n&operation speeds_kmh = 20 /\n")
        best = np.inf
        for _ in range(3):
            for f in d.glob("o.nc*"):
                f.unlink()
            t0 = time.perf_counter()
            r = subprocess.run([exe, str(d / "s.nml"), "-o", str(d / "o.nc"), "--max-profiles",
                                "1"], capture_output=True, text=True, timeout=3600)
            best = min(best, time.perf_counter() - t0)
            if r.returncode != 3:
                raise RuntimeError(r.stderr)
    log(f"  {best:.2f} s (pavefric 0.1.0 grew its list by concatenation: 23 s in the "
        "issue's measurement)")
    return {"entries": n, "seconds": best}


def journal_resume(log=print, n: int = 2000, points: int = 4096) -> dict:
    """What a resume costs: `n` profiles of `points` points in the journal,
    each line's checksum and values checked and each profile file hashed
    (SHA-256) again; against the time to compute those profiles."""
    from .surfaces import spectral_profile, write_profile

    log(f"\n== Resume of a journal of {n:,} profiles ({points} points each): checksums, "
        "values and SHA-256 of every profile file ==")
    exe = _program()
    if exe is None:
        log("not run: needs the pavefric program")
        return {}
    with tempfile.TemporaryDirectory() as tmp:
        d = Path(tmp)
        (d / "p").mkdir()
        base = spectral_profile(points, DX, rms=0.45e-3, seed=1)
        for k in range(n + 2):              # two left: the resume stops after one
            write_profile(str(d / "p" / f"{k:05d}.txt"), np.roll(base, 7 * k))
        (d / "s.nml").write_text("&batch profiles = 'p/*.txt' /\n&surface closed = .false. /\n"
                                 "&operation speeds_kmh = 60 /\n")
        t0 = time.perf_counter()
        r = subprocess.run([exe, str(d / "s.nml"), "-o", str(d / "o.nc"), "--max-profiles",
                            str(n)], capture_output=True, text=True, timeout=3600)
        compute = time.perf_counter() - t0
        if r.returncode != 3:
            raise RuntimeError(r.stderr)
        size = sum(f.stat().st_size for f in (d / "p").iterdir())
        journal = (d / "o.nc.journal").read_bytes()
        best = np.inf
        for _ in range(3):
            shutil.copy(d / "o.nc.journal", d / "keep.journal")
            t0 = time.perf_counter()
            r = subprocess.run([exe, str(d / "s.nml"), "-o", str(d / "o.nc"), "--max-profiles",
                                "1"], capture_output=True, text=True, timeout=3600)
            best = min(best, time.perf_counter() - t0)
            if r.returncode != 3:
                raise RuntimeError(r.stderr)
            shutil.copy(d / "keep.journal", d / "o.nc.journal")
    per = max(best - compute / n, 0.0) / n
    log(f"  computing {n:,} profiles (1 speed, dry): {compute:.2f} s, "
        f"{1e3 * compute / n:.2f} ms a profile")
    log(f"  resuming (journal {len(journal) / 1e6:.1f} MB, profiles {size / 1e6:.1f} MB; "
        f"then one profile computed): {best:.2f} s; the check {1e6 * per:.0f} us a profile "
        f"= {100 * per / (compute / n):.1f} % of computing it")
    return {"profiles": n, "compute": compute, "resume": best}


def run(log=print, quick: bool = False) -> dict:
    """Every batch figure: uneven MPI batch, long list, journal resume
    (``quick``: small sizes, one repeat, to check the code runs)."""
    if quick:
        return {"mpi_uneven": mpi_uneven(log, repeats=1, n_short=24, long_points=10_000),
                "list": profile_list_reading(log, n=2000),
                "resume": journal_resume(log, n=100, points=1024)}
    return {"mpi_uneven": mpi_uneven(log), "list": profile_list_reading(log),
            "resume": journal_resume(log)}


if __name__ == "__main__":
    run()
