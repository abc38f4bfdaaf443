"""What of a MoorDyn file a one-line study can hold: every option MoorDyn reads, used or
named with the reason it is not, and the features cablestudy does not have, refused by
name before anything is built.

MoorDyn's options are those of ``MoorDyn::readOptionsLine`` (MoorDyn v2.7
``source/MoorDyn2.cpp``) plus the names MoorDyn-F (the Fortran MoorDyn of OpenFAST) and
MoorPy read; the meaning of each is from MoorDyn's documentation ("Input Files",
moordyn.readthedocs.io).
"""

from __future__ import annotations

from dataclasses import dataclass

from .moordyn_format import InterchangeError, Line, MoorDynFile, Point, attachment_ref

#: options mapped into the study (statics and dynamics): name -> study key
USED_OPTIONS = {
    "g": "environment.gravity",
    "gravity": "environment.gravity",
    "rho": "environment.fluid",
    "rhow": "environment.fluid",
    "wtrdnsty": "environment.fluid",
    "wtrdpth": "environment.depth",
    "depth": "environment.depth",
    "kbot": "environment.seabed.stiffness",
    "kb": "environment.seabed.stiffness",
    "cbot": "environment.seabed.damping_ratio",
    "cb": "environment.seabed.damping_ratio",
    "frictioncoefficient": "environment.seabed.friction",
    "mu_kt": "environment.seabed.friction",
    "mu_ka": "environment.seabed.friction",
    "currents": "environment.current",
}

#: settings of MoorDyn's own time integration, initial-condition search and output: they
#: carry no physics of the equilibrium or the line (cablestudy's solvers choose their own)
SOLVER_OPTIONS = {
    "dtm": "time step", "dt": "time step", "cfl": "time step from a CFL number",
    "tscheme": "time integration scheme",
    "dtic": "initial-condition convergence check interval", "icdt": "",
    "tmaxic": "initial-condition search time", "ictmax": "",
    "cdscaleic": "drag scaling during the initial-condition search", "icdfac": "",
    "threshic": "initial-condition convergence threshold", "icthresh": "",
    "gendynamicic": "dynamic relaxation for the initial condition", "icgendynamic": "",
    "fileic": "initial state read from a file", "icfile": "",
    "writelog": "log file", "dtout": "output interval", "writeunits": "output units row",
    "disableoutput": "output switch", "disableouttime": "output switch", "echo": "echo",
    "outswitch": "output switch", "inertialf": "inertial frame forces",
    "inertialf_rampt": "inertial frame forces",
}  # fmt: skip

#: options read and not modelled, with the reason; the study is imported, and says so
NOT_MODELLED_OPTIONS = {
    "wavekin": "wave kinematics (read from water_grid.txt with wave_elevation.txt or "
    "wave_frequencies.txt beside the file) act in dynamics only: MoorDyn itself switches "
    "them off while it finds the initial state; cablestudy's statics are in still water "
    "and its dynamics take a prescribed end motion, so these files are not read",
    "waterkin": "wave kinematics file (MoorDyn-F): dynamics only, as WaveKin",
    "dtwave": "time step of MoorDyn's wave grid (dynamics only)",
    "unifycurrentgrid": "interpolation of MoorDyn's current grid onto the wave grid",
    "wavekin_rampt": "wave ramp time (dynamics only)",
    "waterkin_rampt": "wave ramp time (dynamics only)",
    "fricdamp": "friction smoothing velocity scale (Coulomb friction is used as is)",
    "cv": "friction smoothing velocity scale (Coulomb friction is used as is)",
    "statdynfricscale": "static/dynamic friction ratio (one coefficient is used)",
    "mc": "static/dynamic friction ratio (one coefficient is used)",
}

#: features of MoorDyn that cablestudy does not have: key -> what the refusal names
FEATURES = {
    "rods": "rods (rigid or pinned cylinders, lines attached to rod ends)",
    "bodies": "bodies (a file of bodies and rods without lines)",
    "free_bodies": "free bodies (a body found by equilibrium)",
    "pinned_bodies": "pinned bodies (a body held in position and free to rotate)",
    "rotated_bodies": "rotated bodies (a body at nonzero roll, pitch or yaw)",
    "systems": "systems of lines (a free point joining several lines)",
    "viscoelastic": "viscoelastic axial stiffness (EA as static|dynamic parts)",
    "syrope": "the Syrope rope model (EA 'SYROPE:...')",
    "tension_table": "tabulated tension-strain curves (EA from a file)",
    "zero_gravity": "zero gravity (option g = 0)",
    "dynamic_current": "time-varying currents (Currents 2 or 4: current_profile_dynamic.txt)",
    "current_4d": "4D currents (Currents 5: current_profile_4d.txt)",
    "seabed_3d": "3D seabed bathymetry (SeafloorFile)",
    "seabed_at_surface": "a seabed at z = 0 (no water depth and no point below the surface)",
    "vertical_current": "vertical current (uz in current_profile.txt)",
    "surface_crossing": "lines crossing the sea surface (MoorDyn's partial submergence)",
}

#: allowance for the stretch of a line when bounding how low it can hang [-]
STRETCH_ALLOWANCE = 0.01


class NotModelledError(InterchangeError):
    """A MoorDyn file (or the chosen lines of it) needs features cablestudy does not have;
    :attr:`features` lists their keys in :data:`FEATURES`."""

    def __init__(self, message: str, features: list[str]) -> None:
        super().__init__(message)
        self.features = tuple(dict.fromkeys(features))


@dataclass
class Refusals:
    """Features found missing, each with where and what; and whether the chosen lines
    lie wholly above the sea surface (where MoorDyn gives them no buoyancy, added mass or
    drag: a study in vacuum)."""

    items: list[tuple[str, str]]
    above_surface: bool = False

    def add(self, feature: str, where: str, detail: str) -> None:
        self.items.append((feature, f"{where}: {FEATURES[feature]}: {detail}"))

    def raise_if_any(self, source: str, what: str) -> None:
        if self.items:
            raise NotModelledError(
                f"{source}: {what} needs what cablestudy does not model: "
                + "; ".join(text for _, text in self.items),
                [f for f, _ in self.items],
            )


def option_value(md: MoorDynFile, *names: str) -> tuple[float, int] | None:
    """A numeric option (value, file line), or None when absent."""
    opt = md.option(*names)
    if opt is None:
        return None
    try:
        return float(opt.value), opt.source_line
    except ValueError:
        raise InterchangeError(
            f"{md.source}:{opt.source_line}: option {opt.key} must be a number (got {opt.value!r})"
        ) from None


def water_depth(md: MoorDynFile) -> tuple[float, str]:
    """MoorDyn's water depth and where it comes from: ``WtrDpth`` (default 0), deepened to
    the lowest point of the POINTS table where one lies below it (MoorDyn2.cpp reads each
    point's z as written, also for points given relative to a body)."""
    opt = md.option("WtrDpth", "depth")
    depth, origin = 0.0, "MoorDyn's default WtrDpth = 0"
    if opt is not None:
        depth, origin = float(opt.value), f"{md.source}:{opt.source_line} WtrDpth"
    for pt in md.points.values():
        if -pt.position[2] > depth:
            depth = -pt.position[2]
            origin = (
                f"{md.source}:{pt.source_line}: point {pt.id} lies below WtrDpth; MoorDyn "
                "lowers the seabed to it"
            )
    return depth, origin


def point_of(md: MoorDynFile, key: str) -> Point | None:
    """The point a line end names (``3``, ``P3``, ``C3``...), None for a rod end or an
    unknown point."""
    kind, number, _ = attachment_ref(key)
    return md.points.get(number) if kind == "point" and number is not None else None


def absolute_position(md: MoorDynFile, pt: Point, refusals: Refusals) -> list[float] | None:
    """A point's position in the global frame: as written, or, for a point on a body held
    by MoorDyn (fixed or coupled, at its initial position), the body's position plus the
    point's offset. None (with the refusal recorded) for a body that moves or turns."""
    if pt.kind != "body":
        return list(pt.position)
    where = f"{md.source}:{pt.source_line}"
    body = md.bodies.get(pt.body or 0)
    if body is None:
        raise InterchangeError(
            f"{where}: point {pt.id} is attached to {pt.attachment}, which the file does not "
            f"define; bodies: {', '.join(str(b) for b in sorted(md.bodies)) or 'none'}"
        )
    detail = f"point {pt.id} is on body {body.id} ({body.attachment})"
    if body.kind == "free":
        refusals.add("free_bodies", where, detail)
        return None
    if body.kind == "coupled_pinned":
        refusals.add("pinned_bodies", where, detail)
        return None
    if any(body.rotation_deg):
        refusals.add("rotated_bodies", where, f"{detail}, turned by {list(body.rotation_deg)} deg")
        return None
    return [b + p for b, p in zip(body.position, pt.position, strict=True)]


def check_chain(md: MoorDynFile, chain: list[Line], ends: tuple[str, str]) -> Refusals:
    """Features the chosen chain of lines needs and cablestudy lacks (rods, free bodies,
    junctions with other lines, axial models other than a linear EA), and those of the
    whole file's environment (gravity, currents, bathymetry)."""
    refusals = Refusals([])
    src = md.source
    chosen = {ln.id for ln in chain}
    for ln in chain:
        where = f"{src}:{ln.source_line}"
        for key in (ln.attach_a, ln.attach_b):
            if attachment_ref(key)[0] == "rod":
                refusals.add("rods", where, f"line {ln.id} is attached to rod end {key}")
        lt = md.line_types.get(ln.line_type)
        if lt is None:
            continue  # named by the mapping, with the types defined
        ea = lt.axial_stiffness
        lwhere = f"{src}:{lt.source_line}"
        try:
            float(ea)
        except ValueError:
            if ea.upper().startswith("SYROPE:"):
                refusals.add("syrope", lwhere, f"line type {lt.name!r}: EA {ea!r}")
            elif "|" in ea:
                refusals.add("viscoelastic", lwhere, f"line type {lt.name!r}: EA {ea!r}")
            else:
                refusals.add("tension_table", lwhere, f"line type {lt.name!r}: EA from file {ea!r}")
    touching: dict[int, list[int]] = {}
    for ln in md.lines.values():
        for key in (ln.attach_a, ln.attach_b):
            pt = point_of(md, key)
            if pt is not None:
                touching.setdefault(pt.id, []).append(ln.id)
    inside = {point_of(md, k) for ln in chain for k in (ln.attach_a, ln.attach_b)} - {
        point_of(md, k) for k in ends
    }
    heights = []
    for key in ends:
        pt = point_of(md, key)
        if pt is not None:
            position = absolute_position(md, pt, refusals)
            if position is not None:
                heights.append(position[2])
    rho = option_value(md, "rho", "rhoW", "WtrDnsty")
    if len(heights) == 2 and max(heights) > 0.0 and (rho is None or rho[0] > 0.0):
        # MoorDyn's segments above z = 0 have no buoyancy, added mass or drag. A line
        # hanging between ends at z_a, z_b no lower than (z_a + z_b - L) / 2 (it must go
        # down and come back up; L stretched by STRETCH_ALLOWANCE) stays above the
        # surface: a study in vacuum is then MoorDyn's line; otherwise it crosses it
        length = sum(ln.length for ln in chain) * (1.0 + STRETCH_ALLOWANCE)
        if min(heights) > 0.0 and sum(heights) - length > 0.0:
            refusals.above_surface = True
        else:
            refusals.add(
                "surface_crossing",
                f"{src}:{chain[0].source_line}",
                f"ends at z = {heights[0]:g} m and {heights[1]:g} m, length "
                f"{length / (1.0 + STRETCH_ALLOWANCE):g} m: the line may pass above z = 0",
            )
    for pt in [point_of(md, k) for k in ends] + sorted(
        (p for p in inside if p is not None), key=lambda p: p.id
    ):
        if pt is None or pt.kind != "free":
            continue
        others = [i for i in touching.get(pt.id, []) if i not in chosen]
        if others:
            refusals.add(
                "systems",
                f"{src}:{pt.source_line}",
                f"free point {pt.id} joins the chosen lines to line(s) "
                f"{', '.join(str(i) for i in others)}, so its position depends on them",
            )
    environment_refusals(md, refusals)
    return refusals


def environment_refusals(md: MoorDynFile, refusals: Refusals) -> None:
    """The whole file's gravity, currents and seabed, where cablestudy cannot follow."""
    src = md.source
    g = option_value(md, "g", "gravity")
    if g is not None and g[0] == 0.0:
        refusals.add(
            "zero_gravity",
            f"{src}:{g[1]}",
            "cablestudy's environment needs gravity > 0 (a line of no weight is a line "
            "whose mass equals its displaced water, which changes its dynamics)",
        )
    cur = md.option("Currents")
    if cur is not None:
        where = f"{src}:{cur.source_line}"
        value = cur.value.strip()
        if value in ("2", "4"):
            refusals.add("dynamic_current", where, f"Currents {value}")
        elif value == "5":
            refusals.add("current_4d", where, f"Currents {value}")
        elif value not in ("0", "1", "3"):
            raise InterchangeError(
                f"{where}: Currents {value!r} is not a MoorDyn current mode; allowed: 0 (none), "
                "1 or 3 (steady profile), 2 or 4 (time-varying), 5 (4D)"
            )
    floor = md.option("SeafloorFile")
    if floor is not None:
        refusals.add("seabed_3d", f"{src}:{floor.source_line}", f"file {floor.value!r}")
    depth_opt = md.option("WtrDpth", "depth")
    if depth_opt is not None:
        try:
            float(depth_opt.value)
        except ValueError:
            refusals.add(
                "seabed_3d",
                f"{src}:{depth_opt.source_line}",
                f"WtrDpth {depth_opt.value!r} names a bathymetry file",
            )
            return
    if water_depth(md)[0] <= 0.0:
        refusals.add(
            "seabed_at_surface",
            src,
            "MoorDyn's seabed is at z = -WtrDpth (default 0) or the lowest point",
        )


def option_warnings(md: MoorDynFile, *, current_read: bool, friction: bool) -> list[str]:
    """One warning per option read and not modelled, with its reason, and one listing the
    solver settings; options mapped into the study are not repeated."""
    warnings: list[str] = []
    solver = []
    src = md.source
    for key, opt in md.options.items():
        if key in SOLVER_OPTIONS:
            solver.append(opt.key)
        elif key in USED_OPTIONS:
            if key == "currents" and opt.value.strip() not in ("0",) and not current_read:
                warnings.append(f"{src}:{opt.source_line}: Currents {opt.value}: not read")
        elif key in NOT_MODELLED_OPTIONS:
            if key in ("wavekin", "waterkin") and _zero(opt.value):
                continue
            if key in ("fricdamp", "cv", "statdynfricscale", "mc") and not friction:
                continue
            warnings.append(
                f"{src}:{opt.source_line}: option {opt.key} = {opt.value}: "
                f"{NOT_MODELLED_OPTIONS[key]}; not modelled"
            )
        elif key != "seafloorfile":
            warnings.append(
                f"{src}:{opt.source_line}: option {opt.key} = {opt.value}: not an option "
                "MoorDyn reads (it warns and ignores it); not used"
            )
    if solver:
        warnings.append(
            "MoorDyn solver settings not used (cablestudy's solvers choose their own): "
            + ", ".join(solver)
        )
    return warnings


def _zero(text: str) -> bool:
    try:
        return float(text) == 0.0
    except ValueError:
        return False
