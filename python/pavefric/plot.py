"""Plots of pavefric results (matplotlib, PNG)."""
from __future__ import annotations

import os
from pathlib import Path
from typing import Iterable, Sequence

#: What every figure pavefric draws carries in its PNG text chunk
#: ``Software`` (then a space and the version): an existing file at a
#: figure's path is replaced only if its ``Software`` begins so (the core's
#: rule, ``check_output(..., replaces="png")``).
PNG_SOFTWARE = "pavefric"


def save_figure(fig, output: str | os.PathLike, inputs: Iterable = ()) -> str:
    """Write a matplotlib figure as the PNG ``output``, whole or not at all,
    by the rule every pavefric writer follows (``pavefric.core.check_output``):
    ``output`` must end in ``.png``, be missing or a regular file, not be one
    of ``inputs`` (the files the figure was drawn from, links seen through),
    and an existing non-empty file there is replaced only if it is a figure
    pavefric drew (its PNG ``Software`` text begins with 'pavefric'; a
    user's own figure, scene or data named by mistake is refused and left
    byte for byte). Written through a temporary and a rename. Returns the
    path."""
    from . import __version__
    from .core import atomic_output

    with atomic_output(_png_path(output), inputs, replaces="png") as tmp:
        fig.savefig(tmp, format="png", metadata={"Software": f"{PNG_SOFTWARE} {__version__}"})
    return os.fspath(output)


def _checked(output, inputs: Iterable = (), writable: bool = True) -> None:
    """save_figure's checks before a figure is drawn (so that a refused path
    costs no drawing and leaves nothing behind). ``writable``: also that its
    directory exists and may be written (False where the caller makes it)."""
    from .core import check_output

    check_output(_png_path(output), inputs, replaces="png", writable=writable)


def _png_path(output) -> Path:
    """``output`` as a Path, refused unless it ends in .png."""
    from .core import PavefricError

    path = Path(output)
    if path.suffix.lower() != ".png":
        raise PavefricError(f"'{path}': pavefric draws its figures as PNG; give a path "
                            "ending in .png")
    return path


def is_batch(ds) -> bool:
    """Whether a dataset is a batch output (a ``profile`` dimension)."""
    return "profile" in ds.dims


def water_label(ds) -> str:
    """What water a single-scene output ran with, from its ``effects``
    attribute: "dry", or "wet: " and the wet model that ran."""
    effects = ds.attrs.get("effects", "").split(",")
    for effect, name in (("hydrodynamic_bearing", "paper's bearing"),
                         ("squeeze_film", "drainage model"), ("reynolds_film", "Reynolds film")):
        if effect in effects:
            return f"wet: {name}"
    return "dry"


def plot_mu_speed(datasets: Sequence, output: str | os.PathLike,
                  labels: Sequence[str] | None = None, title: str | None = None,
                  inputs: Iterable = ()) -> str:
    """Friction coefficient against sliding speed, one curve per dataset.

    A batch output (one file) is drawn by ``plot_batch`` instead: friction
    along the road.

    Parameters
    ----------
    datasets : sequence of xarray.Dataset or path-like
        Outputs of ``simulate`` or ``run``, or their files.
    output : str or os.PathLike
        The PNG file to write.
    labels : sequence of str, optional
        One label per dataset (default: from the files or the datasets).
    title : str, optional
        The figure's title.
    inputs : iterable of path-like, optional
        Further files the figure comes from (a run's scene), never
        overwritten; the datasets given as files are inputs too.

    Returns
    -------
    str
        The PNG path (``save_figure``'s rule: a file there is replaced only
        if pavefric drew it).
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from .core import PavefricError, open_dataset

    inputs = [*inputs, *(ds for ds in datasets if not hasattr(ds, "variables"))]
    _checked(output, inputs)
    opened = []
    for i, ds in enumerate(datasets):
        if not hasattr(ds, "variables"):
            opened.append((os.path.splitext(os.path.basename(str(ds)))[0], open_dataset(ds)))
        else:
            opened.append((f"scene {i + 1}", ds))
    if any(is_batch(ds) for _, ds in opened):
        if len(opened) != 1:
            raise PavefricError("plot: a batch output is plotted on its own (one file)")
        return plot_batch(opened[0][1], output, title=title, inputs=inputs)
    fig, ax = plt.subplots(figsize=(6.4, 4.4), dpi=120)
    for i, (label_default, ds) in enumerate(opened):
        label = labels[i] if labels else label_default
        label += f" ({water_label(ds)})"
        ax.plot(ds["speed_kmh"].values, ds["mu"].values, marker="o", ms=3, label=label)
    ax.set_xlabel("sliding speed (km/h)")
    ax.set_ylabel("friction coefficient $\\mu$")
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)
    ax.legend(loc="lower left")
    if title:
        ax.set_title(title)
    fig.tight_layout()
    try:
        return save_figure(fig, output, inputs)
    finally:
        plt.close(fig)


def batch_curves(ds) -> tuple:
    """What :func:`plot_batch` draws: the position of each profile along the
    road (chainage in m when the profile list gives it, else the profile's
    number), its label, and mu per (water depth, speed) as arrays over the
    profiles (NaN where a profile failed)."""
    import numpy as np

    if "chainage" in ds.variables:
        x, xlabel = np.asarray(ds["chainage"].values, dtype=float), "chainage (m)"
    else:
        x, xlabel = np.arange(1, ds.sizes["profile"] + 1, dtype=float), "profile number"
    mu = ds["mu"].transpose("profile", "water_depth", "speed_kmh").values
    curves = {}
    for j, depth in enumerate(ds["water_depth"].values):
        for k, speed in enumerate(ds["speed_kmh"].values):
            curves[(float(depth), float(speed))] = np.asarray(mu[:, j, k], dtype=float)
    return x, xlabel, curves


def plot_batch(ds, output: str | os.PathLike, title: str | None = None,
               inputs: Iterable = ()) -> str:
    """A batch output (a path or dataset): friction along the road, one panel
    per water depth and one line per speed, failed profiles as gaps (and
    marked), with the texture depth (MPD) below. Returns the PNG path
    (``save_figure``'s rule; ``inputs``: further files never overwritten,
    the batch output's file among them when ``ds`` is a path)."""
    inputs = [*inputs, *(() if hasattr(ds, "variables") else (ds,))]
    _checked(output, inputs)
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    from .core import open_dataset

    if not hasattr(ds, "variables"):
        ds = open_dataset(ds)
    x, xlabel, curves = batch_curves(ds)
    depths = list(ds["water_depth"].values)
    speeds = list(ds["speed_kmh"].values)
    order = np.argsort(x, kind="stable")
    fig, axes = plt.subplots(len(depths) + 1, 1, figsize=(9, 2.2 * (len(depths) + 1) + 0.6),
                             dpi=110, sharex=True, squeeze=False)
    axes = axes[:, 0]
    failed = np.asarray(ds["status"].values) == 2
    cmap = plt.get_cmap("viridis")
    for j, depth in enumerate(depths):
        ax = axes[j]
        for k, speed in enumerate(speeds):
            colour = cmap(k / max(len(speeds) - 1, 1))
            ax.plot(x[order], curves[(float(depth), float(speed))][order], lw=0.9,
                    color=colour, label=f"{speed:g} km/h")
        if failed.any():
            ax.plot(x[failed], np.zeros(failed.sum()), "rx", ms=5, label="failed profile")
        ax.set_ylabel("$\\mu$")
        ax.set_title("dry" if depth == 0 else f"water depth {depth * 1e3:g} mm", fontsize=9)
        ax.set_ylim(bottom=0)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=7, ncol=min(len(speeds) + 1, 6), loc="lower left")
    mpd = np.asarray(ds["mpd"].values, dtype=float) * 1e3
    axes[-1].plot(x[order], mpd[order], color="0.3", lw=0.8)
    axes[-1].set_ylabel("MPD (mm)")
    axes[-1].set_xlabel(xlabel)
    axes[-1].grid(alpha=0.3)
    fig.suptitle(title or ds.attrs.get("title", "pavefric batch"), fontsize=10)
    fig.tight_layout()
    try:
        return save_figure(fig, output, inputs)
    finally:
        plt.close(fig)


def plot_profile(profile, output: str | os.PathLike, title: str | None = None,
                 xlim: tuple | None = None) -> str:
    """Raw points (dropouts as gaps) against the cleaned profile, in mm.

    Parameters
    ----------
    profile : Profile
        A profile from ``read_profile``.
    output : str or os.PathLike
        The PNG file to write.
    title : str, optional
        The upper panel's title (default: the file's name, format, points and
        dropouts).
    xlim : tuple, optional
        The distance range shown (mm).

    Returns
    -------
    str
        The PNG path (``save_figure``'s rule: a file there is replaced only
        if pavefric drew it; never the profile's own file).
    """
    inputs = [getattr(profile, "path", None)]
    _checked(output, inputs)
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
    try:
        return save_figure(fig, output, inputs)
    finally:
        plt.close(fig)
