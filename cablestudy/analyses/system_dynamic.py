"""The dynamics of a system study case by case: the time-domain model of the system
(every line's lumped-mass model, the free points, the driven points) built from the
study and its static solution, the motion of the bodies and points from
``analysis.dynamic.excitation``, and one case's outputs.

A sweep of the motion (amplitude, frequency, phase, tables) over a system shares the
static solve and the model (lines discretised, packed, brought to their discrete
equilibrium): both are cached per static problem (``case.static_hash``) and element
count, and counted in :data:`cablestudy.counters.COUNTERS` (``system_static_solves``,
``system_assemblies``)."""

from __future__ import annotations

import math
from collections import OrderedDict
from typing import Any

import numpy as np

from ..statics import STATUS_NUMERICAL, STATUS_OK
from ..study.analysis import BodySpectrumExcitation, SpectrumExcitation
from ..study.cases import Case
from ..study.system import BodyPoint, FreePoint
from ..study.system_dynamics import BODY_DOFS, BodyHarmonic, BodyTable, PointHarmonic
from .counters import COUNTERS, trim_lru
from .line_model import march_settings, period_and_step, system_line_extras

_MODEL_CACHE: OrderedDict[tuple, Any] = OrderedDict()
_STATIC_CACHE: OrderedDict[str, Any] = OrderedDict()
_CACHE_SIZE = 16


def system_statics(case: Case, system: Any, solve: Any) -> Any:
    """The case's system static solution, solved once per static problem."""
    hit = _STATIC_CACHE.get(case.static_hash)
    if hit is not None:
        _STATIC_CACHE.move_to_end(case.static_hash)
        return hit
    res = solve()
    COUNTERS["system_static_solves"] += 1
    if res.status == STATUS_OK:  # a failure (a time limit among them) is tried again
        _STATIC_CACHE[case.static_hash] = res
        trim_lru(_STATIC_CACHE, _CACHE_SIZE)
    return res


def system_model_dynamic(case: Case, system: Any, static: Any) -> tuple[Any, ...] | str:
    """The packed time-domain model of the case's system at its discrete static
    equilibrium, cached per static problem and element count: (packed, positions,
    anchors, drive arrays (body, slot owner point, offset, static position), the
    Newton and tension-step scale [N]), or why the equilibrium was not found."""
    from ..dynamics.discrete_line import discretise_nodes, uniform_nodes
    from ..dynamics.system_model import FreePoints, pack
    from ..dynamics.system_timedomain import equilibrium
    from ..statics.system import rotation
    from ..statics.system_model import FREE
    from .line_model import roundoff_force, roundoff_parts

    dyn = case.study.analysis.dynamic
    key = (case.static_hash, dyn.elements)
    hit = _MODEL_CACHE.get(key)
    if hit is not None:
        _MODEL_CACHE.move_to_end(key)
        return hit
    study = case.study
    names = list(study.lines)
    lines, starts, tol, fallback, peak, made_parts = [], [], [], [], [], []
    # per kind of line: (its line model, medium and study segments and attachments, its
    # nodes, model, largest nodal force [N] on a seabed and roundoff_force's factors)
    made: list[tuple[tuple, np.ndarray, Any, float, tuple]] = []
    for k, sl in enumerate(system.lines):
        lm = sl.problem.line
        med = sl.problem.medium
        res = static.lines[k]
        spec = study.lines[names[k]]
        # lines alike in every input (a spread's legs, a spar's bridles) share one
        # discretisation: it depends on these alone (the line model, the medium, and the
        # extras, read from the study line's segments and attachments), not on where the
        # line lies
        inputs = (lm, med, (spec.segments, spec.attachments))
        same = next(
            (m for m in made if m[0][0] is lm and m[0][1] is med and m[0][2] == inputs[2]), None
        )
        if same is None:
            s_nodes = uniform_nodes(lm, dyn.elements)
            line = discretise_nodes(lm, med, s_nodes, system_line_extras(study, names[k], lm))
            force = float(np.max(np.abs(line.force))) if line.has_seabed else -math.inf
            same = (inputs, s_nodes, line, force, roundoff_parts(line))
            made.append(same)
        _, s_nodes, line, force, parts = same
        start = np.stack([np.interp(s_nodes, res.s, res.position[:, c]) for c in range(3)], 1)
        peak.append(float(np.nanmax(res.tension)))
        lines.append(line)
        starts.append(start)
        t_nodes = np.interp(s_nodes, res.s, res.tension)
        fallback.append(0.5 * (t_nodes[:-1] + t_nodes[1:]))
        tol.append(max(1e-9 * max(peak[-1], force), roundoff_force(line, start, parts)))
        made_parts.append(parts)
    COUNTERS["system_assemblies"] += 1
    kind = system.point_kind
    free_index = -np.ones(kind.size, dtype=int)
    free_index[kind == FREE] = np.arange(int(np.sum(kind == FREE)))
    drive_index = -np.ones(kind.size, dtype=int)
    drive_index[kind != FREE] = np.arange(int(np.sum(kind != FREE)))
    end_point = np.array([[free_index[sl.a], free_index[sl.b]] for sl in system.lines])
    end_drive = np.array([[drive_index[sl.a], drive_index[sl.b]] for sl in system.lines])
    pts = list(study.points.values())
    free_pts = [p for p in pts if isinstance(p, FreePoint)]
    rho = study.environment.density
    g = study.environment.gravity
    points = FreePoints(
        mass=np.array([p.mass + p.added_mass for p in free_pts], dtype=float),
        force=np.array(
            [
                np.asarray(p.force, dtype=float) + [0.0, 0.0, -(p.mass - rho * p.volume) * g]
                for p in free_pts
            ],
            dtype=float,
        ).reshape(-1, 3),
        drag=np.array([0.5 * rho * p.drag_area for p in free_pts], dtype=float),
    )
    driven = [i for i in range(kind.size) if kind[i] != FREE]
    drive_body = np.array([system.point_body[i] for i in driven], dtype=np.int64)
    packed = pack(lines, end_point, end_drive, points, drive_body)
    x, anchor, msg = equilibrium(
        packed, np.concatenate(starts), tolerance=np.array(tol), fallback_tension=fallback
    )
    if msg:
        _MODEL_CACHE[key] = msg
        return msg
    # each drive's static position: the node of a line end on it (exactly where the
    # discrete statics left it)
    d_static = np.zeros((len(driven), 3))
    for k in range(packed.he_node.size):
        d_static[packed.he_drive[k]] = x[packed.he_node[k]]
    offsets = np.array(
        [pts[i].offset if isinstance(pts[i], BodyPoint) else [0.0] * 3 for i in driven],
        dtype=float,
    ).reshape(-1, 3)
    body_pos = static.body_position if static.body_position is not None else system.body_position
    body_base = np.asarray(body_pos, dtype=float).reshape(-1, 6)
    body_R0 = np.array([rotation(b[3:]) for b in body_base]).reshape(-1, 3, 3)
    scale = max(peak)
    # rounding of the element forces: the Newton tolerance's floor (the tolerance itself,
    # relative to the static tension, is a dynamic setting: applied per case)
    floor = max(
        4.0 * roundoff_force(ln, x[packed.no[k] : packed.no[k + 1]], made_parts[k])
        for k, ln in enumerate(lines)
    )
    out = (
        packed,
        x,
        anchor,
        driven,
        drive_body,
        offsets,
        d_static,
        body_base,
        body_R0,
        scale,
        floor,
    )
    _MODEL_CACHE[key] = out
    trim_lru(_MODEL_CACHE, _CACHE_SIZE)
    return out


def slot_motion(study: Any, driven: list[int]) -> tuple[Any, np.ndarray, float, float]:
    """The motion slots of the excitation (:class:`.dynamics.system_model.SlotMotion`),
    each drive's own slot (-1: none), the steady-state period [s] and the base step [s]
    (as a one-line study's: the fastest harmonic over ``points_per_period``)."""
    from ..dynamics.excitation import TableMotion
    from ..dynamics.system_model import SlotMotion

    dyn = study.analysis.dynamic
    bodies = list(study.bodies)
    names = list(study.points)
    B = len(bodies)
    own = sorted({e.point for e in dyn.excitations if hasattr(e, "point")}, key=names.index)
    own_slot = {p: 2 * B + q for q, p in enumerate(own)}
    slots, dirs, amps, freqs, phases, tables = [], [], [], [], [], []
    periods: list[float] = []
    for e in dyn.excitations:
        if isinstance(e, BodyHarmonic | BodyTable | BodySpectrumExcitation):
            k = BODY_DOFS.index(e.dof)
            slot = 2 * bodies.index(e.body) + (0 if k < 3 else 1)
            direction = np.eye(3)[k % 3]
        else:
            slot = own_slot[e.point]
            direction = np.asarray(e.direction, dtype=float) / np.linalg.norm(e.direction)
        if isinstance(e, SpectrumExcitation):
            # a spectrum runs as its lines with random phases (seeded), as a line end's
            # (cablestudy.analyses.end_motion): periodic with its lowest line's period
            draws = np.random.default_rng(e.seed).uniform(0.0, 2.0 * math.pi, e.components)
            for f, a, ph in zip(e.line_frequencies, e.line_amplitudes, draws, strict=True):
                slots.append(slot)
                dirs.append(direction)
                amps.append(a)
                freqs.append(f)
                phases.append(float(ph))
                periods.append(1.0 / f)
        elif isinstance(e, BodyHarmonic | PointHarmonic):
            slots.append(slot)
            dirs.append(direction)
            amps.append(e.amplitude)
            freqs.append(e.frequency)
            phases.append(math.radians(e.phase_deg))
            periods.append(1.0 / e.frequency)
        else:
            tm = TableMotion(
                end=0,
                direction=direction,
                times=np.array([r[0] for r in e.table]),
                values=np.array([r[1] for r in e.table]),
                periodic=e.periodic,
            )
            tables.append((slot, tm))
            if e.periodic:
                periods.append(tm.duration)
    period, step = period_and_step(dyn, periods)
    motion = SlotMotion(
        slot=np.array(slots, dtype=np.int64),
        direction=np.array(dirs, dtype=float).reshape(-1, 3),
        amplitude=np.array(amps, dtype=float),
        frequency=np.array(freqs, dtype=float),
        phase=np.array(phases, dtype=float),
        tables=tuple(tables),
        ramp_time=dyn.ramp_periods * period,
    )
    d_slot = np.array([own_slot.get(names[i], -1) for i in driven], dtype=np.int64)
    return motion, d_slot, period, step


def run_system_dynamic(
    case: Case, system: Any, static: Any, deadline: float | None
) -> tuple[int, str, dict[str, np.ndarray]]:
    """The case's time-domain run and its outputs: (status, message, outputs)."""
    from ..dynamics.system_model import Drives
    from ..dynamics.system_timedomain import SystemProblem, simulate_system
    from .along_line import tension_along

    dyn = case.study.analysis.dynamic
    if dyn.method == "frequency":  # the system frequency domain (issue 24)
        from .system_frequency import run_system_frequency

        return run_system_frequency(case, system, static)
    reason = "method: time"
    if dyn.method == "auto":  # the frequency domain where every line passes its checks
        from .system_frequency import run_system_auto

        done, reason = run_system_auto(case, system, static)
        if done is not None:
            return done
    model = system_model_dynamic(case, system, static)
    head = {"dynamic_method": np.asarray("time"), "dynamic_method_reason": np.asarray(reason)}
    if isinstance(model, str):
        return STATUS_NUMERICAL, model, head
    packed, x, anchor, driven, drive_body, offsets, d_static, body_base, body_R0, scale, floor = (
        model
    )
    tol = max(dyn.newton_tolerance * scale, floor)
    motion, d_slot, period, step = slot_motion(case.study, driven)
    hist = dyn.history
    problem = SystemProblem(
        packed=packed,
        static_position=x,
        anchor=anchor,
        drives=Drives(
            body=drive_body,
            slot=d_slot,
            offset=offsets,
            static=d_static,
            body_base=body_base,
            body_R0=body_R0,
        ),
        motion=motion,
        period=period,
        step=step,
        newton_tolerance=tol,
        tension_step=dyn.tension_resolution * scale,
        history_periods=hist.periods if hist else 2.0,
        history_samples=hist.samples_per_period if hist else 64,
        # the step check (cablestudy.dynamics.step_check)
        step_tolerance=dyn.step_tolerance,
        points_per_period=dyn.points_per_period,
        line_names=tuple(case.study.lines),
        **march_settings(dyn),
    )
    res = simulate_system(problem, deadline=deadline)
    if res.status != STATUS_OK:
        return res.status, res.message, head
    n_out = system.lines[0].problem.n_nodes
    env_max, env_min, z_max = [], [], []
    for k, ln in enumerate(packed.lines):
        s_out = np.linspace(0.0, float(ln.s[-1]), n_out)
        el = slice(packed.eo[k], packed.eo[k + 1])
        env_max.append(tension_along(s_out, ln.s, res.element_max[el], res.end_max[k]))
        env_min.append(tension_along(s_out, ln.s, res.element_min[el], res.end_min[k]))
        z_max.append(np.interp(s_out, ln.s, res.z_max[packed.no[k] : packed.no[k + 1]]))
    out = {
        **head,
        "tension_max_a": res.end_max[:, 0],
        "tension_min_a": res.end_min[:, 0],
        "tension_mean_a": res.end_mean[:, 0],
        "tension_max_b": res.end_max[:, 1],
        "tension_min_b": res.end_min[:, 1],
        "tension_mean_b": res.end_mean[:, 1],
        "tension_envelope_max": np.array(env_max),
        "tension_envelope_min": np.array(env_min),
        "z_envelope_max": np.array(z_max),
        "steady_converged": np.asarray(int(res.steady_converged)),
        "periods": np.asarray(res.periods),
        "dynamic_steps": np.asarray(res.steps),
        "newton_iterations": np.asarray(res.newton_iterations),
        "rejected_steps": np.asarray(res.rejected_steps),
    }
    if body_base.shape[0]:
        out["body_force_max"] = res.body_max
        out["body_force_min"] = res.body_min
    if res.history is not None:
        out["history_time"] = res.history["time"]
        out["history_tension_a"] = res.history["tension"][:, 0]
        out["history_tension_b"] = res.history["tension"][:, 1]
    bad = [k for k, v in out.items() if v.dtype.kind == "f" and not np.all(np.isfinite(v))]
    if bad:
        return STATUS_NUMERICAL, f"non-finite values in {', '.join(bad)}", head
    if res.step_warning:  # the step check's: a warning, not a variable (system.py)
        from .plausibility import STEP_WARNING_KEY

        out[STEP_WARNING_KEY] = res.step_warning  # type: ignore[assignment]
    return STATUS_OK, "", out


def failed_dynamic_outputs(study: Any, data: dict[str, Any]) -> dict[str, np.ndarray]:
    """NaN for each output of a system's dynamics that a failed (or not run) case left
    out, shaped as a successful case's: a failed case is NaN in its data variables,
    never dropped, even when every case of the study fails (the dataset's variables are
    the records' keys). Shapes from the case's static outputs (``tension`` (line, s),
    ``body_force`` (body, dof)), else from the study."""
    n_line = len(study.lines)
    tension = data.get("tension")
    n_s = np.shape(tension)[-1] if tension is not None else study.analysis.static.nodes
    out: dict[str, np.ndarray] = {}
    names = [f"tension_{m}_{e}" for m in ("max", "min", "mean") for e in "ab"]
    out.update({k: np.full(n_line, np.nan) for k in names})
    for k in ("tension_envelope_max", "tension_envelope_min", "z_envelope_max"):
        out[k] = np.full((n_line, n_s), np.nan)
    if study.bodies:
        force = data.get("body_force")
        n_body = np.shape(force)[0] if force is not None else len(study.bodies)
        out["body_force_max"] = np.full((n_body, len(BODY_DOFS)), np.nan)
        out["body_force_min"] = np.full((n_body, len(BODY_DOFS)), np.nan)
    if study.analysis.dynamic.method == "frequency":
        out["tension_amplitude_a"] = np.full(n_line, np.nan)
        out["tension_amplitude_b"] = np.full(n_line, np.nan)
    return {k: v for k, v in out.items() if k not in data}
