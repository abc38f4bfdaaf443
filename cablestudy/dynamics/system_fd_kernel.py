"""The compiled drag iteration of a system's frequency domain
(:func:`cablestudy.dynamics.system_frequency_sweep.solve_system_sweep_arrays`): one call does a
case's whole iteration for all lines at once: per line the condensation onto its end
nodes (banded LU of the inner rows), the junction system of the free points, the drag
fit of every node and free point, Anderson mixing and the convergence test, and at the
end the check of the assembled equations.

The lines come packed once per linear model in flat arrays with offsets
(:func:`.system_fd_pack.pack_system`). Same equations, same drag criterion and the same iteration
(start, mixing, tolerance) as the module docstring of :mod:`.system_frequency` gives;
the arithmetic differs from a per-line NumPy/LAPACK sequence only in rounding:

- per line only the columns the junction needs are solved for: three unit motions per
  free end and one column for the prescribed ends' motion together (four right sides
  instead of six on a line from a junction to a body); the end forces are then
  ``A_EE u_E + A_EI u_I``, the same quantity as ``S u_E``;
- the band LU pivots by threshold (:data:`.harmonic_kernel.PIVOT_THRESHOLD`, as the
  single line's kernel), not by LAPACK's partial pivoting; a line whose matrix is block
  tridiagonal in its nodes' 3 x 3 blocks (every inner node free in x, y, z, coupled to
  its neighbours alone: :func:`.system_fd_block.block_lines`) is factored by
  :func:`.system_fd_block.block_factor`, the same LU bit for bit where the band factor
  exchanges no rows, and by the band factor where it would (measured on case8, 20
  elements a line, 50 frequencies: the kernel 0.70-0.74 -> 0.55-0.56 ms a case, 10.06
  drag iterations a case as before, every answer the same bits;
  benchmarks/bench_fd_kernel.py);
- the drag fit and the small-motion Jacobian it leans on share one pass over the
  phases, and at a node without current (drag odd in the relative velocity: the phase
  ``th + pi`` gives the opposite velocity and force) the phases of a half period are
  summed twice, the mean force being zero (:func:`.system_fd_fit.fit_node`); with
  ``samples`` unset such a node takes both as exact period means in closed form
  instead (:mod:`.elliptic_fit`; the oracle: dense quadrature);
- the junction system is solved by Gaussian elimination with partial pivoting of its
  own (:func:`_dense_solve`), as LAPACK's but not its blocked order.

Pure: arrays in, arrays out.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .harmonic_kernel import band_pivot
from .system_fd_block import block_factor

#: no fast-math in these kernels: it made them no faster (the time goes to the fit,
#: :func:`.system_fd_fit.fit_node`) and made their answers depend on whether numba had
#: just compiled them or loaded them from its cache (by up to 2e-9 of a value)
_SAFE_FAST = False
#: codes of the kernel's outcome (``info[0]``)
OK, SINGULAR_LINE, SINGULAR_JUNCTION, NOT_CONVERGED = 0, 1, 2, 3


# ------------------------------------------------------------------------ kernels


@njit(cache=True, error_model="numpy", fastmath=_SAFE_FAST)
def _band_factor(R, bw, N, reach, B, m, pinv):  # noqa: ANN001, ANN201, PLR0913
    """Factor the complex band matrix on row storage ``R`` (>= N, 3 bw + 1) (``A[i, j]``
    at ``R[i, j - i + bw]``) in place, by the threshold pivoting of
    :func:`.harmonic_kernel.band_pivot`, and carry the ``m`` right sides ``B[:N,
    :m]`` through the elimination (``B`` becomes ``L^-1 P B``; the upper factor ``U``
    stays in ``R``, its last column of row ``i`` in ``reach[i]``, and the inverse of
    its diagonal in ``pinv[i]``, for :func:`_back_rows` and the back substitution:
    the same quotient a substitution would form, one complex division a row the
    less). False for a zero pivot or a non-finite eliminated side."""
    for i in range(N):
        reach[i] = min(i + bw, N - 1)
    for k in range(N):
        last = min(k + bw, N - 1)
        p = band_pivot(R, bw, reach, k, last)
        if p < 0:
            return False
        if p != k:
            for c in range(m):
                t = B[k, c]
                B[k, c] = B[p, c]
                B[p, c] = t
        inv = 1.0 / R[k, bw]
        pinv[k] = inv
        rk = reach[k]
        # the right sides with a non-zero at row k (the others stay zero below it: a
        # free end's unit motion is zero down to its own rows, which come last)
        mask = 0
        for c in range(m):
            if B[k, c].real != 0.0 or B[k, c].imag != 0.0:
                mask |= 1 << c
        if bw == 5 and rk == k + 5:
            # a node's three directions and the next node's (bw 5) without a row
            # exchange above: the five entries of row k written out (the same products
            # in the same order as the loop below; a loop of unknown length this short
            # costs more than its arithmetic)
            u1, u2, u3, u4, u5 = R[k, 6], R[k, 7], R[k, 8], R[k, 9], R[k, 10]
            for i in range(k + 1, last + 1):
                o = k - i + 5
                z = R[i, o]
                if z.real == 0.0 and z.imag == 0.0:
                    continue
                f = z * inv
                R[i, o + 1] -= f * u1
                R[i, o + 2] -= f * u2
                R[i, o + 3] -= f * u3
                R[i, o + 4] -= f * u4
                R[i, o + 5] -= f * u5
                if mask:
                    for c in range(m):
                        if (mask >> c) & 1:
                            B[i, c] -= f * B[k, c]
                if rk > reach[i]:
                    reach[i] = rk
            continue
        for i in range(k + 1, last + 1):
            z = R[i, k - i + bw]
            if z.real == 0.0 and z.imag == 0.0:
                continue
            f = z * inv
            for j in range(k + 1, rk + 1):
                R[i, j - i + bw] -= f * R[k, j - k + bw]
            if mask:
                for c in range(m):
                    if (mask >> c) & 1:
                        B[i, c] -= f * B[k, c]
            if rk > reach[i]:
                reach[i] = rk
    for i in range(N):
        for c in range(m):
            if not (math.isfinite(B[i, c].real) and math.isfinite(B[i, c].imag)):
                return False
    return True


@njit(cache=True, error_model="numpy", fastmath=_SAFE_FAST)
def _back_rows(R, bw, N, reach, B, m, low, pinv):  # noqa: ANN001, ANN201, PLR0913
    """Back substitution of :func:`_band_factor`'s ``B`` for its rows ``low .. N-1``
    only (in place: the solution's rows there, exactly as a full substitution gives
    them; the rows above keep ``L^-1 P B``). False for a non-finite answer."""
    for i in range(N - 1, low - 1, -1):
        inv = pinv[i]
        for c in range(m):
            acc = B[i, c]
            for j in range(i + 1, reach[i] + 1):
                acc -= R[i, j - i + bw] * B[j, c]
            B[i, c] = acc * inv
            if not (math.isfinite(B[i, c].real) and math.isfinite(B[i, c].imag)):
                return False
    return True


@njit(cache=True, error_model="numpy")
def _dense_solve(G, rhs, n):  # noqa: ANN001, ANN202
    """Solve ``G[:n, :n] x = rhs[:n]`` in place (Gaussian elimination, partial
    pivoting); False for a zero pivot or a non-finite answer."""
    for k in range(n):
        p = k
        big = abs(G[k, k])
        for i in range(k + 1, n):
            if abs(G[i, k]) > big:
                big, p = abs(G[i, k]), i
        if not big > 0.0:
            return False
        if p != k:
            for j in range(n):
                t = G[k, j]
                G[k, j] = G[p, j]
                G[p, j] = t
            t = rhs[k]
            rhs[k] = rhs[p]
            rhs[p] = t
        for i in range(k + 1, n):
            f = G[i, k] / G[k, k]
            if f == 0.0:
                continue
            for j in range(k + 1, n):
                G[i, j] -= f * G[k, j]
            rhs[i] -= f * rhs[k]
    for i in range(n - 1, -1, -1):
        acc = rhs[i]
        for j in range(i + 1, n):
            acc -= G[i, j] * rhs[j]
        rhs[i] = acc / G[i, i]
        if not (math.isfinite(rhs[i].real) and math.isfinite(rhs[i].imag)):
            return False
    return True


@njit(cache=True, error_model="numpy", fastmath=_SAFE_FAST)
def _line_sides(X, k0, k, rev, line, ends, slot, couple, c0, c1, IE, prescribed):  # noqa: ANN001, ANN202, PLR0913
    """The right sides of line ``line`` into ``X[k0:k0 + k]`` (factor order): the unit
    motions of its free ends, then the prescribed ends' motion together if one moves;
    their number."""
    m = 0
    for e in range(2):
        if slot[ends[line, e]] >= 0:
            for a in range(3):
                for i in range(k):
                    X[k0 + i, m] = 0.0
                for q in range(c0, c1):
                    i = couple[q]
                    X[k0 + (k - 1 - i if rev else i), m] = -IE[k0 + i, 3 * e + a]
                m += 1
    moved = False  # a prescribed end that moves (a fixed anchor's column is zero)
    for e in range(2):
        pt = ends[line, e]
        if slot[pt] < 0:
            for a in range(3):
                if prescribed[pt, a].real != 0.0 or prescribed[pt, a].imag != 0.0:
                    moved = True
    if moved:
        for i in range(k):
            X[k0 + i, m] = 0.0
        for q in range(c0, c1):
            i = couple[q]
            acc = 0j
            for e in range(2):
                pt = ends[line, e]
                if slot[pt] < 0:
                    for a in range(3):
                        acc -= IE[k0 + i, 3 * e + a] * prescribed[pt, a]
            X[k0 + (k - 1 - i if rev else i), m] = acc
        m += 1
    return m


@njit(cache=True, error_model="numpy", fastmath=_SAFE_FAST)
def _line_rows(Rl, Rb, k0, k, rev, bw, drag, na, nb, ncount, nfirst, unit, basis, D, iw):  # noqa: ANN001, ANN202, PLR0913
    """The band rows of a line's dynamic matrix with its drag (``iw D`` on its
    nodes' blocks) into ``Rl[:k]`` (factor order), the room for fill-in zeroed."""
    width = 2 * bw + 1
    if rev:
        for i in range(k):
            for c in range(width):
                Rl[i, c] = Rb[k0 + k - 1 - i, 2 * bw - c]
            for c in range(width, 3 * bw + 1):
                Rl[i, c] = 0.0
    else:
        for i in range(k):
            for c in range(width):
                Rl[i, c] = Rb[k0 + i, c]
            for c in range(width, 3 * bw + 1):
                Rl[i, c] = 0.0
    if drag:
        for g in range(na, nb + 1):
            cnt = ncount[g]
            f0 = nfirst[g]
            if unit[g]:  # the node's basis is the identity: B^T D B is D
                for r in range(3):
                    for c in range(3):
                        if rev:
                            Rl[k - 1 - f0 - r, r - c + bw] += iw * D[g, r, c]
                        else:
                            Rl[f0 + r, c - r + bw] += iw * D[g, r, c]
                continue
            for r in range(cnt):
                for c in range(cnt):
                    val = 0.0
                    for a in range(3):
                        ba = basis[g, a, r]
                        if ba == 0.0:
                            continue
                        for b in range(3):
                            val += ba * D[g, a, b] * basis[g, b, c]
                    if rev:
                        Rl[k - 1 - f0 - r, r - c + bw] += iw * val
                    else:
                        Rl[f0 + r, c - r + bw] += iw * val


@njit(cache=True, error_model="numpy", fastmath=_SAFE_FAST)
def _solve(  # noqa: ANN201, PLR0912, PLR0913, PLR0915
    w,
    drag,
    D,
    Dp,
    prescribed,
    noff,
    koff,
    bw,
    Rb,
    IE,
    EI,
    EE,
    couple,
    coff,
    basis,
    ncount,
    nfirst,
    ends,
    slot,
    free,
    pmass,
    R,
    reach,
    X,
    A_EE,
    uI,
    ncol,
    low,
    uE,
    G,
    rhs,
    disp,
    u_pts,
    forces,
    pinv,
    unit,
    blocky,
):
    """One linear solve at fixed drag (``drag``: ``D`` (nodes, 3, 3) and ``Dp`` (P, 3,
    3) enter) at ``w`` [rad/s] with :func:`.system_fd_sweep._parts_at`'s ``Rb`` ... ``EE`` at ``w``:
    ``u_pts`` (P, 3), ``disp`` (nodes, 3), ``forces`` (L, 6) (the force each line
    needs at its end nodes, ``A_EE u_E + A_EI u_I``). ``couple[coff[l]:coff[l+1]]``:
    the dofs of line ``l`` coupled to its end nodes (the non-zero columns of ``A_EI``
    and rows of ``A_IE``). Returns (code, line).

    Per line the inner rows are factored once (``R``, ``reach`` and the eliminated
    right sides ``X`` kept per line, rows ``koff[l]:koff[l+1]``), in the order that
    puts the free end last: a line whose end A alone is free is eliminated from its
    end B (row ``s`` of the factor is the line's dof ``k - 1 - s``). The junction
    needs ``A_EI X`` at the free ends only, so the back substitution of the right sides
    runs over the rows from the first one coupled to a free end to the last (``low[l, 0]``;
    ``low[l, 1]``: the row above which the unit motions' eliminated sides are zero);
    after the junction solve, the inner motion is one back substitution of the
    eliminated sides combined by the end motions (the rows already solved combined
    directly)."""
    L = ends.shape[0]
    F = free.shape[0]
    iw = 1j * w
    w2 = w * w
    G[:, :] = 0.0
    rhs[:] = 0.0
    for j in range(F):
        p = free[j]
        for a in range(3):
            for b in range(3):
                z = -w2 * pmass[p, a, b]
                if drag:
                    z += iw * Dp[p, a, b]
                G[3 * j + a, 3 * j + b] += z
    for line in range(L):
        k0 = koff[line]
        k = koff[line + 1] - k0
        na, nb = noff[line], noff[line + 1] - 1
        c0, c1 = coff[line], coff[line + 1]
        rev = slot[ends[line, 0]] >= 0 and slot[ends[line, 1]] < 0
        for r in range(6):
            for c in range(6):
                A_EE[line, r, c] = EE[line, r, c]
        if drag:
            for a in range(3):
                for b in range(3):
                    A_EE[line, a, b] += iw * D[na, a, b]
                    A_EE[line, 3 + a, 3 + b] += iw * D[nb, a, b]
        # right sides: unit motions of the free ends, the prescribed ends' motion together
        m = _line_sides(X, k0, k, rev, line, ends, slot, couple, c0, c1, IE, prescribed)
        ncol[line] = m
        # the first row of the factor that a free end's junction rows read, and the
        # first where a free end's unit motion is not zero
        first = top = k
        for q in range(c0, c1):
            i = couple[q]
            s_i = k - 1 - i if rev else i
            for e in range(2):
                if slot[ends[line, e]] >= 0:
                    for a in range(3):
                        z = EI[3 * e + a, k0 + i]
                        if s_i < first and (z.real != 0.0 or z.imag != 0.0):
                            first = s_i
                        z = IE[k0 + i, 3 * e + a]
                        if s_i < top and (z.real != 0.0 or z.imag != 0.0):
                            top = s_i
        low[line, 0] = first
        # above both the unit motions' eliminated sides stay zero (the block factor
        # exchanges no rows and skips a node's zero sides; the band factor may exchange)
        low[line, 1] = 0
        if k > 0:
            Rl = R[k0:]
            done = False
            if blocky[line]:
                # block tridiagonal: its own factor (system_fd_block), reading the band
                # rows and the drag where they are; where it declines (the band factor
                # would exchange rows) the right sides again, and the band factor
                g0 = nb - 1 if rev else na + 1
                done = block_factor(
                    Rb, k0, k, rev, bw, drag, D, g0, iw, Rl, reach[k0:], X[k0:], m, pinv[k0:]
                )
                if not done:
                    _line_sides(X, k0, k, rev, line, ends, slot, couple, c0, c1, IE, prescribed)
            if done:
                low[line, 1] = min(first, top)
            else:
                _line_rows(Rl, Rb, k0, k, rev, bw, drag, na, nb, ncount, nfirst, unit, basis, D, iw)
                if not _band_factor(Rl, bw, k, reach[k0:], X[k0:], m, pinv[k0:]):
                    return SINGULAR_LINE, line
            if not _back_rows(Rl, bw, k, reach[k0:], X[k0:], m, first, pinv[k0:]):
                return SINGULAR_LINE, line
        # the junction rows of the free ends: S u_E = A_EE u_E + A_EI X u_E
        for ea in range(2):
            sa = slot[ends[line, ea]]
            if sa < 0:
                continue
            for al in range(3):
                row = 3 * ea + al
                c = 0
                for eb in range(2):
                    sb = slot[ends[line, eb]]
                    if sb < 0:
                        continue
                    for be in range(3):
                        acc = A_EE[line, row, 3 * eb + be]
                        for q in range(c0, c1):
                            i = couple[q]
                            z = EI[row, k0 + i]
                            if z.real != 0.0 or z.imag != 0.0:
                                acc += z * X[k0 + (k - 1 - i if rev else i), c]
                        G[3 * sa + al, 3 * sb + be] += acc
                        c += 1
                if c < m:  # the prescribed column
                    acc = 0j
                    for eb in range(2):
                        pt = ends[line, eb]
                        if slot[pt] < 0:
                            for be in range(3):
                                acc += A_EE[line, row, 3 * eb + be] * prescribed[pt, be]
                    for q in range(c0, c1):
                        i = couple[q]
                        z = EI[row, k0 + i]
                        if z.real != 0.0 or z.imag != 0.0:
                            acc += z * X[k0 + (k - 1 - i if rev else i), c]
                    rhs[3 * sa + al] -= acc
    for p in range(prescribed.shape[0]):
        for a in range(3):
            u_pts[p, a] = prescribed[p, a]
    if F:
        if not _dense_solve(G, rhs, 3 * F):
            return SINGULAR_JUNCTION, -1
        for j in range(F):
            for a in range(3):
                u_pts[free[j], a] = rhs[3 * j + a]
    for line in range(L):
        k0 = koff[line]
        k = koff[line + 1] - k0
        na, nb = noff[line], noff[line + 1] - 1
        c0, c1 = coff[line], coff[line + 1]
        rev = slot[ends[line, 0]] >= 0 and slot[ends[line, 1]] < 0
        m = ncol[line]
        first, zero = low[line, 0], low[line, 1]
        units = 0  # the unit motions' columns
        for e in range(2):
            if slot[ends[line, e]] >= 0:
                units += 3
        for e in range(2):
            for a in range(3):
                uE[3 * e + a] = u_pts[ends[line, e], a]
        # u_I = X [u_E; 1]: the rows back-substituted already combined, the others
        # substituted back from the combined eliminated sides (row s of the factor is
        # the dof k - 1 - s of a reversed line); above ``zero`` the unit motions' sides
        # are zeros, which leave ``acc`` +0 (the same bits without them)
        for s_ in range(k - 1, -1, -1):
            acc = 0j
            c = units
            if s_ >= zero:
                c = 0
                for e in range(2):
                    if slot[ends[line, e]] >= 0:
                        for a in range(3):
                            acc += X[k0 + s_, c] * uE[3 * e + a]
                            c += 1
            if c < m:
                acc += X[k0 + s_, c]
            if s_ < first:
                for j in range(s_ + 1, reach[k0 + s_] + 1):
                    acc -= R[k0 + s_, j - s_ + bw] * uI[k0 + (k - 1 - j if rev else j)]
                acc = acc * pinv[k0 + s_]
                if not (math.isfinite(acc.real) and math.isfinite(acc.imag)):
                    return SINGULAR_LINE, line
            uI[k0 + (k - 1 - s_ if rev else s_)] = acc
        for g in range(na, nb + 1):
            f0 = nfirst[g]
            if unit[g]:  # the identity basis: the node's dofs are its motion
                for a in range(3):
                    disp[g, a] = uI[k0 + f0 + a]
                continue
            for a in range(3):
                acc = 0j
                for r in range(ncount[g]):
                    acc += basis[g, a, r] * uI[k0 + f0 + r]
                disp[g, a] = acc
        for a in range(3):
            disp[na, a] += uE[a]
            disp[nb, a] += uE[3 + a]
        for row in range(6):
            acc = 0j
            for b in range(6):
                acc += A_EE[line, row, b] * uE[b]
            for q in range(c0, c1):
                i = couple[q]
                acc += EI[row, k0 + i] * uI[k0 + i]
            forces[line, row] = acc
    return OK, -1


#: a complex number whose squared modulus is below this fraction of the largest squared
#: modulus so far cannot have a larger modulus than the number that set it (the
#: squares' rounding and ``abs``'s, a few units in the last place, are far below
#: 1e-15): :func:`_larger` takes ``abs`` (a ``hypot``) only of the others, and the
#: maximum of the moduli is the one of all of them, bit for bit
_NEAR = 1.0 - 1e-12


@njit(cache=True, inline="always")
def _larger(top, top2, z):  # noqa: ANN001, ANN202
    """``max(top, abs(z))`` and the largest squared modulus ``top2`` so far, updated:
    ``abs`` only where it may change the maximum (:data:`_NEAR`)."""
    q = z.real * z.real + z.imag * z.imag
    if q >= _NEAR * top2:
        top = max(top, abs(z))
        top2 = max(top2, q)
    return top, top2


@njit(cache=True, error_model="numpy")
def _residual(
    omega, drag, D, Dp, disp, u_pts, noff, mass, kp, ki, kv, cp, ci, cv, ends, free, pmass
):  # noqa: ANN001, ANN202, PLR0913
    """:func:`.system_frequency._residual`: the largest residual of every line's inner
    rows and every free point's balance relative to the force scale."""
    L = ends.shape[0]
    scale = worst = scale2 = worst2 = 0.0  # the largest moduli and their squares (_larger)
    balance = np.zeros(u_pts.shape, dtype=np.complex128)
    iw = 1j * omega
    w2 = omega * omega
    r = np.empty(3, dtype=np.complex128)
    # a line's column j (node j // 3, direction j % 3) is entry 3 n0 + j of the flat
    # motion: the same values, without a division per stored entry
    flat = disp.reshape(-1)
    for line in range(L):
        n0, n1 = noff[line], noff[line + 1]
        base = 3 * n0
        for g in range(n0, n1):
            for a in range(3):
                row = 3 * g + a
                ku = 0j
                for jj in range(kp[row], kp[row + 1]):
                    ku += kv[jj] * flat[base + ki[jj]]
                cu = 0j
                for jj in range(cp[row], cp[row + 1]):
                    cu += cv[jj] * flat[base + ci[jj]]
                acc = ku + iw * cu
                mu = 0j
                du = 0j
                for b in range(3):
                    mu += mass[g, a, b] * disp[g, b]
                    if drag:
                        du += D[g, a, b] * disp[g, b]
                acc -= w2 * mu
                if drag:
                    acc += iw * du
                r[a] = acc
                scale, scale2 = _larger(scale, scale2, ku)
            if g == n0 or g == n1 - 1:
                e = 0 if g == n0 else 1
                for a in range(3):
                    scale, scale2 = _larger(scale, scale2, r[a])
                    balance[ends[line, e], a] += r[a]
            else:
                for a in range(3):
                    worst, worst2 = _larger(worst, worst2, r[a])
    for j in range(free.shape[0]):
        p = free[j]
        for a in range(3):
            acc = balance[p, a]
            for b in range(3):
                z = -w2 * pmass[p, a, b]
                if drag:
                    z += iw * Dp[p, a, b]
                acc += z * u_pts[p, b]
            worst, worst2 = _larger(worst, worst2, acc)
    return worst / max(scale, 1e-300)
