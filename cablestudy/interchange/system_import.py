"""From a whole MoorDyn file to one system study: every line, point and body.

A MoorDyn file whose lines do not form one chain is a mooring system; it becomes a study
with ``points``, ``bodies`` and ``lines`` (:mod:`cablestudy.study.system`):

- each line keeps its ID as its name (``"1"``, ``"2"``...) and becomes one segment of its
  line type between its two points;
- a ``Fixed``/``Anchor`` point is a fixed point; a ``Free``/``Connect`` point is a free
  point with its mass, volume and steady force (its drag area and added mass act in
  dynamics only and are listed as not used);
- ``Coupled``/``Vessel``/``Fairlead`` points are points of one prescribed body ``vessel``
  at the origin, each at its position as offset, so that a sweep of the vessel's position
  moves them together (the restoring curve); a ``Body#`` point is a point of body ``#`` at
  its offset;
- a fixed or coupled body is prescribed at its position; a free body is found by
  equilibrium with its mass, volume (buoyancy at its reference point, as MoorDyn) and
  centre of gravity;
- the options map as the one-line importer maps them (:func:`.mapping.environment`).

A body's roll, pitch and yaw are converted between MoorDyn's order of rotations
(R = Rx Ry Rz) and the study's (R = Rz Ry Rx): the same rotation matrix.

A steady current (``Currents 1``, its table beside the file) drags the lines and, by their
``CdA``, the free points. What a system study cannot hold (rods, pinned bodies, nonlinear
EA, lines near the sea surface) is refused by name before
anything is built; what it does not use is listed in the warnings.
"""

from __future__ import annotations

import math
import re
from typing import Any

import numpy as np

from ..statics.system import rotation
from .mapping import ImportedStudy, _line_type, _seabed_contact, _segment, environment
from .moordyn_format import InterchangeError, MoorDynFile
from .moordyn_scope import check_chain, point_of

#: the body that holds a file's Coupled / Vessel points
VESSEL = "vessel"


def _moordyn_rotation(angles: np.ndarray) -> np.ndarray:
    """MoorDyn's body rotation R = Rx(roll) Ry(pitch) Rz(yaw) of ``angles`` [rad]
    (MoorDyn v2's EulerXYZ, checked against the moordyn package's point positions)."""
    (cr, cp, cy), (sr, sp, sy) = np.cos(angles), np.sin(angles)
    rx = np.array([[1.0, 0.0, 0.0], [0.0, cr, -sr], [0.0, sr, cr]])
    ry = np.array([[cp, 0.0, sp], [0.0, 1.0, 0.0], [-sp, 0.0, cp]])
    rz = np.array([[cy, -sy, 0.0], [sy, cy, 0.0], [0.0, 0.0, 1.0]])
    return rx @ ry @ rz


def study_angles(rotation_deg: tuple[float, float, float] | list[float]) -> list[float]:
    """A study body's roll, pitch, yaw [rad] (R = Rz Ry Rx) turning it as MoorDyn's
    ``r0 p0 y0`` [deg] (R = Rx Ry Rz) do: the same rotation matrix."""
    r = _moordyn_rotation(np.radians(np.asarray(rotation_deg, dtype=float)))
    pitch = math.asin(max(-1.0, min(1.0, -r[2, 0])))
    return [math.atan2(r[2, 1], r[2, 2]), pitch, math.atan2(r[1, 0], r[0, 0])]


def moordyn_angles(angles: list[float] | np.ndarray) -> list[float]:
    """MoorDyn's ``r0 p0 y0`` [deg] of a study body's roll, pitch, yaw [rad]: the inverse
    of :func:`study_angles`."""
    r = rotation(np.asarray(angles, dtype=float))
    pitch = math.asin(max(-1.0, min(1.0, r[0, 2])))
    return [
        math.degrees(math.atan2(-r[1, 2], r[2, 2])),
        math.degrees(pitch),
        math.degrees(math.atan2(-r[0, 1], r[0, 0])),
    ]


def _point_name(number: int) -> str:
    return f"point{number}"


def _body_name(number: int) -> str:
    return f"body{number}"


def moordyn_system_to_study(
    md: MoorDynFile, *, name: str, current: list[dict[str, float]] | None = None
) -> ImportedStudy:
    """The system study of every line, point and body of ``md`` (module docstring)."""
    src = md.source
    warnings: list[str] = list(md.notes)
    comments: dict[tuple[str | int, ...], str] = {}
    lines = [md.lines[i] for i in sorted(md.lines)]
    refusals = check_chain(md, lines, ())
    used: dict[int, None] = {}
    for ln in lines:
        for key in (ln.attach_a, ln.attach_b):
            pt = point_of(md, key)
            if pt is None and not key.upper().startswith("R"):
                raise InterchangeError(
                    f"{src}:{ln.source_line}: line {ln.id} is attached to point {key}, which "
                    f"the file does not define; defined points: "
                    f"{', '.join(str(p) for p in sorted(md.points))}"
                )
            if pt is not None:
                used[pt.id] = None
    bodies_used: dict[int, None] = {}
    for pid in used:
        pt = md.points[pid]
        if pt.kind == "body":
            body = md.bodies.get(pt.body or 0)
            if body is None:
                raise InterchangeError(
                    f"{src}:{pt.source_line}: point {pt.id} is attached to {pt.attachment}, "
                    "which the file does not define; bodies: "
                    f"{', '.join(str(b) for b in sorted(md.bodies)) or 'none'}"
                )
            bodies_used[body.id] = None
    for bid in bodies_used:
        body = md.bodies[bid]
        where = f"{src}:{body.source_line}"
        for rod in md.rods.values():
            held = re.fullmatch(r"body(\d+)\w*", rod.attachment, flags=re.IGNORECASE)
            if held and int(held.group(1)) == bid:
                refusals.add(
                    "rods",
                    f"{src}:{rod.source_line}",
                    f"rod {rod.id} on body {bid} loads it with its weight and buoyancy",
                )
        if body.kind == "coupled_pinned":
            refusals.add("pinned_bodies", where, f"body {body.id} ({body.attachment})")
    rho_opt = md.option("rho", "rhoW", "WtrDnsty")
    dry = rho_opt is not None and float(rho_opt.value) == 0.0
    for ln in lines:
        for key in (ln.attach_a, ln.attach_b):
            pt = point_of(md, key)
            if pt is None or dry:
                continue
            z = pt.position[2]
            if pt.kind == "body":
                body = md.bodies[pt.body or 0]
                turned = _moordyn_rotation(np.radians(body.rotation_deg)) @ pt.position
                z = body.position[2] + float(turned[2])
            if z > 0.0:
                refusals.add(
                    "surface_crossing",
                    f"{src}:{ln.source_line}",
                    f"line {ln.id} ends at point {pt.id}, z = {z:g} m above the surface, "
                    "where MoorDyn gives it no buoyancy",
                )
    refusals.raise_if_any(src, "the system of lines " + ", ".join(str(ln.id) for ln in lines))

    env, rho = environment(md, current, False, comments, warnings)
    if "bodies" in md.sections:  # the system imports the bodies its lines hang on
        where = f"{src}:{md.sections['bodies'][1]}: section "
        warnings[:] = [w for w in warnings if not w.startswith(where)]

    # ----------------------------------------------------------------- bodies
    bodies: dict[str, Any] = {}
    for bid in bodies_used:
        body = md.bodies[bid]
        bname = _body_name(bid)
        where = f"{src}:{body.source_line} body {body.id} ({body.attachment})"
        position = [*body.position, *study_angles(body.rotation_deg)]
        if body.kind == "free":
            bodies[bname] = {
                "kind": "free",
                "position": position,
                "mass": body.mass,
                "volume": body.volume,
                "center_of_gravity": list(body.center_of_gravity),
            }
            comments[("bodies", bname)] = (
                f"{where}: found by equilibrium; its buoyancy acts at the reference point, "
                "as in MoorDyn; position is the starting guess [m, rad]"
            )
            warnings.append(
                f"{where}: inertia {list(body.inertia)} kg m^2, CdA {list(body.drag_area)} "
                f"m^2 and Ca {list(body.added_mass)} act in dynamics only: not used in statics"
            )
        else:
            bodies[bname] = {"kind": "prescribed", "position": position}
            comments[("bodies", bname)] = f"{where}: held at its position [m, rad]"
    unused = [b for b in sorted(md.bodies) if b not in bodies_used]
    if unused:
        warnings.append(
            f"{src}: bodies {', '.join(str(b) for b in unused)} hold no line: not imported"
        )

    # ----------------------------------------------------------------- points
    points: dict[str, Any] = {}
    for pid in sorted(used):
        pt = md.points[pid]
        pname = _point_name(pid)
        where = f"{src}:{pt.source_line} point {pt.id} ({pt.attachment})"
        if pt.kind == "fixed":
            points[pname] = {"kind": "fixed", "position": list(pt.position)}
        elif pt.kind == "free":
            entry: dict[str, Any] = {"kind": "free", "position": list(pt.position)}
            if pt.mass:
                entry["mass"] = pt.mass
            if pt.volume:
                entry["volume"] = pt.volume
            if any(pt.force):
                entry["force"] = list(pt.force)
            if current and pt.drag_area:
                entry["drag_area"] = pt.drag_area  # its drag in the steady current
            points[pname] = entry
            where += ": found by equilibrium, position is the starting guess"
            unused = [] if current else [f"CdA = {pt.drag_area:g} m^2"] * bool(pt.drag_area)
            unused += [f"Ca = {pt.added_mass:g}"] * bool(pt.added_mass)
            if unused:
                warnings.append(
                    f"{src}:{pt.source_line}: point {pt.id}: {' and '.join(unused)} (a "
                    "point's drag without a current, its added mass) act in dynamics only: "
                    "not used in statics"
                )
        elif pt.kind == "coupled":
            points[pname] = {"kind": "body", "body": VESSEL, "offset": list(pt.position)}
            bodies.setdefault(VESSEL, {"kind": "prescribed", "position": [0.0] * 6})
            comments[("bodies", VESSEL)] = (
                "holds the file's coupled points at their positions; sweep its position "
                "for the restoring curve"
            )
            where += f": on body {VESSEL} (at the origin), offset = the point's position"
        else:
            points[pname] = {
                "kind": "body",
                "body": _body_name(pt.body or 0),
                "offset": list(pt.position),
            }
            where += ": offset from the body's reference point"
        comments[("points", pname)] = where
    unused_points = [p for p in sorted(md.points) if p not in used]
    if unused_points:
        warnings.append(
            f"{src}: points {', '.join(str(p) for p in unused_points)} hold no line: not imported"
        )

    # ------------------------------------------------------------------ lines
    study_lines: dict[str, Any] = {}
    segments: list[dict[str, Any]] = []
    for ln in lines:
        lt = _line_type(md, ln)
        seg = _segment(md, lt, ln, warnings)
        lname = str(ln.id)
        study_lines[lname] = {
            "a": _point_name(point_of(md, ln.attach_a).id),  # type: ignore[union-attr]
            "b": _point_name(point_of(md, ln.attach_b).id),  # type: ignore[union-attr]
            "segments": [seg],
        }
        segments.append(seg)
        comments[("lines", lname)] = (
            f"{src}:{ln.source_line} line {ln.id}; {src}:{lt.source_line} type {lt.name}"
        )
    if env.get("depth"):
        before = len(warnings)
        _seabed_contact(md, env, segments, rho, comments, warnings)
        # each line is one segment: name the line the contact is scaled on
        ref = max(range(len(segments)), key=lambda i: segments[i]["diameter"])
        word, said = f"segment {ref}'s", f"line {lines[ref].id}'s"
        for key in (("environment", "seabed", k) for k in ("stiffness", "damping_ratio")):
            comments[key] = comments[key].replace(word, said)
        warnings[before:] = [w.replace(word, said) for w in warnings[before:]]
    data: dict[str, Any] = {
        "name": name,
        "description": f"imported from {src} ({md.format_name}), the whole system: "
        f"lines {', '.join(study_lines)}",
        "environment": env,
        "points": points,
    }
    if bodies:
        data["bodies"] = bodies
    data["lines"] = study_lines
    static: dict[str, Any] = {}
    if all(ln.segments > 0 for ln in lines):
        most = max(ln.segments for ln in lines)
        static["nodes"] = most + 1
        comments[("analysis", "static", "nodes")] = f"the largest NumSegs {most} of the lines, + 1"
    if any(seg["bending_stiffness"] > 0.0 for seg in segments):
        static["method"] = "discrete"
        comments[("analysis", "static", "method")] = (
            "a line type has EI > 0: the static method that carries bending (each line "
            "pinned at its ends, as MoorDyn's lines are)"
        )
    if static:
        data["analysis"] = {"static": static}
    return ImportedStudy(data=data, comments=comments, warnings=warnings)
