"""Orchestration: cases in chunks as dask tasks, failures captured, a per-study cache
so that a repeated or interrupted study resumes, progress, and the final dataset.

The runner moves cases and records; it knows nothing of physics (it calls
:func:`cablestudy.analyses.evaluate_case`).
"""

from __future__ import annotations

import hashlib
import math
import os
import pickle
import sys
import tempfile
import time
from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from .analyses import evaluate_chunk
from .cases import Case, SweepAxis
from .config.loader import StudySource
from .results import CaseRecord, assemble, write_atomic

SYNCHRONOUS = "synchronous"
PROCESSES = "processes"
THREADS = "threads"


def default_workers() -> int:
    return max(1, min(os.cpu_count() or 1, 8))


def run_chunk(cases: list[Case]) -> list[CaseRecord]:
    """Evaluate a chunk of cases in one task (cases sharing a static problem are
    adjacent, so its solution is reused; compatible static problems are batched)."""
    return evaluate_chunk(cases)


def make_chunks(cases: list[Case], workers: int, *, min_chunks_per_worker: int = 4,
                max_chunk: int = 200) -> list[list[Case]]:
    """Batch cases so that thousands of cheap cases are not drowned by task overhead,
    while every worker gets several chunks (load balance) and an interrupt loses at most
    one chunk per worker."""
    if not cases:
        return []
    ordered = sorted(cases, key=lambda c: (c.static_hash, c.index))
    n_chunks = max(min(len(ordered), workers * min_chunks_per_worker),
                   math.ceil(len(ordered) / max_chunk))
    size = math.ceil(len(ordered) / n_chunks)
    return [ordered[i:i + size] for i in range(0, len(ordered), size)]


class CaseCache:
    """Finished case records on disk, one pickle file per finished chunk, keyed by case
    hash. Written atomically (temporary file then rename)."""

    def __init__(self, directory: Path | None) -> None:
        self.directory = directory
        self.records: dict[str, CaseRecord] = {}
        if directory is not None and directory.is_dir():
            for path in sorted(directory.glob("chunk-*.pkl")):
                try:
                    with open(path, "rb") as fh:
                        for rec in pickle.load(fh):
                            self.records[rec.hash] = rec
                except Exception:  # noqa: BLE001 - an unreadable cache file is recomputed
                    path.unlink(missing_ok=True)

    def store(self, records: list[CaseRecord]) -> None:
        cacheable = [r for r in records if not r.message.startswith("time limit")]
        for rec in records:
            self.records[rec.hash] = rec
        if self.directory is None or not cacheable:
            return
        self.directory.mkdir(parents=True, exist_ok=True)
        key = hashlib.sha256("".join(r.hash for r in cacheable).encode()).hexdigest()[:24]
        fd, tmp = tempfile.mkstemp(dir=self.directory, prefix=".chunk-", suffix=".tmp")
        with os.fdopen(fd, "wb") as fh:
            pickle.dump(cacheable, fh, protocol=pickle.HIGHEST_PROTOCOL)
        os.replace(tmp, self.directory / f"chunk-{key}.pkl")


@dataclass
class RunSummary:
    path: Path
    n_cases: int
    n_reused: int
    n_computed: int
    n_failed: int
    wall_time: float
    failures: dict[str, int] = field(default_factory=dict)

    def report(self) -> str:
        lines = [
            f"wrote {self.path}: {self.n_cases} cases ({self.n_computed} computed, "
            f"{self.n_reused} reused from cache), {self.n_failed} failed, "
            f"{self.wall_time:.2f} s"
        ]
        if self.failures:
            lines.append("failures by message:")
            for msg, count in sorted(self.failures.items(), key=lambda kv: -kv[1]):
                lines.append(f"  {count:6d} x {msg}")
        return "\n".join(lines)


class Progress:
    """A one-line progress bar on a terminal, shown only once a study has run for a few
    seconds."""

    def __init__(self, total: int, *, enabled: bool | None = None, delay: float = 2.0) -> None:
        self.total = total
        self.done = 0
        self.t0 = time.monotonic()
        self.delay = delay
        self.enabled = sys.stderr.isatty() if enabled is None else enabled
        self.shown = False

    def update(self, n: int) -> None:
        self.done += n
        if not self.enabled:
            return
        elapsed = time.monotonic() - self.t0
        if elapsed < self.delay and self.done < self.total:
            return
        frac = self.done / max(self.total, 1)
        bar = "#" * int(30 * frac)
        eta = elapsed / frac - elapsed if frac > 0 else float("nan")
        sys.stderr.write(f"\r[{bar:<30}] {self.done}/{self.total} cases, {elapsed:.0f} s, "
                         f"eta {eta:.0f} s ")
        sys.stderr.flush()
        self.shown = True

    def close(self) -> None:
        if self.shown:
            sys.stderr.write("\n")


def _execute(chunks: list[list[Case]], scheduler: str, workers: int,
             on_done: Callable[[list[CaseRecord]], None]) -> None:
    if scheduler == SYNCHRONOUS or (len(chunks) <= 1 and scheduler in (PROCESSES, THREADS)):
        for chunk in chunks:
            on_done(run_chunk(chunk))
        return
    from dask.distributed import Client, LocalCluster, as_completed

    cluster = None
    if scheduler in (PROCESSES, THREADS):
        cluster = LocalCluster(
            n_workers=workers if scheduler == PROCESSES else 1,
            threads_per_worker=1 if scheduler == PROCESSES else workers,
            processes=scheduler == PROCESSES, dashboard_address=None,
            silence_logs=50,
        )
        client = Client(cluster)
    else:
        client = Client(scheduler)
    try:
        futures = client.map(run_chunk, chunks, pure=False)
        for future in as_completed(futures):
            on_done(future.result())
    finally:
        client.close()
        if cluster is not None:
            cluster.close()


def run_study(
    src: StudySource, axes: list[SweepAxis], cases: list[Case], out_dir: str | Path, *,
    scheduler: str = PROCESSES, workers: int | None = None, use_cache: bool = True,
    progress: bool | None = None, solver_settings: dict[str, Any] | None = None,
) -> RunSummary:
    """Run ``cases`` and write ``<out_dir>/<name>.nc``. ``scheduler`` is 'synchronous',
    'threads', 'processes' (a local dask.distributed cluster) or the address of a running
    dask.distributed scheduler."""
    t0 = time.perf_counter()
    out_dir = Path(out_dir)
    name = str(src.data["name"])
    workers = workers or default_workers()
    cache = CaseCache(out_dir / ".cache" / name if use_cache else None)
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
        _execute(make_chunks(list(unique.values()), workers), scheduler, workers, on_done)
    finally:
        bar.close()
    records = cache.records
    ds = assemble(axes, cases, records, src, solver_settings=solver_settings)
    path = write_atomic(ds, out_dir / f"{name}.nc")
    failures = Counter(records[c.hash].message for c in cases if records[c.hash].status != 0)
    return RunSummary(
        path=path, n_cases=len(cases), n_reused=n_reused, n_computed=len(unique),
        n_failed=sum(failures.values()), wall_time=time.perf_counter() - t0,
        failures=dict(failures),
    )
