"""System studies (lines joined at points, bodies) case by case: the validated study as
a :class:`~cablestudy.statics.system.MooringSystem`, and one case's outputs.

Outputs (names and dimensions in :data:`cablestudy.results.SYSTEM_OUTPUTS`): per line
its end tensions and forces, positions and tension along it (node index ``s``, with
``arc_length`` beside); the free points' positions; per body its position, the force
and moment of the lines on it and its mooring stiffness."""

from __future__ import annotations

import math
import time
from types import SimpleNamespace
from typing import Any

import numpy as np

from .cases import Case
from .config import Study
from .config.system import BodyPoint, FixedPoint, FreePoint
from .problem import line_model, medium
from .results import CaseRecord
from .statics import STATIC_SOLVERS, STATUS_NUMERICAL, STATUS_OK, EndCondition, StaticProblem
from .statics.system import BODY, FIXED, FREE, MooringSystem, SystemLine, solve_system


def system_model(study: Study) -> MooringSystem:
    """The system of a validated system study (SI units)."""
    env = study.environment
    rho, g = env.density, env.gravity
    names = tuple(study.points)
    index = {name: i for i, name in enumerate(names)}
    bodies = tuple(study.bodies)
    kind, position, body, force = [], [], [], []
    for point in study.points.values():
        f = np.zeros(3)
        b = -1
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
    lines = tuple(
        SystemLine(
            name=name,
            problem=StaticProblem(
                line=line_model(SimpleNamespace(environment=env, line=line)),  # type: ignore[arg-type]
                medium=med,
                end_a=placeholder,
                end_b=placeholder,
                n_nodes=settings.nodes,
                tolerance=settings.tolerance,
                max_iterations=settings.max_iterations,
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
        "arc_length": np.array(
            [np.linspace(0.0, ln.problem.line.total_length, n_nodes) for ln in system.lines]
        ),
        "static_iterations": np.asarray(float(res.iterations)),
        "static_residual": np.asarray(float(res.residual) if ok else math.nan),
    }
    if np.any(free):
        out["point_position"] = (
            res.point_position[free] if ok else np.full((int(free.sum()), 3), np.nan)
        )
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
    system = system_model(study)
    try:
        res = solve_system(system, STATIC_SOLVERS["catenary"], deadline=deadline)
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
    warning = ""
    if status == STATUS_OK and getattr(res, "fallback", ""):
        # the compiled system Newton left it to the general path: said, as for one line
        from .plausibility import fallback_warning

        warning = fallback_warning(res.fallback)
    return CaseRecord(
        hash=case.hash,
        index=case.index,
        status=int(status),
        message=message,
        wall_time=time.perf_counter() - t0,
        data=data,
        warning=warning,
    )
