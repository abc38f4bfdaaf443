"""Current profiles: piecewise linear in z, constant beyond the first and last points."""

from __future__ import annotations

import numpy as np


def current_velocity(
    z: np.ndarray, profile_z: np.ndarray, profile_velocity: np.ndarray
) -> np.ndarray:
    """Current velocity at heights ``z`` [m].

    Parameters
    ----------
    z : [m] heights, any shape
    profile_z : [m] shape (m,), strictly increasing heights of the profile points
    profile_velocity : [m/s] shape (m, 3), velocity at those points

    Returns
    -------
    [m/s] shape z.shape + (3,). Zero everywhere when the profile is empty. Each
    Cartesian component is interpolated linearly in z (so a current that turns with
    depth turns smoothly between the given headings).
    """
    z = np.asarray(z, dtype=float)
    out = np.zeros(z.shape + (3,))
    if profile_z.size == 0:
        return out
    for k in range(3):
        out[..., k] = np.interp(z, profile_z, profile_velocity[:, k])
    return out
