"""Benchmark of batch runs: MPI on an uneven batch, reading a long profile
list, and the cost of checking the journal on a resume.

Run from a checkout: ``python -m pavefric.studies.bench_mpi`` (also part of
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

from ..config import program

DX = 0.87e-3


def _program() -> str | None:
    # the executable, not the launcher on PATH (no Python start-up in the times)
    return shutil.which(str(program()))


def _env() -> dict:
    return {**os.environ, "OMP_NUM_THREADS": "1", "OMPI_ALLOW_RUN_AS_ROOT": "1",
            "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1"}


def uneven_batch(directory: Path, n_short: int = 240, n_long: int = 6,
                 short_points: int = 2048, long_points: int = 100_000) -> Path:
    """A batch of `n_short` short profiles and `n_long` long ones, the long
    ones first at odd positions (1, 3, 5...): where a round-robin deal over
    two ranks gives every long profile to rank 0. Returns the scene path."""
    from ..surfaces import spectral_profile, write_profile

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
                    line = [x for x in r.stderr.splitlines() if "CPU seconds per rank" in x][0]
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
    from ..surfaces import spectral_profile, write_profile

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


# The survey that docs/cluster.md plans: a national network's texture survey.
SURVEY = {"profiles": 1_000_000, "points": 100_000, "dx": 0.5e-3, "speeds": 8,
          "depths": (0.0, 0.5e-3, 1.0e-3), "cores_per_node": 64}


def _survey_profiles(directory: Path, n: int, points: int) -> Path:
    """n survey profiles of `points` heights at the survey's spacing, in one
    NetCDF file as pavefric.write_profiles writes it (float64 heights)."""
    from .. import write_profiles
    from ..surfaces import spectral_profile

    zs = np.array([spectral_profile(points, SURVEY["dx"], rms=0.5e-3, skew=-0.4, seed=k,
                                    wavelength_max=40e-3) for k in range(n)])
    path = directory / f"survey_{n}.nc"
    write_profiles(path, zs, dx=SURVEY["dx"], names=[f"s{k:05d}" for k in range(n)],
                   chainage=10.0 * np.arange(n))
    return path


def _survey_scene(directory: Path, survey: Path, speeds: int, depths, tag: str) -> Path:
    kmh = ", ".join(str(10 * (k + 1)) for k in range(speeds))
    dep = ", ".join(repr(float(d)) for d in depths)
    scene = directory / f"survey_{tag}.nml"
    scene.write_text(f"&batch profiles = '{survey.name}', depths = {dep}, restart = .false. /\n"
                     "&surface closed = .false., mu_loc = 0.6 /\n"
                     # a survey checks its accuracy on a sample of profiles
                     # (docs/cluster.md), not with a second pass of each
                     "&numerics error_estimate = .false. /\n"
                     f"&operation speeds_kmh = {kmh} /\n")
    return scene


#: Runs argv[1:] and prints its wall time and peak RSS (kB, wait4). Started
#: by `_timed` as a small process of its own: Linux counts in a child's peak
#: the pages it held before exec, the whole benchmark's after its fork.
_MEASURE_CHILD = """
import os, subprocess, sys, time
t0 = time.perf_counter()
p = subprocess.Popen(sys.argv[1:], stdout=subprocess.DEVNULL)
_, status, usage = os.wait4(p.pid, 0)
seconds = time.perf_counter() - t0
p.returncode = os.waitstatus_to_exitcode(status)
print(seconds, usage.ru_maxrss)
sys.exit(0 if p.returncode == 0 else 1)
"""


def _timed(cmd, env, cwd, repeats) -> tuple[float, float]:
    """Best wall time of `cmd` and the peak RSS (kB) of its last run: that
    process's own, measured from a small intermediate process (not
    RUSAGE_CHILDREN, the largest child this process ever had, nor wait4 on
    a child of this process, which counts the benchmark's own pages: inside
    `python -m pavefric bench` both reported about 500 MB for a 76 MB run)."""
    best = float("inf")
    rss = 0.0
    for _ in range(repeats):
        r = subprocess.run([sys.executable, "-c", _MEASURE_CHILD, *map(str, cmd)],
                           capture_output=True, text=True, env=env, cwd=cwd)
        if r.returncode != 0:
            raise RuntimeError(f"{' '.join(map(str, cmd))}: {r.stderr[-400:]}")
        seconds, kb = r.stdout.split()
        best = min(best, float(seconds))
        rss = float(kb)
    return best, rss


def survey_plan(log=print, quick: bool = False, repeats: int = 3) -> dict:
    """What a survey of SURVEY costs, from measurements on this machine:
    seconds per profile (the full sweep of speeds and depths, one thread),
    the fixed cost per profile (read, preprocess, texture, write: the part
    that does not grow with speeds), weak scaling over 1 and 2 ranks, two
    threads against one; then the planned core-hours, wall time on N nodes,
    input and output sizes. docs/cluster.md quotes it."""
    exe = _program()
    if exe is None or shutil.which("mpirun") is None:
        log("  (survey plan skipped: the program or mpirun is missing)")
        return {}
    points = 10_000 if quick else SURVEY["points"]
    n = 2 if quick else 4
    reps = 1 if quick else repeats
    log(f"\n== Survey plan: measured on {n} profiles of {points:,} points at "
        f"{SURVEY['dx'] * 1e3:g} mm, {SURVEY['speeds']} speeds x {len(SURVEY['depths'])} depths ==")
    out: dict = {}
    with tempfile.TemporaryDirectory() as tmp:
        d = Path(tmp)
        survey = _survey_profiles(d, n, points)
        survey2 = _survey_profiles(d, 2 * n, points)
        full = _survey_scene(d, survey, SURVEY["speeds"], SURVEY["depths"], "full")
        one = _survey_scene(d, survey, 1, (0.0,), "one")
        eight = _survey_scene(d, survey, SURVEY["speeds"], (0.0,), "eight")
        full2 = _survey_scene(d, survey2, SURVEY["speeds"], SURVEY["depths"], "full2")
        env1 = {**_env(), "OMP_NUM_THREADS": "1"}
        t_full, rss = _timed([exe, str(full), "-o", "f.nc"], env1, d, reps)
        t_one, _ = _timed([exe, str(one), "-o", "o.nc"], env1, d, reps)
        t_eight, _ = _timed([exe, str(eight), "-o", "e.nc"], env1, d, reps)
        t_thr, _ = _timed([exe, str(full), "-o", "t.nc"], {**env1, "OMP_NUM_THREADS": "2"}, d,
                          reps)
        mpi = [shutil.which("mpirun"), "--oversubscribe", "-n", "2"]
        if os.geteuid() == 0:
            mpi.append("--allow-run-as-root")
        t_mpi, _ = _timed(mpi + [exe, str(full2), "-o", "m.nc"], env1, d, reps)
        # per profile: the growth from n to 2n profiles (the header is shared)
        out_bytes = ((d / "m.nc").stat().st_size - (d / "f.nc").stat().st_size) / n
        in_bytes = (survey2.stat().st_size - survey.stat().st_size) / n
    per = t_full / n
    # one speed costs (t_eight - t_one) / 7 a profile; the rest of t_one is fixed
    per_speed = max(t_eight - t_one, 0.0) / 7 / n
    fixed = max(t_one / n - per_speed, 0.0)
    weak = t_full / t_mpi
    log(f"  one rank, one thread: {per:.3f} s a profile (all {SURVEY['speeds']} speeds x "
        f"{len(SURVEY['depths'])} depths); peak memory {rss / 1024:.0f} MB")
    log(f"  fixed cost a profile (read, preprocess, texture, write, start-up shared): "
        f"{fixed:.3f} s ({100 * fixed / per:.1f} %); one dry speed {per_speed:.3f} s")
    log(f"  weak scaling: 2 ranks on {2 * n} profiles vs 1 rank on {n}: efficiency "
        f"{weak:.2f}; two threads on one rank: {t_full / t_thr:.2f}x")
    scale = SURVEY["points"] / points
    core_s = SURVEY["profiles"] * per * scale
    core_h = core_s / 3600
    eff = min(weak, 1.0)
    rows = []
    for nodes in (1, 4, 16, 64):
        cores = nodes * SURVEY["cores_per_node"]
        rows.append((nodes, cores, core_h / (cores * eff)))
    in_total = SURVEY["profiles"] * in_bytes * scale
    out_total = SURVEY["profiles"] * out_bytes
    log(f"  planned ({SURVEY['profiles']:,} profiles of {SURVEY['points']:,} points): "
        f"{core_h:,.0f} core-hours at this machine's rate; input {in_total / 1e9:,.0f} GB "
        f"(float64 heights as write_profiles stores them), output {out_total / 1e9:.2f} GB "
        f"({out_bytes / 1e3:.1f} kB a profile)")
    for nodes, cores, hours in rows:
        log(f"    {nodes:3d} nodes x {SURVEY['cores_per_node']} cores: {hours:8.1f} h wall "
            f"(weak-scaling efficiency {eff:.2f})")
    out.update(per_profile=per, fixed=fixed, per_speed=per_speed, weak=weak,
               threads=t_full / t_thr, rss_kb=rss, core_hours=core_h, input_bytes=in_total,
               output_bytes=out_total, plan=rows, points=points, measured_profiles=n)
    return out


def run(log=print, quick: bool = False) -> dict:
    """Every batch figure: uneven MPI batch, long list, journal resume
    (``quick``: small sizes, one repeat, to check the code runs)."""
    if quick:
        return {"mpi_uneven": mpi_uneven(log, repeats=1, n_short=24, long_points=10_000),
                "list": profile_list_reading(log, n=2000),
                "resume": journal_resume(log, n=100, points=1024),
                "survey": survey_plan(log, quick=True)}
    return {"mpi_uneven": mpi_uneven(log), "list": profile_list_reading(log),
            "resume": journal_resume(log), "survey": survey_plan(log)}


if __name__ == "__main__":
    if sys.argv[1:] == ["survey"]:
        survey_plan()
    elif sys.argv[1:] == ["survey", "--quick"]:
        survey_plan(quick=True)
    else:
        run()
