"""Writing one case of a study as a MoorDyn version 2 input file.

The line becomes a chain of MoorDyn lines: one line type per segment, the line split
at segment joints and at attachments, which become free points with their mass and
volume. End A is MoorDyn's anchor end and end B the fairlead end. A fixed end is a
``Fixed`` point; the end an excitation moves (end B without dynamics) is ``Coupled``,
so a coupling program drives it. Ends given by a force (towing, mooring) are written
at the static position our solver finds for them.

MoorDyn integrates explicitly, so its time step must resolve the fastest mode of the
discretised line: the axial mode of its shortest segment, omega_max = 2 c / l with
c = sqrt(EA / (m + rho A Ca_ax)) (a lumped-mass chain's highest frequency is twice
that of one segment). We take dtM = T_min / 20 = pi l / (10 c), rounded down to
1, 2 or 5 times a power of ten: about 20 steps per shortest period.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..physics.contact import default_seabed_stiffness
from ..study import FixedEnd, Study
from ..study.problem import line_model
from .moordyn_format import InterchangeError
from .seabed import to_moordyn


@dataclass(frozen=True)
class ExportedCase:
    """A MoorDyn input file, the files it reads beside it, and what could not be kept."""

    text: str
    extra_files: dict[str, str]
    warnings: list[str]
    coupled: dict[int, np.ndarray]  # point ID -> position [m] to pass to MoorDyn's Init
    time_step: float  # dtM [s]


def current_table(study: Study, opts: list[str]) -> dict[str, str]:
    """MoorDyn's steady current of ``study`` (a one-line or a system study): the option
    row ``Currents 1`` appended to ``opts`` and the table file beside the input file
    (name -> text); nothing without a current."""
    env = study.environment
    if not env.current:
        return {}
    opts.append("1  Currents   ! steady current table in current_profile.txt")
    rows = []
    for p in sorted(env.current, key=lambda p: p.z):
        h = math.radians(p.heading_deg)
        rows.append(f"{_num(p.z)} {_num(p.speed * math.cos(h))} {_num(p.speed * math.sin(h))} 0")
    return {
        "current_profile.txt": (
            "--------------------- MoorDyn steady currents File ----------------------\n"
            f"written by cablestudy for {study.name}\n"
            "z (m), ux (m/s), uy (m/s), uz (m/s)\n" + "\n".join(rows) + "\n"
        )
    }


def _num(v: float) -> str:
    return (
        np.format_float_positional(v, unique=True, trim="-")
        if 1e-4 <= abs(v) < 1e6
        else (np.format_float_scientific(v, unique=True, trim="-") if v != 0.0 else "0")
    )


def _floor125(x: float) -> float:
    """Largest 1, 2 or 5 times a power of ten not above ``x``."""
    e = math.floor(math.log10(x))
    for m in (5.0, 2.0, 1.0):
        if m * 10.0**e <= x * (1 + 1e-12):
            return m * 10.0**e
    return 10.0**e


def axial_step(pieces: list[tuple[Any, float]], rho: float, g: float) -> tuple[float, dict]:
    """The largest time step [s] of MoorDyn's explicit RK2 on the lines written as
    ``pieces`` (segment, node length [m]): about 20 steps per period of the fastest axial
    mode, omega = 2 c / l (a lumped-mass chain's highest), dt = pi l / (10 c); and that
    omega [rad/s] of each segment without axial damping (by ``id``), for
    :func:`added_damping`."""
    dt, fastest = math.inf, {}
    for seg, length in pieces:
        axial_mass = seg.mass_in(rho, g) + rho * seg.area * seg.added_mass_tangential
        c = math.sqrt(seg.elastic_stiffness / axial_mass)
        dt = min(dt, math.pi * length / (10.0 * c))
        if seg.damping_ratio <= 0.0:
            fastest[id(seg)] = max(fastest.get(id(seg), 0.0), 2.0 * c / length)
    return dt, fastest


def added_damping(fastest: dict[int, float], dtm: float) -> tuple[dict[int, float], list[str]]:
    """The damping ratio written for each undamped segment (``fastest``: its fastest
    axial mode omega, :func:`axial_step`) at the exported step ``dtm`` [s], and a warning
    naming it. RK2 amplifies an undamped mode by (omega dt)^4 / 8 a step; zeta = (omega
    dtM)^3 / 4 (BA = -zeta) is twice what cancels that growth (a decay of zeta omega dtM
    a step). It damps a mode of frequency f by about zeta f / f_max, nothing at wave
    frequencies. Measured on the 320 m chain of tests/integration/test_step_check.py,
    no damping, 20 m nodes: dtM 1e-3 and 5e-4 blew up (maximum tension 984 and 312 kN
    against 131 kN)."""
    damping = {k: (omega * dtm) ** 3 / 4.0 for k, omega in fastest.items()}
    if not damping:
        return damping, []
    return damping, [
        "segments without axial damping (damping_ratio 0) are written with MoorDyn's "
        f"BA = -{max(damping.values()):.3g} at most: the least damping that keeps its "
        "explicit RK2 from amplifying their fastest axial mode at dtM; it damps a mode "
        "of frequency f by about that times f / f_max, nothing at wave frequencies"
    ]


#: slip speed [m/s] at which MoorDyn's saturated viscous friction, ``F = min(mu FricDamp
#: |v|, mu N)``, reaches the Coulomb force on the heaviest laid node: FricDamp = w l /
#: SLIP_VELOCITY. MoorDyn's default FricDamp (200 N s/m) saturates a chain's node near
#: 100 m/s: no friction at all (benchmarks/wp_chain_moordyn.py; halving this speed there
#: moves the maximum tension by 6e-4)
SLIP_VELOCITY = 0.02


def seabed_options(
    env: Any, pieces: list[tuple[Any, float]], stiffness: float
) -> tuple[list[str], list[str], float]:
    """MoorDyn's OPTIONS rows of the seabed of ``env`` for the lines written as
    ``pieces`` (segment, node length [m]) with the contact ``stiffness`` [N/m^2]: kBot and
    cBot over the largest diameter, and with friction FrictionCoefficient, FricDamp
    (:data:`SLIP_VELOCITY`) and StatDynFricScale 1; the warnings of what MoorDyn's seabed
    does differently; and the largest time step [s] its explicit integration takes on a
    laid node: omega dt <= 1 on the contact spring and r dt <= 1 on the friction's
    damping rate r (half the stability limit of 2 on a real rate). Measured on
    configs/chain-mooring-surge.yaml with a contact 80 times the default (1e8 N/m^2,
    omega = 790 rad/s, critically damped): MoorDyn 2.7 stays stable up to omega dt =
    1.6, its extremes within 4e-7 of those at a tenth of the step."""
    rho, g = env.density, env.gravity
    ref = max((seg for seg, _ in pieces), key=lambda s: s.diameter)
    m_ref = ref.mass_in(rho, g) + rho * ref.area * ref.added_mass_normal
    kbot, cbot = to_moordyn(stiffness, env.seabed.damping_ratio, diameter=ref.diameter, mass=m_ref)
    rows = [
        f"{_num(kbot)}  kBot   ! the contact stiffness {stiffness:.6g} N/m^2 over the largest "
        f"diameter {ref.diameter:g} m",
        f"{_num(cbot)}  cBot   ! damping ratio {env.seabed.damping_ratio:g} of that contact spring",
    ]
    warnings = []
    if len({seg.diameter for seg, _ in pieces}) > 1:
        warnings.append(
            "MoorDyn's seabed stiffness scales with each line type's diameter; kBot is the "
            "study's contact stiffness over the largest diameter, so thinner lines rest on a "
            "softer seabed in MoorDyn"
        )
    if env.seabed.slope_deg != 0.0:
        warnings.append(
            f"environment.seabed.slope_deg = {env.seabed.slope_deg:g}: MoorDyn's seabed here "
            "is flat at WtrDpth (a bathymetry file is not written)"
        )
    mu = env.seabed.friction
    nodes = [  # (weight in the fluid [N], lightest mass [kg], diameter, length [m]) of a node
        (
            (seg.mass_in(rho, g) - rho * seg.area) * g * length,
            (
                seg.mass_in(rho, g)
                + rho * seg.area * min(seg.added_mass_normal, seg.added_mass_tangential)
            )
            * length,
            seg.diameter,
            length,
        )
        for seg, length in pieces
    ]
    # a buoyant line rests nowhere: no node weight to saturate at
    fric_damp = max(0.0, *(w for w, _, _, _ in nodes)) / SLIP_VELOCITY if mu > 0.0 else 0.0
    dt = math.inf
    for _, mass, d, length in nodes:
        rate = mu * fric_damp / mass
        dt = min(dt, math.sqrt(mass / (kbot * d * length)), 1.0 / rate if rate > 0.0 else math.inf)
    if mu > 0.0:
        rows += [
            f"{_num(mu)}  FrictionCoefficient",
            f"{_num(fric_damp)}  FricDamp   ! saturates at {SLIP_VELOCITY:g} m/s on the "
            "heaviest laid node",
            "1  StatDynFricScale",
        ]
    return rows, warnings, dt


def type_row(name: str, seg: Any, mass: float, damping: dict[int, float]) -> str:
    """The LINE TYPES row ``name`` of segment ``seg`` with mass ``mass`` [kg/m] in the
    fluid's terms (internal damping as MoorDyn's -zeta; ``damping``: that of segments
    without their own, :func:`axial_step`)."""
    zeta = seg.damping_ratio if seg.damping_ratio > 0.0 else damping.get(id(seg), 0.0)
    ba = -zeta if zeta > 0.0 else 0.0
    return (
        f"{name}  {_num(seg.diameter)}  {_num(mass)}  {_num(seg.elastic_stiffness)}  "
        f"{_num(ba)}  {_num(seg.bending_stiffness)}  {_num(seg.drag_normal)}  "
        f"{_num(seg.added_mass_normal)}  {_num(seg.drag_tangential)}  "
        f"{_num(seg.added_mass_tangential)}"
    )


def time_options(dt: float) -> list[str]:
    """The OPTIONS rows of the time step (``dt`` [s] the stability limit of the axial
    waves and the seabed, rounded down to 1-2-5) and the initial-condition settings."""
    return [
        f"{_num(_floor125(dt))}  dtM   ! explicit RK2: about 20 steps per period of the "
        f"fastest axial segment mode (pi l / (10 c)), within the seabed contact's and "
        f"friction's limits: {dt:.3g} s rounded down",
        "0.001  threshIC",
        "300  TmaxIC",
    ]


def file_text(
    front: list[str],
    type_rows: list[str],
    body_rows: list[str],
    point_rows: list[str],
    line_rows: list[str],
    opts: list[str],
    outputs: list[str],
) -> str:
    """A MoorDyn v2 input file of these sections' rows (no BODIES section without
    ``body_rows``)."""
    rows = [
        "--------------------- MoorDyn Input File ------------------------------------",
        *front,
        "---------------------- LINE TYPES ------------------------------------------",
        "TypeName Diam Mass/m EA BA/-zeta EI Cd Ca CdAx CaAx",
        "(name) (m) (kg/m) (N) (N-s/-) (N-m^2) (-) (-) (-) (-)",
        *type_rows,
    ]
    if body_rows:
        rows += [
            "---------------------- BODIES ----------------------------------------------",
            "ID Attachment X0 Y0 Z0 r0 p0 y0 Mass CG* I* Volume CdA* Ca*",
            "(#) (-) (m) (m) (m) (deg) (deg) (deg) (kg) (m) (kg-m^2) (m^3) (m^2) (-)",
            *body_rows,
        ]
    rows += [
        "---------------------- POINTS ----------------------------------------------",
        "ID Attachment X Y Z Mass Volume CdA Ca",
        "(#) (-) (m) (m) (m) (kg) (m^3) (m^2) (-)",
        *point_rows,
        "---------------------- LINES -----------------------------------------------",
        "ID LineType AttachA AttachB UnstrLen NumSegs LineOutputs",
        "(#) (name) (#) (#) (m) (-) (-)",
        *line_rows,
        "---------------------- OPTIONS ---------------------------------------------",
        *opts,
        "---------------------- OUTPUTS ---------------------------------------------",
        *outputs,
        "END",
        "------------------------- need this line -----------------------------------",
    ]
    return "\n".join(rows) + "\n"


def check_exportable(study: Study) -> None:
    """Raise :class:`InterchangeError` for a one-line study the MoorDyn file cannot hold
    (before its statics are solved: a spring line has no segments to solve)."""
    segs = study.line.segments
    if study.line.is_spring:
        raise InterchangeError(
            "line.kind: spring (a massless spring) has no MoorDyn line equivalent; "
            "export a kind: catenary line"
        )
    if study.line.pulleys:
        raise InterchangeError(
            "line.pulleys: a line over fixed pulleys has no MoorDyn line equivalent (a "
            "MoorDyn point holds the line, it does not let it slide); export the line "
            "without pulleys"
        )
    for i, seg in enumerate(segs):
        if seg.axial is not None and seg.axial.law != "linear":
            raise InterchangeError(
                f"line.segments.{i}.axial: the {seg.axial.law} law is not exported (the "
                "MoorDyn file takes a linear EA here); give axial_stiffness to export"
            )


def not_written(study: Study) -> list[str]:
    """Warnings naming what the study models and the MoorDyn file does not hold: the
    file is the line at rest, a MoorDyn run of it does without them."""
    out = []
    static = study.analysis.static
    if static.installation is not None:
        out.append(
            "analysis.static.installation: MoorDyn has no cable laying (pay-out along the "
            "line, moving frame): the file holds the line at rest, whose tension and shape "
            "differ from the laying solution the end positions come from"
        )
    if study.line.failure is not None or any(g.failure is not None for g in study.line.segments):
        out.append(
            "failure: the break condition is not written (no FAILURE section): the line "
            "does not part in MoorDyn"
        )
    if study.line.winch is not None:
        out.append("line.winch: not written: MoorDyn's line keeps its unstretched length")
    return out


def moordyn_input(
    study: Study,
    *,
    end_positions: tuple[np.ndarray, np.ndarray],
    position_at: np.ndarray,
    s_nodes: np.ndarray,
    coupled_ends: set[str],
    title: str,
) -> ExportedCase:
    """A MoorDyn v2 input file of ``study`` (one case, already resolved).

    Parameters
    ----------
    study : the case's study
    end_positions : static positions of ends A and B [m]
    position_at : static positions (n, 3) at ``s_nodes`` [m], for free points' initial guess
    s_nodes : unstretched arc lengths of ``position_at`` [m]
    coupled_ends : ends written as Coupled points ('a', 'b')
    title : front-matter line
    """
    env = study.environment
    rho, g = env.density, env.gravity
    segs = study.line.segments
    check_exportable(study)
    warnings: list[str] = not_written(study)
    bounds = np.concatenate([[0.0], np.cumsum([s.length for s in segs])])
    total = float(bounds[-1])
    for i, att in enumerate(study.line.attachments):
        if any(att.force):
            raise InterchangeError(
                f"line.attachments.{i}.force: a steady force {att.force} N has no MoorDyn v2 "
                "equivalent (points carry mass and volume only); give it as mass or volume"
            )
    # break points: segment joints and attachments; point masses/volumes at each
    cuts = {float(b): [0.0, 0.0, 0.0, 0.0] for b in bounds}  # mass, volume, added mass, CdA
    for i, att in enumerate(study.line.attachments):
        if att.s <= 0.0 or att.s >= total:
            warnings.append(
                f"line.attachments.{i} at s = {att.s:g} m sits on an end point: MoorDyn passes "
                "its load straight to the support, as does a fixed end here"
            )
        key = min(cuts, key=lambda c, s=att.s: abs(c - s))
        if abs(key - att.s) > 1e-9 * total:
            key = float(att.s)
            cuts[key] = [0.0, 0.0, 0.0, 0.0]
        cuts[key][0] += att.mass
        cuts[key][1] += att.volume
        cuts[key][2] += att.added_mass
        cuts[key][3] += att.drag_area
    positions = sorted(cuts)
    # line types: one per segment
    type_rows = []
    for i, seg in enumerate(segs):
        m = seg.mass_in(rho, g)
        if seg.weight_in_fluid is not None and seg.mass_per_length is not None:
            implied = (m - rho * seg.area) * g
            if abs(implied - seg.weight_in_fluid) > 1e-9 * max(abs(implied), 1.0):
                warnings.append(
                    f"line.segments.{i}: weight_in_fluid {seg.weight_in_fluid:g} N/m differs "
                    f"from (mass - rho A) g = {implied:g} N/m; MoorDyn uses mass and diameter"
                )
        type_rows.append((f"seg{i + 1}", seg, m))
    dyn = study.analysis.dynamic
    n_total = dyn.elements if dyn is not None else study.analysis.static.nodes - 1
    # points
    point_rows, coupled = [], {}
    end_a, end_b = end_positions
    for k, s in enumerate(positions):
        pid = k + 1
        if k == 0 or k == len(positions) - 1:
            label = "a" if k == 0 else "b"
            end = study.ends.a if k == 0 else study.ends.b
            pos = (
                np.asarray(end.position)
                if isinstance(end, FixedEnd)
                else (end_a if k == 0 else end_b)
            )
            kind = "Coupled" if label in coupled_ends else "Fixed"
            if kind == "Coupled":
                coupled[pid] = np.asarray(pos, dtype=float)
            note = f"end {label}" + (
                "" if isinstance(end, FixedEnd) else f" ({end.kind} end, at its static position)"
            )
        else:
            kind = "Free"
            pos = np.array([np.interp(s, s_nodes, position_at[:, j]) for j in range(3)])
            note = f"s = {s:g} m"
        mass, vol, added, cda = cuts[s]
        # MoorDyn's point added mass is Ca rho V: a body with added mass and no volume
        # has no Ca that gives it
        ca = added / (rho * vol) if vol > 0.0 and rho > 0.0 else 0.0
        if added > 0.0 and ca == 0.0:
            warnings.append(
                f"point {pid} (s = {s:g} m): added mass {added:g} kg with no displaced volume "
                "has no MoorDyn Ca (MoorDyn's point added mass is Ca rho V); written as 0"
            )
        point_rows.append(
            f"{pid}  {kind}  {_num(pos[0])}  {_num(pos[1])}  {_num(pos[2])}  {_num(mass)}  "
            f"{_num(vol)}  {_num(cda)}  {_num(ca)}   ! {note}"
        )
    # lines between consecutive points
    line_rows = []
    pieces = []  # (segment, node length) of each MoorDyn line
    for k in range(len(positions) - 1):
        s0, s1 = positions[k], positions[k + 1]
        iseg = int(np.searchsorted(bounds, 0.5 * (s0 + s1)) - 1)
        seg = segs[iseg]
        length = s1 - s0
        nseg = max(1, round(n_total * length / total))
        pieces.append((seg, length / nseg))
        line_rows.append(f"{k + 1}  seg{iseg + 1}  {k + 1}  {k + 2}  {_num(length)}  {nseg}  -")
    dt, fastest = axial_step(pieces, rho, g)
    # options
    lowest = min(end_a[2], end_b[2], float(position_at[:, 2].min()))
    opts = [f"{_num(g)}  g", f"{_num(rho)}  rho"]
    if env.depth is not None:
        opts.append(f"{_num(env.depth)}  WtrDpth")
        stiffness = (
            env.seabed.stiffness
            if env.seabed.stiffness is not None
            else default_seabed_stiffness(line_model(study).weight)
        )
        rows, warned, dt_bed = seabed_options(env, pieces, stiffness)
        opts += rows
        warnings += warned
        dt = min(dt, dt_bed)
    else:
        deep = math.ceil(-lowest + 10.0 * total)
        opts.append(
            f"{deep}  WtrDpth   ! the study has no seabed: placed 10 line lengths below the "
            "lowest point, out of reach"
        )
    opts += time_options(dt)
    damping, warned = added_damping(fastest, _floor125(dt))
    warnings += warned
    extra = current_table(study, opts)
    front = [f"MoorDyn v2 input file written by cablestudy: {title}"]
    if dyn is not None:
        for e in dyn.excitations:
            front.append(
                f"! excitation: end {e.end} moved along {list(e.direction)} "
                + (
                    f"(amplitude {e.amplitude:g} m, {e.frequency:g} Hz)"
                    if hasattr(e, "amplitude")
                    else "(a time table)"
                )
                + ": drive the Coupled point through MoorDyn's Step"
            )
    n_lines = len(line_rows)
    text = file_text(
        front,
        [type_row(*row, damping) for row in type_rows],
        [],
        point_rows,
        line_rows,
        opts,
        [f"FairTen{n_lines}", "AnchTen1"],
    )
    return ExportedCase(text, extra, warnings, coupled, _floor125(dt))
