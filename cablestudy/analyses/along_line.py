"""Values along the line at the output points from a line model's element and end
values: an element's tension holds over its length, the end tensions at the ends.
"""

from __future__ import annotations

import numpy as np


def tension_along(
    s_out: np.ndarray, s_nodes: np.ndarray, element: np.ndarray, ends: np.ndarray
) -> np.ndarray:
    """Element values (at element midpoints) with end values, interpolated to ``s_out``:
    the one way a line model's element and end tensions [N] become a variable on the
    dataset's ``s`` (the tension envelope of both dynamic methods, line histories)."""
    mid = 0.5 * (s_nodes[:-1] + s_nodes[1:])
    return np.interp(
        s_out,
        np.concatenate(([s_nodes[0]], mid, [s_nodes[-1]])),
        np.concatenate(([ends[0]], element, [ends[1]])),
    )


def tension_along_cases(
    s_out: np.ndarray, s_nodes: np.ndarray, element: np.ndarray, ends: np.ndarray
) -> np.ndarray:
    """:func:`tension_along` of K responses at once: ``element`` (K, n - 1) and ``ends``
    (K, 2) [N] give (K, len(s_out)), with the operations of ``np.interp`` (the slope
    of the interval times the distance from its left end, plus its left value; a knot
    or a point beyond the ends takes the value there), so the same numbers."""
    mid = 0.5 * (s_nodes[:-1] + s_nodes[1:])
    xp = np.concatenate(([s_nodes[0]], mid, [s_nodes[-1]]))
    fp = np.concatenate((ends[:, :1], element, ends[:, 1:]), axis=1)
    j = np.searchsorted(xp, s_out, side="right") - 1  # xp[j] <= s < xp[j + 1]
    inner = (j >= 0) & (j < xp.size - 1)
    jj = np.clip(j, 0, xp.size - 2)
    slope = (fp[:, jj + 1] - fp[:, jj]) / (xp[jj + 1] - xp[jj])
    out = slope * (s_out - xp[jj]) + fp[:, jj]
    if np.isnan(out).any():  # as np.interp: from the right end of the interval instead
        other = slope * (s_out - xp[jj + 1]) + fp[:, jj + 1]
        out = np.where(np.isnan(out), other, out)
        out = np.where(np.isnan(out) & (fp[:, jj] == fp[:, jj + 1]), fp[:, jj], out)
    knot = ~inner | (xp[np.clip(j, 0, xp.size - 1)] == s_out)
    at = np.where(j < 0, 0, np.clip(j, 0, xp.size - 1))
    return np.where(knot[None], fp[:, at], out)
