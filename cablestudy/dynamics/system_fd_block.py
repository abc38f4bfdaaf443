"""The band factor of a line's dynamic matrix in the system's frequency domain
(:mod:`.system_fd_kernel`) written for the matrix it nearly always is: block
tridiagonal in the 3 x 3 blocks of the line's inner nodes (every node free in x, y and
z, coupled to its neighbours alone: no bending reach beyond the next node).

:func:`block_factor` has the contract of :func:`.system_fd_kernel._band_factor` (the
upper factor ``U`` in the row storage ``R``, the inverses of its diagonal in ``pinv``,
the last column of each row in ``reach``, the right sides ``B`` carried through as
``L^-1 B``), so that the back substitutions of the kernel read its result as they read
the band factor's. Without a row exchange the LU factors of a matrix are unique, so
they are the band factor's own wherever the band factor exchanges no rows; only the
order of the operations differs (rounding). The gain is in the form: per node the
3 x 3 factor, the multipliers of the next node's rows and the Schur update in
straight-line complex arithmetic on locals, instead of the band factor's loops over
a window of five rows with a pivot search per row, and the zeros of the band outside
the blocks skipped (``reach`` of each row ends at the next node's last column).

Where the band factor would exchange rows (a multiplier above
``1 / PIVOT_THRESHOLD`` in ``|re| + |im|``, :data:`.harmonic_kernel.PIVOT_THRESHOLD`:
the same bound on the growth) or a pivot is zero or not finite, :func:`block_factor`
returns False having changed ``R`` and ``B``: the caller builds them again and runs the
band factor, whose threshold pivoting then decides.

Pure: arrays in, arrays out.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .harmonic_kernel import PIVOT_THRESHOLD

#: the largest multiplier without a row exchange (:func:`.harmonic_kernel.band_pivot`)
_LIMIT = 1.0 / PIVOT_THRESHOLD


@njit(cache=True, inline="always")
def _big(z):  # noqa: ANN001, ANN202
    """``|re| + |im|``: the band factor's measure of an entry (LAPACK's)."""
    return abs(z.real) + abs(z.imag)


@njit(cache=True, inline="always")
def _finite(z):  # noqa: ANN001, ANN202
    """Whether both parts of ``z`` are finite."""
    return math.isfinite(z.real) and math.isfinite(z.imag)


@njit(cache=True, inline="always")
def _inverse(z):  # noqa: ANN001, ANN202
    """``1 / z`` (complex), NaN for zero: Smith's quotient, as numba's division."""
    a, b = z.real, z.imag
    if abs(a) >= abs(b):
        if a == 0.0:
            return complex(np.nan, np.nan)
        t = b / a
        d = a + b * t
        return complex(1.0 / d, -t / d)
    t = a / b
    d = a * t + b
    return complex(t / d, -1.0 / d)


@njit(cache=True, inline="always")
def _block(A, k0, k, rev, bw, i, j):  # noqa: ANN001, ANN202, PLR0913
    """The 3 x 3 block at rows ``i ..``, columns ``j ..`` (row-major, nine values) of a
    line's matrix in factor order, read from its band rows in the line's own order
    ``A[k0 + p, q - p + bw]`` (rows ``k0 .. k0 + k - 1``); with ``rev`` the factor's
    row ``i`` is the line's ``k - 1 - i`` (:func:`.system_fd_kernel._line_rows`)."""
    if rev:
        r = k0 + k - 1 - i
        o = bw - (j - i)
        return (
            A[r, o], A[r, o - 1], A[r, o - 2],
            A[r - 1, o + 1], A[r - 1, o], A[r - 1, o - 1],
            A[r - 2, o + 2], A[r - 2, o + 1], A[r - 2, o],
        )  # fmt: skip
    r = k0 + i
    o = bw + (j - i)
    return (
        A[r, o], A[r, o + 1], A[r, o + 2],
        A[r + 1, o - 1], A[r + 1, o], A[r + 1, o + 1],
        A[r + 2, o - 2], A[r + 2, o - 1], A[r + 2, o],
    )  # fmt: skip


@njit(cache=True, inline="always")
def _diagonal(A, k0, k, rev, bw, i, drag, D, g, iw):  # noqa: ANN001, ANN202, PLR0913
    """The diagonal block at row ``i`` of :func:`_block` with ``drag`` the node ``g``'s
    ``iw D[g]`` added (reversed with the line: the band rows' own sums, in their order,
    :func:`.system_fd_kernel._line_rows`)."""
    a00, a01, a02, a10, a11, a12, a20, a21, a22 = _block(A, k0, k, rev, bw, i, i)
    if drag:
        if rev:
            a00 += iw * D[g, 2, 2]
            a01 += iw * D[g, 2, 1]
            a02 += iw * D[g, 2, 0]
            a10 += iw * D[g, 1, 2]
            a11 += iw * D[g, 1, 1]
            a12 += iw * D[g, 1, 0]
            a20 += iw * D[g, 0, 2]
            a21 += iw * D[g, 0, 1]
            a22 += iw * D[g, 0, 0]
        else:
            a00 += iw * D[g, 0, 0]
            a01 += iw * D[g, 0, 1]
            a02 += iw * D[g, 0, 2]
            a10 += iw * D[g, 1, 0]
            a11 += iw * D[g, 1, 1]
            a12 += iw * D[g, 1, 2]
            a20 += iw * D[g, 2, 0]
            a21 += iw * D[g, 2, 1]
            a22 += iw * D[g, 2, 2]
    return a00, a01, a02, a10, a11, a12, a20, a21, a22


@njit(cache=True, error_model="numpy")
def block_factor(A, k0, N, rev, bw, drag, D, g0, iw, R, reach, B, m, pinv):  # noqa: ANN001, ANN201, PLR0913, PLR0915
    """Factor a line's block-tridiagonal complex matrix of 3 x 3 blocks (``N`` rows, a
    multiple of 3) without row exchanges, carrying the ``m`` right sides ``B[:N, :m]``
    (module docstring), in factor order: its band rows ``A`` in the line's own order
    (:func:`_block`; ``bw >= 5`` unless one block), with ``drag`` the drag ``iw D[g]``
    of node ``g = g0 + s`` (``g0 - s`` with ``rev``) on the factor's ``s``-th diagonal
    block (:func:`_diagonal`). ``U`` into ``R`` (rows ``0 .. N - 1``, only its
    entries), ``pinv``, ``reach`` as :func:`.system_fd_kernel._band_factor`. False when
    a multiplier exceeds :data:`_LIMIT`, a pivot is zero or not finite, or an eliminated
    right side is not finite (``R`` and ``B`` then changed: the caller starts again by
    the band factor)."""
    n = N // 3
    s00, s01, s02, s10, s11, s12, s20, s21, s22 = _diagonal(A, k0, N, rev, bw, 0, drag, D, g0, iw)
    for s in range(n):
        r = 3 * s
        # S = L U, L unit lower: multipliers l10, l20, l21
        i0 = _inverse(s00)
        l10 = s10 * i0
        l20 = s20 * i0
        s11 = s11 - l10 * s01
        s12 = s12 - l10 * s02
        s21 = s21 - l20 * s01
        s22 = s22 - l20 * s02
        i1 = _inverse(s11)
        l21 = s21 * i1
        s22 = s22 - l21 * s12
        i2 = _inverse(s22)
        if not (_big(l10) <= _LIMIT and _big(l20) <= _LIMIT and _big(l21) <= _LIMIT):
            return False  # (NaN for a zero pivot fails here too)
        if not _finite(i2):
            return False
        R[r, bw] = s00
        R[r, bw + 1] = s01
        R[r, bw + 2] = s02
        R[r + 1, bw] = s11
        R[r + 1, bw + 1] = s12
        R[r + 2, bw] = s22
        pinv[r] = i0
        pinv[r + 1] = i1
        pinv[r + 2] = i2
        last = s == n - 1
        q = r + 3
        if not last:
            # M = A_{s+1,s} U^-1: the multipliers of the next node's rows
            m00, m01, m02, m10, m11, m12, m20, m21, m22 = _block(A, k0, N, rev, bw, q, r)
            m00 = m00 * i0
            m01 = (m01 - m00 * s01) * i1
            m02 = (m02 - m00 * s02 - m01 * s12) * i2
            m10 = m10 * i0
            m11 = (m11 - m10 * s01) * i1
            m12 = (m12 - m10 * s02 - m11 * s12) * i2
            m20 = m20 * i0
            m21 = (m21 - m20 * s01) * i1
            m22 = (m22 - m20 * s02 - m21 * s12) * i2
            top = max(
                max(max(_big(m00), _big(m01)), max(_big(m02), _big(m10))),
                max(max(_big(m11), _big(m12)), max(_big(m20), max(_big(m21), _big(m22)))),
            )
            if not top <= _LIMIT:
                return False
        # the right sides through the node's rows and on to the next node's; a side
        # zero in the node's rows (a free end's unit motion: zero down to its own rows)
        # is left as it is (the band factor's mask)
        for c in range(m):
            z0, z1, z2 = B[r, c], B[r + 1, c], B[r + 2, c]
            if z0.real == 0.0 and z0.imag == 0.0 and z1.real == 0.0 and z1.imag == 0.0:
                if z2.real == 0.0 and z2.imag == 0.0:
                    continue
            z1 = z1 - l10 * z0
            z2 = z2 - l20 * z0 - l21 * z1
            if not (_finite(z0) and _finite(z1) and _finite(z2)):
                return False  # (the node's rows are final: each row is checked once)
            B[r + 1, c] = z1
            B[r + 2, c] = z2
            if not last:
                B[q, c] = B[q, c] - m00 * z0 - m01 * z1 - m02 * z2
                B[q + 1, c] = B[q + 1, c] - m10 * z0 - m11 * z1 - m12 * z2
                B[q + 2, c] = B[q + 2, c] - m20 * z0 - m21 * z1 - m22 * z2
        if last:
            reach[r] = r + 2
            reach[r + 1] = r + 2
            reach[r + 2] = r + 2
            break
        reach[r] = r + 5
        reach[r + 1] = r + 5
        reach[r + 2] = r + 5
        # V = L^-1 A_{s,s+1} (the upper factor's block right of the diagonal)
        v00, v01, v02, v10, v11, v12, v20, v21, v22 = _block(A, k0, N, rev, bw, r, q)
        v10 = v10 - l10 * v00
        v11 = v11 - l10 * v01
        v12 = v12 - l10 * v02
        v20 = v20 - l20 * v00 - l21 * v10
        v21 = v21 - l20 * v01 - l21 * v11
        v22 = v22 - l20 * v02 - l21 * v12
        R[r, bw + 3] = v00
        R[r, bw + 4] = v01
        R[r, bw + 5] = v02
        R[r + 1, bw + 2] = v10
        R[r + 1, bw + 3] = v11
        R[r + 1, bw + 4] = v12
        R[r + 2, bw + 1] = v20
        R[r + 2, bw + 2] = v21
        R[r + 2, bw + 3] = v22
        # the next node's diagonal block less M V
        g = g0 - s - 1 if rev else g0 + s + 1
        a00, a01, a02, a10, a11, a12, a20, a21, a22 = _diagonal(
            A, k0, N, rev, bw, q, drag, D, g, iw
        )
        s00 = a00 - m00 * v00 - m01 * v10 - m02 * v20
        s01 = a01 - m00 * v01 - m01 * v11 - m02 * v21
        s02 = a02 - m00 * v02 - m01 * v12 - m02 * v22
        s10 = a10 - m10 * v00 - m11 * v10 - m12 * v20
        s11 = a11 - m10 * v01 - m11 * v11 - m12 * v21
        s12 = a12 - m10 * v02 - m11 * v12 - m12 * v22
        s20 = a20 - m20 * v00 - m21 * v10 - m22 * v20
        s21 = a21 - m20 * v01 - m21 * v11 - m22 * v21
        s22 = a22 - m20 * v02 - m21 * v12 - m22 * v22
    return True


def block_lines(
    noff: np.ndarray,
    koff: np.ndarray,
    KR: np.ndarray,
    MR: np.ndarray,
    CR: np.ndarray,
    ncount: np.ndarray,
    nfirst: np.ndarray,
    unit: np.ndarray,
    bw: int,
) -> np.ndarray:
    """Per line whether :func:`block_factor` serves it: its inner nodes, in order, have
    the identity basis (three dofs each: the node's x, y, z; the end nodes none), and
    the band rows of the stiffness, mass and damping (the line's order, ``A[i, j]`` at
    ``[i, j - i + bw]``) couple a node to its neighbours alone (drag adds to the
    diagonal blocks only). Packing time (NumPy)."""
    L = noff.size - 1
    out = np.zeros(L, dtype=bool)
    width = 2 * bw + 1
    for line in range(L):
        k0, k1 = int(koff[line]), int(koff[line + 1])
        na, nb = int(noff[line]), int(noff[line + 1]) - 1
        k = k1 - k0
        inner = slice(na + 1, nb)
        if k == 0 or k != 3 * (nb - na - 1) or (bw < 5 and k > 3):
            continue
        if ncount[na] or ncount[nb] or not np.all(unit[inner]):
            continue
        if np.any(nfirst[inner] != 3 * np.arange(nb - na - 1)):
            continue
        i = np.arange(k)[:, None]
        j = i + np.arange(width)[None, :] - bw
        outside = (j >= 0) & (j < k) & (np.abs(j // 3 - i // 3) > 1)
        if all(not np.any(A[k0:k1][outside] != 0.0) for A in (KR, MR, CR)):
            out[line] = True
    return out
