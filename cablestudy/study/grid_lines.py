"""The line of each case of an array grid whose sweep changes the line's loads.

A grid run as arrays (:attr:`cablestudy.study.grid.CaseGrid.arrays`) may sweep, besides
end positions and segment stiffnesses, the numbers that set the line's weight and buoyancy:
a segment's ``mass_per_length``, ``weight_in_fluid`` or ``diameter``, an attachment's
``mass`` or ``volume`` (:data:`LINE_LOAD`), the line's make-up along its length: a
segment's ``length``, an attachment's position ``s`` and ``force`` (:data:`LINE_GEOMETRY`),
and the seabed's depth, slope and friction (:data:`SEABED`). These do not depend on the other
swept values, so it is built once per combination of the values
on the axes that hold such paths (:func:`line_studies`): each one the template with those
validated values copied in (:func:`cablestudy.study.grid_studies.case_study`, which runs
every combined check of the models on the way, raising as a full validation would), and
a case's line is the one of its combination (:func:`line_index`). The solvers' arrays are
then derived from those studies by the very functions a case alone uses
(:func:`cablestudy.study.problem.line_model`), so the numbers are the same bit for bit.
"""

from __future__ import annotations

import itertools
import math
import re
from typing import Any

import numpy as np

#: swept paths that change the line's loads only (not its lengths nor its stiffness)
LINE_LOAD = re.compile(
    r"^line\.(segments\.\d+\.(mass_per_length|weight_in_fluid|diameter)"
    r"|attachments\.\d+\.(mass|volume))$"
)

#: swept paths that set a segment's hydrodynamic coefficients: its drag (used by the
#: drag iteration of a line in a current, through the line's model) and its added mass
#: (read by no static solver: a static-only sweep of it gives equal cases, as case by
#: case); each case's line is the one of its combination, like its loads
LINE_HYDRO = re.compile(
    r"^line\.segments\.\d+\.(drag_normal|drag_tangential|added_mass_normal|added_mass_tangential)$"
)

#: swept paths that set a break condition's limit (the line's, or a segment's own): the
#: limits of each case's line are checked on its result (per combination, like its loads)
FAILURE = re.compile(
    r"^line\.(segments\.\d+\.)?failure\.(tension|minimum_breaking_load|safety_factor)$"
)

#: a segment's catalogue size (its line type's nominal diameter, from which validation
#: derives its diameter, mass, weight and stiffness): each combination's line is the
#: study validated as a whole with it (:func:`line_studies`)
LINE_TYPE = re.compile(r"^line\.segments\.\d+\.line_type\.nominal_diameter$")

#: swept paths that change the seabed only (its depth, slope and friction): each case's
#: medium is that of its combination, like its line
SEABED = re.compile(r"^environment\.(depth|seabed\.(friction|slope_deg|slope_heading_deg))$")


#: swept paths that change where the line's loads act: a segment's unstretched
#: ``length`` (the line's length, where its nodes lie and on which segment) and an
#: attachment's position ``s`` along the line and its ``force`` components; each
#: case's line is cut into its pieces as a case alone is (the compiled kernels take
#: per-case pieces: :mod:`cablestudy.analyses.static_grid_lines`)
LINE_GEOMETRY = re.compile(r"^line\.(segments\.\d+\.length|attachments\.\d+\.(s|force\.[012]))$")

#: swept paths that change the current only (a profile point's speed or heading): each
#: case's medium is that of its combination, like its seabed (the drag iteration then
#: runs per case in the compiled batch, :mod:`cablestudy.statics.batch_drag`)
CURRENT = re.compile(r"^environment\.current\.\d+\.(speed|heading_deg)$")


#: swept static settings (the output points' count, the drag elements of a line in a
#: current, the solver's tolerance and iteration limit, the strain warning's limit): the
#: array chunk solves its cases per group of equal settings, each group with its own
#: settings (:mod:`cablestudy.analyses.static_grid_settings`), as each case alone is
STATIC_SETTING = re.compile(
    r"^analysis\.static\.(nodes|drag_elements|tolerance|max_iterations|strain_warning)$"
)


def per_line(path: str) -> bool:
    """Whether ``path`` is one whose values are built per combination (a load of the
    line, :data:`LINE_LOAD`, its drag and added-mass coefficients, :data:`LINE_HYDRO`,
    its break limits, :data:`FAILURE`, a segment's catalogue size, :data:`LINE_TYPE`,
    where and how long its parts are, :data:`LINE_GEOMETRY`,
    the seabed, :data:`SEABED`, or the current, :data:`CURRENT`)."""
    return bool(
        LINE_LOAD.match(path)
        or LINE_HYDRO.match(path)
        or FAILURE.match(path)
        or LINE_TYPE.match(path)
        or LINE_GEOMETRY.match(path)
        or SEABED.match(path)
        or CURRENT.match(path)
    )


#: at most this many combinations of line values are built (a grid with more is solved
#: as validated cases: :mod:`cablestudy.analyses.static_grid_cases`)
MAX_LINES = 10_000


def line_axes(grid: Any) -> tuple[int, ...]:
    """The axes of ``grid`` that hold a :data:`LINE_LOAD` or :data:`SEABED` path, in
    order."""
    return tuple(k for k, axis in enumerate(grid.axes) if any(per_line(p) for p in axis.paths))


def line_count(axes: list[Any]) -> int:
    """How many distinct lines a grid over ``axes`` has (1 without a line path)."""
    return math.prod(a.size for a in axes if any(per_line(p) for p in a.paths))


def line_studies(grid: Any) -> list[Any]:
    """Per combination of the values on :func:`line_axes` (C order), the template with
    those validated values copied in (built once, kept in ``grid.memo``). Raises as the
    full validation of a case with that combination would (a segment given both a mass
    and a weight in the fluid, ...)."""
    from .grid_studies import case_study

    found = grid.memo.get("line_studies")
    if found is not None:
        return found
    axes = line_axes(grid)
    paths = [(k, p) for k in axes for p in grid.axes[k].paths if per_line(p)]
    whole = set(getattr(grid, "whole", ()))
    found = []
    for combo in itertools.product(*(range(grid.shape[k]) for k in axes)):
        at = dict(zip(axes, combo, strict=True))
        values = {p: grid.validated[p][1][at[k]] for k, p in paths if p not in whole}
        # a path that cannot be copied in (a segment of a catalogue line type, whose
        # validator derives its other fields): the whole study of those values
        picks = tuple((p, at[k]) for k, p in paths if p in whole)
        base = _whole_study(grid, picks) if picks else grid.template
        found.append(case_study(base, values) if values else base)
    grid.memo["line_studies"] = found
    return found


def _whole_study(grid: Any, picks: tuple[tuple[str, int], ...]) -> Any:
    """The study validated as a whole with the values of the swept ``picks`` (path,
    index along its axis) put in, the others the template's (built once per grid; the
    memo :meth:`cablestudy.study.grid.CaseGrid.study_at` keeps such studies in)."""
    from .cases import _copy_tree, _set_path
    from .loader import validate_data

    found = grid.memo.get(picks)
    if found is None:
        src = grid.src
        data = _copy_tree({k: v for k, v in src.data.items() if k != "sweep"})
        values = {p: v for a in grid.axes for p, v in zip(a.paths, a.values, strict=True)}
        for p, i in picks:
            _set_path(data, p, _copy_tree(values[p][i]))
        found = grid.memo[picks] = validate_data(data, src)
    return found


def line_index(grid: Any, lo: int, hi: int) -> np.ndarray:
    """Per case of rows ``lo:hi`` (C order), the number of its line in
    :func:`line_studies`."""
    axes = line_axes(grid)
    block = (hi - lo, *grid.shape[1:])
    if not axes:
        return np.zeros(math.prod(block), dtype=np.int64)
    idx = np.indices(block).reshape(len(block), -1)
    idx[0] += lo
    return np.ravel_multi_index(
        tuple(idx[k] for k in axes), tuple(grid.shape[k] for k in axes)
    ).astype(np.int64)


def weightless(study: Any) -> bool:
    """Whether the line of ``study`` has no weight in its fluid (what
    :meth:`cablestudy.study.study.Study._physical` asks before its chord check)."""
    env = study.environment
    rho, g = env.density, env.gravity
    return all(seg.weight_in(rho, g) == 0.0 for seg in study.line.segments) and not any(
        att.mass != rho * att.volume or any(att.force) for att in study.line.attachments
    )


def static_setting(template: Any, path: str) -> bool:
    """Whether ``path`` is a static setting the array chunk takes per group of cases
    (:data:`STATIC_SETTING`). ``drag_elements`` only where the template has a current:
    without one each swept value is refused by the support check of every axis value
    (:func:`cablestudy.analyses.unused_keys.unused_key_problems`), which an array grid
    does not run (its template answers for every case)."""
    m = STATIC_SETTING.match(path)
    if m is None:
        return False
    return m.group(1) != "drag_elements" or bool(template.environment.current)
