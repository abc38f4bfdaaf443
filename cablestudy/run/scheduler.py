"""The one execution loop of every study: its chunks serially, on threads, on local
processes or a dask cluster (``auto`` probes the first chunks' cost and chooses), with
the same progress, timeout, interrupt and failure handling whatever the work is: cases
(:class:`Cases`, a chunk per task sized to take about :data:`TARGET_TASK_SECONDS`) or
rows of a grid run as arrays (:class:`Rows`, fixed chunks). A task that dies fails its
cases, not the study.
"""

from __future__ import annotations

import contextlib
import math
import os
import signal
import sys
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..analyses.grid_chunk import GridChunk
from ..study.cases import Case
from .cache import LOST_PREFIX
from .remote import DEFAULT_TIMEOUT, connect

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
#: seconds a local worker process may take to start (connect to this process's
#: scheduler) or to stop: past it the start fails, and the run goes on threads
#: (:func:`_run_dask`), or the stop gives up and kills the workers (:func:`_close`)
CLUSTER_TIMEOUT = 60.0


def default_workers() -> int:
    """Worker processes for a local run: the cores this process may use (so 2 on a
    2-core machine), at most 8."""
    try:
        cores = len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        cores = os.cpu_count() or 1
    return max(1, min(cores, 8))


def run_chunk(cases: list[Case]) -> GridChunk:
    """Evaluate a chunk of cases in one task (cases sharing a static problem are
    adjacent, so its solution is reused; compatible static problems are batched), its
    records turned into the chunk form here, in the worker."""
    from ..analyses.evaluate import evaluate_cases

    return evaluate_cases(cases)


def _lost(exc: BaseException) -> str:
    """The message of the cases of a task that died outside the solvers."""
    return f"{LOST_PREFIX}{type(exc).__name__}: {exc}"


class Cases:
    """Cases of a study, in chunks sized by their measured cost (:func:`make_chunks`),
    a chunk's task :func:`run_chunk`."""

    shared = None
    sized = True

    def __init__(self, cases: list[Case]) -> None:
        self.units = cases

    @staticmethod
    def run(shared: None, batch: list[Case]) -> GridChunk:
        return run_chunk(batch)

    @staticmethod
    def fail(shared: None, batch: list[Case], exc: BaseException) -> GridChunk:
        """The chunk of cases whose task died outside the solvers (a worker lost, an
        unpicklable result): every case failed with the reason, no data, not cached."""
        from ..analyses.grid_chunk import failed_chunk

        hashes = np.array([c.hash for c in batch], dtype=str).reshape(len(batch))
        return failed_chunk(len(batch), _lost(exc), hashes=hashes, status=STATUS_TASK_FAILED)

    @staticmethod
    def batches(units: list[Case], workers: int, per_case: float | None) -> list[Any]:
        return make_chunks(units, workers, per_case=per_case)

    def probe(self, on_done: OnDone, seconds: float) -> Probe:
        return probe_cost(self.units, on_done, seconds)

    def share(self) -> None:
        """Solve the first case's statics in this process (cached by static hash, so
        worker processes forked afterwards reuse it). A failure is left for the case
        itself to record where it runs."""
        from ..analyses.static import solve_static

        first = min(self.units, key=lambda c: (c.static_hash, c.index))
        with contextlib.suppress(Exception):
            solve_static(first, None)


class Rows:
    """Rows ``lo:hi`` of a grid run as arrays
    (:func:`cablestudy.analyses.static_grid.evaluate_grid_chunk`): fixed chunks, each its
    own task, the grid sent to the workers once."""

    sized = False

    def __init__(self, grid: Any, spans: list[tuple[int, int]]) -> None:
        self.shared, self.units = grid, spans

    @staticmethod
    def run(grid: Any, span: tuple[int, int]) -> GridChunk:
        from ..analyses import static_grid

        return static_grid.evaluate_grid_chunk(grid, *span)

    @staticmethod
    def fail(grid: Any, span: tuple[int, int], exc: BaseException) -> GridChunk:
        from ..analyses.grid_chunk import failed_grid_chunk

        return failed_grid_chunk(grid, *span, _lost(exc))

    @staticmethod
    def batches(units: list[Any], workers: int, per_case: float | None) -> list[Any]:
        return list(units)

    def probe(self, on_done: OnDone, seconds: float) -> Probe:
        """The first chunk here, timed: the cost of a chunk."""
        t0 = time.perf_counter()
        on_done(self.run(self.shared, self.units[0]))
        return Probe(self.units[1:], time.perf_counter() - t0)

    def share(self) -> None:
        pass


Work = Cases | Rows


def chunk_limit(per_case: float | None) -> int:
    """Cases per task: as many as take :data:`TARGET_TASK_SECONDS` at ``per_case``
    seconds a case (between 1 and :data:`MAX_CHUNK_CASES`), or
    :data:`DEFAULT_CHUNK_CASES` when the cost is not known."""
    if per_case is None or not per_case > 0 or not math.isfinite(per_case):
        return DEFAULT_CHUNK_CASES
    return int(max(1, min(MAX_CHUNK_CASES, round(TARGET_TASK_SECONDS / per_case))))


def make_chunks(
    cases: list[Case], workers: int, *, per_case: float | None = None
) -> list[list[Case]]:
    """Batch cases so that a task takes about :data:`TARGET_TASK_SECONDS` (``per_case``:
    the measured cost of a case [s]; unknown: at most :data:`DEFAULT_CHUNK_CASES` cases),
    while every worker gets several chunks (four, load balance) and an interrupt loses at
    most one chunk per worker."""
    if not cases:
        return []
    max_chunk = chunk_limit(per_case)
    ordered = sorted(cases, key=lambda c: (c.static_hash, c.index))
    n_chunks = max(min(len(ordered), workers * 4), math.ceil(len(ordered) / max_chunk))
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


OnDone = Callable[[GridChunk], None]


@dataclass
class Probe:
    """What the in-process probe learned: the cases it left, the cost of a case [s] at
    the largest chunk it ran, and (if timed) the speed-up of two threads over one."""

    rest: list[Case]
    per_case: float
    thread_speedup: float | None = None


def probe_cost(
    cases: list[Case], on_done: OnDone, seconds: float, fill: bool = False, first: int = 1
) -> Probe:
    """Run ``cases`` here in doubling chunks (``first``, twice that, ... cases, so that
    cheap cases are timed batched as they will run) until ``seconds`` have passed; the
    cost of a case is that of the last (largest) chunk. The probe's records count:
    nothing is computed twice. ``fill``: after the first, a chunk takes at least as many
    cases as the time left would hold at the last chunk's cost a case (cases solved as
    arrays a chunk at a time, whose chunk costs about a case more than its cases)."""
    ordered = sorted(cases, key=lambda c: (c.static_hash, c.index))
    # probe cases spread over the sweep (bit-reversed order: its ends, its middle, its
    # quarters, ...): a sweep's cost changes along its axes (a dynamic sweep's large
    # amplitudes and high frequencies cost many times its small ones), and its first
    # cases alone would predict the cheap corner
    spread = sorted(range(len(ordered)), key=lambda i: _radical_inverse(i))
    probed: set[int] = set()
    t_start = time.perf_counter()
    size, per_case, pos = max(1, first), math.nan, 0
    while pos < len(spread):
        take = spread[pos : pos + size]
        pos += len(take)
        chunk = [ordered[i] for i in sorted(take)]
        t0 = time.perf_counter()
        on_done(run_chunk(chunk))
        per_case = (time.perf_counter() - t0) / len(chunk)
        probed.update(take)
        elapsed = time.perf_counter() - t_start
        if elapsed >= seconds:
            break
        size *= 2
        if fill and per_case > 0.0:
            size = max(size, min(MAX_CHUNK_CASES, int((seconds - elapsed) / per_case)))
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
    for chunk in results:
        on_done(chunk)
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


def _run_here(work: Work, units: list[Any], on_done: OnDone, per_case: float | None) -> None:
    for batch in work.batches(units, 1, per_case):
        on_done(work.run(work.shared, batch))


def _run_auto(work: Work, workers: int, on_done: OnDone) -> str:
    """Probe the cost of the work in this process and choose (:func:`choose_scheduler`;
    threads are timed for cases, whose chunks can be cut to size); the probe's part is
    done by then. Returns the scheduler used for the rest."""
    probe = work.probe(on_done, AUTO_PROBE_SECONDS)
    if work.sized and workers > 1 and probe.per_case * len(probe.rest) > AUTO_PARALLEL_AFTER:
        probe = probe_threads(probe, on_done, workers)
    chosen = choose_scheduler(probe, workers)
    if chosen == SYNCHRONOUS:
        _run_here(work, probe.rest, on_done, probe.per_case)
    else:
        _run_dask(work, probe.rest, chosen, workers, on_done, per_case=probe.per_case)
    return chosen


def _local_cluster(scheduler: str, workers: int):  # noqa: ANN202 - dask type, imported late
    """A local dask.distributed cluster. Worker processes are forked (on Linux) from this
    process, which has by then imported the solvers and loaded their compiled kernels
    (the probe ran cases here): a worker is ready in a fraction of a second instead of
    importing everything again (about 3 s on a 2-core machine)."""
    import dask
    from dask.distributed import LocalCluster

    method = "fork" if sys.platform.startswith("linux") else "spawn"
    # Ctrl-C reaches every process of the terminal's group: the workers start with it
    # ignored (a disposition both fork and spawn keep), so that only this process stops
    # the run (says so, closes the cluster) instead of each worker printing a traceback
    main = threading.current_thread() is threading.main_thread()
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN) if main else None
    try:
        with dask.config.set({"distributed.worker.multiprocessing-method": method}):
            return LocalCluster(
                n_workers=workers if scheduler == PROCESSES else 1,
                threads_per_worker=1 if scheduler == PROCESSES else workers,
                processes=scheduler == PROCESSES,
                dashboard_address=None,
                silence_logs=50,
                death_timeout=CLUSTER_TIMEOUT,
            )
    finally:
        if main:
            signal.signal(signal.SIGINT, previous)


def _run_dask(
    work: Work,
    units: list[Any],
    scheduler: str,
    workers: int,
    on_done: OnDone,
    *,
    per_case: float | None = None,
    timeout: float = DEFAULT_TIMEOUT,
) -> None:
    """``units`` of ``work`` on threads (:func:`_run_threads`), a local cluster or the
    dask scheduler at the address ``scheduler``. Cases of unknown cost go one per worker
    slot first, and the rest is chunked when the first of them is back."""
    if not units:
        return
    if scheduler == THREADS:
        _run_threads(work, units, workers, on_done, per_case=per_case)
        return
    from dask.distributed import Client, as_completed

    cluster = None
    if scheduler == PROCESSES:
        try:
            cluster = _local_cluster(scheduler, workers)
        except Exception as exc:  # noqa: BLE001 - the run goes on, on threads
            _say(
                f"the local worker processes did not start ({type(exc).__name__}: {exc}); "
                f"running the remaining {len(units)} chunks on {workers} threads instead"
            )
            _run_threads(work, units, workers, on_done, per_case=per_case)
            return
        client = Client(cluster)
    else:
        client = connect(scheduler, timeout)
        # chunk for the cluster as it is: one slot per worker thread
        info = client.scheduler_info()
        workers = max(1, sum(w.get("nthreads", 1) for w in info.get("workers", {}).values()))
    try:
        shared = None if work.shared is None else client.scatter(work.shared, broadcast=True)
        pending = list(units)
        first: list[Any] = []
        if work.sized and per_case is None:
            # the cost is not known yet: one case per worker slot first, timed on the
            # cluster itself
            first = [[c] for c in pending[:workers]]
            pending = pending[workers:]
        else:
            first, pending = work.batches(pending, workers, per_case), []
        batch_of: dict[str, Any] = {}

        def submit(batches: list[Any]) -> list[Any]:
            futures = [client.submit(work.run, shared, b, pure=False) for b in batches]
            batch_of.update({f.key: b for f, b in zip(futures, batches, strict=True)})
            return futures

        done = as_completed(submit(first))
        for future in done:
            try:
                chunk = future.result()
            except Exception as exc:  # noqa: BLE001 - a lost task fails its cases, not the study
                chunk = work.fail(work.shared, batch_of[future.key], exc)
            on_done(chunk)
            future.release()
            if pending:
                times = chunk.wall_time[np.isfinite(chunk.wall_time)]
                cost = float(times.mean()) if len(times) else None
                done.update(submit(work.batches(pending, workers, cost)))
                pending = []
    finally:
        _close(client, cluster)


def _say(message: str) -> None:
    print(f"warning: {message}", file=sys.stderr)


def _close(client: Any, cluster: Any) -> None:
    """Close ``client`` and the local ``cluster`` (if any) within :data:`CLUSTER_TIMEOUT`
    each: every result has reached the caller by then, so a stop that hangs (a worker
    process that does not exit) kills the workers and says so instead of holding the
    run."""
    import multiprocessing

    try:
        client.close(timeout=CLUSTER_TIMEOUT)
        if cluster is not None:
            cluster.close(timeout=CLUSTER_TIMEOUT)
    except Exception as exc:  # noqa: BLE001 - the results are in; only the stop failed
        stuck = [  # the cluster's own worker processes (distributed names them so)
            p for p in multiprocessing.active_children() if cluster is not None and "Dask" in p.name
        ]
        for process in stuck:
            process.kill()
        _say(
            f"the local worker processes did not stop ({type(exc).__name__}: {exc}); "
            f"killed {len(stuck)} of them (every result was already received)"
        )


def _guarded(work: Work, batch: Any) -> GridChunk:
    """A task of ``work``, its cases failed (not the study) if the task itself dies."""
    try:
        return work.run(work.shared, batch)
    except Exception as exc:  # noqa: BLE001 - a lost task fails its cases, not the study
        return work.fail(work.shared, batch, exc)


def _run_threads(
    work: Work, units: list[Any], workers: int, on_done: OnDone, *, per_case: float | None = None
) -> None:
    """The chunks on dask's local threaded scheduler (no dask.distributed: its import
    alone is about 0.4 s, a tenth of a few-second study). The solvers' compiled kernels
    release the GIL, so threads run cases in parallel. Each chunk's records reach
    ``on_done`` in this thread as the chunk finishes, and no copy is kept (bounded
    memory); chunks start in :func:`make_chunks` order (the scheduler takes the largest
    key first, hence the keys count down)."""
    import dask.threaded
    from dask.callbacks import Callback

    batches = work.batches(units, workers, per_case)
    n = len(batches)
    graph = {f"chunk-{n - 1 - i:08d}": (_guarded, work, b) for i, b in enumerate(batches)}

    def posttask(key: str, result: Any, dsk: Any, state: dict, worker_id: Any) -> None:
        on_done(result)
        state["cache"][key] = None

    with Callback(posttask=posttask):
        dask.threaded.get(graph, list(graph), num_workers=workers)


def execute(
    work: Work,
    scheduler: str,
    workers: int,
    on_done: OnDone,
    *,
    timeout: float = DEFAULT_TIMEOUT,
) -> str:
    """Evaluate ``work`` in chunks on ``scheduler``, calling ``on_done`` with each chunk
    as it finishes (in the calling process). Every local scheduler but 'processes' first
    times a few chunks here (``work.probe``), which sizes the chunks of cases to about a
    quarter second and loads the compiled kernels. Returns the scheduler that ran the
    work after the probe ("" when there was none)."""
    if not work.units:
        return ""
    if scheduler == AUTO:
        return _run_auto(work, workers, on_done)
    if "://" in scheduler:
        _run_dask(work, work.units, scheduler, workers, on_done, timeout=timeout)
        return scheduler
    if scheduler == SYNCHRONOUS or len(work.units) <= 1:
        probe = work.probe(on_done, PROBE_SECONDS)
        _run_here(work, probe.rest, on_done, probe.per_case)
        return SYNCHRONOUS
    # the forked workers share what this process has loaded: the compiled kernels
    # (analyses.warm_up, called before this by `cablestudy run`) and the first case's
    # static solution, solved here; no case runs here, so both workers start at once.
    # Chunks of cases are sized from the first cases timed on the workers.
    work.share()
    _run_dask(work, work.units, scheduler, workers, on_done)
    return scheduler
