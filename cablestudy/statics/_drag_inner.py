"""The inner solves of the compiled drag iteration (:mod:`._drag_fast`), the loads of the
drag iterate frozen: a line hanging free (:func:`_solve_free`, the general solver's
:func:`.semi_analytic_newton.solve_free`), and a line anchored at end A on the seabed
(:func:`_anchored`, its :meth:`.semi_analytic.SemiAnalyticSolver._inner` with the line
resting on the seabed from A: :func:`.semi_analytic_newton.solve_contact`).

On the seabed the laid part carries the line's weight only (:func:`._fast_contact._laid`:
friction mobilised towards the anchor, no drag on it), the suspended pieces from the
touchdown point their weight and drag (:func:`._fast_contact._evaluate` with the loads
``q``). The Newton on y = (the touchdown tension in the seabed plane, its arc length)
starts where the general solver's does: the previous drag iterate's y, or for the first
solve the inextensible mooring line's (:func:`._fast_contact._guess`: in still water on
a flat seabed at once; in a current or on a slope once the free-hanging solve reaches
the seabed). Where that solver would leave the contact path (the touchdown point driven
to the anchor, a contact Newton that fails, no laid part in the start), the case is
handed on with its status.

Pure: arrays in, arrays out (SI units).
"""

from __future__ import annotations

import math

import numpy as np

from ._fast import _solve3, line_sums, njit
from ._fast_contact import LIFT_OFF, _contact_newton, _guess, _pieces, _sample

#: a case's status: settled (0), or left to the general solver and why
SETTLED = 0
GIVE_UP = 1  # a path the kernel does not have (regularised retry, singular Jacobian)
FAILED = 2  # every continuation failed (the general solver says why)
DIPS = 3  # a shape of the iteration reaches the seabed (the general solver lays it)
#: ... handed on because the line anchored on the seabed may hang free of it (the general
#: solver's free-hanging path), because its seabed-contact Newton did not settle, or
#: because its solution passes below the seabed
LIFTS_OFF = 4
CONTACT_FAILED = 5
BELOW = 6

#: an inner solve's outcome (the general solver's _Failure statuses it stands for)
_OK = 0
_NOT_CONVERGED = 1
_NUMERICAL = 2
_GIVE_UP = 3

#: the columns of a seabed row: upward normal (3), depth, the in-plane basis (3, 2)
#: row by row, friction coefficient, 1.0 where the seabed is flat
SEABED_COLUMNS = 12


@njit(cache=True, error_model="numpy")
def _plane(seabed: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(upward normal (3,), basis (3, 2) with e1, e2 as columns) of a seabed row."""
    bas = np.empty((3, 2))
    for i in range(3):
        bas[i, 0] = seabed[4 + 2 * i]
        bas[i, 1] = seabed[5 + 2 * i]
    return seabed[:3].copy(), bas


@njit(cache=True, error_model="numpy")
def _sampled(
    y: np.ndarray, q: np.ndarray, w: np.ndarray, EA: np.ndarray, point: np.ndarray,
    bounds: np.ndarray, rA: np.ndarray, seabed: np.ndarray, s: np.ndarray, pos: np.ndarray,
    tension: np.ndarray, fa: np.ndarray, TL: np.ndarray,
) -> tuple[bool, float]:  # fmt: skip
    """The line anchored at ``rA`` solved at y under the loads ``q`` (P, 3) [N/m]
    (:func:`._fast_contact._pieces`) sampled at ``s`` [m]: positions ``pos``,
    ``tension``, the force on the anchor ``fa`` and T(L) ``TL`` [N]; returns (all
    finite, the least height above the seabed [m])."""
    P = w.shape[0]
    nrm, bas = _plane(seabed)
    M = 3 * P
    pcs = (
        np.empty(M), np.empty(M), np.empty((M, 3)), np.empty((M, 3)), np.empty(M),
        np.empty(M, dtype=np.int64), np.empty((M, 3)),
    )  # fmt: skip
    e = np.zeros(3)
    lp = np.zeros(4)
    dr = np.zeros(3)
    jac = np.zeros((3, 3))
    work = (np.empty(P), np.empty(P), np.empty(P), np.empty(P), lp, e, np.zeros(3), dr, jac)
    n = _pieces(y, bas, rA, bounds, w, q, EA, point, nrm, seabed[10], pcs, work, TL)
    got = _sample(n, pcs, e, s, bounds[P], lp[3], TL, nrm, seabed[3], pos, tension, dr, jac)
    for k in range(3):
        fa[k] = lp[3] * e[k]
    return got


@njit(cache=True, error_model="numpy")
def _contact(
    q: np.ndarray, w: np.ndarray, ell: np.ndarray, EA: np.ndarray, point: np.ndarray,
    bounds: np.ndarray, kind: int, rA: np.ndarray, rB: np.ndarray, force: np.ndarray,
    zB: float, seabed: np.ndarray, tol: float, maxit: int, y: np.ndarray, start: int,
    nodes: np.ndarray,
) -> tuple[int, int, float]:  # fmt: skip
    """:func:`.semi_analytic_newton.solve_contact` for the loads ``q`` (P, 3) [N/m] of a
    line anchored at ``rA`` (end B: ``kind`` 0 fixed at ``rB``, 1 mooring at height
    ``zB``, 2 towed; ``force`` on the line at B), from y (in/out) as it is (``start``
    0), from the still-water start (1) or the start in a current (2) of
    :func:`.semi_analytic_newton.initial_contact`. On success the piece boundaries'
    positions into ``nodes`` (P + 1, 3). Returns (0 or :data:`LIFTS_OFF` or
    :data:`CONTACT_FAILED`, Newton iterations, residual)."""
    P = w.shape[0]
    L = bounds[P]
    nrm, bas = _plane(seabed)
    tgt = rB.copy()
    if kind == 1:
        tgt[2] = zB
    Fscale = 0.0
    wsum = 0.0
    for p in range(P):
        Fscale += abs(w[p]) * ell[p]
        wsum += w[p] * ell[p]
    Fscale = max(Fscale, 1e-300)
    if kind != 0:
        Fscale = max(Fscale, math.sqrt(force[0] ** 2 + force[1] ** 2 + force[2] ** 2))
    if start > 0:
        st = _guess(L, wsum / L, rA, tgt, nrm, bas, start == 1, kind, force, y)
        if st != 0 or (start == 1 and not y[2] > 0.0):  # the general solver hangs it free
            return LIFTS_OFF, 0, 0.0
    v3 = np.zeros((9, 3))
    m3 = np.zeros((5, 3, 3))
    A = np.zeros((3, 4))
    t = np.empty((4, P + 1))
    lp = np.zeros(4)
    st, its, res = _contact_newton(
        y, bas, rA, tgt, kind, force, Fscale, L, bounds, w, q, EA, point, nrm, seabed[10],
        tol, maxit, v3[0], v3[1], m3[0], m3[1], v3[2], v3[3], A, v3[4], v3[5], t[0], t[1],
        t[2], t[3], lp, v3[6], m3[2], v3[7], m3[3],
    )  # fmt: skip
    if st != 0:
        return (LIFTS_OFF if st == LIFT_OFF else CONTACT_FAILED), its, res
    _sampled(y, q, w, EA, point, bounds, rA, seabed, bounds, nodes, t[0], v3[0], v3[1])
    return 0, its, res


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
def mooring_vertical(Hh: float, Wz: float, h: float, L: float) -> float:
    """The starting vertical tension at end A [N] of a mooring line (end B at height
    ``h`` [m] above A, the horizontal end force ``Hh`` [N] given): the uniform catenary
    of length ``L`` [m] and total downward load ``Wz`` [N] through both ends; half of
    ``-Wz`` for a line with no downward load. Shared by
    :func:`.semi_analytic_newton.initial_tension` and :func:`_initial_tension`."""
    if Wz <= 0.0:
        return -0.5 * Wz
    w = Wz / L
    c = Wz / max(Hh, 1e-300)
    if c < 600.0 and Hh > 0.0:
        a = math.asinh(w * h / (2.0 * Hh * math.sinh(0.5 * c))) - 0.5 * c
        return Hh * math.sinh(a)
    return 0.5 * (w * h - Wz)


@njit(cache=True, error_model="numpy")
def uniform_end_tension(
    w: float, L: float, h: float, l: float, chord: float, stretch: float
) -> tuple[float, float]:
    """(H, V_A) [N] of the uniform line (load ``w`` [N/m] along ``-up``, length ``L``
    [m]) between ends ``h`` [m] apart along ``up`` and ``l`` [m] across it (``chord``
    [m] apart), after Peyrot & Goulios (1979), with the elastic ``stretch`` [N] of a taut
    chord added: the start of :func:`.semi_analytic_newton.initial_tension` and
    :func:`_initial_tension`."""
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
    return H, VB - w * L


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
        TA[2] = mooring_vertical(math.hypot(TA[0], TA[1]), -Cend[2], zB - rA[2], L)
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
    H, VA = uniform_end_tension(w, L, h, l, chord, stretch)
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
def _anchored(
    q: np.ndarray, weight: np.ndarray, ell: np.ndarray, EA: np.ndarray, point: np.ndarray,
    bounds: np.ndarray, kind: int, rA: np.ndarray, rB: np.ndarray, force: np.ndarray,
    zB: float, seabed: np.ndarray, T: np.ndarray, have: bool, tol: float, maxit: int,
    C: np.ndarray, Cend: np.ndarray, dr: np.ndarray, nodes: np.ndarray, scratch: np.ndarray,
) -> tuple[int, int, float]:  # fmt: skip
    """:meth:`.semi_analytic.SemiAnalyticSolver._inner` of a line anchored at A on the
    seabed, y = ``T`` in/out: in contact from the previous solve's y (``have``); else,
    on a flat seabed in still water, from the mooring line's start; else free-hanging
    first from ``T`` (the start tension), then in contact where that shape certainly
    reaches the seabed (its tension at the anchor points into it). Returns (0 or the
    status that hands the case on, Newton iterations, residual)."""
    if have:
        return _contact(
            q, weight, ell, EA, point, bounds, kind, rA, rB, force, zB, seabed, tol, maxit,
            T, 0, nodes,
        )  # fmt: skip
    still = seabed[11] == 1.0
    for p in range(q.shape[0]):
        still = still and q[p, 0] == 0.0 and q[p, 1] == 0.0
    code, its = _OK, 0
    if not still:
        code, its, _r = _solve_free(
            q, ell, EA, point, bounds[-1], kind, rA, rB, force, zB, T, tol, maxit, True, C,
            Cend, dr, nodes, scratch,
        )  # fmt: skip
        if code == _GIVE_UP:
            return GIVE_UP, 0, 0.0
        if code == _OK and T[0] * seabed[0] + T[1] * seabed[1] + T[2] * seabed[2] >= 0.0:
            return LIFTS_OFF, 0, 0.0  # it may hang free: the general solver's
    st, more, res = _contact(
        q, weight, ell, EA, point, bounds, kind, rA, rB, force, zB, seabed, tol, maxit, T,
        1 if still else 2, nodes,
    )  # fmt: skip
    return st, more + (its if code == _OK else 0), res
