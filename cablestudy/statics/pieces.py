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
    T0: np.ndarray,
    q: np.ndarray,
    ell: np.ndarray,
    EA: np.ndarray,
    *,
    jacobian: bool = True,
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
        # component arrays: numpy reductions over a length-3 axis are slow
        tx, ty, tz = T0[..., 0], T0[..., 1], T0[..., 2]
        qx, qy, qz = q[..., 0], q[..., 1], q[..., 2]
        w = np.sqrt(qx * qx + qy * qy + qz * qz)
        curved = w > 0.0
        inv_w = np.where(curved, 1.0 / np.where(curved, w, 1.0), 0.0)
        ux, uy, uz = -qx * inv_w, -qy * inv_w, -qz * inv_w
        V0 = tx * ux + ty * uy + tz * uz
        hx, hy, hz = tx - V0 * ux, ty - V0 * uy, tz - V0 * uz
        H2 = hx * hx + hy * hy + hz * hz
        wl = w * ell
        V1 = V0 + wl
        T0n = np.sqrt(H2 + V0 * V0)
        T1n = np.sqrt(H2 + V1 * V1)
        a = np.abs(V0)
        b = np.abs(V1)
        same = curved & (V0 * V1 > 0.0)
        opp = curved & ~same & (wl > 0.0)
        straight = ~(same | opp)
        any_opp = bool(np.any(opp))
        any_straight = bool(np.any(straight))

        # same sign of V along the piece: cancellation-free forms
        Dn = b * T0n + a * T1n
        X = (b - a) * (b + a) / Dn
        small = np.abs(X) < 1e-4
        ratio = np.where(small, 1.0 - X * X / 6.0, np.arcsinh(X) / np.where(small, 1.0, X))
        Pl = ell * (a + b) / Dn * ratio
        A1 = 0.5 * ell * (V0 + V1) * (V0 * V0 + V1 * V1 + H2) / (V1 * T1n + V0 * T0n)
        H = np.sqrt(H2)
        if any_opp:
            # V changes sign: no cancellation in the plain differences
            Hs = np.maximum(H, 1e-200 * (a + b))
            wls = np.where(wl > 0.0, wl, 1.0)
            Pl = np.where(opp, ell * (np.arcsinh(V1 / Hs) - np.arcsinh(V0 / Hs)) / wls, Pl)
            A1 = np.where(opp, 0.5 * ell * (V1 * T1n - V0 * T0n) / wls, A1)
        if any_straight:
            # straight piece (no load, or zero length)
            Pl = np.where(straight, ell / T0n, Pl)
            A1 = np.where(straight, ell * T0n, A1)
        A1 = A1 + 0.5 * H2 * np.where(straight, 0.0, Pl)
        zero = ell == 0.0
        Pl = np.where(zero, 0.0, Pl)
        A1 = np.where(zero, 0.0, A1)
        S1 = np.where(zero, 0.0, ell * (V0 + V1) / (T0n + T1n))

        inv_ea = ell / EA
        e2 = 0.5 * ell * inv_ea
        dr = np.stack(
            (
                tx * inv_ea - qx * e2 + hx * Pl + ux * S1,
                ty * inv_ea - qy * e2 + hy * Pl + uy * S1,
                tz * inv_ea - qz * e2 + hz * Pl + uz * S1,
            ),
            axis=-1,
        )
        TT = tx * tx + ty * ty + tz * tz
        Tq = tx * qx + ty * qy + tz * qz
        energy = A1 + (TT * ell - Tq * ell * ell + w * w * ell**3 / 3.0) / (2.0 * EA)
        if not jacobian:
            return dr, None, energy
        # H^2 int(1/|T|^3), finite also as H -> 0 where int(1/|T|^3) alone is not
        H2J = H2 * ell * (a + b) / (T0n * T1n * Dn)
        if any_opp:
            H2J = np.where(opp, ell * (V1 / T1n - V0 / T0n) / wls, H2J)
        if any_straight:
            H2J = np.where(straight, H2 * ell / T0n**3, H2J)
        H2J = np.where(zero, 0.0, H2J)
        L1H = np.where(zero, 0.0, ell * (V0 + V1) * H / ((T0n + T1n) * T0n * T1n))
        K = Pl - H2J
        pos = H > 0.0
        inv_h = np.where(pos, 1.0 / np.where(pos, H, 1.0), 0.0)
        nx, ny, nz = hx * inv_h, hy * inv_h, hz * inv_h
        diag = inv_ea + Pl
        n_ = (nx, ny, nz)
        u_ = (ux, uy, uz)
        jac = np.empty(np.shape(tx) + (3, 3))
        for i in range(3):
            for j in range(i, 3):
                v = -H2J * n_[i] * n_[j] - L1H * (n_[i] * u_[j] + u_[i] * n_[j]) - K * u_[i] * u_[j]
                if i == j:
                    v = v + diag
                jac[..., i, j] = v
                if i != j:
                    jac[..., j, i] = v
    return dr, jac, energy
