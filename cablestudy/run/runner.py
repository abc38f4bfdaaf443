"""The one runner of every study (:func:`run_study`): its grid of cases in chunks
(:mod:`cablestudy.run.grid_runner`: rows of the grid as arrays, or cases on the
scheduler of :mod:`cablestudy.run.scheduler`), every chunk in one record form kept in
the per-study cache so that a repeated or interrupted study resumes, progress, and the
final dataset written atomically (with the quasi-static database's own file when the
study has one).

The runner moves chunks; it knows nothing of physics (it calls
:func:`cablestudy.analyses.evaluate.evaluate_cases` and the array chunk evaluators).
"""

from __future__ import annotations

import glob
import sys
import time
from pathlib import Path

from ..study.grid import CaseGrid
from ..study.loader import StudySource
from .cache import TEMPORARY_PATTERNS
from .grid_runner import run_chunks
from .outputs import CacheLock, remove_stale_temporaries
from .outputs import now as run_started
from .progress import RunSummary
from .remote import DEFAULT_TIMEOUT
from .scheduler import AUTO, default_workers


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

    A grid run in chunks of rows (:attr:`CaseGrid.chunked`) goes as arrays, any other as
    chunks of cases sized by their measured cost (:mod:`cablestudy.run.scheduler`), both
    through :func:`cablestudy.run.grid_runner.run_chunks`. Either way finished chunks are
    cached under ``<out_dir>/.cache/<name>/`` as they complete: an unchanged or
    interrupted study re-run reuses them."""
    t0 = time.perf_counter()
    out_dir = Path(out_dir)
    name = str(src.data["name"])
    workers = workers or default_workers()
    cache_dir = out_dir / ".cache" / name if use_cache else None
    lock = tidy(out_dir, name, cache_dir)
    try:
        summary = run_chunks(
            src, grid, out_dir, cache_dir, lock, scheduler, workers, progress, timeout
        )
    finally:
        if lock is not None:
            lock.release()
    summary.wall_time = time.perf_counter() - t0
    return summary


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
