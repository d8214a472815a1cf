"""The accuracy-cost study (a reduced run)."""
import subprocess
import sys

import numpy as np

from conftest import ROOT


def test_accuracy_study_reduced(tmp_path):
    from pavefric.studies import accuracy

    knobs = {"substeps": [1, 2, 4, 8], "position_stride": [8, 4, 2, 1],
             "wet_tolerance": [1e-3, 1e-8, 1e-14]}
    table = accuracy.study(ROOT / "inputs" / "ctm_wet.nml", speeds_kmh=[20, 60], knobs=knobs,
                           repeats=1)
    for knob in knobs:
        conv = table["convergence"].values[table["knob"].values == knob]
        assert conv[-1] == 0.0 and conv[0] > 0
        if knob != "position_stride":   # stride subsamples too: not monotone (docs)
            assert np.all(np.diff(conv) < 0), (knob, conv)   # refining buys accuracy
    sub = table["time_s"].values[table["knob"].values == "substeps"]
    assert np.all(np.isfinite(sub)) and np.all(sub > 0)
    steps = table["element_steps"].values[table["knob"].values == "substeps"]
    assert list(steps[1:] / steps[:-1]) == [2, 2, 2]
    accuracy.to_csv(table, tmp_path / "a.csv")
    header = (tmp_path / "a.csv").read_text().splitlines()[0]
    assert header.startswith("scene,knob,value,error,convergence,time_s,element_steps,mu_20kmh")


def test_accuracy_command_writes_report(tmp_path):
    report = tmp_path / "docs" / "accuracy.md"
    r = subprocess.run([sys.executable, "-m", "pavefric", "accuracy",
                        str(ROOT / "inputs" / "ctm_dry.nml"), "--speeds", "40",
                        "--repeats", "1", "--outdir", str(tmp_path / "out"),
                        "--report", str(report)], capture_output=True, text=True, timeout=600,
                       cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    text = report.read_text()
    assert "## Recommended settings" in text and "quick look" in text
    # run outside the repository's root, the pad's section says where its
    # tables come from instead of running its study (minutes; its first
    # table is checked against the docs in test_error_estimate.py)
    assert "run the command from the repository's root for the table" in text
    assert (tmp_path / "docs" / "figures" / "accuracy.png").stat().st_size > 10_000
    assert (tmp_path / "out" / "accuracy_ctm_dry.nc").exists()


def test_accuracy_report_measures_each_wet_model(tmp_path, monkeypatch):
    """--wet-models: the order study and the default run's estimate of every
    wet scene under each named wet model too (issue 23: error against time
    for dry and each wet model), beside the scene's own; the scene's own
    model is not run twice, and the command line recorded in the report
    names the option (a reduced run: fewer settings, one speed)."""
    from pavefric.studies import accuracy
    from pavefric.studies.reports import accuracy_report

    monkeypatch.setattr(accuracy, "KNOBS", {"substeps": [1, 2, 4]})
    monkeypatch.setattr(accuracy, "TOLERANCES", [1e-2])
    monkeypatch.setattr(accuracy, "ORDER_SUBSTEPS", [1, 2, 4, 8, 16, 32])
    monkeypatch.chdir(tmp_path)            # no pad-resolution study (minutes)
    report = tmp_path / "docs" / "accuracy.md"
    accuracy_report([str(ROOT / "inputs" / "ctm_wet.nml")], str(tmp_path / "out"),
                    speeds=[40.0], repeats=1, report=str(report),
                    wet_models=("kane2017", "reynolds"), quiet=True)
    text = report.read_text()
    assert "--wet-models kane2017 reynolds --report" in text
    rows = [line for line in text.splitlines() if line.startswith("| ctm_wet")]
    # the order table and the default run's table: the scene's own model
    # (kane2017) once each, the Reynolds film once each
    assert sum(r.startswith("| ctm_wet | kane2017 |") for r in rows) == 2, rows
    assert sum(r.startswith("| ctm_wet_reynolds | reynolds |") for r in rows) == 2, rows
    assert not any(r.startswith("| ctm_wet_kane2017") for r in rows)
    order_rows = [r for r in rows if r.count("|") == 10]
    assert len(order_rows) == 2
    for r in order_rows:
        cells = [c.strip() for c in r.strip("|").split("|")]
        assert float(cells[7]) > 0                     # one pass's time (s)
        if cells[1] == "reynolds":                      # no exact integrator under that film
            assert cells[8].startswith("(backward Euler")
        else:                                           # under the paper's: its step's error
            error, cost = cells[8].split(", ")
            assert 0 < float(error) < 1e-3 and cost.endswith("x")
    assert "- `kane2017` (1 scene): Euler order" in text
    assert "- `reynolds` (1 scene): Euler order" in text
    assert (tmp_path / "docs" / "figures" / "accuracy_order.png").stat().st_size > 10_000


def test_accuracy_command_refuses_an_unknown_wet_model(tmp_path):
    r = subprocess.run([sys.executable, "-m", "pavefric", "accuracy",
                        str(ROOT / "inputs" / "ctm_wet.nml"), "--wet-models", "mud"],
                       capture_output=True, text=True, timeout=120, cwd=tmp_path)
    assert r.returncode == 2
    assert "--wet-models" in r.stderr and "'mud'" in r.stderr
    assert not (tmp_path / "outputs").exists()
