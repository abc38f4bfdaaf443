"""The outputs of a chunk of a case grid (:class:`GridChunk`: one array per output
variable, cases first, with status, message, wall time, warnings and fallbacks per case):
the one record form of every study, whether its chunk was solved as arrays or its cases
one by one (:func:`records_chunk`, in the worker); chunks joined (:func:`join_chunks`)
and the chunk whose cases all failed.
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..study.grid import CaseGrid
from .plausibility import joined
from .variables import OUTPUTS, SYSTEM_OUTPUTS, CaseRecord, analysis_ok

#: status of a case whose solver raised inside an array chunk or gave non-finite values:
#: cablestudy.statics.base.STATUS_NUMERICAL, as evaluate_case gives it (not imported
#: here: the statics package loads every solver)
STATUS_NUMERICAL = 2


@dataclass
class GridChunk:
    """The outputs of rows ``lo:hi`` of a grid (or, with :attr:`hashes`, of the cases of
    those content hashes): one array per variable, cases first in C order (shape
    (n_cases, *extra dims)), an analysis's outputs already filled (NaN, -1 or '') where
    it failed, and per case status, message and wall time (the chunk's time shared out
    equally where its cases were solved together)."""

    lo: int
    hi: int
    key: str
    status: np.ndarray
    message: np.ndarray  # unicode
    wall_time: np.ndarray
    data: dict[str, np.ndarray]
    #: per case, why its kept results are implausible or risky (unicode, '' if not)
    warning: np.ndarray | None = None
    #: per case, why the general solver solved it (unicode, '' if a batch kernel did)
    fallback_reason: np.ndarray | None = None
    #: per case, its content hash, when the chunk holds cases picked from the grid (the
    #: runner places them, and finds them again in the cache, by it); None: rows lo:hi
    hashes: np.ndarray | None = None

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


def numerical_fault(
    exc: Exception, status: np.ndarray
) -> tuple[list[str], dict[int, list[str]], dict[str, np.ndarray]]:
    """A fault inside an array chunk fails all its cases, as data: ``status`` set to
    :data:`STATUS_NUMERICAL` in place; returns the messages (the fault's text for every
    case), no warnings and no data."""
    status[:] = STATUS_NUMERICAL
    return [f"{type(exc).__name__}: {exc}"] * len(status), {}, {}


def array_chunk(
    grid: CaseGrid,
    lo: int,
    hi: int,
    t0: float,
    status: np.ndarray,
    messages: list[str],
    data: dict[str, np.ndarray],
    warnings: dict[int, list[str]],
    reasons: np.ndarray,
) -> GridChunk:
    """Rows ``lo:hi`` of ``grid`` solved together since ``t0`` (:func:`time.perf_counter`):
    the chunk's wall time shared out equally, the warnings as a column, the fallback
    ``reasons`` (object array of text) as unicode."""
    n = len(status)
    wall = (time.perf_counter() - t0) / max(n, 1)
    return GridChunk(
        lo=lo,
        hi=hi,
        key=grid.chunk_key(lo, hi),
        status=status,
        message=np.array(messages, dtype=str).reshape(n),
        wall_time=np.full(n, wall),
        data=data,
        warning=warning_column(n, warnings),
        fallback_reason=np.array(reasons.tolist(), dtype=str).reshape(n),
    )


def failed_grid_chunk(grid: CaseGrid, lo: int, hi: int, message: str) -> GridChunk:
    """Rows ``lo:hi`` failed outside the solvers (a worker lost): status 9, the reason,
    no data."""
    n = (hi - lo) * math.prod(grid.shape[1:])
    return failed_chunk(n, message, lo=lo, hi=hi, key=grid.chunk_key(lo, hi))


def failed_chunk(
    n: int,
    message: str,
    *,
    lo: int = 0,
    hi: int = 0,
    key: str = "",
    hashes: np.ndarray | None = None,
    status: int = 9,
) -> GridChunk:
    """``n`` cases failed outside the solvers (a task lost with its worker): ``status``,
    the reason, NaN wall time, no data."""
    return GridChunk(
        lo=lo,
        hi=hi,
        key=key,
        status=np.full(n, status, dtype=np.int64),
        message=np.array([message] * n, dtype=str).reshape(n),
        wall_time=np.full(n, np.nan),
        data={},
        hashes=hashes,
    )


def _fill(dtype: str, fill: Any = None) -> Any:
    if fill is not None:  # the output's own (OutputVariable.fill)
        return fill
    return {"int64": -1, "str": ""}.get(dtype, np.nan)


def records_chunk(
    records: Sequence[CaseRecord], *, system: bool = False, extent: dict[str, int] | None = None
) -> GridChunk:
    """Case records as a chunk (rows in their order, :attr:`GridChunk.hashes` their
    hashes): per output declared in :data:`OUTPUTS` (:data:`SYSTEM_OUTPUTS` for a
    ``system``) one array, its extra dimensions as long as the largest any record has
    (or ``extent``'s), a record's values where its analysis succeeded
    (:func:`analysis_ok`), else the fill (NaN, -1 or ''), shorter values padded by it;
    text as unicode. Raises KeyError for an output no registry declares."""
    registry = SYSTEM_OUTPUTS if system else OUTPUTS
    n = len(records)
    names = sorted({k for r in records for k in r.data})
    unknown = [k for k in names if k not in registry]
    if unknown:
        raise KeyError(f"output variables not declared in results.OUTPUTS: {unknown}")
    data: dict[str, np.ndarray] = {}
    judged: dict[str | None, list[bool]] = {}
    for name in names:
        spec = registry[name]
        shapes = [np.shape(r.data[name]) for r in records if name in r.data]
        tail = tuple(
            (extent or {}).get(d) or max(s[j] for s in shapes) for j, d in enumerate(spec.dims)
        )
        if spec.analysis not in judged:  # each record's verdict once per analysis
            judged[spec.analysis] = [analysis_ok(r, spec.analysis) for r in records]
        ok = judged[spec.analysis]
        kept = [(i, r.data[name]) for i, r in enumerate(records) if ok[i] and name in r.data]
        if spec.dtype == "str":
            texts = [str(np.asarray(v).item()) if np.ndim(v) == 0 else v for _, v in kept]
            width = max([1, *(np.asarray(t, dtype=str).dtype.itemsize // 4 for t in texts)])
            arr = np.full((n, *tail), "", dtype=f"<U{width}")
            values: list[Any] = texts
        elif len(kept) == n and n > 1 and all(s == tail for s in shapes):
            # every record has it, whole: stacked (the same values as placed one by one:
            # the cast to the output's dtype is the one assignment makes)
            data[name] = _stacked([v for _, v in kept], spec.dtype)
            continue
        else:
            arr = np.full((n, *tail), _fill(spec.dtype, spec.fill), dtype=spec.dtype)
            values = [v for _, v in kept]
        for (i, _), v in zip(kept, values, strict=True):
            arr[(i, *(slice(0, k) for k in np.shape(v)))] = v
        data[name] = arr
    return GridChunk(
        lo=0,
        hi=0,
        key="",
        status=np.array([r.status for r in records], dtype=np.int64),
        message=_text([r.message for r in records]),
        wall_time=np.array([r.wall_time for r in records], dtype=np.float64),
        data=data,
        warning=_text([r.warning for r in records]),
        fallback_reason=_text([r.fallback for r in records]),
        hashes=_text([r.hash for r in records]),
    )


def _stacked(values: list[Any], dtype: str) -> np.ndarray:
    """The records' values (all of one shape) as one array of ``dtype``, each cast as
    assigning it into such an array casts it."""
    arrays = [np.asarray(v) for v in values]
    if len({a.dtype for a in arrays}) == 1:  # one dtype: stacked, then cast once
        return np.stack(arrays).astype(dtype, copy=False)
    arr = np.empty((len(values), *arrays[0].shape), dtype=dtype)
    for i, a in enumerate(arrays):
        arr[i] = a
    return arr


def _text(values: list[str]) -> np.ndarray:
    return np.array(values, dtype=str).reshape(len(values))


def _padded(arr: np.ndarray, tail: tuple[int, ...], fill: Any) -> np.ndarray:
    """``arr`` (n, *its tail) padded by ``fill`` to (n, *tail)."""
    if arr.shape[1:] == tail:
        return arr
    out = np.full((arr.shape[0], *tail), fill, dtype=arr.dtype)
    out[(slice(None), *(slice(0, k) for k in arr.shape[1:]))] = arr
    return out


def output_fill(name: str, arr: np.ndarray) -> Any:
    """The fill of output ``name`` (of values ``arr``): '' for text, -1 for an integer
    output, else NaN."""
    if arr.dtype.kind == "U":
        return ""
    spec = OUTPUTS.get(name) or SYSTEM_OUTPUTS.get(name)
    return _fill(spec.dtype, spec.fill) if spec is not None else np.nan


def join_chunks(chunks: Sequence[GridChunk]) -> GridChunk:
    """The chunks' cases one after another as one chunk: each output as long as the
    longest any chunk has (shorter ones padded by its fill), and a chunk without an
    output (every case of it failed as a whole) filled."""
    if len(chunks) == 1:
        return chunks[0]
    names = sorted({k for c in chunks for k in c.data})
    data: dict[str, np.ndarray] = {}
    for name in names:
        have = [c.data[name] for c in chunks if name in c.data]
        tail = tuple(max(a.shape[1 + j] for a in have) for j in range(have[0].ndim - 1))
        fill = output_fill(name, have[0])
        dtype = np.result_type(*have) if have[0].dtype.kind == "U" else have[0].dtype
        data[name] = np.concatenate(
            [
                _padded(c.data[name], tail, fill)
                if name in c.data
                else np.full((c.n, *tail), fill, dtype=dtype)
                for c in chunks
            ]
        )

    def column(attr: str) -> np.ndarray:
        return np.concatenate([getattr(c, attr) for c in chunks])

    hashes = None
    if all(c.hashes is not None for c in chunks):
        hashes = column("hashes")
    return GridChunk(
        lo=chunks[0].lo,
        hi=chunks[-1].hi,
        key="",
        status=column("status"),
        message=column("message"),
        wall_time=column("wall_time"),
        data=data,
        warning=column("warning"),
        fallback_reason=column("fallback_reason"),
        hashes=hashes,
    )


def take_rows(chunk: GridChunk, rows: np.ndarray) -> GridChunk:
    """The chunk of ``chunk``'s cases at ``rows`` (in that order)."""
    return GridChunk(
        lo=chunk.lo,
        hi=chunk.hi,
        key=chunk.key,
        status=chunk.status[rows],
        message=chunk.message[rows],
        wall_time=chunk.wall_time[rows],
        data={k: v[rows] for k, v in chunk.data.items()},
        warning=chunk.warning[rows],
        fallback_reason=chunk.fallback_reason[rows],
        hashes=None if chunk.hashes is None else chunk.hashes[rows],
    )
