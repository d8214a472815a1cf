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
            label += " (wet: paper's bearing)"
        elif "squeeze_film" in effects:
            label += " (wet: drainage model)"
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


def plot_profile(profile, output: str | os.PathLike, title: str | None = None,
                 xlim: tuple | None = None) -> str:
    """Raw points (dropouts as gaps) against the cleaned profile, in mm."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    fig, (a, b) = plt.subplots(2, 1, figsize=(10, 5.6), dpi=110)
    a.plot(profile.raw_x * 1e3, profile.raw_heights * 1e3, lw=0.4, color="0.4")
    r = profile.report
    a.set_title(title or f"{os.path.basename(profile.path)}: as read ({r['format']}, "
                f"{r['points_read']} points, {r['dropouts']} dropouts)", fontsize=9)
    a.set_ylabel("height (mm)")
    x = np.arange(profile.heights.size) * profile.dx * 1e3
    b.plot(x, profile.heights * 1e3, lw=0.5, color="C0")
    if profile.spike.any():
        b.plot(x[profile.spike], profile.heights[profile.spike] * 1e3, "r.", ms=2,
               label="spikes replaced")
        b.legend(fontsize=7)
    b.set_title(f"cleaned: {r['trimmed_start']} + {r['trimmed_end']} points trimmed "
                f"(plates), {r['spikes']} spike points, spacing {profile.dx * 1e3:.4g} mm"
                + (", low-pass filtered" if r["filtered"] else ""), fontsize=9)
    b.set_xlabel("distance (mm)")
    b.set_ylabel("height (mm)")
    if xlim:
        a.set_xlim(*xlim)
        b.set_xlim(*xlim)
    for ax in (a, b):
        ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(output)
    plt.close(fig)
    return str(output)
