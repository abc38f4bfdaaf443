"""The seabed test of the compiled drag iteration (:mod:`._drag_fast`): whether a shape
of a line hanging free in a current over a seabed reaches it (:func:`_dips`), in which
case the general solver lays the line (:mod:`.midspan`) and the kernel hands it on.

Pure: arrays in, a flag out.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ._fast import _piece_general


@njit(cache=True, error_model="numpy")
def _dips(
    q: np.ndarray,
    ell: np.ndarray,
    EA: np.ndarray,
    bounds: np.ndarray,
    C: np.ndarray,
    TA: np.ndarray,
    nodes: np.ndarray,
    seabed: np.ndarray,
) -> bool:
    """Whether the free-hanging shape (tension ``TA`` at A, offsets ``C`` of the loads
    ``q``, piece starts ``nodes``) reaches the seabed plane ``seabed`` = (upward unit
    normal, depth): at the points where
    :func:`.semi_analytic_shape._penetrates` samples it (max(4 P + 1, 401) evenly along
    s), any height below zero. The general solver lays the line when one is below
    -1e-9 L; zero, not that, is the bound here, so that round-off between the two
    shapes (1e-12 L) can never make them decide differently: a shape within 1e-9 L of
    the seabed is left to the general solver too."""
    P = ell.shape[0]
    L = bounds[P]
    m = max(4 * P + 1, 401)
    step = L / (m - 1)
    dr = np.zeros(3)
    jac = np.zeros((3, 3))
    k = 0
    for j in range(m):
        sj = j * step if j < m - 1 else L
        while k < P - 1 and bounds[k + 1] <= sj:
            k += 1
        sig = min(max(sj - bounds[k], 0.0), ell[k])
        _piece_general(
            TA[0] - C[k, 0], TA[1] - C[k, 1], TA[2] - C[k, 2], q[k, 0], q[k, 1], q[k, 2],
            sig, EA[k], dr, jac, False,
        )  # fmt: skip
        h = (
            (nodes[k, 0] + dr[0]) * seabed[0]
            + (nodes[k, 1] + dr[1]) * seabed[1]
            + (nodes[k, 2] + dr[2] + seabed[3]) * seabed[2]
        )
        if not (h >= 0.0):
            return True
    return False
