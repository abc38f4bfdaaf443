"""Compiled (numba) Newton on the free points of a mooring system, for batches of cases.

The mathematics is that of :func:`.system._solve` (Newton on the free points' positions
with each line's exact end-force stiffness, the step capped at half the shortest line
on a free point, a line search on the system's energy along the step, one polishing
step past the tolerance) with every line solved by the still-water catenary kernels'
own mathematics: a line hanging free by the Newton of :func:`._fast.solve_cases` (end B
fixed), its end stiffness G = J^-1 from the flexibility J = d(r_B - r_A)/d T_A at the
solution; a line anchored at end A on the seabed by the Newton of
:func:`._fast_contact.contact_cases`, its end stiffness K_BB = N M^-1 (M = d r_B / dy
the contact Newton's Jacobian, N = d T(L) / dy, y = (alpha, beta, s_td)), as
:func:`.line_stiffness.line_end_stiffness`.

Each line of a trial starts from its own solution at the current iterate (its tension
at A hanging free, or its touchdown unknowns on the seabed), so a system iteration
costs a few line iterations; the answer is the same equilibrium to the tolerance. A
line anchored on the seabed whose loads all point down is solved hanging free first and
kept where its anchor tension does not point into the seabed (then no point of it is
below the seabed: :func:`.batch._hang_free`), else on the seabed; a line on the seabed
that lifts off hangs free. That choice is made by the ends' positions alone, never by
the line's state at the iterate: the net force on the free points is then a function of
their positions (chosen by history it jumps where a line touches down, and the line
search fails there: measured on case8 at 14.35 m surge). Whatever a trial cannot solve
makes the line search shorten the step, as :func:`.system._trial` does. A line
anchored on the seabed that lies slack there (a free point started by eye) has its end
forces all the same (:func:`._system_lines._slack_line`, as :mod:`.system_slack`), so
the Newton can start there and move to the taut equilibrium.

The kernel gives the free points' positions, each line's end forces and end stiffness
at the last iterate, and a status; the caller re-solves and verifies the lines at the
solution (:mod:`.system_fast`). Pure: arrays in, arrays out.
"""

from __future__ import annotations

import math

import numpy as np

from ._fast import _gauss, njit
from ._fast_contact import LIFT_OFF, NOT_CONVERGED, NUMERICAL
from ._system_lines import _contact_line, _free_line, _inv3, _offsets, _slack_line

#: statuses of :func:`system_cases` (0: converged)
SYS_NOT_CONVERGED = 1
SYS_LINE_SEARCH = 2
SYS_LINE_FAILED = 3
SYS_SINGULAR = 4

#: why (the text of each status)
SYS_REASONS = {
    SYS_NOT_CONVERGED: "the free points did not converge in the iteration limit",
    SYS_LINE_SEARCH: "the line search failed",
    SYS_LINE_FAILED: "a line has no compiled solution at the start",
    SYS_SINGULAR: "singular stiffness of the free points",
}


@njit(cache=True, error_model="numpy")
def _solve_dense(A: np.ndarray, b: np.ndarray, x: np.ndarray, W: np.ndarray) -> bool:
    """x = A^-1 b (Gaussian elimination with partial pivoting in the scratch ``W``
    (n, n + 1)); False when ``A`` is singular or not finite."""
    n = b.shape[0]
    for i in range(n):
        for j in range(n):
            W[i, j] = A[i, j]
        W[i, n] = b[i]
    if not _gauss(W, n, x):
        return False
    for i in range(n):
        if not math.isfinite(x[i]):
            return False
    return True


@njit(cache=True, error_model="numpy")
def _eval_lines(
    c: int,
    pos: np.ndarray,
    only_moving: bool,
    moving: np.ndarray,
    la: np.ndarray,
    lb: np.ndarray,
    poff: np.ndarray,
    ell: np.ndarray,
    EA: np.ndarray,
    w: np.ndarray,
    bounds: np.ndarray,
    point: np.ndarray,
    anchored: np.ndarray,
    clear: np.ndarray,
    normal: np.ndarray,
    basis: np.ndarray,
    depth: float,
    mu: float,
    still: bool,
    has_plane: bool,
    ltol: float,
    lmaxit: int,
    mode_in: np.ndarray,
    TA_in: np.ndarray,
    y_in: np.ndarray,
    mode_out: np.ndarray,
    TA_out: np.ndarray,
    y_out: np.ndarray,
    fa_out: np.ndarray,
    fb_out: np.ndarray,
    K_out: np.ndarray,
    C: np.ndarray,
    sc: np.ndarray,
    sc3: np.ndarray,
    t_lo: np.ndarray,
    t_hi: np.ndarray,
    rate: np.ndarray,
    hi_s: np.ndarray,
    A4: np.ndarray,
    free3: np.ndarray,
    K_in: np.ndarray,
    d_in: np.ndarray,
    d_out: np.ndarray,
) -> bool:
    """Every line of case ``c`` between the points at ``pos`` (n, 3) (with
    ``only_moving``, the lines with an end on a free point; the others keep their
    state), each from its state ``*_in`` to ``*_out``: mode (0 hanging free, 1 on the
    seabed from end A, 2 slack on the seabed from end A: :func:`._system_lines.
    _slack_line`), tension at A, touchdown unknowns, end forces and end stiffness
    (hanging free: G = J^-1, K_AA = K_BB = G, K_AB = K_BA = -G; on the seabed: K_BB in
    ``K_out[m]``). False where a line cannot be solved there.

    In a trial (``only_moving``) a line hanging free starts from its tension at the
    iterate moved to first order with its ends, T_A + G (d - d_in) (``K_in`` its G there,
    ``d_in`` its r_B - r_A; ``d_out`` the new one), and from T_A alone where that start
    does not converge."""
    M = la.shape[1]
    d = sc[10]
    Cend = sc[11]
    r = sc[12]
    rn = sc[13]
    Tn = sc[14]
    g = sc[15]
    stp = sc[16]
    J = sc3[5]
    Jn = sc3[6]
    for m in range(M):
        if only_moving and not moving[m]:
            mode_out[m] = mode_in[m]
            for k in range(3):
                TA_out[m, k] = TA_in[m, k]
                y_out[m, k] = y_in[m, k]
                d_out[m, k] = d_in[m, k]
            continue
        a = la[c, m]
        b = lb[c, m]
        o = poff[m]
        P = poff[m + 1] - o
        ob = o + m
        ell_m = ell[c, o : o + P]
        EA_m = EA[c, o : o + P]
        w_m = w[c, o : o + P]
        b_m = bounds[c, ob : ob + P + 1]
        p_m = point[c, ob : ob + P + 1]
        L = b_m[P]
        for k in range(3):
            d[k] = pos[b, k] - pos[a, k]
        ha = 0.0
        if has_plane:
            limit = 1e-6 * L
            ha = pos[a, 0] * normal[0] + pos[a, 1] * normal[1] + (pos[a, 2] + depth) * normal[2]
            hb = pos[b, 0] * normal[0] + pos[b, 1] * normal[1] + (pos[b, 2] + depth) * normal[2]
            if not hb > limit:
                return False
            if not anchored[c, m] and not ha > limit:
                return False
        _offsets(w_m, ell_m, p_m, C, Cend)
        for k in range(3):
            TA_out[m, k] = TA_in[m, k]
            y_out[m, k] = y_in[m, k]
        done = False
        if not anchored[c, m] or clear[c, m]:
            predicted = only_moving and mode_in[m] == 0
            if predicted:
                for k in range(3):
                    TA_out[m, k] = TA_in[m, k] + (
                        K_in[m, k, 0] * (d[0] - d_in[m, 0])
                        + K_in[m, k, 1] * (d[1] - d_in[m, 1])
                        + K_in[m, k, 2] * (d[2] - d_in[m, 2])
                    )
            ok = _free_line(
                ell_m, EA_m, w_m, C, L, d, TA_out[m], ltol, lmaxit, J, r, rn, Jn, Tn, g, stp, free3
            )
            if not ok and predicted:
                for k in range(3):
                    TA_out[m, k] = TA_in[m, k]
                ok = _free_line(
                    ell_m, EA_m, w_m, C, L, d, TA_out[m], ltol, lmaxit, J, r, rn, Jn, Tn, g, stp,
                    free3,
                )  # fmt: skip
            if ok and anchored[c, m]:  # kept where the line leaves the anchor upwards
                ok = (
                    TA_out[m, 0] * normal[0] + TA_out[m, 1] * normal[1] + TA_out[m, 2] * normal[2]
                    >= 0.0
                )
            if ok:
                done = True
                mode_out[m] = 0
            elif not anchored[c, m]:
                return False
            else:
                for k in range(3):
                    TA_out[m, k] = TA_in[m, k]
        if not done:
            warm = mode_in[m] == 1
            st = _contact_line(
                ell_m, EA_m, w_m, p_m, b_m, pos[a], pos[b], normal, basis, mu, still, ltol,
                lmaxit, y_out[m], warm, fa_out[m], fb_out[m], K_out[m], sc, sc3, t_lo, t_hi,
                rate, hi_s, A4,
            )  # fmt: skip
            if st != 0 and st != LIFT_OFF and warm:  # from its own start, as alone
                st = _contact_line(
                    ell_m, EA_m, w_m, p_m, b_m, pos[a], pos[b], normal, basis, mu, still, ltol,
                    lmaxit, y_out[m], False, fa_out[m], fb_out[m], K_out[m], sc, sc3, t_lo,
                    t_hi, rate, hi_s, A4,
                )  # fmt: skip
            if st == 0:
                mode_out[m] = 1
                for k in range(3):
                    d_out[m, k] = d[k]
                continue
            ok = st == LIFT_OFF or st == NOT_CONVERGED or st == NUMERICAL
            if ok:  # hanging free, as batch._hang_free keeps it
                ok = _free_line(
                    ell_m, EA_m, w_m, C, L, d, TA_out[m], ltol, lmaxit, J, r, rn, Jn, Tn, g, stp,
                    free3,
                )  # fmt: skip
            if ok and st != LIFT_OFF:
                up = TA_out[m, 0] * normal[0] + TA_out[m, 1] * normal[1] + TA_out[m, 2] * normal[2]
                ok = clear[c, m] and up >= 0.0 and ha >= -1e-9 * L
            if not ok:
                # slack on the seabed (a trial only: the solution's lines are solved
                # again and verified): its forces, mode 2 (K_BB only, never warm)
                if has_plane and _slack_line(
                    ell_m, EA_m, w_m, p_m, pos[a], pos[b], normal, depth, fa_out[m], fb_out[m],
                    K_out[m],
                ):  # fmt: skip
                    mode_out[m] = 2
                    for k in range(3):
                        d_out[m, k] = d[k]
                    continue
                return False
            mode_out[m] = 0
        # hanging free: forces and G = J^-1 at the solution
        for k in range(3):
            d_out[m, k] = d[k]
            fa_out[m, k] = TA_out[m, k]
            fb_out[m, k] = -(TA_out[m, k] - Cend[k])
        if not _inv3(J, K_out[m]):
            return False
    return True


@njit(cache=True)
def _slide(x, step, R, normal, depth, margin, work):  # noqa: ANN001, ANN202, PLR0913
    """A free point the step would take below ``margin`` above the seabed plane (its
    upward unit ``normal``, through (0, 0, -depth)) slides along it instead (the step's
    part along the normal cut there), where the slid step still goes downhill
    (R . step > 0): :func:`.system._solve`. ``work`` (3 k,) scratch. True if it slid."""
    k = x.shape[0] // 3
    slid = False
    for i in range(k):
        h = -margin
        for q in range(3):
            h += (x[3 * i + q] + step[3 * i + q]) * normal[q]
        h += depth * normal[2]
        for q in range(3):
            work[3 * i + q] = step[3 * i + q] - min(h, 0.0) * normal[q]
        slid = slid or h < 0.0
    if not slid:
        return False
    phi = 0.0
    for i in range(3 * k):
        phi += R[i] * work[i]
    if phi > 0.0:
        for i in range(3 * k):
            step[i] = work[i]
    return phi > 0.0


@njit(cache=True, error_model="numpy")
def _assemble(
    c: int,
    la: np.ndarray,
    lb: np.ndarray,
    fidx: np.ndarray,
    mode: np.ndarray,
    fa: np.ndarray,
    fb: np.ndarray,
    K: np.ndarray,
    pforce: np.ndarray,
    free_pts: np.ndarray,
    R: np.ndarray,
    Kff: np.ndarray,
) -> None:
    """Net force on the free points (line forces and their constant force), ``R`` (3k,),
    and their assembled stiffness ``Kff`` (3k, 3k)."""
    k3 = R.shape[0]
    for i in range(k3):
        R[i] = 0.0
        for j in range(k3):
            Kff[i, j] = 0.0
    for i in range(free_pts.shape[0]):
        for q in range(3):
            R[3 * i + q] = pforce[c, free_pts[i], q]
    for m in range(la.shape[1]):
        ia = fidx[la[c, m]]
        ib = fidx[lb[c, m]]
        if ia >= 0:
            for q in range(3):
                R[3 * ia + q] += fa[m, q]
        if ib >= 0:
            for q in range(3):
                R[3 * ib + q] += fb[m, q]
        for q in range(3):
            for s in range(3):
                v = K[m, q, s]
                if ib >= 0:
                    Kff[3 * ib + q, 3 * ib + s] += v
                if mode[m] == 0:
                    if ia >= 0:
                        Kff[3 * ia + q, 3 * ia + s] += v
                    if ia >= 0 and ib >= 0:
                        Kff[3 * ia + q, 3 * ib + s] -= v
                        Kff[3 * ib + q, 3 * ia + s] -= v


@njit(cache=True, error_model="numpy")
def system_cases(
    la: np.ndarray,
    lb: np.ndarray,
    poff: np.ndarray,
    ell: np.ndarray,
    EA: np.ndarray,
    w: np.ndarray,
    bounds: np.ndarray,
    point: np.ndarray,
    anchored: np.ndarray,
    clear: np.ndarray,
    moving: np.ndarray,
    fidx: np.ndarray,
    free_pts: np.ndarray,
    pos: np.ndarray,
    pforce: np.ndarray,
    TA0: np.ndarray,
    normal: np.ndarray,
    basis: np.ndarray,
    depth: np.ndarray,
    mu: np.ndarray,
    still: np.ndarray,
    has_plane: np.ndarray,
    ltol: np.ndarray,
    lmaxit: np.ndarray,
    tol: np.ndarray,
    maxit: np.ndarray,
    cap: np.ndarray,
    mode_out: np.ndarray,
    fa_out: np.ndarray,
    fb_out: np.ndarray,
    K_out: np.ndarray,
    iters: np.ndarray,
    resid: np.ndarray,
    status: np.ndarray,
) -> None:
    """Equilibrium of the free points of N cases of one system layout.

    Lines (M) between points ``la``, ``lb`` (N, M) (end A on the seabed where
    ``anchored``), pieces ``ell``, ``EA``, ``w`` (N, sum P) [m, N, N/m] of line m at
    ``poff[m]:poff[m + 1]``, ``bounds`` and ``point`` loads (N, sum P + M[, 3]) at
    ``poff[m] + m``; ``clear`` (N, M) where the line's loads all point down (a free
    solution leaving its anchor upwards is then above the seabed); ``moving`` (M,) a line
    on a free point. Points: positions ``pos`` (N, n, 3) [m] (free points: the start,
    overwritten with the solution), ``fidx`` (n,) the free-point number or -1,
    ``free_pts`` (k,) the free points, their constant forces ``pforce`` (N, n, 3) [N].
    ``TA0`` (N, M, 3) [N] each line's starting tension at A hanging free. The seabed
    per case: ``normal``, ``basis`` (e1, e2 as columns), ``depth``, friction ``mu``,
    ``still`` (flat), ``has_plane``. Line tolerance and iterations ``ltol``, ``lmaxit``;
    the system's ``tol`` (largest net force / force scale), ``maxit``, step ``cap`` [m].

    Outputs per case and line (kernel orientation): ``mode_out`` (0 hanging free, 1 on the
    seabed, 2 slack on the seabed: a trial's state, never verified), end forces
    ``fa_out``, ``fb_out`` (N, M, 3) [N], end stiffness ``K_out`` (N, M, 3, 3) [N/m] (G,
    or K_BB on the seabed) at the last iterate; per case Newton ``iters``, ``resid`` and
    ``status`` (0 or a SYS_* code)."""
    N, M = la.shape
    n = pos.shape[1]
    k = free_pts.shape[0]
    k3 = 3 * k
    Pmax = 1
    for m in range(M):
        Pmax = max(Pmax, poff[m + 1] - poff[m])
    C = np.zeros((Pmax, 3))
    sc = np.zeros((17, 3))
    sc3 = np.zeros((7, 3, 3))
    t_lo = np.empty(Pmax)
    t_hi = np.empty(Pmax)
    rate = np.empty(Pmax)
    hi_s = np.empty(Pmax)
    A4 = np.zeros((3, 4))
    free3 = np.zeros(3, dtype=np.bool_)
    modeS = np.zeros(M, dtype=np.int64)
    modeT = np.zeros(M, dtype=np.int64)
    TAS = np.zeros((M, 3))
    TAT = np.zeros((M, 3))
    yS = np.zeros((M, 3))
    yT = np.zeros((M, 3))
    faT = np.zeros((M, 3))
    fbT = np.zeros((M, 3))
    KT = np.zeros((M, 3, 3))
    dS = np.zeros((M, 3))
    dT = np.zeros((M, 3))
    R = np.zeros(k3)
    Rn = np.zeros(k3)
    Kff = np.zeros((k3, k3))
    Kn = np.zeros((k3, k3))
    stepv = np.zeros(k3)
    W = np.zeros((k3, k3 + 1))
    x = np.zeros(k3)
    xt = np.zeros(k3)
    post = np.zeros((n, 3))
    for c in range(N):
        for m in range(M):
            modeS[m] = 0
            for q in range(3):
                TAS[m, q] = TA0[c, m, q]
                yS[m, q] = 0.0
        for i in range(k):
            for q in range(3):
                x[3 * i + q] = pos[c, free_pts[i], q]
        for i in range(n):
            for q in range(3):
                post[i, q] = pos[c, i, q]
        plane_c = has_plane[c]
        ok = _eval_lines(
            c, post, False, moving, la, lb, poff, ell, EA, w, bounds, point, anchored, clear,
            normal[c], basis[c], depth[c], mu[c], still[c], plane_c, ltol[c], lmaxit[c],
            modeS, TAS, yS, modeS, TAS, yS, fa_out[c], fb_out[c], K_out[c],
            C, sc, sc3, t_lo, t_hi, rate, hi_s, A4, free3, K_out[c], dS, dS,
        )  # fmt: skip
        it = 0
        res = 0.0
        st = 0
        if not ok:
            st = SYS_LINE_FAILED
        elif k > 0:
            _assemble(
                c, la, lb, fidx, modeS, fa_out[c], fb_out[c], K_out[c], pforce, free_pts, R, Kff
            )
            scale = 1e-300
            for m in range(M):
                ta = math.sqrt(fa_out[c, m, 0] ** 2 + fa_out[c, m, 1] ** 2 + fa_out[c, m, 2] ** 2)
                tb = math.sqrt(fb_out[c, m, 0] ** 2 + fb_out[c, m, 1] ** 2 + fb_out[c, m, 2] ** 2)
                scale = max(scale, max(ta, tb))
            for i in range(k):
                for q in range(3):
                    scale = max(scale, abs(pforce[c, free_pts[i], q]))
            res = 0.0
            for i in range(k3):
                res = max(res, abs(R[i]))
            res /= scale
            polished = False
            while res > tol[c] or not polished:
                if res <= tol[c]:
                    polished = True
                if it >= maxit[c]:
                    st = SYS_NOT_CONVERGED
                    break
                it += 1
                if not _solve_dense(Kff, R, stepv, W):
                    st = SYS_SINGULAR
                    break
                phi0 = 0.0
                for i in range(k3):
                    phi0 += R[i] * stepv[i]
                if not phi0 > 0.0:  # not positive definite here: go downhill
                    dmax = 1e-300
                    for i in range(k3):
                        dmax = max(dmax, Kff[i, i])
                    phi0 = 0.0
                    for i in range(k3):
                        stepv[i] = R[i] / dmax
                        phi0 += R[i] * stepv[i]
                longest = 0.0
                for i in range(k):
                    ln = math.sqrt(
                        stepv[3 * i] ** 2 + stepv[3 * i + 1] ** 2 + stepv[3 * i + 2] ** 2
                    )
                    longest = max(longest, ln)
                if longest > cap[c]:
                    f = cap[c] / longest
                    for i in range(k3):
                        stepv[i] *= f
                    phi0 *= f
                if plane_c and _slide(x, stepv, R, normal[c], depth[c], 1e-6 * cap[c], xt):
                    phi0 = 0.0
                    for i in range(k3):
                        phi0 += R[i] * stepv[i]
                # line search on the energy along the step (system._line_search)
                done = res <= tol[c]
                lo, f_lo = 0.0, phi0
                hi, f_hi = math.nan, math.nan
                lam = 1.0
                found = False
                retry = False
                for _ in range(41):
                    for i in range(k3):
                        xt[i] = x[i] + lam * stepv[i]
                    for i in range(k):
                        for q in range(3):
                            post[free_pts[i], q] = xt[3 * i + q]
                    good = _eval_lines(
                        c, post, True, moving, la, lb, poff, ell, EA, w, bounds, point, anchored,
                        clear, normal[c], basis[c], depth[c], mu[c], still[c], plane_c, ltol[c],
                        lmaxit[c], modeS, TAS, yS, modeT, TAT, yT, faT, fbT, KT,
                        C, sc, sc3, t_lo, t_hi, rate, hi_s, A4, free3, K_out[c], dS, dT,
                    )  # fmt: skip
                    if not good:
                        if lo > 0.0 and not retry:
                            # the energy falls all the way to lo and the lines cannot
                            # be solved a little further on: the step to lo
                            # (system._line_search), its lines evaluated again
                            lam, retry = lo, True
                            continue
                        hi, f_hi = lam, math.nan
                        lam = 0.5 * (lo + lam)
                        continue
                    for m in range(M):
                        if not moving[m]:
                            for q in range(3):
                                faT[m, q] = fa_out[c, m, q]
                                fbT[m, q] = fb_out[c, m, q]
                                for s in range(3):
                                    KT[m, q, s] = K_out[c, m, q, s]
                    _assemble(c, la, lb, fidx, modeT, faT, fbT, KT, pforce, free_pts, Rn, Kn)
                    fv = 0.0
                    for i in range(k3):
                        fv += Rn[i] * stepv[i]
                    accept = abs(fv) <= 0.5 * phi0 or (fv > 0.0 and lam == 1.0)
                    if retry or accept or (done and lam == 1.0):
                        found = True
                        break
                    if fv > 0.0:
                        lo, f_lo = lam, fv
                    else:
                        hi, f_hi = lam, fv
                    if math.isnan(f_hi):
                        lam = 0.5 * (lo + hi)
                    else:
                        guess = lo + (hi - lo) * f_lo / (f_lo - f_hi)
                        width = hi - lo
                        lam = min(max(guess, lo + 0.1 * width), hi - 0.1 * width)
                    if hi - lo <= 1e-12:
                        break
                if not found:
                    for i in range(k):  # back to the iterate
                        for q in range(3):
                            post[free_pts[i], q] = x[3 * i + q]
                    if res <= tol[c]:
                        break  # round-off: the polishing step cannot reduce it further
                    st = SYS_LINE_SEARCH
                    break
                for i in range(k3):
                    x[i] = xt[i]
                    R[i] = Rn[i]
                    for j in range(k3):
                        Kff[i, j] = Kn[i, j]
                for m in range(M):
                    modeS[m] = modeT[m]
                    for q in range(3):
                        TAS[m, q] = TAT[m, q]
                        yS[m, q] = yT[m, q]
                        dS[m, q] = dT[m, q]
                        fa_out[c, m, q] = faT[m, q]
                        fb_out[c, m, q] = fbT[m, q]
                        for s in range(3):
                            K_out[c, m, q, s] = KT[m, q, s]
                res = 0.0
                for i in range(k3):
                    res = max(res, abs(R[i]))
                res /= scale
                if polished:
                    break
        for i in range(k):
            for q in range(3):
                pos[c, free_pts[i], q] = x[3 * i + q]
        for m in range(M):
            mode_out[c, m] = modeS[m]
        iters[c] = it
        resid[c] = res
        status[c] = st
