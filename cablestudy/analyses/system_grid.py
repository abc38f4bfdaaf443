"""Sweeps of a system study's positions and loads as a grid (:mod:`cablestudy.grid`),
solved by the compiled system Newton many cases at a time.

A system study whose sweep moves only positions and free points' loads -- a prescribed
body's pose (``bodies.<b>.position.<i>``), a fixed point (``points.<p>.position.<i>``),
a body point's offset (``points.<p>.offset.<i>``), a free point's ``mass``, ``volume``
or ``force.<i>`` -- is validated once as a template and each swept value once in the
model that holds it; the only check that combines swept fields, a fixed point above the
seabed, runs over the whole grid with NumPy. No per-case pydantic model or
:class:`MooringSystem` is built: a chunk of cases is the template's system with arrays
of point positions, body poses and free points' loads,
solved by :func:`cablestudy.statics.system_fast.solve_packed` (the compiled Newton, then
every line re-solved, sampled and verified, the equilibrium checked, the bodies' force
and stiffness), and its outputs stacked into one array per variable with the names,
dims and values of :func:`cablestudy.system_cases.system_outputs`.

Every case starts its Newton from the template's own equilibrium (solved once per
sweep, with the free points' positions the study gives as the start) moved to first
order with the case's own inputs (the template's stiffness), never from another case,
so a case's record does not depend on the chunking or on the order of the cases. A case
the compiled path does not settle from there is tried from the equilibrium alone; what it
does not take or settle is solved by the general path
(:func:`cablestudy.statics.system.solve_system`) from the study's starting positions and
counted with its reason (the dataset's ``cases_fallback`` and ``fallback_reasons``).

Anything else (another swept key, free bodies, a system the compiled path does not take
at all) runs case by case (:mod:`cablestudy.system_cases`), where the compiled path
still solves each case it takes.
"""

from __future__ import annotations

import math
import re
import time
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from ..statics.system_model import FREE
from ..study.cases import _copy_tree, _hash, _set_path, code_fingerprint, parse_sweep
from ..study.grid import CaseGrid, _numeric, grid_shape
from ..study.loader import StudySource
from ..study.study import Study
from .common import segment_of
from .grid_chunk import GridChunk, array_chunk, numerical_fault

#: swept paths the system grid takes: (group, name, field, component)
_PATH = re.compile(r"^(bodies|points)\.([^.]+)\.(position|offset|force)\.(\d)$")
#: a free point's load: (name, field)
_LOAD = re.compile(r"^points\.([^.]+)\.(mass|volume)$")


@dataclass(frozen=True)
class SystemGrid(CaseGrid):
    """A system study's position sweep as a grid (see the module docstring); the
    template's :class:`MooringSystem` and the free points' start."""

    system: Any = None
    #: where every case starts (:func:`cablestudy.statics.system_fast.template_start`):
    #: the template's equilibrium of the free points (k, 3) [m], all points there (n, 3)
    #: [m], the free points' first-order response to the others' displacements (3k, 3n),
    #: their loads (k, 3) [N] and K_FF^-1 (3k, 3k); None where the template is unsettled
    start: tuple[np.ndarray, ...] | None = None
    #: per swept path: (what it sets, index, component): ('pose', body, dof),
    #: ('fixed', point, xyz) or ('offset', point, xyz)
    targets: dict[str, tuple[str, int, int]] = field(default_factory=dict)

    @property
    def is_system(self) -> bool:
        return True


def expand_system_grid(src: StudySource, template: Study) -> SystemGrid | None:
    """The system study as a :class:`SystemGrid` when its sweep moves positions only and
    every swept value and combination is valid, else None (then case by case)."""
    from ..statics.system_fast import ineligible
    from ..study.system import BodyPoint, FixedPoint, FreePoint
    from .system import system_model

    axes = parse_sweep(src)
    if not axes or not _numeric(axes):
        return None
    an = template.analysis
    if an.dynamic is not None or an.static.method != "catenary":
        return None  # the dynamics, method discrete: case by case (system_cases)
    points, bodies = list(template.points), list(template.bodies)
    targets: dict[str, tuple[str, int, int]] = {}
    for axis in axes:
        for path in axis.paths:
            load = _LOAD.match(path)
            if load is not None:
                if not isinstance(template.points.get(load.group(1)), FreePoint):
                    return None
                targets[path] = (load.group(2), points.index(load.group(1)), -1)
                continue
            m = _PATH.match(path)
            if m is None:
                return None
            group, name, key, comp = m.group(1), m.group(2), m.group(3), int(m.group(4))
            if group == "bodies":
                body = template.bodies.get(name)
                if body is None or body.kind != "prescribed" or key != "position" or comp > 5:
                    return None
                targets[path] = ("pose", bodies.index(name), comp)
            else:
                point = template.points.get(name)
                if point is None or comp > 2:
                    return None
                if key == "position" and isinstance(point, FixedPoint):
                    targets[path] = ("fixed", points.index(name), comp)
                elif key == "offset" and isinstance(point, BodyPoint):
                    targets[path] = ("offset", points.index(name), comp)
                elif key == "force" and isinstance(point, FreePoint):
                    targets[path] = ("force", points.index(name), comp)
                else:
                    return None
    system = system_model(template)
    if ineligible(system):
        return None
    # each swept value once, in the model that holds it (a prescribed body, a fixed or a
    # body point: no check of the whole study involves a position but a fixed point's
    # height above the seabed, checked over the grid below); any fault leaves the grid,
    # and expand_cases reports it at its line
    for axis in axes:
        for path, vals in zip(axis.paths, axis.values, strict=True):
            group, name, rest = path.split(".", 2)
            model = getattr(template, group)[name]
            raw = src.data.get(group, {}).get(name)
            if not isinstance(raw, dict):
                return None
            for v in vals:
                data = _copy_tree(raw)
                try:
                    _set_path(data, rest, v)
                    type(model).model_validate(data)
                except (KeyError, ValueError, TypeError):
                    return None
    swept = {
        p: (k, np.asarray(vals, dtype=float))
        for k, axis in enumerate(axes)
        for p, vals in zip(axis.paths, axis.values, strict=True)
    }
    if not _fixed_points_above_seabed(template, swept, targets, [a.size for a in axes]):
        return None
    from ..statics.system_fast import template_start

    start = template_start(system)
    body = template.model_dump(mode="json", exclude={"name", "description", "sweep"})
    return SystemGrid(
        template=template,
        axes=axes,
        swept=swept,
        key=_hash(
            [
                code_fingerprint(),
                body,
                {p: k for p, (k, _) in swept.items()},
                grid_shape(axes),
                "system",
            ]
        ),
        validated={},
        arrays=True,
        system=system,
        start=start,
        targets=targets,
    )


def _fixed_points_above_seabed(
    template: Study,
    swept: dict[str, tuple[int, np.ndarray]],
    targets: dict[str, tuple[str, int, int]],
    shape: list[int],
) -> bool:
    """:meth:`Study._system`'s check that combines swept fields, over the whole grid: every
    fixed point whose position is swept above the seabed."""
    env = template.environment
    if env.depth is None:
        return True
    names = list(template.points)
    moved = {targets[p][1] for p in swept if targets[p][0] == "fixed"}
    for i in moved:
        xyz = []
        for c in range(3):
            path = f"points.{names[i]}.position.{c}"
            if path in swept:
                axis, vals = swept[path]
                s = [1] * len(shape)
                s[axis] = len(vals)
                xyz.append(vals.reshape(s))
            else:
                xyz.append(np.asarray(float(template.points[names[i]].position[c])))
        x, y, z = xyz
        ground = env.seabed_z(x, y)
        if np.any(z < ground - 1e-9 * env.depth):
            return False
    return True


def _case_inputs(grid: SystemGrid, lo: int, hi: int) -> tuple[np.ndarray, ...]:
    """Per case of rows ``lo:hi``: the bodies' poses (n, m, 6), the points' base
    positions (n, n_points, 3) (fixed points where they are, free points' start as the
    study gives, body points' offsets) and the free points' constant force (n, n_points,
    3) [N] (their force plus weight and buoyancy, as system_cases.system_model)."""
    system = grid.system
    n = (hi - lo) * math.prod(grid.shape[1:])
    poses = np.broadcast_to(system.body_position, (n, *system.body_position.shape)).copy()
    base = np.broadcast_to(system.point_position, (n, *system.point_position.shape)).copy()
    pforce = np.broadcast_to(system.point_force, (n, *system.point_force.shape)).copy()
    loads: dict[int, dict[str, Any]] = {}
    for path, (what, i, c) in grid.targets.items():
        vals = grid.values(path, lo, hi)
        if what == "pose":
            poses[:, i, c] = vals
        elif what in ("fixed", "offset"):
            base[:, i, c] = vals
        else:
            loads.setdefault(i, {})[what if c < 0 else f"force{c}"] = vals
    env = grid.template.environment
    names = list(grid.template.points)
    for i, given in loads.items():
        point = grid.template.points[names[i]]
        mass = given.get("mass", point.mass)
        volume = given.get("volume", point.volume)
        force = np.stack(
            [np.broadcast_to(given.get(f"force{c}", point.force[c]), (n,)) for c in range(3)],
            axis=1,
        ).astype(float)
        force[:, 2] += -(mass - env.density * volume) * env.gravity
        pforce[:, i] = force
    return poses, base, pforce


def evaluate_system_chunk(grid: SystemGrid, lo: int, hi: int) -> GridChunk:
    """Solve rows ``lo:hi`` of a system grid and stack the outputs (see the module
    docstring). Never raises: a fault fails the chunk's cases with its text."""
    from ..statics.system_fast import pack, point_positions_many, solve_packed
    from ..statics.system_model import BODY
    from .plausibility import fallback_warning

    t0 = time.perf_counter()
    system = grid.system
    n = (hi - lo) * math.prod(grid.shape[1:])
    reasons = np.full(n, "", dtype=object)
    status = np.zeros(n, dtype=np.int64)
    messages = [""] * n
    warnings: dict[int, list[str]] = {}
    data: dict[str, np.ndarray] = {}
    try:
        poses, base, pforce = _case_inputs(grid, lo, hi)
        body_pts = system.point_kind == BODY
        pos = point_positions_many(system, poses, base if np.any(body_pts) else None, base)
        out = _empty_outputs(system, n)
        why = np.full(n, "", dtype=object)
        todo = np.arange(n)
        for start in _starts(grid, pos, pforce):
            # the template's equilibrium moved to first order with the case's points and
            # loads, then (what that does not settle) the template's equilibrium itself
            pk, why_pk = pack(
                system, pos[todo], None if start is None else start[todo], pforce[todo]
            )
            why[todo] = why_pk
            keep = todo[why_pk == ""]
            if pk is not None:
                sol = solve_packed(system, pk, poses[keep])
                _put(out, keep, sol, system)
                why[keep] = sol.fallback
            todo = keep[sol.fallback != ""] if pk is not None else keep
            if not todo.size:
                break
        if "body_position" in out:
            out["body_position"] = poses.copy()
        for i in np.flatnonzero(why != ""):
            reasons[i] = str(why[i])
            limit = grid.template.analysis.time_limit
            st, msg = _general(system, poses[i], base[i], pforce[i], out, int(i), limit)
            status[i], messages[i] = st, msg
        for i, text in _strain_warnings(grid, out, status).items():
            warnings.setdefault(i, []).append(text)
        from .surface import system_grid_surface_warnings  # a line above the water

        for i, text in system_grid_surface_warnings(grid.template, out, status):
            warnings.setdefault(i, []).append(text)
        for i in np.flatnonzero((reasons != "") & (status == 0)):
            warnings.setdefault(int(i), []).append(fallback_warning(str(reasons[i])))
        bad = status != 0
        for arr in out.values():  # a failed case keeps no static output (as assemble)
            arr[bad] = np.nan
        data = out
    except Exception as exc:  # noqa: BLE001 - a fault in a chunk fails its cases, as data
        messages, warnings, data = numerical_fault(exc, status)
    return array_chunk(grid, lo, hi, t0, status, messages, data, warnings, reasons)


def _starts(grid: SystemGrid, pos: np.ndarray, pforce: np.ndarray) -> list[np.ndarray | None]:
    """The free points' starts (N, k, 3) of the cases whose points are at ``pos``
    (N, n, 3) under the constant forces ``pforce`` (N, n, 3), in the order tried: the
    template's equilibrium plus its first-order response to the case's displacements of
    the other points and changes of the free points' loads, then the equilibrium alone;
    the study's own positions (None) where the template is not settled."""
    if grid.start is None:
        return [None]
    x, at, S, load, flex = grid.start
    N = len(pos)
    free = grid.system.point_kind == FREE
    moved = (pos - at).reshape(N, -1) @ S.T + (pforce[:, free] - load).reshape(N, -1) @ flex.T
    first = x[None] + moved.reshape(N, -1, 3)
    return [first, np.broadcast_to(x, first.shape)]


def _strain_warnings(grid: SystemGrid, out: dict[str, np.ndarray], status: np.ndarray) -> dict:
    """``analysis.static.strain_warning`` per case, worded as case by case
    (:func:`cablestudy.system_cases._strain_warning`): each line's largest strain, T / EA
    of the segment at each node (a grid's lines are linear,
    :func:`cablestudy.statics.system_fast.ineligible`), the lines above the limit named."""
    from .plausibility import largest_strain, strain_warning

    t = grid.template
    limit = t.analysis.static.strain_warning
    names = list(t.lines)
    ea = []
    for m, line in enumerate(t.lines.values()):
        k = segment_of(line.segments, out["arc_length"][0, m])
        ea.append([line.segments[i].elastic_stiffness for i in k])
    strains = largest_strain(out["tension"], np.array(ea))  # (n, M)
    found = {}
    for i in np.flatnonzero((status == 0) & np.any(strains > limit, axis=1)):
        row = np.where(np.isfinite(strains[i]), strains[i], -1.0)
        text = strain_warning(float(strains[i, int(np.argmax(row))]), limit)
        if text:
            over = [names[m] for m in np.flatnonzero(strains[i] > limit)]
            found[int(i)] = f"{text} (lines {', '.join(over)})"
    return found


def _empty_outputs(system: Any, n: int) -> dict[str, np.ndarray]:
    """The output arrays of ``n`` cases (NaN), as :func:`system_cases.system_outputs`
    names and shapes them per case."""
    from ..statics.system_model import FREE

    M = len(system.lines)
    nn = system.lines[0].problem.n_nodes
    k = int(np.count_nonzero(system.point_kind == FREE))
    m = len(system.body_names)
    out = {
        "tension_a": np.full((n, M), np.nan),
        "tension_b": np.full((n, M), np.nan),
        "force_a": np.full((n, M, 3), np.nan),
        "force_b": np.full((n, M, 3), np.nan),
        "x": np.full((n, M, nn), np.nan),
        "y": np.full((n, M, nn), np.nan),
        "z": np.full((n, M, nn), np.nan),
        "tension": np.full((n, M, nn), np.nan),
        "laid_length": np.full((n, M), np.nan),
        "arc_length": np.broadcast_to(
            np.array([np.linspace(0.0, ln.problem.line.total_length, nn) for ln in system.lines]),
            (n, M, nn),
        ).copy(),
        "static_iterations": np.full(n, np.nan),
        "static_residual": np.full(n, np.nan),
    }
    if k:
        out["point_position"] = np.full((n, k, 3), np.nan)
        out["point_seabed_force"] = np.full((n, k, 3), np.nan)
    if m:
        out["body_position"] = np.full((n, m, 6), np.nan)
        out["body_force"] = np.full((n, m, 6), np.nan)
        out["body_stiffness"] = np.full((n, m, 6, 6), np.nan)
    return out


def _put(out: dict[str, np.ndarray], rows: np.ndarray, sol: Any, system: Any) -> None:
    """The compiled path's solutions ``sol`` into rows ``rows`` of ``out``."""
    from ..statics.system_model import FREE

    out["tension_a"][rows] = np.linalg.norm(sol.force_a, axis=2)
    out["tension_b"][rows] = np.linalg.norm(sol.force_b, axis=2)
    out["force_a"][rows] = sol.force_a
    out["force_b"][rows] = sol.force_b
    out["x"][rows] = sol.position[..., 0]
    out["y"][rows] = sol.position[..., 1]
    out["z"][rows] = sol.position[..., 2]
    out["tension"][rows] = sol.tension
    out["laid_length"][rows] = sol.laid_length
    out["static_iterations"][rows] = sol.iterations.astype(float)
    out["static_residual"][rows] = sol.residual
    if "point_position" in out:
        out["point_position"][rows] = sol.point_position[:, system.point_kind == FREE]
        out["point_seabed_force"][rows] = 0.0  # the compiled Newton's points are off it
    if "body_force" in out:
        out["body_force"][rows] = sol.body_force
        out["body_stiffness"][rows] = sol.body_stiffness


def _general(
    system: Any,
    poses: np.ndarray,
    base: np.ndarray,
    pforce: np.ndarray,
    out: dict[str, np.ndarray],
    i: int,
    time_limit: float,
) -> tuple[int, str]:
    """Case ``i`` by the general path (from the study's starting positions): its outputs
    into row ``i`` of ``out``; returns its status and message."""
    from ..statics import STATIC_SOLVERS
    from ..statics.system import solve_system
    from .system import system_outputs

    case = replace(system, body_position=poses, point_position=base, point_force=pforce)
    deadline = time.monotonic() + time_limit  # analysis.time_limit, as case by case
    res = solve_system(case, STATIC_SOLVERS["catenary"], deadline=deadline, compiled=False)
    data = system_outputs(case, res)
    for name, arr in out.items():
        if name in data and name != "body_position":
            arr[i] = data[name]
    return int(res.status), res.message
