"""Line pieces under a non-linear axial law: the closed-form linear piece plus the
exact integral of the law's departure from it.

A piece of unstretched length ``l`` under the constant load ``q`` carries the tension
vector T(sigma) = T0 - q sigma (:mod:`.pieces`). With any axial law e(|T|) (strain of
tension, :mod:`cablestudy.physics.axial`) its end lies at

    delta r = int_0^l (1 + e(|T|)) T / |T| dsigma
            = delta r_linear(EA) + int_0^l g(|T|) T / |T| dsigma,   g(t) = e(t) - t / EA,

where ``delta r_linear`` is the closed form of :func:`.pieces.piece_integrals` for the
reference stiffness EA (exact for any EA: the second term takes the rest). The second
term is integrated by composite Gauss-Legendre quadrature (``sub`` equal sub-intervals
of ``points`` nodes); its integrand is analytic wherever the law is, so the error falls
geometrically with the number of nodes (for T = 4e6 e + 2e7 e^2 + 5e7 e^3 and tensions
of 1e4..1e5 N, 2 x 8 nodes are at round-off: tests/validation/test_axial_laws.py). A
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

#: Gauss-Legendre nodes per sub-interval and sub-intervals per piece
QUADRATURE_POINTS = 8
QUADRATURE_SUB = 2


def _rule(points: int, sub: int) -> tuple[np.ndarray, np.ndarray]:
    x, w = gauss_legendre(points)
    xs = ((np.arange(sub)[:, None] + x[None, :]) / sub).ravel()
    ws = np.tile(w / sub, sub)
    return xs, ws


def piece_increments(
    T0: np.ndarray,
    q: np.ndarray,
    ell: np.ndarray,
    EA: np.ndarray,
    laws: Sequence[AxialLaw | None] | None = None,
    *,
    jacobian: bool = True,
    points: int = QUADRATURE_POINTS,
    sub: int = QUADRATURE_SUB,
) -> tuple[np.ndarray, np.ndarray | None, np.ndarray]:
    """:func:`.pieces.piece_integrals` with each piece's own axial law.

    Parameters
    ----------
    T0, q, ell, EA : as :func:`.pieces.piece_integrals`, with one leading axis (P,)
        [N], [N/m], [m], [N]; EA is the reference stiffness of each piece.
    laws : sequence of AxialLaw or None, length P, or None
        The law of each piece; None (or a linear law) for T = EA e.
    jacobian : bool
    points, sub : int
        Gauss-Legendre nodes per sub-interval and sub-intervals per piece.

    Returns
    -------
    dr [m] (P, 3), jac [m/N] (P, 3, 3) or None, energy [N m] (P,)
    """
    dr, jac, energy = piece_integrals(T0, q, ell, EA, jacobian=jacobian)
    if laws is None:
        return dr, jac, energy
    groups: dict[int, tuple[AxialLaw, list[int]]] = {}
    for p, law in enumerate(laws):
        if law is None or law.is_linear:
            continue
        groups.setdefault(id(law), (law, []))[1].append(p)
    if not groups:
        return dr, jac, energy
    x, w = _rule(points, sub)
    dr = dr.copy()
    energy = energy.copy()
    if jac is not None:
        jac = jac.copy()
    for law, idx_list in groups.values():
        idx = np.asarray(idx_list)
        ell_p = ell[idx]
        # tension vectors at the nodes: (p, j, 3)
        sig = ell_p[:, None] * x[None, :]
        T = T0[idx][:, None, :] - q[idx][:, None, :] * sig[..., None]
        t = np.sqrt(np.einsum("pjk,pjk->pj", T, T))
        ea = EA[idx][:, None]
        e = law.strain(t)
        g = e - t / ea
        pos = t > 0.0
        n = T / np.where(pos, t, 1.0)[..., None]
        wl = ell_p[:, None] * w[None, :]
        dr[idx] += np.einsum("pj,pjk->pk", wl * g, n)
        phi = np.where(pos, t * e - law.strain_energy(e), 0.0)
        energy[idx] += np.sum(wl * (phi - t * t / (2.0 * ea)), axis=1)
        if jac is not None:
            with np.errstate(divide="ignore", invalid="ignore"):
                dg = 1.0 / law.tangent_stiffness(e) - 1.0 / ea
                g_over_t = np.where(pos, g / np.where(pos, t, 1.0), 0.0)
            nn = n[..., :, None] * n[..., None, :]
            eye = np.eye(3)
            term = (wl * dg)[..., None, None] * nn + (wl * g_over_t)[..., None, None] * (eye - nn)
            jac[idx] += term.sum(axis=1)
    return dr, jac, energy
