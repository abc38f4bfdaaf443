"""Quantities along a static line derived from its shape and tension (vaz-patel seed):
tangent angles, elongation and the actual (wall) tension.

The seed describes the line by its elevation angle phi (tangent above the horizontal)
and azimuth psi (the tangent's horizontal projection, from +x towards +y), its
elongation (stretched length p minus unstretched length s, dp/ds = 1 + e with the
strain e = T / EA), and relates the effective tension T of the equilibrium equations
to the actual tension in the wall, T_wall = T_eff - rho g A (h - Y) with h - Y the depth
below the surface; in our frame (z up, surface at 0) that is T_wall = T + rho g z A.
"""

from __future__ import annotations

import numpy as np


def profile_quantities(
    s: np.ndarray,
    position: np.ndarray,
    tension: np.ndarray,
    *,
    axial_stiffness: np.ndarray,
    area: np.ndarray,
    strain: np.ndarray | None = None,
    density: float,
    gravity: float,
) -> dict[str, np.ndarray]:
    """Elevation, azimuth, elongation and wall tension at the points of a static line (or
    of many lines at the same ``s``: leading case axes on ``position``, ``tension``,
    ``axial_stiffness`` and ``strain``, each line's quantities as alone).

    Parameters
    ----------
    s : (n,) [m]
        Unstretched arc length from end A, increasing.
    position : (n, 3) [m]
        Positions, z up, sea surface at z = 0.
    tension : (n,) [N]
        Effective tension.
    axial_stiffness : (n,) [N]
        EA of the segment at each point.
    area : (n,) [m^2]
        Displaced cross-section pi d^2 / 4 at each point.
    strain : (n,) [-], optional
        Axial strain at each point from a non-linear axial law (default T / EA).
    density : [kg/m^3]
    gravity : [m/s^2]

    Returns
    -------
    dict with ``elevation`` [rad] and ``azimuth`` [rad] of the tangent dr/ds
    (second-order differences: an error O(h^2 kappa^2) for node spacing h and curvature
    kappa, and at a point load the mean of the tangents on either side); the azimuth of
    a vertical tangent (horizontal part below 1e-12) is that of the nearest point along
    the line that has one (0 if none does); ``elongation`` [m], the integral of
    T / EA from A (trapezoids, O(h^2)); ``tension_wall`` [N], T + rho g z A.
    """
    s = np.asarray(s, dtype=float)
    position = np.asarray(position, dtype=float)
    tension = np.asarray(tension, dtype=float)
    n = s.size
    if n >= 3:
        d = np.gradient(position, s, axis=-2, edge_order=2)
    else:
        d = np.repeat(np.diff(position, axis=-2), n, axis=-2)[..., :n, :]
    norm = np.linalg.norm(d, axis=-1)
    t = d / np.where(norm > 0.0, norm, 1.0)[..., None]
    horizontal = np.hypot(t[..., 0], t[..., 1])
    elevation = np.arctan2(t[..., 2], horizontal)
    azimuth = np.arctan2(t[..., 1], t[..., 0])
    for line in np.ndindex(horizontal.shape[:-1]):  # one line, or each of many
        defined = horizontal[line] > 1e-12
        if defined.all():
            continue
        if defined.any():
            idx = np.flatnonzero(defined)
            nearest = idx[np.abs(np.arange(n)[:, None] - idx[None, :]).argmin(axis=1)]
            azimuth[line] = azimuth[line][nearest]
        else:
            azimuth[line] = 0.0
    if strain is None:
        strain = tension / np.asarray(axial_stiffness, dtype=float)
    steps = np.cumsum(0.5 * (strain[..., 1:] + strain[..., :-1]) * np.diff(s), axis=-1)
    elongation = np.concatenate([np.zeros((*steps.shape[:-1], 1)), steps], axis=-1)
    tension_wall = tension + density * gravity * position[..., 2] * np.asarray(area, dtype=float)
    return {
        "elevation": elevation,
        "azimuth": azimuth,
        "elongation": elongation,
        "tension_wall": tension_wall,
    }
