"""Break conditions and law ranges on the static results of an array chunk: each case's
limits are its line's (:func:`cablestudy.study.problem.static_limits` of the template,
or of the study of its swept line: a swept length moves the segment ends, a swept
``failure`` value the limit), checked by :func:`cablestudy.statics.limits.apply_limits`
on the case's own result, as the case alone is checked. A broken case keeps its results
(status 10 and a message with where and by how much); a strain past a law's checked
range fails it.
"""

from __future__ import annotations

from typing import Any

import numpy as np


def apply_grid_limits(st: Any, template: Any, lines: Any) -> None:
    """Mark, in place, the cases of ``st`` (a chunk's stacked static results,
    :class:`cablestudy.analyses.static_grid.StaticArrays`) broken or failed where they
    pass their line's limits (``lines``: each case's own line, else ``template``'s).
    A case whose largest tension at its output points is at most its line's smallest
    break limit, on a line without a checked law range, cannot pass it (the tension
    :func:`apply_limits` also checks at the segment ends is interpolated between output
    points, so no larger): it is not looked at."""
    from ..statics.base import StaticResult
    from ..statics.limits import apply_limits
    from ..study.problem import static_limits

    studies = [template] if lines is None else lines.studies
    which = np.zeros(len(st.status), dtype=np.int64) if lines is None else lines.which
    used = np.unique(which)
    limits = {int(j): static_limits(studies[j]) for j in used.tolist()}
    if not any(lim.active for lim in limits.values()):
        return
    # per distinct line the tension no case of it can pass without breaking (-inf where
    # a law's range is checked: every case is looked at)
    low = np.full(len(studies), np.inf)
    for j, lim in limits.items():
        law = any(law is not None for law in lim.law)
        low[j] = -np.inf if law else float(np.min(lim.break_tension))
    lowest = low[which]
    peak = np.max(st.tension, axis=1) if st.tension.size else np.zeros(len(which))
    look = np.flatnonzero((st.status == 0) & ~(peak <= lowest))
    for i in look.tolist():
        lim = limits[int(which[i])]
        if not lim.active:
            continue
        res = StaticResult(
            s=st.s[i],
            position=st.position[i],
            tension=st.tension[i],
            force_a=st.force_a[i],
            force_b=st.force_b[i],
            laid_length=float(st.laid_length[i]),
            status=int(st.status[i]),
            message=st.messages[i],
            iterations=int(st.iterations[i]),
            residual=float(st.residual[i]),
            drag_iterations=int(st.drag_iterations[i]),
        )
        got = apply_limits(res, lim)
        if got is res:
            continue
        st.status[i] = got.status
        st.messages[i] = got.message
        for name in ("s", "position", "tension", "force_a", "force_b"):
            getattr(st, name)[i] = getattr(got, name)
        st.laid_length[i] = got.laid_length
        st.iterations[i] = got.iterations
        st.residual[i] = got.residual
        st.drag_iterations[i] = got.drag_iterations
