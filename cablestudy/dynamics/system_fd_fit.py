"""The compiled drag fit and mixing of a system's frequency domain
(:mod:`.system_fd_kernel`): per node the small-motion lean and the drag fit in one pass
over the phases (:func:`fit_node`), the free points' isotropic drag fit
(:func:`fit_points`), all of a system's nodes and points (:func:`fit_all`) and the
Anderson mixing of the iteration (:func:`anderson`), each the compiled form of the
NumPy reference's step (tests/system_frequency_reference.py).

Pure: arrays in, arrays out.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .drag_lean import lean_from_sums
from .elliptic_fit import still_water_means
from .frequency_model import FIT_REGULARISATION, is_planar, planar_drag_fit
from .harmonic_kernel import fit_from_sums, ring_push, secant_system

#: the sums over the phases may be reassociated (vectorised: the system's frequency
#: domain takes 13% less time a case); no other fast-math flag: with contraction and
#: reciprocals as well, the answer depended on whether numba had just compiled the
#: kernel or loaded it from its cache (up to 4e-11 of the fit)
_REASSOCIATE = {"reassoc"}


@njit(cache=True, error_model="numpy", fastmath=_REASSOCIATE)
def fit_node(i, vr, vi, cur, tan, c_n, c_t, c_b, cs, sn_, exact, lean, out):  # noqa: ANN001, ANN202, PLR0913, PLR0915
    """The small-motion lean (``mean_drag_jacobian`` of the NumPy oracle,
    tests/system_drag_reference.py) into ``lean[i]`` and the drag fit leaning on it
    (``drag_linearisation`` of tests/drag_fit_reference.py) into ``out[i]`` of node ``i``, one
    pass over the phases for both. Without current at the node and with an even number
    of phases, the phases of half a period serve (each sum twice; the mean force is
    zero); with ``samples`` unset (``exact``) such a node does not come here: it takes
    the exact means in :func:`fit_all`."""
    samples = cs.shape[0]
    t0, t1, t2 = tan[i, 0], tan[i, 1], tan[i, 2]
    u0, u1, u2 = cur[i, 0], cur[i, 1], cur[i, 2]
    a0, a1, a2 = vr[i, 0], vr[i, 1], vr[i, 2]
    b0, b1, b2 = vi[i, 0], vi[i, 1], vi[i, 2]
    cn, ct, cb = c_n[i], c_t[i], c_b[i]
    body = cb != 0.0
    odd = u0 == 0.0 and u1 == 0.0 and u2 == 0.0 and samples % 2 == 0
    ns = samples // 2 if odd else samples
    # at three phases or more the sums of w = -(a cos - b sin) over a period are known:
    # sum w = 0, sum w w^T = samples / 2 (a a^T + b b^T) (sum cos^2 = sum sin^2 =
    # samples / 2, sum cos sin = 0); over half a period (odd) half of that
    closed = samples >= 3
    sum_n = sum_r = abs_t = 0.0
    n00 = n01 = n02 = n11 = n12 = n22 = 0.0
    q00 = q01 = q02 = q11 = q12 = q22 = 0.0
    g00 = g01 = g02 = g11 = g12 = g22 = 0.0
    h00 = h01 = h02 = h10 = h11 = h12 = h20 = h21 = h22 = 0.0
    f0s = f1s = f2s = w0s = w1s = w2s = 0.0
    for k in range(ns):
        c, s = cs[k], sn_[k]
        w0 = -(a0 * c - b0 * s)
        w1 = -(a1 * c - b1 * s)
        w2 = -(a2 * c - b2 * s)
        r0, r1, r2 = u0 + w0, u1 + w1, u2 + w2
        wt = r0 * t0 + r1 * t1 + r2 * t2
        x0, x1, x2 = r0 - wt * t0, r1 - wt * t1, r2 - wt * t2
        sn = math.sqrt(x0 * x0 + x1 * x1 + x2 * x2)
        abs_t += abs(wt)
        sum_n += sn
        if sn > 0.0:
            inv = 1.0 / sn
            n00 += x0 * x0 * inv
            n01 += x0 * x1 * inv
            n02 += x0 * x2 * inv
            n11 += x1 * x1 * inv
            n12 += x1 * x2 * inv
            n22 += x2 * x2 * inv
        st = abs(wt) * wt * ct
        sr = 0.0
        if body:
            rr = math.sqrt(r0 * r0 + r1 * r1 + r2 * r2)
            sum_r += rr
            if rr > 0.0:
                inv = 1.0 / rr
                q00 += r0 * r0 * inv
                q01 += r0 * r1 * inv
                q02 += r0 * r2 * inv
                q11 += r1 * r1 * inv
                q12 += r1 * r2 * inv
                q22 += r2 * r2 * inv
            sr = cb * rr
        f0 = cn * sn * x0 + st * t0 + sr * r0
        f1 = cn * sn * x1 + st * t1 + sr * r1
        f2 = cn * sn * x2 + st * t2 + sr * r2
        f0s += f0
        f1s += f1
        f2s += f2
        if not closed:
            w0s += w0
            w1s += w1
            w2s += w2
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
    if closed:
        q = 0.5 * ns
        g00 = q * (a0 * a0 + b0 * b0)
        g01 = q * (a0 * a1 + b0 * b1)
        g02 = q * (a0 * a2 + b0 * b2)
        g11 = q * (a1 * a1 + b1 * b1)
        g12 = q * (a1 * a2 + b1 * b2)
        g22 = q * (a2 * a2 + b2 * b2)
    if odd:  # the other half period: the same sums; sum of f zero
        sum_n, sum_r, abs_t = 2.0 * sum_n, 2.0 * sum_r, 2.0 * abs_t
        n00, n01, n02, n11, n12, n22 = 2 * n00, 2 * n01, 2 * n02, 2 * n11, 2 * n12, 2 * n22
        q00, q01, q02, q11, q12, q22 = 2 * q00, 2 * q01, 2 * q02, 2 * q11, 2 * q12, 2 * q22
        g00, g01, g02, g11, g12, g22 = 2 * g00, 2 * g01, 2 * g02, 2 * g11, 2 * g12, 2 * g22
        h00, h01, h02, h10, h11, h12 = 2 * h00, 2 * h01, 2 * h02, 2 * h10, 2 * h11, 2 * h12
        h20, h21, h22 = 2 * h20, 2 * h21, 2 * h22
    else:  # sum (f - fm) w^T = sum f w^T - fm sum w^T
        fm0, fm1, fm2 = f0s / samples, f1s / samples, f2s / samples
        h00 -= fm0 * w0s
        h01 -= fm0 * w1s
        h02 -= fm0 * w2s
        h10 -= fm1 * w0s
        h11 -= fm1 * w1s
        h12 -= fm1 * w2s
        h20 -= fm2 * w0s
        h21 -= fm2 * w1s
        h22 -= fm2 * w2s
    Wn = ((n00, n01, n02), (n01, n11, n12), (n02, n12, n22))
    Wb = ((q00, q01, q02), (q01, q11, q12), (q02, q12, q22))
    lean_from_sums(sum_n, sum_r, abs_t, Wn, Wb, (t0, t1, t2), cn, ct, cb, samples, lean, i)
    if exact and not body and is_planar(vr, vi, tan, cur, i):
        planar_drag_fit(vr, vi, tan, cur, c_n, c_t, lean, i, out)
        return
    fit_from_sums(
        (g00, g01, g02, g11, g12, g22),
        (h00, h01, h02, h10, h11, h12, h20, h21, h22),
        samples,
        lean,
        i,
        out,
    )


@njit(cache=True, error_model="numpy")
def fit_points(c_p, cur, u_pts, omega, cs, sn_, exact, Dp):  # noqa: ANN001, ANN202, PLR0913
    """The describing-function drag fit of every point (``point_drag_fit`` of the NumPy
    oracle, tests/system_drag_reference.py) at velocities ``i omega u_pts`` into ``Dp``
    (P, 3, 3); with ``exact`` (``samples`` unset) a point without current from the
    exact period means (:func:`.elliptic_fit.still_water_means` of the isotropic drag
    alone) instead of the phase sums."""
    samples = cs.shape[0]
    P = c_p.shape[0]
    w = np.empty((samples, 3))
    f = np.empty((samples, 3))
    lhs = np.empty((3, 3))
    rhs = np.empty((3, 3))
    vr = np.empty(3)
    vi = np.empty(3)
    fm = np.empty(3)
    r = np.empty(3)
    for p in range(P):
        if c_p[p] == 0.0:  # no drag: the fit is zero (H and D_0 are)
            Dp[p] = 0.0
            continue
        for a in range(3):
            v = 1j * omega * u_pts[p, a]
            vr[a] = v.real
            vi[a] = v.imag
        su = math.sqrt(cur[p, 0] ** 2 + cur[p, 1] ** 2 + cur[p, 2] ** 2)
        inv = 1.0 / su if su > 0.0 else 0.0
        if exact and not su > 0.0:
            g6, h9, _ = still_water_means(
                vr[0], vr[1], vr[2], vi[0], vi[1], vi[2], 0.0, 0.0, 0.0, 0.0, 0.0, c_p[p]
            )
            for a in range(3):
                for b in range(3):
                    lhs[a, b] = g6[_SYM[a][b]]
                    rhs[a, b] = h9[3 * a + b]
            _point_solve(lhs, rhs, c_p[p], cur, p, su, inv, Dp)
            continue
        fm[:] = 0.0
        for k in range(samples):
            for a in range(3):
                w[k, a] = -(vr[a] * cs[k] - vi[a] * sn_[k])
                r[a] = cur[p, a] + w[k, a]
            nr = math.sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2])
            for a in range(3):
                f[k, a] = c_p[p] * nr * r[a]
                fm[a] += f[k, a]
        for a in range(3):
            for b in range(3):
                g = 0.0
                h = 0.0
                for k in range(samples):
                    g += w[k, a] * w[k, b]
                    h += (f[k, a] - fm[a] / samples) * w[k, b]
                lhs[a, b] = g / samples
                rhs[a, b] = h / samples
        _point_solve(lhs, rhs, c_p[p], cur, p, su, inv, Dp)


#: the place of entry (a, b) of a symmetric 3 x 3 matrix in its entries 00, 01, 02, 11,
#: 12, 22 (:func:`.elliptic_fit.still_water_means`)
_SYM = ((0, 1, 2), (1, 3, 4), (2, 4, 5))


@njit(cache=True, inline="always")
def _point_solve(lhs, rhs, c, cur, p, su, inv, Dp):  # noqa: ANN001, ANN202, PLR0913
    """``Dp[p] = (H + eps D_0)(G + eps I)^-1`` from the means ``G`` (``lhs``) and ``H``
    (``rhs``) of point ``p``'s fit, ``D_0 = c (|U| I + U U^T / |U|)`` the small-motion
    tangent (``su = |U|``, ``inv = 1 / |U|`` or 0), ``eps``
    :data:`.frequency_model.FIT_REGULARISATION` times the trace of ``G``; ``D_0`` for a
    point at rest."""
    trace = 0.0
    for a in range(3):
        trace += lhs[a, a]
    eps = FIT_REGULARISATION * trace if trace > 0.0 else 1.0
    for a in range(3):
        for b in range(3):
            d0 = c * ((su if a == b else 0.0) + inv * cur[p, a] * cur[p, b])
            rhs[a, b] = rhs[a, b] + eps * d0 if trace > 0.0 else d0
        lhs[a, a] += eps
    Dp[p] = rhs @ np.linalg.inv(lhs)


@njit(cache=True, error_model="numpy")
def fit_all(
    omega, disp, u_pts, cur, tan, c_n, c_t, c_b, c_p, pcur, cs, sn_, exact, vr, vi, lean, D, Dp
):  # noqa: ANN001, ANN202, PLR0913
    """The drag fit of every node (into ``D``) and point (into ``Dp``) at velocities
    ``i omega u``: a node in a current, or every node with ``samples`` set, over the
    phases (:func:`fit_node`), any other by the exact period means
    (:func:`.elliptic_fit.still_water_means`); the points likewise (:func:`fit_points`)."""
    for g in range(disp.shape[0]):
        for a in range(3):
            v = 1j * omega * disp[g, a]
            vr[g, a] = v.real
            vi[g, a] = v.imag
    for g in range(disp.shape[0]):
        if not (exact and cur[g, 0] == 0.0 and cur[g, 1] == 0.0 and cur[g, 2] == 0.0):
            fit_node(g, vr, vi, cur, tan, c_n, c_t, c_b, cs, sn_, exact, lean, D)
            continue
        # no current, samples unset: the lean and the fit from the exact period means
        # (written out here: an inlined function's array arguments cost reference
        # counts, as much as the means); a node moving in the x-z plane (no body) the
        # planar closed form with that lean, as fit_node
        a0, a1, a2, b0, b1, b2 = vr[g, 0], vr[g, 1], vr[g, 2], vi[g, 0], vi[g, 1], vi[g, 2]
        t0, t1, t2 = tan[g, 0], tan[g, 1], tan[g, 2]
        G, H, J = still_water_means(a0, a1, a2, b0, b1, b2, t0, t1, t2, c_n[g], c_t[g], c_b[g])
        lean[g, 0, 0], lean[g, 0, 1], lean[g, 0, 2] = J[0], J[1], J[2]
        lean[g, 1, 0], lean[g, 1, 1], lean[g, 1, 2] = J[1], J[3], J[4]
        lean[g, 2, 0], lean[g, 2, 1], lean[g, 2, 2] = J[2], J[4], J[5]
        if c_b[g] == 0.0 and a1 == 0.0 and b1 == 0.0 and t1 == 0.0:
            planar_drag_fit(vr, vi, tan, cur, c_n, c_t, lean, g, D)
        else:
            fit_from_sums(G, H, 1, lean, g, D)
    fit_points(c_p, pcur, u_pts, omega, cs, sn_, exact, Dp)


#: secant pairs kept by the Anderson mixing (as the reference:
#: ``ANDERSON_DEPTH`` of tests/system_frequency_reference.py)
DEPTH = 4
#: the damping of the mixed step (``MIXING`` of the reference): the next iterate is
#: ``gbar - (1 - MIXING) rbar``, the mixed fit less part of the mixed residual. The
#: fixed point's Jacobian has its largest eigenvalues on the negative side (the drag
#: fit falls as the drag that made the motion grows; on case8 surged at 0.5 Hz the
#: largest are -0.72 +- 0.17i, -0.61, -0.50, with 62 above 0.05 in modulus) and a
#: damped step pulls them towards zero. Chosen over 3/4 x 0.6-1.0 on case8 (20 elements
#: a line; surge, sway, heave, pitch; 50 frequencies 0.02-0.5 Hz): depth 3 undamped
#: 9.71 drag iterations a case, depth 4 at 0.8 9.09 (each motion 6-8 % fewer, the
#: largest count 16 -> 14), the answers as far from the fixed point (the velocity
#: change's tolerance bounds both)
MIXING = 0.8


@njit(cache=True, error_model="numpy")
def anderson(d, g, hist_R, hist_G, gram, state, change, last):  # noqa: ANN001, ANN202, PLR0913
    """``_Anderson.step`` of tests/system_frequency_reference.py on the flat drag ``d``
    (overwritten by the next iterate) and its fit ``g``; the ``state[0]`` pairs in the
    ring of rows of ``hist_R``, ``hist_G`` from row ``state[1]`` on (oldest first: the
    oldest leaves by moving the start, not the rows; the same values in the same
    order as rows kept oldest first), with their Gram matrix ``gram`` (DEPTH + 1,
    DEPTH + 1): each step forms the new residual's products with the kept ones only
    (``count`` sums over the drag, instead of the ``m (m + 3) / 2`` sums of the
    differences' normal equations; ``(r - R_a) . (r - R_b)`` from them, as the single
    line's :func:`.harmonic_kernel._mixed`)."""
    size = d.shape[0]
    keep = hist_R.shape[0]  # DEPTH + 1
    if change >= last:
        state[0] = 0
        state[1] = 0
        for q in range(size):
            d[q] = 0.5 * (d[q] + g[q])
        return
    slot = ring_push(d, g, hist_R, hist_G, state)
    count, head = state[0], state[1]
    r = hist_R[slot]
    for c in range(count):
        j = (head + c) % keep
        acc = _dot(r, hist_R[j], size)
        gram[slot, j] = acc
        gram[j, slot] = acc
    m = count - 1
    if m > 0:
        # the normal equations (dR dR^T + 1e-12 tr I) gam = dR r over the kept pairs,
        # oldest first, by :func:`_small_solve` (BLAS and LAPACK through numba cost
        # more in calls and copies than the sums themselves)
        others, A, gam, trace = secant_system(gram, slot, state)
        if trace > 0.0:
            for a in range(m):
                A[a, a] += 1e-12 * trace
            if _small_solve(A, gam, m):
                # gbar - (1 - MIXING) rbar with gbar = g - sum gam_a (g - G_a) and rbar
                # = r - sum gam_a (r - R_a), a pair at a time over the rows (contiguous)
                damp = 1.0 - MIXING
                for q in range(size):
                    d[q] = g[q] - damp * r[q]
                for a in range(m):
                    ja = others[a]
                    c = gam[a]
                    hg = hist_G[ja]
                    hr = hist_R[ja]
                    for q in range(size):
                        d[q] -= c * ((g[q] - hg[q]) - damp * (r[q] - hr[q]))
                return
    # one pair, or no usable history (a zero or singular system, not met with the
    # regularisation): the damped plain step
    for q in range(size):
        d[q] = d[q] + MIXING * r[q]


@njit(cache=True, inline="always")
def _dot(a, b, n):  # noqa: ANN001, ANN202
    """``sum(a[:n] * b[:n])`` in four interleaved partial sums (a fixed order: the same
    bits on every call), added pairwise at the end."""
    s0 = s1 = s2 = s3 = 0.0
    q = 0
    while q + 4 <= n:
        s0 += a[q] * b[q]
        s1 += a[q + 1] * b[q + 1]
        s2 += a[q + 2] * b[q + 2]
        s3 += a[q + 3] * b[q + 3]
        q += 4
    while q < n:
        s0 += a[q] * b[q]
        q += 1
    return (s0 + s1) + (s2 + s3)


@njit(cache=True)
def _small_solve(A, x, m):  # noqa: ANN001, ANN202
    """Solve ``A[:m, :m] y = x[:m]`` in place into ``x`` (Gaussian elimination with
    partial pivoting, as LAPACK's ``gesv``); False for a zero pivot or a non-finite
    answer."""
    for k in range(m):
        p = k
        for i in range(k + 1, m):
            if abs(A[i, k]) > abs(A[p, k]):
                p = i
        if A[p, k] == 0.0:
            return False
        if p != k:
            for j in range(m):
                A[k, j], A[p, j] = A[p, j], A[k, j]
            x[k], x[p] = x[p], x[k]
        for i in range(k + 1, m):
            f = A[i, k] / A[k, k]
            for j in range(k + 1, m):
                A[i, j] -= f * A[k, j]
            x[i] -= f * x[k]
    for i in range(m - 1, -1, -1):
        acc = x[i]
        for j in range(i + 1, m):
            acc -= A[i, j] * x[j]
        x[i] = acc / A[i, i]
        if not math.isfinite(x[i]):
            return False
    return True
