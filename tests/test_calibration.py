"""Reference surfaces, calibration and the validation report."""
import csv
import subprocess
import sys

import numpy as np
import pytest

import pavefric
from conftest import ROOT, TABLE

SURFACES = ROOT / "inputs" / "surfaces"


@pytest.fixture(scope="module")
def paper():
    from pavefric.reference_surfaces import paper_table

    return paper_table(TABLE)


def test_reference_surfaces_reproduce_v13_and_rank(paper):
    from pavefric.reference_surfaces import NAMES

    mpd = {}
    for name in NAMES:
        scene = pavefric.load_scene(SURFACES / f"{name}.nml")
        v13 = paper["model_dry"][name]
        ds = scene.simulate(speeds_kmh=sorted(v13), depth=0.0)
        np.testing.assert_allclose(ds["mu"].values, [v13[s] for s in sorted(v13)], atol=0.02)
        assert scene.parameters["mu_loc"] == paper["srt"][name]
        assert scene.heights.size == 1024 and scene.dx == 0.87e-3 and scene.closed
        mpd[name] = pavefric.texture(scene.heights, scene.dx)["mpd"]
    # the paper's ranking: polished and sawn granite lowest, VTAC highest
    assert max(mpd["GSP"], mpd["GSS"]) < min(mpd[n] for n in ("GSSB", "RSBA", "MCA", "VTAC"))
    assert mpd["VTAC"] == max(mpd.values())


def test_reference_surfaces_regenerate_identically(tmp_path, paper):
    from pavefric.reference_surfaces import write_surfaces

    write_surfaces(tmp_path, TABLE, log=lambda *a: None)
    for name in ("GSP", "VTAC"):
        assert (tmp_path / f"{name}.txt").read_text() == (SURFACES / f"{name}.txt").read_text()


def test_calibration_recovers_known_parameters(tmp_path):
    """Data made by the model with alpha = 3 and C = 2000 is fitted back from
    alpha = 1, C = 100 to within 1 %."""
    from pavefric import calibrate

    truth = {"alpha": 3.0, "viscosity": 2000.0}
    rows = []
    for name in ("GSS", "GSSB", "MCA"):
        scene = pavefric.load_scene(SURFACES / f"{name}.nml")
        ds = scene.simulate(speeds_kmh=[10, 20, 40, 60, 80], **truth)
        rows += [{"surface": name, "speed_kmh": s, "mu": m}
                 for s, m in zip([10, 20, 40, 60, 80], ds["mu"].values)]
    data = tmp_path / "data.csv"
    with open(data, "w", newline="") as fh:
        w = csv.DictWriter(fh, ["surface", "speed_kmh", "mu"])
        w.writeheader()
        w.writerows(rows)
    measured = calibrate.read_measurements(data)
    fit = calibrate.fit(measured, SURFACES, ["alpha", "viscosity"],
                        start={"alpha": 1.0, "viscosity": 100.0})
    assert fit.converged
    for k, v in truth.items():
        assert fit.values[k] == pytest.approx(v, rel=0.01), (k, fit.values)
    assert fit.rmse < 1e-6
    assert fit.runs > 0
    # the command line prints the same fit
    r = subprocess.run([sys.executable, "-m", "pavefric", "calibrate", str(data), "--scenes",
                        str(SURFACES), "--fit", "alpha", "viscosity", "--start", "alpha=1",
                        "viscosity=100", "-o", str(tmp_path / "fit.json")],
                       capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    assert "model runs" in r.stdout and "alpha" in r.stdout
    import json
    got = json.loads((tmp_path / "fit.json").read_text())
    assert got["parameters"]["alpha"] == pytest.approx(3.0, rel=0.01)


def test_validate_reduced(tmp_path, paper):
    report = tmp_path / "docs" / "validation.md"
    r = subprocess.run([sys.executable, "-m", "pavefric", "validate", "--quick",
                        "--table", str(TABLE), "--report", str(report),
                        "--outdir", str(tmp_path / "out")],
                       capture_output=True, text=True, timeout=900, cwd=ROOT)
    assert r.returncode == 0, r.stderr
    text = report.read_text()
    assert "## Statistics" in text and "| all speeds | 18 |" in text
    assert "wet at 20 km/h |" in text and "bearing acts at GSP" in text
    for fig in ("validation_fig10.png", "validation_fig11.png", "validation_fig12.png"):
        assert (tmp_path / "docs" / "figures" / fig).stat().st_size > 10_000
    with open(tmp_path / "out" / "comparison.csv") as fh:
        rows = list(csv.DictReader(fh))
    assert len(rows) == 18
    assert set(rows[0]) == {"surface", "speed_kmh", "measured", "model", "used_in_fit"}
    assert all((r["used_in_fit"] == "true") == (r["speed_kmh"] == "20") for r in rows)
    assert all(np.isfinite(float(r["model"])) for r in rows)
    from pavefric.validation import CALIBRATED_ALPHA
    import json
    res = json.loads((tmp_path / "out" / "validation.json").read_text())
    # the documented default is the fitted value (to its 3 digits)
    assert res["alpha"] == pytest.approx(CALIBRATED_ALPHA, rel=0.01)
    assert pavefric.defaults()["alpha"] == CALIBRATED_ALPHA
