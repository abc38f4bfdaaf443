"""Writing one case of a system study (points, bodies, lines) as a MoorDyn v2 input file.

Bodies are numbered in the study's order: a prescribed body is a ``Coupled`` body at its
position, a free body a ``Free`` body with its mass, centre of gravity and volume, at
the position the statics find. Points are numbered in the study's order: fixed points
``Fixed``, free points ``Free`` (with mass and volume, at their static position), body
points ``Body#`` at their offset. Each study line is one MoorDyn line of its own line
type when it has one segment and no attachments; otherwise it is cut at its segment
joints and attachments into a chain of MoorDyn lines joined at free points (carrying
the attachments' mass and volume), numbered after the study's single lines.

What MoorDyn v2 cannot hold is refused naming the key: a steady force on a point or a
free body, a centre of buoyancy off a free body's reference point (MoorDyn's buoyancy
acts there), nonlinear axial laws. Body angles are converted to MoorDyn's order of
rotations (:func:`.system_import.moordyn_angles`).
"""

from __future__ import annotations

import math
from types import SimpleNamespace
from typing import Any

import numpy as np

from ..physics.contact import default_seabed_stiffness
from ..study import Study
from ..study.problem import line_model
from ..study.system import BodyPoint, FixedPoint, FreeBody, FreePoint
from .export import (
    ExportedCase,
    _floor125,
    _num,
    added_damping,
    axial_step,
    current_table,
    file_text,
    seabed_options,
    time_options,
    type_row,
)
from .moordyn_format import InterchangeError
from .system_import import moordyn_angles


def _refuse(study: Study) -> None:
    for name, point in study.points.items():
        if isinstance(point, FreePoint) and any(point.force):
            raise InterchangeError(
                f"points.{name}.force: a steady force {point.force} N has no MoorDyn v2 "
                "equivalent (points carry mass and volume only); give it as mass or volume"
            )
    for name, body in study.bodies.items():
        if isinstance(body, FreeBody):
            if any(body.force):
                raise InterchangeError(
                    f"bodies.{name}.force: a steady force {body.force} N on a body has no "
                    "MoorDyn v2 equivalent"
                )
            if body.waterplane_area:
                raise InterchangeError(
                    f"bodies.{name}.waterplane_area: {body.waterplane_area} m^2; a MoorDyn v2 "
                    "body has no hydrostatic stiffness (allowed: 0)"
                )
            if any(body.center_of_buoyancy):
                raise InterchangeError(
                    f"bodies.{name}.center_of_buoyancy: {body.center_of_buoyancy} m; MoorDyn's "
                    "body buoyancy acts at its reference point (allowed: [0, 0, 0])"
                )
    for name, line in study.lines.items():
        for i, seg in enumerate(line.segments):
            if seg.axial is not None and seg.axial.law != "linear":
                raise InterchangeError(
                    f"lines.{name}.segments.{i}.axial: the {seg.axial.law} law is not "
                    "exported (the MoorDyn file takes a linear EA here); give axial_stiffness"
                )
        for i, att in enumerate(line.attachments):
            if any(att.force):
                raise InterchangeError(
                    f"lines.{name}.attachments.{i}.force: a steady force {att.force} N has no "
                    "MoorDyn v2 equivalent (points carry mass and volume only)"
                )


def system_moordyn_input(study: Study, result: Any, *, title: str) -> ExportedCase:
    """A MoorDyn v2 input file of a system study's case.

    Parameters
    ----------
    study : the case's study (a system)
    result : its solved statics (:class:`cablestudy.statics.system.SystemResult`)
    title : front-matter line
    """
    _refuse(study)
    env = study.environment
    rho, g = env.density, env.gravity
    warnings: list[str] = []
    body_ids = {name: k + 1 for k, name in enumerate(study.bodies)}
    point_ids = {name: k + 1 for k, name in enumerate(study.points)}
    positions = np.asarray(result.point_position, dtype=float)
    body_rows = []
    for k, (name, body) in enumerate(study.bodies.items()):
        pos = (
            np.asarray(result.body_position[k], dtype=float)
            if result.body_position is not None
            else np.asarray(body.position, dtype=float)
        )
        angles = moordyn_angles(pos[3:])
        if isinstance(body, FreeBody):
            cg = "|".join(_num(c) for c in body.center_of_gravity)
            row = f"Free  {_num(body.mass)}  {cg}  0  {_num(body.volume)}  0  0"
            warnings.append(
                f"bodies.{name}: written with no inertia, drag or added mass (the study's "
                "statics need none; give them in the file for MoorDyn's dynamics)"
            )
        else:
            row = "Coupled  0  0  0  0  0  0"
        kind, rest = row.split("  ", 1)
        body_rows.append(
            f"{body_ids[name]}  {kind}  "
            + "  ".join(_num(v) for v in [*pos[:3], *angles])
            + f"  {rest}   ! {name}"
        )
    point_rows = []
    for name, point in study.points.items():
        pid = point_ids[name]
        if isinstance(point, FixedPoint):
            kind, xyz, mass, vol = "Fixed", point.position, 0.0, 0.0
        elif isinstance(point, FreePoint):
            kind, xyz = "Free", positions[pid - 1]
            mass, vol = point.mass, point.volume
        else:
            assert isinstance(point, BodyPoint)
            kind, xyz, mass, vol = f"Body{body_ids[point.body]}", point.offset, 0.0, 0.0
        cda = point.drag_area if isinstance(point, FreePoint) else 0.0
        # MoorDyn's point added mass is Ca rho V (as a line's lumped body, export.py)
        added = point.added_mass if isinstance(point, FreePoint) else 0.0
        ca = added / (rho * vol) if vol > 0.0 and rho > 0.0 else 0.0
        if added > 0.0 and ca == 0.0:
            warnings.append(
                f"points.{name}.added_mass: {added:g} kg with no displaced volume has no "
                "MoorDyn Ca (MoorDyn's point added mass is Ca rho V); written as 0"
            )
        point_rows.append(
            f"{pid}  {kind}  {'  '.join(_num(v) for v in xyz)}  {_num(mass)}  {_num(vol)}  "
            f"{_num(cda)}  {_num(ca)}   ! {name}"
        )
    n_nodes = study.analysis.static.nodes
    type_rows: list[tuple[str, Any, float]] = []
    line_rows: list[str] = []
    chained: list[tuple[str, int, int, Any, list[tuple[float, float, float, float]]]] = []
    pieces = []  # (segment, node length) of each MoorDyn line

    def add_line(lid: int, seg: Any, a: int, b: int, length: float, nseg: int, note: str) -> None:
        m = seg.mass_in(rho, g)
        tname = f"type{len(type_rows) + 1}"
        type_rows.append((tname, seg, m))
        line_rows.append(f"{lid}  {tname}  {a}  {b}  {_num(length)}  {nseg}  -   ! {note}")
        pieces.append((seg, length / nseg))

    for k, (name, line) in enumerate(study.lines.items()):
        a, b = point_ids[line.a], point_ids[line.b]
        if len(line.segments) == 1 and not line.attachments:
            seg = line.segments[0]
            add_line(k + 1, seg, a, b, seg.length, n_nodes - 1, name)
        else:
            chained.append((name, a, b, line, []))
    next_line, next_point = len(study.lines) + 1, len(study.points) + 1
    for name, a, b, line, _ in chained:
        res = result.lines[list(study.lines).index(name)]
        shape = np.asarray(res.position, dtype=float)
        bounds = np.concatenate([[0.0], np.cumsum([s.length for s in line.segments])])
        total = float(bounds[-1])
        s_nodes = np.linspace(0.0, total, shape.shape[0])
        cuts = {float(c): [0.0, 0.0] for c in bounds}
        for j, att in enumerate(line.attachments):
            if att.s <= 0.0 or att.s >= total:
                raise InterchangeError(
                    f"lines.{name}.attachments.{j}: at s = {att.s:g} m, on an end point; give "
                    "its mass and volume to that point"
                )
            key = min(cuts, key=lambda c, s=att.s: abs(c - s))
            if abs(key - att.s) > 1e-9 * total:
                key = float(att.s)
                cuts[key] = [0.0, 0.0]
            cuts[key][0] += att.mass
            cuts[key][1] += att.volume
            if att.added_mass or att.drag_area:
                warnings.append(
                    f"lines.{name}.attachments.{j}: added mass and drag area not written "
                    "(statics only)"
                )
        stations = sorted(cuts)
        ids = [a]
        for s in stations[1:-1]:
            xyz = [float(np.interp(s, s_nodes, shape[:, c])) for c in range(3)]
            mass, vol = cuts[s]
            point_rows.append(
                f"{next_point}  Free  {'  '.join(_num(v) for v in xyz)}  {_num(mass)}  "
                f"{_num(vol)}  0  0   ! {name} at s = {_num(s)} m"
            )
            ids.append(next_point)
            next_point += 1
        ids.append(b)
        for j in range(len(stations) - 1):
            s0, s1 = stations[j], stations[j + 1]
            seg = line.segments[int(np.searchsorted(bounds, 0.5 * (s0 + s1)) - 1)]
            nseg = max(1, round((n_nodes - 1) * (s1 - s0) / total))
            add_line(next_line, seg, ids[j], ids[j + 1], s1 - s0, nseg, f"{name}, part {j + 1}")
            next_line += 1
        warnings.append(
            f"lines.{name}: written as a chain of MoorDyn lines through free points (a "
            "MoorDyn line has one line type and no attachments); re-imported, it is a "
            "system of those lines"
        )
    dt, fastest = axial_step(pieces, rho, g)
    opts = [f"{_num(g)}  g", f"{_num(rho)}  rho"]
    if env.depth is not None:
        opts.append(f"{_num(env.depth)}  WtrDpth")
        if env.seabed.stiffness is not None:
            stiffness = env.seabed.stiffness
        else:
            lines = [
                line_model(SimpleNamespace(environment=env, line=ln))  # type: ignore[arg-type]
                for ln in study.lines.values()
            ]
            stiffness = max(default_seabed_stiffness(lm.weight) for lm in lines)
        rows, warned, dt_bed = seabed_options(env, pieces, stiffness)
        opts += rows
        warnings += warned
        dt = min(dt, dt_bed)
    else:
        lowest = min(float(np.min(np.asarray(r.position)[:, 2])) for r in result.lines)
        longest = max(ln.length for ln in study.lines.values())
        deep = math.ceil(-lowest + 10.0 * longest)
        opts.append(
            f"{deep}  WtrDpth   ! the study has no seabed: placed 10 line lengths below the "
            "lowest point, out of reach"
        )
    dtm = _floor125(dt)
    opts += time_options(dt)
    damping, warned = added_damping(fastest, dtm)
    warnings += warned
    extra = current_table(study, opts)
    text = file_text(
        [f"MoorDyn v2 input file written by cablestudy: {title}"],
        [type_row(*row, damping) for row in type_rows],
        body_rows,
        point_rows,
        line_rows,
        opts,
        ["FairTen1"],
    )
    return ExportedCase(text, extra, warnings, {}, dtm)
