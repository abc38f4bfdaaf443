"""Axial laws of a line behind one interface: tension as a function of strain (or, for a
massless spring, of extension), its derivative, its inverse and the two energies.

Every law is tension-only: a non-positive argument carries no tension. The argument is
called ``strain`` below; for a ``kind: spring`` line the same laws take the extension
[m] instead, and their coefficients then carry [N/m^i] instead of [N].

A law is a small frozen dataclass whose ``name`` is the ``law:`` key of a study's
``axial`` mapping. All methods are pure numpy and vectorised over any array shape:

``tension(e)`` [N]
    T(e), 0 for e <= 0.
``tangent_stiffness(e)`` [N]
    dT/de (the tangent stiffness), 0 for e < 0.
``strain(T)``
    the inverse e(T) for T >= 0 (0 for T <= 0): closed form for the linear law, a
    bracketed Newton iteration (to round-off) otherwise.
``strain_energy(e)`` [N]
    W(e) = int_0^e T de'.
``complementary_energy(T)`` [N]
    Phi(T) = int_0^T e(t) dt = T e(T) - W(e(T)); d Phi / dT = e(T). The static solvers
    minimise a complementary energy whose gradient is the end position.
``first_decrease(max_strain)``
    the smallest strain in (0, max_strain] at which the tension stops increasing (None
    if it increases throughout): the input check of a study.

The laws (aqwa seed, section 5.8.1):

* :class:`LinearLaw` T = k e (today's ``axial_stiffness`` EA).
* :class:`PolynomialLaw` T = A e + B e^2 + C e^3 + D e^4 + E e^5.
* :class:`SteelWireLaw` T = k (e - d (1 - exp(-e / d))), asymptotic stiffness k and
  offset d: see its docstring for why this form.
* :class:`TableLaw` a tabulated monotone curve, interpolated by monotone piecewise cubic
  Hermite polynomials (PCHIP, Fritsch & Carlson 1980) and continued linearly beyond the
  last point.
"""

from __future__ import annotations

import functools
import math
from abc import ABC, abstractmethod
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

#: relative step of the inverse's Newton iteration at which it stops
_INVERSE_RTOL = 1e-15


def _asarray(x: np.ndarray | float) -> np.ndarray:
    return np.asarray(x, dtype=float)


@dataclass(frozen=True)
class AxialLaw(ABC):
    """Base of the axial laws (see the module docstring for the contract).

    Subclasses implement ``_tension``, ``_stiffness`` and ``_strain_energy`` for e > 0;
    the base adds the tension-only clipping, the inverse and the energies.
    """

    name: ClassVar[str] = ""
    #: True when T = reference_stiffness * e exactly (closed forms apply)
    is_linear: ClassVar[bool] = False

    # --------------------------------------------------------------- to implement

    @abstractmethod
    def _tension(self, e: np.ndarray) -> np.ndarray:
        """T(e) [N] for e > 0."""

    @abstractmethod
    def _stiffness(self, e: np.ndarray) -> np.ndarray:
        """dT/de [N] for e > 0."""

    @abstractmethod
    def _strain_energy(self, e: np.ndarray) -> np.ndarray:
        """int_0^e T [N] for e > 0."""

    @property
    @abstractmethod
    def reference_stiffness(self) -> float:
        """A representative stiffness [N] (EA for the linear law, the large-strain
        stiffness otherwise): used for initial guesses and scales only."""

    # ------------------------------------------------------------------- public

    def tension(self, strain: np.ndarray | float) -> np.ndarray:
        """Tension [N] at ``strain`` [-] (0 where strain <= 0)."""
        e = _asarray(strain)
        pos = e > 0.0
        return np.where(pos, self._tension(np.where(pos, e, 0.0)), 0.0)

    def tangent_stiffness(self, strain: np.ndarray | float) -> np.ndarray:
        """Tangent stiffness dT/de [N] at ``strain`` (0 where strain < 0; the right
        derivative at 0)."""
        e = _asarray(strain)
        pos = e >= 0.0
        return np.where(pos, self._stiffness(np.where(pos, e, 0.0)), 0.0)

    def strain_energy(self, strain: np.ndarray | float) -> np.ndarray:
        """W(e) = int_0^e T de' [N] (0 where strain <= 0)."""
        e = _asarray(strain)
        pos = e > 0.0
        return np.where(pos, self._strain_energy(np.where(pos, e, 0.0)), 0.0)

    def _guess(self, T: np.ndarray) -> np.ndarray:
        """Starting strain of the inverse's Newton iteration (T > 0)."""
        return T / self.reference_stiffness

    def strain(self, tension: np.ndarray | float) -> np.ndarray:
        """The inverse: strain [-] at ``tension`` [N] (0 where tension <= 0).

        Newton's method from the law's own guess (:meth:`_guess`), kept inside the
        bracket [lo, hi] of the root that its iterates build (a bisection step, or a
        doubling while no upper bound is known, where Newton would leave it); it stops
        when every step is below 1e-15 of the strain (a few ulps), i.e. at round-off (quadratic
        convergence: a few iterations from the guesses of the laws here). Requires a law
        that increases over the strains reached (checked at input).
        """
        T = _asarray(tension)
        pos = T > 0.0
        Tp = np.where(pos, T, 1.0)
        e = np.maximum(self._guess(Tp), 1e-300)
        lo = np.zeros_like(e)
        hi = np.full_like(e, np.inf)
        for _ in range(200):
            f = self._tension(e) - Tp
            lo = np.where(f < 0.0, e, lo)
            hi = np.where(f > 0.0, e, hi)
            d = self._stiffness(e)
            with np.errstate(divide="ignore", invalid="ignore"):
                en = e - f / d
            outside = ~np.isfinite(en) | (en <= lo) | (en >= hi)
            if np.any(outside):
                fallback = np.where(np.isfinite(hi), 0.5 * (lo + hi), 2.0 * e)
                en = np.where(outside, fallback, en)
            step = np.abs(en - e)
            done = (step <= _INVERSE_RTOL * en) | (np.abs(f) <= 4e-16 * Tp)
            e = np.where(np.abs(f) <= 4e-16 * Tp, e, en)
            if np.all(done):
                break
        return np.where(pos, e, 0.0)

    # ------------------------------------------------------- scalar (ODE right-hand sides)

    def _tension_s(self, e: float) -> float:
        return float(self._tension(np.asarray(e, dtype=float)))

    def _stiffness_s(self, e: float) -> float:
        return float(self._stiffness(np.asarray(e, dtype=float)))

    def strain_scalar(self, tension: float) -> float:
        """:meth:`strain` of one float, in plain Python (no array overhead: the shooting
        solver calls it in its ODE right-hand side)."""
        if not tension > 0.0:
            return 0.0
        k = self.reference_stiffness
        lo, hi = 0.0, max(tension / k, 1e-300)
        for _ in range(200):
            if self._tension_s(hi) >= tension:
                break
            lo, hi = hi, 2.0 * hi
        e = min(tension / k, hi) if tension / k > lo else 0.5 * (lo + hi)
        for _ in range(100):
            f = self._tension_s(e) - tension
            if f < 0.0:
                lo = e
            elif f > 0.0:
                hi = e
            else:
                return e
            d = self._stiffness_s(e)
            en = e - f / d if d > 0.0 else 0.5 * (lo + hi)
            if not lo < en < hi:
                en = 0.5 * (lo + hi)
            if abs(en - e) <= _INVERSE_RTOL * abs(en):
                return en
            e = en
        return e

    def breakpoints(self) -> np.ndarray:
        """Tensions [N] where the law is not analytic (a table's knots): quadratures of
        the law split there. Empty for the analytic laws."""
        return np.zeros(0)

    def complementary_energy(self, tension: np.ndarray | float) -> np.ndarray:
        """Phi(T) = int_0^T e(t) dt = T e(T) - W(e(T)) [N] (0 where T <= 0)."""
        T = _asarray(tension)
        e = self.strain(T)
        return np.where(T > 0.0, T * e - self.strain_energy(e), 0.0)

    def first_decrease(self, max_strain: float) -> float | None:
        """Smallest strain in (0, ``max_strain``] where dT/de <= 0 (the tension stops
        increasing, so it is not invertible and may turn negative), or None.

        Sampled on 4001 points refined by bisection on the sign of dT/de; exact roots
        where a subclass knows them (:class:`PolynomialLaw`).
        """
        e = np.linspace(0.0, max_strain, 4001)[1:]
        bad = np.flatnonzero(self._stiffness(e) <= 0.0)
        if bad.size == 0:
            return None
        i = int(bad[0])
        hi = float(e[i])
        lo = float(e[i - 1]) if i > 0 else 0.0
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            if float(self._stiffness(np.array(mid))) <= 0.0:
                hi = mid
            else:
                lo = mid
        return hi


@dataclass(frozen=True)
class LinearLaw(AxialLaw):
    """Hooke's law T = k e, tension-only (aqwa seed 5.8.1.1; dodaran-park eq. 5).

    Parameters
    ----------
    stiffness : float  [N] (EA, in strain) or [N/m] (a spring, in extension)
    """

    stiffness: float
    name: ClassVar[str] = "linear"
    is_linear: ClassVar[bool] = True

    def _tension(self, e: np.ndarray) -> np.ndarray:
        return self.stiffness * e

    def _stiffness(self, e: np.ndarray) -> np.ndarray:
        return np.full(np.shape(e), float(self.stiffness))

    def _strain_energy(self, e: np.ndarray) -> np.ndarray:
        return 0.5 * self.stiffness * e * e

    @property
    def reference_stiffness(self) -> float:
        return float(self.stiffness)

    def strain(self, tension: np.ndarray | float) -> np.ndarray:
        T = _asarray(tension)
        return np.where(T > 0.0, T / self.stiffness, 0.0)

    def strain_scalar(self, tension: float) -> float:
        return tension / self.stiffness if tension > 0.0 else 0.0

    def first_decrease(self, max_strain: float) -> float | None:
        return None


@dataclass(frozen=True)
class PolynomialLaw(AxialLaw):
    """T = c1 e + c2 e^2 + ... + c5 e^5 (aqwa seed 5.8.1.2: coefficients A..E).

    Parameters
    ----------
    coefficients : tuple of float
        c1 [N], c2 [N], ... in strain (a catenary segment), or c1 [N/m], c2 [N/m^2], ...
        in extension [m] (a spring). One to five of them; no constant term (the law
        passes through zero).
    """

    coefficients: tuple[float, ...]
    name: ClassVar[str] = "polynomial"

    def _tension(self, e: np.ndarray) -> np.ndarray:
        out = np.zeros(np.shape(e))
        for c in reversed(self.coefficients):  # Horner: ((c5 e + c4) e + ...) e
            out = (out + c) * e
        return out

    def _stiffness(self, e: np.ndarray) -> np.ndarray:
        out = np.zeros(np.shape(e))
        n = len(self.coefficients)
        for i in range(n, 0, -1):
            out = out * e + i * self.coefficients[i - 1]
        return out

    def _strain_energy(self, e: np.ndarray) -> np.ndarray:
        out = np.zeros(np.shape(e))
        n = len(self.coefficients)
        for i in range(n, 0, -1):
            out = (out + self.coefficients[i - 1] / (i + 1)) * e
        return out * e

    @property
    def reference_stiffness(self) -> float:
        """c1 when positive, else the secant stiffness T(1)/1 of a unit argument."""
        c1 = float(self.coefficients[0])
        return c1 if c1 > 0.0 else max(float(sum(self.coefficients)), 1e-300)

    def _tension_s(self, e: float) -> float:
        out = 0.0
        for c in reversed(self.coefficients):
            out = (out + c) * e
        return out

    def _stiffness_s(self, e: float) -> float:
        out = 0.0
        for i in range(len(self.coefficients), 0, -1):
            out = out * e + i * self.coefficients[i - 1]
        return out

    @property
    def is_linear_only(self) -> bool:
        """Only c1 is nonzero: the law is T = c1 e (used as the linear law)."""
        return all(c == 0.0 for c in self.coefficients[1:])

    def first_decrease(self, max_strain: float) -> float | None:
        """Exact: the smallest real root in [0, max_strain] of dT/de (or 0 when c1 < 0,
        or where dT/de touches zero), from the companion-matrix roots refined by
        bisection."""
        c = self.coefficients
        if c[0] < 0.0:
            return 0.0
        deriv = [i * c[i - 1] for i in range(1, len(c) + 1)]  # d0 + d1 e + ...
        if all(d == 0.0 for d in deriv[1:]):
            return None if deriv[0] > 0.0 else 0.0
        if deriv[0] == 0.0:
            # zero initial stiffness: the lowest nonzero term must rise from 0
            lead = next(d for d in deriv[1:] if d != 0.0)
            if lead < 0.0:
                return 0.0
        roots = np.roots(np.trim_zeros(deriv[::-1], "f"))
        real = sorted(
            float(r.real)
            for r in roots
            if abs(r.imag) <= 1e-9 * max(1.0, abs(r)) and 0.0 < r.real <= max_strain
        )
        return real[0] if real else None


def _x_plus_expm1(x: np.ndarray) -> np.ndarray:
    """x + exp(-x) - 1 (>= 0) without cancellation: its Taylor series x^2/2 - x^3/6 + ...
    to x^14 (truncation below 1e-17 relative) for x < 0.5, the plain form above."""
    x = np.asarray(x, dtype=float)
    small = x < 0.5
    xs = np.where(small, x, 0.0)
    acc = np.zeros_like(xs)
    for m in range(12, -1, -1):  # x^2 sum_m (-x)^m / (m + 2)!
        acc = acc * (-xs) + 1.0 / math.factorial(m + 2)
    acc = acc * xs * xs
    return np.where(small, acc, x + np.expm1(-np.where(small, 1.0, x)))


@dataclass(frozen=True)
class SteelWireLaw(AxialLaw):
    """Steel wire: T = k (e - d (1 - exp(-e / d))), asymptotic stiffness k, offset d.

    The aqwa seed (5.8.1.3) defines the law by its asymptote T -> k (e - d) "at large
    values of extension, [where a factor] tends to unity"; its equation itself did not
    survive the conversion to text, and we could not check the Aqwa manual itself. We
    read the factor that tends to unity as 1 - exp(-e/d), and justify the form on its
    own:

    * T(0) = 0 and dT/de(0) = 0: a new wire rope first straightens and beds its strands
      (the "constructional stretch"), so its tangent stiffness grows from ~0;
    * dT/de = k (1 - exp(-e/d)) increases monotonically to k (convex, invertible for
      every e > 0: no input can make it non-monotone);
    * T - k (e - d) = k d exp(-e/d): the asymptote of the seed is reached exponentially,
      within 1 % of k d once e > 4.6 d;
    * it is smooth (C-infinity), so the quadratures of the statics converge
      exponentially.

    The other reading of the seed's sentence, T = k (e - d tanh(e / d)), has the same
    asymptote and zero initial slope but starts softer (T ~ k e^3 / 3 d^2); a hyperbola
    through zero with that asymptote starts with a finite slope, which the "offset"
    (a length taken up before the wire carries load) does not describe.

    Parameters
    ----------
    stiffness : float  [N] in strain ([N/m] in extension for a spring)
    offset : float  [-] in strain ([m] in extension)
    """

    stiffness: float
    offset: float
    name: ClassVar[str] = "steel_wire"

    def _tension(self, e: np.ndarray) -> np.ndarray:
        d = self.offset
        return self.stiffness * d * _x_plus_expm1(e / d)

    def _stiffness(self, e: np.ndarray) -> np.ndarray:
        return -self.stiffness * np.expm1(-e / self.offset)

    def _tension_s(self, e: float) -> float:
        return self.stiffness * (e + self.offset * math.expm1(-e / self.offset))

    def _stiffness_s(self, e: float) -> float:
        return -self.stiffness * math.expm1(-e / self.offset)

    def _strain_energy(self, e: np.ndarray) -> np.ndarray:
        # int_0^e k (x - d + d exp(-x/d)) dx = k (e^2/2 - d e - d^2 (exp(-e/d) - 1))
        #                                    = k (e^2/2 - d^2 (exp(-x) - 1 + x)), x = e/d
        d = self.offset
        x = e / d
        small = x < 1e-3
        # exp(-x) - 1 + x without cancellation for small x: x^2/2 - x^3/6 + x^4/24
        series = x * x * (0.5 - x * (1.0 / 6.0 - x / 24.0))
        g = np.where(small, series, np.expm1(-np.where(small, 1.0, x)) + x)
        return self.stiffness * (0.5 * e * e - d * d * g)

    @property
    def reference_stiffness(self) -> float:
        return float(self.stiffness)

    def _guess(self, T: np.ndarray) -> np.ndarray:
        """The larger of two lower bounds of the root, T/k (from T <= k e) and
        sqrt(2 d T / k) (from T <= k e^2 / 2d): the law is convex, so Newton's first step
        lands right of the root and the rest converge monotonically."""
        k, d = self.stiffness, self.offset
        return np.maximum(T / k, np.sqrt(2.0 * d * T / k))

    def first_decrease(self, max_strain: float) -> float | None:
        return None


def _pchip_slopes(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Fritsch-Carlson (1980) slopes, as in scipy's PchipInterpolator inside (weighted
    harmonic mean of the neighbouring secants, 0 at a local extremum) and the secant of
    the end interval at both ends (C1 with the linear continuation beyond the table)."""
    h = np.diff(x)
    delta = np.diff(y) / h
    m = np.empty_like(y)
    m[0], m[-1] = delta[0], delta[-1]
    if len(x) > 2:
        w1 = 2.0 * h[1:] + h[:-1]
        w2 = h[1:] + 2.0 * h[:-1]
        d0, d1 = delta[:-1], delta[1:]
        same = (d0 * d1) > 0.0
        with np.errstate(divide="ignore", invalid="ignore"):
            hm = (w1 + w2) / (w1 / d0 + w2 / d1)
        m[1:-1] = np.where(same, hm, 0.0)
    return m


@dataclass(frozen=True)
class TableLaw(AxialLaw):
    """A tabulated tension-strain curve through (0, 0), interpolated by monotone cubic
    Hermite polynomials (PCHIP: C1, no overshoot, monotone where the data are) and
    continued beyond the last point along the tangent of the last interval's secant
    (C1 there too).

    Parameters
    ----------
    strain : tuple of float  [-] (or [m] for a spring), strictly increasing, from 0
    tension : tuple of float  [N], from 0
    """

    strain_points: tuple[float, ...]
    tension_points: tuple[float, ...]
    name: ClassVar[str] = "table"

    def _knots(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        x = np.asarray(self.strain_points, dtype=float)
        y = np.asarray(self.tension_points, dtype=float)
        return x, y, _pchip_slopes(x, y)

    def _hermite(self, e: np.ndarray, what: int) -> np.ndarray:
        """what 0: value, 1: derivative, 2: integral from 0."""
        x, y, m = self._knots()
        e = np.asarray(e, dtype=float)
        n = len(x)
        i = np.clip(np.searchsorted(x, e, side="right") - 1, 0, n - 2)
        h = x[i + 1] - x[i]
        t = (e - x[i]) / h
        y0, y1, m0, m1 = y[i], y[i + 1], m[i] * h, m[i + 1] * h
        beyond = e > x[-1]
        slope_end = m[-1]
        if what == 0:
            h00 = (1 + 2 * t) * (1 - t) ** 2
            h10 = t * (1 - t) ** 2
            h01 = t * t * (3 - 2 * t)
            h11 = t * t * (t - 1)
            val = h00 * y0 + h10 * m0 + h01 * y1 + h11 * m1
            return np.where(beyond, y[-1] + slope_end * (e - x[-1]), val)
        if what == 1:
            d00 = 6 * t * t - 6 * t
            d10 = 3 * t * t - 4 * t + 1
            d01 = -d00
            d11 = 3 * t * t - 2 * t
            val = (d00 * y0 + d10 * m0 + d01 * y1 + d11 * m1) / h
            return np.where(beyond, slope_end, val)
        # integrals of the Hermite basis from 0 to t, times h
        i00 = t - t**3 + 0.5 * t**4
        i10 = 0.5 * t * t - 2.0 * t**3 / 3.0 + 0.25 * t**4
        i01 = t**3 - 0.5 * t**4
        i11 = 0.25 * t**4 - t**3 / 3.0
        part = h * (i00 * y0 + i10 * m0 + i01 * y1 + i11 * m1)
        hk = np.diff(x)
        full = hk * (0.5 * (y[:-1] + y[1:]) + (m[:-1] - m[1:]) * hk / 12.0)
        cum = np.concatenate(([0.0], np.cumsum(full)))
        inside = cum[np.minimum(i, n - 1)] + part
        past = e - x[-1]
        total = cum[-1] + y[-1] * past + 0.5 * slope_end * past * past
        return np.where(beyond, total, inside)

    def _tension(self, e: np.ndarray) -> np.ndarray:
        return self._hermite(e, 0)

    def _stiffness(self, e: np.ndarray) -> np.ndarray:
        return self._hermite(e, 1)

    def _strain_energy(self, e: np.ndarray) -> np.ndarray:
        return self._hermite(e, 2)

    @property
    def reference_stiffness(self) -> float:
        return float(self.tension_points[-1] / self.strain_points[-1])

    def breakpoints(self) -> np.ndarray:
        return np.asarray(self.tension_points[1:], dtype=float)

    def _guess(self, T: np.ndarray) -> np.ndarray:
        """Piecewise-linear inverse through the knots (and the linear continuation)."""
        x = np.asarray(self.strain_points, dtype=float)
        y = np.asarray(self.tension_points, dtype=float)
        slope = (y[-1] - y[-2]) / (x[-1] - x[-2])
        return np.where(T > y[-1], x[-1] + (T - y[-1]) / slope, np.interp(T, y, x))

    def first_decrease(self, max_strain: float) -> float | None:
        """With strictly increasing tensions PCHIP is monotone, and the slopes are
        positive except where the data flatten: the first knot where the tension does
        not increase, or the sampled check of the base class."""
        x, y, _ = self._knots()
        flat = np.flatnonzero(np.diff(y) <= 0.0)
        if flat.size and x[flat[0]] <= max_strain:
            return float(x[flat[0]])
        return super().first_decrease(max_strain)


def is_effectively_linear(law: AxialLaw | None) -> bool:
    """True for no law (today's EA), the linear law and a polynomial with only c1."""
    if law is None or law.is_linear:
        return True
    return isinstance(law, PolynomialLaw) and law.is_linear_only


@functools.lru_cache(maxsize=64)
def gauss_legendre(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Nodes in [0, 1] and weights (summing to 1) of the n-point Gauss-Legendre rule:
    exact for polynomials of degree 2n - 1 [-]. Cached: do not modify the arrays."""
    x, w = np.polynomial.legendre.leggauss(n)
    x, w = 0.5 * (x + 1.0), 0.5 * w
    x.flags.writeable = False
    w.flags.writeable = False
    return x, w


__all__ = [
    "AxialLaw",
    "LinearLaw",
    "PolynomialLaw",
    "SteelWireLaw",
    "TableLaw",
    "gauss_legendre",
    "is_effectively_linear",
]
