"""A chunk of a static grid whose cases the arrays do not take, solved as validated
cases: each case's study is the template with its swept values copied in
(:meth:`cablestudy.study.grid.CaseGrid.study_at`), and the chunk is solved as
:func:`cablestudy.analyses.evaluate.evaluate_chunk` solves a chunk of validated cases (one
:func:`cablestudy.statics.batch.solve_batch` call for the cases a batch kernel may take,
the registry solver per case otherwise, the drag iteration per case); its records are
stacked into a :class:`cablestudy.analyses.grid_chunk.GridChunk` with the values
:func:`cablestudy.run.dataset.assemble` would write, bit for bit.
"""

from __future__ import annotations

import itertools
import math
import time
from typing import Any

import numpy as np


def evaluate_static_chunk(grid: Any, lo: int, hi: int) -> Any:
    """Solve rows ``lo:hi`` of a static grid as :func:`cablestudy.analyses.evaluate.evaluate_chunk`
    solves validated cases, and stack the records. Never raises: a fault fails the
    chunk's cases with its text."""
    from ..study.cases import Case
    from .evaluate import evaluate_case
    from .grid_chunk import STATUS_NUMERICAL, GridChunk, records_chunk
    from .static import presolve_statics

    t0 = time.perf_counter()
    block = (hi - lo, *grid.shape[1:])
    n = math.prod(block)
    reasons = np.full(n, "", dtype=object)
    try:
        cases = []
        for index in itertools.product(*(range(k) for k in block)):
            index = (index[0] + lo, *index[1:])
            cases.append(Case(index, {}, grid.study_at(index), *grid.case_hashes(index)))
        solved, share = presolve_statics(cases)
        records = []
        for i, case in enumerate(cases):
            rec = evaluate_case(case, presolved=solved)
            rec.wall_time += share.pop(case.static_hash, 0.0)
            records.append(rec)
            reasons[i] = rec.fallback
        chunk = records_chunk(records, extent={"s": grid_nodes(grid)})
        # the grid's status is the static analysis's (the dataset writes it as such)
        data = {k: v for k, v in chunk.data.items() if not _status_variable(k)}
        status, message, warning, wall = (
            chunk.status,
            chunk.message,
            chunk.warning,
            chunk.wall_time,
        )
    except Exception as exc:  # noqa: BLE001 - a fault in a chunk fails its cases, as data
        status = np.full(n, STATUS_NUMERICAL, dtype=np.int64)
        message = np.array([f"{type(exc).__name__}: {exc}"] * n, dtype=str).reshape(n)
        warning = None
        data = {}
        wall = np.full(n, (time.perf_counter() - t0) / max(n, 1))
    return GridChunk(
        lo=lo,
        hi=hi,
        key=grid.chunk_key(lo, hi),
        status=status,
        message=message,
        wall_time=wall,
        data=data,
        fallback=int(np.count_nonzero(reasons != "")),
        warning=warning,
        fallback_reason=np.array(reasons.tolist(), dtype=str).reshape(n),
    )


def grid_nodes(grid: Any) -> int:
    """The most nodes any case of ``grid`` has (the extent of the ``s`` dimension)."""
    path = "analysis.static.nodes"
    if path in grid.validated:
        return int(max(grid.validated[path][1]))
    return int(grid.template.analysis.static.nodes)


def _status_variable(name: str) -> bool:
    from .variables import ANALYSES

    return name.endswith("_status") and name[: -len("_status")] in ANALYSES
