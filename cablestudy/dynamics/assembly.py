"""The discretised line's forces and their tangents (:mod:`.model` gives the
formulation): the compiled assembly of the element tensions, bending, drag, added mass
and seabed contact with friction (:func:`assemble`, :func:`evaluate` on a
:class:`Workspace`), the banded solve of the tangent, and the stick and slip states of
the nodes on the seabed.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numba import njit

from .discrete_line import DiscreteLine
from .line_offsets import line_count, line_part, node_range

# ------------------------------------------------------------------ compiled kernels


@njit(cache=True)
def _add_bend_blocks(K_d, K_o, K_o2, kb, nodes, G, count, n0, e0, q0):  # noqa: ANN001, ANN202
    """Add the Gauss-Newton blocks ``kb G_p G_q`` of one curvature term over the
    ``count`` nodes in ``nodes`` (increasing, consecutive; counted within the line
    whose first node, element and two-off block are ``n0``, ``e0``, ``q0``) with
    3 x 3 blocks ``G``."""
    for p in range(count):
        for q in range(p, count):
            i = nodes[p]
            j = nodes[q]
            for a in range(3):
                for b in range(3):
                    acc = 0.0
                    for c in range(3):
                        acc += G[p, a, c] * G[q, c, b]
                    acc *= kb
                    if j == i:
                        K_d[n0 + i, a, b] += acc
                    elif j == i + 1:
                        K_o[e0 + i, a, b] += acc
                    else:
                        K_o2[q0 + i, a, b] += acc


# inlined (numba IR): the caller's row view law_params[e] then costs no reference count
# pair per element (a call took the view as an argument: 3 % of a chain's time step)
@njit(cache=True, inline="always")
def axial_law(code, params, knots, start, count, ea, eps):  # noqa: ANN001, ANN201
    """Tension [N] and tangent dT/d(strain) [N] of an element's axial law at strain
    ``eps`` > 0 (the kernels' copy of :mod:`cablestudy.physics.axial`): 0 linear
    ``ea eps``; 1 polynomial ``sum c_i eps^i``; 2 steel wire ``k (eps - d (1 -
    exp(-eps/d)))``; 3 a table's monotone cubic Hermite curve, continued linearly."""
    if code == 0:
        return ea * eps, ea
    if code == 1:
        t = 0.0
        dt = 0.0
        for i in range(4, -1, -1):
            t = (t + params[i]) * eps
            dt = dt * eps + (i + 1) * params[i]
        return t, dt
    if code == 2:
        k = params[0]
        d = params[1]
        return k * (eps + d * math.expm1(-eps / d)), -k * math.expm1(-eps / d)
    lo = start
    hi = start + count - 1
    if eps >= knots[hi, 0]:
        return knots[hi, 1] + knots[hi, 2] * (eps - knots[hi, 0]), knots[hi, 2]
    j = lo
    while j < hi - 1 and knots[j + 1, 0] <= eps:
        j += 1
    h = knots[j + 1, 0] - knots[j, 0]
    u = (eps - knots[j, 0]) / h
    y0, y1 = knots[j, 1], knots[j + 1, 1]
    m0, m1 = knots[j, 2], knots[j + 1, 2]
    h00 = 2 * u**3 - 3 * u**2 + 1
    h10 = u**3 - 2 * u**2 + u
    h01 = -2 * u**3 + 3 * u**2
    h11 = u**3 - u**2
    t = h00 * y0 + h10 * h * m0 + h01 * y1 + h11 * h * m1
    dt = ((6 * u**2 - 6 * u) * y0 + (6 * u - 6 * u**2) * y1) / h + (
        (3 * u**2 - 4 * u + 1) * m0 + (3 * u**2 - 2 * u) * m1
    )
    return t, dt


@njit(cache=True, nogil=True)
def assemble(x, v, anchor, largs, wargs):  # noqa: ANN001, ANN201
    """Nodal out-of-balance force ``F = f_internal - f_external`` [N] (n + 1, 3) at
    positions ``x`` [m] and velocities ``v`` [m/s] (friction anchors ``anchor`` [m]),
    so that ``M a + F = 0``; its tangents: stiffness ``K = dF/dx`` and damping
    ``C = dF/dv`` as diagonal blocks (n + 1, 3, 3), the blocks coupling node e to
    e + 1 (n, 3, 3) and (stiffness, bending only) node e to e + 2 (n - 1, 3, 3), the
    lower blocks being the transposes; the mass blocks ``M_d`` (n + 1, 3, 3) [kg];
    element tension [N] and strain [-] (n,); the seabed's normal force [N] (n + 1,)
    and friction force [N] (n + 1, 3) on each node.

    The derivatives of drag and added mass through the node tangent, of the current
    through z, of the friction through the normal force and of bending beyond its
    Gauss-Newton part are left out of the tangents (quasi-Newton). An element flagged
    in ``taut0`` (taut at the start of the time step) keeps its axial stiffness in
    ``K`` even where this iterate makes it slack: otherwise a predictor a few
    micrometres short would drop the axial stiffness of a taut element, and Newton
    would take a huge step along the line's soft (inextensional) modes.

    The line's arrays come in ``largs`` (:class:`.discrete_line.LineArrays`), the
    results go to ``wargs`` (:class:`WorkArrays`). One line: :func:`assemble_lines`
    (which holds the formulation) given no offsets (``None``) and the line's own
    ``has_drag``, ``clamp_direction`` (2, 3), ``seabed_offset`` and ``friction`` (2,)."""
    n_el = x.shape[0] - 1
    # largs[:], wargs[:]: the named tuples as plain ones, which numba joins into the arguments
    uel, lel = np.empty((n_el, 3)), np.empty(n_el)
    assemble_lines(None, None, None, None, x, v, anchor, *largs[:], *wargs[:], uel, lel)


# fmt: off
@njit(cache=True, nogil=True)
def assemble_lines(  # noqa: ANN201, PLR0912, PLR0915
    no, eo, o2, ko, x, v, anchor, rest_length, axial_stiffness, internal_damping, force,
    drag_normal, drag_tangential, added_mass_normal, added_mass_tangential, mass,
    current_z, current_velocity, has_drag, bending, clamp_direction, transverse_damping,
    body_added_mass, body_drag, held, seabed_normal, seabed_offset, seabed_stiffness,
    seabed_damping, friction, law_code, law_params, law_knots, law_start, law_count,
    broken, F, K_d, K_o, K_o2, C_d, C_o, M_d, tension, strain, taut0, contact,
    friction_force, slip_state, trial, uel, lel,
):  # noqa: ANN001
    # fmt: on
    """:func:`assemble` of lines packed one after another in flat arrays, all in one
    call (no allocation per line: a system's Newton iteration assembles every line at
    once). Line ``l`` owns nodes ``no[l]:no[l + 1]``, elements ``eo[l]:eo[l + 1]``,
    two-off blocks ``o2[l]:o2[l + 1]`` and law knots ``ko[l]:ko[l + 1]`` (its
    ``law_start`` counted from ``ko[l]``); per line ``has_drag`` (L,),
    ``clamp_direction`` (L, 2, 3), ``seabed_offset`` (L,), ``friction`` (L, 2); the
    rest per node or element as :func:`assemble`'s. ``uel`` (E, 3), ``lel`` (E,):
    scratch (the elements' unit vectors and lengths). With ``no``, ``eo``, ``o2``,
    ``ko`` None: one line, its ``has_drag``, ``clamp_direction``, ``seabed_offset``,
    ``friction`` its own (:func:`assemble`)."""
    u = np.empty(3)
    G = np.zeros((3, 3, 3))
    nodes = np.zeros(3, dtype=np.int64)
    tan = np.empty(3)
    rel = np.empty(3)
    un = np.empty(3)
    nrm = seabed_normal
    for l in range(line_count(no)):  # noqa: E741
        # the line's offsets and its own values, read once (:mod:`.line_offsets`: none
        # for one line); a row view such as friction[l] passed on per contact node
        # would cost a reference count per call
        n0, n, e0, q0, q1, k0, drag, clamp, offset_l, mu_along, mu_across = line_part(
            no, eo, o2, ko, l, x.shape[0], K_o2.shape[0], has_drag, clamp_direction,
            seabed_offset, friction,
        )  # fmt: skip
        n_el = n - 1
        for i in range(n0, n0 + n):
            contact[i] = 0.0
            for a in range(3):
                F[i, a] = -force[i, a]
                friction_force[i, a] = 0.0
                for b in range(3):
                    K_d[i, a, b] = 0.0
                    C_d[i, a, b] = 0.0
                    M_d[i, a, b] = 0.0
        for e in range(q0, q1):
            for a in range(3):
                for b in range(3):
                    K_o2[e, a, b] = 0.0
        for el in range(n_el):
            e = e0 + el
            i0 = n0 + el
            length2 = 0.0
            for a in range(3):
                u[a] = x[i0 + 1, a] - x[i0, a]
                length2 += u[a] * u[a]
            length = math.sqrt(length2)
            rate = 0.0
            for a in range(3):
                u[a] /= length
                uel[e, a] = u[a]
                rate += u[a] * (v[i0 + 1, a] - v[i0, a])
            lel[e] = length
            l0 = rest_length[e]
            eps = length / l0 - 1.0
            strain[e] = eps
            if broken[e]:
                tension[e] = 0.0
                for a in range(3):
                    for b in range(3):
                        K_o[e, a, b] = 0.0
                        C_o[e, a, b] = 0.0
                continue
            t = 0.0
            kax = 0.0
            cax = 0.0
            if eps > 0.0:
                t_el, k_el = axial_law(
                    law_code[e],
                    law_params[e],
                    law_knots,
                    k0 + law_start[e],
                    law_count[e],
                    axial_stiffness[e],
                    eps,
                )
                t = t_el + internal_damping[e] * rate / l0
                if t > 0.0:
                    kax = k_el / l0
                    cax = internal_damping[e] / l0
                else:
                    t = 0.0
            if taut0[e] and kax == 0.0:
                kax = axial_stiffness[e] / l0
            tension[e] = t
            kg = t / length
            for a in range(3):
                F[i0 + 1, a] += t * u[a]
                F[i0, a] -= t * u[a]
                for b in range(3):
                    k = (kax - kg) * u[a] * u[b]
                    if a == b:
                        k += kg
                    c = cax * u[a] * u[b]
                    K_d[i0, a, b] += k
                    K_d[i0 + 1, a, b] += k
                    K_o[e, a, b] = -k
                    C_d[i0, a, b] += c
                    C_d[i0 + 1, a, b] += c
                    C_o[e, a, b] = -c
        # bending: curvature terms at interior nodes and clamped ends
        for i in range(n):
            kb = bending[n0 + i]
            if kb == 0.0:
                continue
            if 0 < i < n - 1:
                ea_ = e0 + i - 1
                eb_ = e0 + i
                if broken[ea_] or broken[eb_]:
                    continue  # no moment across a parted element
                la = lel[ea_]
                lb = lel[eb_]
                # r = u_b - u_a; E = kb/2 |r|^2; G_p = d r / d x_p
                for a in range(3):
                    for b in range(3):
                        pa = (1.0 if a == b else 0.0) - uel[ea_, a] * uel[ea_, b]
                        pb = (1.0 if a == b else 0.0) - uel[eb_, a] * uel[eb_, b]
                        G[0, a, b] = pa / la
                        G[1, a, b] = -pa / la - pb / lb
                        G[2, a, b] = pb / lb
                nodes[0] = i - 1
                nodes[1] = i
                nodes[2] = i + 1
                count = 3
                for a in range(3):
                    r_a = uel[eb_, a] - uel[ea_, a]
                    u[a] = r_a
            else:
                end = 0 if i == 0 else 1
                e = 0 if i == 0 else n_el - 1
                if broken[e0 + e]:
                    continue
                le = lel[e0 + e]
                # r = u_e - d; G for the element's first and second node
                for a in range(3):
                    for b in range(3):
                        p = (1.0 if a == b else 0.0) - uel[e0 + e, a] * uel[e0 + e, b]
                        G[0, a, b] = -p / le
                        G[1, a, b] = p / le
                    u[a] = uel[e0 + e, a] - clamp[end, a]
                nodes[0] = e
                nodes[1] = e + 1
                count = 2
            # force: kb G_p^T r (G symmetric)
            for p in range(count):
                node = n0 + nodes[p]
                for a in range(3):
                    acc = 0.0
                    for c in range(3):
                        acc += G[p, a, c] * u[c]
                    F[node, a] += kb * acc
            _add_bend_blocks(K_d, K_o, K_o2, kb, nodes, G, count, n0, e0, q0)
        sliding = mu_along > 0.0 or mu_across > 0.0
        for j in range(n):
            i = n0 + j
            lo = j - 1 if j > 0 else 0
            hi = j + 1 if j < n - 1 else n - 1
            if 0 < j < n - 1:
                # a node beside a parted element is the end of its part
                if broken[e0 + j - 1]:
                    lo = j
                elif broken[e0 + j]:
                    hi = j
            norm2 = 0.0
            for a in range(3):
                tan[a] = x[n0 + hi, a] - x[n0 + lo, a]
                norm2 += tan[a] * tan[a]
            norm = math.sqrt(norm2)
            for a in range(3):
                tan[a] /= norm
            mn = added_mass_normal[i]
            mt = added_mass_tangential[i]
            for a in range(3):
                for b in range(3):
                    M_d[i, a, b] = (mt - mn) * tan[a] * tan[b]
                M_d[i, a, a] += mass[i] + mn + body_added_mass[i]
            ctr = transverse_damping[i]
            if ctr > 0.0:
                vt = v[i, 0] * tan[0] + v[i, 1] * tan[1] + v[i, 2] * tan[2]
                for a in range(3):
                    F[i, a] += ctr * (v[i, a] - vt * tan[a])
                    for b in range(3):
                        C_d[i, a, b] += ctr * ((1.0 if a == b else 0.0) - tan[a] * tan[b])
            if drag:
                for a in range(3):
                    if current_z.shape[0] > 0:
                        rel[a] = np.interp(x[i, 2], current_z, current_velocity[:, a]) - v[i, a]
                    else:
                        rel[a] = -v[i, a]
                rt = rel[0] * tan[0] + rel[1] * tan[1] + rel[2] * tan[2]
                sn2 = 0.0
                for a in range(3):
                    un[a] = rel[a] - rt * tan[a]
                    sn2 += un[a] * un[a]
                sn = math.sqrt(sn2)
                cn = drag_normal[i]
                ct = drag_tangential[i]
                st = abs(rt)
                for a in range(3):
                    F[i, a] -= cn * sn * un[a] + ct * st * rt * tan[a]
                    for b in range(3):
                        c = 2.0 * ct * st * tan[a] * tan[b] - cn * sn * tan[a] * tan[b]
                        if sn > 0.0:
                            c += cn * un[a] * un[b] / sn
                        if a == b:
                            c += cn * sn
                        C_d[i, a, b] += c
                cb = body_drag[i]
                if cb > 0.0:
                    sr = math.sqrt(rel[0] * rel[0] + rel[1] * rel[1] + rel[2] * rel[2])
                    for a in range(3):
                        F[i, a] -= cb * sr * rel[a]
                        for b in range(3):
                            c = 0.0
                            if sr > 0.0:
                                c = cb * rel[a] * rel[b] / sr
                            if a == b:
                                c += cb * sr
                            C_d[i, a, b] += c
            ks = seabed_stiffness[i]
            if ks > 0.0:
                gap = nrm[0] * x[i, 0] + nrm[1] * x[i, 1] + nrm[2] * x[i, 2] - offset_l
                # contact: by the law (state 0: touching where gap <= 0, pushing only), or
                # held fixed during a time step's Newton iterations (1: touching, the
                # spring and damper linear, 2: not), see contact_changed
                cstate = slip_state[i, 2] if slip_state.shape[1] > 2 else 0
                if ((cstate == 0 or cstate == 3) and gap <= 0.0) or cstate == 1:
                    vn = nrm[0] * v[i, 0] + nrm[1] * v[i, 1] + nrm[2] * v[i, 2]
                    cs = seabed_damping[i] if cstate != 3 else 0.0
                    fn = -ks * gap - cs * vn
                    if fn < 0.0 and cstate != 1:
                        fn = 0.0
                        cs = 0.0
                    contact[i] = max(fn, 0.0)
                    for a in range(3):
                        F[i, a] -= fn * nrm[a]
                        for b in range(3):
                            K_d[i, a, b] += ks * nrm[a] * nrm[b]
                            C_d[i, a, b] += cs * nrm[a] * nrm[b]
                    if fn > 0.0 and sliding:
                        _friction(
                            i,
                            x,
                            anchor,
                            tan,
                            nrm,
                            ks,
                            cs,
                            fn,
                            mu_along,
                            mu_across,
                            F,
                            K_d,
                            C_d,
                            friction_force,
                            slip_state,
                            trial,
                        )


@njit(cache=True)
def _friction(  # noqa: ANN202
    i,  # noqa: ANN001
    x,  # noqa: ANN001
    anchor,  # noqa: ANN001
    tan,  # noqa: ANN001
    nrm,  # noqa: ANN001
    kt,  # noqa: ANN001
    cs,  # noqa: ANN001
    fn,  # noqa: ANN001
    mu_along,  # noqa: ANN001
    mu_across,  # noqa: ANN001
    F,  # noqa: ANN001
    K_d,  # noqa: ANN001
    C_d,  # noqa: ANN001
    friction_force,  # noqa: ANN001
    slip_state,  # noqa: ANN001
    trial,  # noqa: ANN001
):
    """Elastic-plastic Coulomb friction at contact node ``i``: along the line (the node
    tangent projected on the seabed) and across it, each a spring of stiffness ``kt``
    [N/m] to the node's anchor, capped at ``mu N`` (``mu`` the line's coefficient
    ``mu_along`` or ``mu_across``).

    ``slip_state[i, k]`` (k = 0 along, 1 across) chooses how: 0 by the trial spring
    force (stick below mu N, else slide at mu N); 2 stick (the spring, uncapped);
    +1 / -1 slide at +- mu N, with the tangent of mu N through the normal force
    (``mu k_n`` and ``mu c_n`` coupling the normal motion). The time step fixes the
    states during its Newton iterations, so that they see a smooth force, and checks
    them when it has converged (:func:`cablestudy.dynamics.alpha_step.alpha_step`).
    The trial spring force is written to ``trial[i, k]`` [N]."""
    ea = np.empty(3)
    el = np.empty(3)
    tn = tan[0] * nrm[0] + tan[1] * nrm[1] + tan[2] * nrm[2]
    s2 = 0.0
    for a in range(3):
        ea[a] = tan[a] - tn * nrm[a]
        s2 += ea[a] * ea[a]
    if s2 < 1e-24:  # tangent normal to the seabed: any direction in the plane
        ea[0], ea[1], ea[2] = nrm[1], -nrm[0], 0.0
        s2 = ea[0] * ea[0] + ea[1] * ea[1]
        if s2 < 1e-24:
            ea[0], ea[1], ea[2] = 1.0, 0.0, 0.0
            s2 = 1.0
    sn = math.sqrt(s2)
    for a in range(3):
        ea[a] /= sn
    el[0] = nrm[1] * ea[2] - nrm[2] * ea[1]
    el[1] = nrm[2] * ea[0] - nrm[0] * ea[2]
    el[2] = nrm[0] * ea[1] - nrm[1] * ea[0]
    da = 0.0
    dl = 0.0
    for a in range(3):
        d = x[i, a] - anchor[i, a]
        da += d * ea[a]
        dl += d * el[a]
    for k in range(2):
        mu = mu_along if k == 0 else mu_across
        if mu <= 0.0:
            continue
        e = ea if k == 0 else el
        f = -kt * (da if k == 0 else dl)
        trial[i, k] = f
        cap = mu * fn
        state = slip_state[i, k]
        stick = True
        sign = 0.0
        if state == 1 or state == -1:
            sign = float(state)
        elif state == 0:
            if f > cap:
                sign = 1.0
            elif f < -cap:
                sign = -1.0
        if sign != 0.0:
            f = sign * cap
            stick = False
        for a in range(3):
            F[i, a] -= f * e[a]
            friction_force[i, a] += f * e[a]
            if stick:
                for b in range(3):
                    K_d[i, a, b] += kt * e[a] * e[b]
            elif state != 0:
                # d(-f e)/dx with f = sign mu N(x, v): N = -k_n gap - c_n v_n
                for b in range(3):
                    K_d[i, a, b] += sign * mu * kt * e[a] * nrm[b]
                    C_d[i, a, b] += sign * mu * cs * e[a] * nrm[b]


@njit(cache=True)
def update_anchors(x, friction_force, seabed_stiffness, contact, anchor):  # noqa: ANN001, ANN201
    """Friction anchors after an accepted state: where the node touches the seabed, the
    point at which the friction spring carries the friction force just computed
    (``anchor = x + f / k_t``); elsewhere the node itself (no friction stored)."""
    for i in range(x.shape[0]):
        kt = seabed_stiffness[i]
        for a in range(3):
            if contact[i] > 0.0 and kt > 0.0:
                anchor[i, a] = x[i, a] + friction_force[i, a] / kt
            else:
                anchor[i, a] = x[i, a]


@njit(cache=True)
def band_factor(J_d, J_o, J_o2, elim, band, reach):  # noqa: ANN001, ANN201
    """Build and factor (LU without pivoting) in the work array ``band`` (3m, 17) the
    scalar band of a block-banded matrix with 3 x 3 blocks: diagonal blocks ``J_d``
    (m, 3, 3), upper blocks one node off ``J_o`` (m - 1, 3, 3) and, for ``reach`` 2,
    two nodes off ``J_o2`` (m - 2, 3, 3), the lower blocks being their transposes (half
    bandwidth 3 reach + 2). Rows of ``elim`` nodes are replaced by the identity and
    their columns left out (their unknowns are zero, or found apart: a system's
    junctions). The systems here are dominated by their diagonal (mass, or stiffness
    plus regularisation). Returns False on a zero or non-finite pivot."""
    m = J_d.shape[0]
    N = 3 * m
    bw = 3 * reach + 2
    W = 2 * bw + 1
    for r_ in range(N):
        for c in range(W):
            band[r_, c] = 0.0
    for i in range(m):
        for a in range(3):
            row = 3 * i + a
            if elim[i]:
                band[row, bw] = 1.0
                continue
            for b in range(3):
                band[row, bw + b - a] += J_d[i, a, b]
                if i + 1 < m and not elim[i + 1]:
                    band[row, bw + 3 + b - a] += J_o[i, a, b]
                if i >= 1 and not elim[i - 1]:
                    band[row, bw - 3 + b - a] += J_o[i - 1, b, a]
                if reach == 2:
                    if i + 2 < m and not elim[i + 2]:
                        band[row, bw + 6 + b - a] += J_o2[i, a, b]
                    if i >= 2 and not elim[i - 2]:
                        band[row, bw - 6 + b - a] += J_o2[i - 2, b, a]
    for k in range(N):
        piv = band[k, bw]
        if not (abs(piv) > 0.0) or not math.isfinite(piv):
            return False
        top = min(k + bw + 1, N)
        for r_ in range(k + 1, top):
            lf = band[r_, bw + k - r_]
            if lf == 0.0:
                continue
            lf /= piv
            band[r_, bw + k - r_] = lf
            for c in range(k + 1, top):
                band[r_, bw + c - r_] -= lf * band[k, bw + c - k]
    return True


@njit(cache=True)
def band_solve(band, reach, f, off, N):  # noqa: ANN001, ANN201
    """Solve with the factored band for the ``N`` unknowns ``f[off:off + N]`` of a flat
    array (a line's slice of the packed nodes' components), in place."""
    bw = 3 * reach + 2
    for k in range(N):
        fk = f[off + k]
        if fk == 0.0:
            continue
        top = min(k + bw + 1, N)
        for r_ in range(k + 1, top):
            f[off + r_] -= band[r_, bw + k - r_] * fk
    for k in range(N - 1, -1, -1):
        acc = f[off + k]
        top = min(k + bw + 1, N)
        for c in range(k + 1, top):
            acc -= band[k, bw + c - k] * f[off + c]
        f[off + k] = acc / band[k, bw]


@njit(cache=True)
def solve_banded(J_d, J_o, J_o2, held, rhs, out, band):  # noqa: ANN001, ANN201
    """Solve ``J dx = rhs`` into ``out`` (m, 3) for the block-banded ``J`` of
    :func:`band_factor` (reach 2 where ``J_o2`` has blocks), rows of ``held`` nodes
    replaced by the identity with a zero right side. Returns False on a zero or
    non-finite pivot."""
    m = J_d.shape[0]
    reach = 2 if J_o2.shape[0] > 0 else 1
    if not band_factor(J_d, J_o, J_o2, held, band, reach):
        return False
    for i in range(m):
        for a in range(3):
            out[i, a] = 0.0 if held[i] else rhs[i, a]
    band_solve(band, reach, out.reshape(3 * m), 0, 3 * m)
    return True


class WorkArrays(NamedTuple):
    """The arrays :func:`assemble` fills, as the compiled kernels take them
    (:meth:`Workspace.assemble_args`; read by name, ``wargs.F``, or passed on,
    ``*wargs``)."""

    F: np.ndarray
    K_d: np.ndarray
    K_o: np.ndarray
    K_o2: np.ndarray
    C_d: np.ndarray
    C_o: np.ndarray
    M_d: np.ndarray
    tension: np.ndarray
    strain: np.ndarray
    taut0: np.ndarray
    contact: np.ndarray
    friction_force: np.ndarray
    slip_state: np.ndarray
    trial: np.ndarray


class Workspace:
    """Scratch arrays of the kernels for a line of ``n`` elements (allocated once per
    run, reused every step), and the friction anchors (state carried between steps)."""

    def __init__(self, n_elements: int) -> None:
        n = n_elements + 1
        self.F = np.zeros((n, 3))
        self.K_d = np.zeros((n, 3, 3))
        self.K_o = np.zeros((n - 1, 3, 3))
        self.K_o2 = np.zeros((max(n - 2, 0), 3, 3))
        self.C_d = np.zeros((n, 3, 3))
        self.C_o = np.zeros((n - 1, 3, 3))
        self.M_d = np.zeros((n, 3, 3))
        self.tension = np.zeros(n - 1)
        self.strain = np.zeros(n - 1)
        self.taut0 = np.zeros(n - 1, dtype=np.bool_)
        self.contact = np.zeros(n)
        self.friction = np.zeros((n, 3))
        self.anchor = np.zeros((n, 3))
        # stick/slip along and across the line, and the contact state (assemble)
        self.slip_state = np.zeros((n, 3), dtype=np.int64)
        self.trial = np.zeros((n, 2))
        self.J_d = np.zeros((n, 3, 3))
        self.J_o = np.zeros((n - 1, 3, 3))
        self.J_o2 = np.zeros((max(n - 2, 0), 3, 3))
        self.r = np.zeros((n, 3))
        self.dx = np.zeros((n, 3))
        self.band = np.zeros((3 * n, 17))

    def assemble_args(self) -> WorkArrays:
        return WorkArrays(
            self.F,
            self.K_d,
            self.K_o,
            self.K_o2,
            self.C_d,
            self.C_o,
            self.M_d,
            self.tension,
            self.strain,
            self.taut0,
            self.contact,
            self.friction,
            self.slip_state,
            self.trial,
        )

    def solver_args(self, line: DiscreteLine) -> tuple:
        """Jacobian blocks, residual, correction and band work array (the two-off
        blocks empty unless the line bends)."""
        J_o2 = self.J_o2 if line.has_bending else self.J_o2[:0]
        return (self.J_d, self.J_o, J_o2, self.r, self.dx, self.band)


def evaluate(
    line: DiscreteLine,
    x: np.ndarray,
    v: np.ndarray,
    work: Workspace | None = None,
    anchor: np.ndarray | None = None,
) -> Workspace:
    """Forces, tangents, masses and tensions at state (``x`` [m], ``v`` [m/s]), with
    friction anchors ``anchor`` [m] (default: the workspace's)."""
    work = work or Workspace(line.n_elements)
    if anchor is not None:
        work.anchor[:] = anchor
    assemble(
        np.ascontiguousarray(x, dtype=float),
        np.ascontiguousarray(v, dtype=float),
        work.anchor,
        line.kernel_args(),
        work.assemble_args(),
    )
    return work


@njit(cache=True)
def _trial_states(slip_state, trial, contact, friction, keep=False):  # noqa: ANN001, ANN202
    """Stick/slip state of every contact node from its trial spring force: stick (2)
    within mu N, else slide (+-1) with the force's sign; 0 off the seabed. With
    ``keep``, a contact node that has a state keeps it."""
    for i in range(slip_state.shape[0]):
        for k in range(2):
            if keep and contact[i] > 0.0 and slip_state[i, k] != 0:
                continue
            slip_state[i, k] = 0
            if contact[i] > 0.0 and friction[k] > 0.0:
                cap = friction[k] * contact[i]
                if trial[i, k] > cap:
                    slip_state[i, k] = 1
                elif trial[i, k] < -cap:
                    slip_state[i, k] = -1
                else:
                    slip_state[i, k] = 2


@njit(cache=True)
def contact_states(
    x, v, seabed_normal, seabed_offset, seabed_stiffness, seabed_damping, slip_state, fix, count
):  # noqa: ANN001, ANN201, E501
    """Contact states from the contact law at (``x``, ``v``): touching (1) where the
    node is at or below the seabed plane and the spring and damper push, else not (2).
    With ``fix`` False, set them all (the start of a time step); else update them after
    Newton converged with states held fixed and return whether any changed: a node whose
    state has changed ``MAX_CONTACT_FLIPS`` times in the step (it sits on the plane,
    where neither state is consistent) goes back to the law itself (0), which the
    Newton iterations then meet with their landing clip. One line:
    :func:`contact_states_lines` given no offsets (``None``)."""
    return contact_states_lines(
        None, x, v, seabed_normal, seabed_offset, seabed_stiffness, seabed_damping,
        slip_state, fix, count,
    )  # fmt: skip


@njit(cache=True)
def contact_states_lines(
    no, x, v, seabed_normal, seabed_offset, seabed_stiffness, seabed_damping, slip_state, fix, count
):  # noqa: ANN001, ANN201, E501
    """:func:`contact_states` of lines packed one after another (line ``l`` the nodes
    ``no[l]:no[l + 1]``, its seabed plane's offset ``seabed_offset[l]``), in one call;
    ``no`` None: one line, ``seabed_offset`` its own (compiled apart, offsets 0:
    :mod:`.line_offsets`)."""
    changed = False
    for l in range(line_count(no)):  # noqa: E741
        i0, i1, offset_l = node_range(no, l, x.shape[0], seabed_offset)
        for i in range(i0, i1):
            ks = seabed_stiffness[i]
            if ks <= 0.0 or slip_state[i, 2] == 3 and fix:
                continue
            gap = -offset_l
            vn = 0.0
            for a in range(3):
                gap += seabed_normal[a] * x[i, a]
                vn += seabed_normal[a] * v[i, a]
            touching = gap <= 0.0 and -ks * gap - seabed_damping[i] * vn > 0.0
            want = 1 if touching else 2
            if not fix:
                slip_state[i, 2] = want
                count[i] = 0
            elif slip_state[i, 2] != want and count[i] < MAX_CONTACT_FLIPS:
                count[i] += 1
                slip_state[i, 2] = want if count[i] < MAX_CONTACT_FLIPS else 1
                changed = True
    return changed


#: contact state changes of a node within one time step before the law takes over
MAX_CONTACT_FLIPS = 2


@njit(cache=True)
def states_changed(slip_state, trial, contact, friction):  # noqa: ANN001, ANN201
    """Update fixed stick/slip states from a converged state; True if any changed.

    A sticking node whose spring force exceeds mu N slides (with the spring's sign); a
    sliding node whose spring force is back within mu N, or points the other way,
    sticks. Nodes that lost contact, or gained it (state 0), take the trial rule."""
    changed = False
    for i in range(slip_state.shape[0]):
        for k in range(2):
            state = slip_state[i, k]
            if friction[k] <= 0.0:
                continue
            if contact[i] <= 0.0:
                if state != 0:
                    slip_state[i, k] = 0
                continue
            cap = friction[k] * contact[i] * (1.0 + 1e-9)
            f = trial[i, k]
            if state == 0:
                continue
            if state == 2 and abs(f) > cap:
                slip_state[i, k] = 1 if f > 0.0 else -1
                changed = True
            elif (state == 1 or state == -1) and state * f < cap * (1.0 - 2e-9):
                slip_state[i, k] = 2
                changed = True
    return changed
