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

import numpy as np
from numba import njit

from ..physics.seabed import touchdown_from_gap
from .alpha_step import alpha_step
from .assembly import (
    update_anchors,
)
from .end_support import seabed_support
from .excitation import motion_at
from .step_parts import accept_state, predict_positions, relax_level

#: :func:`march` return codes
REACHED_BOUNDARY, ACCEPTED_STEP, NEWTON_FAILED, STEP_BUDGET = 0, 1, 2, 3
#: the line parted at the accepted step (``st_i[7]`` the element); the winched element
#: left its allowed lengths (``st_f[9]`` the length paid out that was asked for)
PARTED, WINCH_LIMIT = 4, 5


@njit(cache=True, nogil=True)
def winch_set(paid, ctl, wini, per_length, s_ini, s, largs):  # noqa: ANN001, ANN201
    """Set the first element's unstretched length to its initial one plus ``paid``
    [m], with what it lumps on nodes 0 and 1 following its length (per unit unstretched
    length constant: mass, added mass, drag, transverse damping, weight, seabed
    stiffness; the seabed damping as the root of stiffness times inertia; the internal
    damping and bending terms with the length). ``ctl[6:9]`` = lower and upper bound of
    the length over its initial one, clamped end A (1/0); ``wini`` the initial values
    (rows: lengths of elements 0 and 1, internal damping, then per node 0/1: mass,
    normal and tangential added mass, drag normal, drag tangential, transverse damping,
    vertical force, seabed stiffness, seabed damping, bending); ``per_length`` the first
    element's lumps per metre (:attr:`DiscreteLine.first_per_length`). Returns False
    (nothing set) when the length would leave the bounds."""
    l_ini = wini[0, 0]
    l0 = l_ini + paid
    if not (ctl[6] * l_ini <= l0 <= ctl[7] * l_ini):
        return False
    half = 0.5 * paid
    rest = largs.rest_length
    rest[0] = l0
    for i in range(1, s.shape[0]):
        s[i] = s_ini[i] + paid
    largs.internal_damping[0] = wini[1, 0] * l0 / l_ini
    arrays = (
        largs.mass,
        largs.added_mass_normal,
        largs.added_mass_tangential,
        largs.drag_normal,
        largs.drag_tangential,
        largs.transverse_damping,
    )
    for k in range(6):
        arr = arrays[k]
        for j in range(2):
            arr[j] = wini[2 + k, j] + half * per_length[k]
    force = largs.force
    for j in range(2):
        force[j, 2] = wini[8, j] - half * per_length[6]
    if per_length[7] > 0.0:
        k_sb = largs.seabed_stiffness
        c_sb = largs.seabed_damping
        body = largs.body_added_mass
        for j in range(2):
            k_new = wini[9, j] + half * per_length[7]
            inertia0 = wini[2, j] + wini[3, j] + body[j]
            inertia = largs.mass[j] + largs.added_mass_normal[j] + body[j]
            if wini[9, j] > 0.0 and inertia0 > 0.0:
                c_sb[j] = wini[10, j] * math.sqrt(k_new * inertia / (wini[9, j] * inertia0))
            k_sb[j] = k_new
    bending = largs.bending
    if bending.shape[0] > 2 and wini[11, 1] > 0.0:
        bending[1] = wini[11, 1] * (l_ini + wini[0, 1]) / (l0 + wini[0, 1])
    if ctl[8] > 0.0:
        bending[0] = wini[11, 0] * l_ini / l0
    return True


@njit(cache=True, nogil=True)
def _attempt(  # noqa: ANN202, PLR0913
    t,
    h,
    x0,
    v0,
    a0,
    x1,
    v1,
    a1,
    F0,
    strain_prev,
    x_pred,
    past_x,
    past_t,
    npast,
    base,
    frac,
    motion,
    raw,
    end_x,
    corr,
    alpha_m,
    alpha_f,
    beta,
    gamma,
    tol,
    max_iterations,
    anchor,
    largs,
    wargs,
    sargs,
    ctl,
    wini,
    per_length,
    s_ini,
    s,
):  # noqa: ANN001
    """One step of length ``h`` from the accepted state at ``t``: the winch set to
    ``t + h`` (when one runs), the end motion, the predictor (quadratic through the
    last three accepted positions, the held ends moved with the prescribed motion,
    shared linearly along ``frac``) and :func:`alpha_step`. Returns (Newton
    iterations, converged, winch within its bounds)."""
    held = largs.held
    taut0 = wargs.taut0
    n = x0.shape[0]
    tn = t + h
    if ctl[3] != 0.0:
        end = min(tn, ctl[5])
        paid = ctl[3] * max(end - ctl[4], 0.0)
        if not winch_set(paid, ctl, wini, per_length, s_ini, s, largs):
            return 0, False, False
    motion_at(tn, *motion, raw)
    predict_positions(x0, v0, past_x, past_t, npast, t, tn, x_pred)
    for e in range(2):
        for c in range(3):
            end_x[e, c] = base[e, c] + raw[0, e, c]
    for i in range(strain_prev.shape[0]):
        taut0[i] = strain_prev[i] > 0.0
    if held[0]:
        for c in range(3):
            corr[c] = end_x[0, c] - x_pred[0, c]
        for i in range(n):
            for c in range(3):
                x_pred[i, c] += (1.0 - frac[i]) * corr[c]
        for c in range(3):
            x_pred[0, c] = end_x[0, c]
    if held[n - 1]:
        for c in range(3):
            corr[c] = end_x[1, c] - x_pred[n - 1, c]
        for i in range(n):
            for c in range(3):
                x_pred[i, c] += frac[i] * corr[c]
        for c in range(3):
            x_pred[n - 1, c] = end_x[1, c]
    # an interior held node (a pulley the line is fixed to) stays where it is
    for i in range(1, n - 1):
        if held[i]:
            for c in range(3):
                x_pred[i, c] = x0[i, c]
    its, ok = alpha_step(
        x0,
        v0,
        a0,
        F0,
        h,
        end_x,
        raw[1],
        raw[2],
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
    )
    return its, ok, True


@njit(cache=True, nogil=True)
def end_forces_of(x1, a1, largs, wargs, forces):  # noqa: ANN001, ANN201
    """Force of the line on the ends [N] (2, 3) into ``forces``: minus a held end
    node's support reaction (without the seabed's part where it rests on the seabed:
    :func:`.end_support.seabed_support`), the end element's pull on a free end node."""
    F = wargs.F
    M_d = wargs.M_d
    tension = wargs.tension
    held = largs.held
    n = x1.shape[0]
    m = tension.shape[0]
    ksb = largs.seabed_stiffness
    for e in range(2):
        node = 0 if e == 0 else n - 1
        if held[node]:
            for c in range(3):
                acc = F[node, c]
                for b in range(3):
                    acc += M_d[node, c, b] * a1[node, b]
                forces[e, c] = -acc
            if ksb.shape[0] > 0 and ksb[node] > 0.0:
                # on the seabed within the statics' touchdown rule (a millionth of the
                # line's length)
                length = 0.0
                for k in range(largs.rest_length.shape[0]):
                    length += largs.rest_length[k]
                seabed_support(
                    forces[e], x1[node], wargs.contact[node], wargs.friction_force[node],
                    ksb[node], largs.seabed_normal, largs.seabed_offset,
                    1e-6 * max(length, 1.0),
                )  # fmt: skip
        else:
            other = 1 if e == 0 else n - 2
            elem = 0 if e == 0 else m - 1
            ln = 0.0
            for c in range(3):
                ln += (x1[other, c] - x1[node, c]) ** 2
            ln = math.sqrt(ln)
            for c in range(3):
                forces[e, c] = tension[elem] * (x1[other, c] - x1[node, c]) / ln


@njit(cache=True, nogil=True)
def march(  # noqa: ANN201, PLR0913, PLR0915
    st_f,
    st_i,
    x0,
    v0,
    a0,
    x1,
    v1,
    a1,
    F0,
    strain_prev,
    x_pred,
    past_x,
    past_t,
    base,
    frac,
    motion,
    ends,
    forces,
    ext_element,
    ext_end,
    ext_touchdown,
    ext_z,
    s,
    touchdown_tolerance,
    step,
    max_level,
    rescue_level,
    tension_step,
    excited,
    eps_t,
    alpha_m,
    alpha_f,
    beta,
    gamma,
    tol,
    max_iterations,
    single,
    budget,
    anchor,
    largs,
    wargs,
    sargs,
    ctl,
    limit,
    due,
    tension_prev,
    wini,
    per_length,
    s_ini,
):  # noqa: ANN001
    """Time steps from ``st_f[0]`` towards the period boundary ``st_f[1]`` [s]: the
    step control of :func:`cablestudy.dynamics.timedomain.simulate`, compiled (the
    GIL released, so threads run cases in parallel).

    Each step is predicted and solved by :func:`_attempt`. A step whose Newton fails,
    or in which an element changes between slack and taut, or the excited end's tension
    changes by more than ``tension_step`` [N], is halved (the latter two up to
    ``max_level`` times, a Newton failure up to ``rescue_level``); after two clean
    steps the step doubles back. An accepted step updates the friction anchors, moves
    (x1, v1, a1) into (x0, v0, a0) and folds the step into the current period's
    statistics:
    ``st_f`` = [t, boundary, max, min, integral of the excited end's tension, largest
    line tension, last end tension, last line maximum, last touchdown, last step],
    ``ext_element`` (2, n) the elements' largest and smallest tension,
    ``ext_end`` (2, 2) the ends', ``ext_touchdown`` (2,) the touchdown point's range,
    ``ext_z`` (n,) the nodes' highest elevation;
    ``st_i`` = [level, clean steps, steps, Newton iterations, rejected steps, positions
    kept for the predictor, parted (1/0), the parted element, seabed contact changes
    (a node landing or lifting off between accepted steps: within the touchdown
    tolerance of the seabed or not), accepted steps in which an element changed between
    slack and taut] (the last two counted for :mod:`.step_check`).
    ``ends`` (2,) and ``forces`` (2, 3) hold the last accepted step's end tensions and
    forces of the line on the ends.

    Breaks and winches: ``ctl`` = [failure time (inf: none), break tolerance [-],
    breakable (1/0), winch speed [m/s], start, stop [s], winch length bounds (2),
    clamped end A]. Before the line has parted, a step that takes an element's tension
    ``tension`` past its ``limit`` [N] is shortened to the instant it reaches it
    (regula falsi, Illinois, on the step length until within the break tolerance of
    the limit; ``tension_prev`` holds the tensions at the step's start); a step lands
    on the failure time, where the most loaded of the elements ``due`` parts. The
    element is flagged broken and :data:`PARTED` returned after the step (the caller
    restarts the integrator from the parted state). A winch sets the first element's
    length before every step (:func:`winch_set`, initial values ``wini``,
    ``per_length``, ``s_ini``).

    Returns :data:`REACHED_BOUNDARY` on the boundary (``t`` set exactly to it),
    :data:`ACCEPTED_STEP` after each accepted step when ``single``,
    :data:`STEP_BUDGET` after ``budget`` accepted steps, :data:`NEWTON_FAILED` when
    Newton failed at the smallest step (``st_f[9]`` the step tried), :data:`PARTED`,
    :data:`WINCH_LIMIT`.
    """
    F = wargs.F
    tension = wargs.tension
    strain = wargs.strain
    contact = wargs.contact
    friction_force = wargs.friction_force
    seabed_normal = largs.seabed_normal
    seabed_offset = largs.seabed_offset
    seabed_stiffness = largs.seabed_stiffness
    broken = largs.broken
    has_seabed = seabed_stiffness.max() > 0.0 if seabed_stiffness.shape[0] else False
    n = x0.shape[0]
    m = tension.shape[0]
    raw = np.empty((3, 2, 3))
    end_x = np.empty((2, 3))
    corr = np.empty(3)
    gap = np.empty(n)
    # each node on the seabed (within the touchdown tolerance) at the last accepted step
    on_bed = np.zeros(n, dtype=np.bool_)
    if has_seabed:
        nz = seabed_normal[2]
        for i in range(n):
            bed = (seabed_offset - seabed_normal[0] * x0[i, 0] - seabed_normal[1] * x0[i, 1]) / nz
            on_bed[i] = x0[i, 2] - bed <= touchdown_tolerance
    accepted = 0
    break_at = ctl[0]
    while True:
        t = st_f[0]
        boundary = st_f[1]
        level = st_i[0]
        intact = st_i[6] == 0
        h = step / 2.0**level
        if boundary - t <= h * (1.0 + 1e-6):
            h = boundary - t
        if intact and break_at > t and break_at - t <= h * (1.0 + 1e-6):
            h = break_at - t  # land on the failure time
        npast = st_i[5]
        its, ok, wound = _attempt(
            t, h, x0, v0, a0, x1, v1, a1, F0, strain_prev, x_pred, past_x, past_t, npast,
            base, frac, motion, raw, end_x, corr, alpha_m, alpha_f, beta, gamma, tol,
            max_iterations, anchor, largs, wargs, sargs, ctl, wini, per_length, s_ini, s,
        )  # fmt: skip
        if not wound:
            st_f[9] = ctl[3] * max(min(t + h, ctl[5]) - ctl[4], 0.0)
            return WINCH_LIMIT
        st_i[3] += its
        if not ok:
            st_i[4] += 1
            if level >= rescue_level:
                st_f[9] = h
                return NEWTON_FAILED
            st_i[0] = level + 1
            st_i[1] = 0
            continue
        switched = False
        for i in range(m):
            if (strain[i] > 0.0) != (strain_prev[i] > 0.0) and not broken[i]:
                switched = True
                break
        end_forces_of(x1, a1, largs, wargs, forces)
        fx = forces[excited]
        t_end = math.sqrt(fx[0] * fx[0] + fx[1] * fx[1] + fx[2] * fx[2])
        steep = abs(t_end - st_f[6]) > tension_step
        if (switched or steep) and level < max_level:
            st_i[4] += 1
            st_i[0] = level + 1
            st_i[1] = 0
            continue
        part = -1
        if intact and ctl[2] > 0.0:
            first = -1
            theta_min = math.inf
            for i in range(m):
                if tension[i] > limit[i]:
                    theta = (limit[i] - tension_prev[i]) / (tension[i] - tension_prev[i])
                    if theta < theta_min:
                        theta_min = theta
                        first = i
            if first >= 0:
                # regula falsi (Illinois) on the step length for the crossing element
                e = first
                lo, g_lo = 0.0, tension_prev[e] - limit[e]
                hi, g_hi = h, tension[e] - limit[e]
                tol_t = ctl[1] * limit[e]
                side = 0
                found = False
                for _ in range(60):
                    h_try = lo + (hi - lo) * (-g_lo) / (g_hi - g_lo)
                    if not (lo < h_try < hi):
                        h_try = 0.5 * (lo + hi)
                    its, ok, wound = _attempt(
                        t, h_try, x0, v0, a0, x1, v1, a1, F0, strain_prev, x_pred, past_x,
                        past_t, npast, base, frac, motion, raw, end_x, corr, alpha_m,
                        alpha_f, beta, gamma, tol, max_iterations, anchor, largs, wargs,
                        sargs, ctl, wini, per_length, s_ini, s,
                    )  # fmt: skip
                    st_i[3] += its
                    if not ok:  # Newton failed inside the bracket: bisect towards t
                        hi = 0.5 * (lo + hi)
                        continue
                    g = tension[e] - limit[e]
                    if abs(g) <= tol_t:
                        h = h_try
                        found = True
                        break
                    if hi - lo <= 1e-12 * step:
                        break
                    if g > 0.0:
                        hi, g_hi = h_try, g
                        if side == 1:
                            g_lo *= 0.5
                        side = 1
                    else:
                        lo, g_lo = h_try, g
                        if side == -1:
                            g_hi *= 0.5
                        side = -1
                if not found:  # to the bracket's end past the limit
                    its, ok, wound = _attempt(
                        t, hi, x0, v0, a0, x1, v1, a1, F0, strain_prev, x_pred, past_x,
                        past_t, npast, base, frac, motion, raw, end_x, corr, alpha_m,
                        alpha_f, beta, gamma, tol, max_iterations, anchor, largs, wargs,
                        sargs, ctl, wini, per_length, s_ini, s,
                    )  # fmt: skip
                    st_i[3] += its
                    h = hi
                    if not ok:
                        st_f[9] = h
                        return NEWTON_FAILED
                part = e
                end_forces_of(x1, a1, largs, wargs, forces)
                fx = forces[excited]
                t_end = math.sqrt(fx[0] * fx[0] + fx[1] * fx[1] + fx[2] * fx[2])
            elif abs(t + h - break_at) <= eps_t:
                # the failure time: the most loaded element due to fail then (tension
                # over its limit, or tension where no limit is finite)
                any_limit = False
                for i in range(m):
                    if due[i] and math.isfinite(limit[i]):
                        any_limit = True
                best = -math.inf
                for i in range(m):
                    if not due[i] or (any_limit and not math.isfinite(limit[i])):
                        continue
                    load = tension[i] / limit[i] if any_limit else tension[i]
                    if load > best:
                        best = load
                        part = i
        tn = t + h
        # accept
        st_i[2] += 1
        if has_seabed:
            update_anchors(x1, friction_force, seabed_stiffness, contact, anchor)
        accept_state(x0, v0, a0, F0, x1, v1, a1, F, ext_z, t, past_x, past_t, npast, st_i)
        t = tn
        for i in range(m):
            strain_prev[i] = strain[i]
            tension_prev[i] = tension[i]
        line_max = -math.inf
        for i in range(m):
            line_max = max(line_max, tension[i])
            ext_element[0, i] = max(ext_element[0, i], tension[i])
            ext_element[1, i] = min(ext_element[1, i], tension[i])
        for e in range(2):
            fe = forces[e]
            ends[e] = math.sqrt(fe[0] * fe[0] + fe[1] * fe[1] + fe[2] * fe[2])
            line_max = max(line_max, ends[e])
            ext_end[0, e] = max(ext_end[0, e], ends[e])
            ext_end[1, e] = min(ext_end[1, e], ends[e])
        td = math.nan
        if has_seabed:
            nz = seabed_normal[2]
            for i in range(n):
                bed = (
                    seabed_offset - seabed_normal[0] * x0[i, 0] - seabed_normal[1] * x0[i, 1]
                ) / nz
                gap[i] = x0[i, 2] - bed
                on = gap[i] <= touchdown_tolerance
                if on != on_bed[i]:
                    st_i[8] += 1
                    on_bed[i] = on
            td = touchdown_from_gap(s, gap, touchdown_tolerance)
            if not math.isnan(td):
                ext_touchdown[0] = td if math.isnan(ext_touchdown[0]) else min(ext_touchdown[0], td)
                ext_touchdown[1] = td if math.isnan(ext_touchdown[1]) else max(ext_touchdown[1], td)
        st_f[2] = max(st_f[2], t_end)
        st_f[3] = min(st_f[3], t_end)
        st_f[4] += 0.5 * (st_f[6] + t_end) * h
        st_f[5] = max(st_f[5], line_max)
        st_f[6] = t_end
        st_f[7] = line_max
        st_f[8] = td
        st_f[9] = h
        if switched:
            st_i[9] += 1
        relax_level(st_i, switched or steep)
        accepted += 1
        at_boundary = abs(t - boundary) <= eps_t
        st_f[0] = boundary if at_boundary else t
        if part >= 0:
            broken[part] = True
            st_i[6] = 1
            st_i[7] = part
            return PARTED
        if at_boundary:
            return REACHED_BOUNDARY
        if single:
            return ACCEPTED_STEP
        if accepted >= budget:
            return STEP_BUDGET
