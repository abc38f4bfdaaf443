"""Compiled (numba) solves of one line between two given end positions, with the line's
exact end stiffness, for the system Newton of :mod:`._system_fast`.

A line hanging free: the Newton of :func:`._fast.solve_cases` (end B fixed) on the
tension at A, and G = J^-1 from its flexibility J = d(r_B - r_A)/d T_A at the solution.
A line anchored at A on the seabed: the Newton of :func:`._fast_contact.contact_cases`
on y = (alpha, beta, s_td), and K_BB = N M^-1 (M = d r_B / dy, N = d T(L) / dy), as
:func:`.line_stiffness.line_end_stiffness`. Pure: arrays in, arrays out.
"""

from __future__ import annotations

import math

import numpy as np

from ._fast import _free_newton, _offsets, njit  # noqa: F401 - _offsets re-exported
from ._fast_contact import NUMERICAL, _contact_newton, _guess, _laid


@njit(cache=True, error_model="numpy")
def _inv3(A: np.ndarray, out: np.ndarray) -> bool:
    """``out`` = A^-1 for a 3 x 3 ``A`` (cofactors); False if singular or not finite."""
    c00 = A[1, 1] * A[2, 2] - A[1, 2] * A[2, 1]
    c01 = A[1, 2] * A[2, 0] - A[1, 0] * A[2, 2]
    c02 = A[1, 0] * A[2, 1] - A[1, 1] * A[2, 0]
    det = A[0, 0] * c00 + A[0, 1] * c01 + A[0, 2] * c02
    if det == 0.0 or not math.isfinite(det):
        return False
    inv = 1.0 / det
    out[0, 0] = c00 * inv
    out[1, 0] = c01 * inv
    out[2, 0] = c02 * inv
    out[0, 1] = (A[0, 2] * A[2, 1] - A[0, 1] * A[2, 2]) * inv
    out[1, 1] = (A[0, 0] * A[2, 2] - A[0, 2] * A[2, 0]) * inv
    out[2, 1] = (A[0, 1] * A[2, 0] - A[0, 0] * A[2, 1]) * inv
    out[0, 2] = (A[0, 1] * A[1, 2] - A[0, 2] * A[1, 1]) * inv
    out[1, 2] = (A[0, 2] * A[1, 0] - A[0, 0] * A[1, 2]) * inv
    out[2, 2] = (A[0, 0] * A[1, 1] - A[0, 1] * A[1, 0]) * inv
    for i in range(3):
        for j in range(3):
            if not math.isfinite(out[i, j]):
                return False
    return True


@njit(cache=True, error_model="numpy")
def _free_line(
    ell: np.ndarray,
    EA: np.ndarray,
    w: np.ndarray,
    C: np.ndarray,
    L: float,
    d: np.ndarray,
    TA: np.ndarray,
    tol: float,
    maxit: int,
    J: np.ndarray,
    r: np.ndarray,
    rn: np.ndarray,
    Jn: np.ndarray,
    Tn: np.ndarray,
    g: np.ndarray,
    step: np.ndarray,
    free: np.ndarray,
) -> bool:
    """A line hanging free with r_B - r_A = ``d``: Newton on T_A (in/out ``TA``) on the
    complementary energy, as :func:`._fast.solve_cases` with end B fixed; ``J`` the
    flexibility at the solution. False where it does not converge."""
    for k in range(3):
        free[k] = True
    tn = math.sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2])
    ok, _, _ = _free_newton(
        TA, C, w, ell, EA, d, free, max(L, tn), tol, maxit, r, J, rn, Jn, Tn, g, step
    )
    return ok


@njit(cache=True, error_model="numpy")
def _contact_line(
    ell: np.ndarray,
    EA: np.ndarray,
    w: np.ndarray,
    point: np.ndarray,
    bounds: np.ndarray,
    rA: np.ndarray,
    rB: np.ndarray,
    normal: np.ndarray,
    bas: np.ndarray,
    mu: float,
    still: bool,
    tol: float,
    maxit: int,
    y: np.ndarray,
    warm: bool,
    fa: np.ndarray,
    fb: np.ndarray,
    Kbb: np.ndarray,
    sc: np.ndarray,
    sc3: np.ndarray,
    t_lo: np.ndarray,
    t_hi: np.ndarray,
    rate: np.ndarray,
    hi_s: np.ndarray,
    A: np.ndarray,
) -> int:
    """A line anchored at A on the seabed, B fixed above it: the Newton of
    :func:`._fast_contact.contact_cases` on y = (alpha, beta, s_td) (in/out ``y``, from
    its start :func:`._fast_contact._guess` unless ``warm``); at the solution the end
    forces ``fa``, ``fb`` and K_BB = N M^-1. Returns 0 or the contact kernel's status."""
    P = w.shape[0]
    L = bounds[P]
    Fscale = 0.0
    wsum = 0.0
    for p in range(P):
        Fscale += abs(w[p]) * ell[p]
        wsum += w[p] * ell[p]
    Fscale = max(Fscale, 1e-300)
    zero3 = sc[0]
    if not warm:
        st = _guess(L, wsum / L, rA, rB, normal, bas, still, 0, zero3, y)
        if st != 0:
            return st
    R = sc[1]
    Rn = sc[2]
    yn = sc[3]
    stp = sc[4]
    rs = sc[5]
    e = sc[6]
    T = sc[7]
    dr = sc[8]
    lp = sc[9]
    Jm = sc3[0]
    Jn = sc3[1]
    Js = sc3[2]
    jac = sc3[3]
    st, _, _ = _contact_newton(
        y, bas, rA, rB, 0, zero3, Fscale, L, bounds, w, sc[:0], EA, point, normal, mu, tol, maxit,
        R, Rn, Jm, Jn, yn, stp, A, T, e, t_lo, t_hi, rate, hi_s, lp, dr, jac, rs, Js,
    )  # fmt: skip
    if st != 0:
        return st
    # the end forces at the solution
    s_td = y[2]
    for i in range(3):
        T[i] = bas[i, 0] * y[0] + bas[i, 1] * y[1]
    tn = math.sqrt(T[0] * T[0] + T[1] * T[1] + T[2] * T[2])
    for i in range(3):
        e[i] = T[i] / tn
    _laid(s_td, tn, e, bounds, w, EA, point, normal, mu, t_lo, t_hi, rate, hi_s, lp)
    kt = 0
    for p in range(1, P):
        if bounds[p] <= s_td:
            kt = p
    Cx, Cy, Cz = 0.0, 0.0, 0.0
    for p in range(kt, P):
        if p > kt:
            Cx += point[p, 0]
            Cy += point[p, 1]
            Cz += point[p, 2]
        Cz -= w[p] * (bounds[p + 1] - (s_td if p == kt else bounds[p]))
    Cx += point[P, 0]
    Cy += point[P, 1]
    Cz += point[P, 2]
    for k in range(3):
        fa[k] = lp[3] * e[k]
    fb[0] = -(T[0] - Cx)
    fb[1] = -(T[1] - Cy)
    fb[2] = -(T[2] - Cz)
    # K_BB = N M^-1: M = L Jm (d r_B / dy), N = [e1, e2, q of the touchdown piece]
    for i in range(3):
        for j in range(3):
            Jn[i, j] = L * Jm[i, j]
    if not _inv3(Jn, Js):
        return NUMERICAL
    for i in range(3):
        n0 = bas[i, 0]
        n1 = bas[i, 1]
        n2 = -w[kt] if i == 2 else 0.0
        for j in range(3):
            Kbb[i, j] = n0 * Js[0, j] + n1 * Js[1, j] + n2 * Js[2, j]
    return 0


@njit(cache=True, error_model="numpy")
def _slack_line(
    ell: np.ndarray,
    EA: np.ndarray,
    w: np.ndarray,
    point: np.ndarray,
    rA: np.ndarray,
    rB: np.ndarray,
    normal: np.ndarray,
    depth: float,
    fa: np.ndarray,
    fb: np.ndarray,
    Kbb: np.ndarray,
) -> bool:
    """A line anchored at A on the seabed lying slack (longer than the path straight down
    from B and along the seabed): its end forces and K_BB as :func:`.system_slack.
    slack_forces` (the part hanging straight down from B to a zero-tension foot, a
    point load at the foot carried in proportion; nothing at A, K_BB only in its
    vertical row). False where that state does not apply (not slack, a piece lighter
    than the fluid, a point load not straight down)."""
    P = w.shape[0]
    for p in range(P):
        if not w[p] > 0.0:
            return False
    for p in range(P + 1):
        if point[p, 0] != 0.0 or point[p, 1] != 0.0 or point[p, 2] > 0.0:
            return False
    above = rB[0] * normal[0] + rB[1] * normal[1] + (rB[2] + depth) * normal[2]
    h = above / normal[2]
    if not h > 0.0:
        return False
    # from B down: pieces P-1 .. 0, the load at the top of each piece (its B-side end)
    top = 0.0
    S = -1.0
    W = 0.0
    k = 0.0
    for jj in range(P):
        j = P - 1 - jj  # the piece in line order
        if jj > 0 and -point[j + 1, 2] > 0.0:  # the foot at this load: carried in part
            h0, T0, flex = _column_b(ell, EA, w, point, j + 1, 0.0, 0.0)
            h1, _, _ = _column_b(ell, EA, w, point, j + 1, 0.0, 1.0)
            if h <= h1:
                phi = (h - h0) / (h1 - h0) if h1 > h0 else 1.0
                S = top
                W = T0 - phi * point[j + 1, 2]
                k = 1.0 / max(flex, 1e-300)
                break
        h_end, _, _ = _column_b(ell, EA, w, point, j, ell[j], 1.0)
        if h <= h_end:
            lo, hi = 0.0, ell[j]
            for _ in range(200):
                mid = 0.5 * (lo + hi)
                if _column_b(ell, EA, w, point, j, mid, 1.0)[0] < h:
                    lo = mid
                else:
                    hi = mid
                if hi - lo <= 1e-15 * max(ell[j], 1.0):
                    break
            x = 0.5 * (lo + hi)
            _, W, flex = _column_b(ell, EA, w, point, j, x, 1.0)
            S = top + x
            k = w[j] / (1.0 + w[j] * flex)
            break
        top += ell[j]
    if S < 0.0:
        return False
    L = 0.0
    for p in range(P):
        L += ell[p]
    fx = rB[0] - rA[0]
    fy = rB[1] - rA[1]
    fz = rB[2] - h - rA[2]
    if not L - S > math.sqrt(fx * fx + fy * fy + fz * fz):
        return False
    for i in range(3):
        fa[i] = 0.0
        fb[i] = point[P, i]
        for j in range(3):
            Kbb[i, j] = 0.0
    fb[2] -= W
    for j in range(3):
        Kbb[2, j] = k * normal[j] / normal[2]
    return True


@njit(cache=True, error_model="numpy")
def _column_b(
    ell: np.ndarray, EA: np.ndarray, w: np.ndarray, point: np.ndarray, j: int, x: float,
    phi: float,
) -> tuple[float, float, float]:  # fmt: skip
    """:func:`.system_slack._column` from end B: the foot ``x`` [m] below the B-side end
    of piece ``j`` (line order; with x = 0 the foot at boundary ``j``, its load carried
    with fraction ``phi``; with x > 0 the foot in piece j, the load at j + 1 whole):
    height [m], top tension [N], flexibility above the foot [m/N]."""
    P = w.shape[0]
    if x > 0.0:
        T = w[j] * x
        height = x + 0.5 * w[j] * x * x / EA[j]
        flex = x / EA[j]
        first = j + 1
    else:
        T = 0.0
        height = 0.0
        flex = 0.0
        first = j
    for i in range(first, P):
        f = -point[i, 2]
        T += f * (phi if (x == 0.0 and i == j) else 1.0)
        height += ell[i] + (T * ell[i] + 0.5 * w[i] * ell[i] * ell[i]) / EA[i]
        flex += ell[i] / EA[i]
        T += w[i] * ell[i]
    return height, T, flex
