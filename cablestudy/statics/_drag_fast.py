"""Compiled (numba) drag iteration of the semi-analytic solver, for batches of lines in a
current (:func:`drag_cases`).

Each case runs, in scalar code of its own, the algorithm of
:meth:`.semi_analytic.SemiAnalyticSolver._drag_loop` for a line hanging free with end A
fixed and no seabed: the outer fixed point on the drag loads per piece (seed eqs.
38-39, Anderson-accelerated, with the stall reset and the current-speed continuation in
1, 4 and 16 steps), around the inner Newton of
:func:`.semi_analytic_newton.solve_free` on the tension at A (warm-started from the
previous iterate, inexact while the loads are far from converged). The same steps, in
the same order, with the same tests; only the 3 x 3 solves (Gaussian elimination here,
LAPACK there) and the order of a few sums differ, so the two agree to round-off of each
iterate. A case's arithmetic depends on its own inputs only, never on the other cases of
the batch: a case alone and the same case in a batch give the same numbers bit for bit.

Where the general solver would take a path this kernel does not have (a regularised
retry of a piece with no load, a singular flexibility, every continuation failing), the
case's status says so and the general solver solves it from the start.

Pure: arrays in, arrays out (SI units).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ._drag_seabed import _dips
from ._fast import _piece_general, _solve3, line_sums

#: a case's status: settled (0), or left to the general solver and why
SETTLED = 0
GIVE_UP = 1  # a path the kernel does not have (regularised retry, singular Jacobian)
FAILED = 2  # every continuation failed (the general solver says why)
DIPS = 3  # a shape of the iteration reaches the seabed (the general solver lays it)

#: an inner solve's outcome (the general solver's _Failure statuses it stands for)
_OK = 0
_NOT_CONVERGED = 1
_NUMERICAL = 2
_GIVE_UP = 3

_EPS = 2.220446049250313e-16


@njit(cache=True, error_model="numpy")
def _interp(x: float, xp: np.ndarray, fp: np.ndarray) -> float:
    """np.interp(x, xp, fp) for increasing ``xp`` (constant beyond the ends)."""
    m = xp.shape[0]
    if m == 0:
        return 0.0
    if x <= xp[0] or m == 1:
        return fp[0]
    if x >= xp[m - 1]:
        return fp[m - 1]
    j = 0
    while xp[j + 1] <= x:
        j += 1
    slope = (fp[j + 1] - fp[j]) / (xp[j + 1] - xp[j])
    return slope * (x - xp[j]) + fp[j]


@njit(cache=True, error_model="numpy")
def _drag_load(
    nodes: np.ndarray,
    ell: np.ndarray,
    diam: np.ndarray,
    cn: np.ndarray,
    ct: np.ndarray,
    rho: float,
    pz: np.ndarray,
    pv: np.ndarray,
    factor: float,
    D: np.ndarray,
) -> None:
    """:meth:`.semi_analytic.DragModel.load` of a free-hanging shape whose piece
    boundaries are at ``nodes`` (P + 1, 3): drag per unstretched length (P, 3) into
    ``D``."""
    P = ell.shape[0]
    for p in range(P):
        cx = nodes[p + 1, 0] - nodes[p, 0]
        cy = nodes[p + 1, 1] - nodes[p, 1]
        cz = nodes[p + 1, 2] - nodes[p, 2]
        lc = math.sqrt(cx * cx + cy * cy + cz * cz)
        div = lc if lc > 0.0 else 1.0
        tx, ty, tz = cx / div, cy / div, cz / div
        zm = 0.5 * (nodes[p, 2] + nodes[p + 1, 2])
        ux = factor * _interp(zm, pz, pv[:, 0])
        uy = factor * _interp(zm, pz, pv[:, 1])
        uz = factor * _interp(zm, pz, pv[:, 2])
        ut = ux * tx + uy * ty + uz * tz
        utx, uty, utz = ut * tx, ut * ty, ut * tz
        unx, uny, unz = ux - utx, uy - uty, uz - utz
        sn = math.sqrt(unx * unx + uny * uny + unz * unz)
        st = math.sqrt(utx * utx + uty * uty + utz * utz)
        k = 0.5 * rho * diam[p]
        a = cn[p] * sn
        b = math.pi * ct[p] * st
        r = lc / ell[p]
        D[p, 0] = k * (a * unx + b * utx) * r
        D[p, 1] = k * (a * uny + b * uty) * r
        D[p, 2] = k * (a * unz + b * utz) * r


@njit(cache=True, error_model="numpy")
def _offsets3(q: np.ndarray, ell: np.ndarray, point: np.ndarray, C: np.ndarray, Cend: np.ndarray):
    """:func:`.semi_analytic_shape._offsets` for loads ``q`` (P, 3) of any direction."""
    P = ell.shape[0]
    for k in range(3):
        cp = 0.0
        cq = 0.0
        for p in range(P):
            cp += point[p, k]
            C[p, k] = cp if p == 0 else cp + cq
            cq += q[p, k] * ell[p]
        Cend[k] = (cp + point[P, k]) + cq


@njit(cache=True, error_model="numpy")
def _initial_tension(
    q: np.ndarray,
    ell: np.ndarray,
    EA: np.ndarray,
    point: np.ndarray,
    L: float,
    C: np.ndarray,
    Cend: np.ndarray,
    kind: int,
    rA: np.ndarray,
    rB: np.ndarray,
    force: np.ndarray,
    zB: float,
    TA: np.ndarray,
) -> None:
    """:func:`.semi_analytic_newton.initial_tension` into ``TA`` (``C``, ``Cend`` the
    offsets of ``q``)."""
    flex = 0.0
    for p in range(ell.shape[0]):
        flex += ell[p] / EA[p]
    EAe = L / flex
    if kind == 2:
        for k in range(3):
            TA[k] = force[k] + Cend[k]
        return
    W = math.sqrt(Cend[0] ** 2 + Cend[1] ** 2 + Cend[2] ** 2)
    if kind == 1:
        TA[0] = force[0] + Cend[0]
        TA[1] = force[1] + Cend[1]
        TA[2] = 0.0
        Hh = math.hypot(TA[0], TA[1])
        Wz = -Cend[2]
        h = zB - rA[2]
        if Wz <= 0.0:
            TA[2] = -0.5 * Wz
            return
        w = Wz / L
        c = Wz / max(Hh, 1e-300)
        if c < 600.0 and Hh > 0.0:
            a = math.asinh(w * h / (2.0 * Hh * math.sinh(0.5 * c))) - 0.5 * c
            TA[2] = Hh * math.sinh(a)
        else:
            TA[2] = 0.5 * (w * h - Wz)
        return
    d0, d1, d2 = rB[0] - rA[0], rB[1] - rA[1], rB[2] - rA[2]
    chord = math.sqrt(d0 * d0 + d1 * d1 + d2 * d2)
    stretch = EAe * max(chord / L - 1.0, 0.0)
    if W <= 1e-12 * max(EAe, 1.0) * 1e-6 or W == 0.0:
        t = stretch if stretch > 0.0 else 1e-6 * EAe
        den = max(chord, 1e-300)
        TA[0] = t * d0 / den
        TA[1] = t * d1 / den
        TA[2] = t * d2 / den
        return
    up0, up1, up2 = -Cend[0] / W, -Cend[1] / W, -Cend[2] / W
    w = W / L
    h = d0 * up0 + d1 * up1 + d2 * up2
    dh0, dh1, dh2 = d0 - h * up0, d1 - h * up1, d2 - h * up2
    l = math.sqrt(dh0 * dh0 + dh1 * dh1 + dh2 * dh2)
    if l > 1e-12 * chord:
        e0, e1, e2 = dh0 / l, dh1 / l, dh2 / l
    else:  # up x (1, 0, 0), else up x (0, 1, 0)
        e0, e1, e2 = 0.0, up2, -up1
        if math.sqrt(e1 * e1 + e2 * e2) < 0.5:
            e0, e1, e2 = -up2, 0.0, up0
        n = math.sqrt(e0 * e0 + e1 * e1 + e2 * e2)
        e0, e1, e2 = e0 / n, e1 / n, e2 / n
    if l <= 1e-12 * chord:
        H = 0.0
        VB = 0.5 * w * (L + h) if L > abs(h) else w * L + max(stretch, 0.0)
    else:
        if L <= chord:
            lam = 0.2
        else:
            lam = max(math.sqrt(3.0 * max((L * L - h * h) / (l * l) - 1.0, 0.0)), 1e-3)
        H = w * l / (2.0 * lam)
        VB = 0.5 * w * (h / math.tanh(lam) + L)
        if chord > L:
            H = max(H, stretch * l / chord)
            VB = max(VB, stretch * h / chord + 0.5 * w * L)
    VA = VB - w * L
    TA[0] = H * e0 + VA * up0 + point[0, 0]
    TA[1] = H * e1 + VA * up1 + point[0, 1]
    TA[2] = H * e2 + VA * up2 + point[0, 2]


@njit(cache=True, error_model="numpy")
def _solve_free(
    q: np.ndarray,
    ell: np.ndarray,
    EA: np.ndarray,
    point: np.ndarray,
    L: float,
    kind: int,
    rA: np.ndarray,
    rB: np.ndarray,
    force: np.ndarray,
    zB: float,
    TA: np.ndarray,
    tol: float,
    maxit: int,
    polish: bool,
    C: np.ndarray,
    Cend: np.ndarray,
    dr_acc: np.ndarray,
    nodes: np.ndarray,
    scratch: np.ndarray,
) -> tuple[int, int, float]:
    """:func:`.semi_analytic_newton.solve_free` (linear axial laws): ``TA`` in/out (the
    start, then the solution), the increments per piece at it into ``dr_acc`` and the
    piece boundaries into ``nodes``. Returns (outcome, iterations, residual)."""
    P = ell.shape[0]
    _offsets3(q, ell, point, C, Cend)
    r = np.zeros(3)
    J = np.zeros((3, 3))
    rn = np.zeros(3)
    Jn = np.zeros((3, 3))
    Tn = np.zeros(3)
    g = np.zeros(3)
    step = np.zeros(3)
    target = np.zeros(3)
    free = np.zeros(3, dtype=np.bool_)
    it = 0
    res = 0.0
    if kind == 2:
        for k in range(3):
            TA[k] = force[k] + Cend[k]
        line_sums(TA, C, q, ell, EA, dr_acc, r, J, False)
    else:
        if kind == 0:
            for k in range(3):
                target[k] = rB[k] - rA[k]
                free[k] = True
        else:
            TA[0] = force[0] + Cend[0]
            TA[1] = force[1] + Cend[1]
            target[2] = zB - rA[2]
            free[2] = True
        scale = max(L, math.sqrt(target[0] ** 2 + target[1] ** 2 + target[2] ** 2))
        E = line_sums(TA, C, q, ell, EA, dr_acc, r, J, True)
        dot = 0.0
        for k in range(3):
            if free[k]:
                dot += target[k] * TA[k]
        psi = E - dot
        polished = 0 if polish else 1
        res = 0.0
        for k in range(3):
            g[k] = r[k] - target[k] if free[k] else 0.0
            res = max(res, abs(g[k]))
        res /= scale
        while True:
            if not math.isfinite(res):
                return _NUMERICAL, it, res
            if res <= tol:
                if polished >= 1 or res <= 1e-15:
                    break
                polished += 1
            if it >= maxit:
                return _NOT_CONVERGED, it, res
            it += 1
            if not _solve3(J, g, free, step):
                return _GIVE_UP, it, res  # the general solver's fallback step
            slope = 0.0
            for k in range(3):
                slope += g[k] * step[k]
            slack = 1e-13 * (abs(E) + abs(dot))
            lam = 1.0
            accepted = False
            En = 0.0
            dotn = 0.0
            for _ in range(80):
                dotn = 0.0
                for k in range(3):
                    Tn[k] = TA[k] + lam * step[k] if free[k] else TA[k]
                    if free[k]:
                        dotn += target[k] * Tn[k]
                En = line_sums(Tn, C, q, ell, EA, scratch, rn, Jn, True)
                psin = En - dotn
                finite = math.isfinite(psin)
                for a in range(3):
                    for b in range(3):
                        if not math.isfinite(Jn[a, b]):
                            finite = False
                if finite and psin <= psi + 1e-4 * lam * slope + slack:
                    accepted = True
                    break
                lam *= 0.5
            if not accepted:
                return _NOT_CONVERGED, it, res
            for k in range(3):
                TA[k] = Tn[k]
                r[k] = rn[k]
                for m in range(3):
                    J[k, m] = Jn[k, m]
            for p in range(P):
                for k in range(3):
                    dr_acc[p, k] = scratch[p, k]
            E = En
            dot = dotn
            psi = En - dotn
            res = 0.0
            for k in range(3):
                g[k] = r[k] - target[k] if free[k] else 0.0
                res = max(res, abs(g[k]))
            res /= scale
    # the shape: piece starts from A (finite, else the general solver's numerical fault)
    for k in range(3):
        nodes[0, k] = rA[k]
    acc = np.zeros(3)
    for p in range(P):
        for k in range(3):
            acc[k] += dr_acc[p, k]
            nodes[p + 1, k] = rA[k] + acc[k]
    for p in range(P):
        for k in range(3):
            if not (math.isfinite(nodes[p, k]) and math.isfinite(TA[k] - C[p, k])):
                return _NUMERICAL, it, res
    return _OK, it, res


@njit(cache=True, error_model="numpy")
def _anderson(
    x: np.ndarray,
    gx: np.ndarray,
    xs: np.ndarray,
    fs: np.ndarray,
    count: int,
    m: int,
    beta: float,
    out: np.ndarray,
) -> int:
    """One step of :class:`.semi_analytic._Anderson` (history ``xs``, ``fs`` (m + 1, V)
    holding ``count`` rows): the next iterate into ``out``; returns the new count."""
    V = x.shape[0]
    if count == m + 1:  # drop the oldest
        for i in range(m):
            for v in range(V):
                xs[i, v] = xs[i + 1, v]
                fs[i, v] = fs[i + 1, v]
        count -= 1
    for v in range(V):
        xs[count, v] = x[v]
        fs[count, v] = gx[v] - x[v]
    count += 1
    f = fs[count - 1]
    if count == 1:
        for v in range(V):
            out[v] = x[v] + beta * f[v]
        return count
    k = count - 1
    dX = np.empty((V, k))
    dF = np.empty((V, k))
    for i in range(k):
        for v in range(V):
            dX[v, i] = xs[i + 1, v] - xs[i, v]
            dF[v, i] = fs[i + 1, v] - fs[i, v]
    gamma = np.linalg.lstsq(dF, f.copy(), rcond=_EPS * max(V, k))[0]
    for v in range(V):
        acc = 0.0
        for i in range(k):
            acc += (dX[v, i] + beta * dF[v, i]) * gamma[i]
        out[v] = x[v] + beta * f[v] - acc
    return count


@njit(cache=True, error_model="numpy")
def _weighted_change(Dn: np.ndarray, D: np.ndarray, ell: np.ndarray) -> tuple[float, float]:
    """(sum |Dn - D| ell, sum |Dn| ell) over the pieces."""
    a = 0.0
    b = 0.0
    for p in range(ell.shape[0]):
        d0, d1, d2 = Dn[p, 0] - D[p, 0], Dn[p, 1] - D[p, 1], Dn[p, 2] - D[p, 2]
        a += math.sqrt(d0 * d0 + d1 * d1 + d2 * d2) * ell[p]
        b += math.sqrt(Dn[p, 0] ** 2 + Dn[p, 1] ** 2 + Dn[p, 2] ** 2) * ell[p]
    return a, b


@njit(cache=True, error_model="numpy")
def _drag_case(
    ell: np.ndarray,
    EA: np.ndarray,
    weight: np.ndarray,
    point: np.ndarray,
    bounds: np.ndarray,
    diam: np.ndarray,
    cn: np.ndarray,
    ct: np.ndarray,
    rho: float,
    pz: np.ndarray,
    pv: np.ndarray,
    kind: int,
    rA: np.ndarray,
    rB: np.ndarray,
    force: np.ndarray,
    zB: float,
    tol: float,
    maxit: int,
    max_drag: int,
    steps: np.ndarray,
    over: bool,
    seabed: np.ndarray,
    TA: np.ndarray,
    Dused: np.ndarray,
    Dout: np.ndarray,
    nodes_out: np.ndarray,
    counts: np.ndarray,
) -> tuple[int, float, float]:
    """One case's drag loop (:meth:`.semi_analytic.SemiAnalyticSolver._drag_loop`).
    Returns (status, the shape's Newton residual, the load residual); on success ``TA``,
    ``Dused`` (the drag the shape was solved with), ``Dout`` (the converged drag loads),
    ``nodes_out`` the shape's piece boundaries; ``counts`` [Newton, drag] iterations.
    A line ``over`` the seabed plane ``seabed`` (normal, depth; both ends above it) is
    the general solver's line hanging free as long as no shape of the iteration reaches
    the seabed (:func:`_dips`); the first one that does ends the case (:data:`DIPS`)."""
    P = ell.shape[0]
    V = 3 * P
    L = bounds[P]
    grav = np.zeros((P, 3))
    for p in range(P):
        grav[p, 2] = -weight[p]
    Fscale = 0.0
    for p in range(P):
        Fscale += abs(weight[p]) * ell[p]
    pabs = 0.0
    for p in range(P + 1):
        for k in range(3):
            pabs += abs(point[p, k])
    Fscale += pabs
    q = np.zeros((P, 3))
    C = np.zeros((P, 3))
    Cend = np.zeros(3)
    dr = np.zeros((P, 3))
    scratch = np.zeros((P, 3))
    nodes = np.zeros((P + 1, 3))
    D = np.zeros((P, 3))
    Dn = np.zeros((P, 3))
    Dnext = np.zeros((P, 3))
    xs = np.zeros((6, V))
    fs = np.zeros((6, V))
    best_TA = np.zeros(3)
    best_D = np.zeros((P, 3))
    best_Dn = np.zeros((P, 3))
    best_nodes = np.zeros((P + 1, 3))
    st_TA = np.zeros(3)  # the solver state's T_A (warm start of the next inner solve)
    have = False
    T = np.zeros(3)
    for a in range(steps.shape[0]):
        n_steps = steps[a]
        for p in range(P):
            for k in range(3):
                D[p, k] = 0.0
        saved = st_TA.copy()
        saved_have = have
        failed = False
        first = True
        shape_res = 0.0
        res = math.inf
        for kk in range(1, n_steps + 1):
            factor = kk / n_steps
            final = kk == n_steps
            if kk > 1:
                f2 = (kk / (kk - 1)) ** 2
                for p in range(P):
                    for k in range(3):
                        D[p, k] = D[p, k] * f2
            tol_fp = tol if final else max(tol, 1e-4)
            # ---- the fixed point (_drag_fixed_point)
            if first:
                for p in range(P):
                    for k in range(3):
                        q[p, k] = grav[p, k] + D[p, k]
                if have:
                    for k in range(3):
                        T[k] = st_TA[k]
                else:
                    _offsets3(q, ell, point, C, Cend)
                    _initial_tension(q, ell, EA, point, L, C, Cend, kind, rA, rB, force, zB, T)
                code, its, _r = _solve_free(
                    q, ell, EA, point, L, kind, rA, rB, force, zB, T,
                    max(tol_fp, 1e-6), maxit, True, C, Cend, dr, nodes, scratch,
                )  # fmt: skip
                if code == _GIVE_UP or (code != _OK and _unloaded(q)):
                    return GIVE_UP, 0.0, 0.0
                if code == _OK:
                    if over and _dips(q, ell, EA, bounds, C, T, nodes, seabed):
                        return DIPS, 0.0, 0.0
                    counts[0] += its
                    for k in range(3):
                        st_TA[k] = T[k]
                    have = True
                else:  # a straight line from A: only the first drag estimate
                    _straight(kind, rA, rB, force, zB, bounds, nodes)
                _drag_load(nodes, ell, diam, cn, ct, rho, pz, pv, factor, D)
            count = 0
            beta = 0.7
            best = math.inf
            best_res = math.inf
            have_best = False
            stall = 0
            res = math.inf
            done = False
            for _it in range(max_drag):
                counts[1] += 1
                tol_inner = max(tol_fp, min(1e-4, 1e-2 * res))
                for p in range(P):
                    for k in range(3):
                        q[p, k] = grav[p, k] + D[p, k]
                if have:
                    for k in range(3):
                        T[k] = st_TA[k]
                else:
                    _offsets3(q, ell, point, C, Cend)
                    _initial_tension(q, ell, EA, point, L, C, Cend, kind, rA, rB, force, zB, T)
                code, its, sres = _solve_free(
                    q, ell, EA, point, L, kind, rA, rB, force, zB, T,
                    tol_inner, maxit, False, C, Cend, dr, nodes, scratch,
                )  # fmt: skip
                if code == _GIVE_UP or (code != _OK and _unloaded(q)):
                    return GIVE_UP, 0.0, 0.0
                if code != _OK:
                    failed = True
                    break
                if over and _dips(q, ell, EA, bounds, C, T, nodes, seabed):
                    return DIPS, 0.0, 0.0
                counts[0] += its
                for k in range(3):
                    st_TA[k] = T[k]
                have = True
                shape_res = sres
                _drag_load(nodes, ell, diam, cn, ct, rho, pz, pv, factor, Dn)
                change, size = _weighted_change(Dn, D, ell)
                res = change / max(Fscale + size, 1e-300)
                if res <= tol_fp and tol_inner <= tol_fp:
                    done = True
                    for k in range(3):
                        TA[k] = T[k]
                    for p in range(P):
                        for k in range(3):
                            Dused[p, k] = D[p, k]
                            Dout[p, k] = Dn[p, k]
                    for p in range(P + 1):
                        for k in range(3):
                            nodes_out[p, k] = nodes[p, k]
                    break
                if res < best_res:
                    best_res = res
                    have_best = True
                    for k in range(3):
                        best_TA[k] = T[k]
                    for p in range(P):
                        for k in range(3):
                            best_D[p, k] = D[p, k]
                            best_Dn[p, k] = Dn[p, k]
                    for p in range(P + 1):
                        for k in range(3):
                            best_nodes[p, k] = nodes[p, k]
                if res < 0.5 * best:
                    best = res
                    stall = 0
                else:
                    stall += 1
                    if stall >= 12:
                        count = 0
                        beta = max(beta * 0.5, 0.05)
                        stall = 0
                count = _anderson(
                    D.reshape(V), Dn.reshape(V), xs, fs, count, 5, beta, Dnext.reshape(V)
                )
                for p in range(P):
                    for k in range(3):
                        D[p, k] = Dnext[p, k]
            if failed:
                break
            if not done:
                if (not final) and have_best and best_res < 1e-2:
                    res = best_res
                    for k in range(3):
                        TA[k] = best_TA[k]
                    for p in range(P):
                        for k in range(3):
                            Dused[p, k] = best_D[p, k]
                            Dout[p, k] = best_Dn[p, k]
                    for p in range(P + 1):
                        for k in range(3):
                            nodes_out[p, k] = best_nodes[p, k]
                else:
                    failed = True
                    break
            # the next step starts from the converged loads
            for p in range(P):
                for k in range(3):
                    D[p, k] = Dout[p, k]
            first = False
        if not failed:
            return SETTLED, shape_res, res
        for k in range(3):
            st_TA[k] = saved[k]
        have = saved_have
    return FAILED, 0.0, 0.0


@njit(cache=True, error_model="numpy")
def _unloaded(q: np.ndarray) -> bool:
    """Whether a piece has no load (the general solver would retry it regularised)."""
    for p in range(q.shape[0]):
        if q[p, 0] == 0.0 and q[p, 1] == 0.0 and q[p, 2] == 0.0:
            return True
    return False


@njit(cache=True, error_model="numpy")
def _straight(
    kind: int,
    rA: np.ndarray,
    rB: np.ndarray,
    force: np.ndarray,
    zB: float,
    bounds: np.ndarray,
    nodes: np.ndarray,
) -> None:
    """:meth:`.semi_analytic.SemiAnalyticSolver._straight_start`'s piece boundaries."""
    d = np.zeros(3)
    if kind == 0:
        for k in range(3):
            d[k] = rB[k] - rA[k]
    else:
        fn = math.sqrt(force[0] ** 2 + force[1] ** 2 + force[2] ** 2)
        if fn > 0.0:
            for k in range(3):
                d[k] = force[k]
        else:
            d[2] = -1.0
        if kind == 1:
            d[2] = zB - rA[2]
    n = math.sqrt(d[0] ** 2 + d[1] ** 2 + d[2] ** 2)
    for k in range(3):
        e = d[k] / n if n > 0.0 else (-1.0 if k == 2 else 0.0)
        for p in range(bounds.shape[0]):
            nodes[p, k] = rA[k] + e * bounds[p]


@njit(cache=True, error_model="numpy")
def drag_cases(
    ell: np.ndarray,
    EA: np.ndarray,
    weight: np.ndarray,
    point: np.ndarray,
    bounds: np.ndarray,
    diam: np.ndarray,
    cn: np.ndarray,
    ct: np.ndarray,
    rho: np.ndarray,
    pz: np.ndarray,
    pv: np.ndarray,
    kind: np.ndarray,
    rA: np.ndarray,
    rB: np.ndarray,
    force: np.ndarray,
    zB: np.ndarray,
    tol: np.ndarray,
    maxit: np.ndarray,
    max_drag: int,
    steps: np.ndarray,
    over: np.ndarray,
    seabed: np.ndarray,
    s: np.ndarray,
    pos: np.ndarray,
    tension: np.ndarray,
    TA_out: np.ndarray,
    TL_out: np.ndarray,
    loads: np.ndarray,
    counts: np.ndarray,
    resid: np.ndarray,
    status: np.ndarray,
) -> None:
    """N lines of P pieces in a current (arrays (N, P), (N, P + 1, 3) point loads and
    bounds, (N,) fluid density, (N, M) / (N, M, 3) current profiles, (N,) end B kind 0
    fixed / 1 mooring / 2 force, (N, 3) ends and forces, (N,) zB, (N,) whether over a
    seabed and (N, 4) its plane, upward normal and depth), each by
    :func:`_drag_case`, sampled at ``s`` (N, n) as :meth:`.semi_analytic_shape.Shape.sample`.
    Outputs: positions, tensions, T_A, T(L), the converged loads per piece (weight and
    drag, (N, P, 3)), counts (N, 2) [Newton, drag iterations], residual, status."""
    N, P = ell.shape
    n = s.shape[1]
    TA = np.zeros(3)
    Dused = np.zeros((P, 3))
    Dout = np.zeros((P, 3))
    nodes = np.zeros((P + 1, 3))
    q = np.zeros((P, 3))
    C = np.zeros((P, 3))
    Cend = np.zeros(3)
    dr = np.zeros(3)
    jac = np.zeros((3, 3))
    for c in range(N):
        st, sres, dres = _drag_case(
            ell[c], EA[c], weight[c], point[c], bounds[c], diam[c], cn[c], ct[c], rho[c],
            pz[c], pv[c], kind[c], rA[c], rB[c], force[c], zB[c], tol[c], maxit[c],
            max_drag, steps, over[c], seabed[c], TA, Dused, Dout, nodes, counts[c],
        )  # fmt: skip
        status[c] = st
        if st != SETTLED:
            continue
        resid[c] = max(sres, dres)
        for p in range(P):
            q[p, 0] = Dused[p, 0]
            q[p, 1] = Dused[p, 1]
            q[p, 2] = -weight[c, p] + Dused[p, 2]
            loads[c, p, 0] = Dout[p, 0]
            loads[c, p, 1] = Dout[p, 1]
            loads[c, p, 2] = -weight[c, p] + Dout[p, 2]
        _offsets3(q, ell[c], point[c], C, Cend)
        for k in range(3):
            TA_out[c, k] = TA[k]
            TL_out[c, k] = TA[k] - Cend[k]
        Lend = bounds[c, P - 1] + ell[c, P - 1]
        for i in range(n):
            si = s[c, i]
            k = 0
            while k < P - 1 and bounds[c, k + 1] <= si:
                k += 1
            sig = min(max(si - bounds[c, k], 0.0), ell[c, k])
            tx, ty, tz = TA[0] - C[k, 0], TA[1] - C[k, 1], TA[2] - C[k, 2]
            _piece_general(tx, ty, tz, q[k, 0], q[k, 1], q[k, 2], sig, EA[c, k], dr, jac, False)
            for m in range(3):
                pos[c, i, m] = nodes[k, m] + dr[m]
            Tx, Ty, Tz = tx - q[k, 0] * sig, ty - q[k, 1] * sig, tz - q[k, 2] * sig
            tension[c, i] = math.sqrt(Tx * Tx + Ty * Ty + Tz * Tz)
            if si <= 0.0:
                tension[c, i] = math.sqrt(TA[0] ** 2 + TA[1] ** 2 + TA[2] ** 2)
            if si >= Lend:
                tension[c, i] = math.sqrt(TL_out[c, 0] ** 2 + TL_out[c, 1] ** 2 + TL_out[c, 2] ** 2)
