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
ellipse converge slowly (as ``exp(-samples k)``; on a line, ``k = 0``, the kink of
``|cos|`` leaves an error falling as ``samples^-3``), and a few square roots a node
instead of a pass over the phases.

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

#: the arithmetic-geometric mean stops once ``c_n < 1e-9 a_n``: the next ``c`` is
#: ``c_n^2 / (4 a_{n+1}) < 3e-19 a``, below rounding in ``K`` and in the sum of ``c^2``
_AGM_STOP = 1e-9


@njit(cache=True, inline="always")
def ellipse_means(k):  # noqa: ANN001, ANN201
    """The period means ``(<r cos^2>, <r sin^2>, <cos^2 / r>, k^2 <sin^2 / r>)`` of
    ``r(psi) = sqrt(cos^2 psi + k^2 sin^2 psi)`` for ``0 <= k <= 1`` (``psi`` uniform).

    With ``m = 1 - k^2``, ``r = sqrt(1 - m sin^2)``, ``K``, ``E`` the complete elliptic
    integrals: ``int_0^{pi/2} sin^2 / r = (K - E) / m = L``, ``cos^2 / r`` gives ``K -
    L``, ``r sin^2`` gives ``J = ((2m - 1) E + (1 - m) K) / (3 m)`` and ``r cos^2``
    gives ``E - J``. ``K = pi / (2 M)`` with ``M`` the arithmetic-geometric mean of 1
    and ``k``, and ``K - E = K sum_n 2^(n-1) c_n^2`` (``c_0^2 = m``, ``c_{n+1} = c_n^2 /
    (4 a_{n+1})``, no difference of near numbers), so ``L = K (1/2 + S)`` with ``S =
    sum_{n>=1} 2^(n-1) c_n^2 / m``, computed as ratios (zero on a circle). ``J`` is
    taken as ``K (3/2 - m + S (1 - 2m)) / 3`` for ``m <= 1/2`` (no cancellation near
    the circle) and by the ``E``, ``K`` form above otherwise (positive terms). Near a
    line ``E = K - m L`` and ``K - L`` lose ``log10(ln(4 / k))`` digits (two at ``k =
    1e-40``); at ``k = 0`` the limits ``(4, 2, 6, 0) / (3 pi)``."""
    if not k > 0.0:  # a line: <|cos|^3>, <|cos| sin^2>, <|cos|>, 0
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
        c2_next = c2 * c2 / (16.0 * a_next * a_next)
        weight *= 2.0
        s += weight * (c2_next / m)
        a, c2 = a_next, c2_next
    big_k = 0.5 * math.pi / (0.5 * (a + b))
    lam = big_k * (0.5 + s)
    e = big_k - m * lam
    if m <= 0.5:
        j = big_k * (1.5 - m + s * (1.0 - 2.0 * m)) / 3.0
    else:
        j = ((2.0 * m - 1.0) * e + (1.0 - m) * big_k) / (3.0 * m)
    return (
        _QUARTER * (e - j),
        _QUARTER * j,
        _QUARTER * big_k * (0.5 - s),
        _QUARTER * k * k * lam,
    )


@njit(cache=True, inline="always")
def principal_turn(a0, a1, a2, b0, b1, b2):  # noqa: ANN001, ANN201, PLR0913
    """``(cos th_0, sin th_0)`` of the phase turn ``th_0 = arg(Z . Z) / 2`` of ``Z = a +
    i b`` (module docstring), from the half-angle formulas of ``cos 2 th_0 = x / rho``,
    ``sin 2 th_0 = y / rho`` (``x = a.a - b.b``, ``y = 2 a.b``, ``rho = |(x, y)|``),
    each square root of a sum of non-negative terms; ``(1, 0)`` for a circle or no
    motion (any turn serves)."""
    x = (a0 * a0 + a1 * a1 + a2 * a2) - (b0 * b0 + b1 * b1 + b2 * b2)
    y = 2.0 * (a0 * b0 + a1 * b1 + a2 * b2)
    rho = math.hypot(x, y)  # not sqrt(x^2 + y^2): x^2 under- or overflows first
    if not rho > 0.0:
        return 1.0, 0.0
    if x >= 0.0:
        c = math.sqrt((rho + x) / (2.0 * rho))
        return c, y / (2.0 * rho * c)
    s = math.copysign(math.sqrt((rho - x) / (2.0 * rho)), y)
    return y / (2.0 * rho * s), s


@njit(cache=True, inline="always")
def _ellipse_terms(coef, a0, a1, a2, b0, b1, b2, f0, f1, f2, g0, g1, g2, t0, t1, t2, acc):  # noqa: ANN001, ANN202, PLR0913
    """Add the means of ``coef |v_e| v_e`` to ``acc`` (3, 3, 3): to ``acc[1]`` (``H``)
    ``<coef |v_e| v_e v^T>`` and to ``acc[2]`` (``J``) the mean Jacobian ``coef (<|v_e|>
    (I - t t^T) + <v_e v_e^T / |v_e|>)``, for ``v_e = a cos - b sin`` (the normal part,
    or ``v`` itself with ``t = 0``) and ``v = f cos - g sin`` the whole velocity. Nothing
    for ``v_e = 0``."""
    c, s = principal_turn(a0, a1, a2, b0, b1, b2)
    x0, x1, x2 = a0 * c + b0 * s, a1 * c + b1 * s, a2 * c + b2 * s
    y0, y1, y2 = b0 * c - a0 * s, b1 * c - a1 * s, b2 * c - a2 * s
    p = math.sqrt(x0 * x0 + x1 * x1 + x2 * x2)
    if not p > 0.0:
        return
    q = math.sqrt(y0 * y0 + y1 * y1 + y2 * y2)
    rc, rs, ic, js = ellipse_means(q / p)
    X = (x0, x1, x2)
    Y = (y0, y1, y2)
    Xf = (f0 * c + g0 * s, f1 * c + g1 * s, f2 * c + g2 * s)
    Yf = (g0 * c - f0 * s, g1 * c - f1 * s, g2 * c - f2 * s)
    t = (t0, t1, t2)
    # the minor axis' unit vector (its term vanishes with q: none for a line)
    inv_q = 1.0 / q if q > 0.0 else 0.0
    e = (y0 * inv_q, y1 * inv_q, y2 * inv_q)
    hx, hy = coef * p * rc, coef * p * rs
    mean_r = coef * p * (rc + rs)
    jx, jy = coef * ic / p, coef * js * p
    for r in range(3):
        for k in range(3):
            acc[1, r, k] += hx * X[r] * Xf[k] + hy * Y[r] * Yf[k]
            eye = 1.0 if r == k else 0.0
            acc[2, r, k] += mean_r * (eye - t[r] * t[k]) + jx * X[r] * X[k] + jy * e[r] * e[k]


@njit(cache=True, inline="always")
def still_water_means(vr, vi, tan, c_n, c_t, c_b, i, acc):  # noqa: ANN001, ANN201, PLR0913
    """The exact period means of node ``i``'s drag fit without current (module
    docstring) into ``acc`` (3, 3, 3): ``G = <w w^T>``, ``H = <f w^T>`` (the mean force
    is zero) and the mean Jacobian ``J = <df/dw>`` (the lean of a system's fit, as
    ``tests/system_drag_reference.mean_drag_jacobian``), for the velocity amplitude
    ``vr[i] + i vi[i]`` [m/s], unit tangent ``tan[i]`` and drag coefficients ``c_n[i]``,
    ``c_t[i]``, ``c_b[i]`` [kg/m] (normal, tangential, isotropic body)."""
    a0, a1, a2 = vr[i, 0], vr[i, 1], vr[i, 2]
    b0, b1, b2 = vi[i, 0], vi[i, 1], vi[i, 2]
    t0, t1, t2 = tan[i, 0], tan[i, 1], tan[i, 2]
    a = (a0, a1, a2)
    b = (b0, b1, b2)
    t = (t0, t1, t2)
    for r in range(3):
        for k in range(3):
            acc[0, r, k] = 0.5 * (a[r] * a[k] + b[r] * b[k])
            acc[1, r, k] = 0.0
            acc[2, r, k] = 0.0
    al = a0 * t0 + a1 * t1 + a2 * t2
    be = b0 * t0 + b1 * t1 + b2 * t2
    if c_n[i] != 0.0:
        _ellipse_terms(
            c_n[i],
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
            acc,
        )
    if c_b[i] != 0.0:
        _ellipse_terms(c_b[i], a0, a1, a2, b0, b1, b2, a0, a1, a2, b0, b1, b2, 0.0, 0.0, 0.0, acc)
    if c_t[i] != 0.0:
        # |x| x of a harmonic of amplitude s_t: first harmonic 8 s_t / (3 pi) x
        s_t = math.sqrt(al * al + be * be)
        gain = c_t[i] * 8.0 * s_t / (3.0 * math.pi)
        along = c_t[i] * 4.0 * s_t / math.pi  # 2 c_T <|w_T|>
        for r in range(3):
            for k in range(3):
                acc[1, r, k] += gain * t[r] * 0.5 * (al * a[k] + be * b[k])
                acc[2, r, k] += along * t[r] * t[k]
