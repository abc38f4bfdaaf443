"""A catenary line sliding over fixed pulleys in the time domain (issue 12 item 4).

The lumped-mass line (:mod:`.model`) is cut at each pulley into sub-lines, each with its
own nodes (a fixed number, uniform in the sub-line's arc length); the node at a pulley
is held at the pulley's position. The split S_k [m] (arc length from A at pulley k) is
a variable: when it changes, the nodes of the sub-lines on either side move along the
material (their arc lengths scale with the sub-line lengths), so element rest lengths
and everything lumped per unstretched length (mass, added mass, weight, drag, damping,
seabed contact) follow with the mass per unstretched length constant; a segment
boundary or an attachment of the line passes over the pulley with the material.

Friction (aqwa seed 5.8.1.1): the line sticks on pulley k while
T_large / T_small <= f_k^(wrap / 180 deg), the tensions T_in, T_out of the elements
arriving at and leaving the pulley node and the wrap the angle between them; when the
ratio would exceed that bound, the line slides towards the larger tension until the
ratio equals the bound. Each implicit step is therefore solved for the split too
(:func:`solve_split`): first with the split of the start of the step (stick); for the
pulleys where the ratio then exceeds the bound (and every frictionless pulley,
f = 1), the split is the root of

    g_k(S) = T_out - r_k T_in,  r_k = bound^(+1) if T_out is the larger, bound^(-1) if not,

each evaluation a full implicit step (its Newton solve) with the line cut at S. A
pulley that slid in the last step starts from the split extrapolated at its last rate
and keeps its direction (a solution that would move the line against the larger tension
sticks instead). T_in, T_out are the adjacent elements' tensions carried to the pulley
through the half-elements' lumped weight (:func:`pulley_tensions`, second order in the
element length). The outer iteration is Broyden's method (the secant method for one
pulley) from the last known Jacobian (first the statics', by forward differences),
stopped when |g_k| is within the step's Newton tolerance [N]: the tension ratio at each
sliding pulley then holds the bound to the accuracy the step itself has (an element
tension is known to about the residual force Newton leaves on its nodes). A split that
does not converge rejects the step, which is halved as for a failed Newton solve.

Approximation, stated: the sliding is quasi-static along the line. The nodes are mesh
points, not material points, when the split moves; the material's axial velocity
relative to them (the sliding speed dS/dt) is not added to their velocities, so the
axial inertia and drag of the sliding itself are neglected (the line's motion normal to
itself, and all of it while the line sticks, is modelled as elsewhere). This is exact
in the stick limit (the pulley is then a fixed node) and a good approximation when the
sliding speed is small against the line's transverse speeds.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np

from ..statics.base import LineModel, Medium
from .discrete_line import DiscreteLine, DynamicExtras, discretise_nodes


@dataclass(frozen=True, kw_only=True)
class SlidingPulleys:
    """Pulleys the line slides over.

    node : (m,) indices of the pulley nodes (held at the pulleys)
    factor : (m,) the seed's friction factor f for a 180-degree wrap (1: frictionless)
    split : (m,) [m] arc length from A at each pulley at the start
    length : [m] the line's unstretched length
    rebuild : the discretised line for a split (m,) [m]
    jacobian : [N/m] (m, m) the last known dg/dS (see :func:`solve_split`), updated in
        place as the run goes (zeros: unknown, taken by forward differences)
    """

    node: np.ndarray
    factor: np.ndarray
    split: np.ndarray
    length: float
    rebuild: Callable[[np.ndarray], DiscreteLine]
    jacobian: np.ndarray


def sub_line_elements(split: np.ndarray, length: float, elements: int) -> np.ndarray:
    """Elements of each sub-line [-] (m + 1,): ``elements`` shared in proportion to the
    sub-lines' lengths, at least 2 each."""
    S = np.concatenate(([0.0], split, [length]))
    return np.maximum(np.round(elements * np.diff(S) / length).astype(int), 2)


def pulley_node_s(split: np.ndarray, length: float, counts: np.ndarray) -> np.ndarray:
    """Arc lengths [m] of the nodes: ``counts`` equal elements on each sub-line."""
    S = np.concatenate(([0.0], split, [length]))
    parts = [np.linspace(S[k], S[k + 1], counts[k] + 1)[:-1] for k in range(len(counts))]
    return np.concatenate([*parts, [length]])


def sliding_pulleys(
    line: LineModel,
    medium: Medium,
    extras: DynamicExtras,
    *,
    split: np.ndarray,
    factor: np.ndarray,
    elements: int,
) -> SlidingPulleys:
    """The line's :class:`SlidingPulleys` with about ``elements`` elements, cut at the
    static ``split`` [m]."""
    L = line.total_length
    counts = sub_line_elements(split, L, elements)
    node = np.cumsum(counts)[:-1]

    def rebuild(S: np.ndarray) -> DiscreteLine:
        disc = discretise_nodes(line, medium, pulley_node_s(S, L, counts), extras)
        held = disc.held.copy()
        held[node] = True
        return replace(disc, held=held)

    return SlidingPulleys(
        node=node,
        factor=np.asarray(factor, dtype=float),
        split=np.asarray(split, dtype=float).copy(),
        length=L,
        rebuild=rebuild,
        jacobian=np.zeros((len(node), len(node))),
    )


def wrap_angle(x: np.ndarray, node: np.ndarray) -> np.ndarray:
    """Angle [rad] the line turns through at each pulley node (0: straight on)."""
    u_in = x[node] - x[node - 1]
    u_out = x[node + 1] - x[node]
    c = np.einsum("ik,ik->i", u_in, u_out) / (
        np.linalg.norm(u_in, axis=1) * np.linalg.norm(u_out, axis=1)
    )
    return np.arccos(np.clip(c, -1.0, 1.0))


def pulley_tensions(
    line: DiscreteLine, x: np.ndarray, tension: np.ndarray, node: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Tensions [N] of the line arriving at and leaving each pulley node, (T_in, T_out):
    the adjacent elements' tensions (taken at their midpoints) carried to the pulley
    through the weight lumped at the node from the half-elements between, in the
    continuum's dT/ds = -f . t (f the load per length): T_in - f_in . u_in and
    T_out + f_out . u_out, f_in and f_out the node's constant load shared in proportion
    to the two rest lengths. The element tensions alone differ from the tension at the
    pulley by O(h) (measured: a first-order error of the split and the end tension);
    carried this way the error is O(h^2)."""
    u_in = x[node] - x[node - 1]
    u_in /= np.linalg.norm(u_in, axis=1)[:, None]
    u_out = x[node + 1] - x[node]
    u_out /= np.linalg.norm(u_out, axis=1)[:, None]
    l_in, l_out = line.rest_length[node - 1], line.rest_length[node]
    share = l_in / (l_in + l_out)
    f = line.force[node]
    T_in = tension[node - 1] - share * np.einsum("ik,ik->i", f, u_in)
    T_out = tension[node] + (1.0 - share) * np.einsum("ik,ik->i", f, u_out)
    return T_in, T_out


def slide_bound(factor: np.ndarray, wrap: np.ndarray) -> np.ndarray:
    """Largest tension ratio [-] before the line slides: factor^(wrap / 180 deg)."""
    return np.asarray(factor, dtype=float) ** (np.asarray(wrap) / math.pi)


def solve_split(
    evaluate: Callable[[np.ndarray], tuple | None],
    pulleys: SlidingPulleys,
    split: np.ndarray,
    tolerance: float,
    *,
    predicted: np.ndarray | None = None,
    direction: np.ndarray | None = None,
    max_iterations: int = 25,
) -> tuple[np.ndarray | None, np.ndarray]:
    """The split [m] at the end of a step (see the module docstring).

    ``evaluate(S)`` solves the step with the line cut at S and returns the tensions
    (T_in, T_out) [N] at the pulleys and the wrap angles [rad], or None when the step
    fails. ``direction`` (m,) says how each pulley's line moved in the last step (+1:
    towards the side leaving the pulley, -1: towards the side arriving, 0: stuck) and
    ``predicted`` (m,) [m] the split change that motion extrapolates to over this step:
    a pulley that slid starts from it, a stuck one from ``split`` (the stick trial).
    Returns (the new split, the directions of this step), the split None when the outer
    iteration fails; the last ``evaluate`` call is at the returned split."""
    m_all = len(split)
    direction = np.zeros(m_all) if direction is None else np.asarray(direction, dtype=float)
    last: list[bytes] = [b""]
    user_evaluate = evaluate

    def evaluate(S: np.ndarray) -> tuple | None:  # remembers where it was called last
        last[0] = S.tobytes()
        return user_evaluate(S)

    frictionless = pulleys.factor <= 1.0
    was = frictionless | (direction != 0.0)
    start = split.copy()
    if predicted is not None:
        start[was] += np.asarray(predicted, dtype=float)[was]
    if not np.all(np.diff(_bounds(start, pulleys)) > 0.0):
        start = split.copy()
    got = evaluate(start)
    if got is None and np.any(start != split):
        start = split.copy()
        got = evaluate(start)
    if got is None:
        return None, direction
    (T_in, T_out), wrap = got
    bound = slide_bound(pulleys.factor, wrap)
    out_larger = T_out > T_in
    ratio = np.where(out_larger, T_out, T_in) / np.maximum(np.minimum(T_in, T_out), 1e-300)
    # the side the line slides towards: as in the last step for a pulley that slid (its
    # ratio may be just under the bound at the extrapolated split), else the larger
    towards_out = np.where(was & ~frictionless, direction > 0.0, out_larger)
    active = frictionless | was | (ratio > bound)
    for _ in range(m_all + 1):
        if not np.any(active):
            if last[0] != split.tobytes() and evaluate(split) is None:
                return None, direction
            return split.copy(), np.zeros(m_all)
        S = _solve_active(
            evaluate,
            pulleys,
            np.where(active, start, split),
            active,
            towards_out,
            tolerance,
            max_iterations,
        )
        if S is None:
            return None, direction
        # material moves towards the larger tension: out (S falls) or in (S grows); a
        # pulley whose solution moves it the other way sticks instead
        moved = S - split
        wrong = active & ~frictionless & np.where(towards_out, moved > 0.0, moved < 0.0)
        if not np.any(wrong):
            new_dir = np.where(active, np.where(moved < 0.0, 1.0, -1.0), 0.0)
            return S, new_dir
        active &= ~wrong
        start = np.where(active, S, split)
    return None, direction


def _solve_active(
    evaluate: Callable[[np.ndarray], tuple | None],
    pulleys: SlidingPulleys,
    start: np.ndarray,
    active: np.ndarray,
    towards_out: np.ndarray,
    tolerance: float,
    max_iterations: int,
) -> np.ndarray | None:
    """Broyden's method on the active pulleys' g_k(S) = 0 from ``start`` (the others
    held); the last ``evaluate`` call is at the returned split."""
    idx = np.nonzero(active)[0]
    m = len(idx)

    def g_at(S: np.ndarray) -> np.ndarray | None:
        got = evaluate(S)
        if got is None:
            return None
        (Ti, To), w = got
        bound = slide_bound(pulleys.factor, w)  # T_out - r T_in, r the bound (out larger) or 1/r
        return (To - np.where(towards_out, bound, 1.0 / bound) * Ti)[idx]

    S = start.copy()
    g = g_at(S)
    if g is None:
        return None
    if np.all(np.abs(g) <= tolerance):
        return S
    known = pulleys.jacobian[np.ix_(idx, idx)]
    if np.all(np.diag(known) > 0.0):
        # the last step's (or the statics') Jacobian: Broyden's method goes on from it
        J = known.copy()
    else:
        # forward differences, a split change of 1e-4 of the shortest sub-line (the
        # statics, from rest: dg/dS ~ EA / L_k when taut, ~ weight per length when slack)
        J = np.empty((m, m))
        for j in range(m):
            d = np.zeros_like(S)
            shortest = float(np.min(np.diff(_bounds(S, pulleys))))
            d[idx[j]] = -1e-4 * math.copysign(1.0, g[j]) * shortest
            gj = g_at(S + d)
            if gj is None:
                return None
            J[:, j] = (gj - g) / d[idx[j]]
    for _ in range(max_iterations):
        try:
            step = -np.linalg.solve(J, g)
        except np.linalg.LinAlgError:
            return None
        trial = S.copy()
        trial[idx] += step
        if not np.all(np.diff(_bounds(trial, pulleys)) > 0.0):
            return None
        g_new = g_at(trial)
        if g_new is None:
            return None
        # Broyden's rank-one update (the secant method for one pulley)
        dg = g_new - g
        J += np.outer(dg - J @ step, step) / float(step @ step)
        S, g = trial, g_new
        if np.all(np.abs(g) <= tolerance):
            if np.all(np.diag(J) > 0.0):
                pulleys.jacobian[np.ix_(idx, idx)] = J
            return S
    return None


def _bounds(S: np.ndarray, pulleys: SlidingPulleys) -> np.ndarray:
    """0, the split, and the line's length [m]."""
    return np.concatenate(([0.0], S, [pulleys.length]))
