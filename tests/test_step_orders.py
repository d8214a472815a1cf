"""Backward Euler's observed order on the paper's wet scene (docs/numerics.md,
"Known gaps": the tolerance's Richardson value assumes first order), from
python -m pavefric.studies.step_orders."""
import re

import numpy as np

import pavefric
from conftest import ROOT
from pavefric.studies.step_orders import ratios, sequence


def test_the_wet_scene_falls_at_second_order_and_the_doc_quotes_it():
    scene = pavefric.load_scene(ROOT / "inputs" / "ctm_wet.nml")
    rows = sequence(scene, [20.0], 7)                   # substeps 1 .. 64
    assert [s for s, _ in rows] == [1, 2, 4, 8, 16, 32, 64]
    table = ratios(rows)
    orders = np.array([o[0] for _, _, _, o in table])   # at 4 .. 64
    assert np.all((orders > 1.7) & (orders < 2.3)), orders
    # the first-order band of simulate_to_tolerance (ratio 1.5 to 3) rejects them
    assert all(not (1.5 <= r[0] <= 3.0) for _, _, r, _ in table)
    changes = [f"{rows[k][1][0] - rows[k - 1][1][0]:.2e}" for k in range(1, len(rows))]
    text = " ".join((ROOT / "docs" / "numerics.md").read_text().split())
    quoted = re.search(r"at 20 km/h the changes are (.*?) from 2 to 512", text).group(1)
    assert quoted.split(", ")[:6] == changes, (quoted, changes)
    quoted_ratios = re.search(r"to 512 substeps, ratios (.*?) \(`python -m "
                              r"pavefric.studies.step_orders`", text).group(1)
    assert quoted_ratios.split(", ")[:5] == [f"{r[0]:.2f}" for _, _, r, _ in table]


def test_ratios_of_a_known_sequence():
    # mu = 1 + h**2 (h = 1 / substeps): ratio 4, order 2; a sign change: no order
    rows = [(s, np.array([1.0 + (1.0 / s) ** 2, 1.0 + (-1) ** s / s])) for s in (1, 2, 4, 8)]
    table = ratios(rows)
    np.testing.assert_allclose([r[0] for _, _, r, _ in table], [4.0, 4.0])
    np.testing.assert_allclose([o[0] for _, _, _, o in table], [2.0, 2.0])
    assert np.isnan(table[0][3][1]) and not np.isnan(table[0][3][0])
