"""Irvine's linear theory of the free vibrations of a shallow level cable.

Irvine & Caughey (1974), Irvine, *Cable Structures* (MIT Press, 1981), ch. 3. A cable
of mass m [kg/m] hangs between two supports at the same level, span l [m], horizontal
tension H [N], weight w [N/m], axial stiffness EA [N]. With the cable parameter

    lambda^2 = (w l / H)^2 l / (H L_e / EA),   L_e = int_0^l (ds/dx)^3 dx ~ l (1 + 8 (d/l)^2)

(d the sag) the circular frequencies are omega = omega_bar sqrt(H / m) / l, with

* out-of-plane modes: omega_bar = n pi;
* in-plane antisymmetric modes: omega_bar = 2 n pi (no extra tension to first order);
* in-plane symmetric modes: the roots of tan(omega_bar / 2) = omega_bar / 2
  - (4 / lambda^2) (omega_bar / 2)^3.

The theory drops terms of order (d / l)^2. Pure functions, SI units.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq


def cable_parameter(
    *,
    span: float,
    weight: float,
    horizontal_tension: float,
    axial_stiffness: float,
    effective_length: float,
) -> float:
    """Irvine's lambda^2 [-].

    Parameters
    ----------
    span : float  [m]
    weight : float  [N/m] weight per length
    horizontal_tension : float  [N]
    axial_stiffness : float  [N] EA
    effective_length : float  [m] L_e = int (ds/dx)^3 dx
    """
    H = horizontal_tension
    return (weight * span / H) ** 2 * span / (H * effective_length / axial_stiffness)


def symmetric_roots(lambda_squared: float, count: int) -> np.ndarray:
    """Dimensionless frequencies omega_bar [-] of the first ``count`` in-plane
    symmetric modes: the roots of tan(x) = x - (4 / lambda^2) x^3, x = omega_bar / 2.

    f(x) = tan x - x + 4 x^3 / lambda^2 increases strictly (f' = tan^2 x + 12 x^2 /
    lambda^2 > 0) from -inf to +inf on each branch ((2k - 1) pi / 2, (2k + 1) pi / 2),
    so each branch k = 1, 2, ... holds exactly one root.
    """
    lam2 = float(lambda_squared)
    out = np.empty(count)
    for k in range(1, count + 1):
        lo = (2 * k - 1) * math.pi / 2
        hi = (2 * k + 1) * math.pi / 2
        eps = 1e-12 * hi

        def f(x: float) -> float:
            return math.tan(x) - x + 4.0 * x**3 / lam2

        out[k - 1] = 2.0 * brentq(f, lo + eps, hi - eps, xtol=1e-15, rtol=1e-15, maxiter=200)
    return out


def frequencies(lambda_squared: float, count: int) -> dict[str, np.ndarray]:
    """Dimensionless frequencies omega_bar = omega l / sqrt(H / m) [-] of the first
    ``count`` modes of each family: ``out_of_plane``, ``antisymmetric``, ``symmetric``."""
    n = np.arange(1, count + 1)
    return {
        "out_of_plane": n * math.pi,
        "antisymmetric": 2.0 * n * math.pi,
        "symmetric": symmetric_roots(lambda_squared, count),
    }
