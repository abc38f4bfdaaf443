"""The static analysis of a validated case: the static solver of its method (the
spring and pulley statics for those lines), solutions kept per static problem in this
process, the outputs along the line, what a method cannot do (refused before any work),
and the distinct still-water problems of a chunk solved as one batch
(:func:`presolve_statics`).
"""

from __future__ import annotations

import time
from collections import OrderedDict
from dataclasses import replace
from typing import Any

import numpy as np

from ..physics.profile import end_pulls, profile_quantities
from ..statics import (
    STATIC_SOLVERS,
    STATUS_NO_SOLUTION,
    STATUS_TIME_LIMIT,
    StaticResult,
)
from ..statics.limits import apply_limits
from ..study.cases import Case
from ..study.loader import StudySource
from ..study.problem import static_limits, static_problem
from .common import CheckedOutputs, non_finite_outputs, segment_of
from .counters import COUNTERS, trim_lru
from .plausibility import largest_strain

#: static solutions already computed in this process, by static hash (a sweep over
#: excitation parameters solves each distinct static problem once)
_STATIC_CACHE: OrderedDict[str, StaticResult] = OrderedDict()
_STATIC_CACHE_SIZE = 64


def law_problems(case: Case, src: StudySource) -> list[str]:
    """Break conditions and winches of a kind: catenary line that no analysis of the
    study would use: a failure time or a winch without analysis.dynamic (the statics
    are the state before any time), ``after_break`` without a break condition, and a
    winch whose stop is not after its start. (Method frequency refuses both through
    :func:`linear_model_gaps`; the time domain parts and winches the line.)"""
    study = case.study
    dyn = study.analysis.dynamic
    out: list[str] = []
    timed = [("line",)] if study.line.failure and study.line.failure.time is not None else []
    timed += [
        ("line", "segments", i)
        for i, seg in enumerate(study.line.segments)
        if seg.failure is not None and seg.failure.time is not None
    ]
    if dyn is None:
        for loc in timed:
            path = (*loc, "failure", "time")
            out.append(
                f"{src.line_of(path) or src.line_of(('line',))}: "
                f"{'.'.join(map(str, path))}: a failure time applies to analysis.dynamic "
                "(the time domain); the statics are the state before any time; "
                "allowed: omit it, or add analysis.dynamic"
            )
    winch = study.line.winch
    if winch is not None:
        at = src.line_of(("line", "winch")) or src.line_of(("line",))
        if dyn is None:
            out.append(
                f"{at}: line.winch: a winch changes the length in analysis.dynamic (the "
                "time domain); the statics ignore it (the state before it runs); "
                "allowed: omit it, or add analysis.dynamic"
            )
        elif winch.stop is not None and winch.stop <= winch.start:
            out.append(
                f"{at}: line.winch.stop: {winch.stop:g} s is not after start "
                f"{winch.start:g} s; allowed: stop > start"
            )
    breaks = study.line.failure is not None or any(
        seg.failure is not None for seg in study.line.segments
    )
    if dyn is not None and "after_break" in dyn.model_fields_set and not breaks:
        at = src.line_of(("analysis", "dynamic", "after_break")) or src.line_of(("analysis",))
        out.append(
            f"{at}: analysis.dynamic.after_break: {dyn.after_break!r} applies to a line "
            "that can part (line.failure or line.segments.N.failure, time domain); "
            "allowed: omit it, or add a failure condition"
        )
    return out


def unsupported_static(method: str, problem: Any) -> list[str]:
    """What the static ``method`` cannot model in ``problem``: its own list, and bending
    stiffness for the cable solvers (only method 'discrete' carries EI)."""
    missing = list(STATIC_SOLVERS[method].unsupported(problem))
    if method != "discrete" and np.any(problem.line.bending_stiffness > 0.0):
        missing.append("bending stiffness (bending_stiffness > 0; method 'discrete' models it)")
    if (
        method != "discrete"
        and problem.medium.has_current
        and problem.medium.density > 0.0
        and np.any(problem.line.attachment_drag_area > 0.0)
    ):
        missing.append(
            "the drag of lumped bodies in a current (line.attachments.*.drag_area > 0; "
            "method 'discrete' models it)"
        )
    return missing


def solve_static(
    case: Case, deadline: float | None, presolved: dict[str, StaticResult] | None = None
) -> StaticResult:
    if presolved is not None and case.static_hash in presolved:
        return apply_limits(presolved[case.static_hash], static_limits(case.study))
    cached = _STATIC_CACHE.get(case.static_hash)
    if cached is not None:
        try:
            _STATIC_CACHE.move_to_end(case.static_hash)
        except KeyError:  # evicted by another thread
            pass
        return cached
    if case.study.line.is_spring:
        from .spring import solve_spring_static

        return apply_limits(solve_spring_static(case.study), static_limits(case.study))
    problem = static_problem(case.study)
    method = case.study.analysis.static.method
    solver = STATIC_SOLVERS[method]
    missing = unsupported_static(method, problem)
    if case.study.line.pulleys and not missing:
        from .pulley import solve_pulley_static

        result = solve_pulley_static(case.study, deadline).check_finite()
    elif missing:
        # the CLI rejects these before any work (check_supported); a caller that skips
        # that check still gets a failure rather than a solution that ignores an input
        return StaticResult.failed(
            np.linspace(0.0, problem.line.total_length, problem.n_nodes),
            STATUS_NO_SOLUTION,
            f"static method {method!r} does not support {'; '.join(missing)}",
        )
    else:
        result = solver.solve(problem, deadline=deadline).check_finite()
    result = apply_limits(result, static_limits(case.study))
    COUNTERS["static_solves"] += 1
    _keep(case.static_hash, result)
    return result


def _keep(key: str, result: StaticResult) -> None:
    """Keep ``result`` for the cases of the same static solution (``key``), unless it
    ran out of time: the time limit is not part of that key, so a case with a longer
    one (or the same one, on a less loaded machine) solves it again."""
    if result.status != STATUS_TIME_LIMIT:
        _STATIC_CACHE[key] = result
        trim_lru(_STATIC_CACHE, _STATIC_CACHE_SIZE)


def static_at(case: Case, n_nodes: int, deadline: float | None) -> StaticResult:
    """The case's static solution sampled at ``n_nodes`` points (cached)."""
    key = f"{case.static_hash}:nodes={n_nodes}"
    cached = _STATIC_CACHE.get(key)
    if cached is None:
        problem = replace(static_problem(case.study), n_nodes=n_nodes)
        solver = STATIC_SOLVERS[case.study.analysis.static.method]
        cached = solver.solve(problem, deadline=deadline).check_finite()
        COUNTERS["static_solves"] += 1
        _keep(key, cached)
    return cached


def static_outputs(res: StaticResult, study: Any = None) -> dict[str, np.ndarray]:
    """The static solution's outputs; with the case's ``study``, also the quantities
    derived along the line (:func:`cablestudy.physics.profile.profile_quantities`)."""
    out = {
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
    if getattr(res, "pulley_force", None) is not None:  # a line over pulleys
        out["pulley_force"] = np.asarray(res.pulley_force)
    if getattr(res, "split", None) is not None:  # a catenary line over pulleys
        out["pulley_arc_length"] = np.asarray(res.split)
    if study is not None and not study.line.is_spring:
        env = study.environment
        segs = study.line.segments
        k = segment_of(segs, res.s)
        out.update(
            profile_quantities(
                res.s,
                res.position,
                res.tension,
                axial_stiffness=np.array([segs[i].elastic_stiffness for i in k]),
                strain=_strain_along(segs, k, res.tension),
                area=np.array([segs[i].area for i in k]),
                density=env.density,
                gravity=env.gravity,
                end_pull=end_pulls(
                    res.force_a,
                    res.force_b,
                    **tangent_ends(study.line, study.analysis.static.tolerance, res.tension),
                ),
            )
        )
    return out


def tangent_ends(line: Any, tolerance: float, tension: np.ndarray) -> dict[str, Any]:
    """The ``free_a``, ``free_b`` and ``floor`` of :func:`~cablestudy.physics.profile.end_pulls`
    for a line (its study model) solved to the relative ``tolerance`` with ``tension``
    (..., n) [N]: an end is free without bending stiffness in its segment and without an
    attachment at it; the floor is the verification's force allowance, 10 tolerance
    times the largest tension (:mod:`cablestudy.statics.verify`)."""
    segs = line.segments
    total = sum(seg.length for seg in segs)
    near = 1e-9 * total  # an attachment put at the end, up to the round-off of its s
    at = [att.s for att in line.attachments]
    return {
        "free_a": segs[0].bending_stiffness == 0.0 and not any(s <= near for s in at),
        "free_b": segs[-1].bending_stiffness == 0.0 and not any(s >= total - near for s in at),
        "floor": 10.0 * tolerance * np.max(np.abs(np.asarray(tension, dtype=float)), axis=-1),
    }


#: the static outputs of the last static solution, with that solution and the names of
#: its non-finite outputs: the cases of a chunk that share a static problem (adjacent in
#: a chunk: a sweep over excitation) share its outputs instead of deriving (and
#: checking) them again per case
_LAST_STATIC_OUTPUTS: dict[str, tuple[StaticResult, dict[str, np.ndarray], list[str]]] = {}


def shared_static_outputs(case: Case, res: StaticResult) -> CheckedOutputs:
    """:func:`static_outputs` of ``res`` for ``case``, reused from the previous case when
    it had the same static problem and the very same solution object (the arrays are
    shared, as the static solution's own arrays already are between such cases), with
    their non-finite variables (:func:`non_finite_outputs`)."""
    hit = _LAST_STATIC_OUTPUTS.get(case.static_hash)
    if hit is None or hit[0] is not res:
        out = static_outputs(res, case.study)
        hit = (res, out, non_finite_outputs(out, "static"))
        _LAST_STATIC_OUTPUTS.clear()
        _LAST_STATIC_OUTPUTS[case.static_hash] = hit
    shared = CheckedOutputs(hit[1])
    shared.non_finite = hit[2]
    return shared


def _strain_along(segs: Any, k: np.ndarray, tension: np.ndarray) -> np.ndarray | None:
    """Strain at each point from its segment's axial law (None: all linear, T / EA)."""
    if not any(seg.is_nonlinear for seg in segs):
        return None
    strain = np.asarray(tension, dtype=float) / np.array([segs[i].elastic_stiffness for i in k])
    for i, seg in enumerate(segs):
        if seg.is_nonlinear:
            on = k == i
            strain[on] = seg.axial_law().strain(np.asarray(tension)[on])
    return strain


def largest_static_strain(study: Any, res: StaticResult) -> float:
    """The largest strain [-] of a static solution: per point the axial law's strain
    (T / EA where linear) of its segment; kind spring: the extension over the
    unstretched length (the stretched length is the path through the points)."""
    line = study.line
    if line.is_spring:
        stretched = float(np.linalg.norm(np.diff(res.position, axis=0), axis=1).sum())
        return (stretched - line.total_length) / line.total_length
    segs = line.segments
    k = segment_of(segs, res.s)
    ea = np.array([seg.elastic_stiffness for seg in segs])[k]
    return float(largest_strain(res.tension, ea, _strain_along(segs, k, res.tension)))


def presolve_statics(cases: list[Case]) -> tuple[dict[str, StaticResult], dict[str, float]]:
    """Solve the distinct still-water static problems of method 'catenary' in ``cases``
    together (:func:`cablestudy.statics.batch.solve_batch`). Returns the solutions by
    static hash and each one's share of the batch wall time [s]. Anything unexpected
    leaves the cases to the one-by-one path (which records its own errors)."""
    from ..statics.batch import solve_batch
    from ..statics.batch_drag import drag_eligible
    from ..statics.batch_kernels import batchable, contact_eligible

    todo: dict[str, Any] = {}
    for case in cases:
        h = case.static_hash
        if h in todo or h in _STATIC_CACHE or case.study.analysis.static.method != "catenary":
            continue
        if case.study.line.is_spring or case.study.line.pulleys:
            continue
        try:
            problem = static_problem(case.study)
        except Exception:  # noqa: BLE001 - the per-case path reports it
            continue
        # a line anchored on the seabed too: solve_batch takes it to the compiled
        # contact kernel with the others of its seabed (one by one, each case paid the
        # kernel's set-up and was verified twice: 7 ms a case, 3x the batch's)
        # and a line hanging free in a current: the compiled drag iteration, per case
        if batchable(problem) or contact_eligible(problem) or drag_eligible(problem):
            todo[h] = (problem, case.study.analysis.time_limit)
    if len(todo) < 2:
        return {}, {}
    t0 = time.perf_counter()
    try:
        deadline = time.monotonic() + max(limit for _, limit in todo.values())
        results = solve_batch([p for p, _ in todo.values()], deadline=deadline)
    except Exception:  # noqa: BLE001 - fall back to one case at a time
        return {}, {}
    COUNTERS["static_solves"] += len(todo)
    share = (time.perf_counter() - t0) / len(todo)
    solved = {h: r.check_finite() for h, r in zip(todo, results, strict=True)}
    return solved, dict.fromkeys(solved, share)
