"""Orchestration: cases in chunks as dask tasks, failures captured, a per-study cache
so that a repeated or interrupted study resumes, progress, and the final dataset.

The runner moves cases and records; it knows nothing of physics (it calls
:func:`cablestudy.analyses.evaluate_case`).
"""

from __future__ import annotations

import contextlib
import glob
import json
import math
import os
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

from .cache import LOST_PREFIX, TEMPORARY_PATTERNS, TRANSIENT_PREFIXES, CaseCache
from .cases import Case, SweepAxis
from .config.loader import StudySource
from .outputs import CacheLock, remove_stale_temporaries, temporary_prefix
from .outputs import now as run_started
from .remote import DEFAULT_TIMEOUT, connect
from .results import CaseRecord, assembled_variables, write_atomic, write_variables_atomic

#: status of a case whose task failed outside the solvers (worker lost)
STATUS_TASK_FAILED = 9

SYNCHRONOUS = "synchronous"
PROCESSES = "processes"
THREADS = "threads"
AUTO = "auto"
SCHEDULERS = (AUTO, SYNCHRONOUS, THREADS, PROCESSES)
#: auto scheduler: seconds spent timing cases in this process before deciding, and the
#: estimated remaining run time [s] above which it runs them in parallel (a local cluster
#: of forked workers starts in about 0.3 s; threads need no start)
AUTO_PROBE_SECONDS = 0.25
AUTO_PARALLEL_AFTER = 2.0
#: other local schedulers: seconds of cases timed here first (sizes the chunks)
PROBE_SECONDS = 0.2
#: seconds of work per chunk in the two-thread probe, and the speed-up of two threads
#: over one above which threads are used rather than processes
THREAD_PROBE_SECONDS = 0.15
THREADS_SCALE = 1.5
#: a task should take about this long [s]: dask's own cost is a few ms per task
#: (README), about 1 % of a quarter second, and tasks this short balance two workers
#: (1.47x on the 92-case dynamic sweep against 1.32-1.36x with tasks of a second)
TARGET_TASK_SECONDS = 0.25
#: cases per chunk when their cost is not known, and at most (bounds a task's memory)
DEFAULT_CHUNK_CASES = 200
MAX_CHUNK_CASES = 20_000
#: runs of adjacent cases per chunk, from evenly spaced parts of the sweep (make_chunks)
STRIPES = 4


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
    from .analyses import evaluate_chunk  # the solvers: not needed by a sweep run as arrays

    return evaluate_chunk(cases)


def chunk_limit(per_case: float | None) -> int:
    """Cases per task: as many as take :data:`TARGET_TASK_SECONDS` at ``per_case``
    seconds a case (between 1 and :data:`MAX_CHUNK_CASES`), or
    :data:`DEFAULT_CHUNK_CASES` when the cost is not known."""
    if per_case is None or not per_case > 0 or not math.isfinite(per_case):
        return DEFAULT_CHUNK_CASES
    return int(max(1, min(MAX_CHUNK_CASES, round(TARGET_TASK_SECONDS / per_case))))


def make_chunks(
    cases: list[Case],
    workers: int,
    *,
    min_chunks_per_worker: int = 4,
    max_chunk: int | None = None,
    per_case: float | None = None,
) -> list[list[Case]]:
    """Batch cases so that a task takes about :data:`TARGET_TASK_SECONDS` (``per_case``:
    the measured cost of a case [s]; unknown: at most :data:`DEFAULT_CHUNK_CASES` cases),
    while every
    worker gets several chunks (load balance) and an interrupt loses at most one chunk
    per worker."""
    if not cases:
        return []
    if max_chunk is None:
        max_chunk = chunk_limit(per_case)
    ordered = sorted(cases, key=lambda c: (c.static_hash, c.index))
    n_chunks = max(
        min(len(ordered), workers * min_chunks_per_worker), math.ceil(len(ordered) / max_chunk)
    )
    # each chunk takes STRIPES runs of adjacent cases from evenly spaced parts of the
    # sweep: neighbouring cases cost alike (a taut-slack corner of a dynamic sweep can
    # cost 50 times the rest), so this spreads an expensive region over several tasks,
    # while cases sharing a static problem stay mostly together. Chunk sizes differ by at
    # most one.
    n = len(ordered)
    sizes = [n * (j + 1) // n_chunks - n * j // n_chunks for j in range(n_chunks)]
    chunks: list[list[Case]] = [[] for _ in range(n_chunks)]
    pos = 0
    for k in range(STRIPES):  # stripe k of every chunk, then stripe k + 1 ...
        for j, size in enumerate(sizes):
            take = size * (k + 1) // STRIPES - size * k // STRIPES
            chunks[j].extend(ordered[pos : pos + take])
            pos += take
    # in the order to submit them: from both ends of the sweep inwards. A case's cost
    # mostly changes monotonically along an axis (larger amplitude, higher frequency,
    # longer line), so the costliest chunk is at one end or the other: started first, it
    # is not the tail of the study
    order = [i // 2 if i % 2 == 0 else n_chunks - 1 - i // 2 for i in range(n_chunks)]
    return [chunks[i] for i in order if chunks[i]]


@dataclass
class RunSummary:
    path: Path
    n_cases: int
    n_reused: int
    n_computed: int
    n_failed: int
    wall_time: float
    failures: dict[str, int] = field(default_factory=dict)
    #: the scheduler that ran the cases after the in-process probe ('' if none ran)
    scheduler: str = ""
    #: seconds per phase, where measured (solve, assembly, write)
    timings: dict[str, float] = field(default_factory=dict)
    #: the quasi-static database's own file, where the study has one
    database_path: Path | None = None
    #: cases whose kept results carry a warning, and each warning with its count
    n_warned: int = 0
    warnings: dict[str, int] = field(default_factory=dict)
    #: per warning text, the first case that has it (sweep coordinates), where known
    warned_cases: dict[str, str] = field(default_factory=dict)
    #: cases of a study run as arrays that no batch kernel took (solved by the general
    #: solver), counted by reason
    fallbacks: dict[str, int] = field(default_factory=dict)

    def report(self) -> str:
        """Text summary; failures grouped by message (numbers in messages masked so that
        e.g. residuals of different size group together), most frequent first."""
        lines = [
            f"wrote {self.path}: {self.n_cases} cases ({self.n_computed} computed, "
            f"{self.n_reused} reused from cache), {self.n_failed} failed, "
            + (f"{self.n_warned} with warnings, " if self.n_warned else "")
            + f"{self.wall_time:.2f} s"
            + (f" ({self.scheduler})" if self.scheduler else "")
        ]
        if self.database_path is not None:
            lines.append(f"wrote {self.database_path}: the quasi-static database")
        if self.fallbacks:
            lines.append(
                f"{sum(self.fallbacks.values())} cases solved by the general solver (no batch "
                "kernel took them): "
                + "; ".join(
                    f"{n} x {why}"
                    for why, n in sorted(self.fallbacks.items(), key=lambda kv: -kv[1])
                )
            )
        for pattern, (count, example) in group_failures(self.failures).items():
            if len(lines) == 1:
                lines.append("failures by message:")
            single = count == self.failures.get(example)
            shown = example if single else f"{pattern}  (e.g. {example})"
            lines.append(f"  {count:6d} x {shown}")
        kinds = group_warnings(self.warnings, self.warned_cases)
        if kinds:
            lines.append("warnings by kind (the cases keep status 0):")
        for kind, (count, examples) in kinds.items():
            lines.append(f"  {count:6d} x {kind}, e.g.:")
            lines.extend(f"           {example}" for example in examples)
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


#: example warnings shown per kind at the end of a run
WARNING_EXAMPLES = 3


def group_warnings(
    warnings: dict[str, int], cases: dict[str, str] | None = None
) -> dict[str, tuple[int, list[str]]]:
    """Case warnings (each a case's ``warning`` text with its count) split into single
    warnings and grouped by kind (the text before the first colon): kind -> (count, up to
    :data:`WARNING_EXAMPLES` distinct examples, each after its case's coordinates where
    ``cases`` gives them), most frequent first."""
    from .plausibility import SEPARATOR

    cases = cases or {}
    groups: dict[str, tuple[int, list[str]]] = {}
    for text, count in warnings.items():
        for one in text.split(SEPARATOR):
            kind = one.split(":", 1)[0]
            n, examples = groups.get(kind, (0, []))
            shown = f"{cases[text]}: {one}" if cases.get(text) else one
            if len(examples) < WARNING_EXAMPLES and shown not in examples:
                examples = [*examples, shown]
            groups[kind] = (n + count, examples)
    return dict(sorted(groups.items(), key=lambda kv: -kv[1][0]))


class Progress:
    """A tqdm progress bar of finished cases on standard error: only on a terminal (or
    when ``enabled``), and only once the study has run for ``delay`` seconds, so quick
    studies and logs stay clean."""

    def __init__(self, total: int, *, enabled: bool | None = None, delay: float = 2.0) -> None:
        self.total = total
        self.done = 0
        self.enabled = sys.stderr.isatty() if enabled is None else enabled
        self._bar = None
        if self.enabled:
            from tqdm import tqdm

            self._bar = tqdm(
                total=total,
                file=sys.stderr,
                delay=delay,
                ascii=" #",
                unit="case",
                dynamic_ncols=True,
                bar_format="[{bar:30}] {n_fmt}/{total_fmt} cases, {elapsed}, eta {remaining} ",
            )

    def update(self, n: int) -> None:
        self.done += n
        if self._bar is not None:
            self._bar.update(n)

    def close(self) -> None:
        if self._bar is not None:
            self._bar.close()


OnDone = Callable[[list[CaseRecord]], None]


@dataclass
class Probe:
    """What the in-process probe learned: the cases it left, the cost of a case [s] at
    the largest chunk it ran, and (if timed) the speed-up of two threads over one."""

    rest: list[Case]
    per_case: float
    thread_speedup: float | None = None


def probe_cost(cases: list[Case], on_done: OnDone, seconds: float) -> Probe:
    """Run ``cases`` here in doubling chunks (1, 2, 4, ... cases, so that cheap cases
    are timed batched as they will run) until ``seconds`` have passed; the cost of a
    case is that of the last (largest) chunk. The probe's records count: nothing is
    computed twice."""
    ordered = sorted(cases, key=lambda c: (c.static_hash, c.index))
    # probe cases spread over the sweep (bit-reversed order: its ends, its middle, its
    # quarters, ...): a sweep's cost changes along its axes (a dynamic sweep's large
    # amplitudes and high frequencies cost many times its small ones), and its first
    # cases alone would predict the cheap corner
    spread = sorted(range(len(ordered)), key=lambda i: _radical_inverse(i))
    probed: set[int] = set()
    t_start = time.perf_counter()
    size, per_case, pos = 1, math.nan, 0
    while pos < len(spread):
        take = spread[pos : pos + size]
        pos += len(take)
        chunk = [ordered[i] for i in sorted(take)]
        t0 = time.perf_counter()
        on_done(run_chunk(chunk))
        per_case = (time.perf_counter() - t0) / len(chunk)
        probed.update(take)
        if time.perf_counter() - t_start >= seconds:
            break
        size *= 2
    rest = [c for i, c in enumerate(ordered) if i not in probed]
    return Probe(rest, per_case)


def _radical_inverse(i: int) -> float:
    """The van der Corput point of ``i`` in base 2 (its bits mirrored about the binary
    point): 0, 1/2, 1/4, 3/4, 1/8, ..., an ordering that spreads any prefix."""
    out, f = 0.0, 0.5
    while i:
        if i & 1:
            out += f
        i >>= 1
        f *= 0.5
    return out


def probe_threads(probe: Probe, on_done: OnDone, workers: int) -> Probe:
    """Time two chunks of about :data:`THREAD_PROBE_SECONDS` each on two threads at once
    against the probe's serial cost: the speed-up threads give (numba kernels that
    release the GIL scale, Python-bound work does not)."""
    from concurrent.futures import ThreadPoolExecutor

    n = min(len(probe.rest) // 2, max(1, round(THREAD_PROBE_SECONDS / probe.per_case)))
    if n < 1 or workers < 2:
        return probe
    chunks, rest = [probe.rest[:n], probe.rest[n : 2 * n]], probe.rest[2 * n :]
    t0 = time.perf_counter()
    with ThreadPoolExecutor(2) as pool:
        results = list(pool.map(run_chunk, chunks))
    wall = time.perf_counter() - t0
    for records in results:
        on_done(records)
    return Probe(rest, probe.per_case, (2 * n * probe.per_case) / max(wall, 1e-9))


def choose_scheduler(probe: Probe, workers: int) -> str:
    """The local scheduler for the cases the probe left: here (synchronous) when they
    would take less than :data:`AUTO_PARALLEL_AFTER` seconds or there is one worker;
    else threads when they scaled on two threads, else worker processes."""
    remaining = probe.per_case * len(probe.rest)
    if workers < 2 or not remaining > AUTO_PARALLEL_AFTER:
        return SYNCHRONOUS
    if probe.thread_speedup is not None and probe.thread_speedup >= THREADS_SCALE:
        return THREADS
    return PROCESSES


def _run_local(cases: list[Case], on_done: OnDone, *, per_case: float | None = None) -> None:
    for chunk in make_chunks(cases, 1, per_case=per_case):
        on_done(run_chunk(chunk))


def _run_auto(cases: list[Case], workers: int, on_done: OnDone) -> str:
    """Probe the cost of a case in this process and choose (:func:`choose_scheduler`);
    the probe's cases are done by then. Returns the scheduler used for the rest."""
    probe = probe_cost(cases, on_done, AUTO_PROBE_SECONDS)
    if workers > 1 and probe.per_case * len(probe.rest) > AUTO_PARALLEL_AFTER:
        probe = probe_threads(probe, on_done, workers)
    chosen = choose_scheduler(probe, workers)
    if chosen == SYNCHRONOUS:
        _run_local(probe.rest, on_done, per_case=probe.per_case)
    else:
        _run_dask(probe.rest, chosen, workers, on_done, per_case=probe.per_case)
    return chosen


def _local_cluster(scheduler: str, workers: int):  # noqa: ANN202 - dask type, imported late
    """A local dask.distributed cluster. Worker processes are forked (on Linux) from this
    process, which has by then imported the solvers and loaded their compiled kernels
    (the probe ran cases here): a worker is ready in a fraction of a second instead of
    importing everything again (about 3 s on a 2-core machine)."""
    import dask
    from dask.distributed import LocalCluster

    method = "fork" if sys.platform.startswith("linux") else "spawn"
    with dask.config.set({"distributed.worker.multiprocessing-method": method}):
        return LocalCluster(
            n_workers=workers if scheduler == PROCESSES else 1,
            threads_per_worker=1 if scheduler == PROCESSES else workers,
            processes=scheduler == PROCESSES,
            dashboard_address=None,
            silence_logs=50,
        )


def _run_dask(
    cases: list[Case],
    scheduler: str,
    workers: int,
    on_done: OnDone,
    *,
    per_case: float | None = None,
    timeout: float = DEFAULT_TIMEOUT,
) -> None:
    if not cases:
        return
    if scheduler == THREADS:
        _run_threads(cases, workers, on_done, per_case=per_case)
        return
    from dask.distributed import Client, as_completed

    cluster = None
    if scheduler in (PROCESSES, THREADS):
        cluster = _local_cluster(scheduler, workers)
        client = Client(cluster)
    else:
        client = connect(scheduler, timeout)
        # chunk for the cluster as it is: one slot per worker thread
        info = client.scheduler_info()
        workers = max(1, sum(w.get("nthreads", 1) for w in info.get("workers", {}).values()))
    try:
        pending = sorted(cases, key=lambda c: (c.static_hash, c.index))
        first: list[list[Case]] = []
        if per_case is None:
            # the cost is not known yet: one case per worker slot first, timed on the
            # cluster itself; the rest is chunked when the first of them is back
            first = [[c] for c in pending[:workers]]
            pending = pending[workers:]
        chunk_of: dict[str, list[Case]] = {}

        def submit(chunks: list[list[Case]]) -> list[Any]:
            futures = client.map(run_chunk, chunks, pure=False)
            chunk_of.update({f.key: chunk for f, chunk in zip(futures, chunks, strict=True)})
            return futures

        done = as_completed(submit(first) if first else [])
        if per_case is not None:
            done.update(submit(make_chunks(pending, workers, per_case=per_case)))
            pending = []
        for future in done:
            try:
                records = future.result()
            except Exception as exc:  # noqa: BLE001 - a lost task fails its cases, not the study
                records = failed_chunk(chunk_of[future.key], exc)
            on_done(records)
            future.release()
            if pending:
                times = [r.wall_time for r in records if math.isfinite(r.wall_time)]
                cost = sum(times) / len(times) if times else None
                done.update(submit(make_chunks(pending, workers, per_case=cost)))
                pending = []
    finally:
        client.close()
        if cluster is not None:
            cluster.close()


def _guarded_chunk(cases: list[Case]) -> list[CaseRecord]:
    """:func:`run_chunk`, its cases failed (not the study) if the task itself dies."""
    try:
        return run_chunk(cases)
    except Exception as exc:  # noqa: BLE001 - a lost task fails its cases, not the study
        return failed_chunk(cases, exc)


def _run_threads(
    cases: list[Case], workers: int, on_done: OnDone, *, per_case: float | None = None
) -> None:
    """The chunks on dask's local threaded scheduler (no dask.distributed: its import
    alone is about 0.4 s, a tenth of a few-second study). The solvers' compiled kernels
    release the GIL, so threads run cases in parallel. Each chunk's records reach
    ``on_done`` in this thread as the chunk finishes, and no copy is kept (bounded
    memory); chunks start in :func:`make_chunks` order (the scheduler takes the largest
    key first, hence the keys count down)."""
    import dask.threaded
    from dask.callbacks import Callback

    chunks = make_chunks(cases, workers, per_case=per_case)
    n = len(chunks)
    graph = {f"chunk-{n - 1 - i:08d}": (_guarded_chunk, chunk) for i, chunk in enumerate(chunks)}

    def posttask(key: str, result: Any, dsk: Any, state: dict, worker_id: Any) -> None:
        on_done(result)
        state["cache"][key] = None

    with Callback(posttask=posttask):
        dask.threaded.get(graph, list(graph), num_workers=workers)


def execute(
    cases: list[Case],
    scheduler: str,
    workers: int,
    on_done: OnDone,
    *,
    timeout: float = DEFAULT_TIMEOUT,
) -> str:
    """Evaluate ``cases`` in chunks on ``scheduler``, calling ``on_done`` with each chunk's
    records as it finishes (in the calling process). Every local scheduler first times
    a few cases here (:func:`probe_cost`), which sizes the chunks to about a quarter second
    and loads the compiled kernels before worker processes are forked. Returns the
    scheduler that ran the cases after the probe."""
    if not cases:
        return scheduler
    if scheduler == AUTO:
        return _run_auto(cases, workers, on_done)
    if "://" in scheduler:
        _run_dask(cases, scheduler, workers, on_done, timeout=timeout)
        return scheduler
    if scheduler == SYNCHRONOUS or len(cases) <= 1:
        probe = probe_cost(cases, on_done, PROBE_SECONDS)
        _run_local(probe.rest, on_done, per_case=probe.per_case)
    else:
        # the forked workers share what this process has loaded: the compiled kernels
        # (analyses.warm_up, called before this by `cablestudy run`) and the first
        # case's static solution, solved here; no case runs here, so both workers start
        # at once. The chunks are sized from the first cases timed on the workers.
        _share_statics(cases)
        _run_dask(cases, scheduler, workers, on_done)
    return scheduler


def _share_statics(cases: list[Case]) -> None:
    """Solve the first case's statics in this process (cached by static hash, so worker
    processes forked afterwards reuse it). A failure is left for the case itself to
    record where it runs."""
    from .analyses import solve_static

    first = min(cases, key=lambda c: (c.static_hash, c.index))
    with contextlib.suppress(Exception):
        solve_static(first, None)


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
    handshake and the wait for a worker, :func:`cablestudy.remote.connect`).

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
    (:func:`cablestudy.outputs.remove_stale_temporaries`), and take the shared lock on
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
    """Write ``<out_dir>/<name>.database.nc`` (:mod:`cablestudy.database_file`) from the
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
    from .grid import evaluate_grid_chunk

    return evaluate_grid_chunk(grid, lo, hi)


def run_grid_study(
    src: StudySource,
    grid: Any,
    out_dir: str | Path,
    *,
    scheduler: str = AUTO,
    workers: int | None = None,
    use_cache: bool = True,
    progress: bool | None = None,
    timeout: float = DEFAULT_TIMEOUT,
) -> RunSummary:
    """Run a study as arrays (:mod:`cablestudy.grid`) and write ``<out_dir>/<name>.nc``
    chunk by chunk: each finished chunk goes to its own data file (the cache, or a
    temporary folder with ``use_cache=False``), and the result file is written from
    those files lazily, so memory holds about one chunk at a time whatever the number
    of cases. A chunk that is in the cache, intact, is reused."""
    import shutil

    from .cache import GridChunkStore

    t0 = time.perf_counter()
    out_dir = Path(out_dir)
    name = str(src.data["name"])
    workers = workers or default_workers()
    lock = tidy(out_dir, name, out_dir / ".cache" / name if use_cache else None)
    if use_cache:
        folder = out_dir / ".cache" / name
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
            ds = grid_dataset_from(src, grid, ordered, summary, lazy=True)
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
    # a study run as arrays has no database (cablestudy.grid refuses one): a database
    # file of this name is an earlier run's, which no longer describes the study
    from .database_file import database_file_name

    (out_dir / database_file_name(name)).unlink(missing_ok=True)
    if lock is not None:
        if lock.alone():  # no other run of the study writing here
            store.keep(set(files.values()) - transient)
        lock.release()
    return RunSummary(
        path=path,
        n_cases=grid.size,
        n_reused=n_reused,
        n_computed=grid.size - n_reused,
        n_failed=sum(summary.failures.values()),
        wall_time=time.perf_counter() - t0,
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
    """A chunk file of the cache as a :class:`cablestudy.grid.GridChunk`."""
    from .grid import GridChunk

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


def _grid_settings(grid: Any) -> dict[str, Any]:
    """:func:`default_solver_settings` of the grid's cases: the first case's analysis
    settings and, where the sweep changes them, every distinct one."""
    if not any(p.startswith("analysis.") for p in getattr(grid, "validated", {})):
        return {
            "analysis": grid.template.analysis.model_dump(mode="json"),
            "static_methods": [grid.template.analysis.static.method],
        }
    import itertools

    from .grid_static import case_study

    swept = {p: v for p, v in grid.validated.items() if p.startswith("analysis.")}
    axes = sorted({k for k, _ in swept.values()})
    settings = []
    for index in itertools.product(*(range(grid.shape[k]) for k in axes)):
        at = dict(zip(axes, index, strict=True))
        study = case_study(grid.template, {p: vals[at[k]] for p, (k, vals) in swept.items()})
        settings.append(study.analysis)
    dumps = [a.model_dump(mode="json") for a in settings]
    out: dict[str, Any] = {
        "analysis": dumps[0],
        "static_methods": sorted({a.static.method for a in settings}),
    }
    distinct = {json.dumps(d, sort_keys=True) for d in dumps}
    if len(distinct) > 1:
        out["analysis_per_case_distinct"] = [json.loads(d) for d in sorted(distinct)]
    return out


def _grid_variables(src: StudySource, grid: Any, chunks: list[Any]) -> tuple[Any, tuple]:
    """The summary of in-memory chunks (all rows of ``grid``, in order) and the dataset's
    (data variables, coordinates, attributes): the dataset
    :func:`cablestudy.results.grid_dataset` assembles from the chunk files."""
    from .cache import summarise
    from .results import grid_variables

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
        solver_settings=_grid_settings(grid),
        fallbacks=summary.fallbacks,
        named=getattr(grid, "named", None),  # a system's (cablestudy.system_grid)
    )
    return summary, variables


def grid_dataset_from(
    src: StudySource, grid: Any, ordered: list[Any], summary: Any, *, lazy: bool = True
) -> Any:
    from .results import grid_dataset

    settings = _grid_settings(grid)
    return grid_dataset(
        grid.axes,
        ordered,
        src,
        names=summary.names,
        tails=summary.tails,
        arc=summary.arc,
        solver_settings=settings,
        lazy=lazy,
        fallbacks=summary.fallbacks,
        named=getattr(grid, "named", None),  # a system's (cablestudy.system_grid)
    )


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
                from .grid import failed_grid_chunk

                chunk = failed_grid_chunk(grid, *futures[future], f"{LOST_PREFIX}{exc!r}")
            on_done(chunk)
            future.release()
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    return scheduler
