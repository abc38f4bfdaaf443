"""Orchestration: cases in chunks as dask tasks, failures captured, a per-study cache
so that a repeated or interrupted study resumes, progress, and the final dataset.

The runner moves cases and records; it knows nothing of physics (it calls
:func:`cablestudy.analyses.evaluate_case`).
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import math
import os
import pickle
import re
import sys
import tempfile
import time
from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from .analyses import evaluate_chunk
from .cases import Case, SweepAxis
from .config.loader import StudySource
from .results import CaseRecord, assemble, write_atomic
from .statics import STATUS_TIME_LIMIT

#: status of a case whose task failed outside the solvers (worker lost)
STATUS_TASK_FAILED = 9
#: messages of records that must not be cached (transient: a rerun may succeed)
LOST_PREFIX = "task failed: "
TRANSIENT_PREFIXES = ("time limit", LOST_PREFIX)


def transient(record: CaseRecord) -> bool:
    """Whether a rerun may succeed where ``record`` failed (time limit, lost worker)."""
    return record.status == STATUS_TIME_LIMIT or record.message.startswith(TRANSIENT_PREFIXES)


SYNCHRONOUS = "synchronous"
PROCESSES = "processes"
THREADS = "threads"
AUTO = "auto"
SCHEDULERS = (AUTO, SYNCHRONOUS, THREADS, PROCESSES)
#: auto scheduler: seconds spent timing cases in this process before deciding, and the
#: estimated remaining run time above which worker processes are started
AUTO_PROBE_SECONDS = 0.5
#: seconds to wait for a dask.distributed scheduler given by its address
CONNECT_TIMEOUT = 10.0
AUTO_PARALLEL_AFTER = 5.0


class SchedulerUnreachable(RuntimeError):
    """The dask.distributed scheduler named by ``--scheduler ADDRESS`` did not answer."""


def default_workers() -> int:
    """Worker processes for a local run: the cores this process may use (so 2 on a
    2-core machine), at most 8."""
    try:
        cores = len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        cores = os.cpu_count() or 1
    return max(1, min(cores, 8))


def failed_chunk(cases: list[Case], exc: BaseException) -> list[CaseRecord]:
    """Records for a chunk whose task died outside the solvers (a worker lost, an
    unpicklable result): every case failed with the reason, NaN data, not cached."""
    message = f"{LOST_PREFIX}{type(exc).__name__}: {exc}"
    return [
        CaseRecord(
            hash=c.hash,
            index=c.index,
            status=STATUS_TASK_FAILED,
            message=message,
            wall_time=math.nan,
        )
        for c in cases
    ]


def run_chunk(cases: list[Case]) -> list[CaseRecord]:
    """Evaluate a chunk of cases in one task (cases sharing a static problem are
    adjacent, so its solution is reused; compatible static problems are batched)."""
    return evaluate_chunk(cases)


def make_chunks(
    cases: list[Case], workers: int, *, min_chunks_per_worker: int = 4, max_chunk: int = 200
) -> list[list[Case]]:
    """Batch cases so that thousands of cheap cases are not drowned by task overhead,
    while every worker gets several chunks (load balance) and an interrupt loses at most
    one chunk per worker."""
    if not cases:
        return []
    ordered = sorted(cases, key=lambda c: (c.static_hash, c.index))
    n_chunks = max(
        min(len(ordered), workers * min_chunks_per_worker), math.ceil(len(ordered) / max_chunk)
    )
    # sizes differ by at most one
    bounds = [len(ordered) * i // n_chunks for i in range(n_chunks + 1)]
    return [ordered[lo:hi] for lo, hi in zip(bounds[:-1], bounds[1:], strict=True)]


def _compact(record: CaseRecord) -> CaseRecord:
    """The record with 0-d arrays as Python scalars (pickles three times faster)."""
    data = {
        k: (v.item() if isinstance(v, np.ndarray) and v.ndim == 0 else v)
        for k, v in record.data.items()
    }
    return dataclasses.replace(record, data=data)


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
        """Keep ``records`` and write the cacheable ones (not time-limited, not lost with
        their worker) to one new chunk file."""
        cacheable = [r for r in records if not transient(r)]
        for rec in records:
            self.records[rec.hash] = rec
        if self.directory is None or not cacheable:
            return
        key = hashlib.sha256("".join(r.hash for r in cacheable).encode()).hexdigest()[:24]
        self._write(self.directory / f"chunk-{key}.pkl", [_compact(r) for r in cacheable])

    def _write(self, path: Path, records: list[CaseRecord]) -> None:
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=".chunk-", suffix=".tmp")
        try:
            with os.fdopen(fd, "wb") as fh:
                pickle.dump(records, fh, protocol=pickle.HIGHEST_PROTOCOL)
                fh.flush()
                os.fsync(fh.fileno())
            os.replace(tmp, path)
        finally:
            if os.path.exists(tmp):
                os.unlink(tmp)

    def compact(self, keep: set[str]) -> None:
        """Rewrite the cache as one file holding the records in ``keep`` (the cases of the
        study as it now stands), dropping records of edited-away cases. The new file is
        in place before the old ones are removed, so a crash loses nothing."""
        if self.directory is None or not self.directory.is_dir():
            return
        old = sorted(self.directory.glob("chunk-*.pkl"))
        records = [r for h, r in self.records.items() if h in keep and not transient(r)]
        if not records:
            return
        key = hashlib.sha256("".join(sorted(r.hash for r in records)).encode()).hexdigest()
        target = self.directory / f"chunk-{key[:24]}.pkl"
        if old == [target]:
            return
        self._write(target, records)
        for path in old:
            if path != target:
                path.unlink(missing_ok=True)


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
        """Text summary; failures grouped by message (numbers in messages masked so that
        e.g. residuals of different size group together), most frequent first."""
        lines = [
            f"wrote {self.path}: {self.n_cases} cases ({self.n_computed} computed, "
            f"{self.n_reused} reused from cache), {self.n_failed} failed, "
            f"{self.wall_time:.2f} s"
        ]
        for pattern, (count, example) in group_failures(self.failures).items():
            if len(lines) == 1:
                lines.append("failures by message:")
            single = count == self.failures.get(example)
            shown = example if single else f"{pattern}  (e.g. {example})"
            lines.append(f"  {count:6d} x {shown}")
        return "\n".join(lines)


_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def group_failures(failures: dict[str, int]) -> dict[str, tuple[int, str]]:
    """Failure messages grouped with their numbers masked as '#': pattern -> (count, first
    example), most frequent first."""
    groups: dict[str, tuple[int, str]] = {}
    for msg, count in failures.items():
        pattern = _NUMBER.sub("#", msg)
        n, example = groups.get(pattern, (0, msg))
        groups[pattern] = (n + count, example)
    return dict(sorted(groups.items(), key=lambda kv: -kv[1][0]))


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
        sys.stderr.write(
            f"\r[{bar:<30}] {self.done}/{self.total} cases, {elapsed:.0f} s, eta {eta:.0f} s "
        )
        sys.stderr.flush()
        self.shown = True

    def close(self) -> None:
        if self.shown:
            sys.stderr.write("\n")


def _run_local(
    cases: list[Case], workers: int, on_done: Callable[[list[CaseRecord]], None]
) -> None:
    for chunk in make_chunks(cases, workers):
        on_done(run_chunk(chunk))


def _run_auto(cases: list[Case], workers: int, on_done: Callable[[list[CaseRecord]], None]) -> None:
    """Probe the cost of a case in this process; keep going here when the whole study
    would take less than :data:`AUTO_PARALLEL_AFTER` seconds (starting worker processes
    costs a few seconds), else hand the rest to a local cluster of ``workers`` processes."""
    t0 = time.perf_counter()
    probe: list[CaseRecord] = []
    rest = list(cases)
    while rest and (not probe or time.perf_counter() - t0 < AUTO_PROBE_SECONDS):
        probe.extend(run_chunk([rest.pop(0)]))
    if probe:
        on_done(probe)
    per_case = (time.perf_counter() - t0) / max(len(probe), 1)
    if workers > 1 and per_case * len(rest) > AUTO_PARALLEL_AFTER:
        _run_dask(rest, PROCESSES, workers, on_done)
    else:
        _run_local(rest, 1, on_done)


def _run_dask(
    cases: list[Case], scheduler: str, workers: int, on_done: Callable[[list[CaseRecord]], None]
) -> None:
    from dask.distributed import Client, LocalCluster, as_completed

    cluster = None
    if scheduler in (PROCESSES, THREADS):
        cluster = LocalCluster(
            n_workers=workers if scheduler == PROCESSES else 1,
            threads_per_worker=1 if scheduler == PROCESSES else workers,
            processes=scheduler == PROCESSES,
            dashboard_address=None,
            silence_logs=50,
        )
        client = Client(cluster)
    else:
        try:
            client = Client(scheduler, timeout=CONNECT_TIMEOUT)
        except (OSError, TimeoutError) as exc:
            raise SchedulerUnreachable(
                f"cannot reach the dask scheduler at {scheduler} within {CONNECT_TIMEOUT:g} s "
                f"({type(exc).__name__}: {exc})"
            ) from None
        # chunk for the cluster as it is: one slot per worker thread
        info = client.scheduler_info()
        workers = max(1, sum(w.get("nthreads", 1) for w in info.get("workers", {}).values()))
    try:
        chunks = make_chunks(cases, workers)
        futures = client.map(run_chunk, chunks, pure=False)
        chunk_of = {f.key: chunk for f, chunk in zip(futures, chunks, strict=True)}
        for future in as_completed(futures):
            try:
                records = future.result()
            except Exception as exc:  # noqa: BLE001 - a lost task fails its cases, not the study
                records = failed_chunk(chunk_of[future.key], exc)
            on_done(records)
            future.release()
    finally:
        client.close()
        if cluster is not None:
            cluster.close()


def execute(
    cases: list[Case], scheduler: str, workers: int, on_done: Callable[[list[CaseRecord]], None]
) -> None:
    """Evaluate ``cases`` in chunks on ``scheduler``, calling ``on_done`` with each chunk's
    records as it finishes (in the calling process)."""
    if not cases:
        return
    if scheduler == SYNCHRONOUS:
        _run_local(cases, workers, on_done)
    elif scheduler == AUTO:
        _run_auto(cases, workers, on_done)
    elif scheduler in (PROCESSES, THREADS) and len(cases) == 1:
        _run_local(cases, 1, on_done)
    else:
        _run_dask(cases, scheduler, workers, on_done)


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
) -> RunSummary:
    """Run ``cases`` and write ``<out_dir>/<name>.nc``. ``scheduler`` is 'auto' (time a
    few cases here, start ``workers`` processes only when the study would take more than a
    few seconds), 'synchronous', 'threads', 'processes' (a local dask.distributed cluster
    of ``workers`` processes, default: the cores available) or the address of a running
    dask.distributed scheduler (``workers`` is then ignored).

    Finished chunks are cached under ``<out_dir>/.cache/<name>/`` as they complete, keyed
    by case hash: an unchanged or interrupted study re-run reuses them."""
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
        execute(list(unique.values()), scheduler, workers, on_done)
    finally:
        bar.close()
    records = cache.records
    if solver_settings is None:
        solver_settings = default_solver_settings(cases)
    ds = assemble(axes, cases, records, src, solver_settings=solver_settings)
    path = write_atomic(ds, out_dir / f"{name}.nc")
    cache.compact({c.hash for c in cases})
    failures = Counter(records[c.hash].message for c in cases if records[c.hash].status != 0)
    return RunSummary(
        path=path,
        n_cases=len(cases),
        n_reused=n_reused,
        n_computed=len(unique),
        n_failed=sum(failures.values()),
        wall_time=time.perf_counter() - t0,
        failures=dict(failures),
    )
