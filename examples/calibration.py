"""A calibration: fit the bearing coefficient alpha to wet friction measured
on two surfaces (docs/calibration.md).

The "measurements" here are made by the model itself at a known alpha, with
a seeded scatter of 0.01 (about a DFT's repeatability) added, so the fit can
be checked: its confidence interval must hold the alpha they were made with. With your own DFT data, write the CSV (surface,
speed_kmh, mu) and one scene per surface, and run the same fit (or
`python -m pavefric calibrate data.csv --scenes DIR --fit alpha`).

    python calibration.py [DIRECTORY]     # default: ./calibration-example
"""
import sys
from pathlib import Path

import numpy as np

import pavefric
from pavefric import calibrate
from pavefric.surfaces import spectral_profile, write_profile

here = Path(sys.argv[1] if len(sys.argv) > 1 else "calibration-example")
scenes = here / "scenes"
scenes.mkdir(parents=True, exist_ok=True)
TRUE_ALPHA = 8.0
speeds = [20, 40, 60]

# two surfaces: a fine and a coarse texture, each a scene with 1 mm of water
for name, rms_mm, seed in (("fine", 0.25, 1), ("coarse", 0.6, 2)):
    z = spectral_profile(1024, 0.87e-3, rms=rms_mm * 1e-3, seed=seed)
    write_profile(str(scenes / f"{name}.txt"), z, f"{name}: rms {rms_mm} mm")
    (scenes / f"{name}.nml").write_text(f"""\
&surface profile_file = '{name}.txt', height_unit = 'mm', dx = 0.87e-3, mu_loc = 0.6 /
&water depth = 1.0e-3, alpha = 1.0 /
&operation speeds_kmh = {', '.join(map(str, speeds))} /
""")

# the "measurements": the model's friction at alpha = TRUE_ALPHA, with scatter
rng = np.random.default_rng(5)
with open(here / "measured.csv", "w", encoding="utf-8") as fh:
    fh.write("surface,speed_kmh,mu\n")
    for name in ("fine", "coarse"):
        scene = pavefric.load_scene(scenes / f"{name}.nml")
        ds = scene.simulate(speeds_kmh=speeds, alpha=TRUE_ALPHA, series=False)
        for speed, mu in zip(speeds, ds["mu"].values):
            fh.write(f"{name},{speed},{mu + rng.normal(0.0, 0.01):.4f}\n")

rows = calibrate.read_measurements(here / "measured.csv")
fit = calibrate.fit(rows, scenes, ["alpha"], start={"alpha": 1.0})
print(calibrate.report_text(fit))
alpha = fit.values["alpha"]
low, high = fit.interval["alpha"]
print(f"alpha = {alpha:.4g} (95 % interval {low:.4g} to {high:.4g}); made with {TRUE_ALPHA:g}")
if not (fit.converged and low <= TRUE_ALPHA <= high):
    sys.exit(f"the fit's interval does not hold alpha = {TRUE_ALPHA:g}")
