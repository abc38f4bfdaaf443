"""The end stiffness of a system line whose touchdown point rests at a clump weight.

A line on the seabed from its anchor may leave the seabed at a downward point load (a
clump), the seabed carrying part R of the load's weight (the pinned contact state of
:mod:`.contact_pin`). There the touchdown point does not move with the fairlead: the
fairlead moves R and the in-plane touchdown tension T_hat instead. The free-TDP
stiffness of :func:`.line_stiffness.line_end_stiffness` (unknowns alpha, beta, s_td) is then
the wrong derivative, and a system's Newton with it converges slowly or not at all (a
clump near a leg's touchdown: "free-point equilibrium did not converge").

With y = (alpha, beta, R), T_hat = alpha e1 + beta e2, the tension past the load
T_hat - j(R) (j of :func:`.contact_pin.pin_jump`) and the laid part's tension t_lo(T_hat,
R) at the load:

    r_B = r_A + e stretched(t_lo) + sum of the suspended pieces' increments,
    T(L) = T_hat - j(R) - C_end,

so M = d r_B / dy = [(J_s + d laid / d T_hat) E, -J_s dj/dR + e flex dt_lo/dR],
N = d T(L) / dy = [E, -dj/dR] (E = [e1, e2]) and K_BB = -d f_B / d r_B = N M^-1, as for
the free TDP with its third column replaced. Pure: arrays in, arrays out (SI units).
"""

from __future__ import annotations

import numpy as np

from .contact_pin import pin_jump, pin_map
from .law_pieces import piece_increments
from .seabed import Plane
from .semi_analytic_shape import Layout, _laid, _suspended


def pinned_stiffness(
    lay: Layout, q: np.ndarray, plane: Plane, s_td: float, fb: np.ndarray
) -> np.ndarray | None:
    """K_BB (3, 3) [N/m] of a line anchored at A whose TDP ``s_td`` [m] rests at a
    downward point load (pinned), from the force ``fb`` [N] on end B; None where s_td is
    not at such a load or the reaction it implies lies outside [0, R_max]."""
    pins = pin_map(lay.bounds, lay.point, lay.weight, plane.normal)
    L = lay.total
    hit = np.flatnonzero(np.abs(pins.s - s_td) <= 1e-12 * L)
    if not hit.size:
        return None
    i = int(hit[0])
    k = int(pins.index[i])
    r_max = float(pins.r_max[i])
    n = plane.normal
    _, ell, EA, qs, C, k_td, Cend = _suspended(lay, q, s_td)
    f = lay.point[k]
    U = -np.asarray(fb, dtype=float) + Cend  # T_hat - j(R)
    R = -float((U + f) @ n)
    if not -1e-9 * r_max <= R <= r_max * (1.0 + 1e-9):
        return None
    R = min(max(R, 0.0), r_max)
    # T_hat: U + j(R), j independent of T_hat (pin_jump's j depends on R only)
    j0, _, _, _, _ = pin_jump(f, R, r_max, np.array([1.0, 0.0, 0.0]), n, plane.friction)
    T_hat = U + j0
    j, dj_dR, t_lo, dt_dT, dt_dR = pin_jump(f, R, r_max, T_hat, n, plane.friction)
    tn = float(np.linalg.norm(T_hat))
    e = T_hat / tn
    laid = _laid(lay, s_td, T_hat, plane, t_lo)
    laws = None if lay.law is None else lay.law[k_td:]
    _, jac, _ = piece_increments(T_hat - j - C, qs, ell, EA, laws)
    assert jac is not None
    Js = jac.sum(axis=0)
    e1, e2 = plane.basis
    basis = np.stack((e1, e2), axis=1)
    dlaid = (
        laid.stretched * (np.eye(3) - np.outer(e, e)) / tn + np.outer(e, dt_dT) * laid.positive_flex
    )
    M = np.column_stack(((Js + dlaid) @ basis, -Js @ dj_dR + e * laid.positive_flex * dt_dR))
    N = np.column_stack((basis, -dj_dR))
    return np.linalg.solve(M.T, N.T).T
