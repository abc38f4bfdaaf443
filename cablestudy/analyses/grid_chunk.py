"""The outputs of a chunk of a case grid (:class:`GridChunk`: one array per output
variable, cases first, with status, message, wall time, warnings and fallbacks per case),
and the chunk whose cases all failed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..study.grid import CaseGrid
from .plausibility import joined

#: status of a case whose solver raised inside an array chunk or gave non-finite values:
#: cablestudy.statics.base.STATUS_NUMERICAL, as evaluate_case gives it (not imported
#: here: the statics package loads every solver)
STATUS_NUMERICAL = 2


@dataclass
class GridChunk:
    """The outputs of rows ``lo:hi`` of a grid: one array per variable, cases first in
    C order (shape (n_cases, *extra dims)), and per case status, message and wall time
    (the chunk's time shared out equally)."""

    lo: int
    hi: int
    key: str
    status: np.ndarray
    message: np.ndarray  # unicode
    wall_time: np.ndarray
    data: dict[str, np.ndarray]
    #: cases no array kernel settled, solved one by one by the general solver
    fallback: int = 0
    #: per case, why its kept results are implausible or risky (unicode, '' if not)
    warning: np.ndarray | None = None
    #: per case, why the general solver solved it (unicode, '' if a batch kernel did)
    fallback_reason: np.ndarray | None = None

    def __post_init__(self) -> None:
        if self.warning is None:
            self.warning = np.full(len(self.status), "")
        if self.fallback_reason is None:
            self.fallback_reason = np.full(len(self.status), "")

    @property
    def n(self) -> int:
        return len(self.status)


def warning_column(n: int, warnings: dict[int, list[str]]) -> np.ndarray:
    """The ``warning`` text of ``n`` cases, from the warnings of those that have some."""
    texts = {i: joined(w) for i, w in warnings.items()}
    width = max((len(t) for t in texts.values()), default=0)
    column = np.full(n, "", dtype=f"<U{max(width, 1)}")
    for i, text in texts.items():
        column[i] = text
    return column


def failed_grid_chunk(grid: CaseGrid, lo: int, hi: int, message: str) -> GridChunk:
    """Rows ``lo:hi`` failed outside the solvers (a worker lost): status 9, the reason,
    no data."""
    n = (hi - lo) * math.prod(grid.shape[1:])
    return GridChunk(
        lo=lo,
        hi=hi,
        key=grid.chunk_key(lo, hi),
        status=np.full(n, 9, dtype=np.int64),
        message=np.array([message] * n, dtype=str).reshape(n),
        wall_time=np.full(n, np.nan),
        data={},
    )
