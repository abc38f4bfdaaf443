"""The numpy form of the graded Gauss-Legendre quadrature of a non-linear axial law's
departure from the linear piece: the tests' reference for the compiled kernel
(:func:`cablestudy.statics._law_fast.law_corrections`, which
:func:`cablestudy.statics.law_pieces.piece_increments` runs). The same boundaries and
nodes, evaluated with whole-array numpy and the law's own methods
(:mod:`cablestudy.physics.axial`), so the two agree to round-off (sums in another order).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from cablestudy.physics.axial import AxialLaw, gauss_legendre
from cablestudy.statics.law_pieces import QUADRATURE_GRADES, QUADRATURE_POINTS
from cablestudy.statics.pieces import piece_integrals


def graded_nodes(
    T0: np.ndarray,
    q: np.ndarray,
    ell: np.ndarray,
    points: int,
    grades: int,
    breaks: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    """Quadrature nodes sigma [m] (P, K) and weights [m] (P, K) on each piece, on the
    sub-intervals graded away from the point of least tension and split at the law's
    kinks as the compiled kernel's (its docstring:
    :func:`cablestudy.statics._law_fast.law_corrections` says why they converge
    whatever the sag). Degenerate sub-intervals get zero weight.
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


def piece_increments_numpy(
    T0: np.ndarray,
    q: np.ndarray,
    ell: np.ndarray,
    EA: np.ndarray,
    laws: Sequence[AxialLaw | None],
    *,
    jacobian: bool = True,
    points: int = QUADRATURE_POINTS,
    grades: int = QUADRATURE_GRADES,
) -> tuple[np.ndarray, np.ndarray | None, np.ndarray]:
    """:func:`cablestudy.statics.law_pieces.piece_increments` in numpy: the closed-form
    linear piece plus the quadrature of each law's departure from it."""
    dr, jac, energy = piece_integrals(T0, q, ell, EA, jacobian=jacobian)
    dr, energy = dr.copy(), energy.copy()
    jac = None if jac is None else jac.copy()
    groups: dict[int, tuple[AxialLaw, list[int]]] = {}
    for p, law in enumerate(laws):
        if law is not None and not law.is_linear:
            groups.setdefault(id(law), (law, []))[1].append(p)
    for law, idx_list in groups.values():
        idx = np.asarray(idx_list)
        sig, wl = graded_nodes(T0[idx], q[idx], ell[idx], points, grades, law.breakpoints())
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
