"""Compiled time stepping of a mooring system: the generalised-alpha step of all lines
and free points together (Newton with the bordered solve of
:func:`.system_kernels.coupled_solve`), the step control, the per-period extremes, and
the discrete static equilibrium the run starts from.

The step is the single line's (:mod:`.integrator`): the same generalised-alpha
coefficients and Newmark relations, the same predictor (quadratic through the last
three accepted positions, the held ends moved to their prescribed positions with the
correction spread along each line), halving the step when Newton fails, when an
element switches between slack and taut, or when a watched line end's tension changes
by more than ``tension_step`` in a step (every line end; in a system of one line the
end the motion moves, as the single line's excited end), and doubling it back after two clean steps.

Pure: arrays in, arrays out (SI units).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .alpha_step import MAX_LANDING_CLIPS, MAX_STATE_CHECKS, STATE_CHECK_FACTOR, landing_clip
from .assembly import _trial_states, contact_states_lines, states_changed, update_anchors
from .end_support import seabed_support
from .step_parts import (
    accept_state,
    largest_correction,
    newmark_correct,
    predict_positions,
    quarter_element_scale,
    relax_level,
    slack_regularisation,
)
from .system_kernels import assemble_all, coupled_solve, drives_at, point_forces

#: :func:`system_march` return codes
BOUNDARY, ACCEPTED, FAILED = 0, 1, 2


@njit(cache=True)
def _contact_states(S, W, x, v, fix, flips):  # noqa: ANN001, ANN201
    """:func:`.assembly.contact_states` of every line (each line's seabed offset), in
    one call; True if any state changed."""
    return contact_states_lines(S[0], x, v, S[22], S[23], S[24], S[25], W[12], fix, flips)


@njit(cache=True)
def _friction_states(S, W, check):  # noqa: ANN001, ANN201
    """Stick/slip states line by line (each line's friction coefficients): from the
    trial forces keeping a contact node's state (``check`` False), or checked after
    convergence (:func:`.model.states_changed`, ``check`` True: whether any changed)."""
    no = S[0]
    changed = False
    for l in range(no.shape[0] - 1):  # noqa: E741
        n0, n1 = no[l], no[l + 1]
        fr = S[26][l]
        if fr[0] <= 0.0 and fr[1] <= 0.0:
            continue
        if check:
            if states_changed(W[12][n0:n1], W[13][n0:n1], W[10][n0:n1], fr):
                changed = True
        else:
            _trial_states(W[12][n0:n1], W[13][n0:n1], W[10][n0:n1], fr, True)
    return changed


@njit(cache=True)
def _static_friction_states(S, W):  # noqa: ANN001, ANN201
    """Every contact node's stick/slip state from its trial force, line by line."""
    no = S[0]
    for l in range(no.shape[0] - 1):  # noqa: E741
        n0, n1 = no[l], no[l + 1]
        fr = S[26][l]
        if fr[0] > 0.0 or fr[1] > 0.0:
            _trial_states(W[12][n0:n1], W[13][n0:n1], W[10][n0:n1], fr)


@njit(cache=True)
def _residuals(S, W, x1, a0, a1, F0, Fp0, Fp, am, af, r, rp):  # noqa: ANN001, ANN201
    """Residuals ``r`` of the nodes and ``rp`` of the free points of the generalised-
    alpha balance; returns the largest over the free unknowns [N]."""
    held, is_junction = S[21], S[40]
    p_mass, p_nodes, p_off = S[35], S[38], S[39]
    F, M_d = W[0], W[6]
    n = x1.shape[0]
    res = 0.0
    for i in range(n):
        for c in range(3):
            acc = (1.0 - af) * F[i, c] + af * F0[i, c]
            for b in range(3):
                acc += M_d[i, c, b] * ((1.0 - am) * a1[i, b] + am * a0[i, b])
            r[i, c] = -acc
            if not held[i] and not is_junction[i]:
                res = max(res, abs(acc))
    for p in range(rp.shape[0]):
        first = p_nodes[p_off[p]]
        for c in range(3):
            acc = (1.0 - af) * Fp[p, c] + af * Fp0[p, c]
            acc += p_mass[p] * ((1.0 - am) * a1[first, c] + am * a0[first, c])
            tot = -acc
            for k in range(p_off[p], p_off[p + 1]):
                tot += r[p_nodes[k], c]
            rp[p, c] = tot
            res = max(res, abs(tot))
    return res


@njit(cache=True)
def _landing_clip(S, W, x1, dx, sbn, sbo, ksb):  # noqa: ANN001, ANN201
    """The fraction of a Newton correction that stops the first node crossing the
    seabed plane on it (a node whose contact state is not held), at least
    :data:`.integrator.MIN_CLIP` (as the single line's step)."""
    no, held = S[0], S[21]
    scale = 1.0
    for l in range(no.shape[0] - 1):  # noqa: E741
        scale = landing_clip(x1, dx, no[l], no[l + 1], held, ksb, W[12], sbn, sbo[l], scale)
    return scale


@njit(cache=True)
def system_step(  # noqa: ANN201
    h,
    x0,
    v0,
    a0,
    F0,
    Fp0,
    x1,
    v1,
    a1,
    x_pred,
    am,
    af,
    beta,
    gamma,
    tol,
    max_it,
    anchor,
    S,
    W,
    r,
    rp,
    dx,
    dp,
    Fp,
    lmin,
):  # noqa: ANN001
    """One generalised-alpha step of length ``h`` [s] from (x0, v0, a0); ``x_pred`` the
    predicted positions with the held nodes at their prescribed positions, whose
    velocity and acceleration are already in ``v1``, ``a1``. Returns (Newton
    iterations, converged)."""
    held = S[21]
    n = x0.shape[0]
    for i in range(n):
        if held[i]:
            for c in range(3):
                x1[i, c] = x_pred[i, c]
            continue
        for c in range(3):
            x1[i, c] = x_pred[i, c]
            a1[i, c] = (x1[i, c] - x0[i, c] - h * v0[i, c] - h * h * (0.5 - beta) * a0[i, c]) / (
                beta * h * h
            )
            v1[i, c] = v0[i, c] + h * ((1.0 - gamma) * a0[i, c] + gamma * a1[i, c])
    cm = (1.0 - am) / (beta * h * h)
    cv = gamma / (beta * h)
    taut0 = W[9]
    # seabed contact and friction as active sets, as the single line's step
    # (:func:`.integrator.alpha_step`): held during the Newton iterations, from the
    # predictor, checked near and at convergence
    ksb, sbn, sbo = S[24], S[22], S[23]
    has_seabed = ksb.shape[0] > 0 and ksb.max() > 0.0
    fr = S[26]
    has_friction = has_seabed and (fr.max() > 0.0)
    fix_states = has_friction
    flips = np.zeros(n, dtype=np.int64)
    if has_seabed:
        _contact_states(S, W, x1, v1, False, flips)
    checks = 0
    checked_early = False
    clips = 0
    it = 0
    while True:
        assemble_all(x1, v1, anchor, S, W)
        if fix_states:
            fix_states = False
            _friction_states(S, W, False)
            continue
        point_forces(S, x1, v1, Fp)
        res = _residuals(S, W, x1, a0, a1, F0, Fp0, Fp, am, af, r, rp)
        if not math.isfinite(res):
            return it, False
        early = res <= STATE_CHECK_FACTOR * tol and not checked_early
        if res <= tol or early:
            checked_early = True
            if has_seabed and checks < MAX_STATE_CHECKS:
                changed = _contact_states(S, W, x1, v1, True, flips)
                if has_friction and _friction_states(S, W, True):
                    changed = True
                if changed:
                    checks += 1
                    checked_early = False
                    continue
            if res <= tol:
                return it, True
        if it >= max_it:
            return it, False
        it += 1
        if not coupled_solve(S, W, cm, 1.0 - af, cv, 0.0, r, rp, dx, dp):
            return it, False
        for e in range(taut0.shape[0]):
            taut0[e] = False
        big = largest_correction(dx, n)
        if big > lmin or not math.isfinite(big):
            return it, False
        scale = 1.0
        if has_seabed and clips < MAX_LANDING_CLIPS:
            scale = _landing_clip(S, W, x1, dx, sbn, sbo, ksb)
            if scale < 1.0:
                clips += 1
        newmark_correct(x1, v1, a1, dx, held, n, scale, beta, gamma, h)


@njit(cache=True)
def end_forces(S, W, x, a, he_node, forces):  # noqa: ANN001, ANN201
    """Force of each line on its end points [N] (L, 2, 3): minus the support reaction
    ``F + M a`` of the line's end node (without the seabed's part where it rests on the
    seabed: :func:`.end_support.seabed_support`, as the single line's), at a held end
    and at a free point alike. A line's end node on a free point lumps the line's half
    end element (its mass, weight and drag are the line's, the point's own are apart),
    so the line's force on the point is that node's reaction, as the statics' end force
    is (the end element's pull alone left out the half element's weight: a first-order
    error, 2 % of a bridle's junction tension at 8 elements)."""
    no, eo = S[0], S[1]
    F, M_d = W[0], W[6]
    rest, ksb = S[4], S[24]
    for l in range(no.shape[0] - 1):  # noqa: E741
        for end in range(2):
            node = no[l] if end == 0 else no[l + 1] - 1
            for c in range(3):
                acc = F[node, c]
                for b in range(3):
                    acc += M_d[node, c, b] * a[node, b]
                forces[l, end, c] = -acc
            if ksb.shape[0] > 0 and ksb[node] > 0.0:
                # the single line's tolerance: a millionth of the line's length
                length = 0.0
                for k in range(eo[l], eo[l + 1]):
                    length += rest[k]
                seabed_support(
                    forces[l, end], x[node], W[10][node], W[11][node], ksb[node],
                    S[22], S[23][l], 1e-6 * max(length, 1.0),
                )  # fmt: skip


@njit(cache=True)
def body_forces(S, x, forces, he_line, he_end, he_body, bx, out):  # noqa: ANN001, ANN201
    """Force and moment [N, N m] (B, 6) of the lines on each body about its reference
    point ``bx`` (B, 3): the lines' forces on the held ends on the body."""
    no = S[0]
    for b in range(out.shape[0]):
        for k in range(6):
            out[b, k] = 0.0
    for k in range(he_line.shape[0]):
        b = he_body[k]
        if b < 0:
            continue
        l = he_line[k]  # noqa: E741
        end = he_end[k]
        node = no[l] if end == 0 else no[l + 1] - 1
        f = forces[l, end]
        rx = x[node, 0] - bx[b, 0]
        ry = x[node, 1] - bx[b, 1]
        rz = x[node, 2] - bx[b, 2]
        out[b, 0] += f[0]
        out[b, 1] += f[1]
        out[b, 2] += f[2]
        out[b, 3] += ry * f[2] - rz * f[1]
        out[b, 4] += rz * f[0] - rx * f[2]
        out[b, 5] += rx * f[1] - ry * f[0]


@njit(cache=True)
def set_drives(t, D, x1, v1, a1, he_node, he_drive, dX, dV, dA, bx, bR):  # noqa: ANN001, ANN201
    """The held ends' prescribed state at ``t`` into (x1, v1, a1)."""
    drives_at(t, D[0], D[1], D[2], D[3], D[4], D[5], D[6], dX, dV, dA, bx, bR)
    for k in range(he_node.shape[0]):
        i = he_node[k]
        d = he_drive[k]
        for c in range(3):
            x1[i, c] = dX[d, c]
            v1[i, c] = dV[d, c]
            a1[i, c] = dA[d, c]


@njit(cache=True, nogil=True)
def _on_seabed(S, x, on_bed, count):  # noqa: ANN001, ANN201
    """Each node of a line with seabed contact on the seabed or not into ``on_bed``
    (within a millionth of its line's unstretched length of the plane, vertically: the
    single line's touchdown rule); with ``count``, how many changed."""
    no, eo, rest, ksb, sbn, sbo = S[0], S[1], S[4], S[24], S[22], S[23]
    changes = 0
    for l in range(no.shape[0] - 1):  # noqa: E741
        length = 0.0
        for k in range(eo[l], eo[l + 1]):
            length += rest[k]
        tol = 1e-6 * max(length, 1.0)
        for i in range(no[l], no[l + 1]):
            if ksb[i] <= 0.0:
                continue
            bed = (sbo[l] - sbn[0] * x[i, 0] - sbn[1] * x[i, 1]) / sbn[2]
            on = x[i, 2] - bed <= tol
            if count and on != on_bed[i]:
                changes += 1
            on_bed[i] = on
    return changes


@njit(cache=True, nogil=True)
def system_march(  # noqa: ANN201, PLR0913, PLR0915
    st_f,
    st_i,
    x0,
    v0,
    a0,
    F0,
    Fp0,
    x1,
    v1,
    a1,
    x_pred,
    past_x,
    past_t,
    frac,
    strain_prev,
    D,
    he_node,
    he_drive,
    he_line,
    he_end,
    he_body,
    dX,
    dV,
    dA,
    bx,
    bR,
    forces,
    ends_prev,
    ext_end,
    int_end,
    ext_el,
    ext_body,
    ext_z,
    body_f,
    watch,
    step,
    max_level,
    rescue_level,
    tension_step,
    am,
    af,
    beta,
    gamma,
    tol,
    max_it,
    budget,
    anchor,
    S,
    W,
    r,
    rp,
    dx,
    dp,
    Fp,
    lmin,
    eps_t,
):  # noqa: ANN001
    """Time steps from ``st_f[0]`` to the period boundary ``st_f[1]`` [s] (or
    ``budget`` accepted steps: :data:`ACCEPTED`). ``st_i`` = [level, clean steps, steps, Newton
    iterations, rejected steps, positions kept, seabed contact changes of nodes between
    accepted steps, accepted steps with an element changing between slack and taut] (the
    last two for :mod:`.step_check`). After each accepted step: the lines'
    end forces ``forces`` (L, 2, 3) and the bodies' ``body_f`` (B, 6); folded into the
    period's extremes ``ext_end`` (2, L, 2) of the end tensions (max, min) and their
    integral ``int_end``, ``ext_el`` (2, E) of the element tensions, ``ext_body``
    (2, B, 6) of the body forces and ``ext_z`` (N,) the nodes' highest elevation.
    The step control's tension test (a change over ``tension_step`` in one step) looks
    at the line ends ``watch`` (L, 2) marks (:func:`.system_timedomain.watched_ends`).
    ``st_f[2]`` holds the step tried when Newton failed."""
    held = S[21]
    no = S[0]
    n_lines = no.shape[0] - 1
    tension, strain, friction_force, contact = W[7], W[8], W[11], W[10]
    ksb = S[24]
    has_seabed = ksb.max() > 0.0
    m = tension.shape[0]
    corr = np.empty(3)
    # each node on the seabed at the last accepted step (the single line's rule: within
    # a millionth of its line's length of the plane, measured vertically)
    on_bed = np.zeros(x0.shape[0], dtype=np.bool_)
    if has_seabed:
        _on_seabed(S, x0, on_bed, False)
    accepted = 0
    while True:
        t = st_f[0]
        boundary = st_f[1]
        level = st_i[0]
        h = step / 2.0**level
        if boundary - t <= h * (1.0 + 1e-6):
            h = boundary - t
        tn = t + h
        npast = st_i[5]
        la, lb, lc = predict_positions(x0, v0, past_x, past_t, npast, t, tn, x_pred)
        set_drives(tn, D, x_pred, v1, a1, he_node, he_drive, dX, dV, dA, bx, bR)
        # spread each held end's correction along its line (the ends were extrapolated)
        for k in range(he_node.shape[0]):
            l = he_line[k]  # noqa: E741
            node = he_node[k]
            # x_pred of the node was overwritten: its extrapolation is recomputed
            if npast < 2:
                for c in range(3):
                    corr[c] = x_pred[node, c] - (x0[node, c] + (tn - t) * v0[node, c])
            else:
                for c in range(3):
                    corr[c] = x_pred[node, c] - (
                        past_x[0, node, c] * la + lb * past_x[1, node, c] + lc * x0[node, c]
                    )
            for i in range(no[l], no[l + 1]):
                if held[i]:
                    continue
                w = frac[i] if he_end[k] == 1 else 1.0 - frac[i]
                for c in range(3):
                    x_pred[i, c] += w * corr[c]
        for e in range(m):
            W[9][e] = strain_prev[e] > 0.0
        its, ok = system_step(
            h, x0, v0, a0, F0, Fp0, x1, v1, a1, x_pred, am, af, beta, gamma, tol, max_it,
            anchor, S, W, r, rp, dx, dp, Fp, lmin,
        )  # fmt: skip
        st_i[3] += its
        if not ok:
            st_i[4] += 1
            if level >= rescue_level:
                st_f[2] = h
                return FAILED
            st_i[0] = level + 1
            st_i[1] = 0
            continue
        switched = False
        for i in range(m):
            if (strain[i] > 0.0) != (strain_prev[i] > 0.0):
                switched = True
                break
        end_forces(S, W, x1, a1, he_node, forces)
        steep = False
        for l in range(n_lines):  # noqa: E741
            for end in range(2):
                if not watch[l, end]:
                    continue
                f = forces[l, end]
                te = math.sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2])
                if abs(te - ends_prev[l, end]) > tension_step:
                    steep = True
        if (switched or steep) and level < max_level:
            st_i[4] += 1
            st_i[0] = level + 1
            st_i[1] = 0
            continue
        # accept
        st_i[2] += 1
        if has_seabed:
            update_anchors(x1, friction_force, ksb, contact, anchor)
        accept_state(x0, v0, a0, F0, x1, v1, a1, W[0], ext_z, t, past_x, past_t, npast, st_i)
        for p in range(Fp0.shape[0]):
            for c in range(3):
                Fp0[p, c] = Fp[p, c]
        for i in range(m):
            strain_prev[i] = strain[i]
            ext_el[0, i] = max(ext_el[0, i], tension[i])
            ext_el[1, i] = min(ext_el[1, i], tension[i])
        for l in range(n_lines):  # noqa: E741
            for end in range(2):
                f = forces[l, end]
                te = math.sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2])
                ext_end[0, l, end] = max(ext_end[0, l, end], te)
                ext_end[1, l, end] = min(ext_end[1, l, end], te)
                int_end[l, end] += 0.5 * (ends_prev[l, end] + te) * h
                ends_prev[l, end] = te
        body_forces(S, x0, forces, he_line, he_end, he_body, bx, body_f)
        for b in range(body_f.shape[0]):
            for k in range(6):
                ext_body[0, b, k] = max(ext_body[0, b, k], body_f[b, k])
                ext_body[1, b, k] = min(ext_body[1, b, k], body_f[b, k])
        if has_seabed:
            st_i[6] += _on_seabed(S, x0, on_bed, True)
        if switched:
            st_i[7] += 1
        relax_level(st_i, switched or steep)
        at_boundary = abs(tn - boundary) <= eps_t
        st_f[0] = boundary if at_boundary else tn
        if at_boundary:
            return BOUNDARY
        accepted += 1
        if accepted >= budget:
            return ACCEPTED


@njit(cache=True, nogil=True)
def system_static(x, anchor, S, W, r, rp, dx, dp, Fp, tol, max_it, lmin):  # noqa: ANN001, ANN201
    """Newton on the discrete static equilibrium of the system (all lines and free
    points at rest, held nodes where ``x`` puts them), with the single line's small
    regularisation of slack nodes and its step limit (a quarter of the shortest element
    per iteration). Returns (iterations, largest residual [N], converged)."""
    held, is_junction = S[21], S[40]
    p_nodes, p_off = S[38], S[39]
    ea = S[5]
    n = x.shape[0]
    v = np.zeros_like(x)
    F = W[0]
    tension = W[7]
    reg = 1e-9 * (ea.max() / lmin)
    reach = 0.0
    for i in range(n):
        for a in range(3):
            reach = max(reach, abs(x[i, a]))
    floor = 1024.0 * 2.220446049250313e-16 * (reach + lmin)
    res = math.inf
    # friction as an active set, as the single line's statics: the trial forces decide
    # which contact nodes stick and which slide, Newton keeps those states, checked once
    # converged
    ksb = S[24]
    has_friction = ksb.shape[0] > 0 and ksb.max() > 0.0 and S[26].max() > 0.0
    fix_states = has_friction
    slip = W[12]
    for i in range(n):
        slip[i, 0] = 0
        slip[i, 1] = 0
    checks = 0
    it = 0
    while True:
        assemble_all(x, v, anchor, S, W)
        if fix_states:
            fix_states = False
            _static_friction_states(S, W)
            continue
        point_forces(S, x, v, Fp)
        res = 0.0
        for i in range(n):
            for a in range(3):
                r[i, a] = -F[i, a]
                if not held[i] and not is_junction[i]:
                    res = max(res, abs(F[i, a]))
        for p in range(rp.shape[0]):
            for a in range(3):
                tot = -Fp[p, a]
                for k in range(p_off[p], p_off[p + 1]):
                    tot += r[p_nodes[k], a]
                rp[p, a] = tot
                res = max(res, abs(tot))
        if res <= tol:
            if has_friction and checks < 20 and _friction_states(S, W, True):
                checks += 1
                continue
            return it, res, True
        if it >= max_it or not math.isfinite(res):
            return it, res, False
        it += 1
        reg_it = slack_regularisation(tension, reg, lmin)
        if not coupled_solve(S, W, 0.0, 1.0, 0.0, reg_it, r, rp, dx, dp):
            return it, res, False
        big = largest_correction(dx, n)
        if big <= floor:
            return it, res, True
        scale = quarter_element_scale(big, lmin)
        for i in range(n):
            if held[i]:
                continue
            for a in range(3):
                x[i, a] += scale * dx[i, a]
