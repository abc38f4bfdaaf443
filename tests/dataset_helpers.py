"""Datasets built from hand-made case records the way the runner builds every dataset
(the records as one chunk, :func:`cablestudy.analyses.grid_chunk.records_chunk`, then
:func:`cablestudy.run.dataset.chunk_variables`), for tests of the dataset conventions."""

from __future__ import annotations

from typing import Any

import xarray as xr

from cablestudy.analyses.grid_chunk import records_chunk
from cablestudy.analyses.variables import CaseRecord
from cablestudy.run.dataset import chunk_variables
from cablestudy.study.cases import Case, SweepAxis
from cablestudy.study.loader import StudySource


def assemble(
    axes: list[SweepAxis],
    cases: list[Case],
    records: dict[str, CaseRecord],
    src: StudySource,
    *,
    solver_settings: dict[str, Any] | None = None,
) -> xr.Dataset:
    """One dataset on the sweep axes from case records (by case hash), rows in C order
    of the grid."""
    ordered = sorted(cases, key=lambda c: c.index)
    chunk = records_chunk([records[c.hash] for c in ordered])
    data_vars, coords, attrs = chunk_variables(
        axes, src, chunk, solver_settings=solver_settings or {}
    )
    return xr.Dataset(data_vars, coords=coords, attrs=attrs)
