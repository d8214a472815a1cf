"""Merge batch outputs of one survey run in parts (SLURM job arrays, one
batch per part) into one NetCDF file: ``python -m pavefric merge``.

A survey split in parts (each a batch scene over its own profiles, with the
same physics, depths and speeds) gives one output per part; this joins them
along ``profile``, in the order given. It is bookkeeping, not physics: every
value is copied, none computed. It refuses parts that ran other physics
(the parameters they used differ outside ``&batch`` and ``&output``: the
core's text of each value, so two spellings of one number agree; the
variable is named), other depths or speeds, or that share a profile name,
naming the files and what differs. The merged file's ``effects`` are those
that ran in any part (a part whose profiles all failed ran none).
docs/cluster.md ("A survey of a million profiles") shows where it fits.
"""
from __future__ import annotations

import os
import re
from pathlib import Path
from typing import Sequence

import numpy as np

# global attributes that differ from part to part by nature (the scenes and
# the parameters used, compared by _scene_difference; the effects that ran,
# which depend on the profiles: joined)
_PER_PART = {"history", "title", "input_namelist", "parameters", "profiles_computed",
             "profiles_failed", "profiles_with_warnings", "date_created", "effects"}
_PER_PART_PREFIXES = ("param_batch_", "param_output_")
_COUNTS = ("profiles_computed", "profiles_failed", "profiles_with_warnings")


class MergeError(ValueError):
    """Parts that cannot be merged (the message says which and why)."""


def _physics(namelist: str) -> str:
    """A scene's text without comments, blank differences and the groups
    that differ between the parts of one survey (&batch, &output): what the
    parts must share. Quotes are respected ('!' and '/' inside a quoted path
    are text)."""
    kept, quote, skipping, k, n = [], None, False, 0, len(namelist)
    while k < n:
        ch = namelist[k]
        if quote:
            if not skipping:
                kept.append(ch)
            if ch == quote:
                quote = None
        elif ch in "'\"":
            quote = ch
            if not skipping:
                kept.append(ch)
        elif ch == "!":                            # a comment, to the end of the line
            end = namelist.find("\n", k)
            k = n if end < 0 else end
            continue
        elif ch in "&$" and not skipping:
            m = re.match(r"[&$]([A-Za-z_]\w*)", namelist[k:])
            if m and m.group(1).lower() in ("batch", "output"):
                skipping = True
                k += m.end()
                continue
            kept.append(ch)
        elif skipping and ch == "/":
            skipping = False
        elif not skipping:
            kept.append(ch)
        k += 1
    return " ".join("".join(kept).split()).lower()


def merge(parts: Sequence[str | os.PathLike], output: str | os.PathLike) -> Path:
    """Join the batch outputs ``parts`` along ``profile`` into ``output``.

    Parameters
    ----------
    parts : sequence of path-like
        Batch outputs of the program (or ``pavefric.run``), in the order
        their profiles should appear.
    output : path-like
        The merged file; written under a temporary name in its directory and
        renamed when complete. It may not be one of the parts.

    Returns
    -------
    pathlib.Path
        The merged file.

    Raises
    ------
    MergeError
        When the parts ran different physics, depths or speeds, share a
        profile, are not batch outputs, or the output is one of them.
    """
    import xarray as xr

    from .core import (PavefricError, atomic_output, check_output, restore_long_attributes,
                       store_long_attributes)

    paths = [Path(p) for p in parts]
    if not paths:
        raise MergeError("merge: no parts given")
    out = Path(output)
    for p in paths:
        if not p.is_file():
            raise MergeError(f"merge: '{p}' is not a file")
    try:        # the rule of every pavefric writer: never over an input, a FIFO, a device
        check_output(out, paths, replaces="results", writable=True)
    except PavefricError as exc:
        raise MergeError(f"merge: {exc}") from None

    sets, opened = [], []
    try:
        for p in paths:
            try:
                ds = xr.open_dataset(p, mask_and_scale=False, decode_times=False)
            except (OSError, ValueError) as exc:
                raise MergeError(f"merge: cannot read '{p}' as NetCDF ({exc})") from None
            opened.append(ds)
            sets.append(restore_long_attributes(ds))  # a long scene is a variable, not an attribute
        first = sets[0]
        for p, ds in zip(paths, sets):
            if "profile" not in ds.dims:
                raise MergeError(f"merge: '{p}' is not a batch output (no 'profile' dimension)")
        names: dict[str, Path] = {}
        for p, ds in zip(paths, sets):
            why = _scene_difference(first, ds)
            if why:
                raise MergeError(f"merge: '{p}' ran another scene than '{paths[0]}' ({why})")
            for name in set(first.variables) ^ set(ds.variables):
                raise MergeError(f"merge: '{name}' is in only one of '{paths[0]}' and '{p}'")
            for name, var in ds.variables.items():
                if "profile" in var.dims:
                    continue
                if not np.array_equal(var.values, first[name].values):
                    raise MergeError(f"merge: '{name}' differs between '{paths[0]}' and '{p}'")
            for name, value in ds.attrs.items():
                # (param_*: the parameters used, compared above; a part
                # written before they were recorded has none)
                if name in _PER_PART or name.startswith("param_"):
                    continue
                if str(first.attrs.get(name)) != str(value):
                    raise MergeError(f"merge: the attribute '{name}' differs between "
                                     f"'{paths[0]}' and '{p}'")
            for name in _profile_names(ds):
                if name in names:
                    raise MergeError(f"merge: the profile '{name}' is in both '{names[name]}' "
                                     f"and '{p}'")
                names[name] = p

        merged = xr.concat([ds.drop_vars([v for v in ds.variables if "profile" not in
                                          ds[v].dims]) for ds in sets], dim="profile",
                           data_vars="all", coords="minimal", compat="equals",
                           combine_attrs="override")
        for name, var in first.variables.items():
            if "profile" not in var.dims:
                merged[name] = var
        merged = merged[list(first.variables)]
        # the profile numbers run on across the parts: 1, 2, ..., N
        merged = merged.assign_coords(profile=merged["profile"].copy(
            data=np.arange(1, merged.sizes["profile"] + 1, dtype=first["profile"].dtype)))
        for name in first.variables:               # keep each variable's own encoding
            merged[name].attrs = dict(first[name].attrs)
            # an integer variable has a _FillValue only in a part where a profile
            # failed: the merged file has it if any part has it
            for ds in sets:
                if "_FillValue" in ds[name].attrs and "_FillValue" not in merged[name].attrs:
                    merged[name].attrs["_FillValue"] = ds[name].attrs["_FillValue"]
            merged[name].encoding = {k: v for k, v in first[name].encoding.items()
                                     if k in ("dtype", "_FillValue", "zlib", "complevel",
                                              "shuffle", "contiguous", "char_dim_name")}
            if merged[name].dtype.kind in "SU":
                merged[name].encoding.pop("dtype", None)
        merged.attrs = dict(first.attrs)
        # the effects that ran in any part (a film or the rubber's memory
        # runs only where a profile calls for it; a part whose profiles all
        # failed ran none), in the order they first appear
        effects: list[str] = []
        for ds in sets:
            effects += [e for e in str(ds.attrs.get("effects", "")).split(",")
                        if e and e not in effects]
        merged.attrs["effects"] = ",".join(effects)
        for key in _COUNTS:
            if key in first.attrs:
                merged.attrs[key] = int(sum(int(ds.attrs.get(key, 0)) for ds in sets))
        merged.attrs["input_namelist"] = str(first.attrs.get("input_namelist", ""))
        merged.attrs["history"] = "\n".join(
            [f"pavefric merge of {len(paths)} parts: " + " ".join(str(p) for p in paths)] +
            [str(ds.attrs.get("history", "")) for ds in sets])
        merged.attrs["merged_parts"] = " ".join(str(p) for p in paths)
        with atomic_output(out, paths, replaces="results") as tmp:
            store_long_attributes(merged).to_netcdf(tmp, format="NETCDF4")
    finally:
        for ds in opened:
            ds.close()
    return out


def _scene_difference(a, b) -> str:
    """How two parts' scenes differ outside &batch and &output ('' where they
    do not). By the parameters used where both parts record them: the
    core's own text of every value, so `0.6000000000000001` and
    `6.000000000000001e-1` agree, and the variable that differs is named;
    else (files of versions before them) by the scenes' text."""
    if "parameters" in a.attrs and "parameters" in b.attrs:
        if _physics(str(a.attrs["parameters"])) == _physics(str(b.attrs["parameters"])):
            return ""
        typed = [k for k in set(a.attrs) | set(b.attrs)
                 if k.startswith("param_") and not k.startswith(_PER_PART_PREFIXES)]
        for key in sorted(typed):
            if key not in a.attrs or key not in b.attrs or not np.array_equal(
                    np.asarray(a.attrs[key]), np.asarray(b.attrs[key])):
                group, name = key[len("param_"):].split("_", 1)
                return (f"&{group} {name}: {_shown(a.attrs.get(key))} against "
                        f"{_shown(b.attrs.get(key))}")
        return "their parameters used differ outside &batch and &output"
    if _physics(str(a.attrs.get("input_namelist", ""))) != \
            _physics(str(b.attrs.get("input_namelist", ""))):
        return "their namelists differ outside &batch and &output"
    return ""


def _shown(value) -> str:
    if value is None:
        return "not set"
    v = np.asarray(value)
    return str(v.tolist()) if v.ndim else str(v.item())


def _profile_names(ds) -> list[str]:
    values = ds["profile_name"].values
    if values.dtype.kind == "S" and values.ndim == 2:          # char(profile, strlen)
        return [b"".join(row).decode("utf-8").rstrip("\x00 ") for row in values]
    return [v.decode("utf-8") if isinstance(v, bytes) else str(v) for v in values]
