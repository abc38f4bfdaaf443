"""Per-case evaluation: which analyses a case asks for, run in order, into a record.

This is the only place that knows which analyses exist: a chunk goes to the evaluator of
its study's kind (:data:`CHUNK_KINDS`: a system of lines, or one line), and a line's case
runs its statics, then each analysis of :data:`AFTER_STATICS` it asks for. A new
analysis kind is one module and one entry there. The runner calls
:func:`evaluate_chunk` and moves records, knowing nothing of physics.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..statics import (
    STATIC_SOLVERS,
    STATUS_BROKEN,
    STATUS_NUMERICAL,
    STATUS_OK,
    STATUS_TIME_LIMIT,
    StaticResult,
)
from ..study.cases import Case
from ..study.loader import StudyError, StudySource
from ..study.problem import static_problem
from ..study.study import Study
from .common import STATUS_NOT_RUN, exception_message, non_finite_outputs
from .dynamic import dynamic_problems, linear_model_problems, presolve_frequency, run_dynamic
from .fallback import static_fallback
from .grid_chunk import GridChunk, records_chunk
from .modal import modal_outputs, solve_modal
from .plausibility import (
    dynamic_warnings,
    fallback_warning,
    joined,
    strain_warning,
    take_step_warning,
)
from .static import (
    largest_static_strain,
    law_problems,
    presolve_statics,
    shared_static_outputs,
    solve_static,
    unsupported_static,
)
from .surface import case_surface_warning
from .unused_keys import unused_key_problems
from .variables import CaseRecord


def check_supported(cases: list[Case], src: StudySource) -> None:
    """Raise :class:`StudyError` (before any work) when a case asks a solver for a
    feature it does not have."""
    problems: list[str] = []
    seen: set[str] = set()
    for case in cases:
        if case.static_hash in seen:
            continue
        seen.add(case.static_hash)
        if case.study.is_system:
            continue  # what a system cannot do is refused by the study model itself
        problems.extend(p for p in unused_key_problems(case, src) if p not in problems)
        if case.study.line.is_spring:
            from .spring import spring_problems

            problems.extend(p for p in spring_problems(case, src) if p not in problems)
            if case.study.analysis.database is not None:  # refused there, by name
                from .database import database_problems

                problems.extend(p for p in database_problems(case, src) if p not in problems)
            continue
        problems.extend(p for p in law_problems(case, src) if p not in problems)
        if case.study.line.pulleys:
            from .pulley import pulley_problems

            problems.extend(p for p in pulley_problems(case, src) if p not in problems)
        if case.study.analysis.database is not None and not case.study.line.pulleys:
            from .database import database_problems

            problems.extend(p for p in database_problems(case, src) if p not in problems)
        method = case.study.analysis.static.method
        problem = static_problem(case.study)
        missing = unsupported_static(method, problem)
        if case.study.analysis.modal is not None:
            for i, mass in enumerate(problem.line.mass):
                if not mass > 0.0:
                    loc = ("line", "segments", str(i), "mass_per_length")
                    msg = (
                        f"{src.line_of(loc) or src.line_of(('line',))}: "
                        f"line.segments.{i}.mass_per_length: {mass:g} kg/m; analysis.modal "
                        "needs a positive mass per length (allowed: > 0)"
                    )
                    if msg not in problems:
                        problems.append(msg)
        for item in missing:
            line = src.line_of(("analysis", "static", "method")) or src.line_of(("analysis",))
            msg = (
                f"{line}: analysis.static.method: {method!r} does not support {item}; "
                f"choose another method (available: {', '.join(sorted(STATIC_SOLVERS))})"
            )
            if msg not in problems:
                problems.append(msg)
    problems.extend(p for p in dynamic_problems(cases, src) if p not in problems)
    problems.extend(p for p in linear_model_problems(cases, src) if p not in problems)
    grids = sorted(
        {c.study.analysis.database.grid for c in cases if c.study.analysis.database is not None}
    )
    if len(grids) > 1:
        where = src.line_of(("analysis", "database")) or ""
        problems.append(
            f"{where}: analysis.database.grid: the sweep gives grids {grids}; the database "
            "file holds one grid kind; allowed: the same grid in every case (run one study "
            "per grid kind)"
        )
    if problems:
        raise StudyError(problems, src.source)


def warm_up(cases: list[Case]) -> None:
    """Load the compiled kernels the cases will need, before any case is timed (the
    runner's scheduler choice probes the first cases: a kernel's one-off load is
    start-up, not case cost). Not part of validation, which must stay light."""
    if cases and cases[0].study.is_system:
        return  # a system's kernels load with its first case (shared by the sweep)
    if any(
        c.study.analysis.dynamic is not None and c.study.analysis.dynamic.method != "time"
        for c in cases
    ):
        from ..dynamics.harmonic_cases import warm_up as warm_up_harmonic

        warm_up_harmonic()
    if any(
        c.study.analysis.dynamic is not None
        and c.study.analysis.dynamic.method != "frequency"
        and c.study.line.kind != "spring"
        for c in cases
    ):
        from ..dynamics.timedomain import warm_up as warm_up_time

        warm_up_time()


@dataclass(frozen=True)
class AfterStatics:
    """An analysis that starts from a case's static solution: whether the case asks for
    it, and how it runs: ``solve(case, static, deadline, linear)`` gives (status,
    message, outputs), ``linear`` being the case's frequency-domain outcome when the
    chunk solved it already (None otherwise)."""

    asked: Callable[[Study], bool]
    solve: Callable[[Case, StaticResult, float | None, Any], tuple[int, str, dict[str, Any]]]


def _modal(
    case: Case, static: StaticResult, deadline: float | None, linear: Any
) -> tuple[int, str, dict[str, Any]]:
    settings = case.study.analysis.modal
    assert settings is not None
    mres = solve_modal(case, static, deadline)
    return (
        mres.status,
        mres.message,
        modal_outputs(mres, static.s, mode_shapes=settings.mode_shapes),
    )


def _dynamic(
    case: Case, static: StaticResult, deadline: float | None, linear: Any
) -> tuple[int, str, dict[str, Any]]:
    if linear is None:
        return run_dynamic(case, static, deadline)
    return run_dynamic(case, static, deadline, linear)


#: the analyses that start from the static solution, by the name of their status
#: variable (``<name>_status``), in the order they run; they do not run when the statics
#: failed (:data:`STATUS_NOT_RUN`)
AFTER_STATICS: dict[str, AfterStatics] = {
    "modal": AfterStatics(lambda study: study.analysis.modal is not None, _modal),
    "dynamic": AfterStatics(lambda study: study.analysis.dynamic is not None, _dynamic),
}


def evaluate_case(
    case: Case, *, presolved: dict[str, StaticResult] | None = None, linear: Any = None
) -> CaseRecord:
    """Run every analysis the case asks for. Never raises: an exception inside a solver
    becomes a failure of that analysis with the exception's text. ``presolved`` maps
    static hashes to static solutions already computed (by :func:`evaluate_chunk`);
    ``linear`` is the case's frequency-domain outcome when already solved (idem).

    Each analysis asked for records ``<analysis>_status`` (0 ok); a failed analysis
    blanks only its own variables at assembly (:func:`cablestudy.analyses.variables.analysis_ok`).
    The modal and dynamic analyses start from the static shape and do not run when it
    failed (:data:`STATUS_NOT_RUN`); a failed modal analysis does not stop the dynamics,
    which does not use the modes. The case's ``status`` is that of the first failed
    analysis (:data:`STATUS_TIME_LIMIT` if any hit the time limit, so that the runner
    does not cache it); its ``message`` is the static solver's message, or names each
    failed analysis ("modal analysis: ...; dynamic analysis: ...").

    Results kept but implausible or risky get a ``warning`` (:func:`case_warnings`)."""
    t0 = time.perf_counter()
    deadline = time.monotonic() + case.study.analysis.time_limit
    data: dict[str, Any] = {}
    outcome: dict[str, tuple[int, str]] = {}

    def run(analysis: str, solve: Any) -> None:
        try:
            status, message, out = solve()
        except Exception as exc:  # noqa: BLE001 - any solver fault is recorded as data
            status, message, out = STATUS_NUMERICAL, exception_message(exc), {}
        data.update(out)
        if status == STATUS_OK:
            bad = non_finite_outputs(out, analysis)
            if bad:
                status, message = STATUS_NUMERICAL, f"non-finite values in {', '.join(bad)}"
        outcome[analysis] = (int(status), message)

    static: list[StaticResult] = []

    def statics() -> tuple[int, str, dict[str, Any]]:
        res = solve_static(case, deadline, presolved)
        static.append(res)
        return res.status, res.message, shared_static_outputs(case, res)

    run("static", statics)
    for name, kind in AFTER_STATICS.items():
        if not kind.asked(case.study):
            continue
        if outcome["static"][0] != STATUS_OK:
            outcome[name] = (STATUS_NOT_RUN, "not run: the static analysis failed")
        else:
            run(name, lambda kind=kind: kind.solve(case, static[0], deadline, linear))
    for name, (st, _) in outcome.items():
        data[f"{name}_status"] = np.asarray(st, dtype=np.int64)
    if case.study.analysis.database is not None and outcome["static"][0] in (
        STATUS_OK,
        STATUS_BROKEN,
    ):
        # the quasi-static database: static solves of its own grid, kept with the case
        from .database import solve_database

        try:
            data.update(solve_database(case.study, deadline))
        except Exception as exc:  # noqa: BLE001 - any solver fault is recorded as data
            outcome["static"] = (STATUS_NUMERICAL, exception_message(exc))
            data["static_status"] = np.asarray(STATUS_NUMERICAL, dtype=np.int64)

    status, message = outcome["static"]
    if status == STATUS_OK:
        failed = [(name, st, msg) for name, (st, msg) in outcome.items() if st != STATUS_OK]
        # a time-limited analysis first, its message starting "time limit": the cache
        # then knows a rerun may finish it (cablestudy.run.cache.TRANSIENT_PREFIXES)
        failed.sort(key=lambda f: f[1] != STATUS_TIME_LIMIT)
        if failed:
            status = failed[0][1]
            message = "; ".join(
                f"{name} analysis: "
                + (
                    f"time limit: {msg}"
                    if st == STATUS_TIME_LIMIT and not msg.startswith("time limit")
                    else msg
                )
                for name, st, msg in failed
            )
    ok = {name for name, (st, _) in outcome.items() if st == STATUS_OK}
    try:
        fallback = static_fallback(
            case.study,
            static[0] if static else None,
            presolved is not None and case.static_hash in presolved,
        )
    except Exception:  # noqa: BLE001 - the statics failed before a solver took the case
        fallback = ""
    try:
        warning = case_warnings(case, static[0] if "static" in ok else None, data, ok)
    except Exception as exc:  # noqa: BLE001 - the results stand; say they went unchecked
        warning = f"unchecked: the plausibility checks failed ({exception_message(exc)})"
    wall = time.perf_counter() - t0
    if not math.isfinite(wall):
        wall = 0.0
    return CaseRecord(
        hash=case.hash,
        index=case.index,
        status=int(status),
        message=message,
        wall_time=wall,
        data=data,
        warning=warning,
        fallback=fallback,
    )


def case_warnings(
    case: Case,
    static: StaticResult | None,
    data: dict[str, Any],
    ok: set[str],
) -> str:
    """The case's ``warning`` text (:mod:`cablestudy.analyses.plausibility`): strain above
    ``analysis.static.strain_warning`` and a batched-kernel fallback
    (:attr:`StaticResult.fallback`) of the statics, when they succeeded (``static``), and
    a line above the water's surface (:func:`cablestudy.analyses.surface.case_surface_warning`);
    slack and an unsettled time-domain run, when the dynamic analysis succeeded (named
    in ``ok``)."""
    found: list[str] = [take_step_warning(data)]  # the time domain's step check
    if static is not None:
        limit = case.study.analysis.static.strain_warning
        found.append(strain_warning(largest_static_strain(case.study, static), limit))
        if static.fallback:
            found.append(fallback_warning(static.fallback))
    found.append(case_surface_warning(case.study, static, data, ok))  # above the water
    if case.study.analysis.database is not None:  # cells the lookup's patches cannot follow
        from .database import cell_warning

        found.append(cell_warning(data, sum(seg.length for seg in case.study.line.segments)))
    dyn = case.study.analysis.dynamic
    if "dynamic" in ok and dyn is not None:
        found.extend(
            dynamic_warnings(
                data,
                max_periods=dyn.max_periods,
                fixed_duration=dyn.duration is not None,
                static_tension=None if static is None else static.tension,
            )
        )
        envelope = data.get("tension_envelope_max")
        if static is not None and envelope is not None and not case.study.line.is_spring:
            # a non-linear law stretched past its checked max_strain by the motion
            from ..study.problem import static_limits
            from .law_range import dynamic_strain_warning, law_range_warning

            beyond = law_range_warning(static.s, envelope, static_limits(case.study))
            found.append(
                beyond  # the law's own range passed: its strain there is extrapolated
                or dynamic_strain_warning(
                    static.s,
                    envelope,
                    case.study.line.segments,
                    case.study.analysis.static.strain_warning,
                )
            )
    return joined(found)


def _system_chunk(cases: list[Case]) -> list[CaseRecord]:
    """A system study's cases, each by :func:`cablestudy.analyses.system.evaluate_system_case`."""
    from .system import evaluate_system_case
    from .system_frequency import sweep_chunk

    # the frequency domain's cases of one linear model solved as one sweep
    with sweep_chunk(cases) as moved:
        records = [evaluate_system_case(case) for case in cases]
    for rec in records:
        rec.wall_time += moved.get(rec.hash, 0.0)
    return records


def _line_chunk(cases: list[Case]) -> list[CaseRecord]:
    """One line's cases: compatible static problems solved as one batch first, and the
    frequency-domain responses of the cases that share a linear model together; then
    every case as in :func:`evaluate_case` (its wall time includes its share of the
    batches)."""
    solved, share = presolve_statics(cases)
    linear, linear_share = presolve_frequency(cases, solved)
    records = []
    for i, case in enumerate(cases):
        rec = evaluate_case(case, presolved=solved, linear=linear.get(i))
        if case.static_hash in share:
            rec.wall_time += share.pop(case.static_hash)
        rec.wall_time += linear_share.get(i, 0.0)
        records.append(rec)
    return records


#: how a chunk of cases is evaluated, by the kind of its study (a chunk holds the cases
#: of one study)
CHUNK_KINDS: dict[str, Callable[[list[Case]], list[CaseRecord]]] = {
    "system": _system_chunk,
    "line": _line_chunk,
}


def evaluate_chunk(cases: list[Case]) -> list[CaseRecord]:
    """Evaluate a chunk of cases in one task, by the evaluator of its study's kind
    (:data:`CHUNK_KINDS`)."""
    kind = "system" if cases and cases[0].study.is_system else "line"
    return CHUNK_KINDS[kind](cases)


def evaluate_cases(cases: list[Case], *, extent: dict[str, int] | None = None) -> GridChunk:
    """:func:`evaluate_chunk`, its records in the one chunk form every study's runner
    stores and assembles (:func:`cablestudy.analyses.grid_chunk.records_chunk`, its
    ``extent``), built where they were computed."""
    system = bool(cases) and cases[0].study.is_system
    if system and extent is None and _excitation_sweep(cases):
        # a system's sweep of its harmonic excitation, as arrays (analyses.system_fd_grid)
        from .system_fd_grid import evaluate_excitation_chunk

        return evaluate_excitation_chunk(cases)
    return records_chunk(evaluate_chunk(cases), system=system, extent=extent)


def _excitation_sweep(cases: list[Case]) -> bool:
    """Whether every case is of a sweep of a system's harmonic excitation
    (:class:`cablestudy.analyses.system_fd_grid.ExcitationCase`)."""
    from .system_fd_grid import ExcitationCase

    return all(isinstance(c, ExcitationCase) for c in cases)
