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
towards the point of least tension (compiled, :func:`._law_fast.law_corrections`; its
numpy form is the tests' reference, ``tests/law_quadrature.py``): the integrand is
analytic between the law's kinks (which are made boundaries), so the error falls
geometrically with the number of nodes per sub-interval
(tests/validation/test_axial_laws.py). A
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


def piece_increments(
    T0: np.ndarray,
    q: np.ndarray,
    ell: np.ndarray,
    EA: np.ndarray,
    laws: Sequence[AxialLaw | None] | None = None,
    *,
    jacobian: bool = True,
) -> tuple[np.ndarray, np.ndarray | None, np.ndarray]:
    """:func:`.pieces.piece_integrals` with each piece's own axial law.

    Parameters
    ----------
    T0, q, ell, EA : as :func:`.pieces.piece_integrals`, with one leading axis (P,)
        [N], [N/m], [m], [N]; EA is the reference stiffness of each piece.
    laws : sequence of AxialLaw or None, length P, or None
        The law of each piece; None (or a linear law) for T = EA e.
    jacobian : bool

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
    from . import _law_fast  # numba is imported on first use, not with the package

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
    # the quadrature of :func:`._law_fast.law_corrections`: QUADRATURE_POINTS nodes per
    # sub-interval, QUADRATURE_GRADES graded sub-intervals each side of the least tension
    xg, wg = gauss_legendre(QUADRATURE_POINTS)
    for law, idx_list in groups.values():
        code, a, b, c = _law_fast.encode(law)
        _law_fast.law_corrections(
            T0,
            q,
            ell,
            EA,
            np.asarray(idx_list),
            code,
            a,
            b,
            c,
            np.asarray(law.breakpoints(), dtype=float),
            np.ascontiguousarray(xg),
            np.ascontiguousarray(wg),
            QUADRATURE_GRADES,
            dr,
            jac if jac is not None else np.zeros((1, 3, 3)),
            energy,
            jac is not None,
        )
    return dr, jac, energy
