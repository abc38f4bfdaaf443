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
the trapezoidal rule on the grid (spectrally accurate for a smooth periodic tension,
O(h^2) for a window that is not a period; a slack phase makes it only as smooth as the
law at zero).

Failure (``line.failure``): when the tension first reaches the limit the spring parts
at that instant, found by bisection to 1e-12 s on the first grid interval where it
crosses, or at ``failure.time`` if that comes first; ``break_time`` [s] is recorded
(NaN: it did not part) and the tension is 0 from then on (the outputs over the window
then include the parted state).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..physics.axial import AxialLaw
from ..statics.spring import wrap_angles
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
    #: time at which the line fails whatever its tension [s] (None: never)
    break_at: float | None = None
    #: fixed pulleys the line passes over [m] (m, 3) and their friction factors (m,)
    pulleys: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))
    friction: np.ndarray = field(default_factory=lambda: np.zeros(0))
    #: end whose tension the outputs give (0: A, 1: B; they differ only with friction)
    excited_end: int = 1
    #: winch: rate of change of the unstretched length [m/s] from ``winch_start`` to
    #: ``winch_stop`` [s] (inf: never stops)
    winch_speed: float = 0.0
    winch_start: float = 0.0
    winch_stop: float = math.inf

    def unstretched(self, t: np.ndarray) -> np.ndarray:
        """Unstretched length [m] at times ``t`` [s] (the winch's change included)."""
        t = np.asarray(t, dtype=float)
        run = np.clip(np.minimum(t, self.winch_stop) - self.winch_start, 0.0, None)
        return self.length + self.winch_speed * run

    @property
    def sticks(self) -> bool:
        """Whether some pulley has friction (the state then depends on the history)."""
        return bool(np.any(self.friction > 1.0))


@dataclass(kw_only=True)
class SpringDynamicResult:
    tension_static: float
    tension_max: float
    tension_min: float
    tension_mean: float
    break_time: float = math.nan
    status: int = 0
    message: str = ""


def end_displacements(motion: EndMotion, t: np.ndarray) -> np.ndarray:
    """Displacements [m] of ends A and B at times ``t`` [s], shape (n, 2, 3): the
    displacement of :meth:`EndMotion.at` (harmonics and ramp vectorised over ``t``;
    time tables point by point; the ramp on all but the non-periodic tables)."""
    t = np.asarray(t, dtype=float).ravel()
    out = np.zeros((t.size, 2, 3))
    if motion.harmonic_amplitude.size:
        om = 2.0 * math.pi * motion.harmonic_frequency
        s = np.sin(np.outer(t, om) + motion.harmonic_phase)  # (n, k)
        for k in range(motion.harmonic_amplitude.size):
            e = int(motion.harmonic_end[k])
            out[:, e, :] += (motion.harmonic_amplitude[k] * s[:, k])[:, None] * (
                motion.harmonic_direction[k]
            )
    for periodic in (True, False):
        for tab in motion.tables:
            if tab.periodic != periodic:
                continue
            u = np.array([tab.evaluate(float(ti))[0] for ti in t])
            out[:, tab.end, :] += u[:, None] * tab.direction
        tr = motion.ramp_time
        if periodic and tr > 0.0:
            # the ramp starts the repeating motions; a non-periodic table, added after
            # it, moves as written (as :func:`.excitation.motion_at`)
            ramp = np.where(
                t >= tr, 1.0, np.where(t <= 0.0, 0.0, 0.5 * (1.0 - np.cos(math.pi * t / tr)))
            )
            out *= ramp[:, None, None]
    return out


def _spans(problem: SpringDynamicProblem, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Span lengths [m] (n, m + 1) at times ``t`` and the path points (n, m + 2, 3)."""
    disp = end_displacements(problem.motion, t)
    n = disp.shape[0]
    m = len(problem.pulleys)
    pts = np.empty((n, m + 2, 3))
    pts[:, 0] = problem.position_a + disp[:, 0]
    pts[:, 1 : m + 1] = problem.pulleys
    pts[:, -1] = problem.position_b + disp[:, 1]
    seg = np.diff(pts, axis=1)
    return np.sqrt(np.einsum("nik,nik->ni", seg, seg)), pts


def _static_spans(problem: SpringDynamicProblem) -> np.ndarray:
    """Span lengths [m] at the static end positions (no motion)."""
    pts = np.vstack((problem.position_a, problem.pulleys, problem.position_b))
    return np.linalg.norm(np.diff(pts, axis=0), axis=1)


def spring_tension_at(problem: SpringDynamicProblem, t: np.ndarray | float) -> np.ndarray:
    """Tension [N] at times ``t`` [s] (array) of a line without pulley friction (the
    same on every span: the law of the path length minus L), ignoring a break."""
    t = np.atleast_1d(np.asarray(t, dtype=float))
    d, _ = _spans(problem, t.ravel())
    dist = d.sum(axis=1).reshape(t.shape)
    return problem.law.tension(dist - problem.unstretched(t))


def _slide_to_bound(
    law: AxialLaw, L: float, d: np.ndarray, lengths: np.ndarray, j: int, ratio: float
) -> None:
    """Move unstretched length between spans j and j + 1 (their sum kept) until the
    larger tension is ``ratio`` times the smaller (the line slides over pulley j + 1),
    by bisection on the share to round-off; in place."""
    total = lengths[j] + lengths[j + 1]

    def tensions(x: float) -> tuple[float, float]:
        # x: length of span j; its tension falls as x grows, span j+1's rises
        t1 = float(law.tension(L * (d[j] / x - 1.0)))
        t2 = float(law.tension(L * (d[j + 1] / (total - x) - 1.0)))
        return t1, t2

    t1, t2 = tensions(lengths[j])
    first_larger = t1 > t2

    def excess(x: float) -> float:
        # > 0 while the side that was larger still exceeds the bound
        a, b = tensions(x)
        return a - ratio * b if first_larger else b - ratio * a

    # the larger side takes length from the other: x grows if span j pulled harder
    lo, hi = (lengths[j], total * (1.0 - 1e-15)) if first_larger else (total * 1e-15, lengths[j])
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        # excess falls from lengths[j] towards the root on both sides
        if (excess(mid) > 0.0) == first_larger:
            lo = mid
        else:
            hi = mid
        if hi - lo <= 1e-15 * total:
            break
    lengths[j] = 0.5 * (lo + hi)
    lengths[j + 1] = total - lengths[j]


def march_with_friction(
    problem: SpringDynamicProblem, t: np.ndarray, lengths: np.ndarray
) -> np.ndarray:
    """Span tensions [N] (n, m + 1) at the increasing times ``t`` [s] of a line over
    pulleys with friction, from the span lengths ``lengths`` [m] at t[0]: at each time
    the line sticks on a pulley while T_large / T_small <= factor^(wrap / pi), and
    otherwise slides to that bound (pulleys visited in turn until none moves)."""
    law, L = problem.law, problem.length
    d_all, pts = _spans(problem, t)
    out = np.empty(d_all.shape)
    lengths = np.array(lengths, dtype=float)
    for i in range(len(t)):
        d = d_all[i]
        wraps = wrap_angles(pts[i])
        bound = problem.friction ** (wraps / math.pi)
        for _ in range(50):
            moved = False
            for j in range(len(problem.pulleys)):
                T = law.tension(L * (d / lengths - 1.0))
                big, small = max(T[j], T[j + 1]), min(T[j], T[j + 1])
                if big > bound[j] * small * (1.0 + 1e-12) and big > 0.0:
                    _slide_to_bound(law, L, d, lengths, j, float(bound[j]))
                    moved = True
            if not moved:
                break
        out[i] = law.tension(L * (d / lengths - 1.0))
    return out


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


def _friction_response(problem: SpringDynamicProblem) -> SpringDynamicResult:
    """Pulley friction: march from t = 0 (the frictionless static state) on a uniform
    grid; extremes and mean over the window from the grid (sampling error O(h^2))."""
    t0, t1 = problem.window
    n = max(int(problem.samples), 16)
    h = (t1 - t0) / n
    before = math.ceil(t0 / h) if t0 > 0.0 else 0
    t = np.concatenate((np.linspace(0.0, t0, before + 1)[:-1], np.linspace(t0, t1, n + 1)))
    d0 = _static_spans(problem)
    lengths = problem.length * d0 / d0.sum()
    T = march_with_friction(problem, t, lengths)
    end = T[:, 0] if problem.excited_end == 0 else T[:, -1]
    win = end[before:]
    static = float(problem.law.tension(float(d0.sum()) - problem.length))
    mean = float(np.sum(0.5 * (win[1:] + win[:-1]))) / (len(win) - 1)
    return SpringDynamicResult(
        tension_static=static,
        tension_max=float(win.max()),
        tension_min=float(win.min()),
        tension_mean=mean,
    )


def spring_response(problem: SpringDynamicProblem) -> SpringDynamicResult:
    """Tension extremes and mean of a massless spring under end motion (module docs)."""
    if problem.sticks:
        return _friction_response(problem)
    t0, t1 = problem.window
    n = max(int(problem.samples), 16)
    grid = np.linspace(t0, t1, n + 1)
    T = spring_tension_at(problem, grid)

    def f(t: float) -> float:
        return float(spring_tension_at(problem, t)[0])

    static = float(problem.law.tension(float(_static_spans(problem).sum()) - problem.length))
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
    if problem.break_at is not None and not problem.break_at >= break_time:
        break_time = float(problem.break_at)
    tol = 1e-12 * max(t1 - t0, 1e-300)
    h = (t1 - t0) / n
    i_max, i_min = int(np.argmax(T)), int(np.argmin(T))
    tmax, Tmax = _refine(f, max(grid[i_max] - h, t0), min(grid[i_max] + h, t1), 1.0, tol)
    _, Tmin = _refine(f, max(grid[i_min] - h, t0), min(grid[i_min] + h, t1), -1.0, tol)
    Tmax, Tmin = max(Tmax, float(T[i_max])), min(Tmin, float(T[i_min]))
    # trapezoidal rule: spectrally accurate on a periodic window, O(h^2) otherwise
    mean = float(np.sum(0.5 * (T[1:] + T[:-1]))) / n
    if math.isfinite(break_time):
        parted = grid >= break_time
        if break_time <= t0:
            Tmax = Tmin = mean = 0.0
        else:
            Tp = np.where(parted, 0.0, T)
            mean = float(np.sum(0.5 * (Tp[1:] + Tp[:-1]))) / n
            if break_time < t1:
                Tmin = 0.0
            if tmax >= break_time:
                before = ~parted
                k = int(np.argmax(np.where(before, T, -np.inf)))
                Tmax = max(float(T[k]), f(break_time))
    return SpringDynamicResult(
        tension_static=static,
        tension_max=Tmax,
        tension_min=Tmin,
        tension_mean=mean,
        break_time=break_time,
    )
