"""Implicit time step of the discretised line: generalised-alpha with Newton.

Chung & Hulbert (1993) generalised-alpha method for ``M(x) a + F(x, v, t) = 0``,
written for the nonlinear case with the forces weighted between the step ends
(the form used by e.g. Erlicher, Bonaventura & Bursi 2002):

    M [(1 - am) a1 + am a0] + (1 - af) F(x1, v1) + af F(x0, v0) = 0,
    x1 = x0 + h v0 + h^2 [(1/2 - beta) a0 + beta a1],
    v1 = v0 + h [(1 - gamma) a0 + gamma a1],

with, for a high-frequency spectral radius ``rho`` in [0, 1],
``am = (2 rho - 1)/(rho + 1)``, ``af = rho/(rho + 1)``, ``gamma = 1/2 - am + af``,
``beta = (1 - am + af)^2 / 4``: second-order accurate, unconditionally stable for
linear problems, and damping the unresolved axial (elastic-wave) modes, so that the
step is set by the motion, not by the axial wave speed. ``rho = 1`` is the
trapezoidal rule (no numerical dissipation).

Newton iterates on the free nodes' positions with the block-banded Jacobian
``J = (1 - am)/(beta h^2) M + (1 - af) [K + gamma/(beta h) C]`` (block-tridiagonal, or
pentadiagonal where the line bends); held nodes (fixed or excited ends) follow their
prescribed motion, a free end node moves with the line.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from numba import njit

from .model import _trial_states, assemble, solve_banded, states_changed


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
    rest_length,
    axial_stiffness,
    internal_damping,
    force,
    drag_normal,
    drag_tangential,
    added_mass_normal,
    added_mass_tangential,
    mass,
    current_z,
    current_velocity,
    has_drag,
    bending,
    clamp_direction,
    transverse_damping,
    body_added_mass,
    body_drag,
    held,
    seabed_normal,
    seabed_offset,
    seabed_stiffness,
    seabed_damping,
    friction,
    law_code,
    law_params,
    law_knots,
    law_start,
    law_count,
    broken,
    F,
    K_d,
    K_o,
    K_o2,
    C_d,
    C_o,
    M_d,
    tension,
    strain,
    taut0,
    contact,
    friction_force,
    slip_state,
    trial,
    J_d,
    J_o,
    J_o2,
    r,
    dx,
    band,
):  # noqa: ANN001, ANN201
    """One step of length ``h`` [s] from (x0, v0, a0) with out-of-balance force F0.

    ``end_x, end_v, end_a`` (2, 3) are the prescribed position, velocity and
    acceleration of end nodes A and B at the end of the step (used where the end node
    is ``held``); ``x_pred`` (n + 1, 3) is the predicted position of every node
    (Newton's start; velocity and acceleration follow from the Newmark relations);
    ``anchor`` holds the seabed friction anchors of the start of the step. On return
    x1, v1, a1 hold the new state, and F, M_d, tension, strain, contact and friction
    are evaluated there. Returns (Newton iterations, converged): converged when the
    largest residual force on a free node is at most ``tol`` [N]."""
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
    has_friction = (friction[0] > 0.0 or friction[1] > 0.0) and seabed_stiffness.max() > 0.0
    fix_states = has_friction
    checks = 0
    it = 0
    while True:
        assemble(
            x1,
            v1,
            anchor,
            rest_length,
            axial_stiffness,
            internal_damping,
            force,
            drag_normal,
            drag_tangential,
            added_mass_normal,
            added_mass_tangential,
            mass,
            current_z,
            current_velocity,
            has_drag,
            bending,
            clamp_direction,
            transverse_damping,
            body_added_mass,
            body_drag,
            held,
            seabed_normal,
            seabed_offset,
            seabed_stiffness,
            seabed_damping,
            friction,
            law_code,
            law_params,
            law_knots,
            law_start,
            law_count,
            broken,
            F,
            K_d,
            K_o,
            K_o2,
            C_d,
            C_o,
            M_d,
            tension,
            strain,
            taut0,
            contact,
            friction_force,
            slip_state,
            trial,
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
        if res <= tol:
            if (
                has_friction
                and checks < MAX_STATE_CHECKS
                and states_changed(slip_state, trial, contact, friction)
            ):
                checks += 1
                continue  # converged with a wrong stick/slip guess: again with the new one
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
        big = 0.0
        for i in range(n):
            for c in range(3):
                big = max(big, abs(dx[i, c]))
        if big > lmin or not math.isfinite(big):
            return it, False
        for i in range(n):
            if held[i]:
                continue
            for c in range(3):
                d = dx[i, c]
                x1[i, c] += d
                a1[i, c] += d / (beta * h * h)
                v1[i, c] += gamma * d / (beta * h)
    return max_iterations, False


#: stick/slip re-checks per time step after Newton converged with a wrong guess
MAX_STATE_CHECKS = 4
