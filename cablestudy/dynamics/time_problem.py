"""A time-domain run's problem and what it records (:mod:`.timedomain` runs it): the
settings (:class:`MarchSettings`, a system's too, and :class:`DynamicProblem`), the
result (:class:`DynamicResult`), the end forces, the extremes along the line and the
histories kept, where it starts, the touchdown point and the steady-state test over a
window of periods.
"""

from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass, field
from typing import Any, NamedTuple

import numpy as np

from ..physics.seabed import touchdown_arc_length
from ..statics.base import STATUS_NUMERICAL, STATUS_OK, STATUS_TIME_LIMIT
from .assembly import Workspace, evaluate
from .discrete_line import DiscreteLine, interpolate_nodes
from .end_support import seabed_support
from .excitation import EndMotion
from .pulley import SlidingPulleys
from .steady import extremes_settled

#: extra step halvings allowed beyond ``max_refinement`` when Newton fails
NEWTON_RESCUE_HALVINGS = 8


@dataclass(frozen=True, kw_only=True)
class MarchSettings:
    """The step control and steady-state settings of a time-domain run, the same for a
    line (:class:`DynamicProblem`) and a system
    (:class:`.system_timedomain.SystemProblem`).

    Parameters
    ----------
    period : [s] steady-state period (windows of the per-period statistics)
    step : [s] base time step
    max_refinement : step halvings allowed around slack-taut transitions
    spectral_radius : [-] generalised-alpha high-frequency spectral radius
    newton_tolerance : [N] largest residual force accepted on a free node
    max_newton_iterations : per step
    tension_step : [N] largest change of the end tension in one step; a larger change
        halves the step (up to ``max_refinement`` times), so snap loads are resolved
    steady_tolerance : [-] change of the per-period max and min, relative to the period's
        dynamic range (max - min), that counts as steady (:mod:`.steady`)
    steady_window : consecutive periods that must agree; outputs are taken over them
    min_periods : periods after the ramp before steady state may be declared
    max_periods : periods run at most (ramp included)
    duration : [s] fixed run time instead (no steady-state detection), or None
    history : whether to keep time histories
    history_periods : [periods] length of the kept record
    history_samples : samples per period of the kept record
    step_tolerance : [-] the step check (:mod:`.step_check`): where the last period had
        seabed landings or lift-offs or slack-taut switches, it is run again from its
        start at half the step, and its end tensions' extremes must agree within this
        fraction of the period's dynamic range; None: no check
    points_per_period : steps a period of the fastest harmonic the step was set from
        (the check's message; 0: the period over the step)
    step_check_factor : the check's re-run step over the run's (1/2; 1 in a test: the
        same step must give the run's extremes bit for bit)
    """

    period: float
    step: float
    max_refinement: int = 3
    spectral_radius: float = 0.3
    newton_tolerance: float = 1e-5
    max_newton_iterations: int = 12
    tension_step: float = math.inf
    steady_tolerance: float = 0.002
    steady_window: int = 2
    min_periods: int = 3
    max_periods: int = 80
    duration: float | None = None
    history: bool = False
    history_periods: float = 2.0
    history_samples: int = 64
    step_tolerance: float | None = None
    points_per_period: float = 0.0
    step_check_factor: float = 0.5

    @property
    def steps_per_period(self) -> float:
        """``points_per_period``, or the period over the step when not given."""
        return self.points_per_period or self.period / self.step

    def settled(self, p_max: Any, p_min: Any, nodes: int) -> bool:
        """Whether the last ``steady_window`` periods' maxima and minima (periods first)
        each changed by at most ``steady_tolerance`` times the period's dynamic range
        (or by at most the Newton tolerance times the square root of ``nodes``, a
        line's node count: the end force sums the nodes' residuals, independent), after
        ``min_periods`` (:func:`.steady.extremes_settled`)."""
        w = self.steady_window
        if len(p_max) < max(self.min_periods, w + 1):
            return False
        return extremes_settled(
            np.asarray(p_max),
            np.asarray(p_min),
            tolerance=self.steady_tolerance,
            window=w,
            floor=self.newton_tolerance * math.sqrt(nodes),
        )


@dataclass(frozen=True, kw_only=True)
class DynamicProblem(MarchSettings):
    """A time-domain run of a line: the settings of :class:`MarchSettings` and

    Parameters
    ----------
    line : the discretised line
    static_position : [m] (n + 1, 3) discrete static equilibrium (start, at rest)
    motion : prescribed motion of the ends about their static positions
    excited_end : 0 (A) or 1 (B): where ``tension_*`` are taken
    history_s : [m] (p,) arc lengths of the points whose motion is kept
    keep_steps : keep every accepted step's full state (for tests and diagnostics)
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
    excited_end: int = 1
    history_s: np.ndarray = field(default_factory=lambda: np.zeros(0))
    keep_steps: bool = False
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
    the last ``steady_window + 1`` periods (each period's change below
    ``steady_tolerance`` times its dynamic range, or the Newton floor, when
    ``steady_converged``). ``history`` holds ``time`` (nt,), ``tension``
    (nt,), ``displacement``, ``velocity``, ``acceleration`` (p, nt, 3) when asked for,
    and with ``history_line`` the nodes' ``line_position``, ``line_velocity``
    (nt, n + 1, 3), ``line_element_tension`` (nt, n) and ``line_end_tension`` (nt, 2).

    Over the same window as ``tension_max``: ``element_tension_max``/``_min`` (n,) are
    each element's largest and smallest tension over the steps, ``end_tension_max``/
    ``_min`` (2,) those at ends A and B (so ``end_tension_max[excited_end]`` is
    ``tension_max``); ``touchdown_min``/``_max`` [m] the range of the touchdown point's
    arc length from A over the steps where the line touches the seabed (NaN if none);
    ``z_max`` [m] (n + 1,) each node's highest elevation. ``touchdown_tracked`` is
    whether the model has a seabed to touch; ``line_s`` [m] (n + 1,) are the nodes' arc
    lengths.

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
    z_max: np.ndarray = field(default_factory=lambda: np.zeros(0))
    line_s: np.ndarray = field(default_factory=lambda: np.zeros(0))
    history: dict[str, np.ndarray] | None = None
    record: dict[str, np.ndarray] | None = None
    #: the step check's verdict (:mod:`.step_check`; None: not run, no risk) and its
    #: warning ('' when the extremes agree)
    step_check: Any = None
    step_warning: str = ""

    @property
    def success(self) -> bool:
        return self.status == STATUS_OK


def end_forces(
    work: Workspace,
    a: np.ndarray,
    x: np.ndarray | None = None,
    held: np.ndarray | None = None,
    line: DiscreteLine | None = None,
) -> np.ndarray:
    """Force of the line on the supports at A and B [N] (2, 3): minus the support
    reaction ``M a + F`` of a held end node (given ``x`` [m] and the ``line``, without
    the seabed's part where the node rests on the seabed:
    :func:`.end_support.seabed_support`, as the compiled step's); at a free end node (a
    towed body, given ``x`` and ``held``) the pull of the end element on it."""
    out = np.empty((2, 3))
    out[0] = -(work.F[0] + work.M_d[0] @ a[0])
    out[1] = -(work.F[-1] + work.M_d[-1] @ a[-1])
    if line is not None and x is not None and line.seabed_stiffness.size:
        tol = 1e-6 * max(float(np.sum(line.rest_length)), 1.0)
        for e, i in ((0, 0), (1, x.shape[0] - 1)):
            if held is None or held[i]:
                seabed_support(
                    out[e], x[i], float(work.contact[i]), work.friction[i],
                    float(line.seabed_stiffness[i]), line.seabed_normal,
                    float(line.seabed_offset), tol,
                )  # fmt: skip
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
    [N] (largest and smallest), the touchdown arc length [m] (NaN where no contact) and
    the nodes' highest elevation z [m]. The current period's are arrays the compiled
    step loop updates in place (``element`` (2, n) and ``end`` (2, 2): largest,
    smallest; ``touchdown`` (2,): least, greatest; ``z`` (n + 1,): highest). Keeps the
    last ``keep`` periods (None: folds every period into one)."""

    def __init__(
        self, keep: int | None, element: np.ndarray, ends: np.ndarray, td: float, z: np.ndarray
    ):
        self.keep = keep
        self.periods: deque[list] = deque()
        self.element = np.empty((2, element.size))
        self.end = np.empty((2, 2))
        self.touchdown = np.empty(2)
        self.z = np.empty(z.size)
        self.start(element, ends, td, z)
        self.run = self.current()  # the whole run, folded at every period boundary

    def start(self, element: np.ndarray, ends: np.ndarray, td: float, z: np.ndarray) -> None:
        self.element[:] = element[None, :]
        self.end[:] = ends[None, :]
        self.touchdown[:] = td
        self.z[:] = z

    def add(self, element: np.ndarray, ends: np.ndarray, td: float, z: np.ndarray) -> None:
        """Fold one step's element and end tensions, touchdown point and node
        elevations in (the compiled loop does this itself)."""
        np.maximum(self.element[0], element, out=self.element[0])
        np.minimum(self.element[1], element, out=self.element[1])
        np.maximum(self.end[0], ends, out=self.end[0])
        np.minimum(self.end[1], ends, out=self.end[1])
        self.touchdown[0] = np.fmin(self.touchdown[0], td)
        self.touchdown[1] = np.fmax(self.touchdown[1], td)
        np.maximum(self.z, z, out=self.z)

    def current(self) -> list:
        return [
            self.element[0].copy(),
            self.element[1].copy(),
            self.end[0].copy(),
            self.end[1].copy(),
            float(self.touchdown[0]),
            float(self.touchdown[1]),
            self.z.copy(),
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
            np.max([i[6] for i in items], axis=0),
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
    resampled uniformly at the end (:func:`_resample`); with ``problem.keep_steps``
    also every accepted step's full state (t, x, v, a, the forces on the ends, the
    element tensions and friction forces, and the run's ``extra`` values)."""

    def __init__(self, problem: DynamicProblem, line: DiscreteLine, extra: tuple = ()) -> None:
        self.problem = problem
        self.line = line
        self.points = np.asarray(problem.history_s, dtype=float)
        self.span = (problem.history_periods + 1.0) * problem.period
        self.buf: deque[tuple] = deque()
        keys = ("t", "x", "v", "a", "end_force", "tension", "friction", *extra)
        self.steps = {k: [] for k in keys} if problem.keep_steps else None

    def push(
        self,
        t: float,
        tension: float,
        ends: np.ndarray,
        forces: np.ndarray,
        x: np.ndarray,
        v: np.ndarray,
        a: np.ndarray,
        work: Workspace,
        *extra: np.ndarray,
    ) -> None:
        """One accepted step: ``tension`` [N] at the excited end, ``ends`` [N] (2,) both
        end tensions, ``forces`` [N] (2, 3) the line's on the ends."""
        if self.steps is not None:
            state = (t, x, v, a, forces, work.tension, work.friction, *extra)
            for values, value in zip(self.steps.values(), state, strict=True):
                values.append(np.array(value, copy=True))
        if not self.problem.history:
            return
        xs = interpolate_nodes(self.line.s, self.points, np.stack([x, v, a]))
        whole = (
            (x.copy(), v.copy(), a.copy(), work.tension.copy(), ends.copy())
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


def close_run(
    result: DynamicResult,
    t: float,
    counters: tuple[int, int, int],
    extremes: list,
    hist: _History,
) -> DynamicResult:
    """The end of a run at ``t`` [s] into ``result``: its (steps, Newton iterations,
    rejected steps), periods, the line's ``extremes`` (:meth:`_LineExtremes.window`),
    the resampled history and the step record (``keep_steps``)."""
    result.steps, result.newton_iterations, result.rejected_steps = counters
    result.periods = t / hist.problem.period
    result.simulated_time = t
    (
        result.element_tension_max,
        result.element_tension_min,
        result.end_tension_max,
        result.end_tension_min,
        result.touchdown_min,
        result.touchdown_max,
        result.z_max,
    ) = extremes
    result.history = hist.resampled(t)
    if hist.steps is not None:
        result.record = {k: np.asarray(v) for k, v in hist.steps.items()}
    return result


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
    f_static = end_forces(work, a0, x0, held, line)
    t_static = float(np.linalg.norm(f_static[ex]))
    result = DynamicResult(tension_static=t_static, line_s=line.s)
    result.touchdown_tracked = line.has_seabed
    extremes = _LineExtremes(
        None if problem.duration is not None else max(1, problem.steady_window),
        work.tension,
        np.sqrt(np.sum(f_static**2, 1)),
        touchdown_of(line, x0, problem.touchdown_tolerance),
        x0[:, 2],
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


def out_of_time(result: Any, t: float) -> Any:
    """``result`` (of a line or a system) stopped by the deadline at ``t`` [s]."""
    result.status = STATUS_TIME_LIMIT
    result.message = f"time limit reached at t = {t:.4g} s of the dynamic run"
    return result


def newton_failed(
    result: Any, t: float, h: float, step: float, level: int, counters: tuple[int, int, int]
) -> Any:
    """``result`` (of a line or a system) stopped at ``t`` [s] where Newton failed with
    the step ``h`` [s], the nominal ``step`` halved ``level`` times; its (steps, Newton
    iterations, rejected steps)."""
    result.status = STATUS_NUMERICAL
    result.message = (
        f"Newton did not converge at t = {t:.6g} s with step {h:.3g} s ({step:.3g} s "
        f"halved {level} times)"
    )
    result.steps, result.newton_iterations, result.rejected_steps = counters
    return result


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
