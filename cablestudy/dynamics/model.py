"""Discretised line model: lumped masses at nodes joined by straight elastic elements.

One line model serves the time-domain solver (its forces and their tangents drive the
implicit step) and the discrete statics that start it. The line is cut along its
unstretched arc length ``s`` into elements (nodes at every segment boundary, so each
element has one material). Element ``e`` joins nodes ``e`` and ``e + 1``; with
``d = x[e+1] - x[e]``, ``l = |d|`` and unit vector ``u = d / l`` its strain and
tension are

    eps = l / l0 - 1                                  (exact for large displacements)
    T   = max(EA eps + c eps_dot, 0)  if eps > 0 else 0   (tension-only)

with ``eps_dot = u . (v[e+1] - v[e]) / l0`` and the internal damping ``c = zeta l0
sqrt(EA m)`` [N s] (``zeta``: fraction of critical damping of the element's axial
mode, the segments' ``damping_ratio``). This is the moustafa seed's nonlinear strain
(its eq. 2 is the same stretch written relative to the static catenary, eqs. 4-6)
without the small-strain truncation, and its tension law eq. (6) with the
compression cut off.

Bending (the ajayi seed's tensioned-beam term ``EI q''''``). The discrete curvature at
an interior node ``i`` is ``(u_i - u_{i-1}) / h_i`` with ``h_i`` the mean unstretched
length of its two elements; the bending energy is ``sum EI_i |u_i - u_{i-1}|^2 /
(2 h_i)``. Its gradient is the nodal bending force; its tangent is taken as the
Gauss-Newton part ``(EI/h) J^T J`` (exact for a straight line; the dropped term is of
order EI times the curvature, a quasi-Newton approximation). A ``pinned`` end carries
no curvature term (zero moment); a ``clamped`` end adds ``EI |u_end - d|^2 / l0`` with
``d`` the end's fixed direction (its static end element's: no moment at rest), i.e.
the end node owns half an element of curvature. Bending couples a node to its second
neighbours, so the tangent has blocks two nodes off the diagonal.

Loads at nodes (tributary length = half of each adjacent element):

* weight in the fluid (weight minus buoyancy), attachment forces, and the constant
  force of a free ``force`` end, all constant;
* Morison drag on the relative velocity ``U = U_current(z) - v``, split along the node
  tangent ``t``: ``f = 1/2 rho d l (C_N |U_N| U_N + pi C_T |U_T| U_T)``
  (:mod:`cablestudy.physics.hydro`, the dodaran-park seed eqs. 38-39); lumped bodies
  (attachments with ``drag_area`` = C_D A) add ``1/2 rho C_D A |U| U``;
* transverse structural damping (the ajayi seed's ``c dq/dt``): ``-c l (v - (v.t) t)``;
* inertia ``M = m l I + C_a rho A l (I - t t) + C_at rho A l t t`` (structural mass
  plus added mass, normal and tangential), plus attachment masses and their
  isotropic added mass;
* seabed contact (:func:`seabed_contact_force` documents the law): a normal penalty
  spring and dashpot per unit length on the plane ``n . x = offset``, and Coulomb
  friction along and across the line as an elastic-plastic (stick-slip) law with a
  per-node anchor: the trial force ``-k_t (x - anchor)`` sticks while it is below
  ``mu N`` in each direction and slides at ``mu N`` otherwise. After each accepted step
  the anchors move so that the force is carried exactly (:func:`update_anchors`): at
  rest the friction force of the static solution is held, so a still line stays
  still; in sliding the friction always opposes the slip (it dissipates energy).

Nodes may be held (their motion prescribed: fixed or excited ends) or free (every
interior node, and an unexcited ``force`` end).

Everything here is pure: arrays in, arrays out, SI units. The kernels are compiled
with numba (cached on disk) because a time step is a few microseconds of arithmetic
on short arrays, where interpreter overhead would dominate.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .assembly import (
    Workspace,
    _trial_states,
    assemble_lines,
    evaluate,
    solve_banded,
    states_changed,
    update_anchors,
)
from .discrete_line import DiscreteLine
from .step_parts import largest_correction, quarter_element_scale, slack_regularisation


@njit(cache=True, nogil=True)
def _static_newton(
    x,
    anchor,
    largs,
    wargs,
    sargs,
    tol,
    max_iterations,
):  # noqa: ANN001, ANN201
    """Newton on the node positions ``x`` (overwritten) of the line's equilibrium
    (:func:`static_equilibrium`); ``largs``, ``wargs``, ``sargs`` as
    :func:`.alpha_step.alpha_step`'s. Returns (iterations, residual, converged)."""
    rest_length, axial_stiffness, held = largs.rest_length, largs.axial_stiffness, largs.held
    seabed_stiffness, friction = largs.seabed_stiffness, largs.friction
    F, K_d, K_o, K_o2 = wargs.F, wargs.K_d, wargs.K_o, wargs.K_o2
    tension, contact = wargs.tension, wargs.contact
    slip_state, trial = wargs.slip_state, wargs.trial
    J_d, J_o, J_o2, r, dx, band = sargs
    n = x.shape[0]
    v = np.zeros_like(x)
    res = np.inf
    lmin = rest_length.min()
    reg = 1e-9 * (axial_stiffness.max() / lmin)
    # a Newton correction below ~1000 ulp of the coordinates cannot lower the residual
    # further (the solve of a stiff line, EA / T up to 1e10, carries its condition
    # number's rounding): the equilibrium is then found to rounding
    reach = 0.0
    for i in range(n):
        for a in range(3):
            reach = max(reach, abs(x[i, a]))
    reach += rest_length.sum()
    floor = 1024.0 * 2.220446049250313e-16 * reach
    has_friction = (friction[0] > 0.0 or friction[1] > 0.0) and seabed_stiffness.max() > 0.0
    has_friction = has_friction and math.isfinite(friction[0]) and math.isfinite(friction[1])
    fix_states = has_friction
    for i in range(n):
        for k in range(2):
            slip_state[i, k] = 0
    checks = 0
    it = 0
    # the elements' unit vectors and lengths (assemble_lines' scratch), once for the loop
    uel = np.empty((rest_length.shape[0], 3))
    lel = np.empty(rest_length.shape[0])
    while True:
        assemble_lines(
            None,
            None,
            None,
            None,
            x,
            v,
            anchor,
            *largs[:],  # [:]: as plain tuples, which numba joins into the arguments
            *wargs[:],
            uel,
            lel,
        )
        if fix_states:
            # friction as an active set, as in the time step: the trial decides which
            # contact nodes stick and which slide, Newton keeps those states
            fix_states = False
            _trial_states(slip_state, trial, contact, friction)
            continue
        res = 0.0
        for i in range(n):
            if held[i]:
                continue
            for a in range(3):
                res = max(res, abs(F[i, a]))
        if res <= tol:
            if (
                has_friction
                and checks < 20
                and states_changed(slip_state, trial, contact, friction)
            ):
                checks += 1
                continue
            return it, res, True
        if it >= max_iterations:
            break
        it += 1
        # a little mass-like regularisation keeps slack nodes solvable; kept well below
        # the geometric stiffness T / l of the taut elements, or a light line's soft
        # modes would converge only linearly
        reg_it = slack_regularisation(tension, reg, lmin)
        for i in range(n):
            for a in range(3):
                r[i, a] = -F[i, a]
                for b in range(3):
                    J_d[i, a, b] = K_d[i, a, b]
                J_d[i, a, a] += reg_it
        for i in range(n - 1):
            for a in range(3):
                for b in range(3):
                    J_o[i, a, b] = K_o[i, a, b]
        for i in range(J_o2.shape[0]):
            for a in range(3):
                for b in range(3):
                    J_o2[i, a, b] = K_o2[i, a, b]
        ok = solve_banded(J_d, J_o, J_o2, held, r, dx, band)
        if not ok:
            return it, res, False
        big = largest_correction(dx, n)
        if big <= floor:
            return it, res, True
        scale = quarter_element_scale(big, lmin)
        for i in range(n):
            for a in range(3):
                x[i, a] += scale * dx[i, a]
    return max_iterations, res, False


def stretched_start(line: DiscreteLine, x0: np.ndarray, tension: np.ndarray) -> np.ndarray:
    """Node positions with the directions of ``x0``'s chords and the lengths the element
    ``tension`` [N] (n,) stretches them to, ``l0 (1 + T / EA)``, rebuilt from end A,
    with the misclosure at end B (if held) spread along the line in proportion to arc
    length. The chords of a smooth curve sampled at the nodes are shorter than its arcs
    by O(h^2 kappa^2): on a stiff line that error times EA is a large spurious tension,
    which this start removes before Newton."""
    d = np.diff(x0, axis=0)
    u = d / np.linalg.norm(d, axis=1, keepdims=True)
    chord = line.rest_length * (1.0 + np.maximum(tension, 0.0) / line.axial_stiffness)
    x = np.vstack([x0[:1], x0[0] + np.cumsum(u * chord[:, None], axis=0)])
    if line.held[-1]:
        frac = (line.s - line.s[0]) / (line.s[-1] - line.s[0])
        x += frac[:, None] * (x0[-1] - x[-1])[None, :]
    return x


def static_equilibrium(
    line: DiscreteLine,
    x0: np.ndarray,
    *,
    tolerance: float,
    max_iterations: int = 100,
    tension: np.ndarray | None = None,
    fallback_tension: np.ndarray | None = None,
) -> tuple[np.ndarray, int, float, bool, np.ndarray]:
    """Equilibrium of the discrete line with its held nodes where ``x0`` puts them.

    Newton from ``x0`` (the continuous static solution at the nodes), so that the time
    integration starts at rest in the discrete model's own equilibrium. Seabed friction
    starts from anchors at ``x0``: friction is mobilised by the small displacement
    from the continuous solution (at most ``mu N / k_t``), never beyond ``mu N``.

    Given the element ``tension`` [N] (n,) of the continuous solution, Newton starts
    from :func:`stretched_start`. Where Newton on positions fails (a stiff line, on a
    seabed), Newton on positions and element tensions
    (:func:`cablestudy.dynamics.mixed.mixed_equilibrium`) from ``x0`` and that tension
    (or ``fallback_tension`` [N] (n,), which leaves the first start at ``x0``) gives
    the equilibrium.

    Returns positions [m] (n + 1, 3), iterations, the largest nodal out-of-balance
    force [N], whether it fell below ``tolerance`` [N], and the friction anchors [m]
    that hold the friction forces of that equilibrium.
    """
    x = np.array(x0, dtype=float, copy=True)
    if tension is not None:
        x = stretched_start(line, x, np.asarray(tension, dtype=float))
    work = Workspace(line.n_elements)
    work.anchor[:] = x
    if line.has_seabed:
        x, work.anchor[:] = _seated_start(line, x, work)
    start, start_anchor = x.copy(), work.anchor.copy()
    it, res, ok = _static_newton(
        x,
        work.anchor,
        line.kernel_args(),
        work.assemble_args(),
        work.solver_args(line),
        tolerance,
        max_iterations,
    )
    if tension is None:
        tension = fallback_tension
    if not ok and tension is not None:
        from .mixed import is_finite_line, mixed_equilibrium

        if is_finite_line(line):
            # Newton on positions cannot start (a stiff line: EA times the start's chord
            # error is a large spurious force): Newton on positions and tensions from
            # the same start, which has no such force
            t0 = np.maximum(np.asarray(tension, dtype=float), 0.0)
            xm = np.array(x0, dtype=float, copy=True)
            anchor_m = xm.copy()
            if line.has_seabed:
                xm, anchor_m = _seated_start(line, xm, Workspace(line.n_elements), t0)
            sol = mixed_equilibrium(
                line,
                xm,
                t0,
                anchor_m,
                tol_force=tolerance,
                relative=tolerance / max(float(np.max(t0)), tolerance),
                max_iterations=max_iterations,
            )
            it += sol.iterations
            if sol.converged:
                return sol.position, int(it), sol.force_residual, True, sol.anchor
            x = start
            work.anchor[:] = start_anchor
            evaluate(line, x, np.zeros_like(x), work)
    anchor = work.anchor.copy()
    update_anchors(x, work.friction, line.seabed_stiffness, work.contact, anchor)
    return x, int(it), float(res), bool(ok), anchor


def _seated_start(
    line: DiscreteLine, x: np.ndarray, work: Workspace, tension: np.ndarray | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """Newton's start on a penalty seabed: nodes that the continuous (rigid-seabed)
    solution lays on the seabed sink by their own penetration (normal load over contact
    stiffness), and their friction anchors are placed so that the friction springs
    already carry the tangential force the laid line needs there (the continuous
    solution's mobilised friction), capped at ``mu N`` along and across the line.
    Given the element ``tension`` [N] (n,), the elements pull with it rather than with
    the tension their chords' stretch gives (on a stiff line that is EA times the
    chords' error). Returns the positions [m] and anchors [m]."""
    normal = line.seabed_normal
    scale = float(np.max(np.abs(x))) + float(np.sum(line.rest_length))
    laid = (x @ normal - line.seabed_offset <= 1e-9 * scale) & (line.seabed_stiffness > 0.0)
    laid &= ~np.asarray(line.held, dtype=bool)  # a held node stays where it is held
    if not np.any(laid):
        return x, x.copy()
    x = x.copy()
    x[laid] += np.outer(line.seabed_offset - x[laid] @ normal, normal)  # onto the plane
    still = np.zeros_like(x)

    def out_of_balance(x: np.ndarray) -> np.ndarray:
        if tension is None:
            return evaluate(line, x, still, work, anchor=x).F.copy()
        from .mixed import axial_forces, other_forces_line

        f = evaluate(other_forces_line(line), x, still, work, anchor=x).F
        return f + axial_forces(x, tension)[0]

    press = out_of_balance(x) @ normal  # load on the seabed
    sink = np.where(laid, np.maximum(press, 0.0) / np.maximum(line.seabed_stiffness, 1e-300), 0.0)
    x -= sink[:, None] * normal
    out = out_of_balance(x)
    w = work
    need = out - np.outer(out @ normal, normal)  # tangential out-of-balance: friction needed
    n = line.n_nodes
    tan = x[np.minimum(np.arange(n) + 1, n - 1)] - x[np.maximum(np.arange(n) - 1, 0)]
    along = tan - np.outer(tan @ normal, normal)
    along /= np.maximum(np.linalg.norm(along, axis=1, keepdims=True), 1e-300)
    across = np.cross(normal, along)
    cap = line.friction[:, None] * w.contact[None, :]
    fa = np.clip(np.einsum("ia,ia->i", need, along), -cap[0], cap[0])
    fl = np.clip(np.einsum("ia,ia->i", need, across), -cap[1], cap[1])
    f = np.where(laid[:, None], fa[:, None] * along + fl[:, None] * across, 0.0)
    return x, x + f / np.maximum(line.seabed_stiffness, 1e-300)[:, None]
