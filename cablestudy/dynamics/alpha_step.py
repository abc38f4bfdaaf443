"""One implicit step of the time integration (:mod:`.integrator` marches them): the
generalised-alpha parameters of a spectral radius (:class:`AlphaParameters`) and the
step solved by Newton's method on the node positions (:func:`alpha_step`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from .assembly import (
    _trial_states,
    assemble_lines,
    contact_states,
    solve_banded,
    states_changed,
)
from .step_parts import largest_correction, newmark_correct


@dataclass(frozen=True)
class AlphaParameters:
    """Generalised-alpha coefficients for spectral radius ``rho`` [-]."""

    alpha_m: float
    alpha_f: float
    beta: float
    gamma: float

    @classmethod
    def from_spectral_radius(cls, rho: float) -> AlphaParameters:
        am = (2.0 * rho - 1.0) / (rho + 1.0)
        af = rho / (rho + 1.0)
        gamma = 0.5 - am + af
        beta = 0.25 * (1.0 - am + af) ** 2
        return cls(am, af, beta, gamma)


@njit(cache=True)
def alpha_step(
    x0,
    v0,
    a0,
    F0,
    h,
    end_x,
    end_v,
    end_a,
    alpha_m,
    alpha_f,
    beta,
    gamma,
    tol,
    max_iterations,
    x_pred,
    x1,
    v1,
    a1,
    anchor,
    largs,
    wargs,
    sargs,
):  # noqa: ANN001, ANN201
    """One step of length ``h`` [s] from (x0, v0, a0) with out-of-balance force F0.

    ``end_x, end_v, end_a`` (2, 3) are the prescribed position, velocity and
    acceleration of end nodes A and B at the end of the step (used where the end node
    is ``held``); ``x_pred`` (n + 1, 3) is the predicted position of every node
    (Newton's start; velocity and acceleration follow from the Newmark relations);
    ``anchor`` holds the seabed friction anchors of the start of the step; ``largs``
    the line's arrays (:class:`.discrete_line.LineArrays`), ``wargs`` those assembled
    (:class:`.assembly.WorkArrays`), ``sargs`` the Newton solve's scratch (``J_d, J_o,
    J_o2, r, dx, band``: :meth:`.assembly.Workspace.solver_args`). On return x1, v1,
    a1 hold the new state, and F, M_d, tension, strain, contact and friction are
    evaluated there. Returns (Newton iterations, converged): converged when the
    largest residual force on a free node is at most ``tol`` [N]."""
    rest_length, held, friction = largs.rest_length, largs.held, largs.friction
    seabed_normal, seabed_offset = largs.seabed_normal, largs.seabed_offset
    seabed_stiffness, seabed_damping = largs.seabed_stiffness, largs.seabed_damping
    F, K_d, K_o, K_o2 = wargs.F, wargs.K_d, wargs.K_o, wargs.K_o2
    C_d, C_o, M_d, taut0 = wargs.C_d, wargs.C_o, wargs.M_d, wargs.taut0
    contact, slip_state, trial = wargs.contact, wargs.slip_state, wargs.trial
    J_d, J_o, J_o2, r, dx, band = sargs
    n = x0.shape[0]
    for i in range(n):
        for c in range(3):
            x1[i, c] = x_pred[i, c]
            a1[i, c] = (x1[i, c] - x0[i, c] - h * v0[i, c] - h * h * (0.5 - beta) * a0[i, c]) / (
                beta * h * h
            )
            v1[i, c] = v0[i, c] + h * ((1.0 - gamma) * a0[i, c] + gamma * a1[i, c])
    for end in range(2):
        node = 0 if end == 0 else n - 1
        if held[node]:
            for c in range(3):
                x1[node, c] = end_x[end, c]
                v1[node, c] = end_v[end, c]
                a1[node, c] = end_a[end, c]
    n_free = 0
    for i in range(n):
        if not held[i]:
            n_free += 1
    cm = (1.0 - alpha_m) / (beta * h * h)
    cv = gamma / (beta * h)
    lmin = rest_length.min()
    has_seabed = seabed_stiffness.max() > 0.0
    has_friction = (friction[0] > 0.0 or friction[1] > 0.0) and has_seabed
    fix_states = has_friction
    # contact is an active set like friction: each node's touching / not touching is
    # held during the Newton iterations (the contact force then smooth: no jump of the
    # damping force c v_n, no kink of the spring), taken from the predictor, and
    # checked once they converge
    fixed_contact = has_seabed and slip_state.shape[1] > 2
    flips = np.zeros(n, dtype=np.int64)
    if fixed_contact:
        contact_states(
            x1,
            v1,
            seabed_normal,
            seabed_offset,
            seabed_stiffness,
            seabed_damping,
            slip_state,
            False,
            flips,
        )
    checks = 0
    checked_early = False
    clips = 0
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
            x1,
            v1,
            anchor,
            # named one by one, not *largs[:], *wargs[:] as elsewhere: this is the
            # time step's inner loop (the slices measured up to 1.6% slower a study)
            largs.rest_length,
            largs.axial_stiffness,
            largs.internal_damping,
            largs.force,
            largs.drag_normal,
            largs.drag_tangential,
            largs.added_mass_normal,
            largs.added_mass_tangential,
            largs.mass,
            largs.current_z,
            largs.current_velocity,
            largs.has_drag,
            largs.bending,
            largs.clamp_direction,
            largs.transverse_damping,
            largs.body_added_mass,
            largs.body_drag,
            largs.held,
            largs.seabed_normal,
            largs.seabed_offset,
            largs.seabed_stiffness,
            largs.seabed_damping,
            largs.friction,
            largs.law_code,
            largs.law_params,
            largs.law_knots,
            largs.law_start,
            largs.law_count,
            largs.broken,
            wargs.F,
            wargs.K_d,
            wargs.K_o,
            wargs.K_o2,
            wargs.C_d,
            wargs.C_o,
            wargs.M_d,
            wargs.tension,
            wargs.strain,
            wargs.taut0,
            wargs.contact,
            wargs.friction_force,
            wargs.slip_state,
            wargs.trial,
            uel,
            lel,
        )
        if fix_states:
            # a contact node keeps the stick/slip state it ended the last step with (a
            # sliding stretch tends to go on sliding); a node new to the seabed takes
            # the predictor's trial; the Newton iterations then keep those states (a
            # smooth force), checked once converged
            fix_states = False
            _trial_states(slip_state, trial, contact, friction, True)
            continue
        res = 0.0
        for i in range(n):
            for c in range(3):
                acc = (1.0 - alpha_f) * F[i, c] + alpha_f * F0[i, c]
                for b in range(3):
                    acc += M_d[i, c, b] * ((1.0 - alpha_m) * a1[i, b] + alpha_m * a0[i, b])
                r[i, c] = -acc
                if not held[i]:
                    res = max(res, abs(acc))
        if not math.isfinite(res):
            return it, False
        # the states are checked once Newton is close (STATE_CHECK_FACTOR times the
        # tolerance: the trial forces that decide them are then settled), so that a
        # wrong guess costs the iterations from there, not from full convergence; and
        # again at convergence
        early = res <= STATE_CHECK_FACTOR * tol and not checked_early
        if res <= tol or early:
            checked_early = True
            if checks < MAX_STATE_CHECKS:
                changed = fixed_contact and contact_states(
                    x1,
                    v1,
                    seabed_normal,
                    seabed_offset,
                    seabed_stiffness,
                    seabed_damping,
                    slip_state,
                    True,
                    flips,
                )
                if has_friction and states_changed(slip_state, trial, contact, friction):
                    changed = True
                if changed:
                    checks += 1
                    checked_early = False
                    continue  # converged with a wrong guess of a state: again with the new
            if res <= tol:
                return it, True
        if it == max_iterations or n_free == 0:
            break
        it += 1
        for i in range(n):
            for c in range(3):
                for b in range(3):
                    J_d[i, c, b] = cm * M_d[i, c, b] + (1.0 - alpha_f) * (
                        K_d[i, c, b] + cv * C_d[i, c, b]
                    )
        for i in range(n - 1):
            for c in range(3):
                for b in range(3):
                    J_o[i, c, b] = (1.0 - alpha_f) * (K_o[i, c, b] + cv * C_o[i, c, b])
        for i in range(J_o2.shape[0]):
            for c in range(3):
                for b in range(3):
                    J_o2[i, c, b] = (1.0 - alpha_f) * K_o2[i, c, b]
        ok = solve_banded(J_d, J_o, J_o2, held, r, dx, band)
        if not ok:
            return it, False
        # the start-of-step stiffness of elements gone slack in the predictor helps the
        # first iteration only; later ones use the exact tangent (quadratic convergence)
        for e in range(taut0.shape[0]):
            taut0[e] = False
        big = largest_correction(dx, n)
        if big > lmin or not math.isfinite(big):
            return it, False
        # a node that would cross the seabed plane (land or lift off) stops on it: the
        # contact force has a kink there, across which the tangent of one side sends
        # Newton back and forth between contact and none; from the plane, the next
        # iteration sees the contact's own tangent. The whole correction is scaled
        # (its direction kept), a few times per step at most.
        scale = 1.0
        if clips < MAX_LANDING_CLIPS:
            scale = landing_clip(
                x1, dx, 0, n, held, seabed_stiffness, slip_state, seabed_normal, seabed_offset, 1.0
            )
            if scale < 1.0:
                clips += 1
        newmark_correct(x1, v1, a1, dx, held, n, scale, beta, gamma, h)
    return max_iterations, False


@njit(cache=True, inline="always")
def landing_clip(x1, dx, lo, hi, held, ksb, slip, normal, offset, scale):  # noqa: ANN001, ANN201, PLR0913
    """``scale`` lowered to the fraction of the Newton correction ``dx`` that stops the
    first of nodes ``lo`` .. ``hi - 1`` crossing the seabed plane (``normal`` . x =
    ``offset``) on it, at least :data:`MIN_CLIP`; a held node, one without seabed
    stiffness ``ksb`` or in a held contact state (``slip[:, 2]`` 1 or 2: no kink to stop
    at) is passed over. Shared by :func:`alpha_step` and the system's step."""
    for i in range(lo, hi):
        if held[i] or ksb[i] <= 0.0:
            continue
        if slip.shape[1] > 2 and (slip[i, 2] == 1 or slip[i, 2] == 2):
            continue
        g0 = -offset
        g1 = -offset
        for c in range(3):
            g0 += normal[c] * x1[i, c]
            g1 += normal[c] * (x1[i, c] + dx[i, c])
        if (g0 > 0.0 and g1 < 0.0) or (g0 < 0.0 and g1 > 0.0):
            scale = min(scale, max(g0 / (g0 - g1), MIN_CLIP))
    return scale


#: stick/slip re-checks per time step after Newton converged with a wrong guess
MAX_STATE_CHECKS = 4
#: the states are first checked when the residual is this many times the tolerance
STATE_CHECK_FACTOR = 1e3
#: Newton corrections per time step stopped where a node meets the seabed plane, and
#: the smallest fraction of a correction kept (so that Newton never stalls)
MAX_LANDING_CLIPS = 4
MIN_CLIP = 0.05
