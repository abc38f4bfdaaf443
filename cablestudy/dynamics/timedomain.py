"""Steady periodic response of the discretised line to prescribed end motion.

:func:`simulate` integrates the line from rest in its static equilibrium with the
generalised-alpha method (:mod:`.integrator`) and

* steps at ``step`` (the period of the fastest harmonic over the points per period),
  landing exactly on period boundaries;
* halves the step, up to ``max_refinement`` times, when an element changes between
  slack and taut within a step (and whenever Newton fails), and grows it back after
  two clean steps: steps shorten around slack-taut transitions, never because of the
  axial wave speed;
* records, per period, the maximum, minimum and mean tension at the excited end (the
  magnitude of the force of the line on the end support) and the largest element
  tension; it stops when the per-period maximum and minimum have changed by less
  than ``steady_tolerance`` times the period's maximum over ``steady_window``
  consecutive periods (steady state), or after ``max_periods`` periods (not
  converged: the spread of the per-period values over the last periods is reported
  with the result, so a response that does not settle (subharmonic, chaotic) is never
  mistaken for a final number);
* records, per step, the tensions of every element and at both ends and the
  touchdown point (:func:`cablestudy.physics.seabed.touchdown_arc_length`), whose
  extremes over the steady window are the line's tension envelope and the touchdown
  point's range of travel;
* optionally keeps time histories of the end tension and of the motion of chosen
  points, and of the whole line (node positions and velocities, element and end
  tensions), resampled uniformly over the last periods;
* parts the line (``break_tension``, ``break_at``) at the instant an element's tension
  reaches its limit, found inside the step by regula falsi on the step length (a
  tension interpolated across the step would miss a snap load's curvature; re-solving
  the step from its start costs a few Newton solves), or at the failure time; the
  element is flagged broken (no force, no moment) and the run restarts from the parted
  state with the free nodes' accelerations in balance, then goes on without
  steady-state detection (or stops: ``after_break``);
* winches end A (``winch_speed``): the first element's unstretched length changes
  with its mass, weight, drag and contact per metre kept.

Pure: arrays in, a :class:`DynamicResult` out (status, message, counters).
"""

from __future__ import annotations

import math
import time
from collections import deque
from dataclasses import dataclass, field, replace
from typing import NamedTuple

import numpy as np

from ..physics.seabed import touchdown_arc_length
from ..statics.base import STATUS_NUMERICAL, STATUS_OK, STATUS_TIME_LIMIT
from .excitation import EndMotion
from .integrator import (
    NEWTON_FAILED,
    PARTED,
    REACHED_BOUNDARY,
    WINCH_LIMIT,
    AlphaParameters,
    march,
)
from .model import DiscreteLine, Workspace, evaluate, interpolate_nodes
from .pulley import SlidingPulleys

#: extra step halvings allowed beyond ``max_refinement`` when Newton fails
NEWTON_RESCUE_HALVINGS = 8


@dataclass(frozen=True, kw_only=True)
class DynamicProblem:
    """A time-domain run.

    Parameters
    ----------
    line : the discretised line
    static_position : [m] (n + 1, 3) discrete static equilibrium (start, at rest)
    motion : prescribed motion of the ends about their static positions
    period : [s] steady-state period (windows of the per-period statistics)
    step : [s] base time step
    excited_end : 0 (A) or 1 (B): where ``tension_*`` are taken
    max_refinement : step halvings allowed around slack-taut transitions
    spectral_radius : [-] generalised-alpha high-frequency spectral radius
    newton_tolerance : [N] largest residual force accepted on a free node
    max_newton_iterations : per step
    steady_tolerance : [-] relative change of per-period max/min that counts as steady
    steady_window : consecutive periods that must agree; outputs are taken over them
    min_periods : periods after the ramp before steady state may be declared
    max_periods : periods run at most (ramp included)
    duration : [s] fixed run time instead (no steady-state detection), or None
    history_s : [m] (p,) arc lengths of the points whose motion is kept
    history : whether to keep time histories
    history_periods : [periods] length of the kept record
    history_samples : samples per period of the kept record
    keep_steps : keep every accepted step's full state (for tests and diagnostics)
    tension_step : [N] largest change of the end tension in one step; a larger change
        halves the step (up to ``max_refinement`` times), so snap loads are resolved
    anchor : [m] (n + 1, 3) seabed friction anchors of the static equilibrium (None:
        at the static positions, no friction force stored)
    history_line : with ``history``, also keep the whole line's history (nodes)
    touchdown_tolerance : [m] largest height above the seabed at which a node counts as
        touching it (touchdown tracking; the penalty contact sinks laid nodes below it)
    break_tension : [N] (n,) tension at which each element parts (inf: never), or None
    break_at : [s] (n,) time at which each element fails (inf: never), or None: at the
        earliest of them the line parts at the most loaded element failing then (the
        largest tension over its limit, or the largest tension where none is finite)
    after_break : ``continue`` (the parts move on, free where no end holds them, to
        ``duration`` or ``max_periods`` periods) or ``stop`` (the run ends at the break)
    break_tolerance : [-] the break instant is where the element tension is within this
        fraction of its limit (regula falsi on the length of the step that reaches it)
    winch_speed : [m/s] rate of change of the first element's unstretched length (a winch
        at end A paying out, > 0, or hauling in, < 0), from ``winch_start`` to
        ``winch_stop`` [s]; the element's lumped mass, weight, added mass, drag and seabed
        contact follow its length (constant per unit unstretched length)
    winch_limits : [-] (lower, upper) bounds of the first element's length over its
        initial length; leaving them fails the run (no re-meshing)
    """

    line: DiscreteLine
    static_position: np.ndarray
    motion: EndMotion
    period: float
    step: float
    excited_end: int = 1
    max_refinement: int = 3
    spectral_radius: float = 0.3
    newton_tolerance: float = 1e-5
    max_newton_iterations: int = 12
    steady_tolerance: float = 0.002
    steady_window: int = 2
    min_periods: int = 3
    max_periods: int = 80
    duration: float | None = None
    history: bool = False
    history_s: np.ndarray = field(default_factory=lambda: np.zeros(0))
    history_periods: float = 2.0
    history_samples: int = 64
    keep_steps: bool = False
    tension_step: float = math.inf
    anchor: np.ndarray | None = None
    history_line: bool = False
    touchdown_tolerance: float = 0.0
    break_tension: np.ndarray | None = None
    break_at: np.ndarray | None = None
    after_break: str = "continue"
    break_tolerance: float = 1e-6
    winch_speed: float = 0.0
    winch_start: float = 0.0
    winch_stop: float = math.inf
    winch_limits: tuple[float, float] = (0.25, 4.0)
    #: pulleys the line slides over (:mod:`.pulley`; None: none)
    pulleys: SlidingPulleys | None = None

    @property
    def breakable(self) -> bool:
        """Whether the line can part in this run."""
        finite = self.break_tension is not None and bool(np.any(np.isfinite(self.break_tension)))
        timed = self.break_at is not None and bool(np.any(np.isfinite(self.break_at)))
        return finite or timed

    def paid_out(self, t: float) -> float:
        """Change of the first element's unstretched length by time ``t`` [m]."""
        if self.winch_speed == 0.0:
            return 0.0
        return self.winch_speed * max(min(t, self.winch_stop) - self.winch_start, 0.0)


@dataclass(kw_only=True)
class DynamicResult:
    """Outcome of :func:`simulate` (tensions [N], times [s]).

    ``tension_max``/``tension_min``/``tension_mean`` are at the excited end over the
    last ``steady_window`` periods; ``tension_max_line`` is the largest element or end
    tension there; the spreads are the ranges of the per-period maxima and minima over
    the last ``steady_window + 1`` periods (below ``steady_tolerance`` times the
    maximum when ``steady_converged``). ``history`` holds ``time`` (nt,), ``tension``
    (nt,), ``displacement``, ``velocity``, ``acceleration`` (p, nt, 3) when asked for,
    and with ``history_line`` the nodes' ``line_position``, ``line_velocity``
    (nt, n + 1, 3), ``line_element_tension`` (nt, n) and ``line_end_tension`` (nt, 2).

    Over the same window as ``tension_max``: ``element_tension_max``/``_min`` (n,) are
    each element's largest and smallest tension over the steps, ``end_tension_max``/
    ``_min`` (2,) those at ends A and B (so ``end_tension_max[excited_end]`` is
    ``tension_max``); ``touchdown_min``/``_max`` [m] the range of the touchdown point's
    arc length from A over the steps where the line touches the seabed (NaN if none).
    ``touchdown_tracked`` is whether the model has a seabed to touch; ``line_s`` [m]
    (n + 1,) are the nodes' arc lengths.

    ``break_time`` [s] is when the line parted (NaN: it did not), ``break_element`` which
    element (-1: none) and ``break_s`` [m] the arc length of its midpoint then. After a
    break ``tension_max``/``_min``/``_mean``/``_max_line`` and the extremes along the
    line cover the whole run from t = 0 (the ramp included: the break may come in it),
    so that they hold the peak that broke the line. ``winch_paid_out`` [m] is the
    change of the unstretched length at the end.
    """

    status: int = STATUS_OK
    message: str = ""
    break_time: float = math.nan
    break_element: int = -1
    break_s: float = math.nan
    winch_paid_out: float = 0.0
    #: with pulleys: the range [m] of each pulley's arc length from A over the window
    split_min: np.ndarray = field(default_factory=lambda: np.zeros(0))
    split_max: np.ndarray = field(default_factory=lambda: np.zeros(0))
    tension_static: float = math.nan
    tension_max: float = math.nan
    tension_min: float = math.nan
    tension_mean: float = math.nan
    tension_max_line: float = math.nan
    tension_max_spread: float = math.nan
    tension_min_spread: float = math.nan
    steady_converged: bool = False
    steps: int = 0
    newton_iterations: int = 0
    rejected_steps: int = 0
    periods: float = 0.0
    simulated_time: float = 0.0
    period_max: np.ndarray = field(default_factory=lambda: np.zeros(0))
    period_min: np.ndarray = field(default_factory=lambda: np.zeros(0))
    element_tension_max: np.ndarray = field(default_factory=lambda: np.zeros(0))
    element_tension_min: np.ndarray = field(default_factory=lambda: np.zeros(0))
    end_tension_max: np.ndarray = field(default_factory=lambda: np.full(2, math.nan))
    end_tension_min: np.ndarray = field(default_factory=lambda: np.full(2, math.nan))
    touchdown_min: float = math.nan
    touchdown_max: float = math.nan
    touchdown_tracked: bool = False
    line_s: np.ndarray = field(default_factory=lambda: np.zeros(0))
    history: dict[str, np.ndarray] | None = None
    record: dict[str, np.ndarray] | None = None

    @property
    def success(self) -> bool:
        return self.status == STATUS_OK


def end_forces(
    work: Workspace, a: np.ndarray, x: np.ndarray | None = None, held: np.ndarray | None = None
) -> np.ndarray:
    """Force of the line on the supports at A and B [N] (2, 3): minus the support
    reaction ``M a + F`` of a held end node; at a free end node (a towed body, given
    ``x`` [m] and ``held``) the pull of the end element on it."""
    out = np.empty((2, 3))
    out[0] = -(work.F[0] + work.M_d[0] @ a[0])
    out[1] = -(work.F[-1] + work.M_d[-1] @ a[-1])
    if held is not None and x is not None:
        if not held[0]:
            d = x[1] - x[0]
            out[0] = work.tension[0] * d / np.linalg.norm(d)
        if not held[-1]:
            d = x[-2] - x[-1]
            out[1] = work.tension[-1] * d / np.linalg.norm(d)
    return out


class _LineExtremes:
    """Per-step extremes along the line over each period: element and end tensions
    [N] (largest and smallest) and the touchdown arc length [m] (NaN where no contact).
    The current period's are arrays the compiled step loop updates in place
    (``element`` (2, n) and ``end`` (2, 2): largest, smallest; ``touchdown`` (2,):
    least, greatest). Keeps the last ``keep`` periods (None: folds every period into
    one)."""

    def __init__(self, keep: int | None, element: np.ndarray, ends: np.ndarray, td: float):
        self.keep = keep
        self.periods: deque[list] = deque()
        self.element = np.empty((2, element.size))
        self.end = np.empty((2, 2))
        self.touchdown = np.empty(2)
        self.start(element, ends, td)
        self.run = self.current()  # the whole run, folded at every period boundary

    def start(self, element: np.ndarray, ends: np.ndarray, td: float) -> None:
        self.element[:] = element[None, :]
        self.end[:] = ends[None, :]
        self.touchdown[:] = td

    def add(self, element: np.ndarray, ends: np.ndarray, td: float) -> None:
        """Fold one step's element and end tensions and touchdown point in (the
        compiled loop does this itself)."""
        np.maximum(self.element[0], element, out=self.element[0])
        np.minimum(self.element[1], element, out=self.element[1])
        np.maximum(self.end[0], ends, out=self.end[0])
        np.minimum(self.end[1], ends, out=self.end[1])
        self.touchdown[0] = np.fmin(self.touchdown[0], td)
        self.touchdown[1] = np.fmax(self.touchdown[1], td)

    def current(self) -> list:
        return [
            self.element[0].copy(),
            self.element[1].copy(),
            self.end[0].copy(),
            self.end[1].copy(),
            float(self.touchdown[0]),
            float(self.touchdown[1]),
        ]

    def fold_run(self) -> None:
        """Fold the current period into the whole run's extremes."""
        self.run = self._fold([self.run, self.current()])

    def close(self) -> None:
        """The current period is one of the steady-state periods: keep it."""
        self.periods.append(self.current())
        if self.keep is None and len(self.periods) > 1:
            self.periods.appendleft(self._fold([self.periods.popleft(), self.periods.pop()]))
        while self.keep is not None and len(self.periods) > self.keep:
            self.periods.popleft()

    @staticmethod
    def _fold(items: list[list]) -> list:
        return [
            np.max([i[0] for i in items], axis=0),
            np.min([i[1] for i in items], axis=0),
            np.max([i[2] for i in items], axis=0),
            np.min([i[3] for i in items], axis=0),
            float(np.fmin.reduce([i[4] for i in items])),
            float(np.fmax.reduce([i[5] for i in items])),
        ]

    def window(self, whole_run: bool = False) -> list:
        """Extremes over the kept periods (the current partial one if none closed), or
        over the whole run (``whole_run``, the current period folded in)."""
        if whole_run:
            return self._fold([self.run, self.current()])
        return self._fold(list(self.periods) or [self.current()])


class _History:
    """The time histories a run keeps (``problem.history``): (t, end tension, x, v, a at
    the history points, and with ``history_line`` x, v, a of every node, the element
    and end tensions) over the last ``history_periods`` periods and one more,
    resampled uniformly at the end (:func:`_resample`)."""

    def __init__(self, problem: DynamicProblem, line: DiscreteLine) -> None:
        self.problem = problem
        self.line = line
        self.points = np.asarray(problem.history_s, dtype=float)
        self.span = (problem.history_periods + 1.0) * problem.period
        self.buf: deque[tuple] = deque()

    def push(
        self,
        t: float,
        tension: float,
        ends: np.ndarray,
        x: np.ndarray,
        v: np.ndarray,
        a: np.ndarray,
        element_tension: np.ndarray,
    ) -> None:
        if not self.problem.history:
            return
        xs = interpolate_nodes(self.line.s, self.points, np.stack([x, v, a]))
        whole = (
            (x.copy(), v.copy(), a.copy(), element_tension.copy(), ends.copy())
            if self.problem.history_line
            else ()
        )
        self.buf.append((t, tension, xs[0], xs[1], xs[2], *whole))
        while len(self.buf) > 2 and self.buf[1][0] < t - self.span:
            self.buf.popleft()

    def resampled(self, t_end: float) -> dict[str, np.ndarray] | None:
        """The kept record resampled over the periods ending at ``t_end`` (None: no
        history asked for, or too short)."""
        if not self.problem.history or len(self.buf) < 2:
            return None
        prob = self.problem
        static = interpolate_nodes(self.line.s, self.points, prob.static_position[None])[0]
        return _resample(self.buf, t_end, prob.period, prob, static)


class _Start(NamedTuple):
    """A run's work arrays and its start: the static equilibrium at rest."""

    work: Workspace
    largs: tuple
    wargs: tuple
    sargs: tuple
    held: np.ndarray
    x0: np.ndarray
    v0: np.ndarray
    a0: np.ndarray
    x1: np.ndarray
    v1: np.ndarray
    a1: np.ndarray
    F0: np.ndarray
    strain_prev: np.ndarray
    base: np.ndarray
    ex: int
    f_static: np.ndarray
    t_static: float
    result: DynamicResult
    extremes: _LineExtremes


def _start(problem: DynamicProblem, line: DiscreteLine) -> _Start:
    """Work arrays of ``line``, the state at rest in ``problem.static_position`` (forces
    with the static friction anchors), the force of the line on the ends there and the
    excited end's tension, an empty result, and the line's extremes started there."""
    work = Workspace(line.n_elements)
    held = line.held
    x0 = np.array(problem.static_position, dtype=float, copy=True)
    v0 = np.zeros_like(x0)
    a0 = np.zeros_like(x0)
    anchor0 = problem.anchor if problem.anchor is not None else x0
    evaluate(line, x0, v0, work, anchor=anchor0)
    ex = problem.excited_end
    f_static = end_forces(work, a0, x0, held)
    t_static = float(np.linalg.norm(f_static[ex]))
    result = DynamicResult(tension_static=t_static, line_s=line.s)
    result.touchdown_tracked = line.has_seabed
    extremes = _LineExtremes(
        None if problem.duration is not None else max(1, problem.steady_window),
        work.tension,
        np.sqrt(np.sum(f_static**2, 1)),
        touchdown_of(line, x0, problem.touchdown_tolerance),
    )
    return _Start(
        work,
        line.kernel_args(),
        work.assemble_args(),
        work.solver_args(line),
        held,
        x0,
        v0,
        a0,
        x0.copy(),
        v0.copy(),
        a0.copy(),
        work.F.copy(),
        work.strain.copy(),
        np.stack([x0[0], x0[-1]]),
        ex,
        f_static,
        t_static,
        result,
        extremes,
    )


def touchdown_of(line: DiscreteLine, x: np.ndarray, tolerance: float) -> float:
    """Arc length [m] where the line at nodes ``x`` leaves the seabed plane (NaN: no
    contact, or no seabed)."""
    if not line.has_seabed:
        return math.nan
    n = line.seabed_normal
    if n[0] == 0.0 and n[1] == 0.0:
        bed: np.ndarray | float = line.seabed_offset / n[2]
    else:
        bed = (line.seabed_offset - n[0] * x[:, 0] - n[1] * x[:, 1]) / n[2]
    return touchdown_arc_length(line.s, x[:, 2], bed, tolerance)


def is_steady(problem: DynamicProblem, p_max: list[float], p_min: list[float]) -> bool:
    """Whether the last ``steady_window`` periods' maxima and minima each changed by at
    most ``steady_tolerance`` times the period's maximum (after ``min_periods``)."""
    w = problem.steady_window
    if len(p_max) < max(problem.min_periods, w + 1):
        return False
    return all(
        abs(p_max[-j] - p_max[-j - 1]) <= problem.steady_tolerance * p_max[-j]
        and abs(p_min[-j] - p_min[-j - 1]) <= problem.steady_tolerance * p_max[-j]
        for j in range(1, w + 1)
    )


def window_statistics(
    result: DynamicResult,
    problem: DynamicProblem,
    periods: tuple[list[float], list[float], list[float], list[float]],
    partial: tuple[float, float, float, float],
) -> slice:
    """Fill ``result``'s tensions from the per-period (max, min, mean, line max) lists:
    over the last ``steady_window`` periods (every period with a fixed ``duration``;
    ``partial``, the last unfinished period's, when the run ended inside the ramp), the
    spreads over one period more. Returns the slice of the periods used."""
    p_max, p_min, p_mean, p_line = (list(v) for v in periods)
    w = max(1, problem.steady_window) if problem.duration is None else len(p_max)
    if not p_max:  # the run ended inside the ramp: use the last (partial) window
        p_max, p_min, p_mean, p_line = ([v] for v in partial)
    sl = slice(-min(w, len(p_max)), None)
    sp = slice(-min(w + 1, len(p_max)), None)
    result.tension_max = max(p_max[sl])
    result.tension_min = min(p_min[sl])
    result.tension_mean = float(np.mean(p_mean[sl]))
    result.tension_max_line = max(p_line[sl])
    result.tension_max_spread = max(p_max[sp]) - min(p_max[sp])
    result.tension_min_spread = max(p_min[sp]) - min(p_min[sp])
    result.period_max = np.asarray(p_max)
    result.period_min = np.asarray(p_min)
    return sl


def _hermite(t: np.ndarray, y: np.ndarray, dy: np.ndarray, tq: np.ndarray) -> np.ndarray:
    """Cubic Hermite interpolation of samples ``y`` (ns, ...) with derivatives ``dy``
    at increasing times ``t`` (ns,) to ``tq`` (clamped to the samples' range)."""
    tq = np.clip(tq, t[0], t[-1])
    i = np.clip(np.searchsorted(t, tq, side="right") - 1, 0, t.size - 2)
    h = t[i + 1] - t[i]
    s = (tq - t[i]) / h
    shape = (-1,) + (1,) * (y.ndim - 1)
    s = s.reshape(shape)
    hh = h.reshape(shape)
    h00 = 2 * s**3 - 3 * s**2 + 1
    h10 = s**3 - 2 * s**2 + s
    h01 = -2 * s**3 + 3 * s**2
    h11 = s**3 - s**2
    return h00 * y[i] + h10 * hh * dy[i] + h01 * y[i + 1] + h11 * hh * dy[i + 1]


def simulate(problem: DynamicProblem, *, deadline: float | None = None) -> DynamicResult:
    """Integrate until steady state (or ``max_periods``, or ``duration``).

    A numerical failure (Newton failing at the smallest step) is returned as a result
    with nonzero status and a message; the deadline (a :func:`time.monotonic` value)
    gives :data:`STATUS_TIME_LIMIT`. A line over sliding pulleys is run by
    :func:`.pulley_timedomain.simulate_sliding` (the split solved with each step).
    """
    if problem.pulleys is not None:
        from .pulley_timedomain import simulate_sliding

        return simulate_sliding(problem, deadline=deadline)
    line = problem.line
    winching = problem.winch_speed != 0.0
    if winching:  # the winch changes these in place: a private copy
        line = replace(line, **{k: np.array(getattr(line, k), copy=True) for k in _WINCHED})
    if problem.breakable:
        line = replace(line, broken=np.zeros(line.n_elements, dtype=np.bool_))
    limit = (
        np.full(line.n_elements, math.inf)
        if problem.break_tension is None
        else np.array(problem.break_tension, dtype=float)
    )
    timed = (
        np.asarray(problem.break_at, dtype=float)
        if problem.break_at is not None
        else np.full(line.n_elements, math.inf)
    )
    break_at = float(timed.min()) if np.isfinite(timed).any() else math.inf
    due = timed <= break_at
    ctl = np.array(
        [
            break_at,
            problem.break_tolerance,
            float(problem.breakable),
            problem.winch_speed,
            problem.winch_start,
            problem.winch_stop,
            *problem.winch_limits,
            float(np.any(line.clamp_direction[0] != 0.0)),
        ]
    )
    wini = _winch_initial(line)
    s_ini = line.s.copy()
    par = AlphaParameters.from_spectral_radius(problem.spectral_radius)
    (
        work,
        largs,
        wargs,
        sargs,
        held,
        x0,
        v0,
        a0,
        x1,
        v1,
        a1,
        F0,
        strain_prev,
        base,
        ex,
        f_static,
        t_static,
        result,
        extremes,
    ) = _start(problem, line)

    T = problem.period
    t_ramp = problem.motion.ramp_time
    t_stop = problem.duration if problem.duration is not None else problem.max_periods * T
    tol = problem.newton_tolerance
    eps_t = 1e-9 * T

    keep_hist = problem.history
    hist = _History(problem, line)

    def push(t: float, tension: float, ends: np.ndarray) -> None:
        hist.push(t, tension, ends, x0, v0, a0, work.tension)

    rec: dict[str, list[np.ndarray]] = {
        k: [] for k in ("t", "x", "v", "a", "end_force", "tension", "friction")
    }

    def keep(t: float, forces: np.ndarray) -> None:
        if problem.keep_steps:
            rec["t"].append(np.asarray(t))
            rec["x"].append(x0.copy())
            rec["v"].append(v0.copy())
            rec["a"].append(a0.copy())
            rec["end_force"].append(forces.copy())
            rec["tension"].append(work.tension.copy())
            rec["friction"].append(work.friction.copy())

    keep(0.0, f_static)
    push(0.0, t_static, np.sqrt(np.sum(f_static**2, 1)))

    # per-period statistics (periods starting after the ramp only)
    p_max: list[float] = []
    p_min: list[float] = []
    p_mean: list[float] = []
    p_line: list[float] = []
    c_start = 0.0
    # the compiled step loop's state (see integrator.march): t, period boundary, the
    # current period's max, min, integral and largest line tension, the last end
    # tension, line maximum, touchdown and step; level, clean steps, steps, Newton
    # iterations, rejected steps, positions kept for the predictor, parted, element
    c_line0 = max(t_static, float(work.tension.max()))
    st_f = np.array(
        [0.0, min(T, t_stop), t_static, t_static, 0.0, c_line0, t_static, c_line0, 0.0, 0.0]
    )
    st_i = np.zeros(8, dtype=np.int64)
    # the same over the whole run (what a run with a break reports), folded at every
    # period boundary
    r_max, r_min, r_int, r_line = t_static, t_static, 0.0, c_line0
    # Newton starts from a quadratic extrapolation of the last three positions: the
    # positions are smooth, whereas the accelerations of generalised-alpha carry the
    # decaying unresolved axial modes, which a Taylor predictor would amplify into
    # large spurious stretches.
    past_x = np.zeros((2, *x0.shape))
    past_t = np.zeros(2)
    frac = line.s / line.s[-1]
    x_pred = np.empty_like(x0)
    ends = np.zeros(2)
    forces = np.zeros((2, 3))
    single = problem.keep_steps or keep_hist
    budget = 64 if deadline is not None else 2**62
    margs = problem.motion.kernel_args()
    tension_prev = work.tension.copy()

    def part_restart() -> None:
        """The line has parted (``line.broken``): forces without the element, and the
        free nodes' accelerations in balance with them (the held ones keep their
        motion), so the integrator restarts from the parted state."""
        e = int(st_i[7])
        result.break_time = float(st_f[0])
        result.break_element = e
        result.break_s = float(0.5 * (line.s[e] + line.s[e + 1]))
        evaluate(line, x0, v0, work)
        F0[:] = work.F
        for i in range(x0.shape[0]):
            if not held[i]:
                a0[i] = -np.linalg.solve(work.M_d[i], work.F[i])
        strain_prev[:] = work.strain
        tension_prev[:] = work.tension
        st_i[5] = 0  # the predictor starts afresh
        st_i[0] = st_i[1] = 0
        f = end_forces(work, a0, x0, held)
        forces[:] = f
        ends[:] = np.sqrt(np.sum(f**2, 1))
        st_f[6] = float(ends[ex])
        st_f[2] = max(st_f[2], st_f[6])
        st_f[3] = min(st_f[3], st_f[6])
        np.minimum(extremes.element[1], work.tension, out=extremes.element[1])
        np.minimum(extremes.end[1], ends, out=extremes.end[1])

    if problem.breakable and bool(np.any(work.tension > limit)):
        # the model's own equilibrium is already over a limit: it parts at once
        st_i[7] = int(np.argmax(work.tension / limit))
        st_i[6] = 1
        line.broken[st_i[7]] = True
        part_restart()
        if problem.after_break == "stop":
            result.tension_max = result.tension_min = result.tension_mean = t_static
            result.tension_max_line = c_line0
            return result

    converged = False
    while True:
        if deadline is not None and time.monotonic() > deadline:
            result.status, result.message = (
                STATUS_TIME_LIMIT,
                (f"time limit reached at t = {st_f[0]:.4g} s of the dynamic run"),
            )
            return result
        code = march(
            st_f,
            st_i,
            x0,
            v0,
            a0,
            x1,
            v1,
            a1,
            F0,
            strain_prev,
            x_pred,
            past_x,
            past_t,
            base,
            frac,
            margs,
            ends,
            forces,
            extremes.element,
            extremes.end,
            extremes.touchdown,
            line.s,
            problem.touchdown_tolerance,
            problem.step,
            problem.max_refinement,
            problem.max_refinement + NEWTON_RESCUE_HALVINGS,
            problem.tension_step,
            ex,
            eps_t,
            par.alpha_m,
            par.alpha_f,
            par.beta,
            par.gamma,
            tol,
            problem.max_newton_iterations,
            single,
            budget,
            work.anchor,
            largs,
            wargs,
            sargs,
            ctl,
            limit,
            due,
            tension_prev,
            wini,
            line.first_per_length,
            s_ini,
        )
        t = float(st_f[0])
        if code == NEWTON_FAILED:
            level = int(st_i[0])
            result.status = STATUS_NUMERICAL
            result.message = (
                f"Newton did not converge at t = {t:.6g} s with step "
                f"{st_f[9]:.3g} s ({problem.step:.3g} s halved {level} times)"
            )
            result.steps, result.newton_iterations = int(st_i[2]), int(st_i[3])
            result.rejected_steps = int(st_i[4])
            return result
        if code == WINCH_LIMIT:
            paid, l_ini = float(st_f[9]), float(wini[0, 0])
            lo, hi = problem.winch_limits
            result.status = STATUS_NUMERICAL
            result.message = (
                f"line.winch: at t = {t:.4g} s the winched first element would be "
                f"{(l_ini + paid) / l_ini:.3g} times its initial length {l_ini:.4g} m (paid "
                f"out {paid:.4g} m); the model keeps it between {lo:g} and {hi:g} times (no "
                "re-meshing): use fewer elements (analysis.dynamic.elements) or a shorter "
                "pay-out"
            )
            result.steps, result.newton_iterations = int(st_i[2]), int(st_i[3])
            return result
        if single:
            keep(t, forces)
            push(t, float(st_f[6]), ends)
        if code == PARTED:
            part_restart()
            if single:
                keep(t, forces)
                push(t, float(st_f[6]), ends)
            if problem.after_break == "stop":
                t_stop = t
            if abs(t - st_f[1]) > eps_t and t < t_stop - eps_t:
                continue
            st_f[1] = t  # a boundary here: the period (or the run) closes at the break
        elif code != REACHED_BOUNDARY:
            continue
        tension = float(st_f[6])
        final = t >= t_stop - eps_t
        r_max, r_min = max(r_max, float(st_f[2])), min(r_min, float(st_f[3]))
        r_int += float(st_f[4])
        r_line = max(r_line, float(st_f[5]))
        extremes.fold_run()
        if c_start >= t_ramp - eps_t or (final and not p_max):
            p_max.append(float(st_f[2]))
            p_min.append(float(st_f[3]))
            p_mean.append(float(st_f[4]) / max(t - c_start, 1e-300))
            p_line.append(float(st_f[5]))
            extremes.close()
        extremes.start(work.tension, ends, float(st_f[8]))
        st_f[2] = st_f[3] = tension
        st_f[4] = 0.0
        st_f[5] = st_f[7]
        c_start = t
        # steady state: not after a break (the parted line has no periodic state to
        # settle on) nor while a winch runs (the periods must start after it stops)
        if problem.duration is None and st_i[6] == 0:
            w = problem.steady_window
            if not winching or t - (w + 1) * T >= problem.winch_stop - eps_t:
                converged = is_steady(problem, p_max, p_min)
        if converged or final:
            break
        st_f[1] = min(st_f[1] + T, t_stop)

    broke = bool(st_i[6])
    steps, newton, rejected = int(st_i[2]), int(st_i[3]), int(st_i[4])
    window_statistics(
        result,
        problem,
        (p_max, p_min, p_mean, p_line),
        (
            float(st_f[2]),
            float(st_f[3]),
            float(st_f[4]) / max(t - c_start, 1e-300),
            float(st_f[5]),
        ),
    )
    if broke:  # the whole run, ramp included (the break may come in it)
        result.tension_max, result.tension_min = r_max, r_min
        result.tension_mean = r_int / max(t, 1e-300)
        result.tension_max_line = r_line
    result.steady_converged = converged
    result.steps, result.newton_iterations, result.rejected_steps = steps, newton, rejected
    result.periods = t / T
    result.simulated_time = t
    (
        result.element_tension_max,
        result.element_tension_min,
        result.end_tension_max,
        result.end_tension_min,
        result.touchdown_min,
        result.touchdown_max,
    ) = extremes.window(broke)
    result.winch_paid_out = problem.paid_out(t)
    result.history = hist.resampled(t)
    if problem.keep_steps:
        result.record = {k: np.asarray(v) for k, v in rec.items()}
    return result


def _resample(
    buf: deque, t_end: float, period: float, problem: DynamicProblem, static_points: np.ndarray
) -> dict[str, np.ndarray]:
    """Uniform record over the last ``history_periods`` periods ending at ``t_end``."""
    nt = int(round(problem.history_periods * problem.history_samples)) + 1
    tq = t_end - problem.history_periods * period + np.arange(nt) * period / problem.history_samples
    ts = np.array([b[0] for b in buf])
    tension = np.array([b[1] for b in buf])
    xs = np.array([b[2] for b in buf])  # (ns, p, 3)
    vs = np.array([b[3] for b in buf])
    acc = np.array([b[4] for b in buf])
    pos = _hermite(ts, xs, vs, tq)
    vel = _hermite(ts, vs, acc, tq)
    ai = np.empty_like(pos)
    for p in range(xs.shape[1]):
        for c in range(3):
            ai[:, p, c] = np.interp(tq, ts, acc[:, p, c])
    out = {
        "time": tq,
        "tension": np.interp(tq, ts, tension),
        "displacement": np.transpose(pos - static_points[None], (1, 0, 2)),
        "velocity": np.transpose(vel, (1, 0, 2)),
        "acceleration": np.transpose(ai, (1, 0, 2)),
    }
    if problem.history_line:
        # nodes as the points: positions and velocities cubic Hermite in time, the
        # tensions (no derivative kept) linear
        xn = np.array([b[5] for b in buf])  # (ns, n + 1, 3)
        vn = np.array([b[6] for b in buf])
        an = np.array([b[7] for b in buf])
        out["line_position"] = _hermite(ts, xn, vn, tq)
        out["line_velocity"] = _hermite(ts, vn, an, tq)
        out["line_element_tension"] = _linear(ts, np.array([b[8] for b in buf]), tq)
        out["line_end_tension"] = _linear(ts, np.array([b[9] for b in buf]), tq)
    return out


def _linear(t: np.ndarray, y: np.ndarray, tq: np.ndarray) -> np.ndarray:
    """Linear interpolation of samples ``y`` (ns, m) at increasing times ``t`` (ns,) to
    ``tq`` (clamped to the samples' range), column by column as :func:`numpy.interp`."""
    tq = np.clip(tq, t[0], t[-1])
    i = np.clip(np.searchsorted(t, tq, side="right") - 1, 0, t.size - 2)
    w = ((tq - t[i]) / (t[i + 1] - t[i]))[:, None]
    return (1.0 - w) * y[i] + w * y[i + 1]


def warm_up() -> None:
    """Load the compiled kernels of the time step (the line model's forces and tangents,
    the banded solve, the discrete statics, the friction anchors, the end motion) on a
    two-element line above a seabed, so that a process forked afterwards has them: a
    kernel's first call in a process costs about a second, which is start-up, not the
    cost of a case."""
    from ..statics.base import LineModel, Medium
    from .excitation import EndMotion
    from .model import DynamicExtras, discretise, static_equilibrium

    one = np.ones(1)
    line = LineModel(
        length=2.0 * one,
        weight=10.0 * one,
        mass=one,
        axial_stiffness=1e6 * one,
        diameter=0.01 * one,
        drag_normal=one,
        drag_tangential=0.0 * one,
        added_mass_normal=one,
        added_mass_tangential=0.0 * one,
        bending_stiffness=0.0 * one,
        damping_ratio=0.0 * one,
        attachment_s=np.zeros(0),
        attachment_force=np.zeros((0, 3)),
        attachment_mass=np.zeros(0),
        attachment_volume=np.zeros(0),
    )
    medium = Medium(density=1000.0, gravity=9.8, depth=10.0, friction=0.5)
    disc = discretise(line, medium, 2, DynamicExtras(seabed_stiffness=1e4, friction_axial=0.5))
    x0 = np.array([[0.0, 0.0, 0.0], [0.999, 0.0, -0.05], [1.998, 0.0, 0.0]])
    x, _, _, _, anchor = static_equilibrium(disc, x0, tolerance=1e-6, max_iterations=20)
    motion = EndMotion(
        harmonic_end=np.array([1]),
        harmonic_direction=np.array([[1.0, 0.0, 0.0]]),
        harmonic_amplitude=np.array([1e-3]),
        harmonic_frequency=np.array([1.0]),
        harmonic_phase=np.zeros(1),
    )
    simulate(
        DynamicProblem(
            line=disc,
            static_position=x,
            motion=motion,
            period=1.0,
            step=0.25,
            duration=0.5,
            anchor=anchor,
        )
    )


#: the line's arrays a winch changes (copied per run)
_WINCHED = (
    "s",
    "rest_length",
    "internal_damping",
    "mass",
    "added_mass_normal",
    "added_mass_tangential",
    "drag_normal",
    "drag_tangential",
    "force",
    "bending",
    "transverse_damping",
    "seabed_stiffness",
    "seabed_damping",
)


def _winch_initial(line: DiscreteLine) -> np.ndarray:
    """The initial values :func:`cablestudy.dynamics.integrator.winch_set` starts from
    (12, 2): lengths of elements 0 and 1, internal damping of element 0, then for nodes
    0 and 1 mass, added mass normal and tangential, drag normal and tangential,
    transverse damping, vertical force, seabed stiffness and damping, bending."""
    out = np.zeros((12, 2))
    l0 = line.rest_length
    out[0] = (l0[0], l0[1] if l0.size > 1 else l0[0])
    out[1, 0] = line.internal_damping[0]
    for row, arr in enumerate(
        (
            line.mass,
            line.added_mass_normal,
            line.added_mass_tangential,
            line.drag_normal,
            line.drag_tangential,
            line.transverse_damping,
            line.force[:, 2],
            line.seabed_stiffness,
            line.seabed_damping,
            line.bending,
        ),
        start=2,
    ):
        out[row] = arr[:2]
    return out
