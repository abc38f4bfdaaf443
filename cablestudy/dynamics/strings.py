"""Closed-form natural frequencies of a string under linearly varying tension (pure, SI
units)."""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq
from scipy.special import j0, y0


def linear_tension_string(
    *, length: float, bottom_tension: float, weight: float, mass: float, count: int
) -> np.ndarray:
    """String fixed at both ends with tension T(s) = T0 + w s (a vertical riser):
    lateral natural frequencies [Hz], the roots of J0(xi_a) Y0(xi_b) - J0(xi_b) Y0(xi_a)
    with xi = 2 omega sqrt(m T) / w (u = A J0(xi) + B Y0(xi) solves (T u')' + m omega^2
    u = 0 when T is linear in s).

    Parameters
    ----------
    length : float  [m]
    bottom_tension : float  [N] T0 > 0
    weight : float  [N/m] w > 0, submerged weight per length
    mass : float  [kg/m] including added mass
    count : int
    """
    T0, w, L = bottom_tension, weight, length
    ra, rb = math.sqrt(mass * T0) / w, math.sqrt(mass * (T0 + w * L)) / w

    def cross(omega: float) -> float:
        a, b = 2 * omega * ra, 2 * omega * rb
        return float(j0(a) * y0(b) - j0(b) * y0(a))

    # Sturm comparison: omega_n lies between the n-th frequencies of uniform strings at
    # the least and the largest tension, n pi / L sqrt(T / m); scan that range finely
    lo = 0.5 * math.pi / L * math.sqrt(T0 / mass)
    hi = (count + 1) * math.pi / L * math.sqrt((T0 + w * L) / mass)
    grid = np.geomspace(lo, hi, 400 * (count + 1))
    vals = np.array([cross(o) for o in grid])
    idx = np.flatnonzero(vals[:-1] * vals[1:] < 0)[:count]
    roots = [brentq(cross, grid[i], grid[i + 1], xtol=1e-14) for i in idx]
    return np.array(roots) / (2 * math.pi)
