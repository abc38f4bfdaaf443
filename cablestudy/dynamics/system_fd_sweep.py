"""The compiled drag iteration of a system's frequency domain over a sweep of cases that
share one linear model (:func:`solve_sweep`: several frequencies and motions in one
compiled call; a case alone is a sweep of one).

The iteration (:func:`iterate`) is the one the module docstring of
:mod:`.system_frequency` gives, by the steps of :mod:`.system_fd_kernel` (the
condensation, the junction system, the residual) and :mod:`.system_fd_fit` (the drag
fit, Anderson mixing), in a work space allocated once (:func:`workspace`) and reused
by every case of a sweep.

Each case starts from its own quasi-static motion (the drag fitted to the response
without drag at zero frequency), whatever the cases beside it: a case in a sweep is the
case alone bit for bit (the work space's state is set afresh by each case's start). The
quasi-static motion depends on the prescribed motion alone, not on the frequency: a case
of the same motion as the one before takes that one's (the same bits) instead of
solving it again.

Pure: arrays in, arrays out.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .system_fd_fit import DEPTH, anderson, fit_all
from .system_fd_kernel import OK, _larger, _residual, _solve

#: ``info`` of a case (``info[i]``): code, iterations, failing line, 1 if it failed in
#: the quasi-static start
INFO = 4


@njit(cache=True)
def workspace(m, bw, samples):  # noqa: ANN001, ANN201
    """The iteration's work arrays for the packed model ``m``
    (:attr:`.system_fd_pack.PackedSystem.arrays`) with band width ``bw`` and
    ``samples`` phases of the drag fit (a tuple, :func:`iterate` reads it)."""
    noff, KR, ends, pcur, free = m[0], m[2], m[31], m[36], m[33]
    N = noff[-1]
    P = pcur.shape[0]
    L = ends.shape[0]
    K = KR.shape[0]
    F = free.shape[0]
    size = 9 * (N + P)
    cs = np.empty(samples)
    sn_ = np.empty(samples)
    for k in range(samples):
        cs[k] = math.cos(2.0 * math.pi * k / samples)
        sn_[k] = math.sin(2.0 * math.pi * k / samples)
    return (
        np.empty((max(K, 1), 3 * bw + 1), dtype=np.complex128),  # R
        np.empty(max(K, 1), dtype=np.int64),  # reach
        np.empty((K, 6), dtype=np.complex128),  # X
        np.empty((L, 6, 6), dtype=np.complex128),  # A_EE
        np.empty(K, dtype=np.complex128),  # uI
        np.empty(L, dtype=np.int64),  # ncol
        np.empty(6, dtype=np.complex128),  # uE
        np.empty((3 * F, 3 * F), dtype=np.complex128),  # G
        np.empty(3 * F, dtype=np.complex128),  # rhs
        np.empty(KR.shape, dtype=np.complex128),  # Rb
        np.zeros((K, 6), dtype=np.complex128),  # IE (its dofs coupled to the ends alone)
        np.zeros((6, K), dtype=np.complex128),  # EI
        np.empty((L, 6, 6), dtype=np.complex128),  # EE
        np.zeros(size),  # flat: the drag D (N, 3, 3) then Dp (P, 3, 3)
        np.zeros(size),  # fit: the fit of the last iterate, as flat
        cs,
        sn_,
        np.empty((N, 3)),  # vr
        np.empty((N, 3)),  # vi
        np.empty((N, 3, 3)),  # lean
        np.zeros((N, 3), dtype=np.complex128),  # prev_d: the last iterate's motion
        np.zeros((P, 3), dtype=np.complex128),  # prev_p
        np.empty((DEPTH + 1, size)),  # hist_R
        np.empty((DEPTH + 1, size)),  # hist_G
        np.zeros(2, dtype=np.int64),  # state: the mixing's pairs and first row
        np.empty((L, 2), dtype=np.int64),  # low: per line the first row back-substituted
        np.zeros((N, 3), dtype=np.complex128),  # qs_d: the last quasi-static start's motion
        np.zeros((P, 3), dtype=np.complex128),  # qs_p
        np.zeros((P, 3), dtype=np.complex128),  # qs_of: the prescribed motion it is of
        np.zeros(1, dtype=np.int64),  # qs_ok: 1 while qs_d, qs_p hold a solved start
        np.empty(max(K, 1), dtype=np.complex128),  # pinv: the band factor's pivots' inverses
        np.empty((DEPTH + 1, DEPTH + 1)),  # gram: the mixing's Gram matrix of hist_R
    )


@njit(cache=True, error_model="numpy")
def _solve_at(w, drag, m, bw, ws, prescribed, disp, u_pts, forces):  # noqa: ANN001, ANN202, PLR0913
    """:func:`.system_fd_kernel._solve` at ``w`` with the model ``m``, the work space
    ``ws`` and its drag (``drag``): (code, line)."""
    N = disp.shape[0]
    D = ws[13][: 9 * N].reshape(N, 3, 3)
    Dp = ws[13][9 * N :].reshape(u_pts.shape[0], 3, 3)
    return _solve(
        w,
        drag,
        D,
        Dp,
        prescribed,
        m[0],
        m[1],
        bw,
        ws[9],
        ws[10],
        ws[11],
        ws[12],
        m[14],
        m[15],
        m[16],
        m[17],
        m[18],
        m[31],
        m[32],
        m[33],
        m[34],
        ws[0],
        ws[1],
        ws[2],
        ws[3],
        ws[4],
        ws[5],
        ws[25],
        ws[6],
        ws[7],
        ws[8],
        disp,
        u_pts,
        forces,
        ws[30],
        m[38],
        m[39],
    )


@njit(cache=True, error_model="numpy")
def _parts_at(w, m, ws):  # noqa: ANN001, ANN202
    """The dynamic matrix of the model ``m`` without drag at ``w`` (``K - w^2 M + i w
    C``) into ``ws``: band rows ``Rb``, couplings ``IE`` (dofs, 6), ``EI`` (6, dofs),
    ``EE`` (L, 6, 6), shared by the iterations of a case. ``IE`` and ``EI`` only at the
    dofs coupled to the end nodes (``couple``: the only ones
    :func:`.system_fd_kernel._solve` reads; the others zero, :func:`workspace`)."""
    KR, MR, CR, koff, couple, coff = m[2], m[3], m[4], m[1], m[14], m[15]
    IEK, IEM, IEC, EIK, EIM, EIC, EEK, EEM, EEC = m[5:14]
    Rb, IE, EI, EE = ws[9], ws[10], ws[11], ws[12]
    iw = 1j * w
    w2 = w * w
    for i in range(KR.shape[0]):
        for c in range(KR.shape[1]):
            Rb[i, c] = KR[i, c] - w2 * MR[i, c] + iw * CR[i, c]
    for line in range(EEK.shape[0]):
        for q in range(coff[line], coff[line + 1]):
            i = koff[line] + couple[q]
            for c in range(6):
                IE[i, c] = IEK[i, c] - w2 * IEM[i, c] + iw * IEC[i, c]
                EI[c, i] = EIK[c, i] - w2 * EIM[c, i] + iw * EIC[c, i]
        for r in range(6):
            for c in range(6):
                EE[line, r, c] = EEK[line, r, c] - w2 * EEM[line, r, c] + iw * EEC[line, r, c]


@njit(cache=True, error_model="numpy")
def _fit_at(omega, m, ws, exact, disp, u_pts, out):  # noqa: ANN001, ANN202, PLR0913
    """:func:`.system_fd_fit.fit_all` of the motion at ``omega`` into ``out`` (flat)."""
    N = disp.shape[0]
    P = u_pts.shape[0]
    fit_all(
        omega,
        disp,
        u_pts,
        m[19],
        m[20],
        m[21],
        m[22],
        m[23],
        m[35],
        m[36],
        ws[15],
        ws[16],
        exact,
        ws[17],
        ws[18],
        ws[19],
        out[: 9 * N].reshape(N, 3, 3),
        out[9 * N :].reshape(P, 3, 3),
    )


@njit(cache=True)
def _same_motion(a, b):  # noqa: ANN001, ANN202
    """Whether the complex arrays ``a`` and ``b`` (P, 3) are equal bit for bit (signs of
    zeros too)."""
    for p in range(a.shape[0]):
        for c in range(3):
            x, y = a[p, c], b[p, c]
            if not (x.real == y.real and x.imag == y.imag):
                return False
            if math.copysign(1.0, x.real) != math.copysign(1.0, y.real):
                return False
            if math.copysign(1.0, x.imag) != math.copysign(1.0, y.imag):
                return False
    return True


@njit(cache=True, error_model="numpy")
def iterate(  # noqa: ANN201, PLR0913
    omega,
    prescribed,
    tolerance,
    max_iterations,
    exact,
    m,
    bw,
    ws,
    disp,
    u_pts,
    forces,
    info,
    finfo,
):
    """A case's harmonic response (:func:`.system_frequency_sweep.solve_system_sweep_arrays`) for
    the packed model ``m`` in the work space ``ws``: ``disp`` (nodes, 3), ``u_pts`` (P,
    3), ``forces`` (L, 6) out; ``info`` (>= 4,) int: code (:data:`.system_fd_kernel.OK`,
    ``SINGULAR_LINE``, ``SINGULAR_JUNCTION``, ``NOT_CONVERGED``), iterations, failing
    line, 1 if it failed in the quasi-static start; ``finfo`` (2,): last change,
    residual (NaN when failed). The start is the quasi-static motion's fit (module
    docstring)."""
    N = disp.shape[0]
    P = u_pts.shape[0]
    flat, fit, prev_d, prev_p, hist_R, hist_G, state = (
        ws[13],
        ws[14],
        ws[20],
        ws[21],
        ws[22],
        ws[23],
        ws[24],
    )
    has_drag = m[37]
    info[0] = OK
    info[1] = 0
    info[2] = -1
    info[3] = 0
    finfo[0] = 0.0
    finfo[1] = np.nan
    if has_drag:
        qs_d, qs_p, qs_of, qs_ok = ws[26], ws[27], ws[28], ws[29]
        if qs_ok[0] and _same_motion(qs_of, prescribed):
            # the quasi-static start depends on the motion alone (not the frequency):
            # that of the case before, of the same motion, is this one's bit for bit
            disp[:, :] = qs_d
            u_pts[:, :] = qs_p
        else:
            qs_ok[0] = 0
            _parts_at(0.0, m, ws)
            code, bad = _solve_at(0.0, False, m, bw, ws, prescribed, disp, u_pts, forces)
            if code != OK:
                info[0], info[2], info[3] = code, bad, 1
                return
            qs_d[:, :] = disp
            qs_p[:, :] = u_pts
            qs_of[:, :] = prescribed
            qs_ok[0] = 1
        _fit_at(omega, m, ws, exact, disp, u_pts, flat)
        prev_d[:, :] = disp
        prev_p[:, :] = u_pts
        _parts_at(omega, m, ws)
        state[0] = 0  # the mixing's history is the case's own
        state[1] = 0
        last = np.inf
        converged = False
        for it in range(1, max_iterations + 1):
            info[1] = it
            code, bad = _solve_at(omega, True, m, bw, ws, prescribed, disp, u_pts, forces)
            if code != OK:
                info[0], info[2] = code, bad
                return
            # the largest modulus of the motion and of its change (abs only near the
            # running maximum: :func:`.system_fd_kernel._larger`)
            big, diff, big2, diff2 = 0.0, 0.0, 0.0, 0.0
            for g in range(N):
                for a in range(3):
                    z = disp[g, a]
                    dz = z - prev_d[g, a]
                    prev_d[g, a] = z
                    big, big2 = _larger(big, big2, z)
                    diff, diff2 = _larger(diff, diff2, dz)
            for p in range(P):
                for a in range(3):
                    z = u_pts[p, a]
                    dz = z - prev_p[p, a]
                    prev_p[p, a] = z
                    big, big2 = _larger(big, big2, z)
                    diff, diff2 = _larger(diff, diff2, dz)
            change = diff / max(big, 1e-300)
            finfo[0] = change
            if change <= tolerance:
                converged = True
                break
            _fit_at(omega, m, ws, exact, disp, u_pts, fit)
            anderson(flat, fit, hist_R, hist_G, ws[31], state, change, last)
            last = change
        if not converged:
            info[0] = 3  # NOT_CONVERGED
            return
    else:
        _parts_at(omega, m, ws)
        code, bad = _solve_at(omega, False, m, bw, ws, prescribed, disp, u_pts, forces)
        if code != OK:
            info[0], info[2] = code, bad
            return
    D = flat[: 9 * N].reshape(N, 3, 3)
    Dp = flat[9 * N :].reshape(P, 3, 3)
    finfo[1] = _residual(
        omega,
        has_drag,
        D,
        Dp,
        disp,
        u_pts,
        m[0],
        m[24],
        m[25],
        m[26],
        m[27],
        m[28],
        m[29],
        m[30],
        m[31],
        m[33],
        m[34],
    )


@njit(cache=True, error_model="numpy")
def solve_sweep(  # noqa: ANN201, PLR0913
    omega,
    prescribed,
    tolerance,
    max_iterations,
    samples,
    exact,
    m,
    bw,
    disp,
    u_pts,
    forces,
    info,
    finfo,
):
    """The cases ``i`` (``omega[i]`` [rad/s], ``prescribed[i]`` (P, 3)) in one work
    space, each from its own start (module docstring): ``disp[i]``, ``u_pts[i]``,
    ``forces[i]``, ``info[i]`` (:data:`INFO`) and ``finfo[i]`` as :func:`iterate`'s."""
    ws = workspace(m, bw, samples)
    for i in range(omega.shape[0]):
        iterate(
            omega[i],
            prescribed[i],
            tolerance,
            max_iterations,
            exact,
            m,
            bw,
            ws,
            disp[i],
            u_pts[i],
            forces[i],
            info[i],
            finfo[i],
        )
