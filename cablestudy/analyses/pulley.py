"""Cases of a catenary line over pulleys (``line.pulleys`` on a ``kind: catenary`` line):
the checks before any work and the static solution of one case (called from
:mod:`.analyses`). The physics is in :mod:`cablestudy.statics.pulley`."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from ..statics import STATIC_SOLVERS, StaticResult
from ..statics.pulley import chord_split, solve_over_pulleys, sub_problems
from ..study.problem import line_model, medium, static_problem

if TYPE_CHECKING:
    from ..study import Study
    from ..study.cases import Case
    from ..study.loader import StudySource

#: static methods that solve a line over pulleys (each sub-line a fixed-fixed line whose
#: solution does not depend on the output points); 'discrete' does not: its mesh is its
#: output points, which the split would cut differently on each side of a pulley
PULLEY_METHODS = ("analytic", "catenary", "shooting")


def pulley_positions(study: Study) -> np.ndarray:
    """The pulleys' positions [m], shape (m, 3)."""
    return np.array([p.position for p in study.line.pulleys], dtype=float).reshape(-1, 3)


def pulley_problems(case: Case, src: StudySource) -> list[str]:
    """Config errors of a catenary line over pulleys (raised before any work by
    :func:`cablestudy.analyses.evaluate.check_supported`); the method's own list of unsupported
    features is checked there on the whole line and here on its sub-lines."""
    study = case.study
    out: list[str] = []

    def at(*loc: Any) -> str:
        return src.line_of(tuple(str(p) for p in loc)) or src.line_of(("line",)) or ""

    where = at("line", "pulleys")
    ends = study.ends
    if ends.a.kind != "fixed" or ends.b.kind != "fixed":
        out.append(
            f"{where}: line.pulleys: a line over pulleys needs both ends fixed (each "
            "sub-line between the ends and the pulleys is a fixed-fixed catenary); "
            f"got ends.a.kind {ends.a.kind!r}, ends.b.kind {ends.b.kind!r}; allowed: ends "
            "of kind fixed"
        )
        return out
    static = study.analysis.static
    if static.method not in PULLEY_METHODS:
        out.append(
            f"{at('analysis', 'static', 'method')}: analysis.static.method: "
            f"{static.method!r} does not solve a line over pulleys (its mesh is its output "
            "points, cut unevenly by the pulleys); allowed with line.pulleys: "
            f"{', '.join(PULLEY_METHODS)}"
        )
    if static.installation is not None:
        out.append(
            f"{at('analysis', 'static', 'installation')}: analysis.static.installation: a "
            "cable laying from a vessel does not pass over fixed pulleys; allowed: omit "
            "installation, or no line.pulleys"
        )
    an = study.analysis
    for key, what in (("modal", "analysis.modal"), ("database", "analysis.database")):
        if getattr(an, key) is not None:
            out.append(
                f"{at('analysis', key)}: {what}: not supported for a kind: catenary line "
                "over pulleys; pulleys on a catenary line are supported by the statics "
                "(analysis.static) and the time domain (analysis.dynamic, method time or "
                f"auto); allowed: omit {what}, or no line.pulleys"
            )
    dyn = an.dynamic
    if dyn is not None:
        for key in ("history", "transfer_function"):
            if getattr(dyn, key) is not None:
                out.append(
                    f"{at('analysis', 'dynamic', key)}: analysis.dynamic.{key}: not "
                    "available for a catenary line over pulleys (its nodes move along the "
                    "line as it slides; the transfer function is the frequency domain's); "
                    "tension_max/min/mean and pulley_arc_length_min/max are written; "
                    "allowed: omit it"
                )
        if "step_tolerance" in dyn.model_fields_set:  # the step check (issue 24)
            out.append(
                f"{at('analysis', 'dynamic', 'step_tolerance')}: analysis.dynamic."
                f"step_tolerance: {dyn.step_tolerance!r}: the step check re-runs a period "
                "of the line's own time domain; a catenary line over sliding pulleys is "
                "run by its own (no step check); allowed: omit it, or no line.pulleys"
            )
        line = study.line
        breaks = [("line", "failure")] if line.failure is not None else []
        breaks += [
            ("line", "segments", i, "failure")
            for i, seg in enumerate(line.segments)
            if seg.failure is not None
        ]
        if line.winch is not None:
            breaks.append(("line", "winch"))
        for path in breaks:
            out.append(
                f"{at(*path)}: {'.'.join(map(str, path))}: a break or a winch on a catenary "
                "line over pulleys in analysis.dynamic: its time domain solves the split "
                "at the pulleys for an intact line of fixed length; breaks and winches "
                "are supported without pulleys; allowed: omit it, or no line.pulleys"
            )
        if study.environment.depth is not None and study.environment.seabed.friction > 0.0:
            out.append(
                f"{at('environment', 'seabed', 'friction')}: environment.seabed.friction: "
                f"{study.environment.seabed.friction:g} with a line sliding over pulleys in "
                "analysis.dynamic: the friction anchors belong to nodes, which move along "
                "the sliding line; allowed: 0 (frictionless contact), or no line.pulleys"
            )
    pts = np.vstack(
        (
            np.asarray(ends.a.position, dtype=float),
            pulley_positions(study),
            np.asarray(ends.b.position, dtype=float),  # type: ignore[union-attr]
        )
    )
    spans = np.linalg.norm(np.diff(pts, axis=0), axis=1)
    if np.any(spans <= 1e-9 * float(np.sum(spans))):
        out.append(
            f"{where}: line.pulleys: a pulley coincides with an end or another pulley (a "
            "sub-line of zero chord); allowed: distinct points"
        )
        return out
    if static.method in PULLEY_METHODS:
        problem = static_problem(study)
        pulleys = pulley_positions(study)
        solver = STATIC_SOLVERS[static.method]
        for k, sub in enumerate(sub_problems(problem, pulleys, chord_split(problem, pulleys))):
            for item in solver.unsupported(sub):
                msg = (
                    f"{at('analysis', 'static', 'method')}: analysis.static.method: "
                    f"{static.method!r} does not support {item} (sub-line {k + 1} of the "
                    f"line over pulleys); allowed with line.pulleys: "
                    f"{', '.join(PULLEY_METHODS)}"
                )
                if msg not in out:
                    out.append(msg)
    return out


def solve_pulley_static(study: Study, deadline: float | None) -> StaticResult:
    """The frictionless static equilibrium of the study's line over its pulleys."""
    problem = static_problem(study)
    solver = STATIC_SOLVERS[study.analysis.static.method]
    return solve_over_pulleys(problem, pulley_positions(study), solver, deadline=deadline)


def pulley_discrete_statics(case: Case, static: StaticResult) -> tuple[Any, ...]:
    """The lumped-mass line of the case cut at its pulleys
    (:func:`cablestudy.dynamics.pulley.sliding_pulleys`) in its own frictionless static
    equilibrium: the split of the continuous statics, moved so that the discrete
    model's element tensions on both sides of each pulley agree (they differ by the
    discretisation error at the continuous split). Returns (line, positions [m], error
    message or "", friction anchors [m], :class:`SlidingPulleys` at that split)."""
    from dataclasses import replace

    from ..dynamics.assembly import evaluate
    from ..dynamics.model import static_equilibrium
    from ..dynamics.pulley import pulley_tensions, sliding_pulleys, solve_split, wrap_angle
    from .line_model import dynamic_extras, roundoff_force

    study = case.study
    dyn = study.analysis.dynamic
    assert dyn is not None
    lm, med = line_model(study), medium(study)
    pulleys = pulley_positions(study)
    split = np.asarray(static.split, dtype=float)  # type: ignore[attr-defined]
    factor = np.array([p.friction_factor for p in study.line.pulleys], dtype=float)

    def start_at(s_nodes: np.ndarray, node: np.ndarray) -> np.ndarray:
        x = np.stack([np.interp(s_nodes, static.s, static.position[:, k]) for k in range(3)], 1)
        x[node] = pulleys
        return x

    # the extras take only the end directions of the start (clamped ends)
    extras = dynamic_extras(study, static.position)
    sliding = sliding_pulleys(lm, med, extras, split=split, factor=factor, elements=dyn.elements)
    node = sliding.node
    scale = float(np.nanmax(static.tension))
    found: dict[bytes, tuple] = {}

    def solve(S: np.ndarray) -> tuple | None:
        line = sliding.rebuild(S)
        x0 = start_at(line.s, node)
        tol = max(1e-9 * scale, roundoff_force(line, x0))
        x, _, _, ok, anchor = static_equilibrium(line, x0, tolerance=tol, max_iterations=200)
        if not ok:
            return None
        work = evaluate(line, x, np.zeros_like(x), anchor=anchor)
        found[S.tobytes()] = (line, x, anchor, tol)
        return pulley_tensions(line, x, work.tension, node), wrap_angle(x, node)

    if solve(split) is None:
        return (
            None,
            None,
            "the discrete static equilibrium over the pulleys did not converge",
            None,
            None,
        )
    frictionless = replace(sliding, factor=np.ones_like(factor))
    tol = found[split.tobytes()][3]
    S, _ = solve_split(solve, frictionless, split, 10.0 * tol)
    if S is None:
        return (
            None,
            None,
            "the split of the discrete line over its pulleys did not converge",
            None,
            None,
        )
    line, x, anchor, _ = found[S.tobytes()]
    # the run starts from the statics' dg/dS (frictionless has it from its solve)
    return (
        line,
        x,
        "",
        anchor,
        replace(sliding, split=S.copy(), jacobian=frictionless.jacobian.copy()),
    )
