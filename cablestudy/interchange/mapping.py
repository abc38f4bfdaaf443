"""From MoorDyn tables to a cablestudy study: one line of line types, points and options.

A cablestudy line runs from end A to end B through uniform segments, with point loads
along it. A MoorDyn system is a graph of lines meeting at points; one cablestudy line
is a chain of MoorDyn lines, joined end to end at free points. The chain's two outer
points become the ends (a fixed or coupled point, or a point on a held body: a fixed end
at its position; a free point that no other line holds: a towing end loaded by the
point's weight, buoyancy and steady force), the points inside it become attachments
(mass, volume, steady force), and consecutive MoorDyn lines of one line type merge into
one segment.

What the chain needs and cablestudy lacks (rods, moving bodies, a free point other lines
pull on, ...) is refused by name before anything is built
(:mod:`cablestudy.interchange.moordyn_scope`); what the file holds and cablestudy does
not model is listed by name in :attr:`ImportedStudy.warnings`; nothing is dropped
silently.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from ..study.environment import FLUID_DENSITY
from .moordyn_format import (
    InterchangeError,
    Line,
    LineType,
    MoorDynFile,
    MoorDynFormatError,
    Point,
)
from .moordyn_scope import (
    FEATURES,
    NotModelledError,
    Refusals,
    absolute_position,
    check_chain,
    option_value,
    option_warnings,
    point_of,
    water_depth,
)
from .seabed import DEFAULT_CBOT, DEFAULT_KBOT, from_moordyn

#: MoorDyn's default gravity (MoorDyn2.cpp sets env->g = 9.80665; MoorDyn-F and the
#: version 1 C code use the same value)
DEFAULT_GRAVITY = 9.80665
DEFAULT_DENSITY = 1025.0
#: MoorPy's default gravity (``moorpy.System(g=9.81)``), which a MoorPy design YAML
#: without one takes
MOORPY_GRAVITY = 9.81


@dataclass
class ImportedStudy:
    """Study data (plain YAML-ready values), comments by YAML path, and warnings."""

    data: dict[str, Any]
    comments: dict[tuple[str | int, ...], str] = field(default_factory=dict)
    warnings: list[str] = field(default_factory=list)


def select_chain(md: MoorDynFile, ids: list[int] | None) -> tuple[list[tuple[Line, bool]], str]:
    """The MoorDyn lines ``ids`` (all lines if None) ordered end to end as one chain.

    Returns (line, reversed) pairs from end A to end B and the key of end A's point.
    The chain starts at a fixed point where it has one (MoorDyn's anchor end), else at
    the A end of the lowest-numbered line."""
    if ids is None:
        ids = sorted(md.lines)
    missing = [i for i in ids if i not in md.lines]
    if missing:
        raise InterchangeError(
            f"{md.source}: no line {missing[0]}; the file has lines "
            f"{', '.join(str(i) for i in sorted(md.lines))}"
        )
    chosen = [md.lines[i] for i in dict.fromkeys(ids)]
    touching: dict[str, list[Line]] = {}
    for ln in chosen:
        for key in (ln.attach_a, ln.attach_b):
            touching.setdefault(key, []).append(ln)
    for key, lines in touching.items():
        if len(lines) > 2:
            raise NotModelledError(
                f"{md.source}: lines {', '.join(str(ln.id) for ln in lines)} meet at point "
                f"{key}: a branched system (e.g. a bridle) is not one line ("
                f"{FEATURES['systems']} are imported whole, without --line); choose the lines "
                "of one line from anchor to fairlead with --line (or line: [ids])",
                ["systems"],
            )
    ends = [k for k, lines in touching.items() if len(lines) == 1]
    if len(ends) != 2:
        raise NotModelledError(
            f"{md.source}: lines {', '.join(str(ln.id) for ln in chosen)} do not form one "
            "chain end to end (a cablestudy line is a single chain of lines joined at "
            f"points; {FEATURES['systems']} are imported whole, without --line); choose "
            "them with --line",
            ["systems"],
        )

    def fixed(key: str) -> bool:
        pt = point_of(md, key)
        return pt is not None and pt.kind == "fixed"

    first = chosen[0]
    if fixed(ends[0]) != fixed(ends[1]):
        start = ends[0] if fixed(ends[0]) else ends[1]
    else:
        start = first.attach_a if first.attach_a in ends else ends[0]
    order: list[tuple[Line, bool]] = []
    at, used = start, set()
    while len(order) < len(chosen):
        nxt = [ln for ln in touching[at] if ln.id not in used]
        if not nxt:
            break
        ln = nxt[0]
        used.add(ln.id)
        rev = ln.attach_b == at and ln.attach_a != at
        order.append((ln, rev))
        at = ln.attach_a if rev else ln.attach_b
    if len(order) != len(chosen):
        raise InterchangeError(
            f"{md.source}: lines {', '.join(str(ln.id) for ln in chosen)} do not form one "
            "chain end to end; choose them with --line"
        )
    return order, start


def _no_lines(md: MoorDynFile) -> None:
    """Refuse a file without lines: by its rods and bodies if it has them."""
    held = [f"{len(md.rods)} rod(s)"] * bool(md.rods) + [f"{len(md.bodies)} body(ies)"] * bool(
        md.bodies
    )
    if not held:
        raise MoorDynFormatError(
            f"{md.source}: no lines found; a MoorDyn file needs a LINES section (or LINE "
            "PROPERTIES, LINE LIST) with at least one line"
        )
    features = ["rods"] * bool(md.rods) + ["bodies"] * bool(md.bodies)
    raise NotModelledError(
        f"{md.source}: the file has no lines, only {' and '.join(held)}: "
        + "; ".join(FEATURES[f] for f in features)
        + " are not modelled by cablestudy",
        features,
    )


def _need_point(md: MoorDynFile, key: str, line: Line) -> Point:
    pt = point_of(md, key)
    if pt is None:
        if key.upper().startswith("R"):
            raise NotModelledError(
                f"{md.source}:{line.source_line}: line {line.id} is attached to rod end "
                f"{key}: {FEATURES['rods']} are not modelled by cablestudy",
                ["rods"],
            )
        raise InterchangeError(
            f"{md.source}:{line.source_line}: line {line.id} is attached to point {key}, "
            f"which the file does not define; defined points: "
            f"{', '.join(str(p) for p in sorted(md.points))}"
        )
    return pt


def _line_type(md: MoorDynFile, ln: Line) -> LineType:
    """The line type of line ``ln`` (refused when the file does not define it)."""
    lt = md.line_types.get(ln.line_type)
    if lt is None:
        raise InterchangeError(
            f"{md.source}:{ln.source_line}: line {ln.id} uses line type {ln.line_type!r}, "
            f"which the file does not define; defined: {', '.join(md.line_types) or 'none'}"
        )
    return lt


def _segment(md: MoorDynFile, lt: LineType, line: Line, warnings: list[str]) -> dict[str, Any]:
    where = f"{md.source}:{lt.source_line}"
    try:
        ea = float(lt.axial_stiffness)
    except ValueError:
        raise InterchangeError(
            f"{where}: line type {lt.name!r} has a nonlinear or viscoelastic EA "
            f"({lt.axial_stiffness!r}); cablestudy models a linear EA [N] only"
        ) from None
    ba_text = lt.damping
    if "|" in ba_text:
        warnings.append(
            f"{where}: line type {lt.name!r}: BA {ba_text!r} has static|dynamic parts; "
            "the first (static) is used"
        )
        ba_text = ba_text.split("|")[0]
    try:
        ba = float(ba_text)
    except ValueError:
        raise InterchangeError(
            f"{where}: line type {lt.name!r}: BA/-zeta must be a number"
        ) from None
    if ba <= 0.0:
        zeta = -ba if ba < 0.0 else 0.0
    else:
        seg_len = line.length / max(line.segments, 1)
        zeta = ba / (seg_len * math.sqrt(ea * lt.mass_per_length)) if lt.mass_per_length else 0.0
        warnings.append(
            f"{where}: line type {lt.name!r}: BA = {ba:g} N s is a damping coefficient; "
            f"cablestudy takes a damping ratio, converted at MoorDyn's segment length "
            f"{seg_len:g} m to zeta = {zeta:.4g} (our elements may differ in length)"
        )
    if zeta > 1.0:
        warnings.append(
            f"{where}: line type {lt.name!r}: damping ratio {zeta:g} above critical; "
            "limited to 1.0 (cablestudy allows 0 to 1)"
        )
        zeta = 1.0
    for key, value in lt.extra.items():
        try:
            nonzero = float(value) != 0.0
        except ValueError:
            nonzero = True
        if nonzero and key in ("Cl",):
            warnings.append(
                f"{where}: line type {lt.name!r}: Cl = {value} (vortex-induced vibration) "
                "is not modelled"
            )
        elif key.startswith("column"):
            warnings.append(f"{where}: line type {lt.name!r}: extra {key} ({value}) not read")
    if line.outputs not in ("-", ""):
        warnings.append(
            f"{md.source}:{line.source_line}: line {line.id} outputs {line.outputs!r} not "
            "used (cablestudy writes every output)"
        )
    return {
        "length": line.length,
        "diameter": lt.diameter,
        "mass_per_length": lt.mass_per_length,
        "axial_stiffness": ea,
        "drag_normal": lt.drag_normal,
        "drag_tangential": lt.drag_tangential,
        "added_mass_normal": lt.added_mass_normal,
        "added_mass_tangential": lt.added_mass_tangential,
        "bending_stiffness": lt.bending_stiffness,
        "damping_ratio": zeta,
    }


def _point_load(pt: Point, md: MoorDynFile, warnings: list[str], role: str) -> None:
    """A free end point's drag and added mass: a ``force`` end carries a constant force
    only, so they are reported, not mapped."""
    where = f"{md.source}:{pt.source_line}"
    if pt.drag_area != 0.0 or pt.added_mass != 0.0:
        warnings.append(
            f"{where}: point {pt.id} ({role}): CdA = {pt.drag_area:g} m^2 and Ca = "
            f"{pt.added_mass:g} (drag and added mass of a point) are not modelled at a "
            "free end (a force end carries its force only)"
        )


def _seabed_contact(
    md: MoorDynFile,
    env: dict[str, Any],
    segments: list[dict[str, Any]],
    rho: float,
    comments: dict[tuple[str | int, ...], str],
    warnings: list[str],
) -> None:
    """MoorDyn's kBot / cBot (or its defaults) as the study's contact stiffness and
    damping ratio (:mod:`cablestudy.interchange.seabed`), on the segment of largest
    diameter."""
    src = md.source
    kb = option_value(md, "kBot", "kb")
    cb = option_value(md, "cBot", "cb")
    ref = max(range(len(segments)), key=lambda i: segments[i]["diameter"])
    seg = segments[ref]
    d = seg["diameter"]
    m_n = seg["mass_per_length"] + rho * math.pi * d * d / 4.0 * seg["added_mass_normal"]
    kbot = kb[0] if kb else DEFAULT_KBOT
    cbot = cb[0] if cb else DEFAULT_CBOT
    stiffness, ratio = from_moordyn(kbot, cbot, diameter=d, mass=m_n)
    seabed = env.setdefault("seabed", {})
    seabed["stiffness"] = stiffness
    seabed["damping_ratio"] = ratio
    how = f"segment {ref}'s diameter {d:g} m"
    comments[("environment", "seabed", "stiffness")] = (
        f"{src}:{kb[1]} kBot" if kb else f"MoorDyn default kBot = {DEFAULT_KBOT:g} Pa/m"
    ) + f" x {how}"
    comments[("environment", "seabed", "damping_ratio")] = (
        f"{src}:{cb[1]} cBot" if cb else f"MoorDyn default cBot = {DEFAULT_CBOT:g} Pa s/m"
    ) + f" x {how}, over 2 sqrt(k m)"
    if len({sg["diameter"] for sg in segments}) > 1:
        warnings.append(
            f"{src}: MoorDyn's seabed stiffness kBot acts on each line type's diameter; the "
            f"study has one contact stiffness per length, kBot x {how} = {stiffness:.6g} "
            "N/m^2, so the thinner segments rest on a stiffer seabed than in MoorDyn"
        )


def moordyn_to_study(
    md: MoorDynFile,
    ids: list[int] | None = None,
    *,
    name: str = "moordyn-import",
    current: list[dict[str, float]] | None = None,
) -> ImportedStudy:
    """The study of one line of a MoorDyn system (see the module docstring).

    Parameters
    ----------
    md : the parsed file
    ids : MoorDyn line IDs forming the chain (None: all lines)
    name : study name
    current : current profile points {z, speed, heading_deg} read from the file's
        steady current table (``Currents 1``), if any
    """
    warnings: list[str] = []
    comments: dict[tuple[str | int, ...], str] = {}
    src = md.source
    if not md.lines:
        _no_lines(md)
    chain, start = select_chain(md, ids)
    end_b_key = start
    for ln, rev in chain:
        end_b_key = ln.attach_a if rev else ln.attach_b
    scope = check_chain(md, [ln for ln, _ in chain], (start, end_b_key))
    scope.raise_if_any(src, "line(s) " + ", ".join(str(ln.id) for ln, _ in chain))
    warnings.extend(md.notes)

    # ------------------------------------------------------------ environment
    env, rho = environment(md, current, scope.above_surface, comments, warnings)

    # ------------------------------------------------------------------- line
    segments: list[dict[str, Any]] = []
    seg_types: list[str] = []
    attachments: list[dict[str, Any]] = []
    nsegs = 0
    s = 0.0
    at = start
    for k, (ln, rev) in enumerate(chain):
        lt = _line_type(md, ln)
        if k > 0:
            pt = _need_point(md, at, ln)
            if pt.kind != "free":
                raise InterchangeError(
                    f"{src}:{pt.source_line}: point {pt.id} inside the chosen chain is "
                    f"{pt.attachment!r}; a point between two lines of one cablestudy line must "
                    "be free (Free/Connect)"
                )
            body = pt.drag_area or (pt.added_mass and pt.volume)
            if pt.mass or pt.volume or any(pt.force) or body:
                att: dict[str, Any] = {"s": s}
                if pt.mass:
                    att["mass"] = pt.mass
                if pt.volume:
                    att["volume"] = pt.volume
                if any(pt.force):
                    att["force"] = list(pt.force)
                if pt.added_mass and pt.volume:  # MoorDyn: Ca rho V
                    att["added_mass"] = pt.added_mass * rho * pt.volume
                if pt.drag_area:
                    if current:
                        warnings.append(
                            f"{src}:{pt.source_line}: point {pt.id}: CdA = {pt.drag_area:g} "
                            "m^2 with a current: not mapped (the static solvers do not load "
                            "bodies with drag; set line.attachments.N.drag_area for a "
                            "time-domain study in still water)"
                        )
                    else:
                        att["drag_area"] = pt.drag_area
                attachments.append(att)
                comments[("line", "attachments", len(attachments) - 1)] = (
                    f"{src}:{pt.source_line} point {pt.id}"
                )
        seg = _segment(md, lt, ln, warnings)
        if segments and seg_types[-1] == lt.name:
            segments[-1]["length"] += seg["length"]
            comments[("line", "segments", len(segments) - 1)] += f", line {ln.id}"
        else:
            segments.append(seg)
            seg_types.append(lt.name)
            comments[("line", "segments", len(segments) - 1)] = (
                f"{src}:{lt.source_line} type {lt.name}; {src}:{ln.source_line} line {ln.id}"
            )
        nsegs += ln.segments
        s += ln.length
        at = ln.attach_a if rev else ln.attach_b
    end_b_key = at

    # ------------------------------------------------------------------- ends
    ends: dict[str, Any] = {}
    rho_g = rho * env["gravity"]
    for label, key, ln in (("a", start, chain[0][0]), ("b", end_b_key, chain[-1][0])):
        pt = _need_point(md, key, ln)
        where = f"{src}:{pt.source_line} point {pt.id} ({pt.attachment})"
        if pt.kind == "free":
            fz = pt.force[2] - (pt.mass * env["gravity"] - pt.volume * rho_g)
            ends[label] = {"kind": "force", "force": [pt.force[0], pt.force[1], fz]}
            comments[("ends", label)] = f"{where}: weight, buoyancy and steady force"
            _point_load(pt, md, warnings, f"end {label}")
            continue
        moving = Refusals([])
        position = absolute_position(md, pt, moving)
        moving.raise_if_any(src, f"end {label}")
        assert position is not None  # a point on a moving body is refused just above
        ends[label] = {"kind": "fixed", "position": position}
        comments[("ends", label)] = where
        if pt.kind == "coupled":
            comments[("ends", label)] += ": held at its initial position"
            if pt.attachment.lower() in ("vessel", "vec", "ves"):
                comments[("ends", label)] += " (vessel frame taken at the origin)"
        elif pt.kind == "body":
            body = md.bodies[pt.body or 0]
            comments[("ends", label)] += (
                f": body {body.id} ({body.attachment}) held at {list(body.position)} + the "
                "point's offset"
            )

    if all(e["kind"] == "force" for e in ends.values()):
        warnings.append(
            f"{src}: both ends of the chosen lines are free points: the study has no fixed "
            "end, which cablestudy's statics need; fix one end before running it"
        )
    if env.get("depth"):
        _seabed_contact(md, env, segments, rho, comments, warnings)
    data: dict[str, Any] = {
        "name": name,
        "description": f"imported from {src} ({md.format_name}), lines "
        + ", ".join(str(ln.id) for ln, _ in chain),
        "environment": env,
        "line": {"segments": segments},
        "ends": ends,
    }
    if attachments:
        data["line"]["attachments"] = attachments
    static: dict[str, Any] = {}
    if all(ln.segments > 0 for ln, _ in chain):
        static["nodes"] = nsegs + 1
        comments[("analysis", "static", "nodes")] = f"NumSegs {nsegs} of the chosen lines, + 1"
    if any(seg["bending_stiffness"] > 0.0 for seg in segments):
        static["method"] = "discrete"
        comments[("analysis", "static", "method")] = (
            "a line type has EI > 0: the static method that carries bending"
        )
    if static:
        data["analysis"] = {"static": static}
    return ImportedStudy(data=data, comments=comments, warnings=warnings)


def environment(
    md: MoorDynFile,
    current: list[dict[str, float]] | None,
    above_surface: bool,
    comments: dict[tuple[str | int, ...], str],
    warnings: list[str],
) -> tuple[dict[str, Any], float]:
    """The study's ``environment`` from the file's options (fluid, gravity, depth,
    friction, current), with comments naming their source lines, warnings for the options
    not modelled, and the fluid density used [kg/m^3]."""
    src = md.source
    env: dict[str, Any] = {}
    rho_opt = option_value(md, "rho", "rhoW", "WtrDnsty")
    rho = rho_opt[0] if rho_opt else DEFAULT_DENSITY
    named = [k for k, v in FLUID_DENSITY.items() if v == rho]
    env["fluid"] = named[0] if named else {"density": rho}
    comments[("environment", "fluid")] = (
        f"{src}:{rho_opt[1]} rho"
        if rho_opt
        else f"{'MoorPy' if md.kind else 'MoorDyn'} default rho = {DEFAULT_DENSITY:g}"
    )
    if above_surface:
        env["fluid"] = "vacuum"
        comments[("environment", "fluid")] = (
            "the line hangs wholly above z = 0, where MoorDyn gives it no buoyancy, added "
            "mass or drag"
        )
        rho = 0.0
    g_opt = option_value(md, "g", "gravity")
    tool, g_default = ("MoorPy", MOORPY_GRAVITY) if md.kind else ("MoorDyn", DEFAULT_GRAVITY)
    env["gravity"] = g_opt[0] if g_opt else g_default
    comments[("environment", "gravity")] = (
        f"{src}:{g_opt[1]} g" if g_opt else f"{tool} default g = {g_default:g}"
    )
    depth, origin = water_depth(md)
    env["depth"] = depth
    comments[("environment", "depth")] = origin
    seabed: dict[str, Any] = {}
    fric = option_value(md, "FrictionCoefficient", "MU_KT")
    if fric is not None:
        seabed["friction"] = fric[0]
        comments[("environment", "seabed", "friction")] = f"{src}:{fric[1]}"
        mu_ka = option_value(md, "MU_KA")
        if mu_ka is not None and mu_ka[0] != fric[0]:
            warnings.append(
                f"{src}:{mu_ka[1]}: MU_KA = {mu_ka[0]:g} (axial friction) differs from the "
                f"transverse {fric[0]:g}; cablestudy has one Coulomb coefficient (used {fric[0]:g})"
            )
    if seabed:
        env["seabed"] = seabed
    if current:
        env["current"] = current
        comments[("environment", "current")] = "from the steady current table (Currents 1)"
    warnings.extend(
        option_warnings(md, current_read=current is not None, friction=fric is not None)
    )
    for title, line_no, count in md.other_sections:
        warnings.append(
            f"{src}:{line_no}: section {title} ({count} entries) is not modelled by cablestudy"
        )
    if md.outputs:
        warnings.append(
            "MoorDyn output channels not used (cablestudy writes every output): "
            + ", ".join(md.outputs)
        )
    return env, rho


def parse_current_profile(text: str, source: str) -> list[dict[str, float]]:
    """MoorDyn's steady current table (``Currents 1``: three header lines, then rows
    ``z ux uy uz``) as cablestudy current points {z, speed, heading_deg}."""
    points: list[dict[str, float]] = []
    for n, raw in enumerate(text.splitlines()[3:], start=4):
        tokens = raw.split()
        if not tokens:
            continue
        try:
            z, ux, uy, *rest = (float(t) for t in tokens)
        except ValueError:
            raise MoorDynFormatError(
                f"{source}:{n}: a current row is 'z ux uy uz' in m and m/s (got {raw.strip()!r})"
            ) from None
        if rest and rest[0] != 0.0:
            raise NotModelledError(
                f"{source}:{n}: {FEATURES['vertical_current']}: uz = {rest[0]:g} m/s is not "
                "modelled (cablestudy's current is horizontal)",
                ["vertical_current"],
            )
        speed = math.hypot(ux, uy)
        heading = math.degrees(math.atan2(uy, ux)) if speed > 0.0 else 0.0
        points.append({"z": z, "speed": speed, "heading_deg": heading})
    return points
