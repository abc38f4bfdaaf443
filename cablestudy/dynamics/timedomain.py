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
  than ``steady_tolerance`` times the period's dynamic range over ``steady_window``
  consecutive periods (steady state, :mod:`.steady`), or after ``max_periods`` periods (not
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
from collections.abc import Callable
from dataclasses import replace

import numpy as np

from ..statics.base import STATUS_NUMERICAL
from .alpha_step import AlphaParameters
from .assembly import evaluate
from .discrete_line import DiscreteLine
from .integrator import NEWTON_FAILED, PARTED, REACHED_BOUNDARY, STEP_BUDGET, WINCH_LIMIT, march
from .step_check import failed_warning, restore, snapshot, step_warning, verdict_of
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
    window_statistics,
)


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

    def push(t: float, tension: float, ends: np.ndarray, forces: np.ndarray) -> None:
        hist.push(t, tension, ends, forces, x0, v0, a0, work)

    push(0.0, t_static, np.sqrt(np.sum(f_static**2, 1)), f_static)

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
    st_i = np.zeros(10, dtype=np.int64)
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
        f = end_forces(work, a0, x0, held, line)
        forces[:] = f
        ends[:] = np.sqrt(np.sum(f**2, 1))
        st_f[6] = float(ends[ex])
        st_f[2] = max(st_f[2], st_f[6])
        st_f[3] = min(st_f[3], st_f[6])
        np.minimum(extremes.element[1], work.tension, out=extremes.element[1])
        np.minimum(extremes.end[1], ends, out=extremes.end[1])

    def run_march(step: float, single: bool, budget: int) -> int:
        """The compiled step loop from the state in the arrays, at base ``step``."""
        return march(
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
            extremes.z,
            line.s,
            problem.touchdown_tolerance,
            step,
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

    # the step check (:mod:`.step_check`): the state at the start of each period, and
    # the end tensions' extremes (max, min; ends A, B) of the last period closed
    checking = problem.step_tolerance is not None
    state = {
        "x0": x0, "v0": v0, "a0": a0, "x1": x1, "v1": v1, "a1": a1, "F0": F0,
        "strain_prev": strain_prev, "tension_prev": tension_prev, "past_x": past_x,
        "past_t": past_t, "st_f": st_f, "st_i": st_i, "ends": ends, "forces": forces,
        "ext_element": extremes.element, "ext_end": extremes.end,
        "ext_touchdown": extremes.touchdown, "ext_z": extremes.z,
        **{f"work_{k}": v for k, v in vars(work).items() if isinstance(v, np.ndarray)},
    }  # fmt: skip
    period_start = snapshot(state) if checking else None
    last_end = extremes.end.copy()
    converged = False
    while True:
        if deadline is not None and time.monotonic() > deadline:
            return out_of_time(result, st_f[0])
        code = run_march(problem.step, single, budget)
        t = float(st_f[0])
        if code == NEWTON_FAILED:
            counters = (int(st_i[2]), int(st_i[3]), int(st_i[4]))
            return newton_failed(result, t, st_f[9], problem.step, int(st_i[0]), counters)
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
            push(t, float(st_f[6]), ends, forces)
        if code == PARTED:
            part_restart()
            if single:
                push(t, float(st_f[6]), ends, forces)
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
        last_end[:] = extremes.end
        extremes.start(work.tension, ends, float(st_f[8]), x0[:, 2])
        st_f[2] = st_f[3] = tension
        st_f[4] = 0.0
        st_f[5] = st_f[7]
        c_start = t
        # steady state: not after a break (the parted line has no periodic state to
        # settle on) nor while a winch runs (the periods must start after it stops)
        if problem.duration is None and st_i[6] == 0:
            w = problem.steady_window
            if not winching or t - (w + 1) * T >= problem.winch_stop - eps_t:
                converged = problem.settled(p_max, p_min, problem.line.n_nodes)
        if converged or final:
            break
        st_f[1] = min(st_f[1] + T, t_stop)
        if checking:
            period_start = snapshot(state)

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
    result.winch_paid_out = problem.paid_out(t)
    close_run(result, t, (steps, newton, rejected), extremes.window(broke), hist)
    if checking and not broke:
        _check_step(problem, result, state, period_start, last_end, run_march, deadline)
    return result


def _check_step(  # noqa: PLR0913
    problem: DynamicProblem,
    result: DynamicResult,
    state: dict[str, np.ndarray],
    start: dict[str, np.ndarray],
    coarse: np.ndarray,
    run_march: Callable[[float, bool, int], int],
    deadline: float | None,
) -> None:
    """The step check of :mod:`.step_check` on a finished run: when its last period
    (from the saved ``start`` to now) had seabed landings or lift-offs or slack-taut
    switches, that period again from ``start`` at half the step (the run's arrays
    ``state`` are overwritten: the results are already out), its end tensions' extremes
    against the run's ``coarse`` ones (2, 2) (max, min; ends A, B), into
    ``result.step_check`` and ``result.step_warning``."""
    contacts = int(state["st_i"][8] - start["st_i"][8])
    switches = int(state["st_i"][9] - start["st_i"][9])
    if contacts == 0 and switches == 0:
        return
    restore(state, start)
    st_f = state["st_f"]
    p = problem.steps_per_period
    code = STEP_BUDGET
    while code == STEP_BUDGET:
        if deadline is not None and time.monotonic() > deadline:
            result.step_warning = failed_warning("time limit reached", p)
            return
        code = run_march(problem.step * problem.step_check_factor, False, 256)
    if code != REACHED_BOUNDARY:
        why = {NEWTON_FAILED: "Newton did not converge", PARTED: "the line parted"}
        what = why.get(code, "the winch left its bounds")
        result.step_warning = failed_warning(f"{what} at t = {float(st_f[0]):.6g} s", p)
        return
    fine = state["ext_end"]
    verdict = verdict_of(
        coarse.T,
        fine.T,
        coarse[0] - coarse[1],
        names=("end A", "end B"),
        step_tolerance=float(problem.step_tolerance),  # type: ignore[arg-type]
        floor=problem.newton_tolerance * math.sqrt(problem.line.n_nodes),
        contact_changes=contacts,
        slack_switches=switches,
        points_per_period=p,
        factor=problem.step_check_factor,
    )
    result.step_check = verdict
    result.step_warning = step_warning(verdict)


def warm_up() -> None:
    """Load the compiled kernels of the time step (the line model's forces and tangents,
    the banded solve, the discrete statics, the friction anchors, the end motion) on a
    two-element line above a seabed, so that a process forked afterwards has them: a
    kernel's first call in a process costs about a second, which is start-up, not the
    cost of a case."""
    from ..statics.base import LineModel, Medium
    from .discrete_line import DynamicExtras, discretise
    from .excitation import EndMotion
    from .model import static_equilibrium

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
