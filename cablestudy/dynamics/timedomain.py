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
  tensions), resampled uniformly over the last periods.

Pure: arrays in, a :class:`DynamicResult` out (status, message, counters).
"""

from __future__ import annotations

import math
import time
from collections import deque
from dataclasses import dataclass, field

import numpy as np

from ..physics.seabed import touchdown_arc_length
from ..statics.base import STATUS_NUMERICAL, STATUS_OK, STATUS_TIME_LIMIT
from .excitation import EndMotion
from .integrator import AlphaParameters, alpha_step
from .model import DiscreteLine, Workspace, evaluate, interpolate_nodes, update_anchors
from .pulley import SlidingPulleys, pulley_tensions, solve_split, wrap_angle

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
    #: pulleys the line slides over (:mod:`.pulley`; None: none)
    pulleys: SlidingPulleys | None = None


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
    """

    status: int = STATUS_OK
    message: str = ""
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
    #: with pulleys: the range [m] of each pulley's arc length from A over the window
    split_min: np.ndarray = field(default_factory=lambda: np.zeros(0))
    split_max: np.ndarray = field(default_factory=lambda: np.zeros(0))
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
    Keeps the last ``keep`` periods (None: folds every period into one)."""

    def __init__(self, keep: int | None, element: np.ndarray, ends: np.ndarray, td: float):
        self.keep = keep
        self.periods: deque[list] = deque()
        self.start(element, ends, td)

    def start(self, element: np.ndarray, ends: np.ndarray, td: float) -> None:
        self.current = [element.copy(), element.copy(), ends.copy(), ends.copy(), td, td]

    def add(self, element: np.ndarray, ends: np.ndarray, td: float) -> None:
        c = self.current
        np.maximum(c[0], element, out=c[0])
        np.minimum(c[1], element, out=c[1])
        np.maximum(c[2], ends, out=c[2])
        np.minimum(c[3], ends, out=c[3])
        c[4] = float(np.fmin(c[4], td))
        c[5] = float(np.fmax(c[5], td))

    def close(self) -> None:
        """The current period is one of the steady-state periods: keep it."""
        self.periods.append(self.current)
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

    def window(self) -> list:
        """Extremes over the kept periods (the current partial one if none closed)."""
        return self._fold(list(self.periods) or [self.current])


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


def _advance(head: tuple, line_args: tuple, tail: tuple) -> int:
    """One implicit step (:func:`.integrator.alpha_step`): its Newton iterations, or
    -1 - iterations when it failed."""
    its, ok = alpha_step(*head, *line_args, *tail)
    return its if ok else -1 - its


def _slide(
    sliding: SlidingPulleys,
    split: np.ndarray,
    direction: np.ndarray,
    predicted: np.ndarray,
    head: tuple,
    tail: tuple,
    work: Workspace,
    x1: np.ndarray,
    tol: float,
) -> tuple[np.ndarray | None, np.ndarray, DiscreteLine | None, int]:
    """The step solved with its split (:func:`.pulley.solve_split`: stick, or slide to
    the friction bound): (the split [m] or None when it failed, the slide directions,
    the line cut at that split, the Newton iterations). The state in ``work`` and
    ``x1`` is that of the returned split."""
    trials: dict[bytes, DiscreteLine] = {}
    node = sliding.node
    iterations = 0
    x_pred = head[14]
    # a trial split changes every element's rest length on both sides of a pulley:
    # Newton starts from the last solved trial's shape with the nodes moved along it to
    # their new arc lengths (the material slides along the line); more iterations are
    # allowed than for a fixed mesh, as a split far from the last one re-stretches the
    # sub-lines
    last: list[tuple[np.ndarray, np.ndarray]] = []
    cap = max(4 * head[13], 40)

    def at_split(S: np.ndarray) -> tuple | None:
        nonlocal iterations
        key = S.tobytes()
        if key not in trials:
            trials[key] = sliding.rebuild(S)
        trial = trials[key]
        if last:
            pred = interpolate_nodes(last[0][0], trial.s, last[0][1][None])[0]
            pred[node] = x_pred[node]
        else:
            pred = x_pred
        got = _advance((*head[:13], cap, pred, *head[15:]), trial.kernel_args(), tail)
        iterations += got if got >= 0 else -1 - got
        if got < 0:
            return None
        last[:] = [(trial.s, x1.copy())]
        return pulley_tensions(trial, x1, work.tension, node), wrap_angle(x1, node)

    found, new_dir = solve_split(
        at_split, sliding, split, tol, predicted=predicted, direction=direction
    )
    if found is None:
        return None, direction, None, iterations
    return found, new_dir, trials[found.tobytes()], iterations


def simulate(problem: DynamicProblem, *, deadline: float | None = None) -> DynamicResult:
    """Integrate until steady state (or ``max_periods``, or ``duration``).

    A numerical failure (Newton failing at the smallest step) is returned as a result
    with nonzero status and a message; the deadline (a :func:`time.monotonic` value)
    gives :data:`STATUS_TIME_LIMIT`.
    """
    line = problem.line
    par = AlphaParameters.from_spectral_radius(problem.spectral_radius)
    work = Workspace(line.n_elements)
    largs = line.kernel_args()
    wargs = work.assemble_args()
    sargs = work.solver_args(line)
    held = line.held
    seabed = line.has_seabed

    x0 = np.array(problem.static_position, dtype=float, copy=True)
    v0 = np.zeros_like(x0)
    a0 = np.zeros_like(x0)
    x1, v1, a1 = x0.copy(), v0.copy(), a0.copy()
    anchor0 = problem.anchor if problem.anchor is not None else x0
    evaluate(line, x0, v0, work, anchor=anchor0)
    F0 = work.F.copy()
    strain_prev = work.strain.copy()
    base = np.stack([x0[0], x0[-1]])
    ex = problem.excited_end
    f_static = end_forces(work, a0, x0, held)
    t_static = float(np.linalg.norm(f_static[ex]))
    result = DynamicResult(tension_static=t_static, line_s=line.s)

    has_seabed = line.has_seabed
    result.touchdown_tracked = has_seabed
    flat = bool(line.seabed_normal[0] == 0.0 and line.seabed_normal[1] == 0.0)

    def touchdown(x: np.ndarray) -> float:
        """Arc length [m] where the line leaves the seabed plane (NaN: no contact)."""
        if not has_seabed:
            return math.nan
        n = line.seabed_normal
        if flat:
            bed: np.ndarray | float = line.seabed_offset / n[2]
        else:
            bed = (line.seabed_offset - n[0] * x[:, 0] - n[1] * x[:, 1]) / n[2]
        return touchdown_arc_length(line.s, x[:, 2], bed, problem.touchdown_tolerance)

    extremes = _LineExtremes(
        None if problem.duration is not None else max(1, problem.steady_window),
        work.tension,
        np.sqrt(np.sum(f_static**2, 1)),
        touchdown(x0),
    )

    T = problem.period
    t_ramp = problem.motion.ramp_time
    t_stop = problem.duration if problem.duration is not None else problem.max_periods * T
    tol = problem.newton_tolerance
    max_level = problem.max_refinement
    eps_t = 1e-9 * T

    # history buffer: (t, end tension, x, v, a at the history points, and with
    # history_line: x, v, a of every node, element tensions, end tensions)
    hs = np.asarray(problem.history_s, dtype=float)
    keep_hist = problem.history
    hist_span = (problem.history_periods + 1.0) * T
    buf: deque[tuple] = deque()

    def push(t: float, tension: float, ends: np.ndarray) -> None:
        if not keep_hist:
            return
        xs = interpolate_nodes(line.s, hs, np.stack([x0, v0, a0]))
        whole = (
            (x0.copy(), v0.copy(), a0.copy(), work.tension.copy(), ends.copy())
            if problem.history_line
            else ()
        )
        buf.append((t, tension, xs[0], xs[1], xs[2], *whole))
        while len(buf) > 2 and buf[1][0] < t - hist_span:
            buf.popleft()

    rec: dict[str, list[np.ndarray]] = {
        k: [] for k in ("t", "x", "v", "a", "end_force", "tension", "friction", "split")
    }
    sliding = problem.pulleys
    split = sliding.split.copy() if sliding is not None else np.zeros(0)
    slide_rate = np.zeros_like(split)  # [m/s] of the last step
    slide_dir = np.zeros_like(split)  # +1 / -1 sliding out / in in the last step, 0 stuck
    # interior held nodes (pulleys) stay where the static state has them
    inner_held = np.nonzero(held[1:-1])[0] + 1

    def keep(t: float, forces: np.ndarray) -> None:
        if problem.keep_steps:
            rec["t"].append(np.asarray(t))
            rec["x"].append(x0.copy())
            rec["v"].append(v0.copy())
            rec["a"].append(a0.copy())
            rec["end_force"].append(forces.copy())
            rec["tension"].append(work.tension.copy())
            rec["friction"].append(work.friction.copy())
            rec["split"].append(split.copy())

    keep(0.0, f_static)
    push(0.0, t_static, np.sqrt(np.sum(f_static**2, 1)))

    # per-period statistics (periods starting after the ramp only)
    p_max: list[float] = []
    p_min: list[float] = []
    p_mean: list[float] = []
    p_line: list[float] = []
    c_max = c_min = t_static
    c_int = 0.0
    c_line = max(t_static, float(work.tension.max()))
    c_start = 0.0
    t_prev_tension = t_static
    c_split = [split.copy(), split.copy()]
    p_split: list[list[np.ndarray]] = []

    # Newton starts from a quadratic extrapolation of the last three positions: the
    # positions are smooth, whereas the accelerations of generalised-alpha carry the
    # decaying unresolved axial modes, which a Taylor predictor would amplify into
    # large spurious stretches.
    past: deque[tuple[float, np.ndarray]] = deque()
    frac = (line.s / line.s[-1])[:, None]
    x_pred = np.empty_like(x0)

    def predict(t_new: float, out: np.ndarray) -> None:
        if len(past) < 2:
            np.add(x0, (t_new - t) * v0, out=out)
            return
        (ta, xa), (tb, xb) = past[0], past[1]
        tc = t
        la = (t_new - tb) * (t_new - tc) / ((ta - tb) * (ta - tc))
        lb = (t_new - ta) * (t_new - tc) / ((tb - ta) * (tb - tc))
        lc = (t_new - ta) * (t_new - tb) / ((tc - ta) * (tc - tb))
        np.multiply(xa, la, out=out)
        out += lb * xb
        out += lc * x0

    t = 0.0
    level = 0
    clean = 0
    next_b = min(T, t_stop)
    steps = newton = rejected = 0
    converged = False
    while True:
        if deadline is not None and steps % 64 == 0 and time.monotonic() > deadline:
            result.status, result.message = (
                STATUS_TIME_LIMIT,
                (f"time limit reached at t = {t:.4g} s of the dynamic run"),
            )
            return result
        h = problem.step / 2**level
        if next_b - t <= h * (1.0 + 1e-6):
            h = next_b - t
        disp, vel, acc = problem.motion.at(t + h)
        predict(t + h, x_pred)
        np.greater(strain_prev, 0.0, out=work.taut0)
        # move the whole line with the ends' prescribed correction, shared linearly
        # along s, so that the predictor neither stretches nor compresses the end
        # elements
        if held[0]:
            x_pred += (1.0 - frac) * (base[0] + disp[0] - x_pred[0])[None, :]
            x_pred[0] = base[0] + disp[0]
        if held[-1]:
            x_pred += frac * (base[1] + disp[1] - x_pred[-1])[None, :]
            x_pred[-1] = base[1] + disp[1]
        if inner_held.size:
            x_pred[inner_held] = problem.static_position[inner_held]

        head = (
            x0,
            v0,
            a0,
            F0,
            h,
            base + disp,
            vel,
            acc,
            par.alpha_m,
            par.alpha_f,
            par.beta,
            par.gamma,
            tol,
            problem.max_newton_iterations,
            x_pred,
            x1,
            v1,
            a1,
            work.anchor,
        )
        tail = (*wargs, *sargs)
        new_line, new_split = line, split
        if sliding is None:
            its = _advance(head, largs, tail)
            ok = its >= 0
            newton += its if ok else -1 - its
        else:
            # the step with its split: stick, or slide to the friction bound
            found, new_dir, got_line, its = _slide(
                sliding, split, slide_dir, slide_rate * h, head, tail, work, x1, tol
            )
            newton += its
            ok = found is not None
            if found is not None and got_line is not None:
                new_split, new_line = found, got_line
        if not ok:
            rejected += 1
            if level >= max_level + NEWTON_RESCUE_HALVINGS:
                result.status = STATUS_NUMERICAL
                result.message = (
                    f"Newton did not converge at t = {t:.6g} s with step "
                    f"{h:.3g} s ({problem.step:.3g} s halved {level} times)"
                )
                result.steps, result.newton_iterations = steps, newton
                result.rejected_steps = rejected
                return result
            level += 1
            clean = 0
            continue
        switched = bool(np.any((work.strain > 0.0) != (strain_prev > 0.0)))
        forces = end_forces(work, a1, x1, held)
        tension = float(math.sqrt(forces[ex] @ forces[ex]))
        steep = abs(tension - t_prev_tension) > problem.tension_step
        if (switched or steep) and level < max_level:
            rejected += 1
            level += 1
            clean = 0
            continue
        # accept
        steps += 1
        if sliding is not None:
            slide_rate = (new_split - split) / h
            slide_dir = new_dir
        if new_line is not line:
            line, split = new_line, new_split
            largs = line.kernel_args()
            np.minimum(c_split[0], split, out=c_split[0])
            np.maximum(c_split[1], split, out=c_split[1])
        if seabed:
            update_anchors(x1, work.friction, line.seabed_stiffness, work.contact, work.anchor)
        past.append((t, x0.copy()))
        if len(past) > 2:
            past.popleft()
        t += h
        x0, x1 = x1, x0
        v0, v1 = v1, v0
        a0, a1 = a1, a0
        F0[:] = work.F
        strain_prev[:] = work.strain
        end_tensions = np.sqrt(np.sum(forces**2, 1))
        line_max = max(float(work.tension.max()), float(end_tensions.max()))
        extremes.add(work.tension, end_tensions, touchdown(x0))
        c_max = max(c_max, tension)
        c_min = min(c_min, tension)
        c_int += 0.5 * (t_prev_tension + tension) * h
        c_line = max(c_line, line_max)
        t_prev_tension = tension
        keep(t, forces)
        push(t, tension, end_tensions)
        if switched or steep:
            clean = 0
        else:
            clean += 1
            if clean >= 2 and level > 0:
                level -= 1
                clean = 0
        if abs(t - next_b) <= eps_t:
            t = next_b
            if c_start >= t_ramp - eps_t:
                p_max.append(c_max)
                p_min.append(c_min)
                p_mean.append(c_int / max(t - c_start, 1e-300))
                p_line.append(c_line)
                p_split.append(c_split)
                extremes.close()
            c_split = [split.copy(), split.copy()]
            extremes.start(work.tension, end_tensions, touchdown(x0))
            c_max = c_min = tension
            c_line = line_max
            c_int = 0.0
            c_start = t
            if problem.duration is None:
                w = problem.steady_window
                if len(p_max) >= max(problem.min_periods, w + 1):
                    converged = all(
                        abs(p_max[-j] - p_max[-j - 1]) <= problem.steady_tolerance * p_max[-j]
                        and abs(p_min[-j] - p_min[-j - 1]) <= problem.steady_tolerance * p_max[-j]
                        for j in range(1, w + 1)
                    )
            if converged or t >= t_stop - eps_t:
                break
            next_b = min(next_b + T, t_stop)

    w = max(1, problem.steady_window) if problem.duration is None else len(p_max)
    if not p_max:  # the run ended inside the ramp: use the last (partial) window
        p_max, p_min, p_line = [c_max], [c_min], [c_line]
        p_mean = [c_int / max(t - c_start, 1e-300)]
    sl = slice(-min(w, len(p_max)), None)
    sp = slice(-min(w + 1, len(p_max)), None)
    result.tension_max = max(p_max[sl])
    result.tension_min = min(p_min[sl])
    result.tension_mean = float(np.mean(p_mean[sl]))
    result.tension_max_line = max(p_line[sl])
    result.tension_max_spread = max(p_max[sp]) - min(p_max[sp])
    result.tension_min_spread = max(p_min[sp]) - min(p_min[sp])
    result.steady_converged = converged
    if sliding is not None:
        kept = p_split[sl] if p_split else [c_split]
        result.split_min = np.min([k[0] for k in kept], axis=0)
        result.split_max = np.max([k[1] for k in kept], axis=0)
    result.line_s = line.s
    result.steps, result.newton_iterations, result.rejected_steps = steps, newton, rejected
    result.periods = t / T
    result.simulated_time = t
    result.period_max = np.asarray(p_max)
    result.period_min = np.asarray(p_min)
    (
        result.element_tension_max,
        result.element_tension_min,
        result.end_tension_max,
        result.end_tension_min,
        result.touchdown_min,
        result.touchdown_max,
    ) = extremes.window()
    if keep_hist and len(buf) >= 2:
        result.history = _resample(
            buf, t, T, problem, interpolate_nodes(line.s, hs, problem.static_position[None])[0]
        )
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
