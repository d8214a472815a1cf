"""docs/inputs.md and docs/outputs.md are generated from the core's declarations
and kept fresh."""
import pavefric
from conftest import ROOT
from pavefric.studies.docs import inputs_markdown, outputs_markdown


def test_inputs_reference_is_fresh():
    committed = (ROOT / "docs" / "inputs.md").read_text(encoding="utf-8")
    assert committed == inputs_markdown(), (
        "docs/inputs.md is stale: run `python -m pavefric docs --inputs docs/inputs.md`")


def test_every_declared_variable_is_documented():
    text = inputs_markdown()
    for p in pavefric.parameters():
        assert f"| `{p.name}` |" in text
        assert f"## `&{p.group}`" in text


def test_python_keywords_and_defaults_come_from_the_declarations():
    from pavefric.core import PARAMETERS

    model = {p.keyword: p for p in pavefric.parameters() if p.scope == "model"}
    assert set(PARAMETERS) == set(model)
    assert pavefric.defaults() == {k: p.default for k, p in model.items()}
    assert pavefric.defaults()["stiffness"] == 1.4e8
    assert PARAMETERS["water_viscosity"] == ("water", "viscosity")


def test_outputs_reference_is_fresh():
    committed = (ROOT / "docs" / "outputs.md").read_text(encoding="utf-8")
    assert committed == outputs_markdown(), (
        "docs/outputs.md is stale: run `python -m pavefric docs --outputs docs/outputs.md`")


def test_every_written_variable_is_documented(tmp_path):
    """Every variable of a run with every optional output (series, the
    drainage film, a tolerance) is in docs/outputs.md."""
    import numpy as np

    text = outputs_markdown()
    z = np.sin(np.arange(512) * 0.3) * 0.5e-3
    ds = pavefric.simulate(z, 0.87e-3, [20.0], depth=1e-3, wet_model="squeeze", series=True,
                           tolerance=3e-2)
    for name in ds.variables:
        assert f"`{name}`" in text, name


def test_docs_index_lists_every_file():
    """docs/index.md links every page and figure of docs/ (one line each),
    and every link in it leads to a file that is there."""
    import re

    docs = ROOT / "docs"
    index = (docs / "index.md").read_text(encoding="utf-8")
    links = re.findall(r"\]\(([^)#\s]+)\)", index)
    for target in links:
        assert (docs / target).is_file(), f"docs/index.md links {target}, which is not there"
    files = sorted(str(p.relative_to(docs)) for p in docs.rglob("*")
                   if p.is_file() and p.name != "index.md")
    assert any(f.endswith(".md") for f in files) and any(f.startswith("figures/") for f in files)
    lines = index.splitlines()
    for name in files:
        hits = [line for line in lines if f"]({name})" in line]
        assert len(hits) == 1, f"docs/{name} is linked from {len(hits)} lines of docs/index.md"
