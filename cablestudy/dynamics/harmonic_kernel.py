"""The compiled drag iteration of :mod:`.harmonic_cases`: per case the drag fitted
over the sample points of a period (:func:`drag_fit_samples`), the banded solve of the
rows that change (:func:`band_solve_rows`), Anderson mixing of the iteration
(:func:`_mixed`) and the loop over cases (:func:`_cases_kernel`).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .drag_lean import lean_from_entries, sampled_lean
from .elliptic_fit import still_water_means
from .frequency_model import (
    FIT_REGULARISATION,
    is_planar,
    planar_drag_fit,
    still_water,
)


@njit(cache=True)
def drag_fit_samples(  # noqa: PLR0913
    vr,
    vi,
    current,
    tangent,
    c_n,
    c_t,
    c_b,
    tangent_d,
    cos,
    sin,
    exact,
    W0,
    W1,
    W2,
    F0,
    F1,
    F2,
    kind,
    lean,
    out,
):  # noqa: ANN001, ANN201, PLR0913
    """``_drag_fit`` (tests/drag_fit_reference.py) given the lean (the mean
    Jacobian, :mod:`.drag_lean`: ``drag_linearisation(line, v, samples, J, exact)``)
    with ``cos``, ``sin`` (samples,) given and the same operations in the same order,
    laid out for the compiler: the drag at every node and phase first, in a loop
    without running sums (which it can vectorise), then the sums over the phases node
    by node; ``W0`` .. ``F2`` (n, samples), ``kind`` (n,) int and ``lean`` (n, 3, 3)
    are work arrays. A node whose motion, tangent and current have no y component
    skips the y terms (zeros: the values are the same); with ``exact`` (and no body:
    ``c_b`` (n,) zero) it takes
    :func:`~cablestudy.dynamics.frequency_model.planar_drag_fit` (whose y row, decoupled
    from the plane, keeps the tangent ``tangent_d``), and with ``exact`` any other node
    without current the exact period means (:func:`.elliptic_fit.still_water_means`),
    as ``_drag_fit`` does. Every fit but the planar one leans on the node's mean
    Jacobian over its motion (:mod:`.drag_lean` says why: not the small-motion tangent,
    zero without current, with which a 3-D line's drag iteration circled), exact with
    the still-water means, over the phases with the sums."""
    n = current.shape[0]
    samples = cos.shape[0]
    for i in range(n):
        if exact and c_b[i] == 0.0 and is_planar(vr, vi, tangent, current, i):
            kind[i] = 2
            planar_drag_fit(vr, vi, tangent, current, c_n, c_t, tangent_d, i, out)
            continue
        if exact and still_water(current, i):
            kind[i] = 2
            g, h, j = still_water_means(
                vr[i, 0],
                vr[i, 1],
                vr[i, 2],
                vi[i, 0],
                vi[i, 1],
                vi[i, 2],
                tangent[i, 0],
                tangent[i, 1],
                tangent[i, 2],
                c_n[i],
                c_t[i],
                c_b[i],
            )
            # the lean of the fit: the mean Jacobian J (what the small-motion tangent,
            # zero without current, misses; see the docstring)
            lean_from_entries(j, lean, i)
            fit_from_sums(g, h, 1, lean, i, out)
            continue
        t0, t1, t2 = tangent[i, 0], tangent[i, 1], tangent[i, 2]
        cn, ct, cb = c_n[i], c_t[i], c_b[i]
        u0, u1, u2 = current[i, 0], current[i, 1], current[i, 2]
        a0, a1, a2 = vr[i, 0], vr[i, 1], vr[i, 2]
        b0, b1, b2 = vi[i, 0], vi[i, 1], vi[i, 2]
        if a1 == 0.0 and b1 == 0.0 and t1 == 0.0 and u1 == 0.0:
            # motion, tangent and current in the x-z plane: every y term below is a
            # zero, and leaving them out changes no value (at most the sign of a zero)
            for k in range(samples):
                c, s = cos[k], sin[k]
                w0 = -(a0 * c - b0 * s)
                w2 = -(a2 * c - b2 * s)
                r0, r2 = u0 + w0, u2 + w2
                wt = r0 * t0 + r2 * t2
                n0, n2 = r0 - wt * t0, r2 - wt * t2
                sn = np.sqrt(n0 * n0 + n2 * n2)
                st = abs(wt) * wt * ct
                sr = cb * np.sqrt(r0 * r0 + r2 * r2)
                W0[i, k], W2[i, k] = w0, w2
                F0[i, k] = cn * sn * n0 + st * t0 + sr * r0
                F2[i, k] = cn * sn * n2 + st * t2 + sr * r2
            kind[i] = 1
            continue
        kind[i] = 0
        for k in range(samples):
            c, s = cos[k], sin[k]
            # Re((a + i b) e^{i th}) = a cos - b sin; the relative velocity is -v
            w0 = -(a0 * c - b0 * s)
            w1 = -(a1 * c - b1 * s)
            w2 = -(a2 * c - b2 * s)
            r0, r1, r2 = u0 + w0, u1 + w1, u2 + w2
            wt = r0 * t0 + r1 * t1 + r2 * t2
            n0, n1, n2 = r0 - wt * t0, r1 - wt * t1, r2 - wt * t2
            sn = np.sqrt(n0 * n0 + n1 * n1 + n2 * n2)
            st = abs(wt) * wt * ct
            sr = cb * np.sqrt(r0 * r0 + r1 * r1 + r2 * r2)
            W0[i, k], W1[i, k], W2[i, k] = w0, w1, w2
            F0[i, k] = cn * sn * n0 + st * t0 + sr * r0
            F1[i, k] = cn * sn * n1 + st * t1 + sr * r1
            F2[i, k] = cn * sn * n2 + st * t2 + sr * r2
    for i in range(n):
        if kind[i] == 2:
            continue
        fm0 = fm1 = fm2 = 0.0
        g00 = g01 = g02 = g11 = g12 = g22 = 0.0
        h00 = h01 = h02 = h10 = h11 = h12 = h20 = h21 = h22 = 0.0
        if kind[i] == 1:
            for k in range(samples):
                fm0 += F0[i, k]
                fm2 += F2[i, k]
            fm0 /= samples
            fm2 /= samples
            for k in range(samples):
                w0, w2 = W0[i, k], W2[i, k]
                f0, f2 = F0[i, k] - fm0, F2[i, k] - fm2
                g00 += w0 * w0
                g02 += w0 * w2
                g22 += w2 * w2
                h00 += f0 * w0
                h02 += f0 * w2
                h20 += f2 * w0
                h22 += f2 * w2
        else:
            for k in range(samples):
                fm0 += F0[i, k]
                fm1 += F1[i, k]
                fm2 += F2[i, k]
            fm0 /= samples
            fm1 /= samples
            fm2 /= samples
            for k in range(samples):
                w0, w1, w2 = W0[i, k], W1[i, k], W2[i, k]
                f0, f1, f2 = F0[i, k] - fm0, F1[i, k] - fm1, F2[i, k] - fm2
                g00 += w0 * w0
                g01 += w0 * w1
                g02 += w0 * w2
                g11 += w1 * w1
                g12 += w1 * w2
                g22 += w2 * w2
                h00 += f0 * w0
                h01 += f0 * w1
                h02 += f0 * w2
                h10 += f1 * w0
                h11 += f1 * w1
                h12 += f1 * w2
                h20 += f2 * w0
                h21 += f2 * w1
                h22 += f2 * w2
        sampled_lean(W0, W1, W2, kind[i] == 1, current, tangent, c_n, c_t, c_b, i, lean)
        fit_from_sums(
            (g00, g01, g02, g11, g12, g22),
            (h00, h01, h02, h10, h11, h12, h20, h21, h22),
            samples,
            lean,
            i,
            out,
        )


@njit(cache=True, inline="always")
def fit_from_sums(g, h, samples, lean, i, out):  # noqa: ANN001, ANN201, PLR0913
    """The 3x3 drag fit ``out[i]`` of node ``i`` from its sums over the ``samples``
    phases: ``g`` of ``w w^T`` (entries 00, 01, 02, 11, 12, 22) and ``h`` of ``(f -
    f_mean) w^T`` (row by row, 00 .. 22), ``w`` the relative velocity and ``f`` the drag.
    The least-squares fit ``D G = H`` (``G``, ``H`` the means) is regularised towards
    ``lean[i]`` (the small-motion tangent, or the mean Jacobian where the caller has it
    in closed form): ``D (G + eps I) = H + eps lean[i]`` with
    ``eps`` :data:`.frequency_model.FIT_REGULARISATION` times the trace of ``G``, and
    solved by cofactors (``G`` symmetric positive definite); a node at rest (zero
    trace) takes ``lean[i]``. Shared by the single line's fit (:func:`drag_fit_samples`)
    and the system's (:func:`.system_fd_fit.fit_node`); inlined into each, so that it
    is compiled with its caller's floating-point flags."""
    g00, g01, g02, g11, g12, g22 = g
    h00, h01, h02, h10, h11, h12, h20, h21, h22 = h
    trace = (g00 + g11 + g22) / samples
    if not trace > 0.0:  # a node at rest: the lean
        for a in range(3):
            for b in range(3):
                out[i, a, b] = lean[i, a, b]
        return
    eps = FIT_REGULARISATION * trace
    G00, G01, G02 = g00 / samples + eps, g01 / samples, g02 / samples
    G11, G12, G22 = g11 / samples + eps, g12 / samples, g22 / samples + eps
    H00 = h00 / samples + eps * lean[i, 0, 0]
    H01 = h01 / samples + eps * lean[i, 0, 1]
    H02 = h02 / samples + eps * lean[i, 0, 2]
    H10 = h10 / samples + eps * lean[i, 1, 0]
    H11 = h11 / samples + eps * lean[i, 1, 1]
    H12 = h12 / samples + eps * lean[i, 1, 2]
    H20 = h20 / samples + eps * lean[i, 2, 0]
    H21 = h21 / samples + eps * lean[i, 2, 1]
    H22 = h22 / samples + eps * lean[i, 2, 2]
    # D G = H  ->  D = H G^-1: the cofactors of the symmetric G over its determinant
    i00 = G11 * G22 - G12 * G12
    i01 = G02 * G12 - G01 * G22
    i02 = G01 * G12 - G02 * G11
    i11 = G00 * G22 - G02 * G02
    i12 = G02 * G01 - G00 * G12
    i22 = G00 * G11 - G01 * G01
    det = G00 * i00 + G01 * i01 + G02 * i02
    i00, i01, i02, i11, i12, i22 = i00 / det, i01 / det, i02 / det, i11 / det, i12 / det, i22 / det
    out[i, 0, 0] = H00 * i00 + H01 * i01 + H02 * i02
    out[i, 0, 1] = H00 * i01 + H01 * i11 + H02 * i12
    out[i, 0, 2] = H00 * i02 + H01 * i12 + H02 * i22
    out[i, 1, 0] = H10 * i00 + H11 * i01 + H12 * i02
    out[i, 1, 1] = H10 * i01 + H11 * i11 + H12 * i12
    out[i, 1, 2] = H10 * i02 + H11 * i12 + H12 * i22
    out[i, 2, 0] = H20 * i00 + H21 * i01 + H22 * i02
    out[i, 2, 1] = H20 * i01 + H21 * i11 + H22 * i12
    out[i, 2, 2] = H20 * i02 + H21 * i12 + H22 * i22


#: threshold of the pivoting of :func:`band_solve_rows` (the diagonal is kept while
#: at least this fraction of the column's largest entry)
PIVOT_THRESHOLD = 0.1


@njit(cache=True, inline="always")
def band_pivot(R, bw, reach, k, last):  # noqa: ANN001, ANN201
    """Pivot row ``p`` of step ``k`` (rows ``k .. last``) by :func:`band_solve_rows`'s
    threshold rule, rows ``k`` and ``p`` of ``R`` and ``reach`` exchanged (the caller
    exchanges its right sides); -1 for a zero column. No rounding: the same inlined
    under any caller's flags."""
    p = k
    z = R[k, bw]
    diag = abs(z.real) + abs(z.imag)
    big = diag
    for i in range(k + 1, last + 1):
        z = R[i, k - i + bw]
        a = abs(z.real) + abs(z.imag)
        if a > big:
            big, p = a, i
    if not big > 0.0:
        return -1
    if diag >= PIVOT_THRESHOLD * big:
        p = k
    if p != k:
        right = max(reach[k], reach[p])
        for j in range(k, right + 1):
            t = R[k, j - k + bw]
            R[k, j - k + bw] = R[p, j - p + bw]
            R[p, j - p + bw] = t
        t2 = reach[k]
        reach[k] = reach[p]
        reach[p] = t2
    return p


@njit(cache=True)
def band_solve_rows(R, bw, reach, rhs, x):  # noqa: ANN001, ANN201
    """Solve the complex banded system on row storage ``R`` (N, 3 bw + 1), A[i, j] at
    R[i, j - i + bw] (room on the right for the fill-in of row exchanges), by Gaussian
    elimination with threshold partial pivoting: the diagonal is kept as the pivot
    unless an entry below it is more than ``1 / PIVOT_THRESHOLD`` times larger (in
    ``|re| + |im|``, LAPACK's measure), else the largest is taken. Each step's
    multipliers are then at most ``1 / PIVOT_THRESHOLD`` (10) in size, which bounds the
    growth as partial pivoting does (with 10 for 1; the threshold rule of sparse
    direct solvers), and a dynamic matrix, whose diagonal dominates, needs no row
    exchange, hence no fill-in beyond the band. ``reach`` (N,) int work array: the last
    column of each row that may be non-zero, so that an elimination step skips
    columns still zero. ``R`` and ``rhs`` are overwritten. Returns False for a zero
    pivot."""
    N = rhs.shape[0]
    for i in range(N):
        reach[i] = min(i + bw, N - 1)
    for k in range(N):
        last = min(k + bw, N - 1)
        p = band_pivot(R, bw, reach, k, last)
        if p < 0:
            return False
        if p != k:
            t = rhs[k]
            rhs[k] = rhs[p]
            rhs[p] = t
        inv = 1.0 / R[k, bw]
        rk = reach[k]
        off_k = bw - k
        for i in range(k + 1, last + 1):
            z = R[i, k - i + bw]
            if z.real == 0.0 and z.imag == 0.0:  # nothing to eliminate
                continue
            f = z * inv
            off_i = bw - i
            for j in range(k + 1, rk + 1):
                R[i, j + off_i] -= f * R[k, j + off_k]
            rhs[i] -= f * rhs[k]
            if rk > reach[i]:
                reach[i] = rk
    for i in range(N - 1, -1, -1):
        acc = rhs[i]
        for j in range(i + 1, reach[i] + 1):
            acc -= R[i, j - i + bw] * x[j]
        x[i] = acc / R[i, bw]
    return True


@njit(cache=True)
def _csr_rows(ptr, idx, val, x, lo, hi, out):  # noqa: ANN001, ANN202
    """out[r - lo] = (A x)[r] for rows lo <= r < hi of the CSR matrix (ptr, idx, val)."""
    for r in range(lo, hi):
        acc = 0j
        for jj in range(ptr[r], ptr[r + 1]):
            acc += val[jj] * x[idx[jj]]
        out[r - lo] = acc


#: secant pairs kept by the Anderson mixing of the drag iteration (:func:`_mixed`)
ANDERSON_DEPTH = 3


@njit(cache=True, inline="always")
def _dot(x, y):  # noqa: ANN001, ANN202
    """``x . y`` of two 1-D arrays, summed in order (inlined into :func:`_mixed`, it
    takes its caller's floating-point flags: none)."""
    acc = 0.0
    for q in range(x.shape[0]):
        acc += x[q] * y[q]
    return acc


@njit(cache=True, inline="always")
def _axpy_difference(d, a, g, h):  # noqa: ANN001, ANN202
    """``d -= a (g - h)`` in place (1-D arrays)."""
    for q in range(d.shape[0]):
        d[q] -= a * (g[q] - h[q])


@njit(cache=True, inline="always")
def ring_push(d, g, hist_R, hist_G, state):  # noqa: ANN001, ANN201
    """Anderson mixing's new pair (residual ``g - d``, fit ``g``; flat drags) into the
    ring of rows of ``hist_R``, ``hist_G`` (depth + 1, size) whose ``state[0]`` pairs
    start at row ``state[1]`` (oldest first: the oldest leaves by moving the start);
    ``state`` updated, returns the new pair's row. Shared by the single line's
    :func:`_mixed` and the system's :func:`.system_fd_fit.anderson`."""
    keep = hist_R.shape[0]
    count, head = state[0], state[1]
    if count == keep:  # the oldest pair leaves; the new one takes its row
        slot = head
        head = (head + 1) % keep
    else:
        slot = (head + count) % keep
        count += 1
    for q in range(d.shape[0]):
        hist_R[slot, q] = g[q] - d[q]
        hist_G[slot, q] = g[q]
    state[0] = count
    state[1] = head
    return slot


@njit(cache=True, inline="always")
def secant_system(gram, slot, state):  # noqa: ANN001, ANN201
    """The normal equations ``A gam = rhs`` of Anderson mixing over the ``m = state[0] -
    1`` pairs other than the new one in row ``slot`` (:func:`ring_push`), from their
    Gram matrix ``gram``: ``A[a, b] = (r - R_a) . (r - R_b)``, ``rhs[a] = (r - R_a) .
    r``; returns (the other pairs' rows oldest first, ``A``, ``rhs``, the trace of
    ``A``)."""
    keep = gram.shape[0]
    count, head = state[0], state[1]
    m = count - 1
    others = np.empty(m, dtype=np.int64)
    c2 = 0
    for c in range(count):
        j = (head + c) % keep
        if j != slot:
            others[c2] = j
            c2 += 1
    A = np.empty((m, m))
    rhs = np.empty(m)
    rr = gram[slot, slot]
    trace = 0.0
    for a in range(m):
        ja = others[a]
        rhs[a] = rr - gram[slot, ja]
        for b in range(m):
            jb = others[b]
            A[a, b] = rr - gram[slot, ja] - gram[slot, jb] + gram[ja, jb]
        trace += A[a, a]
    return others, A, rhs, trace


@njit(cache=True)
def _mixed(D, G, hist_R, hist_G, gram, state, change, last):  # noqa: ANN001, ANN202, PLR0913
    """The next drag matrices ``D`` of the fixed point ``D = G(D)`` (``G`` the fit to the
    motion ``D`` gave): after a change that grew, the mean of the two with the history
    dropped; else Anderson mixing over the last (residual ``R = G - D``, ``G``) pairs,
    ``D = G - sum_j g_j (G - G_j)`` with ``g`` the least-squares fit of ``R`` by the
    residual differences ``R - R_j`` (depth one: the secant step ``theta = R . dR / dR
    . dR``). The pairs sit in the ring ``hist_R``, ``hist_G`` (depth + 1, n * 9) with
    their Gram matrix ``gram`` (depth + 1, depth + 1); ``state`` (2,) int holds the
    number of pairs and the ring's first slot (:func:`ring_push`)."""
    d = D.reshape(-1)
    g = G.reshape(-1)
    size = d.size
    keep = hist_R.shape[0]
    if change >= last:
        for q in range(size):
            d[q] = 0.5 * (d[q] + g[q])
        state[0] = 0
        state[1] = 0
        return
    slot = ring_push(d, g, hist_R, hist_G, state)
    count, head = state[0], state[1]
    for c in range(count):
        j = (head + c) % keep
        acc = _dot(hist_R[slot], hist_R[j])
        gram[slot, j] = acc
        gram[j, slot] = acc
    m = count - 1
    if m == 0:
        for q in range(size):
            d[q] = g[q]
        return
    others, A, rhs, trace = secant_system(gram, slot, state)
    gam = np.zeros(m)
    if trace > 0.0:
        for a in range(m):
            A[a, a] += 1e-12 * trace  # a near-dependent pair gets no weight
        for k in range(m):  # symmetric positive definite: no pivoting
            for i2 in range(k + 1, m):
                f = A[i2, k] / A[k, k]
                for j in range(k, m):
                    A[i2, j] -= f * A[k, j]
                rhs[i2] -= f * rhs[k]
        for k in range(m - 1, -1, -1):
            acc = rhs[k]
            for j in range(k + 1, m):
                acc -= A[k, j] * gam[j]
            gam[k] = acc / A[k, k]
    for q in range(size):
        d[q] = g[q]
    for a in range(m):
        _axpy_difference(d, gam[a], g, hist_G[others[a]])


@njit(cache=True)
def _cases_kernel(  # noqa: ANN201, PLR0913, PLR0912, PLR0915
    omegas,
    motion,
    k_ptr,
    k_idx,
    k_val,
    c_ptr,
    c_idx,
    c_val,
    bt_ptr,
    bt_idx,
    bt_val,
    mass,
    rows_k,
    rows_m,
    rows_c,
    bw,
    offsets,
    basis,
    selected,
    sel,
    pos,
    frac,
    current,
    tangent,
    c_n,
    c_t,
    c_b,
    d_small,
    has_drag,
    samples,
    exact,
    tol,
    max_iterations,
    u_out,
    reaction_out,
    iterations_out,
    converged_out,
    change_out,
    ok_out,
):  # noqa: ANN001
    """Per case c: the displacement u_out[c] (n, 3) and the end rows (A u)[0], (A u)[-1]
    in reaction_out[c] (2, 3), with A the dynamic matrix with the last drag."""
    n = mass.shape[0]
    N = rows_k.shape[0]
    width = rows_k.shape[1]
    cos = np.empty(samples)
    sin = np.empty(samples)
    for k in range(samples):
        cos[k] = np.cos(2.0 * np.pi * k / samples)
        sin[k] = np.sin(2.0 * np.pi * k / samples)
    base = np.empty((N, width), dtype=np.complex128)
    R = np.empty((N, width), dtype=np.complex128)
    reach = np.empty(N, dtype=np.int64)
    rhs0 = np.empty(N, dtype=np.complex128)
    rhs = np.empty(N, dtype=np.complex128)
    q = np.empty(N, dtype=np.complex128)
    up = np.zeros((n, 3), dtype=np.complex128)
    flat = np.zeros(3 * n, dtype=np.complex128)
    y = np.empty(3 * n, dtype=np.complex128)
    yk = np.empty(3 * n, dtype=np.complex128)
    yc = np.empty(3 * n, dtype=np.complex128)
    u = np.empty((n, 3), dtype=np.complex128)
    v = np.empty((n, 3), dtype=np.complex128)
    vr = np.empty((n, 3))
    vi = np.empty((n, 3))
    D = np.zeros((n, 3, 3))
    G = np.empty((n, 3, 3))
    hist_R = np.empty((ANDERSON_DEPTH + 1, 9 * n))
    hist_G = np.empty((ANDERSON_DEPTH + 1, 9 * n))
    gram = np.empty((ANDERSON_DEPTH + 1, ANDERSON_DEPTH + 1))
    mix_state = np.zeros(2, dtype=np.int64)
    end_rows = np.empty(3, dtype=np.complex128)
    W0 = np.empty((n, samples))
    W1 = np.empty((n, samples))
    W2 = np.empty((n, samples))
    F0 = np.empty((n, samples))
    F1 = np.empty((n, samples))
    F2 = np.empty((n, samples))
    kind = np.empty(n, dtype=np.int64)
    lean = np.empty((n, 3, 3))
    # the columns of B^T K, B^T C and B^T M at the six end coordinates (their non-zero
    # rows), from the sparse rows: y = A e_d, then B^T y
    nz_ptr = np.zeros(7, dtype=np.int64)
    nz_row = np.empty(6 * N, dtype=np.int64)
    end_k = np.empty(6 * N)
    end_c = np.empty(6 * N)
    end_m = np.empty(6 * N)
    for e in range(6):
        node = 0 if e < 3 else n - 1
        a = e % 3
        flat[:] = 0.0
        flat[3 * node + a] = 1.0
        _csr_rows(k_ptr, k_idx, k_val, flat, 0, 3 * n, yk)
        _csr_rows(c_ptr, c_idx, c_val, flat, 0, 3 * n, yc)
        for i in range(3 * n):
            y[i] = 0j
        for b in range(3):
            y[3 * node + b] = mass[node, b, a]
        nz = nz_ptr[e]
        for r in range(N):
            ak = 0.0
            ac = 0.0
            am = 0.0
            for jj in range(bt_ptr[r], bt_ptr[r + 1]):
                ak += bt_val[jj] * yk[bt_idx[jj]].real
                ac += bt_val[jj] * yc[bt_idx[jj]].real
                am += bt_val[jj] * y[bt_idx[jj]].real
            if ak != 0.0 or ac != 0.0 or am != 0.0:
                nz_row[nz] = r
                end_k[nz] = ak
                end_c[nz] = ac
                end_m[nz] = am
                nz += 1
        nz_ptr[e + 1] = nz
    for case in range(omegas.shape[0]):
        omega = omegas[case]
        w2 = omega**2
        flat[:] = 0.0
        for a in range(3):
            up[0, a] = motion[case, 0, a]
            up[n - 1, a] = motion[case, 1, a]
            flat[a] = up[0, a]
            flat[3 * (n - 1) + a] = up[n - 1, a]
        # rhs0 = -B^T [K - w^2 M + i w C] u_p: only the six end coordinates move
        for r in range(N):
            rhs0[r] = 0j
        for e in range(6):
            ue = up[0, e] if e < 3 else up[n - 1, e - 3]
            if ue == 0.0:
                continue
            for r in range(nz_ptr[e], nz_ptr[e + 1]):
                row = nz_row[r]
                rhs0[row] -= ((end_k[r] - w2 * end_m[r]) + 1j * omega * end_c[r]) * ue
        for r in range(N):
            for j in range(width):
                base[r, j] = (rows_k[r, j] - w2 * rows_m[r, j]) + 1j * omega * rows_c[r, j]
        ok = True
        converged = True
        change = 0.0
        iterations = 0
        if has_drag:
            for i in range(n):
                for a in range(3):
                    u[i, a] = (1.0 - frac[i]) * up[0, a] + frac[i] * up[n - 1, a]
                    v[i, a] = 1j * omega * u[i, a]
                    vr[i, a] = v[i, a].real
                    vi[i, a] = v[i, a].imag
            mix_state[0] = 0
            mix_state[1] = 0
            last = np.inf
            change = np.inf
            converged = False
            iterations = max_iterations
            for it in range(1, max_iterations + 2):
                # the fit to the last motion: the first one taken as it is, the later
                # ones mixed with the drag that gave the motion (after the last
                # iteration too: the end rows take that drag)
                drag_fit_samples(
                    vr,
                    vi,
                    current,
                    tangent,
                    c_n,
                    c_t,
                    c_b,
                    d_small,
                    cos,
                    sin,
                    exact,
                    W0,
                    W1,
                    W2,
                    F0,
                    F1,
                    F2,
                    kind,
                    lean,
                    G,
                )
                if it == 1:
                    D[:] = G
                else:
                    _mixed(D, G, hist_R, hist_G, gram, mix_state, change, last)
                    last = change
                if it > max_iterations:
                    break
                for r in range(N):
                    for j in range(width):
                        R[r, j] = base[r, j]
                for i in range(n):
                    o = offsets[i]
                    kk = offsets[i + 1] - o
                    if selected[i]:  # B^T D B picks entries of D
                        for r in range(kk):
                            for c in range(kk):
                                R[o + r, c - r + bw] += 1j * omega * D[i, sel[i, r], sel[i, c]]
                        continue
                    for r in range(kk):
                        for c in range(kk):
                            proj = 0.0
                            for a in range(3):
                                for b in range(3):
                                    proj += basis[i, a, r] * D[i, a, b] * basis[i, b, c]
                            R[o + r, c - r + bw] += 1j * omega * proj
                for j in range(N):
                    rhs[j] = rhs0[j]
                if not band_solve_rows(R, bw, reach, rhs, q):
                    ok = False
                    iterations = it
                    break
                d2max = 0.0
                v2max = 0.0
                for i in range(n):
                    o = offsets[i]
                    kk = offsets[i + 1] - o
                    for a in range(3):
                        acc = up[i, a]
                        if selected[i]:
                            if pos[i, a] >= 0:
                                acc += q[o + pos[i, a]]
                        else:
                            for r in range(kk):
                                acc += basis[i, a, r] * q[o + r]
                        vn = 1j * omega * acc
                        dz = vn - v[i, a]
                        d2 = dz.real * dz.real + dz.imag * dz.imag
                        v2 = vn.real * vn.real + vn.imag * vn.imag
                        d2max = max(d2max, d2)
                        v2max = max(v2max, v2)
                        u[i, a] = acc
                        v[i, a] = vn
                if not (d2max < np.inf and v2max < np.inf):  # not finite (or NaN)
                    ok = False
                    iterations = it
                    break
                change = math.sqrt(d2max) / max(math.sqrt(v2max), 1e-300)
                if change <= tol:
                    converged = True
                    iterations = it
                    break
                for i in range(n):
                    for a in range(3):
                        vr[i, a] = v[i, a].real
                        vi[i, a] = v[i, a].imag
        else:
            for r in range(N):
                for j in range(width):
                    R[r, j] = base[r, j]
                for j in range(N):
                    rhs[j] = rhs0[j]
            if N > 0 and not band_solve_rows(R, bw, reach, rhs, q):
                ok = False
            for i in range(n):
                o = offsets[i]
                kk = offsets[i + 1] - o
                for a in range(3):
                    acc = up[i, a]
                    for r in range(kk):
                        acc += basis[i, a, r] * q[o + r]
                    u[i, a] = acc
                    if not (np.isfinite(acc.real) and np.isfinite(acc.imag)):
                        ok = False
        ok_out[case] = ok
        iterations_out[case] = iterations
        converged_out[case] = converged
        change_out[case] = change
        if not ok:
            continue
        for i in range(n):
            for a in range(3):
                u_out[case, i, a] = u[i, a]
                flat[3 * i + a] = u[i, a]
        # the end rows of [K - w^2 M + i w (C + D)] u
        for e in range(2):
            node = 0 if e == 0 else n - 1
            _csr_rows(k_ptr, k_idx, k_val, flat, 3 * node, 3 * node + 3, yk)
            _csr_rows(c_ptr, c_idx, c_val, flat, 3 * node, 3 * node + 3, yc)
            for a in range(3):
                acc = mass[node, a, 0] * u[node, 0] + mass[node, a, 1] * u[node, 1]
                acc += mass[node, a, 2] * u[node, 2]
                val = (yk[a] + 1j * omega * yc[a]) - w2 * acc
                if has_drag:
                    dacc = D[node, a, 0] * u[node, 0] + D[node, a, 1] * u[node, 1]
                    dacc += D[node, a, 2] * u[node, 2]
                    val = val + 1j * omega * dacc
                end_rows[a] = val
            for a in range(3):
                reaction_out[case, e, a] = end_rows[a]
    for case in range(omegas.shape[0]):
        if not ok_out[case]:
            for i in range(n):
                for a in range(3):
                    u_out[case, i, a] = np.nan + 0j
