"""Compiled (numba) drag iteration of the semi-analytic solver, for batches of lines in a
current (:func:`drag_cases`).

Each case runs, in scalar code of its own, the algorithm of
:meth:`.semi_analytic.SemiAnalyticSolver._drag_loop` for a line with end A fixed: the
outer fixed point on the drag loads per piece (seed eqs. 38-39, Anderson-accelerated,
with the stall reset and the current-speed continuation in 1, 4 and 16 steps), around
the inner Newton of :func:`.semi_analytic_newton.solve_free` on the tension at A for a
line hanging free, or of :func:`.semi_analytic_newton.solve_contact` for one resting on
the seabed from an anchor at A (:mod:`._drag_inner`), warm-started from the previous
iterate, inexact while the loads are far from converged. The same steps, in
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

from ._drag_inner import (  # noqa: F401 - the statuses re-exported
    _GIVE_UP,
    _OK,
    BELOW,
    DIPS,
    FAILED,
    GIVE_UP,
    SETTLED,
    _anchored,
    _initial_tension,
    _offsets3,
    _sampled,
    _solve_free,
)
from ._drag_seabed import _dips
from ._fast import _piece_general

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
    bounds: np.ndarray,
    ell: np.ndarray,
    diam: np.ndarray,
    cn: np.ndarray,
    ct: np.ndarray,
    rho: float,
    pz: np.ndarray,
    pv: np.ndarray,
    factor: float,
    D: np.ndarray,
    laid: float,
) -> None:
    """:meth:`.semi_analytic.DragModel.load` of a shape whose piece boundaries are at
    ``nodes`` (P + 1, 3): drag per unstretched length (P, 3) into ``D``, zero on the
    pieces whose middle lies on the ``laid`` [m] length from end A."""
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
        if 0.5 * (bounds[p] + bounds[p + 1]) <= laid:
            D[p, 0], D[p, 1], D[p, 2] = 0.0, 0.0, 0.0


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
    mode: int,
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
    With a seabed (a row of :data:`._drag_inner.SEABED_COLUMNS`: its upward normal and
    depth first): a line over it (``mode`` 1, both ends above it) is the general
    solver's line hanging free as long as no shape of the iteration reaches the seabed
    (:func:`_dips`); the first one that does ends the case (:data:`DIPS`). A line
    anchored at A on it (``mode`` 2) rests on it from A to its touchdown point in every
    inner solve (:func:`_anchored`; ``TA`` is then y = (the touchdown tension in the
    seabed plane, its arc length))."""
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
                if mode == 2:
                    code, its, _r = _anchored(
                        q, weight, ell, EA, point, bounds, kind, rA, rB, force, zB, seabed, T,
                        have, max(tol_fp, 1e-6), maxit, C, Cend, dr, nodes, scratch,
                    )  # fmt: skip
                    if code != SETTLED:
                        return code, 0.0, 0.0
                else:
                    code, its, _r = _solve_free(
                        q, ell, EA, point, L, kind, rA, rB, force, zB, T,
                        max(tol_fp, 1e-6), maxit, True, C, Cend, dr, nodes, scratch,
                    )  # fmt: skip
                if code == _GIVE_UP or (code != _OK and _unloaded(q)):
                    return GIVE_UP, 0.0, 0.0
                if code == _OK:
                    if mode == 1 and _dips(q, ell, EA, bounds, C, T, nodes, seabed):
                        return DIPS, 0.0, 0.0
                    counts[0] += its
                    for k in range(3):
                        st_TA[k] = T[k]
                    have = True
                else:  # a straight line from A: only the first drag estimate
                    _straight(kind, rA, rB, force, zB, bounds, nodes)
                laid = T[2] if mode == 2 else 0.0  # y's touchdown arc length
                _drag_load(nodes, bounds, ell, diam, cn, ct, rho, pz, pv, factor, D, laid)
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
                if mode == 2:
                    code, its, sres = _anchored(
                        q, weight, ell, EA, point, bounds, kind, rA, rB, force, zB, seabed, T,
                        have, tol_inner, maxit, C, Cend, dr, nodes, scratch,
                    )  # fmt: skip
                    if code != SETTLED:
                        return code, 0.0, 0.0
                else:
                    code, its, sres = _solve_free(
                        q, ell, EA, point, L, kind, rA, rB, force, zB, T,
                        tol_inner, maxit, False, C, Cend, dr, nodes, scratch,
                    )  # fmt: skip
                if code == _GIVE_UP or (code != _OK and _unloaded(q)):
                    return GIVE_UP, 0.0, 0.0
                if code != _OK:
                    failed = True
                    break
                if mode == 1 and _dips(q, ell, EA, bounds, C, T, nodes, seabed):
                    return DIPS, 0.0, 0.0
                counts[0] += its
                for k in range(3):
                    st_TA[k] = T[k]
                have = True
                shape_res = sres
                laid = T[2] if mode == 2 else 0.0  # y's touchdown arc length
                _drag_load(nodes, bounds, ell, diam, cn, ct, rho, pz, pv, factor, Dn, laid)
                change, size = _weighted_change(Dn, D, ell)
                res = change / max(Fscale + size, 1e-300)
                if res <= tol_fp and tol_inner <= tol_fp:
                    done = True
                    _keep(T, D, Dn, nodes, TA, Dused, Dout, nodes_out)
                    break
                if res < best_res:
                    best_res = res
                    have_best = True
                    _keep(T, D, Dn, nodes, best_TA, best_D, best_Dn, best_nodes)
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
                    _keep(best_TA, best_D, best_Dn, best_nodes, TA, Dused, Dout, nodes_out)
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
def _keep(T, D, Dn, nodes, T_to, D_to, Dn_to, nodes_to):  # noqa: ANN001, ANN202, PLR0913
    """Copy a drag iterate (the end tension ``T`` (3,), the drag ``D`` the shape was
    solved with and the loads ``Dn`` it gave (P, 3), the piece boundaries ``nodes``
    (P + 1, 3)) into the ``*_to`` arrays of the same shapes."""
    P = D.shape[0]
    for k in range(3):
        T_to[k] = T[k]
    for p in range(P):
        for k in range(3):
            D_to[p, k] = D[p, k]
            Dn_to[p, k] = Dn[p, k]
    for p in range(P + 1):
        for k in range(3):
            nodes_to[p, k] = nodes[p, k]


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
    mode: np.ndarray,
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
    laid: np.ndarray,
) -> None:
    """N lines of P pieces in a current (arrays (N, P), (N, P + 1, 3) point loads and
    bounds, (N,) fluid density, (N, M) / (N, M, 3) current profiles, (N,) end B kind 0
    fixed / 1 mooring / 2 force, (N, 3) ends and forces, (N,) zB, (N,) seabed ``mode``
    (0 none, 1 over it, 2 anchored at A on it) and (N, 12) its plane
    (:data:`._drag_inner.SEABED_COLUMNS`), each by :func:`_drag_case`, sampled at
    ``s`` (N, n) as :meth:`.semi_analytic_shape.Shape.sample`. Outputs: positions,
    tensions, T_A, T(L), the converged loads per piece (weight and drag, (N, P, 3)),
    counts (N, 2) [Newton, drag iterations], residual, status, laid length [m]."""
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
            max_drag, steps, mode[c], seabed[c], TA, Dused, Dout, nodes, counts[c],
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
        laid[c] = 0.0
        if mode[c] == 2:  # resting on the seabed from A (TA: y), checked as the general
            # solver checks it (the line below the seabed by its margin: not resolved)
            laid[c] = TA[2]
            ok, low = _sampled(
                TA, q, weight[c], EA[c], point[c], bounds[c], rA[c], seabed[c], s[c], pos[c],
                tension[c], TA_out[c], TL_out[c],
            )  # fmt: skip
            Lc = bounds[c, P]
            if not (ok and -low <= max(1e-6 * Lc, 1e3 * tol[c] * Lc)):
                status[c] = BELOW
            continue
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
