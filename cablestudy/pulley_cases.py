"""Cases of a catenary line over pulleys (``line.pulleys`` on a ``kind: catenary`` line):
the checks before any work and the static solution of one case (called from
:mod:`.analyses`). The physics is in :mod:`cablestudy.statics.pulley`."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from .problem import static_problem
from .statics import STATIC_SOLVERS, StaticResult
from .statics.pulley import chord_split, solve_over_pulleys, sub_problems

if TYPE_CHECKING:
    from .cases import Case
    from .config import Study
    from .config.loader import StudySource

#: static methods that solve a line over pulleys (each sub-line a fixed-fixed line whose
#: solution does not depend on the output points); 'discrete' does not: its mesh is its
#: output points, which the split would cut differently on each side of a pulley
PULLEY_METHODS = ("analytic", "catenary", "shooting")


def pulley_positions(study: Study) -> np.ndarray:
    """The pulleys' positions [m], shape (m, 3)."""
    return np.array([p.position for p in study.line.pulleys], dtype=float).reshape(-1, 3)


def pulley_problems(case: Case, src: StudySource) -> list[str]:
    """Config errors of a catenary line over pulleys (raised before any work by
    :func:`cablestudy.analyses.check_supported`); the method's own list of unsupported
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
    for key, what in (
        ("modal", "analysis.modal"),
        ("dynamic", "analysis.dynamic"),
        ("database", "analysis.database"),
    ):
        if getattr(an, key) is not None:
            out.append(
                f"{at('analysis', key)}: {what}: not supported for a kind: catenary line "
                "over pulleys; pulleys on a catenary line are supported by the statics "
                "(analysis.static), and pulleys in the dynamics by a kind: spring line; "
                f"allowed: omit {what}, or no line.pulleys"
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
