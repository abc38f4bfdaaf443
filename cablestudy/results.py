"""Assembly of case records into one labelled xarray Dataset, and atomic netCDF writes.

Every output variable is declared once in :data:`OUTPUTS` with its extra dimensions,
units and long name; solvers add variables by adding entries here.
"""

from __future__ import annotations

import json
import os
import tempfile
from dataclasses import dataclass, field
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from . import __version__
from .cases import Case, SweepAxis
from .config.loader import StudySource


@dataclass(frozen=True)
class OutputVariable:
    dims: tuple[str, ...]
    units: str
    long_name: str
    dtype: str = "float64"


#: every data variable a case may produce: name -> extra dims, units, long name
OUTPUTS: dict[str, OutputVariable] = {
    "x": OutputVariable(("s",), "m", "x position along the line"),
    "y": OutputVariable(("s",), "m", "y position along the line"),
    "z": OutputVariable(("s",), "m", "z position (up) along the line"),
    "tension": OutputVariable(("s",), "N", "effective tension along the line"),
    "arc_length": OutputVariable(("s",), "m", "unstretched arc length from end A"),
    "force_a": OutputVariable(("component",), "N", "force of the line on the attachment at end A"),
    "force_b": OutputVariable(("component",), "N", "force of the line on the attachment at end B"),
    "tension_a": OutputVariable((), "N", "tension at end A"),
    "tension_b": OutputVariable((), "N", "tension at end B"),
    "laid_length": OutputVariable((), "m", "unstretched length resting on the seabed"),
    "static_iterations": OutputVariable((), "1", "iterations of the static solver", "int64"),
    "static_residual": OutputVariable((), "1", "final relative residual of the static solver"),
    # dynamics (cablestudy.dynamics.timedomain): tensions at the excited end over the
    # steady-state window (the envelope of the last periods when steady_converged is 0)
    "tension_static": OutputVariable(
        (), "N", "static tension at the excited end (dynamic model)"),
    "tension_max": OutputVariable((), "N", "maximum tension at the excited end, steady window"),
    "tension_min": OutputVariable((), "N", "minimum tension at the excited end, steady window"),
    "tension_mean": OutputVariable((), "N", "mean tension at the excited end, steady window"),
    "tension_max_line": OutputVariable((), "N", "maximum tension along the line, steady window"),
    "tension_max_spread": OutputVariable(
        (), "N", "range of the per-period maximum end tension over the last periods"),
    "tension_min_spread": OutputVariable(
        (), "N", "range of the per-period minimum end tension over the last periods"),
    "steady_converged": OutputVariable(
        (), "1", "1 if the per-period max/min tension settled within the tolerance", "int64"),
    "periods": OutputVariable((), "1", "excitation periods simulated"),
    "dynamic_steps": OutputVariable((), "1", "accepted time steps", "int64"),
    "newton_iterations": OutputVariable((), "1", "Newton iterations of the time steps", "int64"),
    "rejected_steps": OutputVariable((), "1", "rejected (retried shorter) time steps", "int64"),
    "dynamic_method": OutputVariable((), "", "dynamic method used (time | frequency)", "str"),
    "history_time": OutputVariable(("time",), "s", "time of the history samples"),
    "history_tension": OutputVariable(("time",), "N", "tension at the excited end"),
    "history_point_s": OutputVariable(("point",), "m", "arc length of the history points"),
    "history_displacement": OutputVariable(
        ("point", "time", "component"), "m", "displacement of the point from its static position"),
    "history_velocity": OutputVariable(
        ("point", "time", "component"), "m/s", "velocity of the point"),
    "history_acceleration": OutputVariable(
        ("point", "time", "component"), "m/s^2", "acceleration of the point"),
}

#: per-case bookkeeping variables (always present)
CASE_VARIABLES: dict[str, OutputVariable] = {
    "status": OutputVariable((), "1", "case status: 0 ok, nonzero failed", "int64"),
    "message": OutputVariable((), "", "why the case failed (empty when ok)", "str"),
    "wall_time": OutputVariable((), "s", "wall time of the case"),
}

COORDINATES: dict[str, tuple[str, str]] = {
    "s": ("m", "unstretched arc length from end A"),
    "component": ("", "vector component"),
}


@dataclass
class CaseRecord:
    """What one case produced: data arrays by output name, status, message, wall time."""

    hash: str
    index: tuple[int, ...]
    status: int
    message: str
    wall_time: float
    data: dict[str, np.ndarray] = field(default_factory=dict)
    settings: dict[str, Any] = field(default_factory=dict)


def _fill(dtype: str) -> Any:
    return {"int64": -1, "str": ""}.get(dtype, np.nan)


def assemble(
    axes: list[SweepAxis], cases: list[Case], records: dict[str, CaseRecord], src: StudySource,
    *, solver_settings: dict[str, Any] | None = None,
) -> xr.Dataset:
    """One Dataset on the sweep axes. A failed case is NaN (or -1 for counters) in its
    data variables, never dropped."""
    shape = tuple(a.size for a in axes)
    dims = tuple(a.name for a in axes)
    by_index = {c.index: records[c.hash] for c in cases}
    present = sorted({k for r in by_index.values() for k in r.data})
    unknown = [k for k in present if k not in OUTPUTS]
    if unknown:
        raise KeyError(f"output variables not declared in results.OUTPUTS: {unknown}")

    # lengths of extra dims: the largest any case produced
    extent: dict[str, int] = {"component": 3}
    for rec in by_index.values():
        for name, arr in rec.data.items():
            for d, n in zip(OUTPUTS[name].dims, np.shape(arr), strict=True):
                extent[d] = max(extent.get(d, 0), n)

    data_vars: dict[str, Any] = {}
    for name, spec in {**CASE_VARIABLES, **{k: OUTPUTS[k] for k in present}}.items():
        full_shape = shape + tuple(extent[d] for d in spec.dims)
        dtype = object if spec.dtype == "str" else spec.dtype
        arr = np.full(full_shape, _fill(spec.dtype), dtype=dtype)
        for idx, rec in by_index.items():
            if name in CASE_VARIABLES:
                arr[idx] = getattr(rec, name)
            elif name in rec.data and rec.status == 0:
                val = np.asarray(rec.data[name])
                arr[idx + tuple(slice(0, n) for n in val.shape)] = val
        data_vars[name] = (dims + spec.dims, arr, {"units": spec.units, "long_name": spec.long_name})

    coords: dict[str, Any] = {}
    for a in axes:
        attrs = {"units": a.units or "1", "long_name": a.long_name, "sweep_paths": ", ".join(a.paths)}
        coords[a.name] = (a.name, a.coordinate(), attrs)
        if len(a.paths) > 1:
            for path, vals in zip(a.paths, a.values, strict=True):
                if all(isinstance(v, int | float) and not isinstance(v, bool) for v in vals):
                    cname = f"{a.name}_{path.split('.')[-1]}"
                    coords[cname] = (a.name, np.asarray(vals, dtype=float),
                                     {"long_name": path, "units": ""})
    if "component" in extent and any("component" in OUTPUTS[k].dims for k in present):
        coords["component"] = ("component", np.array(["x", "y", "z"]),
                               {"long_name": COORDINATES["component"][1]})
    if "s" in extent:
        arcs = [np.asarray(r.data["arc_length"]) for r in by_index.values()
                if "arc_length" in r.data and r.status == 0]
        if arcs and all(len(a) == extent["s"] and np.array_equal(a, arcs[0]) for a in arcs):
            coords["s"] = ("s", arcs[0], {"units": "m", "long_name": COORDINATES["s"][1]})
            data_vars.pop("arc_length", None)
    if "arc_length" in data_vars and "s" not in coords:
        coords["s"] = ("s", np.arange(extent["s"]), {"units": "1", "long_name": "node index"})

    ds = xr.Dataset(data_vars, coords=coords)
    ds.attrs.update(provenance(src, solver_settings or {}))
    n_failed = int(np.count_nonzero(ds["status"].values != 0))
    ds.attrs["cases"] = int(np.prod(shape)) if shape else 1
    ds.attrs["cases_failed"] = n_failed
    return ds


def provenance(src: StudySource, solver_settings: dict[str, Any]) -> dict[str, Any]:
    import numpy
    import scipy

    return {
        "Conventions": "CF-1.8",
        "title": str(src.data.get("name", "")),
        "study_name": str(src.data.get("name", "")),
        "study_description": str(src.data.get("description", "")),
        "study_yaml": src.text,
        "study_sha256": src.sha256,
        "cablestudy_version": __version__,
        "numpy_version": numpy.__version__,
        "scipy_version": scipy.__version__,
        "xarray_version": xr.__version__,
        "solver_settings": json.dumps(solver_settings, sort_keys=True),
        "history": f"{datetime.now(UTC).isoformat(timespec='seconds')} cablestudy run",
    }


def write_atomic(ds: xr.Dataset, path: str | Path) -> Path:
    """Write ``ds`` to netCDF at ``path`` through a temporary file in the same folder and
    an atomic rename: a crash never leaves a half-written or corrupted result."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    os.close(fd)
    try:
        encoding = {name: {"zlib": True, "complevel": 4} for name, v in ds.data_vars.items()
                    if v.dtype.kind == "f"}
        ds.to_netcdf(tmp, engine="netcdf4", encoding=encoding)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)
    return path
