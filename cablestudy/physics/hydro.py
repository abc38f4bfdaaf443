"""Morison drag on a line element, split into normal and tangential parts.

dodaran-park seed, eqs. (38)-(39): for relative velocity U (fluid minus line) and unit
tangent t, U_tau = (U . t) t and U_N = U - U_tau; per unit length

    f_N   = 1/2 rho C_N d |U_N| U_N
    f_tau = pi/2 rho C_tau d |U_tau| U_tau

(the tangential coefficient acts on the wetted perimeter pi d, as in the seed).
"""

from __future__ import annotations

import numpy as np


def drag_per_length(
    relative_velocity: np.ndarray,
    tangent: np.ndarray,
    *,
    density: float,
    diameter: np.ndarray,
    drag_normal: np.ndarray,
    drag_tangential: np.ndarray,
) -> np.ndarray:
    """Drag force per unit length [N/m], shape (..., 3).

    Parameters
    ----------
    relative_velocity : [m/s] (..., 3) fluid velocity minus line velocity
    tangent : [-] (..., 3) unit tangents
    density : [kg/m^3]
    diameter : [m] (...,)
    drag_normal, drag_tangential : [-] (...,)
    """
    u_t = np.sum(relative_velocity * tangent, axis=-1, keepdims=True) * tangent
    u_n = relative_velocity - u_t
    speed_n = np.linalg.norm(u_n, axis=-1, keepdims=True)
    speed_t = np.linalg.norm(u_t, axis=-1, keepdims=True)
    d = np.asarray(diameter)[..., None]
    cn = np.asarray(drag_normal)[..., None]
    ct = np.asarray(drag_tangential)[..., None]
    return 0.5 * density * d * (cn * speed_n * u_n + np.pi * ct * speed_t * u_t)
