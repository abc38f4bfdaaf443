"""Per-case evaluation: which solvers a case needs, run in order, into a record.

This is the only place that knows which analyses exist; the runner calls
:func:`evaluate_case` and moves records, knowing nothing of physics.
"""

from __future__ import annotations

import math
import time
import traceback
from collections import OrderedDict
from typing import Any

import numpy as np

from .cases import Case
from .config.loader import StudyError, StudySource
from .problem import static_problem
from .results import CaseRecord
from .statics import STATIC_SOLVERS, STATUS_NUMERICAL, STATUS_OK, StaticResult

#: static solutions already computed in this process, by static hash (a sweep over
#: excitation parameters solves each distinct static problem once)
_STATIC_CACHE: OrderedDict[str, StaticResult] = OrderedDict()
_STATIC_CACHE_SIZE = 64


def check_supported(cases: list[Case], src: StudySource) -> None:
    """Raise :class:`StudyError` (before any work) when a case asks a solver for a
    feature it does not have."""
    problems: list[str] = []
    seen: set[str] = set()
    for case in cases:
        if case.static_hash in seen:
            continue
        seen.add(case.static_hash)
        method = case.study.analysis.static.method
        missing = STATIC_SOLVERS[method].unsupported(static_problem(case.study))
        for item in missing:
            line = src.line_of(("analysis", "static", "method")) or src.line_of(("analysis",))
            msg = (f"{line}: analysis.static.method: {method!r} does not support {item}; "
                   f"choose another method (available: {', '.join(sorted(STATIC_SOLVERS))})")
            if msg not in problems:
                problems.append(msg)
    if problems:
        raise StudyError(problems, src.source)


def solve_static(case: Case, deadline: float | None,
                 presolved: dict[str, StaticResult] | None = None) -> StaticResult:
    if presolved is not None and case.static_hash in presolved:
        return presolved[case.static_hash]
    cached = _STATIC_CACHE.get(case.static_hash)
    if cached is not None:
        _STATIC_CACHE.move_to_end(case.static_hash)
        return cached
    problem = static_problem(case.study)
    result = STATIC_SOLVERS[case.study.analysis.static.method].solve(problem, deadline=deadline)
    result = result.check_finite()
    _STATIC_CACHE[case.static_hash] = result
    while len(_STATIC_CACHE) > _STATIC_CACHE_SIZE:
        _STATIC_CACHE.popitem(last=False)
    return result


def static_outputs(res: StaticResult) -> dict[str, np.ndarray]:
    return {
        "arc_length": res.s,
        "x": res.position[:, 0],
        "y": res.position[:, 1],
        "z": res.position[:, 2],
        "tension": res.tension,
        "force_a": res.force_a,
        "force_b": res.force_b,
        "tension_a": np.asarray(np.linalg.norm(res.force_a)),
        "tension_b": np.asarray(np.linalg.norm(res.force_b)),
        "laid_length": np.asarray(res.laid_length),
        "static_iterations": np.asarray(res.iterations),
        "static_residual": np.asarray(res.residual),
        "drag_iterations": np.asarray(res.drag_iterations),
    }


def evaluate_case(case: Case, *,
                  presolved: dict[str, StaticResult] | None = None) -> CaseRecord:
    """Run every analysis the case asks for. Never raises: an exception inside a solver
    becomes a failed record with the exception's text. ``presolved`` maps static hashes
    to static solutions already computed (by :func:`evaluate_chunk`)."""
    t0 = time.perf_counter()
    deadline = time.monotonic() + case.study.analysis.time_limit
    data: dict[str, Any] = {}
    try:
        res = solve_static(case, deadline, presolved)
        status, message = res.status, res.message
        data.update(static_outputs(res))
    except Exception as exc:  # noqa: BLE001 - any solver fault is recorded as data
        status = STATUS_NUMERICAL
        tb = traceback.extract_tb(exc.__traceback__)
        where = f" at {tb[-1].name}:{tb[-1].lineno}" if tb else ""
        message = f"{type(exc).__name__}: {exc}{where}"
    if status == STATUS_OK:
        bad = [k for k, v in data.items()
               if np.asarray(v).dtype.kind == "f" and not np.all(np.isfinite(v))]
        if bad:
            status, message = STATUS_NUMERICAL, f"non-finite values in {', '.join(sorted(bad))}"
    wall = time.perf_counter() - t0
    if not math.isfinite(wall):
        wall = 0.0
    return CaseRecord(hash=case.hash, index=case.index, status=int(status), message=message,
                      wall_time=wall, data=data)


def presolve_statics(cases: list[Case]) -> tuple[dict[str, StaticResult], dict[str, float]]:
    """Solve the distinct still-water static problems of method 'catenary' in ``cases``
    together (:func:`cablestudy.statics.batch.solve_batch`). Returns the solutions by
    static hash and each one's share of the batch wall time [s]. Anything unexpected
    leaves the cases to the one-by-one path (which records its own errors)."""
    from .statics.batch import batchable, solve_batch

    todo: dict[str, Any] = {}
    for case in cases:
        h = case.static_hash
        if h in todo or h in _STATIC_CACHE or case.study.analysis.static.method != "catenary":
            continue
        try:
            problem = static_problem(case.study)
        except Exception:  # noqa: BLE001 - the per-case path reports it
            continue
        if batchable(problem):
            todo[h] = (problem, case.study.analysis.time_limit)
    if len(todo) < 2:
        return {}, {}
    t0 = time.perf_counter()
    try:
        deadline = time.monotonic() + max(limit for _, limit in todo.values())
        results = solve_batch([p for p, _ in todo.values()], deadline=deadline)
    except Exception:  # noqa: BLE001 - fall back to one case at a time
        return {}, {}
    share = (time.perf_counter() - t0) / len(todo)
    solved = {h: r.check_finite() for h, r in zip(todo, results, strict=True)}
    return solved, dict.fromkeys(solved, share)


def evaluate_chunk(cases: list[Case]) -> list[CaseRecord]:
    """Evaluate a chunk of cases in one task: compatible static problems are solved as
    one batch first, then every case runs as in :func:`evaluate_case` (its wall time
    includes its share of the batch)."""
    solved, share = presolve_statics(cases)
    records = []
    for case in cases:
        rec = evaluate_case(case, presolved=solved)
        if case.static_hash in share:
            rec.wall_time += share.pop(case.static_hash)
        records.append(rec)
    return records
