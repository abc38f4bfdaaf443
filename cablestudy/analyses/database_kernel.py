"""The compiled cell evaluation of :class:`cablestudy.analyses.database.QuasiStaticDatabase`
(imported at the first lookup, so that validating a study does not load numba)."""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True, nogil=True)
def evaluate_cell(cells, P, Q, p, q):  # noqa: ANN001, ANN201
    """All quantities at grid coordinates (``p``, ``q``) inside the grid: the cell by
    binary search on the breakpoints ``P``, ``Q``, then its bicubic patch, whose
    coefficients ``cells[i, j]`` (n_quantities, 16) act on t^m u^n (m, n = 0..3, n
    fastest), t and u the coordinates within the cell."""
    i = np.searchsorted(P, p, side="right") - 1
    j = np.searchsorted(Q, q, side="right") - 1
    i = min(max(i, 0), P.shape[0] - 2)
    j = min(max(j, 0), Q.shape[0] - 2)
    t = (p - P[i]) / (P[i + 1] - P[i])
    u = (q - Q[j]) / (Q[j + 1] - Q[j])
    c = cells[i, j]
    out = np.empty(c.shape[0])
    for k in range(c.shape[0]):
        acc = 0.0
        tm = 1.0
        for m in range(4):
            row = c[k, 4 * m] + u * (c[k, 4 * m + 1] + u * (c[k, 4 * m + 2] + u * c[k, 4 * m + 3]))
            acc += tm * row
            tm *= t
        out[k] = acc
    return out
