"""Per-case evaluation: which solvers a case needs, run in order, into a record.

This is the only place that knows which analyses exist; the runner calls
:func:`evaluate_case` and moves records, knowing nothing of physics.
"""

from __future__ import annotations

import math
import time
import traceback
from collections import OrderedDict
from dataclasses import fields, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from .cases import Case
from .config.analysis import (
    DynamicSettings,
    HarmonicExcitation,
    SpectrumExcitation,
    TimeSeriesExcitation,
)
from .config.ends import ForceEnd, MooringEnd
from .config.loader import StudyError, StudySource
from .counters import COUNTERS, trim_lru
from .physics.profile import profile_quantities
from .plausibility import (
    dynamic_warnings,
    fallback_warning,
    joined,
    largest_strain,
    strain_warning,
)
from .problem import line_model, medium, static_limits, static_problem
from .results import OUTPUTS, CaseRecord
from .statics import (
    STATIC_SOLVERS,
    STATUS_BROKEN,
    STATUS_NO_SOLUTION,
    STATUS_NUMERICAL,
    STATUS_OK,
    STATUS_TIME_LIMIT,
    StaticResult,
)
from .statics.limits import apply_limits

if TYPE_CHECKING:  # imported where used: `cablestudy validate` needs none of them
    from .dynamics.excitation import EndMotion
    from .dynamics.modal import ModalResult
    from .dynamics.model import DiscreteLine
    from .dynamics.timedomain import DynamicProblem, DynamicResult

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
        if case.study.is_system:
            continue  # what a system cannot do is refused by the study model itself
        if case.study.line.is_spring:
            from .spring_cases import spring_problems

            problems.extend(p for p in spring_problems(case, src) if p not in problems)
            continue
        problems.extend(p for p in _law_problems(case, src) if p not in problems)
        if case.study.line.pulleys:
            from .pulley_cases import pulley_problems

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
    problems.extend(p for p in _dynamic_problems(cases, src) if p not in problems)
    problems.extend(p for p in _linear_model_problems(cases, src) if p not in problems)
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


def _law_problems(case: Case, src: StudySource) -> list[str]:
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
        from .dynamics.harmonic_cases import warm_up as warm_up_harmonic

        warm_up_harmonic()
    if any(
        c.study.analysis.dynamic is not None
        and c.study.analysis.dynamic.method != "time"
        and c.study.analysis.dynamic.transfer_function is not None
        for c in cases
    ):
        from .dynamics.frequency import warm_up as warm_up_frequency

        warm_up_frequency()
    if any(
        c.study.analysis.dynamic is not None
        and c.study.analysis.dynamic.method != "frequency"
        and c.study.line.kind != "spring"
        for c in cases
    ):
        from .dynamics.timedomain import warm_up as warm_up_time

        warm_up_time()


def linear_model_gaps(study: Any) -> list[tuple[tuple[str | int, ...], str]]:
    """Keys of ``study`` set to something the frequency-domain solver cannot represent,
    as (YAML path, what it is): a line that parts, a winch, a catenary line sliding over
    pulleys, which the time domain models."""
    gaps: list[tuple[tuple[str | int, ...], str]] = []
    if study.line.kind == "spring":
        return gaps
    # the linearised line cannot part or change its length
    if study.line.failure is not None:
        gaps.append((("line", "failure"), "a break condition (the line parts)"))
    gaps += [
        (("line", "segments", i, "failure"), "a break condition (the line parts)")
        for i, seg in enumerate(study.line.segments)
        if seg.failure is not None
    ]
    if study.line.winch is not None:
        gaps.append((("line", "winch"), "a winch (the line's length changes)"))
    if study.line.pulleys:
        gaps.append((("line", "pulleys"), "a line sliding over pulleys"))
    return gaps


def _linear_model_problems(cases: list[Case], src: StudySource) -> list[str]:
    """Keys that ``method: frequency`` would ignore, refused naming the method that
    models them (``method: auto`` runs such cases in the time domain)."""
    problems: list[str] = []
    for case in cases:
        study = case.study
        dyn = study.analysis.dynamic
        if dyn is not None and dyn.method == "frequency" and not study.is_system:
            for path, what in linear_model_gaps(study):
                loc = ".".join(str(p) for p in path)
                problems.append(
                    f"{src.line_of(path) or src.line_of(path[:1])}: {loc}: {what} is modelled "
                    "by the time domain, not by analysis.dynamic.method: frequency; allowed: "
                    "method time or auto, or remove the key"
                )
        if len(problems) > 20:
            break
    return problems


def _dynamic_problems(cases: list[Case], src: StudySource) -> list[str]:
    """Config errors of the dynamic analysis that need the whole study (ends, length)."""
    problems: list[str] = []
    for case in cases:
        dyn = case.study.analysis.dynamic
        if dyn is None or case.study.is_system:  # a system's: config.system_dynamics
            continue
        study = case.study
        excited = {e.end for e in dyn.excitations}
        for label in ("a", "b"):
            end = getattr(study.ends, label)
            # a 'force' or 'mooring' end fixes the static equilibrium; an end the
            # excitation moves then moves about that static position (a vessel-attached
            # end). An unexcited 'force' end is a free node carrying its force (a towed
            # body); an unexcited 'mooring' end (a constant horizontal force at a held
            # height) is no physical support: refused, saying what to write instead.
            if isinstance(end, MooringEnd) and label not in excited:
                line = src.line_of(("ends", label, "kind"))
                problems.append(
                    f"{line}: ends.{label}.kind: 'mooring' is not supported with "
                    "analysis.dynamic unless the excitation moves this end: a fairlead held at "
                    "a height with a constant horizontal force is no support the line can move "
                    "against; allowed: an excitation with end: "
                    f"{label} (the vessel's motion), kind 'fixed' at the static position "
                    "(force_b in a statics run gives it), or kind 'force' for a free end"
                )
            if isinstance(end, ForceEnd) and label not in excited and dyn.method == "frequency":
                line = src.line_of(("ends", label, "kind"))
                problems.append(
                    f"{line}: ends.{label}.kind: an unexcited 'force' end is a free end, "
                    "modelled by the time domain only; allowed: analysis.dynamic.method: time "
                    "or auto"
                )
        if dyn.transfer_function is not None and "frequency" in case.coords:
            line = src.line_of(("analysis", "dynamic", "transfer_function"))
            problems.append(
                f"{line}: analysis.dynamic.transfer_function: writes its own 'frequency' "
                "dimension, and the sweep has an axis named 'frequency'; allowed: a "
                "transfer function instead of the frequency sweep, or name the sweep axis "
                "otherwise (name: ...)"
            )
        spectral = any(isinstance(e, SpectrumExcitation) for e in dyn.excitations)
        if spectral and dyn.method == "frequency" and "frequency" in case.coords:
            line = src.line_of(("analysis", "dynamic", "excitation"))
            problems.append(
                f"{line}: analysis.dynamic.excitation: a spectrum's tension spectrum is "
                "written on a 'frequency' dimension, and the sweep has an axis named "
                "'frequency'; allowed: name the sweep axis otherwise (name: ...)"
            )
        length = study.line.total_length
        if dyn.history is not None:
            for i, s in enumerate(dyn.history.points):
                if s > length:
                    line = src.line_of(("analysis", "dynamic", "history", "points", i))
                    problems.append(
                        f"{line}: analysis.dynamic.history.points.{i}: s = {s} lies beyond "
                        f"the end of the line; allowed 0 <= s <= {length}"
                    )
        if dyn.duration is None and dyn.max_periods < math.ceil(dyn.ramp_periods) + dyn.min_periods:
            line = src.line_of(("analysis", "dynamic", "max_periods"))
            problems.append(
                f"{line}: analysis.dynamic.max_periods: {dyn.max_periods} leaves no room for "
                f"the ramp ({dyn.ramp_periods} periods) and min_periods ({dyn.min_periods}); "
                f"allowed >= {math.ceil(dyn.ramp_periods) + dyn.min_periods}"
            )
        if len(problems) > 20:
            break
    return problems


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
        from .spring_cases import solve_spring_static

        return apply_limits(solve_spring_static(case.study), static_limits(case.study))
    problem = static_problem(case.study)
    method = case.study.analysis.static.method
    solver = STATIC_SOLVERS[method]
    missing = unsupported_static(method, problem)
    if case.study.line.pulleys and not missing:
        from .pulley_cases import solve_pulley_static

        result = solve_pulley_static(case.study, deadline).check_finite()
        result = apply_limits(result, static_limits(case.study))
        COUNTERS["static_solves"] += 1
        _STATIC_CACHE[case.static_hash] = result
        trim_lru(_STATIC_CACHE, _STATIC_CACHE_SIZE)
        return result
    if missing:
        # the CLI rejects these before any work (check_supported); a caller that skips
        # that check still gets a failure rather than a solution that ignores an input
        return StaticResult.failed(
            np.linspace(0.0, problem.line.total_length, problem.n_nodes),
            STATUS_NO_SOLUTION,
            f"static method {method!r} does not support {'; '.join(missing)}",
        )
    result = solver.solve(problem, deadline=deadline).check_finite()
    result = apply_limits(result, static_limits(case.study))
    COUNTERS["static_solves"] += 1
    _STATIC_CACHE[case.static_hash] = result
    trim_lru(_STATIC_CACHE, _STATIC_CACHE_SIZE)
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
        COUNTERS["static_solves"] += 1
        _STATIC_CACHE[key] = cached
        trim_lru(_STATIC_CACHE, _STATIC_CACHE_SIZE)
    return cached


def solve_modal(case: Case, static: StaticResult, deadline: float | None) -> ModalResult:
    """Modal analysis about the static shape on ``analysis.modal.n_elements`` elements.

    ``uniform`` mesh: the static shape at n_elements + 1 equally spaced points (reused
    when the static output has exactly those). ``graded`` mesh: node positions of equal
    transverse-wave travel time are computed from the static tension, and the static
    solution is sampled uniformly fine enough (at least 8 samples in the shortest
    element, an integer number per uniform element) to take the nearest sample for
    each node, so every node lies exactly on the static solution."""
    from .dynamics.modal import (
        ModalProblem,
        graded_arc_lengths,
        modal_analysis,
        snap_to_samples,
        subset_static,
        transverse_mass,
    )

    settings = case.study.analysis.modal
    assert settings is not None
    problem = static_problem(case.study)
    n_el = settings.n_elements
    if settings.mesh == "uniform" or not static.success:
        n_nodes = n_el + 1
        mesh_static = static if n_nodes == len(static.s) else _static_at(case, n_nodes, deadline)
    else:
        mass = transverse_mass(
            problem.line, problem.medium, static.s, include_added_mass=settings.include_added_mass
        )
        tension = static.tension
        joints = problem.line.segment_ends
        med = problem.medium
        if med.friction > 0.0 and static.laid_length > 0.0 and med.depth is not None:
            # the laid part sticks (dynamics.modal): it needs no elements of its own, so
            # grade as if it were as stiff as the most tensioned point, and put a node
            # exactly at the touchdown point, where the pinned part begins
            ground = med.seabed_z(static.position[:, 0], static.position[:, 1])
            on_bed = np.abs(static.position[:, 2] - ground) <= 1e-6 * max(float(static.s[-1]), 1.0)
            tension = np.where(on_bed, float(np.max(static.tension)), static.tension)
            total_length = float(static.s[-1])
            touchdown = [static.laid_length] if on_bed[0] else []
            touchdown += [total_length - static.laid_length] if on_bed[-1] else []
            joints = np.union1d(joints, np.clip(touchdown, 0.0, total_length))
        targets = graded_arc_lengths(static.s, tension, mass, n_el, joints=joints)
        shortest = float(np.min(np.diff(targets)))
        total = float(static.s[-1] - static.s[0])
        per_element = max(8, math.ceil(8.0 * total / (shortest * n_el)))
        per_element = min(per_element, max(1, (MODAL_MAX_SAMPLES - 1) // n_el))
        fine = _static_at(case, n_el * per_element + 1, deadline)
        mesh_static = (
            subset_static(fine, snap_to_samples(fine.s, targets)) if fine.success else fine
        )
    return modal_analysis(
        ModalProblem(
            line=problem.line,
            medium=problem.medium,
            end_a=problem.end_a,
            end_b=problem.end_b,
            static=mesh_static,
            n_modes=settings.modes,
            include_added_mass=settings.include_added_mass,
            include_bending=settings.include_bending,
            extras=dynamic_extras(case.study, mesh_static.position),
        ),
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
        ends = np.cumsum([seg.length for seg in segs])
        k = np.minimum(np.searchsorted(ends, res.s, side="right"), len(segs) - 1)
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
            )
        )
    return out


#: the static outputs of the last static solution, with that solution and the names of
#: its non-finite outputs: the cases of a chunk that share a static problem (adjacent in
#: a chunk: a sweep over excitation) share its outputs instead of deriving (and
#: checking) them again per case
_LAST_STATIC_OUTPUTS: dict[str, tuple[StaticResult, dict[str, np.ndarray], list[str]]] = {}


def _shared_static_outputs(case: Case, res: StaticResult) -> CheckedOutputs:
    """:func:`static_outputs` of ``res`` for ``case``, reused from the previous case when
    it had the same static problem and the very same solution object (the arrays are
    shared, as the static solution's own arrays already are between such cases), with
    their non-finite variables (:func:`_non_finite`)."""
    hit = _LAST_STATIC_OUTPUTS.get(case.static_hash)
    if hit is None or hit[0] is not res:
        out = static_outputs(res, case.study)
        hit = (res, out, _non_finite(out, "static"))
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


#: discrete static equilibria of the dynamic model, by (static hash, elements, the
#: dynamic-only line properties)
_DISCRETE_CACHE: OrderedDict[tuple, tuple[DiscreteLine, np.ndarray, str, np.ndarray]] = (
    OrderedDict()
)


def _fields_key(obj: Any) -> tuple:
    """A hashable key of a dataclass of numbers, tuples and arrays (arrays by dtype,
    shape and bytes: exact, and a hundred times cheaper than their repr)."""
    out = []
    for f in fields(obj):
        v = getattr(obj, f.name)
        if isinstance(v, np.ndarray):
            v = (v.dtype.str, v.shape, v.tobytes())
        out.append((f.name, v))
    return tuple(out)


def discrete_statics(
    case: Case, static: StaticResult
) -> tuple[DiscreteLine, np.ndarray, str, np.ndarray]:
    """The lumped-mass line of the case and its own static equilibrium, found by Newton
    from the static solution (cached per static problem, element count and dynamic line
    properties). The third item is an error message (empty when the equilibrium was
    found), the fourth the seabed friction anchors holding that equilibrium."""
    from .dynamics.model import discretise_nodes, static_equilibrium, uniform_nodes

    dyn = case.study.analysis.dynamic
    assert dyn is not None
    lm = line_model(case.study)
    med = medium(case.study)
    # the clamp directions are the static tangents of the end elements of the mesh
    s_nodes = uniform_nodes(lm, dyn.elements)
    start = np.stack([np.interp(s_nodes, static.s, static.position[:, k]) for k in range(3)], 1)
    extras = dynamic_extras(case.study, start)
    key = (case.static_hash, dyn.elements, _fields_key(extras))
    cached = _DISCRETE_CACHE.get(key)
    if cached is not None:
        return cached
    line = discretise_nodes(lm, med, s_nodes, extras)
    COUNTERS["line_assemblies"] += 1
    scale = float(np.nanmax(static.tension))
    if line.has_seabed:
        # the penalty seabed balances each laid node's weight by a penetration of its
        # own: allow the residual the contact stiffness makes of rounding in z
        scale = max(scale, float(np.max(np.abs(line.force))))
    # the static tension at the element midpoints: where Newton on positions cannot
    # start (a stiff line on a seabed), the positions-and-tensions form starts from it
    t_nodes = np.interp(s_nodes, static.s, static.tension)
    x, its, res, ok, anchor = static_equilibrium(
        line,
        start,
        tolerance=max(1e-9 * scale, roundoff_force(line, start)),
        max_iterations=200,
        fallback_tension=0.5 * (t_nodes[:-1] + t_nodes[1:]),
    )
    msg = (
        ""
        if ok
        else (
            f"the discrete static equilibrium of the dynamic model did not "
            f"converge ({its} iterations, residual {res:.3g} N)"
        )
    )
    _DISCRETE_CACHE[key] = (line, x, msg, anchor)
    trim_lru(_DISCRETE_CACHE, _STATIC_CACHE_SIZE)
    return line, x, msg, anchor


def dynamic_extras(study: Any, start: np.ndarray) -> Any:
    """The dynamic-only line properties of ``study``
    (:class:`cablestudy.dynamics.model.DynamicExtras`): bodies, transverse damping,
    free ends (an unexcited ``force`` end), clamped ends (holding the direction of the
    end elements of ``start`` [m], the static shape at the mesh nodes) and the seabed
    contact."""
    from .dynamics.model import DynamicExtras, default_seabed_stiffness

    dyn = study.analysis.dynamic
    excited = {e.end for e in dyn.excitations} if dyn is not None else set()
    end_force = np.zeros((2, 3))
    free = [False, False]
    clamp = np.zeros((2, 3))
    for k, label in enumerate(("a", "b")):
        end = getattr(study.ends, label)
        if isinstance(end, ForceEnd) and label not in excited:
            free[k] = True
            end_force[k] = end.force
        if end.bending == "clamped":
            d = start[1] - start[0] if k == 0 else start[-1] - start[-2]
            clamp[k] = d / np.linalg.norm(d)
    env = study.environment
    sb = env.seabed
    lm = line_model(study)
    stiffness = 0.0
    if env.depth is not None:
        stiffness = sb.stiffness if sb.stiffness is not None else default_seabed_stiffness(lm)
    atts = study.line.attachments
    return DynamicExtras(
        transverse_damping=np.array([seg.damping_transverse for seg in study.line.segments]),
        attachment_added_mass=np.array([a.added_mass for a in atts], dtype=float),
        attachment_drag_area=np.array([a.drag_area for a in atts], dtype=float),
        end_force=end_force,
        free_end=(free[0], free[1]),
        clamp_direction=clamp,
        seabed_stiffness=float(stiffness),
        seabed_damping_ratio=float(sb.damping_ratio),
        friction_axial=float(sb.friction),
        friction_lateral=float(sb.friction if sb.friction_lateral is None else sb.friction_lateral),
    )


def roundoff_force(line: DiscreteLine, x: np.ndarray) -> float:
    """Nodal force [N] below which a residual is lost in rounding: an element tension
    carries EA * (relative rounding of the node coordinates) / (element length)."""
    reach = float(np.max(np.abs(x))) + float(np.sum(line.rest_length))
    return (
        16.0
        * float(np.finfo(float).eps)
        * float(np.max(line.axial_stiffness))
        * reach
        / float(np.min(line.rest_length))
    )


def end_motion(dyn: DynamicSettings) -> tuple[EndMotion, float, float]:
    """(end motion, steady-state period [s], base time step [s]) of the settings."""
    from .dynamics.excitation import EndMotion, TableMotion

    harmonics = [e for e in dyn.excitations if isinstance(e, HarmonicExcitation)]
    tables = [e for e in dyn.excitations if isinstance(e, TimeSeriesExcitation)]
    spectra = [e for e in dyn.excitations if isinstance(e, SpectrumExcitation)]
    table_motions = tuple(
        TableMotion(
            end=0 if e.end == "a" else 1,
            direction=np.asarray(e.direction) / np.linalg.norm(e.direction),
            times=np.array([r[0] for r in e.table]),
            values=np.array([r[1] for r in e.table]),
            periodic=e.periodic,
        )
        for e in tables
    )
    # a spectrum runs as its lines with random phases (seeded): a periodic motion whose
    # period is that of its lowest line
    lines = [
        (e, f, a, p)
        for e in spectra
        for f, a, p in zip(
            e.line_frequencies,
            e.line_amplitudes,
            np.random.default_rng(e.seed).uniform(0.0, 2.0 * math.pi, e.components),
            strict=True,
        )
    ]
    periods = [1.0 / e.frequency for e in harmonics] + [1.0 / f for _, f, _, _ in lines]
    periods += [m.duration for m in table_motions if m.periodic]
    if dyn.period is not None:
        period = dyn.period
    elif periods:
        period = max(periods)
    else:
        period = dyn.duration  # type: ignore[assignment]  (validated: one of them is set)
    fastest = min(periods) if periods else period
    step = fastest / dyn.points_per_period
    step = period / math.ceil(period / step * (1.0 - 1e-12))
    every = [(e, e.frequency, e.amplitude, math.radians(e.phase_deg)) for e in harmonics]
    every += lines
    motion = EndMotion(
        harmonic_end=np.array([0 if e.end == "a" else 1 for e, _, _, _ in every], dtype=int),
        harmonic_direction=np.array(
            [np.asarray(e.direction) / np.linalg.norm(e.direction) for e, _, _, _ in every]
        ).reshape(-1, 3),
        harmonic_amplitude=np.array([a for _, _, a, _ in every], dtype=float),
        harmonic_frequency=np.array([f for _, f, _, _ in every], dtype=float),
        harmonic_phase=np.array([p for _, _, _, p in every], dtype=float),
        tables=table_motions,
        ramp_time=dyn.ramp_periods * period,
    )
    return motion, period, step


def auto_ineligible(dyn: DynamicSettings, study: Any = None) -> str:
    """Why ``method: auto`` cannot try the frequency domain for these settings ("" if it
    can): it needs one harmonic frequency, time histories come from the time domain, and
    so do free ends and what the linearised model lacks (:func:`linear_model_gaps`)."""
    if study is not None:
        excited = {e.end for e in dyn.excitations}
        for label in ("a", "b"):
            if isinstance(getattr(study.ends, label), ForceEnd) and label not in excited:
                return f"end {label} is free (time domain only)"
        gaps = linear_model_gaps(study)
        if gaps:
            return f"{gaps[0][1]} (time domain only)"
    if not all(isinstance(e, HarmonicExcitation) for e in dyn.excitations):
        return "excitation is not harmonic"
    if len({e.frequency for e in dyn.excitations}) > 1:  # type: ignore[union-attr]
        return "excitation has several frequencies"
    if dyn.history is not None:
        return "time histories asked for"
    if dyn.duration is not None:
        return "a fixed run duration asked for"
    return ""


def run_dynamic(
    case: Case, static: StaticResult, deadline: float | None, outcome: Any = None
) -> tuple[int, str, dict[str, np.ndarray]]:
    """The case's dynamic analysis by its method: (status, message, outputs).

    ``time``: the time domain; ``frequency``: the linearised harmonic response;
    ``auto``: the frequency domain where :mod:`cablestudy.frequency_cases` trusts it,
    else the time domain. ``dynamic_method`` and ``dynamic_method_reason`` record
    which ran and why. ``outcome``: the case's frequency-domain outcome when already
    solved (with the other cases of its chunk, :func:`evaluate_chunk`)."""
    dyn = case.study.analysis.dynamic
    assert dyn is not None
    if case.study.line.is_spring:
        from .spring_cases import run_spring_dynamic

        return run_spring_dynamic(case, static, deadline)
    linear: dict[str, np.ndarray] = {}
    if dyn.method in ("frequency", "auto"):
        why = auto_ineligible(dyn, case.study) if dyn.method == "auto" else ""
        if not why:
            if outcome is not None:
                fres = outcome
            else:
                from .frequency_cases import solve_frequency

                fres = solve_frequency(case, static, deadline)
            if dyn.method == "frequency" or (fres.status == STATUS_OK and not fres.distrust):
                out = dict(fres.data) if fres.non_finite is None else CheckedOutputs(fres.data)
                if fres.non_finite is not None:
                    out.non_finite = fres.non_finite  # type: ignore[attr-defined]
                out["dynamic_method"] = np.asarray("frequency")
                out["dynamic_method_reason"] = (
                    np.asarray("method: frequency")
                    if dyn.method == "frequency"
                    else np.asarray(f"auto: linear ({fres.summary})")
                )
                return fres.status, fres.message, out
            from .frequency_cases import TRANSFER_OUTPUTS

            why = fres.distrust or fres.message
            # the transfer function is a linear result whichever method answers the case
            linear = {k: v for k, v in fres.data.items() if k in TRANSFER_OUTPUTS}
        elif dyn.transfer_function is not None:
            # auto runs the time domain for this case; the transfer function asked for
            # is still the linear model's
            from .frequency_cases import TRANSFER_OUTPUTS, solve_frequency

            fres = solve_frequency(case, static, deadline)
            linear = {k: v for k, v in fres.data.items() if k in TRANSFER_OUTPUTS}
        reason = f"auto: {why}"
    else:
        reason = "method: time"
    dres = solve_dynamic(case, static, deadline)
    out = dynamic_outputs(dres, dyn, static.s)
    line_def = case.study.line
    if line_def.failure is not None or any(seg.failure for seg in line_def.segments):
        out["break_time"] = np.asarray(dres.break_time)
        out["break_s"] = np.asarray(dres.break_s)
    if case.study.line.winch is not None:
        out["winch_paid_out"] = np.asarray(dres.winch_paid_out)
    out["dynamic_method_reason"] = np.asarray(reason)
    out.update(linear)
    message = dres.message
    if dres.status != STATUS_OK and dyn.method == "auto":
        message = f"{reason}, so the time domain ran: {dres.message}"
    return dres.status, message, out


def solve_dynamic(case: Case, static: StaticResult, deadline: float | None) -> DynamicResult:
    from .dynamics.timedomain import DynamicResult, simulate

    problem = dynamic_problem(case, static)
    if isinstance(problem, str):
        return DynamicResult(status=STATUS_NUMERICAL, message=problem)
    return simulate(problem, deadline=deadline)


def dynamic_problem(case: Case, static: StaticResult) -> DynamicProblem | str:
    """The time-domain run of the case about its static solution (or why the discrete
    static equilibrium it starts from was not found)."""
    from .dynamics.timedomain import DynamicProblem

    dyn = case.study.analysis.dynamic
    assert dyn is not None
    sliding = None
    if case.study.line.pulleys:
        from .pulley_cases import pulley_discrete_statics

        line, x_static, msg, anchor, sliding = pulley_discrete_statics(case, static)
    else:
        line, x_static, msg, anchor = discrete_statics(case, static)
    if msg:
        return msg
    motion, period, step = end_motion(dyn)
    first = dyn.excitations[0]
    hist = dyn.history
    return DynamicProblem(
        line=line,
        static_position=x_static,
        motion=motion,
        period=period,
        step=step,
        excited_end=0 if first.end == "a" else 1,
        max_refinement=dyn.max_refinement,
        spectral_radius=dyn.spectral_radius,
        newton_tolerance=max(
            dyn.newton_tolerance * float(np.nanmax(static.tension)),
            4.0 * roundoff_force(line, x_static),
        ),
        max_newton_iterations=dyn.max_newton_iterations,
        tension_step=dyn.tension_resolution * float(np.nanmax(static.tension)),
        steady_tolerance=dyn.steady_tolerance,
        steady_window=dyn.steady_window,
        min_periods=dyn.min_periods,
        max_periods=dyn.max_periods,
        duration=dyn.duration,
        history=hist is not None,
        history_s=np.asarray(hist.points if hist else [], dtype=float),
        history_periods=hist.periods if hist else 0.0,
        history_samples=hist.samples_per_period if hist else 1,
        anchor=anchor,
        history_line=bool(hist and hist.whole_line),
        # a node within a millionth of the line's length of the seabed touches it (the
        # statics' rule); the penalty contact sinks laid nodes below the plane anyway
        touchdown_tolerance=1e-6 * max(float(line.s[-1]), 1.0),
        after_break=dyn.after_break,
        **_element_breaks(case.study, line),
        **_catenary_winch(case.study.line.winch),
        pulleys=sliding,
    )


def _element_breaks(study: Any, line: DiscreteLine) -> dict[str, np.ndarray]:
    """Per element of ``line`` its break tension [N] and failure time [s] (inf: none):
    its segment's ``failure``, else ``line.failure`` (empty when neither is given)."""
    segs = study.line.segments
    if study.line.failure is None and all(seg.failure is None for seg in segs):
        return {}
    ends = np.concatenate(([0.0], np.cumsum([seg.length for seg in segs])))
    mid = 0.5 * (line.s[:-1] + line.s[1:])
    of = np.clip(np.searchsorted(ends, mid, side="right") - 1, 0, len(segs) - 1)
    tension, when = np.full(len(segs), np.inf), np.full(len(segs), np.inf)
    for i, seg in enumerate(segs):
        brk = seg.failure or study.line.failure
        if brk is not None:
            tension[i] = brk.limit
            if brk.time is not None:
                when[i] = float(brk.time)
    return {"break_tension": tension[of], "break_at": when[of]}


def _catenary_winch(winch: Any) -> dict[str, float]:
    """The time domain's winch settings (the first element's length changes)."""
    if winch is None:
        return {}
    return {
        "winch_speed": float(winch.speed),
        "winch_start": float(winch.start),
        "winch_stop": math.inf if winch.stop is None else float(winch.stop),
    }


def dynamic_outputs(
    res: DynamicResult, dyn: DynamicSettings, s_out: np.ndarray
) -> dict[str, np.ndarray]:
    """The time domain's outputs; along-line ones at the static output points ``s_out``
    [m] (the dataset's ``s``)."""
    from .dynamics.model import interpolate_nodes
    from .frequency_cases import tension_along

    s_out = np.asarray(s_out, dtype=float)
    out: dict[str, np.ndarray] = {
        "tension_static": np.asarray(res.tension_static),
        "tension_max": np.asarray(res.tension_max),
        "tension_min": np.asarray(res.tension_min),
        "tension_mean": np.asarray(res.tension_mean),
        "tension_max_line": np.asarray(res.tension_max_line),
        "tension_max_spread": np.asarray(res.tension_max_spread),
        "tension_min_spread": np.asarray(res.tension_min_spread),
        "steady_converged": np.asarray(int(res.steady_converged)),
        "periods": np.asarray(res.periods),
        "dynamic_steps": np.asarray(res.steps),
        "newton_iterations": np.asarray(res.newton_iterations),
        "rejected_steps": np.asarray(res.rejected_steps),
        "dynamic_method": np.asarray("time"),
    }
    if res.touchdown_tracked:  # a seabed to touch: NaN when the line does not touch it
        out["touchdown_min"] = np.asarray(res.touchdown_min)
        out["touchdown_max"] = np.asarray(res.touchdown_max)
    if res.split_min.size:
        # a line over pulleys: its nodes move along the material as it slides, so the
        # elements' extremes belong to no fixed point of the line (no envelope)
        out["pulley_arc_length_min"] = res.split_min
        out["pulley_arc_length_max"] = res.split_max
    elif res.element_tension_max.size:
        out["tension_envelope_max"] = tension_along(
            s_out, res.line_s, res.element_tension_max, res.end_tension_max
        )
        out["tension_envelope_min"] = tension_along(
            s_out, res.line_s, res.element_tension_min, res.end_tension_min
        )
    if res.history is not None and "line_position" in res.history:
        h = res.history
        out["history_line_position"] = interpolate_nodes(res.line_s, s_out, h["line_position"])
        out["history_line_velocity"] = interpolate_nodes(res.line_s, s_out, h["line_velocity"])
        out["history_line_tension"] = np.array(
            [
                tension_along(s_out, res.line_s, el, ends)
                for el, ends in zip(h["line_element_tension"], h["line_end_tension"], strict=True)
            ]
        ).reshape(-1, s_out.size)
    if res.history is not None:
        h = res.history
        out.update(
            {
                "history_time": h["time"],
                "history_tension": h["tension"],
                "history_displacement": h["displacement"],
                "history_velocity": h["velocity"],
                "history_acceleration": h["acceleration"],
                "history_point_s": np.asarray(
                    dyn.history.points if dyn.history else [], dtype=float
                ),
            }
        )
    return out


#: status of an analysis that did not run because the static analysis it starts from
#: failed (the code of :data:`cablestudy.dynamics.modal.STATUS_STATIC_FAILED`)
STATUS_NOT_RUN = 5


def _exception_message(exc: Exception) -> str:
    tb = traceback.extract_tb(exc.__traceback__)
    where = f" at {tb[-1].name}:{tb[-1].lineno}" if tb else ""
    return f"{type(exc).__name__}: {exc}{where}"


#: the outputs last checked by :func:`_non_finite` per analysis, with the answer (holding
#: the arrays, so that a later call with the very same objects can reuse it)
_LAST_CHECKED: dict[str, tuple[dict[str, Any], list[str]]] = {}


def _non_finite(data: dict[str, Any], analysis: str) -> list[str]:
    """Float variables of ``analysis`` in ``data`` holding NaN or infinity where the
    registry does not give NaN a meaning (e.g. 'no seabed contact')."""
    known = getattr(data, "non_finite", None)
    if known is not None:  # found on the arrays of a batch (CheckedOutputs)
        return list(known)
    last = _LAST_CHECKED.get(analysis)
    if (
        last is not None
        and len(last[0]) == len(data)
        and all(k in data and data[k] is v for k, v in last[0].items())
    ):
        return list(last[1])  # the very same arrays (outputs shared between cases)
    bad = []
    for k, v in data.items():
        spec = OUTPUTS.get(k)
        if spec is None or spec.analysis != analysis:
            continue
        v = v if isinstance(v, np.ndarray) else np.asarray(v)
        if v.dtype.kind != "f":
            continue
        if v.ndim == 0:  # a number: no array reductions needed
            x = float(v)
            if not (math.isfinite(x) or (spec.nan_means and math.isnan(x))):
                bad.append(k)
            continue
        if spec.nan_means:
            v = v[~np.isnan(v)]
        if not np.isfinite(v).all():
            bad.append(k)
    _LAST_CHECKED[analysis] = (dict(data), sorted(bad))
    return sorted(bad)


def non_finite_cases(columns: dict[str, np.ndarray], analysis: str) -> list[list[str]]:
    """:func:`_non_finite` of K cases at once: ``columns`` maps output names to arrays
    (K, ...) whose row k is case k's value; per case the sorted names found."""
    n_cases = len(next(iter(columns.values()))) if columns else 0
    bad: list[list[str]] = [[] for _ in range(n_cases)]
    for name in sorted(columns):
        spec = OUTPUTS.get(name)
        v = columns[name]
        if spec is None or spec.analysis != analysis or v.dtype.kind != "f":
            continue
        good = np.isfinite(v)
        if spec.nan_means:
            good |= np.isnan(v)
        for k in np.flatnonzero(~good.reshape(n_cases, -1).all(axis=1)):
            bad[k].append(name)
    return bad


class CheckedOutputs(dict):
    """Outputs whose float variables holding NaN or infinity are known already
    (``non_finite``, sorted names): :func:`_non_finite` takes them instead of scanning
    the arrays."""

    non_finite: list[str]


def evaluate_case(
    case: Case, *, presolved: dict[str, StaticResult] | None = None, linear: Any = None
) -> CaseRecord:
    """Run every analysis the case asks for. Never raises: an exception inside a solver
    becomes a failure of that analysis with the exception's text. ``presolved`` maps
    static hashes to static solutions already computed (by :func:`evaluate_chunk`);
    ``linear`` is the case's frequency-domain outcome when already solved (idem).

    Each analysis asked for records ``<analysis>_status`` (0 ok); a failed analysis
    blanks only its own variables at assembly (:func:`cablestudy.results.analysis_ok`).
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
            status, message, out = STATUS_NUMERICAL, _exception_message(exc), {}
        data.update(out)
        if status == STATUS_OK:
            bad = _non_finite(out, analysis)
            if bad:
                status, message = STATUS_NUMERICAL, f"non-finite values in {', '.join(bad)}"
        outcome[analysis] = (int(status), message)

    static: list[StaticResult] = []

    def statics() -> tuple[int, str, dict[str, Any]]:
        res = solve_static(case, deadline, presolved)
        static.append(res)
        return res.status, res.message, _shared_static_outputs(case, res)

    def modal() -> tuple[int, str, dict[str, Any]]:
        settings = case.study.analysis.modal
        assert settings is not None
        mres = solve_modal(case, static[0], deadline)
        return (
            mres.status,
            mres.message,
            modal_outputs(mres, static[0].s, mode_shapes=settings.mode_shapes),
        )

    def dynamic() -> tuple[int, str, dict[str, Any]]:
        if linear is None:
            return run_dynamic(case, static[0], deadline)
        return run_dynamic(case, static[0], deadline, linear)

    run("static", statics)
    asked = {
        "modal": (case.study.analysis.modal is not None, modal),
        "dynamic": (case.study.analysis.dynamic is not None, dynamic),
    }
    for name, (wanted, solve) in asked.items():
        if not wanted:
            continue
        if outcome["static"][0] != STATUS_OK:
            outcome[name] = (STATUS_NOT_RUN, "not run: the static analysis failed")
        else:
            run(name, solve)
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
            outcome["static"] = (STATUS_NUMERICAL, _exception_message(exc))
            data["static_status"] = np.asarray(STATUS_NUMERICAL, dtype=np.int64)

    status, message = outcome["static"]
    if status == STATUS_OK:
        failed = [(name, st, msg) for name, (st, msg) in outcome.items() if st != STATUS_OK]
        # a time-limited analysis first, its message starting "time limit": the cache
        # then knows a rerun may finish it (cablestudy.cache.TRANSIENT_PREFIXES)
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
        warning = case_warnings(case, static[0] if "static" in ok else None, data, ok)
    except Exception as exc:  # noqa: BLE001 - the results stand; say they went unchecked
        warning = f"unchecked: the plausibility checks failed ({_exception_message(exc)})"
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
    )


def largest_static_strain(study: Any, res: StaticResult) -> float:
    """The largest strain [-] of a static solution: per point the axial law's strain
    (T / EA where linear) of its segment; kind spring: the extension over the
    unstretched length (the stretched length is the path through the points)."""
    line = study.line
    if line.is_spring:
        stretched = float(np.linalg.norm(np.diff(res.position, axis=0), axis=1).sum())
        return (stretched - line.total_length) / line.total_length
    segs = line.segments
    ends = np.cumsum([seg.length for seg in segs])
    k = np.minimum(np.searchsorted(ends, res.s, side="right"), len(segs) - 1)
    ea = np.array([segs[i].elastic_stiffness for i in k])
    return float(largest_strain(res.tension, ea, _strain_along(segs, k, res.tension)))


def case_warnings(
    case: Case,
    static: StaticResult | None,
    data: dict[str, Any],
    ok: set[str],
) -> str:
    """The case's ``warning`` text (:mod:`cablestudy.plausibility`): strain above
    ``analysis.static.strain_warning`` and a batched-kernel fallback
    (:attr:`StaticResult.fallback`) of the statics, when they succeeded (``static``);
    slack and an unsettled time-domain run, when the dynamic analysis succeeded (named
    in ``ok``)."""
    found: list[str] = []
    if static is not None:
        limit = case.study.analysis.static.strain_warning
        found.append(strain_warning(largest_static_strain(case.study, static), limit))
        if static.fallback:
            found.append(fallback_warning(static.fallback))
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
    return joined(found)


def presolve_statics(
    cases: list[Case], *, general: list[str] | None = None
) -> tuple[dict[str, StaticResult], dict[str, float]]:
    """Solve the distinct still-water static problems of method 'catenary' in ``cases``
    together (:func:`cablestudy.statics.batch.solve_batch`). Returns the solutions by
    static hash and each one's share of the batch wall time [s]; the static hashes of
    those no batch kernel settled (solved by the general solver) are appended to
    ``general`` if given. Anything unexpected leaves the cases to the one-by-one path
    (which records its own errors)."""
    from .statics.batch import batchable, solve_batch

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
        if batchable(problem):
            todo[h] = (problem, case.study.analysis.time_limit)
    if len(todo) < 2:
        return {}, {}
    t0 = time.perf_counter()
    try:
        deadline = time.monotonic() + max(limit for _, limit in todo.values())
        handed: list[int] = []
        results = solve_batch([p for p, _ in todo.values()], deadline=deadline, general=handed)
    except Exception:  # noqa: BLE001 - fall back to one case at a time
        return {}, {}
    if general is not None:
        keys = list(todo)
        general.extend(keys[i] for i in handed)
    COUNTERS["static_solves"] += len(todo)
    share = (time.perf_counter() - t0) / len(todo)
    solved = {h: r.check_finite() for h, r in zip(todo, results, strict=True)}
    return solved, dict.fromkeys(solved, share)


def presolve_frequency(
    cases: list[Case], presolved: dict[str, StaticResult]
) -> tuple[dict[int, Any], dict[int, float]]:
    """The frequency-domain outcomes of the cases that will ask for one (``method:
    frequency``, or ``auto`` where the frequency domain may answer), solved together
    per shared linear model (:func:`cablestudy.frequency_cases.solve_frequency_cases`):
    by position in ``cases``, with each case's share of its group's wall time [s].
    Anything unexpected leaves the cases to the one-by-one path (which records its own
    errors), as does a group whose statics or linear model fail. A chunk without such a
    case loads nothing of the frequency domain."""
    asking = []
    for i, case in enumerate(cases):
        dyn = case.study.analysis.dynamic
        if dyn is None or dyn.method == "time":
            continue
        if dyn.method == "auto" and auto_ineligible(dyn, case.study):
            continue
        asking.append(i)
    if not asking:
        return {}, {}
    from .frequency_cases import batch_key, linearised, solve_frequency_cases

    groups: dict[tuple, list[int]] = {}
    for i in asking:
        key = batch_key(cases[i])
        if key is not None:
            groups.setdefault(key, []).append(i)
    outcomes: dict[int, Any] = {}
    share: dict[int, float] = {}
    for members in groups.values():
        t0 = time.perf_counter()
        first = cases[members[0]]
        try:
            deadline = time.monotonic() + first.study.analysis.time_limit
            static = solve_static(first, deadline, presolved)
            if not static.success:
                continue
            red, _ = linearised(first, static, deadline)
            if red is None:
                continue
            solved = solve_frequency_cases([cases[i] for i in members], static, red)
        except Exception:  # noqa: BLE001 - the per-case path reports it
            continue
        each = (time.perf_counter() - t0) / len(members)
        for i, outcome in zip(members, solved, strict=True):
            outcomes[i] = outcome
            share[i] = each
    return outcomes, share


def evaluate_chunk(cases: list[Case]) -> list[CaseRecord]:
    """Evaluate a chunk of cases in one task: compatible static problems are solved as
    one batch first, and the frequency-domain responses of the cases that share a
    linear model together; then every case runs as in :func:`evaluate_case` (its wall
    time includes its share of the batches). A system study's cases go to
    :func:`cablestudy.system_cases.evaluate_system_case`."""
    if cases and cases[0].study.is_system:
        from .system_cases import evaluate_system_case

        return [evaluate_system_case(case) for case in cases]
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
