"""Compiled (numba) kernel of :func:`.law_pieces.piece_increments`: the same graded
Gauss-Legendre quadrature of a non-linear axial law's departure from the linear piece,
one piece at a time in plain loops (no array temporaries), so that a non-linear line
costs a small multiple of a linear one. The laws are passed as a code and parameter
arrays (:func:`encode`); the mathematics is that of :mod:`cablestudy.physics.axial`
(same formulas, same inverse iteration), and the tests hold the two paths to
round-off of each other (the numpy form of the quadrature, ``tests/law_quadrature.py``).
"""

from __future__ import annotations

import math

import numpy as np

from ..physics.axial import AxialLaw, PolynomialLaw, SteelWireLaw, TableLaw, _pchip_slopes
from ._fast import _piece_general, njit

POLYNOMIAL, STEEL_WIRE, TABLE = 1, 2, 3

__all__ = ["encode", "law_corrections"]


def encode(law: AxialLaw) -> tuple[int, np.ndarray, np.ndarray, np.ndarray]:
    """(code, a, b, c) parameter arrays of ``law`` for the kernel (every non-linear law
    of :mod:`cablestudy.physics.axial`)."""
    z = np.zeros(1)
    if isinstance(law, PolynomialLaw):
        return POLYNOMIAL, np.asarray(law.coefficients, dtype=float), z, z
    if isinstance(law, SteelWireLaw):
        return STEEL_WIRE, np.array([law.stiffness, law.offset], dtype=float), z, z
    if isinstance(law, TableLaw):
        x = np.asarray(law.strain_points, dtype=float)
        y = np.asarray(law.tension_points, dtype=float)
        return TABLE, x, y, _pchip_slopes(x, y)
    raise TypeError(f"no compiled form of the axial law {type(law).__name__}")


@njit(cache=True, error_model="numpy")
def _x_plus_expm1(x: float) -> float:
    if x < 0.5:
        acc = 0.0
        f = 1.0
        # 1 / (m + 2)! for m = 12 .. 0, Horner in -x
        for m in range(12, -1, -1):
            f = 1.0
            for n in range(2, m + 3):
                f *= n
            acc = acc * (-x) + 1.0 / f
        return acc * x * x
    return x + math.expm1(-x)


@njit(cache=True, error_model="numpy")
def _seg(x: np.ndarray, e: float) -> int:
    n = x.shape[0]
    lo, hi = 0, n - 1
    if e >= x[n - 1]:
        return n - 2
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if x[mid] <= e:
            lo = mid
        else:
            hi = mid
    return lo


@njit(cache=True, error_model="numpy")
def _law(code: int, a: np.ndarray, b: np.ndarray, c: np.ndarray, e: float, what: int) -> float:
    """what 0: tension, 1: dT/de, 2: W(e) = int_0^e T; for e >= 0."""
    if code == POLYNOMIAL:
        n = a.shape[0]
        out = 0.0
        if what == 0:
            for i in range(n - 1, -1, -1):
                out = (out + a[i]) * e
        elif what == 1:
            for i in range(n, 0, -1):
                out = out * e + i * a[i - 1]
        else:
            for i in range(n, 0, -1):
                out = (out + a[i - 1] / (i + 1)) * e
            out *= e
        return out
    if code == STEEL_WIRE:
        k, d = a[0], a[1]
        x = e / d
        if what == 0:
            return k * d * _x_plus_expm1(x)
        if what == 1:
            return -k * math.expm1(-x)
        if x < 1e-3:
            g = x * x * (0.5 - x * (1.0 / 6.0 - x / 24.0))
        else:
            g = math.expm1(-x) + x
        return k * (0.5 * e * e - d * d * g)
    # table: PCHIP through (a = strain, b = tension, c = slopes), linear beyond
    xk, yk, mk = a, b, c
    n = xk.shape[0]
    if e > xk[n - 1]:
        past = e - xk[n - 1]
        if what == 0:
            return yk[n - 1] + mk[n - 1] * past
        if what == 1:
            return mk[n - 1]
        total = 0.0
        for i in range(n - 1):
            h = xk[i + 1] - xk[i]
            total += h * (0.5 * (yk[i] + yk[i + 1]) + (mk[i] - mk[i + 1]) * h / 12.0)
        return total + yk[n - 1] * past + 0.5 * mk[n - 1] * past * past
    i = _seg(xk, e)
    h = xk[i + 1] - xk[i]
    t = (e - xk[i]) / h
    y0, y1, m0, m1 = yk[i], yk[i + 1], mk[i] * h, mk[i + 1] * h
    if what == 0:
        return (
            (1 + 2 * t) * (1 - t) ** 2 * y0
            + t * (1 - t) ** 2 * m0
            + t * t * (3 - 2 * t) * y1
            + t * t * (t - 1) * m1
        )
    if what == 1:
        return (
            (6 * t * t - 6 * t) * y0
            + (3 * t * t - 4 * t + 1) * m0
            + (6 * t - 6 * t * t) * y1
            + (3 * t * t - 2 * t) * m1
        ) / h
    total = 0.0
    for j in range(i):
        hj = xk[j + 1] - xk[j]
        total += hj * (0.5 * (yk[j] + yk[j + 1]) + (mk[j] - mk[j + 1]) * hj / 12.0)
    i00 = t - t**3 + 0.5 * t**4
    i10 = 0.5 * t * t - 2.0 * t**3 / 3.0 + 0.25 * t**4
    i01 = t**3 - 0.5 * t**4
    i11 = 0.25 * t**4 - t**3 / 3.0
    return total + h * (i00 * y0 + i10 * m0 + i01 * y1 + i11 * m1)


@njit(cache=True, error_model="numpy")
def _guess(code: int, a: np.ndarray, b: np.ndarray, c: np.ndarray, T: float) -> float:
    if code == POLYNOMIAL:
        c1 = a[0]
        if c1 <= 0.0:
            s = 0.0
            for i in range(a.shape[0]):
                s += a[i]
            c1 = max(s, 1e-300)
        return T / c1
    if code == STEEL_WIRE:
        k, d = a[0], a[1]
        return max(T / k, math.sqrt(2.0 * d * T / k))
    n = a.shape[0]
    if T > b[n - 1]:
        return a[n - 1] + (T - b[n - 1]) * (a[n - 1] - a[n - 2]) / (b[n - 1] - b[n - 2])
    i = _seg(b, T)
    return a[i] + (T - b[i]) * (a[i + 1] - a[i]) / (b[i + 1] - b[i])


@njit(cache=True, error_model="numpy")
def _strain(code: int, a: np.ndarray, b: np.ndarray, c: np.ndarray, T: float) -> float:
    """Inverse of the law by the bracketed Newton iteration of AxialLaw.strain."""
    if not T > 0.0:
        return 0.0
    e = max(_guess(code, a, b, c, T), 1e-300)
    lo, hi = 0.0, math.inf
    for _ in range(200):
        f = _law(code, a, b, c, e, 0) - T
        if abs(f) <= 4e-16 * T:
            return e
        if f < 0.0:
            lo = e
        else:
            hi = e
        d = _law(code, a, b, c, e, 1)
        en = e - f / d if d > 0.0 else math.nan
        if not (en > lo and en < hi):
            en = 0.5 * (lo + hi) if hi < math.inf else 2.0 * e
        if abs(en - e) <= 1e-15 * en:
            return en
        e = en
    return e


@njit(cache=True, error_model="numpy")
def law_corrections(
    T0: np.ndarray,
    q: np.ndarray,
    ell: np.ndarray,
    EA: np.ndarray,
    idx: np.ndarray,
    code: int,
    a: np.ndarray,
    b: np.ndarray,
    c: np.ndarray,
    breaks: np.ndarray,
    xg: np.ndarray,
    wg: np.ndarray,
    grades: int,
    dr: np.ndarray,
    jac: np.ndarray,
    energy: np.ndarray,
    want_jac: bool,
) -> None:
    """Add the law's departure from the linear piece to ``dr`` (P, 3), ``jac`` (P, 3, 3)
    and ``energy`` (P,) for the pieces ``idx``: composite Gauss-Legendre quadrature
    (nodes ``xg``, weights ``wg`` on [0, 1]) on graded sub-intervals.

    |T(sigma)| = sqrt(H^2 + V(sigma)^2) with V linear in sigma: the integrand's
    singularities lie at V = +-i H, i.e. at sigma* = sigma_0 +- i r with sigma_0 = -V0/w
    (the point of least tension) and r = H / w. Sub-intervals are graded geometrically
    away from sigma_0 (boundaries sigma_0 +- r_g (2^k - 1), r_g = max(r, l 2^-grades)),
    so that each is at most about a third as long as its distance from sigma*: the
    Gauss-Legendre error then falls like 5.8^(-2 points) per sub-interval, whatever the
    sag. The law's own kinks (``breaks``: tensions of a table's knots) are made
    boundaries too, where |T(sigma)| crosses them. Degenerate sub-intervals are
    skipped."""
    nb = 2 + (grades + 1) + grades + 2 * breaks.shape[0]
    B = np.empty(nb)
    for p in idx:
        tx, ty, tz = T0[p, 0], T0[p, 1], T0[p, 2]
        qx, qy, qz = q[p, 0], q[p, 1], q[p, 2]
        L = ell[p]
        ea = EA[p]
        w = math.sqrt(qx * qx + qy * qy + qz * qz)
        curved = w > 0.0
        inv_w = 1.0 / w if curved else 0.0
        ux, uy, uz = -qx * inv_w, -qy * inv_w, -qz * inv_w
        V0 = tx * ux + ty * uy + tz * uz
        H = math.sqrt(max(tx * tx + ty * ty + tz * tz - V0 * V0, 0.0))
        sig0 = -V0 * inv_w if curved else -1.0
        r = H * inv_w if curved else L
        r = max(r, L * 2.0 ** (-grades))
        k = 0
        B[k] = 0.0
        B[k + 1] = L
        k += 2
        ck = 0.0
        for g in range(grades + 1):
            B[k] = sig0 - r * ck
            k += 1
            if g > 0:
                B[k] = sig0 + r * ck
                k += 1
            ck = 2.0 * ck + 1.0
        for m in range(breaks.shape[0]):
            rad = math.sqrt(max(breaks[m] * breaks[m] - H * H, 0.0))
            B[k] = (rad - V0) * inv_w if curved else -1.0
            B[k + 1] = (-rad - V0) * inv_w if curved else -1.0
            k += 2
        for m in range(nb):
            B[m] = min(max(B[m], 0.0), L)
        B.sort()
        dx = dy = dz = 0.0
        en = 0.0
        j00 = j01 = j02 = j11 = j12 = j22 = 0.0
        iso = 0.0
        for m in range(nb - 1):
            lo, hi = B[m], B[m + 1]
            span = hi - lo
            if span <= 0.0:
                continue
            for n in range(xg.shape[0]):
                s = lo + span * xg[n]
                wt = span * wg[n]
                Tx, Ty, Tz = tx - qx * s, ty - qy * s, tz - qz * s
                t = math.sqrt(Tx * Tx + Ty * Ty + Tz * Tz)
                if not t > 0.0:
                    continue
                e = _strain(code, a, b, c, t)
                g = e - t / ea
                nx, ny, nz = Tx / t, Ty / t, Tz / t
                dx += wt * g * nx
                dy += wt * g * ny
                dz += wt * g * nz
                en += wt * (t * e - _law(code, a, b, c, e, 2) - t * t / (2.0 * ea))
                if want_jac:
                    go = g / t
                    aa = wt * (1.0 / _law(code, a, b, c, e, 1) - 1.0 / ea - go)
                    j00 += aa * nx * nx
                    j01 += aa * nx * ny
                    j02 += aa * nx * nz
                    j11 += aa * ny * ny
                    j12 += aa * ny * nz
                    j22 += aa * nz * nz
                    iso += wt * go
        dr[p, 0] += dx
        dr[p, 1] += dy
        dr[p, 2] += dz
        energy[p] += en
        if want_jac:
            jac[p, 0, 0] += j00 + iso
            jac[p, 1, 1] += j11 + iso
            jac[p, 2, 2] += j22 + iso
            jac[p, 0, 1] += j01
            jac[p, 1, 0] += j01
            jac[p, 0, 2] += j02
            jac[p, 2, 0] += j02
            jac[p, 1, 2] += j12
            jac[p, 2, 1] += j12


@njit(cache=True, error_model="numpy")
def linear_pieces(
    T0: np.ndarray,
    q: np.ndarray,
    ell: np.ndarray,
    EA: np.ndarray,
    dr: np.ndarray,
    jac: np.ndarray,
    energy: np.ndarray,
    want_jac: bool,
) -> None:
    """:func:`.pieces.piece_integrals` for every piece, compiled (the kernel of
    :func:`._fast.line_sums`), into ``dr`` (P, 3), ``jac`` (P, 3, 3), ``energy`` (P,)."""
    d = np.zeros(3)
    J = np.zeros((3, 3))
    for p in range(ell.shape[0]):
        energy[p] = _piece_general(
            T0[p, 0], T0[p, 1], T0[p, 2], q[p, 0], q[p, 1], q[p, 2], ell[p], EA[p], d, J, want_jac
        )
        for k in range(3):
            dr[p, k] = d[k]
            if want_jac:
                for m in range(3):
                    jac[p, k, m] = J[k, m]
