"""Compiled (numba) kernels of the still-water semi-analytic solve, for batches of
cases. The mathematics is that of :mod:`.pieces` and :func:`.semi_analytic_newton.solve_free`
with the load of every piece vertical (weight only) and point loads at piece
boundaries; numba compiles it once per machine (cached on disk).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit


@njit(cache=True, error_model="numpy")
def _asinh_ratio(X: float) -> float:
    if abs(X) < 1e-4:
        return 1.0 - X * X / 6.0
    return math.asinh(X) / X


@njit(cache=True, error_model="numpy")
def _curve(
    curved: bool,
    V0: float,
    V1: float,
    H2: float,
    H: float,
    T0n: float,
    T1n: float,
    ell: float,
    wl: float,
) -> tuple[float, float, float]:
    """(P_l, A_1, H^2 J) of one piece of length ``ell`` > 0 under a load of total ``wl``
    along u, with the tension's components V0, V1 along u at its ends, H2 = H^2 across:
    the catenary whose V keeps its sign, the one where it changes sign, or the straight
    piece (not ``curved``: no load)."""
    a = abs(V0)
    b = abs(V1)
    Dn = b * T0n + a * T1n
    if curved and V0 * V1 > 0.0:
        X = (b - a) * (b + a) / Dn
        Pl = ell * (a + b) / Dn * _asinh_ratio(X)
        A1 = 0.5 * ell * (V0 + V1) * (V0 * V0 + V1 * V1 + H2) / (V1 * T1n + V0 * T0n)
        A1 += 0.5 * H2 * Pl
        H2J = H2 * ell * (a + b) / (T0n * T1n * Dn)
    elif curved and wl > 0.0:
        Hs = max(H, 1e-200 * (a + b))
        Pl = ell * (math.asinh(V1 / Hs) - math.asinh(V0 / Hs)) / wl
        A1 = 0.5 * ell * (V1 * T1n - V0 * T0n) / wl + 0.5 * H2 * Pl
        H2J = ell * (V1 / T1n - V0 / T0n) / wl
    else:
        Pl = ell / T0n
        A1 = ell * T0n
        H2J = H2 * ell / (T0n * T0n * T0n)
    return Pl, A1, H2J


@njit(cache=True, error_model="numpy")
def _flexibility(
    ell: float,
    V0: float,
    V1: float,
    H: float,
    T0n: float,
    T1n: float,
    Pl: float,
    H2J: float,
    inv_ea: float,
    hx: float,
    hy: float,
    hz: float,
    ux: float,
    uy: float,
    uz: float,
    jac: np.ndarray,
) -> None:
    """The flexibility d(dr)/dT of one piece into ``jac`` (3, 3) from its
    :func:`_curve` terms, its tension across the load h (|h| = H) and the load's
    direction u."""
    L1H = ell * (V0 + V1) * H / ((T0n + T1n) * T0n * T1n)
    K = Pl - H2J
    if H > 0.0:
        nx, ny, nz = hx / H, hy / H, hz / H
    else:
        nx, ny, nz = 0.0, 0.0, 0.0
    n = (nx, ny, nz)
    u = (ux, uy, uz)
    diag = inv_ea + Pl
    for i in range(3):
        for j in range(i, 3):
            v = -H2J * n[i] * n[j] - L1H * (n[i] * u[j] + u[i] * n[j]) - K * u[i] * u[j]
            if i == j:
                v += diag
            jac[i, j] = v
            jac[j, i] = v


@njit(cache=True, error_model="numpy")
def _piece(
    tx: float,
    ty: float,
    tz: float,
    w: float,
    ell: float,
    EA: float,
    dr: np.ndarray,
    jac: np.ndarray,
    want_jac: bool,
) -> float:
    """One piece under the vertical load q = (0, 0, -w) (w < 0 buoyant). Writes the
    increment into ``dr`` (3,) and, if asked, the flexibility into ``jac`` (3, 3);
    returns the complementary energy."""
    aw = abs(w)
    uz = 1.0 if w > 0.0 else (-1.0 if w < 0.0 else 0.0)
    V0 = tz * uz
    hz = tz - V0 * uz
    H2 = tx * tx + ty * ty + hz * hz
    wl = aw * ell
    V1 = V0 + wl
    T0n = math.sqrt(H2 + V0 * V0)
    T1n = math.sqrt(H2 + V1 * V1)
    H = math.sqrt(H2)
    if ell == 0.0:
        dr[0] = 0.0
        dr[1] = 0.0
        dr[2] = 0.0
        if want_jac:
            for i in range(3):
                for j in range(3):
                    jac[i, j] = 0.0
        return 0.0
    Pl, A1, H2J = _curve(aw > 0.0, V0, V1, H2, H, T0n, T1n, ell, wl)
    S1 = ell * (V0 + V1) / (T0n + T1n)
    inv_ea = ell / EA
    qz = -w
    dr[0] = tx * inv_ea + tx * Pl
    dr[1] = ty * inv_ea + ty * Pl
    dr[2] = tz * inv_ea - qz * 0.5 * ell * inv_ea + hz * Pl + uz * S1
    TT = tx * tx + ty * ty + tz * tz
    energy = A1 + (TT * ell - tz * qz * ell * ell + w * w * ell**3 / 3.0) / (2.0 * EA)
    if want_jac:
        _flexibility(ell, V0, V1, H, T0n, T1n, Pl, H2J, inv_ea, tx, ty, hz, 0.0, 0.0, uz, jac)
    return energy


@njit(cache=True, error_model="numpy")
def _total(
    TA: np.ndarray,
    C: np.ndarray,
    w: np.ndarray,
    ell: np.ndarray,
    EA: np.ndarray,
    r: np.ndarray,
    J: np.ndarray,
    want_jac: bool,
) -> float:
    P = ell.shape[0]
    dr = np.zeros(3)
    jac = np.zeros((3, 3))
    for k in range(3):
        r[k] = 0.0
        for m in range(3):
            J[k, m] = 0.0
    E = 0.0
    for p in range(P):
        E += _piece(
            TA[0] - C[p, 0],
            TA[1] - C[p, 1],
            TA[2] - C[p, 2],
            w[p],
            ell[p],
            EA[p],
            dr,
            jac,
            want_jac,
        )
        for k in range(3):
            r[k] += dr[k]
            if want_jac:
                for m in range(3):
                    J[k, m] += jac[k, m]
    return E


@njit(cache=True, error_model="numpy")
def _gauss(A: np.ndarray, n: int, x: np.ndarray) -> bool:
    """x[:n] solving A[:n, :n] x = A[:n, n] by Gaussian elimination with partial pivoting
    (``A`` overwritten); False where a pivot is zero or not finite."""
    for c in range(n):
        piv = c
        for i in range(c + 1, n):
            if abs(A[i, c]) > abs(A[piv, c]):
                piv = i
        if A[piv, c] == 0.0 or not math.isfinite(A[piv, c]):
            return False
        if piv != c:
            for j in range(n + 1):
                A[c, j], A[piv, j] = A[piv, j], A[c, j]
        for i in range(c + 1, n):
            f = A[i, c] / A[c, c]
            for j in range(c, n + 1):
                A[i, j] -= f * A[c, j]
    for i in range(n - 1, -1, -1):
        acc = A[i, n]
        for j in range(i + 1, n):
            acc -= A[i, j] * x[j]
        x[i] = acc / A[i, i]
    return True


@njit(cache=True, error_model="numpy")
def _solve3(J: np.ndarray, g: np.ndarray, free: np.ndarray, step: np.ndarray) -> bool:
    """step = -J^-1 g on the free components (Gaussian elimination, partial pivoting)."""
    idx = np.empty(3, dtype=np.int64)
    n = 0
    for k in range(3):
        step[k] = 0.0
        if free[k]:
            idx[n] = k
            n += 1
    A = np.zeros((3, 4))
    for i in range(n):
        for j in range(n):
            A[i, j] = J[idx[i], idx[j]]
        A[i, n] = -g[idx[i]]
    x = np.zeros(3)
    if not _gauss(A, n, x):
        return False
    for i in range(n):
        step[idx[i]] = x[i]
    return True


@njit(cache=True, error_model="numpy")
def _offsets(w: np.ndarray, ell: np.ndarray, point: np.ndarray, C: np.ndarray, Cend: np.ndarray):
    """T at the start of piece p = T_A - C[p]; ``Cend`` the loads on the whole line."""
    P = ell.shape[0]
    a0 = 0.0
    a1 = 0.0
    a2 = 0.0
    for p in range(P):
        a0 += point[p, 0]
        a1 += point[p, 1]
        a2 += point[p, 2]
        C[p, 0] = a0
        C[p, 1] = a1
        C[p, 2] = a2
        a2 += -w[p] * ell[p]
    Cend[0] = a0 + point[P, 0]
    Cend[1] = a1 + point[P, 1]
    Cend[2] = a2 + point[P, 2]


@njit(cache=True, error_model="numpy")
def _free_newton(
    TA: np.ndarray,
    C: np.ndarray,
    w: np.ndarray,
    ell: np.ndarray,
    EA: np.ndarray,
    target: np.ndarray,
    free: np.ndarray,
    scale: float,
    tol: float,
    maxit: int,
    r: np.ndarray,
    J: np.ndarray,
    rn: np.ndarray,
    Jn: np.ndarray,
    Tn: np.ndarray,
    g: np.ndarray,
    step: np.ndarray,
) -> tuple[bool, int, float]:
    """Newton with line search on the complementary energy for the tension at A (in/out
    ``TA``) of a line hanging free whose ``free`` components of r_B - r_A are the
    ``target``'s, shared by :func:`solve_cases` and the system's
    :func:`._system_lines._free_line`: ``r``, ``J`` the span and flexibility at the final
    ``TA`` (the rest scratch). Returns (converged, iterations, final residual max |g| /
    ``scale``)."""
    it = 0
    res = 0.0
    E = _total(TA, C, w, ell, EA, r, J, True)
    polished = False
    while True:
        res = 0.0
        for k in range(3):
            g[k] = r[k] - target[k] if free[k] else 0.0
            res = max(res, abs(g[k]))
        res /= scale
        if not math.isfinite(res):
            return False, it, res
        if res <= tol:
            if polished or res <= 1e-15:
                return True, it, res
            polished = True
        if it >= maxit:
            return False, it, res
        it += 1
        if not _solve3(J, g, free, step):
            return False, it, res
        slope = 0.0
        dot = 0.0
        for k in range(3):
            slope += g[k] * step[k]
            if free[k]:
                dot += target[k] * TA[k]
        psi = E - dot
        slack = 1e-13 * (abs(E) + abs(dot))
        lam = 1.0
        accepted = False
        En = 0.0
        for _ in range(80):
            dotn = 0.0
            for k in range(3):
                Tn[k] = TA[k] + lam * step[k]
                if free[k]:
                    dotn += target[k] * Tn[k]
            En = _total(Tn, C, w, ell, EA, rn, Jn, True)
            psin = En - dotn
            if math.isfinite(psin) and psin <= psi + 1e-4 * lam * slope + slack:
                accepted = True
                break
            lam *= 0.5
        if not accepted:
            return False, it, res
        for k in range(3):
            TA[k] = Tn[k]
            r[k] = rn[k]
            for m in range(3):
                J[k, m] = Jn[k, m]
        E = En


@njit(cache=True, error_model="numpy")
def solve_cases(
    ell: np.ndarray,
    EA: np.ndarray,
    w: np.ndarray,
    point: np.ndarray,
    bounds: np.ndarray,
    kind: np.ndarray,
    rA: np.ndarray,
    target: np.ndarray,
    TA0: np.ndarray,
    tol: np.ndarray,
    maxit: np.ndarray,
    s: np.ndarray,
    pos: np.ndarray,
    tension: np.ndarray,
    TA_out: np.ndarray,
    TL_out: np.ndarray,
    iters: np.ndarray,
    resid: np.ndarray,
    status: np.ndarray,
) -> None:
    """Solve N cases of P pieces (arrays (N, P) / (N, P + 1, 3) ...) and sample them at
    ``s`` (N, n). ``kind`` 0 fixed B (target = rB - rA), 1 mooring (target[2] = zB - zA,
    TA0[:2] known), 2 force (TA0 = T_A). ``status`` 0 converged, 1 not."""
    N, P = ell.shape
    n = s.shape[1]
    C = np.zeros((P, 3))
    Cend = np.zeros(3)
    r = np.zeros(3)
    J = np.zeros((3, 3))
    rn = np.zeros(3)
    Jn = np.zeros((3, 3))
    g = np.zeros(3)
    step = np.zeros(3)
    TA = np.zeros(3)
    Tn = np.zeros(3)
    free = np.zeros(3, dtype=np.bool_)
    dr = np.zeros(3)
    jac = np.zeros((3, 3))
    for c in range(N):
        _offsets(w[c], ell[c], point[c], C, Cend)
        for k in range(3):
            TA[k] = TA0[c, k]
        free[0] = kind[c] == 0
        free[1] = kind[c] == 0
        free[2] = kind[c] != 2
        L = bounds[c, P]
        tn = math.sqrt(target[c, 0] ** 2 + target[c, 1] ** 2 + target[c, 2] ** 2)
        scale = max(L, tn)
        it = 0
        ok = True
        res = 0.0
        if kind[c] != 2:
            ok, it, res = _free_newton(
                TA, C, w[c], ell[c], EA[c], target[c], free, scale, tol[c], maxit[c],
                r, J, rn, Jn, Tn, g, step,
            )  # fmt: skip
        iters[c] = it
        resid[c] = res
        status[c] = 0 if ok else 1
        for k in range(3):
            TA_out[c, k] = TA[k]
        for k in range(3):
            TL_out[c, k] = TA[k] - Cend[k]
        # sample: positions of the piece starts, then each output point in its piece
        p = 0
        x0, y0, z0 = rA[c, 0], rA[c, 1], rA[c, 2]
        for i in range(n):
            si = s[c, i]
            while p < P - 1 and bounds[c, p + 1] <= si:
                _piece(
                    TA[0] - C[p, 0],
                    TA[1] - C[p, 1],
                    TA[2] - C[p, 2],
                    w[c, p],
                    ell[c, p],
                    EA[c, p],
                    dr,
                    jac,
                    False,
                )
                x0 += dr[0]
                y0 += dr[1]
                z0 += dr[2]
                p += 1
            sig = min(max(si - bounds[c, p], 0.0), ell[c, p])
            tx, ty, tz = TA[0] - C[p, 0], TA[1] - C[p, 1], TA[2] - C[p, 2]
            _piece(tx, ty, tz, w[c, p], sig, EA[c, p], dr, jac, False)
            pos[c, i, 0] = x0 + dr[0]
            pos[c, i, 1] = y0 + dr[1]
            pos[c, i, 2] = z0 + dr[2]
            tzs = tz + w[c, p] * sig
            tension[c, i] = math.sqrt(tx * tx + ty * ty + tzs * tzs)
        tension[c, 0] = math.sqrt(TA[0] ** 2 + TA[1] ** 2 + TA[2] ** 2)
        tension[c, n - 1] = math.sqrt(TL_out[c, 0] ** 2 + TL_out[c, 1] ** 2 + TL_out[c, 2] ** 2)


@njit(cache=True, error_model="numpy")
def _piece_general(
    tx: float,
    ty: float,
    tz: float,
    qx: float,
    qy: float,
    qz: float,
    ell: float,
    EA: float,
    dr: np.ndarray,
    jac: np.ndarray,
    want_jac: bool,
) -> float:
    """One piece under a constant load q of any direction (:func:`.pieces.piece_integrals`
    for one piece): writes ``dr`` (3,), ``jac`` (3, 3) if asked; returns the energy."""
    w = math.sqrt(qx * qx + qy * qy + qz * qz)
    if w > 0.0:
        ux, uy, uz = -qx / w, -qy / w, -qz / w
    else:
        ux, uy, uz = 0.0, 0.0, 0.0
    V0 = tx * ux + ty * uy + tz * uz
    hx, hy, hz = tx - V0 * ux, ty - V0 * uy, tz - V0 * uz
    H2 = hx * hx + hy * hy + hz * hz
    wl = w * ell
    V1 = V0 + wl
    T0n = math.sqrt(H2 + V0 * V0)
    T1n = math.sqrt(H2 + V1 * V1)
    H = math.sqrt(H2)
    if ell == 0.0:
        for i in range(3):
            dr[i] = 0.0
            if want_jac:
                for j in range(3):
                    jac[i, j] = 0.0
        return 0.0
    Pl, A1, H2J = _curve(w > 0.0, V0, V1, H2, H, T0n, T1n, ell, wl)
    S1 = ell * (V0 + V1) / (T0n + T1n)
    inv_ea = ell / EA
    e2 = 0.5 * ell * inv_ea
    dr[0] = tx * inv_ea - qx * e2 + hx * Pl + ux * S1
    dr[1] = ty * inv_ea - qy * e2 + hy * Pl + uy * S1
    dr[2] = tz * inv_ea - qz * e2 + hz * Pl + uz * S1
    TT = tx * tx + ty * ty + tz * tz
    Tq = tx * qx + ty * qy + tz * qz
    energy = A1 + (TT * ell - Tq * ell * ell + w * w * ell**3 / 3.0) / (2.0 * EA)
    if want_jac:
        _flexibility(ell, V0, V1, H, T0n, T1n, Pl, H2J, inv_ea, hx, hy, hz, ux, uy, uz, jac)
    return energy


@njit(cache=True, error_model="numpy")
def line_sums(
    TA: np.ndarray,
    C: np.ndarray,
    q: np.ndarray,
    ell: np.ndarray,
    EA: np.ndarray,
    dr_out: np.ndarray,
    r: np.ndarray,
    J: np.ndarray,
    want_jac: bool,
) -> float:
    """Sum over the pieces of a line with T(start of piece p) = T_A - C[p]: increments
    per piece into ``dr_out`` (P, 3), their sum into ``r`` (3,), the summed flexibility
    into ``J`` (3, 3); returns the complementary energy."""
    dr = np.zeros(3)
    jac = np.zeros((3, 3))
    for k in range(3):
        r[k] = 0.0
        for m in range(3):
            J[k, m] = 0.0
    E = 0.0
    for p in range(ell.shape[0]):
        E += _piece_general(
            TA[0] - C[p, 0],
            TA[1] - C[p, 1],
            TA[2] - C[p, 2],
            q[p, 0],
            q[p, 1],
            q[p, 2],
            ell[p],
            EA[p],
            dr,
            jac,
            want_jac,
        )
        for k in range(3):
            dr_out[p, k] = dr[k]
            r[k] += dr[k]
            if want_jac:
                for m in range(3):
                    J[k, m] += jac[k, m]
    return E
