"""Seabed geometry of a line: where it leaves the seabed (the touchdown point).

Pure array functions in SI units.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit


def touchdown_arc_length(
    s: np.ndarray, z: np.ndarray, seabed_z: np.ndarray | float, tol: float
) -> float:
    """Arc length from end A [m] where the line leaves the seabed, or NaN.

    A node touches the seabed where its height above it, ``gap = z - seabed_z``, is at
    most ``tol``. The touchdown point is the end of the first run of touching nodes seen
    from A, on the side of the suspended span next to it: where that run ends (the first
    suspended node's side) when the run starts at A, else where it begins (the line
    hangs from A down to it). NaN when no node touches, or all do (no suspended span).

    Between the last touching node and the first suspended one the point is found by
    interpolation: a line leaving the seabed tangentially rises as the square of the
    distance from touchdown (a catenary's ``sqrt(a^2 + u^2) - a``, a beam's too), so
    the square root of the height over the touching nodes' level is linear in ``s``; it
    is extrapolated to zero from the first two suspended nodes (exact for a parabola;
    for a catenary of parameter ``a`` [m] and node spacing ``h`` the error is at most
    ``3 h^3 / (4 a^2)``). With a single suspended node the gap is interpolated linearly
    to ``tol``. The result stays between the touching node before the last one and the
    first suspended node.

    Parameters
    ----------
    s : [m] (n,) increasing arc lengths of the nodes from end A
    z : [m] (n,) node heights (z up)
    seabed_z : [m] scalar or (n,) seabed height under each node
    tol : [m] largest height above the seabed that counts as touching
    """
    s = np.asarray(s, dtype=float)
    gap = np.asarray(z, dtype=float) - seabed_z
    return touchdown_from_gap(s, np.ascontiguousarray(gap, dtype=float), float(tol))


@njit(cache=True)
def touchdown_from_gap(s, gap, tol):  # noqa: ANN001, ANN201
    """:func:`touchdown_arc_length` from the nodes' heights above the seabed ``gap``
    [m] (n,): compiled, since the time step tracks the touchdown point every step."""
    n = s.shape[0]
    if n < 2:
        return math.nan
    first_on = -1
    first_off = -1
    for i in range(n):
        on_i = gap[i] <= tol
        if on_i and first_on < 0:
            first_on = i
        if not on_i and first_off < 0:
            first_off = i
    if first_on < 0 or first_off < 0:  # no contact, or nothing else
        return math.nan
    if first_on == 0:
        last = first_off - 1  # last touching node of the run from A
        step = 1
    else:
        last = first_on  # first touching node seen from A
        step = -1
    first = last + step  # the first suspended node beyond the run
    base = min(gap[last], tol)  # level of the touching part
    h1 = gap[first] - base
    second = first + step
    lo = last
    if 0 <= last - step < n and gap[last - step] <= tol:
        lo = last - step
    s_td = math.nan
    if 0 <= second < n and not gap[second] <= tol:
        r1, r2 = math.sqrt(h1), math.sqrt(max(gap[second] - base, 0.0))
        if r2 > r1:
            s_td = s[first] - r1 * (s[second] - s[first]) / (r2 - r1)
    if math.isnan(s_td):
        w = (tol - gap[last]) / (gap[first] - gap[last])
        s_td = s[last] + min(max(w, 0.0), 1.0) * (s[first] - s[last])
    a, b = min(s[lo], s[first]), max(s[lo], s[first])
    return min(max(s_td, a), b)
