"""Rubber compounds for the generalised Maxwell element (``&rubber model =
'maxwell'``, docs/rubber.md): dynamic mechanical (DMA) data, their WLF
master curve, a Prony series fitted by non-negative least squares, and the
``&rubber`` group that carries it into a scene.

``python -m pavefric prony DATA.csv -o compound.nml`` runs the whole chain.

- **Data**: a CSV file with a header naming the columns ``frequency_hz`` (or
  ``omega_rad_s``), ``storage_pa`` and ``loss_pa`` (or ``storage_mpa``,
  ``loss_mpa``), and optionally ``temperature_c`` (several temperatures of a
  frequency sweep); ``#`` starts a comment line.
- **Master curve**: a point at temperature T and angular frequency w lies on
  the master curve at the reference temperature at w a_T, with the WLF shift
  ``log10 a_T = -C1 (T - Tref) / (C2 + T - Tref)`` (the core shifts the
  relaxation times by the same a_T, so a fitted series used at T reproduces
  the data at T). C1 and C2 are given, or fitted (``--fit-wlf``) by
  minimising the fit's residual.
- **Prony series**: ``E*(w) = E_inf + sum_k E_k i w tau_k / (1 + i w tau_k)``
  with relaxation times log-spaced over the data's reduced frequencies (a
  decade beyond them on either side); E_inf and the E_k are the non-negative
  least-squares solution (``scipy.optimize.nnls``) of the storage and loss
  moduli, each point weighted by the inverse of its measured value (relative
  errors: the moduli span decades). Arms whose E_k is zero (or below 1e-9 of
  the largest modulus, rounding residue) are dropped.
- **Per unit length**: the core's element works with stiffness per unit
  length of pad (N m-3, like the paper's K): a modulus (Pa) becomes one by
  dividing it by a length. A thin layer of thickness h pressed between
  plates has p = E u / h, so K = E / h with h the rubber thickness
  (``--thickness``, default the DFT pad's 6 mm). Shear data (G', G'') are
  converted with E = 3 G (incompressible rubber) by ``--modulus shear``.
"""
from __future__ import annotations

import csv
import math
import os
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

#: Williams, Landel & Ferry (1955): C1 = 8.86, C2 = 101.6 K for a reference
#: temperature about 50 K above the glass transition; the core's defaults.
WLF_C1, WLF_C2 = 8.86, 101.6
T_REF = 20.0
#: The DFT pad's rubber thickness (m), &pad thickness's default.
THICKNESS = 0.006

#: The representative tread compound of inputs/data/tread_compound_dma.csv:
#: a Havriliak-Negami glass transition between a rubbery modulus E_r and a
#: glassy modulus E_g, E*(w) = E_g - (E_g - E_r) / (1 + (i w tau)^alpha)^beta
#: at the reference temperature, shifted by the WLF constants above. Not a
#: measurement: E_r = 3 MPa (a passenger-car tread's low-frequency Young's
#: modulus), E_g = 1.5 GPa (glassy elastomers: 1-3 GPa), beta = 0.5, and tau,
#: alpha set so that tan delta at 10 Hz is 0.50 at 0 C and 0.12 at 60 C, typical
#: values of the wet-grip and rolling-resistance indicators of passenger-car
#: tread compounds.
REPRESENTATIVE = dict(e_rubbery=3.0e6, e_glassy=1.5e9, tau=8.6e-9, alpha=0.332, beta=0.5)
REPRESENTATIVE_TEMPERATURES = (-20.0, -10.0, 0.0, 10.0, 20.0, 30.0, 40.0, 50.0, 60.0)


def wlf_log10_shift(temperature, reference: float = T_REF, c1: float = WLF_C1,
                    c2: float = WLF_C2):
    """log10 a_T = -C1 (T - Tref) / (C2 + T - Tref), computed by the core
    (the equation the Maxwell rubber runs with, src/physics/pavefric_maxwell.f90):
    for shifting data onto the master curve. ValueError where the equation
    diverges (T - Tref <= -C2) or shifts by more than 100 decades."""
    from . import _core

    t = np.asarray(temperature, dtype=float)
    log_at, why = _core.pf_wlf_log10_shift(np.ascontiguousarray(t.ravel()), float(reference),
                                            float(c1), float(c2))
    if np.any(why == 1):
        low = float(np.min(t))
        raise ValueError(f"WLF shift: the data reach T - Tref = {low - reference:g} K "
                         f"({low:g} C against the reference temperature {reference:g} C), where "
                         f"the WLF equation with C2 = {c2:g} K diverges (T - Tref must be > "
                         f"-C2); give C2 > {reference - low:g} K (prony --c2) or a lower "
                         "reference temperature (--reference-temperature)")
    if np.any(why == 2):
        raise ValueError(f"WLF shift: C1 = {c1:g}, C2 = {c2:g} K shift the data by more than "
                         f"100 decades between {np.min(t):g} and {np.max(t):g} C; give the WLF "
                         "constants of a fit over these temperatures (prony --c1, --c2, "
                         "--fit-wlf)")
    out = np.asarray(log_at, dtype=float).reshape(t.shape)
    return out if out.ndim else float(out)


def cells_of(text: str) -> list[str]:
    """The cells of one CSV line, stripped."""
    return [c.strip() for c in next(csv.reader([text]))]


@dataclass
class DMAData:
    """Dynamic mechanical data: one row a point (temperature in degC,
    frequency in Hz, Young's storage and loss moduli in Pa)."""

    temperature: np.ndarray
    frequency: np.ndarray
    storage: np.ndarray
    loss: np.ndarray
    source: str = ""

    @property
    def omega(self) -> np.ndarray:
        return 2.0 * np.pi * self.frequency


def read_dma(path: str | os.PathLike, modulus: str = "tensile",
             temperature: float | None = None) -> DMAData:
    """Read a DMA CSV file (module docstring); ``modulus = 'shear'`` converts
    G', G'' to E', E'' (E = 3 G). Without a temperature column every row is
    at ``temperature`` (default the reference temperature)."""
    path = Path(path)
    if not path.is_file():
        raise ValueError(f"{path}: no such DMA CSV file (columns temperature_c, frequency_hz, "
                         "storage_pa, loss_pa; python -m pavefric prony --write-representative "
                         "PATH writes an example)")
    lines = path.read_text(encoding="utf-8").splitlines()
    comments = [ln[1:].strip() for ln in lines if ln.lstrip().startswith("#")]
    rows = [(k + 1, ln) for k, ln in enumerate(lines) if ln.strip() and
            not ln.lstrip().startswith("#")]
    if not rows:
        raise ValueError(f"{path}: no header and no data")
    header_line, header = rows[0]
    names = [h.strip().lower() for h in next(csv.reader([header]))]

    def column(*candidates):
        for c in candidates:
            if c in names:
                return names.index(c), c
        return None, None

    i_f, f_name = column("frequency_hz", "omega_rad_s")
    i_s, s_name = column("storage_pa", "storage_mpa")
    i_l, l_name = column("loss_pa", "loss_mpa")
    i_t, _ = column("temperature_c")
    missing = [n for n, i in (("frequency_hz or omega_rad_s", i_f),
                              ("storage_pa or storage_mpa", i_s),
                              ("loss_pa or loss_mpa", i_l)) if i is None]
    if missing:
        raise ValueError(f"{path}:{header_line}: no column {', '.join(missing)} in the "
                         f"header ({', '.join(names)})")
    data = []
    for line_no, text in rows[1:]:
        cells = next(csv.reader([text]))
        if len(cells) != len(names):
            raise ValueError(f"{path}:{line_no}: {len(cells)} values, the header has "
                             f"{len(names)}")
        try:
            values = [float(c) for c in cells]
        except ValueError:
            raise ValueError(f"{path}:{line_no}: '{text}' is not a row of numbers") from None
        data.append(values)
    a = np.array(data, dtype=float).reshape(-1, len(names))
    if a.shape[0] == 0:
        raise ValueError(f"{path}: no data rows")
    if not np.all(np.isfinite(a)):
        r, c = np.argwhere(~np.isfinite(a))[0]
        raise ValueError(f"{path}:{rows[1 + r][0]}: {names[c]} = {cells_of(rows[1 + r][1])[c]!r} "
                         "is not finite; give finite numbers (drop the row if it was not "
                         "measured)")
    freq = a[:, i_f] / (2.0 * np.pi) if f_name == "omega_rad_s" else a[:, i_f]
    scale = 1e6 if s_name.endswith("mpa") else 1.0
    storage = a[:, i_s] * scale
    loss = a[:, i_l] * (1e6 if l_name.endswith("mpa") else 1.0)
    if modulus == "shear":
        storage, loss = 3.0 * storage, 3.0 * loss
    elif modulus != "tensile":
        raise ValueError(f"modulus = {modulus!r}: 'tensile' or 'shear'")
    for name, v in (("frequency", freq), ("storage modulus", storage), ("loss modulus", loss)):
        bad = np.flatnonzero(v <= 0)
        if bad.size:
            raise ValueError(f"{path}:{rows[1 + bad[0]][0]}: the {name} must be > 0")
    temp = a[:, i_t] if i_t is not None else np.full(a.shape[0], T_REF if temperature is None
                                                      else temperature)
    return DMAData(temp, freq, storage, loss, source="; ".join(comments) or str(path))


@dataclass
class PronyFit:
    """A generalised Maxwell (Prony) series at the reference temperature."""

    e_inf: float
    e_arms: np.ndarray
    times: np.ndarray
    reference_temperature: float
    c1: float
    c2: float
    #: RMS relative errors of the storage and loss moduli over the data.
    rms_storage: float = math.nan
    rms_loss: float = math.nan
    #: The reduced angular frequencies the data cover (rad/s).
    omega_range: tuple = (math.nan, math.nan)
    points: int = 0
    temperatures: tuple = field(default_factory=tuple)

    def moduli(self, omega, temperature: float | None = None):
        """(E', E'') (Pa) at angular frequencies ``omega`` (rad/s), at the
        reference temperature or at ``temperature``."""
        w = np.asarray(omega, dtype=float)
        if temperature is not None:
            w = w * 10.0 ** wlf_log10_shift(temperature, self.reference_temperature, self.c1,
                                            self.c2)
        wt = w[..., None] * self.times
        storage = self.e_inf + np.sum(self.e_arms * wt**2 / (1 + wt**2), axis=-1)
        loss = np.sum(self.e_arms * wt / (1 + wt**2), axis=-1)
        return storage, loss

    def parameters(self, thickness: float = THICKNESS) -> dict:
        """``simulate`` keywords of this compound (moduli / thickness)."""
        return dict(rubber_model="maxwell", stiffness=self.e_inf / thickness,
                    prony_stiffness=list(self.e_arms / thickness),
                    prony_times=list(self.times),
                    reference_temperature=self.reference_temperature,
                    wlf_c1=self.c1, wlf_c2=self.c2)

    def namelist(self, thickness: float = THICKNESS, comments: list[str] | None = None) -> str:
        """The ``&rubber`` group (with ``!`` comments before it)."""
        p = self.parameters(thickness)
        lines = [f"! {c}" for c in (comments or [])]
        lines += ["&rubber",
                  "  model = 'maxwell'",
                  f"  stiffness = {p['stiffness']:.6g}          ! E_inf / thickness, N m-3",
                  "  prony_stiffness = " + _wrap([f"{v:.6g}" for v in p["prony_stiffness"]]),
                  "  prony_times = " + _wrap([f"{v:.6g}" for v in p["prony_times"]]),
                  f"  reference_temperature = {self.reference_temperature:g}",
                  f"  temperature = {self.reference_temperature:g}      ! the rubber's "
                  "temperature: set it",
                  f"  wlf_c1 = {self.c1:.6g}",
                  f"  wlf_c2 = {self.c2:.6g}",
                  "/", ""]
        return "\n".join(lines)


def _wrap(values: list[str], per_line: int = 5) -> str:
    chunks = [", ".join(values[k:k + per_line]) for k in range(0, len(values), per_line)]
    return (",\n" + " " * 4).join(chunks)


def _design(omega: np.ndarray, times: np.ndarray, storage: np.ndarray, loss: np.ndarray):
    """The NNLS system: rows E'/E'_measured and E''/E''_measured, columns
    E_inf then each arm's E_k."""
    wt = omega[:, None] * times[None, :]
    a_s = np.hstack([np.ones((omega.size, 1)), wt**2 / (1 + wt**2)]) / storage[:, None]
    a_l = np.hstack([np.zeros((omega.size, 1)), wt / (1 + wt**2)]) / loss[:, None]
    return np.vstack([a_s, a_l]), np.ones(2 * omega.size)


def fit_prony(data: DMAData, reference: float = T_REF, c1: float = WLF_C1,
              c2: float = WLF_C2, per_decade: float = 1.0, fit_wlf: bool = False,
              times=None) -> PronyFit:
    """A Prony series fitted to ``data`` (module docstring). With ``fit_wlf``
    C1 and C2 are fitted too (Nelder-Mead on their logarithms, from the given
    values), minimising the same residual. ``times`` (s, at the reference
    temperature) replaces the log-spaced candidate relaxation times."""
    from scipy.optimize import minimize, nnls

    if per_decade <= 0:
        raise ValueError(f"per_decade = {per_decade:g} (prony --per-decade): must be > 0 "
                         "(candidate relaxation times per decade; default 1)")

    def solve(c1_, c2_):
        w = data.omega * 10.0 ** wlf_log10_shift(data.temperature, reference, c1_, c2_)
        if times is None:
            lo, hi = np.log10(1.0 / w.max()) - 1.0, np.log10(1.0 / w.min()) + 1.0
            n = max(2, int(math.ceil((hi - lo) * per_decade)) + 1)
            candidates = np.logspace(lo, hi, n)
        else:
            candidates = np.sort(np.asarray(times, dtype=float))
            if candidates.ndim != 1 or candidates.size == 0 or not np.all(candidates > 0):
                raise ValueError("times: relaxation times must be a list of numbers > 0")
        a, b = _design(w, candidates, data.storage, data.loss)
        x, rnorm = nnls(a, b, maxiter=50 * a.shape[1])
        return x, candidates, w, rnorm

    if fit_wlf:
        if np.unique(data.temperature).size < 2:
            raise ValueError("--fit-wlf needs data at two temperatures or more")

        def cost(q):
            c1_, c2_ = np.exp(q)
            try:
                wlf_log10_shift(data.temperature, reference, c1_, c2_)
            except ValueError:                  # outside the WLF equation's domain
                return 1e300
            return solve(c1_, c2_)[3]

        res = minimize(cost, np.log([c1, c2]), method="Nelder-Mead",
                       options=dict(xatol=1e-6, fatol=1e-12, maxiter=2000))
        c1, c2 = (float(v) for v in np.exp(res.x))
    x, times, w, _ = solve(c1, c2)
    # arms NNLS set to zero, or to rounding residue of the others
    keep = x[1:] > 1e-9 * max(x.max(), 0.0)
    fit = PronyFit(float(x[0]), x[1:][keep], times[keep], reference, float(c1), float(c2),
                   omega_range=(float(w.min()), float(w.max())), points=int(w.size),
                   temperatures=tuple(float(t) for t in np.unique(data.temperature)))
    s, l = fit.moduli(w)
    fit.rms_storage = float(np.sqrt(np.mean((s / data.storage - 1) ** 2)))
    fit.rms_loss = float(np.sqrt(np.mean((l / data.loss - 1) ** 2)))
    return fit


# --- the representative compound ----------------------------------------------

def representative_moduli(omega, temperature=T_REF, e_rubbery=None, e_glassy=None, tau=None,
                          alpha=None, beta=None):
    """(E', E'') of the representative compound (REPRESENTATIVE) at angular
    frequency ``omega`` (rad/s) and ``temperature`` (degC)."""
    p = dict(REPRESENTATIVE)
    p.update({k: v for k, v in dict(e_rubbery=e_rubbery, e_glassy=e_glassy, tau=tau,
                                    alpha=alpha, beta=beta).items() if v is not None})
    w = np.asarray(omega, dtype=float) * 10.0 ** wlf_log10_shift(temperature)
    e = p["e_glassy"] - (p["e_glassy"] - p["e_rubbery"]) / (
        1.0 + (1j * w * p["tau"]) ** p["alpha"]) ** p["beta"]
    return e.real, e.imag


def representative_dma() -> DMAData:
    """The representative data set: frequency sweeps 0.1-100 Hz (4 points a
    decade) at -20 to 60 degC, from REPRESENTATIVE."""
    f = np.logspace(-1, 2, 13)
    temps, freqs, st, lo = [], [], [], []
    for t in REPRESENTATIVE_TEMPERATURES:
        s, l = representative_moduli(2 * np.pi * f, t)
        temps += [t] * f.size
        freqs += list(f)
        st += list(s)
        lo += list(l)
    return DMAData(np.array(temps), np.array(freqs), np.array(st), np.array(lo),
                   source="representative tread compound (pavefric.rubber.REPRESENTATIVE)")


#: What every compound ``prony -o`` writes begins with: an existing file at
#: ``-o`` is replaced only if it begins so (``check_output``'s ``signature``).
NAMELIST_SIGNATURE = "! Prony series fitted by `python -m pavefric prony"

REPRESENTATIVE_HEADER = """\
# Representative dynamic mechanical data of a passenger-car tread compound.
# NOT A MEASUREMENT: written by `python -m pavefric prony --write-representative
# inputs/data/tread_compound_dma.csv` from a stated model, as an example input
# for `python -m pavefric prony` (see inputs/data/README.md and docs/rubber.md).
# Model: Young's modulus E*(w) = E_g - (E_g - E_r) / (1 + (i w a_T tau)^alpha)^beta
#   (Havriliak & Negami 1966, J. Polym. Sci. C 14, 99) with E_r = {e_rubbery:g} Pa
#   (low-frequency modulus of a tread compound), E_g = {e_glassy:g} Pa (glassy
#   elastomer, 1-3 GPa), beta = {beta:g}, tau = {tau:g} s and alpha = {alpha:g} chosen so
#   that tan delta at 10 Hz is 0.50 at 0 C and 0.12 at 60 C (typical values of the
#   wet-grip and rolling-resistance indicators of passenger-car tread compounds).
# WLF shift (Williams, Landel & Ferry 1955, J. Am. Chem. Soc. 77, 3701):
#   log10 a_T = -{c1:g} (T - {tref:g}) / ({c2:g} + T - {tref:g}), reference {tref:g} C taken
#   50 K above a glass transition of -30 C.
# Columns: temperature (C), frequency (Hz), storage and loss moduli E', E'' (Pa).
"""


def write_dma(path: str | os.PathLike, data: DMAData, header: str = "",
              signature: str | None = None, inputs=()) -> Path:
    """Write DMA data as the CSV ``read_dma`` reads, whole or not at all
    (``pavefric.core.atomic_output``). ``signature``: what the files of this
    kind begin with; an existing file that does not is refused (None: the
    header's first line when there is a header, else the CSV's column line).
    ``inputs``: files never written over (the command's own data)."""
    from .core import atomic_output

    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    rows = [header.rstrip("\n"), "temperature_c,frequency_hz,storage_pa,loss_pa"] if header \
        else ["temperature_c,frequency_hz,storage_pa,loss_pa"]
    for t, f, s, l in zip(data.temperature, data.frequency, data.storage, data.loss):
        rows.append(f"{t:g},{f:.6g},{s:.6e},{l:.6e}")
    if signature is None:
        signature = rows[0].splitlines()[0]
    with atomic_output(path, inputs, signature=signature) as tmp:
        tmp.write_text("\n".join(rows) + "\n", encoding="utf-8")
    return path


# --- a compound file into simulate keywords -------------------------------------

def compound(path: str | os.PathLike) -> dict:
    """The ``&rubber`` group of a namelist fragment (a file ``prony`` wrote)
    as ``simulate`` keywords, read by the core exactly as in a scene."""
    from .core import load_scene, parameters

    text = Path(path).read_text(encoding="utf-8")
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        (tmp / "flat.txt").write_text("\n".join(["0"] * 64) + "\n")
        (tmp / "scene.nml").write_text(text + "\n&surface profile_file = 'flat.txt', "
                                       "dx = 0.87e-3 /\n&operation speeds_kmh = 20 /\n")
        scene = load_scene(tmp / "scene.nml")
    keys = {p.keyword for p in parameters() if p.group == "rubber" and p.keyword}
    return {k: v for k, v in scene.parameters.items() if k in keys}


# --- the command ---------------------------------------------------------------

def plot_fit(fit: PronyFit, data: DMAData, path: str | os.PathLike, title: str = "",
             inputs=()) -> Path:
    """The master curve: data shifted to the reference temperature against the
    fitted series, and tan delta. Written by ``pavefric.plot.save_figure``'s
    rule (a PNG; a file at ``path`` is replaced only if pavefric drew it,
    never one of ``inputs``, the DMA data's file among them)."""
    from .plot import _checked, save_figure

    path = Path(path)
    _checked(path, inputs, writable=False)      # (its directory is made below)
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    path.parent.mkdir(parents=True, exist_ok=True)
    w = data.omega * 10.0 ** wlf_log10_shift(data.temperature, fit.reference_temperature,
                                             fit.c1, fit.c2)
    grid = np.logspace(np.log10(fit.omega_range[0]) - 1, np.log10(fit.omega_range[1]) + 1, 400)
    s, l = fit.moduli(grid)
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4.2), dpi=120)
    a.loglog(w, data.storage, "o", ms=3, color="C0", label="E' data (shifted)")
    a.loglog(w, data.loss, "s", ms=3, color="C1", label="E'' data (shifted)")
    a.loglog(grid, s, "-", color="C0", label=f"E' Prony ({fit.e_arms.size} arms)")
    a.loglog(grid, l, "-", color="C1", label="E'' Prony")
    a.set_xlabel(f"reduced angular frequency ω a_T (rad/s), Tref = {fit.reference_temperature:g} °C")
    a.set_ylabel("modulus (Pa)")
    a.grid(alpha=0.3, which="both")
    a.legend(fontsize=8)
    b.semilogx(w, data.loss / data.storage, "o", ms=3, color="C2", label="data")
    b.semilogx(grid, l / s, "-", color="C2", label="Prony")
    b.set_xlabel("reduced angular frequency ω a_T (rad/s)")
    b.set_ylabel("tan δ")
    b.grid(alpha=0.3, which="both")
    b.legend(fontsize=8)
    fig.suptitle(title or "Prony series fitted to the master curve")
    fig.tight_layout()
    try:
        save_figure(fig, path, inputs)
    finally:
        plt.close(fig)
    return path


def main_prony(args) -> int:
    """``python -m pavefric prony`` (see __main__)."""
    if args.write_representative:
        # (never over the data the same command fits next)
        p = write_dma(args.write_representative, representative_dma(),
                      REPRESENTATIVE_HEADER.format(**REPRESENTATIVE, c1=WLF_C1, c2=WLF_C2,
                                                   tref=T_REF), inputs=[args.data])
        print(f"wrote {p}")
        if not args.data:
            return 0
    if not args.data:
        print("pavefric prony: error: give a DMA CSV file (or --write-representative PATH)")
        return 2
    if args.plot:
        # both outputs checked before the fit: a refused path costs nothing
        from .core import PavefricError
        from .plot import _checked

        if args.output and Path(args.plot).resolve() == Path(args.output).resolve():
            raise PavefricError(f"prony: --plot '{args.plot}' is the -o path; give the "
                                "figure its own .png")
        _checked(args.plot, [args.data], writable=False)     # (plot_fit makes the directory)
    if args.output:
        from .core import check_output

        check_output(args.output, inputs=[args.data], signature=NAMELIST_SIGNATURE)
    data = read_dma(args.data, modulus=args.modulus, temperature=args.reference_temperature)
    fit = fit_prony(data, reference=args.reference_temperature, c1=args.c1, c2=args.c2,
                    per_decade=args.per_decade, fit_wlf=args.fit_wlf)
    header = [ln for ln in data.source.split("; ") if ln][:2] or [str(args.data)]
    comments = [
        f"{NAMELIST_SIGNATURE[2:]} {args.data}` "
        f"({time.strftime('%Y-%m-%d')}).",
        f"Data ({args.data}): {header[0]}",
        *[f"  {ln}" for ln in header[1:]],
        f"{fit.points} points at {', '.join(f'{t:g}' for t in fit.temperatures)} C, shifted "
        f"to Tref = {fit.reference_temperature:g} C with WLF C1 = {fit.c1:.6g}, "
        f"C2 = {fit.c2:.6g} K" + (" (fitted)" if args.fit_wlf else "") + ".",
        f"Non-negative least squares over {args.per_decade:g} relaxation time(s) a decade: "
        f"{fit.e_arms.size} arms; RMS relative error E' {100 * fit.rms_storage:.2f} %, "
        f"E'' {100 * fit.rms_loss:.2f} %.",
        f"Moduli (Pa) divided by the rubber thickness h = {args.thickness:g} m: stiffness "
        "per unit length K = E / h (a thin layer).",
    ]
    text = fit.namelist(args.thickness, comments)
    if args.output:
        from .core import atomic_output

        out = Path(args.output)
        out.parent.mkdir(parents=True, exist_ok=True)
        # replaces only a compound this command wrote (never the user's scene)
        with atomic_output(out, inputs=[args.data], signature=NAMELIST_SIGNATURE) as tmp:
            tmp.write_text(text, encoding="utf-8")
        print(f"wrote {out}")
    else:
        print(text, end="")
    if args.plot:
        print(f"wrote {plot_fit(fit, data, args.plot, inputs=[args.data])}")
    return 0
