"""Choosing one case of a study by its sweep coordinates, solving its statics, and
writing it as a MoorDyn input file (the driver of :func:`.export.moordyn_input`)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..study.loader import StudySource
from .export import ExportedCase, check_exportable, moordyn_input
from .moordyn_format import InterchangeError


def _matches(value: Any, wanted: str) -> bool:
    if isinstance(value, int | float) and not isinstance(value, bool):
        try:
            return math.isclose(float(value), float(wanted), rel_tol=1e-9, abs_tol=1e-12)
        except ValueError:
            return False
    return str(value) == wanted


def choose_case(src: StudySource, selectors: list[str]) -> Any:
    """The one case of the study whose coordinates match ``dim=value`` selectors.

    Raises :class:`InterchangeError` naming the bad dimension or value and the valid ones."""
    from ..study.grid import expand_cases

    axes, cases = expand_cases(src)
    wanted: dict[str, str] = {}
    dims = {a.name: a for a in axes}
    for sel in selectors:
        dim, sep, value = sel.partition("=")
        if not sep:
            raise InterchangeError(f"--case {sel!r}: write dim=value, e.g. --case frequency=0.5")
        if dim not in dims:
            raise InterchangeError(
                f"--case {sel!r}: the study has no sweep dimension {dim!r}; dimensions: "
                f"{', '.join(dims) or 'none (the study has one case)'}"
            )
        wanted[dim] = value
    missing = [d for d in dims if d not in wanted]
    if missing:
        listing = "; ".join(
            f"{d}: {', '.join(str(v) for v in dims[d].coordinate().tolist()[:12])}"
            + (" ..." if dims[d].size > 12 else "")
            for d in missing
        )
        raise InterchangeError(
            f"the study sweeps {', '.join(missing)}: choose one case with --case dim=value "
            f"for each ({listing})"
        )
    found = [c for c in cases if all(_matches(c.coords[d], v) for d, v in wanted.items())]
    if not found:
        listing = "; ".join(
            f"{d}: {', '.join(str(v) for v in dims[d].coordinate().tolist()[:12])}" for d in wanted
        )
        raise InterchangeError(f"no case has {wanted}; values: {listing}")
    return found[0]


def export_case(src: StudySource, selectors: list[str]) -> ExportedCase:
    """The MoorDyn input file of one case of ``src`` (chosen by ``selectors``)."""
    from ..statics import STATIC_SOLVERS, STATUS_OK
    from ..study.problem import static_problem

    case = choose_case(src, selectors)
    study = case.study
    coords = ", ".join(f"{k}={v}" for k, v in case.coords.items())
    title = f"study {study.name}" + (f", case {coords}" if coords else "")
    if study.is_system:
        return _system(study, title)
    check_exportable(study)  # before the statics: a spring line has no segments to solve
    problem = static_problem(study)
    solver = STATIC_SOLVERS[study.analysis.static.method]
    missing = solver.unsupported(problem)
    if missing:
        raise InterchangeError(
            f"static method {study.analysis.static.method!r} does not support {'; '.join(missing)}"
        )
    res = solver.solve(problem, deadline=None)
    if res.status != STATUS_OK:
        raise InterchangeError(
            f"the case's statics failed ({res.message}); its end positions are unknown"
        )
    pos = np.asarray(res.position, dtype=float)
    coupled = set()
    if study.analysis.dynamic is not None:
        coupled = {e.end for e in study.analysis.dynamic.excitations}
    else:
        coupled = {"b"}
    return moordyn_input(
        study,
        end_positions=(pos[0], pos[-1]),
        position_at=pos,
        s_nodes=np.asarray(res.s, dtype=float),
        coupled_ends=coupled,
        title=title,
    )


def _system(study: Any, title: str) -> ExportedCase:
    """The MoorDyn file of a system case, at its solved statics."""
    from ..analyses.system import system_model
    from ..statics import STATIC_SOLVERS, STATUS_OK
    from ..statics.system import solve_system
    from .system_export import system_moordyn_input

    res = solve_system(system_model(study), STATIC_SOLVERS["catenary"], deadline=None)
    if res.status != STATUS_OK:
        raise InterchangeError(
            f"the case's statics failed ({res.message}); its free points' positions are unknown"
        )
    return system_moordyn_input(study, res, title=title)
