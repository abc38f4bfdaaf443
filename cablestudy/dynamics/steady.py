"""The time domain's steady-state rule, one for the single line (:mod:`.timedomain`,
:mod:`.pulley_timedomain`) and for the system (:mod:`.system_timedomain`).

A run is steady when the answer's dynamic part has converged: over the last
``window`` periods, each period's maximum and minimum tension changed from the
period before by at most ``tolerance`` times that period's dynamic range (maximum -
minimum). Judged against the tension instead (the rule before), a small dynamic range
on a large mean tension passes while its extremes still move by several per cent of it
(a 2 N range on 1512 N: 0.002 x 1512 = 3 N allowed). A range that the solve cannot
resolve, a line that barely moves, must still settle: a change of at most ``floor`` [N]
counts as none; the callers pass the force the Newton iteration resolves at an end, its
residual tolerance (set relative to the static tension) times the square root of the
node count (the end force sums the nodes' residuals: with the tolerance alone a laid
chain at rest, its friction at the Newton tolerance, never settled and its end tension
wandered by 6.7e-6 of it over 80 periods).

Pure: per-period extremes in, a bool out.
"""

from __future__ import annotations

import numpy as np


def extremes_settled(
    p_max: np.ndarray, p_min: np.ndarray, *, tolerance: float, window: int, floor: float
) -> bool:
    """Whether the per-period extremes ``p_max``, ``p_min`` [N] (periods first, any
    trailing shape: one end, or every watched end) have settled over the last
    ``window`` periods: for j = 1 .. window, |p[-j] - p[-j - 1]| <= max(``tolerance``
    (p_max[-j] - p_min[-j]), ``floor``) for both extremes, elementwise. Needs
    ``window + 1`` periods (False with fewer)."""
    hi = np.asarray(p_max, dtype=float)
    lo = np.asarray(p_min, dtype=float)
    if window < 1 or hi.shape[0] < window + 1:
        return False
    for j in range(1, window + 1):
        allowed = np.maximum(tolerance * (hi[-j] - lo[-j]), floor)
        # written as 'all within' so that a NaN extreme is never steady
        if not np.all(np.abs(hi[-j] - hi[-j - 1]) <= allowed):
            return False
        if not np.all(np.abs(lo[-j] - lo[-j - 1]) <= allowed):
            return False
    return True
