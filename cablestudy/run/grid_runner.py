"""Every study run in chunks of its grid (:class:`cablestudy.study.grid.CaseGrid`): rows
of the grid as arrays (:func:`cablestudy.analyses.static_grid.evaluate_grid_chunk`), or
its cases (:func:`cablestudy.analyses.evaluate.evaluate_cases`), both on the one loop of
:mod:`cablestudy.run.scheduler`, each
chunk in one record form (:class:`cablestudy.analyses.grid_chunk.GridChunk`) kept in the
cache, held in memory or streamed to disk by size, and the dataset built from them by
one function (:func:`cablestudy.run.dataset.grid_variables`).
"""

from __future__ import annotations

import hashlib
import json
import math
import tempfile
import time
from pathlib import Path
from typing import Any

import numpy as np

from ..study.cases import Case, SweepAxis
from ..study.loader import StudySource
from .cache import TRANSIENT_PREFIXES
from .database_file import write_database_file
from .outputs import CacheLock, temporary_prefix
from .progress import Progress, RunSummary
from .scheduler import Cases, Rows, execute
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


def run_chunks(
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
    """Every case of ``grid`` in chunks, for :func:`cablestudy.run.runner.run_study`, and
    ``<out_dir>/<name>.nc`` written from the chunks (one record form,
    :class:`cablestudy.analyses.grid_chunk.GridChunk`, one store, one dataset builder):
    a grid run as arrays (:attr:`CaseGrid.chunked`) in chunks of rows of its first axis
    (:mod:`cablestudy.analyses.static_grid`), any other in chunks of its cases sized by
    their measured cost (:mod:`cablestudy.run.scheduler`), turned into the chunk form in
    the worker. Each finished chunk goes to its own data file (the cache ``cache_dir``,
    or a temporary folder without one); a chunk of rows that is in the cache, intact, is
    reused, and so is every cached case of a study run case by case (found by its content
    hash). A large grid's result file is written from the files lazily, so memory holds
    about one chunk at a time whatever the number of cases."""
    import shutil

    from .cache import GridChunkStore

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
    plan = _RowPlan(grid, store) if grid.chunked else _CasePlan(grid, store, use_cache)
    bar = Progress(grid.size, enabled=progress)
    bar.update(plan.n_reused)

    #: chunks computed here, held in memory while the whole result fits in
    #: IN_MEMORY_BYTES (decided at the first chunk with data); else every chunk goes to
    #: its file and the result is streamed from the files (a grid of rows only)
    held: dict[Any, Any] = {}
    hold: list[bool | None] = [None if grid.chunked else True]

    def on_done(chunk: Any) -> None:
        span = plan.span(chunk)
        if use_cache:
            path = plan.write(chunk)
            if path is not None:
                plan.files[span] = path
        if hold[0] is None and chunk.data:
            per_case = sum(v.nbytes for v in chunk.data.values()) / max(chunk.n, 1)
            hold[0] = per_case * grid.size <= IN_MEMORY_BYTES
        held[span] = chunk
        if hold[0] is False:  # too large to hold: to files, streamed from there
            for sp, ch in held.items():
                if sp not in plan.files:
                    plan.files[sp] = store.write(ch)
            held.clear()
        bar.update(chunk.n)

    used = ""
    t1 = time.perf_counter()
    try:
        used = execute(plan.work, scheduler, workers, on_done, timeout=timeout)
    finally:
        bar.close()
    t2 = time.perf_counter()
    timings = {"solve": t2 - t1}
    target = out_dir / f"{name}.nc"
    variables = None
    try:
        lazy = hold[0] is False
        if grid.chunked and not held and not lazy:  # all from the cache: as large as it is
            summary = store.summary([plan.files[span] for span in plan.spans])
            per_case = sum(math.prod(t) for t in summary.tails.values()) * 8
            lazy = per_case * grid.size > IN_MEMORY_BYTES
        if lazy:
            summary, ds = _lazy_dataset(src, grid, store, plan)
            timings["assembly"] = time.perf_counter() - t2
            import dask

            with dask.config.set(scheduler="synchronous"):  # one chunk in memory at a time
                path = write_atomic(ds, target)
        else:
            from .cache import summarise
            from .dataset import chunk_variables

            merged = plan.merged(held)
            summary = summarise([merged])
            variables = chunk_variables(
                grid.axes,
                src,
                merged,
                summary,
                solver_settings=grid_settings(grid),
                named=_named(grid),
                static_status=grid.chunked,
            )
            timings["assembly"] = time.perf_counter() - t2
            path = write_variables_atomic(*variables, target)
        # the quasi-static database's own file (a study run as cases may have one)
        database = write_database_file(
            variables, grid.axes, [] if grid.chunked else grid.cases(), src, out_dir
        )
        timings["write"] = time.perf_counter() - t2 - timings["assembly"]
    finally:
        if scratch is not None:
            shutil.rmtree(scratch, ignore_errors=True)
    for p in plan.transient:
        p.unlink(missing_ok=True)
    if lock is not None and lock.alone():  # no other run of the study writing here
        plan.tidy()
    return RunSummary(
        path=path,
        n_cases=grid.size,
        n_reused=plan.n_reused,
        n_computed=plan.n_computed,
        n_failed=sum(summary.failures.values()),
        wall_time=math.nan,
        failures=dict(summary.failures),
        broken=dict(summary.broken),
        scheduler=used,
        timings=timings,
        database_path=database,
        n_warned=summary.n_warned,
        warnings=dict(summary.warnings),
        warned_cases=_warned_labels(grid, summary.warned_at),
        fallbacks=dict(summary.fallbacks),
    )


def _warned_labels(grid: Any, warned_at: dict[str, int]) -> dict[str, str]:
    """Per warning text the label of its first case (:func:`case_label`), the axes'
    coordinates worked out once."""
    if not warned_at:
        return {}
    coordinates = [axis.coordinate() for axis in grid.axes]
    return {
        text: case_label(grid.axes, np.unravel_index(i, grid.shape), coordinates)
        for text, i in warned_at.items()
    }


def _named(grid: Any) -> dict[str, list[str]] | None:
    """A system study's names along its dimensions (None for one line)."""
    return grid.template.system_names if grid.template.is_system else None


def _lazy_dataset(src: StudySource, grid: Any, store: Any, plan: Any) -> tuple[Any, Any]:
    """The summary and the dataset of a grid run in rows too large to hold, its variables
    backed by the chunk files (:func:`cablestudy.run.dataset.grid_dataset`)."""
    from .dataset import grid_dataset

    ordered = [(lo, hi, plan.files[(lo, hi)]) for lo, hi in plan.spans]
    summary = store.summary([p for _, _, p in ordered])
    ds = grid_dataset(
        grid.axes,
        ordered,
        src,
        names=summary.names,
        tails=summary.tails,
        arc=summary.arc,
        solver_settings=grid_settings(grid),
        fallbacks=summary.fallbacks,
        named=_named(grid),
    )
    return summary, ds


class _RowPlan:
    """A grid run in chunks of rows of its first axis (:func:`grid_chunks`), each found
    again in the cache by its content key."""

    def __init__(self, grid: Any, store: Any) -> None:
        self.grid, self.store = grid, store
        self.spans = grid_chunks(grid)
        self.files: dict[Any, Path] = {}
        self.transient: set[Path] = set()
        for lo, hi in self.spans:
            found = store.find(grid.chunk_key(lo, hi))
            if found is not None:
                self.files[(lo, hi)] = found
        row = math.prod(grid.shape[1:])
        self.n_reused = sum((hi - lo) * row for lo, hi in self.files)
        self.n_computed = grid.size - self.n_reused
        self.work = Rows(grid, [span for span in self.spans if span not in self.files])

    @staticmethod
    def span(chunk: Any) -> Any:
        return (chunk.lo, chunk.hi)

    def write(self, chunk: Any) -> Path:
        path = self.store.write(chunk)
        if any(str(m).startswith(TRANSIENT_PREFIXES) for m in chunk.message):
            self.transient.add(path)  # in this result, but not kept: a re-run computes it
        return path

    def merged(self, held: dict[Any, Any]) -> Any:
        """Every row as one chunk, in order (computed here, or read from its file)."""
        from ..analyses.grid_chunk import join_chunks

        return join_chunks(
            [
                held[span] if span in held else self.store.chunk(self.files[span])
                for span in self.spans
            ]
        )

    def tidy(self) -> None:
        """Remove the chunk files of cases edited away."""
        self.store.keep(set(self.files.values()) - self.transient)


class _CasePlan:
    """A grid run case by case: its distinct cases (by content hash) in chunks on the
    scheduler (:func:`cablestudy.run.scheduler.execute`), every cached case reused
    wherever it now is in the sweep."""

    def __init__(self, grid: Any, store: Any, use_cache: bool) -> None:
        self.store = store
        self.cases = grid.cases()
        wanted = {c.hash for c in self.cases}
        self.found, found_files = store.cases(wanted) if use_cache else ([], set())
        self.files: dict[Any, Path] = {p: p for p in found_files}
        self.transient: set[Path] = set()
        done = {h for chunk in self.found for h in chunk.hashes.tolist()}
        self.unique: dict[str, Case] = {}
        for c in self.cases:
            if c.hash not in done:
                self.unique.setdefault(c.hash, c)
        self.n_reused = sum(1 for c in self.cases if c.hash in done)
        self.n_computed = len(self.unique)
        self.work = _case_work(grid)(list(self.unique.values()))
        self.all: Any = None

    @staticmethod
    def span(chunk: Any) -> Any:
        if not chunk.key:  # named by its cases
            chunk.key = hashlib.sha256("\n".join(chunk.hashes.tolist()).encode()).hexdigest()
        return chunk.key

    def write(self, chunk: Any) -> Path | None:
        """The chunk's cases but the transient ones (a time limit, a lost task: a re-run
        computes them) to a file."""
        from ..analyses.grid_chunk import take_rows

        keep = np.flatnonzero([not str(m).startswith(TRANSIENT_PREFIXES) for m in chunk.message])
        if not len(keep):
            return None
        kept = chunk if len(keep) == chunk.n else take_rows(chunk, keep)
        self.span(kept)
        return self.store.write(kept)

    def merged(self, held: dict[Any, Any]) -> Any:
        """Every case as one chunk, in C order of the grid (a case that appears at several
        places of the sweep at each)."""
        from ..analyses.grid_chunk import join_chunks, take_rows

        self.all = join_chunks([*self.found, *held.values()])
        row = {h: i for i, h in enumerate(self.all.hashes.tolist())}
        return take_rows(self.all, np.array([row[c.hash] for c in self.cases], dtype=np.intp))

    def tidy(self) -> None:
        """The cache as one file holding the study's cases as it now stands (the cases of
        edited-away studies dropped; the new file in place before the old ones go)."""
        from ..analyses.grid_chunk import take_rows

        present = self.store.files()
        kept = set(self.files.values()) - self.transient
        if self.all is None or (len(present) == 1 and set(present) == kept and not self.unique):
            return
        target = self.write(take_rows(self.all, np.arange(self.all.n)))
        self.store.keep({target} if target is not None else set())


class _ExcitationCases(Cases):
    """The cases of a sweep of a system's harmonic excitation
    (:class:`cablestudy.analyses.system_fd_grid.ExcitationGrid`): a chunk of them is
    solved as arrays at once, so the probe fills its time with few chunks
    (:func:`cablestudy.run.scheduler.probe_cost` with ``fill``), the first of up to
    :data:`EXCITATION_PROBE_CASES`: a chunk costs the sweep's shared statics and model
    (once) and about half a millisecond a case, so a sweep of that many runs as one
    chunk (each further chunk cost about 0.4 ms more)."""

    def probe(self, on_done: Any, seconds: float) -> Any:
        from .scheduler import probe_cost

        return probe_cost(self.units, on_done, seconds, fill=True, first=EXCITATION_PROBE_CASES)


#: cases in the first chunk of a sweep of a system's harmonic excitation (about 40 ms)
EXCITATION_PROBE_CASES = 64


def _case_work(grid: Any) -> type[Cases]:
    """The scheduler's work of a grid run case by case."""
    from ..analyses.system_fd_grid import ExcitationGrid

    return _ExcitationCases if isinstance(grid, ExcitationGrid) else Cases


def grid_settings(grid: Any) -> str:
    """The analysis settings of the study (defaults filled in), and every distinct value a
    sweep gave them, as the JSON text of the dataset's ``solver_settings`` attribute
    (:func:`cablestudy.run.dataset.provenance`). A case's analysis settings change only
    along the axes that sweep ``analysis`` paths, so one case per combination of those
    axes (the others at their first value) stands for all."""
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
    # each case's settings as JSON once (a sweep of the excitation: one per case), and
    # the whole text made of them: json.dumps(settings, sort_keys=True) of the dict
    # {"analysis": first, "analysis_per_case_distinct": [distinct...], "static_methods":
    # [...]}, without encoding every case's settings a second time
    texts = [json.dumps(a.model_dump(mode="json"), sort_keys=True) for a in analyses]
    parts = {
        "analysis": texts[0] if texts else "{}",
        "static_methods": json.dumps(sorted({a.static.method for a in analyses})),
    }
    distinct = sorted(set(texts))
    if len(distinct) > 1:
        parts["analysis_per_case_distinct"] = f"[{', '.join(distinct)}]"
    return "{" + ", ".join(f"{json.dumps(k)}: {parts[k]}" for k in sorted(parts)) + "}"


def study_grid(src: StudySource) -> Any:
    """The study as a grid of cases (:func:`cablestudy.study.grid.expand_grid`), or a
    system's position sweep as one (:mod:`cablestudy.analyses.system_grid`). Decided from
    the validated template, never from the raw text."""
    from ..study.grid import expand_grid
    from ..study.loader import validate_data

    template = validate_data(src.data, src)
    _refuse_output_names(src)
    if template.is_system:
        from ..analyses.system_grid import expand_system_grid

        grid = expand_system_grid(src, template)
        if grid is not None:
            return grid
        from ..analyses.system_fd_grid import excitation_sweep

        # a sweep of the harmonic excitation in the frequency domain: its chunks of cases
        # evaluated as arrays (analyses.system_fd_grid)
        return excitation_sweep(expand_grid(src, template))
    return expand_grid(src, template)


def _refuse_output_names(src: StudySource) -> None:
    """A sweep axis named as an output variable or coordinate of the dataset is refused
    before any work (the netCDF writer found the clash only after every case had run,
    and failed with a traceback), at the line of its ``name``."""
    from ..analyses.variables import CASE_VARIABLES, COORDINATES, OUTPUTS, SYSTEM_OUTPUTS
    from ..study.cases import parse_sweep
    from ..study.loader import StudyError

    taken = set(OUTPUTS) | set(SYSTEM_OUTPUTS) | set(CASE_VARIABLES) | set(COORDINATES)
    raw = src.data.get("sweep") or {}
    faults = []
    for axis in parse_sweep(src):
        if axis.name not in taken:
            continue
        key = axis.paths[0] if axis.paths[0] in raw else "zip"
        faults.append(
            f"{src.line_of(('sweep', key))}: sweep.{key}: dimension name {axis.name!r} is "
            "the name of an output variable of the dataset; allowed: a name no output "
            f"uses (give the axis another 'name') (got {axis.name!r})"
        )
    if faults:
        raise StudyError(faults, src.source)


def case_label(
    axes: list[SweepAxis], index: tuple[int, ...], coordinates: list[Any] | None = None
) -> str:
    """The case at ``index`` by its sweep coordinates ("amplitude=0.05, frequency=0.2"), or
    "the case" without a sweep; ``coordinates``: the axes' :meth:`SweepAxis.coordinate`,
    when the caller labels many cases (each axis's worked out once)."""
    if coordinates is None:
        coordinates = [axis.coordinate() for axis in axes]
    parts = []
    for axis, coordinate, i in zip(axes, coordinates, index, strict=True):
        value = coordinate[i]
        shown = f"{value:g}" if isinstance(value, int | float | np.number) else str(value)
        parts.append(f"{axis.name}={shown}")
    return ", ".join(parts) or "the case"
