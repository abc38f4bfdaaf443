"""Closed-form increments of an elastic line piece under a constant distributed load.

This is the element of the semi-analytic solver (dodaran-park seed, eqs. 16-25),
written for a load of any direction so that one formula serves weight, weight plus a
piecewise-constant drag, and the straight laid line on a seabed.

A piece of unstretched length ``l`` [m] and axial stiffness ``EA`` [N] carries the
distributed external load ``q`` [N/m] (force applied to the line per unstretched
length). With ``T0`` [N] the tension vector at its start (tension times the unit
tangent along increasing s), equilibrium gives T(sigma) = T0 - q sigma, and Hooke's law
(seed eq. 5) with the compatibility relation (seed eq. 4) gives

    dr/ds = T (1/EA + 1/|T|).

Write w = |q| and u = -q / w (the direction in which T grows), V = T . u and
H = T - V u (constant along the piece). Then V(sigma) = V0 + w sigma and

    delta r = T0 l / EA - q l^2 / (2 EA) + H int(1/|T|) + u int(V/|T|),

the seed's eqs. (23)-(25) with the vertical replaced by u. The derivative of delta r
with respect to T0 (the Jacobian of the Newton iteration on the end forces) is

    d delta r / d T0 = (l/EA) I + int((|T|^2 I - T T^T) / |T|^3),

the flexibility of the piece: symmetric positive semi-definite, and the Hessian of
the convex complementary energy ``int(|T| + |T|^2 / (2 EA))``, also returned. Every
integral is evaluated in a form free of cancellation (for small w, near-vertical
pieces and H -> 0); for instance with a = |V0|, b = |V1| of one sign

    int(1/|T|) = l (a + b) / (b |T0| + a |T1|) * asinh(X) / X,
    X = (b^2 - a^2) / (b |T0| + a |T1|),

which needs no division by w or by H.
"""

from __future__ import annotations

import numpy as np


def piece_integrals(
    T0: np.ndarray, q: np.ndarray, ell: np.ndarray, EA: np.ndarray, *, jacobian: bool = True,
) -> tuple[np.ndarray, np.ndarray | None, np.ndarray]:
    """Position increment, flexibility and complementary energy of line pieces.

    Parameters
    ----------
    T0 : np.ndarray
        [N] shape (..., 3), tension vector at the start of each piece.
    q : np.ndarray
        [N/m] shape (..., 3), distributed load applied to the line per unstretched length.
    ell : np.ndarray
        [m] shape (...), unstretched length of each piece (>= 0).
    EA : np.ndarray
        [N] shape (...), axial stiffness.
    jacobian : bool
        Whether to compute the flexibility matrix.

    Returns
    -------
    dr : np.ndarray
        [m] shape (..., 3), position of the piece's end relative to its start.
    jac : np.ndarray or None
        [m/N] shape (..., 3, 3), d dr / d T0.
    energy : np.ndarray
        [N m] shape (...), int(|T| + |T|^2 / (2 EA)) ds, whose gradient in T0 is dr.
    """
    with np.errstate(all="ignore"):
        w = np.sqrt(np.sum(q * q, axis=-1))
        curved = w > 0.0
        u = np.where(curved[..., None], -q / np.where(curved, w, 1.0)[..., None], 0.0)
        V0 = np.sum(T0 * u, axis=-1)
        Hv = T0 - V0[..., None] * u
        H2 = np.sum(Hv * Hv, axis=-1)
        wl = w * ell
        V1 = V0 + wl
        T0n = np.sqrt(H2 + V0 * V0)
        T1n = np.sqrt(H2 + V1 * V1)
        a = np.abs(V0)
        b = np.abs(V1)
        same = curved & (V0 * V1 > 0.0)
        opp = curved & ~same & (wl > 0.0)
        straight = ~(same | opp)

        # same sign of V along the piece: cancellation-free forms
        Dn = b * T0n + a * T1n
        X = (b - a) * (b + a) / Dn
        small = np.abs(X) < 1e-4
        ratio = np.where(small, 1.0 - X * X / 6.0, np.arcsinh(X) / np.where(small, 1.0, X))
        P_same = ell * (a + b) / Dn * ratio
        J_same = ell * (a + b) / (T0n * T1n * Dn)
        A_same = 0.5 * ell * (V0 + V1) * (V0 * V0 + V1 * V1 + H2) / (V1 * T1n + V0 * T0n)

        # V changes sign: no cancellation in the plain differences
        H = np.sqrt(H2)
        Hs = np.maximum(H, 1e-200 * (a + b))
        wls = np.where(wl > 0.0, wl, 1.0)
        P_opp = ell * (np.arcsinh(V1 / Hs) - np.arcsinh(V0 / Hs)) / wls
        A_opp = 0.5 * ell * (V1 * T1n - V0 * T0n) / wls

        # straight piece (no load, or zero length)
        P_str = ell / T0n
        J_str = ell / T0n**3
        A_str = ell * T0n

        Pl = np.where(same, P_same, np.where(opp, P_opp, P_str))
        A1 = np.where(same, A_same, np.where(opp, A_opp, A_str))
        A1 = A1 + 0.5 * H2 * np.where(straight, 0.0, Pl)
        zero = ell == 0.0
        Pl = np.where(zero, 0.0, Pl)
        A1 = np.where(zero, 0.0, A1)
        S1 = np.where(zero, 0.0, ell * (V0 + V1) / (T0n + T1n))

        inv_ea = ell / EA
        dr = (T0 * inv_ea[..., None] - q * (0.5 * ell * inv_ea)[..., None]
              + Hv * Pl[..., None] + u * S1[..., None])
        TT = np.sum(T0 * T0, axis=-1)
        energy = A1 + (TT * ell - np.sum(T0 * q, axis=-1) * ell * ell
                       + w * w * ell**3 / 3.0) / (2.0 * EA)
        if not jacobian:
            return dr, None, energy
        # H^2 int(1/|T|^3), finite also as H -> 0 where int(1/|T|^3) alone is not
        H2J_opp = ell * (V1 / T1n - V0 / T0n) / wls
        H2J = np.where(same, H2 * J_same, np.where(opp, H2J_opp, H2 * J_str))
        H2J = np.where(zero, 0.0, H2J)
        L1H = np.where(zero, 0.0, ell * (V0 + V1) * H / ((T0n + T1n) * T0n * T1n))
        K = Pl - H2J
        nh = np.where((H > 0.0)[..., None], Hv / np.where(H > 0.0, H, 1.0)[..., None], 0.0)
        eye = np.eye(3)
        jac = ((inv_ea + Pl)[..., None, None] * eye
               - H2J[..., None, None] * nh[..., :, None] * nh[..., None, :]
               - L1H[..., None, None] * (nh[..., :, None] * u[..., None, :]
                                         + u[..., :, None] * nh[..., None, :])
               - K[..., None, None] * u[..., :, None] * u[..., None, :])
    return dr, jac, energy
