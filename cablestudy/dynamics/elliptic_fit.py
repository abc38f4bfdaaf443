"""The period means of the drag fit of a node in still water, in closed form: the limit
of the phase sums of the describing-function fit (:mod:`.frequency`; the sums of
:func:`.harmonic_kernel.drag_fit_samples` and :func:`.system_fd_fit.fit_node`) as the
phases grow, for a node without current, whatever the direction of its motion.

The relative velocity of a node moving with the complex velocity amplitude ``a + i b``
is ``w(th) = -v(th)``, ``v = a cos(th) - b sin(th)``; in still water the drag ``f(w) =
c_N |w_N| w_N + c_T |w_T| w_T t + c_B |w| w`` (normal, tangential, lumped body) is odd
in ``w``, so its period mean is zero and the means of the fit, ``G = <w w^T>``, ``H =
<f w^T>`` and the mean Jacobian ``J = <df/dw>`` (the system's lean), are those of
``v``. Each term is a function of one harmonic vector:

* ``v_N = (I - t t^T) v`` traces an ellipse in the normal plane. Turning the phase by
  ``th_0 = arg(Z . Z) / 2`` (``Z = A + i B``, ``A``, ``B`` the normal parts of ``a``,
  ``b``; the bilinear, not Hermitian, product) makes ``Z e^{-i th_0} = X + i Y`` with
  ``X . Y = 0`` and ``p = |X| >= q = |Y|``: ``v_N = X cos(psi) - Y sin(psi)`` and
  ``|v_N| = p r(psi)``, ``r = sqrt(cos^2 + k^2 sin^2)``, ``k = q / p``. By the
  symmetry ``psi -> -psi`` the means of ``r cos sin`` vanish, so with the same turn
  applied to ``a`` and ``b`` (``v = X_f cos(psi) - Y_f sin(psi)``)

      <|v_N| v_N v^T> = p (<r cos^2> X X_f^T + <r sin^2> Y Y_f^T),
      <|v_N|> = p <r>,   <v_N v_N^T / |v_N|> = <cos^2 / r> X X^T / p
                                             + k^2 <sin^2 / r> p e_2 e_2^T,

  (``e_2 = Y / q``), complete elliptic integrals of parameter ``m = 1 - k^2``
  (:func:`ellipse_means`).
* ``v_T = t . v`` is a scalar harmonic of amplitude ``s_T``; ``|x| x`` of a harmonic
  has the first harmonic ``8 s_T / (3 pi) x``, so ``<|v_T| v_T v^T> = 8 s_T / (3 pi)
  t^T G`` and ``<|v_T|> = 2 s_T / pi``.
* ``v`` itself (the body's isotropic drag) is the same ellipse with ``t = 0``.

``G = (a a^T + b b^T) / 2`` exactly. The cross terms (``<|v_N| v_N v_T>``) are in
``<|v_N| v_N v^T>`` through ``X_f``, ``Y_f``. Exact, where the phase sums of a thin
ellipse converge slowly (as ``exp(-samples atanh(k))``; on a line, ``k = 0``, and for
the tangential drag the kinks of ``|cos|`` leave errors falling as ``samples^-3`` in
``H``, ``samples^-2`` in ``J``), and cheaper: about 110 ns a node in the system's fit
(square roots and divisions: the arithmetic-geometric mean's three to five steps, the
axes), where 16 phases (half a period) took about 170 ns (:func:`_ellipse_terms` needs
no turn; the callers pass scalars, since an inlined function's array arguments cost
reference counts).

Limits: a line (``q = 0``; ``K(m)`` diverges but ``k^2 <sin^2 / r>`` -> 0, the phase
sums' value: the normal Jacobian of a node swinging along ``e_1`` is ``<|v_N|>`` across
and ``2 <|v_N|>`` along, as the sums that skip ``|v_N| = 0`` give), a circle (``m =
0``: the series of the arithmetic-geometric mean ends at once), a node without normal
(or any) motion (its terms are zero, as in the sums).

Pure: floats in, floats out; compiled with numba and inlined into the callers.
"""

from __future__ import annotations

import math

from numba import njit

#: ``2 / pi``: the mean over a period of a function of ``psi`` with the symmetries of
#: ``r(psi)`` is ``2 / pi`` times its integral over a quarter period
_QUARTER = 2.0 / math.pi

#: the arithmetic-geometric mean stops once ``c_n < 1e-4 a_n``: then ``c_{n+1} =
#: c_n^2 / (4 a_{n+1}) < 3e-9 a`` is added to the sum of ``c^2`` and ``M = a_{n+1}``,
#: whose error ``a_{n+1} - M < c_{n+1}^2 / (4 a) < 3e-18 a`` is below rounding, as is
#: the rest of the sum (``c_{n+2}^2``)
_AGM_STOP = 1e-4


#: no contribution: the 15 values of :func:`_ellipse_terms` of a drag that is absent
_NONE = (0.0,) * 15


@njit(cache=True, inline="always")
def ellipse_means(k):  # noqa: ANN001, ANN201
    """The period means ``(<r cos^2>, <r sin^2>, <cos^2 / r>, <sin^2 / r>)`` of ``r(psi)
    = sqrt(cos^2 psi + k^2 sin^2 psi)`` for ``0 <= k <= 1`` (``psi`` uniform).

    With ``m = 1 - k^2``, ``r = sqrt(1 - m sin^2)``, ``K``, ``E`` the complete elliptic
    integrals: ``int_0^{pi/2} sin^2 / r = (K - E) / m = L``, ``cos^2 / r`` gives ``K -
    L``, ``r sin^2`` gives ``J = ((2m - 1) E + (1 - m) K) / (3 m)`` and ``r cos^2``
    gives ``E - J``. ``K = pi / (2 M)`` with ``M`` the arithmetic-geometric mean of 1
    and ``k``, and ``K - E = K sum_n 2^(n-1) c_n^2`` (``c_0^2 = m``, ``c_{n+1} = c_n^2 /
    (4 a_{n+1})``, no difference of near numbers), so ``L = K (1/2 + S)`` with ``S =
    sum_{n>=1} 2^(n-1) c_n^2 / m`` (zero on a circle). ``J`` is taken as ``K (3/2 - m +
    S (1 - 2m)) / 3`` for ``m <= 1/2`` (no cancellation near the circle) and by the
    ``E``, ``K`` form above otherwise (positive terms). Near a line ``E = K - m L`` and
    ``K - L`` lose ``log10(ln(4 / k))`` digits (two at ``k = 1e-40``). At ``k = 0`` the
    limits ``(4 / 3, 2 / 3, 2, 0) / pi``: ``<sin^2 / r>`` diverges as ``ln(4 / k)``,
    but its weight (``q^2``) vanishes faster, and 0 stands for their product."""
    if not k > 0.0:  # a line: <|cos|^3>, <|cos| sin^2>, <|cos|>, and see above
        return 4.0 / (3.0 * math.pi), 2.0 / (3.0 * math.pi), 2.0 / math.pi, 0.0
    if k > 1.0:
        k = 1.0
    m = (1.0 - k) * (1.0 + k)
    a, b = 1.0, k
    c2 = m  # c_n^2
    s = 0.0
    weight = 0.5
    for _ in range(64):
        if not c2 > (_AGM_STOP * a) ** 2:
            break
        a_next = 0.5 * (a + b)
        b = math.sqrt(a * b)
        c2 = c2 * c2 / (16.0 * a_next * a_next)
        weight *= 2.0
        s += weight * (c2 / m)
        a = a_next
    a_next = 0.5 * (a + b)  # M, and the last term of the sum (module constant)
    if m > 0.0:
        s += 2.0 * weight * (c2 * c2 / (16.0 * a_next * a_next) / m)
    big_k = 0.5 * math.pi / a_next
    lam = big_k * (0.5 + s)
    e = big_k - m * lam
    if m <= 0.5:
        j = big_k * (1.5 - m + s * (1.0 - 2.0 * m)) / 3.0
    else:
        j = ((2.0 * m - 1.0) * e + (1.0 - m) * big_k) / (3.0 * m)
    return _QUARTER * (e - j), _QUARTER * j, _QUARTER * big_k * (0.5 - s), _QUARTER * lam


@njit(cache=True, inline="always")
def _ellipse_terms(coef, a0, a1, a2, b0, b1, b2, f0, f1, f2, g0, g1, g2, t0, t1, t2):  # noqa: ANN001, ANN202, PLR0913
    """The means of ``coef |v_e| v_e`` for ``v_e = A cos - B sin`` (the normal part, or
    ``v`` itself with ``t = 0``) and ``v = a cos - b sin`` the whole velocity (``A``:
    ``a0 .. a2``, ``B``: ``b0 .. b2``, ``a``: ``f0 .. f2``, ``b``: ``g0 .. g2``): the 9
    entries of ``<coef |v_e| v_e v^T>`` row by row, then the entries 00, 01, 02, 11,
    12, 22 of the mean Jacobian ``coef (<|v_e|> (I - t t^T) + <v_e v_e^T / |v_e|>)``;
    zeros for ``v_e = 0``.

    The principal axes without the turn itself: with ``x = A.A - B.B``, ``y = 2 A.B``,
    ``rho = |(x, y)|`` (``cos 2 th_0 = x / rho``, ``sin 2 th_0 = y / rho``), ``p^2 + q^2 =
    A.A + B.B``, ``p^2 - q^2 = rho`` and ``p q = |A x B|``, so ``k = q / p = 2 |A x B| /
    (A.A + B.B + rho)``, and ``X X_f^T = c^2 A a^T + s^2 B b^T + c s (A b^T + B a^T)``,
    ``Y Y_f^T`` the same with ``c^2``, ``s^2`` exchanged and ``-c s`` (``c^2 = (1 + cos
    2 th_0) / 2``, ...): one square root and no turn before the mean. Everything is
    scaled by ``A.A + B.B`` first (no square of a square: no under- or overflow where
    the drag itself has none). Scalars throughout (this runs once a node)."""
    aa = a0 * a0 + a1 * a1 + a2 * a2
    bb = b0 * b0 + b1 * b1 + b2 * b2
    s2 = aa + bb
    if not s2 > 0.0:
        return _NONE
    inv = 1.0 / s2
    x = (aa - bb) * inv
    y = 2.0 * (a0 * b0 + a1 * b1 + a2 * b2) * inv
    z0 = (a1 * b2 - a2 * b1) * inv
    z1 = (a2 * b0 - a0 * b2) * inv
    z2 = (a0 * b1 - a1 * b0) * inv
    rho = math.sqrt(x * x + y * y)  # (p^2 - q^2) / (p^2 + q^2), in [0, 1]
    area = math.sqrt(z0 * z0 + z1 * z1 + z2 * z2)  # p q / (p^2 + q^2)
    rc, rs, ic, lm = ellipse_means(min(2.0 * area / (1.0 + rho), 1.0))
    p = math.sqrt(0.5 * s2 * (1.0 + rho))
    if rho > 0.0:
        cc = 0.5 * (1.0 + x / rho)
        ss = 0.5 * (1.0 - x / rho)
        cs = 0.5 * y / rho
    else:  # a circle: any turn
        cc, ss, cs = 1.0, 0.0, 0.0
    # H: coef p (rc X X_f^T + rs Y Y_f^T) = ha A a^T + hb B b^T + hc (A b^T + B a^T)
    hp = coef * p
    ha = hp * (rc * cc + rs * ss)
    hb = hp * (rc * ss + rs * cc)
    hc = hp * (rc - rs) * cs
    # J: coef (p (rc + rs) P + (ic X X^T + lm Y Y^T) / p), the same way
    mean_r = hp * (rc + rs)
    jp = coef / p
    ja = jp * (ic * cc + lm * ss)
    jb = jp * (ic * ss + lm * cc)
    jc = jp * (ic - lm) * cs
    return (
        ha * a0 * f0 + hb * b0 * g0 + hc * (a0 * g0 + b0 * f0),
        ha * a0 * f1 + hb * b0 * g1 + hc * (a0 * g1 + b0 * f1),
        ha * a0 * f2 + hb * b0 * g2 + hc * (a0 * g2 + b0 * f2),
        ha * a1 * f0 + hb * b1 * g0 + hc * (a1 * g0 + b1 * f0),
        ha * a1 * f1 + hb * b1 * g1 + hc * (a1 * g1 + b1 * f1),
        ha * a1 * f2 + hb * b1 * g2 + hc * (a1 * g2 + b1 * f2),
        ha * a2 * f0 + hb * b2 * g0 + hc * (a2 * g0 + b2 * f0),
        ha * a2 * f1 + hb * b2 * g1 + hc * (a2 * g1 + b2 * f1),
        ha * a2 * f2 + hb * b2 * g2 + hc * (a2 * g2 + b2 * f2),
        mean_r * (1.0 - t0 * t0) + ja * a0 * a0 + jb * b0 * b0 + jc * (a0 * b0 + b0 * a0),
        ja * a0 * a1 + jb * b0 * b1 + jc * (a0 * b1 + b0 * a1) - mean_r * t0 * t1,
        ja * a0 * a2 + jb * b0 * b2 + jc * (a0 * b2 + b0 * a2) - mean_r * t0 * t2,
        mean_r * (1.0 - t1 * t1) + ja * a1 * a1 + jb * b1 * b1 + jc * (a1 * b1 + b1 * a1),
        ja * a1 * a2 + jb * b1 * b2 + jc * (a1 * b2 + b1 * a2) - mean_r * t1 * t2,
        mean_r * (1.0 - t2 * t2) + ja * a2 * a2 + jb * b2 * b2 + jc * (a2 * b2 + b2 * a2),
    )


@njit(cache=True, inline="always")
def still_water_means(a0, a1, a2, b0, b1, b2, t0, t1, t2, cn, ct, cb):  # noqa: ANN001, ANN201, PLR0913
    """The exact period means of a node's drag fit without current (module docstring):
    ``G = <w w^T>`` (entries 00, 01, 02, 11, 12, 22), ``H = <f w^T>`` (row by row; the
    mean force is zero) and the mean Jacobian ``J = <df/dw>`` (as ``G``; the lean of a
    system's fit, as ``tests/system_drag_reference.mean_drag_jacobian``), for the
    velocity amplitude ``a + i b`` [m/s], unit tangent ``t`` and drag coefficients
    ``cn``, ``ct``, ``cb`` [kg/m] (normal, tangential, isotropic body): the sums of
    :func:`.harmonic_kernel.fit_from_sums` over one phase. Scalars in (an inlined
    function's array arguments cost reference counts, as much as the means)."""
    al = a0 * t0 + a1 * t1 + a2 * t2
    be = b0 * t0 + b1 * t1 + b2 * t2
    n = _NONE
    if cn != 0.0:
        n = _ellipse_terms(
            cn,
            a0 - al * t0,
            a1 - al * t1,
            a2 - al * t2,
            b0 - be * t0,
            b1 - be * t1,
            b2 - be * t2,
            a0,
            a1,
            a2,
            b0,
            b1,
            b2,
            t0,
            t1,
            t2,
        )
    bd = _NONE
    if cb != 0.0:
        bd = _ellipse_terms(cb, a0, a1, a2, b0, b1, b2, a0, a1, a2, b0, b1, b2, 0.0, 0.0, 0.0)
    # |x| x of a harmonic of amplitude s_t: first harmonic 8 s_t / (3 pi) x, so
    # <|w_T| w_T w^T> = 8 s_t / (3 pi) t^T G; and 2 c_T <|w_T|> = 4 c_T s_t / pi
    s_t = math.sqrt(al * al + be * be)
    gain = ct * (4.0 / (3.0 * math.pi)) * s_t
    along = ct * (4.0 / math.pi) * s_t
    u0, u1, u2 = gain * (al * a0 + be * b0), gain * (al * a1 + be * b1), gain * (al * a2 + be * b2)
    g = (
        0.5 * (a0 * a0 + b0 * b0),
        0.5 * (a0 * a1 + b0 * b1),
        0.5 * (a0 * a2 + b0 * b2),
        0.5 * (a1 * a1 + b1 * b1),
        0.5 * (a1 * a2 + b1 * b2),
        0.5 * (a2 * a2 + b2 * b2),
    )
    h = (
        n[0] + bd[0] + t0 * u0,
        n[1] + bd[1] + t0 * u1,
        n[2] + bd[2] + t0 * u2,
        n[3] + bd[3] + t1 * u0,
        n[4] + bd[4] + t1 * u1,
        n[5] + bd[5] + t1 * u2,
        n[6] + bd[6] + t2 * u0,
        n[7] + bd[7] + t2 * u1,
        n[8] + bd[8] + t2 * u2,
    )
    j = (
        n[9] + bd[9] + along * t0 * t0,
        n[10] + bd[10] + along * t0 * t1,
        n[11] + bd[11] + along * t0 * t2,
        n[12] + bd[12] + along * t1 * t1,
        n[13] + bd[13] + along * t1 * t2,
        n[14] + bd[14] + along * t2 * t2,
    )
    return g, h, j
