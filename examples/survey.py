"""A survey run and its post-processing with xarray.

Writes a few short generated road segments (pavefric.surfaces.road_profiles),
a batch scene over them at two water depths and three speeds, runs the
pavefric program on it (the same command as on a cluster, where it would be
`mpirun -n P pavefric survey.nml`), opens the batch file with
pavefric.open_dataset and summarises it: friction along the road, the
segment with the least wet friction at 60 km/h, and a CSV table.

    python survey.py [DIRECTORY]        # default: ./survey-example
"""
import shutil
import subprocess
import sys
from pathlib import Path

import pavefric
from pavefric.surfaces import road_profiles

here = Path(sys.argv[1] if len(sys.argv) > 1 else "survey-example")
road_profiles(str(here / "profiles"), n=12, points=512)       # 12 segments, 0.45 m each
scene = here / "survey.nml"
scene.write_text("""\
&batch profiles = 'profiles/*.txt', depths = 0.0, 1.0e-3 /
&surface height_unit = 'mm', dx = 0.87e-3, closed = .false., mu_loc = 0.6 /
&operation speeds_kmh = 20, 60, 100 /
&output file = 'survey.nc' /
""")

# the program installed with pavefric (on PATH in an activated environment)
program = shutil.which("pavefric") or str(Path(sys.executable).parent / "pavefric")
run = subprocess.run([program, "-q", scene.name], cwd=here, capture_output=True, text=True)
if run.returncode != 0:
    sys.exit(f"pavefric failed ({run.returncode}): {run.stderr}")
print(run.stdout.strip())                                     # the batch's summary line

with pavefric.open_dataset(here / "survey.nc") as ds:
    mu = ds["mu"]                                   # (profile, water_depth, speed_kmh)
    print(f"{ds.sizes['profile']} profiles, water depths {ds['water_depth'].values.tolist()} m, "
          f"speeds {ds['speed_kmh'].values.tolist()} km/h")
    mean = mu.mean("profile")
    for depth in ds["water_depth"].values:
        row = ", ".join(f"{s:g} km/h {m:.3f}" for s, m in
                        zip(ds["speed_kmh"].values, mean.sel(water_depth=depth).values))
        print(f"mean mu, {depth * 1e3:g} mm of water: {row}")
    wet60 = mu.sel(water_depth=1.0e-3, speed_kmh=60.0)
    worst = int(wet60.argmin("profile"))
    print(f"least wet friction at 60 km/h: {str(ds['profile'].values[worst])} "
          f"(mu = {float(wet60[worst]):.3f}; road mean {float(wet60.mean()):.3f})")
    # a flat table for a spreadsheet: one row per profile, depth and speed
    table = mu.to_dataframe().reset_index()[["profile", "water_depth", "speed_kmh", "mu"]]
    table.to_csv(here / "survey_mu.csv", index=False)
    print(f"wrote {here / 'survey_mu.csv'} ({len(table)} rows)")
