"""Cases of a massless spring line (``line.kind: spring``): the checks before any work,
and the static and dynamic solutions of one case (called from :mod:`.analyses`).

The physics is in :mod:`cablestudy.statics.spring` and :mod:`cablestudy.dynamics.spring`;
this module only converts a case's settings into their inputs and their results into
outputs named as for any line.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from ..statics import STATUS_OK, StaticResult
from ..statics.spring import SpringProblem, reachable_extension, solve_spring
from ..study.analysis import HarmonicExcitation, SpectrumExcitation, TimeSeriesExcitation
from ..study.line import DEFAULT_MAX_STRAIN, check_axial
from ..study.problem import end_condition

if TYPE_CHECKING:
    from ..study import Study
    from ..study.cases import Case
    from ..study.loader import StudySource


def spring_problem(study: Study) -> SpringProblem:
    line = study.line
    assert line.axial is not None and line.length is not None
    return SpringProblem(
        law=line.axial.build(),
        length=float(line.length),
        end_a=end_condition(study.ends.a),
        end_b=end_condition(study.ends.b),
        n_nodes=study.analysis.static.nodes,
        tolerance=min(study.analysis.static.tolerance, 1e-12),
        pulleys=np.array([p.position for p in line.pulleys], dtype=float).reshape(-1, 3),
        friction=np.array([p.friction_factor for p in line.pulleys], dtype=float),
    )


def motion_bound(study: Study) -> float:
    """Upper bound [m] of how far the excitation can move the ends apart: the sum of
    the harmonic amplitudes, the largest table displacements and the spectrum's line
    amplitudes."""
    dyn = study.analysis.dynamic
    if dyn is None:
        return 0.0
    total = 0.0
    for e in dyn.excitations:
        if isinstance(e, HarmonicExcitation):
            total += e.amplitude
        elif isinstance(e, TimeSeriesExcitation):
            total += max(abs(r[1]) for r in e.table)
        elif isinstance(e, SpectrumExcitation):
            total += float(sum(e.line_amplitudes))
    return total


def spring_problems(case: Case, src: StudySource) -> list[str]:
    """Config errors of a spring-line case (raised before any work by
    :func:`cablestudy.analyses.evaluate.check_supported`)."""
    study = case.study
    line = study.line
    out: list[str] = []

    def at(*loc: Any) -> str:
        return src.line_of(tuple(str(p) for p in loc)) or src.line_of(("line",)) or ""

    assert line.axial is not None and line.length is not None
    static = study.analysis.static
    for key in ("method", "drag_elements", "installation", "drag_diameter"):
        if key in static.model_fields_set:
            out.append(
                f"{at('analysis', 'static', key)}: analysis.static.{key}: a kind: spring line "
                "is solved in closed form (straight, massless) and takes no static solver "
                "settings but nodes and tolerance; allowed: omit it"
            )
    if study.environment.current:
        out.append(
            f"{at('environment', 'current')}: environment.current: a kind: spring line is "
            "massless with no drag area, so a current would be ignored; allowed: omit the "
            "current, or use kind: catenary (segments with diameter and drag)"
        )
    if study.analysis.modal is not None:
        out.append(
            f"{at('analysis', 'modal')}: analysis.modal: a massless spring has no modes; "
            "allowed: omit analysis.modal (or use kind: catenary)"
        )
    dyn = study.analysis.dynamic
    if line.winch is not None:
        if dyn is None:
            out.append(
                f"{at('line', 'winch')}: line.winch: a winch changes the length in "
                "analysis.dynamic (the statics are the state before it runs); allowed: "
                "omit it, or add analysis.dynamic"
            )
        elif any(p.friction_factor > 1.0 for p in line.pulleys):
            out.append(
                f"{at('line', 'winch')}: line.winch: not supported with pulley friction yet "
                "(the marching solution keeps the length); allowed: frictionless pulleys"
            )
        elif line.winch.speed < 0.0 and line.winch.stop is None:
            out.append(
                f"{at('line', 'winch')}: line.winch.stop: a winch hauling in (speed < 0) "
                "needs a stop time, so that the extension it reaches (checked against the "
                "law) is bounded; allowed: a stop time [s]"
            )
        elif line.winch.stop is not None and line.winch.stop <= line.winch.start:
            out.append(
                f"{at('line', 'winch', 'stop')}: line.winch.stop: {line.winch.stop:g} s is "
                f"not after start {line.winch.start:g} s; allowed: stop > start"
            )
    if line.failure is not None and line.failure.time is not None and dyn is None:
        out.append(
            f"{at('line', 'failure', 'time')}: line.failure.time: a failure time applies to "
            "analysis.dynamic (the statics are the state before any time); allowed: omit "
            "it, or add analysis.dynamic"
        )
    if dyn is not None and "after_break" in dyn.model_fields_set:
        out.append(
            f"{at('analysis', 'dynamic', 'after_break')}: analysis.dynamic.after_break: the "
            "massless spring's tension is algebraic in the end motion and zero once it has "
            "parted, so nothing runs on after a break; allowed: omit it (it applies to the "
            "time domain of a kind: catenary line)"
        )
    if dyn is not None:
        # the keys a spring line's dynamics would ignore (given in the study; defaults are
        # never refused): its tension is algebraic in the end motion over one period after
        # the ramp (or over duration): no elements, implicit steps, steady state or drag
        out += [
            f"{at('analysis', 'dynamic', key)}: analysis.dynamic.{key}: not used by a kind: "
            "spring line, whose tension is algebraic in the end motion (no elements, time "
            "steps, steady-state detection or drag linearisation) (got "
            f"{getattr(dyn, key)!r}); allowed: omit it (the spring's dynamics reads "
            "excitation, duration, period, ramp_periods and points_per_period)"
            for key in SPRING_UNUSED_DYNAMIC_KEYS
            if key in dyn.model_fields_set
        ]
        for key in ("transfer_function", "history"):
            if getattr(dyn, key) is not None:
                out.append(
                    f"{at('analysis', 'dynamic', key)}: analysis.dynamic.{key}: not "
                    "available for a kind: spring line, whose tension is algebraic in the "
                    "end motion (tension_max/min/mean are written); allowed: omit it"
                )
    a, b = end_condition(study.ends.a), end_condition(study.ends.b)
    for label, end in (("a", a), ("b", b)):
        if end.kind == "force" and end.force is not None and not np.any(end.force):
            out.append(
                f"{at('ends', label, 'force')}: ends.{label}.force: a zero force on a "
                "massless spring leaves its position undetermined; allowed: a nonzero force"
            )
    if line.pulleys:
        if a.kind != "fixed" or b.kind != "fixed":
            out.append(
                f"{at('line', 'pulleys')}: line.pulleys: a spring over pulleys needs both "
                "ends fixed (the end forces then follow from the spans); allowed: ends of "
                "kind fixed"
            )
            return out
        pts = np.vstack((a.position, np.array([p.position for p in line.pulleys]), b.position))
        spans = np.linalg.norm(np.diff(pts, axis=0), axis=1)
        if np.any(spans <= 1e-9 * float(np.sum(spans))):
            out.append(
                f"{at('line', 'pulleys')}: line.pulleys: a pulley coincides with an end or "
                "another pulley (a span of zero length has no direction); allowed: "
                "distinct points"
            )
            return out
        if (
            study.analysis.dynamic is not None
            and line.failure is not None
            and any(p.friction_factor > 1.0 for p in line.pulleys)
        ):
            out.append(
                f"{at('line', 'failure')}: line.failure: not supported with pulley friction "
                "in analysis.dynamic yet (the marching solution does not part); allowed: "
                "frictionless pulleys (friction_factor 1), or no failure key"
            )
        D = float(np.sum(spans))
        reach = max(D + motion_bound(study) - float(line.length), 0.0)
        if line.axial.max_strain is not None:
            reach = max(reach, line.axial.max_strain)
        if reach > 0.0:
            try:
                check_axial(line.axial, reach, ("line", "axial"), "extension [m]")
            except ValueError as exc:
                out.append(f"{at('line', 'axial')}: line.axial: {exc}")
        return out
    hauled = 0.0
    if line.winch is not None and line.winch.speed < 0.0 and line.winch.stop is not None:
        hauled = -line.winch.speed * max(line.winch.stop - line.winch.start, 0.0)
    reach = reachable_extension(float(line.length), a, b, motion_bound(study) + hauled)
    if reach is None:
        # a force end: the law must reach the force's tension within max_strain
        reach = line.axial.max_strain or DEFAULT_MAX_STRAIN * float(line.length)
    elif line.axial.max_strain is not None:
        reach = max(reach, line.axial.max_strain)
    if reach > 0.0:
        try:
            check_axial(line.axial, reach, ("line", "axial"), "extension [m]")
        except ValueError as exc:
            loc = ("line", "axial", "coefficients")
            out.append(f"{at(*loc) or at('line', 'axial')}: line.axial: {exc}")
    return out


def solve_spring_static(study: Study) -> StaticResult:
    return solve_spring(spring_problem(study)).check_finite()


def run_spring_dynamic(
    case: Case, static: StaticResult, deadline: float | None
) -> tuple[int, str, dict[str, np.ndarray]]:
    """The dynamic outputs of a spring line under its end motion: (status, message,
    outputs named as the time domain's)."""
    from ..dynamics.spring import SpringDynamicProblem, spring_response
    from .line_model import end_motion, winch_settings

    study = case.study
    dyn = study.analysis.dynamic
    assert dyn is not None and study.line.axial is not None
    motion, period, step = end_motion(dyn)
    if dyn.duration is not None:
        window = (0.0, float(dyn.duration))
    else:
        window = (motion.ramp_time, motion.ramp_time + period)
    samples = max(4096, int(round((window[1] - window[0]) / step)) * 8)
    problem = SpringDynamicProblem(
        law=study.line.axial.build(),
        length=float(study.line.length),  # type: ignore[arg-type]
        position_a=static.position[0].copy(),
        position_b=static.position[-1].copy(),
        motion=motion,
        window=window,
        samples=samples,
        break_tension=break_tension_of(study.line),
        break_at=study.line.failure.time if study.line.failure is not None else None,
        pulleys=np.array([p.position for p in study.line.pulleys], dtype=float).reshape(-1, 3),
        friction=np.array([p.friction_factor for p in study.line.pulleys], dtype=float),
        excited_end=0 if dyn.excitations[0].end == "a" else 1,
        **winch_settings(study.line.winch),
    )
    res = spring_response(problem)
    out: dict[str, np.ndarray] = {
        "tension_static": np.asarray(res.tension_static),
        "tension_max": np.asarray(res.tension_max),
        "tension_min": np.asarray(res.tension_min),
        "tension_mean": np.asarray(res.tension_mean),
        "steady_converged": np.asarray(1),
        "dynamic_method": np.asarray("spring"),
        "dynamic_method_reason": np.asarray(
            "kind: spring: massless, tension algebraic in the end motion"
        ),
    }
    if study.line.failure is not None:
        out["break_time"] = np.asarray(res.break_time)
    return STATUS_OK, "", out


def break_tension_of(line: Any) -> float | None:
    """The line's breaking tension [N] (``line.failure``), or None."""
    brk = line.failure
    if brk is None or not np.isfinite(brk.limit):
        return None
    return float(brk.limit)


#: settings of the line model's time integration, steady-state detection and drag
#: linearisation that a massless spring's algebraic tension never reads
SPRING_UNUSED_DYNAMIC_KEYS = (
    "elements",
    "max_refinement",
    "tension_resolution",
    "spectral_radius",
    "newton_tolerance",
    "max_newton_iterations",
    "steady_tolerance",
    "step_tolerance",
    "steady_window",
    "min_periods",
    "max_periods",
    "linearisation",
    "auto",
)
