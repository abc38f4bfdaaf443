"""The quasi-static database as its own netCDF dataset (issue 12 item 7).

A study with ``analysis.database`` writes, beside its result ``<name>.nc``, the file
``<name>.database.nc`` holding the database alone, for a vessel simulation or any other
user that needs the lookup table and not the study. It is derived from the study
dataset's variables (:func:`cablestudy.run.dataset.chunk_variables`), so the two always
agree and a rerun that resumes from the cache writes the same file.

Cases map to a dimension, not to files: one file per study, its tables on the study's
sweep dimensions (none for a study without a sweep) followed by the grid's two
dimensions (``horizontal_distance``, ``height_difference`` for grid cartesian;
``distance``, ``angle`` for grid radial) and ``component`` for the end forces. Select a
case with ``--sel DIM=VALUE`` (``cablestudy lookup``) or ``open_database(path, DIM=VALUE)``.

Contents (CF-1.8, SI, ``units`` and ``long_name`` on every variable):

- ``force_a``, ``force_b`` [N], ``tension_a``, ``tension_b``, ``tension_max`` [N],
  ``laid_length`` [m], ``point_status`` (0 ok) per grid point;
- ``cell_check`` per grid point: the build's check of the cell of which it is the lower
  corner (:func:`cablestudy.analyses.database.check_cells`; 0 verified, bit 1 straddles
  the taut chord, bit 2 off a direct solve at its centre, -1 no cell); a lookup refuses
  a point in a flagged cell;
- the grid as coordinates of its dimensions [m; rad for ``angle``], or, when cases of
  the sweep have different grids, as ``<dim>_grid`` variables per case;
- ``heading`` [rad]: the database's vertical plane, from end A towards the study's end B;
- per case ``status`` and ``message`` (as in the study dataset: a failed case is NaN),
  ``case_hash`` (the content hash of the case, as in the cache);
- global attributes: those of the study dataset (study name, YAML, its hash, versions,
  solver settings), ``database_grid`` (cartesian | radial), ``database_of`` (the study
  result's file name), ``line`` and ``end_a`` (the study's line and end A as JSON).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..analyses.variables import DATABASE_LAYOUTS, DATABASE_QUANTITIES
from .writer import VariableSpec, write_variables_atomic

if TYPE_CHECKING:
    from ..study.cases import Case, SweepAxis
    from ..study.loader import StudySource

PREFIX = "quasi-static database: "


def database_variables(
    variables: tuple[dict[str, VariableSpec], dict[str, VariableSpec], dict[str, Any]],
    axes: list[SweepAxis],
    cases: list[Case],
    src: StudySource,
) -> tuple[dict[str, VariableSpec], dict[str, VariableSpec], dict[str, Any]] | None:
    """The (data variables, coordinates, attributes) of the database file, from the
    study dataset's ``variables``; None when it holds no database (none asked for, or
    every case failed)."""
    data_vars, coords, attrs = variables
    kinds = [k for k, lay in DATABASE_LAYOUTS.items() if f"{lay.prefix}tension_a" in data_vars]
    if not kinds:
        return None
    kind = kinds[0]  # one grid kind per study (refused otherwise at validation)
    layout = DATABASE_LAYOUTS[kind]
    sweep = tuple(a.name for a in axes)
    shape = tuple(a.size for a in axes)

    out: dict[str, VariableSpec] = {}
    for name in ("status", "message"):
        out[name] = data_vars[name]
    hashes = np.full(shape, "", dtype=object)
    for c in cases:
        hashes[c.index] = c.hash
    out["case_hash"] = (sweep, hashes, {"units": "1", "long_name": "content hash of the case"})
    for q in DATABASE_QUANTITIES:
        dims, values, var_attrs = data_vars[f"{layout.prefix}{q}"]
        long_name = var_attrs["long_name"].removeprefix(PREFIX)
        out["point_status" if q == "status" else q] = (
            dims,
            values,
            {**var_attrs, "long_name": long_name},
        )
    if f"{layout.prefix}cell_check" in data_vars:  # the build's check of each cell
        dims, values, var_attrs = data_vars[f"{layout.prefix}cell_check"]
        long_name = var_attrs["long_name"].removeprefix(PREFIX)
        out["cell_check"] = (dims, values, {**var_attrs, "long_name": long_name})
    for dim, var in zip(layout.dims, layout.grid_variables, strict=True):
        if var in data_vars:  # cases with different grids: one per case
            out[f"{dim}_grid"] = data_vars[var]
    if "database_heading" in data_vars:
        dims, values, var_attrs = data_vars["database_heading"]
        out["heading"] = (dims, values, var_attrs)

    keep = set(sweep) | set(layout.dims) | {"component"}
    out_coords = {}
    for name, spec in coords.items():
        dims = (spec[0],) if isinstance(spec[0], str) else tuple(spec[0])
        if set(dims) <= keep:
            out_coords[name] = spec

    study = str(attrs.get("study_name", ""))
    out_attrs = dict(attrs)
    out_attrs["title"] = f"{study}: quasi-static database"
    out_attrs["database_grid"] = kind
    out_attrs["database_of"] = f"{study}.nc"
    out_attrs["line"] = json.dumps(src.data.get("line"), sort_keys=True)
    ends = src.data.get("ends")
    out_attrs["end_a"] = json.dumps(ends.get("a") if isinstance(ends, dict) else None)
    return out, out_coords, out_attrs


def write_database_file(
    variables: tuple[Any, Any, Any] | None,
    axes: list[SweepAxis],
    cases: list[Case],
    src: StudySource,
    out_dir: Path,
) -> Path | None:
    """Write ``<out_dir>/<name>.database.nc`` (:mod:`cablestudy.run.database_file`) from the
    study dataset's variables when they hold a quasi-static database; otherwise remove a
    file of that name left by an earlier run of the study, which would no longer
    describe it."""
    target = out_dir / f"{src.data['name']}.database.nc"
    db_vars = None if variables is None else database_variables(variables, axes, cases, src)
    if db_vars is None:
        target.unlink(missing_ok=True)
        return None
    return write_variables_atomic(*db_vars, target)
