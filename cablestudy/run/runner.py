"""A study run case by case: its cases in chunks on the scheduler
(:mod:`cablestudy.run.scheduler`), finished chunks kept in the per-study cache so that a
repeated or interrupted study resumes, progress, and the final dataset written
atomically (with the quasi-static database's own file when the study has one).

The runner moves cases and records; it knows nothing of physics (it calls
:func:`cablestudy.analyses.evaluate.evaluate_chunk`). A sweep that runs as arrays goes
to :mod:`cablestudy.run.grid_runner` instead.
"""

from __future__ import annotations

import glob
import json
import sys
import time
from collections import Counter
from pathlib import Path
from typing import Any

import numpy as np

from ..analyses.variables import CaseRecord
from ..study.cases import Case, SweepAxis
from ..study.loader import StudySource
from .cache import TEMPORARY_PATTERNS, CaseCache
from .dataset import assembled_variables
from .outputs import CacheLock, remove_stale_temporaries
from .outputs import now as run_started
from .progress import Progress, RunSummary
from .remote import DEFAULT_TIMEOUT
from .scheduler import AUTO, default_workers, execute
from .writer import write_variables_atomic


def default_solver_settings(cases: list[Case]) -> dict[str, Any]:
    """The analysis settings of the study (defaults filled in), and every distinct value a
    sweep gave them."""
    settings = [c.study.analysis.model_dump(mode="json") for c in cases]
    out: dict[str, Any] = {"analysis": settings[0] if settings else {}}
    methods = sorted({c.study.analysis.static.method for c in cases})
    out["static_methods"] = methods
    distinct = {json.dumps(s, sort_keys=True) for s in settings}
    if len(distinct) > 1:
        out["analysis_per_case_distinct"] = [json.loads(d) for d in sorted(distinct)]
    return out


def run_study(
    src: StudySource,
    axes: list[SweepAxis],
    cases: list[Case],
    out_dir: str | Path,
    *,
    scheduler: str = AUTO,
    workers: int | None = None,
    use_cache: bool = True,
    progress: bool | None = None,
    solver_settings: dict[str, Any] | None = None,
    timeout: float = DEFAULT_TIMEOUT,
) -> RunSummary:
    """Run ``cases`` and write ``<out_dir>/<name>.nc``. ``scheduler`` is 'auto' (time a
    few cases here, start ``workers`` processes only when the study would take more than a
    few seconds), 'synchronous', 'threads', 'processes' (a local dask.distributed cluster
    of ``workers`` processes, default: the cores available) or the address of a running
    dask.distributed scheduler (``workers`` is then ignored; ``timeout`` [s] bounds its
    handshake and the wait for a worker, :func:`cablestudy.run.remote.connect`).

    Finished chunks are cached under ``<out_dir>/.cache/<name>/`` as they complete, keyed
    by case hash: an unchanged or interrupted study re-run reuses them."""
    t0 = time.perf_counter()
    out_dir = Path(out_dir)
    name = str(src.data["name"])
    workers = workers or default_workers()
    cache_dir = out_dir / ".cache" / name if use_cache else None
    lock = tidy(out_dir, name, cache_dir)
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

    try:
        used = (
            execute(list(unique.values()), scheduler, workers, on_done, timeout=timeout)
            if unique
            else ""
        )
    finally:
        bar.close()
    records = cache.records
    if solver_settings is None:
        solver_settings = default_solver_settings(cases)
    # written by netCDF4 directly (the file xarray writes, without importing it)
    variables = assembled_variables(axes, cases, records, src, solver_settings=solver_settings)
    path = write_variables_atomic(*variables, out_dir / f"{name}.nc")
    database = write_database_file(variables, axes, cases, src, out_dir)
    if lock is not None and lock.alone():  # no other run of the study writing here
        cache.compact({c.hash for c in cases})
    if lock is not None:
        lock.release()
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
        wall_time=time.perf_counter() - t0,
        failures=dict(failures),
        scheduler=used,
        database_path=database,
        n_warned=len(warned),
        warnings=dict(Counter(records[c.hash].warning for c in warned)),
        warned_cases=warned_cases,
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


def case_label(axes: list[SweepAxis], index: tuple[int, ...]) -> str:
    """The case at ``index`` by its sweep coordinates ("amplitude=0.05, frequency=0.2"), or
    "the case" without a sweep."""
    parts = []
    for axis, i in zip(axes, index, strict=True):
        value = axis.coordinate()[i]
        shown = f"{value:g}" if isinstance(value, int | float | np.number) else str(value)
        parts.append(f"{axis.name}={shown}")
    return ", ".join(parts) or "the case"


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
