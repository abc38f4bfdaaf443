"""Line pieces under a non-linear axial law: the closed-form linear piece plus the
exact integral of the law's departure from it.

A piece of unstretched length ``l`` under the constant load ``q`` carries the tension
vector T(sigma) = T0 - q sigma (:mod:`.pieces`). With any axial law e(|T|) (strain of
tension, :mod:`cablestudy.physics.axial`) its end lies at

    delta r = int_0^l (1 + e(|T|)) T / |T| dsigma
            = delta r_linear(EA) + int_0^l g(|T|) T / |T| dsigma,   g(t) = e(t) - t / EA,

where ``delta r_linear`` is the closed form of :func:`.pieces.piece_integrals` for the
reference stiffness EA (exact for any EA: the second term takes the rest). The second
term is integrated by composite Gauss-Legendre quadrature on sub-intervals graded
towards the point of least tension (:func:`_graded_nodes`); the integrand is analytic
between the law's kinks (which are made boundaries), so the error falls geometrically
with the number of nodes per sub-interval (tests/validation/test_axial_laws.py). A
linear law (g = 0) adds exactly nothing, so ``{law: polynomial, coefficients: [EA]}``
reproduces ``axial_stiffness: EA`` bit for bit.

The flexibility (Jacobian in T0) and the complementary energy (whose gradient is delta r)
gain the matching terms

    int [g'(t) n n^T + g(t) / t (I - n n^T)] dsigma,   n = T / t,  g'(t) = de/dT - 1/EA,
    int [Phi(t) - t^2 / (2 EA)] dsigma,                Phi(t) = int_0^t e,

so the Newton iteration on the end forces keeps its convex energy and exact derivatives.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ..physics.axial import AxialLaw, gauss_legendre
from .pieces import piece_integrals

#: Gauss-Legendre nodes per sub-interval
QUADRATURE_POINTS = 8
#: graded sub-intervals on each side of the point of least tension
QUADRATURE_GRADES = 6


def _graded_nodes(
    T0: np.ndarray,
    q: np.ndarray,
    ell: np.ndarray,
    points: int,
    grades: int,
    breaks: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    """Quadrature nodes sigma [m] (P, K) and weights [m] (P, K) on each piece.

    |T(sigma)| = sqrt(H^2 + V(sigma)^2) with V linear in sigma: the integrand's
    singularities lie at V = +-i H, i.e. at sigma* = sigma_0 +- i r with sigma_0 = -V0/w
    (the point of least tension) and r = H / w. Sub-intervals are graded geometrically
    away from sigma_0 (boundaries sigma_0 +- r_g (2^k - 1), r_g = max(r, l 2^-grades)),
    so that each is at most about a third as long as its distance from sigma*: the
    Gauss-Legendre error then falls like 5.8^(-2 points) per sub-interval, whatever the
    sag. The law's own kinks (``breaks``: tensions of a table's knots) are made
    boundaries too, where |T(sigma)| crosses them. Degenerate sub-intervals get zero
    weight.
    """
    x, w = gauss_legendre(points)
    P = len(ell)
    wq = np.sqrt(np.einsum("pk,pk->p", q, q))
    curved = wq > 0.0
    inv_w = np.where(curved, 1.0 / np.where(curved, wq, 1.0), 0.0)
    u = -q * inv_w[:, None]
    V0 = np.einsum("pk,pk->p", T0, u)
    H = np.sqrt(np.maximum(np.einsum("pk,pk->p", T0, T0) - V0 * V0, 0.0))
    sig0 = np.where(curved, -V0 * inv_w, -1.0)
    r = np.maximum(np.where(curved, H * inv_w, ell), ell * 2.0 ** (-grades))
    c = 2.0 ** np.arange(grades + 1) - 1.0  # 0, 1, 3, 7, ...
    bounds = [np.zeros((P, 1)), ell[:, None]]
    bounds.append(sig0[:, None] - r[:, None] * c[None, :])
    bounds.append(sig0[:, None] + r[:, None] * c[None, 1:])
    if breaks.size:
        # |T| = Tk  <=>  V = +-sqrt(Tk^2 - H^2)
        rad = np.sqrt(np.maximum(breaks[None, :] ** 2 - H[:, None] ** 2, 0.0))
        for sign in (1.0, -1.0):
            sk = (sign * rad - V0[:, None]) * inv_w[:, None]
            bounds.append(np.where(curved[:, None], sk, -1.0))
    B = np.sort(np.clip(np.concatenate(bounds, axis=1), 0.0, ell[:, None]), axis=1)
    a, b = B[:, :-1], B[:, 1:]
    sig = (a[..., None] + (b - a)[..., None] * x[None, None, :]).reshape(P, -1)
    wt = ((b - a)[..., None] * w[None, None, :]).reshape(P, -1)
    return sig, wt


def piece_increments(
    T0: np.ndarray,
    q: np.ndarray,
    ell: np.ndarray,
    EA: np.ndarray,
    laws: Sequence[AxialLaw | None] | None = None,
    *,
    jacobian: bool = True,
    points: int | None = None,
    grades: int | None = None,
    compiled: bool = True,
) -> tuple[np.ndarray, np.ndarray | None, np.ndarray]:
    """:func:`.pieces.piece_integrals` with each piece's own axial law.

    Parameters
    ----------
    T0, q, ell, EA : as :func:`.pieces.piece_integrals`, with one leading axis (P,)
        [N], [N/m], [m], [N]; EA is the reference stiffness of each piece.
    laws : sequence of AxialLaw or None, length P, or None
        The law of each piece; None (or a linear law) for T = EA e.
    jacobian : bool
    points, grades : int
        Gauss-Legendre nodes per sub-interval, and graded sub-intervals on each side of
        the point of least tension (:func:`_graded_nodes`); default the module's
        QUADRATURE_POINTS and QUADRATURE_GRADES.
    compiled : bool
        Use the numba kernel (:mod:`._law_fast`, same quadrature) where available.

    Returns
    -------
    dr [m] (P, 3), jac [m/N] (P, 3, 3) or None, energy [N m] (P,)
    """
    groups: dict[int, tuple[AxialLaw, list[int]]] = {}
    for p, law in enumerate(laws or ()):
        if law is None or law.is_linear:
            continue
        groups.setdefault(id(law), (law, []))[1].append(p)
    if not groups:
        return piece_integrals(T0, q, ell, EA, jacobian=jacobian)
    if compiled:
        from . import _law_fast  # numba is imported on first use, not with the package

        compiled = _law_fast.AVAILABLE
    if compiled:
        T0 = np.ascontiguousarray(T0, dtype=float)
        q = np.ascontiguousarray(q, dtype=float)
        ell = np.ascontiguousarray(ell, dtype=float)
        EA = np.ascontiguousarray(EA, dtype=float)
        P = len(ell)
        dr, energy = np.empty((P, 3)), np.empty(P)
        jac = np.empty((P, 3, 3)) if jacobian else None
        _law_fast.linear_pieces(
            T0, q, ell, EA, dr, jac if jac is not None else np.zeros((1, 3, 3)), energy, jacobian
        )
    else:
        dr, jac, energy = piece_integrals(T0, q, ell, EA, jacobian=jacobian)
        dr = dr.copy()
        energy = energy.copy()
        if jac is not None:
            jac = jac.copy()
    points = QUADRATURE_POINTS if points is None else points
    grades = QUADRATURE_GRADES if grades is None else grades
    for law, idx_list in groups.values():
        idx = np.asarray(idx_list)
        code = _law_fast.encode(law) if compiled else None
        if code is not None:
            xg, wg = gauss_legendre(points)
            _law_fast.law_corrections(
                T0,
                q,
                ell,
                EA,
                idx,
                code[0],
                code[1],
                code[2],
                code[3],
                np.asarray(law.breakpoints(), dtype=float),
                np.ascontiguousarray(xg),
                np.ascontiguousarray(wg),
                grades,
                dr,
                jac if jac is not None else np.zeros((1, 3, 3)),
                energy,
                jac is not None,
            )
            continue
        sig, wl = _graded_nodes(T0[idx], q[idx], ell[idx], points, grades, law.breakpoints())
        # tension vectors at the nodes: (p, j, 3)
        T = T0[idx][:, None, :] - q[idx][:, None, :] * sig[..., None]
        t = np.sqrt(np.einsum("pjk,pjk->pj", T, T))
        ea = EA[idx][:, None]
        # nodes of degenerate sub-intervals weigh nothing: the law is not evaluated there
        live = (wl > 0.0) & (t > 0.0)
        tl = t[live]
        el = law.strain(tl)
        e = np.zeros_like(t)
        e[live] = el
        g = np.where(live, e - t / ea, 0.0)
        n = T / np.where(t > 0.0, t, 1.0)[..., None]
        dr[idx] += np.einsum("pj,pjk->pk", wl * g, n)
        phi = np.zeros_like(t)
        phi[live] = (
            tl * el - law.strain_energy(el) - tl * tl / (2.0 * ea.repeat(t.shape[1], axis=1)[live])
        )
        energy[idx] += np.sum(wl * phi, axis=1)
        if jac is not None:
            # g'(t) n n^T + g / t (I - n n^T), summed with the weights
            g_over_t = np.zeros_like(t)
            g_over_t[live] = g[live] / tl
            dg = np.zeros_like(t)
            dg[live] = 1.0 / law.tangent_stiffness(el) - 1.0 / ea.repeat(t.shape[1], axis=1)[live]
            a = wl * (dg - g_over_t)
            jac[idx] += np.einsum("pj,pjk,pjl->pkl", a, n, n)
            jac[idx] += np.sum(wl * g_over_t, axis=1)[:, None, None] * np.eye(3)
    return dr, jac, energy
