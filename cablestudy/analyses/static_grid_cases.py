"""A chunk of a static grid whose cases the arrays do not take, solved as validated
cases: each case's study is the template with its swept values copied in
(:meth:`cablestudy.study.grid.CaseGrid.study_at`), and the chunk is solved as every
study's chunk of validated cases (one :func:`cablestudy.statics.batch.solve_batch` call
for the cases a batch kernel may take, the registry solver per case otherwise, the drag
iteration per case), its records as one :class:`cablestudy.analyses.grid_chunk.GridChunk`.
"""

from __future__ import annotations

import itertools
import math
import time
from typing import Any


def evaluate_static_chunk(grid: Any, lo: int, hi: int) -> Any:
    """Solve rows ``lo:hi`` of a static grid as the cases of any study are solved
    (:func:`cablestudy.analyses.evaluate.evaluate_cases`), as a chunk of those rows. Never
    raises: a fault fails the chunk's cases with its text."""
    from ..study.cases import Case
    from .evaluate import evaluate_cases
    from .grid_chunk import STATUS_NUMERICAL, failed_chunk

    t0 = time.perf_counter()
    block = (hi - lo, *grid.shape[1:])
    n = math.prod(block)
    try:
        cases = []
        for index in itertools.product(*(range(k) for k in block)):
            index = (index[0] + lo, *index[1:])
            cases.append(Case(index, {}, grid.study_at(index), *grid.case_hashes(index)))
        chunk = evaluate_cases(cases, extent={"s": grid_nodes(grid)})
        # the grid's status is the static analysis's (the dataset writes it as such)
        chunk.data = {k: v for k, v in chunk.data.items() if not _status_variable(k)}
    except Exception as exc:  # noqa: BLE001 - a fault in a chunk fails its cases, as data
        chunk = failed_chunk(n, f"{type(exc).__name__}: {exc}", status=STATUS_NUMERICAL)
        chunk.wall_time[:] = (time.perf_counter() - t0) / max(n, 1)
    chunk.lo, chunk.hi, chunk.key, chunk.hashes = lo, hi, grid.chunk_key(lo, hi), None
    return chunk


def grid_nodes(grid: Any) -> int:
    """The most nodes any case of ``grid`` has (the extent of the ``s`` dimension)."""
    path = "analysis.static.nodes"
    if path in grid.validated:
        return int(max(grid.validated[path][1]))
    return int(grid.template.analysis.static.nodes)


def _status_variable(name: str) -> bool:
    from .variables import ANALYSES

    return name.endswith("_status") and name[: -len("_status")] in ANALYSES
