"""Steady periodic response of a mooring system to prescribed body and point motion.

All lines and free points are integrated together (:mod:`.system_march`): the single
line's generalised-alpha step with Newton, the Jacobian banded per line and the free
points coupling the lines through a bordered (Schur complement) solve. The run starts at
rest in the discrete static equilibrium of the system model (:func:`equilibrium`),
steps at ``step`` landing on period boundaries, and stops when the watched line ends'
tensions have settled: the per-period maximum and minimum of each changed by at most
``steady_tolerance`` times that end's dynamic range in the period (or the Newton
tolerance; :mod:`.steady`, the single line's rule) over ``steady_window`` consecutive
periods (or after ``max_periods``; with ``duration`` it runs that long and the
statistics cover every period after the ramp, as for a single line).

The watched ends (:func:`watched_ends`) are every line end; in a system of one line
(no free points) whose motion moves one of its ends, that end alone: the single line's
excited end, so that the steady-state test and the step control's tension test take
the one-line study's decisions and a system of one line reproduces it bit for bit.

Pure: arrays in, a :class:`SystemDynamicResult` out (status, message, counters).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..statics.base import STATUS_OK
from .alpha_step import AlphaParameters
from .model import static_equilibrium
from .step_check import failed_warning, restore, snapshot, step_warning, verdict_of
from .system_kernels import assemble_all, point_forces
from .system_march import (
    ACCEPTED,
    BOUNDARY,
    FAILED,
    end_forces,
    set_drives,
    system_march,
    system_static,
)
from .system_model import Drives, PackedSystem, SlotMotion, work_arrays
from .time_problem import NEWTON_RESCUE_HALVINGS, MarchSettings, newton_failed, out_of_time


@dataclass(frozen=True, kw_only=True)
class SystemProblem(MarchSettings):
    """A time-domain run of a system: the packed lines, the static state and friction
    anchors it starts from, the drives and their motion, and the settings of
    :class:`.time_problem.MarchSettings` (which mean the same as for a line)."""

    packed: PackedSystem
    static_position: np.ndarray
    anchor: np.ndarray
    drives: Drives
    motion: SlotMotion
    #: the lines' names (the step check's warning; empty: numbered)
    line_names: tuple[str, ...] = ()


@dataclass(kw_only=True)
class SystemDynamicResult:
    """Outcome of :func:`simulate_system` over the steady window: end tensions [N]
    (L, 2) (max, min, mean; ends A, B), element tensions (E,) packed line after line,
    body forces and moments (B, 6) (max, min); the nodes' highest elevation [m] (N,)
    packed line after line."""

    status: int = STATUS_OK
    message: str = ""
    end_max: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))
    end_min: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))
    end_mean: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))
    element_max: np.ndarray = field(default_factory=lambda: np.zeros(0))
    element_min: np.ndarray = field(default_factory=lambda: np.zeros(0))
    z_max: np.ndarray = field(default_factory=lambda: np.zeros(0))
    body_max: np.ndarray = field(default_factory=lambda: np.zeros((0, 6)))
    body_min: np.ndarray = field(default_factory=lambda: np.zeros((0, 6)))
    steady_converged: bool = False
    steps: int = 0
    newton_iterations: int = 0
    rejected_steps: int = 0
    periods: float = 0.0
    history: dict[str, np.ndarray] | None = None
    #: the step check's verdict (:mod:`.step_check`; None: not run) and warning
    step_check: Any = None
    step_warning: str = ""


def equilibrium(
    packed: PackedSystem,
    start: np.ndarray,
    *,
    tolerance: np.ndarray,
    fallback_tension: list[np.ndarray] | None = None,
    max_iterations: int = 200,
) -> tuple[np.ndarray, np.ndarray, str]:
    """Discrete static equilibrium of the system model from ``start`` [m] (N, 3) (the
    continuous statics at the nodes). First each line on its own, its ends where the
    continuous statics put them: the single line's :func:`.model.static_equilibrium`
    (its seabed seating, friction anchors and fallbacks; so that a system of one line
    starts exactly where the one-line study does). Then, with free points, the coupled
    Newton (:func:`.system_march.system_static`) moves the junctions to the discrete
    model's own balance, from that near start. ``tolerance`` [N] (L,) per line;
    ``fallback_tension`` [N] per line (n,) the continuous statics' element tensions,
    from which a stiff line's Newton restarts on positions and tensions. Returns
    positions, friction anchors and an error message ("" when found)."""
    x = np.array(start, dtype=float, copy=True)
    anchor = x.copy()
    for l, ln in enumerate(packed.lines):  # noqa: E741
        sl = slice(packed.no[l], packed.no[l + 1])
        xl, its, res, ok, anc = static_equilibrium(
            ln,
            start[sl],
            tolerance=tolerance[l],
            max_iterations=max_iterations,
            fallback_tension=None if fallback_tension is None else fallback_tension[l],
        )
        if not ok:
            return (
                x,
                anchor,
                (
                    f"the discrete static equilibrium of line {l} did not converge ({its} "
                    f"iterations, residual {res:.3g} N)"
                ),
            )
        x[sl], anchor[sl] = xl, anc
    if packed.n_points == 0:
        return x, anchor, ""
    v = np.zeros_like(x)
    W = work_arrays(packed, x, v)
    r, dx = np.zeros_like(x), np.zeros_like(x)
    rp = np.zeros((packed.n_points, 3))
    dp, Fp = np.zeros_like(rp), np.zeros_like(rp)
    its, res, ok = system_static(
        x, anchor, packed.S, W, r, rp, dx, dp, Fp, float(np.min(tolerance)), max_iterations,
        packed.lmin,
    )  # fmt: skip
    if not ok:
        return (
            x,
            anchor,
            (
                f"the discrete static equilibrium of the system model did not converge ({its} "
                f"iterations, residual {res:.3g} N)"
            ),
        )
    return x, anchor, ""


def watched_ends(packed: PackedSystem, drives: Drives, motion: SlotMotion) -> np.ndarray:
    """The line ends (L, 2) the steady-state test and the step control's tension test
    look at: all of them, or in a system of one line without free points the one end
    the motion moves (a held end on a moved body, or on a point moved on its own), as
    the single line's excited end. Both ends moved (or neither): all ends."""
    L = len(packed.lines)
    watch = np.ones((L, 2), dtype=np.bool_)
    if L != 1 or packed.n_points != 0:
        return watch
    slots = {int(s) for s in np.asarray(motion.slot).ravel()} | {int(s) for s, _ in motion.tables}
    moved = np.zeros((L, 2), dtype=np.bool_)
    for k in range(packed.he_line.size):
        d = int(packed.he_drive[k])
        b = int(drives.body[d])
        own = int(drives.slot[d])
        if (b >= 0 and (2 * b in slots or 2 * b + 1 in slots)) or (own >= 0 and own in slots):
            moved[packed.he_line[k], packed.he_end[k]] = True
    return moved if int(moved.sum()) == 1 else watch


def simulate_system(
    problem: SystemProblem, *, deadline: float | None = None
) -> SystemDynamicResult:
    """Integrate the system until steady state (or ``max_periods``, or ``duration``).
    A numerical failure is a result with nonzero status and a message."""
    pk = problem.packed
    S = pk.S
    L = len(pk.lines)
    B = problem.drives.body_base.shape[0]
    par = AlphaParameters.from_spectral_radius(problem.spectral_radius)
    x0 = np.array(problem.static_position, dtype=float, copy=True)
    v0, a0 = np.zeros_like(x0), np.zeros_like(x0)
    x1, v1, a1 = x0.copy(), v0.copy(), a0.copy()
    W = work_arrays(pk, x1, v1)
    anchor = np.array(problem.anchor, dtype=float, copy=True)
    assemble_all(x0, v0, anchor, S, W)
    P = pk.n_points
    Fp0 = np.zeros((P, 3))
    point_forces(S, x0, v0, Fp0)
    F0 = W[0].copy()
    strain_prev = W[8].copy()
    forces = np.zeros((L, 2, 3))
    end_forces(S, W, x0, a0, pk.he_node, forces)
    ends_prev = np.sqrt(np.sum(forces**2, axis=2))
    dr = problem.drives
    D = (
        problem.motion.kernel_args(),
        dr.body_base,
        dr.body_R0,
        dr.body,
        dr.slot,
        dr.offset,
        dr.static,
    )
    nD = dr.body.size
    dX, dV, dA = np.zeros((nD, 3)), np.zeros((nD, 3)), np.zeros((nD, 3))
    bx, bR = np.zeros((B, 3)), np.zeros((B, 3, 3))
    body_f = np.zeros((B, 6))
    # the bodies' static forces (drives at t = 0: the static state)
    set_drives(0.0, D, x1.copy(), v1.copy(), a1.copy(), pk.he_node, pk.he_drive, dX, dV, dA, bx, bR)
    from .system_march import body_forces

    body_forces(S, x0, forces, pk.he_line, pk.he_end, pk.he_body, bx, body_f)

    T = problem.period
    t_stop = problem.duration if problem.duration is not None else problem.max_periods * T
    t_ramp = problem.motion.ramp_time
    eps_t = 1e-9 * T
    st_f = np.array([0.0, min(T, t_stop), 0.0])
    st_i = np.zeros(8, dtype=np.int64)
    past_x = np.zeros((2, *x0.shape))
    past_t = np.zeros(2)
    x_pred = np.empty_like(x0)
    r, dx = np.zeros_like(x0), np.zeros_like(x0)
    rp, dp, Fp = np.zeros((P, 3)), np.zeros((P, 3)), np.zeros((P, 3))

    def fresh(ext: tuple[np.ndarray, ...] | None = None) -> tuple[np.ndarray, ...]:
        """A period's extremes started from the state now: into ``ext`` in place (the
        period's record holds copies), or new arrays."""
        if ext is None:
            ext = (np.empty((2, L, 2)), np.empty((L, 2)), np.empty((2, *W[7].shape)),
                   np.empty((2, B, 6)), np.empty(x0.shape[0]))  # fmt: skip
        ext[0][:], ext[1][:], ext[2][:], ext[3][:] = ends_prev, 0.0, W[7], body_f
        ext[4][:] = x0[:, 2]
        return ext

    ext_end, int_end, ext_el, ext_body, ext_z = ext = fresh()
    periods: list[tuple[np.ndarray, ...]] = []
    hist_t: list[float] = [0.0]
    hist_f: list[np.ndarray] = [ends_prev.copy()]
    single = problem.history
    # one step at a time for the history; with a deadline, back every 64 steps to check it
    budget = 1 if single else (64 if deadline is not None else 2**62)
    result = SystemDynamicResult()
    c_start = 0.0
    converged = False
    lmin = pk.lmin
    watch = watched_ends(pk, dr, problem.motion)

    def run_march(step: float, budget: int, ext: tuple[np.ndarray, ...]) -> int:
        """The compiled step loop from the state in the arrays, at base ``step``, its
        extremes into ``ext`` (end, integral, element, body, z)."""
        return system_march(
            st_f, st_i, x0, v0, a0, F0, Fp0, x1, v1, a1, x_pred, past_x, past_t, pk.frac,
            strain_prev, D, pk.he_node, pk.he_drive, pk.he_line, pk.he_end, pk.he_body,
            dX, dV, dA, bx, bR, forces, ends_prev, *ext, body_f, watch,
            step, problem.max_refinement,
            problem.max_refinement + NEWTON_RESCUE_HALVINGS, problem.tension_step,
            par.alpha_m, par.alpha_f, par.beta, par.gamma, problem.newton_tolerance,
            problem.max_newton_iterations, budget, anchor, S, W, r, rp, dx, dp, Fp, lmin, eps_t,
        )  # fmt: skip

    # the step check (:mod:`.step_check`): the state at the start of each period, copied
    # into the same saved arrays each period; the kernels' scratch (W[14:]: the Newton
    # solve's blocks and factors, the assembly's element scratch, aliases of x1 and v1)
    # is written before it is read in every step, so it is no state
    checking = problem.step_tolerance is not None
    state = {
        "x0": x0, "v0": v0, "a0": a0, "F0": F0, "Fp0": Fp0, "x1": x1, "v1": v1, "a1": a1,
        "past_x": past_x, "past_t": past_t, "strain_prev": strain_prev, "anchor": anchor,
        "forces": forces, "ends_prev": ends_prev, "body_f": body_f, "st_f": st_f,
        "st_i": st_i, "Fp": Fp, **{f"W{k}": w for k, w in enumerate(W[:14])},
    }  # fmt: skip
    period_start = snapshot(state) if checking else None
    nodes = max(ln.n_nodes for ln in pk.lines)  # the steady test's floor: the most nodes
    while True:
        if deadline is not None and time.monotonic() > deadline:
            return out_of_time(result, st_f[0])
        code = run_march(problem.step, budget, ext)
        t = float(st_f[0])
        if code == FAILED:
            counters = (int(st_i[2]), int(st_i[3]), int(st_i[4]))
            return newton_failed(result, t, st_f[2], problem.step, int(st_i[0]), counters)
        if single:
            hist_t.append(t)
            hist_f.append(ends_prev.copy())
        if code != BOUNDARY:
            continue
        final = t >= t_stop - eps_t
        if c_start >= t_ramp - eps_t or (final and not periods):
            periods.append(
                (ext_end[0].copy(), ext_end[1].copy(), int_end / max(t - c_start, 1e-300),
                 ext_el[0].copy(), ext_el[1].copy(), ext_body[0].copy(), ext_body[1].copy(),
                 ext_z.copy())
            )  # fmt: skip
        fresh(ext)
        c_start = t
        if problem.duration is None:  # every watched end's extremes
            converged = problem.settled(
                np.array([p[0][watch] for p in periods]),
                np.array([p[1][watch] for p in periods]),
                nodes,
            )
        if converged or final:
            break
        st_f[1] = min(st_f[1] + T, t_stop)
        if checking:
            restore(period_start, state)  # type: ignore[arg-type]
    w = max(1, problem.steady_window) if problem.duration is None else len(periods)
    win = periods[-min(w, len(periods)) :]
    result.end_max = np.max([p[0] for p in win], axis=0)
    result.end_min = np.min([p[1] for p in win], axis=0)
    result.end_mean = np.mean([p[2] for p in win], axis=0)
    result.element_max = np.max([p[3] for p in win], axis=0)
    result.element_min = np.min([p[4] for p in win], axis=0)
    result.body_max = np.max([p[5] for p in win], axis=0)
    result.body_min = np.min([p[6] for p in win], axis=0)
    result.z_max = np.max([p[7] for p in win], axis=0)
    result.steady_converged = converged
    result.steps, result.newton_iterations = int(st_i[2]), int(st_i[3])
    result.rejected_steps = int(st_i[4])
    result.periods = t / T
    if single:
        result.history = _resample(np.array(hist_t), np.array(hist_f), t, problem)
    if checking and periods:
        _check_step(problem, result, state, period_start, periods[-1], run_march, fresh, deadline)
    return result


def _check_step(  # noqa: PLR0913
    problem: SystemProblem,
    result: SystemDynamicResult,
    state: dict[str, np.ndarray],
    start: dict[str, np.ndarray],
    last: tuple[np.ndarray, ...],
    run_march: Callable[[float, int, tuple[np.ndarray, ...]], int],
    fresh: Callable[[], tuple[np.ndarray, ...]],
    deadline: float | None,
) -> None:
    """The step check of :mod:`.step_check` on a finished system run, as a line's
    (:func:`.timedomain._check_step`): when its last period (``last``: its extremes)
    had seabed landings or lift-offs or slack-taut switches, that period again from the
    saved ``start`` at half the step; every line end's extremes against the run's, each
    within ``step_tolerance`` of its line's largest end-tension range in the period."""
    contacts = int(state["st_i"][6] - start["st_i"][6])
    switches = int(state["st_i"][7] - start["st_i"][7])
    if contacts == 0 and switches == 0:
        return
    restore(state, start)
    ext = fresh()
    p = problem.steps_per_period
    code = ACCEPTED
    while code == ACCEPTED:
        if deadline is not None and time.monotonic() > deadline:
            result.step_warning = failed_warning("time limit reached", p)
            return
        code = run_march(problem.step * problem.step_check_factor, 256, ext)
    if code != BOUNDARY:
        result.step_warning = failed_warning(
            f"Newton did not converge at t = {float(state['st_f'][0]):.6g} s", p
        )
        return
    L = last[0].shape[0]
    coarse = np.stack([last[0].ravel(), last[1].ravel()], axis=1)  # (L * 2, 2)
    fine = np.stack([ext[0][0].ravel(), ext[0][1].ravel()], axis=1)
    names = problem.line_names or tuple(f"line {l}" for l in range(L))  # noqa: E741
    verdict = verdict_of(
        coarse,
        fine,
        coarse[:, 0] - coarse[:, 1],
        names=tuple(f"end {'AB'[e]} of line {names[l]}" for l in range(L) for e in range(2)),  # noqa: E741
        step_tolerance=float(problem.step_tolerance),  # type: ignore[arg-type]
        floor=problem.newton_tolerance * math.sqrt(max(ln.n_nodes for ln in problem.packed.lines)),
        contact_changes=contacts,
        slack_switches=switches,
        points_per_period=p,
        factor=problem.step_check_factor,
        line_of_end=np.repeat(np.arange(L), 2),
    )
    result.step_check = verdict
    result.step_warning = step_warning(verdict)


def _resample(
    t: np.ndarray, f: np.ndarray, t_end: float, problem: SystemProblem
) -> dict[str, np.ndarray]:
    """End tensions (L, 2) per accepted step resampled uniformly over the last
    ``history_periods`` periods: ``time`` (nt,), ``tension`` (L, 2, nt)."""
    nt = int(round(problem.history_periods * problem.history_samples)) + 1
    T = problem.period
    tq = t_end - problem.history_periods * T + np.arange(nt) * T / problem.history_samples
    L = f.shape[1]
    out = np.empty((L, 2, nt))
    for l in range(L):  # noqa: E741
        for e in range(2):
            out[l, e] = np.interp(tq, t, f[:, l, e])
    return {"time": tq, "tension": out}
