"""A study run as arrays (:class:`cablestudy.study.grid.CaseGrid`): rows of the
grid as chunks (:func:`cablestudy.analyses.static_grid.evaluate_grid_chunk`), each
chunk's arrays kept in the cache, held in memory or streamed to disk by size, and the
dataset written from them.
"""

from __future__ import annotations

import json
import math
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from ..study.cases import SweepAxis
from ..study.loader import StudySource
from .cache import LOST_PREFIX, TRANSIENT_PREFIXES
from .outputs import CacheLock, temporary_prefix
from .progress import Progress, RunSummary
from .remote import DEFAULT_TIMEOUT, connect
from .scheduler import (
    AUTO,
    AUTO_PARALLEL_AFTER,
    PROCESSES,
    SYNCHRONOUS,
    _local_cluster,
)
from .writer import write_atomic, write_variables_atomic

#: cases per chunk of a study run as arrays (rows of the first axis are never split);
#: fixed, so that a re-run finds the same chunks in its cache
GRID_CHUNK_CASES = 10_000


#: results of an array-run study up to this size [bytes] are assembled in memory before
#: writing (no dask); larger ones are streamed from the chunk files one chunk at a time
IN_MEMORY_BYTES = 256 << 20


def grid_chunks(grid: Any) -> list[tuple[int, int]]:
    """Rows ``lo:hi`` of the first axis per chunk: about :data:`GRID_CHUNK_CASES` cases."""
    row = math.prod(grid.shape[1:])
    step = max(1, GRID_CHUNK_CASES // max(row, 1))
    n0 = grid.shape[0]
    return [(lo, min(lo + step, n0)) for lo in range(0, n0, step)]


def _grid_chunk_task(grid: Any, lo: int, hi: int) -> Any:
    from ..analyses.static_grid import evaluate_grid_chunk

    return evaluate_grid_chunk(grid, lo, hi)


def run_arrays(
    src: StudySource,
    grid: Any,
    out_dir: Path,
    cache_dir: Path | None,
    lock: CacheLock | None,
    scheduler: str,
    workers: int,
    progress: bool | None,
    timeout: float,
) -> RunSummary:
    """The rows of ``grid`` as arrays (:mod:`cablestudy.analyses.static_grid`), for
    :func:`cablestudy.run.runner.run_study`, and ``<out_dir>/<name>.nc`` written
    chunk by chunk: each finished chunk goes to its own data file (the cache
    ``cache_dir``, or a temporary folder without one), and the result file is written
    from those files lazily, so memory holds about one chunk at a time whatever the
    number of cases. A chunk that is in the cache, intact, is reused."""
    import shutil

    from .cache import GridChunkStore
    from .dataset import grid_dataset

    name = str(src.data["name"])
    use_cache = cache_dir is not None
    if cache_dir is not None:
        folder = cache_dir
        scratch = None
    else:
        out_dir.mkdir(parents=True, exist_ok=True)
        scratch = Path(tempfile.mkdtemp(prefix=temporary_prefix(f".{name}-chunks-"), dir=out_dir))
        folder = scratch
    store = GridChunkStore(folder)
    spans = grid_chunks(grid)
    keys = {(lo, hi): grid.chunk_key(lo, hi) for lo, hi in spans}
    files: dict[tuple[int, int], Path] = {}
    for span, key in keys.items():
        found = store.find(key)
        if found is not None:
            files[span] = found
    row = math.prod(grid.shape[1:])
    n_reused = sum((hi - lo) * row for lo, hi in files)
    bar = Progress(grid.size, enabled=progress)
    bar.update(n_reused)

    transient: set[Path] = set()
    #: chunks computed here, held in memory while the whole result fits in
    #: IN_MEMORY_BYTES (decided at the first chunk with data); else every chunk goes to
    #: its file and the result is streamed from the files
    held: dict[tuple[int, int], Any] = {}
    hold: list[bool | None] = [None]

    def on_done(chunk: Any) -> None:
        span = (chunk.lo, chunk.hi)
        if use_cache:
            path = store.write(chunk)
            files[span] = path
            if any(str(m).startswith(TRANSIENT_PREFIXES) for m in chunk.message):
                transient.add(path)  # in this result, but not kept: a re-run computes it
        if hold[0] is None and chunk.data:
            per_case = sum(v.nbytes for v in chunk.data.values()) / max(chunk.n, 1)
            hold[0] = per_case * grid.size <= IN_MEMORY_BYTES
        held[span] = chunk
        if hold[0] is False:  # too large to hold: to files, streamed from there
            for sp, ch in held.items():
                if sp not in files:
                    files[sp] = store.write(ch)
            held.clear()
        bar.update(chunk.n)

    todo = [span for span in spans if span not in files]
    used = ""
    timings: dict[str, float] = {}
    t1 = time.perf_counter()
    try:
        if todo:
            used = _execute_grid(grid, todo, scheduler, workers, on_done, timeout=timeout)
    finally:
        bar.close()
    t2 = time.perf_counter()
    timings["solve"] = t2 - t1
    target = out_dir / f"{name}.nc"
    try:
        lazy = hold[0] is False
        if not held and not lazy:  # everything from the cache: as large as it is
            summary = store.summary([files[span] for span in spans])
            per_case = sum(math.prod(t) for t in summary.tails.values()) * 8
            lazy = per_case * grid.size > IN_MEMORY_BYTES
        if lazy:
            ordered = [(lo, hi, files[(lo, hi)]) for lo, hi in spans]
            summary = store.summary([p for _, _, p in ordered])
            ds = grid_dataset(
                grid.axes,
                ordered,
                src,
                names=summary.names,
                tails=summary.tails,
                arc=summary.arc,
                solver_settings=grid_settings(grid),
                lazy=True,
                fallbacks=summary.fallbacks,
                named=getattr(grid, "named", None),  # a system's (cablestudy.system_grid)
            )
            t3 = time.perf_counter()
            timings["assembly"] = t3 - t2
            import dask

            with dask.config.set(scheduler="synchronous"):  # one chunk in memory at a time
                path = write_atomic(ds, target)
        else:
            chunks = [
                held[span] if span in held else _stored_chunk(store, files[span]) for span in spans
            ]
            summary, variables = _grid_variables(src, grid, chunks)
            t3 = time.perf_counter()
            timings["assembly"] = t3 - t2
            path = write_variables_atomic(*variables, target)
        timings["write"] = time.perf_counter() - t3
    finally:
        if scratch is not None:
            shutil.rmtree(scratch, ignore_errors=True)
    for p in transient:
        p.unlink(missing_ok=True)
    # a study run as arrays has no database (cablestudy.analyses.static_grid refuses one): a
    # database file of this name is an earlier run's, which no longer describes the study
    from .database_file import database_file_name

    (out_dir / database_file_name(name)).unlink(missing_ok=True)
    if lock is not None and lock.alone():  # no other run of the study writing here
        store.keep(set(files.values()) - transient)
    return RunSummary(
        path=path,
        n_cases=grid.size,
        n_reused=n_reused,
        n_computed=grid.size - n_reused,
        n_failed=sum(summary.failures.values()),
        wall_time=math.nan,
        failures=dict(summary.failures),
        scheduler=used,
        timings=timings,
        n_warned=summary.n_warned,
        warnings=dict(summary.warnings),
        warned_cases={
            text: case_label(grid.axes, np.unravel_index(i, grid.shape))
            for text, i in summary.warned_at.items()
        },
        fallbacks=dict(summary.fallbacks),
    )


def _stored_chunk(store: Any, path: Path) -> Any:
    """A chunk file of the cache as a :class:`cablestudy.analyses.grid_chunk.GridChunk`."""
    from ..analyses.grid_chunk import GridChunk

    z = store.load(path)
    lo, hi = (int(v) for v in z.pop("rows"))
    return GridChunk(
        lo=lo,
        hi=hi,
        key=str(z.pop("key")),
        status=z.pop("status"),
        message=z.pop("message"),
        wall_time=z.pop("wall_time"),
        warning=z.pop("warning", None),
        fallback_reason=z.pop("fallback", None),
        data=z,
    )


def grid_settings(grid: Any) -> dict[str, Any]:
    """The analysis settings of the study (defaults filled in), and every distinct value a
    sweep gave them. A case's analysis settings change only along the axes that sweep
    ``analysis`` paths, so one case per combination of those axes (the others at their
    first value) stands for all."""
    import itertools

    swept = sorted(
        {k for k, a in enumerate(grid.axes) if any(p.startswith("analysis") for p in a.paths)}
    )
    analyses = []
    for picks in itertools.product(*(range(grid.shape[k]) for k in swept)):
        index = [0] * len(grid.shape)
        for k, i in zip(swept, picks, strict=True):
            index[k] = i
        analyses.append(grid.study_at(tuple(index)).analysis)
    settings = [a.model_dump(mode="json") for a in analyses]
    out: dict[str, Any] = {"analysis": settings[0] if settings else {}}
    out["static_methods"] = sorted({a.static.method for a in analyses})
    distinct = {json.dumps(s, sort_keys=True) for s in settings}
    if len(distinct) > 1:
        out["analysis_per_case_distinct"] = [json.loads(d) for d in sorted(distinct)]
    return out


def _grid_variables(src: StudySource, grid: Any, chunks: list[Any]) -> tuple[Any, tuple]:
    """The summary of in-memory chunks (all rows of ``grid``, in order) and the dataset's
    (data variables, coordinates, attributes): the dataset
    :func:`cablestudy.run.dataset.grid_dataset` assembles from the chunk files."""
    from .cache import summarise
    from .dataset import grid_variables

    summary = summarise(
        ((c.status, c.message, c.warning, c.data) for c in chunks),
        (c.fallback_reason for c in chunks),
    )
    rest = grid.shape[1:]
    values: dict[str, Any] = {}
    for name in summary.names:
        if name == "arc_length" and summary.arc is not None:
            continue
        tail = summary.tails[name]
        values[name] = np.concatenate(
            [
                (
                    c.data[name]
                    if name in c.data
                    else np.full((c.n, *tail), np.nan)  # a chunk failed as a whole
                ).reshape((c.hi - c.lo, *rest, *tail))
                for c in chunks
            ]
        )
    variables = grid_variables(
        grid.axes,
        src,
        status=np.concatenate([c.status for c in chunks]),
        message=np.concatenate([c.message for c in chunks]),
        warning=np.concatenate([c.warning for c in chunks]),
        wall_time=np.concatenate([c.wall_time for c in chunks]),
        values=values,
        tails=summary.tails,
        arc=summary.arc,
        solver_settings=grid_settings(grid),
        fallbacks=summary.fallbacks,
        named=getattr(grid, "named", None),  # a system's (cablestudy.system_grid)
    )
    return summary, variables


def _execute_grid(
    grid: Any,
    spans: list[tuple[int, int]],
    scheduler: str,
    workers: int,
    on_done: Callable[[Any], None],
    *,
    timeout: float = DEFAULT_TIMEOUT,
) -> str:
    """Evaluate the chunks ``spans`` of ``grid``: here, or on dask. 'auto' times the
    first chunk here and goes on here unless the rest would take more than
    :data:`AUTO_PARALLEL_AFTER` seconds (then worker processes)."""
    rest = list(spans)
    if scheduler in (AUTO, SYNCHRONOUS) or len(rest) == 1:
        t0 = time.perf_counter()
        on_done(_grid_chunk_task(grid, *rest.pop(0)))
        per_chunk = time.perf_counter() - t0
        if scheduler == AUTO and workers > 1 and per_chunk * len(rest) > AUTO_PARALLEL_AFTER:
            scheduler = PROCESSES
        else:
            for lo, hi in rest:
                on_done(_grid_chunk_task(grid, lo, hi))
            return SYNCHRONOUS
    if not rest:
        return scheduler
    from dask.distributed import Client, as_completed

    cluster = None
    if "://" in scheduler:
        client = connect(scheduler, timeout)
    else:
        cluster = _local_cluster(scheduler, workers)
        client = Client(cluster)
    try:
        remote = client.scatter(grid, broadcast=True)
        futures = {
            client.submit(_grid_chunk_task, remote, lo, hi, pure=False): (lo, hi) for lo, hi in rest
        }
        for future in as_completed(list(futures)):
            try:
                chunk = future.result()
            except Exception as exc:  # noqa: BLE001 - a lost task fails its cases, not the study
                from ..analyses.grid_chunk import failed_grid_chunk

                chunk = failed_grid_chunk(grid, *futures[future], f"{LOST_PREFIX}{exc!r}")
            on_done(chunk)
            future.release()
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    return scheduler


def study_grid(src: StudySource) -> Any:
    """The study as a grid of cases (:func:`cablestudy.study.grid.expand_grid`), or a
    system's position sweep as one (:mod:`cablestudy.analyses.system_grid`). Decided from
    the validated template, never from the raw text."""
    from ..study.grid import expand_grid
    from ..study.loader import validate_data

    template = validate_data(src.data, src)
    if template.is_system:
        from ..analyses.system_grid import expand_system_grid

        grid = expand_system_grid(src, template)
        if grid is not None:
            return grid
    return expand_grid(src, template)


def case_label(axes: list[SweepAxis], index: tuple[int, ...]) -> str:
    """The case at ``index`` by its sweep coordinates ("amplitude=0.05, frequency=0.2"), or
    "the case" without a sweep."""
    parts = []
    for axis, i in zip(axes, index, strict=True):
        value = axis.coordinate()[i]
        shown = f"{value:g}" if isinstance(value, int | float | np.number) else str(value)
        parts.append(f"{axis.name}={shown}")
    return ", ".join(parts) or "the case"
