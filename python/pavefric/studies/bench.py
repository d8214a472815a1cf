"""Benchmark: throughput, scaling and memory of the Fortran core, each figure
printed beside the same work done by the plain loop (plain_loop.f90 beside
this module: MODEL.md written the obvious way in Fortran) and, when given
(``--reference tests/reference.py``), by the NumPy reference of MODEL.md
(the tests' slow oracle, which the package neither ships nor imports), in
the same run.

Run from a checkout: ``python -m pavefric bench [--report docs/performance.md]
[--reference tests/reference.py]``.
Not a test: absolute times are noisy; ratios measured side by side are the
figures to read.
"""
from __future__ import annotations

import importlib.util
import json
import os
import subprocess
import sys
import time
import warnings
from pathlib import Path

import numpy as np

from . import bench_mpi, rubber_report
from ..config import program

DX = 0.87e-3


def _reference(path: str | os.PathLike | None):
    """The NumPy reference the user named (a Python file whose simulate() has
    pavefric.simulate's signature: tests/reference.py in a checkout), or None."""
    if path is None:
        return None
    here = Path(path)
    if not here.is_file():
        from ..core import PavefricError

        raise PavefricError(f"bench --reference {path}: no such file (give the NumPy "
                            "reference, tests/reference.py in a checkout)")
    spec = importlib.util.spec_from_file_location("pavefric_reference", here)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def surfaces():
    """Texture profiles of three kinds (CTM-like, closed, 1024 points)."""
    from ..surfaces import spectral_profile

    return {
        "fine (rms 0.2 mm)": spectral_profile(1024, DX, rms=0.2e-3, seed=21),
        "medium (rms 0.5 mm)": spectral_profile(1024, DX, rms=0.5e-3, skew=-0.3, seed=22),
        "coarse (rms 1.0 mm)": spectral_profile(1024, DX, rms=1.0e-3, skew=-0.6, seed=23),
    }


def _best(fn, repeats=3):
    best = np.inf
    out = None
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def _rate_core(z, dx, closed=True, speeds=(60.0,), repeats=3, **kw):
    from ..core import simulate

    kw.setdefault("error_estimate", False)     # one pass, as the plain loop and the reference
    kw.setdefault("time_scheme", "euler")      # their scheme: one Euler step per sample
    kw.setdefault("min_contacts", 0)           # their pad: no refinement pass
    seconds, ds = _best(lambda: simulate(z, dx, list(speeds), closed=closed, **kw), repeats)
    n_el = ds.attrs["pad_elements"]
    steps = n_el * (ds.attrs["averaged_positions"] + ds.attrs["spinup_positions"]) * len(speeds)
    return steps / seconds, seconds, ds


def _rate_reference(ref, z, dx, closed=True, speeds=(60.0,), **kw):
    """Element-steps per second of the NumPy reference (NaN without one)."""
    if ref is None:
        return float("nan"), float("nan")
    t0 = time.perf_counter()
    ref.simulate(z, dx, list(speeds), closed=closed, **kw)
    seconds = time.perf_counter() - t0
    n_el = int(np.floor(kw.get("length", 0.020) / dx + 0.5))
    positions = (z.size + n_el) if closed else (z.size - n_el + 1)
    return n_el * positions * len(speeds) / seconds, seconds


def _child(code: str, env=None) -> dict:
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                       env={**os.environ, **(env or {})}, timeout=1800)
    if r.returncode != 0:
        raise RuntimeError(r.stderr)
    return json.loads(r.stdout.strip().splitlines()[-1])


def throughput(ref, log, tile: int = 64):
    rows = []
    log("\n== Throughput per core, N = 23 (0.87 mm, 20 mm pad), 60 km/h ==")
    log(f"{'surface':22s} {'scene':5s} {'core Msteps/s':>14s} {'numpy Msteps/s':>15s} {'ratio':>8s}")
    for name, z in surfaces().items():
        big = np.tile(z, tile)                      # 65,536 points: a measurable time
        for scene, kw, nref in (("dry", {}, 1024), ("wet", {"depth": 1e-3}, 128)):
            core, _, _ = _rate_core(big, DX, **kw)
            numpy_rate, _ = _rate_reference(ref, z[:nref], DX, **kw)
            rows.append(dict(surface=name, scene=scene, core=core, numpy=numpy_rate,
                             ratio=core / numpy_rate))
            log(f"{name:22s} {scene:5s} {core / 1e6:14.1f} {numpy_rate / 1e6:15.3f} "
                f"{core / numpy_rate:8.0f}x")
    return rows


def scaling_elements(ref, log, points: int = 8192):
    from ..surfaces import spectral_profile

    log(f"\n== Scaling in pad elements N (finer profiles, 20 mm pad, {points} points, 60 km/h) ==")
    log(f"{'N':>6s} {'dx mm':>8s} {'dry Msteps/s':>13s} {'wet Msteps/s':>13s} "
        f"{'numpy dry':>10s} {'ratio dry':>10s}")
    rows = []
    for r in (1, 2, 4, 8, 16, 32, 87):
        dx = DX / r
        z = spectral_profile(points, dx, rms=0.5e-3, wavelength_min=max(2e-3, 4 * dx),
                             wavelength_max=min(50e-3, points * dx / 4), seed=5)
        # one element a sample (element_length = 0): the pad's own default
        # length would resample every profile to 23 elements
        dry, _, ds = _rate_core(z, dx, repeats=2, element_length=0.0)
        wet, _, _ = _rate_core(z, dx, repeats=2, depth=1e-3, element_length=0.0)
        nref = min(points, max(64, 40000 // (23 * r)))
        numpy_rate, _ = _rate_reference(ref, z[:max(nref, 23 * r + 40)], dx)
        n = ds.attrs["pad_elements"]
        rows.append(dict(N=n, dx=dx, dry=dry, wet=wet, numpy=numpy_rate))
        log(f"{n:6d} {dx * 1e3:8.4f} {dry / 1e6:13.1f} {wet / 1e6:13.1f} "
            f"{numpy_rate / 1e6:10.3f} {dry / numpy_rate:9.0f}x")
    worst = max(rows[0]["dry"] / r["dry"] for r in rows)
    log(f"per-element cost at N = {rows[-1]['N']} vs N = 23: dry "
        f"{rows[0]['dry'] / rows[-1]['dry']:.2f}x, wet {rows[0]['wet'] / rows[-1]['wet']:.2f}x "
        f"(worst dry over N: {worst:.2f}x)")
    return rows


MEMORY_CHILD = """
import json, resource, sys, time, numpy as np, pavefric
n = int(sys.argv[1]); nspeeds = int(sys.argv[2])
z = 1e-4 * np.sin(np.arange(n) * 0.37) + 2e-4 * np.sin(np.arange(n) * 0.051)
pavefric.simulate(z[:200], 0.87e-3, [60.0])
base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
t0 = time.perf_counter()
ds = pavefric.simulate(z, 0.87e-3, list(np.linspace(20, 80, nspeeds)), closed=False,
                       error_estimate=False, time_scheme="euler")
t = time.perf_counter() - t0
peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
print(json.dumps({"n": n, "seconds": t, "extra_bytes": (peak - base) * 1024,
                  "steps": 23 * (n - 22) * nspeeds}))
"""


def scaling_length(log, largest=10_000_000):
    log("\n== Scaling in profile length (open profile, dry, 1 speed, 1 thread) ==")
    log(f"{'points':>10s} {'seconds':>9s} {'Msteps/s':>9s} {'peak extra MB':>14s} "
        f"{'bytes/point':>12s}")
    rows = []
    n = 1000
    while n <= largest:
        res = _child(f"import sys; sys.argv = ['x', '{n}', '1']\n" + MEMORY_CHILD,
                     env={"OMP_NUM_THREADS": "1"})
        rows.append(res)
        log(f"{n:10d} {res['seconds']:9.3f} {res['steps'] / res['seconds'] / 1e6:9.1f} "
            f"{res['extra_bytes'] / 2**20:14.1f} {res['extra_bytes'] / n:12.1f}")
        n *= 10
    six = _child(f"import sys; sys.argv = ['x', '{largest // 10}', '6']\n" + MEMORY_CHILD,
                 env={"OMP_NUM_THREADS": "1"})
    one = next(r for r in rows if r["n"] == largest // 10)
    log(f"memory with 6 speeds vs 1 at {largest // 10:,} points (no series): "
        f"{six['extra_bytes'] / 2**20:.1f} MB vs {one['extra_bytes'] / 2**20:.1f} MB")
    return rows, six


THREADS_CHILD = """
import json, time, numpy as np, pavefric
from pavefric.surfaces import spectral_profile
z = np.tile(spectral_profile(1024, 0.87e-3, rms=0.5e-3, seed=22), TILE)
speeds = [10.0, 20.0, 30.0, 40.0, 60.0, 80.0]
pavefric.simulate(z[:200], 0.87e-3, speeds)
best = 1e9
for _ in range(3):
    t0 = time.perf_counter()
    ds = pavefric.simulate(z, 0.87e-3, speeds, depth=DEPTH, error_estimate=False)
    best = min(best, time.perf_counter() - t0)
print(json.dumps({"seconds": best, "mu": ds["mu"].values.tolist()}))
"""


def threads(log, tile: int = 64):
    log(f"\n== OpenMP over the speeds of a sweep (6 speeds, {1024 * tile:,} points) ==")
    rows = []
    for scene, depth in (("dry", "0.0"), ("wet", "1e-3")):
        code = THREADS_CHILD.replace("DEPTH", depth).replace("TILE", str(tile))
        one = _child(code, env={"OMP_NUM_THREADS": "1"})
        two = _child(code, env={"OMP_NUM_THREADS": "2"})
        same = one["mu"] == two["mu"]
        rows.append(dict(scene=scene, one=one["seconds"], two=two["seconds"], same=same))
        log(f"{scene}: 1 thread {one['seconds']:.3f} s, 2 threads {two['seconds']:.3f} s, "
            f"speed-up {one['seconds'] / two['seconds']:.2f}x, identical results: {same}")
    return rows


API_THREADS_CHILD = r"""
import ctypes as C, json, pathlib, sys, threading, time
import numpy as np, pavefric
from pavefric.surfaces import spectral_profile
lib = C.CDLL(str(pathlib.Path(pavefric.__file__).parent / "lib" / "libpavefric.so"))
vp, dp = C.c_void_p, C.POINTER(C.c_double)
for name, res, args in (("pavefric_new_error", vp, []), ("pavefric_new_scene", vp, [vp, C.c_char_p]),
                        ("pavefric_set_profile", None, [vp, vp, C.c_int, dp, C.c_double, C.c_int]),
                        ("pavefric_run", None, [vp, vp, dp]), ("pavefric_check_error", C.c_int, [vp])):
    f = getattr(lib, name); f.restype = res; f.argtypes = args
TEXT = b"&surface dx = 0.87e-3 / &water depth = DEPTH / &operation speeds_kmh = 20, 40, 60, 80 /"
runs = []
for seed, depth in ((22, b"1e-3"), (23, b"1e-3")):
    z = np.ascontiguousarray(np.tile(spectral_profile(1024, 0.87e-3, rms=0.5e-3, seed=seed), TILE))
    err = lib.pavefric_new_error()
    scene = lib.pavefric_new_scene(err, TEXT.replace(b"DEPTH", depth))
    lib.pavefric_set_profile(err, scene, z.size, z.ctypes.data_as(dp), 0.87e-3, 1)
    assert not lib.pavefric_check_error(err)
    runs.append((err, scene, z))
cpu = {}
def run(k, out, mode):
    err, scene, _ = runs[k]
    t0 = time.thread_time()
    lib.pavefric_run(err, scene, out.ctypes.data_as(dp))
    cpu[mode] = cpu.get(mode, 0.0) + time.thread_time() - t0
    assert not lib.pavefric_check_error(err)
serial_best = parallel_best = 1e9
for _ in range(REPEATS):
    a, b = np.zeros(4), np.zeros(4)
    t0 = time.perf_counter(); run(0, a, "serial"); run(1, b, "serial")
    serial_best = min(serial_best, time.perf_counter() - t0)
    c, d = np.zeros(4), np.zeros(4)
    threads = [threading.Thread(target=run, args=(k, o, "parallel")) for k, o in ((0, c), (1, d))]
    t0 = time.perf_counter()
    for t in threads: t.start()
    for t in threads: t.join()
    parallel_best = min(parallel_best, time.perf_counter() - t0)
    same = a.tobytes() == c.tobytes() and b.tobytes() == d.tobytes()
    if not same: break
# CPU time of the runs (the threads' own clocks), the same whatever else the
# machine does: equal in both modes when nothing in the library serialises
print(json.dumps({"serial": serial_best, "parallel": parallel_best, "same": same,
                  "cpu_serial": cpu["serial"], "cpu_parallel": cpu.get("parallel", 0.0)}))
"""


def api_threads(log, tile: int = 32, repeats: int = 5) -> dict:
    """Issue 19: two scenes (two wet profiles of equal length, 4 speeds each) run on two
    threads at once through the C API (ctypes, which lets go of the GIL),
    against the same two one after the other; one OpenMP thread a run, the
    best of `repeats` each."""
    log(f"\n== C API: two scenes on two threads against one after the other "
        f"({1024 * tile:,} points, 4 speeds, OMP_NUM_THREADS=1) ==")
    code = API_THREADS_CHILD.replace("TILE", str(tile)).replace("REPEATS", str(repeats))
    r = _child(code, env={"OMP_NUM_THREADS": "1"})
    r["ratio"] = r["parallel"] / r["serial"]
    r["cpu_ratio"] = r["cpu_parallel"] / r["cpu_serial"]
    log(f"serial {r['serial']:.3f} s, two threads {r['parallel']:.3f} s: "
        f"{r['ratio']:.2f}x the serial time (target <= 0.7x), identical results: {r['same']}; "
        f"CPU time of the runs on two threads {r['cpu_ratio']:.2f}x that of the serial runs "
        f"(the threads' own clocks: sharing the process costs the runs no extra work; the "
        f"wall time also depends on how many cores are free)")
    return r


def mpi_batch(log, root: Path | None = None) -> dict:
    """Throughput of the demo batch's profiles with 1 and 2 MPI ranks (one
    OpenMP thread each), on a heavier sweep (8 speeds, 3 depths) so that the
    run, not mpirun's start-up, is measured."""
    import shutil
    import tempfile

    log("\n== MPI batch: demo profiles, 1 rank against 2 ranks (OMP_NUM_THREADS=1) ==")
    mpirun = shutil.which("mpirun")
    # the executable itself, not the launcher on PATH (no Python start-up in the times)
    exe = shutil.which(str(program()))
    root = root or Path.cwd()
    demo_dir = root / "inputs" / "batch_demo"
    if mpirun is None or exe is None or not demo_dir.exists():
        log("skipped: needs mpirun, the pavefric program and inputs/batch_demo/")
        return {}
    with tempfile.TemporaryDirectory() as tmp:
        scene = Path(tmp) / "bench_batch.nml"
        scene.write_text(f"&batch profiles = '{demo_dir}/*.txt', depths = 0.0, 0.5e-3, 1.0e-3 /\n"
                         "&surface closed = .false., mu_loc = 0.6 /\n"
                         "&operation speeds_kmh = 10, 20, 30, 40, 50, 60, 70, 80 /\n")
        env = {**os.environ, "OMP_NUM_THREADS": "1", "OMPI_ALLOW_RUN_AS_ROOT": "1",
               "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1"}
        times, rates = {}, {}
        for ranks in (1, 2):
            best, rate = np.inf, 0.0
            for rep in range(3):
                out = Path(tmp) / f"o{ranks}_{rep}.nc"
                t0 = time.perf_counter()
                r = subprocess.run([mpirun, "--oversubscribe", "-n", str(ranks), exe, str(scene),
                                    "-o", str(out)], capture_output=True, text=True, env=env)
                best = min(best, time.perf_counter() - t0)
                if r.returncode != 0:
                    raise RuntimeError(r.stderr)
                # the batch's own throughput: its last progress line (stderr), timed from
                # the first profile (after MPI start-up and reading the inputs)
                last = [l for l in r.stderr.splitlines() if "profiles/s" in l][-1]
                rate = max(rate, float(last.split("%), ")[1].split(" profiles/s")[0]))
            times[ranks], rates[ranks] = best, rate
    n = len(list(demo_dir.glob("*.txt")))
    log(f"{n} profiles x 3 depths x 8 speeds: throughput 1 rank {rates[1]:.0f} profiles/s, "
        f"2 ranks {rates[2]:.0f} profiles/s: {rates[2] / rates[1]:.2f}x")
    log(f"  wall time including mpirun start-up: 1 rank {times[1]:.2f} s, 2 ranks "
        f"{times[2]:.2f} s: {times[1] / times[2]:.2f}x")
    return {"one": times[1], "two": times[2], "rate_one": rates[1], "rate_two": rates[2],
            "profiles": n}


def _checkout_file(rel: str) -> Path:
    here = Path.cwd() / rel
    if not here.exists():
        here = Path(__file__).resolve().parents[3] / rel
    if not here.exists():
        raise FileNotFoundError(f"{rel} not found: run the benchmark from a checkout")
    return here


class PlainLoop:
    """The plain loop (plain_loop.f90 beside this module): MODEL.md written the obvious way
    in Fortran, compiled here with the core's optimisation; its compute time
    (the reading excluded, timed inside it) is the yardstick."""

    def __init__(self, directory: Path):
        import shutil

        fc = shutil.which("gfortran")
        if fc is None:
            raise RuntimeError("gfortran not found: the plain loop cannot be built")
        self.exe = directory / "plain_loop"
        r = subprocess.run([fc, "-O3", "-funroll-loops", "-o", str(self.exe),
                            str(Path(__file__).with_name("plain_loop.f90")), "-llapack"],
                           capture_output=True, text=True)
        if r.returncode != 0:
            raise RuntimeError(r.stderr)
        self.directory = directory

    def run(self, z: np.ndarray, dx: float, speeds, closed: bool, depth: float = 0.0,
            repeats: int = 3) -> dict:
        path = self.directory / "heights.bin"
        np.ascontiguousarray(z, dtype="<f8").tofile(path)
        best = None
        for _ in range(repeats):
            r = subprocess.run([str(self.exe), str(path), repr(dx), "1" if closed else "0",
                                repr(depth)] + [repr(float(v)) for v in speeds],
                               capture_output=True, text=True, timeout=3600)
            if r.returncode != 0:
                raise RuntimeError(r.stderr + r.stdout)
            res = json.loads(r.stdout)
            if best is None or res["seconds"] < best["seconds"]:
                best = res
        return best


SWEEP_CHILD = """
import json, sys, time, warnings, numpy as np, pavefric
warnings.simplefilter("ignore")
z = np.load(sys.argv[1]); speeds = json.loads(sys.argv[2]); kw = json.loads(sys.argv[3])
kw.setdefault("error_estimate", False)
kw.setdefault("time_scheme", "euler")   # the plain loop's scheme, whatever the default
kw.setdefault("min_contacts", 0)        # the plain loop's pad: no refinement pass
pavefric.simulate(z[:4096], 0.87e-3, speeds, **kw)
best = 1e9
for _ in range(int(sys.argv[4])):
    t0 = time.perf_counter()
    ds = pavefric.simulate(z, 0.87e-3, speeds, **kw)
    best = min(best, time.perf_counter() - t0)
steps = ds.attrs["pad_elements"] * (ds.attrs["averaged_positions"]
                                    + ds.attrs["spinup_positions"]) * len(speeds)
print(json.dumps({"seconds": best, "steps": int(steps), "mu": ds["mu"].values.tolist(),
                  "evaluations": ds["bearing_evaluations"].values.tolist(),
                  "positions": int(ds.attrs["averaged_positions"]
                                   + ds.attrs["spinup_positions"])}))
"""

#: The fixed cost of one call: a 64-point profile, 6 speeds, best of many.
CALL_CHILD = """
import json, time, warnings, pavefric
from pavefric.surfaces import spectral_profile
warnings.simplefilter("ignore")
z = spectral_profile(1024, 0.87e-3, rms=1.0e-3, skew=-0.6, seed=23)[:64]
speeds = [10.0, 20.0, 30.0, 40.0, 60.0, 80.0]
pavefric.simulate(z, 0.87e-3, speeds, error_estimate=False)
best = 1e9
for _ in range(200):
    t0 = time.perf_counter()
    pavefric.simulate(z, 0.87e-3, speeds, error_estimate=False)
    best = min(best, time.perf_counter() - t0)
print(json.dumps({"seconds": best}))
"""


def sweep(ref, plain: PlainLoop, log, repeats: int = 2, tile: int = 64, rounds: int = 5) -> list:
    """Issue 13's kernel figures: N = 23 on a 6-speed sweep (10-80 km/h), one
    thread, dry and wet (the paper's bearing, the drainage film and the
    Reynolds film), the core
    beside the plain loop and the NumPy reference on the same profiles. Each
    is timed in `rounds` alternating rounds (the core best of `repeats` runs
    in its child, the plain loop one run), the best of each kept."""
    import tempfile

    speeds = [10.0, 20.0, 30.0, 40.0, 60.0, 80.0]
    log("\n== N = 23, a 6-speed sweep (10-80 km/h), one thread, the core and the plain loop "
        f"in {rounds} alternating rounds, best of each (targets: dry >= 300, "
        "wet >= 60 M element-steps/s) ==")
    log(f"{'surface':22s} {'scene':14s} {'core M/s':>9s} {'plain M/s':>10s} {'core/plain':>11s} "
        f"{'numpy M/s':>10s} {'core/numpy':>11s} {'|mu - plain|':>13s}")
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for name, z0 in surfaces().items():
            z = np.tile(z0, tile)                            # 65,536 points, closed
            zpath = Path(tmp) / "z.npy"
            np.save(zpath, z)
            for scene, kw, depth in (("dry", {}, 0.0), ("wet", {"depth": 1e-3}, 1e-3),
                                     ("wet, squeeze", {"depth": 1e-3, "wet_model": "squeeze"},
                                      None),
                                     ("wet, reynolds", {"depth": 1e-3,
                                                        "wet_model": "reynolds"}, None)):
                # The core and the plain loop in alternate rounds, the best of
                # each: on a shared host the load drifts over seconds, and a
                # ratio of two times taken a minute apart measured the drift
                # (a surface's wet ratio 4.6x in one run where the three
                # surfaces' times were equal within 5 % in a quiet one).
                core, pl = None, None
                for _ in range(rounds):
                    c = _child_args(SWEEP_CHILD, [str(zpath), json.dumps(speeds), json.dumps(kw),
                                                  str(repeats)], env={"OMP_NUM_THREADS": "1"})
                    if core is None or c["seconds"] < core["seconds"]:
                        core = c
                    if depth is not None:
                        p = plain.run(z, DX, speeds, True, depth, repeats=1)
                        if pl is None or p["seconds"] < pl["seconds"]:
                            pl = p
                core_rate = core["steps"] / core["seconds"]
                row = dict(surface=name, scene=scene, core=core_rate)
                if depth is not None:
                    row["plain"] = pl["element_steps"] / pl["seconds"]
                    row["mu_diff"] = float(np.max(np.abs(np.array(pl["mu"]) - core["mu"])))
                nref = 256 if depth == 0.0 else 64
                if depth is not None and ref is not None:
                    numpy_rate, _ = _rate_reference(ref, z0[:nref], DX, speeds=speeds,
                                                    **({"depth": depth, "alpha": 12.0}
                                                       if depth else {}))
                    row["numpy"] = numpy_rate
                if depth:
                    # wet balance evaluations per speed and position
                    row["evaluations"] = sum(core["evaluations"]) / (len(speeds)
                                                                     * core["positions"])
                rows.append(row)
                plain_s = f"{row['plain'] / 1e6:10.1f} {core_rate / row['plain']:10.2f}x" \
                    if "plain" in row else f"{'-':>10s} {'-':>11s}"
                numpy_s = f"{row['numpy'] / 1e6:10.3f} {core_rate / row['numpy']:10.0f}x" \
                    if "numpy" in row else f"{'-':>10s} {'-':>11s}"
                diff = f"{row['mu_diff']:13.1e}" if "mu_diff" in row else f"{'-':>13s}"
                log(f"{name:22s} {scene:14s} {core_rate / 1e6:9.1f} {plain_s} {numpy_s} {diff}")
    sq = [r["core"] for r in rows if r["scene"] == "wet, squeeze"]
    kane = [r["core"] for r in rows if r["scene"] == "wet"]
    ratio = max(k / q for k, q in zip(kane, sq))
    log(f"the drainage film's cost per element-step against the paper's wet model: at most "
        f"{ratio:.2f}x (target <= 2x)")
    rey = [r["core"] for r in rows if r["scene"] == "wet, reynolds"]
    log(f"the Reynolds film's cost per element-step against the paper's wet model: at most "
        f"{max(k / q for k, q in zip(kane, rey)):.2f}x (target <= 3x)")
    ev = [r["evaluations"] for r in rows if "evaluations" in r]
    log(f"the paper's wet balance: {min(ev):.2f}-{max(ev):.2f} bearing evaluations "
        f"(passes over the pad) per speed "
        f"and position")
    call = _child(CALL_CHILD, env={"OMP_NUM_THREADS": "1"})
    log(f"the fixed cost of one call (64 points, 6 speeds, pavefric.simulate): "
        f"{call['seconds'] * 1e3:.2f} ms")
    rows.append({"scene": "call", "seconds": call["seconds"]})
    return rows


def _child_args(code: str, args: list[str], env=None) -> dict:
    r = subprocess.run([sys.executable, "-c", code] + args, capture_output=True, text=True,
                       env={**os.environ, **(env or {})}, timeout=3600)
    if r.returncode != 0:
        raise RuntimeError(r.stderr)
    return json.loads(r.stdout.strip().splitlines()[-1])


def whole_program(plain: PlainLoop, log, points: int = 400_000, repeats: int = 3) -> dict:
    """Issue 13's whole-program figure: the program on a 400,000-point dry
    text profile at 10 speeds (reading, preprocessing checks, the run, the
    NetCDF file), wall time, against the plain loop's compute alone on the
    same heights and speeds; one thread and two."""
    import tempfile

    from ..surfaces import spectral_profile, write_profile

    exe = program()   # the executable, not the launcher (no Python start-up in the time)
    speeds = [10.0, 20.0, 30.0, 40.0, 50.0, 60.0, 70.0, 80.0, 90.0, 100.0]
    out: dict = {}
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        z = spectral_profile(points, DX, rms=0.5e-3, skew=-0.3, seed=41)
        write_profile(str(tmp / "long.txt"), z)
        # the heights as the program reads them (the file's decimal digits)
        from ..profiles import read_profile

        zr = read_profile(tmp / "long.txt").heights
        scene = tmp / "long.nml"
        scene.write_text(f"&surface profile_file = 'long.txt', dx = {DX!r}, closed = .false. /\n"
                         "&numerics error_estimate = .false., time_scheme = 'euler' /\n"
                         "&operation speeds_kmh = " + ", ".join(f"{v:g}" for v in speeds)
                         + " /\n")
        pl = plain.run(zr, DX, speeds, False, 0.0)
        for threads in ("1", "2"):
            best = np.inf
            for _ in range(repeats):
                t0 = time.perf_counter()
                r = subprocess.run([str(exe), str(scene), "-o", str(tmp / "long.nc")],
                                   capture_output=True, text=True,
                                   env={**os.environ, "OMP_NUM_THREADS": threads})
                best = min(best, time.perf_counter() - t0)
                if r.returncode != 0:
                    raise RuntimeError(r.stderr)
            out[threads] = best
        import xarray as xr

        with xr.open_dataset(tmp / "long.nc") as ds:
            diff = float(np.max(np.abs(ds["mu"].values - np.array(pl["mu"]))))
    out.update(plain=pl["seconds"], steps=pl["element_steps"], mu_diff=diff, points=points)
    log(f"\n== Whole program: a {points:,}-point dry text profile, 10 speeds (target: at least "
        "1.5x the plain loop's compute) ==")
    log(f"  plain loop, compute only (reading excluded): {pl['seconds']:.3f} s")
    for threads in ("1", "2"):
        log(f"  pavefric long.nml (read, run, write NetCDF), {threads} thread(s): "
            f"{out[threads]:.3f} s: {pl['seconds'] / out[threads]:.2f}x the plain loop")
    log(f"  largest |mu(program) - mu(plain loop)|: {diff:.1e}")
    return out


# The scenes of the cost estimate: (set, name, namelist groups). The core's
# cost model (src/run/pavefric_simulate.f90, sec_*) was fitted on the
# "training" runs (a 65,536-point open profile, 1 to 12 speeds, each model);
# the "test" runs, which the fit never saw, judge it (other lengths, closed
# profiles, other knobs and pads). Its form (parts per profile sample, per
# pad position, per element-step) was chosen after a first fit on six-speed
# runs alone missed runs of one to four speeds by up to 2x.
_PRONY = "prony_stiffness = 1e8, 5e7, 2e7, prony_times = 1e-4, 1e-3, 1e-2"
_SPEEDS = {1: "40", 3: "20, 40, 60", 6: "10, 20, 30, 40, 60, 80",
           12: "5, 10, 15, 20, 25, 30, 40, 50, 60, 70, 80, 90"}
ESTIMATE_SCENES = [
    *[("training", f"dry Kelvin-Voigt, {n} speed(s)",
       f"&rubber viscosity = 3e3 / &operation speeds_kmh = {v} /") for n, v in _SPEEDS.items()],
    *[("training", f"wet kane2017, {n} speed(s)",
       f"&water depth = 1e-3, alpha = 1.0 / &operation speeds_kmh = {v} /")
      for n, v in _SPEEDS.items()],
    *[("training", f"wet squeeze, {n} speed(s)",
       f"&water depth = 1e-3, wet_model = 'squeeze' / &operation speeds_kmh = {_SPEEDS[n]} /")
      for n in (1, 12)],
    *[("training", f"wet reynolds, {n} speed(s)",
       f"&water depth = 1e-3, wet_model = 'reynolds' / &operation speeds_kmh = {_SPEEDS[n]} /")
      for n in (1, 6)],
    ("training", "dry Kelvin-Voigt, 1 speed, no error estimate",
     "&rubber viscosity = 3e3 / &numerics error_estimate = .false. / &operation speeds_kmh = 60 /"),
    ("training", "wet kane2017, 3 speeds, no error estimate",
     f"&water depth = 1e-3, alpha = 1.0 / &numerics error_estimate = .false. / "
     f"&operation speeds_kmh = {_SPEEDS[3]} /"),
    *[("training", f"dry Maxwell 3 arms, {n} speed(s)",
       f"&rubber model = 'maxwell', {_PRONY} / &operation speeds_kmh = {_SPEEDS[n]} /")
      for n in (1, 12)],
    ("test", "closed 16,384 points, wet kane2017, 3 speeds, substeps 8",
     "&surface closed = .true. / &water depth = 1e-3 / &numerics substeps = 8 / "
     "&operation speeds_kmh = 20, 40, 60 /"),
    ("test", "dry, 1 speed, elements_per_sample 2, substeps 3",
     "&numerics elements_per_sample = 2, substeps = 3 / &operation speeds_kmh = 60 /"),
    ("test", "wet squeeze, 2 speeds, substeps 4",
     "&water depth = 0.5e-3, wet_model = 'squeeze' / &numerics substeps = 4 / "
     "&operation speeds_kmh = 30, 70 /"),
    ("test", "wet kane2017, 10 speeds, a 40 mm pad",
     "&water depth = 2e-3 / &pad length = 0.040 / "
     "&operation speeds_kmh = 5, 10, 20, 30, 40, 50, 60, 70, 80, 90 /"),
    ("test", "closed 16,384 points, wet reynolds, 3 speeds, substeps 2",
     "&surface closed = .true. / &water depth = 0.5e-3, wet_model = 'reynolds' / "
     "&numerics substeps = 2 / &operation speeds_kmh = 20, 50, 80 /"),
    ("test", "dry, 6 speeds, no error estimate",
     "&numerics error_estimate = .false. / &operation speeds_kmh = 10, 20, 30, 40, 60, 80 /"),
    # a fine texture under 1 mm of water: from 40 km/h the film lifts the pad
    # onto few elements, and the default halves them for min_contacts and
    # for the error estimate (passes the estimate, made before the run, does
    # not foresee)
    ("test", "wet kane2017, fine texture (rms 0.2 mm), 3 speeds",
     "&surface fine / &water depth = 1e-3 / &operation speeds_kmh = 20, 50, 80 /"),
    ("test", "dry Maxwell 1 arm, 4 speeds, position_stride 2",
     "&rubber model = 'maxwell', prony_stiffness = 1e8, prony_times = 1e-3 / "
     "&numerics position_stride = 2, substeps = 2 / &operation speeds_kmh = 20, 40, 60, 80 /"),
]


def estimate_accuracy(log, points: int = 65_536, repeats: int = 3) -> list[dict]:
    """The cost the program estimates before a run (printed, and recorded as
    the output's estimated_seconds, from the core's calibrated rates)
    against the wall time of the same run of the program, one thread."""
    import tempfile

    import xarray as xr

    from ..surfaces import spectral_profile, write_profile

    exe = program()   # the executable, not the launcher (no Python start-up in the time)
    log(f"\n== Cost estimate against the measured time (the program on a {points:,}-point "
        f"open profile, or a closed one of a quarter of that, one thread; best of "
        f"{repeats}) ==")
    rows = []
    env = {**os.environ, "OMP_NUM_THREADS": "1"}
    with tempfile.TemporaryDirectory() as tmp:
        d = Path(tmp)
        write_profile(str(d / "p.txt"), spectral_profile(points, 0.87e-3, rms=0.5e-3,
                                                         skew=-0.3, seed=3))
        write_profile(str(d / "c.txt"), spectral_profile(max(points // 4, 1024), 0.87e-3,
                                                         rms=0.6e-3, skew=-0.5, seed=5))
        write_profile(str(d / "f.txt"), spectral_profile(points, 0.87e-3, rms=0.2e-3,
                                                         skew=-0.3, seed=7))
        for k, (which, name, groups) in enumerate(ESTIMATE_SCENES):
            scene = d / f"s{k}.nml"
            closed = "closed = .true." in groups
            fine = "&surface fine / " in groups
            groups = groups.replace("&surface closed = .true. / ", "")
            groups = groups.replace("&surface fine / ", "")
            which_profile = "c" if closed else ("f" if fine else "p")
            scene.write_text(f"&surface profile_file = '{which_profile}.txt', "
                             f"height_unit = 'mm', mu_loc = 0.6, "
                             f"closed = {'.true.' if closed else '.false.'} /\n"
                             + groups.replace("/ ", "/\n") + "\n")
            best = float("inf")
            for _ in range(repeats):
                t0 = time.perf_counter()
                r = subprocess.run([str(exe), str(scene), "-o", str(d / "o.nc")],
                                   capture_output=True, text=True, env=env)
                best = min(best, time.perf_counter() - t0)
                if r.returncode != 0:
                    raise RuntimeError(f"{name}: {r.stderr}")
            with xr.open_dataset(d / "o.nc") as ds:
                est = float(ds.attrs["estimated_seconds"])
                features = _cost_features(ds, groups)
            rows.append({"set": which, "scene": name, "estimated": est, "measured": best,
                         "ratio": est / best, "features": features})
            log(f"  {which:8s} {name:56s} estimated {est:7.3f} s, measured {best:7.3f} s, "
                f"ratio {est / best:5.2f}")
    _log_refit(log, rows)
    return rows


#: The cost model's rates (src/run/pavefric_simulate.f90) in the order of
#: _cost_features; sec_run (1 ms) is fixed, not fitted (the training runs
#: share one profile length, so it and sec_point cannot be told apart).
#: sec_point is paid once per run (reading, preprocessing, texture,
#: writing), sec_point_pass per pass (the refined geometry).
COST_RATES = ("sec_point", "sec_point_pass", "sec_step", "sec_arm", "sec_bearing_step", "sec_bearing_position",
              "sec_squeeze_step", "sec_squeeze_position", "sec_reynolds_step",
              "sec_reynolds_position")
SEC_RUN = 1.0e-3


def _cost_features(ds, groups: str) -> list[float]:
    """What each rate of the cost model multiplies in one run, from its
    output's record (the estimate's element-steps, its pad and profile): the
    terms of estimate_cost, with the passes of step_passes."""
    steps = float(ds.attrs["estimated_element_steps"])
    n_el = float(ds.attrs["pad_elements"])
    ns = ds.sizes["speed_kmh"] if "speed_kmh" in ds.sizes else ds.sizes["speed"]
    positions = steps / max(ns * n_el, 1.0)
    # step_passes: 2 where the exact integrator ran, 3 with the estimate's pass
    if "exact_integrator_ran" in ds and bool(np.any(ds["exact_integrator_ran"].values)):
        passes = 2.0
    else:
        passes = 1.0 if "error_estimate = .false." in groups else 3.0
    arms = int(np.size(ds.attrs["param_rubber_prony_times"])) if "maxwell" in groups else 0
    wet = "depth" in groups
    squeeze = "squeeze" in groups
    reynolds = "reynolds" in groups
    bearing = wet and not squeeze and not reynolds
    points = float(ds.attrs["profile_points"])
    fine = float(ds.attrs["param_numerics_substeps"]) * float(
        ds.attrs["param_numerics_elements_per_sample"])
    return [points, passes * points * fine, passes * steps, passes * steps * arms,
            passes * steps * bearing, passes * positions * bearing,
            passes * steps * squeeze, passes * positions * squeeze,
            passes * steps * reynolds, passes * positions * reynolds]


def _log_refit(log, rows) -> None:
    """The rates refitted on this run's training scenes (non-negative least
    squares on the relative error), and how they would do on its test
    scenes: how the constants in the core were obtained, regenerable."""
    from scipy.optimize import nnls

    train = [r for r in rows if r["set"] == "training"]
    a = np.array([r["features"] for r in train], dtype=float)
    b = np.array([r["measured"] - SEC_RUN for r in train])
    w = 1.0 / np.array([r["measured"] for r in train])      # relative error
    scale = np.maximum(np.abs(a).max(axis=0), 1e-300)
    x, _ = nnls(a * w[:, None] / scale, b * w)
    x = x / scale
    log("  rates refitted on these training runs (src/run/pavefric_simulate.f90 holds the "
        "ones in use): " + ", ".join(f"{n} = {v:.2e}" for n, v in zip(COST_RATES, x)))
    ratios = {s: [(SEC_RUN + float(np.dot(x, r["features"]))) / r["measured"]
                  for r in rows if r["set"] == s] for s in ("training", "test")}
    log("  with them, estimated / measured: " + "; ".join(
        f"{s} {min(v):.2f}-{max(v):.2f}" for s, v in ratios.items() if v))


def accuracy_cost(log, quick: bool = False) -> list[dict]:
    """Issue 23's accuracy target: the default scenes run to &numerics
    tolerance = 1e-6 against their default run (same speeds), with the
    scheme each allows: the exact integrator dry, the extrapolated Euler
    passes wet (the paper's bearing has no exact scheme yet)."""
    from ..core import load_scene

    tol = 1e-4 if quick else 1e-6
    speeds = [20.0] if quick else [20.0, 60.0]
    log(f"\n== The default scenes to tolerance = {tol:g} against their default run "
        f"(speeds {', '.join(f'{v:g}' for v in speeds)} km/h; target <= 10x) ==")
    rows = []
    for name, scheme in (("ctm_dry", "exact"), ("ctm_dry", "extrapolated"),
                         ("ctm_wet", "extrapolated")):
        scene = load_scene(_checkout_file(f"inputs/{name}.nml"))
        # the default run as the issue measured it: one pass, no estimate
        t_default = _best(lambda: scene.simulate(speeds_kmh=speeds, error_estimate=False), 3)[0]
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")        # a tolerance not met says so below
            (t_tol, ds) = _best(lambda: scene.simulate(speeds_kmh=speeds, tolerance=tol,
                                                       time_scheme=scheme),
                                3 if scheme == "exact" else 1)
        est = float(np.max(ds["mu_error_estimate"].values))
        row = {"scene": name, "scheme": scheme, "tolerance": tol, "default_s": t_default,
               "seconds": t_tol, "ratio": t_tol / t_default, "estimate": est,
               "met": bool(est <= tol),
               "substeps": int(np.max(ds["substeps_used"].values))}
        rows.append(row)
        log(f"  {name:8s} {scheme:13s} {t_tol:8.3f} s against {t_default:.4f} s: "
            f"{row['ratio']:8.1f}x; estimate {est:.1e}, substeps {row['substeps']}"
            + ("" if row["met"] else " (tolerance not met)"))
    return rows


#: The benchmark's sections, in the order they run (the progress counts them).
SECTIONS = ("sweep", "program", "throughput", "elements", "length", "threads", "api_threads",
            "mpi", "reading", "batch", "rubber", "estimate", "accuracy")


def run(report: str | None = None, largest: int = 10_000_000, quick: bool = False,
        quiet: bool = False, reference: str | os.PathLike | None = None) -> dict:
    """Every figure, printed as measured; with ``report``, docs/performance.md.
    ``quick``: small sizes and one repeat (minutes to seconds), to check that
    the benchmark runs, not to measure. Progress (sections done, elapsed,
    left) on stderr unless ``quiet``. ``reference``: a Python file with
    MODEL.md's simulate() (tests/reference.py) to time beside the core; the
    NumPy figures are NaN (and the report says "not measured") without it."""
    from . import bench_io
    from ..core import check_output
    from ..progress import Progress
    from .reports import PERFORMANCE_SIGNATURE, machine_description

    if report:
        # the page and its figure checked before minutes of measuring
        check_output(report, signature=PERFORMANCE_SIGNATURE)
        figure = Path(report).parent / "figures" / "performance.png"
        if figure.parent.is_dir():            # (else made later: nothing there to lose)
            check_output(figure, replaces="png")
    lines: list[str] = []
    progress = Progress("bench", len(SECTIONS), "sections", quiet=quiet)

    def log(text=""):
        progress.clear()
        print(text, flush=True)
        lines.append(text)

    def section(name, value):
        progress.advance(what=name)
        return value

    log(f"pavefric benchmark on {machine_description()}")
    ref = _reference(reference)
    import tempfile

    with tempfile.TemporaryDirectory() as tmp:
        plain = PlainLoop(Path(tmp))
        results = {
            "sweep": section("sweep", sweep(ref, plain, log, repeats=1 if quick else 2,
                                            tile=4 if quick else 64,
                                            rounds=1 if quick else 5)),
            "program": section("program", whole_program(
                plain, log, points=40_000 if quick else 400_000, repeats=1 if quick else 3)),
        }
    if quick:
        largest = min(largest, 100_000)
    tile = 4 if quick else 64
    # one at a time, in this order (a dict display evaluates in order)
    results |= {
        "throughput": section("throughput", throughput(ref, log, tile=tile)),
        "elements": section("elements", scaling_elements(ref, log,
                                                         points=4096 if quick else 8192)),
        "length": section("length", scaling_length(log, largest)),
        "threads": section("threads", threads(log, tile=tile)),
        "api_threads": section("api_threads", api_threads(
            log, tile=4 if quick else 32, repeats=1 if quick else 25)),
        "mpi": section("mpi", mpi_batch(log)),
        "reading": section("reading", bench_io.reading(log, largest,
                                                       small=min(largest, 1_000_000))),
        "batch": section("batch", bench_mpi.run(log, quick=quick)),
        "rubber": section("rubber", rubber_report.cost(log, repeats=1 if quick else 7)),
        "estimate": section("estimate", estimate_accuracy(
            log, points=8192 if quick else 65_536, repeats=1 if quick else 3)),
        "accuracy": section("accuracy", accuracy_cost(log, quick=quick)),
    }
    progress.close()
    assert list(results) == list(SECTIONS)
    if report:
        from .reports import performance_report

        performance_report(Path(report), results, lines)
        log(f"\nwrote {report}")
    return results
