"""The time domain of a line over sliding pulleys (``line.pulleys`` on a catenary line).

Each step is solved together with the split of the line at each pulley
(:func:`.pulley.solve_split`: the line sticks, or slides until the tension ratio is
the friction bound): a trial split re-cuts the line and re-runs the implicit step, so
the step loop stays in Python here, calling the compiled step
(:func:`.alpha_step.alpha_step`) per trial; a line without pulleys runs the compiled
loop of :func:`.timedomain.simulate`. Same step control, statistics and outputs.
"""

from __future__ import annotations

import math
import time

import numpy as np

from .alpha_step import AlphaParameters, alpha_step
from .assembly import Workspace, update_anchors
from .discrete_line import DiscreteLine, interpolate_nodes
from .pulley import SlidingPulleys, pulley_tensions, solve_split, wrap_angle
from .step_parts import predict_positions
from .time_problem import (
    NEWTON_RESCUE_HALVINGS,
    DynamicProblem,
    DynamicResult,
    _History,
    _start,
    close_run,
    end_forces,
    newton_failed,
    out_of_time,
    touchdown_of,
    window_statistics,
)


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
        its, ok = alpha_step(*head[:13], cap, pred, *head[15:], trial.kernel_args(), *tail)
        iterations += its
        if not ok:
            return None
        last[:] = [(trial.s, x1.copy())]
        return pulley_tensions(trial, x1, work.tension, node), wrap_angle(x1, node)

    found, new_dir = solve_split(
        at_split, sliding, split, tol, predicted=predicted, direction=direction
    )
    if found is None:
        return None, direction, None, iterations
    return found, new_dir, trials[found.tobytes()], iterations


def simulate_sliding(problem: DynamicProblem, *, deadline: float | None = None) -> DynamicResult:
    """Integrate until steady state (or ``max_periods``, or ``duration``).

    A numerical failure (Newton failing at the smallest step) is returned as a result
    with nonzero status and a message; the deadline (a :func:`time.monotonic` value)
    gives :data:`STATUS_TIME_LIMIT`.
    """
    line = problem.line
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
    td_tol = problem.touchdown_tolerance

    T = problem.period
    t_ramp = problem.motion.ramp_time
    t_stop = problem.duration if problem.duration is not None else problem.max_periods * T
    tol = problem.newton_tolerance
    max_level = problem.max_refinement
    eps_t = 1e-9 * T

    hist = _History(problem, line, extra=("split",))
    sliding = problem.pulleys
    split = sliding.split.copy()
    slide_rate = np.zeros_like(split)  # [m/s] of the last step
    slide_dir = np.zeros_like(split)  # +1 / -1 sliding out / in in the last step, 0 stuck
    # interior held nodes (pulleys) stay where the static state has them
    inner_held = np.nonzero(held[1:-1])[0] + 1

    def push(t: float, tension: float, ends: np.ndarray, forces: np.ndarray) -> None:
        hist.push(t, tension, ends, forces, x0, v0, a0, work, split)

    push(0.0, t_static, np.sqrt(np.sum(f_static**2, 1)), f_static)

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
    # large spurious stretches (:func:`.step_parts.predict_positions`, as the compiled
    # step loop's, from the last ``npast`` accepted positions ``past_x`` at ``past_t``).
    past_x = np.zeros((2, *x0.shape))
    past_t = np.zeros(2)
    npast = 0
    frac = (line.s / line.s[-1])[:, None]
    x_pred = np.empty_like(x0)

    t = 0.0
    level = 0
    clean = 0
    next_b = min(T, t_stop)
    steps = newton = rejected = 0
    converged = False
    while True:
        if deadline is not None and steps % 64 == 0 and time.monotonic() > deadline:
            return out_of_time(result, t)
        h = problem.step / 2**level
        if next_b - t <= h * (1.0 + 1e-6):
            h = next_b - t
        disp, vel, acc = problem.motion.at(t + h)
        predict_positions(x0, v0, past_x, past_t, npast, t, t + h, x_pred)
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
        tail = (wargs, sargs)
        new_line, new_split = line, split
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
                return newton_failed(result, t, h, problem.step, level, (steps, newton, rejected))
            level += 1
            clean = 0
            continue
        switched = bool(np.any((work.strain > 0.0) != (strain_prev > 0.0)))
        forces = end_forces(work, a1, x1, held, new_line)
        tension = float(math.sqrt(forces[ex] @ forces[ex]))
        steep = abs(tension - t_prev_tension) > problem.tension_step
        if (switched or steep) and level < max_level:
            rejected += 1
            level += 1
            clean = 0
            continue
        # accept
        steps += 1
        slide_rate = (new_split - split) / h
        slide_dir = new_dir
        if new_line is not line:
            line, split = new_line, new_split
            np.minimum(c_split[0], split, out=c_split[0])
            np.maximum(c_split[1], split, out=c_split[1])
        if line.has_seabed:
            update_anchors(x1, work.friction, line.seabed_stiffness, work.contact, work.anchor)
        if npast == 2:  # the older of the two goes
            past_x[0] = past_x[1]
            past_t[0] = past_t[1]
        past_x[min(npast, 1)] = x0
        past_t[min(npast, 1)] = t
        npast = min(npast + 1, 2)
        t += h
        x0, x1 = x1, x0
        v0, v1 = v1, v0
        a0, a1 = a1, a0
        F0[:] = work.F
        strain_prev[:] = work.strain
        end_tensions = np.sqrt(np.sum(forces**2, 1))
        line_max = max(float(work.tension.max()), float(end_tensions.max()))
        extremes.add(work.tension, end_tensions, touchdown_of(line, x0, td_tol), x0[:, 2])
        c_max = max(c_max, tension)
        c_min = min(c_min, tension)
        c_int += 0.5 * (t_prev_tension + tension) * h
        c_line = max(c_line, line_max)
        t_prev_tension = tension
        push(t, tension, end_tensions, forces)
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
            extremes.start(work.tension, end_tensions, touchdown_of(line, x0, td_tol), x0[:, 2])
            c_max = c_min = tension
            c_line = line_max
            c_int = 0.0
            c_start = t
            if problem.duration is None:
                converged = problem.settled(p_max, p_min, problem.line.n_nodes)
            if converged or t >= t_stop - eps_t:
                break
            next_b = min(next_b + T, t_stop)

    sl = window_statistics(
        result,
        problem,
        (p_max, p_min, p_mean, p_line),
        (c_max, c_min, c_int / max(t - c_start, 1e-300), c_line),
    )
    result.steady_converged = converged
    kept = p_split[sl] if p_split else [c_split]
    result.split_min = np.min([k[0] for k in kept], axis=0)
    result.split_max = np.max([k[1] for k in kept], axis=0)
    result.line_s = line.s
    return close_run(result, t, (steps, newton, rejected), extremes.window(), hist)
