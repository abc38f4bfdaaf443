"""Compiled kernels of the system time domain: rigid-body kinematics of the driven
points, and the coupled Newton solve of all lines and free points.

The lines' nodes are packed one line after another (line ``l`` owns nodes
``no[l]:no[l+1]`` and elements ``eo[l]:eo[l+1]``); each line keeps its own
block-banded Jacobian (:func:`cablestudy.dynamics.model.assemble` on its slice). A
line end on a free point (a junction, a clump, a buoy) is a free node shared with the
other lines' ends on that point: its three unknowns are the point's. The Newton
correction is a bordered solve (Schur complement on the junction unknowns): per line,
the band with its junction rows set aside is factored once, solved for the residual
``y`` and for the (at most six) junction columns ``Z``; the point's dense matrix

    S = J_PP - sum_lines J_PI Z,    g = r_P - sum_lines J_PI y

(3 x 3 blocks per point: the lines' end-node blocks, the point's own mass, added mass
and drag) is solved for the points' corrections ``dp``, and each line's interior
correction is ``y - Z dp``. No matrix over all nodes is ever formed.

Pure: arrays in, arrays out (SI units), compiled with numba.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .assembly import assemble_lines, band_factor, band_solve
from .excitation import motion_at

# ------------------------------------------------------------------ kinematics


@njit(cache=True)
def _mm3(a, b, out):  # noqa: ANN001, ANN202
    for i in range(3):
        for j in range(3):
            acc = 0.0
            for k in range(3):
                acc += a[i, k] * b[k, j]
            out[i, j] = acc


@njit(cache=True)
def _triple(a, b, c, out, tmp):  # noqa: ANN001, ANN202
    _mm3(a, b, tmp)
    _mm3(tmp, c, out)


@njit(cache=True)
def _elementary(axis, angle, m0, m1, m2):  # noqa: ANN001, ANN202
    """Rotation about ``axis`` (0 x, 1 y, 2 z) by ``angle`` and its first and second
    derivatives with respect to the angle, into m0, m1, m2 (3, 3)."""
    c = math.cos(angle)
    s = math.sin(angle)
    for i in range(3):
        for j in range(3):
            m0[i, j] = 0.0
            m1[i, j] = 0.0
            m2[i, j] = 0.0
    i = (axis + 1) % 3
    j = (axis + 2) % 3
    m0[axis, axis] = 1.0
    # R[i, i] = c, R[i, j] = -s, R[j, i] = s, R[j, j] = c (right-handed about axis)
    m0[i, i], m0[i, j], m0[j, i], m0[j, j] = c, -s, s, c
    m1[i, i], m1[i, j], m1[j, i], m1[j, j] = -s, -c, c, -s
    m2[i, i], m2[i, j], m2[j, i], m2[j, j] = -c, s, -s, -c


@njit(cache=True)
def rotation_motion(angle, rate, accel, R, Rd, Rdd):  # noqa: ANN001, ANN201
    """R = Rz(yaw) Ry(pitch) Rx(roll) at ``angle`` (roll, pitch, yaw) [rad], and its
    first and second time derivatives for angle rates ``rate`` [rad/s] and
    accelerations ``accel`` [rad/s^2] (exact, by the product and chain rules), into
    R, Rd, Rdd (3, 3)."""
    E = np.zeros((3, 3, 3, 3))  # [axis, derivative order, 3, 3]
    for ax in range(3):
        _elementary(ax, angle[ax], E[ax, 0], E[ax, 1], E[ax, 2])
    out = np.empty((3, 3))
    tmp = np.empty((3, 3))
    for i in range(3):
        for j in range(3):
            R[i, j] = 0.0
            Rd[i, j] = 0.0
            Rdd[i, j] = 0.0
    # R = Z Y X: term with derivative orders (dz, dy, dx) and its factor
    for dz in range(3):
        for dy in range(3 - dz):
            for dx in range(3 - dz - dy):
                _triple(E[2, dz], E[1, dy], E[0, dx], out, tmp)
                order = dz + dy + dx
                if order == 0:
                    for i in range(3):
                        for j in range(3):
                            R[i, j] += out[i, j]
                    continue
                if order == 1:
                    k = 2 if dz == 1 else (1 if dy == 1 else 0)
                    f1 = rate[k]
                    f2 = accel[k]
                    for i in range(3):
                        for j in range(3):
                            Rd[i, j] += f1 * out[i, j]
                            Rdd[i, j] += f2 * out[i, j]
                    continue
                # second order: one angle twice, or two angles once each (twice over)
                if dz == 2:
                    f = rate[2] * rate[2]
                elif dy == 2:
                    f = rate[1] * rate[1]
                elif dx == 2:
                    f = rate[0] * rate[0]
                else:
                    f = 2.0
                    if dz == 1:
                        f *= rate[2]
                    if dy == 1:
                        f *= rate[1]
                    if dx == 1:
                        f *= rate[0]
                for i in range(3):
                    for j in range(3):
                        Rdd[i, j] += f * out[i, j]


@njit(cache=True)
def drives_at(  # noqa: ANN201
    t, margs, body_base, body_R0, d_body, d_slot, d_offset, d_static, dx, dv, da, bx, bR
):  # noqa: ANN001
    """Position, velocity, acceleration [m, m/s, m/s^2] of every driven point at ``t``
    into dx, dv, da (D, 3), and each body's reference point ``bx`` (B, 3) and rotation
    ``bR`` (B, 3, 3). A body point (``d_body`` >= 0, offset p = ``d_offset`` in the
    body frame) is at X + R p with the body's exact rotation R, written as its static
    position ``d_static`` plus the reference point's displacement plus (R - R0) p (R0
    the static rotation ``body_R0``), so that a body that only translates moves its
    points by exactly its displacement. A point with a motion of its own
    (``d_slot`` >= 0) adds it."""
    n_body = body_base.shape[0]
    n_slot = 2 * n_body
    for d in range(d_slot.shape[0]):
        n_slot = max(n_slot, d_slot[d] + 1)
    out = np.zeros((3, max(n_slot, 1), 3))
    motion_at(t, *margs, out)
    R = np.empty((3, 3))
    Rd = np.empty((3, 3))
    Rdd = np.empty((3, 3))
    ang = np.empty(3)
    Rds = np.empty((n_body, 3, 3))
    Rdds = np.empty((n_body, 3, 3))
    for b in range(n_body):
        for k in range(3):
            ang[k] = body_base[b, 3 + k] + out[0, 2 * b + 1, k]
        rotation_motion(ang, out[1, 2 * b + 1], out[2, 2 * b + 1], R, Rd, Rdd)
        for i in range(3):
            bx[b, i] = body_base[b, i] + out[0, 2 * b, i]
            for j in range(3):
                bR[b, i, j] = R[i, j]
                Rds[b, i, j] = Rd[i, j]
                Rdds[b, i, j] = Rdd[i, j]
    for d in range(d_body.shape[0]):
        b = d_body[d]
        for i in range(3):
            dx[d, i] = d_static[d, i]
            dv[d, i] = 0.0
            da[d, i] = 0.0
            if b >= 0:
                p_now = 0.0
                p_static = 0.0
                pv = 0.0
                pa = 0.0
                for j in range(3):
                    p_now += bR[b, i, j] * d_offset[d, j]
                    p_static += body_R0[b, i, j] * d_offset[d, j]
                    pv += Rds[b, i, j] * d_offset[d, j]
                    pa += Rdds[b, i, j] * d_offset[d, j]
                dx[d, i] += out[0, 2 * b, i]
                dx[d, i] += p_now - p_static
                dv[d, i] += out[1, 2 * b, i]
                dv[d, i] += pv
                da[d, i] += out[2, 2 * b, i]
                da[d, i] += pa
            s = d_slot[d]
            if s >= 0:
                dx[d, i] += out[0, s, i]
                dv[d, i] += out[1, s, i]
                da[d, i] += out[2, s, i]


# ------------------------------------------------------------------ the coupled solve


@njit(cache=True)
def assemble_all(x, v, anchor, S, W):  # noqa: ANN001, ANN201
    """The line model's forces and tangents of every line of the packed system ``S``
    into the work ``W`` (:func:`cablestudy.dynamics.system_model.pack`), all lines in
    one call (:func:`cablestudy.dynamics.assembly.assemble_lines`)."""
    assemble_lines(
        S[0], S[1], S[2], S[3], x, v, anchor,
        S[4], S[5], S[6], S[7], S[8], S[9], S[10], S[11], S[12], S[13], S[14], S[15], S[16],
        S[17], S[18], S[19], S[20], S[21], S[22], S[23], S[24], S[25], S[26], S[27], S[28],
        S[29], S[30], S[31], S[32],
        W[0], W[1], W[2], W[3], W[4], W[5], W[6], W[7], W[8], W[9], W[10], W[11], W[12],
        W[13], W[24], W[25],
    )  # fmt: skip


@njit(cache=True)
def coupled_solve(S, W, cm, kf, cf, reg, r, rp, dx, dp):  # noqa: ANN001, ANN201, PLR0912, PLR0915
    """Newton correction of the system: J = cm M + kf (K + cf C) (+ ``reg`` on the
    diagonal) per line from the assembled blocks in ``W``, the free points' own mass
    and drag added; residuals ``r`` (N, 3) of the nodes and ``rp`` (P, 3) of the points
    (each the sum of its end nodes' and its own). Corrections into ``dx`` (N, 3, held
    nodes zero, junction nodes their point's) and ``dp`` (P, 3). Returns False when a
    factorisation fails. A line end's coupling to its interior, ``J_PI``, is the
    blocks to its (at most ``reach``) neighbours within the band, gathered once per
    end into ``W[26]`` (2, 2, 3, 3): block ``[end, d - 1]`` couples the end node to the
    node ``d`` along the line."""
    no, eo, o2 = S[0], S[1], S[2]
    bends = S[33]
    held = S[21]
    end_point = S[34]
    p_mass = S[35]
    p_drag = S[37]
    p_nodes, p_off = S[38], S[39]
    cz, cvel = S[13], S[14]
    K_d, K_o, K_o2, C_d, C_o, M_d = W[1], W[2], W[3], W[4], W[5], W[6]
    J_d, J_o, J_o2, band, Z, Smat, g, elim = W[14], W[15], W[16], W[17], W[18], W[19], W[20], W[21]
    v1 = W[22]
    Cb = W[26]
    rel = W[27]
    n_lines = no.shape[0] - 1
    n_p = rp.shape[0]
    n_all = dx.shape[0]
    dx_flat = dx.reshape(3 * n_all)
    Z_flat = Z.reshape(Z.size)
    for i in range(3 * n_p):
        g[i] = rp[i // 3, i % 3]
        for j in range(3 * n_p):
            Smat[i, j] = 0.0
    # the points' own inertia and drag tangent
    for p in range(n_p):
        node = p_nodes[p_off[p]]
        cd = p_drag[p]
        sr = 0.0
        if cd > 0.0:
            for a in range(3):
                cur = 0.0
                if cz.shape[0] > 0:
                    cur = np.interp(W[23][node, 2], cz, cvel[:, a])
                rel[a] = cur - v1[node, a]
            sr = math.sqrt(rel[0] ** 2 + rel[1] ** 2 + rel[2] ** 2)
        for a in range(3):
            Smat[3 * p + a, 3 * p + a] += cm * p_mass[p] + reg
            if cd > 0.0:
                for b in range(3):
                    c = cd * rel[a] * rel[b] / sr if sr > 0.0 else 0.0
                    if a == b:
                        c += cd * sr
                    Smat[3 * p + a, 3 * p + b] += kf * cf * c
    for l in range(n_lines):  # noqa: E741
        n0, n1 = no[l], no[l + 1]
        e0, e1 = eo[l], eo[l + 1]
        q0, q1 = o2[l], o2[l + 1]
        n = n1 - n0
        reach = 2 if bends[l] else 1
        for i in range(n0, n1):
            elim[i - n0] = (
                held[i]
                or (i == n0 and end_point[l, 0] >= 0)
                or (i == n1 - 1 and end_point[l, 1] >= 0)
            )
            for a in range(3):
                for b in range(3):
                    J_d[i, a, b] = cm * M_d[i, a, b] + kf * (K_d[i, a, b] + cf * C_d[i, a, b])
                J_d[i, a, a] += reg
        for e in range(e0, e1):
            for a in range(3):
                for b in range(3):
                    J_o[e, a, b] = kf * (K_o[e, a, b] + cf * C_o[e, a, b])
        for q in range(q0, q1):
            for a in range(3):
                for b in range(3):
                    J_o2[q, a, b] = kf * K_o2[q, a, b]
        jo2 = J_o2[q0:q1] if bends[l] else J_o2[q0:q0]
        if not band_factor(J_d[n0:n1], J_o[e0:e1], jo2, elim[:n], band, reach):
            return False
        for i in range(n):
            for a in range(3):
                dx[n0 + i, a] = 0.0 if elim[i] else r[n0 + i, a]
        band_solve(band, reach, dx_flat, 3 * n0, 3 * n)  # y, in dx
        if end_point[l, 0] < 0 and end_point[l, 1] < 0:
            continue
        # each junction end: its coupling blocks, its columns Z[end, c] = J_II^-1 J_I,end e_c
        for end in range(2):
            p = end_point[l, end]
            if p < 0:
                continue
            node = 0 if end == 0 else n - 1
            for a in range(3):
                for b in range(3):
                    Smat[3 * p + a, 3 * p + b] += J_d[n0 + node, a, b]
            for d in range(1, 3):
                j = node + d if end == 0 else node - d
                lo = node if end == 0 else j
                inside = d <= reach and 0 <= j < n
                for a in range(3):
                    for c in range(3):
                        val = 0.0
                        if inside:
                            if d == 1:
                                val = J_o[e0 + lo, a, c] if end == 0 else J_o[e0 + lo, c, a]
                            else:
                                val = J_o2[q0 + lo, a, c] if end == 0 else J_o2[q0 + lo, c, a]
                        Cb[end, d - 1, a, c] = val
            for c in range(3):
                for i in range(n0, n1):
                    for a in range(3):
                        Z[end, c, i, a] = 0.0
                for d in range(1, reach + 1):
                    j = node + d if end == 0 else node - d
                    if j < 0 or j >= n or elim[j]:
                        continue
                    for a in range(3):
                        # J[i, node] column c = J[node, i]^T entry (c, a)
                        Z[end, c, n0 + j, a] = Cb[end, d - 1, c, a]
                band_solve(band, reach, Z_flat, 3 * ((end * 3 + c) * n_all + n0), 3 * n)
        # S -= J_PI Z, g -= J_PI y; direct end-to-end coupling within the band
        for ei in range(2):
            p = end_point[l, ei]
            if p < 0:
                continue
            node_i = 0 if ei == 0 else n - 1
            lo, hi = max(node_i - 2, 0), min(node_i + 3, n)  # J_PI is zero beyond
            for a in range(3):
                acc = 0.0
                for i in range(lo, hi):
                    d = abs(i - node_i)
                    if elim[i] or d == 0 or d > reach:
                        continue
                    for b in range(3):
                        acc += Cb[ei, d - 1, a, b] * dx[n0 + i, b]
                g[3 * p + a] -= acc
            for ej in range(2):
                q = end_point[l, ej]
                if q < 0:
                    continue
                node_j = 0 if ej == 0 else n - 1
                dj = abs(node_j - node_i)
                for a in range(3):
                    for c in range(3):
                        acc = 0.0
                        if ej != ei and 0 < dj <= reach:
                            acc -= Cb[ei, dj - 1, a, c]
                        for i in range(lo, hi):
                            d = abs(i - node_i)
                            if elim[i] or d == 0 or d > reach:
                                continue
                            for b in range(3):
                                acc += Cb[ei, d - 1, a, b] * Z[ej, c, n0 + i, b]
                        Smat[3 * p + a, 3 * q + c] -= acc
    if n_p > 0:
        sol = np.linalg.solve(Smat, g)
        for p in range(n_p):
            for a in range(3):
                dp[p, a] = sol[3 * p + a]
    for l in range(n_lines):  # noqa: E741
        n0, n1 = no[l], no[l + 1]
        for end in range(2):
            p = end_point[l, end]
            if p < 0:
                continue
            node = n0 if end == 0 else n1 - 1
            for i in range(n0, n1):
                if i == node:
                    continue
                for a in range(3):
                    for c in range(3):
                        dx[i, a] -= Z[end, c, i, a] * dp[p, c]
        for end in range(2):
            p = end_point[l, end]
            if p >= 0:
                node = n0 if end == 0 else n1 - 1
                for a in range(3):
                    dx[node, a] = dp[p, a]
        for i in range(n0, n1):
            if held[i]:
                for a in range(3):
                    dx[i, a] = 0.0
    return True


@njit(cache=True)
def point_forces(S, x, v, Fp):  # noqa: ANN001, ANN201
    """Each free point's own out-of-balance force [N] (P, 3) into ``Fp``: minus its
    constant force (weight, buoyancy, applied) plus its drag on the relative velocity."""
    p_force, p_drag = S[36], S[37]
    p_nodes, p_off = S[38], S[39]
    cz, cvel = S[13], S[14]
    for p in range(Fp.shape[0]):
        node = p_nodes[p_off[p]]
        for a in range(3):
            Fp[p, a] = -p_force[p, a]
        cd = p_drag[p]
        if cd > 0.0:
            rel = np.zeros(3)
            for a in range(3):
                cur = 0.0
                if cz.shape[0] > 0:
                    cur = np.interp(x[node, 2], cz, cvel[:, a])
                rel[a] = cur - v[node, a]
            sr = math.sqrt(rel[0] ** 2 + rel[1] ** 2 + rel[2] ** 2)
            for a in range(3):
                Fp[p, a] -= cd * sr * rel[a]
