"""The one runner of every study (:func:`run_study`): its grid of cases in chunks on the
scheduler, as arrays (:mod:`cablestudy.run.grid_runner`) or as case records
(:mod:`cablestudy.run.scheduler`), finished chunks kept in the per-study cache so that a
repeated or interrupted study resumes, progress, and the final dataset written
atomically (with the quasi-static database's own file when the study has one).

The runner moves cases and records; it knows nothing of physics (it calls
:func:`cablestudy.analyses.evaluate.evaluate_chunk` and the array chunk evaluators).
"""

from __future__ import annotations

import glob
import math
import sys
import time
from collections import Counter
from pathlib import Path
from typing import Any

from ..analyses.variables import CaseRecord
from ..study.cases import Case, SweepAxis
from ..study.grid import CaseGrid
from ..study.loader import StudySource
from .cache import TEMPORARY_PATTERNS, CaseCache
from .dataset import assembled_variables
from .grid_runner import case_label, grid_settings, run_arrays
from .outputs import CacheLock, remove_stale_temporaries
from .outputs import now as run_started
from .progress import Progress, RunSummary
from .remote import DEFAULT_TIMEOUT
from .scheduler import AUTO, default_workers, execute
from .writer import write_variables_atomic


def run_study(
    src: StudySource,
    grid: CaseGrid,
    out_dir: str | Path,
    *,
    scheduler: str = AUTO,
    workers: int | None = None,
    use_cache: bool = True,
    progress: bool | None = None,
    timeout: float = DEFAULT_TIMEOUT,
) -> RunSummary:
    """Run every case of ``grid`` (:func:`cablestudy.run.grid_runner.study_grid`) and write
    ``<out_dir>/<name>.nc``: the one runner of every study. ``scheduler`` is 'auto' (time
    a few cases here, start ``workers`` processes only when the study would take more
    than a few seconds), 'synchronous', 'threads', 'processes' (a local dask.distributed
    cluster of ``workers`` processes, default: the cores available) or the address of a
    running dask.distributed scheduler (``workers`` is then ignored; ``timeout`` [s]
    bounds its handshake and the wait for a worker, :func:`cablestudy.run.remote.connect`).

    A grid run in chunks of rows (:attr:`CaseGrid.chunked`) goes as arrays
    (:func:`cablestudy.run.grid_runner.run_arrays`); any other as chunks of case records
    sized by their measured cost (:mod:`cablestudy.run.scheduler`). Either way finished
    chunks are cached under ``<out_dir>/.cache/<name>/`` as they complete: an unchanged or
    interrupted study re-run reuses them."""
    t0 = time.perf_counter()
    out_dir = Path(out_dir)
    name = str(src.data["name"])
    workers = workers or default_workers()
    cache_dir = out_dir / ".cache" / name if use_cache else None
    lock = tidy(out_dir, name, cache_dir)
    try:
        run = run_arrays if grid.chunked else _run_records
        summary = run(src, grid, out_dir, cache_dir, lock, scheduler, workers, progress, timeout)
    finally:
        if lock is not None:
            lock.release()
    summary.wall_time = time.perf_counter() - t0
    return summary


def _run_records(
    src: StudySource,
    grid: CaseGrid,
    out_dir: Path,
    cache_dir: Path | None,
    lock: CacheLock | None,
    scheduler: str,
    workers: int,
    progress: bool | None,
    timeout: float,
) -> RunSummary:
    """The cases of ``grid`` in chunks of records on the scheduler, each finished chunk
    in the per-case cache (keyed by case hash), and the dataset assembled from the
    records (with the quasi-static database's own file when the study has one)."""
    axes, cases = grid.axes, grid.cases()
    cache = CaseCache(cache_dir)
    pending = [c for c in cases if c.hash not in cache.records]
    unique: dict[str, Case] = {}
    for c in pending:
        unique.setdefault(c.hash, c)
    n_reused = len(cases) - len(pending)
    bar = Progress(len(cases), enabled=progress)
    bar.update(n_reused)

    def on_done(records: list[CaseRecord]) -> None:
        cache.store(records)
        bar.update(len(records))

    t1 = time.perf_counter()
    try:
        used = (
            execute(list(unique.values()), scheduler, workers, on_done, timeout=timeout)
            if unique
            else ""
        )
    finally:
        bar.close()
    t2 = time.perf_counter()
    records = cache.records
    # written by netCDF4 directly (the file xarray writes, without importing it)
    variables = assembled_variables(
        axes,
        cases,
        records,
        src,
        solver_settings=grid_settings(grid),
    )
    t3 = time.perf_counter()
    path = write_variables_atomic(*variables, out_dir / f"{src.data['name']}.nc")
    database = write_database_file(variables, axes, cases, src, out_dir)
    if lock is not None and lock.alone():  # no other run of the study writing here
        cache.compact({c.hash for c in cases})
    failures = Counter(records[c.hash].message for c in cases if records[c.hash].status != 0)
    warned = [c for c in cases if records[c.hash].warning]
    warned_cases: dict[str, str] = {}
    for c in warned:
        warned_cases.setdefault(records[c.hash].warning, case_label(axes, c.index))
    return RunSummary(
        path=path,
        n_cases=len(cases),
        n_reused=n_reused,
        n_computed=len(unique),
        n_failed=sum(failures.values()),
        wall_time=math.nan,
        failures=dict(failures),
        scheduler=used,
        timings={"solve": t2 - t1, "assembly": t3 - t2, "write": time.perf_counter() - t3},
        database_path=database,
        n_warned=len(warned),
        warnings=dict(Counter(records[c.hash].warning for c in warned)),
        warned_cases=warned_cases,
        fallbacks=dict(
            Counter(records[c.hash].fallback for c in cases if records[c.hash].fallback)
        ),
    )


def tidy(out_dir: Path, name: str, cache_dir: Path | None) -> CacheLock | None:
    """Before a run of study ``name``: remove the temporary files and folders that runs
    killed while writing left in ``out_dir`` and ``cache_dir``
    (:func:`cablestudy.run.outputs.remove_stale_temporaries`), and take the shared lock on
    ``cache_dir`` (None without a cache) that keeps other runs from removing its files."""
    started = run_started()
    study = glob.escape(name)
    patterns = (
        f".{study}.nc.*.tmp",
        f".{study}.database.nc.*.tmp",
        f".{study}-chunks-*",
        f".{study}.write-check.*",
    )
    remove_stale_temporaries(out_dir, patterns, started, _warn)
    if cache_dir is None:
        return None
    remove_stale_temporaries(cache_dir, TEMPORARY_PATTERNS, started, _warn)
    return CacheLock(cache_dir)


def _warn(message: str) -> None:
    print(f"warning: {message}", file=sys.stderr)


def write_database_file(
    variables: tuple[Any, Any, Any],
    axes: list[SweepAxis],
    cases: list[Case],
    src: StudySource,
    out_dir: Path,
) -> Path | None:
    """Write ``<out_dir>/<name>.database.nc`` (:mod:`cablestudy.run.database_file`) from the
    study dataset's variables when they hold a quasi-static database; otherwise remove a
    file of that name left by an earlier run of the study, which would no longer
    describe it."""
    from .database_file import database_file_name, database_variables

    target = out_dir / database_file_name(str(src.data["name"]))
    db_vars = database_variables(variables, axes, cases, src)
    if db_vars is None:
        target.unlink(missing_ok=True)
        return None
    return write_variables_atomic(*db_vars, target)
