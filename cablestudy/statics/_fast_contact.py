"""Compiled (numba) kernel of a still-water line anchored at end A on a plane seabed,
for batches of cases.

The mathematics is that of :func:`.semi_analytic_newton.solve_contact` (Newton on the tension
at the touchdown point in the seabed plane and the arc length of the touchdown point,
with the analytic Jacobian and the same line search from the same start,
:func:`.semi_analytic_newton.initial_contact`) and of :func:`.seabed.laid_part` (the laid part
straight along the touchdown tension, the tension falling towards the anchor at
k = w (sqrt((mu n_z)^2 - c^2) + e_z), c the weight's part across the line
(:func:`.seabed.along_friction`), and never below zero; Coulomb friction on point loads resting on
the seabed), for pieces under their weight only (:func:`._fast._piece`) with point loads
at piece boundaries, end B fixed above the seabed or given a known force (mooring or
towed end). Where the tension has fallen to zero the laid line is slack: its tension is
exactly 0 and it lies straight along the touchdown direction.

A case the kernel does not settle gets a nonzero status (:data:`LIFT_OFF`, ...) and is
left to the general solver by the caller; the kernel never guesses.
"""

from __future__ import annotations

import math

import numpy as np

from ._fast import _gauss, _piece, _piece_general, njit

# statuses of :func:`contact_cases`: in a module without numba, so that callers of the
# kernel compiled ahead of time read them without it
from .contact_status import (  # noqa: F401 - re-exported
    BELOW_SEABED,
    LIFT_OFF,
    NOT_CONVERGED,
    NUMERICAL,
    SLACK,
)
from .seabed import along_friction


@njit(cache=True, error_model="numpy")
def _dot3(a: np.ndarray, b: np.ndarray) -> float:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


_along = njit(cache=True, error_model="numpy")(along_friction)


@njit(cache=True, error_model="numpy")
def _laid(
    s_td: float,
    tn: float,
    e: np.ndarray,
    bounds: np.ndarray,
    w: np.ndarray,
    EA: np.ndarray,
    point: np.ndarray,
    normal: np.ndarray,
    mu: float,
    t_lo: np.ndarray,
    t_hi: np.ndarray,
    rate: np.ndarray,
    hi_s: np.ndarray,
    out: np.ndarray,
) -> int:
    """The laid part from the anchor (s = 0) to the TDP ``s_td`` [m] with tension ``tn``
    [N] there along the unit vector ``e``: per laid piece j (layout piece j, cut at
    ``s_td``) its tension at the anchor end ``t_lo[j]`` and TDP end ``t_hi[j]`` [N] (after
    any point load at that boundary), rate ``rate[j]`` [N/m] and TDP-side end ``hi_s[j]``
    [m]. ``out`` = (stretched laid length [m], sum of dl / EA over the tensioned length
    [m/N], rate at the TDP [N/m], tension at the anchor [N]). Returns the number of laid
    pieces. As :func:`.seabed.laid_part` for linear pieces."""
    P = w.shape[0]
    m = 0  # boundaries strictly inside (0, s_td)
    for p in range(1, P + 1):
        if bounds[p] < s_td:
            m += 1
    npc = m + 1
    ez = e[2]
    stretched = 0.0
    flex = 0.0
    t_up = max(tn, 0.0)  # tension at the TDP end of the piece being marched
    for j in range(npc - 1, -1, -1):
        lo = bounds[j]
        hi = bounds[j + 1] if j < m else s_td
        ell = hi - lo
        th = t_up
        if j < m:  # a point load at boundary j + 1 (on the seabed): friction and along-line
            f = point[j + 1]
            if f[0] != 0.0 or f[1] != 0.0 or f[2] != 0.0:
                fn = _dot3(f, normal)
                th = max(th - (mu * max(0.0, -fn) - _dot3(f, e)), 0.0)
        k = w[j] * (_along(mu, normal, e) + ez)
        tl = th - k * ell
        if tl >= 0.0:
            positive = ell
            area = 0.5 * ell * (th + tl)
        else:
            positive = th / k if k > 0.0 else ell
            area = 0.5 * th * positive
            tl = 0.0
        if th <= 0.0:
            positive = 0.0
            area = 0.0
        t_lo[j] = max(tl, 0.0)
        t_hi[j] = max(th, 0.0)
        rate[j] = k
        hi_s[j] = hi
        stretched += ell + area / EA[j]
        flex += positive / EA[j]
        t_up = t_lo[j]
    out[0] = stretched
    out[1] = flex
    out[2] = rate[npc - 1]
    out[3] = t_lo[0]
    return npc


@njit(cache=True, error_model="numpy")
def _load(q: np.ndarray, w: np.ndarray, p: int) -> tuple[float, float, float]:
    """The load of piece ``p`` [N/m]: ``q[p]``, or (0, 0, -``w[p]``) where ``q`` is empty."""
    if q.shape[0] == 0:
        return 0.0, 0.0, -w[p]
    return q[p, 0], q[p, 1], q[p, 2]


@njit(cache=True, error_model="numpy")
def _loaded_piece(
    tx: float, ty: float, tz: float, qx: float, qy: float, qz: float, ell: float, EA: float,
    dr: np.ndarray, jac: np.ndarray, want: bool,
) -> None:  # fmt: skip
    """A suspended piece under the load (qx, qy, qz): :func:`._fast._piece` where it is
    vertical (the weight alone, bit for bit as before), else :func:`._fast._piece_general`."""
    if qx == 0.0 and qy == 0.0:
        _piece(tx, ty, tz, -qz, ell, EA, dr, jac, want)
    else:
        _piece_general(tx, ty, tz, qx, qy, qz, ell, EA, dr, jac, want)


@njit(cache=True, error_model="numpy")
def _evaluate(
    y: np.ndarray,
    basis: np.ndarray,
    rA: np.ndarray,
    target: np.ndarray,
    kind: int,
    force: np.ndarray,
    Fscale: float,
    L: float,
    bounds: np.ndarray,
    w: np.ndarray,
    q: np.ndarray,
    EA: np.ndarray,
    point: np.ndarray,
    normal: np.ndarray,
    mu: float,
    R: np.ndarray,
    Jm: np.ndarray,
    T: np.ndarray,
    e: np.ndarray,
    t_lo: np.ndarray,
    t_hi: np.ndarray,
    rate: np.ndarray,
    hi_s: np.ndarray,
    lp: np.ndarray,
    dr: np.ndarray,
    jac: np.ndarray,
    rs: np.ndarray,
    Js: np.ndarray,
) -> None:
    """Residual ``R`` and its Jacobian ``Jm`` (3, 3) with respect to y = (alpha, beta,
    s_td), T_td = alpha e1 + beta e2, as the ``evaluate`` of
    :func:`.semi_analytic_newton.solve_contact`, the laid part under the weight ``w``,
    the suspended pieces under the loads ``q`` (P, 3) [N/m] (weight and drag; empty
    (0, 3): the weight alone): ``kind`` 0 (end B fixed at ``target``)
    R = (r_B(y) - r_B) / L; 1 (mooring: horizontal ``force`` on the line at B and B's
    height ``target[2]``) the horizontal components of (T(L) - force) / ``Fscale`` and
    (z_B(y) - z_B) / L; 2 (a known ``force``) (T(L) - force) / ``Fscale``. The arrays
    after ``Jm`` are scratch space (sizes as in :func:`contact_cases`)."""
    P = w.shape[0]
    for i in range(3):
        T[i] = basis[i, 0] * y[0] + basis[i, 1] * y[1]
    tn = math.sqrt(T[0] * T[0] + T[1] * T[1] + T[2] * T[2])
    for i in range(3):
        e[i] = T[i] / tn
    s_td = y[2]
    _laid(s_td, tn, e, bounds, w, EA, point, normal, mu, t_lo, t_hi, rate, hi_s, lp)
    stretched, pf, rate_td = lp[0], lp[1], lp[2]
    # suspended pieces: from s_td to the end of its piece k, then k + 1 ... P - 1
    k = 0
    for p in range(1, P):
        if bounds[p] <= s_td:
            k = p
    for i in range(3):
        rs[i] = 0.0
        for j in range(3):
            Js[i, j] = 0.0
    Cx, Cy, Cz = 0.0, 0.0, 0.0
    for p in range(k, P):
        ell = bounds[p + 1] - (s_td if p == k else bounds[p])
        if p > k:
            Cx += point[p, 0]
            Cy += point[p, 1]
            Cz += point[p, 2]
        qx, qy, qz = _load(q, w, p)
        _loaded_piece(T[0] - Cx, T[1] - Cy, T[2] - Cz, qx, qy, qz, ell, EA[p], dr, jac, True)
        Cx += qx * ell
        Cy += qy * ell
        Cz += qz * ell
        for i in range(3):
            rs[i] += dr[i]
            for j in range(3):
                Js[i, j] += jac[i, j]
    qx, qy, qz = _load(q, w, k)
    for i in range(3):
        rB = rA[i] + e[i] * stretched + rs[i]
        R[i] = (rB - target[i]) / L
        for c in range(2):
            v = 0.0
            for j in range(3):
                d = Js[i, j] + e[i] * e[j] * pf
                if i == j:
                    d += stretched / tn
                d -= stretched * e[i] * e[j] / tn
                v += d * basis[j, c]
            Jm[i, c] = v / L
        Jm[i, 2] = (Js[i, 2] * qz + (Js[i, 0] * qx + Js[i, 1] * qy) - e[i] * rate_td * pf) / L
    if kind != 0:  # T(L) = T_td - C_end; d T(L) / d s_td = q of the touchdown piece
        TL0 = T[0] - Cx - point[P, 0]
        TL1 = T[1] - Cy - point[P, 1]
        TL2 = T[2] - Cz - point[P, 2]
        rows = 2 if kind == 1 else 3
        for i in range(rows):
            R[i] = ((TL0, TL1, TL2)[i] - force[i]) / Fscale
            Jm[i, 0] = basis[i, 0] / Fscale
            Jm[i, 1] = basis[i, 1] / Fscale
            Jm[i, 2] = (qx, qy, qz)[i] / Fscale


@njit(cache=True, error_model="numpy")
def _newton_step(J: np.ndarray, R: np.ndarray, A: np.ndarray, step: np.ndarray) -> bool:
    """step = -J^-1 R for a 3 x 3 ``J`` (Gaussian elimination with partial pivoting in the
    scratch ``A`` (3, 4)); False when ``J`` is singular or not finite."""
    for i in range(3):
        for j in range(3):
            A[i, j] = J[i, j]
        A[i, 3] = -R[i]
    return _gauss(A, 3, step)


@njit(cache=True, error_model="numpy")
def _excess(H: float, L: float, h: float, w: float, X: float) -> float:
    """Reach along the seabed minus the horizontal distance to B [m] of the inextensible
    line of weight ``w`` [N/m] with horizontal tension ``H`` [N], height ``h`` [m]."""
    return L - math.sqrt(h * h + 2.0 * h * H / w) + H / w * math.acosh(1.0 + w * h / H) - X


@njit(cache=True, error_model="numpy")
def _guess(
    L: float,
    wbar: float,
    rA: np.ndarray,
    rB: np.ndarray,
    normal: np.ndarray,
    basis: np.ndarray,
    still: bool,
    kind: int,
    force: np.ndarray,
    y: np.ndarray,
) -> int:
    """The start y = (T_td . e1, T_td . e2, s_td) of :func:`.semi_analytic_newton.initial_contact`
    for a fixed end B (``kind`` 0; ``rB`` its position) or a known force at B (1, 2;
    ``rB[2]`` B's height, 0 for a towed end, as there); returns 0, or :data:`SLACK`
    (``still``, B fixed and the line slack on the seabed)."""
    w = max(wbar * normal[2], 1e-12)
    if kind != 0:
        h = max(rB[2] - rA[2], 1e-9 * L)
        fn = force[0] * normal[0] + force[1] * normal[1]
        p0, p1, p2 = force[0] - fn * normal[0], force[1] - fn * normal[1], -fn * normal[2]
        H = math.sqrt(force[0] * force[0] + force[1] * force[1])
        pn = math.sqrt(p0 * p0 + p1 * p1 + p2 * p2)
        if pn > 0.0:
            e0, e1, e2 = p0 / pn, p1 / pn, p2 / pn
        else:
            e0, e1, e2 = basis[0, 0], basis[1, 0], basis[2, 0]
        Ls = min(math.sqrt(h * h + 2.0 * h * H / w), L)
        y[0] = H * (e0 * basis[0, 0] + e1 * basis[1, 0] + e2 * basis[2, 0])
        y[1] = H * (e0 * basis[0, 1] + e1 * basis[1, 1] + e2 * basis[2, 1])
        y[2] = max(L - Ls, 0.0)
        return 0
    d0, d1, d2 = rB[0] - rA[0], rB[1] - rA[1], rB[2] - rA[2]
    dn = d0 * normal[0] + d1 * normal[1] + d2 * normal[2]
    h = max(dn, 1e-9 * L)
    p0, p1, p2 = d0 - dn * normal[0], d1 - dn * normal[1], d2 - dn * normal[2]
    X = math.sqrt(p0 * p0 + p1 * p1 + p2 * p2)
    if X > 0.0:
        e0, e1, e2 = p0 / X, p1 / X, p2 / X
    else:
        e0, e1, e2 = basis[0, 0], basis[1, 0], basis[2, 0]
    if still and L - h - X > 1e-9 * L:
        return SLACK
    Hmax = w * (L * L - h * h) / (2.0 * h) if L > h else w * L
    lo, hi = 1e-9 * w * L, Hmax
    # the reach grows with H: bracket the sign change of its excess over X, narrowed by
    # bisection (in log H) to 1 %, then by the Illinois false-position method (the
    # bracket shrinks from both sides, superlinearly) to the 1e-12 of initial_contact's
    # bisection: the same start to that precision, in about 10 evaluations instead of 45
    f_hi = _excess(hi, L, h, w, X)
    f_lo = _excess(lo, L, h, w, X)
    if f_hi <= 0.0:
        H = hi
    elif f_lo >= 0.0:
        H = lo
    else:
        side = 0
        for _ in range(80):
            if hi <= lo * (1.0 + 1e-12):
                break
            if hi > lo * 1.01:
                mid = math.sqrt(lo * hi)
            else:
                mid = hi - f_hi * (hi - lo) / (f_hi - f_lo)
                if not lo < mid < hi:
                    mid = 0.5 * (lo + hi)
            f = _excess(mid, L, h, w, X)
            if f > 0.0:
                hi, f_hi = mid, f
                if side == 1 and hi <= lo * 1.01:
                    f_lo *= 0.5
                side = 1
            else:
                lo, f_lo = mid, f
                if side == -1 and hi <= lo * 1.01:
                    f_hi *= 0.5
                side = -1
        H = math.sqrt(lo * hi)
    Ls = min(math.sqrt(h * h + 2.0 * h * H / w), L)
    y[0] = H * (e0 * basis[0, 0] + e1 * basis[1, 0] + e2 * basis[2, 0])
    y[1] = H * (e0 * basis[0, 1] + e1 * basis[1, 1] + e2 * basis[2, 1])
    y[2] = max(L - Ls, 0.0)
    return 0  # from s_td = 0 too: the Newton iteration decides whether it lifts off


@njit(cache=True, error_model="numpy")
def _contact_newton(
    y: np.ndarray,
    bas: np.ndarray,
    rA: np.ndarray,
    target: np.ndarray,
    kind: int,
    force: np.ndarray,
    Fscale: float,
    L: float,
    bounds: np.ndarray,
    w: np.ndarray,
    q: np.ndarray,
    EA: np.ndarray,
    point: np.ndarray,
    nrm: np.ndarray,
    mu: float,
    tol: float,
    maxit: int,
    R: np.ndarray,
    Rn: np.ndarray,
    Jm: np.ndarray,
    Jn: np.ndarray,
    yn: np.ndarray,
    step: np.ndarray,
    A: np.ndarray,
    T: np.ndarray,
    e: np.ndarray,
    t_lo: np.ndarray,
    t_hi: np.ndarray,
    rate: np.ndarray,
    hi_s: np.ndarray,
    lp: np.ndarray,
    dr: np.ndarray,
    jac: np.ndarray,
    rs: np.ndarray,
    Js: np.ndarray,
) -> tuple[int, int, float]:
    """The Newton iteration with line search on y = (alpha, beta, s_td) (in/out ``y``,
    from its start), shared by :func:`contact_cases` and the system's
    :func:`._system_lines._contact_line`: arguments as :func:`_evaluate` (``R``, ``Jm``
    the residual and Jacobian at the final ``y``; the rest scratch). Returns (status,
    iterations, final residual max |R|): 0, or :data:`NOT_CONVERGED`, :data:`LIFT_OFF`,
    :data:`SLACK` or :data:`NUMERICAL`."""
    _evaluate(
        y, bas, rA, target, kind, force, Fscale, L, bounds, w, q, EA, point, nrm, mu, R, Jm,
        T, e, t_lo, t_hi, rate, hi_s, lp, dr, jac, rs, Js,
    )  # fmt: skip
    res = max(abs(R[0]), max(abs(R[1]), abs(R[2])))
    polish = 0
    at_zero = 0
    it = 0
    st = 0
    while True:
        if not math.isfinite(res):
            st = NUMERICAL
            break
        if res <= tol:
            if polish >= 1 or res <= 1e-15:
                break
            polish += 1
        if it >= maxit:
            st = NOT_CONVERGED
            break
        it += 1
        if not _newton_step(Jm, R, A, step):
            st = NUMERICAL
            break
        norm0 = math.sqrt(R[0] * R[0] + R[1] * R[1] + R[2] * R[2])
        ny = math.sqrt(y[0] * y[0] + y[1] * y[1])
        lam = 1.0
        accepted = False
        for _ in range(40):
            for k in range(3):
                yn[k] = y[k] + lam * step[k]
            # keep the TDP on the line and the tension positive
            yn[2] = min(max(yn[2], 0.0), L * (1.0 - 1e-9))
            if math.sqrt(yn[0] * yn[0] + yn[1] * yn[1]) <= 1e-3 * ny:
                yn[0] = y[0] * 1e-3
                yn[1] = y[1] * 1e-3
            _evaluate(
                yn, bas, rA, target, kind, force, Fscale, L, bounds, w, q, EA, point, nrm, mu,
                Rn, Jn, T, e, t_lo, t_hi, rate, hi_s, lp, dr, jac, rs, Js,
            )  # fmt: skip
            nn = math.sqrt(Rn[0] * Rn[0] + Rn[1] * Rn[1] + Rn[2] * Rn[2])
            if math.isfinite(nn) and nn <= (1.0 - 1e-4 * lam) * norm0 + 1e-15:
                accepted = True
                break
            lam *= 0.5
        if not accepted:
            st = SLACK if ny < 1e-3 * Fscale else NOT_CONVERGED
            break
        for k in range(3):
            y[k] = yn[k]
            R[k] = Rn[k]
            for m in range(3):
                Jm[k, m] = Jn[k, m]
        res = max(abs(R[0]), max(abs(R[1]), abs(R[2])))
        if math.sqrt(y[0] * y[0] + y[1] * y[1]) < 1e-9 * Fscale and res > tol:
            st = SLACK
            break
        if y[2] <= 0.0:
            at_zero += 1
            if at_zero >= 2:
                st = LIFT_OFF
                break
        else:
            at_zero = 0
    if st == 0 and y[2] <= 0.0:
        st = LIFT_OFF
    return st, it, res


@njit(cache=True, error_model="numpy")
def contact_cases(
    ell: np.ndarray,
    EA: np.ndarray,
    w: np.ndarray,
    point: np.ndarray,
    bounds: np.ndarray,
    rA: np.ndarray,
    rB: np.ndarray,
    kind: np.ndarray,
    force: np.ndarray,
    normal: np.ndarray,
    basis: np.ndarray,
    depth: np.ndarray,
    mu: np.ndarray,
    still: np.ndarray,
    tol: np.ndarray,
    maxit: np.ndarray,
    s: np.ndarray,
    pos: np.ndarray,
    tension: np.ndarray,
    force_a: np.ndarray,
    force_b: np.ndarray,
    laid_length: np.ndarray,
    iters: np.ndarray,
    resid: np.ndarray,
    status: np.ndarray,
) -> None:
    """Solve N lines anchored at A on a plane seabed with B fixed above it, and sample them
    at ``s`` (N, n) [m].

    Per case: pieces ``ell``, ``EA``, ``w`` (N, P) [m, N, N/m] between ``bounds`` (N, P + 1)
    [m], point loads on the line ``point`` (N, P + 1, 3) [N] at the boundaries, the
    anchor ``rA`` (N, 3) [m] and end B: ``kind`` (N,) 0 fixed at ``rB`` (N, 3) [m], 1
    mooring (horizontal ``force`` (N, 3) [N] on the line, height ``rB[:, 2]``), 2 a known
    ``force`` on the line (``rB[:, 2]`` 0); the seabed through (0, 0, -``depth``) with upward unit
    ``normal`` (N, 3), in-plane ``basis`` (N, 3, 2) (e1, e2 as columns), friction ``mu``;
    ``still`` (N,) True where the seabed is flat (a line longer than the path along the
    seabed and up to B is then refused as slack before the Newton iteration, as the
    general solver does). Outputs: positions ``pos`` (N, n, 3) [m], ``tension`` (N, n)
    [N], the forces of the line on its ends ``force_a``, ``force_b`` (N, 3) [N], the laid
    length (N,) [m], Newton iterations, the final residual (max |r_B - r_B target| / L)
    and ``status`` (0 converged and above the seabed, else :data:`NOT_CONVERGED`,
    :data:`LIFT_OFF`, :data:`SLACK`, :data:`NUMERICAL` or :data:`BELOW_SEABED`)."""
    N, P = ell.shape
    n = s.shape[1]
    y = np.zeros(3)
    yn = np.zeros(3)
    R = np.zeros(3)
    Rn = np.zeros(3)
    Jm = np.zeros((3, 3))
    Jn = np.zeros((3, 3))
    step = np.zeros(3)
    A = np.zeros((3, 4))
    rs = np.zeros(3)
    Js = np.zeros((3, 3))
    e = np.zeros(3)
    T = np.zeros(3)
    t_lo = np.empty(P)
    t_hi = np.empty(P)
    rate = np.empty(P)
    hi_s = np.empty(P)
    lp = np.empty(4)
    M = 3 * P
    ps0 = np.empty(M)
    pell = np.empty(M)
    pT0 = np.empty((M, 3))
    pq = np.empty((M, 3))
    pEA = np.empty(M)
    pkind = np.empty(M, dtype=np.int64)  # 0 slack on the seabed, 1 laid, 2 suspended
    pr0 = np.empty((M, 3))
    q = np.zeros((0, 3))
    dr = np.zeros(3)
    jac = np.zeros((3, 3))
    for c in range(N):
        L = bounds[c, P]
        nrm = normal[c]
        bas = basis[c]
        Fscale = 0.0
        wsum = 0.0
        for p in range(P):
            Fscale += abs(w[c, p]) * ell[c, p]
            wsum += w[c, p] * ell[c, p]
        Fscale = max(Fscale, 1e-300)
        kc = kind[c]
        if kc != 0:
            f = force[c]
            Fscale = max(Fscale, math.sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]))
        st = _guess(L, wsum / L, rA[c], rB[c], nrm, bas, still[c], kc, force[c], y)
        it = 0
        res = math.nan
        if st == 0:
            st, it, res = _contact_newton(
                y, bas, rA[c], rB[c], kc, force[c], Fscale, L, bounds[c], w[c], q, EA[c],
                point[c], nrm, mu[c], tol[c], maxit[c], R, Rn, Jm, Jn, yn, step, A,
                T, e, t_lo, t_hi, rate, hi_s, lp, dr, jac, rs, Js,
            )  # fmt: skip
        iters[c] = it
        resid[c] = res
        laid_length[c] = y[2] if st == 0 else math.nan
        if st != 0:
            status[c] = st
            for i in range(n):
                tension[c, i] = math.nan
                for k in range(3):
                    pos[c, i, k] = math.nan
            for k in range(3):
                force_a[c, k] = math.nan
                force_b[c, k] = math.nan
            continue
        # the solved line as pieces, sampled at s
        pcs = (ps0, pell, pT0, pq, pEA, pkind, pr0)
        work = (t_lo, t_hi, rate, hi_s, lp, e, T, dr, jac)
        np_ = _pieces(y, bas, rA[c], bounds[c], w[c], q, EA[c], point[c], nrm, mu[c], pcs, work, R)
        ok, low = _sample(
            np_, pcs, e, s[c], L, lp[3], R, nrm, depth[c], pos[c], tension[c], dr, jac
        )
        for k in range(3):
            force_a[c, k] = lp[3] * e[k]
            force_b[c, k] = -R[k]
        if not ok:
            status[c] = NUMERICAL
        elif -low > max(1e-6 * L, 1e3 * tol[c] * L):
            status[c] = BELOW_SEABED
        else:
            status[c] = 0


@njit(cache=True, error_model="numpy")
def _pieces(
    y: np.ndarray, bas: np.ndarray, rA: np.ndarray, bounds: np.ndarray, w: np.ndarray,
    q: np.ndarray, EA: np.ndarray, point: np.ndarray, nrm: np.ndarray, mu: float,
    pcs: tuple, work: tuple, TL: np.ndarray,
) -> int:  # fmt: skip
    """The line solved at y = (alpha, beta, s_td) (loads as :func:`_evaluate`) as pieces
    in order along s: laid (slack, then tensioned), then suspended, into ``pcs`` = (start
    [m], length [m], tension vector at the start [N], load [N/m], EA [N], kind (0 slack on
    the seabed, 1 laid, 2 suspended), start position [m]), each (3 P) long; T(L) into
    ``TL``; ``work`` = (t_lo, t_hi, rate, hi_s, lp, e, T, dr, jac) as :func:`_laid` and
    :func:`_evaluate` (after it: lp[3] the tension at the anchor, ``e`` the laid
    direction). Returns the number of pieces."""
    ps0, pell, pT0, pq, pEA, pkind, pr0 = pcs
    t_lo, t_hi, rate, hi_s, lp, e, T, dr, jac = work
    P = w.shape[0]
    s_td = y[2]
    for i in range(3):
        T[i] = bas[i, 0] * y[0] + bas[i, 1] * y[1]
    tn = math.sqrt(T[0] * T[0] + T[1] * T[1] + T[2] * T[2])
    for i in range(3):
        e[i] = T[i] / tn
    npc = _laid(s_td, tn, e, bounds, w, EA, point, nrm, mu, t_lo, t_hi, rate, hi_s, lp)
    np_ = 0
    for j in range(npc):
        lo = bounds[j]
        hi = hi_s[j]
        k_ = rate[j]
        slack_len = 0.0
        if t_hi[j] <= 0.0:
            slack_len = hi - lo
        elif t_hi[j] - k_ * (hi - lo) < 0.0 and k_ > 0.0:
            slack_len = (hi - lo) - t_hi[j] / k_
        for part in range(2):  # the slack length, then the tensioned rest
            length = slack_len if part == 0 else hi - lo - slack_len
            if length <= 0.0:
                continue
            ps0[np_] = lo if part == 0 else lo + slack_len
            pell[np_] = length
            pEA[np_] = EA[j]
            pkind[np_] = part
            for i in range(3):
                pT0[np_, i] = 0.0 if part == 0 else max(t_lo[j], 0.0) * e[i]
                pq[np_, i] = 0.0 if part == 0 else -k_ * e[i]
            np_ += 1
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
        ps0[np_] = s_td if p == kt else bounds[p]
        pell[np_] = bounds[p + 1] - ps0[np_]
        pEA[np_] = EA[p]
        pkind[np_] = 2
        pT0[np_, 0] = T[0] - Cx
        pT0[np_, 1] = T[1] - Cy
        pT0[np_, 2] = T[2] - Cz
        pq[np_, 0], pq[np_, 1], pq[np_, 2] = _load(q, w, p)
        Cx += pq[np_, 0] * pell[np_]
        Cy += pq[np_, 1] * pell[np_]
        Cz += pq[np_, 2] * pell[np_]
        np_ += 1
    TL[0] = T[0] - (Cx + point[P, 0])
    TL[1] = T[1] - (Cy + point[P, 1])
    TL[2] = T[2] - (Cz + point[P, 2])
    # start positions of the pieces
    x0, y0, z0 = rA[0], rA[1], rA[2]
    for j in range(np_):
        pr0[j, 0] = x0
        pr0[j, 1] = y0
        pr0[j, 2] = z0
        _increment(pkind[j], pT0[j], pq[j], pell[j], pEA[j], e, dr, jac)
        x0 += dr[0]
        y0 += dr[1]
        z0 += dr[2]
    return np_


@njit(cache=True, error_model="numpy")
def _sample(
    np_: int, pcs: tuple, e: np.ndarray, s: np.ndarray, L: float, ta: float, TL: np.ndarray,
    nrm: np.ndarray, depth: float, pos: np.ndarray, tension: np.ndarray, dr: np.ndarray,
    jac: np.ndarray,
) -> tuple[bool, float]:  # fmt: skip
    """The pieces ``pcs`` of :func:`_pieces` sampled at ``s`` (n,) [m] into ``pos`` (n, 3)
    and ``tension`` (n,) (``ta`` [N] at the anchor, |``TL``| at the end); returns (all
    finite, the least height above the seabed through (0, 0, -``depth``) with upward
    ``nrm`` [m])."""
    ps0, pell, pT0, pq, pEA, pkind, pr0 = pcs
    low = math.inf
    ok = True
    for i in range(s.shape[0]):
        si = s[i]
        j = 0
        while j < np_ - 1 and ps0[j + 1] <= si:
            j += 1
        sig = min(max(si - ps0[j], 0.0), pell[j])
        _increment(pkind[j], pT0[j], pq[j], sig, pEA[j], e, dr, jac)
        tv0 = pT0[j, 0] - pq[j, 0] * sig
        tv1 = pT0[j, 1] - pq[j, 1] * sig
        tv2 = pT0[j, 2] - pq[j, 2] * sig
        tension[i] = math.sqrt(tv0 * tv0 + tv1 * tv1 + tv2 * tv2)
        if si <= 0.0:
            tension[i] = abs(ta)
        if si >= L:
            tension[i] = math.sqrt(TL[0] * TL[0] + TL[1] * TL[1] + TL[2] * TL[2])
        for k in range(3):
            pos[i, k] = pr0[j, k] + dr[k]
            ok = ok and math.isfinite(pos[i, k])
        low = min(low, pos[i, 0] * nrm[0] + pos[i, 1] * nrm[1] + (pos[i, 2] + depth) * nrm[2])
        ok = ok and math.isfinite(tension[i])
    return ok, low


@njit(cache=True, error_model="numpy")
def _increment(
    kind: int,
    T0: np.ndarray,
    q: np.ndarray,
    sig: float,
    EA: float,
    e: np.ndarray,
    dr: np.ndarray,
    jac: np.ndarray,
) -> None:
    """Position increment over ``sig`` [m] of a piece: slack on the seabed (kind 0: straight
    along ``e``, no tension), laid (1: load along the line) or suspended (2: weight, drag)."""
    if kind == 0:
        for k in range(3):
            dr[k] = sig * e[k]
    elif kind == 1:
        _piece_general(T0[0], T0[1], T0[2], q[0], q[1], q[2], sig, EA, dr, jac, False)
    else:
        _loaded_piece(T0[0], T0[1], T0[2], q[0], q[1], q[2], sig, EA, dr, jac, False)
