"""Dynamics of a massless tension-only spring line (``line.kind: spring``).

A massless line has no inertia and no drag: its tension follows the end motion at once,

    T(t) = law(|r_B(t) - r_A(t)| - L),

with r_A, r_B the static end positions plus the prescribed end motion
(:class:`cablestudy.dynamics.excitation.EndMotion`, ramp included). The outputs are
those of the time domain, at the excited end (the spring's tension is the same at both
ends): ``tension_max``, ``tension_min``, ``tension_mean`` over the steady window (one
excitation period after the ramp; for a run of fixed ``duration``, the whole run) and
``tension_static``. There is no transient to settle, so the steady window is exact.

The extremes are found on a uniform grid of ``samples`` points of the window, each
refined by golden-section search on its bracket to 1e-12 of the window; the mean is
the trapezoidal rule on the periodic grid (spectrally accurate for a smooth periodic
tension; a slack phase makes it only as smooth as the law at zero).

Break (``line.failure``): when the tension first reaches the limit the spring parts at
that instant, found by bisection to 1e-12 s on the first grid interval where it
crosses; ``break_time`` [s] is recorded and the tension is 0 from then on (the
outputs over the window then include the parted state).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..physics.axial import AxialLaw
from .excitation import EndMotion

_GOLDEN = 0.5 * (math.sqrt(5.0) - 1.0)


@dataclass(frozen=True, kw_only=True)
class SpringDynamicProblem:
    """``law`` [N] of extension [m]; ``length`` [m]; ``position_a``, ``position_b`` [m]
    static end positions (3,); ``motion`` the end motion; ``window`` (t0, t1) [s] the
    steady window; ``samples`` grid points over it; ``break_tension`` [N] or None."""

    law: AxialLaw
    length: float
    position_a: np.ndarray
    position_b: np.ndarray
    motion: EndMotion
    window: tuple[float, float]
    samples: int = 4096
    break_tension: float | None = None


@dataclass(kw_only=True)
class SpringDynamicResult:
    tension_static: float
    tension_max: float
    tension_min: float
    tension_mean: float
    time_max: float
    time_min: float
    break_time: float = math.nan
    status: int = 0
    message: str = ""


def spring_tension_at(problem: SpringDynamicProblem, t: np.ndarray | float) -> np.ndarray:
    """Tension [N] at times ``t`` [s] (array), ignoring a break."""
    t = np.atleast_1d(np.asarray(t, dtype=float))
    out = np.empty(t.shape)
    for i, ti in enumerate(t.ravel()):
        disp = problem.motion.at(float(ti))[0]
        d = (problem.position_b + disp[1]) - (problem.position_a + disp[0])
        out.flat[i] = math.sqrt(float(d @ d))
    return problem.law.tension(out - problem.length)


def _refine(f, a: float, b: float, sign: float, tol: float) -> tuple[float, float]:  # noqa: ANN001
    """Golden-section search for the maximum of sign * f on [a, b]: (t, f(t))."""
    c = b - _GOLDEN * (b - a)
    d = a + _GOLDEN * (b - a)
    fc, fd = sign * f(c), sign * f(d)
    while b - a > tol:
        if fc > fd:
            b, d, fd = d, c, fc
            c = b - _GOLDEN * (b - a)
            fc = sign * f(c)
        else:
            a, c, fc = c, d, fd
            d = a + _GOLDEN * (b - a)
            fd = sign * f(d)
    t = 0.5 * (a + b)
    return t, float(f(t))


def spring_response(problem: SpringDynamicProblem) -> SpringDynamicResult:
    """Tension extremes and mean of a massless spring under end motion (module docs)."""
    t0, t1 = problem.window
    n = max(int(problem.samples), 16)
    grid = np.linspace(t0, t1, n + 1)
    T = spring_tension_at(problem, grid)

    def f(t: float) -> float:
        return float(spring_tension_at(problem, t)[0])

    chord = float(np.linalg.norm(problem.position_b - problem.position_a))
    static = float(problem.law.tension(chord - problem.length))
    break_time = math.nan
    limit = problem.break_tension
    if limit is not None:
        # from t = 0: the line may part during the ramp, before the window
        if static >= limit:
            break_time = 0.0
        else:
            full = np.linspace(0.0, t1, max(n, int(n * t1 / max(t1 - t0, 1e-300))) + 1)
            Tf = spring_tension_at(problem, full)
            over = np.flatnonzero(Tf >= limit)
            if over.size:
                j = int(over[0])
                a, b = float(full[j - 1]), float(full[j])
                while b - a > 1e-12 * max(t1, 1.0):
                    m = 0.5 * (a + b)
                    if f(m) >= limit:
                        b = m
                    else:
                        a = m
                break_time = b
    tol = 1e-12 * max(t1 - t0, 1e-300)
    h = (t1 - t0) / n
    i_max, i_min = int(np.argmax(T)), int(np.argmin(T))
    tmax, Tmax = _refine(f, max(grid[i_max] - h, t0), min(grid[i_max] + h, t1), 1.0, tol)
    tmin, Tmin = _refine(f, max(grid[i_min] - h, t0), min(grid[i_min] + h, t1), -1.0, tol)
    Tmax, Tmin = max(Tmax, float(T[i_max])), min(Tmin, float(T[i_min]))
    mean = float(np.mean(T[:-1]))  # trapezoid on a periodic grid
    if math.isfinite(break_time):
        parted = grid >= break_time
        if break_time <= t0:
            Tmax = Tmin = mean = 0.0
            tmax = tmin = t0
        else:
            Tp = np.where(parted, 0.0, T)
            mean = float(np.mean(Tp[:-1]))
            if break_time < t1:
                Tmin, tmin = 0.0, break_time
            if tmax >= break_time:
                before = ~parted
                k = int(np.argmax(np.where(before, T, -np.inf)))
                Tmax, tmax = max(float(T[k]), float(limit)), break_time  # type: ignore[arg-type]
    return SpringDynamicResult(
        tension_static=static,
        tension_max=Tmax,
        tension_min=Tmin,
        tension_mean=mean,
        time_max=tmax,
        time_min=tmin,
        break_time=break_time,
    )
