"""A solved line's end-force stiffness from its solver's converged state.

Pure: arrays in, arrays out (SI units, no I/O).

A system of lines (:mod:`.system`) moves each line's ends and needs, for each line,
``K[i, j] = -d f_i / d r_j`` (2, 2, 3, 3): f_i the force of the line on the attachment
at end i (A, B), r_j the position of end j, everything inside the line re-equilibrated.
Two solvers leave a state from which K follows exactly, without finite differences:

* :class:`DiscreteState` (method ``discrete``): the lumped-mass model's tangent at its
  converged equilibrium, condensed onto the two held end nodes,
  ``K = J_ee - J_ei J_ii^-1 J_ie``. For T = EA strain the unknowns are the free nodes'
  positions and the element tensions (the mixed form of :mod:`cablestudy.dynamics.mixed`,
  whose equations hold for any EA); for a nonlinear axial law, the free nodes'
  positions. ``J`` is the Jacobian of the nodal out-of-balance forces (the model's sign:
  minus the sum of the forces on a node, so its derivative is a stiffness) and of the
  element laws. Bending (EI), seabed contact and friction enter through the model's own
  tangent (:func:`cablestudy.dynamics.model.evaluate`); the condensation is exact for
  that tangent.
* :class:`CatenaryState` (method ``catenary`` with a current): the drag loads per piece
  the drag iteration converged to. The end stiffness is that of the catenary carrying
  those loads as constant loads (*drag frozen*): the change of the drag as the line
  turns in the current is left out, so K is the stiffness at constant drag, not the
  exact derivative (exact in still water, where the loads are the weight alone).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np


@dataclass(frozen=True, kw_only=True)
class CatenaryState:
    """The semi-analytic solution's pieces and loads: ``layout`` (the pieces, in the
    solver's order: from B to A when ``reversed``), ``q`` [N/m] (P, 3) the load per
    length of each piece (weight and the converged drag)."""

    layout: Any
    q: np.ndarray
    reversed: bool


@dataclass(frozen=True, kw_only=True)
class DiscreteState:
    """The discrete equilibrium: ``line`` (:class:`~cablestudy.dynamics.model.DiscreteLine`),
    node ``position`` [m] (n + 1, 3), element ``tension`` [N] (n,), seabed friction
    ``anchor`` [m] (n + 1, 3), and whether the tensions are unknowns of their own
    (``mixed``: T = EA strain) or follow from the positions (a nonlinear law)."""

    line: Any
    position: np.ndarray
    tension: np.ndarray
    anchor: np.ndarray
    mixed: bool


def _turning(r: np.ndarray, u: np.ndarray, length: np.ndarray) -> np.ndarray:
    """sum_a r_a d^2 u_a / d d^2 (k, 3, 3) of unit vectors u = d / |d| (k, 3) of lengths
    (k,): -(r u^T + u r^T + (r . u) I - 3 (r . u) u u^T) / |d|^2."""
    ru = np.einsum("ka,ka->k", r, u)
    eye = np.eye(3)[None]
    uu = u[:, :, None] * u[:, None, :]
    out = r[:, :, None] * u[:, None, :] + u[:, :, None] * r[:, None, :]
    out += ru[:, None, None] * (eye - 3.0 * uu)
    return -out / (length**2)[:, None, None]


def _bending_curvature_triplets(line: Any, x: np.ndarray) -> list[tuple]:
    """The part of the bending energy's Hessian the model's Gauss-Newton tangent leaves
    out (:mod:`cablestudy.dynamics.model`: the energy kb/2 |r|^2 at a node, r = u_b - u_a
    between its elements' directions, or u_e - d at a clamped end): kb sum_a r_a
    d^2 r_a, on the two nodes of each element whose direction r holds, with the
    element's pattern [[H, -H], [-H, H]] in its chord."""
    from ..dynamics.mixed import block_triplets

    d = np.diff(x, axis=0)
    length = np.linalg.norm(d, axis=1)
    u = d / length[:, None]
    n, m = line.n_nodes, line.n_elements
    broken = np.asarray(line.broken, dtype=bool)
    kb = np.asarray(line.bending, dtype=float)
    elem, weight, r = [], [], []
    inner = np.arange(1, n - 1)
    inner = inner[(kb[inner] > 0.0) & ~broken[inner - 1] & ~broken[inner]]
    rr = u[inner] - u[inner - 1]
    elem += [inner, inner - 1]  # element b (sign +r), element a (sign -r)
    weight += [kb[inner], -kb[inner]]
    r += [rr, rr]
    for node, e, end in ((0, 0, 0), (n - 1, m - 1, 1)):
        if kb[node] > 0.0 and not broken[e]:
            elem.append(np.array([e]))
            weight.append(np.array([kb[node]]))
            r.append((u[e] - line.clamp_direction[end])[None])
    e = np.concatenate(elem)
    H = np.concatenate(weight)[:, None, None] * _turning(np.concatenate(r), u[e], length[e])
    return [
        block_triplets(e, e, H),
        block_triplets(e + 1, e + 1, H),
        block_triplets(e, e + 1, -H),
        block_triplets(e + 1, e, -H),
    ]


def discrete_jacobian(state: DiscreteState) -> Any:
    """The Jacobian of the discrete equilibrium at ``state``: rows the nodal
    out-of-balance forces (3 (n + 1)) and, in the mixed form, the element laws (n);
    columns the node positions and, in the mixed form, the element tensions (a scipy
    sparse matrix; scipy is imported here, not with the solvers)."""
    import scipy.sparse as sp

    from ..dynamics.mixed import (
        SLACK_WEIGHT,
        axial_forces,
        band_triplets,
        mixed_triplets,
        other_forces_line,
    )
    from ..dynamics.model import Workspace, _trial_states, evaluate

    line, x = state.line, np.asarray(state.position, dtype=float)
    n, m = line.n_nodes, line.n_elements
    model = other_forces_line(line) if state.mixed else line
    work = Workspace(m)
    evaluate(model, x, np.zeros_like(x), work, anchor=state.anchor)
    if line.has_seabed and np.any(line.friction > 0.0):
        # the stick/slip states of the converged state (as its Newton last set them)
        _trial_states(work.slip_state, work.trial, work.contact, line.friction)
        evaluate(model, x, np.zeros_like(x), work, anchor=state.anchor)
    parts = band_triplets(work, n, line.has_bending)
    if line.has_bending:
        parts.extend(_bending_curvature_triplets(line, x))
    if state.mixed:
        t = np.asarray(state.tension, dtype=float)
        _, u, length = axial_forces(x, t)
        # element law c T = max(g, 0), g = l / l0 - 1: taut rows c T - g, slack rows T
        l0 = line.rest_length
        c = 1.0 / np.asarray(line.axial_stiffness, dtype=float)
        # the branch the mixed Newton takes (taut where c T - g <= K c T, K its slack
        # weight): a slack element's row is T = 0
        g = length / l0 - 1.0
        taut = (c * t - g <= SLACK_WEIGHT * c * t) & ~np.asarray(line.broken, dtype=bool)
        parts += mixed_triplets(t, u, length, l0, taut, n)
        col_t = 3 * n + np.arange(m)
        parts.append((col_t, col_t, np.where(taut, c, 1.0)))
    size = 3 * n + (m if state.mixed else 0)
    R = np.concatenate([p[0] for p in parts])
    C = np.concatenate([p[1] for p in parts])
    V = np.concatenate([p[2] for p in parts])
    return sp.csc_matrix((V, (R, C)), shape=(size, size))


def discrete_end_stiffness(state: DiscreteState) -> np.ndarray:
    """``K[i, j] = -d f_i / d r_j`` (2, 2, 3, 3) of a discrete line held at its two end
    nodes: the Schur complement of the Jacobian onto the end nodes' coordinates (every
    free node and element tension re-equilibrated). f is the force of the line on the
    attachment, minus the end node's out-of-balance force, so K is the condensed
    Jacobian itself."""
    import scipy.sparse as sp
    from scipy.sparse.linalg import splu

    line = state.line
    held = np.flatnonzero(np.asarray(line.held, dtype=bool))
    last = line.n_nodes - 1
    if held.tolist() != [0, last]:
        raise ValueError(f"end stiffness: the line must be held at its two ends only (held {held})")
    J = discrete_jacobian(state)
    size = J.shape[0]
    ends = np.concatenate([np.arange(3), 3 * last + np.arange(3)])
    inner = np.setdiff1d(np.arange(size), ends)
    J_ee = J[ends][:, ends].toarray()
    J_ei = J[ends][:, inner]
    J_ie = J[inner][:, ends].toarray()
    J_ii = J[inner][:, inner].tocsc()
    # the mixed Newton's regularisation of the free nodes (1e-10 of the largest tension
    # over the shortest element): a slack stretch on a frictionless seabed leaves its
    # nodes free to slide, a neutral mode the ends do not feel (K changes by ~1e-10)
    n_free = 3 * (line.n_nodes - 2)
    t_max = max(float(np.max(state.tension)), 1e-300)
    reg = 1e-10 * t_max / float(np.min(line.rest_length))
    J_ii = (J_ii + sp.diags(np.r_[np.full(n_free, reg), np.zeros(size - 6 - n_free)])).tocsc()
    K = J_ee - J_ei @ splu(J_ii).solve(J_ie)
    out = np.empty((2, 2, 3, 3))
    for i in range(2):
        for j in range(2):
            out[i, j] = K[3 * i : 3 * i + 3, 3 * j : 3 * j + 3]
    return out
