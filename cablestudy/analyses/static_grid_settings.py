"""Swept static settings in an array chunk: the node count (``analysis.static.nodes``),
the drag elements of a line in a current, the tolerance, the iteration limit and the
strain warning's limit (:data:`cablestudy.study.grid_lines.STATIC_SETTING`).

The cases of a chunk are put in groups of equal settings (:func:`settings_groups`);
each group is solved by the array path with its own settings, as its static problem
(:func:`cablestudy.study.problem.static_problem`) and its study (the template with the
settings' validated values copied in: :func:`cablestudy.study.grid_studies.case_study`)
give them to a case alone, and its outputs are put back at the group's rows
(:func:`solve_in_groups`). Outputs along the line are padded by their fill (NaN) to the
grid's largest node count, as the case-by-case chunk pads them
(:func:`cablestudy.analyses.static_grid_cases.grid_nodes`): the dataset's ``s`` is then
the node index and ``arc_length`` each case's arc lengths.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from ..study.grid_lines import STATIC_SETTING


def settings_groups(grid: Any, lo: int, hi: int) -> list[tuple[np.ndarray, Any]] | None:
    """Per combination of swept static settings among the cases of rows ``lo:hi`` (C
    order): the cases' positions in the chunk and the study of that combination (the
    template with the settings' validated values copied in, built once per grid); None
    when no static setting is swept (the template's settings for every case)."""
    from ..study.grid_studies import case_study

    # the axes that hold a swept static setting, in order
    axes = tuple(
        k for k, axis in enumerate(grid.axes) if any(STATIC_SETTING.match(p) for p in axis.paths)
    )
    if not axes:
        return None
    block = (hi - lo, *grid.shape[1:])
    idx = np.indices(block).reshape(len(block), -1)
    idx[0] += lo
    combo = np.ravel_multi_index(tuple(idx[k] for k in axes), tuple(grid.shape[k] for k in axes))
    paths = [(k, p) for k in axes for p in grid.axes[k].paths if STATIC_SETTING.match(p)]
    groups = []
    for c in np.unique(combo).tolist():
        at = dict(zip(axes, np.unravel_index(c, tuple(grid.shape[k] for k in axes)), strict=True))
        key = ("static_settings", c)
        study = grid.memo.get(key)
        if study is None:
            values = {p: grid.validated[p][1][int(at[k])] for k, p in paths}
            study = grid.memo[key] = case_study(grid.template, values)
        groups.append((np.flatnonzero(combo == c), study))
    return groups


def group_problem(base: Any, study: Any, with_: Callable[..., Any]) -> Any:
    """``base`` (the template's static problem) with the static settings of ``study``,
    the fields :func:`cablestudy.study.problem.static_problem` takes from them."""
    st = study.analysis.static
    return with_(
        base,
        n_nodes=st.nodes,
        tolerance=st.tolerance,
        max_iterations=st.max_iterations,
        drag_elements=st.drag_elements or 0,
    )


def solve_in_groups(
    grid: Any,
    groups: list[tuple[np.ndarray, Any]],
    base: Any,
    pos: dict[str, Any],
    ea: np.ndarray,
    deadline: float,
    solve: Callable[..., Any],
    with_: Callable[..., Any],
    take: Callable[..., Any],
) -> tuple[dict[str, np.ndarray], np.ndarray, list[str], dict[int, list[str]], np.ndarray]:
    """``solve`` (:func:`cablestudy.analyses.static_grid._solve_outputs`) per group of
    :func:`settings_groups` with its study and settings, the outputs put back in the
    chunk's order: those along the line padded by their fill to the grid's largest node
    count (as the case-by-case chunk: :func:`records_chunk` with its extent)."""
    from .grid_chunk import output_fill
    from .static_grid_cases import grid_nodes
    from .variables import OUTPUTS

    n = len(ea)
    n_s = grid_nodes(grid)
    data: dict[str, np.ndarray] = {}
    status = np.zeros(n, dtype=np.int64)
    messages = [""] * n
    warnings: dict[int, list[str]] = {}
    reasons = np.full(n, "", dtype=object)
    for rows, study in groups:
        got, st_g, msg_g, warn_g, why_g = solve(
            study, group_problem(base, study, with_), take(pos, rows), ea[rows], deadline
        )
        for name, arr in got.items():
            if name not in data:
                dims = OUTPUTS[name].dims
                tail = tuple(
                    n_s if d == "s" else k for d, k in zip(dims, arr.shape[1:], strict=True)
                )
                data[name] = np.full((n, *tail), output_fill(name, arr), dtype=arr.dtype)
            data[name][(rows, *(slice(0, k) for k in arr.shape[1:]))] = arr
        status[rows] = st_g
        reasons[rows] = why_g
        for i, msg in zip(rows.tolist(), msg_g, strict=True):
            messages[i] = msg
        for j, texts in warn_g.items():
            warnings[int(rows[j])] = texts
    return data, status, messages, warnings, reasons
