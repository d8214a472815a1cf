"""Thin wrappers over the Fortran core (the f2py extension ``_core``).

Nothing here computes friction: every number comes from the Fortran core, so
``simulate`` gives the same numbers as the ``pavefric`` program, bit for bit.
This module only converts arguments, sizes output arrays, and turns the
core's status and message into a Python exception.
"""
from __future__ import annotations

import contextlib
import functools
import os
import shlex
import stat
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Iterable

import numpy as np

from . import _core

__all__ = [
    "PavefricError",
    "PavefricKeywordError",
    "PavefricWarning",
    "parameters",
    "groups",
    "defaults",
    "simulate",
    "run",
    "open_dataset",
    "Profile",
    "layout",
    "hydro_load",
    "load_scene",
    "Scene",
    "ProfilesFailedWarning",
]


class PavefricError(ValueError):
    """Bad input or a failed run; the message names the group, variable and value."""


class PavefricKeywordError(PavefricError, TypeError):
    """An unknown keyword argument (also a TypeError, as Python reports those)."""


class PavefricMemoryError(PavefricError, MemoryError):
    """A run that would not fit in the memory the process may use, or input
    asking for more than can be held (``&pad element_length = 1e-300``): a
    PavefricError naming what to change, and a MemoryError, as Python reports
    those. The process lives on."""


class PavefricWarning(UserWarning):
    """Plausible-but-suspicious input or results (also recorded in the output's
    ``warnings`` attribute)."""


class PavefricCostWarning(UserWarning):
    """A run estimated (before it starts) to take ``ANNOUNCE_SECONDS`` or more
    on one thread: the warning carries the estimate (element-steps, memory,
    seconds), which the output also records (``estimated_seconds``). It is not
    a ``PavefricWarning`` (nothing is wrong with the input): silence it with
    ``warnings.simplefilter("ignore", pavefric.PavefricCostWarning)``."""


#: A run estimated to take this long (s, one thread) or more warns before it
#: starts (``PavefricCostWarning``); the program prints its estimate from 1 s.
ANNOUNCE_SECONDS = 10.0


def _announce(estimate, text, status, message) -> float:
    """Warn before a long run (the estimate from pf_estimate or
    pf_scene_estimate). A scene the estimate cannot read is left to the run,
    which says why in its own order of checks. Returns the estimate's seconds
    for the passes that refine the pad, which the run then records without
    probing the profile again (-1 when there is no estimate: the run probes)."""
    if int(status) != 0:
        return -1.0
    if float(estimate[2]) < ANNOUNCE_SECONDS:
        return float(estimate[3])
    import warnings

    warnings.warn(f"pavefric: a long run ({_text(text)}); the output records it as "
                  "estimated_seconds", PavefricCostWarning, stacklevel=3)
    return float(estimate[3])


class ProfilesFailedWarning(UserWarning):
    """A batch finished but some of its profiles failed (the program's exit
    status 4): the output is written, its ``status`` (2) and ``error_message``
    variables say which and why. Make it an error with
    ``warnings.simplefilter("error", pavefric.ProfilesFailedWarning)``.

    Parameters
    ----------
    message : str
        The warning's text.
    path : pathlib.Path or None, optional
        The output file.
    failed : dict of str to str or None, optional
        Each failed profile's name and its message.
    """

    def __init__(self, message: str, path: Path | None = None,
                 failed: dict[str, str] | None = None):
        super().__init__(message)
        self.path = path
        self.failed = dict(failed or {})


def _text(raw: Any) -> str:
    if isinstance(raw, bytes):
        raw = raw.decode("utf-8", "replace")
    elif isinstance(raw, np.ndarray):
        raw = raw.tobytes().decode("utf-8", "replace")
    return str(raw).rstrip("\x00 ").strip()


# The core's status kinds (src/base/pavefric_error.f90): stat_memory is "not enough
# memory for the work asked for", which Python reports as PavefricMemoryError (a
# PavefricError and a MemoryError).
_STAT_MEMORY = 3


def _b(text: str | os.PathLike) -> bytes:
    """Text for a Fortran character argument: UTF-8 bytes (f2py refuses a
    non-ASCII str), paths in the file system's encoding."""
    if isinstance(text, bytes):
        return text
    if isinstance(text, os.PathLike):
        return os.fsencode(text)
    return str(text).encode("utf-8")


def _check(status: int, message: Any, keywords: bool = False) -> None:
    """Raise the core's error, if any. ``keywords``: the values came as
    ``simulate`` keywords, so a message about a variable whose keyword is not
    its namelist name names the keyword first (``water_viscosity = 0 (&water
    viscosity): ...``; ``viscosity`` is the rubber's keyword)."""
    if int(status) == 0:
        return
    text = _text(message)
    if keywords:
        for key, (group, name) in PARAMETERS.items():
            head = f"&{group} {name}"
            if key != name and text.startswith(head) and text[len(head):len(head) + 1] in " (:":
                rest = text[len(head):]
                value, sep, tail = rest.partition(": ")
                text = f"{key}{value} ({head}): {tail}" if sep else f"{key} ({head}){rest}"
                break
    if int(status) == _STAT_MEMORY:
        raise PavefricMemoryError(text)
    raise PavefricError(text)


def check_output(path: str | os.PathLike, inputs=(), replaces: str | None = None,
                 signature: str | None = None, writable: bool = False) -> None:
    """The rule every pavefric writer follows, from the core (the program's
    and the C API's own): ``path`` must be missing or a regular file (never a
    FIFO, a device or a directory) and not the same file as any of ``inputs``
    (symbolic and hard links seen through). The caller then writes through a
    temporary in the same directory and a rename.

    Parameters
    ----------
    path : str or os.PathLike
        The file about to be written.
    inputs : iterable of path-like, optional
        The files the data written came from.
    replaces : {"results", "profiles", "png"} or None, optional
        What a writer writes, and so the only kind of existing file it may
        replace (the program's rule): ``"results"`` (a run's, a batch's or
        ``merge``'s output, NetCDF ``source`` 'pavefric <version>'),
        ``"profiles"`` (a survey ``write_profiles`` wrote) or ``"png"`` (a
        figure pavefric's plots drew: a PNG whose text chunk ``Software``
        begins with 'pavefric'). A file of another kind, another tool's
        NetCDF, a figure of the user's or a file of another format is
        refused; an empty file may be replaced. None: no such check.
    signature : str or None, optional
        For a writer of text (a namelist, a CSV, JSON): the characters it
        puts first in every file it writes. An existing non-empty file that
        does not begin with them is refused (a user's scene or data named by
        mistake); an empty file may be replaced. Not with ``replaces``.
    writable : bool, optional
        Also that a file can be made beside ``path`` now (its directory
        exists and may be written: the program's check before a run). Leave
        it False where the writer makes the directory later;
        ``atomic_output`` checks it as it starts writing.

    Returns
    -------
    None

    Raises
    ------
    PavefricError
        Naming the path and why it may not be written.
    """
    if replaces not in (None, "results", "profiles", "png"):
        raise ValueError(f"check_output replaces = {replaces!r}: 'results', 'profiles' "
                         "or 'png'")
    if signature is not None:
        if replaces is not None:
            raise ValueError("check_output: replaces or signature, not both")
        if not signature.strip():
            raise ValueError("check_output signature: empty")
        replaces = "text:" + signature
    if not os.fspath(path):
        raise PavefricError("the output path is empty: give a file name")
    # (read once: an iterator is read here and below; None and '' name nothing)
    inputs = [p for p in inputs if p]
    # an input that does not exist yet (another output of the same command,
    # written later) is the same file only by its path
    target = os.path.abspath(os.fspath(path))
    for p in inputs:
        if not os.path.lexists(p) and os.path.abspath(os.fspath(p)) == target:
            raise PavefricError(f"the output path '{os.fspath(path)}': is also '{os.fspath(p)}', "
                                "another file this command reads or writes; give each its own "
                                "path")
    joined = "\n".join(os.fspath(p) for p in inputs)
    # (f2py takes no empty strings: a blank says no kind)
    status, message = _core.pf_check_output(_b(os.fspath(path)), _b(joined) or b"\n",
                                            _b(replaces or " "), 1 if writable else 0)
    _check(status, message)


@contextlib.contextmanager
def atomic_output(path: str | os.PathLike, inputs=(), replaces: str | None = None,
                  signature: str | None = None):
    """Write ``path`` whole or not at all, as every pavefric writer does:
    ``check_output(path, inputs)``, then the caller writes the temporary this
    yields (``path.tmpPID.pavefric`` beside ``path``, the program's own name, so that a
    later writer removes it if this process is killed outright), which is
    renamed onto ``path`` when the ``with`` block ends without an exception and
    removed otherwise.

    Parameters
    ----------
    path : path-like
        The file to write.
    inputs : iterable of path-like
        The files the data written came from (never overwritten).
    replaces : {"results", "profiles", "png"} or None
        ``check_output``'s: the kind of file the writer may replace.
    signature : str or None
        ``check_output``'s: what a text writer's files begin with.

    Yields
    ------
    pathlib.Path
        The temporary file to write.
    """
    check_output(path, inputs, replaces, signature, writable=True)
    tmp = Path(_text(_core.pf_temporary_name(_b(os.fspath(path)))))
    try:
        yield tmp
        try:
            # the permission bits of the file replaced (a private result
            # stays private), as the core's own writers keep them
            os.chmod(tmp, stat.S_IMODE(os.stat(path).st_mode))
        except FileNotFoundError:
            pass
        os.replace(tmp, path)
    finally:
        if os.path.lexists(tmp):
            tmp.unlink()


def write_text_output(path: str | os.PathLike, text: str, signature: str, inputs=()) -> Path:
    """Write ``text`` to ``path`` by the rule of every pavefric writer
    (``atomic_output``): never over one of ``inputs``, a FIFO, a device or a
    directory; an existing non-empty file replaced only if it begins with
    ``signature`` (what this writer's files begin with, so a user's file
    named by mistake stays byte for byte); whole or not at all. ``text``
    must begin with ``signature``. Returns the path."""
    if not text.startswith(signature):
        raise ValueError(f"write_text_output: the text does not begin with {signature!r}")
    with atomic_output(path, inputs, signature=signature) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return Path(path)


def _warn(text: str) -> None:
    import warnings

    for line in text.splitlines():
        if line.strip():
            warnings.warn(line, PavefricWarning, stacklevel=3)


# --- the one table of parameters, read from the core (pavefric_model) ---------

KIND_REAL, KIND_INTEGER, KIND_LOGICAL, KIND_TEXT, KIND_LIST = 1, 2, 3, 4, 5


@dataclass(frozen=True)
class Parameter:
    """The declaration of one namelist variable, as the core has it."""

    group: str
    name: str
    keyword: str
    scope: str
    unit: str
    default_text: str
    choices: tuple
    meaning: str
    kind: int
    lower: float
    upper: float
    lower_strict: bool
    upper_strict: bool
    plausible_lower: float
    plausible_upper: float
    max_values: int
    required: bool

    @property
    def default(self):
        """The default as a Python value (None when there is none)."""
        if self.default_text in ("", "''") and self.kind != KIND_TEXT:
            return None
        return _value_from_text(self, self.default_text)


@dataclass(frozen=True)
class Group:
    name: str
    title: str
    description: str


def _value_from_text(spec: Parameter, text: str):
    """A value from the core's canonical namelist text (its own output)."""
    text = text.strip()
    if spec.kind == KIND_REAL:
        return float(text)
    if spec.kind == KIND_INTEGER:
        return int(text)
    if spec.kind == KIND_LOGICAL:
        return text.lower() in (".true.", "t", "true")
    if spec.kind == KIND_TEXT:
        return text[1:-1].replace("''", "'")
    return [float(v) for v in text.split(",") if v.strip()]


@functools.lru_cache(maxsize=1)
def _tables() -> tuple:
    n_par, n_groups = _core.pf_parameter_count()
    params = []
    for i in range(1, int(n_par) + 1):
        (group, name, keyword, scope, unit, default, choices, meaning, kind, bounds, strict,
         max_values, required) = _core.pf_parameter_info(i)
        params.append(Parameter(_text(group), _text(name), _text(keyword), _text(scope),
                                _text(unit), _text(default), tuple(_text(choices).split()),
                                _text(meaning), int(kind), float(bounds[0]), float(bounds[1]),
                                bool(strict[0]), bool(strict[1]), float(bounds[2]),
                                float(bounds[3]), int(max_values), bool(required)))
    groups = []
    for i in range(1, int(n_groups) + 1):
        name, title, description = _core.pf_group_info(i)
        groups.append(Group(_text(name), _text(title), _text(description)))
    n_out = int(_core.pf_output_count())
    outputs = []
    for i in range(1, n_out + 1):
        (name, units, long_name, description, var_type, dims, written,
         owner) = _core.pf_output_info(i)
        outputs.append((_text(name), _text(units), _text(long_name), int(var_type), int(dims),
                        _text(written), _text(owner), _text(description)))
    return tuple(params), tuple(groups), tuple(outputs)


@functools.lru_cache(maxsize=1)
def _scalar_table() -> tuple:
    """The scalars of a scene's file: (name, units, long_name, description)
    each, from the core (pavefric_outputs' scalar_table)."""
    rows, i, n = [], 1, 1
    while i <= n:
        n, name, units, long_name, description = _core.pf_scalar_info(i)
        rows.append((_text(name), _text(units), _text(long_name), _text(description)))
        i += 1
    return tuple(rows)


def parameters() -> tuple:
    """Every namelist variable's declaration, from the core.

    Returns
    -------
    tuple of Parameter
        Name, group, unit, default, range and description of each variable.
    """
    return _tables()[0]


def groups() -> tuple:
    """The namelist groups, from the core's declarations.

    Returns
    -------
    tuple of Group
        Each group's name and description, in the namelist's order.
    """
    return _tables()[1]


def _keywords(scope: str) -> dict:
    return {p.keyword: p for p in parameters() if p.scope == scope and p.keyword}


# simulate() keywords -> (namelist group, variable), from the core's table
PARAMETERS: dict[str, tuple[str, str]] = {}


def _init_keywords() -> None:
    PARAMETERS.update({k: (p.group, p.name) for k, p in _keywords("model").items()})


@functools.lru_cache(maxsize=1)
def _version() -> str:
    return _text(_core.pf_version()[0])


#: Spacing of a Circular Track Meter profile (m): the core's default dx.
CTM_DX = float(_core.pf_version()[1])


def defaults() -> dict[str, Any]:
    """The model's default parameters, from the core's declarations.

    Returns
    -------
    dict of str to Any
        ``simulate`` keyword -> default value (SI units).
    """
    return {k: p.default for k, p in _keywords("model").items()}


# --- Python values as typed items (checked by the core's declarations) --------

#: Kinds of a typed item (pavefric_model's apply_typed).
_T_REAL, _T_INTEGER, _T_LOGICAL, _T_TEXT, _T_LIST = 1, 2, 3, 4, 5


def _is_real(v) -> bool:
    return isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(v, (bool, np.bool_))


def _format(spec: Parameter, value, label: str) -> tuple:
    """One keyword's value as a typed item (kind, numbers, text), after the
    checks only Python can make (its type); the core checks it against the
    variable's declaration (range, choices) with the namelist reader's
    messages."""
    where = f"&{spec.group} {spec.name}"
    if spec.kind == KIND_REAL:
        if not _is_real(value):
            raise PavefricError(f"{where} = {value!r}: {label} must be a number")
        return (_T_REAL, [float(value)], b"")
    if spec.kind == KIND_INTEGER:
        if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer, float,
                                                                          np.floating)):
            raise PavefricError(f"{where} = {value!r}: {label} must be a whole number")
        return (_T_INTEGER, [float(value)], b"")       # the core refuses 2.9 (and says so)
    if spec.kind == KIND_LOGICAL:
        if not isinstance(value, (bool, np.bool_)):
            raise PavefricError(f"{where} = {value!r}: {label} must be True or False")
        return (_T_LOGICAL, [1.0 if value else 0.0], b"")
    if spec.kind == KIND_TEXT:
        if isinstance(value, os.PathLike) and spec.unit == "path":
            value = os.fspath(value)
        if not isinstance(value, str):
            raise PavefricError(f"{where} = {value!r}: {label} must be text")
        if "\n" in value or "\r" in value:
            raise PavefricError(f"{where} = {value!r}: {label} must be one line")
        return (_T_TEXT, [], _b(value))
    values = np.atleast_1d(np.asarray(value))
    if values.ndim != 1 or values.dtype.kind not in "iuf":
        raise PavefricError(f"{where} = {value!r}: {label} must be a list of numbers")
    return (_T_LIST, [float(v) for v in values], b"")


def _typed(assignments: dict[tuple[str, str], tuple]) -> tuple:
    """The core's typed items of (group, name) -> _format's item: variable
    ids (1-based, the declaration table's order), kinds, numbers and text
    bytes per item, the numbers and the text (never empty for f2py)."""
    index = {(p.group, p.name): k + 1 for k, p in enumerate(parameters())}
    ids, kinds, counts, lengths, reals, text = [], [], [], [], [], b""
    for key, (kind, numbers, raw) in assignments.items():
        ids.append(index[key])
        kinds.append(kind)
        counts.append(len(numbers))
        lengths.append(len(raw))
        reals.extend(numbers)
        text += raw
    as_int = lambda v: np.asarray(v, dtype=np.int32)        # noqa: E731
    return (as_int(ids), as_int(kinds), as_int(counts), as_int(lengths),
            np.asarray(reals, dtype=np.float64), text or b" ")


def _parameters(given: dict[str, Any], scope: str = "model") -> dict[tuple[str, str], str]:
    known = _keywords(scope)
    unknown = sorted(set(given) - set(known))
    if unknown:
        raise PavefricKeywordError(f"unknown parameter(s) {', '.join(unknown)}; known: "
                                   f"{', '.join(known)}")
    return {(known[k].group, known[k].name): _format(known[k], v, k) for k, v in given.items()}


def _heights(heights_m) -> np.ndarray:
    if np.ma.isMaskedArray(heights_m) and np.ma.getmaskarray(heights_m).any():
        raise PavefricError("heights: a masked array with masked values (fill or remove them: "
                            "pavefric does not guess a height)")
    raw = np.asarray(heights_m)
    if raw.dtype.kind not in "iuf":
        # complex parts would be dropped, strings parsed, booleans taken as 0/1
        raise PavefricError(f"heights: an array of real numbers is expected, got dtype "
                            f"{raw.dtype} (convert it yourself if that is what you mean)")
    try:
        z = np.asarray(raw, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise PavefricError(f"heights: not an array of numbers ({exc})") from None
    if z.ndim != 1:
        raise PavefricError(f"heights: a 1-D array of heights is expected, got shape {z.shape} "
                            "(pass one profile at a time)")
    if z.size == 0:
        raise PavefricError("heights: an empty array; give the profile's heights (m), at least "
                            "as many as the pad has elements")
    return np.ascontiguousarray(z)


def _flag(value, name: str) -> bool:
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    raise PavefricError(f"{name} = {value!r}: must be True or False")


def layout(n_points: int, dx: float, closed: bool = True, **parameters: Any) -> tuple[int, int]:
    """The pad's elements and the averaged positions of a profile.

    Parameters
    ----------
    n_points : int
        Number of profile points.
    dx : float
        Their spacing (m).
    closed : bool, optional
        A closed profile (default) or an open one.
    **parameters : Any
        ``simulate`` keywords that change the layout (``length``,
        ``elements_per_sample``, ``substeps``, ``position_stride``, ...).

    Returns
    -------
    tuple of (int, int)
        (pad elements, averaged positions); 0 positions if the pad does not fit.

    Raises
    ------
    PavefricError
        If a parameter is out of its range.
    """
    settings = {**_parameters(parameters),
                ("surface", "dx"): _format(_spec("surface", "dx"), dx, "dx"),
                ("surface", "closed"): _format(_spec("surface", "closed"),
                                               _flag(closed, "closed"), "closed"),
                ("operation", "speeds_kmh"): _format(_spec("operation", "speeds_kmh"), [0.0],
                                                     "speeds_kmh")}
    n_el, n_pos, _, status, message = _core.pf_layout(*_typed(settings), int(n_points))
    _check(status, message, keywords=True)
    return int(n_el), int(n_pos)


def _spec(group: str, name: str) -> Parameter:
    for p in parameters():
        if p.group == group and p.name == name:
            return p
    raise KeyError((group, name))


def simulate(heights_m: Iterable[float], dx: float, speeds_kmh: Iterable[float] | float, *,
             closed: bool = True, series: bool = False, **parameters: Any):
    """Run the friction model on a profile and return an ``xarray.Dataset``.

    The values go to the core as typed values (no namelist text), checked
    against the same declarations as a scene file's and run by the
    program's own path, so the variables and attributes are those of the
    program's NetCDF output, bit for bit.
    Suspicious values raise a ``PavefricWarning`` (also in
    ``ds.attrs["warnings"]``).

    Parameters
    ----------
    heights_m : iterable of float
        Profile heights in metres (1-D), at uniform spacing ``dx``.
    dx : float
        The spacing (m).
    speeds_kmh : iterable of float or float
        Sliding speeds in km/h.
    closed : bool, optional
        A closed Circular Track Meter circle (default) or an open profile.
    series : bool, optional
        Also return per-position ``mu_inst``, ``hydro_load``, ``penetration``
        and ``contact_elements``.
    **parameters : Any
        The namelist's model variables (SI units); ``viscosity`` is the
        rubber's C, ``water_viscosity`` the water's eta. See ``defaults()``
        and docs/inputs.md.

    Returns
    -------
    xarray.Dataset
        The program's output variables and attributes (docs/outputs.md).

    Raises
    ------
    PavefricError
        If a value is bad (naming the group, the variable and the value).
    PavefricKeywordError
        If a keyword is not a model variable.

    Warns
    -----
    PavefricWarning
        Suspicious input or results (also in ``ds.attrs["warnings"]``).
    PavefricCostWarning
        Before a run estimated to take ``ANNOUNCE_SECONDS`` (10 s) or more on
        one thread, with the estimate (``estimated_seconds`` in the output).
    """
    import xarray as xr

    z = _heights(heights_m)
    speeds = np.atleast_1d(np.asarray(speeds_kmh))
    if speeds.ndim != 1 or speeds.dtype.kind not in "iuf":
        raise PavefricError(f"&operation speeds_kmh = {speeds_kmh!r}: a list of numbers "
                            "is expected")
    if speeds.size == 0:
        raise PavefricError("speeds_kmh = []: give at least one speed (km/h)")
    settings = {**_parameters(parameters),
                ("surface", "dx"): _format(_spec("surface", "dx"), dx, "dx"),
                ("surface", "closed"): _format(_spec("surface", "closed"),
                                               _flag(closed, "closed"), "closed"),
                ("operation", "speeds_kmh"): _format(_spec("operation", "speeds_kmh"), speeds,
                                                     "speeds_kmh"),
                ("output", "series"): _format(_spec("output", "series"), _flag(series, "series"),
                                              "series")}
    typed = _typed(settings)
    npos, n_series = 1, 1
    if series:
        n_el, npos, n_series, status, message = _core.pf_layout(*typed, z.size)
        _check(status, message, keywords=True)
        npos = max(npos, 1)
    forecast = _announce(*_core.pf_estimate(z, *typed))
    _, _, outputs = _tables()
    ntext = 4096 + 2 * len(typed[-1]) + 32 * len(typed[0])
    while True:
        (speed, speed_kmh, values, series_values, present, position, counts, texture, estimate,
         ifi, texts, lengths, status, message) = _core.pf_simulate(z, *typed, speeds.size, npos, len(outputs),
                                                        n_series, ntext, forecast)
        _check(status, message, keywords=True)
        if series and int(counts[1]) != npos:
            # a tolerance run chose finer steps: more positions (run again)
            npos = int(counts[1])
            continue
        if int(lengths.sum()) <= ntext:
            break
        ntext = int(lengths.sum())
    raw = texts.tobytes()[:int(lengths.sum())].decode("utf-8", "replace")
    effects = raw[:lengths[0]]
    warning_text = raw[lengths[0]:lengths[0] + lengths[1]]
    parameters_text = raw[lengths[0] + lengths[1]:]
    coords = {"speed_kmh": ("speed_kmh", speed_kmh.copy(),
                            {"units": "km h-1", "long_name": "sliding speed of the pad"}),
              "speed": ("speed_kmh", speed.copy(),
                        {"units": "m s-1", "long_name": "sliding speed of the pad"})}
    if series:
        coords["position"] = ("position", position.copy(),
                              {"units": "m",
                               "long_name": "distance slid from the first averaged position"})
    dtypes = {1: np.float64, 2: np.int64, 3: np.int32, 4: np.int8}
    data = {}
    slot = -1
    for k, (name, units, long_name, var_type, dims, _, _, description) in enumerate(outputs):
        if not present[k]:
            continue
        if dims != 1:
            slot += 1
        # as the program's file: a few words, the whole description beside
        attrs = {"long_name": long_name}
        if description != long_name:
            attrs["comment"] = description
        if units:
            attrs["units"] = units
        if var_type == 4:
            attrs.update(flag_values=np.array([0, 1], dtype=np.int8), flag_meanings="no yes")
        if dims == 1:
            data[name] = ("speed_kmh", values[:, k].astype(dtypes[var_type]), attrs)
        else:
            data[name] = (("speed_kmh", "position"),
                          np.ascontiguousarray(series_values[:, :, slot].T).astype(
                              dtypes[var_type]),
                          attrs)
    n_el, n_pos, n_spin, has_texture, n_seg, n_valid = (int(c) for c in counts)
    # the scalars, as the core's scalar table declares them (the program's
    # file alike): mpd, rms_height, rms_slope, ifi_f60, ifi_sp, speed_constant
    scalars = dict(zip(("mpd", "rms_height", "rms_slope", "ifi_f60", "ifi_sp",
                        "speed_constant"),
                       ((has_texture, texture[0]), (has_texture, texture[1]),
                        (has_texture, texture[2]), (ifi[0], ifi[1]), (ifi[5], ifi[2]),
                        (ifi[3], ifi[4]))))
    for name, units, long_name, description in _scalar_table():
        present_, value = scalars[name]
        if not present_:
            continue
        attrs = {"units": units, "long_name": long_name}
        if description != long_name:
            attrs["comment"] = description
        if name == "mpd":
            attrs.update(n_segments=n_seg, n_valid_segments=n_valid)
        data[name] = ((), float(value), attrs)
    attrs = {
        "effects": effects,
        "warnings": warning_text,
        "parameters": parameters_text,
        "pavefric_version": _version(),
        "pad_elements": n_el,
        "pad_element_spacing": float(estimate[3]),
        "averaged_positions": n_pos,
        "spinup_positions": n_spin,
        "profile_points": int(z.size),
        "profile_dx": float(dx),
        "profile_closed": int(bool(closed)),
        "estimated_element_steps": float(estimate[0]),
        "estimated_memory_bytes": float(estimate[1]),
        "estimated_seconds": float(estimate[2]),
    }
    attrs.update(_parameter_attributes(parameters_text))
    if warning_text:
        _warn(warning_text)
    return xr.Dataset(data, coords=coords, attrs=attrs)


def _parse_echo(text: str) -> dict[tuple[str, str], Any]:
    """The core's canonical namelist echo (one ``name = value`` a line) as
    typed values keyed by (group, name)."""
    table = {(p.group, p.name): p for p in parameters()}
    out = {}
    group = None
    for line in text.splitlines():
        line = line.strip()
        if line.startswith("&"):
            group = line[1:]
        elif line == "/":
            group = None
        elif "=" in line and group:
            name, value = line.split("=", 1)
            spec = table[(group, name.strip())]
            out[(group, spec.name)] = _value_from_text(spec, value)
    return out


def _parameter_attributes(text: str) -> dict[str, Any]:
    """param_<group>_<name> attributes, as the program writes them."""
    attrs = {}
    for (group, name), value in _parse_echo(text).items():
        if isinstance(value, bool):
            value = int(value)
        elif isinstance(value, list):
            value = np.array(value)
        attrs[f"param_{group}_{name}"] = value
    return attrs


def hydro_load(h_out, h_in: float, prefactor: float = 1.0):
    """Bearing load Wh (N) of Eq. 15 for outlet films ``h_out`` (m), inlet film
    ``h_in`` (m) and prefactor alpha 6 eta V**beta l L**2; returns (Wh, dWh/dHout)."""
    h = np.ascontiguousarray(np.atleast_1d(np.asarray(h_out, dtype=np.float64)))
    wh, dwh = _core.pf_hydro_load(float(prefactor), float(h_in), h)
    return wh, dwh


def run(path: str | os.PathLike, output: str | os.PathLike | None = None,
        progress: bool | None = None) -> Path:
    """Run the scene namelist at ``path`` as the program does.

    A batch scene (with a ``&batch`` group) is computed profile by profile
    through the core, with a progress bar, resuming from the journal of an
    interrupted run.

    Parameters
    ----------
    path : str or os.PathLike
        The scene namelist.
    output : str or os.PathLike, optional
        The NetCDF file to write (default: the scene's ``&output file``).
    progress : bool, optional
        A batch's progress bar on stderr (default: when stderr is a terminal).

    Returns
    -------
    pathlib.Path
        The output written.

    Raises
    ------
    PavefricError
        If the scene is bad or the run fails (nothing is written then).

    Warns
    -----
    PavefricCostWarning
        Before a single scene estimated to take ``ANNOUNCE_SECONDS`` (10 s)
        or more on one thread, with the estimate.
    """
    command = "pavefric.run(" + shlex.quote(str(path)) + (
        f", output={shlex.quote(str(output))})" if output else ")")
    if Path(sys.argv[0]).name == "__main__.py":
        command = "python -m pavefric " + " ".join(shlex.quote(a) for a in sys.argv[1:])
    is_batch, status, message = _core.pf_scene_is_batch(_b(os.fspath(path)))
    _check(status, message)
    if is_batch:
        return _run_batch(str(path), str(output or ""), command, progress)
    forecast = _announce(*_core.pf_scene_estimate(_b(os.fspath(path))))
    out_path, warnings_text, status, message = _core.pf_run_scene(
        _b(os.fspath(path)), _b(os.fspath(output) if output else ""), _b(command), forecast)
    _check(status, message)
    if _text(warnings_text):
        _warn(_text(warnings_text))
    return Path(_text(out_path))


def _run_batch(path: str, output: str, command: str, progress: bool | None) -> Path:
    """The batch through the core in calls of a few profiles each (a progress
    bar between calls). Each call re-reads the journal and checks the
    profiles in it (a cost that grows with the profiles done, about 0.5 % of
    computing them, docs/cluster.md), so a call computes at least an eighth
    of the profiles done, and about half a second of work."""
    import time

    if progress is None:
        progress = sys.stderr.isatty()
    bar = _ProgressBar(progress)
    chunk = 1
    while True:
        t0 = time.perf_counter()
        (out_path, computed, finished, total, done, status, message) = _core.pf_batch_run(
            path, output, command, chunk)
        _check(status, message)
        dt = time.perf_counter() - t0
        bar.update(int(done), int(total))
        if finished:
            bar.close()
            out = Path(_text(out_path))
            _warn_failed_profiles(path, out)
            return out
        if computed == 0:
            raise PavefricError(f"batch {path}: no progress (max_profiles reached?)")
        timed = int(chunk * max(0.5, min(4.0, 0.5 / max(dt, 1e-6))))
        chunk = max(1, min(int(total), max(timed, int(done) // 8)))


def _warn_failed_profiles(path: str, out: Path) -> None:
    """A ProfilesFailedWarning naming the failed profiles, if any; then a
    PavefricWarning for each of the scene's own warnings and one naming the
    profiles with warnings (n_warnings, warning_message), if any."""
    import warnings

    import xarray as xr

    with xr.open_dataset(out, engine="netcdf4") as ds:
        total = ds.sizes["profile"]
        bad = np.flatnonzero(ds["status"].values == 2)
        failed = {str(ds["profile_name"].values[i]): str(ds["error_message"].values[i])
                  for i in bad}
        scene_warnings = str(ds.attrs.get("warnings", "")).splitlines()
        warned, first, n_all = np.zeros(0, dtype=int), [], 0
        if "n_warnings" in ds.variables:
            warned = np.flatnonzero(ds["n_warnings"].values > 0)
            first = [f"{ds['profile_name'].values[i]}: "
                     f"{str(ds['warning_message'].values[i]).splitlines()[0]}"
                     for i in warned[:3]]
            n_all = int(ds["n_warnings"].values.sum())
    if failed:
        shown = "; ".join(f"{n}: {m}" for n, m in list(failed.items())[:5])
        more = f"; ... {len(failed) - 5} more" if len(failed) > 5 else ""
        warnings.warn(ProfilesFailedWarning(
            f"batch {path}: {len(failed)} of {total} profiles failed (status = 2 and "
            f"error_message in {out}): {shown}{more}", out, failed), stacklevel=4)
    for line in scene_warnings:
        warnings.warn(PavefricWarning(line), stacklevel=4)
    if warned.size:
        more = f"; ... {warned.size - 3} more" if warned.size > 3 else ""
        warnings.warn(PavefricWarning(
            f"batch {path}: {warned.size} of {total} profiles have warnings ({n_all} in all; "
            f"n_warnings and warning_message in {out}): {'; '.join(first)}{more}"),
            stacklevel=4)


class _ProgressBar:
    """tqdm when installed, else a one-line text bar on stderr."""

    def __init__(self, enabled: bool):
        self.enabled = enabled
        self._tqdm = None
        self._done = 0
        if enabled:
            try:
                from tqdm import tqdm
                self._tqdm = tqdm(unit="profile", desc="pavefric batch")
            except ImportError:
                self._tqdm = None

    def update(self, done: int, total: int) -> None:
        if not self.enabled:
            return
        if self._tqdm is not None:
            self._tqdm.total = total
            self._tqdm.update(done - self._done)
        else:
            width = 30
            fill = int(width * done / max(total, 1))
            sys.stderr.write(f"\rpavefric batch [{'#' * fill}{'.' * (width - fill)}] "
                             f"{done}/{total}")
            sys.stderr.flush()
        self._done = done

    def close(self) -> None:
        if not self.enabled:
            return
        if self._tqdm is not None:
            self._tqdm.close()
        else:
            sys.stderr.write("\n")


# A global attribute too long for HDF5's attribute storage is written as a
# character variable of its name; the attribute then begins with this note
# (src/io/pavefric_netcdf.f90, long_text_note).
LONG_TEXT_NOTE = "in the variable of this name: "


def restore_long_attributes(ds):
    """Put the texts pavefric wrote as variables (attributes longer than
    HDF5 allows, e.g. a 200 KB scene in ``input_namelist``) back into
    ``ds.attrs``, and drop those variables. Returns ``ds``."""
    for name, value in list(ds.attrs.items()):
        if isinstance(value, str) and value.startswith(LONG_TEXT_NOTE) and name in ds.variables:
            text = ds[name].values
            if text.dtype.kind == "S":
                text = b"".join(np.atleast_1d(text).ravel()).decode("utf-8", "replace")
            ds.attrs[name] = str(text.item() if hasattr(text, "item") and
                                 not isinstance(text, str) else text)
            ds = ds.drop_vars(name)
    return ds


# Texts longer than this (bytes) are stored as variables (LONG_TEXT_NOTE).
LONG_TEXT_LIMIT = 16384


def store_long_attributes(ds):
    """The inverse of ``restore_long_attributes``, for Python's writers: each
    global text attribute longer than LONG_TEXT_LIMIT becomes a character
    variable of its name, the attribute saying where (the core's own
    convention, src/io/pavefric_netcdf.f90). Returns a new dataset."""
    ds = ds.copy()
    for name, value in list(ds.attrs.items()):
        if isinstance(value, str) and len(value.encode("utf-8")) > LONG_TEXT_LIMIT:
            raw = np.frombuffer(value.encode("utf-8"), dtype="S1")
            ds[name] = (f"{name}_strlen",), raw, {
                "long_name": f"the global attribute {name}, too long for an attribute"}
            ds[name].encoding = {"dtype": "S1"}
            ds.attrs[name] = f"{LONG_TEXT_NOTE}{raw.size} characters"
    return ds


def open_dataset(path: str | os.PathLike):
    """Read a pavefric NetCDF output into memory.

    Long attributes, stored as variables, are restored
    (``restore_long_attributes``). ``pavefric.open`` is the same function.

    Parameters
    ----------
    path : str or os.PathLike
        A scene's or a batch's output file.

    Returns
    -------
    xarray.Dataset
        The file's variables and attributes, loaded (the file is closed).

    Raises
    ------
    FileNotFoundError
        If there is no such file.
    """
    import xarray as xr

    with xr.open_dataset(path, engine="netcdf4") as ds:
        return _text_coordinates(restore_long_attributes(ds.load()))


def _text_coordinates(ds):
    """Text coordinates (a batch's profile names) as NumPy unicode rather
    than Python objects, and an index on ``profile_name``, so that
    ``ds.sel(profile_name="seg_0042")`` selects a profile by name (the
    dimension's own coordinate, ``profile``, numbers them 1, 2, ...)."""
    for name, coord in ds.coords.items():
        if coord.dtype == object and all(isinstance(v, str) for v in coord.values.ravel()):
            ds = ds.assign_coords({name: coord.copy(data=coord.values.astype(str))})
    if "profile_name" in ds.coords and ds["profile_name"].dims == ("profile",) \
            and "profile_name" not in ds.indexes:
        ds = ds.set_xindex("profile_name")
    return ds


@dataclass
class Scene:
    """A scene namelist as the core reads it (``load_scene``).

    Parameters
    ----------
    name : str
        The scene's name (its file's stem).
    heights : numpy.ndarray
        The profile's heights (m), preprocessed as the scene says.
    dx : float
        Their spacing (m).
    closed : bool
        A closed Circular Track Meter circle (True) or an open profile.
    speeds_kmh : numpy.ndarray
        The sliding speeds (km/h).
    parameters : dict
        The model parameters as ``simulate`` keywords (SI units).
    series : bool
        Whether per-position series are written.
    profile_file : str
        The profile file the scene reads.
    output_file : str
        The scene's output file (``&output file``).
    """

    name: str
    heights: np.ndarray
    dx: float
    closed: bool
    speeds_kmh: np.ndarray
    parameters: dict
    series: bool
    profile_file: str
    output_file: str

    def simulate(self, speeds_kmh=None, series=None, **overrides):
        """Run this scene through ``simulate`` (parameters may be overridden)."""
        params = {**self.parameters, **overrides}
        return simulate(self.heights, self.dx,
                        self.speeds_kmh if speeds_kmh is None else speeds_kmh,
                        closed=self.closed, series=self.series if series is None else series,
                        **params)


def load_scene(path: str | os.PathLike) -> Scene:
    """Read a scene namelist and its profile with the core's readers.

    ``parameters`` holds the scene's model variables (every ``simulate``
    keyword, defaults included) exactly as the core read them, so
    ``scene.simulate()`` gives the program's numbers bit for bit.

    Parameters
    ----------
    path : str or os.PathLike
        The scene namelist.

    Returns
    -------
    Scene
        The profile, speeds and parameters.

    Raises
    ------
    PavefricError
        If the scene or its profile is missing or bad (the message names the
        group, the variable and the value).
    """
    (np_, ns, dx, closed, series, ntext, profile_file, output_file,
     status, message) = _core.pf_scene_info(_b(os.fspath(path)))
    _check(status, message)
    z, speeds, text, status, message = _core.pf_scene_arrays(_b(os.fspath(path)), int(np_), int(ns),
                                                             int(ntext))
    _check(status, message)
    values = _parse_echo(text.tobytes().decode("utf-8"))
    params = {k: values[(p.group, p.name)] for k, p in _keywords("model").items()
              if (p.group, p.name) in values}
    return Scene(name=Path(path).stem, heights=z.copy(), dx=float(dx), closed=bool(closed),
                 speeds_kmh=speeds.copy(), parameters=params, series=bool(series),
                 profile_file=_text(profile_file), output_file=_text(output_file))


@dataclass
class Profile:
    """A profile as the core reads and preprocesses it (``read_profile``).

    Parameters
    ----------
    heights : numpy.ndarray
        Heights (m) at spacing ``dx``, fit for analysis.
    dx : float
        Spacing of ``heights`` (m).
    path : str
        The file read.
    report : dict
        What preprocessing did (points read, trimmed, dropouts, ...;
        ``chainage`` (m) for a NetCDF profile).
    raw_x : numpy.ndarray
        The file's positions (m), for checking.
    raw_heights : numpy.ndarray
        The file's heights (m), NaN at dropouts.
    dropout_fraction : numpy.ndarray
        Per sample of ``heights``: the fraction interpolated over dropouts.
    spike : numpy.ndarray
        Per sample of ``heights``: whether it was a spike (texture validity).
    """

    heights: np.ndarray
    dx: float
    path: str
    report: dict
    raw_x: np.ndarray
    raw_heights: np.ndarray
    dropout_fraction: np.ndarray
    spike: np.ndarray


_init_keywords()
