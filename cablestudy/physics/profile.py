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
    end_pull: np.ndarray | None = None,
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
    end_pull : (2, 3) [N], optional
        The tension vector T(s) (the pull of the part beyond s on the part before it) at
        end A and at end B (:func:`end_pulls`), for a line without bending stiffness at
        that end: along the tangent dr/ds, so the end's angles are its direction,
        exactly. A zero vector (no tension there, or not known) keeps the end's
        one-sided difference; a non-finite one (a failed case) gives NaN.

    Returns
    -------
    dict with ``elevation`` [rad] and ``azimuth`` [rad] of the tangent dr/ds
    (second-order differences: an error O(h^2 kappa^2) for node spacing h and curvature
    kappa, and at a point load the mean of the tangents on either side; at an end with
    a non-zero ``end_pull``, its direction); the azimuth of
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
    if end_pull is not None:
        t = _ends_along(t, np.asarray(end_pull, dtype=float))
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


def _ends_along(t: np.ndarray, pull: np.ndarray) -> np.ndarray:
    """Unit tangents ``t`` (..., n, 3) with the first and last replaced by the direction
    of ``pull`` (..., 2, 3) where that is non-zero (NaN where it is not finite)."""
    t = t.copy()
    size = np.sqrt(np.sum(pull * pull, axis=-1))  # (..., 2)
    use = ~(size == 0.0)  # NaN (a failed case) is used too: its angles are NaN
    unit = pull / np.where(use, size, 1.0)[..., None]
    t[..., 0, :] = np.where(use[..., 0, None], unit[..., 0, :], t[..., 0, :])
    t[..., -1, :] = np.where(use[..., 1, None], unit[..., 1, :], t[..., -1, :])
    return t


def end_pulls(
    force_a: np.ndarray,
    force_b: np.ndarray,
    *,
    free_a: np.ndarray | bool,
    free_b: np.ndarray | bool,
    floor: np.ndarray | float = 0.0,
) -> np.ndarray:
    """The tension vectors (..., 2, 3) [N] at end A and end B for ``profile_quantities``:
    from the forces the line exerts on its ends (``force_a``, ``force_b`` (..., 3)),
    T(0) = force_a and T(L) = -force_b (the end's support pulls the line with
    -force_a at A, and the line there pulls towards B; at B the support's pull
    -force_b is the line's tension pointing away from A). ``free_a``, ``free_b``
    (bool, or (...,)): whether the tension is along the tangent at that end (no bending
    stiffness there, whose shear would tilt the end force, and no point load at the
    end itself, which T(0) = force_a leaves out); where not, the vector is zero. So is
    an end force no larger than ``floor`` [N] (or (...,)): one within the solver's
    force tolerance of zero (a slack end laid on the seabed) has no direction to
    trust; its end keeps the position differences."""
    fa = np.asarray(force_a, dtype=float)
    fb = np.asarray(force_b, dtype=float)
    floor = np.asarray(floor, dtype=float)
    big_a = ~(np.sqrt(np.sum(fa * fa, axis=-1)) <= floor)  # NaN stays: a failed case
    big_b = ~(np.sqrt(np.sum(fb * fb, axis=-1)) <= floor)
    a = np.where((np.asarray(free_a) & big_a)[..., None], fa, 0.0)
    b = np.where((np.asarray(free_b) & big_b)[..., None], -fb, 0.0)
    return np.stack(np.broadcast_arrays(a, b), axis=-2)
