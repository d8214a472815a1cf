"""Plots of pavefric results (matplotlib, PNG)."""
from __future__ import annotations

import os
from typing import Sequence


def plot_mu_speed(datasets: Sequence, output: str | os.PathLike,
                  labels: Sequence[str] | None = None, title: str | None = None) -> str:
    """Friction coefficient against sliding speed, one curve per dataset (or path).

    Positions where the pad hydroplaned are marked; returns the PNG path.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from .core import open_dataset

    fig, ax = plt.subplots(figsize=(6.4, 4.4), dpi=120)
    for i, ds in enumerate(datasets):
        if not hasattr(ds, "variables"):
            label_default = os.path.splitext(os.path.basename(str(ds)))[0]
            ds = open_dataset(ds)
        else:
            label_default = f"scene {i + 1}"
        label = labels[i] if labels else label_default
        effects = ds.attrs.get("effects", "")
        if "hydrodynamic_bearing" in effects:
            label += " (wet)"
        else:
            label += " (dry)"
        ax.plot(ds["speed_kmh"].values, ds["mu"].values, marker="o", ms=3, label=label)
    ax.set_xlabel("sliding speed (km/h)")
    ax.set_ylabel("friction coefficient $\\mu$")
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)
    ax.legend(loc="lower left")
    if title:
        ax.set_title(title)
    fig.tight_layout()
    fig.savefig(output)
    plt.close(fig)
    return str(output)
