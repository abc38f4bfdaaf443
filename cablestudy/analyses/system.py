"""System studies (lines joined at points, bodies) case by case: the validated study as
a :class:`~cablestudy.statics.system.MooringSystem`, and one case's outputs.

Outputs (names and dimensions in :data:`cablestudy.analyses.variables.SYSTEM_OUTPUTS`): per line
its end tensions and forces, positions and tension along it (node index ``s``, with
``arc_length`` beside); the free points' positions; per body its position, the force
and moment of the lines on it and its mooring stiffness."""

from __future__ import annotations

import math
import time
from collections import OrderedDict
from types import SimpleNamespace
from typing import Any

import numpy as np

from ..statics import STATIC_SOLVERS, STATUS_NUMERICAL, STATUS_OK, EndCondition, StaticProblem
from ..statics.system_methods import solve_system_by
from ..statics.system_model import BODY, FIXED, FREE, MooringSystem, SystemLine
from ..study import Study
from ..study.cases import Case
from ..study.problem import line_model, medium
from ..study.system import BodyPoint, FixedPoint, FreePoint
from .counters import trim_lru
from .plausibility import SURFACE
from .variables import CaseRecord

#: per static problem of a study with dynamics (``case.static_hash``, which covers every
#: swept path outside ``analysis`` and the static settings, and the strain-warning
#: limit): the system, its verified static solution, outputs and warnings, shared by the
#: cases of a motion sweep (they are the same numbers computed again otherwise)
_STATICS_CACHE: OrderedDict[tuple, tuple] = OrderedDict()
_CACHE_SIZE = 16


def system_model(study: Study) -> MooringSystem:
    """The system of a validated system study (SI units)."""
    env = study.environment
    rho, g = env.density, env.gravity
    names = tuple(study.points)
    index = {name: i for i, name in enumerate(names)}
    bodies = tuple(study.bodies)
    kind, position, body, force, drag = [], [], [], [], []
    for point in study.points.values():
        f = np.zeros(3)
        b = -1
        drag.append(0.5 * rho * point.drag_area if isinstance(point, FreePoint) else 0.0)
        if isinstance(point, FixedPoint):
            kind.append(FIXED)
            position.append(point.position)
        elif isinstance(point, FreePoint):
            kind.append(FREE)
            position.append(point.position)
            f = np.asarray(point.force, dtype=float) + np.array(
                [0.0, 0.0, -(point.mass - rho * point.volume) * g]
            )
        else:
            assert isinstance(point, BodyPoint)
            kind.append(BODY)
            position.append(point.offset)
            b = bodies.index(point.body)
        body.append(b)
        force.append(f)
    settings = study.analysis.static
    med = medium(study)
    placeholder = EndCondition(kind="fixed", position=np.zeros(3))
    made: list[tuple[Any, Any]] = []  # (segments and attachments, line model)

    def model_of(line: Any) -> Any:
        """The line's model; lines alike in their segments and attachments (all that
        line_model reads of a line: a spar's bridles, a spread's legs) share one."""
        key = (line.segments, line.attachments)
        for k, m in made:
            if k == key:
                return m
        m = line_model(SimpleNamespace(environment=env, line=line))  # type: ignore[arg-type]
        made.append((key, m))
        return m

    lines = tuple(
        SystemLine(
            name=name,
            problem=StaticProblem(
                line=model_of(line),
                medium=med,
                end_a=placeholder,
                end_b=placeholder,
                n_nodes=settings.nodes,
                tolerance=settings.tolerance,
                max_iterations=settings.max_iterations,
                # the drag elements fixed here (default max(nodes - 1, 20), as for one
                # line): the free-point Newton samples the lines at fewer nodes
                drag_elements=settings.drag_elements or max(settings.nodes - 1, 20),
                seabed_stiffness=env.seabed.stiffness,
                friction_lateral=env.seabed.friction_lateral,
            ),
            a=index[line.a],
            b=index[line.b],
        )
        for name, line in study.lines.items()
    )
    return MooringSystem(
        point_names=names,
        point_kind=np.array(kind, dtype=int),
        point_position=np.array(position, dtype=float).reshape(-1, 3),
        point_body=np.array(body, dtype=int),
        point_force=np.array(force, dtype=float).reshape(-1, 3),
        point_drag=np.array(drag, dtype=float),
        body_names=bodies,
        body_position=np.array([b.position for b in study.bodies.values()], dtype=float).reshape(
            -1, 6
        ),
        body_free=np.array([b.kind == "free" for b in study.bodies.values()], dtype=bool),
        body_weight=np.array([_of(b, "mass", 0.0) * g for b in study.bodies.values()]),
        body_buoyancy=np.array([rho * _of(b, "volume", 0.0) * g for b in study.bodies.values()]),
        body_cog=_rows([_of(b, "center_of_gravity", [0.0] * 3) for b in study.bodies.values()]),
        body_cob=_rows([_of(b, "center_of_buoyancy", [0.0] * 3) for b in study.bodies.values()]),
        body_applied=_rows([_of(b, "force", [0.0] * 3) for b in study.bodies.values()]),
        body_waterplane=np.array(
            [rho * _of(b, "waterplane_area", 0.0) * g for b in study.bodies.values()]
        ),
        lines=lines,
        tolerance=settings.tolerance,
        max_iterations=settings.max_iterations,
    )


def _of(body: Any, key: str, default: Any) -> Any:
    """A free body's ``key`` (a prescribed body has none: ``default``)."""
    return getattr(body, key, default)


def _rows(values: list[Any]) -> np.ndarray:
    return np.array(values, dtype=float).reshape(-1, 3)


def system_outputs(system: MooringSystem, res: Any) -> dict[str, np.ndarray]:
    """The output arrays of one solved system (NaN where it failed)."""
    n_lines = len(system.lines)
    n_nodes = system.lines[0].problem.n_nodes
    ok = res.status == STATUS_OK and len(res.lines) == n_lines
    free = system.point_kind == FREE

    def per_line(get: Any, shape: tuple[int, ...]) -> np.ndarray:
        if not ok:
            return np.full((n_lines, *shape), np.nan)
        return np.array([get(r) for r in res.lines], dtype=float).reshape(n_lines, *shape)

    out = {
        "tension_a": per_line(lambda r: np.linalg.norm(r.force_a), ()),
        "tension_b": per_line(lambda r: np.linalg.norm(r.force_b), ()),
        "force_a": per_line(lambda r: r.force_a, (3,)),
        "force_b": per_line(lambda r: r.force_b, (3,)),
        "x": per_line(lambda r: r.position[:, 0], (n_nodes,)),
        "y": per_line(lambda r: r.position[:, 1], (n_nodes,)),
        "z": per_line(lambda r: r.position[:, 2], (n_nodes,)),
        "tension": per_line(lambda r: r.tension, (n_nodes,)),
        "laid_length": per_line(lambda r: r.laid_length, ()),
        # as np.linspace(0, L, n) line by line, bit for bit
        "arc_length": np.linspace(
            np.zeros(n_lines),
            [ln.problem.line.total_length for ln in system.lines],
            n_nodes,
            axis=1,
        ),  # fmt: skip
        "static_iterations": np.asarray(float(res.iterations)),
        "static_residual": np.asarray(float(res.residual) if ok else math.nan),
    }
    if np.any(free):
        out["point_position"] = (
            res.point_position[free] if ok else np.full((int(free.sum()), 3), np.nan)
        )
        seabed = np.zeros((int(free.sum()), 3))
        if res.seabed_force is not None:
            seabed = res.seabed_force[free]
        out["point_seabed_force"] = seabed if ok else np.full_like(seabed, np.nan)
    if len(system.body_names):
        if ok and res.body_position is not None:
            out["body_position"] = np.array(res.body_position, dtype=float)
        else:  # a free body's position is unknown when the solve failed
            out["body_position"] = np.where(
                system.body_free[:, None], np.nan, np.array(system.body_position, dtype=float)
            )
        out["body_force"] = res.body_force
        out["body_stiffness"] = res.body_stiffness
    return out


def evaluate_system_case(case: Case) -> CaseRecord:
    """Solve one case of a system study. Never raises: a fault is status and message."""
    t0 = time.perf_counter()
    study = case.study
    deadline = time.monotonic() + study.analysis.time_limit
    system, res, status, message, data, warnings = case_statics(case, deadline)
    if study.analysis.dynamic is not None:  # the system time domain (analyses.system_dynamic)
        status, message = _dynamics(case, system, res, status, message, deadline, data)
        from .plausibility import take_step_warning  # the time domain's step check

        warnings.append(take_step_warning(data))
        if int(data.get("steady_converged", 1)) == 0 and study.analysis.dynamic.duration is None:
            # the one-line study's text: one warning ('; ' separates warnings)
            from .plausibility import unsettled_warning

            periods = float(np.asarray(data.get("periods", np.nan)))
            warnings.append(unsettled_warning(periods, study.analysis.dynamic.max_periods))
        if status == STATUS_OK:
            warnings.append(_slack_warning(list(study.lines), data))
    if status == STATUS_OK and not any(w.startswith(SURFACE) for w in warnings):
        from .surface import system_motion_surface_warning  # a line out of the water

        warnings.append(system_motion_surface_warning(study, data))
    warning = "; ".join(w for w in warnings if w)
    return CaseRecord(
        hash=case.hash,
        index=case.index,
        status=int(status),
        message=message,
        wall_time=time.perf_counter() - t0,
        data=data,
        warning=warning,
        # the compiled system Newton left it to the general path (as the grid counts it)
        fallback=str(getattr(res, "fallback", "") or ""),
    )


def case_statics(case: Case, deadline: float) -> tuple[Any, Any, int, str, dict, list[str]]:
    """The case's system, static solution, status, message, static outputs and warnings
    (:func:`_statics`), shared through :data:`_STATICS_CACHE` by the cases of a study
    with dynamics that have one static problem (a sweep of the motion); the outputs and
    warnings are the caller's own copies."""
    study = case.study
    key = None
    if study.analysis.dynamic is not None and case.static_hash:
        key = (case.static_hash, study.analysis.static.strain_warning)
    hit = _STATICS_CACHE.get(key) if key is not None else None
    if hit is not None:
        _STATICS_CACHE.move_to_end(key)
        system, res, status, message, shared, shared_warnings = hit
        data, warnings = dict(shared), list(shared_warnings)
    else:
        system, res, status, message, data, warnings = _statics(case, deadline)
        if key is not None and status == STATUS_OK:  # a failure is tried again
            _STATICS_CACHE[key] = (system, res, status, message, dict(data), list(warnings))
            trim_lru(_STATICS_CACHE, _CACHE_SIZE)
    return system, res, status, message, data, warnings


def _slack_warning(names: list[str], data: dict[str, Any]) -> str:
    """The one-line study's slack warning (:func:`.plausibility.slack_warning`) for a
    system's dynamics: a line end whose smallest tension is at or below zero, else a
    point along a line (where its static tension is positive: a stretch slack in statics
    does not go slack) whose envelope minimum is; the lines named."""
    from .plausibility import slack_warning

    ends = np.stack([np.asarray(data.get(f"tension_min_{e}", np.nan), float) for e in "ab"])
    ends = np.broadcast_to(ends, (2, len(names))) if ends.size else np.full((2, len(names)), np.nan)
    if np.any(ends <= 0.0):
        slack = [n for n, t in zip(names, np.min(ends, axis=0), strict=True) if t <= 0.0]
        return slack_warning(float(np.min(ends)), f"at an end of line {', '.join(slack)}")
    env = np.asarray(data.get("tension_envelope_min", np.nan), dtype=float)
    static = np.asarray(data.get("tension", np.nan), dtype=float)
    if env.shape != static.shape or env.ndim != 2:
        return ""
    env = np.where(static > 0.0, env, np.nan)
    if not np.any(env <= 0.0):  # no point at or below zero: no row's minimum is
        return ""
    low = np.array([np.nanmin(r) if np.any(np.isfinite(r)) else np.nan for r in env])
    if not np.any(low <= 0.0):
        return ""
    slack = [n for n, t in zip(names, low, strict=True) if t <= 0.0]
    return slack_warning(float(np.nanmin(low)), f"along line {', '.join(slack)}")


def _statics(case: Case, deadline: float) -> tuple[Any, Any, int, str, dict, list[str]]:
    """The case's system, static solution, status, message, static outputs and
    warnings."""
    study = case.study
    system = system_model(study)
    res = None
    try:
        method = study.analysis.static.method  # catenary or discrete (config.study)
        if study.analysis.dynamic is not None:  # a sweep of the motion shares the statics
            from .system_dynamic import system_statics
            from .system_prejudge import extreme_poses

            # auto's quasi-static check: the body at the motion's extremes solved with
            # the static state, as more cases of the same compiled call
            extra = extreme_poses(case, system.body_position)
            res = system_statics(
                case,
                system,
                lambda: solve_system_by(
                    system, method, STATIC_SOLVERS, deadline=deadline, extra_poses=extra
                ),
            )
        else:
            res = solve_system_by(system, method, STATIC_SOLVERS, deadline=deadline)
        status, message = res.status, res.message
        data = system_outputs(system, res)
    except Exception as exc:  # noqa: BLE001 - any solver fault is recorded as data
        status, message = STATUS_NUMERICAL, f"{type(exc).__name__}: {exc}"
        data = {}
    if status == STATUS_OK:
        bad = [k for k, v in data.items() if not np.all(np.isfinite(v))]
        if bad:
            status, message = STATUS_NUMERICAL, f"non-finite values in {', '.join(bad)}"
    data["static_status"] = np.asarray(status, dtype=np.int64)
    warnings = [_strain_warning(study, res) if status == STATUS_OK else ""]
    if status == STATUS_OK:  # a line above the water's surface
        from .surface import system_surface_warning

        warnings.append(system_surface_warning(study, res))
    if status == STATUS_OK and getattr(res, "fallback", ""):
        # the compiled system Newton left it to the general path: said, as for one line
        from .plausibility import fallback_warning

        warnings.append(fallback_warning(res.fallback))
    return system, res, status, message, data, warnings


def _dynamics(
    case: Case,
    system: MooringSystem,
    res: Any,
    status: int,
    message: str,
    deadline: float,
    data: dict[str, Any],
) -> tuple[int, str]:
    """Run the case's dynamics after its statics (not run when they failed) into
    ``data``; the case's status and message."""
    from .common import STATUS_NOT_RUN
    from .system_dynamic import failed_dynamic_outputs, run_system_dynamic

    if status != STATUS_OK:
        data["dynamic_status"] = np.asarray(STATUS_NOT_RUN, dtype=np.int64)
        data.update(failed_dynamic_outputs(case.study, data))  # NaN, never dropped
        return status, message
    try:
        d_status, d_message, d_data = run_system_dynamic(case, system, res, deadline)
    except Exception as exc:  # noqa: BLE001 - any solver fault is recorded as data
        d_status, d_message, d_data = STATUS_NUMERICAL, f"{type(exc).__name__}: {exc}", {}
    data.update(d_data)
    data["dynamic_status"] = np.asarray(d_status, dtype=np.int64)
    if d_status != STATUS_OK:
        data.update(failed_dynamic_outputs(case.study, data))  # NaN, never dropped
        return d_status, f"dynamic analysis: {d_message}"
    return status, message


def _strain_warning(study: Study, res: Any) -> str:
    """``analysis.static.strain_warning`` of a system: the largest strain of each line
    (as for one line), the lines above the limit named."""
    from .plausibility import strain_warning
    from .static import largest_static_strain

    limit = study.analysis.static.strain_warning
    strains = {
        name: largest_static_strain(SimpleNamespace(line=line), r)
        for (name, line), r in zip(study.lines.items(), res.lines, strict=True)
    }
    worst = max(strains, key=lambda k: strains[k] if math.isfinite(strains[k]) else -1.0)
    text = strain_warning(strains[worst], limit)
    if not text:
        return ""
    over = [k for k, v in strains.items() if v > limit]
    return f"{text} (lines {', '.join(over)})"
