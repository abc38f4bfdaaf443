"""Per-case evaluation: which solvers a case needs, run in order, into a record.

This is the only place that knows which analyses exist; the runner calls
:func:`evaluate_case` and moves records, knowing nothing of physics.
"""

from __future__ import annotations

import math
import time
import traceback
from collections import OrderedDict
from dataclasses import replace
from typing import Any

import numpy as np

from .cases import Case
from .config.loader import StudyError, StudySource
from .dynamics.modal import (
    ModalProblem,
    ModalResult,
    graded_arc_lengths,
    modal_analysis,
    snap_to_samples,
    subset_static,
    transverse_mass,
)
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
        problem = static_problem(case.study)
        missing = STATIC_SOLVERS[method].unsupported(problem)
        if case.study.analysis.modal is not None:
            for i, mass in enumerate(problem.line.mass):
                if not mass > 0.0:
                    loc = ("line", "segments", str(i), "mass_per_length")
                    msg = (f"{src.line_of(loc) or src.line_of(('line',))}: "
                           f"line.segments.{i}.mass_per_length: {mass:g} kg/m; analysis.modal "
                           "needs a positive mass per length (allowed: > 0)")
                    if msg not in problems:
                        problems.append(msg)
        for item in missing:
            line = src.line_of(("analysis", "static", "method")) or src.line_of(("analysis",))
            msg = (f"{line}: analysis.static.method: {method!r} does not support {item}; "
                   f"choose another method (available: {', '.join(sorted(STATIC_SOLVERS))})")
            if msg not in problems:
                problems.append(msg)
    if problems:
        raise StudyError(problems, src.source)


def solve_static(case: Case, deadline: float | None) -> StaticResult:
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


#: most static sample points asked for to place the nodes of a graded modal mesh
MODAL_MAX_SAMPLES = 200_001


def _static_at(case: Case, n_nodes: int, deadline: float | None) -> StaticResult:
    """The case's static solution sampled at ``n_nodes`` points (cached)."""
    key = f"{case.static_hash}:nodes={n_nodes}"
    cached = _STATIC_CACHE.get(key)
    if cached is None:
        problem = replace(static_problem(case.study), n_nodes=n_nodes)
        solver = STATIC_SOLVERS[case.study.analysis.static.method]
        cached = solver.solve(problem, deadline=deadline).check_finite()
        _STATIC_CACHE[key] = cached
        while len(_STATIC_CACHE) > _STATIC_CACHE_SIZE:
            _STATIC_CACHE.popitem(last=False)
    return cached


def solve_modal(case: Case, static: StaticResult, deadline: float | None) -> ModalResult:
    """Modal analysis about the static shape on ``analysis.modal.n_elements`` elements.

    ``uniform`` mesh: the static shape at n_elements + 1 equally spaced points (reused
    when the static output has exactly those). ``graded`` mesh: node positions of equal
    transverse-wave travel time are computed from the static tension, and the static
    solution is sampled uniformly fine enough (at least 8 samples in the shortest
    element, an integer number per uniform element) to take the nearest sample for
    each node, so every node lies exactly on the static solution."""
    settings = case.study.analysis.modal
    assert settings is not None
    problem = static_problem(case.study)
    n_el = settings.n_elements
    if settings.mesh == "uniform" or not static.success:
        n_nodes = n_el + 1
        mesh_static = static if n_nodes == len(static.s) else _static_at(case, n_nodes, deadline)
    else:
        mass = transverse_mass(problem.line, problem.medium, static.s,
                               include_added_mass=settings.include_added_mass)
        targets = graded_arc_lengths(static.s, static.tension, mass, n_el,
                                     joints=problem.line.segment_ends)
        shortest = float(np.min(np.diff(targets)))
        total = float(static.s[-1] - static.s[0])
        per_element = max(8, math.ceil(8.0 * total / (shortest * n_el)))
        per_element = min(per_element, max(1, (MODAL_MAX_SAMPLES - 1) // n_el))
        fine = _static_at(case, n_el * per_element + 1, deadline)
        mesh_static = (subset_static(fine, snap_to_samples(fine.s, targets))
                       if fine.success else fine)
    return modal_analysis(
        ModalProblem(line=problem.line, medium=problem.medium, end_a=problem.end_a,
                     end_b=problem.end_b, static=mesh_static, n_modes=settings.modes,
                     include_added_mass=settings.include_added_mass,
                     include_bending=settings.include_bending),
        deadline=deadline,
    )


def modal_outputs(res: ModalResult, s: np.ndarray, *, mode_shapes: bool) -> dict[str, np.ndarray]:
    out = {
        "natural_frequency": res.frequency,
        "modal_dof": np.asarray(res.n_dof),
    }
    if mode_shapes:
        out["mode_shape"] = res.shape_at(s)
    return out


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


def evaluate_case(case: Case) -> CaseRecord:
    """Run every analysis the case asks for. Never raises: an exception inside a solver
    becomes a failed record with the exception's text."""
    t0 = time.perf_counter()
    deadline = time.monotonic() + case.study.analysis.time_limit
    data: dict[str, Any] = {}
    try:
        res = solve_static(case, deadline)
        status, message = res.status, res.message
        data.update(static_outputs(res))
        modal = case.study.analysis.modal
        if modal is not None and status == STATUS_OK:
            mres = solve_modal(case, res, deadline)
            data.update(modal_outputs(mres, res.s, mode_shapes=modal.mode_shapes))
            if mres.status != STATUS_OK:
                status, message = mres.status, f"modal analysis: {mres.message}"
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
