"""Assembly of case records (or a grid's chunk arrays) into one labelled dataset on the
sweep axes, with the coordinates, the CF status flags and the provenance attributes
that trace it to its inputs. The variables are declared in
:mod:`cablestudy.analyses.variables`; the writing is :mod:`cablestudy.run.writer`'s.
"""

from __future__ import annotations

import functools
import json
from datetime import UTC, datetime
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from .. import __version__
from ..analyses.variables import (
    BODY_DOFS,
    CASE_VARIABLES,
    COORDINATES,
    DATABASE_LAYOUTS,
    FEWER_MODES,
    OUTPUTS,
    STATUS_BROKEN,
    SYSTEM_OUTPUTS,
)
from ..study.cases import SweepAxis
from ..study.line_types import line_type_attrs
from ..study.loader import StudySource
from .conventions import command_line, is_status_variable, status_flag_attrs
from .writer import VariableSpec

if TYPE_CHECKING:  # imported where used: a sweep run as arrays writes without xarray
    import xarray as xr


def sweep_coordinates(axes: list[SweepAxis]) -> dict[str, Any]:
    """The coordinates of the sweep dimensions (and, for axes of non-scalar values, zip
    groups or labels, their value coordinates), with units and long names. An axis with
    labels has them as its coordinate; its values go to ``<dim>_value``."""
    coords: dict[str, Any] = {}
    for a in axes:
        numeric = a.coordinate().dtype.kind in "iuf"
        indexed = len(a.paths) > 1 or not all(
            isinstance(v, int | float | str | bool) for v in a.values[0]
        )
        attrs = {
            "units": (a.units or "1") if numeric else "1",
            "long_name": a.long_name,
            "sweep_paths": ", ".join(a.paths),
        }
        if a.labels is not None:
            attrs["units"] = "1"
            attrs["long_name"] = a.long_name or f"label of the swept value of {a.paths[0]}"
        elif indexed:
            attrs["units"] = "1"
            if len(a.paths) == 1:
                attrs["long_name"] = f"index of the swept value of {a.paths[0]}"
        coords[a.name] = (a.name, a.coordinate(), attrs)
        if len(a.paths) == 1 and a.labels is not None and not indexed:
            # labelled scalars: the values themselves beside the labels
            values = np.asarray(a.values[0])
            scalar_units = (a.units or "1") if values.dtype.kind in "iuf" else "1"
            coords[f"{a.name}_value"] = (
                a.name,
                values.astype(object) if values.dtype.kind == "U" else values,
                {"long_name": a.long_name, "units": scalar_units},
            )
        if len(a.paths) == 1 and indexed:
            # values that are not scalars (vectors, mappings): keep them as text
            coords[f"{a.name}_value"] = (
                a.name,
                np.array([json.dumps(v) for v in a.values[0]], dtype=object),
                {"long_name": f"swept value of {a.paths[0]} (JSON)", "units": "1"},
            )
        if len(a.paths) > 1:
            for path, vals in zip(a.paths, a.values, strict=True):
                cname = f"{a.name}_{path.split('.')[-1]}"
                if cname in coords or cname == a.name:
                    cname = f"{a.name}_{path.replace('.', '_')}"
                units, long_name = _path_info(path)
                if all(isinstance(v, int | float) and not isinstance(v, bool) for v in vals):
                    coords[cname] = (
                        a.name,
                        np.asarray(vals, dtype=float),
                        {"long_name": long_name, "units": units or "1"},
                    )
                else:
                    coords[cname] = (
                        a.name,
                        np.array([json.dumps(v) for v in vals], dtype=object),
                        {"long_name": f"{long_name} (JSON)", "units": "1"},
                    )
    return coords


def chunk_variables(
    axes: list[SweepAxis],
    src: StudySource,
    chunk: Any,
    summary: Any = None,
    *,
    solver_settings: dict[str, Any] | str,
    named: dict[str, list[str]] | None = None,
    static_status: bool = False,
) -> tuple[dict[str, VariableSpec], dict[str, VariableSpec], dict[str, Any]]:
    """The (data variables, coordinates, attributes) of the dataset of every case of the
    study held in memory as one :class:`cablestudy.analyses.grid_chunk.GridChunk` (its
    rows in C order of the grid): :func:`grid_variables` on its arrays shaped as the
    grid. ``static_status``: the case's status is its static analysis's (a static grid:
    no ``static_status`` of its own). ``summary``: the chunk's
    (:func:`cablestudy.run.cache.summarise`), if known."""
    if summary is None:
        from .cache import summarise

        summary = summarise([chunk])
    shape = tuple(a.size for a in axes)
    values = {
        name: arr.reshape(shape + arr.shape[1:])
        for name, arr in chunk.data.items()
        if not (name == "arc_length" and summary.arc is not None)
    }
    return grid_variables(
        axes,
        src,
        status=chunk.status,
        message=chunk.message,
        warning=chunk.warning,
        wall_time=chunk.wall_time,
        values=values,
        tails=summary.tails,
        arc=summary.arc,
        solver_settings=solver_settings,
        fallbacks=summary.fallbacks,
        named=named,
        static_status=static_status,
    )


def fallback_attrs(fallbacks: dict[str, int]) -> dict[str, Any]:
    """The ``cases_fallback`` and ``fallback_reasons`` attributes: how many cases the
    general solver solved (no batch kernel took them), and why, most frequent first."""
    return {
        "cases_fallback": int(sum(fallbacks.values())),
        "fallback_reasons": "; ".join(
            f"{n} x {why}" for why, n in sorted(fallbacks.items(), key=lambda kv: -kv[1])
        ),
    }


def _flag_statuses(data_vars: dict[str, Any]) -> None:
    """Add the CF status flags (:func:`status_flag_attrs`) to the status variables among
    ``data_vars`` (name -> (dims, values, attrs)), in place."""
    for name, (dims, values, var_attrs) in list(data_vars.items()):
        dtype = getattr(values, "dtype", None)
        if is_status_variable(name) and dtype is not None and dtype.kind in "if":
            data_vars[name] = (dims, values, {**var_attrs, **status_flag_attrs(dtype)})


def _path_info(path: str) -> tuple[str, str]:
    from ..study.cases import _field_info

    return _field_info(tuple(path.split(".")))


@functools.cache
def installed_version(name: str) -> str:
    """The version of the installed distribution ``name``, the string
    :func:`importlib.metadata.version` gives: the ``Version`` header of its metadata,
    read from the headers alone (``version`` parses the whole file, scipy's licences
    included: some 60 kB through the e-mail parser, a few ms a run), once a process."""
    from importlib.metadata import distribution, version

    text = distribution(name).read_text("METADATA") or ""
    for line in text.splitlines():
        if not line.strip():  # the end of the headers
            break
        key, colon, value = line.partition(":")
        if colon and key.strip().lower() == "version":
            return value.strip()
    return version(name)


def provenance(src: StudySource, solver_settings: dict[str, Any] | str) -> dict[str, Any]:
    """Global attributes that trace a dataset to its inputs: the study YAML and its hash,
    package versions, the solver-code fingerprint and the solver settings (or their JSON
    text, sorted keys: :func:`cablestudy.run.grid_runner.grid_settings`)."""
    import platform

    import numpy
    import pydantic

    from ..study.cases import code_fingerprint

    return {
        "Conventions": "CF-1.8",
        "title": str(src.data.get("name", "")),
        "study_name": str(src.data.get("name", "")),
        "study_description": str(src.data.get("description", "")),
        "study_yaml": src.text,
        "study_sha256": src.sha256,
        "cablestudy_version": __version__,
        "numpy_version": numpy.__version__,
        # from the installed metadata: the same strings as scipy.__version__ and
        # xarray.__version__, without importing them (the array path needs neither)
        "scipy_version": installed_version("scipy"),
        "xarray_version": installed_version("xarray"),
        "pydantic_version": pydantic.VERSION,
        "dask_version": installed_version("dask"),
        "python_version": platform.python_version(),
        "cablestudy_code_sha256": code_fingerprint(),
        "solver_settings": solver_settings
        if isinstance(solver_settings, str)
        else json.dumps(solver_settings, sort_keys=True),
        "history": f"{datetime.now(UTC).isoformat(timespec='seconds')}: {command_line()}",
        **line_type_attrs(src),
    }


def grid_dataset(
    axes: list[SweepAxis],
    chunks: list[tuple[int, int, Path]],
    src: StudySource,
    *,
    names: list[str],
    tails: dict[str, tuple[int, ...]],
    arc: np.ndarray | None,
    solver_settings: dict[str, Any] | str,
    fallbacks: dict[str, int] | None = None,
    named: dict[str, list[str]] | None = None,
) -> xr.Dataset:
    """The dataset of a study run as arrays (:mod:`cablestudy.analyses.static_grid`), with the same
    variables, dims, coordinates and attributes as :func:`chunk_variables` would give,
    its large variables backed lazily (dask) by the chunk files ``(lo, hi, path)`` (rows
    ``lo:hi`` of the first axis each, written by the runner), so that writing it streams
    chunk by chunk. ``arc``: the arc lengths every successful case shares (then the
    ``s`` coordinate), or None (then ``arc_length`` stays a variable and ``s`` is the
    node index)."""
    import dask
    import dask.array as da
    import xarray as xr

    shape = tuple(a.size for a in axes)
    rest = shape[1:]

    def load(path: Path, name: str) -> np.ndarray:
        with np.load(path, allow_pickle=False) as z:
            key = f"v_{name}"
            if key in z.files:
                return z[key]
            n = len(z["v_status"])
            if name == "warning":  # a chunk with no warnings may not store the column
                return np.full(n, "")
            # a chunk that failed as a whole holds no data: NaN, as a failed case
            return np.full((n, *tails[name]), np.nan)

    def column(name: str) -> np.ndarray:
        return np.concatenate([load(path, name) for _, _, path in chunks])

    values: dict[str, Any] = {}
    for name in names:
        if name == "arc_length" and arc is not None:
            continue
        tail = tails[name]
        values[name] = da.concatenate(
            [
                da.from_delayed(
                    dask.delayed(load)(path, name).reshape((hi - lo, *rest, *tail)),
                    shape=(hi - lo, *rest, *tail),
                    dtype=np.float64,
                )
                for lo, hi, path in chunks
            ],
            axis=0,
        )
    data_vars, coords, attrs = grid_variables(
        axes,
        src,
        status=column("status"),
        message=column("message"),
        warning=column("warning"),
        wall_time=column("wall_time"),
        values=values,
        tails=tails,
        arc=arc,
        solver_settings=solver_settings,
        fallbacks=fallbacks,
        named=named,
    )
    return xr.Dataset(data_vars, coords=coords, attrs=attrs)


def grid_variables(
    axes: list[SweepAxis],
    src: StudySource,
    *,
    status: np.ndarray,
    message: np.ndarray,
    wall_time: np.ndarray,
    values: dict[str, Any],
    warning: np.ndarray | None = None,
    tails: dict[str, tuple[int, ...]],
    arc: np.ndarray | None,
    solver_settings: dict[str, Any] | str,
    fallbacks: dict[str, int] | None = None,
    named: dict[str, list[str]] | None = None,
    static_status: bool = True,
) -> tuple[dict[str, VariableSpec], dict[str, VariableSpec], dict[str, Any]]:
    """Data variables, coordinates and global attributes of every study's dataset, in
    the form ``xarray.Dataset(data_vars, coords=coords, attrs=attrs)`` takes (and
    :func:`write_variables_atomic` writes): per case ``status``, ``message``,
    ``wall_time`` (flat, cases in C order) and per output its values (shape
    (*sweep shape, *tail), NumPy or dask) -- the variables, dims, coordinates and
    attributes of every study. ``arc``: the arc lengths every successful case
    shares (then the ``s`` coordinate, and ``arc_length`` is not among ``values``), or
    None (then ``s`` is the node index). ``fallbacks``: why cases were solved by the
    general solver, counted (the ``cases_fallback`` and ``fallback_reasons``
    attributes). ``named``: a system study's coordinates by dimension (line, point,
    body; cablestudy.analyses.system_grid), whose outputs are :data:`SYSTEM_OUTPUTS`.
    ``static_status``: the case's status is its static analysis's (a static grid, whose
    chunks record no ``static_status``).

    Values held in memory also give the coordinates every case shares: the transfer
    function's frequencies (``transfer_frequency`` -> ``frequency``) and the quasi-static
    database's grid, each from the cases whose analysis kept them (the others hold the
    fill); text (unicode) is written as strings."""
    registry = OUTPUTS if named is None else SYSTEM_OUTPUTS
    shape = tuple(a.size for a in axes)
    dims = tuple(a.name for a in axes)
    data_vars: dict[str, VariableSpec] = {}
    status = status.reshape(shape)
    warnings = (
        np.full(shape, "", dtype=object)
        if warning is None
        else warning.astype(object).reshape(shape)
    )
    case = (
        ("status", status),
        ("message", message.astype(object).reshape(shape)),
        ("warning", warnings),
        ("wall_time", wall_time.reshape(shape)),
    )
    for name, arr in case:
        spec = CASE_VARIABLES[name]
        data_vars[name] = (dims, arr, {"units": spec.units, "long_name": spec.long_name})
    if static_status and "static_status" not in values:
        # a static grid runs the statics only: its status is the case's
        spec = OUTPUTS["static_status"]
        data_vars["static_status"] = (
            dims,
            status.astype(np.int64),
            {"units": spec.units, "long_name": spec.long_name},
        )
    extent: dict[str, int] = {}
    for name in sorted(values):
        spec = registry[name]
        value = values[name]
        if isinstance(value, np.ndarray) and value.dtype.kind == "U":
            value = value.astype(object)  # text as str, "" where missing
        for d, n in zip(spec.dims, np.shape(value)[len(shape) :], strict=True):
            extent[d] = max(extent.get(d, 0), n)
        var_attrs = {"units": spec.units, "long_name": spec.long_name}
        if spec.nan_means:  # what a NaN of a case whose analysis succeeded means
            var_attrs["nan_means"] = spec.nan_means
        if name == "natural_frequency" and "modal_status" in values:
            # cases asking for fewer modes than others (a sweep over analysis.modal.modes)
            # are padded with NaN: a NaN of a solved case means only that
            solved = np.asarray(values["modal_status"]) == 0
            if np.isnan(np.asarray(value, dtype=float)[solved]).any():
                var_attrs["nan_means"] = FEWER_MODES
        data_vars[name] = (dims + spec.dims, value, var_attrs)
    coords = sweep_coordinates(axes)
    shared = [("transfer_frequency", "frequency")] + [
        (g, d)
        for lay in DATABASE_LAYOUTS.values()
        for g, d in zip(lay.grid_variables, lay.dims, strict=True)
    ]
    for name, dim in shared:  # a coordinate when every case has the same values
        if name in data_vars and dim not in coords and isinstance(values[name], np.ndarray):
            common = _shared_row(values[name], len(shape))
            if common is not None:
                spec = registry[name]
                coords[dim] = (dim, common, {"units": spec.units, "long_name": spec.long_name})
                data_vars.pop(name)
    if "mode" in extent:
        coords["mode"] = (
            "mode",
            np.arange(1, extent["mode"] + 1),
            {"units": COORDINATES["mode"][0], "long_name": COORDINATES["mode"][1]},
        )
    if named is not None:  # a system: its named dimensions
        named = {**named, "dof": list(BODY_DOFS), "dof_j": list(BODY_DOFS)}
        for dim, names in named.items():
            if any(dim in registry[k].dims for k in values):
                coords[dim] = (
                    dim,
                    np.array(names),
                    {"units": "1", "long_name": COORDINATES[dim][1]},
                )
    if any("component" in registry[k].dims for k in values):
        coords["component"] = (
            "component",
            np.array(["x", "y", "z"]),
            {"units": COORDINATES["component"][0], "long_name": COORDINATES["component"][1]},
        )
    if arc is not None:
        coords["s"] = ("s", arc, {"units": "m", "long_name": COORDINATES["s"][1]})
    elif "arc_length" in values:
        n_s = tails["arc_length"][-1]  # (s,) per case, or a system's (line, s)
        coords["s"] = ("s", np.arange(n_s), {"units": "1", "long_name": "node index"})
    _flag_statuses(data_vars)
    attrs = provenance(src, solver_settings)
    attrs["cases"] = int(np.prod(shape))
    # a broken line is a result, not a failure
    attrs["cases_failed"] = int(np.count_nonzero((status != 0) & (status != STATUS_BROKEN)))
    attrs["cases_warned"] = int(np.count_nonzero(warnings != ""))
    if np.any(status == STATUS_BROKEN):
        attrs["cases_broken"] = int(np.count_nonzero(status == STATUS_BROKEN))
    attrs.update(fallback_attrs(fallbacks or {}))
    return data_vars, coords, attrs


def _shared_row(values: np.ndarray, ndim: int) -> np.ndarray | None:
    """The values every case shares (``values``: the sweep's ``ndim`` dimensions first),
    among the cases that have any (not all NaN: the others' analysis did not keep
    them); None if they differ or no case has any."""
    rows = values.reshape(-1, *values.shape[ndim:])
    flat = rows.reshape(len(rows), -1)
    kept = rows[~np.all(np.isnan(flat), axis=1)] if flat.size else rows[:0]
    if len(kept) and np.all(kept == kept[0]):
        return kept[0]
    return None
